"""The BirdsEye toolbar: every action has its own icon, drawn for 16, 24 and 32 px, and a tooltip that
says what it is for (issue 16, item 5)."""
from __future__ import annotations

import itertools
from pathlib import Path

import pytest
from qgis.PyQt.QtCore import QCoreApplication, QEvent, QSize
from qgis.PyQt.QtGui import QImage
from qgis.PyQt.QtSvg import QSvgRenderer
from qgis.PyQt.QtWidgets import QToolBar

REPO_ROOT = Path(__file__).resolve().parents[2]
SIZES = (16, 24, 32)


@pytest.fixture
def toolbar(qgis_iface, birdseye_provider):
    """The plugin's toolbar after initGui (with a provider under its own id: the session's holds ``birdseye``)."""
    from birdseye.birdseye_qgis.gui import plugin as plugin_module
    from birdseye.processing.provider import BirdsEyeProvider

    class ProviderUnderTest(BirdsEyeProvider):
        def id(self):
            return "birdseye_icon_test"

    plugin = plugin_module.BirdsEyePlugin(qgis_iface, ProviderUnderTest)
    plugin.initGui()
    try:
        bars = qgis_iface.mainWindow().findChildren(QToolBar, plugin_module.TOOLBAR_OBJECT_NAME)
        assert len(bars) == 1
        yield bars[0]
    finally:
        plugin.unload()
        QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)


def rendered(icon, size: int) -> QImage:
    image = icon.pixmap(QSize(size, size)).toImage().convertToFormat(QImage.Format.Format_ARGB32)
    assert (image.width(), image.height()) == (size, size)
    return image


def opaque_share(image: QImage) -> float:
    pixels = [image.pixelColor(x, y).alpha() for x in range(image.width()) for y in range(image.height())]
    return sum(a > 128 for a in pixels) / len(pixels)


def test_each_toolbar_action_has_its_own_icon_at_every_size(toolbar):
    actions = [a for a in toolbar.actions() if not a.isSeparator()]
    assert len(actions) >= 3, [a.text() for a in actions]  # algorithms, review, sensor bound
    for action in actions:
        assert not action.icon().isNull(), action.text()
        for size in SIZES:
            share = opaque_share(rendered(action.icon(), size))
            assert 0.15 < share < 0.9, f"{action.text()} at {size} px: {share:.0%} of the square drawn"
    for size in SIZES:
        for a, b in itertools.combinations(actions, 2):
            assert rendered(a.icon(), size) != rendered(b.icon(), size), f"{a.text()} and {b.text()} look alike"


def test_each_toolbar_action_has_a_tooltip_of_its_own(toolbar):
    """A tooltip that explains, not Qt's default (the action's text)."""
    actions = [a for a in toolbar.actions() if not a.isSeparator()]
    for action in actions:
        text = action.text().replace("&", "").rstrip("…")
        assert action.toolTip() and action.toolTip().rstrip("…") != text, action.text()
        assert len(action.toolTip()) > len(text) + 10, action.toolTip()
    assert len({a.toolTip() for a in actions}) == len(actions)


def test_the_icons_are_svg_files_qt_draws():
    from birdseye.birdseye_qgis.gui import plugin as plugin_module

    paths = [REPO_ROOT / plugin_module.ALGORITHMS_ICON] + [REPO_ROOT / e.icon for e in plugin_module.DOCKS]
    assert len(set(paths)) == len(paths)
    for path in paths:
        renderer = QSvgRenderer(str(path))
        assert renderer.isValid(), path
        assert renderer.viewBoxF().width() == renderer.viewBoxF().height() == 24, f"{path}: drawn on a 24 px grid"

"""The ``birdseye`` provider and the plugin object, as QGIS sees them.

Every algorithm module is checked against the contract in docs/design.md#algorithms and base.py: one algorithm per
file named after its id, a group from the fixed set, UPPER_SNAKE parameter names, a help file, and
``createInstance`` giving a fresh object of the same class. The plugin's ``initGui``/``unload`` are run
against pytest-qgis's iface (patched in conftest to act on a real main window).
"""
from __future__ import annotations

import importlib.machinery
import re
import sys
import types
from pathlib import Path

import pytest
from qgis.core import Qgis, QgsApplication
from qgis.PyQt import sip
from qgis.PyQt.QtCore import QCoreApplication, QEvent
from qgis.PyQt.QtWidgets import QDockWidget, QToolBar

REPO_ROOT = Path(__file__).resolve().parents[2]
ALGORITHM_DIR = REPO_ROOT / "processing" / "algorithms"
ALGORITHM_MODULES = sorted(p.stem for p in ALGORITHM_DIR.glob("*.py") if p.stem not in {"__init__", "base"})
UPPER_SNAKE = re.compile(r"^[A-Z][A-Z0-9]*(_[A-Z0-9]+)*$")


def delete_later_now() -> None:
    """Run pending ``deleteLater`` calls, as the desktop's event loop would."""
    QCoreApplication.sendPostedEvents(None, QEvent.DeferredDelete)


def test_provider_identity(birdseye_provider):
    assert birdseye_provider.id() == "birdseye"
    assert birdseye_provider.name() == "BirdsEye"
    assert not birdseye_provider.icon().isNull(), "resources/icons/birdseye.svg did not load"
    assert QgsApplication.processingRegistry().providerById("birdseye") is birdseye_provider


def test_every_algorithm_module_registers_one_algorithm_named_after_its_file(birdseye_provider):
    """A module that fails to import is logged and skipped by the provider; here it fails the test."""
    registered = sorted(alg.name() for alg in birdseye_provider.algorithms())
    assert registered == ALGORITHM_MODULES


@pytest.mark.parametrize("alg_id", ALGORITHM_MODULES)
def test_algorithm_contract(birdseye_provider, alg_id):
    from birdseye.birdseye_qgis.__about__ import HELP_DIR
    from birdseye.processing.algorithms.base import GROUPS

    alg = QgsApplication.processingRegistry().algorithmById(f"birdseye:{alg_id}")
    assert alg is not None, f"birdseye:{alg_id} is not registered"
    assert alg.displayName().strip(), "empty display name"
    assert alg.groupId() in GROUPS, f"group {alg.groupId()!r} is not one of {sorted(GROUPS)}"

    help_file = HELP_DIR / f"{alg_id}.md"
    assert help_file.is_file(), f"missing help text {help_file.relative_to(REPO_ROOT)}"
    assert help_file.read_text(encoding="utf-8").strip()
    assert alg.shortHelpString().strip()

    names = [p.name() for p in alg.parameterDefinitions()]
    assert names, "an algorithm without parameters"
    assert len(names) == len(set(names)), f"duplicate parameter names: {names}"
    bad = [n for n in names if not UPPER_SNAKE.match(n)]
    assert not bad, f"parameter names must be UPPER_SNAKE: {bad}"

    copy = alg.createInstance()
    assert type(copy) is type(alg) and copy is not alg
    copy.initAlgorithm({})
    assert [p.name() for p in copy.parameterDefinitions()] == names


def test_algorithm_ids_are_unique_across_modules():
    ids = []
    for path in ALGORITHM_DIR.glob("*.py"):
        ids += re.findall(r"^\s+ALG_ID\s*=\s*[\"'](\w+)[\"']", path.read_text(encoding="utf-8"), re.M)
    assert len(ids) == len(set(ids)), f"an ALG_ID is used twice: {sorted(ids)}"


# ------------------------------------------------------------------------------------ plugin object
@pytest.fixture
def plugin_module(birdseye_provider, monkeypatch):
    """The plugin module, with ``ProviderUnderTest``: the provider class under a test id, so it never
    collides with the session's.

    The session provider already owns the id ``birdseye`` (the registry refuses a second one), so
    the plugin registers and removes a provider of the same class under ``birdseye_plugin_test``.
    """
    from birdseye.birdseye_qgis.gui import plugin
    from birdseye.processing import provider

    class ProviderUnderTest(provider.BirdsEyeProvider):
        def id(self):
            return "birdseye_plugin_test"

    monkeypatch.setattr(plugin, "ProviderUnderTest", ProviderUnderTest, raising=False)
    monkeypatch.setattr(provider, "BirdsEyeProvider", ProviderUnderTest)  # what classFactory hands over
    return plugin


@pytest.fixture
def fake_dock_module(monkeypatch):
    """A dock module the plugin can import lazily, as a later feature's dock would be."""
    name = "birdseye.birdseye_qgis.gui._dock_under_test"
    module = types.ModuleType(name)
    module.__spec__ = importlib.machinery.ModuleSpec(name, loader=None)

    class DockUnderTest(QDockWidget):
        created = []

        def __init__(self, iface):
            super().__init__("Dock under test", iface.mainWindow())
            DockUnderTest.created.append(self)

    module.DockUnderTest = DockUnderTest
    monkeypatch.setitem(sys.modules, name, module)
    return DockUnderTest


def menu_bar_menus(iface):
    return [a.menu() for a in iface.mainWindow().menuBar().actions() if a.menu() is not None]


def test_plugin_gui_is_added_and_removed(qgis_iface, plugin_module, fake_dock_module, monkeypatch):
    import birdseye

    entries = [plugin_module.DockEntry("birdseye_qgis.gui._dock_under_test", "DockUnderTest", "Test dock")]
    monkeypatch.setattr(plugin_module, "DOCKS", entries)
    registry = QgsApplication.processingRegistry()
    main_window = qgis_iface.mainWindow()

    plugin = birdseye.classFactory(qgis_iface)
    plugin.initGui()
    try:
        menus = [m for m in menu_bar_menus(qgis_iface) if m.objectName() == plugin_module.MENU_OBJECT_NAME]
        assert len(menus) == 1
        menu_texts = [a.text() for a in menus[0].actions() if not a.isSeparator()]
        assert menu_texts == ["BirdsEye algorithms…", "Test dock", "Install dependencies…"]
        toolbars = main_window.findChildren(QToolBar, plugin_module.TOOLBAR_OBJECT_NAME)
        assert len(toolbars) == 1 and len(toolbars[0].actions()) == 2
        assert registry.providerById("birdseye_plugin_test") is not None

        # the dock is imported and created only when first opened, then toggled by the same action
        assert fake_dock_module.created == []
        dock_action = next(a for a in menus[0].actions() if a.text() == "Test dock")
        dock_action.trigger()
        assert len(fake_dock_module.created) == 1
        dock = fake_dock_module.created[0]
        assert main_window.findChildren(QDockWidget) == [dock] and dock.isVisibleTo(main_window)
        dock_action.trigger()
        assert not dock.isVisibleTo(main_window) and len(fake_dock_module.created) == 1
    finally:
        plugin.unload()
    delete_later_now()

    assert not any(m.objectName() == plugin_module.MENU_OBJECT_NAME for m in menu_bar_menus(qgis_iface))
    assert main_window.findChildren(QToolBar, plugin_module.TOOLBAR_OBJECT_NAME) == []
    assert sip.isdeleted(dock)
    assert registry.providerById("birdseye_plugin_test") is None
    assert registry.providerById("birdseye") is not None, "unload removed someone else's provider"


def test_broken_dock_is_reported_not_raised(qgis_iface, plugin_module, monkeypatch):
    # the module exists (it is plugin.py itself) but has no such class
    monkeypatch.setattr(plugin_module, "DOCKS", [
        plugin_module.DockEntry("birdseye_qgis.gui.plugin", "NoSuchDockClass", "Broken dock")])
    qgis_iface.messageBar().clear_messages()
    plugin = plugin_module.BirdsEyePlugin(qgis_iface, plugin_module.ProviderUnderTest)
    plugin.initGui()
    try:
        [action] = plugin.dock_actions.values()
        action.trigger()
        assert not action.isChecked(), "the action must not stay checked for a dock that never opened"
        warnings = qgis_iface.messageBar().get_messages(Qgis.Warning)
        assert any("Broken dock" in w and "NoSuchDockClass" in w for w in warnings), warnings
        assert plugin.docks == {}
    finally:
        plugin.unload()
        delete_later_now()


def test_algorithms_action_without_processing_plugin_explains(qgis_iface, plugin_module, monkeypatch):
    """Under pytest there is no Processing *plugin* (no toolbox dock): the user is told what to do."""
    from qgis import utils

    monkeypatch.setattr(utils, "plugins", {})
    qgis_iface.messageBar().clear_messages()
    plugin = plugin_module.BirdsEyePlugin(qgis_iface, plugin_module.ProviderUnderTest)
    plugin.initGui()
    try:
        plugin.toolbox_action.trigger()
        warnings = qgis_iface.messageBar().get_messages(Qgis.Warning)
        assert any("Processing plugin" in w for w in warnings), warnings
    finally:
        plugin.unload()
        delete_later_now()


def test_the_plugin_registers_the_review_dock_and_the_sensor_bound_calculator():
    from birdseye.birdseye_qgis.gui import plugin as plugin_module

    assert [e.class_name for e in plugin_module.DOCKS] == ["ReviewDock", "SensorBoundDock"]


@pytest.mark.parametrize("entry_index", range(2))  # the review dock and the sensor-bound calculator
def test_registered_docks_open_and_close(qgis_iface, birdseye_provider, entry_index):
    """Every dock in the plugin's registry opens with the iface and unloads."""
    from birdseye.birdseye_qgis.gui import plugin as plugin_module
    from birdseye.processing.provider import BirdsEyeProvider

    entry = plugin_module.DOCKS[entry_index]
    qgis_iface.messageBar().clear_messages()
    plugin = plugin_module.BirdsEyePlugin(qgis_iface, BirdsEyeProvider)
    plugin.initGui()
    try:
        plugin.dock_actions[entry].trigger()
        assert qgis_iface.messageBar().get_messages(Qgis.Warning) == []
        dock = plugin.docks[entry]
        assert isinstance(dock, QDockWidget) and dock.isVisibleTo(qgis_iface.mainWindow())
    finally:
        plugin.unload()
        delete_later_now()
    assert sip.isdeleted(dock)

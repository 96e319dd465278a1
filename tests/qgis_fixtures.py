"""Fixtures for every suite that runs with pytest-qgis (registered by tests/conftest.py): the ``birdseye``
provider in the registry and a fuller iface stub.

pytest-qgis creates the one ``QgsApplication`` of the run (with widgets, offscreen); nothing here
builds QGIS objects at import time.
"""
from __future__ import annotations

import sys
from pathlib import Path

import pytest

REPO_ROOT = Path(__file__).resolve().parents[1]
QGIS_PYTHON_PLUGINS = Path("/usr/share/qgis/python/plugins")


def _let_qgis_processing_win() -> None:
    """Make ``import processing`` find QGIS's Processing framework, never our ``processing/`` folder.

    ``python -m pytest`` run from the repository puts the repository root (as ``''`` or its path) on
    ``sys.path``, and so can QGIS's own start-up; there our top-level ``processing``
    package would shadow QGIS's. Tests import the plugin as ``birdseye`` through build/pluginpath, so
    the root itself is never needed. Runs at start-up and again once QGIS has started (its Python
    start-up can put the working folder first on ``sys.path``).
    """
    sys.path[:] = [p for p in sys.path if Path(p or ".").resolve() != REPO_ROOT]
    if str(QGIS_PYTHON_PLUGINS) not in sys.path:
        sys.path.append(str(QGIS_PYTHON_PLUGINS))
    shadowing = sys.modules.get("processing")
    if shadowing is not None and Path(getattr(shadowing, "__file__", "") or "/").resolve().is_relative_to(REPO_ROOT):
        for name in [n for n in sys.modules if n == "processing" or n.startswith("processing.")]:
            del sys.modules[name]


_let_qgis_processing_win()


@pytest.fixture(scope="session")
def qgis_app(qgis_app):
    """pytest-qgis's application, with ``sys.path`` cleaned before anything imports ``processing``, and
    every map layer the tests left alive deleted before QGIS exits."""
    _let_qgis_processing_win()
    give_the_canvas_a_crs()
    yield qgis_app
    delete_surviving_layers()


def give_the_canvas_a_crs() -> None:
    """Give the test iface's map canvas a CRS, as the desktop's always has.

    ``processing.run`` builds its expression context from ``iface.mapCanvas().mapSettings()``
    (processing/tools/dataobjects.py, ``createExpressionContext``); on pytest-qgis's canvas, which starts
    with no CRS, that asks PROJ for the operation of an empty CRS and PROJ prints
    "proj_create: unrecognized format / unknown name" (found with ``strace -k``:
    ``QgsExpressionContextUtils::mapSettingsScope`` → ``QgsCoordinateReferenceSystem::operation``).
    """
    from qgis.core import QgsCoordinateReferenceSystem
    from qgis.utils import iface

    if iface is not None and not iface.mapCanvas().mapSettings().destinationCrs().isValid():
        iface.mapCanvas().setDestinationCrs(QgsCoordinateReferenceSystem("EPSG:4326"))


def delete_surviving_layers() -> int:
    """Delete the C++ side of every Python-owned map layer still alive; returns how many there were.

    A ``QgsMapLayer`` that outlives the ``QgsApplication`` crashes QGIS 3.22 at interpreter exit: Python's
    finalisation destroys it after QGIS has shut down, and the layer's destructor touches registries
    that are gone (gdb: ``QgsRasterPipe::~QgsRasterPipe`` ← ``QgsRasterLayer::~QgsRasterLayer`` ←
    ``Py_FinalizeEx``, SIGSEGV after a green run). Layers handed to ``processing.run`` in a parameter
    dict stay referenced after the test, so some always survive; deleting them while QGIS is still up
    lets the process end normally, with pytest's own exit status.
    """
    import gc

    from qgis.core import QgsMapLayer, QgsProject
    from qgis.PyQt import sip

    QgsProject.instance().clear()
    gc.collect()
    survivors = [obj for obj in gc.get_objects() if isinstance(obj, QgsMapLayer)]
    for layer in survivors:
        if not sip.isdeleted(layer) and sip.ispyowned(layer):
            sip.delete(layer)
    return len(survivors)


@pytest.fixture(scope="session")
def birdseye_provider(qgis_app, qgis_processing):
    """The ``birdseye`` provider, registered once per session after QGIS's Processing is initialised.

    ``qgis_processing`` (pytest-qgis) runs ``Processing.initialize()``, so ``processing.run`` works
    with native algorithms as well as ours.
    """
    import processing
    from qgis.core import QgsApplication

    from birdseye.processing.provider import BirdsEyeProvider

    assert Path(processing.__file__).resolve().is_relative_to(QGIS_PYTHON_PLUGINS), (
        f"'processing' resolves to {processing.__file__}, not QGIS's Processing framework")
    registry = QgsApplication.processingRegistry()
    provider = registry.providerById("birdseye")
    if provider is None:
        provider = BirdsEyeProvider()
        assert registry.addProvider(provider), "the birdseye provider could not be registered"
    return provider


class _IfaceUiPatches:
    """What pytest-qgis's iface stub only pretends to do, done on its real QMainWindow.

    The stub's ``addDockWidget``/``removeDockWidget`` do nothing and ``addToolBar(QToolBar)`` only
    records the toolbar; plugins and docks under test need them to act as in the desktop, so their
    widgets can be found, shown and removed. Its ``layerTreeView()`` is a MagicMock, which QGIS 3.44's
    Processing hands to C++ when it loads an algorithm's results (``QgsProcessingGuiUtils.addResultLayers``)
    and which C++ refuses: here it is a real view of the project's layer tree.
    """

    def __init__(self, iface):
        self.iface = iface
        self.plugin_menus = {}
        self.layer_tree_view = None

    def addDockWidget(self, area, dock):
        self.iface.mainWindow().addDockWidget(area, dock)

    def removeDockWidget(self, dock):
        self.iface.mainWindow().removeDockWidget(dock)

    def addToolBar(self, toolbar, area=None):
        from qgis.PyQt.QtCore import Qt
        from qgis.PyQt.QtWidgets import QToolBar

        main_window = self.iface.mainWindow()
        if isinstance(toolbar, str):
            toolbar = QToolBar(toolbar, main_window)
            toolbar.setObjectName(toolbar.windowTitle())
        main_window.addToolBar(area if area is not None else Qt.TopToolBarArea, toolbar)
        return toolbar

    def layerTreeView(self):
        if self.layer_tree_view is None:
            from qgis.core import QgsLayerTreeModel, QgsProject
            from qgis.gui import QgsLayerTreeView

            self.layer_tree_view = QgsLayerTreeView(self.iface.mainWindow())
            self.layer_tree_view.setModel(QgsLayerTreeModel(QgsProject.instance().layerTreeRoot(),
                                                            self.layer_tree_view))
        return self.layer_tree_view

    def pluginMenu(self):
        from qgis.PyQt.QtWidgets import QMenu

        menu_bar = self.iface.mainWindow().menuBar()
        for action in menu_bar.actions():
            if action.menu() is not None and action.menu().objectName() == "mPluginMenu":
                return action.menu()
        menu = QMenu("&Plugins", self.iface.mainWindow())
        menu.setObjectName("mPluginMenu")
        menu_bar.addMenu(menu)
        return menu

    def addPluginToMenu(self, name, action):
        submenu = self.plugin_menus.get(name)
        if submenu is None:
            submenu = self.plugin_menus[name] = self.pluginMenu().addMenu(name)
        submenu.addAction(action)

    def removePluginMenu(self, name, action):
        submenu = self.plugin_menus.get(name)
        if submenu is not None:
            submenu.removeAction(action)
            if submenu.isEmpty():
                self.pluginMenu().removeAction(submenu.menuAction())
                del self.plugin_menus[name]


@pytest.fixture(scope="session", autouse=True)
def _iface_acts_on_main_window(qgis_iface):
    """Install :class:`_IfaceUiPatches` on the session's iface stub (instance attributes)."""
    patches = _IfaceUiPatches(qgis_iface)
    names = ["addDockWidget", "removeDockWidget", "addToolBar", "layerTreeView", "pluginMenu", "addPluginToMenu",
             "removePluginMenu"]
    with pytest.MonkeyPatch.context() as monkeypatch:
        for name in names:
            monkeypatch.setattr(qgis_iface, name, getattr(patches, name), raising=False)
        yield patches

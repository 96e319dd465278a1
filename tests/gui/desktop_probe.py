"""Run inside the QGIS desktop by tests/gui/test_desktop.py (``qgis --code desktop_probe.py``).

Once the main window is up it records what the test checks — BirdsEye loaded, its provider and
algorithms registered, its menu and toolbar present, the toolbox action and every dock working, the
message log free of Python errors — saves a screenshot, writes the JSON file named by
``BIRDSEYE_PROBE_RESULT`` and quits QGIS. Any exception is recorded rather than shown in a dialog,
so the desktop never waits for a click.
"""
import json
import os
import traceback

from qgis.core import QgsApplication
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtWidgets import QDockWidget, QTabWidget, QToolBar, QWidget
from qgis.utils import iface, plugins

RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
SCREENSHOT_PATH = os.environ["BIRDSEYE_PROBE_SCREENSHOT"]
result = {"errors": []}


def message_log() -> dict:
    """Text of every tab of QGIS's Log Messages panel (it records from start-up on)."""
    viewers = [w for w in iface.mainWindow().findChildren(QWidget)
               if w.metaObject().className() == "QgsMessageLogViewer"]
    tabs = {}
    for viewer in viewers:
        for tab_widget in viewer.findChildren(QTabWidget):
            for i in range(tab_widget.count()):
                page = tab_widget.widget(i)
                tabs[tab_widget.tabText(i)] = page.toPlainText() if hasattr(page, "toPlainText") else ""
    return tabs


def toolbox_algorithm_ids(toolbox) -> list:
    """Algorithm ids the Processing toolbox shows under its current filter."""
    tree = toolbox.algorithmTree
    model = tree.model()
    found, pending = [], [model.index(r, 0) for r in range(model.rowCount())]
    while pending:
        index = pending.pop()
        algorithm = tree.algorithmForIndex(index)
        if algorithm is not None:
            found.append(algorithm.id())
        pending += [model.index(r, 0, index) for r in range(model.rowCount(index))]
    return sorted(found)


def inspect() -> None:
    main_window = iface.mainWindow()
    main_window.resize(1600, 1000)
    plugin = plugins.get("birdseye")
    result["plugins"] = sorted(plugins)
    registry = QgsApplication.processingRegistry()
    provider = registry.providerById("birdseye")
    result["provider_algorithms"] = sorted(a.id() for a in provider.algorithms()) if provider else None
    result["menu_bar"] = [a.menu().objectName() for a in main_window.menuBar().actions() if a.menu()]
    toolbars = main_window.findChildren(QToolBar, "mBirdsEyeToolBar")
    result["toolbar_actions"] = [a.text() for a in toolbars[0].actions()] if toolbars else None
    if plugin is None:
        return
    plugin.toolbox_action.trigger()
    toolbox = plugins["processing"].toolbox
    result["toolbox"] = {"visible": toolbox.isVisible(), "filter": toolbox.searchBox.text(),
                         "algorithms": toolbox_algorithm_ids(toolbox)}
    result["docks"] = {}
    for entry, action in plugin.dock_actions.items():
        action.trigger()
        dock = plugin.docks.get(entry)
        result["docks"][entry.class_name] = bool(dock is not None and isinstance(dock, QDockWidget)
                                                  and dock.isVisible())


def finish() -> None:
    try:
        result["message_log"] = message_log()
        result["message_bar"] = [[item.title(), item.text()] for item in iface.messageBar().items()]
        os.makedirs(os.path.dirname(SCREENSHOT_PATH), exist_ok=True)
        result["screenshot_saved"] = iface.mainWindow().grab().save(SCREENSHOT_PATH)
    except Exception:  # noqa: BLE001 — reported to the test
        result["errors"].append(traceback.format_exc())
    with open(RESULT_PATH, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    QgsApplication.instance().quit()


def run() -> None:
    try:
        inspect()
    except Exception:  # noqa: BLE001 — reported to the test
        result["errors"].append(traceback.format_exc())
    QTimer.singleShot(500, finish)  # let the toolbox and docks paint before the screenshot


QTimer.singleShot(500, run)

"""Run inside the QGIS desktop by tests/gui/test_desktop.py (``qgis --code desktop_probe.py``).

Once the main window is up it records what the test checks — BirdsEye loaded, its provider and
algorithms registered, its menu and toolbar present, the toolbox action and every dock working, the
message log free of Python errors — saves a screenshot, writes the JSON file named by
``BIRDSEYE_PROBE_RESULT`` and quits QGIS (``probe_session.play``). Any exception is recorded rather than
shown in a dialog, so the desktop never waits for a click.
"""
import os
import sys

from qgis.core import QgsApplication
from qgis.PyQt.QtWidgets import QDockWidget, QToolBar
from qgis.utils import iface, plugins

sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
from probe_session import message_log, play, settle  # noqa: E402

RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
SCREENSHOT_PATH = os.environ["BIRDSEYE_PROBE_SCREENSHOT"]
result = {"errors": []}


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


def session():
    """Everything at once, then half a second for the toolbox and the docks to paint before the screenshot."""
    inspect()
    yield settle(500, "toolbox and docks painted")


def last_records() -> None:
    """QGIS's log and message bar at the end, and the screenshot."""
    result["message_log"] = message_log()
    result["message_bar"] = [[item.title(), item.text()] for item in iface.messageBar().items()]
    os.makedirs(os.path.dirname(SCREENSHOT_PATH), exist_ok=True)
    result["screenshot_saved"] = iface.mainWindow().grab().save(SCREENSHOT_PATH)


play(session(), result, RESULT_PATH, last_records, start_ms=500)

"""Run inside the QGIS desktop by tests/gui/test_desktop_e2e.py (``qgis --code desktop_e2e_probe.py``).

A user's first session, scripted: open the demo project (``BIRDSEYE_E2E_PROJECT``), look at the map,
open every BirdsEye dock and use it on the demo's layers (review the held-out flight's clusters, the
sensor bound of its camera), then run *Plan the survey flight* through its Processing dialog — set
the parameters, click Run, wait for it, close it. Screenshots go to ``BIRDSEYE_E2E_SCREENSHOTS``; the
JSON report (``BIRDSEYE_PROBE_RESULT``) records what the test checks. Every exception is recorded, never
shown in a dialog, so the desktop never waits for a click; QGIS quits at the end.

The steps are a generator: each ``yield`` hands the driver a condition to wait for (polled on the Qt
event loop, so QGIS keeps painting and running its tasks meanwhile).
"""
import json
import os
import time
import traceback

from qgis.core import QgsApplication, QgsProject
from qgis.PyQt.QtCore import QTimer
from qgis.PyQt.QtWidgets import QTabWidget, QWidget
from qgis.utils import iface, plugins

PROJECT = os.environ["BIRDSEYE_E2E_PROJECT"]
SCREENSHOTS = os.environ["BIRDSEYE_E2E_SCREENSHOTS"]
RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
STORE = os.environ["BIRDSEYE_E2E_VERDICTS"]
result = {"errors": [], "screenshots": {}, "timeouts": []}


class Wait:
    """Wait until ``ready()`` is true (at most ``timeout_s``); ``what`` names it in the report."""

    def __init__(self, ready, timeout_s: float, what: str, settle_ms: int = 0):
        self.ready, self.timeout_s, self.what, self.settle_ms = ready, timeout_s, what, settle_ms


def message_log() -> dict:
    """Text of every tab of QGIS's Log Messages panel (it records from start-up on)."""
    tabs = {}
    for viewer in [w for w in iface.mainWindow().findChildren(QWidget)
                   if w.metaObject().className() == "QgsMessageLogViewer"]:
        for tab_widget in viewer.findChildren(QTabWidget):
            for i in range(tab_widget.count()):
                page = tab_widget.widget(i)
                tabs[tab_widget.tabText(i)] = page.toPlainText() if hasattr(page, "toPlainText") else ""
    return tabs


def shoot(name: str, widget) -> None:
    path = os.path.join(SCREENSHOTS, f"{name}.png")
    result["screenshots"][name] = path if widget.grab().save(path) else None


def layer_by_file(stem: str):
    """The project layer read from ``<stem>.gpkg``."""
    for layer in QgsProject.instance().mapLayers().values():
        if os.path.splitext(os.path.basename(layer.source().split("|")[0]))[0] == stem:
            return layer
    raise LookupError(f"the demo project has no layer from {stem}.gpkg")


def canvas_idle():
    canvas = iface.mapCanvas()
    return Wait(lambda: not canvas.isDrawing(), 30, "map canvas drawing", settle_ms=800)


# ------------------------------------------------------------------------------------------ the session
def session():
    main_window = iface.mainWindow()
    main_window.resize(1600, 1000)
    plugin = plugins.get("birdseye")
    result["plugin_loaded"] = plugin is not None

    # 1. Open the demo project, as File > Open Project does.
    result["project_opened"] = iface.addProject(PROJECT)
    project = QgsProject.instance()
    yield canvas_idle()
    result["layers"] = {layer.name(): layer.isValid() for layer in project.mapLayers().values()}
    result["groups"] = [node.name() for node in project.layerTreeRoot().children()]
    extent = iface.mapCanvas().extent()
    held_out = layer_by_file("frames_heldout").extent()
    result["canvas_shows_held_out_flight"] = extent.intersects(held_out) and extent.width() < 20 * held_out.width()
    shoot("project", main_window)

    # 2. Every dock of the plugin, through its menu action.
    result["docks"] = {}
    for entry, action in plugin.dock_actions.items():
        action.trigger()
        dock = plugin.docks.get(entry)
        result["docks"][entry.class_name] = bool(dock is not None and dock.isVisible())
    actions = {entry.class_name: action for entry, action in plugin.dock_actions.items()}
    docks = {entry.class_name: dock for entry, dock in plugin.docks.items()}

    # 3. The sensor-bound calculator on the demo camera (alone on the right, for its screenshot).
    bound_dock = docks["SensorBoundDock"]
    actions["ReviewDock"].trigger()  # the menu action toggles: hides the review dock for now
    calibration = os.path.join(os.path.dirname(PROJECT), "campaigns", "heldout", "calibration.yaml")
    bound_dock.calibration_widget.setFilePath(calibration)  # as choosing the file in its "…" dialog does
    yield Wait(lambda: bound_dock.result is not None, 30, "sensor bound computed", settle_ms=800)
    result["bound_calibration"] = calibration
    result["bound_intrinsics"] = bound_dock.result["inputs"]["intrinsics"] if bound_dock.result else None
    result["bound_verdicts"] = [a["verdict_exact"] for a in bound_dock.result["altitudes"]] \
        if bound_dock.result else None
    shoot("sensor_bound_dock", bound_dock)

    # 4. The review dock on the held-out flight's detections, frames and geotags.
    actions["SensorBoundDock"].trigger()
    actions["ReviewDock"].trigger()
    review = docks["ReviewDock"]
    review.set_inputs([layer_by_file("detections")], layer_by_file("frames_heldout"),
                      layer_by_file("geotags_heldout"), STORE)
    result["review_started"] = review.start_review()
    result["review_banner"] = review.banner.text() if review.banner.isVisible() else ""
    if result["review_started"]:
        yield Wait(lambda: review.current_key is not None and review.chips_shown_for == review.current_key, 30,
                   "review chips shown")
        yield Wait(lambda: not review._score_timer.isActive()
                   and review._shown_score_generation == review._score_generation, 30, "review scores", 300)
        result["review_units"] = len(review.entries)
        result["review_scores_error"] = review.scores_error
        review.run_command("confirmed_real")
        yield Wait(lambda: True, 1, "verdict recorded", settle_ms=800)
        result["review_progress"] = review.progress_label.text()
    yield canvas_idle()
    shoot("review_dock", review)
    shoot("desktop_with_docks", main_window)

    # 5. Plan the survey flight through its Processing dialog: set the parameters, click Run, close.
    import processing

    layers_before = set(project.mapLayers())
    dialog = processing.createAlgorithmDialog("birdseye:planflight", {
        "GEOTAGS": layer_by_file("geotags_heldout").id(), "ALTITUDE_M": 12.0, "SPEED_MS": 2.0})
    finished = {}
    dialog.algorithmFinished.connect(lambda ok, results: (finished.update(ok=ok, results=results),
                                                          shoot("processing_dialog", dialog)))
    dialog.show()
    yield Wait(lambda: dialog.isVisible(), 10, "Processing dialog shown", settle_ms=500)
    shoot("processing_dialog_parameters", dialog)
    dialog.runButton().click()
    yield Wait(lambda: "ok" in finished, 60, "planflight run from its dialog", settle_ms=500)
    result["dialog_run_ok"] = finished.get("ok")
    result["dialog_results"] = {k: v for k, v in finished.get("results", {}).items()
                                if isinstance(v, (int, float, str))}
    added = [project.mapLayer(i) for i in set(project.mapLayers()) - layers_before]
    result["dialog_layers"] = {layer.name(): [layer.isValid(), layer.featureCount()] for layer in added}
    dialog.close()
    yield canvas_idle()
    shoot("after_dialog", main_window)


# ------------------------------------------------------------------------------------------ the driver
def finish() -> None:
    try:
        result["message_log"] = message_log()
        result["message_bar"] = [[item.title(), item.text(), int(item.level())] for item in iface.messageBar().items()]
    except Exception:  # noqa: BLE001 — reported to the test
        result["errors"].append(traceback.format_exc())
    with open(RESULT_PATH, "w", encoding="utf-8") as f:
        json.dump(result, f, indent=1)
    # Close the project while the window still exists: QGIS 3.22 crashes (signal 11 in
    # setMapStyleDockLayer) when it removes a project's layers during its own shutdown.
    iface.newProject(False)
    QTimer.singleShot(500, QgsApplication.instance().quit)


def drive(steps, waiting=None, started=None) -> None:
    """Advance the session to its next wait, then poll that wait every 100 ms."""
    try:
        if waiting is not None:
            if not waiting.ready():
                if time.monotonic() - started < waiting.timeout_s:
                    QTimer.singleShot(100, lambda: drive(steps, waiting, started))
                    return
                result["timeouts"].append(waiting.what)
            if waiting.settle_ms and not getattr(waiting, "settled", False):
                waiting.settled = True  # let the widgets paint before the next screenshot
                QTimer.singleShot(waiting.settle_ms, lambda: drive(steps, waiting, started))
                return
        following = next(steps)
        QTimer.singleShot(0, lambda: drive(steps, following, time.monotonic()))
    except StopIteration:
        QTimer.singleShot(200, finish)
    except Exception:  # noqa: BLE001 — reported to the test
        result["errors"].append(traceback.format_exc())
        QTimer.singleShot(200, finish)


QTimer.singleShot(1000, lambda: drive(session()))

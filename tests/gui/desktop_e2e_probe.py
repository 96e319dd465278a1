"""Run inside the QGIS desktop by tests/gui/test_desktop_e2e.py (``qgis --code desktop_e2e_probe.py``).

A user's first session, scripted: open the demo project (``BIRDSEYE_E2E_PROJECT``), look at the map,
open every BirdsEye dock and use it on the demo's layers (review the held-out flight's clusters, the
sensor bound of its camera), then run *Plan the survey flight* through its Processing dialog — set
the parameters, click Run, wait for it, close it. Screenshots go to ``BIRDSEYE_E2E_SCREENSHOTS``; the
JSON report (``BIRDSEYE_PROBE_RESULT``) records what the test checks, QGIS's log and message bar last.

The steps are a generator played by ``probe_session.play``: each ``yield`` hands it a condition to wait for
(polled on the Qt event loop, so QGIS keeps painting and running its tasks meanwhile). Every exception is
recorded, never shown in a dialog, so the desktop never waits for a click; QGIS quits at the end.
"""
import os
import sys

from qgis.core import QgsProject
from qgis.utils import iface, plugins

sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
from probe_session import Wait, canvas_idle, file_stem, message_log, play  # noqa: E402

PROJECT = os.environ["BIRDSEYE_E2E_PROJECT"]
SCREENSHOTS = os.environ["BIRDSEYE_E2E_SCREENSHOTS"]
RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
STORE = os.environ["BIRDSEYE_E2E_VERDICTS"]
result = {"errors": [], "screenshots": {}, "timeouts": []}


def shoot(name: str, widget) -> None:
    path = os.path.join(SCREENSHOTS, f"{name}.png")
    result["screenshots"][name] = path if widget.grab().save(path) else None


def layer_by_file(stem: str):
    """The project layer read from ``<stem>.gpkg``."""
    for layer in QgsProject.instance().mapLayers().values():
        if file_stem(layer) == stem:
            return layer
    raise LookupError(f"the demo project has no layer from {stem}.gpkg")


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


def last_records() -> None:
    """What QGIS's log and message bar say at the end of the session."""
    result["message_log"] = message_log()
    result["message_bar"] = [[item.title(), item.text(), int(item.level())] for item in iface.messageBar().items()]


play(session(), result, RESULT_PATH, last_records)

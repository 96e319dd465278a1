"""Run inside the QGIS desktop by tests/gui/test_docks_desktop.py (``qgis --code docks_probe.py``).

Looks at every BirdsEye dock and dialog as a person meets them, on the demo project and a screen the size
of the X server's (1366 × 768 or 1920 × 1080): the review dock as it opens (its settings unfolded too), after
Start — pressed with the layers it chose itself: the detections found on the held-out field's orthomosaic —
and after Start on the flight's own detections, the sensor-bound calculator on its default
platform and on the demo's calibration, and Install dependencies. For each it saves a screenshot to
``BIRDSEYE_DOCKS_SCREENSHOTS`` and records the cut-off widgets (``docks_layout.layout_problems``), the kind
of every layer each layer choice stands on, and what QGIS's log said; the JSON report
(``BIRDSEYE_PROBE_RESULT``) is what the test checks.

The steps are a generator played by ``probe_session.play``: each ``yield`` hands it a condition to wait for,
polled on the Qt event loop so QGIS keeps painting meanwhile. Exceptions are recorded, never shown in a dialog;
QGIS quits at the end.
"""
import importlib
import os
import sys
from functools import partial

from qgis.core import QgsApplication, QgsProject
from qgis.PyQt.QtCore import Qt
from qgis.PyQt.QtGui import QGuiApplication
from qgis.PyQt.QtWidgets import QApplication
from qgis.utils import iface, plugins

sys.path.insert(0, os.environ["BIRDSEYE_PROBE_DIR"])
import probe_session  # noqa: E402
from docks_layout import layout_problems  # noqa: E402
from probe_session import canvas_idle, file_stem, play  # noqa: E402

PROJECT = os.environ["BIRDSEYE_DOCKS_PROJECT"]
SCREENSHOTS = os.environ["BIRDSEYE_DOCKS_SCREENSHOTS"]
RESULT_PATH = os.environ["BIRDSEYE_PROBE_RESULT"]
result = {"errors": [], "timeouts": [], "screenshots": {}, "contents": {}, "problems": {}, "widths": {},
          "choices": {}, "log": [], "review_started": {}, "review_banner": {}, "review_chips": {}}
QgsApplication.messageLog().messageReceived.connect(
    lambda message, tag, level: result["log"].append([tag, int(level), message]))
# Every wait here is followed by a screenshot: 600 ms of painting after each, unless it says otherwise.
Wait = partial(probe_session.Wait, settle_ms=600)


def birdseye_module(name: str):
    """A module of the plugin, under the package name QGIS loaded it as."""
    return importlib.import_module(f"{type(plugins['birdseye']).__module__.rsplit('.birdseye_qgis.', 1)[0]}.{name}")


def look_at(name: str, widget, check: bool = True) -> None:
    """Screenshot of what a person sees now; for a BirdsEye widget (``check``) also its cut-off widgets and width."""
    path = os.path.join(SCREENSHOTS, f"{name}.png")
    result["screenshots"][name] = path if widget.grab().save(path) else None
    if check:
        result["problems"][name] = layout_problems(widget)
        result["widths"][name] = widget.width()
    scroll = widget.widget() if hasattr(widget, "widget") and callable(widget.widget) else None
    if scroll is not None and hasattr(scroll, "widget") and scroll.widget() is not None:
        # The whole of a dock, as if the screen were tall enough: what scrolling would show.
        path = os.path.join(SCREENSHOTS, f"{name}_content.png")
        result["contents"][name] = path if scroll.widget().grab().save(path) else None


def review_choices(dock) -> dict:
    """The kind of the layer each of the review's layer choices stands on."""
    kinds = birdseye_module("birdseye_qgis.qgis_io.layer_kinds")
    project = QgsProject.instance()
    detections = [project.mapLayer(i) for i in dock.detections_combo.checkedItemsData()]
    frames, geotags = dock.frames_combo.currentLayer(), dock.geotags_combo.currentLayer()
    return {"detections": [kinds.layer_kind(layer) for layer in detections],
            "frames": kinds.layer_kind(frames) if frames else None,
            "geotags": kinds.layer_kind(geotags) if geotags else None,
            "files": [file_stem(layer) for layer in detections + [frames, geotags]]}


def start_review(dock, name: str):
    """Press Start and wait for the first unit's chips and the scores; records whether it started, what the
    banner said and the layer choices it stood on (under ``name``)."""
    dock.start_button.click()
    started = dock.session is not None
    result["review_started"][name] = started
    result["review_banner"][name] = dock.banner.text() if dock.banner.isVisible() else ""
    if started:
        yield Wait(lambda: dock.current_key is not None and dock.chips_shown_for == dock.current_key, 30,
                   f"review chips shown ({name})")
        yield Wait(lambda: not dock._score_timer.isActive()
                   and dock._shown_score_generation == dock._score_generation, 30, f"review scores ({name})")
    yield canvas_idle()
    result["choices"][f"review_{name}"] = review_choices(dock)


def review_chip_report(dock) -> dict:
    """What the current unit's chips are: how many, cut from which files, their windows, the error if any."""
    if dock.session is None or dock.current_key not in dock.chip_loader.chips:
        return {}
    plans, images, n_frames, error = dock.chip_loader.chips[dock.current_key]
    return {"n": len(plans), "images": [os.path.basename(p.image) for p in plans], "error": error,
            "windows": [list(p.window) for p in plans], "shown": len(dock.chips.pixmaps),
            "frames_enabled": dock.frames_combo.isEnabled()}


# ------------------------------------------------------------------------------------------ the session
def session():
    main_window = iface.mainWindow()
    main_window.setGeometry(QGuiApplication.primaryScreen().availableGeometry())
    main_window.showMaximized()
    iface.addProject(PROJECT)
    yield canvas_idle()
    result["window"] = [main_window.width(), main_window.height()]
    font = QApplication.font()
    result["font"] = [font.family(), font.pointSizeF()]
    plugin = plugins["birdseye"]
    actions = {entry.class_name: action for entry, action in plugin.dock_actions.items()}

    # The review dock as it opens on the demo, then with its settings unfolded.
    actions["ReviewDock"].trigger()
    review = next(dock for entry, dock in plugin.docks.items() if entry.class_name == "ReviewDock")
    yield Wait(review.isVisible, 10, "review dock shown")
    result["choices"]["review_dock"] = review_choices(review)
    look_at("review_dock", review)
    settings = [box for box in review.findChildren(type(review.setup_box)) if box is not review.setup_box]
    for box in settings:
        box.setCollapsed(False)
    yield Wait(lambda: True, 1, "settings unfolded")
    look_at("review_dock_settings", review)
    for box in settings:
        box.setCollapsed(True)

    # Start, as the user presses it, with the layers the dock chose: the most recent detections, the demo's found
    # on the held-out field's orthomosaic, reviewed with chips cut from it.
    yield from start_review(review, "raster")
    result["review_chips"]["raster"] = review_chip_report(review)
    look_at("review_dock_raster", review)
    look_at("desktop_review_raster", main_window, check=False)

    # The flight's own detections instead, ticked and unticked as clicks do (toggleItemCheckState: the combo's
    # setItemCheckState tells no one): chips cut from its frames.
    project, combo = QgsProject.instance(), review.detections_combo
    for i in range(combo.count()):
        wanted = file_stem(project.mapLayer(combo.itemData(i))) == "detections"
        if (combo.itemCheckState(i) == Qt.CheckState.Checked) != wanted:
            combo.toggleItemCheckState(i)
    yield from start_review(review, "frames")
    result["review_chips"]["frames"] = review_chip_report(review)
    look_at("review_dock_started", review)
    look_at("desktop_review", main_window, check=False)
    actions["ReviewDock"].trigger()

    # The sensor-bound calculator on its default platform, then on the demo's camera.
    actions["SensorBoundDock"].trigger()
    bound = next(dock for entry, dock in plugin.docks.items() if entry.class_name == "SensorBoundDock")
    yield Wait(lambda: bound.isVisible() and bound.result is not None, 30, "sensor bound computed")
    look_at("sensor_bound_dock", bound)
    before = bound.result
    bound.calibration_widget.setFilePath(os.path.join(os.path.dirname(PROJECT), "campaigns", "heldout",
                                                      "calibration.yaml"))
    yield Wait(lambda: bound.result is not before, 30, "sensor bound of the demo camera")
    result["bound_calibration_kept"] = bool(bound.calibration_widget.filePath())
    look_at("sensor_bound_dock_calibration", bound)
    look_at("desktop_sensor_bound", main_window, check=False)
    actions["SensorBoundDock"].trigger()

    # BirdsEye › Install dependencies…, shown without blocking (the menu action runs it modal).
    dialog = birdseye_module("birdseye_qgis.gui.dependencies").DependenciesDialog(main_window,
                                                                                 folder=plugin.package_folder)
    dialog.show()
    yield Wait(dialog.isVisible, 10, "dependencies dialog shown")
    result["dependencies_buttons"] = {button.text(): [button.isEnabled(), button.toolTip()]
                                      for button in (dialog.install_button, dialog.group_button)}
    look_at("dependencies_dialog", dialog)
    dialog.close()


play(session(), result, RESULT_PATH)

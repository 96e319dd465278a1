"""Every BirdsEye dock and dialog in the real QGIS desktop, on laptop and desktop screens, as a person sees them.

QGIS runs under its own Xvfb at 1366 × 768 and at 1920 × 1080 with the small demo project open (a copy of the
session's demo, conftest.py: Start writes the review's log into the demo's detections); ``docks_probe.py`` opens the
review dock (as it opens, its settings unfolded, after Start with the layers it chose itself — the detections found
on the orthomosaic — and after Start on the flight's detections), the sensor-bound
calculator (default platform, the demo's camera) and Install dependencies, and saves each to
build/screenshots/docks/<size>/<name>.png. The tests fail on a horizontal scroll bar, a widget whose text is cut off
(``docks_layout.py``), a layer choice standing on a layer of the wrong kind, or an error in QGIS's log. Set
``BIRDSEYE_E2E_DEMO`` to a folder made by ``make demo`` to look at the full demo (a copy of it too).
"""
from __future__ import annotations

import json
from pathlib import Path

import pytest
import test_desktop
from test_desktop import REPO_ROOT, run_probe, screenshot_folder

PROBE = Path(__file__).with_name("docks_probe.py")
SCREENSHOTS = REPO_ROOT / "build" / "screenshots" / "docks"
SIZES = ("1366x768", "1920x1080")
TIMEOUT_S = 150
SHOTS = ("review_dock", "review_dock_settings", "review_dock_raster", "desktop_review_raster", "review_dock_started",
         "desktop_review", "sensor_bound_dock", "sensor_bound_dock_calibration", "desktop_sensor_bound",
         "dependencies_dialog")

pytestmark = test_desktop.pytestmark  # slow, and skipped without Debian's qgis or Xvfb


@pytest.fixture(scope="module", params=SIZES)
def seen(request, demo_project_copy, tmp_path_factory) -> dict:
    """QGIS started on a screen of the given size, on this module's copy of the demo (conftest.py: Start writes the
    review's log into the demo's detections); the probe's report and QGIS's output."""
    size = request.param
    work = tmp_path_factory.mktemp(f"docks-{size}")
    shots = screenshot_folder(SCREENSHOTS / size)
    result = run_probe(PROBE, work, TIMEOUT_S, shots / "timeout.png", shots / "qgis-output.txt",
                       report_copy=shots / "report.json", screen=f"{size}x24",
                       BIRDSEYE_DOCKS_PROJECT=str(demo_project_copy), BIRDSEYE_DOCKS_SCREENSHOTS=str(shots))
    return {**result, "size": size, "shots": shots}


def test_the_session_ran_and_every_screenshot_was_saved(seen):
    from qgis.PyQt.QtGui import QImage

    report = seen["report"]
    assert report["errors"] == [] and report["timeouts"] == [], report
    assert seen["returncode"] == 0, seen["output"]
    width, height = (int(v) for v in seen["size"].split("x"))
    assert report["window"] == [width, height], "QGIS fills the screen"
    assert sorted(report["screenshots"]) == sorted(SHOTS)
    for name, path in report["screenshots"].items():
        assert path and not QImage(path).isNull(), name


def test_nothing_is_cut_off_and_nothing_scrolls_sideways(seen):
    problems = {name: found for name, found in seen["report"]["problems"].items() if found}
    assert problems == {}, json.dumps(problems, indent=1, ensure_ascii=False)


def test_every_layer_choice_stands_on_a_layer_of_its_kind(seen):
    report = seen["report"]
    for moment in ("review_dock", "review_raster", "review_frames"):
        choices = report["choices"][moment]
        assert choices["detections"] == ["detections"], choices
        assert (choices["frames"], choices["geotags"]) == ("frames", "geotags"), choices
    assert report["review_started"] == {"raster": True, "frames": True}, report["review_banner"]
    # On the demo: the most recent detections, those found on the held-out field's orthomosaic, with the held-out
    # flight's layers (newer frames of training flights exist); the frames are not needed for them.
    assert report["choices"]["review_dock"]["files"] == ["detections_mosaic", "frames_heldout", "geotags_heldout"]
    # The setup keeps showing the layers under review (the verdict layer Start adds changes nothing).
    assert report["choices"]["review_raster"]["files"] == report["choices"]["review_dock"]["files"]
    assert report["choices"]["review_frames"]["files"] == ["detections", "frames_heldout", "geotags_heldout"]


def test_the_review_cuts_its_chips_from_the_raster_or_from_the_frames(seen):
    """Detections found on a raster: one chip, a window of the orthomosaic, the frame choice disabled; the flight's
    detections: chips from its frames."""
    chips = seen["report"]["review_chips"]
    raster, frames = chips["raster"], chips["frames"]
    assert raster["error"] is None and raster["n"] == raster["shown"] == 1, raster
    assert raster["images"][0].lower().endswith((".tif", ".tiff")) and not raster["frames_enabled"], raster
    assert frames["error"] is None and frames["n"] == frames["shown"] >= 1 and frames["frames_enabled"], frames
    assert not any(image.lower().endswith((".tif", ".tiff")) for image in frames["images"]), frames


def test_the_review_starts_without_errors_in_the_log(seen):
    from qgis.core import Qgis

    bad = [entry for entry in seen["report"]["log"]
           if entry[1] >= int(Qgis.MessageLevel.Warning) or "Cannot" in entry[2] or "verdicts" in entry[2]]
    assert bad == [], bad


def test_the_calibration_file_stays_named_once_loaded(seen):
    assert seen["report"]["bound_calibration_kept"]


def test_a_disabled_button_says_why(seen):
    for text, (enabled, tip) in seen["report"]["dependencies_buttons"].items():
        assert enabled or tip, f"{text!r} is greyed out without saying why"

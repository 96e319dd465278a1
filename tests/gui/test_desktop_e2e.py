"""End to end in the real QGIS desktop, under its own Xvfb: the demo project, every dock, a Processing dialog.

On the session's small demo (conftest.py: ``scripts/demo.py --size small``, the whole chain, bundled model
included), QGIS starts with a fresh profile and ``--code desktop_e2e_probe.py``, which opens the
project, opens and uses each dock, runs *Plan the survey flight* through its dialog, saves screenshots
to build/screenshots/e2e/ and writes a JSON report that the tests below read. The review's verdicts go to a
GeoPackage of the test's own, so the session leaves the demo folder as it found it.

Set ``BIRDSEYE_E2E_DEMO`` to a demo folder made by ``make demo`` to run the same session on the full demo
(how the README's screenshots are made).
"""
from __future__ import annotations

from pathlib import Path

import pytest
import test_desktop
from test_desktop import REPO_ROOT, run_probe, screenshot_folder

PROBE = Path(__file__).with_name("desktop_e2e_probe.py")
SCREENSHOTS = REPO_ROOT / "build" / "screenshots" / "e2e"
DESKTOP_TIMEOUT_S = 150

pytestmark = test_desktop.pytestmark  # slow, and skipped without Debian's qgis or Xvfb


@pytest.fixture(scope="module")
def session(demo_project, tmp_path_factory) -> dict:
    """Start QGIS once, let the probe play the session, and return its report plus QGIS's output."""
    work = tmp_path_factory.mktemp("desktop-e2e")
    screenshot_folder(SCREENSHOTS)
    return run_probe(PROBE, work, DESKTOP_TIMEOUT_S, SCREENSHOTS / "timeout.png", SCREENSHOTS / "qgis-output.txt",
                     BIRDSEYE_E2E_PROJECT=str(demo_project), BIRDSEYE_E2E_SCREENSHOTS=str(SCREENSHOTS),
                     BIRDSEYE_E2E_VERDICTS=str(work / "verdicts.gpkg"))


def test_session_ran_to_the_end(session):
    report = session["report"]
    assert report["errors"] == []
    assert report["timeouts"] == []
    assert session["returncode"] == 0, session["output"]


def test_demo_project_opens_with_every_layer_valid(session):
    report = session["report"]
    assert report["plugin_loaded"] and report["project_opened"]
    assert report["layers"] and all(report["layers"].values()), report["layers"]
    assert report["groups"] == ["survey", "flight", "labels", "detections", "clusters", "plan", "farm map"]
    assert report["canvas_shows_held_out_flight"], "the project must open on its fields, not on the whole world"


def test_every_dock_opens_and_works_on_the_demo(session):
    report = session["report"]
    assert report["docks"] == {"ReviewDock": True, "SensorBoundDock": True}
    from birdseye.birdseye_qgis.core.geometry.camera import load_calibration

    camera = load_calibration(report["bound_calibration"])
    used = report["bound_intrinsics"]
    assert (used["width"], used["height"]) == (camera.width, camera.height)
    assert used["fx"] == pytest.approx(camera.fx) and used["cy"] == pytest.approx(camera.cy)
    assert report["bound_verdicts"]
    assert set(report["bound_verdicts"]) <= {"accept", "reject"}
    assert report["review_started"], report["review_banner"]
    assert report["review_units"] > 0 and report["review_scores_error"] is None
    assert report["review_progress"].startswith("1 ") or " 1 " in report["review_progress"], report["review_progress"]


def test_algorithm_runs_from_its_processing_dialog(session):
    report = session["report"]
    assert report["dialog_run_ok"] is True
    assert report["dialog_results"]["GEOTAG_COUNT"] > 0 and report["dialog_results"]["WAYPOINT_COUNT"] > 0
    layers = report["dialog_layers"]
    assert sorted(layers) == ["Route", "Waypoints"], layers
    assert all(valid and count > 0 for valid, count in layers.values()), layers


def test_no_python_error_in_the_log(session):
    log = session["report"]["message_log"]
    assert "Python error" not in log, log.get("Python error")
    ours = [line for line in log.get("BirdsEye", "").splitlines() if "WARNING" in line or "CRITICAL" in line]
    assert ours == []
    assert "Traceback" not in session["output"], session["output"]
    from qgis.core import Qgis

    warnings = [item for item in session["report"]["message_bar"] if item[2] in (Qgis.Warning, Qgis.Critical)]
    assert warnings == [], "the message bar shows warnings (a style's font missing? a layer not loading?)"


def test_screenshots_saved(session):
    from qgis.PyQt.QtGui import QImage

    shots = session["report"]["screenshots"]
    assert set(shots) == {"project", "sensor_bound_dock", "review_dock", "desktop_with_docks",
                          "processing_dialog_parameters", "processing_dialog", "after_dialog"}
    for name, path in shots.items():
        assert path, f"{name} was not saved"
        image = QImage(path)
        assert image.width() >= 300 and image.height() >= 300, name
    assert QImage(shots["project"]).width() >= 1024


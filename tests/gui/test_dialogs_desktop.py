"""Every BirdsEye Processing dialog in the real QGIS desktop, under its own Xvfb, at 1366 × 768 and 1920 × 1080.

On the session's small demo (conftest.py: frames, geotags, detections, clusters, waypoints, rasters; or
``BIRDSEYE_E2E_DEMO``'s demo folder made before), QGIS starts once per screen size with a fresh profile and
``--code dialogs_probe.py``, which opens the demo project, adds a review verdict table (a GeoPackage of the test's
own: the demo folder stays as it was), opens every algorithm's dialog as the toolbox does, saves a screenshot of each
to build/screenshots/dialogs/<width>x<height>/<alg_id>.png and reports what the tests below check: the dialog on the
screen, no horizontal scroll bar in its parameter panel, no control wider than the panel's visible width (advanced
parameters shown too), and each layer box on a layer of its kind.
"""
from __future__ import annotations

import warnings
from pathlib import Path

import pytest
import test_desktop
from test_desktop import ALGORITHM_IDS, REPO_ROOT, run_probe, screenshot_folder

PROBE = Path(__file__).with_name("dialogs_probe.py")
SCREENSHOTS = REPO_ROOT / "build" / "screenshots" / "dialogs"
SIZES = ("1366x768", "1920x1080")
DESKTOP_TIMEOUT_S = 240

pytestmark = test_desktop.pytestmark  # slow, and skipped without Debian's qgis or Xvfb


@pytest.fixture(scope="module", params=SIZES)
def session(request, demo_project, tmp_path_factory) -> dict:
    """QGIS started at one screen size; the probe's report, QGIS's output and the screenshot folder."""
    size = request.param
    work = tmp_path_factory.mktemp(f"dialogs-{size}")
    shots = screenshot_folder(SCREENSHOTS / size)
    result = run_probe(PROBE, work, DESKTOP_TIMEOUT_S, shots / "timeout.png", shots / "qgis-output.txt",
                       screen=f"{size}x24", BIRDSEYE_DIALOGS_PROJECT=str(demo_project),
                       BIRDSEYE_DIALOGS_SCREENSHOTS=str(shots), BIRDSEYE_DIALOGS_VERDICTS=str(work / "verdicts.gpkg"))
    return {**result, "size": size, "shots": shots}


def dialogs(session) -> dict:
    """Algorithm id → what the probe saw of its dialog; every algorithm's, or the test fails."""
    found = session["report"]["dialogs"]
    assert sorted(f"birdseye:{alg_id}" for alg_id in found) == ALGORITHM_IDS, session["report"]["errors"]
    return found


def test_every_dialog_opened(session):
    report = session["report"]
    for name in report["deleted_wrappers"]:  # QGIS's own wrappers, not layer boxes (the probe checks): shown
        warnings.warn(f"the dialog held a deleted parameter wrapper: {name}", stacklevel=1)
    assert report["errors"] == []
    assert report["plugin_loaded"] and report["project_opened"]
    assert "birdseye_verdicts" in report["layers"]
    assert dialogs(session)


def test_every_dialog_fits_the_screen(session):
    outside = {alg_id: (d["frame"], d["screen"]) for alg_id, d in dialogs(session).items()
               if not d["fits_screen"]}
    assert outside == {}


def scrolling_sideways(session, alg_ids) -> dict:
    return {alg_id: (d["content_min_width"], d["visible_width"], d["advanced_widest"][:2])
            for alg_id, d in dialogs(session).items()
            if alg_id in alg_ids and (d["horizontal_scrollbar"] or d["advanced_horizontal_scrollbar"])}


def clipped_controls(session, alg_ids) -> dict:
    return {alg_id: (d["clipped"] + d["advanced_clipped"])[:3] for alg_id, d in dialogs(session).items()
            if alg_id in alg_ids and (d["clipped"] or d["advanced_clipped"])}


def test_no_parameter_panel_scrolls_sideways(session):
    """A horizontal scroll bar means a control wider than the panel: its end (a "…" button, a combo's arrow) is
    out of sight."""
    assert scrolling_sideways(session, set(dialogs(session))) == {}, "width needed, width visible, the widest controls"


def test_no_control_is_clipped(session):
    assert clipped_controls(session, set(dialogs(session))) == {}


def test_every_layer_box_starts_on_a_layer_of_its_kind(session):
    """BirdsEye's layer boxes list only their kind and a required one starts on such a layer (the demo has one
    of every kind); an optional one starts empty, as does every other layer box (a DEM, Import geotags' layer)."""
    wrong, checked = [], 0
    for alg_id, dialog in dialogs(session).items():
        for box in dialog["layer_boxes"]:
            checked += 1
            where = f"{alg_id}:{box['parameter']}"
            if box["kind"] is None:
                if box["current"] is not None:
                    wrong.append((where, "starts on", box["current"]))
            elif box["listed_kinds"] not in ([], [box["kind"]]):
                wrong.append((where, "lists", box["listed_kinds"]))
            elif box["optional"] and box["current"] is not None:
                wrong.append((where, "optional, yet starts on", box["current"]))
            elif not box["optional"] and box["current_kind"] != box["kind"]:
                wrong.append((where, f"takes {box['kind']}, starts on", box["current"], box["current_kind"]))
    assert checked >= 20 and wrong == []


def test_a_box_that_follows_another_starts_over_the_same_ground(session):
    """Compare detectors' frames and geotags are the flight of its detections, Write labels' geotags the survey of
    its frames' field (the demo has three fields)."""
    following = {f"{alg_id}:{box['parameter']}": box["over_near"] for alg_id, dialog in dialogs(session).items()
                 for box in dialog["layer_boxes"] if box["near"] and box["current"] is not None}
    assert {"comparedetectors:FRAMES", "comparedetectors:GEOTAGS", "writelabels:GEOTAGS"} <= set(following)
    assert all(following.values()), following


def test_screenshots_saved(session):
    from qgis.PyQt.QtGui import QImage

    width, height = map(int, session["size"].split("x"))
    for alg_id, dialog in dialogs(session).items():
        assert dialog["screenshot"], alg_id
        image = QImage(dialog["screenshot"])
        assert 300 <= image.width() <= width and 200 <= image.height() <= height, alg_id

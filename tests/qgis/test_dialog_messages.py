"""What a person reads when a run is refused or reports: through the Processing registry, as the dialog, the
Modeler and ``qgis_process`` run it.

* a number out of range names its range and unit (base.checkParameterValues), not QGIS's bare "Incorrect
  parameter value";
* an output path that cannot be written is refused before the run, saying why, and a file-system error during a
  run is a sentence naming the path, never a traceback;
* results are information and problems warnings (qgis_io/layers.report_to_feedback): the label check's figures
  are no warning;
* Refine frame poses on frames without their images says where it looked and how to give them;
* figures in layers and results are rounded to what they mean (0.01 px, 1 mm);
* a normal run is quiet: no matplotlib "Axes3D" warning, no COLMAP log lines.
"""
from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import sysconfig
from pathlib import Path

import pytest
from qgis.core import QgsProcessingException
from registry import Recorder, imported_campaign, run

from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig

REPO_ROOT = Path(__file__).resolve().parents[2]
BRIGHTON = REPO_ROOT / "tests" / "data" / "brighton_beach_960"
WHEAT = REPO_ROOT.parent / "shared" / "data" / "real_solutions" / "metashape_wheat_tanashi" / "wheat_tanashi.psx"


def refused(alg_id, parameters) -> str:
    with pytest.raises(QgsProcessingException) as raised:
        run(alg_id, parameters)
    return str(raised.value)


@pytest.mark.parametrize("alg_id, parameters, message", [
    ("refineposes", {"MATCH_SIZE_PX": 50}, "MATCH_SIZE_PX must be between 400 and 10000 px, got 50"),
    ("writelabels", {"SIGMA_PX": 0.1}, "SIGMA_PX must be between 0.5 and 500 px, got 0.1"),
    ("detect", {"EDGE_BUFFER_PX": -3}, "EDGE_BUFFER_PX must be at least 0 px, got -3"),
    ("planflight", {"FORWARD_OVERLAP_PCT": 150}, "FORWARD_OVERLAP_PCT must be between 0 and 99 %, got 150"),
    ("traindetector", {"VALIDATION_FRACTION": 0.9}, "VALIDATION_FRACTION must be between 0 and 0.5, got 0.9"),
])
def test_a_number_out_of_range_names_the_range_and_unit(birdseye_provider, alg_id, parameters, message):
    assert message in refused(alg_id, parameters)


@pytest.fixture(scope="module")
def flight(birdseye_provider, tmp_path_factory):
    """A small simulated flight's geotags and frames."""
    folder = tmp_path_factory.mktemp("flight")
    geotags, frames = imported_campaign(folder, CampaignConfig(seed=5, n_targets=4, field_width_m=6.0,
                                                               field_length_m=4.0, image_width=320, image_height=200))
    return {"geotags": geotags, "frames": frames}


def test_an_output_path_that_cannot_be_written_is_refused_saying_why(flight, tmp_path, monkeypatch):
    labels = {"GEOTAGS": flight["geotags"], "FRAMES": flight["frames"], "WRITE_RASTERS": False}
    a_file = tmp_path / "labels.txt"
    a_file.write_text("not a folder")
    assert f"OUTPUT_FOLDER: {a_file} is a file; give a folder" in refused(
        "writelabels", {**labels, "OUTPUT_FOLDER": str(a_file)})
    a_folder = tmp_path / "report"
    a_folder.mkdir()
    assert f"OUTPUT_REPORT: {a_folder} is a folder; give a file name" in refused(
        "refineposes", {"FRAMES": flight["frames"], "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_REPORT": str(a_folder)})
    # A folder the user may not write in (tests may run as root, who may write anywhere: the check is asked).
    from birdseye.processing.algorithms import base

    locked = tmp_path / "locked"
    locked.mkdir()
    monkeypatch.setattr(base.os, "access", lambda path, mode: Path(path) != locked)
    assert f"OUTPUT_FOLDER: {locked / 'labels'} cannot be written ({locked} is read-only for you)" in refused(
        "writelabels", {**labels, "OUTPUT_FOLDER": str(locked / "labels")})


def test_a_file_system_error_during_a_run_is_a_sentence_not_a_traceback(flight, tmp_path):
    """A folder inside a file: no check before the run can know every path a step makes; the run's error is
    turned into a message naming the path."""
    a_file = tmp_path / "notes.txt"
    a_file.write_text("a file")
    message = refused("writelabels", {"GEOTAGS": flight["geotags"], "FRAMES": flight["frames"],
                                      "WRITE_RASTERS": False, "OUTPUT_FOLDER": str(a_file / "labels")})
    assert str(a_file) in message and "Not a directory" in message and "Traceback" not in message


def test_the_label_check_is_information_and_its_figures_rounded(birdseye_provider):
    """The real Metashape project (shared/data/real_solutions): its label check (median 5.5 px) is a result."""
    assert WHEAT.is_file(), f"the real Metashape project is missing: {WHEAT}"
    feedback = Recorder()
    result = run("importcameras", {"CAMERAS": str(WHEAT), "OUTPUT": "TEMPORARY_OUTPUT",
                                   "OUTPUT_CONTROL": "TEMPORARY_OUTPUT", "OUTPUT_MARK_CHECK": "TEMPORARY_OUTPUT"},
                 feedback)
    assert any("Label accuracy against 23 pinned image mark(s)" in info for info in feedback.infos)
    assert any(info.startswith("Per point") for info in feedback.infos)
    assert not any("Label accuracy" in w or "Per point" in w or "Worst frames" in w for w in feedback.warnings)
    assert result["MARKS_MEDIAN_PX"] == pytest.approx(5.54, abs=0.01) == round(result["MARKS_MEDIAN_PX"], 2)
    errors = [f["error_px"] for f in result["OUTPUT_MARK_CHECK"].getFeatures()]
    assert errors and all(e == round(e, 2) for e in errors)


def test_refine_poses_without_images_says_where_it_looked_and_what_to_do(birdseye_provider, tmp_path):
    images = tmp_path / "images"
    shutil.copytree(BRIGHTON, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    shutil.rmtree(images)
    message = refused("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_REPORT": None})
    assert "only 0 of 6 frame(s) have their image file" in message
    assert f"e.g. {images}{os.sep}DJI_00" in message, "where it looked"
    assert "IMAGES parameter of Import camera solution" in message, "what gives the frames their images"


GLOG_LINE = re.compile(r"^[IWEF]\d{4,8} \d\d:\d\d:\d\d", re.M)


@pytest.mark.timeout(600)
def test_refine_poses_is_quiet_and_rounds_its_figures(birdseye_provider, tmp_path, capfd):
    """COLMAP's own log (glog: "I20250612 10:00:00.123 …" lines on stderr, from C++) stays out of a normal run."""
    import pycolmap  # noqa: F401  (refineposes needs it: a missing install fails here, not skips)

    images = tmp_path / "images"
    shutil.copytree(BRIGHTON, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    capfd.readouterr()
    feedback = Recorder()
    result = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT", "OUTPUT_REPORT": None}, feedback)
    captured = capfd.readouterr()
    assert not GLOG_LINE.search(captured.err + captured.out), (captured.err + captured.out)[-2000:]
    assert not any(w.startswith("Warning:") for w in feedback.warnings), "a warning says so once, not twice"
    rows = [f for f in result["OUTPUT"].getFeatures() if f["registered"]]
    assert rows
    for field, decimals in (("reprojection_rms_px", 2), ("position_change_m", 3), ("rotation_change_deg", 3)):
        assert all(f[field] == round(f[field], decimals) for f in rows), field


def test_matplotlib_warns_nothing_once_the_plugin_is_loaded(tmp_path):
    """A pip matplotlib beside Debian's warns "Unable to import Axes3D" on its first import; once QGIS has loaded
    the plugin (its provider), that warning is gone. The same import without the plugin shows whether this
    Python has the two installations at all."""
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(REPO_ROOT / "build" / "pluginpath"),
                                                        sysconfig.get_path("purelib"),
                                                        "/usr/share/qgis/python/plugins"]),
           "QT_QPA_PLATFORM": "offscreen"}
    code = "import sys; {plugin}import matplotlib.figure"

    def warnings_of(plugin: str) -> str:
        result = subprocess.run([sys.executable, "-W", "default", "-c", code.format(plugin=plugin)], env=env,
                                cwd=tmp_path, capture_output=True, text=True, timeout=120, check=True)
        return result.stderr

    if "Axes3D" not in warnings_of(""):
        pytest.skip("this Python has one matplotlib: it never warns about Axes3D")
    assert "Axes3D" not in warnings_of("import birdseye.processing.provider; ")

"""birdseye:refineposes through the Processing registry on the six real Brighton Beach DJI frames
(the copies in tests/data/brighton_beach_960): every frame registered, sub-pixel reprojection, the pose change
reported per frame and in the HTML report; a frame without its image keeps its metadata pose."""
from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from registry import run

BRIGHTON = Path(__file__).resolve().parents[1] / "data" / "brighton_beach_960"


@pytest.mark.timeout(600)
def test_brighton_frames_are_all_registered_and_the_change_reported(birdseye_provider, tmp_path):
    import pycolmap  # noqa: F401  (refineposes needs it: a missing install fails here, not skips)
    images = tmp_path / "images"
    shutil.copytree(BRIGHTON, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    (images / "DJI_0023.JPG").unlink()  # copied away before refinement: must keep its metadata pose
    before = {f["frame_id"]: (f["lat"], f["lon"], f["height_m"]) for f in frames.getFeatures()}
    result = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT",
                                 "OUTPUT_REPORT": str(tmp_path / "report.html")})
    assert result["REGISTERED_COUNT"] == 5
    rows = {f["frame_id"]: f for f in result["OUTPUT"].getFeatures()}
    registered = [f for f in rows.values() if f["registered"]]
    assert len(registered) == 5
    assert sum(f["reprojection_rms_px"] for f in registered) / 5 <= 1.0
    assert all(f["n_points"] >= 20 and "refined" in f["flags"] for f in registered)
    # The metadata is metres and degrees off; the change is reported, not hidden.
    assert all(f["position_change_m"] > 0.05 and f["rotation_change_deg"] > 0.05 for f in registered)
    missing = next(f for f in rows.values() if not f["registered"])
    assert "not_refined" in missing["flags"]
    assert (missing["lat"], missing["lon"], missing["height_m"]) == before[missing["frame_id"]]
    report = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "5 of 6" in report and "image file not found" in report and "DJI_0023.JPG" in report

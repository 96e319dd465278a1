"""End to end on a simulated DJI RTK flight: labels from the drone's own metadata, then from the poses
photogrammetry refines, both measured against the holes rendered in the frames.

simulatecampaign (PLATFORM = DJI drone: 51 photos of 1280 × 960 px from 8 m over an 18 × 16 m field,
three lines, 80 % forward and 70 % side overlap; the metadata's heading, tilt and 1.5 m height errors)
→ importdjiimages → writelabels (metadata: tens of pixels off) → refineposes → writelabels (refined:
median ≤ 1 px, 95 % ≤ 3 px). Geotags are exact (RTK_SIGMA_M 0, fixed solutions only), so only the
poses move the labels.

Real frames: the six Brighton Beach DJI Phantom 3 images (960 px copies in tests/data; no DewarpData, so
the camera is only nominal): all registered, sub-pixel, the focal length fixed by the flying height, the
attitude fields of the refined nadir frames not flipped. The focal length against geotags' surveyed heights, in
their own (ellipsoidal) reference: test_refine_geoid.py.
"""
from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest
from test_dji_simulation import fixed_geotags, label_errors, run, simulate, write_labels

E2E_FLIGHT = {"SEED": 11, "N_TARGETS": 20, "FIELD_WIDTH_M": 18.0, "FIELD_LENGTH_M": 16.0}


def summary(errors) -> str:
    return (f"{len(errors)} labels, median {np.median(errors):.2f} px, 95 % {np.quantile(errors, 0.95):.2f} px, "
            f"max {errors.max():.2f} px")


@pytest.mark.slow
@pytest.mark.timeout(3600)
def test_refined_poses_bring_dji_labels_onto_the_rendered_holes(birdseye_provider, tmp_path):
    folder = tmp_path / "dji"
    result = simulate(folder, **E2E_FLIGHT)
    assert result["FRAME_COUNT"] >= 45
    frames = run("importdjiimages", {"IMAGES": result["FRAMES_FOLDER"], "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    geotags = fixed_geotags(folder)

    metadata = label_errors(folder, write_labels(geotags, frames, tmp_path / "labels_metadata"))
    print(f"labels from the DJI metadata vs rendered holes: {summary(metadata)}")
    assert len(metadata) >= 100 and np.median(metadata) > 20.0

    refinement = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT"})
    refined = refinement["OUTPUT"]
    print(f"refineposes registered {refinement['REGISTERED_COUNT']} of {refined.featureCount()} frames")
    assert refinement["REGISTERED_COUNT"] >= 0.9 * result["FRAME_COUNT"]
    after = label_errors(folder, write_labels(geotags, refined, tmp_path / "labels_refined"))
    print(f"labels from the refined poses vs rendered holes: {summary(after)}")
    assert len(after) >= 0.9 * len(metadata)
    assert np.median(after) <= 1.0 and np.quantile(after, 0.95) <= 3.0


BRIGHTON = Path(__file__).resolve().parents[1] / "data" / "brighton_beach_960"


@pytest.mark.timeout(900)
def test_real_dji_frames_with_a_nominal_camera_all_register_below_a_pixel(birdseye_provider, tmp_path):
    images = tmp_path / "images"
    shutil.copytree(BRIGHTON, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
    frames = run("importdjiimages", {"IMAGES": str(images), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    before = list(frames.getFeatures())
    assert all("approx_intrinsics" in f["flags"] for f in before)
    nominal = json.loads(before[0]["camera"])["fx"]
    result = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT",
                                 "OUTPUT_REPORT": str(tmp_path / "report.html")})
    rows = list(result["OUTPUT"].getFeatures())
    assert result["REGISTERED_COUNT"] == len(rows) == 6
    rms = [f["reprojection_rms_px"] for f in rows]
    print(f"Brighton, nominal camera: 6/6 registered, mean reprojection {np.mean(rms):.3f} px")
    assert np.mean(rms) <= 1.0
    focal = json.loads(rows[0]["camera"])["fx"]
    report = (tmp_path / "report.html").read_text(encoding="utf-8")
    assert "fixed so that the block" in report and f"{focal:.1f} px fixed" in report
    assert abs(focal / nominal - 1.0) > 0.01  # the EXIF focal length is not the camera's
    # Nadir gimbals, refined a few degrees off the vertical: heading stays in yaw, roll stays small.
    for old, new in zip(before, rows):
        assert abs(new["roll_deg"]) < 15 and abs((new["yaw_deg"] - old["yaw_deg"] + 180) % 360 - 180) < 15


@pytest.mark.timeout(900)
def test_real_frames_with_exif_only_are_imported_and_all_register_below_a_pixel(birdseye_provider, tmp_path):
    """The same real frames with their XMP stripped (what most other drones and JPEG-rewriting tools leave):
    placed from EXIF GPS, a nominal camera and a heading along the track, then refined."""
    from strip_xmp import strip_xmp

    images = tmp_path / "images"
    images.mkdir()
    for path in sorted(BRIGHTON.glob("*.JPG")):
        strip_xmp(path, images / path.name)
    frames = run("importdjiimages", {"IMAGES": str(images), "FLIGHT_HEIGHT_M": 40.0,
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    before = list(frames.getFeatures())
    assert len(before) == 6
    assert all({"approx_intrinsics", "attitude_from_track"} <= set(f["flags"].split(",")) for f in before)
    result = run("refineposes", {"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT"})
    rows = list(result["OUTPUT"].getFeatures())
    rms = [f["reprojection_rms_px"] for f in rows]
    print(f"Brighton, EXIF only: {result['REGISTERED_COUNT']}/6 registered, mean reprojection {np.mean(rms):.3f} px")
    assert result["REGISTERED_COUNT"] == 6 and np.mean(rms) <= 1.0

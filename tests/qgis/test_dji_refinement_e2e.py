"""End to end on a simulated DJI RTK flight: labels from the drone's own metadata, then from the poses
photogrammetry refines, both measured against the holes rendered in the frames.

simulatecampaign (PLATFORM = DJI drone: 51 photos of 1280 × 960 px from 8 m over an 18 × 16 m field,
three lines, 80 % forward and 70 % side overlap; the metadata's heading, tilt and 1.5 m height errors)
→ importdjiimages → writelabels (metadata: tens of pixels off) → refineposes → writelabels (refined:
median ≤ 1 px, 95 % ≤ 3 px). Geotags are exact (RTK_SIGMA_M 0, fixed solutions only), so only the
poses move the labels.
"""
from __future__ import annotations

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
    pytest.importorskip("pycolmap")
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

"""A simulated DJI flight through the product path: simulatecampaign (PLATFORM = DJI drone) →
importdjiimages → importgeotags → writelabels, labels measured against the rendered holes.

* Exact metadata (NOISE_OFF): every label within 0.5 px of its rendered hole — the simulator writes,
  and the importer reads, the DJI conventions (gimbal angles, DewarpData, heights) the same way.
* The drone's metadata errors (heading, tilt, 1.5 m height): labels miss by tens of pixels.
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_pairs
from birdseye.birdseye_qgis.core.sim.dji_images import dji_camera_model

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from registry import rows, run
from rendered_holes import dark_core_centroid

# One line of 1280 × 960 frames from 8 m (8.9 mm per pixel) over a 10 × 8 m field with 10 burrows;
# exact geotags so that only the poses move the labels.
DJI_FLIGHT = {"PLATFORM": 1, "SEED": 4, "N_TARGETS": 10, "FIELD_WIDTH_M": 10.0, "FIELD_LENGTH_M": 8.0,
              "ALTITUDE_M": 8.0, "IMAGE_WIDTH": 1280, "IMAGE_HEIGHT": 960, "RTK_SIGMA_M": 0.0, "N_MISSED": 0,
              "N_SPURIOUS": 0}


def simulate(folder, **params):
    return run("simulatecampaign", {**DJI_FLIGHT, **params, "OUTPUT_FOLDER": str(folder)})


def fixed_geotags(folder):
    """The rover's geotags with an RTK fixed solution (float fixes are metres of centimetres off)."""
    return run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "FIX_FILTER": 1,
                                 "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]


def write_labels(geotags, frames, out):
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 5.0, "WRITE_RASTERS": False,
                        "OUTPUT_FOLDER": str(out), "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None})
    return rows(Path(out) / "labels.csv")


def label_errors(folder, labels):
    """Distance (px) from each label to its rendered hole, the hole measured in the image alone around
    where the TRUE pose puts it (so a label tens of pixels off does not steer the measurement).
    Holes too close to the image edge to measure are left out."""
    import cv2

    truth = {Path(r["image"]).name: r for r in rows(folder / "truth" / "frames_true.csv")}
    targets = {int(r["geotag_row"]): r for r in rows(folder / "truth" / "targets.csv") if r["geotag_row"]}
    first = cv2.imread(labels[0]["image"], cv2.IMREAD_GRAYSCALE)
    camera = dji_camera_model(first.shape[1], first.shape[0])
    t = [truth[Path(r["image"]).name] for r in labels]
    num = lambda key: np.array([float(r[key]) for r in t])
    quat = np.stack([num(k) for k in ("qw", "qx", "qy", "qz")], axis=1)
    poses = FramePoses(np.arange(len(t)), num("lat_deg"), num("lon_deg"), num("height_m"), quat, num("ground_h_m"),
                       camera)
    local = LocalFrame.around(poses.lat, poses.lon, poses.height)
    geometry = FrameGeometry(poses, local)
    target = [targets[int(r["geotag_id"])] for r in labels]
    points = local.from_geodetic(np.array([float(g["lat"]) for g in target]),
                                 np.array([float(g["lon"]) for g in target]), num("ground_h_m"))
    true_uv = project_pairs(geometry, np.arange(len(t)), points, LevelPlaneGround(geometry)).uv
    gsd = geometry.depth_below() / camera.fx
    errors, images = [], {}
    for k, r in enumerate(labels):
        radius, outer = float(target[k]["radius_m"]) / gsd[k], float(target[k]["mound_radius_m"]) / gsd[k]
        u, v = true_uv[k]
        if min(u, v, camera.width - 1 - u, camera.height - 1 - v) < 1.8 * outer:
            continue
        if r["image"] not in images:
            images[r["image"]] = cv2.imread(r["image"]).astype(float).mean(axis=2)
        hole = dark_core_centroid(images[r["image"]], true_uv[k], radius, outer)
        errors.append(np.hypot(*(hole - [float(r["u"]), float(r["v"])])))
    return np.asarray(errors)


def test_labels_from_exact_dji_metadata_sit_on_the_rendered_holes(birdseye_provider, tmp_path):
    folder = tmp_path / "exact"
    result = simulate(folder, NOISE_OFF=True)
    frames = run("importdjiimages", {"IMAGES": result["FRAMES_FOLDER"], "OUTPUT": "TEMPORARY_OUTPUT"})
    assert frames["FRAME_COUNT"] == result["FRAME_COUNT"] and frames["UNPLACED_COUNT"] == 0
    errors = label_errors(folder, write_labels(fixed_geotags(folder), frames["OUTPUT"], tmp_path / "labels"))
    assert len(errors) >= 20
    assert errors.max() < 0.5, f"label to rendered hole: max {errors.max():.3f} px"


def test_labels_from_erroneous_dji_metadata_miss_by_tens_of_pixels(birdseye_provider, tmp_path):
    from qgis.core import QgsProcessingFeedback

    class Log(QgsProcessingFeedback):
        def __init__(self):
            super().__init__()
            self.infos = []

        def pushInfo(self, info):
            self.infos.append(info)

    folder = tmp_path / "dji"
    result = simulate(folder)
    assert result["POSES"] == "" and result["CALIBRATION"] == "" and result["FRAME_COUNT"] >= 10
    log = Log()
    frames = run("importdjiimages", {"IMAGES": result["FRAMES_FOLDER"], "OUTPUT": "TEMPORARY_OUTPUT"}, log)
    cameras = [line for line in log.infos if line.startswith("Camera:")]
    assert len(cameras) == 1 and "DewarpData DJI M3E SIM-M3E-0001" in cameras[0]   # one camera, not one per frame
    errors = label_errors(folder, write_labels(fixed_geotags(folder), frames["OUTPUT"], tmp_path / "labels"))
    median, p95 = np.median(errors), np.quantile(errors, 0.95)
    print(f"labels from DJI metadata vs rendered holes: {len(errors)} labels, median {median:.1f} px, "
          f"95 % {p95:.1f} px, max {errors.max():.1f} px")
    assert len(errors) >= 20
    assert 20.0 < median < 200.0 and errors.min() > 2.0

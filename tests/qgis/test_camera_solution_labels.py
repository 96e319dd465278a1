"""A camera solution end to end on rendered pixels: the true poses of a simulated DJI flight, written as
a Metashape export by Metashape's own conventions (tests/data/camera_solutions.py), imported with
importcameras; writelabels then projects the geotags at their surveyed heights (no altimeter) and every
label must sit on its rendered hole. The same flight's metadata labels miss by tens of pixels
(test_dji_simulation.py)."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
from test_dji_simulation import fixed_geotags, label_errors, rows, run, simulate, write_labels

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from camera_solutions import metashape_calibration, write_metashape_ecef

from birdseye.birdseye_qgis.core.field.dji import T_CAM_GIMBAL
from birdseye.birdseye_qgis.core.geometry.geodesy import geodetic_to_ecef, rotation_ecef_enu
from birdseye.birdseye_qgis.core.geometry.rotations import R_ENU_NED, quat_to_rotmat
from birdseye.birdseye_qgis.core.sim.dji_images import dji_camera_model


def test_metashape_solution_of_a_dji_flight_puts_labels_on_the_rendered_holes(birdseye_provider, tmp_path):
    folder = tmp_path / "dji"
    result = simulate(folder)
    truth = rows(folder / "truth" / "frames_true.csv")
    num = lambda key: np.array([float(r[key]) for r in truth])
    lat, lon, h = num("lat_deg"), num("lon_deg"), num("height_m")
    quat = np.stack([num(k) for k in ("qw", "qx", "qy", "qz")], axis=1)
    # gimbal → NED (the simulator's truth), camera axes by the DJI mount, NED → ECEF at each frame
    r_ecef_ned = rotation_ecef_enu(lat, lon) @ R_ENU_NED
    r_ecef_cam = r_ecef_ned @ quat_to_rotmat(quat) @ T_CAM_GIMBAL[:3, :3].T
    first = next(Path(result["FRAMES_FOLDER"]).glob("*.JPG"))
    import cv2

    height_px, width_px = cv2.imread(str(first), cv2.IMREAD_GRAYSCALE).shape
    camera = dji_camera_model(width_px, height_px)
    write_metashape_ecef(tmp_path / "cameras.xml", r_ecef_cam, geodetic_to_ecef(lat, lon, h),
                         [Path(r["image"]).stem for r in truth], metashape_calibration(camera), width_px, height_px)
    frames = run("importcameras", {"CAMERAS": str(tmp_path / "cameras.xml"), "IMAGES": result["FRAMES_FOLDER"],
                                   "OUTPUT": "TEMPORARY_OUTPUT"})
    assert frames["FRAME_COUNT"] == len(truth) and frames["NOT_ALIGNED_COUNT"] == 0
    errors = label_errors(folder, write_labels(fixed_geotags(folder), frames["OUTPUT"], tmp_path / "labels"))
    print(f"labels from the Metashape solution vs rendered holes: {len(errors)} labels, median "
          f"{np.median(errors):.2f} px, 95 % {np.quantile(errors, 0.95):.2f} px, max {errors.max():.2f} px")
    assert len(errors) >= 20
    assert np.median(errors) <= 1.0 and np.quantile(errors, 0.95) <= 2.0

"""Labels land on the targets: the whole product path (import → writelabels) on simulated campaigns.

* Noise off, at a site 2.95° east of a UTM central meridian (grid convergence ≈ 2.1°): every label is
  within 0.5 px of the rendered hole, measured in the image alone.
* Noise on: the label error against the true pose follows the first-order covariance of the sensor
  bound, with the altimeter carrying the depth (so σz is the altimeter's, not the INS's).
"""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from birdseye.birdseye_qgis.core.design.sensor_bound import pixel_covariance, sigmas_to_variances
from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_pairs
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from registry import rows
from rendered_holes import dark_core_centroid


def product_labels(folder, out, **extra):
    import processing

    def run(alg, params):
        return processing.run(f"birdseye:{alg}", params)

    geotags = run("importgeotags", {"INPUT": str(folder / "geotags.csv"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    frames = run("importflightlog", {"POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
                                     "CALIBRATION": str(folder / "calibration.yaml"),
                                     "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 5.0, "WRITE_RASTERS": False,
                        "OUTPUT_FOLDER": str(out), "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None, **extra})
    return geotags, rows(out / "labels.csv")


def truth_projection(folder, labels):
    """Each label's geotag projected through the TRUE pose of its frame, onto the true ground."""
    camera = load_calibration(folder / "calibration.yaml")
    truth = {Path(r["image"]).name: r for r in rows(folder / "truth" / "frames_true.csv")}
    geotags = [line.split(",") for line in (folder / "geotags.csv").read_text().splitlines()]
    t = [truth[Path(r["image"]).name] for r in labels]
    num = lambda key: np.array([float(r[key]) for r in t])
    quat = np.stack([num(k) for k in ("qw", "qx", "qy", "qz")], axis=1)
    poses = FramePoses(np.arange(len(t)), num("lat_deg"), num("lon_deg"), num("height_m"), quat, num("ground_h_m"),
                       camera)
    local = LocalFrame.around(poses.lat, poses.lon, poses.height)
    geometry = FrameGeometry(poses, local)
    g = np.array([[float(v) for v in geotags[int(r["geotag_id"]) - 1][:2]] for r in labels])
    points = local.from_geodetic(g[:, 0], g[:, 1], num("ground_h_m"))
    from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround

    proj = project_pairs(geometry, np.arange(len(t)), points, LevelPlaneGround(geometry))
    return proj.uv, geometry, camera


def test_noise_off_labels_sit_on_the_rendered_holes_near_a_utm_zone_edge(birdseye_provider, tmp_path):
    import cv2

    folder = tmp_path / "campaign"
    simulate_campaign(CampaignConfig(seed=11, n_targets=8, field_width_m=9.0, field_length_m=7.0, image_width=640,
                                     image_height=400, site_lat=45.0, site_lon=11.95, ground_height_m=120.0,
                                     n_missed=0, n_spurious=0, noise_off=True), folder)
    geotags, labels = product_labels(folder, tmp_path / "labels")
    assert geotags.crs().authid() == "EPSG:32632"  # the geotags come back through UTM grid coordinates
    targets = {int(r["geotag_row"]): r for r in rows(folder / "truth" / "targets.csv") if r["geotag_row"]}
    _, geometry, camera = truth_projection(folder, labels)
    gsd = float(np.median(geometry.gsd_m()))
    errors = []
    for r in labels:
        target = targets[int(r["geotag_id"])]
        radius, outer = float(target["radius_m"]) / gsd, float(target["mound_radius_m"]) / gsd
        if float(r["margin_px"]) < 1.8 * outer:
            continue
        gray = cv2.imread(r["image"]).astype(float).mean(axis=2)
        uv = np.array([float(r["u"]), float(r["v"])])
        errors.append(dark_core_centroid(gray, uv, radius, outer) - uv)
    errors = np.hypot(*np.asarray(errors).T)
    assert len(errors) >= 10
    assert errors.max() < 0.5, f"label to rendered hole: max {errors.max():.3f} px"


def test_noise_on_label_errors_follow_the_sensor_bound_covariance(birdseye_provider, tmp_path):
    sigmas = (0.01, 0.01, 0.06, 0.04, 0.04, 0.13)
    radalt = 0.03
    folder = tmp_path / "campaign"
    simulate_campaign(CampaignConfig(seed=21, n_targets=30, field_width_m=14.0, field_length_m=10.0,
                                     image_width=640, image_height=400, sigmas=sigmas, radalt_sigma_m=radalt,
                                     rtk_sigma_m=0.0, rtk_float_episodes=0, n_missed=0, n_spurious=0), folder)
    _, labels = product_labels(folder, tmp_path / "labels")
    uv_true, geometry, camera = truth_projection(folder, labels)
    uv = np.array([[float(r["u"]), float(r["v"])] for r in labels])
    error = uv - uv_true
    # The altimeter measures the depth: the INS height error cancels, the altimeter's remains.
    variances = sigmas_to_variances(np.array(sigmas[:2] + (radalt,) + sigmas[3:]))
    depth = geometry.depth_below()
    cov = np.stack([pixel_covariance(camera, np.array([u]), np.array([v]), d, variances)[0]
                    for (u, v), d in zip(uv_true, depth)])
    d2 = np.einsum("ni,nij,nj->n", error, np.linalg.inv(cov), error)
    assert len(d2) > 200
    # χ²(2): mean 2, 95 % quantile 5.99. The INS noise is correlated in time, so frames are not
    # independent samples: the bounds allow for a much smaller effective sample size, and still
    # refuse a covariance off by a third.
    print(f"label error vs sensor bound: mean Mahalanobis² {d2.mean():.2f}, 95 % {np.quantile(d2, 0.95):.2f}")
    assert 1.5 < d2.mean() < 2.6, f"mean Mahalanobis² {d2.mean():.2f} (χ²₂: 2)"
    assert 4.5 < np.quantile(d2, 0.95) < 7.8

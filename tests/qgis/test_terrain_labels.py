"""Labels over a 20° slope, through the product path (simulatecampaign → importers → writelabels).

A campaign is simulated over a plane tilted by 20° (noise off) and flown terrain-following at 10 m;
the importers read it, ``importflightlog`` with the campaign's DEM.

* With the DEM, every label sits within 0.5 px of its rendered hole (measured in the image alone).
* Without it (the level plane at the altimeter's ground), every label is off by what the terrain-slope
  study predicts. The study's geometry (``core/design/terrain_slope.py``): a nadir camera ``h`` above the level
  plane, a target at horizontal distance ``d`` from the camera's foot and ``Δ`` above that plane; the
  level model draws it at depth ``h``, the camera sees it at depth ``h − Δ``, so the label falls short
  of the target, towards the nadir, by ``e = f·d/(h − Δ) − f·d/h`` px — for a target uphill of the
  nadir on a plane of slope α (``Δ = d·tan α``) that is the study's ``f·ρ²·tan α / (1 − ρ·tan α)``,
  ρ = d/h. Here each label has its own ``h`` (the altimeter's level plane under its frame), ``d`` and
  ``Δ`` (from the target's true position: the slope meets it at an angle and the altimeter's level
  plane passes through the terrain where the tilted beam hits it, not under the camera), i.e. an
  effective slope ``atan(Δ/d)`` along the target's direction; for uphill targets the prediction is
  taken from ``slope_error_px`` itself. The real camera is tilted by a degree or two and has lens
  distortion, which the study leaves out: they change the error by a few per cent.
"""
from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.design.terrain_slope import slope_error_px
from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "data"))
from registry import Recorder, rows, run, simulated_terrain_campaign
from rendered_holes import dark_core_centroid

SLOPE_DEG = 20.0
CAMPAIGN = {"SEED": 7, "N_TARGETS": 14, "FIELD_WIDTH_M": 8.0, "FIELD_LENGTH_M": 6.0, "IMAGE_WIDTH": 640,
            "IMAGE_HEIGHT": 400, "FPS": 2.0, "N_MISSED": 0, "N_SPURIOUS": 0, "NOISE_OFF": True,
            "TERRAIN": 1, "SLOPE_DEG": SLOPE_DEG, "SLOPE_ASPECT_DEG": 250.0}

@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    """The campaign, imported, and labelled twice: with the DEM and with the level plane."""
    base = tmp_path_factory.mktemp("slope")
    folder = base / "campaign"
    imported = simulated_terrain_campaign(folder, CAMPAIGN)
    dem, geotags, frames = imported["dem"], imported["geotags"], imported["frames"]
    assert Path(imported["DEM"]) == folder / "truth" / "dem.tif"
    common = {"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 5.0, "WRITE_RASTERS": False,
              "OUTPUT_FRAMES": None, "OUTPUT_GEOTAGS": None}
    run("writelabels", {**common, "DEM": dem, "DEM_VERTICAL_DATUM": 0, "OUTPUT_FOLDER": str(base / "dem")})
    level_feedback = Recorder()
    run("writelabels", {**common, "OUTPUT_FOLDER": str(base / "level")}, level_feedback)
    key = lambda r: (int(r["frame_id"]), int(r["geotag_id"]))
    return {"folder": folder, "frames": frames, "level_warnings": level_feedback.warnings,
            "dem_labels": {key(r): r for r in rows(base / "dem" / "labels.csv")},
            "level_labels": {key(r): r for r in rows(base / "level" / "labels.csv")}}


@pytest.fixture(scope="module")
def measured(campaign):
    """Per DEM label clear of the image edge: the label, the rendered hole's centre (px) and the study's
    geometry of its target — camera height h above the frame's level plane, horizontal distance d from
    the camera's foot, height Δ of the target above the level plane (m) — and the nadir's pixel."""
    import cv2

    folder, frame_layer = campaign["folder"], campaign["frames"]
    camera = load_calibration(folder / "calibration.yaml")
    frames = {f["frame_id"]: f for f in frame_layer.getFeatures()}
    targets = {int(r["geotag_row"]): r for r in rows(folder / "truth" / "targets.csv") if r["geotag_row"]}
    keys = sorted(campaign["dem_labels"])
    recs = [frames[k[0]] for k in keys]
    num = lambda name: np.array([float(f[name]) for f in recs])
    poses = FramePoses(np.arange(len(keys)), num("lat"), num("lon"), num("height_m"),
                       np.stack([num(q) for q in ("qw", "qx", "qy", "qz")], axis=1), num("ground_h_m"), camera)
    geometry = FrameGeometry(poses, LocalFrame.around(poses.lat, poses.lon, poses.height))
    t = [targets[k[1]] for k in keys]
    target_xyz = geometry.local.from_geodetic(*(np.array([float(r[c]) for r in t]) for c in ("lat", "lon", "h_ground")))
    up = geometry.up
    h = np.einsum("fi,fi->f", geometry.C - geometry.ground_point, up)
    delta = np.einsum("fi,fi->f", target_xyz - geometry.ground_point, up)
    offset = target_xyz - geometry.C
    d = np.linalg.norm(offset - np.einsum("fi,fi->f", offset, up)[:, None] * up, axis=1)
    nadir_uv = camera.project(geometry.to_camera(np.arange(len(keys)), geometry.C - 100.0 * up))
    f_px = math.sqrt(camera.fx * camera.fy)
    out = []
    for i, k in enumerate(keys):
        label = campaign["dem_labels"][k]
        gsd = (h[i] - delta[i]) / f_px  # at the target's own depth
        radius, outer = float(t[i]["radius_m"]) / gsd, float(t[i]["mound_radius_m"]) / gsd
        if float(label["margin_px"]) < 1.8 * outer:
            continue
        gray = cv2.imread(label["image"]).astype(float).mean(axis=2)
        uv = np.array([float(label["u"]), float(label["v"])])
        out.append({"key": k, "dem_uv": uv, "hole": dark_core_centroid(gray, uv, radius, outer),
                    "h": h[i], "d": d[i], "delta": delta[i], "nadir_uv": nadir_uv[i]})
    return camera, out


def test_simulatecampaign_offers_terrain_and_returns_its_dem(birdseye_provider, campaign):
    from qgis.core import QgsApplication

    alg = QgsApplication.processingRegistry().algorithmById("birdseye:simulatecampaign")
    names = {p.name() for p in alg.parameterDefinitions()}
    for name in ("TERRAIN", "SLOPE_DEG", "SLOPE_ASPECT_DEG", "RELIEF_M", "HILL_WAVELENGTH_M"):
        assert name in names and name in alg.shortHelpString()
    assert "DEM" in {o.name() for o in alg.outputDefinitions()}
    record = json.loads((campaign["folder"] / "truth" / "campaign.json").read_text())["terrain"]
    assert record["kind"] == "plane" and record["slope_deg"] == SLOPE_DEG and record["dem"] == "truth/dem.tif"


def test_importflightlog_with_the_dem_flags_every_frame_steep(campaign):
    frames = list(campaign["frames"].getFeatures())
    assert len(frames) > 20
    for f in frames:
        assert f["terrain_slope_deg"] == pytest.approx(SLOPE_DEG, abs=0.3)
        assert "steep_terrain" in (f["flags"] or "")
    # The level-plane labelling is warned that those frames drift off target.
    assert any("steep_terrain" in w and "DEM" in w for w in campaign["level_warnings"])


def test_labels_with_the_dem_sit_on_the_rendered_holes(campaign, measured):
    _, labels = measured
    errors = np.array([np.hypot(*(m["hole"] - m["dem_uv"])) for m in labels])
    print(f"DEM labels to rendered holes ({len(errors)}): median {np.median(errors):.3f}, max {errors.max():.3f} px")
    assert len(errors) >= 20
    assert errors.max() < 0.5, f"label to rendered hole: max {errors.max():.3f} px"


def test_level_plane_labels_err_as_the_terrain_slope_study_predicts(campaign, measured):
    camera, labels = measured
    f_study = max(camera.fx, camera.fy)
    compared, largest = 0, 0.0
    report = []
    for m in labels:
        level = campaign["level_labels"].get(m["key"])
        if level is None:  # the level plane put it outside the image (or into the edge buffer)
            continue
        error = np.array([float(level["u"]), float(level["v"])]) - m["hole"]
        h, d, delta = m["h"], m["d"], m["delta"]
        predicted = f_study * d / (h - delta) - f_study * d / h  # > 0: uphill, the label falls short
        if delta > 0:
            study = slope_error_px(camera, h, math.degrees(math.atan2(delta, d)), d / h)
            assert float(study) == pytest.approx(predicted, rel=1e-9)
        measured_px = np.hypot(*error)
        report.append((measured_px, predicted))
        assert measured_px == pytest.approx(abs(predicted), rel=0.05, abs=0.5), (
            f"label {m['key']}: level-plane error {measured_px:.2f} px, study {predicted:+.2f} px "
            f"(h {h:.2f} m, d {d:.2f} m, Δ {delta:+.3f} m)")
        if abs(predicted) > 3.0:
            # It points at the nadir for targets above the level plane, away from it below.
            towards_nadir = (m["nadir_uv"] - m["hole"]) / np.hypot(*(m["nadir_uv"] - m["hole"]))
            assert np.dot(error / measured_px, np.sign(predicted) * towards_nadir) > 0.99
        compared += 1
        largest = max(largest, abs(predicted))
    report = np.array(report)
    rel = np.abs(report[:, 0] - np.abs(report[:, 1])) / np.maximum(np.abs(report[:, 1]), 1e-9)
    print(f"level plane vs study ({compared} labels): predicted up to {largest:.1f} px; |measured − predicted| "
          f"max {np.max(np.abs(report[:, 0] - np.abs(report[:, 1]))):.2f} px, relative (|pred| > 3 px) "
          f"max {np.max(rel[np.abs(report[:, 1]) > 3]) * 100:.1f} %")
    assert compared >= 15 and largest > 10.0  # the slope matters: tens of pixels at the image edge

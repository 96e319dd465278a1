"""birdseye:detect through the registry: a frame layer in, PointZ detections on the ground out.

Frames are synthetic (targets painted where the geometry core projects them) and the model is a
fixed convolution whose heatmap is the image itself, so every output can be checked exactly.
"""
from __future__ import annotations

import hashlib
import json

import cv2
import numpy as np
import onnx
import pytest
from qgis.core import (
    QgsFeature,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsRasterLayer,
    QgsVectorLayer,
)
from raster_scene import identity_model
from registry import Recorder

from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELDS, euler_degrees
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_pairs
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

UTM = "EPSG:32756"
NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
TARGETS = np.array([[0.15, 0.2, 0.0], [-0.3, -0.1, 0.0], [0.4, -0.15, 0.0]])  # local ENU, on the ground


def run(params):
    import processing

    return processing.run("birdseye:detect", params)


@pytest.fixture(scope="module")
def scene(tmp_path_factory):
    """Three frames 10 m above level ground (1 cm/px), their images, and a frame layer in UTM."""
    folder = tmp_path_factory.mktemp("frames")
    t = np.eye(4)
    t[:3, :3] = NADIR
    cam = CameraModel(240, 180, 1000.0, 1000.0, 121.0, 88.5, (-0.05, 0.02, 0, 0, 0), t)
    local = LocalFrame(-27.55, 151.95, 400.0)
    n = 3
    lat, lon, h = local.to_geodetic(np.column_stack([[0.0, 0.2, 0.45], [0.0, 0.05, -0.05], [10.0, 10.1, 9.9]]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians([1.0, -2.0, 0.5]), np.radians([0.5, 1.0, -1.5]),
                                           np.radians([5.0, 20.0, 40.0])))
    poses = FramePoses(np.array([7, 8, 9]), lat, lon, h, q, np.full(n, 400.0), cam)
    geom = FrameGeometry(poses, local)
    proj = project_pairs(geom, np.repeat(np.arange(n), len(TARGETS)), np.tile(TARGETS, (n, 1)),
                         LevelPlaneGround(geom))
    yy, xx = np.mgrid[0:180, 0:240]
    roll, pitch, yaw = euler_degrees(q)
    layer = QgsVectorLayer(f"Polygon?crs={UTM}", "frames", "memory")
    from birdseye.birdseye_qgis.qgis_io.layers import qgs_fields

    layer.dataProvider().addAttributes(qgs_fields(FRAME_FIELDS).toList())
    layer.updateFields()
    utm = ProjectedCRS(UTM)
    features = []
    for k in range(n):
        sel = (proj.frame_idx == k) & proj.in_view
        img = np.zeros((180, 240))
        for u, v in proj.uv[sel]:
            img = np.maximum(img, 0.9 * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * 3.0 ** 2)))
        path = folder / f"{poses.frame_id[k]}.png"
        cv2.imwrite(str(path), np.repeat(np.rint(255 * img).astype(np.uint8)[:, :, None], 3, axis=2))
        rec = {"frame_id": int(poses.frame_id[k]), "image": str(path), "time_s": float(k), "lat": lat[k],
               "lon": lon[k], "height_m": h[k], "qw": q[k, 0], "qx": q[k, 1], "qy": q[k, 2], "qz": q[k, 3],
               "roll_deg": roll[k], "pitch_deg": pitch[k], "yaw_deg": yaw[k], "ground_h_m": 400.0,
               "depth_m": float(geom.depth_below()[k]), "rtk_status": 3, "sync_offset_s": 0.0,
               "gsd_cm": float(geom.gsd_m()[k] * 100), "height_ref": "ellipsoidal", "ground_src": "altimeter",
               "camera": cam.to_json(), "flags": ""}
        f = QgsFeature(layer.fields())
        f.setAttributes([v.item() if isinstance(v, np.generic) else v for v in (rec[n] for n, _, _ in FRAME_FIELDS)])
        x, y = utm.from_geodetic(lat[k], lon[k])
        f.setGeometry(QgsGeometry.fromPolygonXY([[QgsPointXY(float(x) + dx, float(y) + dy)
                                                  for dx, dy in ((-1, -1), (1, -1), (1, 1), (-1, 1))]]))
        features.append(f)
    assert layer.dataProvider().addFeatures(features)[0]
    t_lat, t_lon, t_h = local.to_geodetic(TARGETS)
    tx, ty = utm.from_geodetic(t_lat, t_lon)
    return {"layer": layer, "folder": folder, "targets_xyz": np.column_stack([tx, ty, t_h]),
            "views": {int(poses.frame_id[k]): proj.uv[(proj.frame_idx == k) & proj.in_view] for k in range(n)}}


def test_detections_are_written_on_the_ground_in_the_layer_crs(birdseye_provider, scene, tmp_path):
    model = identity_model(tmp_path / "m.onnx")
    result = run({"FRAMES": scene["layer"], "MODEL": model, "OUTPUT": "TEMPORARY_OUTPUT",
                  "OUTPUT_HEATMAPS": str(tmp_path / "heat")})
    out = result["OUTPUT"]
    assert out.crs().authid() == UTM and out.wkbType() == 1001  # PointZ
    assert out.fields().names() == ["frame_id", "u", "v", "score", "model", "model_digest", "threshold", "ground",
                                    "dem_source", "dem_datum", "dem_n_m", "height_ref"]
    feats = list(out.getFeatures())
    expected = sum(len(v) for v in scene["views"].values())
    assert result["DETECTION_COUNT"] == len(feats) == expected >= 6
    assert result["FRAMES_PROCESSED"] == 3 and result["FRAMES_SKIPPED"] == 0
    digest = hashlib.sha256(open(model, "rb").read()).hexdigest()
    assert result["MODEL_DIGEST"] == digest and result["THRESHOLD_USED"] == pytest.approx(0.3)
    for f in feats:
        assert f["model"] == "m.onnx" and f["model_digest"] == digest and f["threshold"] == pytest.approx(0.3)
        assert f["ground"] == "level" and not f["dem_source"] and f["height_ref"] == "ellipsoidal"
        truth = scene["views"][f["frame_id"]]
        assert np.min(np.hypot(truth[:, 0] - f["u"], truth[:, 1] - f["v"])) < 0.05
        p = f.geometry().constGet()
        d = np.linalg.norm(scene["targets_xyz"] - [p.x(), p.y(), p.z()], axis=1)
        assert d.min() < 0.002  # m, through pose, lens and level ground (Z: ellipsoidal height)
    heat = cv2.imread(str(tmp_path / "heat" / "7.png"), cv2.IMREAD_UNCHANGED)
    assert heat.shape == (180, 240)


def test_threshold_edge_buffer_and_skipped_frames(birdseye_provider, scene, tmp_path):
    model = identity_model(tmp_path / "m.onnx", threshold=0.95)
    assert run({"FRAMES": scene["layer"], "MODEL": model, "OUTPUT": "TEMPORARY_OUTPUT"})["DETECTION_COUNT"] == 0
    all_ = run({"FRAMES": scene["layer"], "MODEL": model, "THRESHOLD": 0.3, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert all_["THRESHOLD_USED"] == pytest.approx(0.3) and all_["DETECTION_COUNT"] > 0
    margin = min(min(uv[:, 0].min(), uv[:, 1].min(), 239 - uv[:, 0].max(), 179 - uv[:, 1].max())
                 for uv in scene["views"].values())
    cut = run({"FRAMES": scene["layer"], "MODEL": model, "THRESHOLD": 0.3, "EDGE_BUFFER_PX": float(margin + 1),
               "OUTPUT": "TEMPORARY_OUTPUT"})
    assert cut["DETECTION_COUNT"] < all_["DETECTION_COUNT"]
    # A frame whose image is gone is skipped with a warning; the others are processed.
    layer = scene["layer"].clone()
    layer.startEditing()
    first = next(layer.getFeatures())
    layer.changeAttributeValue(first.id(), layer.fields().indexOf("image"), str(tmp_path / "gone.png"))
    layer.commitChanges()
    result = run({"FRAMES": layer, "MODEL": model, "THRESHOLD": 0.3, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["FRAMES_SKIPPED"] == 1 and result["FRAMES_PROCESSED"] == 2


def test_a_model_with_bad_metadata_is_refused_with_every_problem(birdseye_provider, scene, tmp_path):
    bad = onnx.load(identity_model(tmp_path / "bad.onnx"))
    props = {p.key: p for p in bad.metadata_props}
    props["output_kind"].value = json.dumps("scores")
    bad.metadata_props.remove(props["resolution"])
    onnx.save(bad, str(tmp_path / "bad.onnx"))
    with pytest.raises(QgsProcessingException) as err:
        run({"FRAMES": scene["layer"], "MODEL": str(tmp_path / "bad.onnx"), "OUTPUT": "TEMPORARY_OUTPUT"})
    assert "missing key(s): resolution" in str(err.value) and "'output_kind' must be one of" in str(err.value)


def test_the_bundled_model_is_the_default(birdseye_provider, scene):
    from birdseye.processing.algorithms.detect import DEFAULT_MODEL

    result = run({"FRAMES": scene["layer"], "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["MODEL_DIGEST"] == hashlib.sha256(DEFAULT_MODEL.read_bytes()).hexdigest()
    assert result["FRAMES_PROCESSED"] == 3
    meta = json.loads(dict((p.key, p.value) for p in onnx.load(str(DEFAULT_MODEL)).metadata_props)["default_threshold"])
    assert result["THRESHOLD_USED"] == pytest.approx(meta)


def test_the_bundled_model_finds_simulated_burrows_end_to_end(birdseye_provider, tmp_path):
    """Simulate → import → detect with the defaults: ≥ 80 % of the in-view burrows get a detection
    within 0.2 m. Small frames flown low keep the demo's ground resolution (≈ 0.23 cm/px) cheaply."""
    import csv

    import processing

    from birdseye.birdseye_qgis.core.field.frame_records import poses_from_records
    from birdseye.birdseye_qgis.core.field.geotags import Geotags
    from birdseye.birdseye_qgis.core.labels.training_set import project_labels
    from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign
    from birdseye.birdseye_qgis.qgis_io.layers import pyproj_crs, read_frame_layer

    folder = tmp_path / "campaign"
    simulate_campaign(CampaignConfig(seed=404, n_targets=6, field_width_m=4.0, field_length_m=3.0, altitude_m=2.5,
                                     image_width=480, image_height=300, n_missed=0, n_spurious=0), folder)
    frames = processing.run("birdseye:importflightlog", {
        "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
        "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    result = run({"FRAMES": frames, "OUTPUT": "TEMPORARY_OUTPUT"})
    rows = list(csv.DictReader(open(folder / "truth" / "targets.csv", encoding="utf-8")))
    truth = Geotags([int(r["id"]) for r in rows], [float(r["lat"]) for r in rows], [float(r["lon"]) for r in rows],
                    [float(r["h_ground"]) for r in rows], ["burrow"] * len(rows))
    (poses, _), = poses_from_records(read_frame_layer(frames))
    in_view = np.zeros(len(truth), bool)
    for fl in project_labels(poses, truth):
        in_view[fl.geotag_index[~fl.edge]] = True
    tx, ty = ProjectedCRS(pyproj_crs(frames.crs())).from_geodetic(truth.lat, truth.lon)
    points = np.array([[f.geometry().constGet().x(), f.geometry().constGet().y(), f.geometry().constGet().z()]
                       for f in result["OUTPUT"].getFeatures()])
    assert len(points) and np.all(np.abs(points[:, 2] - 400.0) < 0.5)  # on the altimeter's ground (ellipsoidal)
    d = np.hypot(tx[:, None] - points[None, :, 0], ty[:, None] - points[None, :, 1]).min(axis=1)
    assert in_view.sum() >= 4
    assert (d[in_view] <= 0.2).mean() >= 0.8

def without_ground_height(layer):
    """The frame layer with every frame's ground height gone, as a camera solution with no tie points
    in view writes it."""
    out = layer.clone()
    out.startEditing()
    for f in out.getFeatures():
        out.changeAttributeValue(f.id(), out.fields().indexOf("ground_h_m"), None)
        out.changeAttributeValue(f.id(), out.fields().indexOf("flags"), "no_ground_height")
    assert out.commitChanges()
    return out


def flat_dem_layer(scene_layer, height_m, path):
    from test_writelabels import write_geotiff

    from birdseye.birdseye_qgis.core.sim.terrain import synthetic_terrain

    first = next(scene_layer.getFeatures())
    dem = synthetic_terrain(first["lat"], first["lon"], kind="plane", base_height_m=height_m, size_m=40.0,
                            cell_m=0.5, crs=UTM, vertical_datum="ellipsoidal")
    return QgsRasterLayer(write_geotiff(dem, path), path.stem)


def test_frames_without_a_ground_height_are_placed_on_a_dem_or_named_as_skipped(birdseye_provider, scene, tmp_path,
                                                                                monkeypatch):
    import processing

    from birdseye.birdseye_qgis.core.detect import detector

    model = identity_model(tmp_path / "m.onnx")
    frames = without_ground_height(scene["layer"])
    level_gsd = {f["frame_id"]: f["gsd_cm"] for f in scene["layer"].getFeatures()}  # cm/px at ground 400 m

    # Without a DEM nothing can be placed: each frame is named in a warning, no traceback.
    feedback = Recorder()
    result = processing.run("birdseye:detect", {"FRAMES": frames, "MODEL": model, "OUTPUT": "TEMPORARY_OUTPUT"},
                            feedback=feedback)
    assert result["FRAMES_SKIPPED"] == 3 and result["FRAMES_PROCESSED"] == 0 and result["DETECTION_COUNT"] == 0
    for fid in level_gsd:
        assert any(w.startswith(f"Frame {fid}: the frame has no ground height") and "give a DEM" in w
                   for w in feedback.warnings)

    # With a DEM at the true ground every frame is detected at the level run's places, resampled at the
    # DEM's ground resolution (camera to DEM under the image centre).
    seen = []
    real_model_size = detector.model_size

    def model_size(width, height, gsd_cm, resolution_cm):
        seen.append(gsd_cm)
        return real_model_size(width, height, gsd_cm, resolution_cm)

    monkeypatch.setattr(detector, "model_size", model_size)
    result = run({"FRAMES": frames, "MODEL": model, "DEM": flat_dem_layer(frames, 400.0, tmp_path / "at.tif"),
                  "DEM_VERTICAL_DATUM": 0, "OUTPUT": "TEMPORARY_OUTPUT"})
    assert result["FRAMES_PROCESSED"] == 3 and result["FRAMES_SKIPPED"] == 0
    assert seen == pytest.approx(list(level_gsd.values()), rel=1e-4)
    feats = list(result["OUTPUT"].getFeatures())
    assert len(feats) == sum(len(v) for v in scene["views"].values())
    for f in feats:
        p = f.geometry().constGet()
        assert np.linalg.norm(scene["targets_xyz"] - [p.x(), p.y(), p.z()], axis=1).min() < 0.002

    # A DEM 10 m lower doubles the ground resolution (10 m → 20 m below the camera): the coarse-frame
    # warning names the frames, which only a GSD taken from the DEM can give them.
    seen.clear()
    feedback = Recorder()
    processing.run("birdseye:detect", {"FRAMES": frames, "MODEL": model, "DEM_VERTICAL_DATUM": 0,
                                       "DEM": flat_dem_layer(frames, 390.0, tmp_path / "low.tif"),
                                       "OUTPUT": "TEMPORARY_OUTPUT"}, feedback=feedback)
    depth = [g / 100.0 * 1000.0 for g in level_gsd.values()]  # m, f = 1000 px
    assert seen == pytest.approx([(d + 10.0) / 1000.0 * 100.0 for d in depth], rel=1e-4)
    assert any("coarser than 1.5× the model's resolution" in w and "7, 8, 9" in w for w in feedback.warnings)


def geotag_layer(targets_xyz):
    from qgis.core import QgsField, QgsPoint
    from qgis.PyQt.QtCore import QVariant

    layer = QgsVectorLayer(f"PointZ?crs={UTM}", "geotags", "memory")
    layer.dataProvider().addAttributes([QgsField("id", QVariant.Int), QgsField("label", QVariant.String)])
    layer.updateFields()
    feats = []
    for k, (x, y, z) in enumerate(targets_xyz):
        f = QgsFeature(layer.fields())
        f.setAttributes([k + 1, "burrow"])
        f.setGeometry(QgsGeometry(QgsPoint(float(x), float(y), float(z))))
        feats.append(f)
    assert layer.dataProvider().addFeatures(feats)[0]
    return layer


def test_the_algorithms_after_detect_name_frames_without_a_ground_height(birdseye_provider, scene, tmp_path):
    """Frames without a ground height fed to Write labels warn, naming the frames, instead of failing with
    a traceback; Cluster detections and Evaluate detections score detections Detect placed on a DEM on
    that DEM, every frame included, and without it say which DEM they need."""
    import processing

    frames = without_ground_height(scene["layer"])
    geotags = geotag_layer(scene["targets_xyz"])
    dem = flat_dem_layer(frames, 400.0, tmp_path / "at.tif")
    detections = run({"FRAMES": frames, "MODEL": identity_model(tmp_path / "m.onnx"), "DEM": dem,
                      "DEM_VERTICAL_DATUM": 0, "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    on_dem = {"DEM": dem, "DEM_VERTICAL_DATUM": 0}
    # Each algorithm runs to the end (a raw ValueError would fail here) and warns (None: does not warn).
    calls = {
        "writelabels": ({"GEOTAGS": geotags, "FRAMES": frames, "SIGMA_PX": 4.0, "OUTPUT_FOLDER": str(tmp_path / "l"),
                         "OUTPUT_FRAMES": "TEMPORARY_OUTPUT", "OUTPUT_GEOTAGS": "TEMPORARY_OUTPUT"},
                        "3 frame(s) have no ground height (no usable altimeter reading, flag no_ground_height) and "
                        "get no labels; first: 7, 8, 9"),
        "clusterdetections": ({"DETECTIONS": detections, "GEOTAGS": geotags, "FRAMES": frames, "MIN_SAMPLES": 1,
                               "OUTPUT": "TEMPORARY_OUTPUT"}, None),
        "evaluatedetections": ({"DETECTIONS": [detections], "GEOTAGS": geotags, "FRAMES": [frames],
                                "OUTPUT_JSON": str(tmp_path / "s.json"), "OUTPUT_REPORT": str(tmp_path / "r.html")},
                               None),
    }
    for alg, (params, warning) in calls.items():
        feedback = Recorder()
        if warning is None:
            with pytest.raises(QgsProcessingException, match=r"placed on the DEM .*at\.tif.*give that DEM \(DEM"):
                processing.run(f"birdseye:{alg}", params, feedback=feedback)
            processing.run(f"birdseye:{alg}", {**params, **on_dem}, feedback=feedback)
            assert not any("not counted as processed" in w for w in feedback.warnings), (alg, feedback.warnings)
        else:
            processing.run(f"birdseye:{alg}", params, feedback=feedback)
            assert any(warning in w for w in feedback.warnings), (alg, feedback.warnings)

"""The training recipe end to end on a tiny labelled set: train a few steps, export, detect.

torch is a training extra (requirements-train.txt), yet required here: the unit suite runs only in the
host's .venv, where scripts/setup.sh (run by ``make test``) installs requirements-train.txt; the QGIS
chroots run only tests/qgis, gui and e2e. A missing torch is a broken install and fails these tests.
"""
import importlib.util
import json
import sys
from pathlib import Path

import cv2
import numpy as np
import onnxruntime
import pytest
import torch

from birdseye.birdseye_qgis.core.detect.detector import DetectRequest, HeatmapModel, detect_frames
from birdseye.birdseye_qgis.core.detect.model_metadata import read_onnx_metadata
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.labels.training_set import LabelRequest, project_labels, write_label_set

RECIPE = Path(__file__).resolve().parents[3] / "training" / "train_heatmap.py"
NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


@pytest.fixture(scope="module")
def recipe():
    spec = importlib.util.spec_from_file_location("train_heatmap", RECIPE)
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up while the recipe loads
    spec.loader.exec_module(module)
    torch.set_num_threads(1)
    return module


@pytest.fixture(scope="module")
def labelled(tmp_path_factory):
    """Four 320×240 frames at 0.25 cm/px of a textured field with dark round targets, labelled by the
    label core (rasters + 128 px tiles)."""
    root = tmp_path_factory.mktemp("campaign")
    t = np.eye(4)
    t[:3, :3] = NADIR
    cam = CameraModel(320, 240, 4000.0, 4000.0, 159.5, 119.5, (0, 0, 0, 0, 0), t)  # 10 m → 0.25 cm/px
    local = LocalFrame(-27.55, 151.95, 400.0)
    n = 4
    lat, lon, h = local.to_geodetic(np.column_stack([np.linspace(0, 0.3, n), np.zeros(n), np.full(n, 10.0)]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(n), np.zeros(n), np.zeros(n)))
    poses = FramePoses(np.arange(1, n + 1), lat, lon, h, q, np.full(n, 400.0), cam)
    rng = np.random.default_rng(0)
    targets = np.column_stack([rng.uniform(-0.3, 0.6, 6), rng.uniform(-0.25, 0.25, 6), np.zeros(6)])
    g_lat, g_lon, g_h = local.to_geodetic(targets)
    geotags = Geotags(np.arange(1, 7), g_lat, g_lon, g_h, ["burrow"] * 6)
    labels = project_labels(poses, geotags, local=local)
    images = []
    yy, xx = np.mgrid[0:240, 0:320]
    for k, fl in enumerate(labels):
        img = rng.normal(120, 12, (240, 320, 1)) + np.array([0.0, 10.0, 25.0])
        for u, v in fl.uv:
            img *= 1 - 0.7 * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * 8.0 ** 2))[:, :, None]
        path = root / f"{k + 1}.png"
        cv2.imwrite(str(path), np.clip(img, 0, 255).astype(np.uint8))
        images.append(str(path))
    out = root / "labels"
    write_label_set(poses, images, geotags, labels, out, LabelRequest(sigma_px=8.0, tile_size=128, seed=1))
    gsd_cm = FrameGeometry(poses, local).gsd_m() * 100
    return {"poses": poses, "images": images, "labels": labels, "local": local, "folder": out,
            "gsd_of": {str(f): float(g) for f, g in zip(poses.frame_id, gsd_cm)}}


def test_tiles_are_resampled_to_the_model_resolution(recipe, labelled):
    tiles = recipe.load_tiles([(labelled["folder"], labelled["gsd_of"])], resolution_cm=0.5)
    summary = json.loads((labelled["folder"] / "summary.json").read_text())
    assert len(tiles) == summary["tiles"]["positive"] + summary["tiles"]["negative"]
    # 128 px tiles at 0.25 cm/px are 64 px at 0.5 cm/px; labels stay in [0, 1].
    assert all(im.shape == (64, 64, 3) for im in tiles.images)
    # Halving by area: each resampled label pixel is the mean of a 2×2 block of the raster / 255.
    names = sorted(p.name for p in (labelled["folder"] / "tiles" / "labels").glob("*.png"))
    for name, lab in zip(names, tiles.labels):
        raw = cv2.imread(str(labelled["folder"] / "tiles" / "labels" / name), cv2.IMREAD_UNCHANGED) / 255.0
        np.testing.assert_allclose(lab, raw.reshape(64, 2, 64, 2).mean(axis=(1, 3)), atol=1e-5)
    assert tiles.positive.sum() >= summary["tiles"]["positive"] > 0


def test_train_export_and_detect(recipe, labelled, tmp_path):
    tiles = recipe.load_tiles([(labelled["folder"], labelled["gsd_of"])], resolution_cm=0.5)
    meta = recipe.make_metadata(tiles, 0.5, 0.3, 4.0, "unit test")
    net = recipe.build_network(width=4)
    enc0 = [p.detach().clone() for p in net.encoder.parameters()]
    history = recipe.train_network(net, tiles, meta, minutes=0, steps=10, batch=4, crop=48, log=lambda m: None)
    assert history["frozen_steps"] == 2 and history["finetune_steps"] == 8
    assert any(not torch.equal(a, b) for a, b in zip(enc0, net.encoder.parameters()))  # fine-tuned at the end

    path = recipe.export_onnx(net, meta, tmp_path / "tiny.onnx")
    assert read_onnx_metadata(path) == meta
    # The exported graph computes the network's probabilities, on tiles of the model's size (fixed: Deepness).
    x = np.random.default_rng(2).normal(size=(2, 3, meta.tile_size, meta.tile_size)).astype(np.float32)
    with torch.no_grad():
        expected = torch.sigmoid(net(torch.from_numpy(x))).numpy()
    got = onnxruntime.InferenceSession(str(path), providers=["CPUExecutionProvider"]).run(None, {"image": x})[0]
    np.testing.assert_allclose(got, expected, atol=1e-5)

    model = HeatmapModel(path)
    found = list(detect_frames(model, labelled["poses"], labelled["images"],
                               DetectRequest(heatmap_dir=str(tmp_path / "heat")), local=labelled["local"]))
    assert [f.skipped for f in found] == [None] * 4
    heat = cv2.imread(found[0].heatmap_path, cv2.IMREAD_UNCHANGED)
    assert heat.shape == (240, 320)


def test_frozen_stage_leaves_encoder_weights_alone(recipe, labelled):
    tiles = recipe.load_tiles([(labelled["folder"], labelled["gsd_of"])], resolution_cm=0.5)
    meta = recipe.make_metadata(tiles, 0.5, 0.3, None, "unit test")
    net = recipe.build_network(width=4)
    enc0 = {n: p.detach().clone() for n, p in net.encoder.named_parameters()}
    dec0 = [p.detach().clone() for p in net.decoder_parameters()]
    recipe.train_network(net, tiles, meta, minutes=0, steps=4, frozen_fraction=1.0, batch=2, crop=48,
                         log=lambda m: None)
    assert all(torch.equal(enc0[n], p) for n, p in net.encoder.named_parameters())
    assert any(not torch.equal(a, b) for a, b in zip(dec0, net.decoder_parameters()))


def test_train_command_on_writelabels_output_and_a_frame_geopackage(recipe, labelled, tmp_path):
    import sqlite3

    gpkg = tmp_path / "frames.gpkg"
    con = sqlite3.connect(gpkg)
    con.execute("CREATE TABLE gpkg_contents (table_name TEXT, data_type TEXT)")
    con.execute("INSERT INTO gpkg_contents VALUES ('frames', 'features')")
    con.execute("CREATE TABLE frames (fid INTEGER PRIMARY KEY, frame_id INTEGER, gsd_cm REAL)")
    con.executemany("INSERT INTO frames (frame_id, gsd_cm) VALUES (?, ?)",
                    [(int(f), g) for f, g in labelled["gsd_of"].items()])
    con.commit()
    con.close()
    assert recipe.frame_gsd_from_gpkg(gpkg) == pytest.approx(labelled["gsd_of"])
    assert recipe.frame_records_from_gpkg(gpkg) is None  # GSDs alone: no poses to validate on the ground with
    out = tmp_path / "mine.onnx"
    args = ["train", "--labels", str(labelled["folder"]), "--frames", str(gpkg), "--resolution-cm", "0.5",
            "--minutes", "0.01", "--width", "4", "--threads", "1", "--threshold", "0.4", "--out", str(out)]
    recipe.main(args)
    meta = read_onnx_metadata(out)
    assert meta.resolution_cm == 0.5 and meta.default_threshold == 0.4
    assert meta.label_sigma_px == pytest.approx(8.0 * np.median(list(labelled["gsd_of"].values())) / 0.5, abs=1e-3)
    assert out.with_suffix(".pt").is_file() and out.with_suffix(".training.json").is_file()
    # A second model starts from the first one's weights.
    recipe.main(args[:-1] + [str(tmp_path / "again.onnx"), "--init", str(out.with_suffix(".pt"))])
    assert HeatmapModel(tmp_path / "again.onnx").metadata.default_threshold == 0.4


def test_frame_records_from_a_geopackage_join_a_split_camera(recipe, tmp_path):
    import sqlite3

    gpkg = tmp_path / "frames.gpkg"
    con = sqlite3.connect(gpkg)
    con.execute("CREATE TABLE gpkg_contents (table_name TEXT, data_type TEXT)")
    con.execute("INSERT INTO gpkg_contents VALUES ('frames', 'features')")
    con.execute("CREATE TABLE frames (fid INTEGER PRIMARY KEY, frame_id INTEGER, lat REAL, gsd_cm REAL, "
                "camera TEXT, camera_2 TEXT, camera_10 TEXT, other TEXT)")
    con.execute("INSERT INTO frames (frame_id, lat, gsd_cm, camera, camera_2, camera_10, other) "
                "VALUES (7, -27.5, 0.23, '{\"a\": ', '1', '}', 'x')")
    con.commit()
    con.close()
    (record,) = recipe.frame_records_from_gpkg(gpkg)
    assert record == {"frame_id": 7, "lat": -27.5, "gsd_cm": 0.23, "camera": '{"a": 1}'}


def test_threshold_figures_are_runs_at_each_threshold_not_a_score_filter(recipe, tmp_path):
    """The recipe chooses the bundled model's threshold from figures at every threshold of its grid:
    each must count what Detect finds when run at that threshold alone (peaks re-extracted, a blob that
    splits above a higher threshold splits), on a small simulated campaign with the bundled model."""
    from birdseye.birdseye_qgis.__about__ import BUNDLED_MODEL
    from birdseye.birdseye_qgis.core.detect.detector import DetectRequest, HeatmapModel, detect_frames
    from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

    simulate_campaign(CampaignConfig(seed=3, n_targets=6, field_width_m=4.0, field_length_m=3.0, image_width=480,
                                     image_height=300), tmp_path / "c")
    campaign = recipe.load_campaign(tmp_path / "c")
    thresholds = (0.05, 0.3)
    figures = recipe.evaluate(BUNDLED_MODEL, [campaign], thresholds)
    model = HeatmapModel(BUNDLED_MODEL)
    for t in thresholds:
        alone = sum(len(f) for f in detect_frames(model, campaign.poses, campaign.images, DetectRequest(threshold=t))
                    if f.skipped is None)
        assert figures[t]["detections"] == alone > 0
    assert figures[thresholds[0]]["frames"] == figures[thresholds[1]]["frames"] == len(campaign.images)

"""Projected labels: rasters, the sparse PNG encoder, the written files and their summary."""
import csv
import io
import json

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.labels.sparse_png import encode_gray_png
from birdseye.birdseye_qgis.core.labels.training_set import (
    LabelRequest,
    project_labels,
    soft_label_raster,
    tile_origins,
    write_label_set,
)

NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def test_soft_label_hump_values_and_cut_at_three_sigma():
    r = soft_label_raster(200, 100, np.array([[50.0, 40.0]]), sigma_px=5.0)
    assert r[40, 50] == 255
    assert r[40, 55] == round(255 * np.exp(-0.5))          # one σ to the right
    assert r[40, 65] == round(255 * np.exp(-4.5))          # exactly 3σ: still drawn
    assert r[40, 66] == 0 and r[40, 34] == 0               # beyond 3σ
    assert r.sum() == r[25:56, 35:66].sum()


def test_overlapping_humps_combine_by_max_and_clip_at_edges():
    a, b = np.array([[30.2, 20.7]]), np.array([[38.9, 24.1]])
    both = soft_label_raster(64, 48, np.vstack([a, b]), 4.0)
    np.testing.assert_array_equal(both, np.maximum(soft_label_raster(64, 48, a, 4.0),
                                                   soft_label_raster(64, 48, b, 4.0)))
    corner = soft_label_raster(64, 48, np.array([[-2.0, 47.4]]), 4.0)
    assert corner[47, 0] > 0 and corner.shape == (48, 64)
    assert soft_label_raster(64, 48, np.array([[-40.0, 10.0]]), 4.0).sum() == 0


def _decode(png: bytes) -> np.ndarray:
    from PIL import Image

    return np.asarray(Image.open(io.BytesIO(png)))


@settings(max_examples=60, deadline=None)
@given(h=st.integers(1, 90), w=st.integers(1, 130), n=st.integers(0, 5), seed=st.integers(0, 2 ** 16))
def test_sparse_png_decodes_to_the_same_raster(h, w, n, seed):
    rng = np.random.default_rng(seed)
    raster = soft_label_raster(w, h, np.column_stack([rng.uniform(0, w, n), rng.uniform(0, h, n)]), 3.0)
    if seed % 5 == 0:
        raster = rng.integers(0, 256, (h, w), dtype=np.uint8)  # dense rows as well
    np.testing.assert_array_equal(_decode(encode_gray_png(raster)), raster)


def test_sparse_png_is_read_by_opencv_too():
    import cv2
    raster = soft_label_raster(1920, 1200, np.array([[10.0, 10.0], [1900.0, 1190.0], [960.0, 600.0]]), 10.0)
    png = encode_gray_png(raster)
    back = cv2.imdecode(np.frombuffer(png, np.uint8), cv2.IMREAD_UNCHANGED)
    np.testing.assert_array_equal(back, raster)
    assert len(png) < 60_000


def test_tile_origins_cover_the_image_with_the_last_tile_flush():
    assert tile_origins(1200, 224) == [0, 224, 448, 672, 896, 976]
    assert tile_origins(448, 224) == [0, 224]
    assert tile_origins(100, 224) == [0]


def small_campaign(edge_geotag=False):
    t = np.eye(4)
    t[:3, :3] = NADIR
    cam = CameraModel(640, 400, 1400.0, 1400.0, 319.5, 199.5, (-0.05, 0.02, 0.0, 0.0, 0.0), t)
    local = LocalFrame(-27.55, 151.95, 400.0)
    enu = np.array([[0.0, 0.0, 10.0], [2.0, 0.0, 10.0], [30.0, 30.0, 10.0]])
    lat, lon, h = local.to_geodetic(enu)
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(3), np.zeros(3), np.zeros(3)))
    poses = FramePoses([101, 102, 103], lat, lon, h, q, np.full(3, 400.0), cam)
    # geotags: one seen by frames 101 and 102, one only by 101, one never; antenna heights vary.
    g = np.array([[0.3, 0.2, 1.5], [-1.0, -0.5, 0.0], [100.0, 100.0, 0.0]])
    if edge_geotag:
        g = np.vstack([g, [-2.22, 0.0, 0.0]])  # ~8 px inside frame 101's left edge
    g_lat, g_lon, g_h = local.to_geodetic(g + [0, 0, 400.0])
    geotags = Geotags(np.arange(1, len(g) + 1), g_lat, g_lon, g_h,
                      ["burrow", "gap", "burrow"] + ["burrow"] * (len(g) - 3))
    return poses, geotags, local


def grey_frames(poses, folder) -> list[str]:
    """One uniform grey 640 × 400 image per frame of ``poses`` in ``folder``, named by frame id."""
    import cv2

    images = []
    for fid in poses.frame_id:
        path = folder / f"{fid}.png"
        cv2.imwrite(str(path), np.full((400, 640, 3), 90, np.uint8))
        images.append(str(path))
    return images


def test_project_labels_finds_every_frame_that_sees_each_geotag():
    poses, geotags, local = small_campaign()
    labels = project_labels(poses, geotags, local=local)
    assert [fl.geotag_index.tolist() for fl in labels] == [[0, 1], [0], []]
    # Nadir, heading north: 0.3 m east, 0.2 m north of frame 101 at 10 m → right of and above centre.
    u, v = labels[0].uv[0]
    assert u > 319.5 + 35 and v < 199.5 - 20


def test_edge_buffer_reports_edge_labels_and_writes_no_positive(tmp_path):
    poses, geotags, local = small_campaign(edge_geotag=True)
    labels = project_labels(poses, geotags, edge_buffer_px=20, local=local)
    assert labels[0].edge.tolist() == [False, False, True]
    images = [f"/frames/{i}.jpg" for i in poses.frame_id]
    result = write_label_set(poses, images, geotags, labels, tmp_path,
                             LabelRequest(sigma_px=3.0, edge_buffer_px=20, coco=True))
    rows = list(csv.DictReader(open(tmp_path / "labels.csv")))
    assert [(r["frame_id"], r["geotag_id"], r["label"]) for r in rows] == [
        ("101", "1", "burrow"), ("101", "2", "gap"), ("102", "1", "burrow")]
    assert result.summary["n_edge"] == 1 and result.summary["n_labels"] == 3
    assert result.summary["geotags_never_in_view"] == [3]
    assert result.summary["geotags_only_at_edge"] == [4]
    assert result.frames_per_geotag.tolist() == [2, 1, 0, 0]
    lines = (tmp_path / "labels.txt").read_text().splitlines()
    assert lines[0].split(" ")[:2] == ["0", "/frames/101.jpg"] and len(lines) == 2
    u, v, cls = lines[0].split(" ")[2].split(",")
    assert int(cls) == result.summary["classes"].index("burrow")
    assert float(u) == pytest.approx(float(rows[0]["u"]), abs=0.01)
    raster = _decode((tmp_path / "rasters" / "101.png").read_bytes())
    assert raster.shape == (400, 640)
    u0, v0 = float(rows[0]["u"]), float(rows[0]["v"])
    r2 = (round(u0) - u0) ** 2 + (round(v0) - v0) ** 2
    assert raster[round(v0), round(u0)] == round(255 * np.exp(-r2 / 18.0))
    assert not (tmp_path / "rasters" / "103.png").exists() or _decode(
        (tmp_path / "rasters" / "103.png").read_bytes()).sum() == 0
    coco = json.loads((tmp_path / "coco_keypoints.json").read_text())
    assert len(coco["images"]) == 3 and len(coco["annotations"]) == 3
    assert coco["annotations"][0]["keypoints"][2] == 2
    assert json.loads((tmp_path / "summary.json").read_text())["n_frames_with_labels"] == 2


def test_tiles_keep_every_positive_and_a_seeded_share_of_negatives(tmp_path):
    import cv2
    poses, geotags, local = small_campaign()
    images = grey_frames(poses, tmp_path)
    labels = project_labels(poses, geotags, local=local)
    req = LabelRequest(sigma_px=3.0, write_rasters=False, tile_size=128, negative_ratio=1.0, seed=5)
    r1 = write_label_set(poses, images, geotags, labels, tmp_path / "a", req)
    write_label_set(poses, images, geotags, labels, tmp_path / "b", req)
    tiles = r1.summary["tiles"]
    xs, ys = tile_origins(640, 128), tile_origins(400, 128)
    n_tiles = len(xs) * len(ys)
    expected_pos, expected_neg = 0, 0
    for fl in labels:
        pos = sum(any(x0 - 0.5 <= u < x0 + 127.5 and y0 - 0.5 <= v < y0 + 127.5 for u, v in fl.uv)
                  for x0 in xs for y0 in ys)
        expected_pos += pos
        expected_neg += min(n_tiles - pos, max(1, pos))  # ratio 1: one negative per positive, at least one
    assert tiles["positive"] == expected_pos >= 3
    assert tiles["negative"] == expected_neg
    names = sorted(p.name for p in (tmp_path / "a" / "tiles" / "images").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "b" / "tiles" / "images").iterdir())
    assert names == sorted(p.name for p in (tmp_path / "a" / "tiles" / "labels").iterdir())
    assert cv2.imread(str(tmp_path / "a" / "tiles" / "images" / names[0])).shape == (128, 128, 3)


def test_frames_without_a_ground_height_get_no_labels():
    poses, geotags, local = small_campaign()
    poses.ground_height[0] = np.nan  # frame 101 had no usable altimeter reading
    labels = project_labels(poses, geotags, local=local)
    assert [fl.geotag_index.tolist() for fl in labels] == [[], [0], []]


def test_camera_solution_frames_project_geotags_at_their_surveyed_heights():
    """With ``geotag_heights`` a geotag 1.5 m above the ground (a marker on a post) is projected where it
    is, closed form for a nadir frame: u − cx = f·east/depth, v − cy = −f·north/depth with depth = 10 − 1.5;
    the wrong ground height the frame carries plays no part."""
    poses, geotags, local = small_campaign()
    geotags.height -= 400.0  # small_campaign's heights are relative to the 400 m site: make them absolute
    poses.ground_height[:] = 395.0  # 5 m off: must not matter
    no_distortion = FramePoses(poses.frame_id, poses.lat, poses.lon, poses.height, poses.quat, poses.ground_height,
                               CameraModel(640, 400, 1400.0, 1400.0, 319.5, 199.5, T_cam_imu=poses.camera.T_cam_imu))
    labels = project_labels(no_distortion, geotags, local=local, geotag_heights=True)
    uv = labels[0].uv[labels[0].geotag_index.tolist().index(0)]
    np.testing.assert_allclose(uv, [319.5 + 1400 * 0.3 / 8.5, 199.5 - 1400 * 0.2 / 8.5], atol=0.02)


def test_geotags_without_height_go_onto_the_flight_ground_of_the_surveyed_ones():
    """A geotag without height on a frame without ground height lands on the level plane at the median
    surveyed height (400 m here, from the other geotags): depth 10 m."""
    poses, geotags, local = small_campaign()
    geotags.height -= 400.0
    poses.ground_height[:] = np.nan
    geotags.height[1] = np.nan  # the 'gap' at (−1, −0.5) has no height
    geotags.height[0] = geotags.height[2]  # both surveyed ones at ground level: median 400 m
    no_distortion = FramePoses(poses.frame_id, poses.lat, poses.lon, poses.height, poses.quat, poses.ground_height,
                               CameraModel(640, 400, 1400.0, 1400.0, 319.5, 199.5, T_cam_imu=poses.camera.T_cam_imu))
    labels = project_labels(no_distortion, geotags, local=local, geotag_heights=True)
    k = labels[0].geotag_index.tolist().index(1)
    np.testing.assert_allclose(labels[0].uv[k], [319.5 - 1400 * 1.0 / 10, 199.5 + 1400 * 0.5 / 10], atol=0.05)


def test_review_targets_are_labelled_with_their_provenance_and_hard_negatives_fill_the_negative_sample(tmp_path):
    """A confirmed cluster nobody surveyed is a label like a geotag (provenance review); a rejected one
    (hard negative) puts its tile first in the negative sample, label all zero."""
    import cv2
    poses, survey, local = small_campaign()
    # Frame 101 (centre 0, 0) alone sees the review target; frame 102 (centre 2, 0) alone the hard negative.
    r_lat, r_lon, r_h = local.to_geodetic(np.array([[-1.5, 0.5, 400.0], [3.5, -1.0, 400.0]]))
    targets = survey + Geotags(["det#7"], r_lat[:1], r_lon[:1], [np.nan], ["burrow"], ["review"])
    hard = Geotags(["det#9"], r_lat[1:], r_lon[1:], [np.nan], ["hard_negative"])
    images = grey_frames(poses, tmp_path)
    labels = project_labels(poses, targets, local=local)
    hard_labels = project_labels(poses, hard, local=local)
    assert [fl.geotag_index.tolist() for fl in hard_labels] == [[], [0], []]
    for seed in (0, 1, 2):
        out = tmp_path / f"seed{seed}"
        result = write_label_set(poses, images, targets, labels, out,
                                 LabelRequest(sigma_px=3.0, write_rasters=False, tile_size=128, seed=seed),
                                 hard_negatives=hard, hard_negative_labels=hard_labels)
        rows = list(csv.DictReader(open(out / "labels.csv")))
        assert [(r["frame_id"], r["geotag_id"], r["provenance"]) for r in rows] == [
            ("101", "1", "survey"), ("101", "2", "survey"), ("101", "det#7", "review"), ("102", "1", "survey")]
        s = result.summary
        assert s["provenance"] == {"survey": {"n_targets": 3, "n_in_view": 2, "n_labels": 3},
                                   "review": {"n_targets": 1, "n_in_view": 1, "n_labels": 1}}
        assert s["hard_negatives"] == {"n_clusters": 1, "n_in_view": 1, "n_frames": 1}
        assert json.loads((out / "summary.json").read_text())["tiles"]["hard_negative"] == 1
        # Frame 102 has one positive tile, so ratio 1 keeps one negative: whatever the seed, the hard one.
        u, v = hard_labels[1].uv[0]
        tiles = {p.name: cv2.imread(str(p), cv2.IMREAD_UNCHANGED) for p in (out / "tiles" / "labels").glob("102_*")}
        negative = [name for name, label in tiles.items() if label.max() == 0]
        assert len(tiles) == 2 and len(negative) == 1
        y0, x0 = (int(k) for k in negative[0][:-4].split("_")[1:])
        assert x0 - 0.5 <= u < x0 + 127.5 and y0 - 0.5 <= v < y0 + 127.5

"""The detector core with tiny ONNX models whose heatmap is known exactly.

The models are fixed convolutions built with the ``onnx`` helpers: the heatmap is the image itself
(1×1 kernel, mean of the channels / 255) or a known 5×5 filter of it, so tiling, stitching, peaks,
resampling and back-projection can each be checked against an independent derivation.
"""
import hashlib

import cv2
import numpy as np
import onnx
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from onnx import TensorProto, helper

from birdseye.birdseye_qgis.core.detect.detector import (
    DetectRequest,
    HeatmapModel,
    cut_tiles,
    detect_frames,
    find_peaks,
    frame_heatmap,
    model_size,
    normalise,
    read_bgr,
    read_reduction,
    stitch,
    tile_spans,
    to_frame_pixels,
)
from birdseye.birdseye_qgis.core.detect.model_metadata import ModelMetadata, ModelMetadataError, embed_metadata
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import pixel_to_ground, project_pairs
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def conv_model(path, kernel=None, tile=32, overlap_pct=25.0, output_kind="probability", threshold=0.3,
               resolution_cm=1.0, fixed_size=False, **meta_changes):
    """An ONNX model: one convolution of the channel mean (pixel/255) with ``kernel`` (default 1×1)."""
    kernel = np.ones((1, 1)) if kernel is None else np.asarray(kernel, dtype=float)
    k = kernel.shape[0]
    hw = [tile, tile] if fixed_size else ["h", "w"]
    x = helper.make_tensor_value_info("image", TensorProto.FLOAT, ["n", 3] + hw)
    y = helper.make_tensor_value_info("heat", TensorProto.FLOAT, ["n", 1] + hw)
    weight = helper.make_tensor("k", TensorProto.FLOAT, [1, 3, k, k], np.repeat(kernel[None] / 3.0, 3, 0).ravel())
    node = helper.make_node("Conv", ["image", "k"], ["heat"], pads=[k // 2] * 4)
    model = helper.make_model(helper.make_graph([node], "conv", [x], [y], [weight]),
                              opset_imports=[helper.make_opsetid("", 17)])
    embed_metadata(model, ModelMetadata(**dict(dict(
        resolution_cm=resolution_cm, tile_size=tile, tiles_overlap_pct=overlap_pct, output_kind=output_kind,
        default_threshold=threshold, peak_blur_sigma_px=1.0), **meta_changes)))
    onnx.save(model, str(path))
    return path


def gaussian_image(width, height, centres, sigma, amplitude=0.9):
    """A grey BGR uint8 image with Gaussian humps (value 255·amplitude at each centre) on black."""
    yy, xx = np.mgrid[0:height, 0:width]
    img = np.zeros((height, width))
    for u, v in centres:
        img = np.maximum(img, amplitude * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * sigma ** 2)))
    return np.repeat(np.rint(255 * img).astype(np.uint8)[:, :, None], 3, axis=2)


def campaign(fx=1000.0, width=200, height=150, n=3, dist=(-0.08, 0.03, 0.0005, -0.0004, 0.0)):
    """n nadir-ish frames 10 m above level ground, 1 cm/px at fx = 1000, tilted a few degrees."""
    t = np.eye(4)
    t[:3, :3] = NADIR
    t[:3, 3] = [0.02, -0.01, 0.05]
    cam = CameraModel(width, height, fx, fx, (width - 1) / 2 + 3.2, (height - 1) / 2 - 2.1, dist, t)
    local = LocalFrame(-27.55, 151.95, 400.0)
    enu = np.column_stack([np.linspace(0, 0.6, n), np.linspace(0, 0.3, n), np.full(n, 10.0)])
    lat, lon, h = local.to_geodetic(enu)
    rpy = np.radians(np.column_stack([np.linspace(-2, 3, n), np.linspace(1.5, -1, n), np.linspace(10, 40, n)]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(rpy[:, 0], rpy[:, 1], rpy[:, 2]))
    poses = FramePoses(np.arange(11, 11 + n), lat, lon, h, q, np.full(n, 400.0), cam)
    return poses, local


# ---------------------------------------------------------------------- tiling
@settings(max_examples=200, deadline=None)
@given(length=st.integers(1, 700), tile=st.integers(8, 128), overlap_frac=st.floats(0, 0.9))
def test_tile_cores_partition_the_axis_and_keep_half_the_overlap_as_context(length, tile, overlap_frac):
    overlap = min(tile - 1, int(tile * overlap_frac))
    spans = tile_spans(length, tile, overlap)
    starts, begin, end = spans.T
    assert begin[0] == 0 and end[-1] == length and np.all(begin[1:] == end[:-1]) and np.all(end > begin)
    assert np.all(starts >= 0) and np.all(np.diff(starts) <= tile - overlap)
    if length >= tile:
        assert np.all(starts + tile <= length)
    assert np.all(begin >= starts) and np.all(end <= starts + tile)
    # Context: a kept pixel is at least overlap // 2 px away from any tile edge that is not the image's.
    inner_begin = begin[1:] - starts[1:]
    inner_end = (starts + tile - end)[:-1]
    assert np.all(inner_begin >= overlap // 2) and np.all(inner_end >= overlap // 2)


def test_tile_spans_regular_case():
    assert tile_spans(100, 40, 8).tolist() == [[0, 0, 36], [32, 36, 66], [60, 66, 100]]
    assert tile_spans(30, 40, 8).tolist() == [[0, 0, 30]]
    with pytest.raises(ValueError):
        tile_spans(100, 8, 8)


def test_stitched_tiles_reproduce_a_whole_image_run(tmp_path):
    import onnxruntime as ort
    kernel = np.random.default_rng(1).normal(size=(5, 5))  # receptive field radius 2 px
    rng = np.random.default_rng(2)
    frame = rng.normal(size=(3, 77, 100)).astype(np.float32)
    whole = ort.InferenceSession(str(conv_model(tmp_path / "m.onnx", kernel)),
                                 providers=["CPUExecutionProvider"]).run(None, {"image": frame[None]})[0][0, 0]
    for overlap, equal in ((8, True), (4, True), (0, False)):  # cores keep overlap // 2 ≥ 2 px of context
        model = HeatmapModel(conv_model(tmp_path / f"m{overlap}.onnx", kernel, tile=32, overlap_pct=overlap / 32 * 100))
        sy, sx = tile_spans(77, 32, overlap), tile_spans(100, 32, overlap)
        heat = stitch(model.run(cut_tiles(frame, sy, sx, 32)), sy, sx, (77, 100))
        assert np.allclose(heat, whole, atol=1e-5) == equal, overlap


@pytest.mark.parametrize("order", ["RGB", "BGR"])
@pytest.mark.parametrize("size", [(77, 100), (20, 45)])  # the second smaller than a tile: padded
def test_tiles_cut_and_normalised_in_batches_equal_the_whole_frame_normalised_then_cut(tmp_path, order, size):
    kernel = np.random.default_rng(5).normal(size=(5, 5))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", kernel, tile=32, overlap_pct=25.0, input_channel_order=order,
                                    standardization_mean=[0.4, 0.5, 0.6], standardization_std=[0.2, 0.25, 0.3]))
    img = np.random.default_rng(6).integers(0, 256, size + (3,), dtype=np.uint8)
    sy, sx = tile_spans(size[0], 32, 8), tile_spans(size[1], 32, 8)
    expected = stitch(model.run(cut_tiles(normalise(img, model.metadata), sy, sx, 32)), sy, sx, size)
    for batch in (None, 1, 3):
        assert np.array_equal(frame_heatmap(model, img, batch), expected), batch


def test_fixed_size_input_and_batch_run_match(tmp_path):
    model = HeatmapModel(conv_model(tmp_path / "f.onnx", tile=24, fixed_size=True))
    img = np.random.default_rng(3).integers(0, 256, (50, 61, 3), dtype=np.uint8)
    heat = frame_heatmap(model, img)
    np.testing.assert_allclose(heat, img.mean(axis=2) / 255.0, atol=1e-6)


# ---------------------------------------------------------------------- peaks
def test_peaks_are_subpixel_centroids_of_each_blob():
    rng = np.random.default_rng(4)
    for _ in range(100):
        centres = np.array([[rng.uniform(15, 45), rng.uniform(15, 65)], [rng.uniform(75, 105), rng.uniform(15, 65)]])
        sigma, amp = rng.uniform(2.0, 5.0), rng.uniform(0.5, 1.0)
        yy, xx = np.mgrid[0:80, 0:120]
        heat = np.maximum.reduce([amp * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * sigma ** 2))
                                  for u, v in centres])
        uv, score = find_peaks(heat, 0.3, blur_sigma_px=1.0)
        order = np.argsort(uv[:, 0])
        assert len(uv) == 2
        np.testing.assert_allclose(uv[order], centres, atol=0.05)
        # Blurring a Gaussian of σ by one of σ_b = 1 gives a Gaussian of σ² + 1 and peak a·σ²/(σ² + 1);
        # the score is its value at the pixel nearest the centre.
        s2 = sigma ** 2 + 1.0
        d2 = np.sum((centres - np.rint(centres)) ** 2, axis=1)
        np.testing.assert_allclose(score[order], amp * sigma ** 2 / s2 * np.exp(-d2 / (2 * s2)), rtol=0.015)
    assert find_peaks(np.full((20, 20), 0.2), 0.3)[0].shape == (0, 2)


def test_a_threshold_above_a_blob_drops_it():
    yy, xx = np.mgrid[0:40, 0:80]
    heat = 0.8 * np.exp(-((xx - 20) ** 2 + (yy - 20) ** 2) / 18) + 0.5 * np.exp(-((xx - 60) ** 2 + (yy - 20) ** 2) / 18)
    uv, score = find_peaks(heat, 0.6, blur_sigma_px=0)
    assert len(uv) == 1 and abs(uv[0, 0] - 20) < 0.05 and score[0] == pytest.approx(0.8, abs=1e-6)


def test_logits_pass_through_a_sigmoid(tmp_path):
    img = np.random.default_rng(5).integers(0, 256, (40, 50, 3), dtype=np.uint8)
    prob = frame_heatmap(HeatmapModel(conv_model(tmp_path / "p.onnx")), img)
    logit = frame_heatmap(HeatmapModel(conv_model(tmp_path / "l.onnx", output_kind="logits")), img)
    np.testing.assert_allclose(logit, 1.0 / (1.0 + np.exp(-prob)), atol=1e-6)


# ---------------------------------------------------------------------- resampling
def test_model_pixels_map_back_to_frame_pixel_centres():
    # Halving: model pixel 0 averages frame pixels 0 and 1, so its centre is frame pixel 0.5.
    np.testing.assert_allclose(to_frame_pixels([[0.0, 0.0], [9.5, 4.0]], (200, 100), (100, 50)),
                               [[0.5, 0.5], [19.5, 8.5]])
    assert model_size(1920, 1200, 0.25, 0.5) == (960, 600)


def test_decoding_does_the_power_of_two_part_of_the_reduction(tmp_path):
    assert read_reduction(1920, 1200, (441, 276)) == 4
    assert read_reduction(1920, 1200, (960, 600)) == 2 and read_reduction(1920, 1200, (961, 600)) == 1
    assert read_reduction(1921, 1200, (441, 276)) == 1  # not an exact divisor: no pixel-centre shift
    assert read_reduction(4000, 3000, (100, 75)) == 8
    img = np.random.default_rng(6).integers(0, 256, (120, 160, 3), dtype=np.uint8)
    path = tmp_path / "f.png"
    cv2.imwrite(str(path), img)
    box = img.reshape(30, 4, 40, 4, 3).mean(axis=(1, 3))
    assert np.abs(read_bgr(str(path), 4).astype(float) - box).max() <= 1.0  # the 4 × 4 block means
    smooth = cv2.GaussianBlur(img, (0, 0), 3.0)
    jpeg = tmp_path / "f.jpg"
    cv2.imwrite(str(jpeg), smooth, [cv2.IMWRITE_JPEG_QUALITY, 95])
    decoded = cv2.imread(str(jpeg)).astype(float).reshape(30, 4, 40, 4, 3).mean(axis=(1, 3))
    assert np.abs(read_bgr(str(jpeg), 4).astype(float) - decoded).mean() < 1.0  # reduced in the DCT
    assert read_bgr(str(tmp_path / "none.png")) is None


# ---------------------------------------------------------------------- frames → ground
def targets_in_frames(poses, local, targets_enu):
    geom = FrameGeometry(poses, local)
    ground = LevelPlaneGround(geom)
    f = np.repeat(np.arange(len(poses)), len(targets_enu))
    proj = project_pairs(geom, f, np.tile(targets_enu, (len(poses), 1)), ground)
    return geom, ground, proj


def render_frames(tmp_path, poses, proj, sigma):
    cam = poses.camera
    paths = []
    for k in range(len(poses)):
        sel = (proj.frame_idx == k) & proj.in_view
        path = tmp_path / f"frame_{k}.png"
        cv2.imwrite(str(path), gaussian_image(cam.width, cam.height, proj.uv[sel], sigma))
        paths.append(str(path))
    return paths


def test_detections_land_on_the_ground_point_of_the_target(tmp_path):
    poses, local = campaign()
    targets = np.array([[0.1, 0.2, 0.0], [-0.25, -0.1, 0.0], [0.35, 0.05, 0.0]])
    geom, ground, proj = targets_in_frames(poses, local, targets)
    paths = render_frames(tmp_path, poses, proj, sigma=3.0)
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    found = list(detect_frames(model, poses, paths, local=local))
    assert [f.frame_id for f in found] == [11, 12, 13]
    for f in found:
        truth = proj.uv[(proj.frame_idx == f.frame_index) & proj.in_view]
        assert f.skipped is None and len(f) == len(truth) >= 2
        d = np.linalg.norm(f.uv[:, None] - truth[None], axis=2)
        assert d.min(axis=1).max() < 0.05  # px (1 cm/px → 0.5 mm)
        # Back-projection is the geometry core's, applied to the detected pixel.
        pts, valid = pixel_to_ground(geom, ground, np.full(len(f), f.frame_index), f.uv)
        assert valid.all()
        np.testing.assert_allclose(f.ground_local, pts, atol=1e-9)
        # ... and lands on the target placed on the frame's ground (an independent forward projection).
        placed = ground.place(np.full(len(targets), f.frame_index), targets)
        miss = np.linalg.norm(f.ground_local[:, None] - placed[None], axis=2).min(axis=1)
        assert miss.max() < 0.001  # m
        lat, lon, h = local.to_geodetic(f.ground_local)
        np.testing.assert_allclose([f.lat, f.lon, f.height], [lat, lon, h])
        assert f.gsd_cm == pytest.approx(100 * geom.gsd_m()[f.frame_index])


@pytest.mark.parametrize("fx", [2000.0, 2170.0, 4340.0])  # 0.5, 0.46, 0.23 cm/px frames; 1 cm/px model
def test_frames_are_resampled_to_the_model_resolution(tmp_path, fx):
    poses, local = campaign(fx=fx, width=400, height=300, n=1)
    geom = FrameGeometry(poses, local)
    targets, _ = pixel_to_ground(geom, LevelPlaneGround(geom), [0, 0], [[120.0, 110.0], [270.0, 200.0]])
    _, _, proj = targets_in_frames(poses, local, targets)
    paths = render_frames(tmp_path, poses, proj, sigma=6.0 * fx / 2000.0)  # 3 px at the model's resolution
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", resolution_cm=1.0))
    (f,) = detect_frames(model, poses, paths, DetectRequest(heatmap_dir=str(tmp_path / "heat")), local=local)
    truth = proj.uv[proj.in_view]
    assert len(f) == 2
    assert np.linalg.norm(f.uv[:, None] - truth[None], axis=2).min(axis=1).max() < 0.15
    heat = cv2.imread(f.heatmap_path, cv2.IMREAD_UNCHANGED)
    assert heat.shape == (300, 400) and heat.dtype == np.uint8
    u, v = np.rint(truth[0]).astype(int)
    assert 0.9 * 0.9 * 255 < heat[v, u] <= 0.9 * 255 + 1  # resampling smooths the peak a little


def test_edge_buffer_drops_detections_near_the_border(tmp_path):
    poses, local = campaign(n=1, dist=(0, 0, 0, 0, 0))
    cam = poses.camera
    path = tmp_path / "edge.png"
    cv2.imwrite(str(path), gaussian_image(cam.width, cam.height, [[5.0, 70.0], [100.0, 70.0]], 2.0))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    (kept,) = detect_frames(model, poses, [path], DetectRequest(edge_buffer_px=0), local=local)
    (cut,) = detect_frames(model, poses, [path], DetectRequest(edge_buffer_px=10), local=local)
    assert len(kept) == 2 and len(cut) == 1 and cut.n_edge == 1 and abs(cut.uv[0, 0] - 100) < 0.05


def test_unusable_images_are_skipped_with_the_reason(tmp_path):
    poses, local = campaign(n=4)
    poses.ground_height[1] = np.nan  # no altimeter reading
    good = tmp_path / "good.png"
    cv2.imwrite(str(good), gaussian_image(200, 150, [[100, 75]], 3.0))
    small = tmp_path / "small.png"
    cv2.imwrite(str(small), gaussian_image(100, 75, [[50, 40]], 3.0))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    found = list(detect_frames(model, poses, [tmp_path / "missing.png", good, small, good], local=local))
    assert "missing.png' cannot be read" in found[0].skipped
    assert "no ground height" in found[1].skipped
    assert "is 100×75 px but the frame's camera model is 200×150 px" in found[2].skipped
    assert found[3].skipped is None and len(found[3]) == 1
    assert len(found[0]) == len(found[1]) == len(found[2]) == 0
    # The last frame is placed with its own pose although an earlier frame had no ground.
    geom = FrameGeometry(poses.subset([3]), local)
    pts, _ = pixel_to_ground(geom, LevelPlaneGround(geom), [0], found[3].uv)
    np.testing.assert_allclose(found[3].ground_local, pts, atol=1e-9)


def test_frames_stream_one_at_a_time_with_progress_and_cancel(tmp_path):
    poses, local = campaign(n=3)
    path = tmp_path / "f.png"
    cv2.imwrite(str(path), gaussian_image(200, 150, [[100, 75]], 3.0))
    model = HeatmapModel(conv_model(tmp_path / "m.onnx"))
    reads, fractions = [], []

    def read(p, reduction):
        reads.append(p)
        return cv2.imread(p)

    gen = detect_frames(model, poses, [str(path)] * 3, local=local, read_image=read, progress=fractions.append)
    next(gen)
    assert len(reads) == 1 and fractions == []
    list(gen)
    assert len(reads) == 3 and fractions == pytest.approx([1 / 3, 2 / 3, 1.0])
    gen = detect_frames(model, poses, [str(path)] * 3, local=local, is_canceled=lambda: len(reads) >= 4,
                        read_image=read)
    with pytest.raises(Cancelled):
        list(gen)
    assert len(reads) == 4


def test_threshold_defaults_to_the_model_and_is_checked(tmp_path):
    poses, local = campaign(n=1, dist=(0, 0, 0, 0, 0))
    path = tmp_path / "f.png"
    cv2.imwrite(str(path), gaussian_image(200, 150, [[60, 75]], 3.0, 0.9) // 2
                + gaussian_image(200, 150, [[140, 75]], 3.0, 0.9))
    # Humps of ≈0.45 and 0.9 (0.37 and 0.74 after the peak blur).
    low = HeatmapModel(conv_model(tmp_path / "low.onnx", threshold=0.3))
    high = HeatmapModel(conv_model(tmp_path / "high.onnx", threshold=0.5))
    assert len(next(detect_frames(low, poses, [path], local=local))) == 2
    assert len(next(detect_frames(high, poses, [path], local=local))) == 1
    assert len(next(detect_frames(high, poses, [path], DetectRequest(threshold=0.3), local=local))) == 2
    with pytest.raises(InputError, match="between 0 and 1"):
        next(detect_frames(low, poses, [path], DetectRequest(threshold=1.5), local=local))


def test_model_identity_and_metadata_errors(tmp_path):
    path = conv_model(tmp_path / "m.onnx")
    model = HeatmapModel(path)
    assert model.digest == hashlib.sha256(path.read_bytes()).hexdigest() and model.name == "m.onnx"
    bad = conv_model(tmp_path / "bad.onnx", tile=32, fixed_size=True)
    m = onnx.load(str(bad))
    for p in m.metadata_props:
        if p.key == "tile_size":
            p.value = "48"
        if p.key == "output_kind":
            p.value = '"scores"'
    onnx.save(m, str(bad))
    with pytest.raises(ModelMetadataError) as err:
        HeatmapModel(bad)
    assert len(err.value.problems) == 2 and "bad.onnx" in str(err.value)
    with pytest.raises(InputError, match="not found"):
        HeatmapModel(tmp_path / "nothing.onnx")


def test_the_log_states_where_the_model_runs(tmp_path, monkeypatch):
    import onnxruntime as ort

    path = conv_model(tmp_path / "m.onnx")
    lines = []
    HeatmapModel(path, log=lines.append)
    assert len(lines) == 1 and "CPU" in lines[0]
    # A GPU provider that is listed but cannot run here: the model falls back to the CPU and says so.
    monkeypatch.setattr(ort, "get_available_providers", lambda: ["CUDAExecutionProvider", "CPUExecutionProvider"])
    lines.clear()
    model = HeatmapModel(path, log=lines.append)
    assert model.providers == ["CPUExecutionProvider"]
    assert any("CUDAExecutionProvider" in line and "CPU" in line for line in lines)
    img = np.full((40, 40, 3), 51, np.uint8)
    np.testing.assert_allclose(frame_heatmap(model, img), 0.2, atol=1e-6)

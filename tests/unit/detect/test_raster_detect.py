"""Detection on a raster read window by window, with the tiny fixed-convolution models of test_detector (the
heatmap is the image): seams, resampling, 16-bit values, nodata, the area asked for, reads that stay small."""
import numpy as np
import pytest
from test_detector import conv_model, gaussian_image

from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel, tile_spans
from birdseye.birdseye_qgis.core.detect.raster_detect import (
    RasterGrid,
    _resampled_window,
    detect_raster,
    model_canvas,
    to_8bit,
    window_overlap_px,
)
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError


class ArrayRaster:
    """A raster held in a numpy array (H, W, 3), read as QGIS's provider would be: any window, zero and
    invalid outside, ``nodata`` pixels invalid; every read recorded."""

    def __init__(self, rgb, nodata=None):
        self.rgb, self.nodata, self.reads = rgb, nodata, []

    def __call__(self, col0, row0, cols, rows):
        self.reads.append((col0, row0, cols, rows))
        h, w = self.rgb.shape[:2]
        planes = np.zeros((3, rows, cols), dtype=self.rgb.dtype)
        valid = np.zeros((rows, cols), dtype=bool)
        c0, r0, c1, r1 = max(col0, 0), max(row0, 0), min(col0 + cols, w), min(row0 + rows, h)
        if c1 > c0 and r1 > r0:
            block = self.rgb[r0:r1, c0:c1]
            planes[:, r0 - row0:r1 - row0, c0 - col0:c1 - col0] = np.moveaxis(block, -1, 0)
            ok = np.ones(block.shape[:2], dtype=bool) if self.nodata is None else ~np.all(block == self.nodata, -1)
            valid[r0 - row0:r1 - row0, c0 - col0:c1 - col0] = ok
        return planes, valid


def grid_of(width, height, gsd_cm=1.0):
    return RasterGrid(width, height, 500000.0, 6000000.0, gsd_cm / 100.0, gsd_cm / 100.0)


def found_once_each(found, targets, tol):
    """Each target matched by exactly one detection within ``tol`` px, and no detection left over."""
    pts = np.column_stack([found.col, found.row])
    d = np.linalg.norm(pts[:, None] - np.asarray(targets, float)[None], axis=2)
    assert (d.min(axis=0) < tol).all(), f"missed {np.asarray(targets)[d.min(axis=0) >= tol]}"
    assert ((d < tol).sum(axis=0) == 1).all(), "a target counted twice"
    assert len(found) == len(targets)


def test_targets_on_window_and_tile_seams_are_found_once(tmp_path):
    """Windows of 4 tiles of 32 px on a 640 × 420 px raster at the model's resolution: a target on every
    boundary between two window cores (and at their crossings), and on tile seams inside windows."""
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, overlap_pct=25.0, threshold=0.3))
    width, height = 640, 420
    wx = tile_spans(width, 128, window_overlap_px(model.metadata))
    wy = tile_spans(height, 128, window_overlap_px(model.metadata))
    assert len(wx) > 3 and len(wy) > 2
    edges_x = [float(e) - 0.5 for e in wx[1:, 1]]  # between pixel e − 1 and e: exactly on the seam
    edges_y = [float(e) - 0.5 for e in wy[1:, 1]]
    targets = [(x, 60.0) for x in edges_x] + [(100.0, y) for y in edges_y] + [(edges_x[1], edges_y[0])]
    tiles_x = tile_spans(128, 32, model.metadata.overlap_px)  # tile seams inside the first window
    targets += [(float(e) - 0.5, 300.0) for e in tiles_x[1:3, 1]]
    raster = ArrayRaster(gaussian_image(width, height, targets, sigma=2.5))
    found = detect_raster(model, grid_of(width, height), raster, window_tiles=4)
    assert found.windows == len(wx) * len(wy) and found.merged >= 1
    found_once_each(found, targets, tol=0.15)
    # Map coordinates: the pixel-centre rule by hand.
    k = int(np.argmin(np.abs(found.col - targets[0][0]) + np.abs(found.row - targets[0][1])))
    assert found.x[k] == pytest.approx(500000.0 + (found.col[k] + 0.5) * 0.01)
    assert found.y[k] == pytest.approx(6000000.0 - (found.row[k] + 0.5) * 0.01)


@pytest.mark.parametrize("gsd_cm", [2.0, 0.5, 0.37])
def test_a_raster_finer_or_coarser_than_the_model_is_resampled(tmp_path, gsd_cm):
    """Humps of 3 cm σ on rasters at 2, 0.5 and 0.37 cm/px, a model at 1 cm/px: found at their raster pixels."""
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, threshold=0.3))
    width = height = int(round(300 / gsd_cm))
    rng = np.random.default_rng(3)
    targets = rng.uniform(0.1, 0.9, (12, 2)) * width
    raster = ArrayRaster(gaussian_image(width, height, targets, sigma=3.0 / gsd_cm))
    grid = grid_of(width, height, gsd_cm)
    s, w, h = model_canvas(grid, 1.0)
    assert (w, h) == (round(width * gsd_cm), round(height * gsd_cm))
    found = detect_raster(model, grid, raster, window_tiles=3)
    found_once_each(found, targets, tol=0.25 / gsd_cm)


def test_16_bit_values_are_scaled_from_their_range(tmp_path):
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, threshold=0.3))
    targets = [(40.0, 50.0), (150.0, 90.0)]
    rgb8 = gaussian_image(200, 160, targets, sigma=2.5)
    rgb16 = (rgb8.astype(np.uint16) * 16 + 1000).astype(np.uint16)  # a 12-bit sensor with an offset
    found8 = detect_raster(model, grid_of(200, 160), ArrayRaster(rgb8))
    found16 = detect_raster(model, grid_of(200, 160), ArrayRaster(rgb16), value_range=(1000, 1000 + 255 * 16))
    assert np.allclose(np.sort(found16.col), np.sort(found8.col), atol=1e-3)
    with pytest.raises(InputError, match="not 8-bit.*VALUE_RANGE"):
        detect_raster(model, grid_of(200, 160), ArrayRaster(rgb16))
    assert to_8bit(np.array([[[0, 500, 1000, 2000]]]), [(500, 1500)]).tolist() == [[[0, 0, 128, 255]]]
    with pytest.raises(InputError, match="band 1 is empty"):
        to_8bit(np.zeros((1, 2, 2), np.uint16), [(5, 5)])


def test_nodata_and_the_area_asked_for_drop_detections_and_skip_windows(tmp_path):
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, threshold=0.3))
    width, height = 600, 200
    targets = [(50.0, 100.0), (300.0, 100.0), (550.0, 100.0)]
    rgb = gaussian_image(width, height, targets, sigma=2.5)
    rgb[80:120, 530:570] = (7, 7, 7)  # nodata over the third target
    grid = grid_of(width, height)
    found = detect_raster(model, grid, ArrayRaster(rgb, nodata=(7, 7, 7)), window_tiles=4)
    found_once_each(found, targets[:2], tol=0.15)
    # Only the left third of the raster is asked for: windows wholly right of it are not even read.
    x_limit = 500000.0 + 200 * 0.01
    raster = ArrayRaster(rgb)
    found = detect_raster(model, grid, raster, window_tiles=4,
                          window_needed=lambda x0, y0, x1, y1: x0 < x_limit,
                          keep=lambda x, y: x < x_limit)
    found_once_each(found, targets[:1], tol=0.15)
    assert found.skipped_windows >= 1 and len(raster.reads) == found.windows
    assert max(c0 for c0, _, _, _ in raster.reads) < 200


def test_reads_are_windows_never_the_whole_raster_with_progress_and_cancel(tmp_path):
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, threshold=0.3))
    raster = ArrayRaster(gaussian_image(900, 700, [(450.0, 350.0)], sigma=2.5))
    seen = []
    found = detect_raster(model, grid_of(900, 700), raster, window_tiles=4, progress=seen.append)
    assert len(found) == 1 and seen[-1] == 1.0 and seen == sorted(seen) and len(seen) == found.windows
    # A window of 4 tiles of 32 px, its overlap and the interpolation's margin: never more.
    assert max(c for _, _, c, _ in raster.reads) <= 128 + 3 and max(r for _, _, _, r in raster.reads) <= 128 + 3
    calls = []
    with pytest.raises(Cancelled):
        detect_raster(model, grid_of(900, 700), raster, window_tiles=4,
                      is_canceled=lambda: calls.append(1) or len(calls) > 2)
    assert len(calls) == 3


def test_a_raster_without_a_pixel_size_is_refused():
    with pytest.raises(InputError, match="georeferenced"):
        RasterGrid(10, 10, 0.0, 0.0, 0.0, 1.0)


def deepness_segmentor(path, tile=32, **props):
    """A Deepness-style segmentor with Deepness's keys only: two channels (background 1 − p, target p) of
    p = the channel mean / 255, fixed input size, no tile_size key (Deepness reads the input's size)."""
    import json

    import onnx
    from onnx import TensorProto, helper

    x = helper.make_tensor_value_info("input", TensorProto.FLOAT, [1, 3, tile, tile])
    y = helper.make_tensor_value_info("output", TensorProto.FLOAT, [1, 2, tile, tile])
    weight = helper.make_tensor("k", TensorProto.FLOAT, [2, 3, 1, 1], [-1 / 3] * 3 + [1 / 3] * 3)
    bias = helper.make_tensor("b", TensorProto.FLOAT, [2], [1.0, 0.0])
    node = helper.make_node("Conv", ["input", "k", "b"], ["output"])
    model = helper.make_model(helper.make_graph([node], "seg", [x], [y], [weight, bias]),
                              opset_imports=[helper.make_opsetid("", 17)])
    meta = {"model_type": "Segmentor", "resolution": 1.0, "tiles_overlap": 25,
            "class_names": {"0": "background", "1": "nest"}, "seg_thresh": 0.3,
            "standardization_mean": [0.0, 0.0, 0.0], "standardization_std": [1.0, 1.0, 1.0], **props}
    for key, value in meta.items():
        model.metadata_props.add(key=key, value=json.dumps(value))
    onnx.save(model, str(path))
    return path


def test_a_deepness_segmentor_runs_as_a_heatmap(tmp_path):
    """A two-channel Deepness segmentor (batch 1, fixed size) finds what the one-channel BirdsEye model with
    the same heatmap finds, at its seg_thresh."""
    lines = []
    seg = HeatmapModel(deepness_segmentor(tmp_path / "seg.onnx"), log=lines.append)
    assert "output channel 1 (nest), default threshold 0.3, tiles of 32 px overlapping 25 %" in lines[-1]
    assert (seg.metadata.output_channel, seg.metadata.schema_version, seg.max_batch) == (1, 0, 1)
    assert (seg.metadata.tile_size, seg.metadata.overlap_px, seg.metadata.default_threshold) == (32, 8, 0.3)
    ours = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, overlap_pct=25.0, threshold=0.3))
    targets = [(40.0, 50.0), (150.0, 90.0), (95.5, 31.5)]
    raster = ArrayRaster(gaussian_image(200, 160, targets, sigma=2.5))
    found = detect_raster(seg, grid_of(200, 160), raster, window_tiles=3)
    found_once_each(found, targets, tol=0.15)
    expected = detect_raster(ours, grid_of(200, 160), raster, window_tiles=3)
    assert np.allclose(found.col, expected.col, atol=1e-4) and np.allclose(found.score, expected.score, atol=1e-5)


def test_a_deepness_segmentor_whose_names_contradict_its_output_is_refused(tmp_path):
    path = deepness_segmentor(tmp_path / "seg.onnx", class_names={"0": "a", "1": "b", "2": "c"})
    with pytest.raises(InputError, match=r"(?s)seg.onnx: .*names 3 classes for 2 output channel"):
        HeatmapModel(path)


def test_a_target_at_the_far_edge_of_a_much_finer_raster_is_found(tmp_path):
    """At 0.3 cm/px a model pixel is 3.3 raster pixels: the raster is reduced 3× first. Targets 3.5 cm from
    the right and bottom edges (a model pixel or so inside the last window's reach) are found where they are."""
    model = HeatmapModel(conv_model(tmp_path / "m.onnx", tile=32, threshold=0.3))
    width, height = 1000, 700
    targets = [(width - 12.0, 300.0), (400.0, height - 12.0), (width - 12.0, height - 12.0)]
    raster = ArrayRaster(gaussian_image(width, height, targets, sigma=10.0))
    found = detect_raster(model, grid_of(width, height, 0.3), raster, window_tiles=3)
    found_once_each(found, targets, tol=1.0)


@pytest.mark.parametrize("window", [(0, 0, 64, 48), (37, 21, 50, 40), (70, 50, 40, 30)])
def test_at_the_models_resolution_a_window_is_the_rasters_pixels_as_the_warp_gives_them(window):
    """A raster at the model's resolution is cut, not warped: the same pixels and valid mask as OpenCV's bilinear
    warp by the whole-pixel shift (inside, at the raster's edge, and partly off it)."""
    import cv2

    rng = np.random.default_rng(3)
    rgb = rng.integers(0, 256, (80, 100, 3), dtype=np.uint8)
    raster = ArrayRaster(rgb)
    x0, y0, w, h = window
    image, valid = _resampled_window(raster, grid_of(100, 80), 1.0, x0, y0, w, h, None)
    bgr = np.ascontiguousarray(rgb[:, :, ::-1])
    m = np.array([[1.0, 0.0, x0], [0.0, 1.0, y0]])
    flags = cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP
    warped = cv2.warpAffine(bgr, m, (w, h), flags=flags, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    inside = cv2.warpAffine(np.full((80, 100), 255, np.uint8), m, (w, h), flags=flags,
                            borderMode=cv2.BORDER_CONSTANT, borderValue=0) >= 128
    assert image.shape == (h, w, 3) and valid.shape == (h, w)
    np.testing.assert_array_equal(image, warped)
    np.testing.assert_array_equal(valid, inside)
    assert valid.all() == (x0 + w <= 100 and y0 + h <= 80)

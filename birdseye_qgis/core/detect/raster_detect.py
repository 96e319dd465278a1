"""Run an ONNX heatmap model over a georeferenced raster (an orthomosaic), window by window.

The frames' detector (:mod:`.detector`) reads a whole frame; an orthomosaic may be 20,000 px wide, so here
the raster is read in *windows* through a caller's reader (QGIS's raster provider in the plugin, a numpy
array in tests), and memory stays that of one window whatever the raster's size.

Geometry, in the raster's pixels (pixel-centre convention as everywhere: pixel (0, 0) is the centre of the
top-left pixel) and the model's (the raster resampled to the model's ``resolution``):

* the scale ``s = gsd / resolution`` (model px per raster px) maps a model pixel ``u'`` to the raster pixel
  ``u = (u' + 0.5) / s − 0.5`` and back — the frames' :func:`.detector.to_frame_pixels` rule;
* the model-resolution canvas (``round(width · s)`` × ``round(height · s)`` px) is cut into square windows by
  :func:`.detector.tile_spans` — the tiles' own rule one level up: windows overlap by :func:`window_overlap_px`
  and their *cores* partition the canvas. Inside a window :func:`.detector.frame_heatmap` tiles and stitches
  exactly as on a frame;
* peaks (:func:`.detector.find_peaks`) are kept when their centroid lies in the window's core. The overlap
  holds a target's whole hump and the tiles' context on both sides of a core's edge, so a target on a seam is
  found by both windows at (nearly) the same place and kept by the one whose core holds it; peaks of two
  windows closer than :data:`SEAM_MERGE_PX` (the one left of a sub-pixel disagreement at the very edge) are
  merged, keeping the higher score — never a target counted twice, never one lost between two cores.

Pixel values: 8-bit bands as they are; other types scaled linearly from the ``value_range`` of each band
(low → 0, high → 255, clipped), which the caller takes from the raster's statistics or the user. Pixels the
reader marks invalid (nodata, outside the raster) are black, and a peak on one is dropped.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable

import numpy as np

from ..errors import InputError, check_cancel
from .detector import HeatmapModel, find_peaks, frame_heatmap, tile_spans

#: Window edge in model tiles: 8 tiles of 288 px make 2304 px windows, about 64 MB of float input each.
WINDOW_TILES = 8
#: Tiles run through the model at a time: ONNX Runtime's activations grow with the batch (tens of MB a tile for
#: the bundled model), and a window holds about a hundred tiles.
TILE_BATCH = 8
#: Peaks of two windows closer than this (px at the model's resolution) are one target seen by both.
SEAM_MERGE_PX = 2.0


@dataclass(frozen=True)
class RasterGrid:
    """Where a north-up raster's pixels lie: ``width`` × ``height`` px, the map position of the top-left
    *corner* (``origin_x``, ``origin_y``) and the pixel size (``pixel_x``, ``pixel_y`` > 0, map units; rows
    go south), ``metres_per_unit`` of the map units (1 for a metric CRS)."""

    width: int
    height: int
    origin_x: float
    origin_y: float
    pixel_x: float
    pixel_y: float
    metres_per_unit: float = 1.0

    def __post_init__(self):
        if self.width <= 0 or self.height <= 0:
            raise InputError(f"the raster has no pixels ({self.width} × {self.height})")
        if not (self.pixel_x > 0 and self.pixel_y > 0 and self.metres_per_unit > 0):
            raise InputError("the raster's pixel size is not positive: is it georeferenced?")

    @property
    def gsd_cm(self) -> float:
        """The ground sample distance, cm/px (the mean of the two axes')."""
        return 50.0 * (self.pixel_x + self.pixel_y) * self.metres_per_unit

    def to_map(self, col, row) -> tuple[np.ndarray, np.ndarray]:
        """Map coordinates of raster pixels (pixel-centre convention)."""
        col, row = np.asarray(col, dtype=float), np.asarray(row, dtype=float)
        return self.origin_x + (col + 0.5) * self.pixel_x, self.origin_y - (row + 0.5) * self.pixel_y

    def to_pixel(self, x, y) -> tuple[np.ndarray, np.ndarray]:
        """Raster pixels (col, row) of map coordinates: :meth:`to_map` inverted."""
        x, y = np.asarray(x, dtype=float), np.asarray(y, dtype=float)
        return (x - self.origin_x) / self.pixel_x - 0.5, (self.origin_y - y) / self.pixel_y - 0.5


@dataclass
class RasterDetections:
    """Detections on a raster: its pixels (``col``, ``row``), map coordinates (``x``, ``y``), ``score``;
    ``windows`` read and ``skipped_windows`` (outside the area asked for), ``merged`` peaks found twice on a
    seam and kept once."""

    col: np.ndarray
    row: np.ndarray
    x: np.ndarray
    y: np.ndarray
    score: np.ndarray
    windows: int = 0
    skipped_windows: int = 0
    merged: int = 0

    def __len__(self) -> int:
        return len(self.score)


#: ``read(col0, row0, cols, rows) -> (planes (3, rows, cols), valid (rows, cols) bool)``: the raster's
#: pixels [col0, col0 + cols) × [row0, row0 + rows) as the red, green and blue the model reads (the model's
#: own channel order is applied later), any numeric type; pixels outside the raster or nodata invalid.
ReadWindow = Callable[[int, int, int, int], tuple[np.ndarray, np.ndarray]]


def window_overlap_px(meta) -> int:
    """Overlap of two windows (px at the model's resolution): a tile on each side, so a peak at a core's
    edge has the same context in both windows as anywhere inside one."""
    return int(meta.tile_size)


def model_canvas(grid: RasterGrid, resolution_cm: float) -> tuple[float, int, int]:
    """(s, width, height): model px per raster px and the model-resolution canvas."""
    s = grid.gsd_cm / float(resolution_cm)
    return s, max(1, int(round(grid.width * s))), max(1, int(round(grid.height * s)))


def to_8bit(planes: np.ndarray, value_range=None) -> np.ndarray:
    """Planes (C, H, W) as uint8: 8-bit values as they are, others scaled from ``value_range`` — one
    (low, high) per plane, or one for all — to 0..255 and clipped."""
    planes = np.asarray(planes)
    if planes.dtype == np.uint8 and value_range is None:
        return planes
    if value_range is None:
        raise InputError(f"the raster's values are {planes.dtype}, not 8-bit: give the range of values that "
                         "maps to 0..255 (VALUE_RANGE), or let it come from the raster's statistics")
    ranges = np.asarray(value_range, dtype=np.float64).reshape(-1, 2)
    if len(ranges) == 1:
        ranges = np.repeat(ranges, len(planes), axis=0)
    out = np.empty(planes.shape, dtype=np.uint8)
    for c, (low, high) in enumerate(ranges[:len(planes)]):
        if not high > low:
            raise InputError(f"the value range of band {c + 1} is empty ({low:g} … {high:g})")
        scaled = (planes[c].astype(np.float32) - low) * (255.0 / (high - low))
        np.clip(np.rint(scaled), 0, 255, out=scaled)
        out[c] = scaled
    return out


def _resampled_window(read: ReadWindow, grid: RasterGrid, s: float, x0: int, y0: int, w: int, h: int,
                      value_range) -> tuple[np.ndarray, np.ndarray]:
    """The model-resolution window [x0, x0 + w) × [y0, y0 + h) as a BGR uint8 image (h, w, 3) and its valid
    mask, from the raster pixels it covers (one pixel of margin for the interpolation)."""
    import cv2

    # Raster pixels the window's pixel centres fall between.
    c0 = int(np.floor((x0 + 0.5) / s - 0.5)) - 1
    r0 = int(np.floor((y0 + 0.5) / s - 0.5)) - 1
    c1 = int(np.ceil((x0 + w - 0.5) / s - 0.5)) + 2
    r1 = int(np.ceil((y0 + h - 0.5) / s - 0.5)) + 2
    # Reduce by whole factors k with area averaging first (no aliasing), then warp the rest bilinearly; the block
    # is read a whole number of k wide and high, so the reduction drops none of it.
    k = max(1, int(np.floor(1.0 / s)))
    c1, r1 = c0 + -(-(c1 - c0) // k) * k, r0 + -(-(r1 - r0) // k) * k
    planes, valid = read(c0, r0, c1 - c0, r1 - r0)
    rgb = to_8bit(planes, value_range)
    # dst pixel (u', v') of the window → raster pixel u = (u' + x0 + 0.5)/s − 0.5 → block pixel u − c0 →
    # reduced pixel (u − c0 + 0.5)/k − 0.5.
    a = 1.0 / (s * k)
    shift_x, shift_y = ((x0 + 0.5) / s - 0.5 - c0 + 0.5) / k - 0.5, ((y0 + 0.5) / s - 0.5 - r0 + 0.5) / k - 0.5
    if k == 1 and a == 1.0 and float(shift_x).is_integer() and float(shift_y).is_integer():
        # The raster is at the model's resolution, on its pixel grid: the warp would shift by whole pixels, which
        # bilinear interpolation reproduces exactly — a slice of the block does the same without the warp.
        cols, rows = slice(int(shift_x), int(shift_x) + w), slice(int(shift_y), int(shift_y) + h)
        return np.ascontiguousarray(np.stack([rgb[2, rows, cols], rgb[1, rows, cols], rgb[0, rows, cols]], axis=-1)), \
            np.ascontiguousarray(valid[rows, cols])
    bgr = np.ascontiguousarray(np.stack([rgb[2], rgb[1], rgb[0]], axis=-1))
    valid8 = valid.astype(np.uint8) * 255
    if k > 1:
        size = ((c1 - c0) // k, (r1 - r0) // k)
        bgr = cv2.resize(bgr, size, interpolation=cv2.INTER_AREA)
        valid8 = cv2.resize(valid8, size, interpolation=cv2.INTER_AREA)
    m = np.array([[a, 0.0, shift_x], [0.0, a, shift_y]])
    flags = cv2.INTER_LINEAR | cv2.WARP_INVERSE_MAP
    image = cv2.warpAffine(bgr, m, (w, h), flags=flags, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    mask = cv2.warpAffine(valid8, m, (w, h), flags=flags, borderMode=cv2.BORDER_CONSTANT, borderValue=0)
    return image, mask >= 128


def detect_raster(model: HeatmapModel, grid: RasterGrid, read: ReadWindow, threshold: float | None = None,
                  value_range=None, window_tiles: int = WINDOW_TILES,
                  window_needed: Callable[[float, float, float, float], bool] | None = None,
                  keep: Callable[[np.ndarray, np.ndarray], np.ndarray] | None = None,
                  progress=None, is_canceled=None) -> RasterDetections:
    """Detections of ``model`` on the raster ``grid`` read through ``read`` (module docstring).

    ``threshold``: probability (None: the model's default). ``value_range``: see :func:`to_8bit`.
    ``window_needed(x_min, y_min, x_max, y_max)`` (map units) says whether a window's core is in the area
    asked for (None: all are); ``keep(x, y)`` which detections are (None: all). Progress after each window,
    cancel before each."""
    meta = model.metadata
    threshold = meta.default_threshold if threshold is None else float(threshold)
    if not 0.0 < threshold < 1.0:
        raise InputError(f"the threshold must be a probability between 0 and 1 (got {threshold})")
    s, width, height = model_canvas(grid, meta.resolution_cm)
    window = max(int(window_tiles), 2) * int(meta.tile_size)
    overlap = window_overlap_px(meta)
    spans_y, spans_x = tile_spans(height, window, overlap), tile_spans(width, window, overlap)
    found_u, found_v, found_score, found_window = [], [], [], []
    n_windows, skipped, done = len(spans_y) * len(spans_x), 0, 0
    for y0, yb, ye in spans_y:
        for x0, xb, xe in spans_x:
            check_cancel(is_canceled)
            done += 1
            if window_needed is not None:  # the core's corners (pixel i spans [i, i + 1)), on the map
                m = SEAM_MERGE_PX
                xs = grid.origin_x + np.array([xb - m, xe + m]) / s * grid.pixel_x
                ys = grid.origin_y - np.array([ye + m, yb - m]) / s * grid.pixel_y
                if not window_needed(float(xs[0]), float(ys[0]), float(xs[1]), float(ys[1])):
                    skipped += 1
                    if progress is not None:
                        progress(done / n_windows)
                    continue
            w, h = min(window, width - x0), min(window, height - y0)
            image, valid = _resampled_window(read, grid, s, x0, y0, w, h, value_range)
            uv, score = find_peaks(frame_heatmap(model, image, TILE_BATCH), threshold, meta.peak_blur_sigma_px)
            if len(uv):
                u, v = uv[:, 0] + x0, uv[:, 1] + y0
                # The core, widened by the merge radius: a peak at the edge is kept by both and merged below.
                inside = ((u >= xb - 0.5 - SEAM_MERGE_PX) & (u < xe - 0.5 + SEAM_MERGE_PX)
                          & (v >= yb - 0.5 - SEAM_MERGE_PX) & (v < ye - 0.5 + SEAM_MERGE_PX))
                iu = np.clip(np.rint(uv[:, 0]).astype(int), 0, w - 1)
                iv = np.clip(np.rint(uv[:, 1]).astype(int), 0, h - 1)
                inside &= valid[iv, iu]
                found_u.append(u[inside])
                found_v.append(v[inside])
                found_score.append(score[inside])
                found_window.append(np.full(int(inside.sum()), done))
            if progress is not None:
                progress(done / n_windows)
    u, v, score, win = (np.concatenate(a) if a else np.empty(0) for a in (found_u, found_v, found_score,
                                                                          found_window))
    keep_mask, merged = _merge_seams(u, v, score, win)
    u, v, score = u[keep_mask], v[keep_mask], score[keep_mask]
    col, row = (u + 0.5) / s - 0.5, (v + 0.5) / s - 0.5
    x, y = grid.to_map(col, row)
    if keep is not None and len(x):
        wanted = np.asarray(keep(x, y), dtype=bool)
        col, row, x, y, score = col[wanted], row[wanted], x[wanted], y[wanted], score[wanted]
    return RasterDetections(col, row, x, y, score, n_windows - skipped, skipped, merged)


def _merge_seams(u, v, score, window) -> tuple[np.ndarray, int]:
    """Keep-mask of the peaks: of peaks from different windows within :data:`SEAM_MERGE_PX`, the highest
    score stays (ties: the first window's). Peaks of one window are never merged: they are distinct blobs."""
    keep = np.ones(len(u), dtype=bool)
    if len(u) < 2:
        return keep, 0
    from scipy.spatial import cKDTree

    pairs = cKDTree(np.column_stack([u, v])).query_pairs(SEAM_MERGE_PX, output_type="ndarray")
    pairs = pairs[window[pairs[:, 0]] != window[pairs[:, 1]]] if len(pairs) else pairs
    order = np.lexsort((window, -score))  # best first
    rank = np.empty(len(u), dtype=int)
    rank[order] = np.arange(len(u))
    for i, j in sorted(pairs.tolist(), key=lambda p: min(rank[p[0]], rank[p[1]])):
        if keep[i] and keep[j]:
            keep[j if rank[i] < rank[j] else i] = False
    return keep, int((~keep).sum())

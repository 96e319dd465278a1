"""Training labels on a raster (an orthomosaic): the survey's targets at the raster's own pixels, written as the
tiles Train detector reads.

Write labels (:mod:`.training_set`) projects every geotag into every frame that sees it; an orthomosaic is one
north-up image whose geotransform places a map position at a pixel (:class:`..detect.raster_detect.RasterGrid`,
pixel-centre convention: ``col = (x − origin_x) / pixel_x − 0.5``). The folder written here has Write labels'
layout (docs/design.md#labels), so Train detector reads it unchanged:

* ``tiles/images`` + ``tiles/labels`` — t × t px tiles on :func:`.training_set.tile_origins`' grid (the last row and
  column flush with the raster's border), cut from the raster read tile by tile through the caller's
  :data:`..detect.raster_detect.ReadWindow` (never the whole raster); pixels the reader marks invalid (nodata,
  transparent, beyond the raster) are black. Labels are :func:`.training_set.soft_label_raster`'s Gaussian humps
  (σ px = ``sigma_cm`` / the raster's GSD, 255 at a centre, cut at 3σ, max-combined) of the targets near the tile;
* **each tile is one frame**: ``<frame_id>_<y0>_<x0>.png`` with ``frame_id`` the tile's index on the grid (row by
  row), (x0, y0) its top-left pixel in the raster. Train detector's split keeps a frame's tiles together and
  groups frames by the targets they see, so one frame per tile lets the spatial blocks hold out part of the
  raster (one frame for the whole raster would see every target and leave nothing to hold out);
* ``labels.csv`` — one row per target per tile whose label shows it (its 3σ disc reaches into the tile): u, v
  in the raster's pixels, ``margin_px`` the distance to the tile's nearest edge (negative: outside the tile, by
  that much), ``image`` the raster's source. A tile is positive when a row's centre lies in it
  (:func:`.training_set.inside_tile`, the rule Train detector tells positives by); the rows of targets only
  reaching in keep a tile on the same side of the split as the target it partly shows;
* ``labels.txt`` — one line per positive tile: its image and the centres inside it in the tile's pixels;
* ``targets.csv`` — the targets labelled (:func:`.training_set.write_targets`: WGS84 position, the geotag's own
  height and its reference; a raster carries no heights);
* ``summary.json`` — Write labels' counts, σ in px and cm, and ``raster``: the source, size, pixel size, CRS
  and the GSD (cm/px) Train detector resamples the tiles from (:func:`raster_record`), with the ground diagonal
  of a tile (its "footprint", for the size of the spatial blocks).

**No tile teaches a target as background** (Write labels' rule): a target outside the raster whose label disc
reaches in, or whose centre pixel is invalid (a hole in the orthomosaic), is not labelled, and no tile within
3σ of it is written; a tile without a positive is written only when its whole ground outline lies in the
surveyed area, and when it holds a valid pixel. Negative tiles are drawn at random (``seed``) until
``negative_ratio`` × the positive tiles are written, reading only the tiles drawn.
"""
from __future__ import annotations

import csv
import json
from dataclasses import dataclass
from pathlib import Path
from typing import Callable

import numpy as np

from ..detect.raster_detect import RasterGrid, ReadWindow, to_8bit
from ..errors import InputError, check_cancel
from ..field.geotags import PROVENANCES, Geotags
from ..geometry.geodesy import LocalFrame
from .training_set import (
    LABEL_RADIUS_SIGMAS,
    LABELS_CSV_FIELDS,
    inside_tile,
    soft_label_raster,
    tile_distance,
    tile_origins,
    tile_outlines_px,
    write_targets,
)

#: ``to_lat_lon(x, y) -> (lat, lon)``: WGS84 degrees of map coordinates in the raster's CRS (arrays).
ToLatLon = Callable[[np.ndarray, np.ndarray], tuple[np.ndarray, np.ndarray]]


@dataclass(frozen=True)
class RasterLabelRequest:
    """What to write: σ of the labels on the ground (cm), the tile side (px), negative tiles per positive tile
    and the seed of their sample."""

    sigma_cm: float
    tile_size: int = 224
    negative_ratio: float = 1.0
    seed: int = 0

    def sigma_px(self, grid: RasterGrid) -> float:
        """σ in the raster's pixels: σ (cm) / GSD (cm/px)."""
        return self.sigma_cm / grid.gsd_cm


def raster_record(folder) -> dict | None:
    """The ``raster`` record of a raster-labels folder's summary.json (``gsd_cm``, ``tile_diagonal_m``, …), or
    None for a folder of frames (or without summary.json)."""
    path = Path(folder) / "summary.json"
    if not path.is_file():
        return None
    try:
        record = json.loads(path.read_text(encoding="utf-8")).get("raster")
    except ValueError as exc:
        raise InputError(f"is not JSON ({exc})", source=str(path)) from exc
    if record is None:
        return None
    if not isinstance(record, dict) or not float(record.get("gsd_cm") or 0) > 0:
        raise InputError("the raster record has no positive gsd_cm (cm/px)", source=str(path), field="raster")
    return record


def write_raster_labels(out_dir, grid: RasterGrid, read: ReadWindow, geotags: Geotags, x, y,
                        request: RasterLabelRequest, value_range=None, surveyed=None,
                        to_lat_lon: ToLatLon | None = None, raster: dict | None = None, hard_negatives=None,
                        unresolved=None, progress=None, is_canceled=None) -> dict:
    """Write the label folder of the targets ``geotags`` at map positions ``x``, ``y`` (the raster's CRS) on the
    raster ``grid`` read through ``read`` (module docstring); returns the summary (also in summary.json).

    ``value_range``: non-8-bit bands to 0..255 (:func:`..detect.raster_detect.to_8bit`). ``surveyed``: the
    surveyed area (:class:`..field.surveyed_area.SurveyedArea`; None: negatives anywhere), placed through
    ``to_lat_lon``, which it needs. ``raster``: what summary.json records of the raster's source (file, CRS).
    ``hard_negatives``, ``unresolved``: map positions (x, y) of the clusters a review rejected — negative tiles
    holding one are drawn first — and of those it left unresolved (maybe targets: no tile within 3σ of one is
    written); None: no review.
    Progress after each tile written, cancel before each."""
    t = int(request.tile_size)
    if t < 1:
        raise InputError(f"the tile size must be a positive number of pixels (got {t})", field="TILE_SIZE")
    if not request.sigma_cm > 0:
        raise InputError(f"σ must be positive (got {request.sigma_cm:g} cm)", field="SIGMA_CM")
    if surveyed is not None and to_lat_lon is None:
        raise InputError("a surveyed area needs the raster's map coordinates in WGS84 (to_lat_lon)")
    sigma_px = request.sigma_px(grid)
    radius = LABEL_RADIUS_SIGMAS * sigma_px
    uv = _pixels(grid, (x, y))
    bad = np.flatnonzero(~np.isfinite(uv).all(axis=1))
    if len(bad):
        raise InputError("has no position on the raster's map", source=geotags.source or "geotags",
                         row=int(geotags.source_row[bad[0]]), field="geometry")
    from_raster = tile_distance(uv, 0, 0, grid.width, grid.height)
    inside = _in_raster(grid, uv)
    on_nodata = np.zeros(len(uv), dtype=bool)
    for i in np.flatnonzero(inside):  # one pixel each: where the orthomosaic has a hole, no target can be seen
        check_cancel(is_canceled)
        on_nodata[i] = not read(int(np.floor(uv[i, 0] + 0.5)), int(np.floor(uv[i, 1] + 0.5)), 1, 1)[1][0, 0]
    labelled = inside & ~on_nodata
    # Not labelled but maybe visible: its tiles would teach it as background.
    ignore_uv = np.vstack([uv[~labelled & (from_raster <= radius)], _pixels(grid, unresolved)])
    hard_uv = _pixels(grid, hard_negatives)
    target_uv, target_index = uv[labelled], np.flatnonzero(labelled)

    xs, ys = tile_origins(grid.width, t), tile_origins(grid.height, t)
    positives, candidates, n_ignored = [], [], 0
    for iy, y0 in enumerate(ys):
        for ix, x0 in enumerate(xs):
            tile = (iy * len(xs) + ix, y0, x0)
            if np.any(tile_distance(ignore_uv, x0, y0, t) <= radius):
                n_ignored += 1
            elif inside_tile(target_uv, x0, y0, t).any():
                positives.append(tile)
            else:
                candidates.append(tile)
    in_area = _surveyed_test(grid, surveyed, to_lat_lon, geotags, t)([(y0, x0) for _, y0, x0 in candidates])
    negatives = [c for c, ok in zip(candidates, in_area) if ok]
    n_neg = min(len(negatives), int(round(request.negative_ratio * max(1, len(positives)))))
    is_hard = np.array([inside_tile(hard_uv, x0, y0, t).any() for _, y0, x0 in negatives], dtype=bool)
    # What the detector got wrong first, each group in a seeded random order; read until n_neg are written.
    order = np.random.default_rng(request.seed).permutation(len(negatives))
    order = np.concatenate([order[is_hard[order]], order[~is_hard[order]]]).astype(int)

    out = Path(out_dir)
    for sub in ("images", "labels"):
        (out / "tiles" / sub).mkdir(parents=True, exist_ok=True)
    classes = sorted({str(name) for name in geotags.labels[target_index]}) or ["target"]
    class_index = {name: i for i, name in enumerate(classes)}
    writer = _TileWriter(out, t, read, value_range, geotags, target_uv, target_index, sigma_px, class_index,
                         str((raster or {}).get("source", "")))
    total = len(positives) + n_neg
    n_written_neg = n_hard = n_empty = 0
    try:
        for tile in positives:
            check_cancel(is_canceled)
            writer.write(*tile, keep_empty=True)
            if progress is not None:
                progress(writer.n_tiles / max(1, total))
        for j in order:
            if n_written_neg >= n_neg:
                break
            check_cancel(is_canceled)
            if writer.write(*negatives[j], keep_empty=False):
                n_written_neg += 1
                n_hard += int(is_hard[j])
            else:
                n_empty += 1
            if progress is not None:
                progress(writer.n_tiles / max(1, total))
    finally:
        writer.close()
    seen = np.zeros(len(geotags), dtype=bool)
    seen[sorted(writer.targets_written)] = True
    write_targets(out / "targets.csv", geotags, np.flatnonzero(seen))
    gsd = grid.gsd_cm
    summary = {
        "n_frames": writer.n_tiles,
        "frames": "one per tile (frame_id: the tile's index on the raster's tile grid, row by row)",
        "n_frames_with_labels": len(positives),
        "n_labels": writer.n_rows,
        "n_geotags": len(geotags),
        "n_geotags_in_view": int(seen.sum()),
        "geotags_outside_raster": [_json_id(geotags.ids[i]) for i in np.flatnonzero(~inside)],
        "geotags_on_nodata": [_json_id(geotags.ids[i]) for i in np.flatnonzero(on_nodata)],
        "geotags_never_in_view": [_json_id(geotags.ids[i]) for i in np.flatnonzero(~seen)],
        "classes": classes,
        "sigma_px": round(sigma_px, 6),
        "sigma_cm": request.sigma_cm,
        "sigma_source": {"source": "given", "parameter": "SIGMA_CM", "rule": "σ px = σ cm / GSD"},
        "label_radius_px": round(radius, 6),
        "provenance": {p: {"n_targets": int((geotags.provenance == p).sum()),
                           "n_in_view": int((seen & (geotags.provenance == p)).sum())} for p in PROVENANCES},
        "hard_negatives": {"n_clusters": len(hard_uv), "n_in_raster": int(_in_raster(grid, hard_uv).sum())},
        "n_unresolved_in_raster": int(_in_raster(grid, _pixels(grid, unresolved)).sum()),
        "surveyed_area": None if surveyed is None else surveyed.to_dict(),
        "tiles": {"size": t, "positive": len(positives), "negative": n_written_neg, "hard_negative": n_hard,
                  "skipped": {"unlabelled_target": n_ignored,
                              "outside_surveyed_area": int(len(candidates) - len(negatives)),
                              "no_data": n_empty}},
        "raster": {**(raster or {}), "width": grid.width, "height": grid.height, "pixel_x": grid.pixel_x,
                   "pixel_y": grid.pixel_y, "metres_per_unit": grid.metres_per_unit, "gsd_cm": gsd,
                   "tile_diagonal_m": round(t * np.sqrt(2.0) * gsd / 100.0, 4)},
        "raster_encoding": "uint8 PNG, 255·exp(−r²/2σ²) to r = 3σ, max-combined",
    }
    (out / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
    return summary


class _TileWriter:
    """Writes tiles, their labels and their labels.csv / labels.txt rows; counts what it wrote."""

    def __init__(self, out: Path, tile: int, read, value_range, geotags, target_uv, target_index, sigma_px,
                 class_index, image: str):
        self.out, self.tile, self.read, self.value_range = out, tile, read, value_range
        self.geotags, self.uv, self.index = geotags, target_uv, target_index
        self.sigma_px, self.class_index, self.image = sigma_px, class_index, image
        self.radius = LABEL_RADIUS_SIGMAS * sigma_px
        self.n_tiles = self.n_rows = 0
        self.targets_written: set = set()
        self._csv_file = open(out / "labels.csv", "w", newline="", encoding="utf-8")
        self._txt = open(out / "labels.txt", "w", encoding="utf-8")
        self._csv = csv.writer(self._csv_file)
        self._csv.writerow(LABELS_CSV_FIELDS)

    def close(self) -> None:
        self._csv_file.close()
        self._txt.close()

    def write(self, frame_id: int, y0: int, x0: int, keep_empty: bool) -> bool:
        """Read and write one tile; False (nothing written) when it holds no valid pixel and not ``keep_empty``."""
        import cv2

        t = self.tile
        planes, valid = self.read(x0, y0, t, t)
        if not keep_empty and not valid.any():
            return False
        rgb = to_8bit(planes, self.value_range)
        bgr = np.ascontiguousarray(np.stack([rgb[2], rgb[1], rgb[0]], axis=-1) * valid[..., None].astype(np.uint8))
        distance = tile_distance(self.uv, x0, y0, t)
        near = np.flatnonzero(distance <= self.radius)
        local = self.uv[near] - [x0, y0]
        label = soft_label_raster(t, t, local, self.sigma_px)
        name = f"{frame_id}_{y0}_{x0}.png"
        cv2.imwrite(str(self.out / "tiles" / "images" / name), bgr)
        cv2.imwrite(str(self.out / "tiles" / "labels" / name), label)
        geotags = self.geotags
        for k in near:
            g = int(self.index[k])
            (u, v), margin = self.uv[k], _margin(self.uv[k], x0, y0, t, distance[k])
            self._csv.writerow([frame_id, self.image, geotags.ids[g], geotags.labels[g], f"{u:.3f}", f"{v:.3f}",
                                f"{self.sigma_px:g}", f"{margin:.1f}", geotags.provenance[g]])
            self.targets_written.add(g)
        self.n_rows += len(near)
        centred = near[inside_tile(self.uv[near], x0, y0, t)]
        if len(centred):
            classes = [self.class_index[str(geotags.labels[self.index[k]])] for k in centred]
            self._txt.write(f"{frame_id} tiles/images/{name} " + " ".join(
                f"{self.uv[k, 0] - x0:.2f},{self.uv[k, 1] - y0:.2f},{c}" for k, c in zip(centred, classes)) + "\n")
        self.n_tiles += 1
        return True


def _surveyed_test(grid: RasterGrid, surveyed, to_lat_lon: ToLatLon | None, geotags: Geotags, t: int):
    """origins [(y0, x0), …] → mask of the tiles whose ground outline lies wholly in the surveyed area (all of them
    without one). The area is placed in a local frame at the raster's centre, at the geotags' median height."""
    if surveyed is None:
        return lambda origins: np.ones(len(origins), dtype=bool)
    c_lat, c_lon = to_lat_lon(*grid.to_map(np.array([0.0, grid.width - 1.0]), np.array([0.0, grid.height - 1.0])))
    heights = geotags.height[np.isfinite(geotags.height)]
    local = LocalFrame.around(c_lat, c_lon, heights if len(heights) else None)
    area = surveyed.placed(local)

    def test(origins):
        if not origins:
            return np.zeros(0, dtype=bool)
        outlines = tile_outlines_px(origins, t)
        lat, lon = to_lat_lon(*grid.to_map(outlines[..., 0].ravel(), outlines[..., 1].ravel()))
        xy = local.from_geodetic(lat, lon, np.full(len(lat), local.h0))[:, :2]
        return area.contains_polygons(xy.reshape(outlines.shape))
    return test


def _pixels(grid: RasterGrid, xy) -> np.ndarray:
    """Raster pixels (n, 2) of map positions ``xy`` = (x, y) arrays; none for None."""
    if xy is None:
        return np.empty((0, 2))
    col, row = grid.to_pixel(np.asarray(xy[0], dtype=float), np.asarray(xy[1], dtype=float))
    return np.column_stack([col, row]).reshape(-1, 2)


def _in_raster(grid: RasterGrid, uv) -> np.ndarray:
    """Which pixels (n, 2) lie on the raster (each pixel's square from −0.5 to +0.5)."""
    return (uv[:, 0] >= -0.5) & (uv[:, 0] < grid.width - 0.5) & (uv[:, 1] >= -0.5) & (uv[:, 1] < grid.height - 0.5)


def _margin(uv, x0, y0, t, distance) -> float:
    """Distance (px) of a point to the tile's nearest edge: positive inside, negative outside."""
    if distance > 0:
        return -float(distance)
    return float(min(uv[0] - (x0 - 0.5), x0 + t - 0.5 - uv[0], uv[1] - (y0 - 0.5), y0 + t - 0.5 - uv[1]))


def _json_id(value):
    return value.item() if hasattr(value, "item") else value

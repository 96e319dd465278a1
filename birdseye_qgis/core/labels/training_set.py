"""Projected labels: every geotag in every frame that sees it, written as a training set.

One output folder per run (docs/design.md#labels) holds

* ``labels.csv`` — ``frame_id, image, geotag_id, label, u, v, sigma_px, margin_px, provenance``: u, v
  in the original (distorted) image, OpenCV pixel-centre convention; one row per target per frame in
  view; ``provenance`` says where the target came from: ``survey`` (a geotag) or ``review`` (a cluster
  the review confirmed real that no geotag matches, :mod:`..scoring.reviewed_clusters`);
* ``labels.txt`` — the reference payload's line format ``idx path u,v,cls [u,v,cls ...]``, one line
  per frame with labels (``cls`` = index of the label in ``summary.json``'s ``classes``);
* ``rasters/<frame_id>.png`` — one soft-label raster per frame, the image's size, 8-bit:
  ``round(255 · exp(−r² / 2σ²))`` drawn out to r = 3σ, overlapping humps combined by max;
* optionally ``tiles/images`` + ``tiles/labels`` (image and label tiles side by side; negative tiles
  that hold a hard negative — a cluster the review rejected — are drawn before the others) and
  ``coco_keypoints.json`` (COCO keypoints, one "centre" keypoint per label, pixel-centre coordinates);
* ``summary.json`` — counts: frames with labels, labels per frame, frames per geotag, geotags never
  in view, edge cases; targets and labels per provenance; hard negatives and their tiles.

A geotag whose projection lies inside the image but within ``edge_buffer_px`` of its border is
reported as "edge" and not written as a positive. Writing streams frame by frame: memory does not
grow with the number of frames (only the small per-label rows are kept for the summary).
"""
from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import check_cancel
from ..field.geotags import PROVENANCES, REVIEW, UNLABELLED, Geotags
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround
from ..geometry.heights import ELLIPSOIDAL_REFERENCE, convert_heights
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import Projection, project_in_view
from .sparse_png import encode_gray_png

LABELS_CSV_FIELDS = ["frame_id", "image", "geotag_id", "label", "u", "v", "sigma_px", "margin_px", "provenance"]
#: A label is drawn out to this many σ (rasters and COCO boxes), so a label of radius r px has σ_label = r / 3.
LABEL_RADIUS_SIGMAS = 3.0


def label_sigma_px(radius_px: float) -> float:
    """σ_label (px) of labels of radius ``radius_px`` (the sensor bound's tolerance r): r / 3."""
    return radius_px / LABEL_RADIUS_SIGMAS


def review_label_inputs(clusters, survey: Geotags) -> tuple[Geotags, Geotags]:
    """What a review adds to a label set, from :class:`..scoring.reviewed_clusters.ReviewedCluster`
    objects: the targets (clusters confirmed real that no geotag matches; provenance review) and the
    hard negatives, each at its cluster's centroid and on the ground each frame sees (no height).

    A review target takes the survey's class when the survey has one; with several classes the
    cluster's is unknown and it is labelled ``target``.
    """
    classes = sorted({str(x) for x in survey.labels})
    label = classes[0] if len(classes) == 1 else UNLABELLED

    def spots(chosen, name, provenance):
        return Geotags([c.key for c in chosen], [c.lat for c in chosen], [c.lon for c in chosen],
                       np.full(len(chosen), np.nan), [name] * len(chosen), [provenance] * len(chosen))

    return (spots([c for c in clusters if c.is_target], label, REVIEW),
            spots([c for c in clusters if c.is_hard_negative], "hard_negative", REVIEW))


@dataclass
class FrameLabels:
    """The labels of one frame: geotag indices, pixels and margins; ``edge`` ones are not positives."""

    frame_index: int
    geotag_index: np.ndarray
    uv: np.ndarray
    margin_px: np.ndarray
    edge: np.ndarray
    n_occluded: int = 0


@dataclass
class LabelSetResult:
    """What was written: the summary (also in summary.json) and per-geotag / per-frame counts."""

    summary: dict
    frames_per_geotag: np.ndarray
    labels_per_frame: np.ndarray


@dataclass
class LabelRequest:
    sigma_px: float = 10.0
    edge_buffer_px: float = 0.0
    write_rasters: bool = True
    tile_size: int = 0
    negative_ratio: float = 1.0
    seed: int = 0
    coco: bool = False
    classes: list = field(default_factory=list)


def project_labels(poses: FramePoses, geotags: Geotags, edge_buffer_px: float = 0.0,
                   local: LocalFrame | None = None,
                   ground=None, geotag_heights: bool = False) -> list[FrameLabels]:
    """Labels of every frame (in frame order; frames with nothing in view get an empty entry).

    Geotags are placed on the ground each frame sees, so a rover antenna height never shifts a label.
    ``ground`` builds the ground model from a :class:`FrameGeometry` (default: the level plane at the
    altimeter depth; e.g. a DEM's ``DemGround.from_dem``). With the level plane, frames without a
    ground height (no usable altimeter reading) get no labels: :func:`frames_without_ground` tells
    which, so callers can report them. A ground model that can tell occlusion (a DEM) drops geotags
    hidden behind terrain and counts them in ``n_occluded``.

    ``geotag_heights`` (frames of a camera solution whose heights are ellipsoidal, flag
    ``geotag_heights``): there is no altimeter, and the geotags' own surveyed heights are the truth, so
    a geotag with a height is projected where it is; one without a height goes onto the ground model,
    whose level plane lies, for frames without a ground height, at the median surveyed geotag height
    (the flight's ground).
    """
    local = local or LocalFrame.around(np.append(poses.lat, geotags.lat), np.append(poses.lon, geotags.lon),
                                       poses.height)
    empty = [FrameLabels(f, np.empty(0, np.int64), np.empty((0, 2)), np.empty(0), np.empty(0, bool))
             for f in range(len(poses))]
    own_height = np.isfinite(geotags.height) if geotag_heights else np.zeros(len(geotags), dtype=bool)
    surveyed = np.nan_to_num(geotags.height, nan=0.0)
    if geotag_heights and own_height.any():
        # Surveyed heights are ellipsoidal; the frames' heights are in their own reference.
        surveyed = np.where(own_height, convert_heights(surveyed, geotags.lat, geotags.lon, ELLIPSOIDAL_REFERENCE,
                                                        poses.reference), 0.0)
        flight_ground = float(np.median(surveyed[own_height]))
        poses = replace(poses, ground_height=np.where(np.isfinite(poses.ground_height), poses.ground_height,
                                                      flight_ground))
    usable = np.flatnonzero(~frames_without_ground(poses)) if ground is None else np.arange(len(poses))
    if len(usable) == 0 or len(geotags) == 0:
        return empty
    geom = FrameGeometry(poses.subset(usable), local)
    ground_model = (ground or LevelPlaneGround)(geom)
    pts = local.from_geodetic(geotags.lat, geotags.lon, surveyed)
    parts = []
    for own in (True, False):
        which = np.flatnonzero(own_height == own)
        if len(which) == 0:
            continue
        proj = project_in_view(geom, pts[which], None if own else ground_model, edge_buffer_px,
                               prefilter_ground=ground_model, keep_edge=True)
        proj.point_idx = which[proj.point_idx]
        placed = pts[proj.point_idx] if own else ground_model.place(proj.frame_idx, pts[proj.point_idx])
        parts.append((proj, placed))
    proj = Projection(*(np.concatenate([getattr(p, name) for p, _ in parts]) for name in Projection.FIELDS))
    occluded = np.zeros(len(proj.frame_idx), dtype=bool)
    if hasattr(ground_model, "occluded") and len(proj.frame_idx):
        occluded = ground_model.occluded(proj.frame_idx, np.concatenate([placed for _, placed in parts]))
    n_occluded = np.bincount(proj.frame_idx[occluded], minlength=len(usable))
    proj = proj.select(~occluded)
    order = np.lexsort((proj.point_idx, proj.frame_idx))
    proj = proj.select(order)
    bounds = np.searchsorted(proj.frame_idx, np.arange(len(usable) + 1))
    for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        f = int(usable[k])
        empty[f] = FrameLabels(f, proj.point_idx[a:b], proj.uv[a:b], proj.margin_px[a:b], ~proj.in_frame[a:b],
                               int(n_occluded[k]))
    return empty


def frames_without_ground(poses: FramePoses) -> np.ndarray:
    """Mask of frames whose level ground is unknown (no usable altimeter reading)."""
    return ~np.isfinite(poses.ground_height)


def soft_label_raster(width: int, height: int, uv: np.ndarray, sigma_px: float) -> np.ndarray:
    """8-bit soft-label raster: Gaussian humps of σ px centred on ``uv``, cut at 3σ, combined by max."""
    out = np.zeros((height, width), dtype=np.uint8)
    radius = int(np.ceil(LABEL_RADIUS_SIGMAS * sigma_px))
    offsets = np.arange(-radius, radius + 1)
    for u, v in np.asarray(uv, dtype=float).reshape(-1, 2):
        cu, cv = int(round(u)), int(round(v))
        xs, ys = cu + offsets, cv + offsets
        x_ok, y_ok = (xs >= 0) & (xs < width), (ys >= 0) & (ys < height)
        if not x_ok.any() or not y_ok.any():
            continue
        xs, ys = xs[x_ok], ys[y_ok]
        r2 = (ys[:, None] - v) ** 2 + (xs[None, :] - u) ** 2
        hump = np.where(r2 <= LABEL_RADIUS_SIGMAS ** 2 * sigma_px ** 2,
                        np.rint(255.0 * np.exp(-r2 / (2.0 * sigma_px ** 2))), 0)
        block = out[ys[0]:ys[-1] + 1, xs[0]:xs[-1] + 1]
        np.maximum(block, hump.astype(np.uint8), out=block)
    return out


def tile_origins(length: int, tile: int) -> list[int]:
    """Tile starts covering [0, length): a regular grid, the last tile flush with the border."""
    if length <= tile:
        return [0]
    starts = list(range(0, length - tile + 1, tile))
    if starts[-1] + tile < length:
        starts.append(length - tile)
    return starts


def write_label_set(poses: FramePoses, images, geotags: Geotags, frame_labels: list[FrameLabels],
                    out_dir, request: LabelRequest, progress=None, is_canceled=None,
                    hard_negatives: Geotags | None = None,
                    hard_negative_labels: list[FrameLabels] | None = None) -> "LabelSetResult":
    """Write labels.csv, labels.txt, rasters, tiles and COCO for the projected labels of one camera."""
    with LabelWriter(out_dir, geotags, request, hard_negatives) as writer:
        writer.add_frames(poses, images, frame_labels, progress, is_canceled, hard_negative_labels)
    return writer.result


class LabelWriter:
    """Streams frames into one label folder; frames of several cameras can be added in turn.

    Use as a context manager; ``result`` holds the summary once it is closed. ``hard_negatives`` are
    spots the review rejected; their projections (``add_frames``' ``hard_negative_labels``) only decide
    which negative tiles are drawn first.
    """

    def __init__(self, out_dir, geotags: Geotags, request: LabelRequest, hard_negatives: Geotags | None = None):
        self.out = Path(out_dir)
        self.out.mkdir(parents=True, exist_ok=True)
        self.geotags, self.request = geotags, request
        self.classes = request.classes or sorted({str(x) for x in geotags.labels})
        self.class_index = {name: i for i, name in enumerate(self.classes)}
        self.rng = np.random.default_rng(request.seed)
        self.raster_dir = self.out / "rasters"
        if request.write_rasters:
            self.raster_dir.mkdir(exist_ok=True)
        if request.tile_size:
            (self.out / "tiles" / "images").mkdir(parents=True, exist_ok=True)
            (self.out / "tiles" / "labels").mkdir(parents=True, exist_ok=True)
        self.coco = {"images": [], "annotations": [],
                     "categories": [{"id": i + 1, "name": c, "supercategory": "target",
                                     "keypoints": ["centre"], "skeleton": []}
                                    for i, c in enumerate(self.classes)]} if request.coco else None
        self.frames_per_geotag = np.zeros(len(geotags), dtype=np.int64)
        self.hard_negatives = hard_negatives
        self.frames_per_hard_negative = np.zeros(0 if hard_negatives is None else len(hard_negatives), np.int64)
        self.n_tiles_hard = self.n_frames_hard = 0
        self.labels_by_provenance = dict.fromkeys(PROVENANCES, 0)
        self.seen_at_edge = np.zeros(len(geotags), dtype=bool)
        self.labels_per_frame: list[int] = []
        self.missing_images: list[str] = []
        self.n_edge = self.n_occluded = self.n_tiles_pos = self.n_tiles_neg = 0
        self.result: LabelSetResult | None = None
        self._csv_file = open(self.out / "labels.csv", "w", newline="", encoding="utf-8")
        self._txt_file = open(self.out / "labels.txt", "w", encoding="utf-8")
        self._csv = csv.writer(self._csv_file)
        self._csv.writerow(LABELS_CSV_FIELDS)

    def __enter__(self) -> "LabelWriter":
        return self

    def __exit__(self, exc_type, exc, tb) -> None:
        self._csv_file.close()
        self._txt_file.close()
        if exc_type is None:
            self.result = self._finish()

    def add_frames(self, poses: FramePoses, images, frame_labels: list[FrameLabels], progress=None,
                   is_canceled=None, hard_negative_labels: list[FrameLabels] | None = None) -> np.ndarray:
        """Write the frames of one camera; returns the number of labels written per frame.

        ``hard_negative_labels``: the hard negatives projected like the targets (same frame order)."""
        counts = np.zeros(len(frame_labels), dtype=np.int64)
        for k, fl in enumerate(frame_labels):
            check_cancel(is_canceled)
            hard = hard_negative_labels[k] if hard_negative_labels is not None else None
            counts[k] = self._add_frame(poses, str(images[fl.frame_index]), fl, hard)
            if progress is not None:
                progress((k + 1) / max(1, len(frame_labels)))
        return counts

    def _add_frame(self, poses: FramePoses, image: str, fl: FrameLabels, hard: FrameLabels | None) -> int:
        request, geotags, cam = self.request, self.geotags, poses.camera
        pos = ~fl.edge
        self.n_edge += int(fl.edge.sum())
        self.n_occluded += fl.n_occluded
        self.seen_at_edge[fl.geotag_index[fl.edge]] = True
        gi, uv, margin = fl.geotag_index[pos], fl.uv[pos], fl.margin_px[pos]
        frame_id = poses.frame_id[fl.frame_index]
        idx = len(self.labels_per_frame)
        self.labels_per_frame.append(len(gi))
        self.frames_per_geotag[gi] += 1
        for p in geotags.provenance[gi]:
            self.labels_by_provenance[p] += 1
        names = [str(geotags.labels[g]) for g in gi]
        for g, (u, v), m, name in zip(gi, uv, margin, names):
            self._csv.writerow([frame_id, image, geotags.ids[g], name, f"{u:.3f}", f"{v:.3f}",
                                f"{request.sigma_px:g}", f"{m:.1f}", geotags.provenance[g]])
        if len(gi):
            self._txt_file.write(f"{idx} {image} " + " ".join(
                f"{u:.2f},{v:.2f},{self.class_index[n]}" for (u, v), n in zip(uv, names)) + "\n")
        raster = None
        if request.write_rasters or request.tile_size:
            raster = soft_label_raster(cam.width, cam.height, uv, request.sigma_px)
        if request.write_rasters:
            (self.raster_dir / f"{frame_id}.png").write_bytes(encode_gray_png(raster))
        # Edge projections of a hard negative still lie in the image: its tile is still a hard one.
        hard_uv = np.empty((0, 2)) if hard is None else hard.uv
        if hard is not None and len(hard.geotag_index):
            self.frames_per_hard_negative[np.unique(hard.geotag_index)] += 1
            self.n_frames_hard += 1
        if request.tile_size:
            tiles = _write_tiles(self.out / "tiles", frame_id, image, raster, uv, request, self.rng, hard_uv)
            if tiles is None:
                self.missing_images.append(image)
            else:
                self.n_tiles_pos += tiles[0]
                self.n_tiles_neg += tiles[1]
                self.n_tiles_hard += tiles[2]
        if self.coco is not None:
            _add_coco(self.coco, frame_id, image, cam, uv, names, self.class_index, request.sigma_px)
        return len(gi)

    def _finish(self) -> "LabelSetResult":
        request, geotags = self.request, self.geotags
        if self.coco is not None:
            (self.out / "coco_keypoints.json").write_text(json.dumps(self.coco), encoding="utf-8")
        lpf = np.asarray(self.labels_per_frame, dtype=np.int64)
        fpg = self.frames_per_geotag
        summary = {
            "n_frames": len(lpf),
            "n_frames_with_labels": int((lpf > 0).sum()),
            "n_labels": int(lpf.sum()),
            "n_edge": self.n_edge,
            "n_occluded": self.n_occluded,
            "labels_per_frame": _stats(lpf[lpf > 0]),
            "frames_per_geotag": _stats(fpg[fpg > 0]),
            "n_geotags": len(geotags),
            "n_geotags_in_view": int((fpg > 0).sum()),
            "geotags_never_in_view": [_json_id(geotags.ids[i])
                                      for i in np.flatnonzero((fpg == 0) & ~self.seen_at_edge)],
            "geotags_only_at_edge": [_json_id(geotags.ids[i])
                                     for i in np.flatnonzero((fpg == 0) & self.seen_at_edge)],
            "classes": self.classes,
            "sigma_px": request.sigma_px,
            "edge_buffer_px": request.edge_buffer_px,
            "provenance": {p: {"n_targets": int((geotags.provenance == p).sum()),
                               "n_in_view": int(((fpg > 0) & (geotags.provenance == p)).sum()),
                               "n_labels": int(self.labels_by_provenance[p])} for p in PROVENANCES},
            "hard_negatives": {"n_clusters": len(self.frames_per_hard_negative),
                               "n_in_view": int((self.frames_per_hard_negative > 0).sum()),
                               "n_frames": int(self.n_frames_hard)},
            "tiles": {"size": request.tile_size, "positive": self.n_tiles_pos, "negative": self.n_tiles_neg,
                      "hard_negative": self.n_tiles_hard,
                      "missing_images": self.missing_images} if request.tile_size else None,
            "raster_encoding": "uint8 PNG, 255·exp(−r²/2σ²) to r = 3σ, max-combined",
        }
        (self.out / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
        return LabelSetResult(summary, fpg, lpf)


def _inside(uv, x0, y0, t) -> np.ndarray:
    if not len(uv):
        return np.zeros(0, bool)
    return (uv[:, 0] >= x0 - 0.5) & (uv[:, 0] < x0 + t - 0.5) & (uv[:, 1] >= y0 - 0.5) & (uv[:, 1] < y0 + t - 0.5)


def _write_tiles(tile_dir: Path, frame_id, image, raster, uv, request: LabelRequest, rng, hard_uv=()):
    """Cut image and raster into tiles: every positive tile, a seeded sample of negatives.

    Negative tiles holding a hard negative (``hard_uv``) fill the sample first, since they teach what the
    detector got wrong; the rest of the sample is drawn from the other negatives.
    Returns (positives, negatives, hard negatives among them) written, or None when the image cannot be
    read.
    """
    import cv2

    img = cv2.imread(image, cv2.IMREAD_COLOR)
    if img is None:
        return None
    t = request.tile_size
    h, w = raster.shape
    hard_uv = np.asarray(hard_uv, dtype=float).reshape(-1, 2)
    positives, hard, negatives = [], [], []
    for y0 in tile_origins(h, t):
        for x0 in tile_origins(w, t):
            if _inside(uv, x0, y0, t).any():
                positives.append((y0, x0))
            else:
                (hard if _inside(hard_uv, x0, y0, t).any() else negatives).append((y0, x0))
    n_neg = min(len(hard) + len(negatives), int(round(request.negative_ratio * max(1, len(positives)))))
    n_hard = min(len(hard), n_neg)
    keep_hard = [hard[i] for i in sorted(rng.choice(len(hard), n_hard, replace=False))] if n_hard else []
    n_plain = n_neg - n_hard
    keep_neg = [negatives[i] for i in sorted(rng.choice(len(negatives), n_plain, replace=False))] if n_plain else []
    for y0, x0 in positives + keep_hard + keep_neg:
        name = f"{frame_id}_{y0}_{x0}.png"
        cv2.imwrite(str(tile_dir / "images" / name), img[y0:y0 + t, x0:x0 + t])
        cv2.imwrite(str(tile_dir / "labels" / name), raster[y0:y0 + t, x0:x0 + t])
    return len(positives), len(keep_hard) + len(keep_neg), len(keep_hard)


def _add_coco(coco: dict, frame_id, image, cam, uv, names, class_index, sigma_px) -> None:
    image_id = len(coco["images"]) + 1
    coco["images"].append({"id": image_id, "file_name": image, "width": cam.width, "height": cam.height,
                           "frame_id": _json_id(frame_id)})
    half = LABEL_RADIUS_SIGMAS * sigma_px
    for (u, v), name in zip(uv, names):
        coco["annotations"].append({
            "id": len(coco["annotations"]) + 1, "image_id": image_id, "category_id": class_index[name] + 1,
            "keypoints": [round(float(u), 3), round(float(v), 3), 2], "num_keypoints": 1,
            "bbox": [round(float(u) - half, 3), round(float(v) - half, 3), 2 * half, 2 * half],
            "area": (2 * half) ** 2, "iscrowd": 0})


def _stats(values: np.ndarray) -> dict:
    if len(values) == 0:
        return {"mean": 0.0, "median": 0.0, "min": 0, "max": 0}
    return {"mean": round(float(values.mean()), 3), "median": float(np.median(values)),
            "min": int(values.min()), "max": int(values.max())}


def _json_id(value):
    return value.item() if hasattr(value, "item") else value

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
  in view, edge cases; targets and labels per provenance; hard negatives and their tiles; the tiles skipped
  and why; the σ used and where it came from; the surveyed area; the relief check (:mod:`.relief`);
* ``targets.csv`` — ``geotag_id, label, provenance, lat, lon, height_m, height_ref``: one row per target
  written to labels.csv, WGS84 degrees, the target's height in the reference it carries (a geotag's is
  ellipsoidal; a review target has none: both fields empty).

A geotag whose projection lies inside the image but within ``edge_buffer_px`` of its border is
reported as "edge" and not written as a positive. Writing streams frame by frame: memory does not
grow with the number of frames (only the small per-label rows are kept for the summary).

**No tile teaches a target as background.** A tile is written as negative only when nothing in it may be a
target nobody labelled; it is skipped (not written at all, positive or not: an ignore mask would need the
trainer to read one) when within the label radius (3σ) of it lies

* a target in view but not labelled: inside the edge buffer, or just beyond the image border (its centre
  outside, its label disc reaching in: ``project_labels``' ``reach_px``);
* a cluster the review left unresolved (uncertain, unreviewed, conflicting): it may be a target.

A frame whose targets could not be placed (no ground height) gets no tiles: its view is unknown. A tile that
holds no positive and whose ground footprint is not wholly inside the surveyed area
(:mod:`..field.surveyed_area`) is skipped too: an unsurveyed target may lie there. Positives are kept anywhere.
summary.json counts the tiles skipped for each reason. Targets hidden behind terrain (a DEM) are not in the
image, and their tiles show background truly. The frame rasters and COCO cover whole frames and carry no ignore
marks: train from the tiles.
"""
from __future__ import annotations

import csv
import json
from dataclasses import dataclass, field, replace
from pathlib import Path

import numpy as np

from ..errors import InputError, check_cancel
from ..field.geotags import PROVENANCES, REVIEW, UNLABELLED, Geotags
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import GroundModel, LevelPlaneGround
from ..geometry.heights import ELLIPSOIDAL_REFERENCE, VerticalReference, convert_heights
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import Projection, pixel_to_ground, project_in_view
from .relief import ReliefCheck, TargetRelief
from .sparse_png import encode_gray_png

LABELS_CSV_FIELDS = ["frame_id", "image", "geotag_id", "label", "u", "v", "sigma_px", "margin_px", "provenance"]
TARGETS_CSV_FIELDS = ["geotag_id", "label", "provenance", "lat", "lon", "height_m", "height_ref"]
#: A label is drawn out to this many σ (rasters and COCO boxes), so a label of radius r px has σ_label = r / 3.
LABEL_RADIUS_SIGMAS = 3.0
#: Points per side of a tile's ground footprint, for the surveyed-area test (a lens bends the sides a little).
TILE_SIDE_POINTS = 4


def label_sigma_px(radius_px: float) -> float:
    """σ_label (px) of labels of radius ``radius_px`` (the sensor bound's tolerance r): r / 3."""
    return radius_px / LABEL_RADIUS_SIGMAS


def review_label_inputs(clusters, survey: Geotags) -> tuple[Geotags, Geotags, Geotags]:
    """What a review adds to a label set, from :class:`..scoring.reviewed_clusters.ReviewedCluster`
    objects: the targets (clusters confirmed real that no geotag matches; provenance review), the
    hard negatives, and the unresolved clusters (uncertain, unreviewed, conflicting: maybe targets, so no tile
    near one is written), each at its cluster's centroid and on the ground each frame sees (no height).

    A review target takes the survey's class when the survey has one; with several classes the
    cluster's is unknown and it is labelled ``target``.
    """
    classes = sorted({str(x) for x in survey.labels})
    label = classes[0] if len(classes) == 1 else UNLABELLED

    def spots(chosen, name, provenance):
        return Geotags([c.key for c in chosen], [c.lat for c in chosen], [c.lon for c in chosen],
                       np.full(len(chosen), np.nan), [name] * len(chosen), [provenance] * len(chosen))

    return (spots([c for c in clusters if c.is_target], label, REVIEW),
            spots([c for c in clusters if c.is_hard_negative], "hard_negative", REVIEW),
            spots([c for c in clusters if c.is_unresolved], "unresolved", REVIEW))


@dataclass(frozen=True)
class FrameGround:
    """Pixel → ground of one frame, on the ground model its labels were placed on."""

    geometry: FrameGeometry
    model: GroundModel
    index: int

    def to_ground(self, uv) -> np.ndarray:
        """Local east, north (N, 2) of where the pixels' rays meet the ground; NaN where they miss it."""
        uv = np.asarray(uv, dtype=float).reshape(-1, 2)
        pts, valid = pixel_to_ground(self.geometry, self.model, np.full(len(uv), self.index), uv)
        return np.where(valid[:, None], pts[:, :2], np.nan)


@dataclass
class FrameLabels:
    """The labels of one frame: geotag indices, pixels and margins; ``edge`` ones are not positives.

    ``edge`` entries are in view but not labelled: inside the image within the edge buffer (``margin_px`` ≥ 0),
    or beyond its border by at most the reach (``margin_px`` < 0). ``nadir_distance_m`` (r) and ``height_m`` (d):
    each entry's horizontal distance from the camera's nadir and the camera's height above it, on the ground it
    was placed on (:mod:`.relief`). ``ground``: the frame's pixel → ground; None when its targets could not be
    placed (no ground height), so what it shows is unknown.
    """

    frame_index: int
    geotag_index: np.ndarray
    uv: np.ndarray
    margin_px: np.ndarray
    edge: np.ndarray
    n_occluded: int = 0
    nadir_distance_m: np.ndarray = field(default_factory=lambda: np.empty(0))
    height_m: np.ndarray = field(default_factory=lambda: np.empty(0))
    ground: FrameGround | None = None


@dataclass
class LabelSetResult:
    """What was written: the summary (also in summary.json) and per-geotag / per-frame counts."""

    summary: dict
    frames_per_geotag: np.ndarray
    labels_per_frame: np.ndarray


@dataclass
class LabelRequest:
    """What to write. ``sigma_source`` says where σ came from, for summary.json (:func:`write_label_set`)."""

    sigma_px: float = 10.0
    edge_buffer_px: float = 0.0
    write_rasters: bool = True
    tile_size: int = 0
    negative_ratio: float = 1.0
    seed: int = 0
    coco: bool = False
    classes: list = field(default_factory=list)
    sigma_source: dict = field(default_factory=lambda: {"source": "given"})

    @property
    def label_radius_px(self) -> float:
        """The label radius r = 3σ (px): how far a label is drawn, and a target's reach into a tile."""
        return LABEL_RADIUS_SIGMAS * self.sigma_px


def project_labels(poses: FramePoses, geotags: Geotags, edge_buffer_px: float = 0.0,
                   local: LocalFrame | None = None,
                   ground=None, geotag_heights: bool = False, reach_px: float = 0.0) -> list[FrameLabels]:
    """Labels of every frame (in frame order; frames with nothing in view get an empty entry).

    Geotags are placed on the ground each frame sees, so a rover antenna height never shifts a label.
    ``ground`` builds the ground model from a :class:`FrameGeometry` (default: the level plane at the
    altimeter depth; e.g. a DEM's ``DemGround.from_dem``). With the level plane, frames without a
    ground height (no usable altimeter reading) get no labels and no ``ground``: :func:`frames_without_ground`
    tells which, so callers can report them. A ground model that can tell occlusion (a DEM) drops geotags
    hidden behind terrain and counts them in ``n_occluded``.

    ``geotag_heights`` (frames of a camera solution whose heights are ellipsoidal, flag
    ``geotag_heights``): there is no altimeter, and the geotags' own surveyed heights are the truth, so
    a geotag with a height is projected where it is; one without a height goes onto the ground model,
    whose level plane lies, for frames without a ground height, at the median surveyed geotag height
    (the flight's ground).

    ``reach_px``: geotags projected outside the image by at most this much are kept as ``edge`` entries too
    (a target whose centre lies beyond the border but whose label disc of that radius reaches in).
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
    if len(usable) == 0:
        return empty
    geom = FrameGeometry(poses.subset(usable), local)
    ground_model = (ground or LevelPlaneGround)(geom)
    for k, f in enumerate(usable):
        empty[f].ground = FrameGround(geom, ground_model, k)
    if len(geotags) == 0:
        return empty
    pts = local.from_geodetic(geotags.lat, geotags.lon, surveyed)
    parts = []
    for own in (True, False):
        which = np.flatnonzero(own_height == own)
        if len(which) == 0:
            continue
        # A negative buffer grows the image: "in view" here is in front and inside it by the reach.
        proj = project_in_view(geom, pts[which], None if own else ground_model, -float(reach_px),
                               prefilter_ground=ground_model)
        proj.point_idx = which[proj.point_idx]
        placed = pts[proj.point_idx] if own else ground_model.place(proj.frame_idx, pts[proj.point_idx])
        parts.append((proj, placed))
    proj = Projection(*(np.concatenate([getattr(p, name) for p, _ in parts]) for name in Projection.FIELDS))
    placed = np.concatenate([placed for _, placed in parts])
    occluded = np.zeros(len(proj.frame_idx), dtype=bool)
    if hasattr(ground_model, "occluded") and len(proj.frame_idx):
        occluded = ground_model.occluded(proj.frame_idx, placed)
    n_occluded = np.bincount(proj.frame_idx[occluded], minlength=len(usable))
    proj, placed = proj.select(~occluded), placed[~occluded]
    order = np.lexsort((proj.point_idx, proj.frame_idx))
    proj, placed = proj.select(order), placed[order]
    edge = ~geom.camera.in_frame(proj.uv, edge_buffer_px)
    offset = geom.C[proj.frame_idx] - placed
    height = np.einsum("ni,ni->n", offset, geom.up[proj.frame_idx])
    nadir = np.linalg.norm(offset - height[:, None] * geom.up[proj.frame_idx], axis=1)
    bounds = np.searchsorted(proj.frame_idx, np.arange(len(usable) + 1))
    for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
        f = int(usable[k])
        empty[f] = FrameLabels(f, proj.point_idx[a:b], proj.uv[a:b], proj.margin_px[a:b], edge[a:b],
                               int(n_occluded[k]), nadir[a:b], height[a:b], empty[f].ground)
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


def tile_outlines_px(origins, tile: int, per_side: int = TILE_SIDE_POINTS) -> np.ndarray:
    """The outlines (T, 4·per_side, 2) of the tiles at ``origins`` ((y0, x0) each), along their pixels' outer
    edges, clockwise, as (u, v)."""
    corners = np.array([[0.0, 0.0], [tile, 0.0], [tile, tile], [0.0, tile]]) - 0.5
    t = np.arange(per_side)[:, None] / per_side
    outline = np.concatenate([a + t * (b - a) for a, b in zip(corners, np.roll(corners, -1, axis=0))])
    return outline[None, :, :] + np.asarray(origins, dtype=float).reshape(-1, 2)[:, None, ::-1]


def write_label_set(poses: FramePoses, images, geotags: Geotags, frame_labels: list[FrameLabels],
                    out_dir, request: LabelRequest, progress=None, is_canceled=None,
                    hard_negatives: Geotags | None = None,
                    hard_negative_labels: list[FrameLabels] | None = None, surveyed=None,
                    unresolved_labels: list[FrameLabels] | None = None,
                    relief: TargetRelief | None = None) -> "LabelSetResult":
    """Write labels.csv, labels.txt, targets.csv, rasters, tiles and COCO for the projected labels of one camera
    (:class:`LabelWriter` says what the optional arguments do)."""
    with LabelWriter(out_dir, geotags, request, hard_negatives, surveyed, relief) as writer:
        writer.add_frames(poses, images, frame_labels, progress, is_canceled, hard_negative_labels, unresolved_labels)
    return writer.result


class LabelWriter:
    """Streams frames into one label folder; frames of several cameras can be added in turn.

    Use as a context manager; ``result`` holds the summary once it is closed. ``hard_negatives`` are
    spots the review rejected; their projections (``add_frames``' ``hard_negative_labels``) only decide
    which negative tiles are drawn first. ``surveyed``: the surveyed area (:class:`..field.surveyed_area.
    SurveyedArea`) — negative tiles only where it holds their whole ground footprint; None: everywhere.
    ``relief``: each target's relief, for the relief check (:mod:`.relief`); None: no check.
    """

    def __init__(self, out_dir, geotags: Geotags, request: LabelRequest, hard_negatives: Geotags | None = None,
                 surveyed=None, relief: TargetRelief | None = None):
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
        self.surveyed = surveyed
        self._placed_area = (None, None)  # (local frame, the surveyed area placed in it): one per run in practice
        self.relief = None if relief is None else ReliefCheck(relief, request.label_radius_px)
        self.labels_by_provenance = dict.fromkeys(PROVENANCES, 0)
        self.seen_at_edge = np.zeros(len(geotags), dtype=bool)
        self.labels_per_frame: list[int] = []
        self.missing_images: list[str] = []
        self.n_edge = self.n_beyond = self.n_unresolved = self.n_occluded = 0
        self.n_tiles_pos = self.n_tiles_neg = 0
        self.skipped = {"unlabelled_target": 0, "outside_surveyed_area": 0}
        self.frames_unplaced: list = []
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
                   is_canceled=None, hard_negative_labels: list[FrameLabels] | None = None,
                   unresolved_labels: list[FrameLabels] | None = None) -> np.ndarray:
        """Write the frames of one camera; returns the number of labels written per frame.

        ``hard_negative_labels``, ``unresolved_labels``: the hard negatives and the unresolved clusters
        projected like the targets (same frame order; the latter with the same reach, all entries kept)."""
        counts = np.zeros(len(frame_labels), dtype=np.int64)
        for k, fl in enumerate(frame_labels):
            check_cancel(is_canceled)
            hard = hard_negative_labels[k] if hard_negative_labels is not None else None
            unresolved = unresolved_labels[k] if unresolved_labels is not None else None
            counts[k] = self._add_frame(poses, str(images[fl.frame_index]), fl, hard, unresolved)
            if progress is not None:
                progress((k + 1) / max(1, len(frame_labels)))
        return counts

    def _add_frame(self, poses: FramePoses, image: str, fl: FrameLabels, hard: FrameLabels | None,
                   unresolved: FrameLabels | None) -> int:
        request, geotags, cam = self.request, self.geotags, poses.camera
        pos = ~fl.edge
        beyond = fl.edge & (fl.margin_px < 0)
        self.n_edge += int((fl.edge & ~beyond).sum())
        self.n_beyond += int(beyond.sum())
        self.n_occluded += fl.n_occluded
        self.seen_at_edge[fl.geotag_index[fl.edge & ~beyond]] = True
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
        if self.relief is not None and len(gi):
            self.relief.add(frame_id, geotags.ids[gi], gi, fl.nadir_distance_m[pos], fl.height_m[pos],
                            float(np.sqrt(cam.fx * cam.fy)))
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
        unresolved_uv = np.empty((0, 2)) if unresolved is None else unresolved.uv
        self.n_unresolved += len(unresolved_uv)
        if request.tile_size:
            if fl.ground is None:
                self.frames_unplaced.append(_json_id(frame_id))
            else:
                self._add_tiles(frame_id, image, raster, uv, hard_uv, np.vstack([fl.uv[fl.edge], unresolved_uv]),
                                fl.ground)
        if self.coco is not None:
            _add_coco(self.coco, frame_id, image, cam, uv, names, self.class_index, request.sigma_px)
        return len(gi)

    def _add_tiles(self, frame_id, image, raster, uv, hard_uv, ignore_uv, ground: FrameGround) -> None:
        tiles = _write_tiles(self.out / "tiles", frame_id, image, raster, uv, self.request, self.rng, hard_uv,
                             ignore_uv, self._surveyed_test(ground))
        if tiles is None:
            self.missing_images.append(image)
            return
        self.n_tiles_pos += tiles["positive"]
        self.n_tiles_neg += tiles["negative"]
        self.n_tiles_hard += tiles["hard_negative"]
        for reason in self.skipped:
            self.skipped[reason] += tiles[reason]

    def _surveyed_test(self, ground: FrameGround):
        """Which tiles (origins (y0, x0)) of the frame have their whole ground footprint in the surveyed area."""
        t = self.request.tile_size
        if self.surveyed is None:
            return lambda origins: np.ones(len(origins), dtype=bool)
        local = ground.geometry.local
        if self._placed_area[0] is not local:
            self._placed_area = (local, self.surveyed.placed(local))
        area = self._placed_area[1]

        def test(origins):
            if not origins:
                return np.zeros(0, dtype=bool)
            outlines = tile_outlines_px(origins, t)
            return area.contains_polygons(ground.to_ground(outlines.reshape(-1, 2)).reshape(outlines.shape))
        return test

    def _finish(self) -> "LabelSetResult":
        request, geotags = self.request, self.geotags
        if self.coco is not None:
            (self.out / "coco_keypoints.json").write_text(json.dumps(self.coco), encoding="utf-8")
        lpf = np.asarray(self.labels_per_frame, dtype=np.int64)
        fpg = self.frames_per_geotag
        write_targets(self.out / "targets.csv", geotags, np.flatnonzero(fpg > 0))
        summary = {
            "n_frames": len(lpf),
            "n_frames_with_labels": int((lpf > 0).sum()),
            "n_labels": int(lpf.sum()),
            "n_edge": self.n_edge,
            "n_beyond_border": self.n_beyond,
            "n_unresolved_in_view": self.n_unresolved,
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
            "sigma_source": request.sigma_source,
            "label_radius_px": request.label_radius_px,
            "edge_buffer_px": request.edge_buffer_px,
            "provenance": {p: {"n_targets": int((geotags.provenance == p).sum()),
                               "n_in_view": int(((fpg > 0) & (geotags.provenance == p)).sum()),
                               "n_labels": int(self.labels_by_provenance[p])} for p in PROVENANCES},
            "hard_negatives": {"n_clusters": len(self.frames_per_hard_negative),
                               "n_in_view": int((self.frames_per_hard_negative > 0).sum()),
                               "n_frames": int(self.n_frames_hard)},
            "surveyed_area": None if self.surveyed is None else self.surveyed.to_dict(),
            "tiles": {"size": request.tile_size, "positive": self.n_tiles_pos, "negative": self.n_tiles_neg,
                      "hard_negative": self.n_tiles_hard,
                      "skipped": {**self.skipped, "frames_without_ground": len(self.frames_unplaced)},
                      "frames_without_ground": self.frames_unplaced,
                      "missing_images": self.missing_images} if request.tile_size else None,
            "relief": None if self.relief is None else self.relief.summary(),
            "raster_encoding": "uint8 PNG, 255·exp(−r²/2σ²) to r = 3σ, max-combined",
        }
        (self.out / "summary.json").write_text(json.dumps(summary, indent=2), encoding="utf-8")
        return LabelSetResult(summary, fpg, lpf)


def read_targets(folder) -> Geotags | None:
    """The targets of a Write-labels folder, as :func:`write_targets` wrote them to ``targets.csv``; None when the
    folder has none (written before it existed). Heights are ellipsoidal (``height_ref``); an empty height (a
    review target) reads as NaN. A row whose height is in another reference, or not a number, is refused with
    its row and field."""
    path = Path(folder) / "targets.csv"
    if not path.is_file():
        return None
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        missing = [name for name in TARGETS_CSV_FIELDS if name not in (reader.fieldnames or ())]
        if missing:
            raise InputError(f"is not a targets.csv of Write training labels: no column {', '.join(missing)}",
                             source=str(path))
        rows = list(reader)
    heights = []
    for row_number, row in enumerate(rows, start=2):  # the header is line 1
        text = (row["height_m"] or "").strip()
        if not text:
            heights.append(np.nan)
            continue
        reference = VerticalReference.parse(row["height_ref"], str(path), row_number, "height_ref")
        if reference != ELLIPSOIDAL_REFERENCE:
            raise InputError(f"the height is {reference.describe()}; targets.csv holds ellipsoidal heights (WGS84)",
                             source=str(path), row=row_number, field="height_ref")
        try:
            heights.append(float(text))
        except ValueError as exc:
            raise InputError(f"{text!r} is not a height in metres", source=str(path), row=row_number,
                             field="height_m") from exc
    try:
        lat, lon = [float(r["lat"]) for r in rows], [float(r["lon"]) for r in rows]
    except ValueError as exc:
        raise InputError(f"is not a targets.csv of Write training labels ({exc})", source=str(path)) from exc
    return Geotags([r["geotag_id"] for r in rows], lat, lon, heights, [r["label"] or "target" for r in rows],
                   [r["provenance"] or "survey" for r in rows], source=str(path))


def write_targets(path: Path, geotags: Geotags, written) -> None:
    """targets.csv: the targets ``written`` (geotag indices, in order) to labels.csv (module docstring)."""
    with open(path, "w", newline="", encoding="utf-8") as f:
        out = csv.writer(f)
        out.writerow(TARGETS_CSV_FIELDS)
        for g in written:
            h = float(geotags.height[g])
            known = np.isfinite(h)
            out.writerow([geotags.ids[g], geotags.labels[g], geotags.provenance[g], f"{geotags.lat[g]:.9f}",
                          f"{geotags.lon[g]:.9f}", f"{h:.3f}" if known else "",
                          ELLIPSOIDAL_REFERENCE.text if known else ""])


def inside_tile(uv, x0, y0, t) -> np.ndarray:
    """Which points of ``uv`` (n, 2) lie in the t × t px tile at (x0, y0): pixel centres at integers, a pixel's
    square from −0.5 to +0.5. The rule tiles are cut by, and Train detector's positive tiles are told by."""
    if not len(uv):
        return np.zeros(0, bool)
    return (uv[:, 0] >= x0 - 0.5) & (uv[:, 0] < x0 + t - 0.5) & (uv[:, 1] >= y0 - 0.5) & (uv[:, 1] < y0 + t - 0.5)


def tile_distance(uv, x0, y0, t, t_rows: int | None = None) -> np.ndarray:
    """Distance (px) of each point of ``uv`` (n, 2) from the t × t px tile at (x0, y0) — t × ``t_rows`` when given —
    measured to its pixels' outer edges; 0 inside."""
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    rows = t if t_rows is None else t_rows
    du = np.maximum(np.maximum(x0 - 0.5 - uv[:, 0], uv[:, 0] - (x0 + t - 0.5)), 0.0)
    dv = np.maximum(np.maximum(y0 - 0.5 - uv[:, 1], uv[:, 1] - (y0 + rows - 0.5)), 0.0)
    return np.hypot(du, dv)


def _near(uv, x0, y0, t, radius) -> bool:
    """Whether a point of ``uv`` lies within ``radius`` px of the tile (its pixels' outer edges)."""
    return bool(np.any(tile_distance(uv, x0, y0, t) <= radius))


def _write_tiles(tile_dir: Path, frame_id, image, raster, uv, request: LabelRequest, rng, hard_uv=(),
                 ignore_uv=(), surveyed=None):
    """Cut image and raster into tiles: every positive tile, a seeded sample of negatives.

    A tile within the label radius of an ``ignore_uv`` spot (a target in view but not labelled) is not written;
    nor is a tile without a positive whose footprint ``surveyed`` (origins → mask; None: all) does not hold
    inside the surveyed area. Negative tiles holding a hard negative (``hard_uv``) fill the sample first, since
    they teach what the detector got wrong; the rest of the sample is drawn from the other negatives.
    Returns the tiles written (positive, negative, hard_negative among the negatives) and skipped
    (unlabelled_target, outside_surveyed_area), or None when the image cannot be read.
    """
    import cv2

    img = cv2.imread(image, cv2.IMREAD_COLOR)
    if img is None:
        return None
    t = request.tile_size
    h, w = raster.shape
    hard_uv = np.asarray(hard_uv, dtype=float).reshape(-1, 2)
    ignore_uv = np.asarray(ignore_uv, dtype=float).reshape(-1, 2)
    positives, candidates, n_ignored = [], [], 0
    for y0 in tile_origins(h, t):
        for x0 in tile_origins(w, t):
            if _near(ignore_uv, x0, y0, t, request.label_radius_px):
                n_ignored += 1
            elif inside_tile(uv, x0, y0, t).any():
                positives.append((y0, x0))
            else:
                candidates.append((y0, x0))
    inside = np.ones(len(candidates), dtype=bool) if surveyed is None else surveyed(candidates)
    hard, negatives = [], []
    for (y0, x0), ok in zip(candidates, inside):
        if ok:
            (hard if inside_tile(hard_uv, x0, y0, t).any() else negatives).append((y0, x0))
    n_neg = min(len(hard) + len(negatives), int(round(request.negative_ratio * max(1, len(positives)))))
    n_hard = min(len(hard), n_neg)
    keep_hard = [hard[i] for i in sorted(rng.choice(len(hard), n_hard, replace=False))] if n_hard else []
    n_plain = n_neg - n_hard
    keep_neg = [negatives[i] for i in sorted(rng.choice(len(negatives), n_plain, replace=False))] if n_plain else []
    for y0, x0 in positives + keep_hard + keep_neg:
        name = f"{frame_id}_{y0}_{x0}.png"
        cv2.imwrite(str(tile_dir / "images" / name), img[y0:y0 + t, x0:x0 + t])
        cv2.imwrite(str(tile_dir / "labels" / name), raster[y0:y0 + t, x0:x0 + t])
    return {"positive": len(positives), "negative": len(keep_hard) + len(keep_neg), "hard_negative": len(keep_hard),
            "unlabelled_target": n_ignored, "outside_surveyed_area": int((~inside).sum())}


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

"""Checkpoint screening: health guards and the scores the method tabulates, per checkpoint on validation flights.

Per checkpoint, pooled (micro-averaged) over every block of every flight: recall and GMCF, **F1 = the
harmonic mean of pooled recall and pooled GMCF** (``f1_geo``, :func:`~.sweep.f1_geo`), **detections
per frame** and the **review load** = detections per frame / the lightest healthy checkpoint's; beside
them the pixel-space F1 (``f1_pixel``, detections matched to projected labels within a stated radius)
and the health guards. A *block* is a run of consecutive frames of one flight scored on its own, as a
flight is (its own in-view geotags and clusters): the method screens in blocks of 500 frames.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..detect.clustering import GroundPositions, cluster_detections
from ..errors import InputError
from .operating_point import OperatingPoint
from .pre_review import PreCounts, ratio, score_flight
from .sweep import f1_geo, pareto_front

#: Health guards of checkpoint screening (both are parameters of screencheckpoints).
DEFAULT_COLLAPSED_BELOW = 0.05
DEFAULT_SPARSE_BELOW = 1.7
DEFAULT_PIXEL_RADIUS_PX = 10.0


@dataclass(frozen=True)
class ScreenPreset:
    """Blocks (``block_frames`` consecutive frames; 0 = each flight whole) and threshold (None = each
    checkpoint's own default) of a screening."""

    key: str
    block_frames: int
    threshold: float | None


#: The method's screening first (the default), then BirdsEye's own.
SCREEN_PRESETS = (ScreenPreset("method", 500, 0.03), ScreenPreset("birdseye", 0, None))


def frame_blocks(frame_ids, block_frames: int) -> list[np.ndarray]:
    """The frames of one flight, in flight order, cut into consecutive blocks of ``block_frames``
    frames (the last block holds the rest); 0 keeps the flight as one block."""
    if int(block_frames) != block_frames or block_frames < 0:
        raise InputError(f"must be a whole number of frames ≥ 0 (got {block_frames})", field="BLOCK_FRAMES")
    ids = np.asarray(frame_ids)
    if block_frames == 0 or len(ids) <= block_frames:
        return [ids]
    return [ids[i:i + int(block_frames)] for i in range(0, len(ids), int(block_frames))]


def relative_to_lightest(values: Sequence[float | None], eligible: Sequence[bool] | None = None) -> list[float | None]:
    """Each value divided by the smallest eligible one (every one by default): the review load from
    detections per frame. None stays None; all are None without a positive smallest value."""
    eligible = [True] * len(values) if eligible is None else list(eligible)
    lightest = min((v for v, ok in zip(values, eligible) if ok and v is not None), default=None)
    if not lightest:
        return [None] * len(values)
    return [None if v is None else v / lightest for v in values]


def distinct_position_fraction(uv) -> float | None:
    """Distinct pixel positions (rounded to whole pixels) / detections, frames ignored: a collapsed
    model fires at the same pixels in every frame. None without detections."""
    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    if len(uv) == 0:
        return None
    return len(np.unique(np.rint(uv).astype(np.int64), axis=0)) / len(uv)


def pixel_matches(det_frame, det_uv, label_frame, label_uv, radius_px: float) -> int:
    """True positives of a one-to-one, nearest-first matching of detections to labels of the same
    frame within ``radius_px`` (greedy by distance; ties by order)."""
    from scipy.spatial import cKDTree

    det_frame = np.asarray(det_frame).reshape(-1)
    label_frame = np.asarray(label_frame).reshape(-1)
    det_uv = np.asarray(det_uv, dtype=float).reshape(-1, 2)
    label_uv = np.asarray(label_uv, dtype=float).reshape(-1, 2)
    if len(det_uv) == 0 or len(label_uv) == 0:
        return 0
    _, codes = np.unique(np.concatenate([det_frame, label_frame]), return_inverse=True)
    codes = codes.reshape(-1)
    # Frames laid side by side far apart: one tree answers every frame at once.
    span = 4.0 * (max(np.abs(det_uv).max(), np.abs(label_uv).max()) + radius_px) + 1.0
    d_pts = det_uv + np.column_stack([codes[:len(det_uv)] * span, np.zeros(len(det_uv))])
    l_pts = label_uv + np.column_stack([codes[len(det_uv):] * span, np.zeros(len(label_uv))])
    pairs = cKDTree(d_pts).sparse_distance_matrix(cKDTree(l_pts), radius_px, output_type="ndarray")
    if len(pairs) == 0:
        return 0
    order = np.lexsort((pairs["j"], pairs["i"], pairs["v"]))
    used_d = np.zeros(len(det_uv), dtype=bool)
    used_l = np.zeros(len(label_uv), dtype=bool)
    tp = 0
    for i, j in zip(pairs["i"][order].tolist(), pairs["j"][order].tolist()):
        if not used_d[i] and not used_l[j]:
            used_d[i] = used_l[j] = True
            tp += 1
    return tp


@dataclass
class ScreenRun:
    """One checkpoint run over one block of frames, at the screening threshold.

    Detections: ``frame_id`` (N,), ``uv`` (N, 2) pixels, ``positions`` on the ground; ``n_frames``
    processed; pixel labels ``label_frame_id`` (L,), ``label_uv`` (L, 2) (in-view geotags projected
    into each frame); ``geotag_xy`` (G, 2) the geotags in view of the block's frames, local frame.
    """

    checkpoint: str
    block: str
    n_frames: int
    frame_id: np.ndarray
    uv: np.ndarray
    positions: GroundPositions
    label_frame_id: np.ndarray
    label_uv: np.ndarray
    geotag_xy: np.ndarray


@dataclass
class CheckpointScreen:
    checkpoint: str
    counts: PreCounts
    n_detections: int
    n_frames: int
    distinct_position_fraction: float | None
    worst_detections_per_frame: float | None
    worst_block: str
    pixel_tp: int
    pixel_fp: int
    pixel_fn: int
    pixel_radius_px: float
    collapsed: bool
    too_sparse: bool
    review_load: float | None = None
    frontier: bool = False

    @property
    def healthy(self) -> bool:
        return not (self.collapsed or self.too_sparse)

    @property
    def detections_per_frame(self):
        return ratio(self.n_detections, self.n_frames)

    @property
    def f1_geo(self):
        r, g = self.counts.recall_pre, self.counts.gmcf_pre
        return None if r is None or g is None else float(f1_geo(r, g))

    @property
    def f1_pixel(self):
        return ratio(2 * self.pixel_tp, 2 * self.pixel_tp + self.pixel_fp + self.pixel_fn)

    @property
    def unmatched_clusters(self) -> int:
        return self.counts.n_clusters - self.counts.n_hit_clusters

    def to_dict(self) -> dict:
        out = {"checkpoint": self.checkpoint, "healthy": self.healthy, "collapsed": self.collapsed,
               "too_sparse": self.too_sparse, "distinct_position_fraction": self.distinct_position_fraction,
               "worst_detections_per_frame": self.worst_detections_per_frame, "worst_block": self.worst_block,
               "n_detections": self.n_detections, "n_frames": self.n_frames,
               "detections_per_frame": self.detections_per_frame, "review_load": self.review_load,
               "f1_geo": self.f1_geo, "f1_pixel": self.f1_pixel, "f1_pixel_radius_px": self.pixel_radius_px,
               "pixel_tp": self.pixel_tp, "pixel_fp": self.pixel_fp, "pixel_fn": self.pixel_fn,
               "unmatched_clusters": self.unmatched_clusters, "frontier": self.frontier}
        out.update(self.counts.to_dict())
        return out


def screen_checkpoints(runs: Sequence[ScreenRun], op: OperatingPoint = OperatingPoint(),
                       radius_px: float = DEFAULT_PIXEL_RADIUS_PX,
                       collapsed_below: float = DEFAULT_COLLAPSED_BELOW,
                       sparse_below: float = DEFAULT_SPARSE_BELOW) -> list[CheckpointScreen]:
    """Health guards and pooled scores per checkpoint (input order), each block scored as a flight.

    ``review_load`` = detections per frame / the smallest detections per frame of any healthy
    checkpoint (1.0 = the lightest review; None for every checkpoint when none is healthy). ``frontier``: healthy
    and Pareto-optimal in (recall, GMCF).
    """
    names = list(dict.fromkeys(r.checkpoint for r in runs))
    out = []
    for name in names:
        mine = [r for r in runs if r.checkpoint == name]
        counts, tp, n_det, n_lab, n_frames = PreCounts(), 0, 0, 0, 0
        per_frame = {}
        for r in mine:
            clustering = cluster_detections(r.positions, r.frame_id, None, op.dedup_cm, op.eps_m, op.min_samples,
                                            core_count=op.core_count)
            g = np.asarray(r.geotag_xy, dtype=float).reshape(-1, 2)
            counts = counts + score_flight(clustering, g, np.ones(len(g), dtype=bool), op.eps_pred_m).counts
            tp += pixel_matches(r.frame_id, r.uv, r.label_frame_id, r.label_uv, radius_px)
            n_det += len(r.frame_id)
            n_lab += len(r.label_frame_id)
            n_frames += r.n_frames
            per_frame[r.block] = ratio(len(r.frame_id), r.n_frames)
        uv_all = np.concatenate([np.asarray(r.uv, dtype=float).reshape(-1, 2) for r in mine])
        distinct = distinct_position_fraction(uv_all)
        known = {b: v for b, v in per_frame.items() if v is not None}
        worst_block = min(known, key=known.get) if known else ""
        worst = known.get(worst_block)
        out.append(CheckpointScreen(
            name, counts, n_det, n_frames, distinct, worst, worst_block, tp, n_det - tp, n_lab - tp, float(radius_px),
            collapsed=distinct is None or distinct < collapsed_below,
            too_sparse=worst is None or worst < sparse_below))
    for s, load in zip(out, relative_to_lightest([s.detections_per_frame for s in out], [s.healthy for s in out])):
        s.review_load = load
    healthy = [s for s in out if s.healthy]
    if healthy:
        r = np.array([s.counts.recall_pre if s.counts.recall_pre is not None else np.nan for s in healthy])
        g = np.array([s.counts.gmcf_pre if s.counts.gmcf_pre is not None else np.nan for s in healthy])
        for s, on in zip(healthy, pareto_front(r, g, np.isfinite(r) & np.isfinite(g))):
            s.frontier = bool(on)
    return out

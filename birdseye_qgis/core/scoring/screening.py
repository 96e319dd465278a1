"""Checkpoint screening: health guards, recall, GMCF and pixel F1 of several models on validation flights."""
from __future__ import annotations

from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..detect.clustering import cluster_detections
from .operating_point import OperatingPoint
from .pre_review import PreCounts, ratio, score_flight
from .sweep import pareto_front

#: Health guards of checkpoint screening (both are parameters of screencheckpoints).
DEFAULT_COLLAPSED_BELOW = 0.05
DEFAULT_SPARSE_BELOW = 1.7
DEFAULT_PIXEL_RADIUS_PX = 10.0


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
    """One checkpoint run over one validation flight, at the screening threshold.

    Detections: ``frame_id`` (N,), ``uv`` (N, 2) pixels, ``xy`` (N, 2) local metres; ``n_frames``
    processed; pixel labels ``label_frame_id`` (L,), ``label_uv`` (L, 2) (in-view geotags projected
    into each frame); ``geotag_xy`` (G, 2) the in-view geotags in the local frame.
    """

    checkpoint: str
    flight: str
    n_frames: int
    frame_id: np.ndarray
    uv: np.ndarray
    xy: np.ndarray
    label_frame_id: np.ndarray
    label_uv: np.ndarray
    geotag_xy: np.ndarray


@dataclass
class CheckpointScreen:
    checkpoint: str
    counts: PreCounts
    n_detections: int
    distinct_position_fraction: float | None
    worst_detections_per_frame: float | None
    worst_flight: str
    pixel_tp: int
    pixel_fp: int
    pixel_fn: int
    collapsed: bool
    too_sparse: bool
    unmatched_clusters: int
    relative_review_load: float | None = None
    frontier: bool = False

    @property
    def healthy(self) -> bool:
        return not (self.collapsed or self.too_sparse)

    @property
    def pixel_f1(self):
        return ratio(2 * self.pixel_tp, 2 * self.pixel_tp + self.pixel_fp + self.pixel_fn)

    def to_dict(self) -> dict:
        out = {"checkpoint": self.checkpoint, "healthy": self.healthy, "collapsed": self.collapsed,
               "too_sparse": self.too_sparse, "n_detections": self.n_detections,
               "distinct_position_fraction": self.distinct_position_fraction,
               "worst_detections_per_frame": self.worst_detections_per_frame, "worst_flight": self.worst_flight,
               "pixel_tp": self.pixel_tp, "pixel_fp": self.pixel_fp, "pixel_fn": self.pixel_fn,
               "pixel_f1": self.pixel_f1, "unmatched_clusters": self.unmatched_clusters,
               "relative_review_load": self.relative_review_load, "frontier": self.frontier}
        out.update(self.counts.to_dict())
        return out


def screen_checkpoints(runs: Sequence[ScreenRun], op: OperatingPoint = OperatingPoint(),
                       radius_px: float = DEFAULT_PIXEL_RADIUS_PX,
                       collapsed_below: float = DEFAULT_COLLAPSED_BELOW,
                       sparse_below: float = DEFAULT_SPARSE_BELOW) -> list[CheckpointScreen]:
    """Health guards, pooled recall and GMCF, pixel F1 and review load per checkpoint (input order).

    ``relative_review_load`` = unmatched clusters / the fewest unmatched clusters of any healthy
    checkpoint (1.0 = the lightest review). ``frontier``: healthy and Pareto-optimal in (recall, GMCF).
    """
    names = list(dict.fromkeys(r.checkpoint for r in runs))
    out = []
    for name in names:
        mine = [r for r in runs if r.checkpoint == name]
        counts, tp, n_det, n_lab = PreCounts(), 0, 0, 0
        per_frame = {}
        for r in mine:
            clustering = cluster_detections(r.xy, r.frame_id, None, op.dedup_cm, op.eps_m, op.min_samples)
            g = np.asarray(r.geotag_xy, dtype=float).reshape(-1, 2)
            counts = counts + score_flight(clustering, g, np.ones(len(g), dtype=bool), op.eps_pred_m).counts
            tp += pixel_matches(r.frame_id, r.uv, r.label_frame_id, r.label_uv, radius_px)
            n_det += len(r.frame_id)
            n_lab += len(r.label_frame_id)
            per_frame[r.flight] = len(r.frame_id) / r.n_frames if r.n_frames else None
        uv_all = np.concatenate([np.asarray(r.uv, dtype=float).reshape(-1, 2) for r in mine])
        distinct = distinct_position_fraction(uv_all)
        known = {f: v for f, v in per_frame.items() if v is not None}
        worst_flight = min(known, key=known.get) if known else ""
        worst = known.get(worst_flight)
        out.append(CheckpointScreen(
            name, counts, n_det, distinct, worst, worst_flight, tp, n_det - tp, n_lab - tp,
            collapsed=distinct is None or distinct < collapsed_below,
            too_sparse=worst is None or worst < sparse_below,
            unmatched_clusters=counts.n_clusters - counts.n_hit_clusters))
    healthy = [s for s in out if s.healthy]
    lightest = min((s.unmatched_clusters for s in healthy), default=0)
    for s in out:
        s.relative_review_load = s.unmatched_clusters / max(lightest, 1)
    if healthy:
        r = np.array([s.counts.recall_pre if s.counts.recall_pre is not None else np.nan for s in healthy])
        g = np.array([s.counts.gmcf_pre if s.counts.gmcf_pre is not None else np.nan for s in healthy])
        for s, on in zip(healthy, pareto_front(r, g, np.isfinite(r) & np.isfinite(g))):
            s.frontier = bool(on)
    return out

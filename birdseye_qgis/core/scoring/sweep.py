"""Operating-point sweeps: checkpoint × threshold × EPS × MIN_SAMPLES × EPS_PRED scored, credible points, Pareto front.

**The threshold axis.** For each threshold t of the grid a flight brings the detections of a peak
extraction *at t* (:func:`~..detect.detector.detect_frames_at_thresholds`, or a Detect run at t), never
the detections of a lower threshold kept when their score is ≥ t: Detect makes one detection per blob
of the smoothed heatmap above its threshold, so a blob whose humps meet between two thresholds is one
detection at the lower and two at the higher, and each blob's centroid is weighted by (value − t).

**The default grid** (:data:`METHOD_GRID`) holds every operating point the method reports — thresholds
0.03 to 0.12 and 0.035 (the threshold of its "lowest review burden" arm), EPS 0.10, 0.15 and 0.20 m,
MIN_SAMPLES 2, 5, 10 and 20, EPS_PRED 0.20 and 0.35 m — and has the method's size, 14,400 per checkpoint
= 12 thresholds (0.03, 0.035, 0.04, 0.045, 0.05, then 0.06 … 0.12 in steps of 0.01) × 10 EPS (0.025 …
0.25 m in steps of 0.025 m) × 12 MIN_SAMPLES (1 … 10, 15, 20) × 10 EPS_PRED (0.05 … 0.50 m in steps of
0.05 m). The method names those values and the total; the values in between are ours. Half steps of the
threshold below 0.05: that is where the method's arms lie and where detections per frame (the review
burden) change fastest with the threshold. The two extra thresholds are paid for by the EPS axis, which
stops one step (0.05 m) above the largest EPS the method reports (0.20 m): beyond it a cluster spans
neighbouring burrows, which the credibility filter rejects anyway.

**What DBSCAN counts** (``core_count``, :mod:`~..detect.clustering`) is one value per sweep, like the
de-duplication cell, recorded in every row; each (flight, threshold) weighs its cells once and every
(EPS, MIN_SAMPLES) of the grid reuses those weights with the one radius graph.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Mapping, Sequence

import numpy as np

from ..detect.clustering import (
    DEFAULT_CORE_COUNT,
    DEFAULT_DEDUP_CM,
    GroundPositions,
    check_core_count,
    cluster_centroids_and_extents,
    dbscan,
    deduplicate,
    neighbour_graph,
)
from ..errors import InputError, check_cancel
from .matching import match_to_clusters
from .pre_review import f1_geo

#: Credibility filter of sweeps (both are parameters of sweepoperatingpoints).
DEFAULT_MAX_GEOTAGS_PER_HIT = 1.5
DEFAULT_MAX_MEAN_EXTENT_M = 1.0

#: The default grid: axis name → values (see the module docstring).
METHOD_GRID = {
    "thresholds": (0.03, 0.035, 0.04, 0.045) + tuple(round(0.05 + 0.01 * i, 2) for i in range(8)),
    "eps_m": tuple(round(0.025 * i, 3) for i in range(1, 11)),
    "min_samples": (1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 15, 20),
    "eps_pred_m": tuple(round(0.05 * i, 2) for i in range(1, 11)),
}
#: Two thresholds closer than this are the same threshold (layers store them as doubles).
THRESHOLD_TOLERANCE = 1e-9


@dataclass
class SweepFlight:
    """One flight seen by one checkpoint.

    ``detections[t]``: the ground positions (local frame and WGS84) of the detections a peak
    extraction at threshold t gives, one entry per threshold of the grid; ``n_frames`` the frames
    processed; ``geotag_xy`` (G, 2) the in-view geotags in the same frame.
    """

    detections: Mapping[float, GroundPositions]
    geotag_xy: np.ndarray
    n_frames: int
    name: str = ""
    checkpoint: str = ""
    model_digest: str = ""

    def at_threshold(self, threshold: float) -> GroundPositions:
        for t, positions in self.detections.items():
            if abs(float(t) - float(threshold)) <= THRESHOLD_TOLERANCE:
                return positions
        have = ", ".join(f"{float(t):g}" for t in sorted(self.detections)) or "none"
        raise InputError(f"{self.checkpoint or 'the checkpoint'} on {self.name or 'a flight'}: no detections "
                         f"made at threshold {float(threshold):g} (thresholds detected at: {have})",
                         field="THRESHOLDS")


@dataclass
class SweepGrid:
    thresholds: np.ndarray
    eps_m: np.ndarray
    min_samples: np.ndarray
    eps_pred_m: np.ndarray
    dedup_cm: float = DEFAULT_DEDUP_CM
    core_count: str = DEFAULT_CORE_COUNT

    def __post_init__(self):
        def clean(values, name, integer=False):
            arr = np.unique(np.asarray(values, dtype=float).reshape(-1))
            if len(arr) == 0:
                raise InputError("needs at least one value", field=name)
            if integer and (np.any(arr != np.round(arr)) or arr.min() < 1):
                raise InputError("must be whole numbers ≥ 1", field=name)
            if not integer and name != "THRESHOLDS" and arr.min() <= 0:
                raise InputError("must all be larger than 0", field=name)
            return arr.astype(np.int64) if integer else arr

        self.thresholds = clean(self.thresholds, "THRESHOLDS")
        if self.thresholds.min() <= 0 or self.thresholds.max() >= 1:
            raise InputError("must be probabilities between 0 and 1", field="THRESHOLDS")
        self.eps_m = clean(self.eps_m, "EPS_M")
        self.min_samples = clean(self.min_samples, "MIN_SAMPLES", integer=True)
        self.eps_pred_m = clean(self.eps_pred_m, "EPS_PRED_M")
        check_core_count(self.core_count)

    @property
    def shape(self) -> tuple:
        return len(self.thresholds), len(self.eps_m), len(self.min_samples), len(self.eps_pred_m)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))


#: Count arrays of a sweep, each of shape (checkpoints,) + grid shape; those that do not depend on an
#: axis are broadcast over it.
_SWEEP_COUNTS = ("n_frames", "n_detections", "n_in_view", "n_recovered", "n_clusters", "n_hit_clusters",
                 "n_geotag_matches", "sum_median_extent_m")


@dataclass
class SweepResult:
    """Pooled (micro-averaged) counts per checkpoint over the grid: arrays of shape :attr:`shape`.

    ``checkpoints``: (name, model digest) of each checkpoint, in the order of the first axis.
    """

    grid: SweepGrid
    checkpoints: list
    counts: dict
    max_geotags_per_hit: float = DEFAULT_MAX_GEOTAGS_PER_HIT
    max_mean_extent_m: float = DEFAULT_MAX_MEAN_EXTENT_M

    @property
    def shape(self) -> tuple:
        return (len(self.checkpoints),) + self.grid.shape

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))

    def _ratio(self, num, den):
        num, den = self.counts[num].astype(float), self.counts[den].astype(float)
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.where(den > 0, num / np.where(den > 0, den, 1), np.nan)

    @property
    def recall_pre(self):
        return self._ratio("n_recovered", "n_in_view")

    @property
    def gmcf_pre(self):
        return self._ratio("n_hit_clusters", "n_clusters")

    @property
    def f1_geo(self):
        return f1_geo(self.recall_pre, self.gmcf_pre)

    @property
    def detections_per_frame(self):
        return self._ratio("n_detections", "n_frames")

    @property
    def mean_geotags_per_hit_cluster(self):
        return self._ratio("n_geotag_matches", "n_hit_clusters")

    @property
    def mean_median_extent_m(self):
        return self._ratio("sum_median_extent_m", "n_clusters")

    @property
    def credible(self):
        """Mean geotags per hit cluster ≤ the limit and mean median extent ≤ the limit (both defined)."""
        g, e = self.mean_geotags_per_hit_cluster, self.mean_median_extent_m
        with np.errstate(invalid="ignore"):
            return (g <= self.max_geotags_per_hit) & (e <= self.max_mean_extent_m)

    @property
    def pareto(self):
        """Credible configurations of any checkpoint that no other credible one dominates."""
        r, g = self.recall_pre, self.gmcf_pre
        return pareto_front(r.ravel(), g.ravel(), (self.credible & np.isfinite(r) & np.isfinite(g)).ravel()
                            ).reshape(self.shape)

    def rows(self) -> list[dict]:
        """One dict per configuration (checkpoint-major, then threshold-major order), JSON-ready (NaN → None)."""
        c, t, e, m, p = np.meshgrid(np.arange(len(self.checkpoints)), self.grid.thresholds, self.grid.eps_m,
                                    self.grid.min_samples, self.grid.eps_pred_m, indexing="ij")
        cols = {"threshold": t, "eps_m": e, "min_samples": m, "eps_pred_m": p}
        cols.update({k: self.counts[k] for k in _SWEEP_COUNTS})
        cols.update({"detections_per_frame": self.detections_per_frame, "recall_pre": self.recall_pre,
                     "gmcf_pre": self.gmcf_pre, "f1_geo": self.f1_geo,
                     "mean_geotags_per_hit_cluster": self.mean_geotags_per_hit_cluster,
                     "mean_median_extent_m": self.mean_median_extent_m,
                     "credible": self.credible, "pareto": self.pareto})
        flat = {k: np.broadcast_to(v, self.shape).ravel().tolist() for k, v in cols.items()}
        names = [self.checkpoints[i] for i in c.ravel().tolist()]
        out = []
        for i in range(self.size):
            row = {"checkpoint": names[i][0], "model_digest": names[i][1]}
            for k, v in flat.items():
                x = v[i]
                if isinstance(x, float) and not math.isfinite(x):
                    x = None
                row[k] = x
            row["dedup_cm"] = float(self.grid.dedup_cm)
            row["core_count"] = self.grid.core_count
            out.append(row)
        return out


def pareto_front(recall, gmcf, eligible=None) -> np.ndarray:
    """Mask of eligible configurations no other eligible one dominates (≥ in both, > in one)."""
    recall, gmcf = np.asarray(recall, dtype=float), np.asarray(gmcf, dtype=float)
    eligible = np.ones(len(recall), dtype=bool) if eligible is None else np.asarray(eligible, dtype=bool)
    idx = np.flatnonzero(eligible)
    front = np.zeros(len(recall), dtype=bool)
    if len(idx) == 0:
        return front
    # Sort by recall descending, then gmcf descending: a point is on the front iff its gmcf beats
    # every point of strictly higher recall, and ties in both values stay together.
    order = idx[np.lexsort((-gmcf[idx], -recall[idx]))]
    best_gmcf_above = -np.inf
    k = 0
    while k < len(order):
        r = recall[order[k]]
        group = [order[k]]
        k += 1
        while k < len(order) and recall[order[k]] == r:
            group.append(order[k])
            k += 1
        top = gmcf[group[0]]
        if top > best_gmcf_above:
            for j in group:
                if gmcf[j] == top:
                    front[j] = True
            best_gmcf_above = top
    return front


@dataclass
class DetectionRun:
    """Detections of one checkpoint on one flight from one peak extraction at ``threshold`` (a Detect
    layer): their ground positions; ``source`` names the layer in messages."""

    positions: GroundPositions
    threshold: float | None
    flight: str
    checkpoint: str
    model_digest: str
    source: str


def flights_from_runs(runs: Sequence[DetectionRun], geotag_xy: Mapping[str, np.ndarray],
                      n_frames: Mapping[str, int]) -> tuple[list[SweepFlight], list[float]]:
    """Sweep flights from detection runs (checkpoint × flight × threshold), and the thresholds they cover.

    Each run is used at the threshold it was detected at; every (checkpoint, flight) needs a run at
    every threshold any run was detected at. ``geotag_xy`` and ``n_frames`` are keyed by flight.
    """
    by_key, thresholds = {}, []
    for run in runs:
        if run.threshold is None:
            raise InputError("has no detection threshold (field 'threshold'); the sweep uses each layer at the "
                             "threshold it was detected at (make the layer with Detect targets)", source=run.source)
        t = next((u for u in thresholds if abs(u - run.threshold) <= THRESHOLD_TOLERANCE), float(run.threshold))
        if t not in thresholds:
            thresholds.append(t)
        key = (run.checkpoint, run.model_digest, run.flight)
        other = by_key.setdefault(key, {}).get(t)
        if other is not None:
            raise InputError(f"{other.source} and {run.source} are both {run.checkpoint or 'one model'} on "
                             f"{run.flight} at threshold {t:g}; give each once", field="DETECTIONS")
        by_key[key][t] = run
    thresholds.sort()
    flights = []
    for (checkpoint, digest, flight), per_threshold in by_key.items():
        missing = [f"{t:g}" for t in thresholds if t not in per_threshold]
        if missing:
            raise InputError(f"{checkpoint or 'a model'} on {flight} has no layer detected at threshold(s) "
                             f"{', '.join(missing)}, which other layers were detected at: give every checkpoint "
                             "and flight a layer at every threshold, or give CHECKPOINTS to re-run the peak "
                             "extraction at each threshold", field="DETECTIONS")
        flights.append(SweepFlight({t: r.positions for t, r in per_threshold.items()}, geotag_xy[flight],
                                   n_frames[flight], flight, checkpoint, digest))
    return flights, thresholds


def group_by_checkpoint(flights: Sequence[SweepFlight]) -> dict:
    """(checkpoint, model digest) → its flights, in input order; every checkpoint must have been run on
    the same flights, or their pooled scores would not be comparable."""
    groups = {}
    for f in flights:
        groups.setdefault((f.checkpoint, f.model_digest), []).append(f)
    seen = {key: sorted(f.name for f in fl) for key, fl in groups.items()}
    first_key, first = next(iter(seen.items()), (None, []))
    for key, names in seen.items():
        if len(set(names)) != len(names):
            raise InputError(f"{key[0] or 'a checkpoint'} is given twice on one flight ({', '.join(names)})")
        if names != first:
            raise InputError(f"every checkpoint must be scored on the same flights: {first_key[0] or '?'} on "
                             f"{', '.join(first)}, but {key[0] or '?'} on {', '.join(names)}")
    return groups


def sweep(flights: Sequence[SweepFlight], grid: SweepGrid,
          max_geotags_per_hit: float = DEFAULT_MAX_GEOTAGS_PER_HIT,
          max_mean_extent_m: float = DEFAULT_MAX_MEAN_EXTENT_M, progress=None, is_canceled=None) -> SweepResult:
    """Pooled PRE counts per checkpoint over threshold × eps × min_samples × eps_pred, reusing work.

    Per flight and threshold the detections are de-duplicated once (the cells' weights of
    ``grid.core_count`` with them) and one radius graph is built at the largest eps; per (eps,
    min_samples) DBSCAN runs once on that graph; every eps_pred is then
    scored from one k-d tree query at the largest eps_pred. Identical to running
    :func:`~.clustering.cluster_detections` + :func:`score_flight` per configuration.
    """
    groups = group_by_checkpoint(flights)
    checkpoints = list(groups)
    shape = (len(checkpoints),) + grid.shape
    counts = {k: np.zeros(shape, dtype=float if k == "sum_median_extent_m" else np.int64) for k in _SWEEP_COUNTS}
    total_steps = max(1, len(flights) * int(np.prod(grid.shape[:3])))
    step = 0
    eps_max, pred_max = float(grid.eps_m.max()), float(grid.eps_pred_m.max())
    for ci, key in enumerate(checkpoints):
        for flight in groups[key]:
            geotags = np.asarray(flight.geotag_xy, dtype=float).reshape(-1, 2)
            counts["n_in_view"][ci] += len(geotags)
            counts["n_frames"][ci] += int(flight.n_frames)
            for ti, t in enumerate(grid.thresholds):
                positions = flight.at_threshold(t)
                xy = positions.xy
                counts["n_detections"][ci, ti] += len(xy)
                points = deduplicate(positions, grid.dedup_cm / 100.0)
                weight = points.weights(grid.core_count)
                graph = neighbour_graph(points.xy, eps_max)
                for ei, eps in enumerate(grid.eps_m):
                    for mi, m in enumerate(grid.min_samples):
                        check_cancel(is_canceled)
                        result = dbscan(graph, eps, int(m), weight)
                        nc = result.n_clusters
                        _, extent = cluster_centroids_and_extents(xy, result.labels[points.inverse], nc)
                        counts["n_clusters"][ci, ti, ei, mi, :] += nc
                        counts["sum_median_extent_m"][ci, ti, ei, mi, :] += float(np.sum(extent)) if nc else 0.0
                        matches = match_to_clusters(points.xy[result.core], result.labels[result.core], geotags,
                                                    pred_max)
                        for pi, pred in enumerate(grid.eps_pred_m):
                            w = matches.within(pred)
                            counts["n_recovered"][ci, ti, ei, mi, pi] += len(np.unique(w.point))
                            counts["n_hit_clusters"][ci, ti, ei, mi, pi] += len(np.unique(w.cluster))
                            counts["n_geotag_matches"][ci, ti, ei, mi, pi] += len(w.point)
                        step += 1
                        if progress is not None:
                            progress(step / total_steps)
    return SweepResult(grid, checkpoints, counts, max_geotags_per_hit, max_mean_extent_m)

"""Operating-point sweeps: every threshold × clustering combination scored, credible points, Pareto front."""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np

from ..detect.clustering import DEFAULT_DEDUP_CM, cluster_centroids_and_extents, dbscan, deduplicate, neighbour_graph
from ..errors import Cancelled, InputError
from .matching import match_to_clusters

#: Credibility filter of sweeps (both are parameters of sweepoperatingpoints).
DEFAULT_MAX_GEOTAGS_PER_HIT = 1.5
DEFAULT_MAX_MEAN_EXTENT_M = 1.0


@dataclass
class SweepFlight:
    """One flight for a sweep: detections (N, 2) in a local metric frame, their scores, and the
    in-view geotags (G, 2) in the same frame."""

    xy: np.ndarray
    score: np.ndarray
    geotag_xy: np.ndarray
    name: str = ""


@dataclass
class SweepGrid:
    thresholds: np.ndarray
    eps_m: np.ndarray
    min_samples: np.ndarray
    eps_pred_m: np.ndarray
    dedup_cm: float = DEFAULT_DEDUP_CM

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
        if self.thresholds.min() < 0 or self.thresholds.max() > 1:
            raise InputError("must be probabilities in [0, 1]", field="THRESHOLDS")
        self.eps_m = clean(self.eps_m, "EPS_M")
        self.min_samples = clean(self.min_samples, "MIN_SAMPLES", integer=True)
        self.eps_pred_m = clean(self.eps_pred_m, "EPS_PRED_M")

    @property
    def shape(self) -> tuple:
        return len(self.thresholds), len(self.eps_m), len(self.min_samples), len(self.eps_pred_m)

    @property
    def size(self) -> int:
        return int(np.prod(self.shape))


#: Count arrays of a sweep; those without an eps_pred axis are broadcast over it.
_SWEEP_COUNTS = ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters", "n_geotag_matches",
                 "sum_median_extent_m")


@dataclass
class SweepResult:
    """Pooled (micro-averaged) counts over the grid, arrays of shape ``grid.shape``."""

    grid: SweepGrid
    counts: dict
    max_geotags_per_hit: float = DEFAULT_MAX_GEOTAGS_PER_HIT
    max_mean_extent_m: float = DEFAULT_MAX_MEAN_EXTENT_M

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
        r, g = self.recall_pre, self.gmcf_pre
        return pareto_front(r.ravel(), g.ravel(), (self.credible & np.isfinite(r) & np.isfinite(g)).ravel()
                            ).reshape(self.grid.shape)

    def rows(self) -> list[dict]:
        """One dict per configuration (threshold-major order), JSON-ready (NaN → None)."""
        t, e, m, p = np.meshgrid(self.grid.thresholds, self.grid.eps_m, self.grid.min_samples,
                                 self.grid.eps_pred_m, indexing="ij")
        cols = {"threshold": t, "eps_m": e, "min_samples": m, "eps_pred_m": p}
        cols.update({k: self.counts[k] for k in _SWEEP_COUNTS})
        cols.update({"recall_pre": self.recall_pre, "gmcf_pre": self.gmcf_pre,
                     "mean_geotags_per_hit_cluster": self.mean_geotags_per_hit_cluster,
                     "mean_median_extent_m": self.mean_median_extent_m,
                     "credible": self.credible, "pareto": self.pareto})
        flat = {k: np.broadcast_to(v, self.grid.shape).ravel().tolist() for k, v in cols.items()}
        out = []
        for i in range(self.grid.size):
            row = {}
            for k, v in flat.items():
                x = v[i]
                if isinstance(x, float) and not math.isfinite(x):
                    x = None
                row[k] = x
            row["dedup_cm"] = float(self.grid.dedup_cm)
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


def sweep(flights: Sequence[SweepFlight], grid: SweepGrid,
          max_geotags_per_hit: float = DEFAULT_MAX_GEOTAGS_PER_HIT,
          max_mean_extent_m: float = DEFAULT_MAX_MEAN_EXTENT_M, progress=None, is_canceled=None) -> SweepResult:
    """Pooled PRE counts over threshold × eps × min_samples × eps_pred, reusing work.

    Per flight and threshold the detections are de-duplicated once and one radius graph is built at
    the largest eps; per (eps, min_samples) DBSCAN runs once on that graph; every eps_pred is then
    scored from one k-d tree query at the largest eps_pred. Identical to running
    :func:`~.clustering.cluster_detections` + :func:`score_flight` per configuration.
    """
    shape = grid.shape
    counts = {k: np.zeros(shape, dtype=float if k == "sum_median_extent_m" else np.int64) for k in _SWEEP_COUNTS}
    total_steps = max(1, len(flights) * shape[0] * shape[1] * shape[2])
    step = 0
    eps_max, pred_max = float(grid.eps_m.max()), float(grid.eps_pred_m.max())
    for flight in flights:
        xy = np.asarray(flight.xy, dtype=float).reshape(-1, 2)
        score = np.asarray(flight.score, dtype=float).reshape(-1)
        geotags = np.asarray(flight.geotag_xy, dtype=float).reshape(-1, 2)
        counts["n_in_view"] += len(geotags)
        for ti, t in enumerate(grid.thresholds):
            sel = xy[score >= t]
            points = deduplicate(sel, grid.dedup_cm / 100.0)
            graph = neighbour_graph(points.xy, eps_max)
            for ei, eps in enumerate(grid.eps_m):
                for mi, m in enumerate(grid.min_samples):
                    if is_canceled is not None and is_canceled():
                        raise Cancelled()
                    result = dbscan(graph, eps, int(m))
                    nc = result.n_clusters
                    _, extent = cluster_centroids_and_extents(sel, result.labels[points.inverse], nc)
                    counts["n_clusters"][ti, ei, mi, :] += nc
                    counts["sum_median_extent_m"][ti, ei, mi, :] += float(np.sum(extent)) if nc else 0.0
                    matches = match_to_clusters(points.xy[result.core], result.labels[result.core], geotags,
                                                pred_max)
                    for pi, pred in enumerate(grid.eps_pred_m):
                        w = matches.within(pred)
                        counts["n_recovered"][ti, ei, mi, pi] += len(np.unique(w.point))
                        counts["n_hit_clusters"][ti, ei, mi, pi] += len(np.unique(w.cluster))
                        counts["n_geotag_matches"][ti, ei, mi, pi] += len(w.point)
                    step += 1
                    if progress is not None:
                        progress(step / total_steps)
    return SweepResult(grid, counts, max_geotags_per_hit, max_mean_extent_m)

"""Scores before review: recall_pre and GMCF per flight, pooled by micro-averaging."""
from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Iterable

import numpy as np

from ..detect.clustering import Clustering
from .matching import match_to_clusters


def ratio(num, den):
    return None if den == 0 else float(num) / float(den)


def f1_geo(recall, gmcf):
    """F1 as the method tabulates it: the harmonic mean 2·r·g / (r + g) of pooled recall and pooled GMCF
    (0 when both are 0, NaN where either is undefined). Works element-wise on arrays."""
    r, g = np.asarray(recall, dtype=float), np.asarray(gmcf, dtype=float)
    total = r + g
    with np.errstate(invalid="ignore", divide="ignore"):
        out = np.where(total > 0, 2.0 * r * g / np.where(total > 0, total, 1.0), 0.0)
    return np.where(np.isfinite(r) & np.isfinite(g), out, np.nan)


@dataclass
class PreCounts:
    """Counts of one flight or of pooled flights; ``+`` pools by micro-averaging (sums the counts)."""

    n_in_view: int = 0
    n_recovered: int = 0
    n_clusters: int = 0
    n_hit_clusters: int = 0
    #: (in-view geotag, hit cluster) pairs within eps_pred_m: the credibility filter's numerator.
    n_geotag_matches: int = 0
    #: Sum over clusters of their median extent (m): the credibility filter's numerator.
    sum_median_extent_m: float = 0.0

    def __add__(self, other: "PreCounts") -> "PreCounts":
        return PreCounts(*(getattr(self, f.name) + getattr(other, f.name) for f in fields(PreCounts)))

    @property
    def recall_pre(self):
        return ratio(self.n_recovered, self.n_in_view)

    @property
    def gmcf_pre(self):
        return ratio(self.n_hit_clusters, self.n_clusters)

    @property
    def f1_geo(self):
        """The harmonic mean of recall_pre and gmcf_pre, the F1 every table of the method prints."""
        if self.recall_pre is None or self.gmcf_pre is None:
            return None
        return float(f1_geo(self.recall_pre, self.gmcf_pre))

    @property
    def mean_geotags_per_hit_cluster(self):
        return ratio(self.n_geotag_matches, self.n_hit_clusters)

    @property
    def mean_median_extent_m(self):
        return ratio(self.sum_median_extent_m, self.n_clusters)

    def to_dict(self) -> dict:
        return {"n_in_view": int(self.n_in_view), "n_recovered": int(self.n_recovered),
                "recall_pre": self.recall_pre, "n_clusters": int(self.n_clusters),
                "n_hit_clusters": int(self.n_hit_clusters), "gmcf_pre": self.gmcf_pre, "f1_geo": self.f1_geo,
                "mean_geotags_per_hit_cluster": self.mean_geotags_per_hit_cluster,
                "mean_median_extent_m": self.mean_median_extent_m}


def pool(counts: Iterable[PreCounts]) -> PreCounts:
    """Micro-average: the sum of the flights' counts (ratios are then taken once)."""
    total = PreCounts()
    for c in counts:
        total = total + c
    return total


@dataclass
class FlightScore:
    """PRE scores of one flight and what they rest on.

    ``recovered`` (G,) over the geotags given (False when not in view); ``cluster_hit`` (C,);
    ``cluster_geotags[k]`` the indices of the in-view geotags matched to cluster k.
    """

    counts: PreCounts
    recovered: np.ndarray
    cluster_hit: np.ndarray
    cluster_geotags: list


def score_flight(clustering: Clustering, geotag_xy, geotag_in_view, eps_pred_m: float) -> FlightScore:
    """Recovered geotags and hit clusters of one flight (geotags (G, 2) in the clustering's frame)."""
    geotag_xy = np.asarray(geotag_xy, dtype=float).reshape(-1, 2)
    geotag_in_view = np.asarray(geotag_in_view, dtype=bool).reshape(-1)
    visible = np.flatnonzero(geotag_in_view)
    m = match_to_clusters(clustering.core_xy, clustering.core_cluster, geotag_xy[visible], eps_pred_m)
    recovered = np.zeros(len(geotag_xy), dtype=bool)
    recovered[visible[m.point]] = True
    n = clustering.n_clusters
    hit = np.zeros(n, dtype=bool)
    hit[m.cluster] = True
    order = np.argsort(m.cluster, kind="stable")
    cluster_geotags = np.split(visible[m.point[order]], np.searchsorted(m.cluster[order], np.arange(1, n))) \
        if n else []
    extent = clustering.summary.median_extent_m
    counts = PreCounts(len(visible), int(recovered.sum()), n, int(hit.sum()), len(m.point),
                       float(np.sum(extent)) if n else 0.0)
    return FlightScore(counts, recovered, hit, cluster_geotags)

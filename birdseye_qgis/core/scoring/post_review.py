"""Scores after review: GMCF and recall with confirmed clusters and added targets."""
from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Sequence

import numpy as np

from ..detect.clustering import Clustering
from .matching import match_to_clusters
from .pre_review import PreCounts, ratio
from .verdicts import CONFIRMED, CONVENTIONS, VerdictLog

#: When recall_post is a point value rather than the bound printed with "≥" (a > 0), it is the
#: recall over every real target in view under these assumptions; the help texts repeat them.
POINT_VALUE_ASSUMPTIONS = (
    "the reviewer's search for missed targets was exhaustive (every real target in view that nobody "
    "surveyed and the detector missed was added); every in-view geotag is one real target; every "
    "confirmed cluster is one real target, distinct from the geotags and from the other confirmed "
    "clusters; unmatched clusters not resolved confirmed_real (hard_negative, uncertain, unreviewed) "
    "are not real targets")


def countable_added_targets(added_xy, added_in_view, clustering: Clustering, geotag_xy,
                            eps_pred_m: float) -> np.ndarray:
    """Which added targets (A, 2) count in ``a`` for one flight (mask (A,)): those in view where no
    cluster fired (no core point within ``eps_pred_m``) and no geotag lies within ``eps_pred_m``.

    An added target near a cluster is that cluster's spot (its verdict counts through ``c``), and one
    near a geotag is already in ``n_in_view``: counting either in ``a`` would count a target twice.
    """
    added_xy = np.asarray(added_xy, dtype=float).reshape(-1, 2)
    geotag_xy = np.asarray(geotag_xy, dtype=float).reshape(-1, 2)
    keep = np.asarray(added_in_view, dtype=bool).reshape(-1).copy()
    keep[match_to_clusters(clustering.core_xy, clustering.core_cluster, added_xy, eps_pred_m).point] = False
    each_geotag_alone = np.arange(len(geotag_xy))
    keep[match_to_clusters(geotag_xy, each_geotag_alone, added_xy, eps_pred_m).point] = False
    return keep


@dataclass
class ReviewedFlight:
    """What POST scoring needs of one flight: PRE counts, per-cluster hit flags and attached unit
    keys, and ``a``, the number of added targets that count for the flight
    (:func:`countable_added_targets`)."""

    counts: PreCounts
    cluster_hit: Sequence[bool]
    cluster_units: Sequence[Sequence[str]]
    n_added: int = 0


@dataclass
class PostCounts:
    n_in_view: int = 0
    n_recovered: int = 0
    n_clusters: int = 0
    n_hit_clusters: int = 0
    c: int = 0
    a: int = 0

    def __add__(self, other: "PostCounts") -> "PostCounts":
        return PostCounts(*(getattr(self, f.name) + getattr(other, f.name) for f in fields(PostCounts)))

    @property
    def gmcf_post(self):
        return ratio(self.n_hit_clusters + self.c, self.n_clusters)

    @property
    def recall_post(self):
        return ratio(self.n_recovered + self.c, self.n_in_view + self.c + self.a)

    @property
    def recall_post_is_bound(self) -> bool:
        """Only with a = 0 is recall_post printed "≥ x", a lower bound on the recall over the known
        targets; with a > 0 it is a point value under :data:`POINT_VALUE_ASSUMPTIONS`."""
        return self.a == 0

    def recall_post_text(self) -> str | None:
        value = self.recall_post
        if value is None:
            return None
        return f"≥ {value:.3f}" if self.recall_post_is_bound else f"{value:.3f}"

    def to_dict(self) -> dict:
        return {"c": int(self.c), "a": int(self.a), "n_hit_clusters": int(self.n_hit_clusters),
                "n_clusters": int(self.n_clusters), "n_recovered": int(self.n_recovered),
                "n_in_view": int(self.n_in_view), "gmcf_post": self.gmcf_post,
                "recall_post_value": self.recall_post,
                "recall_post_kind": "lower_bound" if self.recall_post_is_bound else "point_value",
                "recall_post": self.recall_post_text()}


@dataclass
class PostScores:
    """POST counts of one convention: per flight and pooled (micro-averaged)."""

    convention: str
    flights: list
    pooled: PostCounts


def post_scores(log: VerdictLog, flights: Sequence[ReviewedFlight],
                conventions: Sequence[str] = CONVENTIONS) -> dict:
    """``{convention: PostScores}`` for reviewed flights (see the module docstring)."""
    out = {}
    for convention in conventions:
        per_flight = []
        for flight in flights:
            c = sum(1 for hit, units in zip(flight.cluster_hit, flight.cluster_units)
                    if not hit and units and log.resolve_cluster(units, convention) == CONFIRMED)
            k = flight.counts
            per_flight.append(PostCounts(k.n_in_view, k.n_recovered, k.n_clusters, k.n_hit_clusters, c,
                                         int(flight.n_added)))
        pooled = PostCounts()
        for p in per_flight:
            pooled = pooled + p
        out[convention] = PostScores(convention, per_flight, pooled)
    return out

"""Scores after review: GMCF and recall with confirmed clusters and added targets."""
from __future__ import annotations

from dataclasses import dataclass, fields
from typing import Sequence

from .pre_review import PreCounts, ratio
from .verdicts import CONFIRMED, CONVENTIONS, VerdictLog, combine


@dataclass
class ReviewedFlight:
    """What POST scoring needs of one flight: PRE counts, per-cluster hit flags and attached unit
    keys, and the number of added targets in view of the flight."""

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
    def recall_post_bound(self):
        return ratio(self.n_recovered + self.c, self.n_in_view + self.c + self.a)

    def to_dict(self) -> dict:
        bound = self.recall_post_bound
        return {"c": int(self.c), "a": int(self.a), "n_hit_clusters": int(self.n_hit_clusters),
                "n_clusters": int(self.n_clusters), "n_recovered": int(self.n_recovered),
                "n_in_view": int(self.n_in_view), "gmcf_post": self.gmcf_post,
                "recall_post_bound": bound,
                "recall_post": None if bound is None else f"≥ {bound:.3f}"}


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
        resolved: dict[str, str] = {}
        per_flight = []
        for flight in flights:
            c = 0
            for hit, units in zip(flight.cluster_hit, flight.cluster_units):
                if hit or not units:
                    continue
                for u in units:
                    if u not in resolved:
                        resolved[u] = log.resolve(u, convention)
                if combine((resolved[u] for u in units), convention) == CONFIRMED:
                    c += 1
            k = flight.counts
            per_flight.append(PostCounts(k.n_in_view, k.n_recovered, k.n_clusters, k.n_hit_clusters, c,
                                         int(flight.n_added)))
        pooled = PostCounts()
        for p in per_flight:
            pooled = pooled + p
        out[convention] = PostScores(convention, per_flight, pooled)
    return out

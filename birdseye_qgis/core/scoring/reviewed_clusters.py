"""What a review decided about each cluster it scored: the input of the review loop.

The clusters are those of :func:`.evaluation.evaluate_flights` (the scoring of
``birdseye:evaluatedetections``) and the verdicts attach to them as they do for ``c`` in the POST
scores (:func:`.verdicts.units_of_clusters`), so a cluster counted in ``c`` is a cluster that
becomes a label here.

A cluster's **outcome** is read over all direct and propagated judgements of its units:

* ``confirmed_real`` / ``hard_negative`` — every vote says so (all three conventions agree);
* ``conflicting`` — votes on both sides: the conventions resolve it differently, so the review
  has not settled it whatever the convention (a majority of one is no training label);
* ``uncertain`` — only abstentions; ``unreviewed`` — nobody judged it.

Clusters that match an in-view geotag (``hit``) are settled by the survey whatever the review says.
Of the others, confirmed clusters become training targets (provenance ``review``), hard negatives
become hard-negative tiles (``birdseye:writelabels``), and the rest are **unresolved**: the next
flight or walk should visit them (``birdseye:planflight``, ``birdseye:preparefieldsurvey``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .evaluation import Evaluation
from .verdicts import CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED, VerdictLog

CONFLICTING = "conflicting"
OUTCOMES = (CONFIRMED, HARD_NEGATIVE, CONFLICTING, UNCERTAIN, UNREVIEWED)
UNRESOLVED = (CONFLICTING, UNCERTAIN, UNREVIEWED)


def cluster_outcome(log: VerdictLog, unit_keys) -> str:
    """The outcome of a cluster from the judgements of its units (see the module docstring)."""
    lenient = log.resolve_cluster(unit_keys, "positive_wins")
    strict = log.resolve_cluster(unit_keys, "hard_negative_wins")
    return lenient if lenient == strict else CONFLICTING


@dataclass(frozen=True)
class ReviewedCluster:
    """One scored cluster: where it is (its centroid, WGS84 degrees), whether a geotag matches it and
    what the review made of it; ``unit_keys``: the review units its verdicts attach to
    (``Evaluation``'s ``cluster_units``), which a verdict on the cluster from the field is written against."""

    flight: str
    cluster_id: int
    lat: float
    lon: float
    hit: bool
    outcome: str
    n_detections: int
    unit_keys: tuple = ()

    @property
    def key(self) -> str:
        """Names the cluster in labels and waypoints: ``<detection layer>#<cluster id>``."""
        return f"{self.flight}#{self.cluster_id}"

    @property
    def is_target(self) -> bool:
        """A real target nobody surveyed: confirmed and matched by no geotag."""
        return not self.hit and self.outcome == CONFIRMED

    @property
    def is_hard_negative(self) -> bool:
        return not self.hit and self.outcome == HARD_NEGATIVE

    @property
    def is_unresolved(self) -> bool:
        return not self.hit and self.outcome in UNRESOLVED


def reviewed_clusters(evaluation: Evaluation, log: VerdictLog) -> list[ReviewedCluster]:
    """Every cluster of every flight of an evaluation made with ``log`` (``evaluate_flights(..., log)``),
    with its outcome, in flight and cluster order."""
    out = []
    for flight in evaluation.flights:
        n = flight.clustering.n_clusters
        if n == 0:
            continue
        centroid = np.asarray(flight.clustering.summary.centroid, dtype=float).reshape(-1, 2)
        lat, lon, _ = evaluation.local.to_geodetic(np.column_stack([centroid, np.zeros(n)]))
        lat, lon = np.atleast_1d(lat), np.atleast_1d(lon)
        units = flight.cluster_units or [()] * n
        for k in range(n):
            out.append(ReviewedCluster(flight.name, k, float(lat[k]), float(lon[k]),
                                       bool(flight.score.cluster_hit[k]), cluster_outcome(log, units[k]),
                                       int(flight.clustering.summary.n_detections[k]), tuple(units[k])))
    return out


def outcome_counts(clusters) -> dict:
    """How many clusters end in each outcome, and how many of them match a geotag."""
    counts = {name: sum(1 for c in clusters if not c.hit and c.outcome == name) for name in OUTCOMES}
    counts["hit"] = sum(1 for c in clusters if c.hit)
    return counts

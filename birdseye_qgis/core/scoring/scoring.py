"""Honest scores for a detector: recall and the geotag-matched cluster fraction, before and after review.

Definitions (issue "Clusters on the map and honest scores"; the help texts repeat them)
-------------------------------------------------------------------------------------
Detections of all processed frames are back-projected, de-duplicated on a ``dedup_cm`` grid and
clustered with DBSCAN (``eps_m``, ``min_samples``) in a local metric frame (:mod:`.clustering`).

* A geotag is **in view** when it passes the in-frame test (:func:`~.projection.project_in_view`
  over :class:`~.ground.LevelPlaneGround`, ``edge_buffer_px``) in at least one processed frame.
  "Processed" = every frame of the frame layer given (detect ran on all of them); frames without a
  ground height are left out, as detect skips them.
* An in-view geotag is **recovered** when it lies within ``eps_pred_m`` (horizontal distance,
  ``d ≤ eps_pred_m``) of a *core* point of some cluster.
* A cluster is a **hit** when at least one in-view geotag lies within ``eps_pred_m`` of its core
  points. A geotag near two clusters makes both hits; a cluster near two geotags is one hit.
* ``recall_pre = n_recovered / n_in_view``;
  ``gmcf_pre = n_hit_clusters / n_clusters`` — the geotag-matched cluster fraction, a *lower bound on
  precision, not precision*: surveys are never exhaustive, so an unmatched cluster may be real.
* After review (``c`` = clusters confirmed real and not hit, ``a`` = targets a reviewer added that
  are in view): ``gmcf_post = (n_hit_clusters + c) / n_clusters`` and
  ``recall_post ≥ (n_recovered + c) / (n_in_view + c + a)``, printed with "≥" as the method writes it;
  real targets nobody surveyed, found or added are in no term, so the figure bounds the recall over
  all real targets from above. Computed under each tie-break convention (:data:`CONVENTIONS`).
* No F1 is reported in geospatial units (screening's pixel-space F1 is for choosing checkpoints only).
* Several flights pool by **micro-averaging**: numerators and denominators are summed over flights,
  then divided once (:meth:`PreCounts.__add__`); ratios are never averaged. A geotag in view in two
  flights counts once per flight.

Verdict log API (for the review dock, issue 9)
----------------------------------------------
The dock stores an append-only table; this module needs from each row only::

    unit_key    str   the review unit (a consensus cluster) or an added target
    verdict     str   "confirmed_real" | "hard_negative" | "uncertain" | "unreviewed" | "added"
    provenance  str   "direct", or "propagated:<rule>" (e.g. "propagated:dbscan_0.20m")
    time        str   ISO 8601 (naive = UTC); informational order key, see below
    reviewer    str
    lat, lon    float WGS84 degrees of the unit's centroid / of the added target (required for
                      "added" rows; on unit rows it lets a *headless* scorer place the unit)
    sequence    int   append order (the GeoPackage fid); defaults to the position in the input

Rules (:class:`VerdictLog`):

1. Per (unit_key, provenance) the **latest** row wins: largest (time, sequence). An "unreviewed" row
   withdraws that provenance's vote (undo); an "added" row is undone the same way.
2. A unit's **votes** are the latest verdicts of its provenances, "unreviewed" dropped. They resolve
   under a convention (:func:`combine`):
   ``positive_wins`` — confirmed_real if any vote says so, else hard_negative if any, else uncertain;
   ``hard_negative_wins`` — hard_negative if any, else confirmed_real if any, else uncertain;
   ``majority_wins`` — the verdict with the most votes; a tie between the leaders is "uncertain".
   No vote at all → "unreviewed".
3. A cluster of a detection layer takes the resolved verdicts of the units attached to it (the dock
   knows them; headless, :func:`units_of_clusters` attaches every unit whose position lies within
   ``eps_pred_m`` of the cluster's core points) and combines them under the same convention.
4. ``c`` counts the clusters that are not hits and resolve to confirmed_real; ``a`` counts the added
   targets in view of the flight (same in-view test as geotags).

Feeding it: ``log = VerdictLog.from_records(rows)`` (mappings with the fields above, e.g. GeoPackage
features as dicts in fid order), then per flight a :class:`ReviewedFlight` (its :class:`PreCounts`,
per-cluster hit flags and attached unit keys, and ``n_added``), and
``post_scores(log, flights) -> {convention: PostScores}``. :func:`evaluate_flights` does all of it
from geodetic inputs, exactly as ``birdseye:evaluatedetections`` does.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field, fields
from datetime import datetime, timezone
from typing import Iterable, Mapping, Sequence

import numpy as np

from ..detect.clustering import (DEFAULT_DEDUP_CM, DEFAULT_EPS_M, DEFAULT_MIN_SAMPLES, Clustering,
                         cluster_centroids_and_extents, cluster_detections, dbscan, deduplicate,
                         neighbour_graph)
from ..errors import Cancelled, InputError
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import project_in_view

DEFAULT_EPS_PRED_M = 0.20
DEFAULT_EDGE_BUFFER_PX = 0.0
#: Credibility filter of sweeps (both are parameters of sweepoperatingpoints).
DEFAULT_MAX_GEOTAGS_PER_HIT = 1.5
DEFAULT_MAX_MEAN_EXTENT_M = 1.0
#: Health guards of checkpoint screening (both are parameters of screencheckpoints).
DEFAULT_COLLAPSED_BELOW = 0.05
DEFAULT_SPARSE_BELOW = 1.7
DEFAULT_PIXEL_RADIUS_PX = 10.0

CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED, ADDED = (
    "confirmed_real", "hard_negative", "uncertain", "unreviewed", "added")
VERDICTS = (CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED)
CONVENTIONS = ("positive_wins", "majority_wins", "hard_negative_wins")
DIRECT = "direct"
PROPAGATED_PREFIX = "propagated:"


# ====================================================================================== parameters
@dataclass(frozen=True)
class OperatingPoint:
    """A full operating point: detection threshold and the clustering/scoring parameters."""

    threshold: float | None = None
    dedup_cm: float = DEFAULT_DEDUP_CM
    eps_m: float = DEFAULT_EPS_M
    min_samples: int = DEFAULT_MIN_SAMPLES
    eps_pred_m: float = DEFAULT_EPS_PRED_M
    edge_buffer_px: float = DEFAULT_EDGE_BUFFER_PX

    def __post_init__(self):
        for name in ("dedup_cm", "eps_m", "eps_pred_m"):
            if not getattr(self, name) > 0:
                raise InputError(f"must be larger than 0 (got {getattr(self, name)})", field=name.upper())
        if int(self.min_samples) != self.min_samples or self.min_samples < 1:
            raise InputError(f"must be a whole number ≥ 1 (got {self.min_samples})", field="MIN_SAMPLES")
        if self.threshold is not None and not 0.0 <= self.threshold <= 1.0:
            raise InputError(f"must be a probability in [0, 1] (got {self.threshold})", field="THRESHOLD")
        if self.edge_buffer_px < 0:
            raise InputError(f"must be ≥ 0 px (got {self.edge_buffer_px})", field="EDGE_BUFFER_PX")

    def to_dict(self) -> dict:
        return {"threshold": None if self.threshold is None else float(self.threshold),
                "dedup_cm": float(self.dedup_cm), "eps_m": float(self.eps_m),
                "min_samples": int(self.min_samples), "eps_pred_m": float(self.eps_pred_m),
                "edge_buffer_px": float(self.edge_buffer_px)}

    @classmethod
    def from_dict(cls, d: Mapping, source: str = "operating point") -> "OperatingPoint":
        unknown = set(d) - {f.name for f in fields(cls)}
        if unknown:
            raise InputError(f"has unknown key(s) {', '.join(sorted(unknown))}", source=source)
        try:
            return cls(**{k: (None if v is None else (int(v) if k == "min_samples" else float(v)))
                          for k, v in d.items()})
        except (TypeError, ValueError) as exc:
            raise InputError(f"has a value that is not a number ({exc})", source=source) from exc


# ====================================================================================== in view
@dataclass
class InView:
    """``mask`` (G,) True for points in view of at least one processed frame; frame counts."""

    mask: np.ndarray
    n_frames: int
    n_frames_without_ground: int


def in_view(pose_groups: Sequence[FramePoses], local: LocalFrame, points, edge_buffer_px: float = 0.0,
            progress=None, is_canceled=None) -> InView:
    """Which local points (G, 3) pass the in-frame test in at least one frame of ``pose_groups``.

    Frames without a ground height are left out (detect skips them, so they were not processed).
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    mask = np.zeros(len(points), dtype=bool)
    n_frames = n_skipped = 0
    for g, poses in enumerate(pose_groups):
        if is_canceled is not None and is_canceled():
            raise Cancelled()
        has_ground = np.isfinite(poses.ground_height)
        n_skipped += int((~has_ground).sum())
        if not has_ground.all():
            poses = poses.subset(np.flatnonzero(has_ground))
        n_frames += len(poses)
        if len(poses) and len(points):
            geom = FrameGeometry(poses, local)
            proj = project_in_view(geom, points, LevelPlaneGround(geom), edge_buffer_px)
            mask[proj.point_idx] = True
        if progress is not None:
            progress((g + 1) / len(pose_groups))
    return InView(mask, n_frames, n_skipped)


# ====================================================================================== matching
@dataclass
class Matches:
    """(point, cluster) pairs with the smallest distance (m) from the point to the cluster's core points."""

    point: np.ndarray
    cluster: np.ndarray
    distance: np.ndarray

    def within(self, radius_m: float) -> "Matches":
        keep = self.distance <= radius_m
        return Matches(self.point[keep], self.cluster[keep], self.distance[keep])


def match_to_clusters(core_xy, core_cluster, points_xy, radius_m: float) -> Matches:
    """Every (point, cluster) pair with a core point of the cluster within ``radius_m`` of the point."""
    from scipy.spatial import cKDTree

    core_xy = np.asarray(core_xy, dtype=float).reshape(-1, 2)
    points_xy = np.asarray(points_xy, dtype=float).reshape(-1, 2)
    empty = Matches(np.empty(0, np.int64), np.empty(0, np.int64), np.empty(0))
    if len(core_xy) == 0 or len(points_xy) == 0:
        return empty
    hits = cKDTree(core_xy).query_ball_point(points_xy, radius_m * (1 + 1e-9), return_sorted=False)
    counts = np.fromiter((len(h) for h in hits), dtype=np.int64, count=len(hits))
    if counts.sum() == 0:
        return empty
    point = np.repeat(np.arange(len(points_xy)), counts)
    core = np.fromiter((i for h in hits for i in h), dtype=np.int64, count=int(counts.sum()))
    d = np.hypot(points_xy[point, 0] - core_xy[core, 0], points_xy[point, 1] - core_xy[core, 1])
    cluster = np.asarray(core_cluster, dtype=np.int64)[core]
    keep = d <= radius_m
    point, cluster, d = point[keep], cluster[keep], d[keep]
    order = np.lexsort((d, cluster, point))
    point, cluster, d = point[order], cluster[order], d[order]
    first = np.ones(len(point), dtype=bool)
    first[1:] = (point[1:] != point[:-1]) | (cluster[1:] != cluster[:-1])
    return Matches(point[first], cluster[first], d[first])


# ====================================================================================== PRE scores
def _ratio(num, den):
    return None if den == 0 else float(num) / float(den)


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
        return _ratio(self.n_recovered, self.n_in_view)

    @property
    def gmcf_pre(self):
        return _ratio(self.n_hit_clusters, self.n_clusters)

    @property
    def mean_geotags_per_hit_cluster(self):
        return _ratio(self.n_geotag_matches, self.n_hit_clusters)

    @property
    def mean_median_extent_m(self):
        return _ratio(self.sum_median_extent_m, self.n_clusters)

    def to_dict(self) -> dict:
        return {"n_in_view": int(self.n_in_view), "n_recovered": int(self.n_recovered),
                "recall_pre": self.recall_pre, "n_clusters": int(self.n_clusters),
                "n_hit_clusters": int(self.n_hit_clusters), "gmcf_pre": self.gmcf_pre,
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


# ====================================================================================== verdicts
@dataclass(frozen=True)
class Verdict:
    """One row of the verdict log (see the module docstring)."""

    unit_key: str
    verdict: str
    provenance: str = DIRECT
    time: str = ""
    reviewer: str = ""
    lat: float | None = None
    lon: float | None = None
    sequence: int = 0


def _time_key(text: str, source: str, row: int) -> float:
    if not text:
        return -math.inf
    try:
        t = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    except ValueError as exc:
        raise InputError(f"'{text}' is not an ISO 8601 time (e.g. 2024-05-01T14:03:00Z)", source=source,
                         row=row, field="time") from exc
    if t.tzinfo is None:
        t = t.replace(tzinfo=timezone.utc)
    return t.timestamp()


def combine(verdicts: Iterable[str], convention: str) -> str:
    """Resolve votes (verdict strings) under a tie-break convention; "unreviewed" votes are ignored."""
    votes = [v for v in verdicts if v != UNREVIEWED]
    if convention not in CONVENTIONS:
        raise ValueError(f"unknown convention {convention!r}; expected one of {CONVENTIONS}")
    if not votes:
        return UNREVIEWED
    if convention == "positive_wins":
        order = (CONFIRMED, HARD_NEGATIVE, UNCERTAIN)
    elif convention == "hard_negative_wins":
        order = (HARD_NEGATIVE, CONFIRMED, UNCERTAIN)
    else:
        tally = {v: votes.count(v) for v in (CONFIRMED, HARD_NEGATIVE, UNCERTAIN)}
        best = max(tally.values())
        leaders = [v for v, n in tally.items() if n == best]
        return leaders[0] if len(leaders) == 1 else UNCERTAIN
    return next(v for v in order if v in votes)


class VerdictLog:
    """The latest verdict per (unit_key, provenance) of an append-only log, and how units resolve."""

    def __init__(self, rows: Iterable[Verdict] = (), source: str = "verdict log"):
        self.source = source
        latest: dict[tuple[str, str], tuple[tuple[float, int], Verdict]] = {}
        for n, row in enumerate(rows, start=1):
            self._check(row, n)
            key = (_time_key(row.time, source, n), row.sequence)
            slot = (row.unit_key, row.provenance)
            if slot not in latest or key >= latest[slot][0]:
                latest[slot] = (key, row)
        self.latest = {slot: row for slot, (_, row) in latest.items()}
        self._by_unit: dict[str, list[Verdict]] = {}
        for (unit, _), row in sorted(self.latest.items()):
            self._by_unit.setdefault(unit, []).append(row)

    def _check(self, row: Verdict, n: int) -> None:
        if not row.unit_key:
            raise InputError("is empty; every verdict needs its unit key", source=self.source, row=n,
                             field="unit_key")
        if row.verdict not in VERDICTS + (ADDED,):
            raise InputError(f"'{row.verdict}' is not a verdict (expected one of "
                             f"{', '.join(VERDICTS + (ADDED,))})", source=self.source, row=n, field="verdict")
        if row.provenance != DIRECT and not (row.provenance.startswith(PROPAGATED_PREFIX)
                                             and len(row.provenance) > len(PROPAGATED_PREFIX)):
            raise InputError(f"'{row.provenance}' is not a provenance (expected 'direct' or "
                             "'propagated:<rule>')", source=self.source, row=n, field="provenance")
        if row.verdict == ADDED and (row.lat is None or row.lon is None
                                     or not (math.isfinite(row.lat) and math.isfinite(row.lon))):
            raise InputError("an added target needs its position (lat, lon)", source=self.source, row=n,
                             field="lat")

    @classmethod
    def from_records(cls, records: Iterable[Mapping], source: str = "verdict log") -> "VerdictLog":
        """A log from mappings (rows in append order); missing optional fields take their defaults."""
        rows = []
        for n, rec in enumerate(records, start=1):
            missing = [k for k in ("unit_key", "verdict") if k not in rec]
            if missing:
                raise InputError(f"has no field(s) {', '.join(missing)}: not a BirdsEye verdict log",
                                 source=source, row=n)

            def text(name, default=""):
                v = rec.get(name)
                return default if v is None else str(v).strip()

            def number(name):
                v = rec.get(name)
                if v is None or v == "":
                    return None
                try:
                    return float(v)
                except (TypeError, ValueError) as exc:
                    raise InputError(f"'{v}' is not a number", source=source, row=n, field=name) from exc

            seq = rec.get("sequence", rec.get("fid"))
            rows.append(Verdict(text("unit_key"), text("verdict"), text("provenance", DIRECT) or DIRECT,
                                text("time"), text("reviewer"), number("lat"), number("lon"),
                                int(seq) if seq not in (None, "") else n))
        return cls(rows, source)

    def votes(self, unit_key: str) -> list[str]:
        """Latest verdict of each provenance of a unit ("unreviewed" and "added" dropped)."""
        return [r.verdict for r in self._by_unit.get(unit_key, ()) if r.verdict in (CONFIRMED, HARD_NEGATIVE,
                                                                                   UNCERTAIN)]

    def resolve(self, unit_key: str, convention: str) -> str:
        return combine(self.votes(unit_key), convention)

    def unit_keys(self) -> list[str]:
        """Units with at least one vote."""
        return [u for u in self._by_unit if self.votes(u)]

    def unit_positions(self):
        """(keys, lat, lon) of voted units whose latest rows carry a position, and keys without one."""
        keys, lat, lon, unplaced = [], [], [], []
        for unit in self.unit_keys():
            placed = [r for r in self._by_unit[unit] if r.lat is not None and r.lon is not None]
            if placed:
                keys.append(unit)
                lat.append(placed[0].lat)
                lon.append(placed[0].lon)
            else:
                unplaced.append(unit)
        return keys, np.asarray(lat, dtype=float), np.asarray(lon, dtype=float), unplaced

    def added_targets(self) -> list[Verdict]:
        """Targets whose latest direct row is "added" (a later "unreviewed" row withdraws one)."""
        out = []
        for unit, rows in self._by_unit.items():
            direct = [r for r in rows if r.provenance == DIRECT]
            if direct and direct[0].verdict == ADDED:
                out.append(direct[0])
        return out


def units_of_clusters(clustering: Clustering, unit_xy, unit_keys: Sequence[str], radius_m: float) -> list:
    """Unit keys attached to each cluster: units within ``radius_m`` of one of its core points."""
    m = match_to_clusters(clustering.core_xy, clustering.core_cluster, unit_xy, radius_m)
    out = [[] for _ in range(clustering.n_clusters)]
    for p, c in zip(m.point.tolist(), m.cluster.tolist()):
        out[c].append(unit_keys[p])
    return [tuple(u) for u in out]


# ====================================================================================== POST scores
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
        return _ratio(self.n_hit_clusters + self.c, self.n_clusters)

    @property
    def recall_post_bound(self):
        return _ratio(self.n_recovered + self.c, self.n_in_view + self.c + self.a)

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


# ====================================================================================== evaluation
@dataclass
class Detections:
    """One detection layer: WGS84 positions (ellipsoidal heights, NaN allowed), frame ids, scores."""

    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    frame_id: np.ndarray
    score: np.ndarray
    name: str = "detections"
    model: str = ""
    model_digest: str = ""
    threshold: float | None = None

    def __post_init__(self):
        for n in ("lat", "lon", "height", "score"):
            setattr(self, n, np.asarray(getattr(self, n), dtype=float).reshape(-1))
        self.frame_id = np.asarray(self.frame_id).reshape(-1)

    def __len__(self) -> int:
        return len(self.lat)

    def local_xy(self, local: LocalFrame) -> np.ndarray:
        h = np.where(np.isfinite(self.height), self.height, local.h0)
        return local.from_geodetic(self.lat, self.lon, h)[:, :2] if len(self) else np.empty((0, 2))


@dataclass
class Flight:
    """One flight to score: its detections and its processed frames (pose groups, one per camera)."""

    detections: Detections
    pose_groups: Sequence[FramePoses]
    name: str = ""


@dataclass
class Geotags:
    """Surveyed targets: ids and WGS84 positions (heights may be NaN: the ground model places them)."""

    ids: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray

    def __post_init__(self):
        self.ids = np.asarray(self.ids).reshape(-1)
        for n in ("lat", "lon", "height"):
            setattr(self, n, np.asarray(getattr(self, n), dtype=float).reshape(-1))

    def __len__(self) -> int:
        return len(self.lat)

    def subset(self, index) -> "Geotags":
        return Geotags(self.ids[index], self.lat[index], self.lon[index], self.height[index])


@dataclass
class FlightEvaluation:
    name: str
    clustering: Clustering
    score: FlightScore
    in_view: InView
    n_detections: int
    n_added_in_view: int = 0
    cluster_units: list = field(default_factory=list)


@dataclass
class Evaluation:
    """PRE (and POST when reviewed) scores of one or several flights, and the local frame used."""

    op: OperatingPoint
    local: LocalFrame
    flights: list
    pooled: PreCounts
    post: dict | None = None
    review_notes: list = field(default_factory=list)

    def to_dict(self) -> dict:
        """The JSON of evaluatedetections: pooled keys at the top, per-flight rows, the POST block."""
        out = dict(self.pooled.to_dict())
        out["parameters"] = self.op.to_dict()
        out["pooling"] = "micro-average over flights (sums of counts, one division)"
        out["flights"] = []
        for i, f in enumerate(self.flights):
            row = {"name": f.name, "n_detections": int(f.n_detections), "n_frames": int(f.in_view.n_frames),
                   "n_frames_without_ground": int(f.in_view.n_frames_without_ground)}
            row.update(f.score.counts.to_dict())
            if self.post is not None:
                row["post"] = {conv: p.flights[i].to_dict() for conv, p in self.post.items()}
            out["flights"].append(row)
        if self.post is not None:
            out["post"] = {conv: p.pooled.to_dict() for conv, p in self.post.items()}
            out["review_notes"] = list(self.review_notes)
        return out


def local_frame_for(pose_groups: Sequence[FramePoses], geotags: Geotags | None = None) -> LocalFrame:
    """A local frame at the middle of every frame (and geotag) position, at the median ground height."""
    pose_groups = list(pose_groups)
    lat = np.concatenate([p.lat for p in pose_groups] +
                         ([geotags.lat] if geotags is not None and len(geotags) else []))
    lon = np.concatenate([p.lon for p in pose_groups] +
                         ([geotags.lon] if geotags is not None and len(geotags) else []))
    h = np.concatenate([p.ground_height for p in pose_groups] or [np.empty(0)])
    if len(lat) == 0:
        raise InputError("there are no frames to score against")
    return LocalFrame.around(lat, lon, h[np.isfinite(h)] if np.isfinite(h).any() else None)


def evaluate_flights(flights: Sequence[Flight], geotags: Geotags, op: OperatingPoint = OperatingPoint(),
                     log: VerdictLog | None = None, local: LocalFrame | None = None,
                     progress=None, is_canceled=None) -> Evaluation:
    """Cluster and score every flight, pool them, and compute POST scores when a verdict log is given.

    Detections below ``op.threshold`` (when set) are left out before clustering.
    """
    if not flights:
        raise InputError("give at least one detection layer")
    local = local or local_frame_for([p for f in flights for p in f.pose_groups], geotags)
    geotag_local = local.from_geodetic(geotags.lat, geotags.lon,
                                       np.where(np.isfinite(geotags.height), geotags.height, local.h0)) \
        if len(geotags) else np.empty((0, 3))
    unit_keys, unit_xy, added_local, notes = [], np.empty((0, 2)), np.empty((0, 3)), []
    if log is not None:
        unit_keys, ulat, ulon, unplaced = log.unit_positions()
        if len(unit_keys):
            unit_xy = local.from_geodetic(ulat, ulon, np.full(len(ulat), local.h0))[:, :2]
        if unplaced:
            notes.append(f"{len(unplaced)} reviewed unit(s) have no position (lat, lon) and could not be "
                         f"attached to clusters, e.g. {', '.join(unplaced[:3])}")
        added = log.added_targets()
        if added:
            added_local = local.from_geodetic([r.lat for r in added], [r.lon for r in added],
                                              np.full(len(added), local.h0))
    results = []
    n = len(flights)
    for i, flight in enumerate(flights):
        if is_canceled is not None and is_canceled():
            raise Cancelled()
        det = flight.detections
        keep = np.ones(len(det), dtype=bool) if op.threshold is None else det.score >= op.threshold
        xy = det.local_xy(local)[keep]
        clustering = cluster_detections(xy, det.frame_id[keep], det.score[keep], op.dedup_cm, op.eps_m,
                                        op.min_samples)
        view = in_view(flight.pose_groups, local, geotag_local, op.edge_buffer_px)
        score = score_flight(clustering, geotag_local[:, :2], view.mask, op.eps_pred_m)
        ev = FlightEvaluation(flight.name or det.name, clustering, score, view, int(keep.sum()))
        if log is not None:
            ev.cluster_units = units_of_clusters(clustering, unit_xy, unit_keys, op.eps_pred_m)
            if len(added_local):
                ev.n_added_in_view = int(in_view(flight.pose_groups, local, added_local, op.edge_buffer_px).mask.sum())
        results.append(ev)
        if progress is not None:
            progress((i + 1) / n)
    pooled = pool(r.score.counts for r in results)
    post = None
    if log is not None:
        post = post_scores(log, [ReviewedFlight(r.score.counts, r.score.cluster_hit, r.cluster_units,
                                                r.n_added_in_view) for r in results])
    return Evaluation(op, local, results, pooled, post, notes)


# ====================================================================================== sweeps
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


# ====================================================================================== screening
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
        return _ratio(2 * self.pixel_tp, 2 * self.pixel_tp + self.pixel_fp + self.pixel_fn)

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


# ====================================================================================== reports
def figure_data_uri(fig) -> str:
    """A matplotlib figure as a base64 PNG data URI (for self-contained HTML reports)."""
    import base64
    import io

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=110, bbox_inches="tight")
    return "data:image/png;base64," + base64.b64encode(buf.getvalue()).decode("ascii")


def new_figure(width_in: float, height_in: float):
    """A matplotlib Figure drawn by Agg without pyplot: safe in QGIS's worker threads, whatever
    backend the desktop uses."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width_in, height_in))
    FigureCanvasAgg(fig)
    return fig


def html_table(header: Sequence[str], rows: Iterable[Sequence]) -> str:
    import html

    def cell(v):
        if v is None:
            return "–"
        if isinstance(v, float):
            return f"{v:.3f}"
        return html.escape(str(v))

    head = "".join(f"<th>{html.escape(h)}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{cell(v)}</td>" for v in row) + "</tr>" for row in rows)
    return f"<table><tr>{head}</tr>{body}</table>"


def html_page(title: str, body: str) -> str:
    import html

    style = ("body{font-family:sans-serif;max-width:60em;margin:1em auto;color:#222}"
             "table{border-collapse:collapse;margin:.5em 0}td,th{border:1px solid #bbb;padding:.2em .5em;"
             "text-align:right}th{background:#eee}td:first-child{text-align:left}"
             ".note{color:#555;font-size:90%}img{max-width:100%}")
    return (f"<!DOCTYPE html><html><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{style}</style></head><body><h1>{html.escape(title)}</h1>{body}</body></html>")


def evaluation_report_html(evaluation: Evaluation) -> str:
    """The map-free HTML report of evaluatedetections: definitions, tables and plots."""
    import html

    d = evaluation.to_dict()
    rows = [[f["name"], f["n_frames"], f["n_detections"], f["n_in_view"], f["n_recovered"], f["recall_pre"],
             f["n_clusters"], f["n_hit_clusters"], f["gmcf_pre"]] for f in d["flights"]]
    rows.append(["pooled (micro-average)", sum(f["n_frames"] for f in d["flights"]),
                 sum(f["n_detections"] for f in d["flights"]), d["n_in_view"], d["n_recovered"],
                 d["recall_pre"], d["n_clusters"], d["n_hit_clusters"], d["gmcf_pre"]])
    body = ["<h2>Before review</h2>",
            html_table(["flight", "frames", "detections", "geotags in view", "recovered", "recall_pre",
                        "clusters", "hit clusters", "gmcf_pre"], rows),
            "<p class='note'>recall_pre = recovered / in view. gmcf_pre = hit clusters / clusters: the "
            "geotag-matched cluster fraction, a lower bound on precision, not precision (surveys are never "
            "exhaustive). Flights pool by micro-averaging: counts are summed, then divided once.</p>"]
    op = evaluation.op.to_dict()
    body.append("<p class='note'>" + ", ".join(f"{k} = {v}" for k, v in op.items() if v is not None) + "</p>")
    if evaluation.post is not None:
        post_rows = [[conv, p["c"], p["a"], p["gmcf_post"], p["recall_post"]] for conv, p in d["post"].items()]
        body += ["<h2>After review</h2>",
                 html_table(["convention", "c (confirmed, not hit)", "a (added)", "gmcf_post", "recall_post"],
                            post_rows),
                 "<p class='note'>gmcf_post = (hit clusters + c) / clusters; recall_post ≥ (recovered + c) / "
                 "(in view + c + a). Real targets nobody surveyed, found or added are in no term, so the "
                 "recall figure is an upper bound on the recall over all real targets. The spread between "
                 "the conventions is part of the result.</p>"]
        for note in d["review_notes"]:
            body.append(f"<p class='note'>{html.escape(note)}</p>")

    fig = new_figure(10, 3.6)
    axes = fig.subplots(1, 2)
    names = [r[0] for r in rows]
    x = np.arange(len(rows))
    for off, key, label in ((-0.2, 5, "recall_pre"), (0.2, 8, "gmcf_pre")):
        axes[0].bar(x + off, [np.nan if r[key] is None else r[key] for r in rows], 0.4, label=label)
    axes[0].set_xticks(x, names, rotation=20, ha="right", fontsize=8)
    axes[0].set_ylim(0, 1.05)
    axes[0].legend(fontsize=8)
    axes[0].set_title("Scores per flight and pooled", fontsize=10)
    sizes_hit = np.concatenate([f.clustering.summary.n_detections[f.score.cluster_hit] for f in evaluation.flights])
    sizes_miss = np.concatenate([f.clustering.summary.n_detections[~f.score.cluster_hit] for f in evaluation.flights])
    top = max(2, int(max(sizes_hit.max(initial=1), sizes_miss.max(initial=1))))
    bins = np.unique(np.geomspace(1, top + 1, 20).astype(int))
    axes[1].hist([sizes_hit, sizes_miss], bins=bins, label=["hit clusters", "unmatched clusters"], stacked=True)
    axes[1].set_xscale("log")
    axes[1].set_xlabel("detections per cluster")
    axes[1].set_ylabel("clusters")
    axes[1].legend(fontsize=8)
    axes[1].set_title("Cluster sizes", fontsize=10)
    body.append(f"<img alt='scores and cluster sizes' src='{figure_data_uri(fig)}'>")
    return html_page("BirdsEye — detection scores", "".join(body))


def frontier_figure(points, title: str):
    """Scatter of (gmcf_pre, recall_pre) with the Pareto front drawn through its points.

    ``points``: iterable of (gmcf, recall, kind, label) with kind "front", "eligible" or "excluded".
    """
    fig = new_figure(6.4, 4.8)
    ax = fig.subplots()
    styles = {"excluded": dict(c="#bbbbbb", marker="x", s=14, label="not credible / unhealthy"),
              "eligible": dict(c="#1f77b4", marker="o", s=14, label="credible / healthy"),
              "front": dict(c="#d62728", marker="o", s=30, label="Pareto front")}
    pts = [(g, r, k, lab) for g, r, k, lab in points if g is not None and r is not None
           and math.isfinite(g) and math.isfinite(r)]
    for kind, style in styles.items():
        sel = [(g, r) for g, r, k, _ in pts if k == kind]
        if sel:
            ax.scatter(*zip(*sel), **style)
    front = sorted((g, r) for g, r, k, _ in pts if k == "front")
    if len(front) > 1:
        ax.plot(*zip(*front), c="#d62728", lw=1)
    for g, r, k, lab in pts:
        if lab and k != "excluded":
            ax.annotate(lab, (g, r), fontsize=7, xytext=(3, 3), textcoords="offset points")
    ax.set_xlabel("gmcf_pre (a lower bound on precision)")
    ax.set_ylabel("recall_pre")
    ax.set_xlim(-0.02, 1.02)
    ax.set_ylim(-0.02, 1.02)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="lower left")
    ax.set_title(title, fontsize=10)
    return fig


def sweep_figure(result: SweepResult):
    credible, front = result.credible.ravel(), result.pareto.ravel()
    kinds = np.where(front, "front", np.where(credible, "eligible", "excluded"))
    return frontier_figure(zip(result.gmcf_pre.ravel().tolist(), result.recall_pre.ravel().tolist(), kinds,
                               [""] * len(kinds)), f"Operating points ({result.grid.size} configurations)")


def screen_figure(screens: Sequence[CheckpointScreen]):
    return frontier_figure(((s.counts.gmcf_pre, s.counts.recall_pre,
                             "front" if s.frontier else ("eligible" if s.healthy else "excluded"), s.checkpoint)
                            for s in screens), "Checkpoints at one threshold")

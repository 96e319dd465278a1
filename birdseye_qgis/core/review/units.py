"""Review units: the detections of one flight's layers pooled into the spots a person judges, as
consensus clusters (the default) or as the method's per-frame groups (see the package docstring)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from ..detect.clustering import (
    DEFAULT_CORE_COUNT,
    DEFAULT_DEDUP_CM,
    DEFAULT_EPS_M,
    DEFAULT_MIN_SAMPLES,
    Clustering,
    GroundPositions,
    check_core_count,
    cluster_detections,
    dbscan,
    neighbour_graph,
)
from ..errors import InputError
from ..field.geotags import Geotags
from ..geometry.geodesy import LocalFrame
from ..geometry.poses import FramePoses
from ..scoring.evaluation import Detections, min_samples_for, raster_view
from ..scoring.matching import in_view, match_to_clusters
from ..scoring.operating_point import DEFAULT_EDGE_BUFFER_PX, DEFAULT_EPS_PRED_M, OperatingPoint
from ..scoring.pre_review import score_flight

PROPAGATION_EPS_M = 0.20
PROPAGATION_RULE = f"dbscan_{PROPAGATION_EPS_M:.2f}m"
UNIT_PREFIX, ADDED_PREFIX = "u", "a"
CONSENSUS_UNITS, METHOD_UNITS = "consensus", "method"
UNIT_CONSTRUCTIONS = (CONSENSUS_UNITS, METHOD_UNITS)
#: The method's grouping radius: detections of one frame grouped while every pair stays within it.
METHOD_GROUP_PX = 30.0


@dataclass(frozen=True)
class ReviewParameters:
    """Clustering of the union (post-processing; ``core_count``: what DBSCAN's core test counts,
    :mod:`~..detect.clustering`) and matching parameters of a review."""

    dedup_cm: float = DEFAULT_DEDUP_CM
    eps_m: float = DEFAULT_EPS_M
    min_samples: int = DEFAULT_MIN_SAMPLES
    eps_pred_m: float = DEFAULT_EPS_PRED_M
    edge_buffer_px: float = DEFAULT_EDGE_BUFFER_PX
    units: str = CONSENSUS_UNITS
    group_px: float = METHOD_GROUP_PX
    core_count: str = DEFAULT_CORE_COUNT

    def __post_init__(self):
        check_core_count(self.core_count)
        if self.units not in UNIT_CONSTRUCTIONS:
            raise InputError(f"'{self.units}' is not a way to build review units (expected one of "
                             f"{', '.join(UNIT_CONSTRUCTIONS)})", field="units")
        if self.units == METHOD_UNITS and not (math.isfinite(self.group_px) and self.group_px > 0):
            raise InputError(f"{self.group_px} is not a grouping radius; expected a positive number of pixels",
                             field="group_px")

    def postprocessing(self) -> dict:
        """How detections became units (recorded with every verdict). Dedup, EPS, minimum points and what
        they count also cluster each layer for its scores, so they are recorded with either construction;
        rows recorded without ``core_count`` counted cells
        (:data:`~..scoring.operating_point.RECORDED_WITHOUT_CORE_COUNT`)."""
        out = {"dedup_cm": float(self.dedup_cm), "eps_m": float(self.eps_m),
               "min_samples": int(self.min_samples), "core_count": self.core_count, "threshold": None,
               "units": self.units}
        if self.units == METHOD_UNITS:
            out["group_px"] = float(self.group_px)
        return out

    def operating_point(self) -> OperatingPoint:
        """The operating point each reviewed layer is scored at (no threshold: the layers' own)."""
        return OperatingPoint(None, self.dedup_cm, self.eps_m, self.min_samples, self.eps_pred_m, self.edge_buffer_px,
                              self.core_count)

    def matching(self) -> dict:
        """How units meet geotags and each other (recorded with every verdict)."""
        position = "core point nearest the centroid" if self.units == CONSENSUS_UNITS \
            else "detection nearest the group's mean"
        return {"eps_pred_m": float(self.eps_pred_m), "edge_buffer_px": float(self.edge_buffer_px),
                "unit_position": position, "propagation": PROPAGATION_RULE}

@dataclass
class ReviewLayer:
    """One detection layer under review: the scoring view (:class:`.scoring.Detections`, as
    ``evaluatedetections`` reads it) and each detection's pixel (u, v) in its frame."""

    detections: Detections
    u: np.ndarray
    v: np.ndarray

    @property
    def name(self) -> str:
        return self.detections.name

    def __post_init__(self):
        self.u = np.asarray(self.u, dtype=float).reshape(-1)
        self.v = np.asarray(self.v, dtype=float).reshape(-1)
        if not len(self.u) == len(self.v) == len(self.detections):
            raise ValueError(f"{self.name}: u, v and detections differ in length")


@dataclass
class ReviewUnits:
    """The units of a review. Arrays of length U (unit order = union cluster order); ``order`` is
    the review order (indices); detection arrays (length N, all layers concatenated) say which unit
    (−1 noise) and layer every detection belongs to."""

    keys: list
    lat: np.ndarray
    lon: np.ndarray
    xy: np.ndarray
    layers_fired: list
    n_detections: np.ndarray
    n_frames: np.ndarray
    max_score: np.ndarray
    matched: np.ndarray
    matched_geotags: list
    order: np.ndarray
    propagation_group: np.ndarray
    layer_names: list
    detection_unit: np.ndarray
    detection_layer: np.ndarray
    detection_frame: np.ndarray
    detection_uv: np.ndarray
    detection_score: np.ndarray
    clustering: Clustering | None = None
    index: dict = field(default_factory=dict)

    def __post_init__(self):
        self.index = {k: i for i, k in enumerate(self.keys)}

    def __len__(self) -> int:
        return len(self.keys)

    def neighbours(self, i: int) -> list[int]:
        """Other units of unit i's propagation group."""
        return [int(j) for j in np.flatnonzero(self.propagation_group == self.propagation_group[i]) if j != i]

    def ref(self, i: int) -> "UnitRef":
        return UnitRef(self.keys[i], float(self.lat[i]), float(self.lon[i]), tuple(self.layers_fired[i]))


@dataclass(frozen=True)
class UnitRef:
    """What a verdict row records of the unit it is about."""

    key: str
    lat: float
    lon: float
    layers_fired: tuple = ()


def frame_key(value):
    """Frame ids compare as integers when they are whole numbers (providers return 3 or 3.0 or '3')."""
    try:
        f = float(value)
    except (TypeError, ValueError):
        return str(value)
    return int(f) if math.isfinite(f) and f == int(f) else str(value)


def position_key(prefix: str, lat: float, lon: float) -> str:
    """``prefix`` + latitude and longitude to 7 decimals (about 1 cm): a stable, readable key."""
    return f"{prefix}{lat:+.7f}{lon:+.7f}"


def added_key(lat: float, lon: float) -> str:
    return position_key(ADDED_PREFIX, lat, lon)


def propagation_groups(xy, eps_m: float = PROPAGATION_EPS_M) -> np.ndarray:
    """Group number per unit (U,): DBSCAN over unit positions (m) with ``eps_m`` and one point per
    neighbourhood, i.e. units chained by gaps of at most ``eps_m`` share a group."""
    xy = np.asarray(xy, dtype=float).reshape(-1, 2)
    if len(xy) == 0:
        return np.empty(0, np.int64)
    return dbscan(neighbour_graph(xy, eps_m), eps_m, 1).labels


@dataclass
class PooledDetections:
    """The detections of every layer of a review, concatenated (layer order, then each layer's order)."""

    positions: GroundPositions
    layer: np.ndarray
    frame: np.ndarray
    score: np.ndarray
    uv: np.ndarray
    layer_names: list

    @property
    def xy(self) -> np.ndarray:
        return self.positions.xy

    @classmethod
    def of(cls, layers: Sequence[ReviewLayer], local: LocalFrame) -> "PooledDetections":
        if not layers:
            raise InputError("choose at least one detection layer to review")
        positions = [layer.detections.ground_positions(local) for layer in layers]
        return cls(GroundPositions.concatenate(positions),
                   np.concatenate([np.full(len(p), k, dtype=np.int64) for k, p in enumerate(positions)]),
                   np.concatenate([np.asarray(layer.detections.frame_id, dtype=object) for layer in layers]),
                   np.concatenate([layer.detections.score for layer in layers]),
                   np.concatenate([np.column_stack([layer.u, layer.v]) for layer in layers]),
                   [layer.name for layer in layers])

    def layers_fired(self, detection_unit: np.ndarray, n_units: int) -> list:
        fired = [[] for _ in range(n_units)]
        inside = detection_unit >= 0
        for u, k in sorted(set(zip(detection_unit[inside].tolist(), self.layer[inside].tolist()))):
            fired[u].append(self.layer_names[k])
        return fired


def _geotags_in_view(local: LocalFrame, geotags: Geotags, pose_groups: Sequence[FramePoses],
                     edge_buffer_px: float, ground=None, view_mask=None) -> tuple[np.ndarray, np.ndarray]:
    """Geotags in the local frame (G, 3) and which of them are in view (G,): ``view_mask`` when given (detections
    found on a raster: the geotags it covers, as :func:`..scoring.evaluate_flights` counts them), else those in
    view of the flight's frames on ``ground``."""
    if not len(geotags):
        return np.empty((0, 3)), np.zeros(0, bool)
    g_local = geotags.in_local(local)
    if view_mask is not None:
        return g_local, raster_view(view_mask, len(g_local)).mask
    return g_local, in_view(pose_groups, local, g_local, edge_buffer_px, ground).mask


def _review_order(matched, n_frames, max_score, keys) -> np.ndarray:
    """Unmatched units first (they need a person), then most frames, highest score, key."""
    return np.array(sorted(range(len(keys)), key=lambda i: (bool(matched[i]), -int(n_frames[i]),
                                                            -float(np.nan_to_num(max_score[i], nan=-1)), keys[i])),
                    dtype=np.int64)


def build_units(layers: Sequence[ReviewLayer], local: LocalFrame, geotags: Geotags, pose_groups: Sequence[FramePoses],
                params: ReviewParameters = ReviewParameters(), ground=None, view_mask=None) -> ReviewUnits:
    """The review units of ``layers`` as ``params.units`` says: consensus clusters (the default) or
    the method's per-frame groups (see the package docstring). ``ground``: the ground-model factory the
    layers' detections were placed with (None = the level plane), which the in-view test stands on.

    Detections found on a raster (all layers on one raster; no ``pose_groups``) are matched against the
    geotags in ``view_mask`` (G,), those the raster covers, instead of the frames' test; their "frame" is the
    raster (frame_id 0, ``u``, ``v`` its pixels)."""
    if params.units == METHOD_UNITS:
        return build_method_units(layers, local, geotags, pose_groups, params, ground, view_mask)
    return build_consensus_units(layers, local, geotags, pose_groups, params, ground, view_mask)


def build_consensus_units(layers: Sequence[ReviewLayer], local: LocalFrame, geotags: Geotags,
                          pose_groups: Sequence[FramePoses],
                          params: ReviewParameters = ReviewParameters(), ground=None, view_mask=None) -> ReviewUnits:
    """Consensus units over the union of ``layers`` (see the package docstring); ``view_mask`` as
    :func:`build_units` takes it."""
    det = PooledDetections.of(layers, local)
    # DBSCAN's core test as each layer's scores count it (one detection is a target on a raster); the layers of
    # a review stand on one ground (review_store.read_review_inputs), so the first layer's rule is every layer's.
    min_samples = min_samples_for(layers[0].detections, params.min_samples)
    clustering = cluster_detections(det.positions, det.frame, det.score, params.dedup_cm, params.eps_m,
                                    min_samples, core_count=params.core_count)
    n = clustering.n_clusters
    det_unit = clustering.detection_cluster
    # Position: the core cell nearest each cluster's mean detection position.
    core_idx = np.flatnonzero(clustering.dbscan.core)
    core_label = clustering.dbscan.labels[core_idx]
    d2 = np.sum((clustering.points.xy[core_idx] - clustering.summary.centroid[core_label]) ** 2, axis=1)
    order = np.lexsort((d2, core_label))
    first = np.searchsorted(core_label[order], np.arange(n))
    unit_xy = clustering.points.xy[core_idx[order[first]]] if n else np.empty((0, 2))
    lat, lon, _ = local.to_geodetic(np.column_stack([unit_xy, np.zeros(n)])) if n else (np.empty(0), np.empty(0), None)
    keys = [position_key(UNIT_PREFIX, a, b) for a, b in zip(lat.tolist(), lon.tolist())]
    if len(set(keys)) != len(keys):   # two units within a centimetre: cannot happen with eps ≥ 2 cm
        raise InputError("two review units share a position to the centimetre; increase EPS_M")
    # Matching: the hit test of the scores, on the union's clusters.
    g_local, visible = _geotags_in_view(local, geotags, pose_groups, params.edge_buffer_px, ground, view_mask)
    fs = score_flight(clustering, g_local[:, :2], visible, params.eps_pred_m)
    matched_ids = [[geotags.ids[g] for g in idx] for idx in fs.cluster_geotags] if n else []
    s = clustering.summary
    return ReviewUnits(keys, np.asarray(lat, float), np.asarray(lon, float), unit_xy, det.layers_fired(det_unit, n),
                       s.n_detections.copy(), s.n_frames.copy(), s.max_score.copy(), fs.cluster_hit.copy(),
                       matched_ids, _review_order(fs.cluster_hit, s.n_frames, s.max_score, keys),
                       propagation_groups(unit_xy), det.layer_names, det_unit, det.layer, det.frame, det.uv, det.score,
                       clustering)


def complete_linkage_groups(uv, frame, group_px: float = METHOD_GROUP_PX) -> np.ndarray:
    """Group number per detection (N,): per frame, complete-linkage clusters of the pixel positions
    ``uv`` (N, 2) cut at ``group_px``, so every two detections of a group are at most ``group_px``
    apart. Groups are numbered frame by frame (frames and, within one, detections sorted by pixel
    position), so the numbering does not depend on the input order."""
    from scipy.cluster.hierarchy import fcluster, linkage

    uv = np.asarray(uv, dtype=float).reshape(-1, 2)
    frames = [frame_key(f) for f in np.asarray(frame, dtype=object).reshape(-1)]
    group = np.full(len(uv), -1, dtype=np.int64)
    by_frame: dict = {}
    for i, f in enumerate(frames):
        by_frame.setdefault(f, []).append(i)
    n_groups = 0
    for f in sorted(by_frame, key=lambda k: (isinstance(k, str), k if isinstance(k, str) else float(k))):
        idx = np.asarray(by_frame[f], dtype=np.int64)
        idx = idx[np.lexsort((uv[idx, 1], uv[idx, 0]))]
        if len(idx) == 1:
            labels = np.zeros(1, dtype=np.int64)
        else:
            labels = fcluster(linkage(uv[idx], method="complete"), t=group_px, criterion="distance")
            first_seen: dict = {}
            labels = np.array([first_seen.setdefault(lab, len(first_seen)) for lab in labels.tolist()], np.int64)
        group[idx] = labels + n_groups
        n_groups += int(labels.max()) + 1
    return group


def build_method_units(layers: Sequence[ReviewLayer], local: LocalFrame, geotags: Geotags,
                       pose_groups: Sequence[FramePoses],
                       params: ReviewParameters = ReviewParameters(units=METHOD_UNITS),
                       ground=None, view_mask=None) -> ReviewUnits:
    """The method's review units (see the package docstring): detections matched to an in-view geotag
    are set aside one by one; per frame, the rest are grouped by complete linkage at ``group_px``;
    ``view_mask`` as :func:`build_units` takes it."""
    det = PooledDetections.of(layers, local)
    g_local, visible = _geotags_in_view(local, geotags, pose_groups, params.edge_buffer_px, ground, view_mask)
    seen = np.flatnonzero(visible)
    near = match_to_clusters(g_local[seen, :2], np.arange(len(seen)), det.xy, params.eps_pred_m).point
    unmatched = np.ones(len(det.xy), dtype=bool)
    unmatched[near] = False
    rest = np.flatnonzero(unmatched)
    det_unit = np.full(len(det.xy), -1, dtype=np.int64)
    det_unit[rest] = complete_linkage_groups(det.uv[rest], det.frame[rest], params.group_px)
    n = int(det_unit.max()) + 1 if len(rest) else 0
    members = [np.flatnonzero(det_unit == u) for u in range(n)]
    # Position: the member nearest the group's mean ground position (always on a detection).
    nearest_mean = [m[np.argmin(np.sum((det.xy[m] - det.xy[m].mean(0)) ** 2, axis=1))] for m in members]
    unit_xy = det.xy[nearest_mean] if n else np.empty((0, 2))
    lat, lon, _ = local.to_geodetic(np.column_stack([unit_xy, np.zeros(n)])) if n else (np.empty(0), np.empty(0), None)
    keys = [f"{position_key(UNIT_PREFIX, a, b)}@{frame_key(det.frame[m[0]])}"
            for a, b, m in zip(lat.tolist(), lon.tolist(), members)]
    if len(set(keys)) != len(keys):
        clash = next(k for k in keys if keys.count(k) > 1)
        raise InputError(f"two review units of one frame share a position to the centimetre ({clash}); "
                         "use consensus units for these detections")
    n_detections = np.array([len(m) for m in members], dtype=np.int64)
    n_frames = np.ones(n, dtype=np.int64)
    max_score = np.array([np.nanmax(det.score[m]) if np.isfinite(det.score[m]).any() else np.nan for m in members])
    matched = np.zeros(n, dtype=bool)
    return ReviewUnits(keys, np.asarray(lat, float), np.asarray(lon, float), unit_xy, det.layers_fired(det_unit, n),
                       n_detections, n_frames, max_score, matched, [[] for _ in range(n)],
                       _review_order(matched, n_frames, max_score, keys), propagation_groups(unit_xy),
                       det.layer_names, det_unit, det.layer, det.frame, det.uv, det.score)

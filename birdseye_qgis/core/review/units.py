"""Review units: the detections of one flight's layers pooled into the spots a person judges once."""
from __future__ import annotations

from dataclasses import dataclass, field
from typing import Sequence

import numpy as np

from ..detect.clustering import (
    DEFAULT_DEDUP_CM,
    DEFAULT_EPS_M,
    DEFAULT_MIN_SAMPLES,
    Clustering,
    cluster_detections,
    dbscan,
    neighbour_graph,
)
from ..errors import InputError
from ..geometry.geodesy import LocalFrame
from ..geometry.poses import FramePoses
from ..scoring.evaluation import Detections, Geotags
from ..scoring.matching import in_view
from ..scoring.operating_point import DEFAULT_EDGE_BUFFER_PX, DEFAULT_EPS_PRED_M
from ..scoring.pre_review import score_flight

PROPAGATION_EPS_M = 0.20
PROPAGATION_RULE = f"dbscan_{PROPAGATION_EPS_M:.2f}m"
UNIT_PREFIX, ADDED_PREFIX = "u", "a"


@dataclass(frozen=True)
class ReviewParameters:
    """Clustering of the union (post-processing) and matching parameters of a review."""

    dedup_cm: float = DEFAULT_DEDUP_CM
    eps_m: float = DEFAULT_EPS_M
    min_samples: int = DEFAULT_MIN_SAMPLES
    eps_pred_m: float = DEFAULT_EPS_PRED_M
    edge_buffer_px: float = DEFAULT_EDGE_BUFFER_PX

    def postprocessing(self) -> dict:
        """How detections became units (recorded with every verdict)."""
        return {"dedup_cm": float(self.dedup_cm), "eps_m": float(self.eps_m),
                "min_samples": int(self.min_samples), "threshold": None}

    def matching(self) -> dict:
        """How units meet geotags and each other (recorded with every verdict)."""
        return {"eps_pred_m": float(self.eps_pred_m), "edge_buffer_px": float(self.edge_buffer_px),
                "unit_position": "core point nearest the centroid",
                "propagation": PROPAGATION_RULE}

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


def build_units(layers: Sequence[ReviewLayer], local: LocalFrame, geotags: Geotags, pose_groups: Sequence[FramePoses],
                params: ReviewParameters = ReviewParameters()) -> ReviewUnits:
    """Consensus units over the union of ``layers`` (see the module docstring)."""
    if not layers:
        raise InputError("choose at least one detection layer to review")
    xy = [layer.detections.local_xy(local) for layer in layers]
    all_xy = np.concatenate(xy) if xy else np.empty((0, 2))
    det_layer = np.concatenate([np.full(len(p), k, dtype=np.int64) for k, p in enumerate(xy)])
    frame = np.concatenate([np.asarray(layer.detections.frame_id, dtype=object) for layer in layers])
    score = np.concatenate([layer.detections.score for layer in layers])
    uv = np.concatenate([np.column_stack([layer.u, layer.v]) for layer in layers]) if layers else np.empty((0, 2))
    clustering = cluster_detections(all_xy, frame, score, params.dedup_cm, params.eps_m, params.min_samples)
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
    names = [layer.name for layer in layers]
    fired = [[] for _ in range(n)]
    for u, k in sorted(set(zip(det_unit[det_unit >= 0].tolist(), det_layer[det_unit >= 0].tolist()))):
        fired[u].append(names[k])
    # Matching: the hit test of the scores, on the union's clusters.
    g_local = local.from_geodetic(geotags.lat, geotags.lon,
                                  np.where(np.isfinite(geotags.height), geotags.height, local.h0)) \
        if len(geotags) else np.empty((0, 3))
    visible = in_view(pose_groups, local, g_local, params.edge_buffer_px).mask if len(geotags) else np.zeros(0, bool)
    fs = score_flight(clustering, g_local[:, :2], visible, params.eps_pred_m)
    matched_ids = [[geotags.ids[g] for g in idx] for idx in fs.cluster_geotags] if n else []
    s = clustering.summary
    review_order = np.array(sorted(range(n), key=lambda i: (bool(fs.cluster_hit[i]), -int(s.n_frames[i]),
                                                             -float(np.nan_to_num(s.max_score[i], nan=-1)), keys[i])),
                            dtype=np.int64)
    return ReviewUnits(keys, np.asarray(lat, float), np.asarray(lon, float), unit_xy, fired,
                       s.n_detections.copy(), s.n_frames.copy(), s.max_score.copy(), fs.cluster_hit.copy(),
                       matched_ids, review_order, propagation_groups(unit_xy), names, det_unit, det_layer, frame,
                       uv, score, clustering)

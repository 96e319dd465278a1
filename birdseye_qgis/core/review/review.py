"""Review units, verdict actions, input digests and image chips for the adjudication dock (issue 9).

Everything the review dock decides lives here, free of QGIS and Qt; ``review_store`` persists it and
``gui/review_dock`` shows it. Scores are never computed here: the dock calls
:func:`.scoring.evaluate_flights`, exactly as ``birdseye:evaluatedetections`` does.

Review units
------------
One or several detection layers of one flight (checkpoints, thresholds) are reviewed together, so each
physical spot is judged once whichever model fired there:

* the detections of every layer are placed in the local metric frame of the flight
  (:func:`.scoring.local_frame_for`, the frame the scores use), pooled, de-duplicated on the
  ``dedup_cm`` grid and DBSCAN-clustered (``eps_m``, ``min_samples``) with
  :func:`.clustering.cluster_detections` — the chain a single layer goes through. Each cluster of the
  union is one **review unit**; the record keeps which layers fired in it. Noise is no unit.
* a unit's **position** is its core point (de-duplicated cell) nearest the mean of its detections:
  always on the detections, so a verdict attaches (within ``eps_pred_m``) to the clusters the layers
  formed there, even for a long, chained unit whose mean lies between detections.
* a unit's **key** is ``u`` + its latitude and longitude to 7 decimals (about 1 cm), e.g.
  ``u-27.5500131+151.9500099``: the same inputs and parameters give the same keys, so a review resumes
  on the same units; an added target is keyed ``a`` + its position the same way.
* a unit is **matched** when an in-view geotag lies within ``eps_pred_m`` of its core points (the hit
  test of :func:`.scoring.score_flight`). Order: unmatched units first (they need a person), then by
  frames that saw the unit (most first), highest score, key.

Verdict actions (the log is append-only)
----------------------------------------
Rows follow :mod:`.scoring`'s verdict-log API (unit_key, verdict, provenance, time, reviewer, lat, lon,
sequence = fid). Every user action appends one group of rows sharing an ``action_id``:

* **verdict** — a direct row for the unit; with propagation on, a row for every other unit of its
  propagation group (DBSCAN over unit positions, ε = :data:`PROPAGATION_EPS_M`, one point per
  neighbourhood) with provenance ``propagated:dbscan_0.20m/<source key>``. One provenance per source
  keeps every source's vote, so a spot two neighbours disagree on is a conflict the three conventions
  resolve (:data:`.scoring.CONVENTIONS`), not a silent overwrite. Votes a source has propagated follow
  its later verdicts (also with propagation off), so a propagated vote never contradicts its source.
  Rows that would not change their slot (unit, provenance) are not written.
* **add** — an ``added`` row for a target the reviewer placed (the ``a`` term).
* **undo** — for every row of the latest action not yet undone, a row restoring that slot's verdict
  from before the action (``unreviewed`` when it had none); the undo row names the action it undoes.
  Nothing is ever deleted, and the undo history is rebuilt from the log when a review resumes.

Input digests
-------------
:func:`content_digest` is a SHA-256 over a layer's relevant content (CRS, the listed fields, the
geometry), independent of feature order; every row records the digests of the inputs it was made
against, and :func:`check_inputs` reports verdicts recorded against other contents or parameters.

Chips
-----
:func:`plan_unit_chips` picks the frames that detected a unit (highest score first), a crop window of
``window_px`` around the detection (moved inside the image), the unit's detections in that frame and
the geotags nearby projected into it (:func:`.projection.project_pairs` on the level ground);
:func:`render_chip` draws them (detections as circles, geotags as crosses). Pixels follow the OpenCV
convention (DESIGN §3): (0, 0) is the centre of the top-left pixel.
"""
from __future__ import annotations

import hashlib
import json
import math
import threading
from collections import OrderedDict
from dataclasses import dataclass, field
from typing import Iterable, Mapping, Sequence

import numpy as np

from ..detect.clustering import (DEFAULT_DEDUP_CM, DEFAULT_EPS_M, DEFAULT_MIN_SAMPLES, Clustering, cluster_detections,
                         dbscan, neighbour_graph)
from ..errors import InputError
from ..geometry.geodesy import LocalFrame
from ..geometry.ground import LevelPlaneGround
from ..geometry.poses import FrameGeometry, FramePoses
from ..geometry.projection import project_in_view, project_pairs
from ..scoring.scoring import (ADDED, CONFIRMED, CONVENTIONS, DEFAULT_EDGE_BUFFER_PX, DEFAULT_EPS_PRED_M, DIRECT,
                      HARD_NEGATIVE, PROPAGATED_PREFIX, UNCERTAIN, UNREVIEWED, Detections, Geotags, VerdictLog,
                      in_view, local_frame_for, score_flight)

PROPAGATION_EPS_M = 0.20
PROPAGATION_RULE = f"dbscan_{PROPAGATION_EPS_M:.2f}m"
UNIT_PREFIX, ADDED_PREFIX = "u", "a"
#: The verdicts a reviewer gives (``added`` is given with the map tool).
REVIEW_VERDICTS = (CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED)
ACTION_VERDICT, ACTION_ADD, ACTION_UNDO = "verdict", "add", "undo"
DEFAULT_WINDOW_PX = 128
DEFAULT_MAX_CHIPS = 4


# ====================================================================================== parameters
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


# ====================================================================================== units
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


# ====================================================================================== verdict actions
@dataclass(frozen=True)
class PlannedRow:
    """A row an action will append (the store adds action, time, reviewer, digests and parameters)."""

    unit_key: str
    verdict: str
    provenance: str
    lat: float
    lon: float
    layers_fired: tuple = ()


def propagation_provenance(source_key: str) -> str:
    """Provenance of a vote propagated from ``source_key``: ``propagated:dbscan_0.20m/<source key>``."""
    return f"{PROPAGATED_PREFIX}{PROPAGATION_RULE}/{source_key}"


class Ledger:
    """The verdict log as appended so far (rows in append order) and what the next action appends.

    Rows are mappings with at least ``fid``, ``unit_key``, ``verdict``, ``provenance``, ``action_id``,
    ``action`` and ``undoes`` (None unless an undo), plus ``lat``, ``lon``, ``layers_fired``.
    """

    def __init__(self, rows: Iterable[Mapping] = ()):
        self.rows: list[dict] = []
        self._units: dict[str, dict[str, str]] = {}
        self._by_source: dict[str, set] = {}
        self.extend(rows)

    def extend(self, rows: Iterable[Mapping]) -> None:
        for row in rows:
            row = dict(row)
            self.rows.append(row)
            self._units.setdefault(row["unit_key"], {})[row["provenance"]] = row["verdict"]
            if row["provenance"].startswith(PROPAGATED_PREFIX):
                source = row["provenance"].split("/", 1)[-1]
                self._by_source.setdefault(source, set()).add(row["unit_key"])

    # ---------------------------------------------------------------- state
    def latest(self, unit_key: str, provenance: str = DIRECT) -> str:
        """The slot's latest verdict (append order), ``unreviewed`` when it has none."""
        return self._units.get(unit_key, {}).get(provenance, UNREVIEWED)

    def direct(self, unit_key: str) -> str:
        return self.latest(unit_key, DIRECT)

    def votes(self, unit_key: str) -> dict:
        """Live votes of a unit: {provenance: verdict}, ``unreviewed`` slots left out."""
        return {p: v for p, v in self._units.get(unit_key, {}).items() if v not in (UNREVIEWED, ADDED)}

    def added_targets(self) -> list[UnitRef]:
        """Targets whose latest direct row is ``added``, in the order they were added."""
        out, seen = [], set()
        for row in self.rows:
            key = row["unit_key"]
            if row["verdict"] == ADDED and key not in seen and self.direct(key) == ADDED:
                seen.add(key)
                out.append(UnitRef(key, float(row["lat"]), float(row["lon"]), ()))
        return out

    def verdict_log(self, source: str = "verdict log") -> VerdictLog:
        """The scoring view of the log (:class:`.scoring.VerdictLog`, sequence = fid)."""
        return VerdictLog.from_records(self.rows, source)

    # ---------------------------------------------------------------- planning
    def plan_verdict(self, unit: UnitRef, verdict: str, neighbours: Sequence[UnitRef] = (),
                     propagate: bool = False) -> list[PlannedRow]:
        """Rows for ``verdict`` on ``unit``: its direct row, and the votes it propagates to ``neighbours``
        (all of them when ``propagate``; otherwise only those that already hold a live vote from it)."""
        if verdict not in REVIEW_VERDICTS:
            raise ValueError(f"{verdict!r} is not a review verdict (expected one of {REVIEW_VERDICTS})")
        rows = []
        if self.direct(unit.key) != verdict:
            rows.append(PlannedRow(unit.key, verdict, DIRECT, unit.lat, unit.lon, unit.layers_fired))
        provenance = propagation_provenance(unit.key)
        for n in neighbours:
            current = self.latest(n.key, provenance)
            if (propagate or current != UNREVIEWED) and current != verdict:
                rows.append(PlannedRow(n.key, verdict, provenance, n.lat, n.lon, n.layers_fired))
        return rows

    def plan_add(self, lat: float, lon: float) -> list[PlannedRow]:
        key = added_key(lat, lon)
        return [] if self.direct(key) == ADDED else [PlannedRow(key, ADDED, DIRECT, float(lat), float(lon))]

    def open_actions(self) -> list[int]:
        """Action ids that can still be undone, oldest first (undo rows are not undoable)."""
        actions, undone = [], set()
        for row in self.rows:
            if row["action"] == ACTION_UNDO:
                undone.add(row["undoes"])
            elif not actions or actions[-1] != row["action_id"]:
                actions.append(row["action_id"])
        return [a for a in dict.fromkeys(actions) if a not in undone]

    def plan_undo(self) -> tuple[int | None, list[PlannedRow]]:
        """(action id, rows) restoring every slot the latest open action touched; (None, []) if none."""
        open_ = self.open_actions()
        if not open_:
            return None, []
        action = open_[-1]
        mine = [r for r in self.rows if r["action_id"] == action and r["action"] != ACTION_UNDO]
        first = min(r["fid"] for r in mine)
        before: dict[tuple[str, str], str] = {}
        for r in self.rows:
            if r["fid"] < first:
                before[(r["unit_key"], r["provenance"])] = r["verdict"]
        rows, seen = [], set()
        for r in mine:
            slot = (r["unit_key"], r["provenance"])
            if slot in seen:
                continue
            seen.add(slot)
            rows.append(PlannedRow(r["unit_key"], before.get(slot, UNREVIEWED), r["provenance"], float(r["lat"]),
                                   float(r["lon"]), tuple(_layers(r.get("layers_fired")))))
        return action, rows

    def propagated_from(self, source_key: str) -> list[str]:
        """Units holding a live vote propagated from ``source_key``."""
        prov = propagation_provenance(source_key)
        return sorted(u for u in self._by_source.get(source_key, ()) if self.latest(u, prov) != UNREVIEWED)


def _layers(value) -> list:
    if value in (None, ""):
        return []
    if isinstance(value, (list, tuple)):
        return list(value)
    return list(json.loads(value))


@dataclass(frozen=True)
class UnitStatus:
    """How a unit stands: its direct verdict, live votes and the resolution under each convention."""

    direct: str
    votes: dict
    resolved: dict

    @property
    def reviewed(self) -> bool:
        return bool(self.votes)

    @property
    def conflict(self) -> bool:
        return len(set(self.resolved.values())) > 1

    @property
    def propagated_only(self) -> bool:
        return self.direct == UNREVIEWED and bool(self.votes)


def unit_status(log: VerdictLog, ledger: Ledger, key: str) -> UnitStatus:
    return UnitStatus(ledger.direct(key), ledger.votes(key), {c: log.resolve(key, c) for c in CONVENTIONS})


def resume_key(order_keys: Sequence[str], ledger: Ledger, cursor_key: str | None) -> str | None:
    """Where a review resumes: the saved cursor when it names a unit of ``order_keys``; else the unit
    after the one reviewed last; else the first unit without a vote; else the first unit."""
    if not order_keys:
        return None
    if cursor_key in order_keys or (cursor_key and cursor_key.startswith(ADDED_PREFIX)
                                    and ledger.direct(cursor_key) == ADDED):
        return cursor_key
    position = {k: i for i, k in enumerate(order_keys)}
    for row in reversed(ledger.rows):
        if row["provenance"] == DIRECT and row["unit_key"] in position:
            return order_keys[min(position[row["unit_key"]] + 1, len(order_keys) - 1)]
    return next((k for k in order_keys if not ledger.votes(k)), order_keys[0])


# ====================================================================================== digests
def _canonical(value):
    if value is None:
        return None
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, (int, float, np.integer, np.floating)):
        v = float(value)
        return repr(v) if math.isfinite(v) else str(v)
    return str(value)


def content_digest(kind: str, crs: str, field_names: Sequence[str], rows: Iterable[Sequence]) -> str:
    """SHA-256 (hex) of a layer's relevant content: its kind, CRS, the listed field names and, per
    feature, the values of those fields (geometry coordinates included by the caller as values).

    Numbers hash by value (3 and 3.0 alike, exact binary value), so a provider returning integers as
    floats changes nothing; features are sorted, so their order does not matter either.
    """
    encoded = sorted(json.dumps([_canonical(v) for v in row], ensure_ascii=False) for row in rows)
    h = hashlib.sha256()
    h.update(json.dumps({"kind": kind, "crs": crs, "fields": list(field_names)}, sort_keys=True).encode())
    for line in encoded:
        h.update(b"\n")
        h.update(line.encode("utf-8"))
    return h.hexdigest()


def input_id(role: str, name: str) -> str:
    """The key of an input in the recorded digests: ``detections:<layer name>`` etc."""
    return f"{role}:{name}"


@dataclass
class InputCheck:
    """Verdicts of this review recorded against other inputs or parameters than the current ones."""

    changed: dict = field(default_factory=dict)        # input id -> rows recorded against other content
    missing: dict = field(default_factory=dict)        # input id recorded, not among the current inputs
    new: list = field(default_factory=list)            # current inputs no row was recorded against
    parameters: dict = field(default_factory=dict)     # parameter -> (recorded values, current value)
    orphaned: list = field(default_factory=list)       # reviewed unit keys no current unit carries
    n_rows: int = 0                                    # rows of this review

    @property
    def ok(self) -> bool:
        return not (self.changed or self.missing or self.parameters or self.orphaned)

    def messages(self) -> list[str]:
        out = []
        for iid, n in self.changed.items():
            role, name = iid.split(":", 1)
            out.append(f"The {role} layer '{name}' changed since {n} of {self.n_rows} verdict rows were recorded "
                       "(its content digest differs).")
        for iid, n in self.missing.items():
            role, name = iid.split(":", 1)
            out.append(f"{n} verdict rows were recorded with the {role} layer '{name}', which is not part of this "
                       "review now.")
        for name, (old, new) in self.parameters.items():
            out.append(f"Parameter {name} was {', '.join(map(str, old))} when verdicts were recorded; now {new}.")
        if self.orphaned:
            out.append(f"{len(self.orphaned)} reviewed unit(s) are not among the current units (e.g. "
                       f"{', '.join(self.orphaned[:2])}); their verdicts still count by position.")
        return out


def check_inputs(rows: Iterable[Mapping], current_digests: Mapping[str, str], current_params: Mapping,
                 unit_keys: Iterable[str]) -> InputCheck:
    """Compare the digests and parameters recorded on the rows of this review with the current ones.

    Rows of this review are those recorded with at least one of the current detection layers (a
    GeoPackage may hold the reviews of other flights). ``current_params`` is flat (name → value).
    """
    rows = list(rows)
    current_det = {k for k in current_digests if k.startswith("detections:")}
    check = InputCheck()
    recorded_params: dict[str, set] = {}
    reviewed = set()
    for row in rows:
        digests = _json(row.get("input_digests"))
        if not current_det & set(digests):
            continue
        check.n_rows += 1
        for iid, digest in digests.items():
            if iid not in current_digests:
                check.missing[iid] = check.missing.get(iid, 0) + 1
            elif digest != current_digests[iid]:
                check.changed[iid] = check.changed.get(iid, 0) + 1
        for blob in ("postprocessing", "matching_parameters"):
            for name, value in _json(row.get(blob)).items():
                recorded_params.setdefault(name, set()).add(json.dumps(value))
        if row["provenance"] == DIRECT and row["verdict"] in (CONFIRMED, HARD_NEGATIVE, UNCERTAIN):
            reviewed.add(row["unit_key"])
    if check.n_rows:
        seen = set()
        for row in rows:
            digests = _json(row.get("input_digests"))
            if current_det & set(digests):
                seen.update(digests)
        check.new = sorted(set(current_digests) - seen)
    for name, values in recorded_params.items():
        if name in current_params:
            now = json.dumps(current_params[name])
            if values != {now}:
                check.parameters[name] = (sorted(json.loads(v) for v in values - {now}), current_params[name])
    check.orphaned = sorted(reviewed - set(unit_keys))
    return check


def _json(value) -> dict:
    if value in (None, ""):
        return {}
    return value if isinstance(value, dict) else json.loads(value)


# ====================================================================================== chips
class FrameIndex:
    """Frames by id: their pose group, index and image, with the geometry of the frames that have a
    ground height (the others cannot place geotags and were not processed by detect)."""

    def __init__(self, pose_groups: Sequence[FramePoses], images: Sequence[Sequence[str]], local: LocalFrame):
        self.local = local
        self.groups = []
        self.lookup: dict = {}
        for g, (poses, paths) in enumerate(zip(pose_groups, images)):
            keep = np.flatnonzero(np.isfinite(poses.ground_height))
            sub = poses.subset(keep)
            geometry = FrameGeometry(sub, local) if len(sub) else None
            self.groups.append((geometry, LevelPlaneGround(geometry) if geometry is not None else None))
            for i, k in enumerate(keep.tolist()):
                self.lookup[frame_key(poses.frame_id[k])] = (g, i, paths[k] or "")

    def __contains__(self, frame_id) -> bool:
        return frame_key(frame_id) in self.lookup


def frame_key(value):
    """Frame ids compare as integers when they are whole numbers (providers return 3 or 3.0 or '3')."""
    try:
        f = float(value)
    except (TypeError, ValueError):
        return str(value)
    return int(f) if math.isfinite(f) and f == int(f) else str(value)


@dataclass
class ChipPlan:
    """One chip: a crop ``window`` (x0, y0, x1, y1; x1, y1 exclusive, px of the original image) of a
    frame, with the detections (u, v, layer index) and geotags (u, v, label) inside, in window pixels."""

    key: str
    frame_id: object
    image: str
    window: tuple
    detections: list
    geotags: list
    score: float | None = None


def crop_window(u: float, v: float, size: int, width: int, height: int) -> tuple[int, int, int, int]:
    """A ``size``-pixel square around pixel (u, v), moved to lie inside a width × height image (and
    shrunk only when the image is smaller)."""
    w, h = min(size, width), min(size, height)
    x0 = int(round(u - (w - 1) / 2.0))
    y0 = int(round(v - (h - 1) / 2.0))
    x0 = min(max(x0, 0), width - w)
    y0 = min(max(y0, 0), height - h)
    return x0, y0, x0 + w, y0 + h


def _geotag_marks(frames: FrameIndex, g: int, i: int, window, geotag_local, geotag_labels, centre_xy, radius_m):
    if geotag_local is None or not len(geotag_local):
        return []
    near = np.flatnonzero(np.hypot(*(geotag_local[:, :2] - centre_xy).T) <= radius_m)
    if not len(near):
        return []
    geometry, ground = frames.groups[g]
    proj = project_pairs(geometry, np.full(len(near), i), geotag_local[near], ground)
    x0, y0, x1, y1 = window
    out = []
    for k, (u, v), front in zip(near.tolist(), proj.uv.tolist(), proj.in_front.tolist()):
        if front and x0 - 0.5 <= u <= x1 - 0.5 and y0 - 0.5 <= v <= y1 - 0.5:
            out.append((u - x0, v - y0, str(geotag_labels[k])))
    return out


def _radius_m(frames: FrameIndex, g: int, i: int, window_px: int) -> float:
    geometry = frames.groups[g][0]
    return float(geometry.gsd_m()[i]) * window_px * 0.75 + 0.5


def plan_unit_chips(units: ReviewUnits, unit: int, frames: FrameIndex, geotag_local=None, geotag_labels=(),
                    window_px: int = DEFAULT_WINDOW_PX, max_chips: int = DEFAULT_MAX_CHIPS) -> tuple[list, int]:
    """Chips of unit ``unit`` from the frames that detected it (highest score first), and how many
    frames detected it. Frames missing from the frame layer are skipped."""
    mine = np.flatnonzero(units.detection_unit == unit)
    by_frame: dict = {}
    for d in mine.tolist():
        by_frame.setdefault(frame_key(units.detection_frame[d]), []).append(d)
    ranked = sorted(by_frame.items(), key=lambda kv: (-max(units.detection_score[d] for d in kv[1]), str(kv[0])))
    plans = []
    for fid, dets in ranked:
        if fid not in frames.lookup:
            continue
        if len(plans) == max_chips:
            break
        g, i, image = frames.lookup[fid]
        camera = frames.groups[g][0].camera
        best = max(dets, key=lambda d: units.detection_score[d])
        window = crop_window(*units.detection_uv[best], window_px, camera.width, camera.height)
        marks = [(float(units.detection_uv[d, 0] - window[0]), float(units.detection_uv[d, 1] - window[1]),
                  int(units.detection_layer[d])) for d in dets]
        crosses = _geotag_marks(frames, g, i, window, geotag_local, geotag_labels, units.xy[unit],
                                _radius_m(frames, g, i, window_px))
        plans.append(ChipPlan(units.keys[unit], fid, image, window, marks, crosses,
                              float(units.detection_score[best])))
    return plans, len(by_frame)


def plan_point_chips(key: str, lat: float, lon: float, frames: FrameIndex, geotag_local=None, geotag_labels=(),
                     window_px: int = DEFAULT_WINDOW_PX, max_chips: int = DEFAULT_MAX_CHIPS) -> tuple[list, int]:
    """Chips of a ground point (an added target): the frames it is in view of, nearest the image
    centre first."""
    point = frames.local.from_geodetic([lat], [lon], [frames.local.h0])
    candidates = []
    for g, (geometry, ground) in enumerate(frames.groups):
        if geometry is None:
            continue
        proj = project_in_view(geometry, point, ground)
        centre = np.array([(geometry.camera.width - 1) / 2.0, (geometry.camera.height - 1) / 2.0])
        off_centre = np.hypot(*(proj.uv - centre).T)
        for i, uv, d in zip(proj.frame_idx.tolist(), proj.uv.tolist(), off_centre.tolist()):
            candidates.append((d, g, i, uv))
    candidates.sort(key=lambda c: c[0])
    by_position = {(g, i): fid for fid, (g, i, _) in frames.lookup.items()}
    plans = []
    for _, g, i, (u, v) in candidates[:max_chips]:
        fid = by_position[(g, i)]
        camera = frames.groups[g][0].camera
        window = crop_window(u, v, window_px, camera.width, camera.height)
        crosses = _geotag_marks(frames, g, i, window, geotag_local, geotag_labels, point[0, :2],
                                _radius_m(frames, g, i, window_px))
        plans.append(ChipPlan(key, fid, frames.lookup[fid][2], window, [(u - window[0], v - window[1], -1)],
                              crosses))
    return plans, len(candidates)


#: Colours (RGB) of detections by layer index; −1 = an added target.
LAYER_COLOURS = [(255, 196, 0), (0, 200, 255), (255, 80, 200), (120, 255, 80), (255, 120, 40)]
ADDED_COLOUR = (80, 255, 120)
GEOTAG_COLOUR = (255, 40, 40)


def render_chip(image, plan: ChipPlan, out_px: int) -> np.ndarray:
    """The chip as an RGB array (out_px, out_px, 3): the window scaled to ``out_px`` (nearest pixel
    when enlarging, so single pixels stay sharp), detections as circles, geotags as crosses.
    ``image`` is the frame as read by OpenCV (BGR or grey); None draws a grey "image missing" chip."""
    import cv2

    x0, y0, x1, y1 = plan.window
    if image is None:
        chip = np.full((out_px, out_px, 3), 90, np.uint8)
        cv2.putText(chip, "image missing", (8, out_px // 2), cv2.FONT_HERSHEY_SIMPLEX, 0.45, (230, 230, 230), 1,
                    cv2.LINE_AA)
        return chip
    crop = image[y0:y1, x0:x1]
    if crop.ndim == 2:
        crop = cv2.cvtColor(crop, cv2.COLOR_GRAY2RGB)
    else:
        crop = cv2.cvtColor(crop[:, :, :3], cv2.COLOR_BGR2RGB)
    w, h = x1 - x0, y1 - y0
    scale = out_px / max(w, h)
    chip = np.zeros((out_px, out_px, 3), np.uint8)
    resized = cv2.resize(crop, (max(1, round(w * scale)), max(1, round(h * scale))),
                         interpolation=cv2.INTER_NEAREST if scale >= 1 else cv2.INTER_AREA)
    chip[:resized.shape[0], :resized.shape[1]] = resized

    def at(u, v):  # window pixel (centre convention) → chip pixel
        return int(round((u + 0.5) * scale - 0.5)), int(round((v + 0.5) * scale - 0.5))

    # Rings wider than a target, so the target stays visible inside; one ring per layer that fired.
    radius = max(9, round(out_px * 0.12))
    for u, v, layer in sorted(plan.detections, key=lambda d: -d[2]):
        colour = ADDED_COLOUR if layer < 0 else LAYER_COLOURS[layer % len(LAYER_COLOURS)]
        r = radius + 4 * max(layer, 0)
        cv2.circle(chip, at(u, v), r, (0, 0, 0), 4, cv2.LINE_AA)
        cv2.circle(chip, at(u, v), r, colour, 2, cv2.LINE_AA)
    # Geotags: a diagonal cross with an open centre (the surveyed spot itself is left visible).
    inner, outer = max(4, radius // 2), max(8, radius - 3)
    for u, v, _ in plan.geotags:
        cx, cy = at(u, v)
        for thickness, colour in ((3, (0, 0, 0)), (1, GEOTAG_COLOUR)):
            for sx, sy in ((1, 1), (1, -1), (-1, 1), (-1, -1)):
                a = (round(cx + sx * inner * 0.7071), round(cy + sy * inner * 0.7071))
                b = (round(cx + sx * outer * 0.7071), round(cy + sy * outer * 0.7071))
                cv2.line(chip, a, b, colour, thickness, cv2.LINE_AA)
    return chip


class ImageCache:
    """A small thread-safe LRU of decoded frames (consecutive units share most of their frames)."""

    def __init__(self, capacity: int = 16):
        self.capacity = capacity
        self._images: OrderedDict = OrderedDict()
        self._lock = threading.Lock()

    def get(self, path: str):
        """The image (as OpenCV reads it), or None when the file is missing or unreadable."""
        import cv2

        with self._lock:
            if path in self._images:
                self._images.move_to_end(path)
                return self._images[path]
        image = cv2.imread(path, cv2.IMREAD_UNCHANGED) if path else None
        if image is not None and image.dtype != np.uint8:   # 16-bit frames: show them as 8-bit
            image = cv2.convertScaleAbs(image, alpha=255.0 / max(1.0, float(image.max())))
        with self._lock:
            self._images[path] = image
            while len(self._images) > self.capacity:
                self._images.popitem(last=False)
        return image


def load_chips(plans: Sequence[ChipPlan], out_px: int, cache: ImageCache) -> list[np.ndarray]:
    """Rendered chips (RGB arrays) for ``plans``, reading frames through ``cache``."""
    return [render_chip(cache.get(p.image), p, out_px) for p in plans]


def review_local_frame(pose_groups: Sequence[FramePoses], geotags: Geotags) -> LocalFrame:
    """The local frame of a review: the one ``evaluatedetections`` scores a flight in."""
    return local_frame_for(pose_groups, geotags)

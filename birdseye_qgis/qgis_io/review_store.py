"""The review's storage and inputs: the append-only verdict log in a GeoPackage, and layers → core.

Verdict log (docs/design.md#review-log)
-----------------------------------------------------
Table :data:`VERDICT_TABLE` of a GeoPackage (the first detection layer's, or one next to the project),
a point layer in EPSG:4326 so QGIS can show it, and the ``REVIEW`` input of ``evaluatedetections``.
Columns (:data:`VERDICT_COLUMNS`): ``fid`` (append order = the scoring's ``sequence``), ``geom``,
``unit_key``, ``verdict``, ``provenance`` (``direct`` or ``propagated:<rule>``), ``action_id`` /
``action`` / ``undoes`` (rows one user action appended share an id; an undo names the action it undoes),
``time`` (ISO 8601 UTC, never earlier than the row before), ``reviewer``, ``lat`` / ``lon`` (WGS84
degrees), ``layers_fired`` (JSON list), ``matching_parameters`` and ``postprocessing`` (JSON),
``input_digests`` (JSON: ``"<role>:<layer name>" → SHA-256``).

Nothing the user decided may be lost:

* every action is one SQLite transaction (``BEGIN IMMEDIATE`` … ``COMMIT`` with ``synchronous=FULL``),
  committed before the call returns and the UI moves on; SQLite's journal (rollback or WAL, whichever
  the file uses) rolls an interrupted transaction back, so a killed process leaves whole actions only;
* triggers refuse ``UPDATE`` and ``DELETE`` on the table: the log is append-only for QGIS users too;
* the reviewer's position (``cursor``: unit, filters) lives in :data:`STATE_TABLE` and is written in the
  same transaction as the verdict that moves it, so a resumed review opens exactly where it stopped.

:class:`VerdictStore` and :class:`ReviewSession` need only sqlite3 (and OGR to create a new
GeoPackage); :func:`open_store`, :func:`read_review_inputs` and :func:`layer_digest` are the QGIS side.
"""
from __future__ import annotations

import hashlib
import json
import os
import sqlite3
import struct
from dataclasses import dataclass
from datetime import datetime, timezone
from functools import partial
from pathlib import Path
from typing import Sequence

from ..core.errors import InputError
from ..core.geometry.ground_record import DEM, common_ground
from ..core.review.actions import ACTION_ADD, ACTION_UNDO, ACTION_VERDICT, Ledger, PlannedRow
from ..core.review.digests import input_id
from ..core.review.units import ADDED_PREFIX, ReviewParameters, ReviewUnits, UnitRef
from ..core.scoring.verdicts import VerdictLog
from ..qgis_enums import CRS_WKT2_2019

VERDICT_TABLE = "birdseye_verdicts"
STATE_TABLE = "birdseye_review_state"
WGS84_SRS_ID = 4326
GPKG_APPLICATION_ID = 0x47504B47   # "GPKG"

#: (name, SQL type, description) of the verdict log, after ``fid`` and ``geom``.
VERDICT_COLUMNS = [
    ("unit_key", "TEXT NOT NULL", "review unit (u<lat><lon>) or added target (a<lat><lon>)"),
    ("verdict", "TEXT NOT NULL CHECK (verdict IN ('confirmed_real','hard_negative','uncertain','unreviewed',"
                "'added'))", "confirmed_real, hard_negative, uncertain, unreviewed (withdrawn) or added"),
    ("provenance", "TEXT NOT NULL CHECK (provenance = 'direct' OR provenance LIKE 'propagated:_%')",
     "direct, or propagated:<rule>/<source unit>"),
    ("action_id", "INTEGER NOT NULL", "rows appended by one user action share this number"),
    ("action", "TEXT NOT NULL CHECK (action IN ('verdict','add','undo'))", "verdict, add or undo"),
    ("undoes", "INTEGER", "the action an undo row reverts"),
    ("time", "TEXT NOT NULL", "ISO 8601, UTC"),
    ("reviewer", "TEXT NOT NULL", "who decided"),
    ("lat", "REAL NOT NULL", "latitude of the unit or added target, WGS84 (deg)"),
    ("lon", "REAL NOT NULL", "longitude, WGS84 (deg)"),
    ("layers_fired", "TEXT NOT NULL", "JSON list of the detection layers that fired at the unit"),
    ("matching_parameters", "TEXT NOT NULL", "JSON: eps_pred_m, edge_buffer_px, unit position, propagation"),
    ("postprocessing", "TEXT NOT NULL", "JSON: dedup_cm, eps_m, min_samples, core_count (absent: cells), threshold, "
                                        "units"),
    ("input_digests", "TEXT NOT NULL", "JSON: role:layer → SHA-256 of its content"),
]
VERDICT_FIELD_NAMES = ["fid"] + [c[0] for c in VERDICT_COLUMNS]


def utc_now() -> str:
    return datetime.now(timezone.utc).strftime("%Y-%m-%dT%H:%M:%S.%fZ")


def point_blob(lon: float, lat: float, srs_id: int = WGS84_SRS_ID) -> bytes:
    """A GeoPackage geometry blob (little-endian header without envelope + WKB) of a 2D point."""
    return b"GP" + bytes([0, 0x01]) + struct.pack("<i", srs_id) + struct.pack("<BIdd", 1, 1, lon, lat)


@dataclass(frozen=True)
class RowMeta:
    """What every row of a session records besides the verdict: who, against what, with which settings."""

    reviewer: str
    input_digests: str
    matching_parameters: str
    postprocessing: str

    @classmethod
    def of(cls, reviewer: str, digests: dict, params: ReviewParameters) -> "RowMeta":
        return cls(reviewer or "unknown", json.dumps(digests, sort_keys=True),
                   json.dumps(params.matching(), sort_keys=True), json.dumps(params.postprocessing(), sort_keys=True))


class VerdictStore:
    """The verdict log and review state in a GeoPackage (created, or the tables added, when missing)."""

    def __init__(self, path, create: bool = True):
        self.path = Path(path)
        #: True when this opening added the log's tables to the file (see :func:`open_store`).
        self.created_tables = False
        if not self.path.exists():
            if not create:
                raise InputError("does not exist", source=str(self.path))
            _create_geopackage(self.path)
        try:
            self.connection = sqlite3.connect(str(self.path), timeout=15.0, isolation_level=None)
            self.connection.execute("PRAGMA synchronous=FULL")
            self._ensure_tables()
        except sqlite3.DatabaseError as exc:
            raise InputError(f"cannot be used for the verdict log ({exc}); is it a GeoPackage?",
                             source=str(self.path)) from exc

    @property
    def layer_uri(self) -> str:
        """The OGR data source of the log, for QGIS and for ``evaluatedetections``' REVIEW."""
        return f"{self.path}|layername={VERDICT_TABLE}"

    def close(self) -> None:
        if self.connection is not None:
            self.connection.close()
            self.connection = None

    # ------------------------------------------------------------------ schema
    def _ensure_tables(self) -> None:
        c = self.connection
        tables = {r[0] for r in c.execute("SELECT name FROM sqlite_master WHERE type='table'")}
        if "gpkg_contents" not in tables:
            raise sqlite3.DatabaseError("no gpkg_contents table")
        if VERDICT_TABLE in tables and STATE_TABLE in tables:
            return
        with self._transaction():
            if not c.execute("SELECT 1 FROM gpkg_spatial_ref_sys WHERE srs_id=?", (WGS84_SRS_ID,)).fetchone():
                c.execute("INSERT INTO gpkg_spatial_ref_sys (srs_name, srs_id, organization, organization_coordsys_id,"
                          " definition) VALUES ('WGS 84 geodetic', 4326, 'EPSG', 4326, ?)", (_WGS84_WKT,))
            now = utc_now()
            self.created_tables = True
            if VERDICT_TABLE not in tables:
                columns = ",\n".join(f'"{n}" {t}' for n, t, _ in VERDICT_COLUMNS)
                c.execute(f'CREATE TABLE "{VERDICT_TABLE}" (fid INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, '
                          f'geom POINT, {columns})')
                c.execute(f'CREATE INDEX "{VERDICT_TABLE}_unit" ON "{VERDICT_TABLE}" (unit_key, provenance)')
                for what in ("UPDATE", "DELETE"):
                    c.execute(f'CREATE TRIGGER "{VERDICT_TABLE}_no_{what.lower()}" BEFORE {what} ON "{VERDICT_TABLE}" '
                              "BEGIN SELECT RAISE(ABORT, 'the BirdsEye verdict log is append-only: add a row "
                              "instead (the review dock does this for undo)'); END")
                c.execute("INSERT INTO gpkg_contents (table_name, data_type, identifier, description, last_change, "
                          "srs_id) VALUES (?, 'features', ?, ?, ?, ?)",
                          (VERDICT_TABLE, "BirdsEye review verdicts",
                           "Append-only log of review verdicts (BirdsEye review dock)", _gpkg_time(now), WGS84_SRS_ID))
                c.execute("INSERT INTO gpkg_geometry_columns (table_name, column_name, geometry_type_name, srs_id, "
                          "z, m) VALUES (?, 'geom', 'POINT', ?, 0, 0)", (VERDICT_TABLE, WGS84_SRS_ID))
            if STATE_TABLE not in tables:
                c.execute(f'CREATE TABLE "{STATE_TABLE}" (fid INTEGER PRIMARY KEY AUTOINCREMENT NOT NULL, '
                          'key TEXT UNIQUE NOT NULL, value TEXT NOT NULL, time TEXT NOT NULL)')
                c.execute("INSERT INTO gpkg_contents (table_name, data_type, identifier, description, last_change) "
                          "VALUES (?, 'attributes', ?, ?, ?)",
                          (STATE_TABLE, "BirdsEye review state",
                           "Where each review stopped (BirdsEye review dock); not verdicts", _gpkg_time(now)))

    # ------------------------------------------------------------------ transactions
    class _Txn:
        def __init__(self, connection):
            self.c = connection

        def __enter__(self):
            self.c.execute("BEGIN IMMEDIATE")
            return self.c

        def __exit__(self, kind, value, tb):
            if kind is None:
                self.c.execute("COMMIT")
            else:
                self.c.execute("ROLLBACK")
            return False

    def _transaction(self):
        return self._Txn(self.connection)

    # ------------------------------------------------------------------ writing
    def append(self, rows: Sequence[PlannedRow], action: str, meta: RowMeta | Sequence[RowMeta],
               undoes: int | None = None, state: dict | None = None) -> list[dict]:
        """Append one action's rows (and optionally state entries) in one committed transaction.

        ``meta``: one for every row, or one per row (an action whose rows have different reviewers or inputs:
        a field survey's decisions). Returns the rows as stored (with fid, action_id and time)."""
        if not rows:
            return []
        metas = [meta] * len(rows) if isinstance(meta, RowMeta) else list(meta)
        if len(metas) != len(rows):
            raise ValueError(f"{len(metas)} row metadata for {len(rows)} rows")
        c = self.connection
        with self._transaction():
            action_id = c.execute(f'SELECT COALESCE(MAX(action_id), 0) + 1 FROM "{VERDICT_TABLE}"').fetchone()[0]
            last = c.execute(f'SELECT MAX(time) FROM "{VERDICT_TABLE}"').fetchone()[0]
            now = utc_now()
            time = max(now, last) if last else now   # never earlier than the row before: time order = fid order
            stored = []
            for r, meta in zip(rows, metas):
                values = {"unit_key": r.unit_key, "verdict": r.verdict, "provenance": r.provenance,
                          "action_id": action_id, "action": action, "undoes": undoes, "time": time,
                          "reviewer": meta.reviewer, "lat": float(r.lat), "lon": float(r.lon),
                          "layers_fired": json.dumps(list(r.layers_fired)),
                          "matching_parameters": meta.matching_parameters, "postprocessing": meta.postprocessing,
                          "input_digests": meta.input_digests}
                names = list(values)
                cur = c.execute(f'INSERT INTO "{VERDICT_TABLE}" (geom, {", ".join(names)}) VALUES (?, '
                                f'{", ".join("?" for _ in names)})', [point_blob(r.lon, r.lat)] + list(values.values()))
                stored.append({"fid": cur.lastrowid, **values})
            c.execute("UPDATE gpkg_contents SET last_change=? WHERE table_name=?", (_gpkg_time(now), VERDICT_TABLE))
            for key, value in (state or {}).items():
                self._write_state(key, value, now)
        return stored

    def write_state(self, key: str, value) -> None:
        """Save a state entry (JSON-serialisable) in its own transaction."""
        with self._transaction():
            self._write_state(key, value, utc_now())

    def _write_state(self, key, value, now) -> None:
        self.connection.execute(
            f'INSERT INTO "{STATE_TABLE}" (key, value, time) VALUES (?, ?, ?) '
            "ON CONFLICT(key) DO UPDATE SET value=excluded.value, time=excluded.time",
            (key, json.dumps(value, sort_keys=True), now))

    # ------------------------------------------------------------------ reading
    def rows(self) -> list[dict]:
        """Every row of the log in append order, as dicts of :data:`VERDICT_FIELD_NAMES`."""
        cur = self.connection.execute(f'SELECT {", ".join(VERDICT_FIELD_NAMES)} FROM "{VERDICT_TABLE}" ORDER BY fid')
        return [dict(zip(VERDICT_FIELD_NAMES, r)) for r in cur]

    def read_state(self, key: str):
        row = self.connection.execute(f'SELECT value FROM "{STATE_TABLE}" WHERE key=?', (key,)).fetchone()
        return None if row is None else json.loads(row[0])

    def integrity_check(self) -> str:
        return self.connection.execute("PRAGMA integrity_check").fetchone()[0]


def _gpkg_time(iso: str) -> str:
    return iso[:23] + "Z"   # GeoPackage's last_change: milliseconds


def _create_geopackage(path: Path) -> None:
    """An empty, valid GeoPackage (OGR writes the required metadata tables)."""
    from osgeo import ogr

    path.parent.mkdir(parents=True, exist_ok=True)
    driver = ogr.GetDriverByName("GPKG")
    ds = driver.CreateDataSource(str(path)) if driver is not None else None
    if ds is None:
        raise InputError("cannot be created as a GeoPackage (is the folder writable?)", source=str(path))
    ds = None


_WGS84_WKT = ('GEOGCS["WGS 84",DATUM["WGS_1984",SPHEROID["WGS 84",6378137,298.257223563,AUTHORITY["EPSG","7030"]],'
              'AUTHORITY["EPSG","6326"]],PRIMEM["Greenwich",0,AUTHORITY["EPSG","8901"]],UNIT["degree",'
              '0.0174532925199433,AUTHORITY["EPSG","9122"]],AXIS["Latitude",NORTH],AXIS["Longitude",EAST],'
              'AUTHORITY["EPSG","4326"]]')


# ====================================================================================== session
def review_id(detection_names: Sequence[str]) -> str:
    """Names a review in the state table: the detection layers reviewed together."""
    return hashlib.sha256(json.dumps(sorted(detection_names)).encode()).hexdigest()[:16]


class ReviewSession:
    """A review in progress: its units, the ledger of the log and the store.

    Every method that records something returns only after its transaction is committed.
    """

    def __init__(self, store: VerdictStore, units: ReviewUnits, reviewer: str, digests: dict,
                 params: ReviewParameters = ReviewParameters()):
        self.store = store
        self.units = units
        self.params = params
        self.digests = dict(digests)
        self.meta = RowMeta.of(reviewer, self.digests, params)
        self.review_id = review_id(units.layer_names)
        self.ledger = Ledger(store.rows())
        self._log: VerdictLog | None = None

    @property
    def cursor_key(self) -> str:
        return f"cursor/{self.review_id}"

    def log(self) -> VerdictLog:
        """The scoring view of the log (cached until the next append)."""
        if self._log is None:
            self._log = self.ledger.verdict_log(self.store.layer_uri)
        return self._log

    def ref(self, key: str) -> UnitRef:
        i = self.units.index.get(key)
        if i is not None:
            return self.units.ref(i)
        for target in self.ledger.added_targets():
            if target.key == key:
                return target
        raise KeyError(key)

    def _append(self, rows, action, undoes=None, cursor=None) -> list[dict]:
        state = {self.cursor_key: cursor} if cursor is not None else None
        stored = self.store.append(rows, action, self.meta, undoes, state)
        if not stored and cursor is not None:
            self.store.write_state(self.cursor_key, cursor)
        self.ledger.extend(stored)
        if stored:
            self._log = None
        return stored

    def set_verdict(self, key: str, verdict: str, propagate: bool = False, cursor: dict | None = None) -> list[dict]:
        """Record a verdict on a unit (or withdraw an added target with ``unreviewed``)."""
        if key.startswith(ADDED_PREFIX):
            if verdict != "unreviewed":
                raise InputError("an added target can only be withdrawn (unreviewed), not judged")
            neighbours = []
        else:
            i = self.units.index[key]
            neighbours = [self.units.ref(j) for j in self.units.neighbours(i)]
        rows = self.ledger.plan_verdict(self.ref(key), verdict, neighbours, propagate)
        return self._append(rows, ACTION_VERDICT, cursor=cursor)

    def add_target(self, lat: float, lon: float, cursor: dict | None = None) -> str | None:
        """Record a target the reviewer added; returns its key (None if it is there already)."""
        rows = self.ledger.plan_add(lat, lon)
        stored = self._append(rows, ACTION_ADD, cursor=cursor)
        return stored[0]["unit_key"] if stored else None

    def undo(self, cursor_for=None) -> tuple[int, str] | None:
        """Undo the latest action not yet undone: (its id, the unit it was about), or None.

        ``cursor_for(unit_key) -> dict`` gives the cursor to save with the undo (the UI goes there)."""
        action, rows = self.ledger.plan_undo()
        if action is None:
            return None
        about = rows[0].unit_key
        self._append(rows, ACTION_UNDO, undoes=action, cursor=cursor_for(about) if cursor_for else None)
        return action, about

    def save_cursor(self, cursor: dict) -> None:
        self.store.write_state(self.cursor_key, cursor)

    def load_cursor(self) -> dict | None:
        return self.store.read_state(self.cursor_key)


# ====================================================================================== QGIS side
def open_store(path, project) -> VerdictStore:
    """The verdict log at ``path`` (created when missing), with ``project``'s layers of that file reopened
    when its tables were just added.

    QGIS's OGR provider shares one open dataset among the layers of a GeoPackage. One opened before the
    verdict table existed does not know it, so the verdict layer the review shows would be opened through it
    and fail ("OGR: Cannot reopen …: Cannot find layer birdseye_verdicts"). Reloading the layers that hold the
    file (e.g. the detections the log sits beside) opens it anew.
    """
    from qgis.core import QgsProviderRegistry, QgsVectorLayer

    store = VerdictStore(path)
    if store.created_tables:
        registry = QgsProviderRegistry.instance()
        for layer in project.mapLayers().values():
            if isinstance(layer, QgsVectorLayer) and layer.providerType() == "ogr":
                source = registry.decodeUri("ogr", layer.source()).get("path") or ""
                if source and os.path.realpath(source) == os.path.realpath(store.path):
                    layer.dataProvider().reloadData()
    return store


def _plain(value):
    """A QVariant-free Python value (NULL → None)."""
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    return value


def _crs_text(crs) -> str:

    return crs.authid() or crs.toWkt(CRS_WKT2_2019)


def layer_digest(layer, role: str) -> str:
    """SHA-256 of what a review depends on in a layer (see ``core.review.content_digest``):
    detections — geometry and frame_id, u, v, score, model, model_digest, threshold; frames — the
    frame-layer fields (poses, camera, image path); geotags — geometry and id, label."""
    from ..core.field.frame_records import FRAME_FIELD_NAMES
    from ..core.review.digests import content_digest

    wanted = {"detections": ["frame_id", "u", "v", "score", "model", "model_digest", "threshold"],
              "frames": FRAME_FIELD_NAMES, "geotags": ["id", "label"]}[role]
    names = [n for n in wanted if n in layer.fields().names()]
    with_geometry = role != "frames"
    rows = []
    for feature in layer.getFeatures():
        row = [_plain(feature[n]) for n in names]
        if with_geometry:
            geometry = feature.geometry()
            if geometry is None or geometry.isEmpty():
                row += [None, None, None]
            else:
                p = geometry.vertexAt(0)
                row += [p.x(), p.y(), p.z() if p.is3D() else None]
        rows.append(row)
    return content_digest(role, _crs_text(layer.crs()), names + (["x", "y", "z"] if with_geometry else []), rows)


@dataclass
class ReviewInputs:
    """The layers of a review, read once: detection layers, frames (pose groups and image paths),
    geotags, the local frame of the scores, the content digests, and the ground-model factory the
    detections were placed with (None = the level plane). ``ground_fallback`` says why the review stands
    on the level plane instead of the recorded DEM (empty when it stands on the recorded ground).

    A review of detections found on a raster has no frames (``pose_groups`` and ``images`` empty):
    ``raster`` is the raster's file (empty for frame detections), ``view_mask`` (G,) the geotags in view, those the
    raster covers (:func:`.raster_reader.covered_geotags`, as Evaluate detections counts them), and ``covers``
    the same test for other points — the targets the reviewer adds, which count where the raster covers them."""

    layers: list
    pose_groups: list
    images: list
    geotags: object
    local: object
    digests: dict
    ground: object = None
    ground_fallback: str = ""
    raster: str = ""
    view_mask: object = None
    covers: object = None

    def flights(self) -> list:
        """Each reviewed layer as the :class:`..core.scoring.evaluation.Flight` Evaluate detections scores on the
        same layers (the raster's in-view mask, or the frames on the review's ground)."""
        from ..core.scoring.evaluation import Flight

        return [Flight(layer.detections, self.pose_groups, layer.name, self.ground, self.view_mask, self.covers)
                for layer in self.layers]


def read_review_inputs(detection_layers, frame_layer, geotag_layer) -> ReviewInputs:
    """Read the review's layers with the readers ``evaluatedetections`` uses, plus each detection's
    (u, v). Frame detections need ``frame_layer``; detections found on one raster need none (it is not
    read). Raises :class:`InputError` naming the layer and what is wrong — also for a review mixing
    detections found on a raster with frame detections, or found on two rasters."""
    import numpy as np
    from qgis.core import QgsProcessingContext, QgsProject

    from ..core.geometry.ground_record import RASTER
    from ..core.review.chips import review_local_frame
    from ..core.review.units import ReviewLayer
    from . import layers as layer_io
    from .detections import read_detections, read_pose_groups
    from .raster_reader import covered_geotags

    if not detection_layers:
        raise InputError("choose at least one detection layer to review")
    if geotag_layer is None:
        raise InputError("choose the geotag layer (the survey points)")
    names = [layer.name() for layer in detection_layers]
    if len(set(names)) != len(names):
        raise InputError("two detection layers have the same name; rename one (Layer Properties › Source) so "
                         "the verdict log can tell them apart")
    context = QgsProcessingContext()
    context.setProject(QgsProject.instance())
    read = [read_detections(layer, context, layer.name())[0] for layer in detection_layers]
    on_raster = [det.ground.model == RASTER for det in read]
    if any(on_raster) and not all(on_raster):
        raise InputError("a review is of frame detections (with their frame layer) or of detections found on one "
                         "raster, not both: {raster} found on a raster, {frames} in frames. Review them "
                         "separately".format(raster=", ".join(n for n, r in zip(names, on_raster) if r),
                                             frames=", ".join(n for n, r in zip(names, on_raster) if not r)))
    on_raster = all(on_raster)
    if frame_layer is None and not on_raster:
        raise InputError("choose the frame layer of the flight (Import flight log, Import drone images or Import "
                         "camera solution)")
    review_layers = []
    for layer, det in zip(detection_layers, read):
        if "u" not in layer.fields().names() or "v" not in layer.fields().names():
            raise InputError("has no fields u, v (the detection's pixel); make it with Detect targets",
                             source=layer.name())
        cols = layer_io.read_point_layer(layer, context.transformContext(), ["u", "v", "score"], layer.name())
        values = cols["attributes"]
        score = np.array([np.nan if v is None else float(v) for v in values["score"]], dtype=float)
        ok = np.isfinite(cols["lat"]) & np.isfinite(score)   # read_detections' selection
        u = np.array([np.nan if v is None else float(v) for v in values["u"]], dtype=float)[ok]
        v = np.array([np.nan if v is None else float(v) for v in values["v"]], dtype=float)[ok]
        review_layers.append(ReviewLayer(det, u, v))
    record = common_ground([layer.detections.ground for layer in review_layers], names)   # also: one raster
    geotags = layer_io.read_geotag_layer(geotag_layer, context.transformContext())
    digests = {input_id("detections", layer.name()): layer_digest(layer, "detections") for layer in detection_layers}
    digests[input_id("geotags", geotag_layer.name())] = layer_digest(geotag_layer, "geotags")
    if on_raster:
        # No frames: the local frame stands on the geotags (as Evaluate detections' does without frames) and the
        # geotags in view are those the raster covers.
        covers = partial(covered_geotags, record.dem_source, transform_context=context.transformContext())
        return ReviewInputs(review_layers, [], [], geotags, review_local_frame([], geotags), digests,
                            raster=record.dem_source, view_mask=covers(geotags.lat, geotags.lon), covers=covers)
    groups, records, with_index = read_pose_groups(frame_layer, frame_layer.name())
    images = [[records[i].get("image") or "" for i in idx] for _, idx in with_index]
    local = review_local_frame(groups, geotags)
    digests[input_id("frames", frame_layer.name())] = layer_digest(frame_layer, "frames")
    ground, fallback = review_ground(record, groups)
    return ReviewInputs(review_layers, groups, images, geotags, local, digests, ground, fallback)


def review_ground(record, pose_groups) -> tuple[object, str]:
    """The ground-model factory a review of detections placed on ``record``'s ground stands on, and why it
    is the level plane instead (empty when it is the recorded ground).

    A DEM is opened from the file the detection layer names, with the recorded vertical datum, and checked
    against the frames as Detect checked it. The review has no DEM parameter: when the file is gone or
    fails the check, chips and in-view counts fall back to the level plane, with the reason, rather than
    stop the review."""
    from qgis.core import QgsRasterLayer

    from ..core.geometry.dem import check_vertical_datum
    from . import layers as layer_io

    if record.model != DEM:
        return record.factory(None), ""
    raster = QgsRasterLayer(record.dem_source, "DEM")
    try:
        if not raster.isValid():
            raise InputError("cannot be opened (moved or deleted?)", source=record.dem_source)
        ground = record.factory(layer_io.read_dem(raster, record.dem_datum, record.geoid_undulation_m))
        for poses in pose_groups:
            check_vertical_datum(ground.dem, poses, ground.tolerance_m)
    except InputError as exc:
        return None, str(exc)
    return ground, ""


def default_store_path(detection_layers, project_file: str = "") -> str:
    """Where the verdict log goes by default: the first detection layer's GeoPackage, else a
    GeoPackage next to the project (``<project>_review.gpkg``), else "" (the user chooses)."""
    for layer in detection_layers[:1]:
        path = layer.source().split("|", 1)[0]
        if path.lower().endswith(".gpkg") and os.path.isfile(path):
            return path
    if project_file:
        p = Path(project_file)
        return str(p.with_name(p.stem + "_review.gpkg"))
    return ""


"""QGIS glue shared by the algorithms: fields, features, sinks, styles, CRS helpers, layer readers.

The schemas live in ``core`` (``FRAME_FIELDS`` and friends, lists of (name, type, description));
this module turns them into :class:`QgsFields`, writes records to sinks, applies the ``.qml`` styles
of ``resources/styles`` when Processing loads an output, and reads layers back into plain columns
and records for the core functions. Nothing here computes geometry.
"""
from __future__ import annotations

import functools
import json
import os
import tempfile
from pathlib import Path

import numpy as np
from qgis.core import (
    Qgis,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsCoordinateTransformContext,
    QgsCsException,
    QgsFeature,
    QgsFeatureRequest,
    QgsFeatureSink,
    QgsField,
    QgsFields,
    QgsGeometry,
    QgsLineString,
    QgsPoint,
    QgsPointXY,
    QgsPolygon,
    QgsProcessingContext,
    QgsProcessingLayerPostProcessorInterface,
    QgsProject,
    QgsVectorFileWriter,
    QgsVectorLayer,
    QgsWkbTypes,
)
from qgis.PyQt.QtCore import QDate, QDateTime, Qt

from ..__about__ import STYLE_DIR, tr
from ..core.errors import InputError
from ..core.field.frame_records import (
    CAMERA_FIELD,
    camera_cut_at,
    camera_part_fields,
    join_camera,
    split_cameras,
)
from ..core.field.frames import FRAME_LAYER_FIELDS
from ..core.field.geotags import UNLABELLED, Geotags, geotag_ids
from ..core.geometry.camera import CalibrationError, CameraModel
from ..core.geometry.geodesy import ProjectedCRS, utm_epsg
from ..core.geometry.heights import metres_per_unit
from ..core.labels.mark_check import MARK_CHECK_FIELDS, SIGMA_FIELDS
from ..qgis_enums import (
    CRS_WKT2_2019,
    DISTANCE_METERS,
    GEOMETRY_POINT,
    REQUEST_NO_GEOMETRY,
    WKB_LINE_STRING_Z,
    WKB_POINT,
    WKB_POLYGON_Z,
)

WGS84 = "EPSG:4326"

# Field types: QGIS 3.38 moved QgsField to QMetaType.Type, the only kind QGIS 4 (Qt 6) has; 3.22 takes QVariant.
if Qgis.QGIS_VERSION_INT >= 33800:
    from qgis.PyQt.QtCore import QMetaType

    FIELD_TYPES = {"int": QMetaType.Type.Int, "double": QMetaType.Type.Double, "string": QMetaType.Type.QString,
                   "bool": QMetaType.Type.Bool, "datetime": QMetaType.Type.QDateTime}
else:
    from qgis.PyQt.QtCore import QVariant

    FIELD_TYPES = {"int": QVariant.Int, "double": QVariant.Double, "string": QVariant.String,  # noqa: QGS402
                   "bool": QVariant.Bool, "datetime": QVariant.DateTime}  # noqa: QGS402


# ------------------------------------------------------------------------------------------ fields
def qgs_fields(spec) -> QgsFields:
    """QgsFields from a core schema: (name, type, description) with type "int"/"double"/"string"/"bool"/"datetime"."""
    fields = QgsFields()
    for name, kind, description in spec:
        fields.append(qgs_field(name, kind, description))
    return fields


def qgs_field(name: str, kind: str, description: str = "") -> QgsField:
    """One field of type "int", "double", "string", "bool" or "datetime", on QGIS 3.22 and QGIS 4 alike."""
    field = QgsField(name, FIELD_TYPES[kind])
    field.setComment(description)
    return field


# ------------------------------------------------------------------------------------------ geometry
def polygon_z(ring: np.ndarray) -> QgsGeometry:
    """A PolygonZ from an open ring (K, 3) of x, y, z."""
    ring = np.asarray(ring, dtype=float)
    closed = np.vstack([ring, ring[:1]])
    return QgsGeometry(QgsPolygon(QgsLineString(closed[:, 0].tolist(), closed[:, 1].tolist(),
                                                closed[:, 2].tolist())))


def line_z(xyz: np.ndarray) -> QgsGeometry:
    xyz = np.asarray(xyz, dtype=float)
    return QgsGeometry(QgsLineString(xyz[:, 0].tolist(), xyz[:, 1].tolist(), xyz[:, 2].tolist()))


def point_z(x: float, y: float, z: float) -> QgsGeometry:
    return QgsGeometry(QgsPoint(float(x), float(y), float(z)))


def write_records(sink, fields: QgsFields, records, geometries, feedback=None, start=0.0, end=100.0,
                  total: int | None = None) -> int:
    """Add one feature per (record, geometry) to ``sink``; a None geometry gives a feature without one.

    Honours cancel between features and moves the progress bar from ``start`` to ``end`` percent.
    """
    names = [fields.at(i).name() for i in range(fields.count())]
    count = 0
    step = max(1, (total or 1) // 100)
    for record, geometry in zip(records, geometries):
        if feedback is not None and count % step == 0:
            if feedback.isCanceled():
                break
            if total:
                feedback.setProgress(start + (end - start) * count / total)
        feature = QgsFeature(fields)
        feature.setAttributes([record.get(n) for n in names])
        if geometry is not None:
            feature.setGeometry(geometry)
        if not sink.addFeature(feature, QgsFeatureSink.Flag.FastInsert):
            raise InputError(f"could not write feature {count + 1} to the output")
        count += 1
    return count


# ------------------------------------------------------------------------------------------ styles
class _StyleOnLoad(QgsProcessingLayerPostProcessorInterface):
    """Applies a .qml style (and optionally a name) to an output when Processing loads it."""

    def __init__(self, style_path: Path, layer_name: str | None):
        super().__init__()
        self.style_path = style_path
        self.layer_name = layer_name

    def postProcessLayer(self, layer, context, feedback):
        if layer is None or not layer.isValid():
            return
        message, ok = layer.loadNamedStyle(str(self.style_path))
        if not ok and feedback is not None:
            feedback.pushInfo(f"Style {self.style_path.name} not applied: {message}")
        if self.layer_name:
            layer.setName(self.layer_name)
        layer.triggerRepaint()


# QGIS does not take ownership of Python post-processors: keep them alive until the run's layers load.
_POST_PROCESSORS: dict[str, _StyleOnLoad] = {}


def data_file(layer) -> str:
    """The file a layer's data lives in (a GeoPackage, Shapefile, GeoTIFF …, without ``|layername=``), "" for a
    layer without one (memory, a database)."""
    from qgis.core import QgsProviderRegistry

    path = QgsProviderRegistry.instance().decodeUri(layer.providerType(), layer.source()).get("path") or ""
    return path if path and os.path.isfile(path) else ""


def style_on_load(context, dest_id: str, style: str, layer_name: str | None = None) -> None:
    """Style output ``dest_id`` with ``resources/styles/<style>`` once Processing loads it."""
    if not dest_id or not context.willLoadLayerOnCompletion(dest_id):
        return
    post = _StyleOnLoad(STYLE_DIR / style, layer_name)
    _POST_PROCESSORS[dest_id] = post
    context.layerToLoadOnCompletionDetails(dest_id).setPostProcessor(post)


# ------------------------------------------------------------------------------------------ CRS
def pyproj_crs(crs: QgsCoordinateReferenceSystem) -> str:
    """The CRS as pyproj understands it: ``EPSG:nnnn`` when it has one, else WKT2."""
    authid = crs.authid()
    if authid.upper().startswith("EPSG:"):
        return authid
    return crs.toWkt(CRS_WKT2_2019)


def qgs_crs(crs: str) -> QgsCoordinateReferenceSystem:
    """A QgsCoordinateReferenceSystem from an ``EPSG:nnnn`` string or WKT."""
    out = QgsCoordinateReferenceSystem(crs) if crs.upper().startswith("EPSG:") \
        else QgsCoordinateReferenceSystem.fromWkt(crs)
    if not out.isValid():
        raise InputError(f"CRS {crs[:60]} is not known to QGIS")
    return out


def chosen_projected_crs(crs: QgsCoordinateReferenceSystem | None, parameter: str = "OUTPUT_CRS"):
    """The user's projected output CRS as a core :class:`ProjectedCRS`, or None to pick UTM automatically.

    A geographic CRS (degrees) is refused: footprints, GSD and distances need metres.
    """
    if crs is None or not crs.isValid():
        return None
    if crs.isGeographic():
        raise InputError(f"{crs.authid() or crs.description()} is a geographic CRS (degrees); choose a "
                         "projected CRS in metres, or leave it empty for the UTM zone of the site",
                         field=parameter)
    if crs.mapUnits() != DISTANCE_METERS:
        raise InputError(f"{crs.authid() or crs.description()} is not in metres; choose a projected CRS in "
                         "metres, or leave it empty for the UTM zone of the site", field=parameter)
    return ProjectedCRS(pyproj_crs(crs))


def output_crs(chosen: ProjectedCRS | None, lat, lon) -> tuple[ProjectedCRS, QgsCoordinateReferenceSystem]:
    """The chosen CRS, else the UTM zone of the site (median position); as core and QGIS objects.

    A chosen CRS whose area of use (widened by 1°) does not contain the site is refused: its
    coordinates there would be distorted or meaningless.
    """
    lat, lon = np.asarray(lat, dtype=float), np.asarray(lon, dtype=float)
    site_lat, site_lon = float(np.nanmedian(lat)), float(np.nanmedian(lon))
    if chosen is None:
        chosen = ProjectedCRS(utm_epsg(site_lat, site_lon))
        return chosen, qgs_crs(chosen.crs)
    crs = qgs_crs(chosen.crs)
    bounds = crs.bounds()  # area of use, WGS84 degrees; empty when unknown
    if not bounds.isEmpty() and not bounds.buffered(1.0).contains(QgsPointXY(site_lon, site_lat)):
        raise InputError(
            f"the site ({site_lat:.5f}°, {site_lon:.5f}°) lies outside the area of use of "
            f"{crs.authid() or crs.description()} ({bounds.yMinimum():.1f}…{bounds.yMaximum():.1f}° N, "
            f"{bounds.xMinimum():.1f}…{bounds.xMaximum():.1f}° E); choose a CRS for this area or leave "
            "OUTPUT_CRS empty for the UTM zone of the site", field="OUTPUT_CRS")
    return chosen, crs


# ------------------------------------------------------------------------------------------ readers
def read_point_layer(source, transform_context=None, attributes=(), source_name: str | None = None):
    """Columns of a point layer/feature source: lat, lon (WGS84, deg), z (the geometry's Z, NaN if
    none), the feature numbers (1..) and the named attributes (NULL as None; a date and time as ISO 8601 UTC
    text, a date as ISO 8601 text: :func:`plain_value`).

    Any CRS is transformed to EPSG:4326; a source without a valid CRS is refused.
    """
    name = source_name or (source.sourceName() if hasattr(source, "sourceName") else "point layer")
    crs = source.sourceCrs() if hasattr(source, "sourceCrs") else source.crs()
    if not crs.isValid():
        raise InputError("has no valid CRS; set the layer's CRS (Layer Properties › Source) and run again",
                         source=name)
    if QgsWkbTypes.geometryType(source.wkbType()) != GEOMETRY_POINT:
        raise InputError("is not a point layer", source=name)
    names = source.fields().names()
    for a in attributes:
        if a and a not in names:
            raise InputError(f"has no field '{a}' (fields: {', '.join(names)})", source=name, field=a)
    transform = QgsCoordinateTransform(crs, QgsCoordinateReferenceSystem(WGS84),
                                       transform_context or QgsProject.instance().transformContext())
    lat, lon, z, rows = [], [], [], []
    values = {a: [] for a in attributes if a}
    for number, feature in enumerate(source.getFeatures(), start=1):
        geometry = feature.geometry()
        if geometry is None or geometry.isEmpty():
            lat.append(np.nan), lon.append(np.nan), z.append(np.nan)
        else:
            vertex = geometry.vertexAt(0)
            try:
                p = transform.transform(vertex.x(), vertex.y())
            except Exception as exc:
                raise InputError(f"cannot be transformed to WGS84 ({exc}); is the layer's CRS right?",
                                 source=name, row=number, field="geometry") from exc
            lat.append(p.y()), lon.append(p.x())
            z.append(vertex.z() if vertex.is3D() else np.nan)
        rows.append(number)
        for a in values:
            values[a].append(plain_value(feature[a]))
    return {"lat": np.asarray(lat, dtype=float), "lon": np.asarray(lon, dtype=float),
            "z": np.asarray(z, dtype=float), "row": np.asarray(rows, dtype=np.int64), "attributes": values}


def plain_value(value):
    """An attribute as core reads it: NULL → None; a QDateTime with a zone → ISO 8601 UTC text to the millisecond
    (``2026-05-20T15:27:09.400Z``, converted from its zone), one without (Qt's local time) → the same text without
    a zone (``2026-05-20T15:27:09.400``); a QDate → ``2026-05-20``; anything else as it is. So the core stays free
    of Qt types and judges the times (``core.field.geotags.utc_text``)."""
    if value is None or (hasattr(value, "isNull") and value.isNull()):
        return None
    if isinstance(value, QDateTime):
        if not value.isValid():
            return None
        # OGR hands a time stored without a zone over as local time: the file never said so, and converting it
        # with this computer's zone would invent an offset. It stays zone-less (a field named time_utc is UTC).
        if value.timeSpec() == Qt.TimeSpec.LocalTime:
            return value.toString(Qt.DateFormat.ISODateWithMs)
        return value.toUTC().toString(Qt.DateFormat.ISODateWithMs)
    if isinstance(value, QDate):
        return value.toString(Qt.DateFormat.ISODate) if value.isValid() else None
    return value


def read_geotag_layer(source, transform_context=None, id_field: str = "id", selected_only: bool = False,
                      source_name: str | None = None) -> Geotags:
    """A point layer as :class:`Geotags`: the one reading of a geotag layer, in every algorithm and dock.

    Ids: the ``id_field`` value when the layer has that field, else the feature's row (1.., the
    layer's feature order), never the provider's feature id (a GeoPackage counts from 1, a Shapefile
    from 0); empty or shared ids are refused (:func:`core.field.geotags.geotag_ids`). Heights: the
    ``h_ellipsoid`` field when present (Import geotags writes Z = 0 where it is NULL), else the
    geometry's Z; NaN where unknown. Labels: the ``label`` field, empty → ``target``. Features
    without a position are left out (one entry each in ``problems``), the others keep their ids.
    ``selected_only``: the selected features of a vector layer, with the ids they have in the whole layer.
    """
    name = source_name or (source.sourceName() if hasattr(source, "sourceName") else "geotag layer")
    names = source.fields().names()
    has_id = id_field in names
    wanted = [n for n in (id_field if has_id else "", "label", "h_ellipsoid") if n in names]
    cols = read_point_layer(source, transform_context, wanted, name)
    values = cols["attributes"]
    keep = np.ones(len(cols["row"]), dtype=bool)
    if selected_only:
        selected = set(source.selectedFeatureIds())
        request = QgsFeatureRequest().setNoAttributes().setFlags(REQUEST_NO_GEOMETRY)
        keep = np.array([f.id() in selected for f in source.getFeatures(request)], dtype=bool)
    positioned = np.isfinite(cols["lat"]) & np.isfinite(cols["lon"])
    problems = [InputError("has no position (empty geometry)", source=name, row=int(row),
                           field="geometry") for row in cols["row"][keep & ~positioned]]
    keep &= positioned
    rows = cols["row"][keep]
    ids = geotag_ids([v for v, k in zip(values[id_field], keep) if k] if has_id else None, rows, name, id_field)
    if "h_ellipsoid" in values:
        height = np.array([_number_or_nan(v, name, row, "h_ellipsoid")
                           for v, row in zip(values["h_ellipsoid"], cols["row"])])
    else:
        height = cols["z"]
    labels = ([(str(v).strip() if v is not None else "") or UNLABELLED for v in values["label"]]
              if "label" in values else [UNLABELLED] * len(keep))
    return Geotags(ids, cols["lat"][keep], cols["lon"][keep], height[keep], np.asarray(labels, dtype=object)[keep],
                   source_row=rows, source=name, problems=problems)


def read_polygon_rings(source, transform_context=None, source_name: str | None = None) -> list:
    """The rings of a polygon layer/feature source — every exterior ring and hole of every feature — as
    (lat, lon) arrays (WGS84, deg) for :func:`core.field.surveyed_area.surveyed_area`. Curved rings are
    replaced by straight segments; features without a geometry are skipped; a layer with no polygon at all,
    or without a valid CRS, is refused."""
    name = source_name or (source.sourceName() if hasattr(source, "sourceName") else "polygon layer")
    crs = source.sourceCrs() if hasattr(source, "sourceCrs") else source.crs()
    if not crs.isValid():
        raise InputError("has no valid CRS; set the layer's CRS (Layer Properties › Source) and run again",
                         source=name)
    transform = QgsCoordinateTransform(crs, QgsCoordinateReferenceSystem(WGS84),
                                       transform_context or QgsProject.instance().transformContext())
    rings = []
    for number, feature in enumerate(source.getFeatures(), start=1):
        geometry = QgsGeometry(feature.geometry())
        if geometry.isNull() or geometry.isEmpty():
            continue
        geometry.convertToStraightSegment()
        try:
            geometry.transform(transform)
        except QgsCsException as exc:
            raise InputError(f"cannot be transformed to WGS84 ({exc}); is the layer's CRS right?",
                             source=name, row=number, field="geometry") from exc
        polygons = geometry.asMultiPolygon() if geometry.isMultipart() else [geometry.asPolygon()]
        for polygon in polygons:
            for ring in polygon:
                rings.append((np.array([p.y() for p in ring]), np.array([p.x() for p in ring])))
    if not rings:
        raise InputError("has no polygon", source=name)
    return rings


def read_mark_check_layer(source, source_name: str | None = None) -> list[dict]:
    """The records of a label check (Import camera solution's mark-check layer, saved as any format) with the
    fields :data:`core.labels.mark_check.SIGMA_FIELDS`, each value of its schema type or None; a missing field
    or a value not of its type is refused, naming it."""
    name = source_name or (source.sourceName() if hasattr(source, "sourceName") else "label check")
    names = source.fields().names()
    kinds = {n: kind for n, kind, _ in MARK_CHECK_FIELDS if n in SIGMA_FIELDS}
    absent = [n for n in kinds if n not in names]
    if absent:
        raise InputError(f"is not a label check of Import camera solution: it has no field "
                         f"{', '.join(absent)} (fields: {', '.join(names)})", source=name, field=absent[0])
    return [{n: _schema_value(feature[n], kind, name, row, n) for n, kind in kinds.items()}
            for row, feature in enumerate(source.getFeatures(), start=1)]


def _number_or_nan(value, source: str, row: int, field_name: str) -> float:
    if value is None:
        return float("nan")
    try:
        return float(value)
    except (TypeError, ValueError):
        raise InputError(f"{value!r} is not a number", source=source, row=row, field=field_name) from None


# dBase (.dbf, the attributes of an ESRI Shapefile) keeps field names of at most 10 characters.
_DBF_NAME_CHARS = 10


def read_frame_layer(source, source_name: str | None = None) -> list[dict]:
    """Records (dicts with the :data:`FRAME_LAYER_FIELDS` names the layer has) of a BirdsEye frame layer, in
    feature order, for :func:`core.frame_records.poses_from_records`, from any format QGIS saves to (§4.6).

    Each value has its field's schema type (int, float, str) or is None: NULL and empty text are one value,
    as a CSV cannot tell them apart. A value that is not of its type (a word in a number field) is refused,
    naming row and field. The camera model is text spelled as :func:`_camera_json` spells it, whatever the
    format did to it, so frames of one camera group together and compare equal in every format. A camera
    split over ``camera``, ``camera_2``, … (a format with short text fields) is joined; one the layer's
    format cut is refused, saying what to do. A field name a Shapefile cut to 10 characters
    (``sync_offse``) is read as the field it stands for.
    """
    name = source_name or (source.sourceName() if hasattr(source, "sourceName") else "frame layer")
    fields = source.fields()
    names = fields.names()
    kinds = {n: kind for n, kind, _ in FRAME_LAYER_FIELDS if n != CAMERA_FIELD}
    columns = {n: n if n in names else n[:_DBF_NAME_CHARS] for n in kinds}
    columns = {n: c for n, c in columns.items() if c in names}
    parts = [CAMERA_FIELD] + [f for f, _, _ in camera_part_fields(len(names)) if f in names] \
        if CAMERA_FIELD in names else []
    lengths = [fields.field(p).length() for p in parts]
    checked = set()
    records = []
    for row, feature in enumerate(source.getFeatures(), start=1):
        rec = {n: _schema_value(feature[c], kinds[n], name, row, n) for n, c in columns.items()}
        if parts:
            texts = tuple(_schema_value(feature[p], "string", name, row, p) for p in parts)
            if texts not in checked:
                _refuse_cut_camera(source, name, row, rec.get("frame_id"), texts, lengths)
                checked.add(texts)
            rec[CAMERA_FIELD] = _camera_json(join_camera(texts))
        records.append(rec)
    if not records:
        raise InputError("has no frames", source=name)
    return records


def _schema_value(value, kind: str, source: str, row: int, field_name: str):
    """An attribute (of a frame layer, a label check) as its schema type ``kind`` ("int", "double", "string"); None
    for NULL or empty.

    Formats hand values back in their own types: a CSV read through OGR every value as text and NULL as
    empty text, the delimited-text provider a column of whole numbers as int, a Shapefile empty text as
    NULL, GeoJSON a text that holds a JSON object (the camera) as that object: a dict, given back here
    as JSON text.
    """
    if value is None or (hasattr(value, "isNull") and value.isNull()) or value == "":
        return None
    if kind == "string":
        return json.dumps(value, separators=(",", ":")) if isinstance(value, (dict, list)) else str(value)
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise InputError(f"{value!r} is not a number", source=source, row=row, field=field_name) from None
    if kind == "double":
        return number
    if not number.is_integer():
        raise InputError(f"{value!r} is not a whole number", source=source, row=row, field=field_name)
    return int(number)


@functools.lru_cache(maxsize=64)
def _camera_json(text: str | None) -> str | None:
    """The camera model ``text`` in one spelling: :meth:`CameraModel.to_json`'s, with every number in a list a
    float and no negative zero; two texts of the same numbers give the same text. Frames are grouped, and
    cameras compared, by this text (``geometry.poses.indices_by_camera``), and a format may keep a camera's
    numbers but not their spelling: QGIS hands a GeoJSON camera back as a dict in which 0.0 and −0.0 are 0 and
    the keys are sorted. Text that is no camera model is returned as it is, for :func:`poses_from_records` to
    refuse with its row."""
    if not text:
        return text
    try:
        camera = CameraModel.from_json(text)
    except CalibrationError:
        return text
    return json.dumps(_plain_numbers(camera.to_dict()), separators=(",", ":"))


def _plain_numbers(value, in_list: bool = False):
    """``value`` (a camera's dict) with −0.0 as 0.0 and the numbers in its lists as floats: every list in a
    camera's JSON (``dist``, ``T_cam_imu``, ``t_imu_rad``) holds floats."""
    if isinstance(value, dict):
        return {k: _plain_numbers(v) for k, v in value.items()}
    if isinstance(value, list):
        return [_plain_numbers(v, True) for v in value]
    if isinstance(value, float) or (in_list and isinstance(value, int) and not isinstance(value, bool)):
        return float(value) + 0.0  # -0.0 + 0.0 is 0.0
    return value


def _refuse_cut_camera(source, name: str, row: int, frame_id, texts, lengths) -> None:
    """Refuse a camera model the layer's format cut (``camera_cut_at``), naming the format and the fix."""
    length = camera_cut_at(texts, lengths)
    if length is None:
        return
    storage = source.storageType() if hasattr(source, "storageType") else ""
    raise InputError(tr(
        "the camera model of frame {frame} was cut at {length} characters: {format} keeps at most {length} "
        "characters in a text field and a camera model needs about 500: the layer was probably saved to it after "
        "the import (Save Features As…). Save the original frame layer as a GeoPackage (.gpkg) instead, or run "
        "the import again with its output written to a GeoPackage (or to this format: the import then splits "
        "the camera over fields camera, camera_2, …).").format(
            frame=frame_id, length=length, format=storage or tr("the layer's file format (e.g. ESRI Shapefile)")),
        source=name, row=row, field=CAMERA_FIELD)


# ------------------------------------------------------------------------------------------ outputs
def report_to_feedback(feedback, report) -> None:
    """An ``ImportReport`` in the Processing log: bad input left out and notes (something to check) → warnings —
    the run succeeded with the rest, so nothing here is an error (qgis_process would print ERROR and exit 0);
    findings (results: what was read, a check's figures) and counts → information."""
    if feedback is None:
        return
    for message in report.errors + report.notes:
        feedback.pushWarning(message)
    for message in report.findings:
        feedback.pushInfo(message)
    if report.counts:
        feedback.pushInfo(", ".join(f"{k}: {v:.4g}" if isinstance(v, float) else f"{k}: {v}"
                                    for k, v in report.counts.items()))


def write_frames(algorithm, parameters, context, feedback, result, crs: QgsCoordinateReferenceSystem,
                 output: str = "OUTPUT", track_output: str | None = None, start: float = 80.0,
                 extra_fields=(), extra_values=None) -> dict:
    """Write a core ``FlightImport`` (frames + footprints [+ flight line]) to the algorithm's sinks,
    styled on load; returns the outputs dict entries. ``extra_fields`` (a core schema) follow the
    frame-layer fields, one dict of their values per frame in ``extra_values``. In a format whose text
    fields are too short for the camera model (an ESRI Shapefile), it goes on in ``camera_2``, … (§4.6)."""
    from ..core.field.flight_track import TRACK_FIELDS
    from ..core.field.frames import FRAME_LAYER_FIELDS, frame_records

    records = frame_records(result.frames, result.footprints)
    if extra_values is not None:
        records = ({**rec, **more} for rec, more in zip(records, extra_values))
    # Where the output goes, asked of a scratch context: asked of the run's, Processing would load it twice.
    scratch = QgsProcessingContext()
    scratch.setExpressionContext(context.expressionContext())
    max_chars = text_field_limit(algorithm.parameterAsOutputLayer(parameters, output, scratch))
    camera_parts = []
    if max_chars is not None:
        camera_parts, records = split_cameras(records, max_chars)
    if camera_parts and feedback is not None:
        feedback.pushInfo(tr("The output's format keeps at most {n} characters in a text field: each frame's camera "
                             "model goes on in fields {fields}; keep them with the layer.").format(
                                 n=max_chars, fields=", ".join(f[0] for f in camera_parts)))
    fields = qgs_fields(FRAME_LAYER_FIELDS + list(extra_fields) + camera_parts)
    sink, dest_id = algorithm.parameterAsSink(parameters, output, context, fields, WKB_POLYGON_Z, crs)
    if sink is None:
        raise InputError("the frame output cannot be created", field=output)
    geometries = (None if ring is None else polygon_z(ring) for ring in result.footprints.rings)
    n = write_records(sink, fields, records, geometries, feedback, start, 99.0, total=len(result.frames))
    style_on_load(context, dest_id, "frames.qml")
    outputs = {output: dest_id, "FRAME_COUNT": n}
    if track_output:
        track_fields = qgs_fields(TRACK_FIELDS)
        track_sink, track_id = algorithm.parameterAsSink(parameters, track_output, context, track_fields,
                                                         WKB_LINE_STRING_Z, crs)
        if track_sink is not None:
            write_records(track_sink, track_fields, (s.attributes for s in result.track),
                          (line_z(s.xyz) for s in result.track))
            style_on_load(context, track_id, "track.qml")
            outputs[track_output] = track_id
    return outputs


def text_field_limit(destination: str | None) -> int | None:
    """The most characters a text field keeps in the vector file ``destination`` (a path, as Processing
    gives an output), or None: no limit, or not a file format QGIS writes."""
    path = Path((destination or "").split("|")[0])
    driver = QgsVectorFileWriter.driverForExtension(path.suffix[1:]) if path.suffix else ""
    return _driver_text_limit(driver, path.suffix) if driver else None


@functools.lru_cache(maxsize=None)
def _driver_text_limit(driver: str, suffix: str) -> int | None:
    """What a text field of OGR driver ``driver`` keeps, measured once: a long text written and read back."""
    from osgeo import gdal

    probe = "x" * 4096
    fields = qgs_fields([("text", "string", "")])
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName, options.fileEncoding = driver, "UTF-8"
    feature = QgsFeature(fields)
    feature.setAttributes([probe])
    gdal.PushErrorHandler("CPLQuietErrorHandler")  # not GDAL's "truncated" warning, 4096 x's long, in the log
    try:
        with tempfile.TemporaryDirectory(prefix="birdseye_") as folder:
            path = str(Path(folder) / f"probe{suffix}")
            writer = QgsVectorFileWriter.create(path, fields, WKB_POINT, QgsCoordinateReferenceSystem(WGS84),
                                                QgsCoordinateTransformContext(), options)
            written = writer.addFeature(feature)
            del writer  # closes the file
            layer = QgsVectorLayer(path, "probe", "ogr")
            kept = next((f["text"] for f in layer.getFeatures()), None) if written and layer.isValid() else None
            del layer
    finally:
        gdal.PopErrorHandler()
    return len(kept) if isinstance(kept, str) and len(kept) < len(probe) else None


# ------------------------------------------------------------------------------------------ rasters
# Cells kept beyond a requested extent: bilinear sampling at the extent's edge needs the next cell centre.
_WINDOW_PAD_CELLS = 2


def _height_unit(band, dataset, name: str) -> tuple[float, str]:
    """Metres per height unit of the DEM and the unit's name: the band's unit type, else the vertical
    part of a compound CRS, else metres (what DEM files without a unit almost always hold)."""
    unit = (band.GetUnitType() or "").strip()
    if unit:
        try:
            return metres_per_unit(unit), unit
        except InputError:
            raise InputError(f"has heights in '{unit}', a unit BirdsEye does not know; convert them to metres "
                             "(Raster › Raster Calculator) and set the band's unit to 'm', then run again",
                             source=name) from None
    srs = dataset.GetSpatialRef()
    if srs is not None and srs.IsCompound():
        return srs.GetTargetLinearUnits("VERT_CS"), srs.GetAttrValue("VERT_CS|UNIT") or "metre"
    return 1.0, "metre"


def _window(gt, size, extent) -> tuple[int, int, int, int]:
    """(col, row, cols, rows) of the cells covering ``extent`` (xmin, ymin, xmax, ymax, DEM CRS) plus
    a pad of cells, clipped to the raster; the whole raster when the extent misses it."""
    cols, rows = size
    xmin, ymin, xmax, ymax = extent
    c = sorted(((xmin - gt[0]) / gt[1], (xmax - gt[0]) / gt[1]))
    r = sorted(((ymin - gt[3]) / gt[5], (ymax - gt[3]) / gt[5]))
    c0 = max(0, int(np.floor(c[0])) - _WINDOW_PAD_CELLS)
    c1 = min(cols, int(np.ceil(c[1])) + _WINDOW_PAD_CELLS)
    r0 = max(0, int(np.floor(r[0])) - _WINDOW_PAD_CELLS)
    r1 = min(rows, int(np.ceil(r[1])) + _WINDOW_PAD_CELLS)
    # An extent off the raster is read whole, so the core's "the DEM does not cover the frames" check speaks.
    if c1 - c0 < 2 or r1 - r0 < 2:
        return 0, 0, cols, rows
    return c0, r0, c1 - c0, r1 - r0


def extent_in(source, crs: QgsCoordinateReferenceSystem, context, margin: float, margin_m: float):
    """(xmin, ymin, xmax, ymax) of a feature source's features in ``crs``, grown on every side by
    ``margin`` × its larger side and at least ``margin_m``; None when the source has no extent."""
    box = source.sourceExtent()
    if box.isNull() or not source.sourceCrs().isValid():
        return None
    transform = QgsCoordinateTransform(source.sourceCrs(), crs, context.transformContext())
    try:
        box = transform.transformBoundingBox(box)
    except QgsCsException:  # no window then: the whole raster is read, as without one
        return None
    grow = max(margin * max(box.width(), box.height()), margin_m)
    return box.xMinimum() - grow, box.yMinimum() - grow, box.xMaximum() + grow, box.yMaximum() + grow


def read_dem(layer, vertical_datum: str, geoid_undulation_m: float | None = None, extent=None,
             feedback=None):
    """A core :class:`~.core.geometry.dem.DemRaster` from band 1 of a raster layer (read with GDAL).

    A geographic DEM (degrees), or one whose cells are not metres, is refused with the fix: warp it to
    the site's UTM zone first. Heights in feet (band unit type, or the vertical CRS when the band has
    none) are converted to metres, said on ``feedback``; an unknown height unit is refused. With
    ``extent`` (xmin, ymin, xmax, ymax in the DEM's CRS, the caller's margin included) only the cells
    covering it are read.
    """
    from osgeo import gdal

    from ..core.geometry.dem import DemRaster

    name = layer.name() or layer.source()
    crs = layer.crs()
    if not crs.isValid():
        raise InputError("has no valid CRS; set it in Layer Properties › Source", source=name)
    if crs.isGeographic():
        raise InputError(f"is in a geographic CRS ({crs.authid()}, degrees); warp it to a projected CRS in "
                         "metres first (Raster › Projections › Warp, e.g. to the UTM zone of the site)",
                         source=name)
    # Cell sizes and positions are taken as metres by the core: a CRS in feet would scale every distance.
    if crs.mapUnits() != DISTANCE_METERS:
        raise InputError(f"is in {crs.authid() or crs.description()}, whose cells are not metres; warp it to a "
                         "projected CRS in metres first (Raster › Projections › Warp, e.g. to the UTM zone "
                         "of the site)", source=name)
    dataset = gdal.Open(layer.source())
    if dataset is None:
        raise InputError("cannot be read by GDAL", source=name)
    gt = dataset.GetGeoTransform()
    if gt[2] != 0 or gt[4] != 0:
        raise InputError("is a rotated raster; warp it to a north-up grid first", source=name)
    band = dataset.GetRasterBand(1)
    factor, unit = _height_unit(band, dataset, name)
    if extent is None:
        col, row, cols, rows = 0, 0, dataset.RasterXSize, dataset.RasterYSize
    else:
        col, row, cols, rows = _window(gt, (dataset.RasterXSize, dataset.RasterYSize), extent)
    heights = band.ReadAsArray(col, row, cols, rows).astype(float)
    nodata = band.GetNoDataValue()
    if factor != 1.0:
        # No-data is masked before the scaling, so it cannot be mistaken for a height after it.
        if nodata is not None:
            heights[heights == nodata] = np.nan
        heights *= factor
        if feedback is not None:
            feedback.pushInfo(f"DEM {name}: heights in {unit}, converted to metres (× {factor:.10g})")
    origin = (gt[0] + col * gt[1], gt[3] + row * gt[5])
    return DemRaster(heights, (origin[0], gt[1], origin[1], gt[5]), pyproj_crs(crs), vertical_datum,
                     geoid_undulation_m, nodata if factor == 1.0 else None, source=name)

"""Writing the field survey package QField opens (docs/design.md#field-survey).

``core/field/field_survey.py`` names the tables, fields, expressions and decisions; this module writes the
GeoPackage's tables with them and builds the QGIS project that carries what a GeoPackage cannot hold: the
forms (value maps, aliases, read-only fields), the default values QField fills from the receiver, the
accuracy constraint, the styles and the layer order. Layers are stored with paths relative to the project,
so the folder can be copied to a device as it is.

A package is written only into a folder that holds none: a package that went to the field holds the
worker's records, so an existing one is never overwritten (:func:`refuse_existing_package`).
"""
from __future__ import annotations

import json
import shutil
from dataclasses import dataclass
from datetime import datetime, timezone
from pathlib import Path

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsCoordinateTransformContext,
    QgsDefaultValue,
    QgsEditorWidgetSetup,
    QgsExpression,
    QgsExpressionContextUtils,
    QgsFeature,
    QgsFieldConstraints,
    QgsFields,
    QgsFillSymbol,
    QgsGeometry,
    QgsPalLayerSettings,
    QgsPointXY,
    QgsProject,
    QgsRasterFileWriter,
    QgsRasterLayer,
    QgsRasterPipe,
    QgsReferencedRectangle,
    QgsRuleBasedRenderer,
    QgsSingleSymbolRenderer,
    QgsSymbol,
    QgsTextBufferSettings,
    QgsTextFormat,
    QgsValueMapFieldFormatter,
    QgsVectorFileWriter,
    QgsVectorLayer,
    QgsVectorLayerSimpleLabeling,
    QgsWkbTypes,
)
from qgis.PyQt.QtGui import QColor

from ..__about__ import tr
from ..core.errors import InputError, check_cancel
from ..core.field import field_survey as fs
from ..core.field.geotags import Geotags
from ..core.scoring.verdicts import CONFIRMED, HARD_NEGATIVE, UNCERTAIN
from ..qgis_enums import GEOMETRY_POINT, GEOMETRY_POLYGON, WKB_MULTI_POLYGON, WKB_NO_GEOMETRY, WKB_POINT, WKB_POINT_Z
from . import layers

#: Who recorded a point: the QFieldCloud user, else the device's user name (QField's own variables).
WORKER_EXPRESSION = "coalesce(@cloud_username, @user_full_name)"
#: Project variables QField expressions can read.
RADIUS_VARIABLE, CLASSES_VARIABLE = "birdseye_label_radius_m", "birdseye_classes"
#: The field_survey schema names QGIS expression types ("text"); layers.FIELD_TYPES says "string".
_KINDS = {"text": "string"}
#: QFieldSync's layer actions (libqfieldsync ``layer.SyncAction``), as custom properties QFieldSync and
#: QFieldCloud read when the project is packaged again or uploaded: editable layers travel as offline-editing
#: copies, the rest as copied files.
_QFIELDSYNC_ACTIONS = {True: ("offline", "offline"), False: ("copy", "no_action")}
_RED, _GREEN, _ORANGE, _BLUE = "#e31a1c", "#33a02c", "#ff7f00", "#1f78b4"
_DECISION_COLOURS = {CONFIRMED: _GREEN, HARD_NEGATIVE: "#636363", UNCERTAIN: "#bdbdbd"}


@dataclass(frozen=True)
class SurveySettings:
    """What the worker records and what a record must satisfy; written to :data:`field_survey.META_TABLE`.

    ``height_reference`` is a key of :data:`field_survey.HEIGHT_FIELDS`; ``block_inaccurate`` makes the
    accuracy requirement a hard constraint (QField refuses to save the point) instead of a soft one (QField
    warns, keeps the point, and the style shows it red)."""

    classes: tuple
    label_radius_m: float
    require_fixed: bool
    max_h_accuracy_m: float | None
    block_inaccurate: bool
    height_reference: str
    review_log: str = ""

    @property
    def requirement(self) -> str:
        """The accuracy requirement expression ("" when there is none)."""
        return fs.accuracy_requirement_expression(self.max_h_accuracy_m, self.require_fixed)

    @property
    def height_field(self) -> str:
        return fs.HEIGHT_FIELDS[self.height_reference]

    def requirement_description(self) -> str:
        """The requirement in the worker's words ("Needs RTK fixed and ≤ 5 cm horizontal accuracy"); only for a
        package with a requirement (:attr:`requirement` not empty)."""
        if self.max_h_accuracy_m is None:
            return tr("Needs RTK fixed")
        text = (tr("Needs RTK fixed and ≤ {cm:g} cm horizontal accuracy") if self.require_fixed
                else tr("Needs ≤ {cm:g} cm horizontal accuracy"))
        return text.format(cm=100.0 * self.max_h_accuracy_m)

    def meta_rows(self) -> dict:
        return {fs.META_CLASSES: json.dumps(list(self.classes)),
                fs.META_LABEL_RADIUS_M: repr(float(self.label_radius_m)),
                fs.META_MAX_H_ACC_M: "" if self.max_h_accuracy_m is None else repr(float(self.max_h_accuracy_m)),
                fs.META_REQUIRE_FIXED: "1" if self.require_fixed else "0",
                fs.META_HEIGHT_REFERENCE: self.height_reference,
                fs.META_REVIEW_LOG: self.review_log,
                fs.META_CREATED_UTC: datetime.now(timezone.utc).isoformat(timespec="seconds")}


@dataclass(frozen=True)
class Visit:
    """A point the worker goes to and decides about (a row of :data:`field_survey.VISIT_TABLE`)."""

    visit_id: str
    origin: str
    question: str
    lat: float
    lon: float
    unit_keys: tuple = ()


@dataclass(frozen=True)
class PackageSources:
    """What a package shows besides its own tables: geotags surveyed before, the field's polygons (any polygon
    feature source), the frame footprints (a frame layer's source) and the orthomosaic (a raster layer)."""

    surveyed: Geotags | None = None
    area: object = None
    frames: object = None
    background: QgsRasterLayer | None = None


def package_files(folder, name: str) -> dict:
    """The files a package named ``name`` consists of in ``folder``: project, GeoPackage, orthomosaic copy."""
    folder = Path(folder)
    return {"project": folder / f"{name}.qgz", "gpkg": folder / fs.PACKAGE_GPKG,
            "background": folder / f"{name}_orthomosaic.tif"}


def refuse_existing_package(folder, name: str) -> None:
    """Raise InputError when ``folder`` holds a file of the package ``name`` (:func:`package_files`) already."""
    existing = [path.name for path in package_files(folder, name).values() if path.exists()]
    if existing:
        raise InputError(
            "already holds a field survey package ({files}); a package that went to the field holds the worker's "
            "records, so it is never overwritten: choose another folder, or delete those files if they hold "
            "nothing you need".format(files=", ".join(existing)), source=str(folder), field="OUTPUT_FOLDER")


def write_package(folder, name: str, settings: SurveySettings, visits, sources: PackageSources,
                  transform_context, progress=None, is_canceled=None) -> Path:
    """Write the package ``name`` into ``folder`` (made when missing) and return the project's path.

    Refuses (InputError) a folder that holds a package's file already. A run that fails or is cancelled removes
    what it wrote, so it never leaves a half package that would refuse the next run. ``progress(fraction)`` and
    ``is_canceled()`` as core loops take them."""
    refuse_existing_package(folder, name)
    files = package_files(folder, name)
    Path(folder).mkdir(parents=True, exist_ok=True)
    before = set(Path(folder).iterdir())
    try:
        _write_files(files, settings, visits, sources, transform_context, progress, is_canceled)
    except BaseException:
        # The package's files and their side files (GDAL's .aux.xml, SQLite's -wal): whatever this run made.
        for path in set(Path(folder).iterdir()) - before:
            if any(path.name.startswith(f.name) for f in files.values()):
                path.unlink()
        raise
    return files["project"]


def _write_files(files: dict, settings: SurveySettings, visits, sources: PackageSources, transform_context,
                 progress, is_canceled) -> None:
    gpkg = files["gpkg"]
    stages = 6

    def advance(stage: int) -> None:
        check_cancel(is_canceled)
        if progress is not None:
            progress(stage / stages)

    _write_table(gpkg, fs.META_TABLE, _fields([("key", "string"), ("value", "string")]), WKB_NO_GEOMETRY,
                 ((list(row), None) for row in settings.meta_rows().items()), first=True)
    _write_table(gpkg, fs.GEOTAG_TABLE, geotag_fields(settings), WKB_POINT_Z, [])
    _write_table(gpkg, fs.VISIT_TABLE, visit_fields(), WKB_POINT, _visit_rows(visits))
    advance(1)
    if sources.surveyed is not None:
        _write_table(gpkg, fs.SURVEYED_TABLE,
                     _fields([("id", "string"), ("label", "string"), ("h_ellipsoid", "double")]), WKB_POINT,
                     _surveyed_rows(sources.surveyed))
    advance(2)
    if sources.area is not None:
        _copy_polygons(gpkg, fs.AREA_TABLE, sources.area, transform_context)
    advance(3)
    if sources.frames is not None:
        _copy_polygons(gpkg, fs.FOOTPRINT_TABLE, sources.frames, transform_context, keep=("frame_id",))
    advance(4)
    if sources.background is not None:
        _copy_background(sources.background, files["background"], transform_context)
    advance(5)
    project = _project(files, settings, sources, transform_context)
    if not project.write():
        raise InputError(f"could not be written: {project.error()}", source=str(files["project"]))


# ------------------------------------------------------------------------------------------ tables
def _fields(spec) -> QgsFields:
    return layers.qgs_fields((name, _KINDS.get(kind, kind), "") for name, kind in spec)


def _gnss_spec():
    return [(f.name, f.kind) for f in fs.GNSS_FIELDS]


def geotag_fields(settings: SurveySettings) -> QgsFields:
    """The fields of :data:`field_survey.GEOTAG_TABLE`: label, the height field, label radius, note, worker,
    then the GNSS fields."""
    return _fields([("label", "text"), (settings.height_field, "double"), ("radius_m", "double"), ("note", "text"),
                    ("worker", "text"), *_gnss_spec()])


def visit_fields() -> QgsFields:
    """The fields of :data:`field_survey.VISIT_TABLE`: what to decide where, the decision, and the GNSS fields
    that say when and with what fix it was decided."""
    return _fields([("visit_id", "text"), ("origin", "text"), ("unit_keys", "text"), ("question", "text"),
                    ("decision", "text"), ("note", "text"), ("worker", "text"), *_gnss_spec()])


def _visit_rows(visits):
    for visit in visits:
        values = {"visit_id": visit.visit_id, "origin": visit.origin, "unit_keys": json.dumps(list(visit.unit_keys)),
                  "question": visit.question}
        yield values, QgsGeometry.fromPointXY(QgsPointXY(visit.lon, visit.lat))


def _surveyed_rows(geotags: Geotags):
    for i in range(len(geotags)):
        height = float(geotags.height[i])
        values = {"id": str(geotags.ids[i]), "label": str(geotags.labels[i]),
                  "h_ellipsoid": height if height == height else None}
        yield values, QgsGeometry.fromPointXY(QgsPointXY(float(geotags.lon[i]), float(geotags.lat[i])))


def _writer(gpkg: Path, table: str, fields: QgsFields, wkb_type, first: bool):
    """A writer of a new WGS84 table (the whole file when ``first``); features come in WGS84 already."""
    options = QgsVectorFileWriter.SaveVectorOptions()
    options.driverName = "GPKG"
    options.layerName = table
    options.fileEncoding = "UTF-8"
    options.actionOnExistingFile = (QgsVectorFileWriter.ActionOnExistingFile.CreateOrOverwriteFile if first
                                    else QgsVectorFileWriter.ActionOnExistingFile.CreateOrOverwriteLayer)
    writer = QgsVectorFileWriter.create(str(gpkg), fields, wkb_type, QgsCoordinateReferenceSystem(layers.WGS84),
                                        QgsCoordinateTransformContext(), options)
    if writer.hasError() != QgsVectorFileWriter.WriterError.NoError:
        raise InputError(f"table {table} could not be written: {writer.errorMessage()}", source=str(gpkg))
    return writer


def _write_table(gpkg: Path, table: str, fields: QgsFields, wkb_type, rows, first: bool = False) -> int:
    """A new table of ``rows``: (values as a dict by field name or a list, WGS84 geometry or None)."""
    writer = _writer(gpkg, table, fields, wkb_type, first)
    names = fields.names()
    count = 0
    for values, geometry in rows:
        feature = QgsFeature(fields)
        feature.setAttributes([values.get(n) for n in names] if isinstance(values, dict) else values)
        if geometry is not None:
            feature.setGeometry(geometry)
        if not writer.addFeature(feature):
            raise InputError(f"table {table}: feature {count + 1} could not be written: {writer.errorMessage()}",
                             source=str(gpkg))
        count += 1
    del writer  # closes the table
    return count


def _copy_polygons(gpkg: Path, table: str, source, transform_context, keep=None) -> int:
    """``source``'s polygons as a MultiPolygon table in WGS84, flattened to 2D, with its attributes (only those
    named in ``keep`` when given; never a ``fid``, which the GeoPackage numbers itself)."""
    name = source.sourceName()
    crs = source.sourceCrs()
    if not crs.isValid():
        raise InputError("has no valid CRS; set the layer's CRS (Layer Properties › Source) and run again",
                         source=name)
    columns = [(i, field) for i, field in enumerate(source.fields())
               if field.name().lower() != "fid" and (keep is None or field.name() in keep)]
    fields = QgsFields()
    for _, field in columns:
        fields.append(field)
    transform = QgsCoordinateTransform(crs, QgsCoordinateReferenceSystem(layers.WGS84), transform_context)
    rows = []
    for feature in source.getFeatures():
        geometry = QgsGeometry(feature.geometry())
        if geometry.isNull() or QgsWkbTypes.geometryType(geometry.wkbType()) != GEOMETRY_POLYGON:
            continue
        geometry.get().dropZValue()
        geometry.get().dropMValue()
        geometry.convertToMultiType()
        geometry.transform(transform)
        attributes = feature.attributes()
        rows.append(([attributes[i] for i, _ in columns], geometry))
    return _write_table(gpkg, table, fields, WKB_MULTI_POLYGON, rows)


def _copy_background(layer: QgsRasterLayer, path: Path, transform_context) -> None:
    """The orthomosaic as a GeoTIFF at ``path``: a GeoTIFF file copied as it is, any other raster QGIS reads
    whole (another GDAL format, a memory raster) written out; a web or tile service is refused (it has no
    size to copy, and QField would need the network)."""
    source = layer.source()
    if layer.providerType() == "gdal" and Path(source).is_file() and _is_geotiff(source):
        shutil.copyfile(source, path)
        return
    provider = layer.dataProvider()
    if provider is None or provider.xSize() <= 0 or provider.ySize() <= 0:
        raise InputError("is not a raster QGIS can copy whole (a web or tile service?): save it as a GeoTIFF "
                         "(Export › Save As…) and give that", source=layer.name(), field="BACKGROUND")
    writer = QgsRasterFileWriter(str(path))
    writer.setOutputFormat("GTiff")
    pipe = QgsRasterPipe()
    pipe.set(provider.clone())
    error = writer.writeRaster(pipe, provider.xSize(), provider.ySize(), provider.extent(), provider.crs(),
                               transform_context)
    if error != QgsRasterFileWriter.WriterError.NoError:
        raise InputError(f"could not be written as a GeoTIFF to {path} (QGIS raster writer error {int(error)})",
                         source=layer.name(), field="BACKGROUND")


def _is_geotiff(path: str) -> bool:
    from osgeo import gdal

    dataset = gdal.OpenEx(path, gdal.OF_RASTER)
    return dataset is not None and dataset.GetDriver().ShortName == "GTiff"


# ------------------------------------------------------------------------------------------ project
def _project(files: dict, settings: SurveySettings, sources: PackageSources, transform_context) -> QgsProject:
    """The project over the written tables: layers top to bottom geotags, visits, surveyed before, area,
    footprints, orthomosaic; relative paths; CRS and extent (of what the worker works on), title, instructions."""
    project = QgsProject()
    project.setFileName(str(files["project"]))
    project.setTransformContext(transform_context)
    project.writeEntryBool("Paths", "/Absolute", False)
    gpkg = files["gpkg"]

    def table(name, title):
        layer = QgsVectorLayer(f"{gpkg}|layername={name}", title, "ogr")
        if not layer.isValid():
            raise InputError(f"table {name} does not open as a layer", source=str(gpkg))
        return layer

    # What the worker works on, then the background; each list top to bottom.
    work = [_geotag_layer(table(fs.GEOTAG_TABLE, tr("Geotags")), settings),
            _visit_layer(table(fs.VISIT_TABLE, tr("Points to visit")))]
    if sources.surveyed is not None:
        work.append(_surveyed_layer(table(fs.SURVEYED_TABLE, tr("Surveyed before"))))
    if sources.area is not None:
        work.append(_outline_layer(table(fs.AREA_TABLE, tr("Survey area")), "#ffff00", 0.8, "partition"))
    background = []
    if sources.frames is not None:
        background.append(_outline_layer(table(fs.FOOTPRINT_TABLE, tr("Frame footprints")), "#a6cee3", 0.3, None))
    if sources.background is not None:
        raster = QgsRasterLayer(str(files["background"]), tr("Orthomosaic"), "gdal")
        if not raster.isValid():
            raise InputError("the orthomosaic copy does not open as a raster", source=str(files["background"]))
        _set_qfieldsync_action(raster, editable=False)
        background.append(raster)
    for layer in work + background:
        project.addMapLayer(layer, False)
        project.layerTreeRoot().addLayer(layer)

    crs, extent = _crs_and_extent(work, transform_context)
    if extent is None:  # nothing to work on yet: open on the background
        crs, extent = _crs_and_extent(background, transform_context)
    project.setCrs(crs)
    if extent is not None:
        project.viewSettings().setDefaultViewExtent(QgsReferencedRectangle(extent, crs))
    QgsExpressionContextUtils.setProjectVariable(project, RADIUS_VARIABLE, float(settings.label_radius_m))
    QgsExpressionContextUtils.setProjectVariable(project, CLASSES_VARIABLE, json.dumps(list(settings.classes)))
    project.setTitle(tr("BirdsEye field survey: {name}").format(name=files["project"].stem))
    metadata = project.metadata()
    metadata.setAbstract(instructions(settings))
    project.setMetadata(metadata)
    return project


def instructions(settings: SurveySettings) -> str:
    """What the worker does, in three lines, and the QField height setting the package assumes."""
    fix = settings.requirement_description() if settings.requirement else tr("Use the best fix you can get")
    if settings.height_reference == fs.HEIGHT_ORTHOMETRIC:
        height = tr("3. QField settings › Positioning: “Use orthometric altitude from device” ON (heights go to "
                    "{field}).")
    else:
        height = tr("3. QField settings › Positioning: “Use orthometric altitude from device” OFF and no vertical "
                    "grid shift (heights go to {field}).")
    return "\n".join([
        tr("1. Connect the RTK receiver; add each geotag with the crosshair snapped to your position (the GNSS "
           "button), never by tapping the map."),
        tr("2. {fix}: wait for it before saving; hold the pole on the target's centre (label radius {r:g} "
           "m).").format(fix=fix, r=settings.label_radius_m),
        height.format(field=settings.height_field)])


def _crs_and_extent(stack, transform_context):
    """The project CRS: the site's UTM zone (the centre of the extent of ``stack``'s layers that hold something),
    else EPSG:3857; and that extent with a margin (10 %, at least 2 m: a single point gets 2 m around it), else None."""
    wgs84 = QgsCoordinateReferenceSystem(layers.WGS84)
    union = None
    for layer in stack:
        if isinstance(layer, QgsVectorLayer) and layer.featureCount() == 0:
            continue
        extent = QgsCoordinateTransform(layer.crs(), wgs84, transform_context).transformBoundingBox(layer.extent())
        if union is None:
            union = extent
        else:
            union.combineExtentWith(extent)
    if union is None:
        return QgsCoordinateReferenceSystem("EPSG:3857"), None
    centre = union.center()
    _, crs = layers.output_crs(None, [centre.y()], [centre.x()])
    extent = QgsCoordinateTransform(wgs84, crs, transform_context).transformBoundingBox(union)
    margin = max(2.0, 0.1 * max(extent.width(), extent.height()))
    return crs, extent.buffered(margin)


def _set_qfieldsync_action(layer, editable: bool) -> None:
    action, cloud_action = _QFIELDSYNC_ACTIONS[editable]
    layer.setCustomProperty("QFieldSync/action", action)
    layer.setCustomProperty("QFieldSync/cloud_action", cloud_action)


def _index(layer, name: str) -> int:
    return layer.fields().indexOf(name)


def _default(layer, name: str, expression: str, on_update: bool = False) -> None:
    """``expression`` as ``name``'s default value, applied when a feature is added, and with ``on_update`` on
    every edit too."""
    layer.setDefaultValueDefinition(_index(layer, name), QgsDefaultValue(expression, on_update))


def _value_map(layer, name: str, pairs) -> None:
    """A drop-down of (stored value, shown text) pairs; a None value is QGIS's NULL entry."""
    entries = [{shown: QgsValueMapFieldFormatter.NULL_VALUE if value is None else value} for value, shown in pairs]
    layer.setEditorWidgetSetup(_index(layer, name), QgsEditorWidgetSetup("ValueMap", {"map": entries}))


def _read_only(layer, name: str) -> None:
    config = layer.editFormConfig()
    config.setReadOnly(_index(layer, name), True)
    layer.setEditFormConfig(config)


def _common_fields(layer, recorded_when=None) -> None:
    """The worker and GNSS fields of the geotag and visit tables, shown read-only (the record is what the
    receiver said). Without ``recorded_when`` they are filled when a feature is added (a geotag); with it (an
    expression) on every edit while it holds and NULL otherwise: a visit exists before the worker gets there, so
    its fields record the edit that decided it."""
    for name, expression, alias in [("worker", WORKER_EXPRESSION, None),
                                    *((f.name, f.expression, f.alias) for f in fs.GNSS_FIELDS)]:
        if recorded_when is None:
            _default(layer, name, expression)
        else:
            _default(layer, name, f"if({recorded_when}, {expression}, NULL)", on_update=True)
        if alias is not None:
            layer.setFieldAlias(_index(layer, name), alias)
            _read_only(layer, name)
    layer.setFieldAlias(_index(layer, "worker"), tr("Worker"))
    layer.setFieldAlias(_index(layer, "note"), tr("Note"))
    if _index(layer, "fid") >= 0:  # the GeoPackage's own row number: nothing for the worker to read or set
        layer.setEditorWidgetSetup(_index(layer, "fid"), QgsEditorWidgetSetup("Hidden", {}))


def _geotag_layer(layer: QgsVectorLayer, settings: SurveySettings) -> QgsVectorLayer:
    _value_map(layer, "label", [(c, c) for c in settings.classes])
    _default(layer, "label", _quoted(settings.classes[0]))
    layer.setFieldAlias(_index(layer, "label"), tr("Class"))
    _default(layer, settings.height_field, fs.ALTITUDE_EXPRESSION)
    layer.setFieldAlias(_index(layer, settings.height_field), (
        tr("Height above MSL (m, receiver)") if settings.height_field == fs.HEIGHT_FIELDS[fs.HEIGHT_ORTHOMETRIC]
        else tr("Ellipsoidal height (m, receiver)")))
    _read_only(layer, settings.height_field)
    _default(layer, "radius_m", repr(float(settings.label_radius_m)))
    layer.setFieldAlias(_index(layer, "radius_m"), tr("Label radius (m)"))
    _common_fields(layer)
    rules = [(tr("Geotag"), None, _GREEN)]
    if settings.requirement:
        index = _index(layer, "h_acc_m")
        layer.setConstraintExpression(index, settings.requirement, settings.requirement_description())
        strength = (QgsFieldConstraints.ConstraintStrength.ConstraintStrengthHard if settings.block_inaccurate
                    else QgsFieldConstraints.ConstraintStrength.ConstraintStrengthSoft)
        layer.setFieldConstraint(index, QgsFieldConstraints.Constraint.ConstraintExpression, strength)
        # The same expression colours the points: a flagged (soft) point stays red on the map.
        rules = [(tr("Fails: {what}").format(what=settings.requirement_description()),
                  f"NOT ({settings.requirement})", _RED),
                 (tr("Meets the accuracy requirement"), None, _GREEN)]
    layer.setRenderer(_rule_renderer(rules, GEOMETRY_POINT))
    _label_by(layer, "label")
    _set_qfieldsync_action(layer, editable=True)
    return layer


def _visit_layer(layer: QgsVectorLayer) -> QgsVectorLayer:
    _value_map(layer, "decision", [(None, tr("Not visited")), *fs.DECISIONS.items()])
    for name, alias in (("visit_id", tr("Visit")), ("origin", tr("Why it is visited")), ("unit_keys", None),
                        ("question", tr("Question")), ("decision", tr("Decision"))):
        if name != "decision":
            _read_only(layer, name)
        if alias is not None:
            layer.setFieldAlias(_index(layer, name), alias)
    _common_fields(layer, recorded_when='"decision" IS NOT NULL')
    rules = [(tr("Not visited"), '"decision" IS NULL', _ORANGE)]
    rules += [(shown, f'"decision" = {_quoted(value)}', _DECISION_COLOURS[value])
              for value, shown in fs.DECISIONS.items()]
    layer.setRenderer(_rule_renderer(rules, GEOMETRY_POINT))
    _set_qfieldsync_action(layer, editable=True)
    # A visit is decided where it is: QField keeps its point in place (QFieldSync's geometry lock).
    layer.setCustomProperty("QFieldSync/is_geometry_locked", True)
    return layer


def _surveyed_layer(layer: QgsVectorLayer) -> QgsVectorLayer:
    layer.setRenderer(_rule_renderer([(tr("Surveyed before"), None, _BLUE)], GEOMETRY_POINT))
    _label_by(layer, "label")
    return _fixed(layer)


def _outline_layer(layer: QgsVectorLayer, colour: str, width_mm: float, label_field) -> QgsVectorLayer:
    """A polygon layer drawn as outlines only, so the imagery below stays visible; labelled by ``label_field``
    when the layer has it (a partition's name)."""
    symbol = QgsFillSymbol.createSimple({"style": "no", "outline_color": colour, "outline_width": str(width_mm)})
    layer.setRenderer(QgsSingleSymbolRenderer(symbol))
    if label_field and _index(layer, label_field) >= 0:
        _label_by(layer, label_field)
    return _fixed(layer)


def _fixed(layer: QgsVectorLayer) -> QgsVectorLayer:
    """Read-only in QGIS and QField, carried as a copied file by QFieldSync."""
    layer.setReadOnly(True)
    _set_qfieldsync_action(layer, editable=False)
    return layer


def _rule_renderer(rules, geometry_type) -> QgsRuleBasedRenderer:
    """Rules of (legend label, filter expression or None for "everything else", colour)."""
    root = QgsRuleBasedRenderer.Rule(None)
    for label, expression, colour in rules:
        symbol = QgsSymbol.defaultSymbol(geometry_type)
        symbol.setColor(QColor(colour))
        if geometry_type == GEOMETRY_POINT:
            symbol.setSize(3.0)
        rule = QgsRuleBasedRenderer.Rule(symbol, 0, 0, expression or "", label)
        if expression is None:  # setIsElse(False) would also turn the filter into ELSE (QGIS 3.22)
            rule.setIsElse(True)
        root.appendChild(rule)
    return QgsRuleBasedRenderer(root)


def _label_by(layer: QgsVectorLayer, field: str) -> None:
    settings = QgsPalLayerSettings()
    settings.fieldName = field
    text = QgsTextFormat()
    buffer = QgsTextBufferSettings()
    buffer.setEnabled(True)  # readable over imagery
    text.setBuffer(buffer)
    settings.setFormat(text)
    layer.setLabeling(QgsVectorLayerSimpleLabeling(settings))
    layer.setLabelsEnabled(True)


def _quoted(text: str) -> str:
    return QgsExpression.quotedValue(text)

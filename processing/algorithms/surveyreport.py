"""``birdseye:surveyreport`` — the field survey's cost in people's time: geotags per worker-hour, per worker,
partition and flight (core/field/survey_report.py holds the rule)."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeatureRequest,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterField,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsSpatialIndex,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP, QDateTime, Qt

from ...birdseye_qgis.core.field.survey_report import (
    DEFAULT_SESSION_GAP_S,
    label_counts,
    survey_report,
    survey_report_html,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, SOURCE_VECTOR_POINT, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm

#: The geotag layer's capture-time field (Import geotags' and the field package's).
TIME_FIELD = "time_utc"


class SurveyReport(BirdsEyeAlgorithm):
    ALG_ID = "surveyreport"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SurveyReport", "Survey report")
    GROUP = "field"

    GEOTAGS = "GEOTAGS"
    WORKER_FIELD = "WORKER_FIELD"
    SESSION_GAP_MIN = "SESSION_GAP_MIN"
    AREA = "AREA"
    PARTITION_FIELD = "PARTITION_FIELD"
    FRAMES = "FRAMES"
    LABELS_SUMMARY = "LABELS_SUMMARY"
    LABEL_COUNT = "LABEL_COUNT"
    FRAME_COUNT = "FRAME_COUNT"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_HTML = "OUTPUT_HTML"
    #: Output numbers: name, label, key of the report's "overall" record.
    NUMBERS = (("GEOTAGS_PER_WORKER_HOUR", "Geotags per worker-hour", "geotags_per_worker_hour"),
               ("WORKER_HOURS", "Worker-hours [h]", "worker_hours"),
               ("PEOPLE", "People", "people"),
               ("ELAPSED_HOURS", "Elapsed field time [h]", "elapsed_hours"),
               ("LABELS_PER_WORKER_HOUR", "Labels per worker-hour", "labels_per_worker_hour"),
               ("FRAMES_PER_WORKER_HOUR", "Frames with labels per worker-hour", "frames_per_worker_hour"))

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags (with time_utc)"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterField(
            self.WORKER_FIELD, self.tr("Worker field"), defaultValue="worker",
            parentLayerParameterName=self.GEOTAGS, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.SESSION_GAP_MIN, self.tr("A gap longer than this starts a session [min]"), NUMBER_DOUBLE,
            defaultValue=DEFAULT_SESSION_GAP_S / 60.0, minValue=0.1))
        self.addParameter(source_parameter(
            self.AREA, self.tr("Partitions (polygons)"), layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON],
            optional=True))
        self.addParameter(QgsProcessingParameterField(
            self.PARTITION_FIELD, self.tr("Partition id field (empty: the row)"),
            parentLayerParameterName=self.AREA, optional=True))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Frame layers (one flight each)"), SOURCE_VECTOR_POLYGON, optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.LABELS_SUMMARY, self.tr("Write labels summary.json"), optional=True,
            fileFilter="Write labels summary (summary.json);;JSON (*.json)"))
        self.addParameter(QgsProcessingParameterNumber(
            self.LABEL_COUNT, self.tr("Labels (empty: summary.json)"), NUMBER_INTEGER, optional=True,
            minValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.FRAME_COUNT, self.tr("Frames with labels (empty: summary.json)"), NUMBER_INTEGER,
            optional=True, minValue=0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Survey report (JSON)"), "JSON (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_HTML, self.tr("Survey report (HTML)"), "HTML (*.html)", optional=True,
            createByDefault=True))
        for name, label, _ in self.NUMBERS:
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(label)))

    def processAlgorithm(self, parameters, context, feedback):
        source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer could not be opened."))
        name = source.sourceName()
        fields = source.fields().names()
        if TIME_FIELD not in fields:
            raise QgsProcessingException(self.tr(
                "GEOTAGS: layer '{layer}' has no {time} field, so the report has no capture times (fields: "
                "{fields}). Import geotags writes it from the rover's time column; the field package's geotags "
                "have it.").format(layer=name, time=TIME_FIELD, fields=", ".join(fields)))
        if source.featureCount() == 0:
            raise QgsProcessingException(self.tr("GEOTAGS: layer '{}' has no geotags: there is nothing to report.")
                                         .format(name))
        worker_field = self.parameterAsString(parameters, self.WORKER_FIELD, context)
        if worker_field and worker_field not in fields:
            feedback.pushInfo(self.tr("Layer '{layer}' has no field '{field}': its geotags are one unnamed worker's.")
                              .format(layer=name, field=worker_field))
            worker_field = ""
        columns = self.run_core(layers.read_point_layer, source, context.transformContext(),
                                [TIME_FIELD, worker_field], name)
        times = [capture_time_text(v) for v in columns["attributes"][TIME_FIELD]]
        workers = columns["attributes"][worker_field] if worker_field else None
        points = [QgsPointXY(x, y) for x, y in zip(columns["lon"], columns["lat"])]

        partition_of, partitions = None, ()
        area = self.parameterAsSource(parameters, self.AREA, context)
        if area is not None:
            partitions, partition_of = self._partitions(area, parameters, context, points)
        flights = {layer.name(): [bool(rows) for rows in containing(layer, points, context)]
                   for layer in self.parameterAsLayerList(parameters, self.FRAMES, context)}
        label_count, frame_count = self._counts(parameters, context)

        report = self.run_core(
            survey_report, times, workers, partition_of, partitions, flights,
            self.parameterAsDouble(parameters, self.SESSION_GAP_MIN, context) * 60.0, label_count, frame_count, name)
        result = report.to_dict()
        json_path = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        Path(json_path).parent.mkdir(parents=True, exist_ok=True)
        Path(json_path).write_text(json.dumps(result, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
        outputs = {self.OUTPUT_JSON: json_path}
        html_path = self.parameterAsFileOutput(parameters, self.OUTPUT_HTML, context)
        if html_path:
            Path(html_path).parent.mkdir(parents=True, exist_ok=True)
            Path(html_path).write_text(survey_report_html(report), encoding="utf-8")
            outputs[self.OUTPUT_HTML] = html_path
        self._log(feedback, result)
        outputs.update({name: result["overall"][key] for name, _, key in self.NUMBERS})
        return outputs

    def _partitions(self, area, parameters, context, points):
        """Every partition's id (the PARTITION_FIELD value, else the row 1..) and, per geotag, the id of the first
        partition holding it (None: none does)."""
        field = self.parameterAsString(parameters, self.PARTITION_FIELD, context)
        ids = [str(feature[field]) if field else str(row)
               for row, feature in enumerate(area.getFeatures(), start=1)]
        if len(set(ids)) != len(ids):
            raise QgsProcessingException(self.tr("PARTITION_FIELD: field '{}' gives two partitions one id; choose a "
                                                 "field that names each once, or leave it empty.").format(field))
        return ids, [ids[rows[0] - 1] if rows else None for rows in containing(area, points, context)]

    def _counts(self, parameters, context):
        """(labels, frames with labels): typed, else from LABELS_SUMMARY, else None."""
        summary = self.parameterAsFile(parameters, self.LABELS_SUMMARY, context)
        labels, frames = self.run_core(label_counts, summary) if summary else (None, None)
        typed = [None if parameters.get(name) in (None, "") else self.parameterAsInt(parameters, name, context)
                 for name in (self.LABEL_COUNT, self.FRAME_COUNT)]
        return (typed[0] if typed[0] is not None else labels), (typed[1] if typed[1] is not None else frames)

    def _log(self, feedback, result):
        o = result["overall"]
        rate = o["geotags_per_worker_hour"]
        feedback.pushInfo(self.tr(
            "{g} geotag(s), {t} with a capture time, by {p} people in {s} session(s): {h:.2f} worker-hours, "
            "{rate} geotags per worker-hour; elapsed field time {e:.2f} h ({first} to {last}).").format(
            g=o["geotags"], t=o["geotags_with_time"], p=o["people"], s=o["sessions"], h=o["worker_hours"],
            rate="–" if rate is None else f"{rate:.1f}", e=o["elapsed_hours"], first=o["first_utc"],
            last=o["last_utc"]))
        untimed = o["geotags"] - o["geotags_with_time"]
        if untimed:
            feedback.pushWarning(self.tr("{n} geotag(s) have no capture time: counted, but left out of the rates.")
                                 .format(n=untimed))
        if o["labels_per_worker_hour"] is not None:
            feedback.pushInfo(self.tr("{n} labels / {h:.2f} worker-hours = {r:.0f} labels per worker-hour.").format(
                n=o["label_count"], h=o["worker_hours"], r=o["labels_per_worker_hour"]))
        c = result["coverage"]
        if c["partitions"]:
            feedback.pushInfo(self.tr("{k} of {n} partition(s) hold a geotag; {out} geotag(s) lie outside every "
                                      "partition.").format(k=c["partitions_with_geotags"], n=c["partitions"],
                                                           out=c["geotags_outside_partitions"]))


def capture_time_text(value) -> str:
    """A capture time as a layer holds it — ISO 8601 text, or a QDateTime (a GeoPackage DateTime field, as the
    field package's ``time_utc``) — as text for ``core.field.survey_report.capture_seconds``; "" when empty. A
    QDateTime without a zone is taken as UTC, as the field's name says, never as this computer's local time."""
    if isinstance(value, QDateTime):
        if not value.isValid():
            return ""
        utc = value if value.timeSpec() == Qt.TimeSpec.LocalTime else value.toUTC()
        return utc.toString("yyyy-MM-ddTHH:mm:ss.zzz") + "Z"
    return "" if value is None else str(value)


def containing(source, points, context) -> list:
    """For each point (WGS84 lon, lat as QgsPointXY; NaN: no position), the rows (1.., the layer's feature order)
    of the polygons of ``source`` that hold it."""
    transform = QgsCoordinateTransform(QgsCoordinateReferenceSystem(layers.WGS84), source.sourceCrs(),
                                       context.transformContext())
    polygons, index = {}, QgsSpatialIndex()
    for row, feature in enumerate(source.getFeatures(QgsFeatureRequest().setNoAttributes()), start=1):
        geometry = feature.geometry()
        if geometry is None or geometry.isEmpty():
            continue
        feature.setId(row)
        engine = QgsGeometry.createGeometryEngine(geometry.constGet())
        engine.prepareGeometry()  # many points against one polygon
        polygons[row] = (geometry, engine)  # the engine reads the geometry: keep both
        index.addFeature(feature)
    out = []
    for point in points:
        if point.x() != point.x():  # NaN: a geotag without a position lies in nothing
            out.append([])
            continue
        here = QgsGeometry.fromPointXY(transform.transform(point))
        candidates = index.intersects(here.boundingBox())
        out.append(sorted(row for row in candidates if polygons[row][1].contains(here.constGet())))
    return out

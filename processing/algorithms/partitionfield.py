"""``birdseye:partitionfield`` — a field cut into pieces of about an hour of one person's surveying, shared out
among the people (core/field/survey_report.py finds the cuts; QGIS cuts the geometry)."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.field.survey_report import (
    DEFAULT_GEOTAGS_PER_HOUR,
    DEFAULT_TARGETS_PER_HA,
    M2_PER_HA,
    PARTITION_FIELDS,
    partition_field,
    partition_records,
    report_geotags_per_hour,
)
from ...birdseye_qgis.qgis_enums import (
    DISTANCE_METERS,
    GEOMETRY_POLYGON,
    NUMBER_DOUBLE,
    NUMBER_INTEGER,
    SOURCE_VECTOR_POLYGON,
    WKB_MULTI_POLYGON,
)
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm


class PartitionField(BirdsEyeAlgorithm):
    ALG_ID = "partitionfield"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("PartitionField", "Partition field")
    GROUP = "field"

    AREA = "AREA"
    N_PEOPLE = "N_PEOPLE"
    HOURS_PER_PIECE = "HOURS_PER_PIECE"
    GEOTAGS_PER_HOUR = "GEOTAGS_PER_HOUR"
    REPORT = "REPORT"
    TARGETS_PER_HA = "TARGETS_PER_HA"
    OUTPUT = "OUTPUT"

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(
            self.AREA, self.tr("Field(s) to partition (polygons)"), layer_kinds.AREAS, [SOURCE_VECTOR_POLYGON]))
        self.addParameter(QgsProcessingParameterNumber(
            self.N_PEOPLE, self.tr("People surveying"), NUMBER_INTEGER, defaultValue=2, minValue=1))
        self.addParameter(QgsProcessingParameterNumber(
            self.HOURS_PER_PIECE, self.tr("Surveying time per piece [h]"), NUMBER_DOUBLE, defaultValue=1.0,
            minValue=0.01))
        self.addParameter(QgsProcessingParameterNumber(
            self.GEOTAGS_PER_HOUR, self.tr("Geotags per worker-hour"), NUMBER_DOUBLE,
            defaultValue=DEFAULT_GEOTAGS_PER_HOUR, minValue=0.01))
        self.addParameter(QgsProcessingParameterFile(
            self.REPORT, self.tr("Rate from a Survey report (JSON)"), optional=True,
            fileFilter="Survey report (*.json)"))
        self.addParameter(QgsProcessingParameterNumber(
            self.TARGETS_PER_HA, self.tr("Targets per hectare"), NUMBER_DOUBLE,
            defaultValue=DEFAULT_TARGETS_PER_HA, minValue=0.01))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Partitions"), SOURCE_VECTOR_POLYGON))
        for name, label in (("PIECES", "Pieces"), ("AREA_HA", "Area [ha]"),
                            ("EXPECTED_HOURS", "Expected worker-hours [h]"),
                            ("GEOTAGS_PER_HOUR_USED", "Geotags per worker-hour used")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(label)))

    def processAlgorithm(self, parameters, context, feedback):
        area = self.parameterAsSource(parameters, self.AREA, context)
        if area is None:
            raise QgsProcessingException(self.tr("AREA: the polygon layer could not be opened."))
        rate = self.parameterAsDouble(parameters, self.GEOTAGS_PER_HOUR, context)
        report = self.parameterAsFile(parameters, self.REPORT, context)
        if report:
            rate = self.run_core(report_geotags_per_hour, report)
            feedback.pushInfo(self.tr("Rate from the survey report: {r:.1f} geotags per worker-hour.").format(r=rate))
        people = self.parameterAsInt(parameters, self.N_PEOPLE, context)
        hours_per_piece = self.parameterAsDouble(parameters, self.HOURS_PER_PIECE, context)
        targets = self.parameterAsDouble(parameters, self.TARGETS_PER_HA, context)
        crs = self._metric_crs(area, context)
        to_metric = QgsCoordinateTransform(area.sourceCrs(), crs, context.transformContext())
        fields_cut, plans = [], []
        for row, feature in enumerate(area.getFeatures(), start=1):
            geometry = QgsGeometry(feature.geometry())
            if geometry.isNull() or geometry.isEmpty():
                raise QgsProcessingException(self.tr("AREA: row {row} of layer '{layer}' has no polygon; remove it "
                                                     "or draw the field.").format(row=row, layer=area.sourceName()))
            geometry.convertToStraightSegment()
            geometry.transform(to_metric)
            fields_cut.append(geometry)
            plans.append(self.run_core(partition_field, polygon_rings(geometry), people, hours_per_piece, rate,
                                       targets))
        if not plans:
            raise QgsProcessingException(self.tr("AREA: layer '{}' has no polygon to partition.")
                                         .format(area.sourceName()))

        fields = layers.qgs_fields(PARTITION_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_MULTI_POLYGON, crs)
        records = self.run_core(partition_records, plans)
        geometries = (self._piece(fields_cut[record["field"] - 1], plan, piece) for plan, piece, record in records)
        self.run_core(layers.write_records, sink, fields, [r for _, _, r in records], geometries, feedback)
        layers.style_on_load(context, dest_id, "partitions.qml")
        total_ha = sum(plan.area_m2 for plan in plans) / M2_PER_HA
        hours = sum(piece.expected_hours for _, piece, _ in records)
        feedback.pushInfo(self.tr(
            "{n} field(s), {ha:.2f} ha → {k} piece(s) of about {h:.2f} h each for {p} people ({r:g} geotags per "
            "worker-hour, {t:g} targets per ha): {hours:.1f} worker-hours in all.").format(
            n=len(plans), ha=total_ha, k=len(records), h=hours / len(records),
            p=people, r=rate, t=targets, hours=hours))
        return {self.OUTPUT: dest_id, "PIECES": len(records), "AREA_HA": total_ha, "EXPECTED_HOURS": hours,
                "GEOTAGS_PER_HOUR_USED": rate}

    def _metric_crs(self, area, context) -> QgsCoordinateReferenceSystem:
        """The area's own CRS when it is projected in metres, else the UTM zone of its centre: areas and cuts need
        metres."""
        crs = area.sourceCrs()
        if not crs.isValid():
            raise QgsProcessingException(self.tr("AREA: layer '{}' has no valid CRS; set it (Layer Properties › "
                                                 "Source) and run again.").format(area.sourceName()))
        if not crs.isGeographic() and crs.mapUnits() == DISTANCE_METERS:
            return crs
        extent = QgsCoordinateTransform(crs, QgsCoordinateReferenceSystem(layers.WGS84),
                                        context.transformContext()).transformBoundingBox(area.sourceExtent())
        centre = extent.center()
        return self.run_core(layers.output_crs, None, [centre.y()], [centre.x()])[1]

    def _piece(self, field_geometry, plan, piece) -> QgsGeometry:
        """The piece's part of the field: the field cut by its strip (QGIS's intersection keeps a concave field's
        strip as it is, in one or several parts)."""
        strip = QgsGeometry.fromPolygonXY([[QgsPointXY(float(x), float(y)) for x, y in plan.strip(piece)]])
        cut = field_geometry.intersection(strip)
        # A cut along one of the field's own edges adds that edge as a line (a geometry collection): keep the area.
        cut.convertGeometryCollectionToSubclass(GEOMETRY_POLYGON)
        if cut.isEmpty():
            raise InputError(f"piece {piece.partition} of the field came out empty; is the field's polygon valid?")
        cut.convertToMultiType()
        return cut


def polygon_rings(geometry: QgsGeometry) -> list:
    """A polygon geometry as core's polygons: per part, its rings (exterior, then holes) as (K, 2) arrays."""
    parts = geometry.asMultiPolygon() if geometry.isMultipart() else [geometry.asPolygon()]
    return [[np.array([(p.x(), p.y()) for p in ring]) for ring in part] for part in parts]

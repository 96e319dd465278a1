"""birdseye:importcameras — a photogrammetry camera solution → frame footprints with refined poses."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.geotags import GEOTAG_FIELDS
from ...birdseye_qgis.core.field.solutions import import_camera_solution
from ...birdseye_qgis.core.geometry.geodesy import ProjectedCRS
from ...birdseye_qgis.core.labels.mark_check import MARK_CHECK_FIELDS
from ...birdseye_qgis.qgis_enums import (
    DISTANCE_METERS,
    FILE_BEHAVIOR_FILE,
    FILE_BEHAVIOR_FOLDER,
    NUMBER_DOUBLE,
    SOURCE_VECTOR_POINT,
    SOURCE_VECTOR_POLYGON,
    WKB_POINT_Z,
)
from ...birdseye_qgis.qgis_io import layers
from ..parameters.dem import DemParametersMixin
from .base import BirdsEyeAlgorithm, rounded

#: Decimals of the label check layer's computed figures: 0.01 px, 1 mm (the marks keep the solution's own).
MARK_CHECK_DECIMALS = {"u_label": 2, "v_label": 2, "error_px": 2, "error_m": 3}
#: COLMAP_REFERENCE choices, in the order of :data:`COLMAP_REFERENCE_LABELS`.
COLMAP_REFERENCES = ("gps", "ecef", "enu")
COLMAP_REFERENCE_LABELS = (
    QT_TRANSLATE_NOOP("ImportCameras", "Align to the images' GPS tags (needs IMAGES)"),
    QT_TRANSLATE_NOOP("ImportCameras", "Georegistered in ECEF (COLMAP's model_aligner)"),
    QT_TRANSLATE_NOOP("ImportCameras", "East-north-up at ENU_ORIGIN"),
)


class ImportCameras(DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "importcameras"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ImportCameras",
                                    "Import camera solution (Metashape, OpenDroneMap, COLMAP, Pix4D)")
    GROUP = "field"
    CAMERAS = "CAMERAS"
    IMAGES = "IMAGES"
    GROUND_HEIGHT_M = "GROUND_HEIGHT_M"
    COLMAP_REFERENCE = "COLMAP_REFERENCE"
    ENU_ORIGIN = "ENU_ORIGIN"
    SOLUTION_CRS = "SOLUTION_CRS"
    OUTPUT_CRS = "OUTPUT_CRS"
    OUTPUT = "OUTPUT"
    OUTPUT_CONTROL = "OUTPUT_CONTROL"
    OUTPUT_MARK_CHECK = "OUTPUT_MARK_CHECK"
    FRAME_COUNT = "FRAME_COUNT"
    NOT_ALIGNED_COUNT = "NOT_ALIGNED_COUNT"
    MARKS_MEDIAN_PX = "MARKS_MEDIAN_PX"
    MARKS_P90_PX = "MARKS_P90_PX"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.CAMERAS, self.tr("Metashape .psx/.psz or other camera solution"),
            behavior=FILE_BEHAVIOR_FILE,
            fileFilter=self.tr("Camera solutions") + " (*.psx *.psz *.xml *.json *.bin *.txt);;"
                       + self.tr("All files") + " (*)"))
        self.addParameter(QgsProcessingParameterFile(
            self.IMAGES, self.tr("Image folder (matched by file name)"), behavior=FILE_BEHAVIOR_FOLDER, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.GROUND_HEIGHT_M, self.tr("Ground height without tie points (m)"),
            NUMBER_DOUBLE, None, optional=True, minValue=-1000.0, maxValue=9000.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.COLMAP_REFERENCE, self.tr("A COLMAP model's frame"),
            options=[self.tr(label) for label in COLMAP_REFERENCE_LABELS], defaultValue=0))
        self.addParameter(QgsProcessingParameterString(
            self.ENU_ORIGIN, self.tr("COLMAP ENU origin: lat, lon, height (m)"),
            optional=True))
        self.addParameter(QgsProcessingParameterCrs(
            self.SOLUTION_CRS, self.tr("Output CRS of a Pix4D project"), optional=True))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: the site's UTM zone)"), optional=True))
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Solved frames"), SOURCE_VECTOR_POLYGON))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_CONTROL, self.tr("Control points (as geotags)"), SOURCE_VECTOR_POINT,
            optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_MARK_CHECK, self.tr("Label check (pinned image marks)"),
            SOURCE_VECTOR_POINT, optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputNumber(self.FRAME_COUNT, self.tr("Frames written")))
        self.addOutput(QgsProcessingOutputNumber(self.NOT_ALIGNED_COUNT, self.tr("Cameras the solution did not "
                                                                                 "align")))
        self.addOutput(QgsProcessingOutputNumber(self.MARKS_MEDIAN_PX, self.tr("Median distance of the control "
                                                                               "points' labels from their marks (px)")))
        self.addOutput(QgsProcessingOutputNumber(self.MARKS_P90_PX, self.tr("90th percentile of that distance "
                                                                            "(px)")))

    def processAlgorithm(self, parameters, context, feedback):
        path = self.parameterAsFile(parameters, self.CAMERAS, context)
        images = self.parameterAsFile(parameters, self.IMAGES, context) or None
        ground = (self.parameterAsDouble(parameters, self.GROUND_HEIGHT_M, context)
                  if parameters.get(self.GROUND_HEIGHT_M) not in (None, "") else None)
        reference = COLMAP_REFERENCES[self.parameterAsEnum(parameters, self.COLMAP_REFERENCE, context)]
        if reference == "enu":
            reference = "enu:" + self.parameterAsString(parameters, self.ENU_ORIGIN, context)
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        solution_crs = self._solution_crs(parameters, context)
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 80.0)
        result = self.run_core(import_camera_solution, path, images, chosen, dem, ground, reference,
                               solution_crs=solution_crs, progress=progress, is_canceled=is_canceled)
        layers.report_to_feedback(feedback, result.report)
        for cam in {id(c): c for c in result.frames.cameras}.values():
            feedback.pushInfo(self.tr("Camera: {width}×{height} px, fx {fx:.2f}, fy {fy:.2f}, cx {cx:.2f}, cy {cy:.2f} "
                                      "({source})").format(width=cam.width, height=cam.height, fx=cam.fx, fy=cam.fy,
                                                           cx=cam.cx, cy=cam.cy, source=cam.source))
        crs_core, crs = self.run_core(layers.output_crs, chosen, result.frames.lat, result.frames.lon)
        feedback.pushInfo(self.tr("Output CRS: {value}").format(value=crs.authid() or crs.description()))
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, crs)
        outputs[self.NOT_ALIGNED_COUNT] = result.report.counts.get("not_aligned", 0)
        if result.control_points is not None:
            outputs.update(self.run_core(self._write_control, parameters, context, result, crs_core, crs))
        return outputs

    def _solution_crs(self, parameters, context) -> ProjectedCRS | None:
        """The CRS of a Pix4D project's coordinates, or None when not given (a Pix4D input is then refused)."""
        crs = self.parameterAsCrs(parameters, self.SOLUTION_CRS, context)
        if not crs.isValid():
            return None
        if crs.isGeographic() or crs.mapUnits() != DISTANCE_METERS:
            raise QgsProcessingException(self.tr(
                "SOLUTION_CRS: {crs} is not a projected CRS in metres; give the Pix4D project's output CRS "
                "(easting, northing and height in metres)").format(crs=crs.authid() or crs.description()))
        return ProjectedCRS(layers.pyproj_crs(crs))

    def _write_control(self, parameters, context, result, crs_core, crs) -> dict:
        """The control points as a geotag layer, and each pinned mark with its label's distance from it."""
        points, check = result.control_points, result.mark_check
        outputs = {}
        fields = layers.qgs_fields(GEOTAG_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT_CONTROL, context, fields, WKB_POINT_Z, crs)
        if sink is not None:
            x, y = crs_core.from_geodetic(points.lat, points.lon)
            z = np.nan_to_num(points.height)
            layers.write_records(sink, fields, points.records(), (layers.point_z(*p) for p in zip(x, y, z)))
            layers.style_on_load(context, dest_id, "geotags.qml", self.tr("Control points"))
            outputs[self.OUTPUT_CONTROL] = dest_id
        if check is None:
            return outputs
        summary = rounded(check.summary(), {"median_px": 2, "p90_px": 2})
        outputs[self.MARKS_MEDIAN_PX] = summary.get("median_px")
        outputs[self.MARKS_P90_PX] = summary.get("p90_px")
        fields = layers.qgs_fields(MARK_CHECK_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT_MARK_CHECK, context, fields, WKB_POINT_Z, crs)
        if sink is not None:
            x, y = crs_core.from_geodetic(check.mark_lat, check.mark_lon)
            z = np.nan_to_num(points.height)[check.point_idx]
            geometries = (layers.point_z(*p) if np.all(np.isfinite(p)) else None for p in zip(x, y, z))
            records = (rounded(record, MARK_CHECK_DECIMALS)
                       for record in check.records(result.frames.frame_id, result.frames.image))
            layers.write_records(sink, fields, records, geometries)
            layers.style_on_load(context, dest_id, "mark_check.qml", self.tr("Label check (pinned marks)"))
            outputs[self.OUTPUT_MARK_CHECK] = dest_id
        return outputs

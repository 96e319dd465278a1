"""birdseye:importdjiimages — a folder of drone JPEGs (DJI or any other) → frame footprints from their own
metadata. The id keeps its DJI name: saved models and scripts call it."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.drone_images import import_drone_images
from ...birdseye_qgis.core.geometry.camera import load_calibration
from ...birdseye_qgis.qgis_enums import FILE_BEHAVIOR_FOLDER, NUMBER_DOUBLE, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layers
from ..parameters.dem import DemParametersMixin
from .base import BirdsEyeAlgorithm


class ImportDjiImages(DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "importdjiimages"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ImportDjiImages", "Import drone images")
    GROUP = "field"
    IMAGES = "IMAGES"
    CALIBRATION = "CALIBRATION"
    OUTPUT_CRS = "OUTPUT_CRS"
    FLIGHT_HEIGHT_M = "FLIGHT_HEIGHT_M"
    OUTPUT = "OUTPUT"
    FRAME_COUNT = "FRAME_COUNT"
    UNPLACED_COUNT = "UNPLACED_COUNT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.IMAGES, self.tr("Folder of drone images (JPEG)"), behavior=FILE_BEHAVIOR_FOLDER))
        self.addParameter(QgsProcessingParameterFile(
            self.CALIBRATION, self.tr("Camera calibration (YAML)"), optional=True,
            fileFilter="Calibration (*.yaml *.yml);;All files (*)"))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: the site's UTM zone)"), optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.FLIGHT_HEIGHT_M, self.tr("Flight height above take-off (m)"), NUMBER_DOUBLE,
            None, optional=True, minValue=0.5))
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Drone frames"), SOURCE_VECTOR_POLYGON))
        self.addOutput(QgsProcessingOutputNumber(self.FRAME_COUNT, self.tr("Frames written")))
        self.addOutput(QgsProcessingOutputNumber(self.UNPLACED_COUNT, self.tr("Images that cannot be placed")))

    def processAlgorithm(self, parameters, context, feedback):
        folder = self.parameterAsFile(parameters, self.IMAGES, context)
        calibration_path = self.parameterAsFile(parameters, self.CALIBRATION, context)
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        calibration = self.run_core(load_calibration, calibration_path) if calibration_path else None
        flight_height = (self.parameterAsDouble(parameters, self.FLIGHT_HEIGHT_M, context)
                         if parameters.get(self.FLIGHT_HEIGHT_M) not in (None, "") else None)
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 80.0)
        result = self.run_core(import_drone_images, folder, calibration, chosen, progress=progress,
                               is_canceled=is_canceled, dem=dem, flight_height_m=flight_height)
        layers.report_to_feedback(feedback, result.report)
        for error in result.report.unplaced[5:]:
            feedback.pushInfo(self.tr("Not placed: {error}").format(error=error))
        cameras = {id(c): c for c in result.frames.cameras}.values()
        for cam in cameras:
            feedback.pushInfo(self.tr("Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} "
                                      "({source})").format(
                                  width=cam.width, height=cam.height, fx=cam.fx, fy=cam.fy, source=cam.source))
        _, crs = self.run_core(layers.output_crs, chosen, result.frames.lat, result.frames.lon)
        feedback.pushInfo(self.tr("Output CRS: {value}").format(value=crs.authid() or crs.description()))
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, crs)
        outputs[self.UNPLACED_COUNT] = len(result.report.unplaced)
        return outputs

"""birdseye:importflightlog — pose log (or flight_data.db) + images + calibration → frame footprints."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.flight_log import import_flight_log
from ...birdseye_qgis.core.geometry.camera import load_calibration
from ...birdseye_qgis.qgis_enums import FILE_BEHAVIOR_FOLDER, NUMBER_DOUBLE, SOURCE_VECTOR_LINE, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layers
from ..parameters.dem import DemParametersMixin
from .base import BirdsEyeAlgorithm


class ImportFlightLog(DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "importflightlog"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ImportFlightLog", "Import flight log")
    GROUP = "field"
    POSE_LOG = "POSE_LOG"
    IMAGES = "IMAGES"
    CALIBRATION = "CALIBRATION"
    FPS = "FPS"
    RADALT_SNR_MIN = "RADALT_SNR_MIN"
    RTK_FILTER = "RTK_FILTER"
    UTM_CRS = "UTM_CRS"
    OUTPUT_CRS = "OUTPUT_CRS"
    OUTPUT = "OUTPUT"
    OUTPUT_TRACK = "OUTPUT_TRACK"

    RTK_FILTERS = ["All frames (float and no-RTK frames flagged)", "RTK fixed frames only"]

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.POSE_LOG, self.tr("Pose log (BirdsEye CSV or flight_data.db)"),
            fileFilter="Pose logs (*.csv *.txt *.db *.sqlite);;All files (*)"))
        self.addParameter(QgsProcessingParameterFile(
            self.IMAGES, self.tr("Image folder"),
            behavior=FILE_BEHAVIOR_FOLDER, optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.CALIBRATION, self.tr("Camera calibration (Kalibr camchain or OpenCV YAML)"),
            fileFilter="Calibration (*.yaml *.yml);;All files (*)"))
        fps = QgsProcessingParameterNumber(self.FPS, self.tr("Camera frame rate (frames/s)"),
                                           NUMBER_DOUBLE, 5.0, minValue=0.01)
        self.addParameter(fps)
        self.addParameter(QgsProcessingParameterNumber(
            self.RADALT_SNR_MIN, self.tr("Minimum altimeter SNR (dB)"), NUMBER_DOUBLE, 13.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.RTK_FILTER, self.tr("RTK filter"), options=self.RTK_FILTERS, defaultValue=0))
        self.addParameter(QgsProcessingParameterCrs(
            self.UTM_CRS, self.tr("UTM zone of flight_data.db x, y"), optional=True))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: the site's UTM zone)"), optional=True))
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Frames"), SOURCE_VECTOR_POLYGON))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT_TRACK, self.tr("Flight line"), SOURCE_VECTOR_LINE, optional=True,
            createByDefault=True))
        for name, text in (("FRAME_COUNT", "Frames written"), ("UNMATCHED_STROBES", "Strobes without image"),
                           ("UNMATCHED_IMAGES", "Images without strobe"), ("BAD_ROWS", "Bad rows left out")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        pose_log = self.parameterAsFile(parameters, self.POSE_LOG, context)
        images = self.parameterAsFile(parameters, self.IMAGES, context) or None
        calibration = self.parameterAsFile(parameters, self.CALIBRATION, context)
        utm = self.parameterAsCrs(parameters, self.UTM_CRS, context)
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        utm_crs = self.run_core(layers.chosen_projected_crs, utm, self.UTM_CRS)
        camera = self.run_core(load_calibration, calibration)
        feedback.pushInfo(self.tr("Camera: {width}×{height} px, fx {fx:.1f}, fy {fy:.1f} "
                                  "({source})").format(
                              width=camera.width, height=camera.height, fx=camera.fx, fy=camera.fy,
                              source=camera.source))
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 80.0)
        result = self.run_core(
            import_flight_log, pose_log, images, camera, dem=dem,
            fps=self.parameterAsDouble(parameters, self.FPS, context),
            radalt_snr_min=self.parameterAsDouble(parameters, self.RADALT_SNR_MIN, context),
            fixed_only=self.parameterAsEnum(parameters, self.RTK_FILTER, context) == 1,
            utm_crs=None if utm_crs is None else utm_crs.crs, crs=chosen,
            with_track=parameters.get(self.OUTPUT_TRACK) is not None,
            progress=progress, is_canceled=is_canceled)
        layers.report_to_feedback(feedback, result.report)
        _, crs = self.run_core(layers.output_crs, chosen, result.frames.lat, result.frames.lon)
        feedback.pushInfo(self.tr("Output CRS: {value}").format(value=crs.authid() or crs.description()))
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, crs,
                                self.OUTPUT, self.OUTPUT_TRACK)
        counts = result.report.counts
        outputs.update(UNMATCHED_STROBES=counts.get("unmatched_strobes", 0),
                       UNMATCHED_IMAGES=counts.get("unmatched_images", 0), BAD_ROWS=counts.get("bad_rows", 0))
        return outputs

"""birdseye:importcameras — a photogrammetry camera solution → frame footprints with refined poses."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.solutions import import_camera_solution
from ...birdseye_qgis.qgis_enums import FILE_BEHAVIOR_FILE, FILE_BEHAVIOR_FOLDER, NUMBER_DOUBLE, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layers
from ..parameters.dem import DemParametersMixin
from .base import BirdsEyeAlgorithm

#: COLMAP_REFERENCE choices, in the order of :data:`COLMAP_REFERENCE_LABELS`.
COLMAP_REFERENCES = ("gps", "ecef", "enu")
COLMAP_REFERENCE_LABELS = (
    QT_TRANSLATE_NOOP("ImportCameras", "Align to the images' GPS tags (needs IMAGES)"),
    QT_TRANSLATE_NOOP("ImportCameras", "Already georegistered in ECEF (model_aligner --alignment_type ecef)"),
    QT_TRANSLATE_NOOP("ImportCameras", "East-north-up at the origin given in ENU_ORIGIN"),
)


class ImportCameras(DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "importcameras"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ImportCameras", "Import camera solution (Metashape, OpenDroneMap, COLMAP)")
    GROUP = "field"
    CAMERAS = "CAMERAS"
    IMAGES = "IMAGES"
    GROUND_HEIGHT_M = "GROUND_HEIGHT_M"
    COLMAP_REFERENCE = "COLMAP_REFERENCE"
    ENU_ORIGIN = "ENU_ORIGIN"
    OUTPUT_CRS = "OUTPUT_CRS"
    OUTPUT = "OUTPUT"
    FRAME_COUNT = "FRAME_COUNT"
    NOT_ALIGNED_COUNT = "NOT_ALIGNED_COUNT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.CAMERAS, self.tr("Camera solution (Metashape cameras .xml, OpenSfM/ODM reconstruction.json, or a "
                                  "COLMAP model folder)"),
            behavior=FILE_BEHAVIOR_FILE,
            fileFilter="Camera solutions (*.xml *.json *.bin *.txt);;All files (*)"))
        self.addParameter(QgsProcessingParameterFile(
            self.IMAGES, self.tr("Folder of the images (optional; matched by file name)"),
            behavior=FILE_BEHAVIOR_FOLDER, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.GROUND_HEIGHT_M, self.tr("Ground height for frames without tie points (m, same reference as the "
                                          "solution; optional)"),
            NUMBER_DOUBLE, None, optional=True, minValue=-1000.0, maxValue=9000.0))
        self.addParameter(QgsProcessingParameterEnum(
            self.COLMAP_REFERENCE, self.tr("A COLMAP model's frame"),
            options=[self.tr(label) for label in COLMAP_REFERENCE_LABELS], defaultValue=0))
        self.addParameter(QgsProcessingParameterString(
            self.ENU_ORIGIN, self.tr("ENU origin of a COLMAP model: lat, lon, ellipsoidal height"), optional=True))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: UTM zone of the site)"), optional=True))
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Solved frames"), SOURCE_VECTOR_POLYGON))
        self.addOutput(QgsProcessingOutputNumber(self.FRAME_COUNT, self.tr("Frames written")))
        self.addOutput(QgsProcessingOutputNumber(self.NOT_ALIGNED_COUNT, self.tr("Cameras the solution did not "
                                                                                 "align")))

    def processAlgorithm(self, parameters, context, feedback):
        path = self.parameterAsFile(parameters, self.CAMERAS, context)
        images = self.parameterAsFile(parameters, self.IMAGES, context) or None
        ground = (self.parameterAsDouble(parameters, self.GROUND_HEIGHT_M, context)
                  if parameters.get(self.GROUND_HEIGHT_M) not in (None, "") else None)
        reference = COLMAP_REFERENCES[self.parameterAsEnum(parameters, self.COLMAP_REFERENCE, context)]
        if reference == "enu":
            reference = "enu:" + self.parameterAsString(parameters, self.ENU_ORIGIN, context)
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        dem = self.read_dem(parameters, context)
        self.report_dem(feedback, dem)
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 80.0)
        result = self.run_core(import_camera_solution, path, images, chosen, dem, ground, reference,
                               progress=progress, is_canceled=is_canceled)
        layers.report_to_feedback(feedback, result.report)
        for cam in {id(c): c for c in result.frames.cameras}.values():
            feedback.pushInfo(self.tr("Camera: {width}×{height} px, fx {fx:.2f}, fy {fy:.2f}, cx {cx:.2f}, cy {cy:.2f} "
                                      "({source})").format(width=cam.width, height=cam.height, fx=cam.fx, fy=cam.fy,
                                                           cx=cam.cx, cy=cam.cy, source=cam.source))
        _, crs = self.run_core(layers.output_crs, chosen, result.frames.lat, result.frames.lon)
        feedback.pushInfo(self.tr("Output CRS: {value}").format(value=crs.authid() or crs.description()))
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, crs)
        outputs[self.NOT_ALIGNED_COUNT] = result.report.counts.get("not_aligned", 0)
        return outputs

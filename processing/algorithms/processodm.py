"""birdseye:processodm — a flight's images processed on an OpenDroneMap node, imported as a camera solution."""
from __future__ import annotations

from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingParameterCrs,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFile,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.odm import parse_options, process_on_node
from ...birdseye_qgis.core.field.solutions import import_camera_solution
from ...birdseye_qgis.qgis_enums import FILE_BEHAVIOR_FOLDER, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layers
from .base import BirdsEyeAlgorithm


class ProcessOdm(BirdsEyeAlgorithm):
    ALG_ID = "processodm"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ProcessOdm", "Process on an OpenDroneMap node")
    GROUP = "field"
    IMAGES = "IMAGES"
    NODE_URL = "NODE_URL"
    TOKEN = "TOKEN"
    ODM_OPTIONS = "ODM_OPTIONS"
    OUTPUT_CRS = "OUTPUT_CRS"
    OUTPUT_FOLDER = "OUTPUT_FOLDER"
    OUTPUT = "OUTPUT"
    FRAME_COUNT = "FRAME_COUNT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.IMAGES, self.tr("Folder of the flight's images"), behavior=FILE_BEHAVIOR_FOLDER))
        self.addParameter(QgsProcessingParameterString(
            self.NODE_URL, self.tr("NodeODM / ClusterODM address"), defaultValue="http://localhost:3000"))
        self.addParameter(QgsProcessingParameterString(
            self.TOKEN, self.tr("Access token (if the node asks for one)"), optional=True))
        self.addParameter(QgsProcessingParameterString(
            self.ODM_OPTIONS, self.tr("OpenDroneMap options (name=value, …)"), optional=True,
            multiLine=True))
        self.addParameter(QgsProcessingParameterCrs(
            self.OUTPUT_CRS, self.tr("Output CRS (empty: the site's UTM zone)"), optional=True))
        self.addParameter(QgsProcessingParameterFolderDestination(
            self.OUTPUT_FOLDER, self.tr("Folder for the downloaded reconstruction")))
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Solved frames"), SOURCE_VECTOR_POLYGON))
        self.addOutput(QgsProcessingOutputNumber(self.FRAME_COUNT, self.tr("Frames written")))

    def processAlgorithm(self, parameters, context, feedback):
        images = self.parameterAsFile(parameters, self.IMAGES, context)
        options = self.run_core(parse_options, self.parameterAsString(parameters, self.ODM_OPTIONS, context) or "")
        out_dir = self.parameterAsString(parameters, self.OUTPUT_FOLDER, context)
        chosen = self.run_core(layers.chosen_projected_crs, self.parameterAsCrs(parameters, self.OUTPUT_CRS, context))
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 80.0)
        reconstruction = self.run_core(
            process_on_node, images, self.parameterAsString(parameters, self.NODE_URL, context), out_dir, options,
            self.parameterAsString(parameters, self.TOKEN, context) or "", progress, is_canceled, feedback.pushInfo)
        feedback.pushInfo(self.tr("Reconstruction: {path}").format(path=reconstruction))
        result = self.run_core(import_camera_solution, reconstruction, images, chosen)
        layers.report_to_feedback(feedback, result.report)
        _, crs = self.run_core(layers.output_crs, chosen, result.frames.lat, result.frames.lon)
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, crs)
        outputs[self.OUTPUT_FOLDER] = out_dir
        return outputs

"""birdseye:refineposes — structure from motion over a frame layer's images, aligned to its GNSS positions."""
from __future__ import annotations

import tempfile
from pathlib import Path

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterBoolean,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.field.frames import compute_footprints, dem_ground_for, frames_from_records
from ...birdseye_qgis.core.field.import_report import FlightImport, ImportReport
from ...birdseye_qgis.core.field.refinement import (
    REFINE_FIELDS,
    RefineOptions,
    ground_text,
    refine_frames,
    refinement_report_html,
    terrain_grounds,
)
from ...birdseye_qgis.qgis_enums import NUMBER_INTEGER, SOURCE_VECTOR_POINT, SOURCE_VECTOR_POLYGON
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm, rounded

#: Decimals of the refinement's figures in the refined frame layer: 0.01 px, 1 mm, 0.001°.
LAYER_DECIMALS = {"reprojection_rms_px": 2, "position_change_m": 3, "rotation_change_deg": 3,
                  "alignment_residual_m": 3}


class RefinePoses(DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "refineposes"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("RefinePoses", "Refine frame poses (structure from motion)")
    GROUP = "field"
    FRAMES = "FRAMES"
    MATCH_SIZE_PX = "MATCH_SIZE_PX"
    MAX_FEATURES = "MAX_FEATURES"
    REFINE_INTRINSICS = "REFINE_INTRINSICS"
    GEOTAGS = "GEOTAGS"
    OUTPUT = "OUTPUT"
    OUTPUT_REPORT = "OUTPUT_REPORT"
    REGISTERED_COUNT = "REGISTERED_COUNT"

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(
            self.FRAMES, self.tr("Frames (with their images)"), layer_kinds.FRAMES, [SOURCE_VECTOR_POLYGON]))
        self.addParameter(QgsProcessingParameterNumber(
            self.MATCH_SIZE_PX, self.tr("Feature image size (px, longer side)"),
            NUMBER_INTEGER, 2000, minValue=400, maxValue=10000))
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_FEATURES, self.tr("Features per image (at most)"), NUMBER_INTEGER, 8192,
            minValue=500, maxValue=65536))
        self.addParameter(QgsProcessingParameterBoolean(
            self.REFINE_INTRINSICS, self.tr("Refine focal length and distortion"), defaultValue=False))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags with surveyed heights"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT],
            optional=True))
        self.add_dem_parameters()
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Refined frames"), SOURCE_VECTOR_POLYGON))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_REPORT, self.tr("Report (HTML)"), "HTML (*.html)", optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputNumber(self.REGISTERED_COUNT, self.tr("Frames registered")))

    def processAlgorithm(self, parameters, context, feedback):
        source = self.parameterAsSource(parameters, self.FRAMES, context)
        if source is None:
            raise QgsProcessingException(self.tr("FRAMES is required."))
        name = source.sourceName()
        records = self.run_core(layers.read_frame_layer, source, name)
        frames = self.run_core(frames_from_records, records, name)
        options = RefineOptions(match_size_px=self.parameterAsInt(parameters, self.MATCH_SIZE_PX, context),
                                max_features=self.parameterAsInt(parameters, self.MAX_FEATURES, context),
                                refine_intrinsics=self.parameterAsBoolean(parameters, self.REFINE_INTRINSICS, context))
        feedback.pushInfo(self.tr("{n} frames; SIFT features at {size} px, at most {features} per image").format(
            n=len(frames), size=options.match_size_px, features=options.max_features))
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        heights = None if geotag_source is None else self.run_core(
            layers.read_geotag_layer, geotag_source, context.transformContext()).height
        if heights is not None and np.isfinite(heights).any():
            feedback.pushInfo(self.tr("{n} geotags with a surveyed height: the ground plane at {h:.2f} m "
                                      "(ellipsoidal)").format(n=int(np.isfinite(heights).sum()),
                                                              h=float(np.nanmedian(heights))))
        undulation = (self.parameterAsDouble(parameters, self.GEOID_UNDULATION_M, context)
                      if parameters.get(self.GEOID_UNDULATION_M) not in (None, "") else None)
        dem = self.read_dem(parameters, context, source, feedback)
        self.report_dem(feedback, dem)
        terrain = None
        if dem is not None:
            terrain, check = self.run_core(terrain_grounds, frames, dem)
            feedback.pushInfo(self.tr("DEM against the frames: {check}").format(check=check.describe()))
        progress, is_canceled = self.progress_callbacks(feedback, 0.0, 85.0)
        with tempfile.TemporaryDirectory(prefix="birdseye-sfm-") as workdir:
            refined, refinement, values = self.run_core(refine_frames, frames, workdir, options, progress, is_canceled,
                                                        heights, undulation, terrain)
        for choice in refinement.grounds:
            feedback.pushInfo(self.tr("Ground of the GNSS camera-to-ground distances: {text}").format(
                text=ground_text(choice, frames)))
            if choice.warning:
                feedback.pushWarning(choice.warning)
        feedback.pushInfo(self.tr("Registered {n} of {total} frames in {seconds:.0f} s ({rate:.1f} images per "
                                  "minute); intrinsics {intrinsics}").format(
                              n=refinement.n_registered, total=len(frames), seconds=sum(refinement.seconds.values()),
                              rate=refinement.images_per_minute, intrinsics=refinement.intrinsics))
        if refinement.similarity is not None:
            feedback.pushInfo(self.tr("Aligned to the GNSS positions: residual RMS {rms:.3f} m").format(
                rms=refinement.alignment_rms_m))
        if np.isfinite(refinement.depth_ratio):
            feedback.pushInfo(self.tr("Camera-to-ground distance of the block / (GNSS height − ground height): "
                                      "{ratio:.4f}").format(ratio=refinement.depth_ratio))
        for note in refinement.notes:
            feedback.pushWarning(note)
        missing = [(frames.image[i], r.reason) for i, r in enumerate(refinement.frames) if not r.registered]
        if missing:
            feedback.reportError(self.tr("{n} frame(s) keep their metadata pose (flag not_refined); first: "
                                         "{items}").format(n=len(missing), items="; ".join(
                                             f"{Path(image).name}: {why}" for image, why in missing[:5])), False)
        chosen = self.run_core(layers.chosen_projected_crs, source.sourceCrs(), self.FRAMES)
        crs, qgs_crs = self.run_core(layers.output_crs, chosen, refined.lat, refined.lon)
        report = ImportReport(name)
        fp = self.run_core(compute_footprints, refined, crs, ground=self.run_core(dem_ground_for, refined, dem, report))
        layers.report_to_feedback(feedback, report)
        result = FlightImport(refined, fp, [], report)
        outputs = self.run_core(layers.write_frames, self, parameters, context, feedback, result, qgs_crs,
                                extra_fields=REFINE_FIELDS,
                                extra_values=[rounded(v, LAYER_DECIMALS) for v in values])
        outputs[self.REGISTERED_COUNT] = refinement.n_registered
        report_path = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        if report_path:
            try:
                Path(report_path).write_text(refinement_report_html(refinement, frames, values, name),
                                             encoding="utf-8")
            except OSError as exc:
                raise QgsProcessingException(self.tr("OUTPUT_REPORT: cannot write {path} ({error})").format(
                    path=report_path, error=exc)) from exc
            outputs[self.OUTPUT_REPORT] = report_path
        return outputs

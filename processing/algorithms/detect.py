"""birdseye:detect — run an ONNX heatmap model over the frames of a frame layer → detections on the ground."""
from __future__ import annotations

import numpy as np
from qgis.core import (
    QgsProcessingOutputNumber,
    QgsProcessingOutputString,
    QgsProcessingParameterFeatureSink,
    QgsProcessingParameterFolderDestination,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.__about__ import BUNDLED_MODEL
from ...birdseye_qgis.core.detect.detector import DetectRequest, HeatmapModel, detect_frames
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.field.frame_records import local_frame_around, poses_from_records
from ...birdseye_qgis.core.geometry.geodesy import ProjectedCRS
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_VECTOR_POINT, SOURCE_VECTOR_POLYGON, WKB_POINT_Z
from ...birdseye_qgis.qgis_io import layer_kinds, layers
from ...birdseye_qgis.qgis_io.detections import DETECTION_FIELDS, ground_attributes
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from ..parameters.model import ModelParametersMixin
from .base import BirdsEyeAlgorithm

DEFAULT_MODEL = BUNDLED_MODEL


class Detect(ModelParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "detect"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("Detect", "Detect targets (ONNX heatmap model)")
    GROUP = "detect"
    FRAMES = "FRAMES"
    EDGE_BUFFER_PX = "EDGE_BUFFER_PX"
    OUTPUT = "OUTPUT"
    OUTPUT_HEATMAPS = "OUTPUT_HEATMAPS"
    MODEL_DIGEST = "MODEL_DIGEST"

    def initAlgorithm(self, config=None):
        self.addParameter(source_parameter(
            self.FRAMES, self.tr("Frames"), layer_kinds.FRAMES, [SOURCE_VECTOR_POLYGON, SOURCE_VECTOR_POINT]))
        self.add_model_parameters()
        self.addParameter(QgsProcessingParameterNumber(
            self.EDGE_BUFFER_PX, self.tr("Edge buffer at the image border (px)"),
            NUMBER_DOUBLE, 0.0, minValue=0.0))
        self.add_dem_parameters(ground_model=True)
        self.addParameter(QgsProcessingParameterFeatureSink(
            self.OUTPUT, self.tr("Detections"), SOURCE_VECTOR_POINT))
        self.addParameter(QgsProcessingParameterFolderDestination(
            self.OUTPUT_HEATMAPS, self.tr("Heatmap folder (one PNG per frame)"), optional=True,
            createByDefault=False))
        for name, text in (("DETECTION_COUNT", "Detections written"), ("FRAMES_PROCESSED", "Frames processed"),
                           ("FRAMES_SKIPPED", "Frames skipped"), ("THRESHOLD_USED", "Threshold used")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))
        self.addOutput(QgsProcessingOutputString(self.MODEL_DIGEST, self.tr("SHA-256 of the model")))

    def processAlgorithm(self, parameters, context, feedback):
        source = self.parameterAsSource(parameters, self.FRAMES, context)
        if source is None:
            raise self.user_error(InputError("no frame layer given", field=self.FRAMES))
        self.dem = self.read_dem(parameters, context)
        self.report_dem(feedback, self.dem)
        model_path, threshold = self.model_choice(parameters, context)
        heat_dir = None
        if parameters.get(self.OUTPUT_HEATMAPS) not in (None, ""):
            heat_dir = self.parameterAsString(parameters, self.OUTPUT_HEATMAPS, context) or None
        request = DetectRequest(threshold=threshold,
                                edge_buffer_px=self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
                                heatmap_dir=heat_dir)

        model = self.run_core(HeatmapModel, model_path, log=feedback.pushInfo)
        meta = model.metadata
        used = meta.default_threshold if threshold is None else threshold
        feedback.pushInfo(self.tr("Model {name} (sha256 {value}…): {resolution_cm:g} cm/px, "
                                  "tiles {tile_size} px with {overlap_px} px overlap, threshold "
                                  "{used:g}{value2}.").format(
                              name=model.name, value=model.digest[:12], resolution_cm=meta.resolution_cm,
                              tile_size=meta.tile_size, overlap_px=meta.overlap_px, used=used,
                              value2=' (the model default)' if threshold is None else ''))
        records = self.run_core(layers.read_frame_layer, source, self.tr(self.FRAMES))
        groups = self.run_core(poses_from_records, records, source.sourceName() or self.FRAMES)
        crs = source.sourceCrs()
        if crs.isValid():
            to_crs = ProjectedCRS(layers.pyproj_crs(crs))
        else:  # a frame layer saved as CSV and read back through OGR names no CRS: the site's UTM zone
            to_crs, crs = layers.output_crs(None, np.concatenate([p.lat for p, _ in groups]),
                                            np.concatenate([p.lon for p, _ in groups]))
            feedback.pushWarning(self.tr("{FRAMES} has no CRS: the detections are written in {crs}, the UTM zone "
                                         "of the site.").format(FRAMES=self.FRAMES, crs=crs.authid()))

        fields = layers.qgs_fields(DETECTION_FIELDS)
        sink, dest_id = self.parameterAsSink(parameters, self.OUTPUT, context, fields, WKB_POINT_Z, crs)
        if sink is None:
            raise self.user_error(InputError("the detection output cannot be created", field=self.OUTPUT))
        counts = self.run_core(self._detect, model, groups, records, request, to_crs, sink, fields, feedback)
        layers.style_on_load(context, dest_id, "detections.qml")
        feedback.pushInfo(self.tr("{detections} detections in {processed} frames ({value:.2f} "
                                  "per frame); {edge} dropped within {edge_buffer_px:g} px of "
                                  "the border, {no_ground} whose ray missed the ground; "
                                  "{skipped} frames skipped.").format(
                              detections=counts['detections'], processed=counts['processed'],
                              value=counts['detections'] / max(1, counts['processed']), edge=counts['edge'],
                              edge_buffer_px=request.edge_buffer_px, no_ground=counts['no_ground'],
                              skipped=counts['skipped']))
        return {"OUTPUT": dest_id, self.OUTPUT_HEATMAPS: heat_dir, "DETECTION_COUNT": counts["detections"],
                "FRAMES_PROCESSED": counts["processed"], "FRAMES_SKIPPED": counts["skipped"],
                "THRESHOLD_USED": used, self.MODEL_DIGEST: model.digest}

    def _detect(self, model, groups, records, request, to_crs, sink, fields, feedback) -> dict:
        """Stream every camera group's frames through the detector into the sink."""
        local = local_frame_around(groups)
        threshold = model.metadata.default_threshold if request.threshold is None else request.threshold
        # Every detection carries the ground it was placed on: scoring and the review stand on the same one.
        placed_on = {**ground_attributes(self.ground_record(self.dem)), "height_ref": groups[0][0].reference.text}
        ground = self.dem_ground(self.dem, [poses for poses, _ in groups], feedback)
        total = sum(len(p) for p, _ in groups)
        counts = dict(detections=0, processed=0, skipped=0, edge=0, no_ground=0)
        coarse = []
        done = 0
        for poses, record_index in groups:
            images = [records[i].get("image") or "" for i in record_index]
            progress, is_canceled = self.progress_callbacks(feedback, 100.0 * done / total,
                                                            100.0 * (done + len(poses)) / total)
            for found in detect_frames(model, poses, images, request, local=local, progress=progress,
                                       is_canceled=is_canceled, ground=ground):
                if found.skipped:
                    counts["skipped"] += 1
                    feedback.pushWarning(self.tr("Frame {frame_id}: {skipped}; skipped.").format(
                                             frame_id=found.frame_id, skipped=found.skipped))
                    continue
                counts["processed"] += 1
                counts["edge"] += found.n_edge
                counts["no_ground"] += found.n_no_ground
                if found.gsd_cm > 1.5 * model.metadata.resolution_cm:
                    coarse.append(found.frame_id)
                if len(found):
                    x, y = to_crs.from_geodetic(found.lat, found.lon)
                    rows = ({"frame_id": int(found.frame_id), "u": float(u), "v": float(v), "score": float(s),
                             "model": model.name, "model_digest": model.digest, "threshold": threshold,
                             **placed_on}
                            for (u, v), s in zip(found.uv, found.score))
                    geoms = (layers.point_z(a, b, c) for a, b, c in zip(np.atleast_1d(x), np.atleast_1d(y),
                                                                       found.height))
                    counts["detections"] += layers.write_records(sink, fields, rows, geoms)
            done += len(poses)
        if coarse:
            feedback.pushWarning(
                self.tr("{n_coarse} frame(s) (e.g. {items}) are coarser than 1.5× the model's "
                        "resolution of {resolution_cm:g} cm/px: targets look smaller than in "
                        "training, so expect fewer detections (fly lower or use a model trained "
                        "at that resolution).").format(
                    n_coarse=len(coarse), items=', '.join(str(f) for f in coarse[:5]),
                    resolution_cm=model.metadata.resolution_cm))
        return counts

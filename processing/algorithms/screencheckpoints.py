"""birdseye:screencheckpoints — several ONNX checkpoints over several validation flights at one threshold."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from qgis.core import (
    QgsProcessing,
    QgsProcessingException,
    QgsProcessingMultiStepFeedback,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.detector import DetectRequest, HeatmapModel, detect_frames
from ...birdseye_qgis.core.errors import Cancelled
from ...birdseye_qgis.core.labels.training_set import Geotags as LabelGeotags
from ...birdseye_qgis.core.labels.training_set import project_labels
from ...birdseye_qgis.core.scoring.evaluation import local_frame_for
from ...birdseye_qgis.core.scoring.matching import in_view
from ...birdseye_qgis.core.scoring.reports import screen_figure
from ...birdseye_qgis.core.scoring.screening import (
    DEFAULT_COLLAPSED_BELOW,
    DEFAULT_PIXEL_RADIUS_PX,
    DEFAULT_SPARSE_BELOW,
    ScreenRun,
    screen_checkpoints,
)
from ...birdseye_qgis.qgis_io.detections import read_geotags, read_pose_groups
from ...birdseye_qgis.qgis_io.outputs import write_output, write_rows_csv
from ..parameters.clustering import ClusteringParametersMixin
from .base import BirdsEyeAlgorithm


def pixel_labels(poses, local, geotags, edge_buffer_px):
    """(frame_id, uv) of every in-view geotag in every frame, as writelabels would write them."""
    tags = LabelGeotags(geotags.ids, [""] * len(geotags), geotags.lat, geotags.lon,
                        np.where(np.isfinite(geotags.height), geotags.height, local.h0))
    frame_ids, uvs = [], []
    for fl in project_labels(poses, tags, edge_buffer_px, local=local):
        keep = ~fl.edge
        frame_ids.append(np.full(int(keep.sum()), poses.frame_id[fl.frame_index], dtype=object))
        uvs.append(fl.uv[keep])
    if not frame_ids:
        return np.empty(0, dtype=object), np.empty((0, 2))
    return np.concatenate(frame_ids), np.concatenate(uvs)


class ScreenCheckpoints(ClusteringParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "screencheckpoints"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ScreenCheckpoints", "Screen checkpoints")
    GROUP = "detect"
    CHECKPOINTS = "CHECKPOINTS"
    FRAMES = "FRAMES"
    GEOTAGS = "GEOTAGS"
    THRESHOLD = "THRESHOLD"
    PIXEL_RADIUS_PX = "PIXEL_RADIUS_PX"
    COLLAPSED_BELOW = "COLLAPSED_BELOW"
    SPARSE_BELOW = "SPARSE_BELOW"
    OUTPUT_TABLE = "OUTPUT_TABLE"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PLOT = "OUTPUT_PLOT"
    N_HEALTHY = "N_HEALTHY"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.CHECKPOINTS, self.tr("ONNX checkpoints"), QgsProcessing.TypeFile))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Validation flights (frame layers with their images)"), QgsProcessing.TypeVector))
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.GEOTAGS, self.tr("Geotags"), [QgsProcessing.TypeVectorPoint]))
        self.addParameter(QgsProcessingParameterNumber(
            self.THRESHOLD, self.tr("Detection threshold (empty: each checkpoint's default)"),
            QgsProcessingParameterNumber.Double, None, optional=True, minValue=0.001, maxValue=0.999))
        self.add_clustering_parameters()
        self.addParameter(QgsProcessingParameterNumber(
            self.PIXEL_RADIUS_PX, self.tr("Pixel F1: match radius (px)"), QgsProcessingParameterNumber.Double,
            DEFAULT_PIXEL_RADIUS_PX, minValue=0.5))
        self.addParameter(QgsProcessingParameterNumber(
            self.COLLAPSED_BELOW, self.tr("Collapsed if the distinct-position fraction is below"),
            QgsProcessingParameterNumber.Double, DEFAULT_COLLAPSED_BELOW, minValue=0.0, maxValue=1.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.SPARSE_BELOW, self.tr("Too sparse if detections per frame on the worst flight are below"),
            QgsProcessingParameterNumber.Double, DEFAULT_SPARSE_BELOW, minValue=0.0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_TABLE, self.tr("Checkpoint table (CSV)"), "CSV (*.csv)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Checkpoint table (JSON)"), "JSON (*.json)", optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PLOT, self.tr("Frontier plot (PNG)"), "PNG (*.png)", optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputNumber(self.N_HEALTHY, self.tr("Healthy checkpoints")))

    def processAlgorithm(self, parameters, context, feedback):
        checkpoints = self.parameterAsFileList(parameters, self.CHECKPOINTS, context)
        frame_layers = self.parameterAsLayerList(parameters, self.FRAMES, context)
        if not checkpoints:
            raise QgsProcessingException(self.tr("CHECKPOINTS: give at least one ONNX file."))
        if not frame_layers:
            raise QgsProcessingException(self.tr("FRAMES: give at least one validation flight."))
        threshold = None if parameters.get(self.THRESHOLD) in (None, "") else \
            self.parameterAsDouble(parameters, self.THRESHOLD, context)
        op = self.read_operating_point(parameters, context, threshold)
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if geotag_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer cannot be read."))
        geotags = self.run_core(read_geotags, geotag_source, context)
        flights = []
        for layer in frame_layers:
            groups, records, grouped = self.run_core(read_pose_groups, layer, layer.name())
            images = [[records[i].get("image") or "" for i in idx] for _, idx in grouped]
            flights.append((layer.name(), groups, images))
        local = self.run_core(local_frame_for, [p for _, groups, _ in flights for p in groups], geotags)
        h = np.where(np.isfinite(geotags.height), geotags.height, local.h0)
        g_local = local.from_geodetic(geotags.lat, geotags.lon, h)
        truth = {}
        for name, groups, _ in flights:
            visible = self.run_core(in_view, groups, local, g_local, op.edge_buffer_px).mask
            parts = [self.run_core(pixel_labels, p.subset(np.flatnonzero(np.isfinite(p.ground_height))), local,
                                   geotags.subset(visible),
                                   op.edge_buffer_px) for p in groups]
            truth[name] = (g_local[visible, :2], np.concatenate([p[0] for p in parts]),
                           np.concatenate([p[1] for p in parts]))
        steps = len(checkpoints) * len(flights)
        multi = QgsProcessingMultiStepFeedback(steps + 1, feedback)
        runs, step = [], 0
        for path in checkpoints:
            model = self.run_core(HeatmapModel, path, feedback.pushInfo)
            name = Path(path).name
            for flight_name, groups, images in flights:
                multi.setCurrentStep(step)
                step += 1
                progress, is_canceled = self.progress_callbacks(multi)
                run = self._detect(model, name, flight_name, groups, images, op, local, truth[flight_name],
                                   progress, is_canceled, feedback)
                runs.append(run)
        multi.setCurrentStep(steps)
        screens = self.run_core(screen_checkpoints, runs, op, self.parameterAsDouble(parameters, self.PIXEL_RADIUS_PX,
                                                                                   context),
                                self.parameterAsDouble(parameters, self.COLLAPSED_BELOW, context),
                                self.parameterAsDouble(parameters, self.SPARSE_BELOW, context))
        rows = [s.to_dict() for s in screens]
        for row in rows:
            row["threshold"] = op.threshold
        outputs = {"N_HEALTHY": sum(s.healthy for s in screens)}
        table = self.parameterAsFileOutput(parameters, self.OUTPUT_TABLE, context)
        write_output(table, self.OUTPUT_TABLE, lambda p: write_rows_csv(p, rows))
        outputs[self.OUTPUT_TABLE] = table
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        if out_json:
            document = {"operating_point": op.to_dict(), "flights": [n for n, _, _ in flights],
                        "pooling": "micro-average over flights (sums of counts, one division)",
                        "pixel_f1_note": "pixel-space F1 is for choosing checkpoints only, never a field score",
                        "checkpoints": rows}
            write_output(out_json, self.OUTPUT_JSON, lambda p: Path(p).write_text(
                json.dumps(document, indent=1, ensure_ascii=False) + "\n", encoding="utf-8"))
            outputs[self.OUTPUT_JSON] = out_json
        out_plot = self.parameterAsFileOutput(parameters, self.OUTPUT_PLOT, context)
        if out_plot:
            write_output(out_plot, self.OUTPUT_PLOT, lambda p: screen_figure(screens).savefig(
                p, dpi=110, bbox_inches="tight"))
            outputs[self.OUTPUT_PLOT] = out_plot
        for s in screens:
            state = "healthy" if s.healthy else ", ".join(
                w for w, on in (("collapsed", s.collapsed), ("too sparse", s.too_sparse)) if on)
            feedback.pushInfo(self.tr("{checkpoint}: {state}; recall_pre {value}, gmcf_pre "
                                      "{value2}, pixel F1 {value3}, review load {value4}{value5}").format(
                                  checkpoint=s.checkpoint, state=state, value=_fmt(s.counts.recall_pre),
                                  value2=_fmt(s.counts.gmcf_pre), value3=_fmt(s.pixel_f1),
                                  value4=_fmt(s.relative_review_load), value5=' (frontier)' if s.frontier else ''))
        return outputs

    def _detect(self, model, name, flight_name, groups, images, op, local, truth, progress, is_canceled, feedback):
        request = DetectRequest(threshold=op.threshold, edge_buffer_px=op.edge_buffer_px)
        frame_ids, uvs, xys, n_frames, skipped = [], [], [], 0, 0
        total = sum(len(p) for p in groups)
        done = 0
        for poses, paths in zip(groups, images):
            def group_progress(fraction, offset=done, size=len(poses)):
                progress((offset + fraction * size) / max(total, 1))

            try:
                for found in detect_frames(model, poses, paths, request, local=local, progress=group_progress,
                                           is_canceled=is_canceled):
                    if found.skipped:
                        skipped += 1
                        continue
                    n_frames += 1
                    frame_ids.append(np.full(len(found), found.frame_id, dtype=object))
                    uvs.append(found.uv)
                    xys.append(found.ground_local[:, :2])
            except Cancelled:
                raise QgsProcessingException(self.tr("Cancelled by the user.")) from None
            done += len(poses)
        if skipped:
            feedback.pushWarning(self.tr("{name} on {flight_name}: {skipped} frame(s) skipped "
                                         "(unreadable image or no ground height)").format(
                                     name=name, flight_name=flight_name, skipped=skipped))
        geotag_xy, label_frames, label_uv = truth
        return ScreenRun(name, flight_name, n_frames, _concat(frame_ids, np.empty(0, dtype=object)),
                         _concat(uvs, np.empty((0, 2))), _concat(xys, np.empty((0, 2))), label_frames, label_uv,
                         geotag_xy)


def _concat(parts, empty):
    return np.concatenate(parts) if parts else empty


def _fmt(v):
    return "–" if v is None else f"{v:.3f}"

"""birdseye:screencheckpoints — several ONNX checkpoints over several validation flights at one threshold."""
from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterEnum,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.detector import HeatmapModel
from ...birdseye_qgis.core.detect.flight_detections import detect_flight
from ...birdseye_qgis.core.geometry.ground import placeable_frames
from ...birdseye_qgis.core.labels.training_set import project_labels
from ...birdseye_qgis.core.scoring.evaluation import local_frame_for
from ...birdseye_qgis.core.scoring.matching import in_view
from ...birdseye_qgis.core.scoring.reports import screen_figure
from ...birdseye_qgis.core.scoring.screening import (
    DEFAULT_COLLAPSED_BELOW,
    DEFAULT_PIXEL_RADIUS_PX,
    DEFAULT_SPARSE_BELOW,
    SCREEN_PRESETS,
    ScreenRun,
    frame_blocks,
    screen_checkpoints,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, NUMBER_INTEGER, SOURCE_FILE, SOURCE_VECTOR, SOURCE_VECTOR_POINT
from ...birdseye_qgis.qgis_io import layer_kinds
from ...birdseye_qgis.qgis_io.detections import read_pose_groups
from ...birdseye_qgis.qgis_io.layers import read_geotag_layer
from ...birdseye_qgis.qgis_io.outputs import write_output, write_rows_csv
from ..parameters.clustering import ClusteringParametersMixin
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm


def pixel_labels(poses, local, geotags, edge_buffer_px, ground=None):
    """(frame_id, uv) of every in-view geotag in every frame, as writelabels would write them on ``ground``
    (a ground-model factory; None = the level plane)."""
    tags = replace(geotags, height=np.where(np.isfinite(geotags.height), geotags.height, local.h0))
    frame_ids, uvs = [], []
    for fl in project_labels(poses, tags, edge_buffer_px, local=local, ground=ground):
        keep = ~fl.edge
        frame_ids.append(np.full(int(keep.sum()), poses.frame_id[fl.frame_index], dtype=object))
        uvs.append(fl.uv[keep])
    if not frame_ids:
        return np.empty(0, dtype=object), np.empty((0, 2))
    return np.concatenate(frame_ids), np.concatenate(uvs)


class ScreenCheckpoints(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "screencheckpoints"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ScreenCheckpoints", "Screen checkpoints")
    GROUP = "detect"
    CHECKPOINTS = "CHECKPOINTS"
    FRAMES = "FRAMES"
    GEOTAGS = "GEOTAGS"
    PRESET = "PRESET"
    THRESHOLD = "THRESHOLD"
    BLOCK_FRAMES = "BLOCK_FRAMES"
    PIXEL_RADIUS_PX = "PIXEL_RADIUS_PX"
    COLLAPSED_BELOW = "COLLAPSED_BELOW"
    SPARSE_BELOW = "SPARSE_BELOW"
    OUTPUT_TABLE = "OUTPUT_TABLE"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PLOT = "OUTPUT_PLOT"
    N_HEALTHY = "N_HEALTHY"
    PRESET_NAMES = (QT_TRANSLATE_NOOP("ScreenCheckpoints", "Method: blocks of 500 frames, threshold 0.03"),
                    QT_TRANSLATE_NOOP("ScreenCheckpoints", "BirdsEye: whole flights, each model's threshold"))

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.CHECKPOINTS, self.tr("ONNX checkpoints"), SOURCE_FILE))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Validation flights (frame layers with their images)"), SOURCE_VECTOR))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterEnum(
            self.PRESET, self.tr("Preset (blocks and threshold)"),
            options=[self.tr(name) for name in self.PRESET_NAMES], defaultValue=0))
        self.addParameter(QgsProcessingParameterNumber(
            self.THRESHOLD, self.tr("Threshold (empty: the preset's)"),
            NUMBER_DOUBLE, None, optional=True, minValue=0.001, maxValue=0.999))
        self.addParameter(QgsProcessingParameterNumber(
            self.BLOCK_FRAMES, self.tr("Frames per block (0: whole flights)"),
            NUMBER_INTEGER, None, optional=True, minValue=0))
        self.add_clustering_parameters()
        self.add_dem_parameters(ground_model=True)
        self.addParameter(QgsProcessingParameterNumber(
            self.PIXEL_RADIUS_PX, self.tr("Pixel F1: match radius (px)"), NUMBER_DOUBLE,
            DEFAULT_PIXEL_RADIUS_PX, minValue=0.5))
        self.addParameter(QgsProcessingParameterNumber(
            self.COLLAPSED_BELOW, self.tr("Collapsed if the distinct-position fraction is below"),
            NUMBER_DOUBLE, DEFAULT_COLLAPSED_BELOW, minValue=0.0, maxValue=1.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.SPARSE_BELOW, self.tr("Too sparse below (detections/frame, worst block)"),
            NUMBER_DOUBLE, DEFAULT_SPARSE_BELOW, minValue=0.0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_TABLE, self.tr("Checkpoint table (CSV)"), "CSV (*.csv)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Checkpoint table (JSON)"), "JSON (*.json)", optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PLOT, self.tr("Frontier plot (PNG)"), "PNG (*.png)", optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputNumber(self.N_HEALTHY, self.tr("Healthy checkpoints")))

    def processAlgorithm(self, parameters, context, feedback):
        checkpoints = [p for p in self.parameterAsFileList(parameters, self.CHECKPOINTS, context) if p]
        frame_layers = self.parameterAsLayerList(parameters, self.FRAMES, context)
        if not checkpoints:
            raise QgsProcessingException(self.tr("CHECKPOINTS: give at least one ONNX file."))
        if not frame_layers:
            raise QgsProcessingException(self.tr("FRAMES: give at least one validation flight."))
        preset = SCREEN_PRESETS[self.parameterAsEnum(parameters, self.PRESET, context)]
        threshold = preset.threshold if parameters.get(self.THRESHOLD) in (None, "") else \
            self.parameterAsDouble(parameters, self.THRESHOLD, context)
        block_frames = preset.block_frames if parameters.get(self.BLOCK_FRAMES) in (None, "") else \
            self.parameterAsInt(parameters, self.BLOCK_FRAMES, context)
        op = self.read_operating_point(parameters, context, threshold)
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if geotag_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer cannot be read."))
        geotags = self.run_core(read_geotag_layer, geotag_source, context.transformContext())
        flights = []
        for layer in frame_layers:
            groups, records, grouped = self.run_core(read_pose_groups, layer, layer.name())
            images = [[records[i].get("image") or "" for i in idx] for _, idx in grouped]
            flights.append((layer.name(), groups, images, [r["frame_id"] for r in records]))
        local = self.run_core(local_frame_for, [p for _, groups, _, _ in flights for p in groups], geotags)
        h = np.where(np.isfinite(geotags.height), geotags.height, local.h0)
        g_local = local.from_geodetic(geotags.lat, geotags.lon, h)
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        # One ground for the checkpoints' detections, the in-view test and the pixel labels.
        ground = self.dem_ground(dem)
        blocks = {name: self._blocks(name, groups, order, block_frames, local, geotags, g_local, op, ground)
                  for name, groups, _, order in flights}
        feedback.pushInfo(self.tr("{n_blocks} block(s) of {size} frames over {n_flights} flight(s); threshold "
                                  "{threshold}").format(
            n_blocks=sum(len(b) for b in blocks.values()), size=block_frames or self.tr("all"), n_flights=len(flights),
            threshold=self.tr("of each checkpoint") if threshold is None else f"{threshold:g}"))
        runs, used, step = [], {}, 0
        for path in checkpoints:
            model = self.run_core(HeatmapModel, path, feedback.pushInfo)
            used[model.name] = model.metadata.default_threshold if threshold is None else threshold
            for flight_name, groups, images, _ in flights:
                progress, is_canceled = self.progress_callbacks(
                    feedback, 95.0 * step / (len(checkpoints) * len(flights)),
                    95.0 * (step + 1) / (len(checkpoints) * len(flights)))
                step += 1
                found = self.run_core(detect_flight, model, groups, images, [used[model.name]], op.edge_buffer_px,
                                      local, progress, is_canceled, ground)
                if found.skipped:
                    feedback.pushWarning(self.tr("{name} on {flight_name}: {skipped} frame(s) skipped "
                                                 "(unreadable image or no ground height)").format(
                                             name=model.name, flight_name=flight_name, skipped=len(found.skipped)))
                runs += [self._block_run(model.name, found, block) for block in blocks[flight_name]]
        screens = self.run_core(screen_checkpoints, runs, op, self.parameterAsDouble(parameters, self.PIXEL_RADIUS_PX,
                                                                                   context),
                                self.parameterAsDouble(parameters, self.COLLAPSED_BELOW, context),
                                self.parameterAsDouble(parameters, self.SPARSE_BELOW, context))
        rows = [{**s.to_dict(), "threshold": used[s.checkpoint]} for s in screens]
        outputs = {self.N_HEALTHY: sum(s.healthy for s in screens)}
        table = self.parameterAsFileOutput(parameters, self.OUTPUT_TABLE, context)
        write_output(table, self.OUTPUT_TABLE, lambda p: write_rows_csv(p, rows))
        outputs[self.OUTPUT_TABLE] = table
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        if out_json:
            document = {"operating_point": op.to_dict(), "preset": preset.key, "block_frames": block_frames,
                        "flights": [n for n, _, _, _ in flights],
                        "blocks": [b["label"] for n, _, _, _ in flights for b in blocks[n]],
                        "pooling": "micro-average over blocks (sums of counts, one division)",
                        "f1_geo": "harmonic mean of pooled recall_pre and pooled gmcf_pre",
                        "review_load": "detections per frame / the lightest healthy checkpoint's",
                        "f1_pixel": "pixel-space F1 within f1_pixel_radius_px of the projected labels; for choosing "
                                    "checkpoints only, never a field score",
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
            state = self.tr("healthy") if s.healthy else ", ".join(
                w for w, on in ((self.tr("collapsed"), s.collapsed), (self.tr("too sparse"), s.too_sparse)) if on)
            feedback.pushInfo(self.tr("{checkpoint}: {state}; recall_pre {recall}, gmcf_pre {gmcf}, F1 {f1_geo}, "
                                      "{dpf} detections per frame, review load {load}, pixel F1 {f1_pixel} "
                                      "(within {radius:g} px){frontier}").format(
                                  checkpoint=s.checkpoint, state=state, recall=_fmt(s.counts.recall_pre),
                                  gmcf=_fmt(s.counts.gmcf_pre), f1_geo=_fmt(s.f1_geo), dpf=_fmt(s.detections_per_frame),
                                  load=_fmt(s.review_load), f1_pixel=_fmt(s.f1_pixel), radius=s.pixel_radius_px,
                                  frontier=self.tr(" (frontier)") if s.frontier else ""))
        return outputs

    def _blocks(self, flight_name, groups, order, block_frames, local, geotags, g_local, op, ground) -> list[dict]:
        """The flight's blocks: label, frame ids, in-view geotags and pixel labels of each, on ``ground``."""
        out = []
        parts = self.run_core(frame_blocks, np.array(order, dtype=object), block_frames)
        start = 0
        for ids in parts:
            label = flight_name if len(parts) == 1 else f"{flight_name}, frames {start + 1}–{start + len(ids)}"
            start += len(ids)
            wanted = set(ids.tolist())
            mine = [p.subset(np.flatnonzero([f in wanted for f in p.frame_id])) for p in groups]
            mine = [p for p in mine if len(p)]
            visible = self.run_core(in_view, mine, local, g_local, op.edge_buffer_px, ground).mask
            labels = [self.run_core(pixel_labels, p.subset(np.flatnonzero(placeable_frames(p, ground))), local,
                                    geotags.subset(visible), op.edge_buffer_px, ground) for p in mine]
            out.append({"label": label, "frames": wanted, "geotag_xy": g_local[visible, :2],
                        "label_frame_id": _concat([lab[0] for lab in labels], np.empty(0, dtype=object)),
                        "label_uv": _concat([lab[1] for lab in labels], np.empty((0, 2)))})
        return out

    @staticmethod
    def _block_run(checkpoint, found, block) -> ScreenRun:
        """One checkpoint's detections on one block (the flight's detections at the screening threshold)."""
        det = found.by_threshold[0]
        inside = np.fromiter((f in block["frames"] for f in det.frame_id), dtype=bool, count=len(det))
        n_frames = sum(f in block["frames"] for f in found.processed)
        return ScreenRun(checkpoint, block["label"], n_frames, det.frame_id[inside], det.uv[inside],
                         det.positions.subset(inside), block["label_frame_id"], block["label_uv"], block["geotag_xy"])


def _concat(parts, empty):
    return np.concatenate(parts) if parts else empty


def _fmt(v):
    return "–" if v is None else f"{v:.3f}"

"""birdseye:screencheckpoints — several ONNX checkpoints over several validation flights at one threshold (and
over held-out flights: the transfer report)."""
from __future__ import annotations

import json
from dataclasses import dataclass, replace
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
from ...birdseye_qgis.core.scoring.reports import screen_figure, screening_report_html
from ...birdseye_qgis.core.scoring.screening import (
    DEFAULT_COLLAPSED_BELOW,
    DEFAULT_PIXEL_RADIUS_PX,
    DEFAULT_SPARSE_BELOW,
    SCREEN_PRESETS,
    ScreenRun,
    frame_blocks,
    screen_checkpoints,
)
from ...birdseye_qgis.core.scoring.transfer import SurveyDensity, transfer_report
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


@dataclass
class _ScreenSet:
    """The flights of one side of a screening (validation or held-out), read once and shared by every
    checkpoint: each flight's name, pose groups, images and frame order; the local frame; the blocks."""

    name: str
    flights: list
    local: object
    blocks: dict

    def block_labels(self) -> list:
        return [b["label"] for name, _, _, _ in self.flights for b in self.blocks[name]]

    def density(self) -> dict:
        """Survey density (in-view geotags per processed frame) per flight and pooled."""
        per_flight = {name: [b["per_frame"] for b in self.blocks[name]] for name, _, _, _ in self.flights}
        out = {name: SurveyDensity.of(parts) for name, parts in per_flight.items()}
        out["pooled"] = SurveyDensity.of(part for parts in per_flight.values() for part in parts)
        return out


class ScreenCheckpoints(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "screencheckpoints"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("ScreenCheckpoints", "Screen checkpoints")
    GROUP = "detect"
    CHECKPOINTS = "CHECKPOINTS"
    FRAMES = "FRAMES"
    GEOTAGS = "GEOTAGS"
    HELDOUT_FRAMES = "HELDOUT_FRAMES"
    HELDOUT_GEOTAGS = "HELDOUT_GEOTAGS"
    PRESET = "PRESET"
    THRESHOLD = "THRESHOLD"
    BLOCK_FRAMES = "BLOCK_FRAMES"
    PIXEL_RADIUS_PX = "PIXEL_RADIUS_PX"
    COLLAPSED_BELOW = "COLLAPSED_BELOW"
    SPARSE_BELOW = "SPARSE_BELOW"
    OUTPUT_TABLE = "OUTPUT_TABLE"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PLOT = "OUTPUT_PLOT"
    OUTPUT_REPORT = "OUTPUT_REPORT"
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
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.HELDOUT_FRAMES, self.tr("Held-out flights (frame layers)"), SOURCE_VECTOR,
            optional=True))
        self.addParameter(source_parameter(
            self.HELDOUT_GEOTAGS, self.tr("Held-out geotags (empty: Geotags)"), layer_kinds.GEOTAGS,
            [SOURCE_VECTOR_POINT], optional=True))
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
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_REPORT, self.tr("Report (HTML)"), "HTML (*.html)", optional=True, createByDefault=True))
        self.addOutput(QgsProcessingOutputNumber(self.N_HEALTHY, self.tr("Healthy checkpoints")))

    def processAlgorithm(self, parameters, context, feedback):
        checkpoints = [p for p in self.parameterAsFileList(parameters, self.CHECKPOINTS, context) if p]
        frame_layers = self.parameterAsLayerList(parameters, self.FRAMES, context)
        heldout_layers = self.parameterAsLayerList(parameters, self.HELDOUT_FRAMES, context)
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
        heldout_geotag_source = self.parameterAsSource(parameters, self.HELDOUT_GEOTAGS, context)
        if heldout_geotag_source is not None and not heldout_layers:
            raise QgsProcessingException(self.tr("HELDOUT_GEOTAGS: give the held-out flights (HELDOUT_FRAMES) too, "
                                                 "or leave it empty."))
        heldout_geotags = geotags if heldout_geotag_source is None else \
            self.run_core(read_geotag_layer, heldout_geotag_source, context.transformContext())
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        # One ground for the checkpoints' detections, the in-view test and the pixel labels.
        ground = self.dem_ground(dem)
        sets = [self._screen_set(self.tr("validation"), frame_layers, geotags, block_frames, op, ground)]
        if heldout_layers:
            sets.append(self._screen_set(self.tr("held-out"), heldout_layers, heldout_geotags, block_frames, op,
                                         ground))
        for screen_set in sets:
            feedback.pushInfo(self.tr("{side}: {n_blocks} block(s) of {size} frames over {n_flights} flight(s); "
                                      "threshold {threshold}").format(
                side=screen_set.name, n_blocks=sum(len(b) for b in screen_set.blocks.values()),
                size=block_frames or self.tr("all"), n_flights=len(screen_set.flights),
                threshold=self.tr("of each checkpoint") if threshold is None else f"{threshold:g}"))
        runs, used = [[] for _ in sets], {}
        steps, step = len(checkpoints) * sum(len(s.flights) for s in sets), 0
        for path in checkpoints:
            model = self.run_core(HeatmapModel, path, feedback.pushInfo)
            used[model.name] = model.metadata.default_threshold if threshold is None else threshold
            for screen_set, set_runs in zip(sets, runs):
                for flight_name, groups, images, _ in screen_set.flights:
                    progress, is_canceled = self.progress_callbacks(feedback, 95.0 * step / steps,
                                                                    95.0 * (step + 1) / steps)
                    step += 1
                    found = self.run_core(detect_flight, model, groups, images, [used[model.name]], op.edge_buffer_px,
                                          screen_set.local, progress, is_canceled, ground)
                    if found.skipped:
                        feedback.pushWarning(self.tr("{name} on {flight_name}: {skipped} frame(s) skipped "
                                                     "(unreadable image or no ground height)").format(
                                                 name=model.name, flight_name=flight_name, skipped=len(found.skipped)))
                    set_runs += [self._block_run(model.name, found, block) for block in screen_set.blocks[flight_name]]
        guards = (self.parameterAsDouble(parameters, self.PIXEL_RADIUS_PX, context),
                  self.parameterAsDouble(parameters, self.COLLAPSED_BELOW, context),
                  self.parameterAsDouble(parameters, self.SPARSE_BELOW, context))
        screens = [self.run_core(screen_checkpoints, set_runs, op, *guards) for set_runs in runs]
        transfer = self.run_core(transfer_report, screens[0], screens[1]) if heldout_layers else None
        rows = [{**s.to_dict(), "threshold": used[s.checkpoint]} for s in screens[0]]
        if transfer is not None:
            for row, t in zip(rows, transfer.checkpoints):
                row.update({"recall_pre_heldout": t.heldout.recall_pre, "gmcf_pre_heldout": t.heldout.gmcf_pre,
                            "delta_recall": t.delta_recall, "delta_gmcf": t.delta_gmcf})
        outputs = {self.N_HEALTHY: sum(s.healthy for s in screens[0])}
        table = self.parameterAsFileOutput(parameters, self.OUTPUT_TABLE, context)
        write_output(table, self.OUTPUT_TABLE, lambda p: write_rows_csv(p, rows))
        outputs[self.OUTPUT_TABLE] = table
        densities = [s.density() for s in sets]
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        if out_json:
            document = {"operating_point": op.to_dict(), "preset": preset.key, "block_frames": block_frames,
                        "flights": [n for n, _, _, _ in sets[0].flights], "blocks": sets[0].block_labels(),
                        "survey_density": {k: d.to_dict() for k, d in densities[0].items()},
                        "pooling": "micro-average over blocks (sums of counts, one division)",
                        "f1_geo": "harmonic mean of pooled recall_pre and pooled gmcf_pre",
                        "review_load": "detections per frame / the lightest healthy checkpoint's",
                        "f1_pixel": "pixel-space F1 within f1_pixel_radius_px of the projected labels; for choosing "
                                    "checkpoints only, never a field score",
                        "survey_density_definition": "in-view geotags per processed frame",
                        "checkpoints": rows}
            if transfer is not None:
                document["heldout"] = {"flights": [n for n, _, _, _ in sets[1].flights],
                                       "blocks": sets[1].block_labels(),
                                       "survey_density": {k: d.to_dict() for k, d in densities[1].items()},
                                       "checkpoints": [{**s.to_dict(), "threshold": used[s.checkpoint]}
                                                       for s in screens[1]]}
                document["transfer"] = transfer.to_dict()
            write_output(out_json, self.OUTPUT_JSON, lambda p: Path(p).write_text(
                json.dumps(document, indent=1, ensure_ascii=False) + "\n", encoding="utf-8"))
            outputs[self.OUTPUT_JSON] = out_json
        out_plot = self.parameterAsFileOutput(parameters, self.OUTPUT_PLOT, context)
        if out_plot:
            write_output(out_plot, self.OUTPUT_PLOT, lambda p: screen_figure(screens[0]).savefig(
                p, dpi=110, bbox_inches="tight"))
            outputs[self.OUTPUT_PLOT] = out_plot
        out_report = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        if out_report:
            html = screening_report_html(op, screens[0], densities[0], screens[1] if transfer else None,
                                         densities[1] if transfer else None, transfer)
            write_output(out_report, self.OUTPUT_REPORT, lambda p: Path(p).write_text(html, encoding="utf-8"))
            outputs[self.OUTPUT_REPORT] = out_report
        for s in screens[0]:
            state = self.tr("healthy") if s.healthy else ", ".join(
                w for w, on in ((self.tr("collapsed"), s.collapsed), (self.tr("too sparse"), s.too_sparse)) if on)
            feedback.pushInfo(self.tr("{checkpoint}: {state}; recall_pre {recall}, gmcf_pre {gmcf}, F1 {f1_geo}, "
                                      "{dpf} detections per frame, review load {load}, pixel F1 {f1_pixel} "
                                      "(within {radius:g} px){frontier}").format(
                                  checkpoint=s.checkpoint, state=state, recall=_fmt(s.counts.recall_pre),
                                  gmcf=_fmt(s.counts.gmcf_pre), f1_geo=_fmt(s.f1_geo), dpf=_fmt(s.detections_per_frame),
                                  load=_fmt(s.review_load), f1_pixel=_fmt(s.f1_pixel), radius=s.pixel_radius_px,
                                  frontier=self.tr(" (frontier)") if s.frontier else ""))
        for screen_set, density in zip(sets, densities):
            pooled = density["pooled"]
            feedback.pushInfo(self.tr("Survey density ({side}): {mean} geotags in view per frame (median {median}, "
                                      "{empty} of the frames see none)").format(
                side=screen_set.name, mean=_fmt(pooled.mean), median=_fmt(pooled.median),
                empty="–" if pooled.frames_without_geotag is None else f"{pooled.frames_without_geotag:.0%}"))
        if transfer is not None:
            self._report_transfer(transfer, feedback)
        return outputs

    def _report_transfer(self, transfer, feedback) -> None:
        for t in transfer.checkpoints:
            feedback.pushInfo(self.tr("{checkpoint}: recall {recall_v} → {recall_h} (Δ {d_recall}), GMCF {gmcf_v} → "
                                      "{gmcf_h} (Δ {d_gmcf}), validation → held-out").format(
                checkpoint=t.checkpoint, recall_v=_fmt(t.validation.recall_pre), recall_h=_fmt(t.heldout.recall_pre),
                d_recall=_fmt(t.delta_recall), gmcf_v=_fmt(t.validation.gmcf_pre), gmcf_h=_fmt(t.heldout.gmcf_pre),
                d_gmcf=_fmt(t.delta_gmcf)))
        for figure, rank in (("recall", transfer.recall), ("GMCF", transfer.gmcf)):
            if rank.rho is None:
                feedback.pushInfo(self.tr("Spearman's ρ of {figure}, validation vs held-out: {note}").format(
                    figure=figure, note=rank.note))
            else:
                feedback.pushInfo(self.tr("Spearman's ρ of {figure}, validation vs held-out: {rho:.3f} over {n} "
                                          "healthy checkpoints").format(figure=figure, rho=rank.rho, n=rank.n))

    def _screen_set(self, name, frame_layers, geotags, block_frames, op, ground) -> _ScreenSet:
        """One side of the screening: its flights, its local frame and each flight's blocks."""
        flights = []
        for layer in frame_layers:
            groups, records, grouped = self.run_core(read_pose_groups, layer, layer.name())
            images = [[records[i].get("image") or "" for i in idx] for _, idx in grouped]
            flights.append((layer.name(), groups, images, [r["frame_id"] for r in records]))
        local = self.run_core(local_frame_for, [p for _, groups, _, _ in flights for p in groups], geotags)
        g_local = geotags.in_local(local)
        blocks = {flight: self._blocks(flight, groups, order, block_frames, local, geotags, g_local, op, ground)
                  for flight, groups, _, order in flights}
        return _ScreenSet(name, flights, local, blocks)

    def _blocks(self, flight_name, groups, order, block_frames, local, geotags, g_local, op, ground) -> list[dict]:
        """The flight's blocks: label, frame ids, in-view geotags (and how many each frame sees) and pixel labels
        of each, on ``ground``."""
        out = []
        parts = self.run_core(frame_blocks, np.array(order, dtype=object), block_frames)
        start = 0
        for ids in parts:
            label = flight_name if len(parts) == 1 else f"{flight_name}, frames {start + 1}–{start + len(ids)}"
            start += len(ids)
            wanted = set(ids.tolist())
            mine = [p.subset(np.flatnonzero([f in wanted for f in p.frame_id])) for p in groups]
            mine = [p for p in mine if len(p)]
            view = self.run_core(in_view, mine, local, g_local, op.edge_buffer_px, ground)
            visible = view.mask
            labels = [self.run_core(pixel_labels, p.subset(np.flatnonzero(placeable_frames(p, ground))), local,
                                    geotags.subset(visible), op.edge_buffer_px, ground) for p in mine]
            out.append({"label": label, "frames": wanted, "geotag_xy": g_local[visible, :2],
                        "per_frame": view.per_frame,
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

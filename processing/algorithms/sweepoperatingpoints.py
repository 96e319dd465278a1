"""birdseye:sweepoperatingpoints — pooled recall and GMCF over checkpoints × a grid of operating points."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.clustering import DEFAULT_DEDUP_CM
from ...birdseye_qgis.core.detect.detector import HeatmapModel
from ...birdseye_qgis.core.detect.flight_detections import detect_flight
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.geometry.ground_record import common_ground
from ...birdseye_qgis.core.scoring.evaluation import local_frame_for
from ...birdseye_qgis.core.scoring.matching import in_view
from ...birdseye_qgis.core.scoring.operating_point import DEFAULT_EDGE_BUFFER_PX
from ...birdseye_qgis.core.scoring.reports import sweep_figure
from ...birdseye_qgis.core.scoring.sweep import (
    DEFAULT_MAX_GEOTAGS_PER_HIT,
    DEFAULT_MAX_MEAN_EXTENT_M,
    METHOD_GRID,
    DetectionRun,
    SweepFlight,
    SweepGrid,
    flights_from_runs,
    sweep,
)
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_FILE, SOURCE_VECTOR, SOURCE_VECTOR_POINT
from ...birdseye_qgis.qgis_io import layer_kinds
from ...birdseye_qgis.qgis_io.detections import read_detections, read_pose_groups
from ...birdseye_qgis.qgis_io.layers import read_geotag_layer
from ...birdseye_qgis.qgis_io.outputs import write_output, write_rows_csv
from ..parameters.clustering import ClusteringParametersMixin
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter
from .base import BirdsEyeAlgorithm


def _listed(values) -> str:
    return ",".join(f"{v:g}" for v in values)


LISTS = (("THRESHOLDS", "Thresholds (comma-separated, for CHECKPOINTS)",
          _listed(METHOD_GRID["thresholds"])),
         ("EPS_M", "DBSCAN radii EPS (m, comma-separated)", _listed(METHOD_GRID["eps_m"])),
         ("MIN_SAMPLES", "DBSCAN minimum points (comma-separated)", _listed(METHOD_GRID["min_samples"])),
         ("EPS_PRED_M", "Match radii EPS_PRED (m, comma-separated)", _listed(METHOD_GRID["eps_pred_m"])))


def parse_list(text: str, name: str) -> list[float]:
    values = []
    for part in (text or "").replace(";", ",").split(","):
        part = part.strip()
        if not part:
            continue
        try:
            values.append(float(part))
        except ValueError as exc:
            raise InputError(f"'{part}' is not a number (expected a comma-separated list, e.g. 0.1,0.2)",
                             field=name) from exc
    if not values:
        raise InputError("needs at least one value", field=name)
    return values


class SweepOperatingPoints(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "sweepoperatingpoints"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SweepOperatingPoints", "Sweep operating points")
    GROUP = "detect"
    CHECKPOINTS = "CHECKPOINTS"
    DETECTIONS = "DETECTIONS"
    GEOTAGS = "GEOTAGS"
    FRAMES = "FRAMES"
    DEDUP_CM = "DEDUP_CM"
    EDGE_BUFFER_PX = "EDGE_BUFFER_PX"
    MAX_GEOTAGS_PER_HIT = "MAX_GEOTAGS_PER_HIT"
    MAX_MEAN_EXTENT_M = "MAX_MEAN_EXTENT_M"
    OUTPUT_TABLE = "OUTPUT_TABLE"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_PLOT = "OUTPUT_PLOT"
    N_CONFIGURATIONS = "N_CONFIGURATIONS"
    N_CREDIBLE = "N_CREDIBLE"
    N_PARETO = "N_PARETO"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.CHECKPOINTS, self.tr("ONNX checkpoints (run over FRAMES)"),
            SOURCE_FILE, optional=True))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.DETECTIONS, self.tr("Or detection layers (from Detect)"),
            SOURCE_VECTOR_POINT, optional=True))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Frame layers (one per flight or detection layer)"), SOURCE_VECTOR))
        for name, text, default in LISTS:
            self.addParameter(QgsProcessingParameterString(name, self.tr(text), default))
        self.addParameter(QgsProcessingParameterNumber(
            self.DEDUP_CM, self.tr("De-duplication grid cell (cm)"), NUMBER_DOUBLE,
            DEFAULT_DEDUP_CM, minValue=0.1, maxValue=100.0))
        self.add_core_count_parameter()
        self.addParameter(QgsProcessingParameterNumber(
            self.EDGE_BUFFER_PX, self.tr("Edge buffer at the image border (px)"),
            NUMBER_DOUBLE, DEFAULT_EDGE_BUFFER_PX, minValue=0.0, maxValue=1000.0))
        self.add_dem_parameters(ground_model=True)
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_GEOTAGS_PER_HIT, self.tr("Credible: mean geotags per hit cluster at most"),
            NUMBER_DOUBLE, DEFAULT_MAX_GEOTAGS_PER_HIT, minValue=1.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_MEAN_EXTENT_M, self.tr("Credible: mean median cluster extent at most (m)"),
            NUMBER_DOUBLE, DEFAULT_MAX_MEAN_EXTENT_M, minValue=0.0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_TABLE, self.tr("Configurations (CSV)"), "CSV (*.csv)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Configurations and Pareto front (JSON)"), "JSON (*.json)",
            optional=True, createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PLOT, self.tr("Frontier plot (PNG)"), "PNG (*.png)", optional=True, createByDefault=True))
        for name, text in ((self.N_CONFIGURATIONS, "Configurations"), (self.N_CREDIBLE, "Credible configurations"),
                           (self.N_PARETO, "Configurations on the Pareto front")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        lists = {name: self.run_core(parse_list, self.parameterAsString(parameters, name, context), name)
                 for name, _, _ in LISTS}
        checkpoints = [p for p in self.parameterAsFileList(parameters, self.CHECKPOINTS, context) if p]
        det_layers = self.parameterAsLayerList(parameters, self.DETECTIONS, context)
        frame_layers = self.parameterAsLayerList(parameters, self.FRAMES, context)
        if bool(checkpoints) == bool(det_layers):
            raise QgsProcessingException(self.tr(
                "CHECKPOINTS, DETECTIONS: give ONNX checkpoints (the sweep runs them over the frames) or detection "
                "layers made by Detect, not both and not neither."))
        if not frame_layers:
            raise QgsProcessingException(self.tr("FRAMES: give at least one frame layer."))
        if det_layers and len(frame_layers) != len(det_layers):
            raise QgsProcessingException(self.tr(
                "FRAMES: give one frame layer per detection layer, in the same order (got {detections} "
                "detection layer(s) and {frames} frame layer(s)).").format(
                detections=len(det_layers), frames=len(frame_layers)))
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if geotag_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer cannot be read."))
        geotags = self.run_core(read_geotag_layer, geotag_source, context.transformContext())
        flights = {}
        for layer in frame_layers:
            if layer.id() not in flights:
                flights[layer.id()] = (layer.name(),) + self.run_core(read_pose_groups, layer, layer.name())
        names = [name for name, *_ in flights.values()]
        flight_names = {key: name if names.count(name) == 1 else f"{name} ({key})"
                        for key, (name, *_) in flights.items()}
        local = self.run_core(local_frame_for, [p for _, groups, _, _ in flights.values() for p in groups], geotags)
        g_local = geotags.in_local(local)
        edge = self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context)
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        read = [(det_layer, frame_layer) + self.run_core(read_detections, det_layer, context, det_layer.name())
                for det_layer, frame_layer in zip(det_layers, frame_layers)]
        grounds = self._grounds(flights, read, dem, feedback)
        geotag_xy, n_frames = {}, {}
        for key, (_, groups, _, _) in flights.items():
            view = self.run_core(in_view, groups, local, g_local, edge, grounds[key])
            geotag_xy[flight_names[key]] = g_local[view.mask, :2]
            n_frames[flight_names[key]] = view.n_frames
            feedback.pushInfo(self.tr("{name}: {n_frames} frames, {value} geotags in view").format(
                name=flight_names[key], n_frames=view.n_frames, value=int(view.mask.sum())))
        feedback.setProgress(5)
        dedup = self.parameterAsDouble(parameters, self.DEDUP_CM, context)
        core_count = self.read_core_count(parameters, context)
        if det_layers:
            runs = []
            for det_layer, frame_layer, det, dropped in read:
                if dropped:
                    feedback.pushWarning(self.tr("{layer}: {n} detection(s) without a position or score left "
                                                 "out").format(layer=det_layer.name(), n=dropped))
                runs.append(DetectionRun(det.ground_positions(local), det.threshold, flight_names[frame_layer.id()],
                                         det.model or det_layer.name(), det.model_digest, det_layer.name()))
            sweep_flights, thresholds = self.run_core(flights_from_runs, runs, geotag_xy, n_frames)
            feedback.pushInfo(self.tr("Threshold axis: the thresholds the layers were detected at, {values} "
                                      "(THRESHOLDS is used with CHECKPOINTS only).").format(
                values=", ".join(f"{t:g}" for t in thresholds)))
            grid = self.run_core(SweepGrid, thresholds, lists["EPS_M"], lists["MIN_SAMPLES"], lists["EPS_PRED_M"],
                                 dedup, core_count)
        else:
            grid = self.run_core(SweepGrid, lists["THRESHOLDS"], lists["EPS_M"], lists["MIN_SAMPLES"],
                                 lists["EPS_PRED_M"], dedup, core_count)
            sweep_flights = self._run_checkpoints(checkpoints, flights, flight_names, grid, edge, local, geotag_xy,
                                                  grounds, feedback)
        n_checkpoints = len({(f.checkpoint, f.model_digest) for f in sweep_flights})
        feedback.pushInfo(self.tr("Sweeping {n_checkpoints} checkpoint(s) × {size} configurations ({items}: "
                                  "threshold × eps × min_samples × eps_pred; minimum points count {counted})").format(
                              n_checkpoints=n_checkpoints, size=grid.size, items=' × '.join(map(str, grid.shape)),
                              counted=grid.core_count))
        progress, is_canceled = self.progress_callbacks(feedback, 60.0 if checkpoints else 10.0, 95.0)
        result = self.run_core(sweep, sweep_flights, grid,
                               self.parameterAsDouble(parameters, self.MAX_GEOTAGS_PER_HIT, context),
                               self.parameterAsDouble(parameters, self.MAX_MEAN_EXTENT_M, context),
                               progress, is_canceled)
        rows = result.rows()
        for row in rows:
            row["edge_buffer_px"] = edge
        outputs = {self.N_CONFIGURATIONS: len(rows), self.N_CREDIBLE: int(result.credible.sum()),
                   self.N_PARETO: int(result.pareto.sum())}
        table = self.parameterAsFileOutput(parameters, self.OUTPUT_TABLE, context)
        write_output(table, self.OUTPUT_TABLE, lambda p: write_rows_csv(p, rows))
        outputs[self.OUTPUT_TABLE] = table
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        if out_json:
            document = {"pooling": "micro-average over flights (sums of counts, one division)",
                        "threshold_axis": ("peaks extracted at every threshold from each frame's heatmap"
                                           if checkpoints else "each detection layer at its own detect threshold"),
                        "checkpoints": [{"checkpoint": c, "model_digest": d} for c, d in result.checkpoints],
                        "flights": sorted(geotag_xy),
                        "grid": {"thresholds": grid.thresholds.tolist(), "eps_m": grid.eps_m.tolist(),
                                 "min_samples": grid.min_samples.tolist(), "eps_pred_m": grid.eps_pred_m.tolist(),
                                 "dedup_cm": grid.dedup_cm, "core_count": grid.core_count, "edge_buffer_px": edge},
                        "credibility": {"max_geotags_per_hit": result.max_geotags_per_hit,
                                        "max_mean_extent_m": result.max_mean_extent_m},
                        "pareto": [r for r in rows if r["pareto"]], "configurations": rows}
            write_output(out_json, self.OUTPUT_JSON, lambda p: Path(p).write_text(
                json.dumps(document, indent=1, ensure_ascii=False) + "\n", encoding="utf-8"))
            outputs[self.OUTPUT_JSON] = out_json
        out_plot = self.parameterAsFileOutput(parameters, self.OUTPUT_PLOT, context)
        if out_plot:
            write_output(out_plot, self.OUTPUT_PLOT, lambda p: sweep_figure(result).savefig(p, dpi=110,
                                                                                        bbox_inches="tight"))
            outputs[self.OUTPUT_PLOT] = out_plot
        for r in sorted((r for r in rows if r["pareto"]), key=lambda r: -r["recall_pre"]):
            feedback.pushInfo(self.tr("Pareto: {checkpoint}, threshold {threshold}, eps {eps_m} m, min_samples "
                                      "{min_samples}, eps_pred {eps_pred_m} m → recall_pre {recall_pre:.3f}, "
                                      "gmcf_pre {gmcf_pre:.3f}, F1 {f1_geo:.3f}").format(
                                  checkpoint=r["checkpoint"], threshold=r['threshold'], eps_m=r['eps_m'],
                                  min_samples=r['min_samples'], eps_pred_m=r['eps_pred_m'],
                                  recall_pre=r['recall_pre'], gmcf_pre=r['gmcf_pre'], f1_geo=r['f1_geo']))
        if not outputs[self.N_CREDIBLE]:
            feedback.pushWarning(self.tr("No configuration passed the credibility filter."))
        feedback.setProgress(100)
        return outputs

    def _grounds(self, flights, read, dem, feedback) -> dict:
        """Each flight's ground-model factory, keyed like ``flights``: with CHECKPOINTS the one DEM /
        GROUND_MODEL give, which the detections are placed on; with DETECTIONS (``read``: layer, frame layer,
        detections, dropped) the one its layers were placed on, which must be one for all of them."""
        if not read:
            return {key: self.dem_ground(dem) for key in flights}
        by_flight = {}
        for _, frame_layer, det, _ in read:
            by_flight.setdefault(frame_layer.id(), []).append(det)
        grounds = {}
        for key, detections in by_flight.items():
            self.run_core(common_ground, [d.ground for d in detections], [d.name for d in detections])
            grounds[key] = self.recorded_ground(detections[0], dem, feedback)
        return grounds

    def _run_checkpoints(self, checkpoints, flights, flight_names, grid, edge, local, geotag_xy, grounds, feedback):
        """Every checkpoint over every flight's frames: one heatmap per frame, peaks at every threshold, placed
        on the flight's ground (``grounds``)."""
        sweep_flights = []
        steps = len(checkpoints) * len(flights)
        for i, path in enumerate(checkpoints):
            model = self.run_core(HeatmapModel, path, feedback.pushInfo)
            for j, (key, (_, groups, records, grouped)) in enumerate(flights.items()):
                step = i * len(flights) + j
                progress, is_canceled = self.progress_callbacks(feedback, 5.0 + 55.0 * step / steps,
                                                                5.0 + 55.0 * (step + 1) / steps)
                images = [[records[k].get("image") or "" for k in idx] for _, idx in grouped]
                found = self.run_core(detect_flight, model, groups, images, grid.thresholds, edge, local, progress,
                                      is_canceled, grounds[key])
                name = flight_names[key]
                if found.skipped:
                    feedback.pushWarning(self.tr("{checkpoint} on {flight}: {n} frame(s) skipped, e.g. {frame_id}: "
                                                 "{reason}").format(checkpoint=model.name, flight=name,
                                                                    n=len(found.skipped), frame_id=found.skipped[0][0],
                                                                    reason=found.skipped[0][1]))
                sweep_flights.append(SweepFlight({d.threshold: d.positions for d in found.by_threshold},
                                                 geotag_xy[name], len(found.processed), name, model.name,
                                                 model.digest))
        return sweep_flights

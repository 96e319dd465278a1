"""birdseye:sweepoperatingpoints — pooled recall and GMCF over a grid of operating points."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
from qgis.core import (
    QgsProcessing,
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFeatureSource,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.clustering import DEFAULT_DEDUP_CM
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.scoring.evaluation import local_frame_for
from ...birdseye_qgis.core.scoring.matching import in_view
from ...birdseye_qgis.core.scoring.operating_point import DEFAULT_EDGE_BUFFER_PX
from ...birdseye_qgis.core.scoring.reports import sweep_figure
from ...birdseye_qgis.core.scoring.sweep import (
    DEFAULT_MAX_GEOTAGS_PER_HIT,
    DEFAULT_MAX_MEAN_EXTENT_M,
    SweepFlight,
    SweepGrid,
    sweep,
)
from ...birdseye_qgis.qgis_io.detections import read_geotags
from ...birdseye_qgis.qgis_io.outputs import write_output, write_rows_csv
from ..parameters.clustering import ClusteringParametersMixin
from .base import BirdsEyeAlgorithm

LISTS = (("THRESHOLDS", "Detection thresholds (comma-separated probabilities)", "0.3,0.4,0.5,0.6,0.7"),
         ("EPS_M", "DBSCAN radii EPS (m, comma-separated)", "0.05,0.10,0.15,0.20"),
         ("MIN_SAMPLES", "DBSCAN minimum points (comma-separated whole numbers)", "2,3,4,6"),
         ("EPS_PRED_M", "Match radii EPS_PRED (m, comma-separated)", "0.10,0.20,0.30"))


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


class SweepOperatingPoints(ClusteringParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "sweepoperatingpoints"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SweepOperatingPoints", "Sweep operating points")
    GROUP = "detect"
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

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.DETECTIONS, self.tr("Detection layers (one per flight, detected at the lowest threshold)"),
            QgsProcessing.TypeVectorPoint))
        self.addParameter(QgsProcessingParameterFeatureSource(
            self.GEOTAGS, self.tr("Geotags"), [QgsProcessing.TypeVectorPoint]))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Frame layers (one per flight, same order)"), QgsProcessing.TypeVector))
        for name, text, default in LISTS:
            self.addParameter(QgsProcessingParameterString(name, self.tr(text), default))
        self.addParameter(QgsProcessingParameterNumber(
            self.DEDUP_CM, self.tr("De-duplication grid cell (cm)"), QgsProcessingParameterNumber.Double,
            DEFAULT_DEDUP_CM, minValue=0.1, maxValue=100.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.EDGE_BUFFER_PX, self.tr("Edge buffer of the in-view test (px)"), QgsProcessingParameterNumber.Double,
            DEFAULT_EDGE_BUFFER_PX, minValue=0.0, maxValue=1000.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_GEOTAGS_PER_HIT, self.tr("Credible: mean geotags per hit cluster at most"),
            QgsProcessingParameterNumber.Double, DEFAULT_MAX_GEOTAGS_PER_HIT, minValue=1.0))
        self.addParameter(QgsProcessingParameterNumber(
            self.MAX_MEAN_EXTENT_M, self.tr("Credible: mean median cluster extent at most (m)"),
            QgsProcessingParameterNumber.Double, DEFAULT_MAX_MEAN_EXTENT_M, minValue=0.0))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_TABLE, self.tr("Configurations (CSV)"), "CSV (*.csv)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Configurations and Pareto front (JSON)"), "JSON (*.json)", optional=True,
            createByDefault=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_PLOT, self.tr("Frontier plot (PNG)"), "PNG (*.png)", optional=True, createByDefault=True))
        for name, text in (("N_CONFIGURATIONS", "Configurations"), ("N_CREDIBLE", "Credible configurations"),
                           ("N_PARETO", "Configurations on the Pareto front")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        lists = {name: self.run_core(parse_list, self.parameterAsString(parameters, name, context), name)
                 for name, _, _ in LISTS}
        grid = self.run_core(SweepGrid, lists["THRESHOLDS"], lists["EPS_M"], lists["MIN_SAMPLES"],
                             lists["EPS_PRED_M"], self.parameterAsDouble(parameters, self.DEDUP_CM, context))
        flights = self.read_flights(parameters, context, feedback)
        for f in flights:
            t = f.detections.threshold
            if t is not None and t > grid.thresholds.min() + 1e-12:
                raise QgsProcessingException(
                    self.tr("THRESHOLDS: {name} was detected at threshold {t}, above the sweep's "
                            "lowest threshold {value}; detections below {t} were never made. Run "
                            "Detect at the lowest threshold of the sweep, or raise THRESHOLDS.").format(
                        name=f.name, t=t, value=grid.thresholds.min()))
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if geotag_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer cannot be read."))
        geotags = self.run_core(read_geotags, geotag_source, context)
        feedback.setProgress(10)
        local = self.run_core(local_frame_for, [p for f in flights for p in f.pose_groups], geotags)
        h = np.where(np.isfinite(geotags.height), geotags.height, local.h0)
        g_local = local.from_geodetic(geotags.lat, geotags.lon, h) if len(geotags) else np.empty((0, 3))
        edge = self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context)
        sweep_flights = []
        for f in flights:
            visible = self.run_core(in_view, f.pose_groups, local, g_local, edge).mask
            sweep_flights.append(SweepFlight(f.detections.local_xy(local), f.detections.score,
                                             g_local[visible, :2], f.name))
            feedback.pushInfo(self.tr("{name}: {n_detections} detections, {value} geotags in view").format(
                                  name=f.name, n_detections=len(f.detections), value=int(visible.sum())))
        feedback.pushInfo(self.tr("Sweeping {size} configurations ({items}: threshold × eps × "
                                  "min_samples × eps_pred)").format(
                              size=grid.size, items=' × '.join(map(str, grid.shape))))
        progress, is_canceled = self.progress_callbacks(feedback, 15.0, 95.0)
        result = self.run_core(sweep, sweep_flights, grid,
                               self.parameterAsDouble(parameters, self.MAX_GEOTAGS_PER_HIT, context),
                               self.parameterAsDouble(parameters, self.MAX_MEAN_EXTENT_M, context),
                               progress, is_canceled)
        rows = result.rows()
        for row in rows:
            row["edge_buffer_px"] = edge
        outputs = {"N_CONFIGURATIONS": len(rows), "N_CREDIBLE": int(result.credible.sum()),
                   "N_PARETO": int(result.pareto.sum())}
        table = self.parameterAsFileOutput(parameters, self.OUTPUT_TABLE, context)
        write_output(table, self.OUTPUT_TABLE, lambda p: write_rows_csv(p, rows))
        outputs[self.OUTPUT_TABLE] = table
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        if out_json:
            front = [r for r in rows if r["pareto"]]
            document = {"pooling": "micro-average over flights (sums of counts, one division)",
                        "flights": [f.name for f in flights],
                        "grid": {"thresholds": grid.thresholds.tolist(), "eps_m": grid.eps_m.tolist(),
                                 "min_samples": grid.min_samples.tolist(), "eps_pred_m": grid.eps_pred_m.tolist(),
                                 "dedup_cm": grid.dedup_cm, "edge_buffer_px": edge},
                        "credibility": {"max_geotags_per_hit": result.max_geotags_per_hit,
                                        "max_mean_extent_m": result.max_mean_extent_m},
                        "pareto": front, "configurations": rows}
            write_output(out_json, self.OUTPUT_JSON, lambda p: Path(p).write_text(
                json.dumps(document, indent=1, ensure_ascii=False) + "\n", encoding="utf-8"))
            outputs[self.OUTPUT_JSON] = out_json
        out_plot = self.parameterAsFileOutput(parameters, self.OUTPUT_PLOT, context)
        if out_plot:
            write_output(out_plot, self.OUTPUT_PLOT, lambda p: sweep_figure(result).savefig(p, dpi=110,
                                                                                        bbox_inches="tight"))
            outputs[self.OUTPUT_PLOT] = out_plot
        for r in sorted((r for r in rows if r["pareto"]), key=lambda r: -r["recall_pre"]):
            feedback.pushInfo(self.tr("Pareto: threshold {threshold}, eps {eps_m} m, min_samples "
                                      "{min_samples}, eps_pred {eps_pred_m} m → recall_pre "
                                      "{recall_pre:.3f}, gmcf_pre {gmcf_pre:.3f}").format(
                                  threshold=r['threshold'], eps_m=r['eps_m'], min_samples=r['min_samples'],
                                  eps_pred_m=r['eps_pred_m'], recall_pre=r['recall_pre'], gmcf_pre=r['gmcf_pre']))
        if not outputs["N_CREDIBLE"]:
            feedback.pushWarning(self.tr("No configuration passed the credibility filter."))
        feedback.setProgress(100)
        return outputs

"""birdseye:evaluatedetections — recall and GMCF of one or several flights, before and after review."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputNumber,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.__about__ import tr
from ...birdseye_qgis.core.scoring import preregistration
from ...birdseye_qgis.core.scoring.evaluation import evaluate_flights
from ...birdseye_qgis.core.scoring.operating_point import OperatingPoint
from ...birdseye_qgis.core.scoring.reports import evaluation_report_html
from ...birdseye_qgis.qgis_enums import SOURCE_VECTOR, SOURCE_VECTOR_POINT
from ...birdseye_qgis.qgis_io import layer_kinds
from ...birdseye_qgis.qgis_io.detections import read_verdicts
from ...birdseye_qgis.qgis_io.layers import read_geotag_layer
from ..parameters.clustering import ClusteringParametersMixin
from ..parameters.dem import DemParametersMixin
from ..parameters.layer_parameters import source_parameter, vector_parameter
from .base import BirdsEyeAlgorithm


def operating_point_from_rule(path, flights, arm_name, feedback) -> tuple[OperatingPoint, dict]:
    """Verify a sealed rule and return the operating point of the arm that scores the flights' detections."""
    doc = preregistration.read(path)
    arm, op = preregistration.arm_for_detections(doc, [f.detections for f in flights], str(path), arm_name)
    feedback.pushInfo(tr("Sealed rule verified (seal {value}…, sealed {sealed_at}); arm "
                         "'{name}': its operating point replaces the dialog's values: {value2}").format(
                          value=doc['seal'][:12], sealed_at=doc['sealed_at'], name=arm['name'],
                          value2=op.to_dict()))
    if "core_count" not in arm["operating_point"]:
        feedback.pushInfo(tr("The rule was sealed before BirdsEye recorded what the minimum points count; its arms "
                             "were chosen counting cells, so it is scored counting cells, as sealed."))
    return op, {"seal": doc["seal"], "sealed_at": doc["sealed_at"], "arm": arm["name"],
                "model_digest": arm["model_digest"]}


class EvaluateDetections(ClusteringParametersMixin, DemParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "evaluatedetections"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("EvaluateDetections", "Evaluate detections (recall, GMCF)")
    GROUP = "detect"
    DETECTIONS = "DETECTIONS"
    GEOTAGS = "GEOTAGS"
    FRAMES = "FRAMES"
    REVIEW = "REVIEW"
    PREREGISTRATION = "PREREGISTRATION"
    ARM = "ARM"
    OUTPUT_JSON = "OUTPUT_JSON"
    OUTPUT_REPORT = "OUTPUT_REPORT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.DETECTIONS, self.tr("Detection layers (one per flight)"), SOURCE_VECTOR_POINT))
        self.addParameter(source_parameter(
            self.GEOTAGS, self.tr("Geotags"), layer_kinds.GEOTAGS, [SOURCE_VECTOR_POINT]))
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.FRAMES, self.tr("Frame layers (one per flight, same order)"), SOURCE_VECTOR, optional=True))
        self.add_clustering_parameters()
        self.add_dem_parameters()
        self.addParameter(vector_parameter(
            self.REVIEW, self.tr("Review verdicts (for scores after review)"), layer_kinds.VERDICTS,
            [SOURCE_VECTOR], optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.PREREGISTRATION, self.tr("Sealed selection rule (JSON)"),
            optional=True, fileFilter="Preregistration (*.json)"))
        self.addParameter(QgsProcessingParameterString(
            self.ARM, self.tr("Arm to score (its name in the rule)"), optional=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_JSON, self.tr("Scores (JSON)"), "JSON (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT_REPORT, self.tr("Report (HTML)"), "HTML (*.html)", optional=True, createByDefault=True))
        for name, text in (("N_IN_VIEW", "Geotags in view"), ("N_RECOVERED", "Geotags recovered"),
                           ("RECALL_PRE", "recall_pre"), ("N_CLUSTERS", "Clusters"),
                           ("N_HIT_CLUSTERS", "Hit clusters"), ("GMCF_PRE", "gmcf_pre")):
            self.addOutput(QgsProcessingOutputNumber(name, self.tr(text)))

    def processAlgorithm(self, parameters, context, feedback):
        dem = self.read_dem(parameters, context, feedback=feedback)
        self.report_dem(feedback, dem)
        flights = self.read_flights(parameters, context, feedback,
                                    ground_for=lambda detections: self.recorded_ground(detections, dem, feedback))
        geotag_source = self.parameterAsSource(parameters, self.GEOTAGS, context)
        if geotag_source is None:
            raise QgsProcessingException(self.tr("GEOTAGS: the geotag layer cannot be read."))
        geotags = self.run_core(read_geotag_layer, geotag_source, context.transformContext())
        if len(geotags) == 0:
            raise QgsProcessingException(self.tr("GEOTAGS: the layer holds no point with a position."))
        rule_path = self.parameterAsFile(parameters, self.PREREGISTRATION, context)
        arm_name = self.parameterAsString(parameters, self.ARM, context).strip() or None
        rule = None
        if rule_path:
            op, rule = self.run_core(operating_point_from_rule, rule_path, flights, arm_name, feedback)
        elif arm_name:
            raise QgsProcessingException(self.tr("ARM: names an arm of a sealed selection rule; give the rule "
                                                 "(PREREGISTRATION) too, or leave ARM empty."))
        else:
            op = self.read_operating_point(parameters, context)
        review = self.parameterAsVectorLayer(parameters, self.REVIEW, context)
        log = self.run_core(read_verdicts, review, context) if review is not None else None
        feedback.setProgress(20)
        progress, is_canceled = self.progress_callbacks(feedback, 20.0, 90.0)
        evaluation = self.run_core(evaluate_flights, flights, geotags, op, log, None, progress, is_canceled)
        result = evaluation.to_dict()
        if rule is not None:
            result["preregistration"] = rule
        for note in evaluation.review_notes:
            feedback.pushWarning(note)
        for f in evaluation.flights:
            if f.in_view.n_frames_without_ground:
                feedback.pushWarning(self.tr("{name}: {n_frames_without_ground} frame(s) without "
                                             "a ground height were not counted as processed").format(
                                         name=f.name, n_frames_without_ground=f.in_view.n_frames_without_ground))
        out_json = self.parameterAsFileOutput(parameters, self.OUTPUT_JSON, context)
        try:
            Path(out_json).write_text(json.dumps(result, indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
        except OSError as exc:
            raise QgsProcessingException(self.tr("OUTPUT_JSON: cannot write {out_json} ({exc})").format(
                                             out_json=out_json, exc=exc)) from exc
        outputs = {"OUTPUT_JSON": out_json}
        out_report = self.parameterAsFileOutput(parameters, self.OUTPUT_REPORT, context)
        if out_report:
            try:
                Path(out_report).write_text(evaluation_report_html(evaluation), encoding="utf-8")
            except OSError as exc:
                raise QgsProcessingException(self.tr("OUTPUT_REPORT: cannot write {out_report} "
                                                     "({exc})").format(out_report=out_report, exc=exc)) from exc
            outputs[self.OUTPUT_REPORT] = out_report
        p = evaluation.pooled
        feedback.pushInfo(self._summary(result))
        outputs.update({"N_IN_VIEW": p.n_in_view, "N_RECOVERED": p.n_recovered, "RECALL_PRE": p.recall_pre,
                        "N_CLUSTERS": p.n_clusters, "N_HIT_CLUSTERS": p.n_hit_clusters, "GMCF_PRE": p.gmcf_pre})
        feedback.setProgress(100)
        return outputs

    @staticmethod
    def _summary(result: dict) -> str:
        def fmt(v):
            return "undefined" if v is None else f"{v:.3f}"

        lines = [f"recall_pre = {result['n_recovered']}/{result['n_in_view']} = {fmt(result['recall_pre'])}; "
                 f"gmcf_pre = {result['n_hit_clusters']}/{result['n_clusters']} = {fmt(result['gmcf_pre'])} "
                 "(a lower bound on precision, not precision)"]
        for conv, p in result.get("post", {}).items():
            if p["recall_post"] is None:
                recall = "undefined"
            elif p["recall_post_kind"] == "lower_bound":
                recall = p["recall_post"]
            else:
                recall = f"= {p['recall_post']} (a point value under the assumptions the help states)"
            lines.append(f"POST {conv}: c = {p['c']}, a = {p['a']}, gmcf_post = {fmt(p['gmcf_post'])}, "
                         f"recall_post {recall}")
        return "\n".join(lines)


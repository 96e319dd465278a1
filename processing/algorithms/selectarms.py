"""birdseye:selectarms — the method's three arms (max F1, max recall, lowest review burden) from a sweep."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import QgsProcessingParameterFile, QgsProcessingParameterFileDestination
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.scoring.arms import arms_document, read_sweep, select_arms
from ...birdseye_qgis.qgis_io.outputs import write_output
from .base import BirdsEyeAlgorithm


class SelectArms(BirdsEyeAlgorithm):
    ALG_ID = "selectarms"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SelectArms", "Select arms (max F1, max recall, lowest review burden)")
    GROUP = "detect"
    SWEEP = "SWEEP"
    OUTPUT = "OUTPUT"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterFile(
            self.SWEEP, self.tr("Sweep (the JSON output of Sweep operating points)"), fileFilter="JSON (*.json)"))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT, self.tr("Arms (JSON)"), "JSON (*.json)"))

    def processAlgorithm(self, parameters, context, feedback):
        path = self.parameterAsFile(parameters, self.SWEEP, context)
        document = self.run_core(read_sweep, path)
        arms = self.run_core(select_arms, document["configurations"], path)
        out = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        write_output(out, self.OUTPUT, lambda p: Path(p).write_text(
            json.dumps(arms_document(document, arms, str(path)), indent=1, ensure_ascii=False) + "\n",
            encoding="utf-8"))
        for arm in arms:
            op, scores = arm["operating_point"], arm["scores"]
            feedback.pushInfo(self.tr("{name}: {checkpoint} at threshold {threshold:g}, eps {eps_m:g} m, min_samples "
                                      "{min_samples}, eps_pred {eps_pred_m:g} m → recall_pre {recall:.3f}, gmcf_pre "
                                      "{gmcf:.3f}, F1 {f1:.3f}, {dpf} detections per frame (row {row})").format(
                name=arm["name"], checkpoint=arm["checkpoint"], threshold=op["threshold"], eps_m=op["eps_m"],
                min_samples=op["min_samples"], eps_pred_m=op["eps_pred_m"], recall=scores["recall_pre"],
                gmcf=scores["gmcf_pre"], f1=scores["f1_geo"],
                dpf="–" if scores["detections_per_frame"] is None else f"{scores['detections_per_frame']:.2f}",
                row=arm["sweep_row"]))
        return {self.OUTPUT: out}

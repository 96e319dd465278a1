"""birdseye:sealpreregistration — write a selection rule as canonical JSON sealed with SHA-256."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import (
    QgsProcessingException,
    QgsProcessingOutputString,
    QgsProcessingParameterFile,
    QgsProcessingParameterFileDestination,
    QgsProcessingParameterMultipleLayers,
    QgsProcessingParameterNumber,
    QgsProcessingParameterString,
)
from qgis.PyQt.QtCore import QT_TRANSLATE_NOOP

from ...birdseye_qgis.core.detect.detector import file_digest
from ...birdseye_qgis.core.errors import InputError
from ...birdseye_qgis.core.scoring import preregistration
from ...birdseye_qgis.core.scoring.arms import read_arms
from ...birdseye_qgis.qgis_enums import NUMBER_DOUBLE, SOURCE_FILE
from ..parameters.clustering import ClusteringParametersMixin
from .base import BirdsEyeAlgorithm


def read_descriptive(path) -> list:
    """Configurations to record (a sweep's or screen's JSON output, or any JSON list/object)."""
    try:
        data = json.loads(Path(path).read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"cannot be read as JSON ({exc})", source=str(path), field="DESCRIPTIVE") from exc
    if isinstance(data, dict):
        for key in ("pareto", "checkpoints", "configurations"):
            if isinstance(data.get(key), list):
                return data[key]
        return [data]
    if isinstance(data, list):
        return data
    raise InputError("holds neither a JSON list nor an object", source=str(path), field="DESCRIPTIVE")


class SealPreregistration(ClusteringParametersMixin, BirdsEyeAlgorithm):
    ALG_ID = "sealpreregistration"
    DISPLAY_NAME = QT_TRANSLATE_NOOP("SealPreregistration", "Seal a preregistered selection rule")
    GROUP = "detect"
    CHECKPOINTS = "CHECKPOINTS"
    ARMS = "ARMS"
    ARM_LINES = "ARM_LINES"
    THRESHOLD = "THRESHOLD"
    DESCRIPTIVE = "DESCRIPTIVE"
    NOTE = "NOTE"
    OUTPUT = "OUTPUT"
    SEAL = "SEAL"

    def initAlgorithm(self, config=None):
        self.addParameter(QgsProcessingParameterMultipleLayers(
            self.CHECKPOINTS, self.tr("ONNX checkpoints (one arm each)"),
            SOURCE_FILE, optional=True))
        self.addParameter(QgsProcessingParameterFile(
            self.ARMS, self.tr("Arms file (JSON, from Select arms)"),
            optional=True, fileFilter="JSON (*.json)"))
        self.addParameter(QgsProcessingParameterString(
            self.ARM_LINES, self.tr("Or arms typed, one per line"), "",
            multiLine=True, optional=True))
        self.addParameter(QgsProcessingParameterNumber(
            self.THRESHOLD, self.tr("Detection threshold of the checkpoints' arms"),
            NUMBER_DOUBLE, 0.5, minValue=0.001, maxValue=0.999))
        self.add_clustering_parameters()
        self.addParameter(QgsProcessingParameterFile(
            self.DESCRIPTIVE, self.tr("Sweep or screen JSON (recorded only)"),
            optional=True, fileFilter="JSON (*.json)"))
        self.addParameter(QgsProcessingParameterString(
            self.NOTE, self.tr("Note (what was chosen and why)"), "", multiLine=True,
            optional=True))
        self.addParameter(QgsProcessingParameterFileDestination(
            self.OUTPUT, self.tr("Sealed rule (JSON)"), "JSON (*.json)"))
        self.addOutput(QgsProcessingOutputString(self.SEAL, self.tr("Seal (SHA-256)")))

    def processAlgorithm(self, parameters, context, feedback):
        paths = [p for p in self.parameterAsFileList(parameters, self.CHECKPOINTS, context) if p]
        arms_path = self.parameterAsFile(parameters, self.ARMS, context)
        lines = self.parameterAsString(parameters, self.ARM_LINES, context).strip()
        if arms_path and lines:
            raise QgsProcessingException(self.tr("ARMS, ARM_LINES: give the arms file or typed arms, not both."))
        for path in paths:
            if not Path(path).is_file():
                raise QgsProcessingException(self.tr("CHECKPOINTS: {path} is not a file").format(path=path))
        digests = {Path(path).name: file_digest(path) for path in paths}
        if len(digests) < len(paths):
            raise QgsProcessingException(self.tr("CHECKPOINTS: two files share a file name; arms name their "
                                                 "checkpoint by file name, so rename one."))
        if arms_path:
            arms = self.run_core(preregistration.arms_from_selection, self.run_core(read_arms, arms_path),
                                 digests or None)
        elif not paths:
            raise QgsProcessingException(self.tr("CHECKPOINTS: give at least one ONNX file (or an ARMS file)."))
        elif lines:
            arms = self.run_core(preregistration.parse_arm_lines, lines, digests,
                                 self.parameterAsDouble(parameters, self.DEDUP_CM, context),
                                 self.parameterAsDouble(parameters, self.EDGE_BUFFER_PX, context),
                                 self.read_core_count(parameters, context))
        else:
            op = self.read_operating_point(parameters, context,
                                           self.parameterAsDouble(parameters, self.THRESHOLD, context))
            arms = [self.run_core(preregistration.make_arm, path, digests[Path(path).name], op) for path in paths]
        for arm in arms:
            feedback.pushInfo(self.tr("Arm {name}: {checkpoint} (sha256 {model_digest}) at {operating_point}").format(
                name=arm["name"], checkpoint=arm["checkpoint"], model_digest=arm["model_digest"],
                operating_point=arm["operating_point"]))
        descriptive_path = self.parameterAsFile(parameters, self.DESCRIPTIVE, context)
        descriptive = self.run_core(read_descriptive, descriptive_path) if descriptive_path else []
        rule = {"arms": arms, "descriptive": descriptive,
                "note": self.parameterAsString(parameters, self.NOTE, context) or ""}
        document = self.run_core(preregistration.seal, rule)
        out = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        try:
            preregistration.write(document, out)
        except OSError as exc:
            raise QgsProcessingException(
                self.tr("OUTPUT: cannot write {out} ({exc})").format(out=out, exc=exc)) from exc
        feedback.pushInfo(self.tr("Sealed at {sealed_at}: {seal}").format(
                              sealed_at=document['sealed_at'], seal=document['seal']))
        feedback.pushInfo(self.tr("Record this seal somewhere you cannot edit later (an e-mail, "
                                  "a lab notebook, a commit): the seal proves the rule unchanged "
                                  "only against a copy kept elsewhere."))
        return {"OUTPUT": out, self.SEAL: document["seal"]}

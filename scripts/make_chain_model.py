"""Write resources/models/birdseye_chain.model3, the whole chain as a Graphical Modeler model.

Built with QGIS's model API rather than by hand, so the file is what the Modeler itself would save.
Run it after changing an algorithm's parameters (``make chain-model``); ``tests/qgis/test_chain_model.py``
loads the shipped file and runs it.
"""
from __future__ import annotations

import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
MODEL_PATH = REPO / "resources" / "models" / "birdseye_chain.model3"

# (child id, algorithm, {parameter: ("input", name) | ("child", child id, output) | ("value", v)},
#  {model output name: child output}, description)
STEPS = [
    ("importgeotags", "birdseye:importgeotags", {"INPUT": ("input", "GEOTAG_FILE")},
     {"Geotags": "OUTPUT"}, "Import geotags"),
    ("importflightlog", "birdseye:importflightlog",
     {"POSE_LOG": ("input", "POSE_LOG"), "IMAGES": ("input", "IMAGES"), "CALIBRATION": ("input", "CALIBRATION")},
     {"Frames": "OUTPUT", "Flight line": "OUTPUT_TRACK"}, "Import flight log"),
    ("writelabels", "birdseye:writelabels",
     {"GEOTAGS": ("child", "importgeotags", "OUTPUT"), "FRAMES": ("child", "importflightlog", "OUTPUT"),
      "OUTPUT_FRAMES": ("value", None), "OUTPUT_GEOTAGS": ("value", None)},
     {"Label folder": "OUTPUT_FOLDER"}, "Write training labels"),
    ("detect", "birdseye:detect", {"FRAMES": ("child", "importflightlog", "OUTPUT")},
     {"Detections": "OUTPUT"}, "Detect targets"),
    ("clusterdetections", "birdseye:clusterdetections",
     {"DETECTIONS": ("child", "detect", "OUTPUT"), "GEOTAGS": ("child", "importgeotags", "OUTPUT"),
      "FRAMES": ("child", "importflightlog", "OUTPUT"), "OUTPUT_POINTS": ("value", None)},
     {"Clusters": "OUTPUT"}, "Cluster detections"),
    ("evaluatedetections", "birdseye:evaluatedetections",
     {"DETECTIONS": ("children", [("detect", "OUTPUT")]), "GEOTAGS": ("child", "importgeotags", "OUTPUT"),
      "FRAMES": ("children", [("importflightlog", "OUTPUT")])},
     {"Scores (JSON)": "OUTPUT_JSON", "Evaluation report": "OUTPUT_REPORT"}, "Evaluate detections"),
]


def build_model():
    from qgis.core import (
        QgsProcessingModelAlgorithm,
        QgsProcessingModelChildAlgorithm,
        QgsProcessingModelChildParameterSource,
        QgsProcessingModelOutput,
        QgsProcessingModelParameter,
        QgsProcessingParameterFile,
    )
    from qgis.PyQt.QtCore import QPointF

    model = QgsProcessingModelAlgorithm("BirdsEye: survey and flight to labels, detections and scores",
                                        "BirdsEye", "birdseye")
    model.setHelpContent({"ALG_DESC": "The BirdsEye chain on your own data: import the rover geotags and the "
                                      "flight log, write the training labels, run the detector (the bundled demo "
                                      "model unless you edit the Detect step), cluster the detections and score "
                                      "them against the survey."})
    inputs = [
        ("GEOTAG_FILE", "Rover geotags (CSV or NMEA)", QgsProcessingParameterFile.File, "Geotags (*.csv *.txt *.nmea)"),
        ("POSE_LOG", "Pose log (CSV) or flight_data.db", QgsProcessingParameterFile.File, "Pose logs (*.csv *.db)"),
        ("IMAGES", "Folder of frames", QgsProcessingParameterFile.Folder, ""),
        ("CALIBRATION", "Camera calibration (Kalibr or OpenCV YAML)", QgsProcessingParameterFile.File,
         "Calibration (*.yaml *.yml)"),
    ]
    for k, (name, text, behaviour, file_filter) in enumerate(inputs):
        model.addModelParameter(QgsProcessingParameterFile(name, text, behavior=behaviour, fileFilter=file_filter),
                                _placed(QgsProcessingModelParameter(name), QPointF(120, 80 + 90 * k)))
    for k, (child_id, alg_id, sources, outputs, description) in enumerate(STEPS):
        child = QgsProcessingModelChildAlgorithm(alg_id)
        child.setChildId(child_id)
        child.setDescription(description)
        child.setPosition(QPointF(420 + 260 * (k // 3), 80 + 160 * (k % 3)))
        for parameter, source in sources.items():
            child.addParameterSources(parameter, _sources(source, QgsProcessingModelChildParameterSource))
        model_outputs = {}
        for name, child_output in outputs.items():
            out = QgsProcessingModelOutput(name, name)
            out.setChildId(child_id)
            out.setChildOutputName(child_output)
            model_outputs[name] = out
        child.setModelOutputs(model_outputs)
        model.addChildAlgorithm(child)
    return model


def _placed(component, position):
    component.setPosition(position)
    return component


def _sources(source, kind):
    if source[0] == "input":
        return [kind.fromModelParameter(source[1])]
    if source[0] == "child":
        return [kind.fromChildOutput(source[1], source[2])]
    if source[0] == "children":
        return [kind.fromChildOutput(child, output) for child, output in source[1]]
    return [kind.fromStaticValue(source[1])]


def main() -> int:
    sys.path.insert(0, str(REPO / "build" / "pluginpath"))
    sys.path.append("/usr/share/qgis/python/plugins")
    from qgis.core import QgsApplication

    app = QgsApplication([], False)
    app.initQgis()
    from processing.core.Processing import Processing

    Processing.initialize()
    from birdseye.processing.provider import BirdsEyeProvider

    provider = BirdsEyeProvider()
    QgsApplication.processingRegistry().addProvider(provider)
    model = build_model()
    MODEL_PATH.parent.mkdir(parents=True, exist_ok=True)
    ok = model.toFile(str(MODEL_PATH))
    print(f"{'wrote' if ok else 'could not write'} {MODEL_PATH.relative_to(REPO)}")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())

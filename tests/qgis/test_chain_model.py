"""The shipped Graphical Modeler model: it loads, every step is a registered algorithm, and it runs."""
from __future__ import annotations

import json
from pathlib import Path

from qgis.core import QgsApplication, QgsProcessingContext, QgsProcessingFeedback, QgsProcessingModelAlgorithm

from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

MODEL = Path(__file__).resolve().parents[2] / "resources" / "models" / "birdseye_chain.model3"


def load_model():
    model = QgsProcessingModelAlgorithm()
    assert model.fromFile(str(MODEL)), f"{MODEL} does not load"
    return model


def test_the_model_is_the_chain_of_registered_birdseye_algorithms(birdseye_provider):
    model = load_model()
    registry = QgsApplication.processingRegistry()
    steps = {child.childId(): child.algorithmId() for child in model.childAlgorithms().values()}
    assert set(steps.values()) == {f"birdseye:{a}" for a in ("importgeotags", "importflightlog", "writelabels",
                                                            "detect", "clusterdetections", "evaluatedetections")}
    for alg_id in steps.values():
        assert registry.algorithmById(alg_id) is not None, alg_id
    assert {p.name() for p in model.parameterDefinitions()} >= {"GEOTAG_FILE", "POSE_LOG", "IMAGES", "CALIBRATION"}


def test_the_model_runs_on_a_simulated_campaign(birdseye_provider, tmp_path):
    import processing

    folder = tmp_path / "campaign"
    simulate_campaign(CampaignConfig(seed=4, n_targets=4, field_width_m=6.0, field_length_m=5.0, image_width=640,
                                     image_height=400), folder)
    model = load_model()
    outputs = {name: str(tmp_path / file) for name, file in (
        ("writelabels:Label folder", "labels"), ("evaluatedetections:Scores (JSON)", "scores.json"),
        ("evaluatedetections:Evaluation report", "report.html"))}
    for name in ("importgeotags:Geotags", "importflightlog:Frames", "importflightlog:Flight line",
                 "detect:Detections", "clusterdetections:Clusters"):
        outputs[name] = "TEMPORARY_OUTPUT"
    params = {"GEOTAG_FILE": str(folder / "geotags.csv"), "POSE_LOG": str(folder / "poses.csv"),
              "IMAGES": str(folder / "frames"), "CALIBRATION": str(folder / "calibration.yaml"), **outputs}
    result = processing.run(model, params, context=QgsProcessingContext(), feedback=QgsProcessingFeedback())
    assert (tmp_path / "labels" / "labels.csv").is_file()
    scores = json.loads((tmp_path / "scores.json").read_text())
    assert scores["n_in_view"] >= 1 and 0.0 <= scores["recall_pre"] <= 1.0
    assert result["detect:Detections"] is not None

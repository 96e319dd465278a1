"""The method's held-out step through the registry: a sweep's three arms (two of them on one checkpoint)
are sealed, and Evaluate detections scores one named arm on a layer detected at that arm's threshold."""
from __future__ import annotations

import json

import numpy as np
import pytest
from qgis.core import QgsField, QgsProcessingException
from qgis.PyQt.QtCore import QVariant
from registry import Recorder
from test_cluster_algorithms import DIGEST, detection_layer, frame_layer, point_layer, run
from test_operating_points import GEOTAGS3, UNMATCHED, A, C, E, arms_sweep


@pytest.fixture
def sealed_arms(birdseye_provider, tmp_path):
    """The arms of ``arms_sweep`` sealed: max_f1 at 0.4, max_recall at 0.3, lowest_review_burden at 0.5,
    each with EPS 0.05 m, MIN_SAMPLES 2, EPS_PRED 0.20 m, all on checkpoint demo.onnx."""
    arms = tmp_path / "arms.json"
    run("selectarms", {"SWEEP": str(arms_sweep(tmp_path)), "OUTPUT": str(arms)})
    checkpoint = tmp_path / "demo.onnx"
    checkpoint.write_bytes(b"demo model")                      # its SHA-256 is the detections' model_digest
    rule = tmp_path / "rule.json"
    run("sealpreregistration", {"ARMS": str(arms), "CHECKPOINTS": [str(checkpoint)], "OUTPUT": str(rule)})
    return rule


def held_out(tmp_path, detections, threshold, **extra):
    out = tmp_path / f"scores_{threshold}.json"
    geo = point_layer("geotags", [QgsField("id", QVariant.Int)], [[k] for k in GEOTAGS3], list(GEOTAGS3.values()))
    run("evaluatedetections", {"DETECTIONS": [detection_layer(detections, threshold=threshold, name="held-out")],
                               "GEOTAGS": geo, "FRAMES": [frame_layer()], "OUTPUT_JSON": str(out),
                               "OUTPUT_REPORT": None, "EPS_PRED_M": 5.0, **extra})
    return json.loads(out.read_text(encoding="utf-8"))


def test_the_named_arm_is_scored_at_its_own_operating_point(sealed_arms, tmp_path):
    at_04 = np.concatenate([A, C, UNMATCHED[0]])
    scores = held_out(tmp_path, at_04, 0.4, PREREGISTRATION=str(sealed_arms), ARM="max_f1")
    assert scores["preregistration"]["arm"] == "max_f1" and scores["preregistration"]["model_digest"] == DIGEST
    # the arm's point replaces the dialog's: its EPS_PRED 5 m would recover geotag 3, 3.7 m from A
    assert scores["parameters"] == {"threshold": 0.4, "dedup_cm": 3.0, "eps_m": 0.05, "min_samples": 2,
                                    "eps_pred_m": 0.2, "edge_buffer_px": 0.0, "core_count": "detections"}
    # A and C on geotags 1 and 2, one unmatched spot; geotag 3 missed: recall 2/3, GMCF 2/3
    assert (scores["n_in_view"], scores["n_recovered"], scores["n_clusters"], scores["n_hit_clusters"]) == (3, 2, 3, 2)
    at_03 = np.concatenate([A, C, E] + UNMATCHED)
    scores = held_out(tmp_path, at_03, 0.3, PREREGISTRATION=str(sealed_arms), ARM="max_recall")
    assert scores["preregistration"]["arm"] == "max_recall" and scores["parameters"]["threshold"] == 0.3
    assert (scores["n_recovered"], scores["n_clusters"], scores["n_hit_clusters"]) == (3, 7, 3)


def test_arms_sharing_the_checkpoint_must_be_named_and_exist(sealed_arms, tmp_path):
    layer = np.concatenate([A, C, UNMATCHED[0]])
    with pytest.raises(QgsProcessingException, match="seals 3 arms .*say which arm to score \\(ARM\\)"):
        held_out(tmp_path, layer, 0.4, PREREGISTRATION=str(sealed_arms))
    with pytest.raises(QgsProcessingException, match="no arm 'max_F1'"):
        held_out(tmp_path, layer, 0.4, PREREGISTRATION=str(sealed_arms), ARM="max_F1")
    with pytest.raises(QgsProcessingException, match="ARM: names an arm of a sealed selection rule"):
        held_out(tmp_path, layer, 0.4, ARM="max_f1")


def test_a_layer_detected_at_another_threshold_than_the_arms_is_refused(sealed_arms, tmp_path):
    # the 0.3 run holds every detection of the 0.4 run, but filtering it is not a run at 0.4
    with pytest.raises(QgsProcessingException, match="held-out, field 'threshold': was detected at threshold 0.3, "
                                                     "but arm 'max_f1' is sealed at 0.4.*THRESHOLD 0.4"):
        held_out(tmp_path, np.concatenate([A, C, E] + UNMATCHED), 0.3, PREREGISTRATION=str(sealed_arms),
                 ARM="max_f1")
    with pytest.raises(QgsProcessingException, match="was detected at threshold 0.5, but arm 'max_f1'"):
        held_out(tmp_path, A, 0.5, PREREGISTRATION=str(sealed_arms), ARM="max_f1")


def test_a_rule_sealed_before_core_count_was_recorded_is_scored_counting_cells(birdseye_provider, tmp_path):
    """Its arms record no core_count: they were chosen on figures that counted cells. Five detections at
    geotag 1, all in one cell, form a cluster when detections are counted, but not under the sealed rule."""
    from birdseye.birdseye_qgis.core.scoring import preregistration

    point = {"threshold": 0.4, "dedup_cm": 3.0, "eps_m": 0.05, "min_samples": 2, "eps_pred_m": 0.2,
             "edge_buffer_px": 0.0}
    rule = tmp_path / "old_rule.json"
    preregistration.write(preregistration.seal({"arms": [{"name": "max_f1", "checkpoint": "demo.onnx",
                                                           "model_digest": DIGEST, "operating_point": point}]}), rule)
    assert "core_count" not in rule.read_text(encoding="utf-8")
    one_cell = np.repeat([GEOTAGS3[1]], 5, axis=0)
    feedback = Recorder()
    out = tmp_path / "old.json"
    geo = point_layer("geotags", [QgsField("id", QVariant.Int)], [[k] for k in GEOTAGS3], list(GEOTAGS3.values()))
    run("evaluatedetections", {"DETECTIONS": [detection_layer(one_cell, threshold=0.4, name="held-out")],
                               "GEOTAGS": geo, "FRAMES": [frame_layer()], "OUTPUT_JSON": str(out),
                               "OUTPUT_REPORT": None, "PREREGISTRATION": str(rule)}, feedback)
    scores = json.loads(out.read_text(encoding="utf-8"))
    assert scores["parameters"]["core_count"] == "cells"
    assert (scores["n_clusters"], scores["n_recovered"]) == (0, 0)
    assert any("sealed before BirdsEye recorded" in m for m in feedback.infos)
    counted = held_out(tmp_path, one_cell, 0.4, EPS_PRED_M=0.2)
    assert counted["parameters"]["core_count"] == "detections"
    assert (counted["n_clusters"], counted["n_recovered"]) == (1, 1)

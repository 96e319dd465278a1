"""The method's selection protocol through the registry: the sweep's threshold axis against real Detect
runs on a simulated flight, screening in blocks, the three arms, and sealing them."""
from __future__ import annotations

import csv
import json

import numpy as np
import pytest
from qgis.core import QgsField, QgsProcessingException
from qgis.PyQt.QtCore import QVariant
from test_cluster_algorithms import (
    DIGEST,
    detection_layer,
    frame_layer,
    grid9,
    onnx_model,
    point_layer,
    run,
    three_frame_scene,
)

from birdseye.birdseye_qgis.__about__ import BUNDLED_MODEL
from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

COUNTS = ("n_frames", "n_detections", "n_in_view", "n_recovered", "n_clusters", "n_hit_clusters", "n_geotag_matches")


def read_rows(path):
    with open(path, newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def configuration(row):
    return float(row["threshold"]), float(row["eps_m"]), int(row["min_samples"]), float(row["eps_pred_m"])


# ------------------------------------------------------------------ the threshold axis is a real re-run
@pytest.fixture(scope="module")
def simulated_flight(birdseye_provider, tmp_path_factory):
    """A small simulated flight (67 frames of 320 × 200 px over 3 burrows), imported."""
    import processing

    folder = tmp_path_factory.mktemp("campaign")
    simulate_campaign(CampaignConfig(seed=5, n_targets=3, field_width_m=6.0, field_length_m=5.0, image_width=320,
                                     image_height=200, noise_off=True), folder)
    frames = processing.run("birdseye:importflightlog", {
        "POSE_LOG": str(folder / "poses.csv"), "IMAGES": str(folder / "frames"),
        "CALIBRATION": str(folder / "calibration.yaml"), "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    geotags = processing.run("birdseye:importgeotags", {"INPUT": str(folder / "geotags.csv"),
                                                        "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]
    return frames, geotags


def test_the_sweeps_threshold_axis_equals_detect_runs_at_each_threshold(simulated_flight, tmp_path):
    frames, geotags = simulated_flight
    # noise off: a burrow's detections fall into one 3 cm cell, a cluster only at MIN_SAMPLES 1
    grid = {"EPS_M": "0.1,0.2", "MIN_SAMPLES": "1,2", "EPS_PRED_M": "0.2,0.35"}

    def detect(threshold):
        return run("detect", {"FRAMES": frames, "THRESHOLD": threshold, "OUTPUT": "TEMPORARY_OUTPUT"})["OUTPUT"]

    # What makes the comparison bite: the low run's detections scored ≥ high are not the high run's — a
    # blob that was one detection at low splits at high. Which threshold splits one depends on the
    # heatmap's last digits, which move with the onnxruntime and OpenCV releases, so the first candidate
    # that does is taken.
    low = 0.02
    layers = {low: detect(low)}
    for high in (0.03, 0.05, 0.1, 0.2):
        layers[high] = detect(high)
        if sum(f["score"] >= high for f in layers[low].getFeatures()) != layers[high].featureCount():
            break
    else:
        pytest.fail("no blob splits between 0.02 and any of 0.03–0.2: pick thresholds that do")
    rerun = run("sweepoperatingpoints", {"CHECKPOINTS": [str(BUNDLED_MODEL)], "FRAMES": [frames], "GEOTAGS": geotags,
                                         "THRESHOLDS": f"{low},{high}", **grid, "OUTPUT_TABLE": str(tmp_path / "a.csv"),
                                         "OUTPUT_JSON": None, "OUTPUT_PLOT": None})
    detected = run("sweepoperatingpoints", {"DETECTIONS": [layers[low], layers[high]], "FRAMES": [frames, frames],
                                            "GEOTAGS": geotags, **grid, "OUTPUT_TABLE": str(tmp_path / "b.csv"),
                                            "OUTPUT_JSON": None, "OUTPUT_PLOT": None})
    a = {configuration(r): r for r in read_rows(rerun["OUTPUT_TABLE"])}
    b = {configuration(r): r for r in read_rows(detected["OUTPUT_TABLE"])}
    assert a.keys() == b.keys() and len(a) == 2 * 2 * 2 * 2
    for key, row in a.items():
        assert row["checkpoint"] == b[key]["checkpoint"] == BUNDLED_MODEL.name
        assert [row[c] for c in COUNTS] == [b[key][c] for c in COUNTS], key
        assert int(row["n_detections"]) == layers[key[0]].featureCount()
    assert int(a[(high, 0.1, 1, 0.2)]["n_in_view"]) > 0 and int(a[(high, 0.1, 1, 0.2)]["n_hit_clusters"]) > 0


# ------------------------------------------------------------------ screening in blocks
def test_screencheckpoints_method_preset_and_blocks(birdseye_provider, tmp_path):
    frames, geo = three_frame_scene(tmp_path)
    good = onnx_model(tmp_path / "good.onnx")
    out = tmp_path / "screen.json"
    # the method preset (threshold 0.03), its 500-frame blocks overridden by 2: blocks of frames 1–2 and 3
    run("screencheckpoints", {"CHECKPOINTS": [str(good)], "FRAMES": [frames], "GEOTAGS": geo, "BLOCK_FRAMES": 2,
                              "MIN_SAMPLES": 1, "OUTPUT_TABLE": str(tmp_path / "screen.csv"), "OUTPUT_JSON": str(out),
                              "OUTPUT_PLOT": None})
    document = json.loads(out.read_text(encoding="utf-8"))
    assert document["preset"] == "method" and document["block_frames"] == 2
    assert document["blocks"] == ["frames, frames 1–2", "frames, frames 3–3"]
    (row,) = document["checkpoints"]
    assert row["threshold"] == 0.03
    # every target is in view of both blocks: 6 in view, 6 recovered; 3 clusters per block, all hits
    assert (row["n_in_view"], row["n_recovered"], row["n_clusters"], row["n_hit_clusters"]) == (6, 6, 6, 6)
    assert row["f1_geo"] == 1.0 and row["detections_per_frame"] == 3.0 and row["review_load"] == 1.0
    assert row["worst_block"] in document["blocks"] and row["f1_pixel_radius_px"] == 10.0


def test_screencheckpoints_reports_the_transfer_to_held_out_flights(birdseye_provider, tmp_path):
    """The same scene flown again as the held-out flight, whose survey found a fourth burrow the images do not
    show: held-out recall 3/4 against 3/3 on validation (ΔRecall −0.25), GMCF 1 on both; every frame sees 3
    geotags on validation and 4 held out. One healthy checkpoint: no Spearman's ρ, and the report says why."""
    frames, geo = three_frame_scene(tmp_path)
    (tmp_path / "heldout").mkdir()
    heldout_frames, _ = three_frame_scene(tmp_path / "heldout")
    targets = [(0.1, 0.2), (-0.25, -0.1), (0.45, 0.05), (0.3, -0.5)]
    heldout_geo = point_layer("heldout geotags", [QgsField("id", QVariant.Int)], [[1], [2], [3], [4]], targets)
    good, flat = onnx_model(tmp_path / "good.onnx"), onnx_model(tmp_path / "flat.onnx", bias=0.8)
    out, table, report = tmp_path / "screen.json", tmp_path / "screen.csv", tmp_path / "screen.html"
    run("screencheckpoints", {"CHECKPOINTS": [str(good), str(flat)], "FRAMES": [frames], "GEOTAGS": geo,
                              "HELDOUT_FRAMES": [heldout_frames], "HELDOUT_GEOTAGS": heldout_geo, "PRESET": 1,
                              "MIN_SAMPLES": 1, "COLLAPSED_BELOW": 0.5, "OUTPUT_TABLE": str(table),
                              "OUTPUT_JSON": str(out), "OUTPUT_PLOT": None, "OUTPUT_REPORT": str(report)})
    document = json.loads(out.read_text(encoding="utf-8"))
    assert document["survey_density"]["pooled"]["mean"] == 3.0
    assert document["heldout"]["survey_density"]["pooled"] == {"n_frames": 3, "mean": 4.0, "median": 4.0, "p10": 4.0,
                                                               "p90": 4.0, "min": 4, "max": 4,
                                                               "frames_without_geotag": 0.0}
    transfer = {t["checkpoint"]: t for t in document["transfer"]["checkpoints"]}
    g = transfer["good.onnx"]
    assert (g["recall_validation"], g["recall_heldout"], g["gmcf_validation"], g["gmcf_heldout"]) == (1.0, 0.75, 1.0,
                                                                                                      1.0)
    assert g["delta_recall"] == pytest.approx(-0.25) and g["delta_gmcf"] == 0.0
    assert g["heldout"] == {"n_in_view": 4, "n_recovered": 3, "n_clusters": 3, "n_hit_clusters": 3}
    f = transfer["flat.onnx"]
    assert f["healthy_on_validation"] is False
    heldout_rows = {r["checkpoint"]: r for r in document["heldout"]["checkpoints"]}
    assert f["recall_heldout"] == heldout_rows["flat.onnx"]["recall_pre"]
    spearman = document["transfer"]["spearman"]
    assert spearman["recall"]["spearman_rho"] is None and spearman["recall"]["n_checkpoints"] == 1
    assert spearman["gmcf"]["note"].startswith("not enough checkpoints: 1")
    rows = {r["checkpoint"]: r for r in read_rows(table)}
    assert float(rows["good.onnx"]["recall_pre_heldout"]) == 0.75 and float(rows["good.onnx"]["delta_recall"]) == -0.25
    html = report.read_text(encoding="utf-8")
    assert "Validation → held-out" in html and "not enough checkpoints" in html and "Survey density" in html
    with pytest.raises(QgsProcessingException, match="HELDOUT_GEOTAGS: give the held-out flights"):
        run("screencheckpoints", {"CHECKPOINTS": [str(good)], "FRAMES": [frames], "GEOTAGS": geo,
                                  "HELDOUT_GEOTAGS": heldout_geo, "OUTPUT_TABLE": str(table)})


# ------------------------------------------------------------------ arms and their seal
GEOTAGS3 = {1: (-2.9, 0.0), 2: (5.1, -5.0), 3: (-5.1, 3.0)}
A, C, E = grid9(-3.0, 0.0), grid9(5.0, -5.0), grid9(-5.0, 3.0)             # on geotags 1, 2, 3
UNMATCHED = [grid9(3.0, 1.0), grid9(0.0, 3.0), grid9(-6.0, -3.0), grid9(6.0, 3.0)]


def arms_sweep(tmp_path):
    """One checkpoint detected at three thresholds on one frame:
    0.3: A, C, E + 4 unmatched → recall 1, GMCF 3/7, F1 0.6 (the highest recall);
    0.4: A, C + 1 unmatched → recall 2/3, GMCF 2/3, F1 2/3 (the highest F1);
    0.5: A alone → recall 1/3, GMCF 1, F1 1/2, 9 detections per frame (the lightest)."""
    layers = [detection_layer(np.concatenate([A, C, E] + UNMATCHED), threshold=0.3, name="t03"),
              detection_layer(np.concatenate([A, C, UNMATCHED[0]]), threshold=0.4, name="t04"),
              detection_layer(A, threshold=0.5, name="t05")]
    geo = point_layer("geotags", [QgsField("id", QVariant.Int)], [[k] for k in GEOTAGS3], list(GEOTAGS3.values()))
    frames = frame_layer()
    out = tmp_path / "sweep.json"
    run("sweepoperatingpoints", {"DETECTIONS": layers, "FRAMES": [frames] * 3, "GEOTAGS": geo, "EPS_M": "0.05,0.1",
                                 "MIN_SAMPLES": "2,3", "EPS_PRED_M": "0.05,0.2", "OUTPUT_JSON": str(out),
                                 "OUTPUT_TABLE": str(tmp_path / "s.csv"), "OUTPUT_PLOT": None})
    return out


def test_selectarms_applies_the_three_rules_to_the_credible_front(birdseye_provider, tmp_path):
    sweep_json = arms_sweep(tmp_path)
    rows = json.loads(sweep_json.read_text(encoding="utf-8"))["configurations"]
    assert len(rows) == 3 * 2 * 2 * 2
    out = tmp_path / "arms.json"
    run("selectarms", {"SWEEP": str(sweep_json), "OUTPUT": str(out)})
    arms = {a["name"]: a for a in json.loads(out.read_text(encoding="utf-8"))["arms"]}
    assert list(arms) == ["max_f1", "max_recall", "lowest_review_burden"]
    # ties in the clustering axes (all four give the same clusters) go to the earliest row: eps 0.05, 2
    for name, threshold, recall, gmcf in (("max_f1", 0.4, 2 / 3, 2 / 3), ("max_recall", 0.3, 1.0, 3 / 7),
                                          ("lowest_review_burden", 0.5, 1 / 3, 1.0)):
        arm = arms[name]
        assert arm["checkpoint"] == "demo.onnx" and arm["model_digest"] == DIGEST
        assert arm["operating_point"] == {"threshold": threshold, "dedup_cm": 3.0, "eps_m": 0.05, "min_samples": 2,
                                          "eps_pred_m": 0.2, "edge_buffer_px": 0.0, "core_count": "detections"}
        assert arm["scores"]["recall_pre"] == pytest.approx(recall) and arm["scores"]["gmcf_pre"] == pytest.approx(gmcf)
    assert arms["lowest_review_burden"]["scores"]["detections_per_frame"] == 9.0
    with pytest.raises(QgsProcessingException, match="no 'configurations' list"):
        run("selectarms", {"SWEEP": str(out), "OUTPUT": str(tmp_path / "again.json")})


def test_sealpreregistration_seals_each_arm_with_its_own_operating_point(birdseye_provider, tmp_path):
    sweep_json = arms_sweep(tmp_path)
    arms = tmp_path / "arms.json"
    run("selectarms", {"SWEEP": str(sweep_json), "OUTPUT": str(arms)})
    checkpoint = tmp_path / "demo.onnx"
    checkpoint.write_bytes(b"demo model")                      # its SHA-256 is the detections' model_digest
    rule = tmp_path / "rule.json"
    sealed = run("sealpreregistration", {"ARMS": str(arms), "CHECKPOINTS": [str(checkpoint)], "OUTPUT": str(rule),
                                         "DESCRIPTIVE": str(sweep_json), "THRESHOLD": 0.9})
    doc = json.loads(rule.read_text(encoding="utf-8"))
    assert sealed["SEAL"] == doc["seal"] and doc["model_digests"] == [DIGEST]
    assert [(a["name"], a["operating_point"]["threshold"]) for a in doc["rule"]["arms"]] == [
        ("max_f1", 0.4), ("max_recall", 0.3), ("lowest_review_burden", 0.5)]       # THRESHOLD 0.9 is not used
    other = tmp_path / "other.onnx"
    other.write_bytes(b"another model")
    with pytest.raises(QgsProcessingException, match="none of the checkpoint files"):
        run("sealpreregistration", {"ARMS": str(arms), "CHECKPOINTS": [str(other)], "OUTPUT": str(rule)})
    typed = run("sealpreregistration", {"CHECKPOINTS": [str(checkpoint)], "EDGE_BUFFER_PX": 4.0, "CORE_COUNT": 1,
                                        "OUTPUT": str(rule),
                                        "ARM_LINES": "max_f1: demo.onnx, 0.05, 0.20, 2, 0.20\n"
                                                     "max_recall: demo.onnx, 0.03, 0.15, 5, 0.35"})
    doc = json.loads(rule.read_text(encoding="utf-8"))
    assert typed["SEAL"] == doc["seal"]
    assert doc["rule"]["arms"][1]["operating_point"] == {"threshold": 0.03, "dedup_cm": 3.0, "eps_m": 0.15,
                                                         "min_samples": 5, "eps_pred_m": 0.35, "edge_buffer_px": 4.0,
                                                         "core_count": "cells"}
    with pytest.raises(QgsProcessingException, match="not both"):
        run("sealpreregistration", {"ARMS": str(arms), "ARM_LINES": "x: demo.onnx, 0.05, 0.2, 2, 0.2",
                                    "CHECKPOINTS": [str(checkpoint)], "OUTPUT": str(rule)})
    with pytest.raises(QgsProcessingException, match="row 1.*not among CHECKPOINTS"):
        run("sealpreregistration", {"ARM_LINES": "x: nothere.onnx, 0.05, 0.2, 2, 0.2",
                                    "CHECKPOINTS": [str(checkpoint)], "OUTPUT": str(rule)})

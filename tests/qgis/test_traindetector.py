"""birdseye:traindetector through the Processing registry: a simulated campaign imported and labelled by
the plugin's own algorithms, a short training in a separate Python (.venv's, which has torch), the model
run by Detect targets; cancel leaves no process and no model but a checkpoint; a pretrained encoder from
a weights file made here. torch must never enter this (QGIS's) process."""
from __future__ import annotations

import json
import re
import subprocess
import sys
import time
from pathlib import Path

import pytest
from qgis.core import QgsProcessingException, QgsProcessingFeedback

from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig
from birdseye.birdseye_qgis.core.train.protocol import process_alive

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "unit" / "train"))
from fake_labels import make_label_folder  # noqa: E402
from registry import Recorder as Log
from registry import imported_campaign, run
from training_python import TRAINING_PYTHON, needs_training_python

pytestmark = needs_training_python


class Recorder(QgsProcessingFeedback):
    """Keeps what the algorithm reports; cancels at the first training progress when asked to."""

    def __init__(self, cancel_when_training: bool = False):
        super().__init__()
        self.infos, self.warnings, self.progress, self.pid = [], [], [], None
        self.cancel_when_training = cancel_when_training
        self.progressChanged.connect(self._progress)

    def pushInfo(self, info):  # noqa: N802 — QGIS's name
        self.infos.append(info)
        found = re.match(r"Training process (\d+) started", info)
        if found:
            self.pid = int(found[1])
        super().pushInfo(info)

    def pushWarning(self, warning):  # noqa: N802 — QGIS's name
        self.warnings.append(warning)
        super().pushWarning(warning)

    def _progress(self, value):
        self.progress.append(value)
        if self.cancel_when_training and value > 2.0 and not self.isCanceled():
            self.cancel()


@pytest.fixture(scope="module")
def campaign(birdseye_provider, tmp_path_factory):
    """A small simulated campaign (two frame footprints long: spatial blocks can be held out), imported, and its
    training labels with 96 px tiles."""
    folder = tmp_path_factory.mktemp("campaign")
    geotags, frames = imported_campaign(folder, CampaignConfig(seed=5, n_targets=14, field_width_m=12.0,
                                                               field_length_m=5.0, image_width=480, image_height=300))
    labels = folder / "labels"
    run("writelabels", {"GEOTAGS": geotags, "FRAMES": frames, "WRITE_RASTERS": False, "WRITE_TILES": True,
                        "TILE_SIZE": 96, "OUTPUT_FOLDER": str(labels), "OUTPUT_FRAMES": None,
                        "OUTPUT_GEOTAGS": None})
    return frames, labels


def test_trains_a_model_detect_accepts_without_torch_in_qgis(campaign, tmp_path):
    from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel

    frames, labels = campaign
    feedback = Recorder()
    out = tmp_path / "trained" / "mine.onnx"
    started = time.perf_counter()
    result = run("traindetector", {"LABELS": [str(labels / "summary.json")], "FRAMES": [frames], "MINUTES": 0.25,
                                   "VALIDATION_FRACTION": 0.25, "THREADS": 2, "PYTHON": TRAINING_PYTHON,
                                   "OUTPUT_MODEL": str(out)}, feedback)
    seconds = time.perf_counter() - started
    assert "torch" not in sys.modules, "QGIS's process imported torch"
    assert result["OUTPUT_MODEL"] == str(out) and out.is_file()
    model = HeatmapModel(str(out))  # onnxruntime session + BirdsEye metadata, validated
    assert model.metadata.resolution_cm == 1.0 and model.metadata.tile_size == 288
    assert 0.0 < model.metadata.default_threshold < 1.0 and model.metadata.label_sigma_px
    card = Path(result["MODEL_CARD"]).read_text(encoding="utf-8")
    assert "## Validation (held-out tiles, a diagnostic)" in card and "| threshold | recall |" in card
    assert "## Validation split" in card and "provenance" in card
    # Spatial blocks by default; the frame layer gives the held-out frames' poses: scored on the ground, or a
    # warning says why the threshold was not validated there.
    report = json.loads(out.with_name("mine.training.json").read_text(encoding="utf-8"))
    split = report["split"]
    assert split["method"] == "blocks" and report["settings"]["validation"] == "blocks"
    print(f"split: {split}; threshold {report['threshold']} ({report['threshold_rule']})")
    if split["held_out"]:
        ground = report["ground_validation"]
        # Scored on the ground: the held-out frames and those kept out of both tile sets for seeing both sides.
        assert ground["frames"] == split["frames"]["val"] + split["frames_dropped"] and ground["frames_skipped"] == 0
        assert "## Validation on the ground" in card and "| threshold | recall | GMCF |" in card
        assert report["validated_on"] == "ground" or any("not validated on the ground" in w
                                                         for w in report["warnings"])
    else:
        assert report["warnings"] and "not validated" in report["warnings"][0]
    if report["validated_on"] != "ground":
        assert feedback.warnings and "not validated" in " ".join(feedback.warnings)
    assert Path(result["PLOT"]).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert Path(result["CHECKPOINT"]).is_file() and not out.with_name("mine.checkpoint.pt").exists()
    assert result["TILES"] > 0 and result["TILES_PER_SECOND"] > 0
    assert len(feedback.progress) >= 5 and max(feedback.progress) == 100
    assert any(" step " in line and "validation" in line for line in feedback.infos), "loss points were relayed"
    assert feedback.pid is not None and not process_alive(feedback.pid)
    assert not list(out.parent.glob(".*.tmp*")), "no temporary file left"
    print(f"traindetector: {seconds:.1f} s for a {0.25 * 60:.0f} s budget")
    detections = run("detect", {"FRAMES": frames, "MODEL": str(out), "OUTPUT": "TEMPORARY_OUTPUT"})
    assert detections["FRAMES_PROCESSED"] > 0 and detections["MODEL_DIGEST"] == model.digest
    assert "torch" not in sys.modules


def test_cancel_ends_the_process_keeps_a_checkpoint_and_writes_no_model(tmp_path):
    labels = make_label_folder(tmp_path / "labels", n_frames=6)
    out = tmp_path / "cancelled.onnx"
    feedback = Recorder(cancel_when_training=True)
    started = time.perf_counter()
    with pytest.raises(QgsProcessingException, match="Cancelled by the user; no model was written.*checkpoint"):
        run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 1.0, "MINUTES": 5, "THREADS": 2,
                              "PYTHON": TRAINING_PYTHON, "OUTPUT_MODEL": str(out)}, feedback)
    assert time.perf_counter() - started < 120, "a 5-minute budget was not cut short"
    assert feedback.pid is not None and not process_alive(feedback.pid), "the training process is still there"
    assert not out.exists() and not list(tmp_path.glob("*.onnx")) and not list(tmp_path.glob(".*.tmp*"))
    assert (tmp_path / "cancelled.checkpoint.pt").is_file(), "the last good checkpoint is kept"
    assert "torch" not in sys.modules


def test_a_pretrained_encoder_from_a_weights_file(tmp_path):
    weights = tmp_path / "resnet18_random.pth"
    script = ("import sys, torch; sys.path.insert(0, sys.argv[2]); from birdseye_qgis.core.train.recipe import "
              "import_torchvision; tv = import_torchvision(); torch.manual_seed(0); "
              "torch.save(tv.models.resnet18(weights=None).state_dict(), sys.argv[1])")
    subprocess.run([TRAINING_PYTHON, "-c", script, str(weights), str(Path(__file__).resolve().parents[2])],
                   check=True, timeout=120)
    labels = make_label_folder(tmp_path / "labels", n_frames=4)
    out = tmp_path / "pretrained.onnx"
    result = run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 1.0, "BACKBONE": 6, "WEIGHTS": str(weights),
                                   "MINUTES": 0.1, "THREADS": 2, "PYTHON": TRAINING_PYTHON, "OUTPUT_MODEL": str(out)})
    report = json.loads(out.with_name("pretrained.training.json").read_text(encoding="utf-8"))
    assert report["settings"]["backbone"] == "resnet18" and report["settings"]["weights"] == str(weights)
    assert report["metadata"]["standardization_mean"] == [0.485, 0.456, 0.406]
    assert result["OUTPUT_MODEL"] == str(out) and "torch" not in sys.modules


def test_missing_weights_and_missing_torch_say_what_to_do(tmp_path):
    labels = make_label_folder(tmp_path / "labels", n_frames=3)
    with pytest.raises(QgsProcessingException, match="does not exist"):
        run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 1.0, "BACKBONE": 1, "MINUTES": 0.1,
                              "WEIGHTS": str(tmp_path / "nowhere.pth"), "PYTHON": TRAINING_PYTHON,
                              "OUTPUT_MODEL": str(tmp_path / "m.onnx")})
    with pytest.raises(QgsProcessingException, match=r"Install dependencies….*PyTorch \(training\).*pip install"):
        run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 1.0, "MINUTES": 0.1, "PYTHON": "/usr/bin/python3",
                              "OUTPUT_MODEL": str(tmp_path / "m.onnx")})
    assert not (tmp_path / "m.onnx").exists()


def in_a_model(labels_expression: str, others: dict):
    """A Graphical Modeler model running traindetector alone, LABELS given by an expression, the rest as values."""
    from qgis.core import (
        QgsProcessingModelAlgorithm,
        QgsProcessingModelChildAlgorithm,
        QgsProcessingModelChildParameterSource,
    )

    model = QgsProcessingModelAlgorithm("train", "tests")
    child = QgsProcessingModelChildAlgorithm("birdseye:traindetector")
    child.setChildId("train")
    child.addParameterSources("LABELS", [QgsProcessingModelChildParameterSource.fromExpression(labels_expression)])
    for name, value in others.items():
        child.addParameterSources(name, [QgsProcessingModelChildParameterSource.fromStaticValue(value)])
    model.addChildAlgorithm(child)
    return model


def test_labels_and_numbers_from_the_modeler_and_expressions(birdseye_provider, tmp_path):
    """LABELS as the Graphical Modeler passes it (an expression's array of folders, or text joining them), read
    through the Processing API; an empty THRESHOLD or RESOLUTION_CM is "not given", not 0. Training stops at the
    missing PyTorch (after the inputs were read), or at the folder that is not a labels folder."""
    import processing
    from qgis.core import QgsApplication, QgsProcessingContext, QgsProperty

    labels = make_label_folder(tmp_path / "labels", n_frames=2)
    no_torch = {"GSD_CM": 1.0, "MINUTES": 0.1, "PYTHON": "/usr/bin/python3", "OUTPUT_MODEL": str(tmp_path / "m.onnx")}
    for value in (f"{labels};{labels / 'summary.json'}", [str(labels), str(labels / "summary.json")]):
        with pytest.raises(QgsProcessingException, match="PyTorch"):
            run("traindetector", {"LABELS": value, **no_torch})
    elsewhere = tmp_path / "elsewhere"
    elsewhere.mkdir()
    for expression, expected in ((f"array('{labels}', '{labels / 'summary.json'}')", "PyTorch"),
                                 (f"array('{labels}', '{elsewhere}')",
                                  re.escape(str(elsewhere)) + ".*not a Write training labels")):
        log = Log()  # a model reports its child's error in the log
        with pytest.raises(QgsProcessingException):
            processing.run(in_a_model(expression, no_torch), {}, feedback=log)
        assert any(re.search(expected, error) for error in log.errors), (expected, log.errors)

    # An expression (QgsProperty) reaches the algorithm's reader resolved: Processing's own check refuses one for
    # LABELS in a run (QGIS 3.22), and a model hands over its evaluated array, as above; QGIS 3.22 reads an
    # expression's value as text, which may join paths with ";".
    alg = QgsApplication.processingRegistry().createAlgorithmById("birdseye:traindetector")
    context = QgsProcessingContext()
    property_ = QgsProperty.fromExpression(f"'{labels / 'summary.json'}' || ';' || '{labels}'")
    assert alg._label_folders({"LABELS": property_}, context) == [labels, labels]
    for value, expected in ((None, None), ("", None), (0.35, 0.35), (0.0, 0.0),
                            (QgsProperty.fromExpression("0.1 + 0.2"), 0.3), (QgsProperty.fromExpression("NULL"), None)):
        got = alg._optional_double({"THRESHOLD": value}, "THRESHOLD", context)
        assert (got == pytest.approx(expected)) if expected is not None else got is None, value
    assert alg._optional_double({}, "RESOLUTION_CM", context) is None


def test_init_takes_the_earlier_models_resolution_and_refuses_another(birdseye_provider, tmp_path):
    """A model trained at 1.25 cm/px; fine-tuned from it with RESOLUTION_CM empty: 1.25 cm/px and its
    normalisation; with RESOLUTION_CM 1: refused, naming both."""
    from qgis.core import QgsProperty

    from birdseye.birdseye_qgis.core.detect.model_metadata import read_onnx_metadata

    labels = make_label_folder(tmp_path / "labels", n_frames=3)
    common = {"LABELS": [str(labels)], "GSD_CM": 1.0, "MINUTES": 0.05, "VALIDATION_FRACTION": 0.0, "THREADS": 2,
              "PYTHON": TRAINING_PYTHON}
    first = run("traindetector", {**common, "RESOLUTION_CM": 1.25, "OUTPUT_MODEL": str(tmp_path / "first.onnx")})
    again = run("traindetector", {**common, "INIT": first["CHECKPOINT"], "OUTPUT_MODEL": str(tmp_path / "again.onnx"),
                                  "THRESHOLD": QgsProperty.fromExpression("NULL")})
    assert again["THRESHOLD_USED"] == 0.5, "an expression giving NULL leaves THRESHOLD empty (no held-out targets)"
    before, after = read_onnx_metadata(first["OUTPUT_MODEL"]), read_onnx_metadata(again["OUTPUT_MODEL"])
    assert after.resolution_cm == 1.25 and after.standardization_mean == before.standardization_mean
    assert after.class_names == ("burrow",)
    with pytest.raises(QgsProcessingException, match=r"first\.onnx.*trained at 1\.25 cm/px.*asked for is 1 cm/px"):
        run("traindetector", {**common, "INIT": first["OUTPUT_MODEL"], "RESOLUTION_CM": 1.0,
                              "OUTPUT_MODEL": str(tmp_path / "refused.onnx")})
    assert not (tmp_path / "refused.onnx").exists() and "torch" not in sys.modules


def test_the_method_preset_trains_on_the_cpu_and_its_card_names_it(birdseye_provider, tmp_path, monkeypatch):
    """PRESET 1 (the method): EfficientNetV2-S from random initialisation (no weights file, an empty torch
    hub folder), at the frames' own GSD, a 3-second budget (a step or two of each stage); the card and
    training JSON name the preset, its settings and what ended the run."""
    from birdseye.birdseye_qgis.core.train.preset import PRESETS
    from birdseye.processing.algorithms.traindetector import PRESET_LABELS

    assert PRESET_LABELS == tuple(p.title for p in PRESETS), "PRESET lists core.train.preset.PRESETS in order"
    monkeypatch.setenv("TORCH_HOME", str(tmp_path / "torch"))  # the child finds no cached ImageNet weights
    labels = make_label_folder(tmp_path / "labels", n_frames=4)
    out = tmp_path / "method.onnx"
    result = run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 0.5, "PRESET": 1, "MINUTES": 0.05,
                                   "THREADS": 2, "PYTHON": TRAINING_PYTHON, "OUTPUT_MODEL": str(out)})
    assert "torch" not in sys.modules and out.is_file()
    report = json.loads(out.with_name("method.training.json").read_text(encoding="utf-8"))
    settings, history = report["settings"], report["history"]
    assert settings["preset"] == "method" and settings["backbone"] == "efficientnet_v2_s"
    assert settings["resolution_cm"] == 0.5 and settings["crop_px"] == 224 and settings["positive_weight"] == 0
    assert [s["stage"] for s in history["stages"]] == ["frozen-encoder", "fine-tune"]
    assert history["ended_by"] in ("time budget", "early stopping") and history["unfrozen_blocks"] == 8
    card = Path(result["MODEL_CARD"]).read_text(encoding="utf-8")
    assert "**Method (EfficientNetV2, two stages, AdamW)** (`method`)" in card
    assert "NOT ImageNet-pretrained" in card and "The run was ended by" in card and "not resampled" in card


def test_nothing_held_out_is_a_warning_and_leaves_the_ground_figures_empty(birdseye_provider, tmp_path):
    labels = make_label_folder(tmp_path / "labels", n_frames=3)
    feedback = Recorder()
    out = tmp_path / "unvalidated.onnx"
    result = run("traindetector", {"LABELS": [str(labels)], "GSD_CM": 1.0, "VALIDATION": 2, "MINUTES": 0.05,
                                   "THREADS": 2, "PYTHON": TRAINING_PYTHON, "OUTPUT_MODEL": str(out)}, feedback)
    assert result["THRESHOLD_USED"] == 0.5 and result["VALIDATION_RECALL"] is None
    assert any("Nothing was held out for validation (no validation was asked for)" in w for w in feedback.warnings)
    report = json.loads(out.with_name("unvalidated.training.json").read_text(encoding="utf-8"))
    assert report["settings"]["validation"] == "none" and report["validated_on"] is None
    assert "torch" not in sys.modules

"""Which sealed arm scores a set of detection layers: one model the rule names, the arm named when several
share it, and every layer detected at the arm's sealed threshold."""
import hashlib

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.scoring import preregistration as prereg
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

DIGEST_A = hashlib.sha256(b"checkpoint A").hexdigest()
DIGEST_B = hashlib.sha256(b"checkpoint B").hexdigest()


def sealed_rule():
    """Arms max_f1 (A at 0.05) and max_recall (A at 0.03) share checkpoint A; B has one arm at 0.12."""
    arms = [prereg.make_arm("a.onnx", DIGEST_A, OperatingPoint(0.05, 3.0, 0.2, 2, 0.2), "max_f1"),
            prereg.make_arm("a.onnx", DIGEST_A, OperatingPoint(0.03, 3.0, 0.15, 5, 0.35), "max_recall"),
            prereg.make_arm("b.onnx", DIGEST_B, OperatingPoint(0.12, 3.0, 0.1, 20, 0.2), "lowest_review_burden")]
    return prereg.seal({"arms": arms}, sealed_at="2024-05-01T09:30:00Z")


def layer(name, digest, threshold):
    return Detections(np.zeros(1), np.zeros(1), np.zeros(1), np.zeros(1), np.full(1, 0.9), name=name,
                      model_digest=digest, threshold=threshold)


def test_the_named_arm_scores_layers_detected_at_its_own_threshold():
    doc = sealed_rule()
    arm, op = prereg.arm_for_detections(doc, [layer("f1", DIGEST_A, 0.03), layer("f2", DIGEST_A, 0.03)],
                                        arm_name="max_recall")
    assert arm["name"] == "max_recall" and op == OperatingPoint(0.03, 3.0, 0.15, 5, 0.35, 0.0)
    # a threshold read back from a layer's double field is still the sealed one
    assert prereg.arm_for_detections(doc, [layer("f1", DIGEST_A, 0.05 + 1e-15)], arm_name="max_f1")[0]["name"] \
        == "max_f1"
    assert prereg.arm_for_detections(doc, [layer("f1", DIGEST_B, 0.12)])[1].min_samples == 20


def test_arms_sharing_a_checkpoint_must_be_named():
    with pytest.raises(prereg.SealError, match="seals 2 arms .*max_f1, max_recall.*say which arm to score \\(ARM\\)"):
        prereg.arm_for_detections(sealed_rule(), [layer("f1", DIGEST_A, 0.05)])


@pytest.mark.parametrize("threshold", [0.03, 0.07])
def test_a_layer_detected_at_another_threshold_is_refused_not_filtered(threshold):
    """Below the sealed threshold a score filter would merge blobs that split at 0.05; above it,
    detections between the two were never made: both are refused, naming the layer and the rerun."""
    with pytest.raises(prereg.SealError, match=f"^f2, field 'threshold': was detected at threshold {threshold:g}, "
                                               "but arm 'max_f1' is sealed at 0.05.*THRESHOLD 0.05"):
        prereg.arm_for_detections(sealed_rule(), [layer("f1", DIGEST_A, 0.05), layer("f2", DIGEST_A, threshold)],
                                  arm_name="max_f1")


def test_layers_without_threshold_digest_or_of_several_models_are_refused():
    doc = sealed_rule()
    with pytest.raises(prereg.SealError, match="^f1, field 'threshold': records no detection threshold.*0.12"):
        prereg.arm_for_detections(doc, [layer("f1", DIGEST_B, None)])
    with pytest.raises(prereg.SealError, match="has no model_digest"):
        prereg.arm_for_detections(doc, [layer("f1", "", 0.12)])
    with pytest.raises(prereg.SealError, match="different models"):
        prereg.arm_for_detections(doc, [layer("f1", DIGEST_A, 0.05), layer("f2", DIGEST_B, 0.12)])
    with pytest.raises(prereg.SealError, match="no arm 'max_f1' for model"):
        prereg.arm_for_detections(doc, [layer("f1", DIGEST_B, 0.12)], arm_name="max_f1")

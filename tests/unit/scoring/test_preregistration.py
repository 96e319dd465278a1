"""Sealed selection rules: canonical form, the seal, and refusal of tampered or mismatched rules."""
import hashlib
import json

import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.scoring import preregistration as prereg
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

DIGEST_A = hashlib.sha256(b"checkpoint A").hexdigest()
DIGEST_B = hashlib.sha256(b"checkpoint B").hexdigest()
SEALED_AT = "2024-05-01T09:30:00Z"


def rule():
    return {"arms": [prereg.make_arm("models/a.onnx", DIGEST_A, OperatingPoint(0.45, 3, 0.1, 3, 0.2)),
                     prereg.make_arm("b.onnx", DIGEST_B, OperatingPoint(0.6, 3, 0.12, 4, 0.2, 5))],
            "descriptive": [{"threshold": 0.3, "recall_pre": 0.91, "gmcf_pre": 0.42}],
            "note": "Arms chosen on flights 1–3; scored on flight 4 only. Überprüft."}


def test_seal_is_sha256_of_the_canonical_json_of_rule_digests_and_time():
    doc = prereg.seal(rule(), sealed_at=SEALED_AT)
    payload = {"schema": prereg.SCHEMA, "rule": doc["rule"], "model_digests": sorted([DIGEST_A, DIGEST_B]),
               "sealed_at": SEALED_AT}
    independent = json.dumps(payload, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    assert doc["seal"] == hashlib.sha256(independent.encode("utf-8")).hexdigest()
    assert doc["rule"]["arms"][0]["checkpoint"] == "a.onnx"
    assert doc["rule"]["arms"][1]["operating_point"] == {"threshold": 0.6, "dedup_cm": 3.0, "eps_m": 0.12,
                                                         "min_samples": 4, "eps_pred_m": 0.2,
                                                         "edge_buffer_px": 5.0, "core_count": "detections"}


def test_canonical_json_ignores_key_order_and_refuses_nan():
    assert prereg.canonical_json({"b": 1, "a": [1.5, "é"]}) == prereg.canonical_json({"a": [1.5, "é"], "b": 1})
    assert prereg.canonical_json({"a": [1.5, "é"]}) == '{"a":[1.5,"é"]}'
    with pytest.raises(prereg.SealError, match="non-finite"):
        prereg.canonical_json({"a": float("nan")})


def test_written_rule_reads_back_verified(tmp_path):
    doc = prereg.seal(rule(), sealed_at=SEALED_AT)
    path = tmp_path / "rule.json"
    prereg.write(doc, path)
    back = prereg.read(path)
    assert back == doc
    arm, op = prereg.arm_for(back, DIGEST_B)
    assert arm["name"] == "b" and op == OperatingPoint(0.6, 3, 0.12, 4, 0.2, 5)


def test_every_single_byte_change_is_refused_or_changes_nothing(tmp_path):
    """Tamper with one byte at every position of the sealed file: reading either refuses it, or (for a
    change that JSON ignores) yields exactly the sealed content."""
    doc = prereg.seal(rule(), sealed_at=SEALED_AT)
    path = tmp_path / "rule.json"
    prereg.write(doc, path)
    original = path.read_bytes()
    reference = prereg.canonical_json(doc)
    refused = 0
    for i, byte in enumerate(original):
        ch = chr(byte)
        repl = str((int(ch) + 1) % 10) if ch.isdigit() else ("b" if ch == "a" else "a") if ch.isalpha() else "x"
        path.write_bytes(original[:i] + repl.encode() + original[i + 1:])
        try:
            got = prereg.read(path)
        except prereg.SealError:
            refused += 1
            continue
        assert prereg.canonical_json(got) == reference, f"byte {i} changed the content without refusal"
    assert refused == len(original)


@pytest.mark.parametrize("edit", ["threshold", "time", "digest", "seal", "extra_key", "arm_removed"])
def test_edited_documents_are_refused(edit):
    doc = json.loads(json.dumps(prereg.seal(rule(), sealed_at=SEALED_AT)))
    if edit == "threshold":
        doc["rule"]["arms"][0]["operating_point"]["threshold"] = 0.4
    elif edit == "time":
        doc["sealed_at"] = "2024-05-02T09:30:00Z"
    elif edit == "digest":
        doc["model_digests"][0] = DIGEST_A.replace(DIGEST_A[0], "f" if DIGEST_A[0] != "f" else "e", 1)
    elif edit == "seal":
        doc["seal"] = doc["seal"][:-1] + ("0" if doc["seal"][-1] != "0" else "1")
    elif edit == "extra_key":
        doc["comment"] = "added later"
    else:
        doc["rule"]["arms"].pop()
    with pytest.raises(prereg.SealError):
        prereg.verify(doc)


def test_resealed_document_with_inconsistent_digests_is_refused():
    doc = prereg.seal(rule(), sealed_at=SEALED_AT)
    doc["model_digests"] = [DIGEST_A]
    doc["seal"] = prereg.seal_digest(doc)
    with pytest.raises(prereg.SealError, match="do not match the arms"):
        prereg.verify(doc)


def test_a_model_the_rule_never_named_is_refused():
    doc = prereg.seal(rule(), sealed_at=SEALED_AT)
    other = hashlib.sha256(b"another model").hexdigest()
    with pytest.raises(prereg.SealError, match="does not name"):
        prereg.arm_for(doc, other)
    with pytest.raises(prereg.SealError, match="not one of the sealed checkpoints"):
        prereg.check_checkpoint_files(doc, ["c.onnx"], lambda p: other)
    prereg.check_checkpoint_files(doc, ["a.onnx"], lambda p: DIGEST_A)


def test_rules_without_arms_or_threshold_cannot_be_sealed(tmp_path):
    with pytest.raises(prereg.SealError, match="at least one arm"):
        prereg.seal({"arms": []})
    with pytest.raises(prereg.SealError, match="threshold"):
        prereg.make_arm("a.onnx", DIGEST_A, OperatingPoint())
    with pytest.raises(prereg.SealError, match="SHA-256"):
        prereg.make_arm("a.onnx", "abc", OperatingPoint(0.5))
    (tmp_path / "x.json").write_text("{not json", encoding="utf-8")
    with pytest.raises(prereg.SealError, match="not valid JSON"):
        prereg.read(tmp_path / "x.json")
    assert prereg.seal(rule())["sealed_at"].endswith("Z")


# -------------------------------------------------------------------- a different operating point per arm
def selected_arms():
    point = {"dedup_cm": 3.0, "edge_buffer_px": 0.0, "core_count": "detections"}
    return [{"name": "max_f1", "checkpoint": "a.onnx", "model_digest": DIGEST_A,
             "operating_point": {"threshold": 0.05, "eps_m": 0.2, "min_samples": 2, "eps_pred_m": 0.2, **point}},
            {"name": "max_recall", "checkpoint": "a.onnx", "model_digest": DIGEST_A,
             "operating_point": {"threshold": 0.03, "eps_m": 0.15, "min_samples": 5, "eps_pred_m": 0.35, **point}},
            {"name": "lowest_review_burden", "checkpoint": "b.onnx", "model_digest": DIGEST_B,
             "operating_point": {"threshold": 0.12, "eps_m": 0.1, "min_samples": 20, "eps_pred_m": 0.2, **point}}]


def test_three_arms_each_sealed_with_its_own_operating_point():
    arms = prereg.arms_from_selection(selected_arms(), {"a.onnx": DIGEST_A, "b.onnx": DIGEST_B})
    doc = prereg.verify(json.loads(json.dumps(prereg.seal({"arms": arms}, sealed_at=SEALED_AT))))
    assert doc["model_digests"] == sorted([DIGEST_A, DIGEST_B])
    assert [a["operating_point"]["threshold"] for a in doc["rule"]["arms"]] == [0.05, 0.03, 0.12]
    # two arms share checkpoint A: scoring its detections must say which arm
    with pytest.raises(prereg.SealError, match="seals 2 arms for model .*max_f1, max_recall.*say which arm"):
        prereg.arm_for(doc, DIGEST_A)
    arm, op = prereg.arm_for(doc, DIGEST_A, arm_name="max_recall")
    assert op == OperatingPoint(0.03, 3.0, 0.15, 5, 0.35, 0.0)
    assert prereg.arm_for(doc, DIGEST_B)[1].min_samples == 20
    with pytest.raises(prereg.SealError, match="no arm 'max_f1' for model"):
        prereg.arm_for(doc, DIGEST_B, arm_name="max_f1")


def test_arms_must_match_the_checkpoint_files_and_carry_distinct_names():
    with pytest.raises(prereg.SealError, match="'lowest_review_burden' is checkpoint b.onnx.*none of the"):
        prereg.arms_from_selection(selected_arms(), {"a.onnx": DIGEST_A})
    arms = prereg.arms_from_selection(selected_arms())
    arms[1]["name"] = "max_f1"
    with pytest.raises(prereg.SealError, match="arm 2 has the name 'max_f1' of an earlier arm"):
        prereg.seal({"arms": arms})


def test_typed_arm_lines():
    text = ("# chosen on flights 1-3\n"
            "max_f1: a.onnx, 0.05, 0.20, 2, 0.20\n\n"
            "max_recall: /models/a.onnx, 0.03, 0.15, 5, 0.35\n")
    arms = prereg.parse_arm_lines(text, {"a.onnx": DIGEST_A}, dedup_cm=3.0, edge_buffer_px=4.0)
    assert [a["name"] for a in arms] == ["max_f1", "max_recall"]
    assert arms[1]["operating_point"] == {"threshold": 0.03, "dedup_cm": 3.0, "eps_m": 0.15, "min_samples": 5,
                                          "eps_pred_m": 0.35, "edge_buffer_px": 4.0, "core_count": "detections"}
    cells = prereg.parse_arm_lines(text, {"a.onnx": DIGEST_A}, 3.0, 4.0, core_count="cells")
    assert {a["operating_point"]["core_count"] for a in cells} == {"cells"}
    for bad, message in (("max_f1 a.onnx, 0.05, 0.2, 2, 0.2", "row 1.*is not 'name: checkpoint"),
                         ("x: c.onnx, 0.05, 0.2, 2, 0.2", "row 1.*'c.onnx', which is not among CHECKPOINTS"),
                         ("\nx: a.onnx, 0.05, wide, 2, 0.2", "row 2.*must be numbers"),
                         ("x: a.onnx, 0.05, 0.2, 2.5, 0.2", "whole number"),
                         ("x: a.onnx, 1.5, 0.2, 2, 0.2", "THRESHOLD"),
                         ("# nothing", "holds no arm line")):
        with pytest.raises(InputError, match=message):
            prereg.parse_arm_lines(bad, {"a.onnx": DIGEST_A}, 3.0, 0.0)


# -------------------------------------------------------------------- rules sealed before core_count existed
def test_a_rule_sealed_before_core_count_was_recorded_verifies_and_scores_counting_cells(tmp_path):
    """Such a rule's operating points have no core_count; its arms were chosen on figures computed
    counting cells. It must still verify byte for byte (nothing rewritten) and score at what was sealed."""
    point = {"threshold": 0.035, "dedup_cm": 3.0, "eps_m": 0.2, "min_samples": 2, "eps_pred_m": 0.2,
             "edge_buffer_px": 0.0}
    sealed = {"schema": "birdseye-preregistration/1",
              "rule": {"arms": [{"name": "lowest_review_burden", "checkpoint": "a.onnx", "model_digest": DIGEST_A,
                                 "operating_point": point}], "descriptive": [], "note": ""},
              "model_digests": [DIGEST_A], "sealed_at": SEALED_AT}
    payload = json.dumps(sealed, sort_keys=True, separators=(",", ":"), ensure_ascii=False)
    sealed["seal"] = hashlib.sha256(payload.encode("utf-8")).hexdigest()
    path = tmp_path / "old_rule.json"
    path.write_text(json.dumps(sealed, indent=2), encoding="utf-8")
    doc = prereg.read(path)
    assert doc == sealed and "core_count" not in doc["rule"]["arms"][0]["operating_point"]
    arm, op = prereg.arm_for(doc, DIGEST_A)
    assert op == OperatingPoint(0.035, 3.0, 0.2, 2, 0.2, 0.0, core_count="cells")
    # Resealing its arms (e.g. from an old arms file) writes the cells out explicitly.
    resealed = prereg.seal({"arms": prereg.arms_from_selection(doc["rule"]["arms"])}, sealed_at=SEALED_AT)
    assert resealed["rule"]["arms"][0]["operating_point"]["core_count"] == "cells"


def test_an_operating_point_with_an_unknown_core_count_is_refused():
    with pytest.raises(InputError, match="arm x.*core_count is 'points'"):
        OperatingPoint.from_dict({"threshold": 0.1, "core_count": "points"}, source="arm x")
    with pytest.raises(InputError, match="CORE_COUNT"):
        OperatingPoint(0.1, core_count="points")

"""Sealed selection rules: canonical form, the seal, and refusal of tampered or mismatched rules."""
import hashlib
import json

import pytest

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
                                                         "edge_buffer_px": 5.0}


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

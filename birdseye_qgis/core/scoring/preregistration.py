"""Preregistered selection rules: canonical JSON sealed with SHA-256, verified before scoring.

A *rule* says, before a held-out flight is scored, which detector and operating point will be
judged: its **arms** (checkpoint file digest + the full operating point) and, for the record, the
**descriptive** configurations looked at while choosing (reported, never used to decide).

The sealed document (one JSON file)::

    {"schema": "birdseye-preregistration/1",
     "rule": {"arms": [{"name": str, "checkpoint": str, "model_digest": sha256 hex,
                        "operating_point": {threshold, dedup_cm, eps_m, min_samples, eps_pred_m,
                                            edge_buffer_px}}, ...],
              "descriptive": [...], "note": str},
     "model_digests": [sorted sha256 hex of every arm's checkpoint],
     "sealed_at": "YYYY-MM-DDTHH:MM:SSZ",
     "seal": sha256 hex}

``seal = SHA-256(canonical_json({"schema", "rule", "model_digests", "sealed_at"}))`` where
:func:`canonical_json` is UTF-8 JSON with sorted keys, no insignificant whitespace, no NaN, and
floats in Python's shortest round-trip form. Changing any byte of what the seal covers — or the seal
itself — makes :func:`verify` refuse the document.

The seal shows that the rule was not edited after it was sealed *provided its hex value was recorded
somewhere the analyst cannot rewrite* (an e-mail, a lab notebook, a commit): a hash is not a
signature, anyone can re-seal an edited rule. The help text says so.
"""
from __future__ import annotations

import hashlib
import hmac
import json
import math
from datetime import datetime, timezone
from pathlib import Path

from ..errors import InputError
from .operating_point import OperatingPoint

SCHEMA = "birdseye-preregistration/1"
_SEALED_KEYS = ("schema", "rule", "model_digests", "sealed_at")
_HEX = set("0123456789abcdef")


class SealError(InputError):
    """A preregistration that is tampered with, malformed, or does not match what is scored."""


def canonical_json(obj) -> str:
    """The one byte-exact JSON form a seal is computed over (sorted keys, compact, no NaN)."""
    _check_finite(obj)
    return json.dumps(obj, sort_keys=True, separators=(",", ":"), ensure_ascii=False, allow_nan=False)


def _check_finite(obj, path="rule"):
    if isinstance(obj, float) and not math.isfinite(obj):
        raise SealError(f"holds a non-finite number at {path}; a sealed rule must be plain JSON")
    if isinstance(obj, dict):
        for k, v in obj.items():
            if not isinstance(k, str):
                raise SealError(f"has a non-text key {k!r} at {path}")
            _check_finite(v, f"{path}.{k}")
    elif isinstance(obj, (list, tuple)):
        for i, v in enumerate(obj):
            _check_finite(v, f"{path}[{i}]")


def seal_digest(document: dict) -> str:
    """SHA-256 hex of the canonical JSON of the sealed part of a document."""
    return hashlib.sha256(canonical_json({k: document[k] for k in _SEALED_KEYS}).encode("utf-8")).hexdigest()


def _is_digest(value) -> bool:
    return isinstance(value, str) and len(value) == 64 and set(value) <= _HEX


def make_arm(checkpoint: str, model_digest: str, op: OperatingPoint, name: str | None = None) -> dict:
    """One arm: a checkpoint (file name and SHA-256) with its full operating point."""
    if not _is_digest(model_digest):
        raise SealError(f"'{model_digest}' is not a SHA-256 digest (64 lower-case hex digits)",
                        field="model_digest")
    if op.threshold is None:
        raise SealError("an arm's operating point needs its detection threshold", field="THRESHOLD")
    return {"name": name or Path(checkpoint).stem, "checkpoint": Path(checkpoint).name,
            "model_digest": model_digest, "operating_point": op.to_dict()}


def seal(rule: dict, sealed_at: str | None = None) -> dict:
    """A sealed document for ``rule`` (a dict with "arms", optional "descriptive" and "note")."""
    arms = rule.get("arms") or []
    if not arms:
        raise SealError("a selection rule needs at least one arm (checkpoint + operating point)")
    if sealed_at is None:
        sealed_at = datetime.now(timezone.utc).replace(microsecond=0).strftime("%Y-%m-%dT%H:%M:%SZ")
    rule = json.loads(canonical_json({"arms": list(arms), "descriptive": list(rule.get("descriptive", [])),
                                      "note": str(rule.get("note", ""))}))
    _check_rule(rule, "rule")
    document = {"schema": SCHEMA, "rule": rule,
                "model_digests": sorted({a["model_digest"] for a in rule["arms"]}), "sealed_at": sealed_at}
    document["seal"] = seal_digest(document)
    return document


def _check_rule(rule, source: str) -> None:
    if not isinstance(rule, dict) or not isinstance(rule.get("arms"), list) or not rule["arms"]:
        raise SealError("has no arms", source=source)
    for i, arm in enumerate(rule["arms"], start=1):
        if not isinstance(arm, dict) or not _is_digest(arm.get("model_digest")):
            raise SealError(f"arm {i} has no valid model_digest", source=source)
        OperatingPoint.from_dict(arm.get("operating_point") or {}, source=f"{source}, arm {i}")


def write(document: dict, path) -> None:
    Path(path).write_text(json.dumps(document, indent=2, sort_keys=True, ensure_ascii=False) + "\n",
                          encoding="utf-8")


def read(path) -> dict:
    """A sealed document, verified (:func:`verify`)."""
    path = Path(path)
    try:
        text = path.read_bytes().decode("utf-8")
        document = json.loads(text)
    except FileNotFoundError as exc:
        raise SealError("file not found", source=str(path)) from exc
    except (UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise SealError(f"is not valid JSON any more ({exc}); the preregistration was damaged or edited",
                        source=str(path)) from exc
    return verify(document, source=str(path))


def verify(document, source: str = "preregistration") -> dict:
    """Return the document if its seal matches its content, else raise :class:`SealError`."""
    if not isinstance(document, dict) or document.get("schema") != SCHEMA:
        raise SealError(f"is not a BirdsEye preregistration (schema '{SCHEMA}')", source=source)
    missing = [k for k in _SEALED_KEYS + ("seal",) if k not in document]
    if missing:
        raise SealError(f"lacks {', '.join(missing)}", source=source)
    extra = set(document) - set(_SEALED_KEYS) - {"seal"}
    if extra:
        raise SealError(f"has unsealed key(s) {', '.join(sorted(extra))}", source=source)
    claimed = document["seal"]
    try:
        actual = seal_digest(document)
    except (TypeError, ValueError) as exc:
        raise SealError(f"cannot be put in canonical form ({exc})", source=source) from exc
    if not isinstance(claimed, str) or not hmac.compare_digest(claimed, actual):
        raise SealError("seal does not match its content: the rule, the model digests or the time were "
                        "changed after sealing (refused)", source=source)
    _check_rule(document["rule"], source)
    if sorted({a["model_digest"] for a in document["rule"]["arms"]}) != document["model_digests"]:
        raise SealError("model_digests do not match the arms' checkpoints", source=source)
    return document


def arm_for(document: dict, model_digest: str, source: str = "preregistration") -> tuple[dict, OperatingPoint]:
    """The arm sealed for a model digest, and its operating point; refuses a model the rule never named."""
    for arm in document["rule"]["arms"]:
        if arm["model_digest"] == model_digest:
            return arm, OperatingPoint.from_dict(arm["operating_point"], source=source)
    names = ", ".join(f"{a['name']} ({a['model_digest'][:12]}…)" for a in document["rule"]["arms"])
    raise SealError(f"the detections come from model {model_digest[:12] or '(no digest)'}…, which the sealed "
                    f"rule does not name (arms: {names}); refusing to score", source=source)


def check_checkpoint_files(document: dict, paths, digest_of) -> None:
    """Refuse checkpoint files whose SHA-256 (``digest_of(path)``) is not among the sealed digests."""
    sealed = set(document["model_digests"])
    for p in paths:
        d = digest_of(p)
        if d not in sealed:
            raise SealError(f"has digest {d[:12]}…, not one of the sealed checkpoints", source=str(p))

"""Preregistered selection rules: canonical JSON sealed with SHA-256, verified before scoring.

A *rule* says, before a held-out flight is scored, which detector and operating point will be
judged: its **arms** (checkpoint file digest + the full operating point of that arm; several arms may
share a checkpoint at different operating points, as the method's three arms often do) and, for the
record, the **descriptive** configurations looked at while choosing (reported, never used to decide).
Arms come from an arms file of ``selectarms`` (:func:`arms_from_selection`), from typed lines
(:func:`parse_arm_lines`), or one per checkpoint at one operating point (:func:`make_arm`).

An arm is scored on detection layers of its checkpoint *detected at its sealed threshold*
(:func:`arm_for_detections`): a lower-threshold run filtered by score is not that run, since a blob
of the heatmap splits above a higher threshold and every centroid moves with it
(:func:`~..detect.detector.detect_frames_at_thresholds`).

The sealed document (one JSON file)::

    {"schema": "birdseye-preregistration/1",
     "rule": {"arms": [{"name": str, "checkpoint": str, "model_digest": sha256 hex,
                        "operating_point": {threshold, dedup_cm, eps_m, min_samples, eps_pred_m,
                                            edge_buffer_px, core_count}}, ...],
              "descriptive": [...], "note": str},
     "model_digests": [sorted sha256 hex of every arm's checkpoint],
     "sealed_at": "YYYY-MM-DDTHH:MM:SSZ",
     "seal": sha256 hex}

``seal = SHA-256(canonical_json({"schema", "rule", "model_digests", "sealed_at"}))`` where
:func:`canonical_json` is UTF-8 JSON with sorted keys, no insignificant whitespace, no NaN, and
floats in Python's shortest round-trip form. Changing any byte of what the seal covers — or the seal
itself — makes :func:`verify` refuse the document.

A rule sealed before BirdsEye recorded ``core_count`` has none in its operating points. It verifies
as it was sealed (nothing in it is rewritten) and is scored as it was computed, counting cells
(:data:`.operating_point.RECORDED_WITHOUT_CORE_COUNT`): reading the absent key as today's default would
score the arm at an operating point nobody sealed.

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
from typing import Mapping

from ..detect.clustering import DEFAULT_CORE_COUNT
from ..errors import InputError
from .operating_point import OperatingPoint
from .sweep import THRESHOLD_TOLERANCE

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


def arms_from_selection(selected: list[dict], checkpoint_digests: Mapping[str, str] | None = None) -> list[dict]:
    """Arms from an arms file's entries (:func:`.arms.read_arms`), each with its own operating point.

    ``checkpoint_digests`` (file name → SHA-256 of the checkpoint files at hand), when given, must hold
    every arm's digest: the seal then names files that exist, not only what the sweep recorded.
    """
    known = set((checkpoint_digests or {}).values())
    arms = []
    for entry in selected:
        if checkpoint_digests is not None and entry["model_digest"] not in known:
            raise SealError(f"arm '{entry['name']}' is checkpoint {entry['checkpoint']} "
                            f"({entry['model_digest'][:12] or 'no digest'}…), which none of the checkpoint files "
                            f"is ({', '.join(sorted(checkpoint_digests))})", field="CHECKPOINTS")
        arms.append(make_arm(entry["checkpoint"], entry["model_digest"],
                             OperatingPoint.from_dict(entry["operating_point"], source=f"arm {entry['name']}"),
                             entry["name"]))
    return arms


#: The fields of a typed arm line, after "name:".
ARM_LINE_FIELDS = ("checkpoint", "threshold", "eps_m", "min_samples", "eps_pred_m")


def parse_arm_lines(text: str, checkpoint_digests: Mapping[str, str], dedup_cm: float,
                    edge_buffer_px: float, core_count: str = DEFAULT_CORE_COUNT) -> list[dict]:
    """Arms typed one per line, ``name: checkpoint, threshold, eps_m, min_samples, eps_pred_m`` (the
    checkpoint by file name among ``checkpoint_digests``; DEDUP_CM, EDGE_BUFFER_PX and CORE_COUNT shared
    by every arm). Blank lines and lines starting with # are skipped."""
    arms = []
    for row, line in enumerate((text or "").splitlines(), start=1):
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        name, sep, rest = line.partition(":")
        values = [v.strip() for v in rest.split(",")]
        if not sep or not name.strip() or len(values) != len(ARM_LINE_FIELDS):
            raise InputError(f"'{line}' is not 'name: {', '.join(ARM_LINE_FIELDS)}' "
                             "(e.g. 'max_f1: model.onnx, 0.05, 0.20, 2, 0.20')", row=row, field="ARM_LINES")
        checkpoint = Path(values[0]).name
        if checkpoint not in checkpoint_digests:
            raise InputError(f"names checkpoint '{values[0]}', which is not among CHECKPOINTS "
                             f"({', '.join(sorted(checkpoint_digests))})", row=row, field="ARM_LINES")
        try:
            threshold, eps_m, min_samples, eps_pred_m = (float(v) for v in values[1:])
        except ValueError as exc:
            raise InputError(f"'{line}': threshold, eps_m, min_samples and eps_pred_m must be numbers",
                             row=row, field="ARM_LINES") from exc
        if min_samples != int(min_samples):
            raise InputError(f"'{line}': min_samples must be a whole number", row=row, field="ARM_LINES")
        op = OperatingPoint(threshold, dedup_cm, eps_m, int(min_samples), eps_pred_m, edge_buffer_px, core_count)
        arms.append(make_arm(checkpoint, checkpoint_digests[checkpoint], op, name.strip()))
    if not arms:
        raise InputError("holds no arm line", field="ARM_LINES")
    return arms


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
    names = set()
    for i, arm in enumerate(rule["arms"], start=1):
        if not isinstance(arm, dict) or not _is_digest(arm.get("model_digest")):
            raise SealError(f"arm {i} has no valid model_digest", source=source)
        OperatingPoint.from_dict(arm.get("operating_point") or {}, source=f"{source}, arm {i}")
        if arm.get("name") in names:
            raise SealError(f"arm {i} has the name '{arm.get('name')}' of an earlier arm; arms need distinct names",
                            source=source)
        names.add(arm.get("name"))


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


def arm_for(document: dict, model_digest: str, source: str = "preregistration",
            arm_name: str | None = None) -> tuple[dict, OperatingPoint]:
    """The arm sealed for a model digest (and name, needed when several arms share the checkpoint), and
    its operating point; refuses a model or an arm the rule never named."""
    arms = document["rule"]["arms"]
    names = ", ".join(f"{a['name']} ({a['model_digest'][:12]}…)" for a in arms)
    mine = [a for a in arms if a["model_digest"] == model_digest]
    if not mine:
        raise SealError(f"the detections come from model {model_digest[:12] or '(no digest)'}…, which the sealed "
                        f"rule does not name (arms: {names}); refusing to score", source=source)
    if arm_name is not None:
        mine = [a for a in mine if a["name"] == arm_name]
        if not mine:
            raise SealError(f"has no arm '{arm_name}' for model {model_digest[:12]}… (arms: {names})", source=source)
    if len(mine) > 1:
        raise SealError(f"seals {len(mine)} arms for model {model_digest[:12]}… "
                        f"({', '.join(a['name'] for a in mine)}); say which arm to score (ARM)", source=source)
    return mine[0], OperatingPoint.from_dict(mine[0]["operating_point"], source=source)


def arm_for_detections(document: dict, detections, source: str = "preregistration",
                       arm_name: str | None = None) -> tuple[dict, OperatingPoint]:
    """The sealed arm that scores these detection layers, and its operating point.

    ``detections``: one per flight, each with ``name``, ``model_digest`` and ``threshold`` (the
    threshold Detect ran at; :class:`.evaluation.Detections`). They must all come from one model the
    rule names and each be detected at the arm's sealed threshold.
    """
    digests = {d.model_digest for d in detections}
    if "" in digests:
        raise SealError("a detection layer has no model_digest, so it cannot be checked against the sealed rule",
                        source=source)
    if len(digests) != 1:
        raise SealError("the detection layers come from different models; a sealed rule scores one arm at a time",
                        source=source)
    arm, op = arm_for(document, digests.pop(), source, arm_name)
    sealed = op.threshold
    for d in detections:
        if d.threshold is None:
            raise SealError(f"records no detection threshold, so it cannot be shown to be a run at arm "
                            f"'{arm['name']}''s sealed threshold {sealed:g}; run Detect with THRESHOLD {sealed:g} "
                            "(it writes the threshold into every detection)", source=d.name, field="threshold")
        if abs(d.threshold - sealed) > THRESHOLD_TOLERANCE:
            raise SealError(f"was detected at threshold {d.threshold:g}, but arm '{arm['name']}' is sealed at "
                            f"{sealed:g}. No score filter turns one run into the other (a blob above the lower "
                            "threshold splits into several above a higher one, and every centroid moves): run "
                            f"Detect on this flight with THRESHOLD {sealed:g} and score that layer",
                            source=d.name, field="threshold")
    return arm, op


def check_checkpoint_files(document: dict, paths, digest_of) -> None:
    """Refuse checkpoint files whose SHA-256 (``digest_of(path)``) is not among the sealed digests."""
    sealed = set(document["model_digests"])
    for p in paths:
        d = digest_of(p)
        if d not in sealed:
            raise SealError(f"has digest {d[:12]}…, not one of the sealed checkpoints", source=str(p))

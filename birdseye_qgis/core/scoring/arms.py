"""The method's three arms, chosen from an operating-point sweep: max F1, max recall, lowest review burden.

Every rule looks only at the sweep's *credible configurations on its Pareto front* (recall_pre against
gmcf_pre over every checkpoint's configurations; credible = mean geotags per hit cluster and mean
median cluster extent within their limits, :mod:`.sweep`) and picks one row of the table: a checkpoint
with its full operating point.

- ``max_f1``: the highest ``f1_geo``, the harmonic mean of pooled recall and pooled GMCF; ties → the
  higher recall, then the earlier row.
- ``max_recall``: the highest ``recall_pre``; ties → the higher ``gmcf_pre``, then the earlier row.
- ``lowest_review_burden``: the fewest detections per frame — what a reviewer walks through, frame by
  frame, and what the screening's review load divides; ties (configurations that differ only in
  clustering, which leaves detections per frame unchanged) → the higher ``f1_geo``, the higher recall,
  then the earlier row.

The arms file (:func:`arms_document`)::

    {"schema": "birdseye-arms/1", "sweep": {source, flights, grid, credibility},
     "arms": [{"name", "rule", "checkpoint", "model_digest",
               "operating_point": {threshold, dedup_cm, eps_m, min_samples, eps_pred_m, edge_buffer_px,
                                   core_count},
               "scores": {recall_pre, gmcf_pre, f1_geo, detections_per_frame, n_clusters, ...},
               "sweep_row": int}, ...]}

``sealpreregistration`` seals these arms as they are. A sweep row without ``core_count`` (a sweep
made before BirdsEye recorded it) counted cells, and its arm says so
(:data:`.operating_point.RECORDED_WITHOUT_CORE_COUNT`).
"""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Mapping, Sequence

from ..errors import InputError
from .operating_point import OperatingPoint

SCHEMA = "birdseye-arms/1"

#: Rule name → what it picks (also written into the arms file).
RULES = {
    "max_f1": "highest f1_geo (harmonic mean of pooled recall and GMCF); ties: higher recall, earlier row",
    "max_recall": "highest recall_pre; ties: higher gmcf_pre, earlier row",
    "lowest_review_burden": "fewest detections per frame; ties: higher f1_geo, higher recall, earlier row",
}

_OPERATING_POINT_KEYS = ("threshold", "dedup_cm", "eps_m", "min_samples", "eps_pred_m", "edge_buffer_px")
#: Read when present; older sweep tables lack it (OperatingPoint.from_dict reads that as cells).
_RECORDED_SINCE = ("core_count",)
_SCORE_KEYS = ("recall_pre", "gmcf_pre", "f1_geo", "detections_per_frame")
_REPORTED = _SCORE_KEYS + ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters", "n_frames", "n_detections")


def _number(row: Mapping, key: str, source: str, index: int) -> float:
    value = row.get(key)
    if value is None and key == "detections_per_frame":
        return math.inf
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise InputError(f"is {value!r}, expected a number (is this a table written by Sweep operating points?)",
                         source=source, row=index + 1, field=key)
    return float(value)


def _sort_keys(row: Mapping, source: str, index: int) -> dict:
    recall, gmcf, f1 = (_number(row, k, source, index) for k in ("recall_pre", "gmcf_pre", "f1_geo"))
    burden = _number(row, "detections_per_frame", source, index)
    return {"max_f1": (-f1, -recall, index), "max_recall": (-recall, -gmcf, index),
            "lowest_review_burden": (burden, -f1, -recall, index)}


def select_arms(rows: Sequence[Mapping], source: str = "sweep") -> list[dict]:
    """The three arms (:data:`RULES`, in that order) from a sweep's configuration rows."""
    front = []
    for index, row in enumerate(rows):
        if not isinstance(row, Mapping):
            raise InputError("is not a configuration (expected a JSON object)", source=source, row=index + 1)
        for key in ("credible", "pareto"):
            if not isinstance(row.get(key), bool):
                raise InputError("is missing or not true/false (is this a table written by Sweep operating "
                                 "points?)", source=source, row=index + 1, field=key)
        if row["credible"] and row["pareto"]:
            front.append((index, row, _sort_keys(row, source, index)))
    if not front:
        raise InputError("has no credible configuration on its Pareto front, so no arm can be chosen (widen the "
                         "grid or the credibility limits and sweep again)", source=source)
    arms = []
    for rule, description in RULES.items():
        index, row, _ = min(front, key=lambda entry, r=rule: entry[2][r])
        arms.append(_arm(rule, description, row, index, source))
    return arms


def _arm(rule: str, description: str, row: Mapping, index: int, source: str) -> dict:
    for key in ("checkpoint", "model_digest"):
        if not isinstance(row.get(key), str):
            raise InputError("is missing (the sweep names each configuration's checkpoint)", source=source,
                             row=index + 1, field=key)
    missing = [k for k in _OPERATING_POINT_KEYS if k not in row]
    if missing:
        raise InputError(f"lacks {', '.join(missing)} of its operating point", source=source, row=index + 1)
    op = OperatingPoint.from_dict({k: row[k] for k in _OPERATING_POINT_KEYS + _RECORDED_SINCE if k in row},
                                  source=f"{source}, row {index + 1}")
    return {"name": rule, "rule": description, "checkpoint": row["checkpoint"], "model_digest": row["model_digest"],
            "operating_point": op.to_dict(), "scores": {k: row.get(k) for k in _REPORTED}, "sweep_row": index + 1}


def read_sweep(path) -> dict:
    """A sweep's JSON output (Sweep operating points' OUTPUT_JSON), with its configuration rows."""
    try:
        document = json.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError as exc:
        raise InputError("file not found", source=str(path)) from exc
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"cannot be read as JSON ({exc}); give the JSON output of Sweep operating points",
                         source=str(path)) from exc
    if not isinstance(document, dict) or not isinstance(document.get("configurations"), list):
        raise InputError("has no 'configurations' list; give the JSON output of Sweep operating points",
                         source=str(path))
    return document


def arms_document(sweep_document: Mapping, arms: list[dict], source: str) -> dict:
    """The arms file: the arms and what the sweep they were chosen from looked at."""
    return {"schema": SCHEMA,
            "sweep": {"source": source, **{k: sweep_document.get(k) for k in ("flights", "grid", "credibility")}},
            "arms": arms}


def read_arms(path) -> list[dict]:
    """The arms of an arms file (:func:`arms_document`), each checked to name a checkpoint, its digest and
    a full operating point."""
    path = Path(path)
    try:
        document = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError as exc:
        raise InputError("file not found", source=str(path)) from exc
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise InputError(f"cannot be read as JSON ({exc})", source=str(path)) from exc
    if not isinstance(document, dict) or document.get("schema") != SCHEMA:
        raise InputError(f"is not an arms file (schema '{SCHEMA}'); make it with Select arms", source=str(path))
    arms = document.get("arms")
    if not isinstance(arms, list) or not arms:
        raise InputError("has no arms", source=str(path))
    for i, arm in enumerate(arms, start=1):
        where = f"{path}, arm {i}"
        if not isinstance(arm, dict):
            raise InputError("is not a JSON object", source=where)
        for key in ("name", "checkpoint", "model_digest"):
            if not isinstance(arm.get(key), str) or not arm[key]:
                raise InputError("is missing or empty", source=where, field=key)
        if not isinstance(arm.get("operating_point"), dict):
            raise InputError("is missing", source=where, field="operating_point")
        OperatingPoint.from_dict(arm["operating_point"], source=where)
    return arms

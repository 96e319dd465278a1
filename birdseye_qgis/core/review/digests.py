"""Input digests: which layer contents and parameters each verdict was recorded against."""
from __future__ import annotations

import hashlib
import json
import math
from dataclasses import dataclass, field
from typing import Iterable, Mapping, Sequence

import numpy as np

from ..scoring.operating_point import RECORDED_WITHOUT_CORE_COUNT
from ..scoring.verdicts import CONFIRMED, DIRECT, HARD_NEGATIVE, UNCERTAIN


def _canonical(value):
    if value is None:
        return None
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, (int, float, np.integer, np.floating)):
        v = float(value)
        return repr(v) if math.isfinite(v) else str(v)
    return str(value)


def content_digest(kind: str, crs: str, field_names: Sequence[str], rows: Iterable[Sequence]) -> str:
    """SHA-256 (hex) of a layer's relevant content: its kind, CRS, the listed field names and, per
    feature, the values of those fields (geometry coordinates included by the caller as values).

    Numbers hash by value (3 and 3.0 alike, exact binary value), so a provider returning integers as
    floats changes nothing; features are sorted, so their order does not matter either.
    """
    encoded = sorted(json.dumps([_canonical(v) for v in row], ensure_ascii=False) for row in rows)
    h = hashlib.sha256()
    h.update(json.dumps({"kind": kind, "crs": crs, "fields": list(field_names)}, sort_keys=True).encode())
    for line in encoded:
        h.update(b"\n")
        h.update(line.encode("utf-8"))
    return h.hexdigest()


def input_id(role: str, name: str) -> str:
    """The key of an input in the recorded digests: ``detections:<layer name>`` etc."""
    return f"{role}:{name}"


@dataclass
class InputCheck:
    """Verdicts of this review recorded against other inputs or parameters than the current ones."""

    changed: dict = field(default_factory=dict)        # input id -> rows recorded against other content
    missing: dict = field(default_factory=dict)        # input id recorded, not among the current inputs
    new: list = field(default_factory=list)            # current inputs no row was recorded against
    parameters: dict = field(default_factory=dict)     # parameter -> (recorded values, current value)
    orphaned: list = field(default_factory=list)       # reviewed unit keys no current unit carries
    n_rows: int = 0                                    # rows of this review

    @property
    def ok(self) -> bool:
        return not (self.changed or self.missing or self.parameters or self.orphaned)

    def messages(self) -> list[str]:
        out = []
        for iid, n in self.changed.items():
            role, name = iid.split(":", 1)
            out.append(f"The {role} layer '{name}' changed since {n} of {self.n_rows} verdict rows were recorded "
                       "(its content digest differs).")
        for iid, n in self.missing.items():
            role, name = iid.split(":", 1)
            out.append(f"{n} verdict rows were recorded with the {role} layer '{name}', which is not part of this "
                       "review now.")
        for name, (old, new) in self.parameters.items():
            out.append(f"Parameter {name} was {', '.join(map(str, old))} when verdicts were recorded; now {new}.")
        if self.orphaned:
            out.append(f"{len(self.orphaned)} reviewed unit(s) are not among the current units (e.g. "
                       f"{', '.join(self.orphaned[:2])}); their verdicts still count by position.")
        return out


def check_inputs(rows: Iterable[Mapping], current_digests: Mapping[str, str], current_params: Mapping,
                 unit_keys: Iterable[str]) -> InputCheck:
    """Compare the digests and parameters recorded on the rows of this review with the current ones.

    Rows of this review are those recorded with at least one of the current detection layers (a
    GeoPackage may hold the reviews of other flights). ``current_params`` is flat (name → value).
    """
    rows = list(rows)
    current_det = {k for k in current_digests if k.startswith("detections:")}
    check = InputCheck()
    recorded_params: dict[str, set] = {}
    reviewed = set()
    for row in rows:
        digests = _json(row.get("input_digests"))
        if not current_det & set(digests):
            continue
        check.n_rows += 1
        for iid, digest in digests.items():
            if iid not in current_digests:
                check.missing[iid] = check.missing.get(iid, 0) + 1
            elif digest != current_digests[iid]:
                check.changed[iid] = check.changed.get(iid, 0) + 1
        for blob in ("postprocessing", "matching_parameters"):
            recorded = _json(row.get(blob))
            if blob == "postprocessing" and recorded:
                # Rows written before core_count was recorded were clustered counting cells.
                recorded = {"core_count": RECORDED_WITHOUT_CORE_COUNT, **recorded}
            for name, value in recorded.items():
                recorded_params.setdefault(name, set()).add(json.dumps(value))
        if row["provenance"] == DIRECT and row["verdict"] in (CONFIRMED, HARD_NEGATIVE, UNCERTAIN):
            reviewed.add(row["unit_key"])
    if check.n_rows:
        seen = set()
        for row in rows:
            digests = _json(row.get("input_digests"))
            if current_det & set(digests):
                seen.update(digests)
        check.new = sorted(set(current_digests) - seen)
    for name, values in recorded_params.items():
        if name in current_params:
            now = json.dumps(current_params[name])
            if values != {now}:
                check.parameters[name] = (sorted(json.loads(v) for v in values - {now}), current_params[name])
    check.orphaned = sorted(reviewed - set(unit_keys))
    return check


def _json(value) -> dict:
    if value in (None, ""):
        return {}
    return value if isinstance(value, dict) else json.loads(value)

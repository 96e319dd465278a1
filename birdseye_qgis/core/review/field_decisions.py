"""A field survey's decisions at the points it visited, as verdicts of the review they came from.

A field package's visit table (``field_survey.VISIT_TABLE``) holds, per point to visit, the review units it
settles (``unit_keys``, a JSON list; ``[]`` for a plain point) and what the worker decided there (``decision``,
a key of ``field_survey.DECISIONS``, the review's own verdicts; NULL = not visited). Import geotags appends each
decision to the review's verdict log as one direct verdict per unit, reviewer ``field:<worker>``
(docs/design.md#geotags). This module reads the visits and plans those rows; the store writes them.
"""
from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from typing import Iterable, Mapping, Sequence

from ..errors import InputError, detached
from ..field.field_survey import DECISIONS, FIELD_REVIEWER_PREFIX
from ..scoring.verdicts import DIRECT
from .actions import PlannedRow, layers_fired

#: The reviewer of a decision whose worker left no name.
FIELD_REVIEWER = FIELD_REVIEWER_PREFIX.rstrip(":")
#: The log metadata a unit without an earlier row gets (an empty JSON object each).
NO_METADATA = "{}"


@dataclass(frozen=True)
class Visit:
    """A point of the visit table: its row (1.., the table's feature order), id, the review units it settles,
    the decision (a review verdict, None = not visited), the worker, and its position (WGS84, deg)."""

    row: int
    visit_id: str
    unit_keys: tuple
    decision: str | None
    worker: str
    lat: float
    lon: float


def field_reviewer(worker: str) -> str:
    """The verdict log's reviewer of a worker's decisions: ``field:<worker>``, ``field`` without a name."""
    worker = (worker or "").strip()
    return FIELD_REVIEWER_PREFIX + worker if worker else FIELD_REVIEWER


def read_visits(records: Iterable[Mapping], source: str = "visits") -> tuple[list[Visit], list[InputError]]:
    """The visits of ``records`` (mappings with ``row``, ``lat``, ``lon`` and the visit table's ``visit_id``,
    ``unit_keys``, ``decision``, ``worker``; None for NULL), and the rows left out: a decision that is not one
    of ``field_survey.DECISIONS``, unit keys that are not a JSON list of texts, or a decided visit without a
    position (one :class:`InputError` each, naming ``source``, row and field)."""
    visits, problems = [], []
    for rec in records:
        row = int(rec["row"])
        try:
            decision = (str(rec.get("decision") or "").strip()) or None
            if decision is not None and decision not in DECISIONS:
                raise InputError(f"'{decision}' is not a field decision (expected one of {', '.join(DECISIONS)}, or "
                                 "empty: not visited)", source=source, row=row, field="decision")
            keys = _unit_keys(rec.get("unit_keys"), source, row)
            lat, lon = float(rec["lat"]), float(rec["lon"])
            if decision is not None and not (math.isfinite(lat) and math.isfinite(lon)):
                raise InputError("has a decision but no position (empty geometry)", source=source, row=row,
                                 field="geometry")
        except InputError as exc:
            problems.append(detached(exc))
            continue
        visits.append(Visit(row, str(rec.get("visit_id") or row), keys, decision,
                            str(rec.get("worker") or "").strip(), lat, lon))
    return visits, problems


def _unit_keys(value, source: str, row: int) -> tuple:
    """The review units of a visit from its ``unit_keys`` text (a JSON list; empty or NULL: none)."""
    if value is None or not str(value).strip():
        return ()
    try:
        keys = json.loads(str(value))
    except ValueError:
        keys = None
    if not isinstance(keys, list) or not all(isinstance(k, str) and k.strip() for k in keys):
        raise InputError(f"'{value}' is not a JSON list of review unit keys (e.g. [\"u-27.5500000151.9500000\"])",
                         source=source, row=row, field="unit_keys")
    return tuple(k.strip() for k in keys)


@dataclass(frozen=True)
class FieldVerdict:
    """A verdict row to append and the log metadata it carries: the reviewer, and the input digests, matching
    parameters and post-processing (JSON text) of the unit's latest row in the log, ``{}`` without one."""

    row: PlannedRow
    reviewer: str
    input_digests: str = NO_METADATA
    matching_parameters: str = NO_METADATA
    postprocessing: str = NO_METADATA


@dataclass
class FieldDecisions:
    """What a field survey's visits give a review: the verdicts to append (one per unit, in the order the
    visits first name the units), the units skipped because their latest direct verdict is already this
    decision by this field reviewer (importing a package again appends nothing), the decided visits without review units
    (plain points: nothing to write), the number of visits not decided, and notes for the log (a unit two
    visits decide differently)."""

    verdicts: list = field(default_factory=list)
    already: list = field(default_factory=list)
    plain: list = field(default_factory=list)
    undecided: int = 0
    notes: list = field(default_factory=list)


def plan_field_decisions(visits: Sequence[Visit], log_rows: Iterable[Mapping]) -> FieldDecisions:
    """The verdicts the decided ``visits`` append to a verdict log whose rows (``log_rows``, append order, as
    ``VerdictStore.rows`` gives them) are already there.

    Each unit of a decided visit gets one direct verdict: the decision, at the visit's position, reviewer
    :func:`field_reviewer`, with the layers fired and metadata of the unit's latest row in the log. A unit two
    visits decide is decided by the later visit (the table's order), and a note names both. A unit whose latest
    direct row already holds this decision from this reviewer is skipped."""
    latest: dict[str, Mapping] = {}
    latest_direct: dict[str, Mapping] = {}
    for row in log_rows:
        latest[row["unit_key"]] = row
        if row["provenance"] == DIRECT:
            latest_direct[row["unit_key"]] = row
    out = FieldDecisions()
    deciding: dict[str, Visit] = {}
    for visit in visits:
        if visit.decision is None:
            out.undecided += 1
            continue
        if not visit.unit_keys:
            out.plain.append(visit)
        for key in visit.unit_keys:
            earlier = deciding.get(key)
            if earlier is not None and earlier.decision != visit.decision:
                out.notes.append(f"unit {key}: visit {earlier.visit_id} decided {earlier.decision}, the later visit "
                                 f"{visit.visit_id} {visit.decision}; the later one is recorded")
            deciding[key] = visit
    for key, visit in deciding.items():
        reviewer = field_reviewer(visit.worker)
        direct = latest_direct.get(key)
        if direct is not None and direct["verdict"] == visit.decision and direct.get("reviewer") == reviewer:
            out.already.append(key)
            continue
        before = latest.get(key, {})
        out.verdicts.append(FieldVerdict(
            PlannedRow(key, visit.decision, DIRECT, visit.lat, visit.lon, layers_fired(before.get("layers_fired"))),
            reviewer, *(before.get(name) or NO_METADATA
                        for name in ("input_digests", "matching_parameters", "postprocessing"))))
    return out

"""Verdict actions on the append-only log: verdicts with propagation, added targets, undo; the ledger."""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import Iterable, Mapping, Sequence

from ..scoring.verdicts import (
    ADDED,
    CONFIRMED,
    CONVENTIONS,
    DIRECT,
    HARD_NEGATIVE,
    PROPAGATED_PREFIX,
    UNCERTAIN,
    UNREVIEWED,
    VerdictLog,
)
from .units import ADDED_PREFIX, PROPAGATION_RULE, UnitRef, added_key

#: The verdicts a reviewer gives (``added`` is given with the map tool).
REVIEW_VERDICTS = (CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED)
ACTION_VERDICT, ACTION_ADD, ACTION_UNDO = "verdict", "add", "undo"


@dataclass(frozen=True)
class PlannedRow:
    """A row an action will append (the store adds action, time, reviewer, digests and parameters)."""

    unit_key: str
    verdict: str
    provenance: str
    lat: float
    lon: float
    layers_fired: tuple = ()


def propagation_provenance(source_key: str) -> str:
    """Provenance of a vote propagated from ``source_key``: ``propagated:dbscan_0.20m/<source key>``."""
    return f"{PROPAGATED_PREFIX}{PROPAGATION_RULE}/{source_key}"


class Ledger:
    """The verdict log as appended so far (rows in append order) and what the next action appends.

    Rows are mappings with at least ``fid``, ``unit_key``, ``verdict``, ``provenance``, ``action_id``,
    ``action`` and ``undoes`` (None unless an undo), plus ``lat``, ``lon``, ``layers_fired``.
    """

    def __init__(self, rows: Iterable[Mapping] = ()):
        self.rows: list[dict] = []
        self._units: dict[str, dict[str, str]] = {}
        self._by_source: dict[str, set] = {}
        self.extend(rows)

    def extend(self, rows: Iterable[Mapping]) -> None:
        for row in rows:
            row = dict(row)
            self.rows.append(row)
            self._units.setdefault(row["unit_key"], {})[row["provenance"]] = row["verdict"]
            if row["provenance"].startswith(PROPAGATED_PREFIX):
                source = row["provenance"].split("/", 1)[-1]
                self._by_source.setdefault(source, set()).add(row["unit_key"])

    # ---------------------------------------------------------------- state
    def latest(self, unit_key: str, provenance: str = DIRECT) -> str:
        """The slot's latest verdict (append order), ``unreviewed`` when it has none."""
        return self._units.get(unit_key, {}).get(provenance, UNREVIEWED)

    def direct(self, unit_key: str) -> str:
        return self.latest(unit_key, DIRECT)

    def votes(self, unit_key: str) -> dict:
        """Live votes of a unit: {provenance: verdict}, ``unreviewed`` slots left out."""
        return {p: v for p, v in self._units.get(unit_key, {}).items() if v not in (UNREVIEWED, ADDED)}

    def added_targets(self) -> list[UnitRef]:
        """Targets whose latest direct row is ``added``, in the order they were added."""
        out, seen = [], set()
        for row in self.rows:
            key = row["unit_key"]
            if row["verdict"] == ADDED and key not in seen and self.direct(key) == ADDED:
                seen.add(key)
                out.append(UnitRef(key, float(row["lat"]), float(row["lon"]), ()))
        return out

    def verdict_log(self, source: str = "verdict log") -> VerdictLog:
        """The scoring view of the log (:class:`.scoring.VerdictLog`, sequence = fid)."""
        return VerdictLog.from_records(self.rows, source)

    # ---------------------------------------------------------------- planning
    def plan_verdict(self, unit: UnitRef, verdict: str, neighbours: Sequence[UnitRef] = (),
                     propagate: bool = False) -> list[PlannedRow]:
        """Rows for ``verdict`` on ``unit``: its direct row, and the votes it propagates to ``neighbours``
        (all of them when ``propagate``; otherwise only those that already hold a live vote from it)."""
        if verdict not in REVIEW_VERDICTS:
            raise ValueError(f"{verdict!r} is not a review verdict (expected one of {REVIEW_VERDICTS})")
        rows = []
        if self.direct(unit.key) != verdict:
            rows.append(PlannedRow(unit.key, verdict, DIRECT, unit.lat, unit.lon, unit.layers_fired))
        provenance = propagation_provenance(unit.key)
        for n in neighbours:
            current = self.latest(n.key, provenance)
            if (propagate or current != UNREVIEWED) and current != verdict:
                rows.append(PlannedRow(n.key, verdict, provenance, n.lat, n.lon, n.layers_fired))
        return rows

    def plan_add(self, lat: float, lon: float) -> list[PlannedRow]:
        key = added_key(lat, lon)
        return [] if self.direct(key) == ADDED else [PlannedRow(key, ADDED, DIRECT, float(lat), float(lon))]

    def open_actions(self) -> list[int]:
        """Action ids that can still be undone, oldest first (undo rows are not undoable)."""
        actions, undone = [], set()
        for row in self.rows:
            if row["action"] == ACTION_UNDO:
                undone.add(row["undoes"])
            elif not actions or actions[-1] != row["action_id"]:
                actions.append(row["action_id"])
        return [a for a in dict.fromkeys(actions) if a not in undone]

    def plan_undo(self) -> tuple[int | None, list[PlannedRow]]:
        """(action id, rows) restoring every slot the latest open action touched; (None, []) if none."""
        open_ = self.open_actions()
        if not open_:
            return None, []
        action = open_[-1]
        mine = [r for r in self.rows if r["action_id"] == action and r["action"] != ACTION_UNDO]
        first = min(r["fid"] for r in mine)
        before: dict[tuple[str, str], str] = {}
        for r in self.rows:
            if r["fid"] < first:
                before[(r["unit_key"], r["provenance"])] = r["verdict"]
        rows, seen = [], set()
        for r in mine:
            slot = (r["unit_key"], r["provenance"])
            if slot in seen:
                continue
            seen.add(slot)
            rows.append(PlannedRow(r["unit_key"], before.get(slot, UNREVIEWED), r["provenance"], float(r["lat"]),
                                   float(r["lon"]), layers_fired(r.get("layers_fired"))))
        return action, rows

    def propagated_from(self, source_key: str) -> list[str]:
        """Units holding a live vote propagated from ``source_key``."""
        prov = propagation_provenance(source_key)
        return sorted(u for u in self._by_source.get(source_key, ()) if self.latest(u, prov) != UNREVIEWED)


def layers_fired(value) -> tuple:
    """A log row's ``layers_fired`` as a tuple of layer names: the stored JSON list, a list already
    decoded, or nothing (an empty tuple)."""
    if value in (None, ""):
        return ()
    if isinstance(value, (list, tuple)):
        return tuple(value)
    return tuple(json.loads(value))


@dataclass(frozen=True)
class UnitStatus:
    """How a unit stands: its direct verdict, live votes and the resolution under each convention."""

    direct: str
    votes: dict
    resolved: dict

    @property
    def reviewed(self) -> bool:
        return bool(self.votes)

    @property
    def conflict(self) -> bool:
        return len(set(self.resolved.values())) > 1

    @property
    def propagated_only(self) -> bool:
        return self.direct == UNREVIEWED and bool(self.votes)


def unit_status(log: VerdictLog, ledger: Ledger, key: str) -> UnitStatus:
    return UnitStatus(ledger.direct(key), ledger.votes(key), {c: log.resolve(key, c) for c in CONVENTIONS})


def resume_key(order_keys: Sequence[str], ledger: Ledger, cursor_key: str | None) -> str | None:
    """Where a review resumes: the saved cursor when it names a unit of ``order_keys``; else the unit
    after the one reviewed last; else the first unit without a vote; else the first unit."""
    if not order_keys:
        return None
    if cursor_key in order_keys or (cursor_key and cursor_key.startswith(ADDED_PREFIX)
                                    and ledger.direct(cursor_key) == ADDED):
        return cursor_key
    position = {k: i for i, k in enumerate(order_keys)}
    for row in reversed(ledger.rows):
        if row["provenance"] == DIRECT and row["unit_key"] in position:
            return order_keys[min(position[row["unit_key"]] + 1, len(order_keys) - 1)]
    return next((k for k in order_keys if not ledger.votes(k)), order_keys[0])

"""The verdict log of the review dock and how a unit's votes resolve under each convention."""
from __future__ import annotations

import math
from dataclasses import dataclass
from datetime import datetime, timezone
from typing import Iterable, Mapping, Sequence

import numpy as np

from ..detect.clustering import Clustering
from ..errors import InputError
from .matching import match_to_clusters

CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED, ADDED = (
    "confirmed_real", "hard_negative", "uncertain", "unreviewed", "added")
VERDICTS = (CONFIRMED, HARD_NEGATIVE, UNCERTAIN, UNREVIEWED)
CONVENTIONS = ("positive_wins", "majority_wins", "hard_negative_wins")
DIRECT = "direct"
PROPAGATED_PREFIX = "propagated:"


@dataclass(frozen=True)
class Verdict:
    """One row of the verdict log (see the module docstring)."""

    unit_key: str
    verdict: str
    provenance: str = DIRECT
    time: str = ""
    reviewer: str = ""
    lat: float | None = None
    lon: float | None = None
    sequence: int = 0


def _time_key(text: str, source: str, row: int) -> float:
    if not text:
        return -math.inf
    try:
        t = datetime.fromisoformat(text.strip().replace("Z", "+00:00"))
    except ValueError as exc:
        raise InputError(f"'{text}' is not an ISO 8601 time (e.g. 2024-05-01T14:03:00Z)", source=source,
                         row=row, field="time") from exc
    if t.tzinfo is None:
        t = t.replace(tzinfo=timezone.utc)
    return t.timestamp()


def combine(verdicts: Iterable[str], convention: str) -> str:
    """Resolve judgements (verdict strings) under a convention.

    "uncertain" and "unreviewed" are abstentions, not votes: only confirmed_real and hard_negative
    count. Judgements that all abstain resolve to "uncertain" (someone looked) or, with no
    confirmed_real, hard_negative or uncertain at all, to "unreviewed". ``majority_wins`` takes the
    larger count; a tie is "uncertain" (neither side has a majority).
    """
    if convention not in CONVENTIONS:
        raise ValueError(f"unknown convention {convention!r}; expected one of {CONVENTIONS}")
    judged = [v for v in verdicts if v in (CONFIRMED, HARD_NEGATIVE, UNCERTAIN)]
    if not judged:
        return UNREVIEWED
    n_confirmed, n_hard_negative = judged.count(CONFIRMED), judged.count(HARD_NEGATIVE)
    if n_confirmed == n_hard_negative == 0:
        return UNCERTAIN
    if convention == "positive_wins":
        return CONFIRMED if n_confirmed else HARD_NEGATIVE
    if convention == "hard_negative_wins":
        return HARD_NEGATIVE if n_hard_negative else CONFIRMED
    if n_confirmed == n_hard_negative:
        return UNCERTAIN
    return CONFIRMED if n_confirmed > n_hard_negative else HARD_NEGATIVE


class VerdictLog:
    """The latest verdict per (unit_key, provenance) of an append-only log, and how units resolve."""

    def __init__(self, rows: Iterable[Verdict] = (), source: str = "verdict log"):
        self.source = source
        latest: dict[tuple[str, str], tuple[tuple[float, int], Verdict]] = {}
        for n, row in enumerate(rows, start=1):
            self._check(row, n)
            key = (_time_key(row.time, source, n), row.sequence)
            slot = (row.unit_key, row.provenance)
            if slot not in latest or key >= latest[slot][0]:
                latest[slot] = (key, row)
        self.latest = {slot: row for slot, (_, row) in latest.items()}
        self._by_unit: dict[str, list[Verdict]] = {}
        for (unit, _), row in sorted(self.latest.items()):
            self._by_unit.setdefault(unit, []).append(row)

    def _check(self, row: Verdict, n: int) -> None:
        if not row.unit_key:
            raise InputError("is empty; every verdict needs its unit key", source=self.source, row=n,
                             field="unit_key")
        if row.verdict not in VERDICTS + (ADDED,):
            raise InputError(f"'{row.verdict}' is not a verdict (expected one of "
                             f"{', '.join(VERDICTS + (ADDED,))})", source=self.source, row=n, field="verdict")
        if row.provenance != DIRECT and not (row.provenance.startswith(PROPAGATED_PREFIX)
                                             and len(row.provenance) > len(PROPAGATED_PREFIX)):
            raise InputError(f"'{row.provenance}' is not a provenance (expected 'direct' or "
                             "'propagated:<rule>')", source=self.source, row=n, field="provenance")
        if row.verdict == ADDED and (row.lat is None or row.lon is None
                                     or not (math.isfinite(row.lat) and math.isfinite(row.lon))):
            raise InputError("an added target needs its position (lat, lon)", source=self.source, row=n,
                             field="lat")

    @classmethod
    def from_records(cls, records: Iterable[Mapping], source: str = "verdict log") -> "VerdictLog":
        """A log from mappings (rows in append order); missing optional fields take their defaults."""
        rows = []
        for n, rec in enumerate(records, start=1):
            missing = [k for k in ("unit_key", "verdict") if k not in rec]
            if missing:
                raise InputError(f"has no field(s) {', '.join(missing)}: not a BirdsEye verdict log",
                                 source=source, row=n)

            def text(name, default=""):
                v = rec.get(name)
                return default if v is None else str(v).strip()

            def number(name):
                v = rec.get(name)
                if v is None or v == "":
                    return None
                try:
                    return float(v)
                except (TypeError, ValueError) as exc:
                    raise InputError(f"'{v}' is not a number", source=source, row=n, field=name) from exc

            seq = rec.get("sequence", rec.get("fid"))
            rows.append(Verdict(text("unit_key"), text("verdict"), text("provenance", DIRECT) or DIRECT,
                                text("time"), text("reviewer"), number("lat"), number("lon"),
                                int(seq) if seq not in (None, "") else n))
        return cls(rows, source)

    def votes(self, unit_key: str) -> list[str]:
        """Latest verdict of each provenance of a unit ("unreviewed" and "added" dropped)."""
        return [r.verdict for r in self._by_unit.get(unit_key, ()) if r.verdict in (CONFIRMED, HARD_NEGATIVE,
                                                                                   UNCERTAIN)]

    def resolve(self, unit_key: str, convention: str) -> str:
        return combine(self.votes(unit_key), convention)

    def resolve_cluster(self, unit_keys: Iterable[str], convention: str) -> str:
        """One resolution over every direct and propagated judgement of every unit attached to a
        cluster (not a vote of the units' own resolutions)."""
        return combine([v for unit in unit_keys for v in self.votes(unit)], convention)

    def unit_keys(self) -> list[str]:
        """Units with at least one vote."""
        return [u for u in self._by_unit if self.votes(u)]

    def unit_positions(self):
        """(keys, lat, lon) of voted units whose latest rows carry a position, and keys without one."""
        keys, lat, lon, unplaced = [], [], [], []
        for unit in self.unit_keys():
            placed = [r for r in self._by_unit[unit] if r.lat is not None and r.lon is not None]
            if placed:
                keys.append(unit)
                lat.append(placed[0].lat)
                lon.append(placed[0].lon)
            else:
                unplaced.append(unit)
        return keys, np.asarray(lat, dtype=float), np.asarray(lon, dtype=float), unplaced

    def added_targets(self) -> list[Verdict]:
        """Targets whose latest direct row is "added" (a later "unreviewed" row withdraws one)."""
        out = []
        for unit, rows in self._by_unit.items():
            direct = [r for r in rows if r.provenance == DIRECT]
            if direct and direct[0].verdict == ADDED:
                out.append(direct[0])
        return out


def units_of_clusters(clustering: Clustering, unit_xy, unit_keys: Sequence[str], radius_m: float) -> list:
    """Unit keys attached to each cluster: units within ``radius_m`` of one of its core points."""
    m = match_to_clusters(clustering.core_xy, clustering.core_cluster, unit_xy, radius_m)
    out = [[] for _ in range(clustering.n_clusters)]
    for p, c in zip(m.point.tolist(), m.cluster.tolist()):
        out[c].append(unit_keys[p])
    return [tuple(u) for u in out]

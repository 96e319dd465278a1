"""Which review entries the dock shows and in what order; where next and previous lead.

The entries are the review units in review order (:attr:`.units.ReviewUnits.order`: unmatched first)
followed by the targets the reviewer added. A filter keeps some of them in view; moving on goes to the
next shown entry *in the full order*, so a unit that leaves the filter because it was just judged does
not make the reviewer lose their place.
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import Callable

from .actions import UnitStatus
from .units import ADDED_PREFIX, ReviewUnits

#: Filter modes besides a direct verdict ("confirmed_real", "hard_negative", "uncertain").
FILTER_MODES = ("all", "todo", "propagated", "conflict", "unmatched", "added")


class Entries(Sequence):
    """The review's entry keys in order (a sequence of them), and the subset a filter shows."""

    def __init__(self, units: ReviewUnits, added_keys: Sequence[str]):
        self.units = units
        self.keys = [units.keys[i] for i in units.order] + list(added_keys)
        self.position = {k: i for i, k in enumerate(self.keys)}

    def __getitem__(self, i):
        return self.keys[i]

    def __len__(self) -> int:
        return len(self.keys)

    def added_keys(self) -> list[str]:
        return [k for k in self.keys if k.startswith(ADDED_PREFIX)]

    def passes(self, key: str, layer: str, mode: str, status: Callable[[str], UnitStatus]) -> bool:
        """Whether ``key`` shows under a layer filter (``""`` = every layer) and a mode.

        Modes: ``all``; ``todo`` (no vote yet); a direct verdict; ``propagated`` (only propagated votes);
        ``conflict`` (the tie-break conventions disagree); ``unmatched`` (no geotag within eps_pred);
        ``added`` (targets the reviewer added). Added targets fired in no layer, so a layer filter
        hides them, and they show only under ``all`` and ``added``.
        """
        added = key.startswith(ADDED_PREFIX)
        if layer and (added or layer not in self.units.layers_fired[self.units.index[key]]):
            return False
        if mode == "all":
            return True
        if mode == "added":
            return added
        if added:
            return False
        s = status(key)
        return {"todo": not s.reviewed, "propagated": s.propagated_only, "conflict": s.conflict,
                "unmatched": not self.units.matched[self.units.index[key]]}.get(mode, s.direct == mode)

    def shown(self, layer: str, mode: str, status: Callable[[str], UnitStatus]) -> list[str]:
        return [k for k in self.keys if self.passes(k, layer, mode, status)]

    def neighbour(self, shown: Sequence[str], key: str | None, step: int) -> str | None:
        """The next (``step`` > 0) or previous shown entry from ``key``'s place in the full order.

        None at either end (no wrap-around: the end of the list is news to the reviewer); the first
        shown entry when ``key`` is no entry at all.
        """
        if not shown:
            return None
        if key not in self.position:
            return shown[0]
        visible = set(shown)
        p = self.position[key]
        sequence = self.keys[p + 1:] if step > 0 else reversed(self.keys[:p])
        return next((k for k in sequence if k in visible), None)


def display_verdict(key: str, status: UnitStatus) -> str:
    """The verdict the unit table shows: the direct one, else what its votes resolve to (majority)."""
    if key.startswith(ADDED_PREFIX):
        return "added"
    if status.direct != "unreviewed":
        return status.direct
    return status.resolved["majority_wins"] if status.reviewed else "unreviewed"

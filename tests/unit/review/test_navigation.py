"""Filters and next/previous of the review dock, without Qt (core.review.navigation)."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.review.actions import UnitStatus
from birdseye.birdseye_qgis.core.review.navigation import Entries, display_verdict
from birdseye.birdseye_qgis.core.review.units import ReviewUnits

ALL_THREE = ("positive_wins", "majority_wins", "hard_negative_wins")


def units(keys, order, layers_fired, matched):
    n = len(keys)
    empty = np.zeros(0)
    return ReviewUnits(keys=list(keys), lat=np.zeros(n), lon=np.zeros(n), xy=np.zeros((n, 2)),
                       layers_fired=layers_fired, n_detections=np.ones(n), n_frames=np.ones(n),
                       max_score=np.ones(n), matched=np.asarray(matched, bool), matched_geotags=[[]] * n,
                       order=np.asarray(order), propagation_group=np.arange(n), layer_names=["A", "B"],
                       detection_unit=empty, detection_layer=empty, detection_frame=empty, detection_uv=empty,
                       detection_score=empty)


def status(direct="unreviewed", votes=None, resolved=None):
    votes = votes or {}
    resolved = resolved or {c: (direct if votes else "unreviewed") for c in ALL_THREE}
    return UnitStatus(direct, votes, resolved)


@pytest.fixture
def entries():
    # review order u2, u0, u3, u1 (unmatched first), then one added target
    u = units(["u0", "u1", "u2", "u3"], [2, 0, 3, 1], [["A"], ["A", "B"], ["B"], ["A"]], [True, True, False, False])
    return Entries(u, ["a+1+2"])


STATUS = {
    "u0": status("confirmed_real", {"direct": "confirmed_real"}),
    "u1": status(),
    "u2": status("unreviewed", {"propagated:x": "hard_negative"},     # a propagated vote only
                 {c: "hard_negative" for c in ALL_THREE}),
    "u3": status("uncertain", {"direct": "uncertain", "propagated:y": "confirmed_real",
                               "propagated:z": "hard_negative"},
                 {"positive_wins": "confirmed_real", "majority_wins": "uncertain",
                  "hard_negative_wins": "hard_negative"}),
}


def test_entries_follow_the_review_order_then_the_added_targets(entries):
    assert entries.keys == ["u2", "u0", "u3", "u1", "a+1+2"]
    assert entries.position["u3"] == 2 and entries.added_keys() == ["a+1+2"]
    assert list(entries) == entries.keys and len(entries) == 5 and entries[-1] == "a+1+2" and "u1" in entries


@pytest.mark.parametrize("layer, mode, expected", [
    ("", "all", ["u2", "u0", "u3", "u1", "a+1+2"]),
    ("", "todo", ["u1"]),                     # u2 has a (propagated) vote, so it is not "to review"
    ("", "confirmed_real", ["u0"]),
    ("", "uncertain", ["u3"]),
    ("", "propagated", ["u2"]),
    ("", "conflict", ["u3"]),                 # its conventions disagree
    ("", "unmatched", ["u2", "u3"]),
    ("", "added", ["a+1+2"]),
    ("B", "all", ["u2", "u1"]),               # added targets fired in no layer
    ("A", "todo", ["u1"]),
    ("B", "added", []),
])
def test_filters(entries, layer, mode, expected):
    assert entries.shown(layer, mode, STATUS.get) == expected


def test_next_and_previous_walk_the_full_order_and_stop_at_the_ends(entries):
    shown = entries.shown("", "unmatched", STATUS.get)           # u2, u3
    assert entries.neighbour(shown, "u2", +1) == "u3"
    # from a unit the filter no longer shows (u0 was judged away), next is the next shown one after it
    assert entries.neighbour(shown, "u0", +1) == "u3"
    assert entries.neighbour(shown, "u0", -1) == "u2"
    assert entries.neighbour(shown, "u3", +1) is None            # no wrap-around
    assert entries.neighbour(shown, "u2", -1) is None
    assert entries.neighbour(shown, None, +1) == "u2"            # no current entry: the first shown
    assert entries.neighbour([], "u2", +1) is None


def test_display_verdict_prefers_the_direct_one_then_the_majority():
    assert display_verdict("u0", STATUS["u0"]) == "confirmed_real"
    assert display_verdict("u2", STATUS["u2"]) == "hard_negative"   # majority of its propagated votes
    assert display_verdict("u1", STATUS["u1"]) == "unreviewed"
    assert display_verdict("a+1+2", status()) == "added"

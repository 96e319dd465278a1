"""Review core: consensus units, ordering, propagation, verdict actions and undo, digests, chips.

The scene: level nadir frames 10 m above flat ground near Dalby (undistorted 480 × 300 px camera,
fx = fy = 500 px, so 2 cm per pixel); targets are points on the ground in metres east/north of the
site, detections are their projections into the frames that see them (so u, v and the ground position
agree exactly), and scores follow from a hand-written table.
"""
from __future__ import annotations

import json

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.ground_record import RASTER, GroundRecord
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_all
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.review.actions import Ledger, propagation_provenance, resume_key, unit_status
from birdseye.birdseye_qgis.core.review.chips import (
    GEOTAG_COLOUR,
    LAYER_COLOURS,
    FrameIndex,
    ImageCache,
    RasterIndex,
    crop_window,
    load_chips,
    plan_point_chips,
    plan_raster_point_chips,
    plan_raster_unit_chips,
    plan_unit_chips,
    render_chip,
)
from birdseye.birdseye_qgis.core.review.digests import check_inputs, content_digest
from birdseye.birdseye_qgis.core.review.units import (
    ReviewLayer,
    ReviewParameters,
    UnitRef,
    added_key,
    build_units,
    complete_linkage_groups,
    position_key,
    propagation_groups,
)
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections
from birdseye.birdseye_qgis.core.scoring.verdicts import CONVENTIONS, VerdictLog

SITE = LocalFrame(-27.55, 151.95, 400.0)
FRAMES_EN = [(-1.0, 0.0), (0.0, 0.0), (1.0, 0.0), (2.0, 0.0)]   # m east/north of the site


def camera():
    t = np.eye(4)
    t[:3, :3] = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
    return CameraModel(480, 300, 500.0, 500.0, 239.5, 149.5, (0, 0, 0, 0, 0), t)


def poses(frames_en=FRAMES_EN):
    en = np.asarray(frames_en, dtype=float)
    lat, lon, h = SITE.to_geodetic(np.column_stack([en, np.full(len(en), 10.0)]))
    q = np.tile(rotmat_to_quat(euler_zyx_to_rotmat(0.0, 0.0, 0.0)), (len(en), 1))
    return FramePoses(np.arange(len(en)) + 100, lat, lon, h, q, np.full(len(en), SITE.h0), camera())


def ground_points(en):
    en = np.atleast_2d(np.asarray(en, dtype=float))
    lat, lon, h = SITE.to_geodetic(np.column_stack([en, np.zeros(len(en))]))
    return lat, lon, h


def detections_of(spots, name, score=0.8, jitter=0.0, seed=0):
    """Each spot (m east, north) detected in every frame that sees it, at its exact projection."""
    p = poses()
    geometry = FrameGeometry(p, SITE)
    lat, lon, h = ground_points(spots)
    local = SITE.from_geodetic(lat, lon, h)
    proj = project_all(geometry, local, LevelPlaneGround(geometry))
    proj = proj.select(proj.in_view)
    rng = np.random.default_rng(seed)
    pts = local[proj.point_idx] + np.column_stack([rng.normal(0, jitter, (len(proj.point_idx), 2)),
                                                   np.zeros(len(proj.point_idx))])
    dlat, dlon, dh = SITE.to_geodetic(pts)
    det = Detections(dlat, dlon, dh, p.frame_id[proj.frame_idx], np.full(len(pts), score), name=name)
    return ReviewLayer(det, proj.uv[:, 0], proj.uv[:, 1])


def geotags_at(en, ids=None):
    lat, lon, h = ground_points(en)
    return Geotags(np.asarray(ids if ids is not None else range(1, len(lat) + 1), dtype=object), lat, lon,
                   np.full(len(lat), np.nan))


def blob(cx, cy, n=3, step=0.03):
    """A small square of detection positions (n × n, step m) around (cx, cy)."""
    return [(cx + i * step, cy + j * step) for i in range(-(n // 2), n - n // 2) for j in range(-(n // 2), n - n // 2)]


S1, S2, S3 = (-0.5, 0.2), (0.6, -0.3), (1.5, 0.4)


@pytest.fixture
def two_layers():
    a = detections_of(blob(*S1) + blob(*S2), "model A")
    b = detections_of(blob(*S2) + blob(*S3), "model B", score=0.6)
    return [a, b]


def build(layers, geotags=None, **params):
    g = geotags if geotags is not None else geotags_at([S2])
    return build_units(layers, SITE, g, [poses()], ReviewParameters(**params))


# ---------------------------------------------------------------------------------------------- units
def test_units_are_consensus_clusters_that_record_which_layers_fired(two_layers):
    units = build(two_layers)
    assert len(units) == 3
    nearest = {spot: int(np.argmin(np.hypot(*(units.xy - SITE.from_geodetic(*ground_points(spot))[0, :2]).T)))
               for spot in (S1, S2, S3)}
    assert units.layers_fired[nearest[S1]] == ["model A"]
    assert units.layers_fired[nearest[S2]] == ["model A", "model B"]
    assert units.layers_fired[nearest[S3]] == ["model B"]
    # Every detection of a spot is in its unit; the unit's frames are the frames that saw the spot.
    for spot in (S1, S2, S3):
        k = nearest[spot]
        assert units.n_detections[k] == int((units.detection_unit == k).sum()) > 0
        assert units.n_frames[k] == len(set(units.detection_frame[units.detection_unit == k].tolist()))


def test_unmatched_units_come_first_and_matching_uses_eps_pred(two_layers):
    units = build(two_layers)
    matched = [units.keys[i] for i in units.order if units.matched[i]]
    assert len(matched) == 1 and units.order[-1] == units.index[matched[0]]
    assert units.matched_geotags[units.index[matched[0]]] == [1]
    # A geotag 0.25 m from S2 misses at eps_pred 0.20 m and matches at 0.30 m.
    far = geotags_at([(S2[0] + 0.25 + 0.03, S2[1])])
    assert not build(two_layers, far).matched.any()
    assert build(two_layers, far, eps_pred_m=0.30).matched.sum() == 1


def test_unit_keys_are_stable_and_positions_sit_on_core_cells(two_layers):
    units = build(two_layers)
    a, b = two_layers
    perm = np.random.default_rng(1).permutation(len(a.detections))
    shuffled = ReviewLayer(Detections(a.detections.lat[perm], a.detections.lon[perm], a.detections.height[perm],
                                         a.detections.frame_id[perm], a.detections.score[perm], name="model A"),
                              a.u[perm], a.v[perm])
    assert sorted(build([b, shuffled]).keys) == sorted(units.keys)
    core = units.clustering.points.xy[units.clustering.dbscan.core]
    for k, key in enumerate(units.keys):
        assert np.min(np.hypot(*(core - units.xy[k]).T)) == 0.0
        assert key == position_key("u", units.lat[k], units.lon[k]) and key.startswith("u-27.")


def test_a_chained_unit_is_placed_on_its_detections_not_between_them():
    # Two dense blobs 0.6 m apart joined by a bridge of single cells every 8 cm: one DBSCAN cluster
    # whose mean lies in the bridge's gap region, away from the heavy blobs.
    bridge = [(x, 0.0) for x in np.arange(-0.22, 0.23, 0.08)]
    spots = blob(-0.3, 0.0, 5, 0.02) + blob(0.3, 0.0, 5, 0.02) + bridge
    layer = detections_of(spots, "model A")
    units = build([layer], geotags_at([(5.0, 5.0)]), min_samples=1)
    assert len(units) == 1
    mean = units.clustering.summary.centroid[0]
    assert np.min(np.hypot(*(units.clustering.points.xy - units.xy[0]).T)) == 0.0
    assert np.hypot(*(units.xy[0] - mean)) < 0.08


def test_a_spot_whose_detections_share_one_cell_is_a_unit_unless_cells_are_counted():
    """Four frames see one spot at its exact position: four detections in one grid cell. Counting detections
    (the default) makes it a unit at minimum points 2; the method's reading (one point per cell) does not."""
    layer = detections_of([(0.5, 0.1)], "model A")
    assert len(layer.detections) == 4
    default = build([layer], geotags_at([(5.0, 5.0)]))
    assert len(default) == 1 and default.n_detections[0] == 4 and len(default.clustering.points) == 1
    assert len(build([layer], geotags_at([(5.0, 5.0)]), core_count="cells")) == 0
    assert ReviewParameters().postprocessing()["core_count"] == "detections"
    assert ReviewParameters(core_count="cells").operating_point().core_count == "cells"


def test_propagation_groups_chain_units_within_20_cm():
    xy = np.array([[0.0, 0.0], [0.15, 0.0], [0.30, 0.0], [0.61, 0.0], [5.0, 5.0]])
    g = propagation_groups(xy)
    assert g[0] == g[1] == g[2] and len({g[0], g[3], g[4]}) == 3
    wider = propagation_groups(xy, 0.32)
    assert wider[3] == wider[0] != wider[4]


# ---------------------------------------------------------------------------------------------- the method's units
def partition(labels, names):
    groups: dict = {}
    for name, label in zip(names, labels.tolist()):
        groups.setdefault(label, set()).add(name)
    return sorted(sorted(g) for g in groups.values())


def test_complete_linkage_groups_by_hand():
    # Frame 7: A–B 18 px, B–C 22 px, A–C 40 px: A and B join first, then {A, B}–C is 40 px > 30, so C
    # stays alone (single linkage at 30 px would chain all three). D–E 24, D–F 25, E–F 34.7: D and E
    # join, F stays alone. G–H exactly 30 px: together. Frame 8 repeats A and B: its own group.
    # Frame "x" has one detection.
    points = {"A": (7, 0, 0), "B": (7, 18, 0), "C": (7, 40, 0), "D": (7, 100, 100), "E": (7, 100, 124),
              "F": (7, 125, 100), "G": (7, 200, 0), "H": (7, 230, 0), "A8": (8.0, 0, 0), "B8": ("8", 18, 0),
              "X": ("x", 5, 5)}
    names = list(points)
    frame = np.array([v[0] for v in points.values()], dtype=object)
    uv = np.array([v[1:] for v in points.values()], dtype=float)
    labels = complete_linkage_groups(uv, frame, 30.0)
    assert partition(labels, names) == [["A", "B"], ["A8", "B8"], ["C"], ["D", "E"], ["F"], ["G", "H"], ["X"]]
    assert sorted(set(labels.tolist())) == list(range(7))
    # Numbering follows frames and pixel positions, not the input order.
    perm = np.random.default_rng(3).permutation(len(names))
    np.testing.assert_array_equal(complete_linkage_groups(uv[perm], frame[perm], 30.0), labels[perm])
    # A smaller radius splits G from H and A from B.
    assert ["G", "H"] not in partition(complete_linkage_groups(uv, frame, 17.0), names)


def test_method_units_are_per_frame_groups_of_the_detections_no_geotag_matches(two_layers):
    method = ReviewParameters(units="method")
    units = build(two_layers, geotags_at([S2]), units="method")
    # S2 (both layers) is matched detection by detection and set aside; S1 (A) and S3 (B) are seen by
    # all four frames: one unit per spot and frame.
    assert len(units) == 8 and not units.matched.any()
    assert sorted(k.rsplit("@", 1)[1] for k in units.keys) == sorted(["100", "101", "102", "103"] * 2)
    s1, s2 = (SITE.from_geodetic(*ground_points(spot))[0, :2] for spot in (S1, S2))
    xy = np.concatenate([layer.detections.ground_positions(SITE).xy for layer in two_layers])
    np.testing.assert_array_equal(units.detection_unit == -1, np.hypot(*(xy - s2).T) < 0.1)
    at_s1 = np.hypot(*(units.xy - s1).T) < 0.05
    assert at_s1.sum() == 4
    for k in range(len(units)):
        mine = units.detection_unit == k
        assert units.n_frames[k] == 1 and len(set(units.detection_frame[mine].tolist())) == 1
        assert units.n_detections[k] == mine.sum() == 9
        assert units.layers_fired[k] == (["model A"] if at_s1[k] else ["model B"])
    # The same spot in four frames: one propagation group per spot.
    assert len(set(units.propagation_group[at_s1].tolist())) == 1
    assert set(units.propagation_group[at_s1].tolist()).isdisjoint(units.propagation_group[~at_s1].tolist())
    assert units.clustering is None and method.postprocessing()["units"] == "method"
    assert method.postprocessing()["group_px"] == 30.0 and "group_px" not in ReviewParameters().postprocessing()


def test_method_matching_is_per_detection_and_the_rest_of_a_spot_is_one_unit_per_frame(two_layers):
    # A geotag 0.215 m east of S2: of each layer's 3 × 3 blob (3 cm steps) only the east column is
    # within 0.20 m (0.185–0.188 m); the six others (0.215–0.247 m) stay, both layers' together.
    units = build(two_layers, geotags_at([(S2[0] + 0.215, S2[1])]), units="method")
    s2 = SITE.from_geodetic(*ground_points(S2))[0, :2]
    at_s2 = np.flatnonzero(np.hypot(*(units.xy - s2).T) < 0.05)
    assert len(at_s2) == 4 and len(units) == 12
    for k in at_s2.tolist():
        assert units.layers_fired[k] == ["model A", "model B"] and units.n_detections[k] == 12
    set_aside = units.detection_unit == -1
    assert set_aside.sum() == 2 * 3 * 4
    east = SITE.from_geodetic(*ground_points([(S2[0] + 0.215, S2[1])]))[0, :2]
    xy = np.concatenate([layer.detections.ground_positions(SITE).xy for layer in two_layers])
    np.testing.assert_array_equal(set_aside, np.hypot(*(xy - east).T) <= 0.20)


def test_method_unit_keys_are_stable_and_the_construction_is_checked(two_layers):
    units = build(two_layers, units="method")
    a, b = two_layers
    perm = np.random.default_rng(2).permutation(len(a.detections))
    shuffled = ReviewLayer(Detections(a.detections.lat[perm], a.detections.lon[perm], a.detections.height[perm],
                                      a.detections.frame_id[perm], a.detections.score[perm], name="model A"),
                           a.u[perm], a.v[perm])
    assert sorted(build([b, shuffled], units="method").keys) == sorted(units.keys)
    for k, key in enumerate(units.keys):
        assert key.startswith(position_key("u", units.lat[k], units.lon[k]) + "@")
    with pytest.raises(InputError, match="field 'units'.*'clusters' is not a way to build review units"):
        ReviewParameters(units="clusters")
    with pytest.raises(InputError, match="field 'group_px'"):
        ReviewParameters(units="method", group_px=0.0)


# ---------------------------------------------------------------------------------------------- ledger
def stored(ledger, planned, action, undoes=None):
    """Append planned rows as the store would (fid and action id in order)."""
    fid = len(ledger.rows) + 1
    action_id = max([r["action_id"] for r in ledger.rows], default=0) + 1
    rows = [{"fid": fid + k, "unit_key": p.unit_key, "verdict": p.verdict, "provenance": p.provenance,
             "action_id": action_id, "action": action, "undoes": undoes, "lat": p.lat, "lon": p.lon,
             "layers_fired": json.dumps(list(p.layers_fired)), "time": "", "reviewer": "t"}
            for k, p in enumerate(planned)]
    ledger.extend(rows)
    return rows


A, B, C = (UnitRef(k, -27.55, 151.95 + i * 1e-6, ("m",)) for i, k in enumerate(("uA", "uB", "uC")))


def test_propagation_writes_one_vote_per_source_and_conflicts_resolve_under_three_conventions():
    ledger = Ledger()
    stored(ledger, ledger.plan_verdict(A, "confirmed_real", [B, C], propagate=True), "verdict")
    stored(ledger, ledger.plan_verdict(B, "hard_negative", [A, C], propagate=True), "verdict")
    prov_a, prov_b = propagation_provenance("uA"), propagation_provenance("uB")
    assert prov_a == "propagated:dbscan_0.20m/uA"
    assert ledger.votes("uC") == {prov_a: "confirmed_real", prov_b: "hard_negative"}
    log = ledger.verdict_log()
    resolved = {c: log.resolve("uC", c) for c in CONVENTIONS}
    assert resolved == {"positive_wins": "confirmed_real", "majority_wins": "uncertain",
                        "hard_negative_wins": "hard_negative"}
    # B: its own hard_negative and A's propagated confirmed_real — the same spread.
    status = unit_status(log, ledger, "uB")
    assert status.direct == "hard_negative" and status.conflict and not status.propagated_only
    assert unit_status(log, ledger, "uC").propagated_only


def test_propagated_votes_follow_their_source_even_with_propagation_off():
    ledger = Ledger()
    stored(ledger, ledger.plan_verdict(A, "confirmed_real", [B], propagate=True), "verdict")
    rows = ledger.plan_verdict(A, "hard_negative", [B, C], propagate=False)
    assert [(r.unit_key, r.verdict, r.provenance) for r in rows] == [
        ("uA", "hard_negative", "direct"), ("uB", "hard_negative", propagation_provenance("uA"))]
    stored(ledger, rows, "verdict")
    assert ledger.plan_verdict(A, "hard_negative", [B, C]) == []   # nothing would change
    assert ledger.propagated_from("uA") == ["uB"]


def test_undo_restores_every_slot_and_the_stack_is_rebuilt_from_the_log():
    ledger = Ledger()
    stored(ledger, ledger.plan_verdict(A, "uncertain"), "verdict")
    stored(ledger, ledger.plan_verdict(A, "confirmed_real", [B, C], propagate=True), "verdict")
    stored(ledger, ledger.plan_add(-27.5501, 151.9502), "add")
    key = added_key(-27.5501, 151.9502)
    assert [t.key for t in ledger.added_targets()] == [key]
    for expected_open in ([1, 2], [1]):
        action, rows = ledger.plan_undo()
        stored(ledger, rows, "undo", undoes=action)
        assert Ledger(ledger.rows).open_actions() == ledger.open_actions() == expected_open
    # The add is withdrawn, A is back to uncertain, the propagated votes withdrawn.
    assert ledger.added_targets() == [] and ledger.direct(key) == "unreviewed"
    assert ledger.direct("uA") == "uncertain" and ledger.votes("uB") == {} and ledger.votes("uC") == {}
    log = VerdictLog.from_records(ledger.rows)
    assert log.added_targets() == [] and log.resolve("uB", "positive_wins") == "unreviewed"
    action, rows = ledger.plan_undo()
    stored(ledger, rows, "undo", undoes=action)
    assert ledger.plan_undo() == (None, []) and ledger.direct("uA") == "unreviewed"
    assert len(ledger.rows) == 1 + 3 + 1 + 1 + 3 + 1   # three actions, three undos; nothing deleted


def test_resume_prefers_the_cursor_then_the_unit_after_the_last_reviewed():
    order = ["u1", "u2", "u3", "u4"]
    ledger = Ledger()
    assert resume_key(order, ledger, None) == "u1"
    stored(ledger, ledger.plan_verdict(UnitRef("u2", 0, 0), "confirmed_real"), "verdict")
    assert resume_key(order, ledger, None) == "u3"
    assert resume_key(order, ledger, "u1") == "u1"
    assert resume_key(order, ledger, "gone") == "u3"
    assert resume_key([], ledger, "u1") is None


# ---------------------------------------------------------------------------------------------- digests
def test_content_digest_ignores_order_and_number_type_but_sees_any_change():
    rows = [[1, 10.5, "m.onnx", 3.25, 4.5, 400.0], [2, 11.0, "m.onnx", 3.5, 4.5, None]]
    fields = ["frame_id", "u", "model", "x", "y", "z"]
    d = content_digest("detections", "EPSG:32756", fields, rows)
    assert len(d) == 64
    assert content_digest("detections", "EPSG:32756", fields, rows[::-1]) == d
    assert content_digest("detections", "EPSG:32756", fields, [[1.0] + rows[0][1:], rows[1]]) == d
    moved = [rows[0][:3] + [3.25 + 1e-9] + rows[0][4:], rows[1]]
    assert content_digest("detections", "EPSG:32756", fields, moved) != d
    assert content_digest("detections", "EPSG:32755", fields, rows) != d
    assert content_digest("detections", "EPSG:32756", fields, rows[:1]) != d


def digest_row(unit, digests, params=None, provenance="direct", verdict="confirmed_real"):
    return {"unit_key": unit, "verdict": verdict, "provenance": provenance, "input_digests": json.dumps(digests),
            "postprocessing": json.dumps(params or {"eps_m": 0.1}), "matching_parameters": json.dumps({})}


def test_check_inputs_reports_changed_layers_parameters_and_orphans():
    now = {"detections:A": "d1", "frames:F": "f1", "geotags:G": "g1"}
    rows = [digest_row("u1", now), digest_row("u2", {**now, "detections:A": "d0"}),
            digest_row("u3", {**now, "detections:A": "d0"}, {"eps_m": 0.15}),
            digest_row("x9", {"detections:Other": "o"})]             # another review in the same GeoPackage
    check = check_inputs(rows, now, {"eps_m": 0.1}, ["u1", "u2"])
    assert check.n_rows == 3 and not check.ok
    assert check.changed == {"detections:A": 2} and check.missing == {} and check.new == []
    assert check.parameters == {"eps_m": ([0.15], 0.1)}
    assert check.orphaned == ["u3"]
    messages = " ".join(check.messages())
    assert "'A' changed since 2 of 3" in messages and "eps_m" in messages and "u3" in messages
    same = check_inputs(rows[:1], now, {"eps_m": 0.1}, ["u1"])
    assert same.ok and same.messages() == []
    extra = check_inputs(rows[:1], {**now, "detections:B": "b"}, {"eps_m": 0.1}, ["u1"])
    assert extra.ok and extra.new == ["detections:B"]


def test_verdicts_recorded_before_core_count_was_recorded_were_clustered_counting_cells():
    now = {"detections:A": "d1"}
    old = [digest_row("u1", now, {"eps_m": 0.1})]
    check = check_inputs(old, now, {"eps_m": 0.1, "core_count": "detections"}, ["u1"])
    assert check.parameters == {"core_count": (["cells"], "detections")}
    assert "Parameter core_count was cells" in " ".join(check.messages())
    assert check_inputs(old, now, {"eps_m": 0.1, "core_count": "cells"}, ["u1"]).ok
    recorded = [digest_row("u1", now, {"eps_m": 0.1, "core_count": "detections"})]
    assert check_inputs(recorded, now, {"eps_m": 0.1, "core_count": "detections"}, ["u1"]).ok


# ---------------------------------------------------------------------------------------------- chips
@pytest.mark.parametrize("u, v, size, expected", [
    (100.0, 80.0, 64, (68, 48, 132, 112)),
    (3.0, 2.0, 64, (0, 0, 64, 64)),
    (479.0, 299.0, 64, (416, 236, 480, 300)),
    (10.0, 10.0, 400, (0, 0, 400, 300)),
])
def test_crop_window_stays_inside_the_image(u, v, size, expected):
    window = crop_window(u, v, size, 480, 300)
    assert window == expected
    x0, y0, x1, y1 = window
    assert 0 <= x0 < x1 <= 480 and 0 <= y0 < y1 <= 300


def test_chips_show_the_unit_where_it_was_detected_and_geotags_where_they_project(two_layers, tmp_path):
    import cv2

    g = geotags_at([S2, (S2[0] + 0.1, S2[1] + 0.05), (9.0, 9.0)])
    units = build(two_layers, g)
    frames = FrameIndex([poses()], [[str(tmp_path / f"{i}.png") for i in range(len(FRAMES_EN))]], SITE)
    g_local = SITE.from_geodetic(g.lat, g.lon, np.full(len(g), SITE.h0))
    k = int(np.flatnonzero(units.matched)[0])
    plans, n_frames = plan_unit_chips(units, k, frames, g_local, [str(i) for i in g.ids], window_px=64,
                                         max_chips=2)
    assert n_frames == units.n_frames[k] > 2 and len(plans) == 2
    for plan in plans:
        x0, y0, x1, y1 = plan.window
        assert (x1 - x0, y1 - y0) == (64, 64)
        assert {m[2] for m in plan.detections} == {0, 1}           # both layers fired in this frame
        # Detections are exact projections of the blob: the first geotag (at the blob's centre
        # cell) projects onto the centre detection; the one 9 m away is not drawn.
        labels = [c[2] for c in plan.geotags]
        assert labels == ["1", "2"]
        centre = min(plan.detections, key=lambda m: np.hypot(m[0] - plan.geotags[0][0], m[1] - plan.geotags[0][1]))
        assert np.hypot(centre[0] - plan.geotags[0][0], centre[1] - plan.geotags[0][1]) < 1e-6
        # 0.1 m east, 0.05 m north at 2 cm/px: 5 px right, 2.5 px up
        assert plan.geotags[1][0] - plan.geotags[0][0] == pytest.approx(5.0, abs=0.05)
        assert plan.geotags[1][1] - plan.geotags[0][1] == pytest.approx(-2.5, abs=0.05)
    # Rendering: a grey frame, the circle in the first layer's colour around the detection.
    image = np.full((300, 480, 3), 128, np.uint8)
    cv2.imwrite(plans[0].image, image)
    chip = load_chips(plans[:1], 128, ImageCache())[0]
    assert chip.shape == (128, 128, 3)
    colours = {tuple(c) for c in chip.reshape(-1, 3).tolist()}
    assert GEOTAG_COLOUR in colours and (128, 128, 128) in colours
    assert any(np.allclose(c, LAYER_COLOURS[0], atol=40) for c in colours)
    missing = render_chip(None, plans[1], 96)
    assert missing.shape == (96, 96, 3)


def test_an_added_target_gets_chips_from_the_frames_that_see_it(tmp_path):
    frames = FrameIndex([poses()], [["" for _ in FRAMES_EN]], SITE)
    lat, lon, _ = ground_points([(0.9, 0.1)])
    plans, n = plan_point_chips("a", float(lat[0]), float(lon[0]), frames, window_px=64, max_chips=3)
    assert n == 4 and len(plans) == 3
    assert [p.frame_id for p in plans] == [102, 101, 103]   # most central first (0.1, 0.9, 1.1 m away)
    u, v, layer = plans[0].detections[0]
    x0, y0, _, _ = plans[0].window
    # 0.1 m west and 0.1 m north of that frame's centre, at 2 cm/px
    assert layer == -1 and (u + x0, v + y0) == pytest.approx((239.5 - 5.0, 149.5 - 5.0), abs=0.01)


# ---------------------------------------------------------------------------------------------- a raster
def raster_layer(spots, px_of, name="on mosaic", score=0.7):
    """One detection per spot (m east, north), found on a raster: frame 0, (u, v) its pixel ``px_of(spot)``."""
    lat, lon, _ = ground_points(spots)
    det = Detections(lat, lon, np.full(len(lat), np.nan), np.zeros(len(lat), dtype=int),
                     np.full(len(lat), score), name=name, ground=GroundRecord(RASTER, "/data/ortho.tif"))
    uv = np.array([px_of(s) for s in spots], dtype=float)
    return ReviewLayer(det, uv[:, 0], uv[:, 1])


def test_raster_units_take_the_rasters_in_view_mask_and_one_detection_is_a_unit():
    """No frames: a geotag is in view when the mask says so (the raster covers it); one detection is a target, so each
    spot is a unit at the default minimum points (2)."""
    layer = raster_layer([S1, S2, S3], lambda s: (100 + 100 * s[0], 100 - 100 * s[1]))
    g = geotags_at([S1, S2])
    for units_kind in ("consensus", "method"):
        covered = build_units([layer], SITE, g, [], ReviewParameters(units=units_kind), view_mask=[True, False])
        if units_kind == "consensus":
            assert len(covered) == 3 and covered.matched.sum() == 1
            assert covered.matched_geotags[int(np.flatnonzero(covered.matched)[0])] == [1]
        else:   # the method sets aside detections on an in-view geotag: S1's
            assert len(covered) == 2 and set(covered.n_frames.tolist()) == {1}
    with pytest.raises(InputError, match="in-view mask has 1 entries for 2 geotags"):
        build_units([layer], SITE, g, [], ReviewParameters(), view_mask=[True])


def test_a_raster_units_chip_is_a_window_of_raster_pixels_around_it_with_the_geotags_inside():
    layer = raster_layer([S1, S2], lambda s: (30.0, 40.0) if s == S1 else (500.0, 200.0))
    units = build_units([layer], SITE, geotags_at([S1]), [], ReviewParameters(), view_mask=[True])
    raster = RasterIndex("/data/ortho.tif", 600, 300, np.array([[31.0, 38.5], [np.nan, np.nan]]), ["7", "8"])
    k = units.index[next(key for key in units.keys if units.matched[units.index[key]])]
    (plan,), n = plan_raster_unit_chips(units, k, raster, window_px=64)
    assert n == 1 and plan.image == "/data/ortho.tif" and plan.frame_id == 0
    assert plan.window == (0, 8, 64, 72)                      # moved inside the raster at its top-left corner
    assert plan.detections == [(30.0, 32.0, 0)] and plan.geotags == [(31.0, 30.5, "7")]
    other = 1 - k
    (plan,), _ = plan_raster_unit_chips(units, other, raster, window_px=64)
    assert plan.window == (468, 168, 532, 232) and plan.geotags == []
    # An added target: on the raster, a chip around its pixel; off it, none.
    (plan,), n = plan_raster_point_chips("a", 590.0, 10.0, raster, window_px=64)
    assert n == 1 and plan.window == (536, 0, 600, 64) and plan.detections == [(54.0, 10.0, -1)]
    assert plan_raster_point_chips("a", 650.0, 10.0, raster) == ([], 0)

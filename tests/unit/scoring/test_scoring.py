"""Scores against hand-computed fixtures: in view, recovered, hit, recall/GMCF, pooling, POST.

The fixture field (metres east/north of a site) is scored by one nadir frame 10 m above level ground
with an undistorted 1920 × 1200 px camera, fx = fy = 1000 px, principal point at the image centre:
its footprint spans ±9.6 m east and ±6 m north (half-size (W/2)/fx · 10 m), so which geotags are in
view follows from the numbers alone.
"""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.clustering import GroundPositions, cluster_detections
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, evaluate_flights
from birdseye.birdseye_qgis.core.scoring.matching import in_view, match_to_clusters
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint
from birdseye.birdseye_qgis.core.scoring.post_review import ReviewedFlight, post_scores
from birdseye.birdseye_qgis.core.scoring.pre_review import PreCounts, pool, score_flight
from birdseye.birdseye_qgis.core.scoring.verdicts import CONVENTIONS, Verdict, VerdictLog, combine

SITE = LocalFrame(-27.55, 151.95, 400.0)
NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


def camera():
    t = np.eye(4)
    t[:3, :3] = NADIR
    return CameraModel(1920, 1200, 1000.0, 1000.0, 959.5, 599.5, (0, 0, 0, 0, 0), t)


def poses_over(east_north, agl=10.0, first_id=0):
    """Level nadir frames (yaw 0: image up = north) over the given site offsets (m)."""
    en = np.atleast_2d(np.asarray(east_north, dtype=float))
    lat, lon, h = SITE.to_geodetic(np.column_stack([en, np.full(len(en), agl)]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(len(en)), np.zeros(len(en)), np.zeros(len(en))))
    return FramePoses(np.arange(first_id, first_id + len(en)), lat, lon, h, q, np.full(len(en), SITE.h0),
                      camera())


def grid9(cx, cy, step=0.04):
    g = np.array([(cx + i * step, cy + j * step) for i in (-1, 0, 1) for j in (-1, 0, 1)])
    return g


# -------------------------------------------------------------------- the flight-1 fixture, in metres
CHAIN = np.column_stack([-8.0 + 0.08 * np.arange(9), np.zeros(9)])   # core: the 7 interior points
B, C = grid9(-3.0, 0.0), grid9(-2.65, 0.0)                           # 0.27 m apart: two clusters
D, E = grid9(9.75, 3.0), grid9(5.0, -3.0)
NOISE = np.array([[0.0, 4.0], [1.0, 4.0]])
FLIGHT1_DETECTIONS = np.concatenate([CHAIN, B, C, D, E, NOISE])
FLIGHT1_GEOTAGS = {                      # id: (east, north), in view?, recovered?
    "g1": ((-7.30, 0.0), True, True),      # 0.14 m from the chain's last core point
    "g_border": ((-7.21, 0.0), True, False),  # 0.15 m from a border point, 0.23 m from a core point
    "g2": ((-2.825, 0.0), True, True),     # 0.135 m from both B and C: both are hits
    "g3": ((9.70, 3.0), False, False),     # beside D but outside the footprint (east > 9.6 m)
    "g4": ((0.05, 4.0), True, False),      # beside a noise point only
    "g5": ((6.0, 5.0), True, False),       # far from everything
    "g6": ((12.0, 0.0), False, False),     # outside the footprint
}
# flight 2: one frame 100 m east; F is hit by h1, G is unmatched, h2 is missed
F, G = grid9(100.0, 1.0), grid9(98.0, -2.0)
FLIGHT2_DETECTIONS = np.concatenate([F, G])
FLIGHT2_GEOTAGS = {"h1": ((100.1, 1.0), True, True), "h2": ((103.0, -2.0), True, False)}
OP = OperatingPoint(threshold=None, dedup_cm=3, eps_m=0.10, min_samples=3, eps_pred_m=0.20)


def geodetic(en):
    en = np.atleast_2d(np.asarray(en, dtype=float))
    return SITE.to_geodetic(np.column_stack([en, np.zeros(len(en))]))


def detections(en, name):
    lat, lon, h = geodetic(en)
    n = len(lat)
    return Detections(lat, lon, h, np.arange(n) % 4, np.linspace(0.5, 0.9, n), name=name)


def all_geotags():
    tags = {**FLIGHT1_GEOTAGS, **FLIGHT2_GEOTAGS}
    lat, lon, _ = geodetic([v[0] for v in tags.values()])
    return Geotags(list(tags), lat, lon, np.full(len(lat), np.nan))


def flights():
    return [Flight(detections(FLIGHT1_DETECTIONS, "flight 1"), [poses_over([0.0, 0.0])], "flight 1"),
            Flight(detections(FLIGHT2_DETECTIONS, "flight 2"), [poses_over([100.0, 0.0], first_id=50)], "flight 2")]


# -------------------------------------------------------------------- in view
def test_in_view_follows_the_closed_form_footprint_and_the_edge_buffer():
    en = np.array([[9.5, 0.0], [9.7, 0.0], [-9.5, 5.9], [0.0, 6.1], [0.0, -5.95], [3.0, 2.0]])
    pts = SITE.from_geodetic(*geodetic(en))
    groups = [poses_over([0.0, 0.0])]
    np.testing.assert_array_equal(in_view(groups, SITE, pts).mask, [True, False, True, False, True, True])
    # 9.5 m east is u = 959.5 + 950 = 1909.5 px: 10 px from the right edge; 5.95 m south is 5 px in.
    # (-9.5, 5.9) is at u = 9.5, v = 9.5 px: 10 px in from the top-left corner.
    np.testing.assert_array_equal(in_view(groups, SITE, pts, edge_buffer_px=8).mask,
                                  [True, False, True, False, False, True])
    np.testing.assert_array_equal(in_view(groups, SITE, pts, edge_buffer_px=12).mask,
                                  [False, False, False, False, False, True])


def test_frames_without_ground_height_are_not_processed():
    p = poses_over([[0.0, 0.0], [30.0, 0.0]])
    p.ground_height[1] = np.nan
    pts = SITE.from_geodetic(*geodetic([[30.0, 0.0], [0.0, 0.0]]))
    v = in_view([p], SITE, pts)
    np.testing.assert_array_equal(v.mask, [False, True])
    assert (v.n_frames, v.n_frames_without_ground) == (1, 1)


# -------------------------------------------------------------------- recovered, hit, PRE
def flight1_score():
    clustering = cluster_detections(GroundPositions.from_local(SITE, FLIGHT1_DETECTIONS), None, None, OP.dedup_cm,
                                    OP.eps_m, OP.min_samples)
    xy = np.array([v[0] for v in FLIGHT1_GEOTAGS.values()])
    visible = np.array([v[1] for v in FLIGHT1_GEOTAGS.values()])
    return clustering, score_flight(clustering, xy, visible, OP.eps_pred_m)


def cluster_of(clustering, points):
    """The one cluster label of a fixture group's detections."""
    labels = clustering.dbscan.labels[clustering.points.inverse]
    idx = [int(np.flatnonzero(np.all(np.isclose(FLIGHT1_DETECTIONS, p), axis=1))[0]) for p in points]
    found = set(labels[idx].tolist())
    assert len(found) == 1
    return found.pop()


def test_recovered_and_hit_follow_the_definitions_by_hand():
    clustering, s = flight1_score()
    assert clustering.n_clusters == 5
    np.testing.assert_array_equal(s.recovered, [v[2] for v in FLIGHT1_GEOTAGS.values()])
    hits = {cluster_of(clustering, grp) for grp in (CHAIN, B, C)}
    assert set(np.flatnonzero(s.cluster_hit).tolist()) == hits
    # g2 is matched to both B and C; D's neighbour g3 is not in view, so D is not a hit.
    ids = list(FLIGHT1_GEOTAGS)
    assert [ids[i] for i in s.cluster_geotags[cluster_of(clustering, B)]] == ["g2"]
    assert [ids[i] for i in s.cluster_geotags[cluster_of(clustering, C)]] == ["g2"]
    assert len(s.cluster_geotags[cluster_of(clustering, D)]) == 0
    k = s.counts
    assert (k.n_in_view, k.n_recovered, k.n_clusters, k.n_hit_clusters, k.n_geotag_matches) == (5, 2, 5, 3, 3)
    assert k.recall_pre == pytest.approx(2 / 5) and k.gmcf_pre == pytest.approx(3 / 5)
    assert k.mean_geotags_per_hit_cluster == pytest.approx(1.0)


def test_recovery_needs_a_core_point_not_any_cluster_point():
    clustering, _ = flight1_score()
    g_border = np.array([[-7.21, 0.0]])
    assert len(match_to_clusters(clustering.core_xy, clustering.core_cluster, g_border, 0.20).point) == 0
    # the same geotag is within 0.2 m of the chain's border point
    assert np.hypot(*(CHAIN[-1] - g_border[0])) < 0.20
    assert len(match_to_clusters(clustering.core_xy, clustering.core_cluster, g_border, 0.24).point) == 1


def test_pooling_is_a_micro_average_and_differs_from_the_macro_average():
    ev = evaluate_flights(flights(), all_geotags(), OP)
    f1, f2 = (f.score.counts for f in ev.flights)
    assert (f1.n_in_view, f1.n_recovered, f1.n_clusters, f1.n_hit_clusters) == (5, 2, 5, 3)
    assert (f2.n_in_view, f2.n_recovered, f2.n_clusters, f2.n_hit_clusters) == (2, 1, 2, 1)
    assert pool([f1, f2]) == ev.pooled
    assert ev.pooled.recall_pre == pytest.approx(3 / 7)
    assert ev.pooled.gmcf_pre == pytest.approx(4 / 7)
    macro_recall = (2 / 5 + 1 / 2) / 2
    macro_gmcf = (3 / 5 + 1 / 2) / 2
    assert abs(ev.pooled.recall_pre - macro_recall) > 0.02 and abs(ev.pooled.gmcf_pre - macro_gmcf) > 0.02
    d = ev.to_dict()
    for key in ("n_in_view", "n_recovered", "recall_pre", "n_clusters", "n_hit_clusters", "gmcf_pre"):
        assert key in d
    assert d["n_in_view"] == 7 and d["n_hit_clusters"] == 4 and "post" not in d


def test_threshold_of_the_operating_point_drops_low_scores_before_clustering():
    fl = flights()
    # flight 1 scores rise linearly; a threshold above the chain's scores removes the chain's cluster
    chain_scores = fl[0].detections.score[:len(CHAIN)]
    op = OperatingPoint(threshold=float(chain_scores.max()) + 1e-9)
    ev = evaluate_flights(fl[:1], all_geotags(), op)
    assert ev.flights[0].n_detections == len(FLIGHT1_DETECTIONS) - len(CHAIN)
    assert ev.flights[0].score.counts.n_recovered == 1  # g1 lost with the chain


# -------------------------------------------------------------------- verdicts and POST
def rows_for_fixture():
    lat, lon, _ = geodetic([D.mean(0), E.mean(0), B.mean(0), G.mean(0), [0.5, 4.0], [7.0, -5.0], [6.0, -5.0],
                            [12.0, 5.0]])
    at = dict(zip(["D", "E", "B", "G", "noise", "t1", "t2", "t3"], zip(lat.tolist(), lon.tolist())))

    def row(unit, verdict, provenance="direct", time="2024-05-01T10:00:00Z", where=None):
        la, lo = at[where or unit] if (where or unit) in at else (None, None)
        return {"unit_key": unit, "verdict": verdict, "provenance": provenance, "time": time,
                "reviewer": "ana", "lat": la, "lon": lo}

    return [
        row("u1", "confirmed_real", where="D"),
        row("u1", "hard_negative", "propagated:dbscan_0.20m", "2024-05-01T10:05:00Z", where="D"),
        row("u2", "confirmed_real", where="E"),
        row("u2", "confirmed_real", "propagated:a", where="E"),
        row("u2", "hard_negative", "propagated:b", where="E"),
        row("u3", "hard_negative", where="B"),                       # on a hit cluster: changes nothing
        row("u4", "hard_negative", time="2024-05-01T09:00:00Z", where="G"),
        row("u4", "confirmed_real", time="2024-05-01T11:00:00Z", where="G"),   # latest direct wins
        row("u5", "confirmed_real", where="noise"),                  # near noise only: attached nowhere
        row("t1", "added", where="t1"),                              # in view of flight 1
        row("t2", "added", time="2024-05-01T10:00:00Z", where="t2"),
        row("t2", "unreviewed", time="2024-05-01T10:01:00Z", where="t2"),      # withdrawn
        row("t3", "added", where="t3"),                              # in view of no flight
    ]


def test_post_scores_differ_by_convention_as_computed_by_hand():
    log = VerdictLog.from_records(rows_for_fixture())
    ev = evaluate_flights(flights(), all_geotags(), OP, log=log)
    # Flight 1 unmatched clusters: D (u1: confirmed vs hard negative), E (u2: 2 confirmed, 1 hard neg.);
    # flight 2: G (u4: confirmed). Added in view: t1 in flight 1.
    expected_c = {"positive_wins": 3, "majority_wins": 2, "hard_negative_wins": 1}
    for conv in CONVENTIONS:
        p = ev.post[conv].pooled
        assert (p.c, p.a) == (expected_c[conv], 1), conv
        assert p.gmcf_post == pytest.approx((4 + p.c) / 7)
        assert p.recall_post == pytest.approx((3 + p.c) / (7 + p.c + 1))
        assert [f.a for f in ev.post[conv].flights] == [1, 0]
    d = ev.to_dict()
    assert d["post"]["majority_wins"]["recall_post"] == "0.500"           # a = 1: a point value
    assert d["post"]["majority_wins"]["recall_post_kind"] == "point_value"
    assert d["flights"][1]["post"]["majority_wins"]["recall_post"] == "≥ 0.667"   # a = 0: (1 + 1) / (2 + 1)
    assert d["post"]["positive_wins"]["gmcf_post"] == pytest.approx(1.0)
    assert d["flights"][1]["post"]["hard_negative_wins"]["c"] == 1


def test_a_cluster_resolves_once_over_all_judgements_of_its_units():
    log = VerdictLog([Verdict("u1", "confirmed_real"), Verdict("u1", "confirmed_real", "propagated:r"),
                      Verdict("u1", "hard_negative", "propagated:s"), Verdict("u2", "uncertain")])
    assert log.resolve("u1", "majority_wins") == "confirmed_real"
    counts = PreCounts(n_in_view=4, n_recovered=2, n_clusters=3, n_hit_clusters=1)
    flight = ReviewedFlight(counts, [True, False, False], [("u2",), ("u1", "u2"), ("u1",)], n_added=2)
    post = post_scores(log, [flight])
    # cluster 1: judgements C, C, HN and u2's U (an abstention): 2 to 1, confirmed under majority and
    # positive-wins; the hard-negative vote makes hard-negative-wins say hard negative. Cluster 2 the same.
    assert post["majority_wins"].pooled.c == 2
    assert post["positive_wins"].pooled.c == 2
    assert post["hard_negative_wins"].pooled.c == 0
    p = post["positive_wins"].pooled
    assert p.recall_post == pytest.approx((2 + 2) / (4 + 2 + 2))


def test_combine_conventions_and_withdrawn_votes():
    assert combine([], "positive_wins") == "unreviewed"
    assert combine(["unreviewed"], "majority_wins") == "unreviewed"
    assert combine(["hard_negative", "uncertain"], "positive_wins") == "hard_negative"
    assert combine(["confirmed_real", "uncertain"], "hard_negative_wins") == "confirmed_real"
    assert combine(["confirmed_real", "hard_negative", "hard_negative"], "majority_wins") == "hard_negative"
    assert combine(["confirmed_real", "hard_negative"], "majority_wins") == "uncertain"
    log = VerdictLog([Verdict("u", "confirmed_real", time="2024-01-01T10:00:00"),
                      Verdict("u", "unreviewed", time="2024-01-01T10:00:00+00:00", sequence=1)])
    assert log.votes("u") == [] and log.resolve("u", "positive_wins") == "unreviewed"
    # the same time: the later row of the log wins; an earlier time loses whatever its position
    log = VerdictLog([Verdict("u", "hard_negative", time="2024-01-01T12:00:00Z", sequence=5),
                      Verdict("u", "confirmed_real", time="2024-01-01T11:00:00Z", sequence=9)])
    assert log.votes("u") == ["hard_negative"]


def test_bad_verdict_rows_are_refused_with_row_and_field():
    with pytest.raises(InputError, match="row 2, field 'verdict'"):
        VerdictLog.from_records([{"unit_key": "a", "verdict": "confirmed_real"},
                                 {"unit_key": "b", "verdict": "maybe"}], source="review.gpkg")
    with pytest.raises(InputError, match="field 'provenance'"):
        VerdictLog.from_records([{"unit_key": "a", "verdict": "uncertain", "provenance": "auto"}])
    with pytest.raises(InputError, match="field 'lat'"):
        VerdictLog.from_records([{"unit_key": "t", "verdict": "added"}])
    with pytest.raises(InputError, match="field 'time'"):
        VerdictLog.from_records([{"unit_key": "a", "verdict": "uncertain", "time": "yesterday"}])
    with pytest.raises(InputError, match="not a BirdsEye verdict log"):
        VerdictLog.from_records([{"key": "a"}])


def test_unplaced_units_are_reported_not_silently_dropped():
    log = VerdictLog([Verdict("u9", "confirmed_real")])
    ev = evaluate_flights(flights()[:1], all_geotags(), OP, log=log)
    assert any("u9" in n for n in ev.review_notes)
    assert all(ev.post[c].pooled.c == 0 for c in CONVENTIONS)


def test_operating_point_validation_names_the_parameter():
    with pytest.raises(InputError, match="EPS_M"):
        OperatingPoint(eps_m=0)
    with pytest.raises(InputError, match="MIN_SAMPLES"):
        OperatingPoint(min_samples=2.5)
    with pytest.raises(InputError, match="THRESHOLD"):
        OperatingPoint(threshold=1.5)
    assert OperatingPoint.from_dict(OperatingPoint(0.4).to_dict()) == OperatingPoint(0.4)
    assert OperatingPoint.from_dict({"min_samples": 5.0}).min_samples == 5
    with pytest.raises(InputError, match="min_samples must be a whole number.*2.5"):
        OperatingPoint.from_dict({"min_samples": 2.5})  # a sealed or typed 2.5 is not silently 2

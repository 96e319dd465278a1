"""Adjudication votes (abstentions, one majority per cluster) and which added targets count in ``a``.

The field is the one of test_scoring: one nadir frame 10 m above level ground at the site, footprint
±9.6 m east and ±6 m north, so what is in view follows from the numbers alone.
"""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.clustering import GroundPositions, cluster_detections
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground_record import RASTER, GroundRecord
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, added_in_view, evaluate_flights
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint
from birdseye.birdseye_qgis.core.scoring.post_review import (
    PostCounts,
    ReviewedFlight,
    countable_added_targets,
    post_scores,
)
from birdseye.birdseye_qgis.core.scoring.pre_review import PreCounts
from birdseye.birdseye_qgis.core.scoring.verdicts import CONVENTIONS, Verdict, VerdictLog, combine

C, HN, U, NONE = "confirmed_real", "hard_negative", "uncertain", "unreviewed"
SITE = LocalFrame(-27.55, 151.95, 400.0)
OP = OperatingPoint(threshold=None, dedup_cm=3, eps_m=0.10, min_samples=3, eps_pred_m=0.20)


def one_nadir_frame():
    """1920 × 1200 px, fx = fy = 1000 px, 10 m above the site, image up = north."""
    t = np.eye(4)
    t[:3, :3] = [[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]
    camera = CameraModel(1920, 1200, 1000.0, 1000.0, 959.5, 599.5, (0, 0, 0, 0, 0), t)
    lat, lon, h = SITE.to_geodetic(np.array([[0.0, 0.0, 10.0]]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.zeros(1), np.zeros(1), np.zeros(1)))
    return FramePoses(np.arange(1), lat, lon, h, q, np.full(1, SITE.h0), camera)


def geodetic(en):
    en = np.atleast_2d(np.asarray(en, dtype=float))
    return SITE.to_geodetic(np.column_stack([en, np.zeros(len(en))]))


def grid9(cx, cy, step=0.04):
    return np.array([(cx + i * step, cy + j * step) for i in (-1, 0, 1) for j in (-1, 0, 1)])


# -------------------------------------------------------------------- votes
@pytest.mark.parametrize("judgements, expected", [
    # uncertain and unreviewed abstain: they neither win nor break a majority
    ([C, U], {"positive_wins": C, "majority_wins": C, "hard_negative_wins": C}),
    ([C, C, HN, U, U], {"positive_wins": C, "majority_wins": C, "hard_negative_wins": HN}),
    ([HN, U, U, U], {"positive_wins": HN, "majority_wins": HN, "hard_negative_wins": HN}),
    ([C, HN, U, NONE], {"positive_wins": C, "majority_wins": U, "hard_negative_wins": HN}),   # a tie
    ([C, HN, HN, NONE, NONE, NONE], {"positive_wins": C, "majority_wins": HN, "hard_negative_wins": HN}),
    ([U, U], {c: U for c in CONVENTIONS}),                # someone looked, nobody voted
    ([U, NONE], {c: U for c in CONVENTIONS}),
    ([NONE], {c: NONE for c in CONVENTIONS}),             # nobody looked
    ([], {c: NONE for c in CONVENTIONS}),
])
def test_uncertain_and_unreviewed_are_abstentions(judgements, expected):
    assert {c: combine(judgements, c) for c in CONVENTIONS} == expected


def test_one_majority_over_every_judgement_of_a_cluster_not_a_vote_of_unit_resolutions():
    log = VerdictLog([Verdict("u1", C),
                      Verdict("u2", HN), Verdict("u2", HN, "propagated:dbscan_0.20m/u9"),
                      Verdict("u3", U), Verdict("u4", C), Verdict("u4", U, "propagated:dbscan_0.20m/u3")])
    # Resolving the units first would give u1 C against u2 HN, a tie; the judgements are 1 C to 2 HN.
    assert log.resolve("u1", "majority_wins") == C and log.resolve("u2", "majority_wins") == HN
    assert log.resolve_cluster(["u1", "u2"], "majority_wins") == HN
    # u3's uncertain and u4's propagated uncertain abstain: 1 C to 0.
    assert log.resolve_cluster(["u3", "u4"], "majority_wins") == C
    assert log.resolve_cluster(["u1", "u2", "u4"], "majority_wins") == U     # 2 C to 2 HN
    counts = PreCounts(n_in_view=5, n_recovered=3, n_clusters=4, n_hit_clusters=1)
    flight = ReviewedFlight(counts, [False, False, False, True], [("u1", "u2"), ("u3", "u4"), ("u1", "u2", "u4"),
                                                                   ("u4",)])
    post = post_scores(log, [flight])
    # the hit cluster never counts in c, whatever its verdicts
    assert {c: post[c].pooled.c for c in CONVENTIONS} == {"positive_wins": 3, "majority_wins": 1,
                                                          "hard_negative_wins": 1}


# -------------------------------------------------------------------- recall_post: "≥" only when a = 0
def test_recall_post_is_a_bound_without_added_targets_and_a_point_value_with_them():
    bound = PostCounts(n_in_view=8, n_recovered=5, n_clusters=10, n_hit_clusters=6, c=2, a=0)
    assert bound.recall_post == pytest.approx(7 / 10) and bound.gmcf_post == pytest.approx(8 / 10)
    d = bound.to_dict()
    assert (d["recall_post"], d["recall_post_kind"], d["recall_post_value"]) == ("≥ 0.700", "lower_bound",
                                                                               pytest.approx(0.7))
    point = PostCounts(n_in_view=8, n_recovered=5, n_clusters=10, n_hit_clusters=6, c=2, a=4)
    d = point.to_dict()
    assert (d["recall_post"], d["recall_post_kind"]) == ("0.500", "point_value")   # 7 / (8 + 2 + 4)
    assert (bound + point).to_dict()["recall_post"] == "0.583"                     # 14 / 24, pooled a = 4
    assert PostCounts().to_dict()["recall_post"] is None


# -------------------------------------------------------------------- which added targets count in a
BLOB = grid9(2.0, 1.0)                                              # one cluster, all 9 points core
CHAIN = np.column_stack([-8.0 + 0.08 * np.arange(9), np.zeros(9)])  # core: -7.92 … -7.44; border -8.0, -7.36
GEOTAG = np.array([[5.0, -3.0]])
ADDED = {                        # (east, north): counts in a?
    "alone": ((-1.0, -4.0), True),
    "beside the blob": ((2.0 + 0.04 + 0.19, 1.0), False),      # 0.19 m from the blob's corner core point
    "0.21 m from the blob": ((2.0 + 0.04 + 0.21, 1.0), True),
    "beside a border point only": ((-8.15, 0.0), True),       # 0.15 m from the border, 0.23 m from a core point
    "beside the geotag": ((5.0, -3.0 + 0.19), False),
    "0.21 m from the geotag": ((5.0, -3.0 - 0.21), True),
    "out of view": ((9.7, 0.0), False),                       # east of the 9.6 m footprint edge
}


def test_countable_added_targets_by_hand():
    clustering = cluster_detections(GroundPositions.from_local(SITE, np.concatenate([BLOB, CHAIN])), None, None,
                                    OP.dedup_cm, OP.eps_m, OP.min_samples)
    assert clustering.n_clusters == 2
    xy = np.array([v[0] for v in ADDED.values()])
    in_view = np.array([name != "out of view" for name in ADDED])
    mask = countable_added_targets(xy, in_view, clustering, GEOTAG, OP.eps_pred_m)
    assert dict(zip(ADDED, mask.tolist())) == {name: v[1] for name, v in ADDED.items()}
    # an out-of-view target stays out even far from everything; no clusters and no geotags: only view counts
    empty = cluster_detections(GroundPositions.from_local(SITE, np.empty((0, 2))), None, None, OP.dedup_cm,
                               OP.eps_m, OP.min_samples)
    np.testing.assert_array_equal(countable_added_targets(xy, in_view, empty, np.empty((0, 2)), 0.2), in_view)


def test_evaluation_counts_in_a_only_the_added_targets_the_definition_admits():
    lat, lon, h = geodetic(np.concatenate([BLOB, CHAIN]))
    n = len(lat)
    flight = Flight(Detections(lat, lon, h, np.zeros(n), np.full(n, 0.9), name="f"), [one_nadir_frame()], "f")
    glat, glon, _ = geodetic(GEOTAG)
    geotags = Geotags(["g"], glat, glon, np.full(1, np.nan))
    alat, alon, _ = geodetic([v[0] for v in ADDED.values()])
    log = VerdictLog([Verdict(f"a{k}", "added", lat=la, lon=lo) for k, (la, lo) in enumerate(zip(alat, alon))])
    ev = evaluate_flights([flight], geotags, OP, log=log)
    expected_a = sum(v[1] for v in ADDED.values())
    assert expected_a == 4
    for conv in CONVENTIONS:
        p = ev.post[conv].pooled
        assert p.a == expected_a and p.c == 0
        # the geotag is missed (no cluster near it): recall_post = (0 + 0) / (1 + 0 + 4), a point value
        assert p.to_dict()["recall_post"] == "0.000"


def test_on_a_raster_an_added_target_counts_where_the_raster_covers_it():
    """Detections found on a raster have no frames: the targets a reviewer added are in view where the raster
    covers them (``covers``, as its geotags), not by a frame's test that would leave every one out."""
    lat, lon, h = geodetic(BLOB)
    n = len(lat)
    det = Detections(lat, lon, np.full(n, np.nan), np.zeros(n), np.full(n, 0.9), name="mosaic",
                     ground=GroundRecord(RASTER, "/data/ortho.tif"))
    glat, glon, _ = geodetic(GEOTAG)
    geotags = Geotags(["g"], glat, glon, np.full(1, np.nan))
    spots = {"covered": ((-1.0, -4.0), True), "off the raster": ((30.0, 0.0), False),
             "beside the blob": ((2.0 + 0.04 + 0.19, 1.0), False)}   # the blob's spot: its verdict counts in c
    alat, alon, _ = geodetic([xy for xy, _ in spots.values()])
    log = VerdictLog([Verdict(f"a{k}", "added", lat=la, lon=lo) for k, (la, lo) in enumerate(zip(alat, alon))])
    east_of_site = SITE.to_geodetic(np.array([[20.0, 0.0, 0.0]]))[1][0]

    def covers(lat, lon):   # the raster: everything west of 20 m east of the site
        return np.asarray(lon) < east_of_site

    ev = evaluate_flights([Flight(det, [], "mosaic", covers=covers)], geotags, OP, log=log)
    assert ev.flights[0].n_added == 1 and ev.flights[0].in_view.mask.tolist() == [True]
    for conv in CONVENTIONS:
        assert ev.post[conv].pooled.a == 1
    alocal = SITE.from_geodetic(alat, alon, np.full(len(alat), SITE.h0))
    seen = added_in_view(Flight(det, [], "mosaic", covers=covers), SITE, alat, alon, alocal, OP.edge_buffer_px)
    assert seen.tolist() == [True, False, True]
    # A mosaic compared with frames (a view mask, no coverage function) counts added targets by its frames.
    mosaic = Flight(det, [one_nadir_frame()], "mosaic", None, np.array([True]))
    assert added_in_view(mosaic, SITE, alat, alon, alocal, OP.edge_buffer_px).tolist() == [True, False, True]


def test_pooled_counts_report_the_methods_f1():
    """f1_geo = 2·r·g/(r + g): recall 8/10 and GMCF 6/10 give 0.6857…; undefined without clusters."""
    counts = PreCounts(n_in_view=10, n_recovered=8, n_clusters=10, n_hit_clusters=6)
    assert counts.to_dict()["f1_geo"] == pytest.approx(2 * 0.8 * 0.6 / 1.4)
    assert PreCounts(n_in_view=3, n_recovered=0).to_dict()["f1_geo"] is None

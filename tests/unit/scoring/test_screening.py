"""Checkpoint screening: pixel matching, health guards, the scores the method tabulates (F1 of pooled
recall and GMCF, detections per frame, review load), blocks and presets — hand-computed."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.clustering import GroundPositions
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint
from birdseye.birdseye_qgis.core.scoring.screening import (
    SCREEN_PRESETS,
    ScreenRun,
    distinct_position_fraction,
    frame_blocks,
    pixel_matches,
    relative_to_lightest,
    screen_checkpoints,
)


def test_pixel_matching_is_one_to_one_nearest_first_within_the_radius():
    det_f = np.array([1, 1, 1, 2, 2])
    det_uv = np.array([[100, 100], [104, 100], [300, 300], [100, 100], [500, 500]], float)
    lab_f = np.array([1, 1, 2, 3])
    lab_uv = np.array([[103, 100], [200, 200], [100, 108], [100, 100]], float)
    # frame 1: the label at 103 takes the detection at 104 (1 px) not 100 (3 px); frame 2: 8 px ≤ 10;
    # frame 3's label has no detection in its own frame.
    assert pixel_matches(det_f, det_uv, lab_f, lab_uv, 10.0) == 2
    assert pixel_matches(det_f, det_uv, lab_f, lab_uv, 5.0) == 1


def screen_run(name, block, n_frames, uv, frame_id, xy, geotag_xy, labels):
    lf, luv = labels
    return ScreenRun(name, block, n_frames, np.asarray(frame_id), np.asarray(uv, float),
                     GroundPositions.from_local(LocalFrame(-27.55, 151.95), np.asarray(xy, float)),
                     np.asarray(lf), np.asarray(luv, float), np.asarray(geotag_xy, float))


def test_screening_health_guards_and_frontier():
    rng = np.random.default_rng(5)
    targets = np.array([[1.0, 1.0], [3.0, 1.0], [5.0, 1.0]])
    frames = np.repeat(np.arange(10), 3)
    good_xy = targets[np.tile([0, 1, 2], 10)] + rng.normal(0, 0.03, (30, 2))
    good_uv = rng.uniform(0, 1000, (30, 2))
    labels = (frames, good_uv + 2.0)
    # "collapsed": the same two pixels in every frame, however the ground points spread
    collapsed_uv = np.tile([[10.0, 10.0], [20.0, 20.0]], (15, 1))
    # "sparse": a third of the detections (1 per frame) on the second block
    extra = rng.uniform(0, 30, (20, 2))
    runs = [
        screen_run("good", "A", 10, good_uv, frames, good_xy, targets, labels),
        screen_run("good", "B", 10, good_uv, frames, good_xy, targets, labels),
        screen_run("noisy", "A", 10, np.concatenate([good_uv, rng.uniform(0, 1000, (20, 2))]),
                   np.concatenate([frames, np.arange(20) % 10]),
                   np.concatenate([good_xy, extra]), targets, labels),
        screen_run("noisy", "B", 10, good_uv, frames, good_xy, targets, labels),
        screen_run("collapsed", "A", 10, collapsed_uv, frames, good_xy, targets, labels),
        screen_run("collapsed", "B", 10, collapsed_uv, frames, good_xy, targets, labels),
        screen_run("sparse", "A", 10, good_uv, frames, good_xy, targets, labels),
        screen_run("sparse", "B", 10, good_uv[::3], frames[::3], good_xy[::3], targets, labels),
    ]
    out = {s.checkpoint: s for s in screen_checkpoints(runs, OperatingPoint(min_samples=2), radius_px=5)}
    assert list(out) == ["good", "noisy", "collapsed", "sparse"]
    assert out["collapsed"].collapsed and not out["collapsed"].too_sparse
    assert out["collapsed"].distinct_position_fraction == pytest.approx(2 / 60)
    assert out["sparse"].too_sparse and out["sparse"].worst_block == "B"
    assert out["sparse"].worst_detections_per_frame == pytest.approx(1.0)
    assert out["good"].healthy and out["noisy"].healthy
    g = out["good"]
    assert (g.counts.n_in_view, g.counts.n_recovered) == (6, 6)
    assert (g.pixel_tp, g.pixel_fp, g.pixel_fn) == (60, 0, 0) and g.f1_pixel == pytest.approx(1.0)
    assert out["noisy"].pixel_fp == 20 and out["noisy"].f1_pixel == pytest.approx(120 / 140)
    # 60 detections in 20 frames against the noisy checkpoint's 80: the good one is the lightest review
    assert g.detections_per_frame == 3.0 and out["noisy"].detections_per_frame == 4.0
    assert g.review_load == 1.0 and out["noisy"].review_load == pytest.approx(4 / 3)
    # unhealthy checkpoints are measured against the lightest healthy one, never the reference
    assert out["sparse"].review_load == pytest.approx((40 / 20) / 3.0)
    assert out["good"].frontier and not out["collapsed"].frontier
    assert distinct_position_fraction(np.empty((0, 2))) is None


def test_f1_geo_detections_per_frame_and_review_load_by_hand():
    """Three tight clusters, two on geotags, and four geotags in view: recall 2/4, GMCF 2/3, so
    F1 = 2·(1/2)·(2/3) / (1/2 + 2/3) = 4/7; 9 detections in 4 frames (2.25 per frame) against 18."""
    spots = np.array([[0.0, 0.0], [2.0, 0.0], [4.0, 0.0]])
    geotags = np.array([[0.0, 0.0], [2.0, 0.0], [6.0, 0.0], [8.0, 0.0]])
    offsets = np.array([[0.0, 0.0], [0.05, 0.0], [0.0, 0.05]])
    xy = (spots[:, None, :] + offsets[None]).reshape(-1, 2)
    frame_id = np.tile([0, 1, 2], 3)
    uv = np.column_stack([np.arange(9) * 50.0, np.zeros(9)])
    # 6 of the 9 detections sit on a label, 2 labels have no detection: TP 6, FP 3, FN 2
    labels = (np.concatenate([frame_id[:6], [3, 3]]), np.concatenate([uv[:6], [[900.0, 900.0], [950.0, 950.0]]]))
    light = screen_run("light", "f1 frames 1–4", 4, uv, frame_id, xy, geotags, labels)
    heavy = screen_run("heavy", "f1 frames 1–4", 4, np.concatenate([uv, uv + 1]), np.tile(frame_id, 2),
                       np.concatenate([xy, xy + 0.001]), geotags, labels)
    out = {s.checkpoint: s for s in screen_checkpoints([light, heavy], OperatingPoint(eps_m=0.1, min_samples=2),
                                                       radius_px=10)}
    x = out["light"]
    assert (x.counts.recall_pre, x.counts.gmcf_pre) == (0.5, pytest.approx(2 / 3))
    assert x.f1_geo == pytest.approx(4 / 7)
    assert (x.pixel_tp, x.pixel_fp, x.pixel_fn) == (6, 3, 2) and x.f1_pixel == pytest.approx(12 / 17)
    assert x.detections_per_frame == 2.25 and x.review_load == 1.0
    assert out["heavy"].detections_per_frame == 4.5 and out["heavy"].review_load == 2.0
    row = x.to_dict()
    assert row["f1_geo"] == pytest.approx(4 / 7) and row["f1_pixel_radius_px"] == 10.0
    assert row["review_load"] == 1.0 and row["detections_per_frame"] == 2.25


def test_review_load_is_relative_to_the_lightest_eligible_value():
    # detections per frame 3.2, 4.8, 6.4 → 1, 1.5, 2 (the method's review-load column from its dpf column)
    assert relative_to_lightest([3.2, 4.8, 6.4]) == pytest.approx([1.0, 1.5, 2.0])
    assert relative_to_lightest([2.0, 3.0, None, 1.0], [True, True, True, False]) == [1.0, 1.5, None, 0.5]
    assert relative_to_lightest([2.0, 1.0], [False, False]) == [None, None]
    assert relative_to_lightest([0.0, 1.0]) == [None, None]


def test_flights_are_cut_into_blocks_of_consecutive_frames():
    ids = np.arange(1234)
    blocks = frame_blocks(ids, 500)
    assert [len(b) for b in blocks] == [500, 500, 234]
    np.testing.assert_array_equal(np.concatenate(blocks), ids)
    assert [len(b) for b in frame_blocks(ids, 0)] == [1234]
    assert [len(b) for b in frame_blocks(ids[:500], 500)] == [500]
    with pytest.raises(InputError, match="BLOCK_FRAMES"):
        frame_blocks(ids, -1)


def test_the_method_preset_screens_in_blocks_of_500_frames_at_threshold_0_03():
    method, birdseye = SCREEN_PRESETS
    assert (method.key, method.block_frames, method.threshold) == ("method", 500, 0.03)
    assert (birdseye.key, birdseye.block_frames, birdseye.threshold) == ("birdseye", 0, None)

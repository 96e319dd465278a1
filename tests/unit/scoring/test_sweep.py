"""Operating-point sweeps: a fresh run per configuration, the checkpoint axis, the threshold axis, the
credibility filter, the Pareto front, F1 and the default grid, against hand-computed expectations."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.clustering import GroundPositions, cluster_detections
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.scoring.pre_review import PreCounts, score_flight
from birdseye.birdseye_qgis.core.scoring.sweep import (
    METHOD_GRID,
    DetectionRun,
    SweepFlight,
    SweepGrid,
    f1_geo,
    flights_from_runs,
    pareto_front,
    sweep,
)

SITE = LocalFrame(-27.55, 151.95, 400.0)


def on_ground(xy) -> GroundPositions:
    return GroundPositions.from_local(SITE, xy)


def random_detections(rng, targets, spread=0.03):
    seen = rng.random(len(targets)) < 0.8
    det = [targets[i] + rng.normal(0, spread, (rng.integers(3, 15), 2)) for i in np.flatnonzero(seen)]
    clutter_spots = rng.uniform(0, 30, (8, 2))
    det += [c + rng.normal(0, spread, (rng.integers(2, 8), 2)) for c in clutter_spots]
    det.append(rng.uniform(0, 30, (40, 2)))
    return np.concatenate(det)


def random_flight(seed, thresholds, checkpoint="a.onnx", n_targets=25):
    """Independent detections per threshold (a peak extraction per threshold need not nest)."""
    rng = np.random.default_rng(seed)
    targets = rng.uniform(0, 30, (n_targets, 2))
    detections = {t: on_ground(random_detections(rng, targets)) for t in thresholds}
    return SweepFlight(detections, targets[rng.random(n_targets) < 0.9], 10 + seed, f"flight {seed % 10}",
                       checkpoint, checkpoint.upper())


@pytest.mark.parametrize("core_count", ["detections", "cells"])
def test_sweep_equals_one_fresh_run_per_configuration_pooled_over_flights_per_checkpoint(core_count):
    thresholds = [0.3, 0.6]
    fl = [random_flight(1, thresholds), random_flight(2, thresholds),
          random_flight(11, thresholds, "b.onnx"), random_flight(12, thresholds, "b.onnx")]
    grid = SweepGrid(thresholds, [0.06, 0.12], [2, 4], [0.1, 0.25], core_count=core_count)
    result = sweep(fl, grid)
    assert result.checkpoints == [("a.onnx", "A.ONNX"), ("b.onnx", "B.ONNX")] and result.shape == (2, 2, 2, 2, 2)
    for ci, mine in enumerate((fl[:2], fl[2:])):
        for ti, t in enumerate(grid.thresholds):
            n_det = sum(len(f.detections[t]) for f in mine)
            assert result.counts["n_detections"][ci, ti, 0, 0, 0] == n_det
            assert result.detections_per_frame[ci, ti, 1, 1, 1] == pytest.approx(n_det / sum(f.n_frames for f in mine))
            for ei, eps in enumerate(grid.eps_m):
                for mi, m in enumerate(grid.min_samples):
                    for pi, pred in enumerate(grid.eps_pred_m):
                        total = PreCounts()
                        for f in mine:
                            c = cluster_detections(f.detections[t], None, None, grid.dedup_cm, eps, int(m),
                                                   core_count=core_count)
                            total = total + score_flight(c, f.geotag_xy, np.ones(len(f.geotag_xy), bool),
                                                         pred).counts
                        at = (ci, ti, ei, mi, pi)
                        for key in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters", "n_geotag_matches"):
                            assert result.counts[key][at] == getattr(total, key), key
                        assert result.counts["sum_median_extent_m"][at] == pytest.approx(total.sum_median_extent_m,
                                                                                         abs=1e-12)
                        assert result.recall_pre[at] == pytest.approx(total.recall_pre)
    rows = result.rows()
    assert len(rows) == 2 * grid.size
    assert [r["checkpoint"] for r in rows[::grid.size]] == ["a.onnx", "b.onnx"]
    assert {r["core_count"] for r in rows} == {core_count}
    assert {"model_digest", "threshold", "eps_m", "min_samples", "eps_pred_m", "n_frames", "n_detections",
            "detections_per_frame", "credible", "pareto", "recall_pre", "gmcf_pre", "f1_geo"} <= set(rows[0])
    # the front runs over every checkpoint's configurations together
    assert sum(r["pareto"] for r in rows) == int(result.pareto.sum()) > 0


def test_the_threshold_axis_takes_each_thresholds_own_detections():
    """At 0.5 the blob that was one detection at 0.3 is two: the sweep must see two clusters there.
    (Three frames see it; de-duplication merges each spot's three detections into one point.)"""
    one = np.array([[0.0, 0.0]])
    two = np.array([[-0.3, 0.0], [0.3, 0.0]])
    flight = SweepFlight({0.3: on_ground(np.tile(one, (3, 1))), 0.5: on_ground(np.repeat(two, 3, axis=0))},
                         np.array([[0.3, 0.0]]), 3)
    r = sweep([flight], SweepGrid([0.3, 0.5], [0.1], [1], [0.05]))
    assert r.counts["n_clusters"][0, :, 0, 0, 0].tolist() == [1, 2]
    assert r.gmcf_pre[0, :, 0, 0, 0].tolist() == [0.0, 0.5]
    assert r.detections_per_frame[0, :, 0, 0, 0].tolist() == [1.0, 2.0]
    with pytest.raises(InputError, match="no detections made at threshold 0.4"):
        sweep([flight], SweepGrid([0.4], [0.1], [1], [0.05]))


def test_credibility_filter_rejects_chained_and_greedy_configurations():
    flight = random_flight(4, [0.2])
    grid = SweepGrid([0.2], [0.05, 8.0], [2], [0.2, 3.0])
    r = sweep([flight], grid, max_geotags_per_hit=1.5, max_mean_extent_m=1.0)
    # eps 8 m chains the field into a few huge clusters; eps_pred 3 m lets each hit swallow many geotags
    assert r.credible[0, 0, 0, 0, 0]
    assert not r.credible[0, 0, 1, 0, :].any()
    assert r.mean_median_extent_m[0, 0, 1, 0, 0] > 1.0
    assert r.mean_geotags_per_hit_cluster[0, 0, 0, 0, 1] > 1.5 and not r.credible[0, 0, 0, 0, 1]
    assert not (r.pareto & ~r.credible).any()


def test_pareto_front_by_hand():
    recall = np.array([0.9, 0.8, 0.8, 0.5, 0.95, 0.9, 0.7])
    gmcf = np.array([0.5, 0.7, 0.6, 0.9, 0.4, 0.5, 0.95])
    eligible = np.array([True, True, True, True, True, True, False])
    # (0.9, 0.5) twice (ties stay), (0.8, 0.7), (0.5, 0.9), (0.95, 0.4); (0.8, 0.6) is dominated;
    # (0.7, 0.95) would dominate (0.5, 0.9) but is not eligible.
    np.testing.assert_array_equal(pareto_front(recall, gmcf, eligible),
                                  [True, True, False, True, True, True, False])


def test_f1_geo_is_the_harmonic_mean_of_recall_and_gmcf():
    # 2·0.8·0.6 / 1.4 = 0.96 / 1.4 = 0.685714…; 2·1·0.5 / 1.5 = 2/3
    assert float(f1_geo(0.8, 0.6)) == pytest.approx(0.6857142857142857, abs=1e-15)
    np.testing.assert_allclose(f1_geo([1.0, 0.5, 0.0, 0.9], [0.5, 0.5, 0.0, 0.0]), [2 / 3, 0.5, 0.0, 0.0])
    assert np.isnan(f1_geo(np.nan, 0.5)) and np.isnan(f1_geo(0.5, np.nan))


def test_the_default_grid_holds_every_reported_point_and_has_the_methods_size():
    grid = SweepGrid(*METHOD_GRID.values())
    assert grid.shape == (12, 10, 12, 10) and grid.size == 14_400
    assert len(grid.thresholds) == len(METHOD_GRID["thresholds"])     # no value given twice
    # 0.03 … 0.12 in steps of 0.01, and 0.035: the threshold of the method's lowest-review-burden arm
    for values, reported in ((grid.thresholds, (0.03, 0.035) + tuple(np.arange(4, 13) / 100)),
                             (grid.eps_m, (0.10, 0.15, 0.20)), (grid.min_samples, (2, 5, 10, 20)),
                             (grid.eps_pred_m, (0.20, 0.35))):
        for value in reported:
            assert np.isclose(values, value, atol=1e-12).sum() == 1, value


def test_thresholds_must_be_probabilities_a_detector_can_run_at():
    for bad in ([0.0, 0.3], [0.3, 1.0]):
        with pytest.raises(InputError, match="THRESHOLDS.*between 0 and 1"):
            SweepGrid(bad, [0.1], [2], [0.2])


def run(checkpoint, flight, threshold, n=2, source=None):
    return DetectionRun(on_ground(np.zeros((n, 2))), threshold, flight, checkpoint, checkpoint.upper(),
                        source or f"{checkpoint}@{flight}@{threshold}")


def test_detection_layers_become_flights_per_checkpoint_at_their_own_thresholds():
    runs = [run("a", "f1", 0.3), run("a", "f1", 0.5, n=3), run("b", "f1", 0.5 + 1e-12), run("b", "f1", 0.3)]
    flights, thresholds = flights_from_runs(runs, {"f1": np.zeros((4, 2))}, {"f1": 7})
    assert thresholds == [0.3, 0.5]
    assert [(f.checkpoint, f.name, f.n_frames) for f in flights] == [("a", "f1", 7), ("b", "f1", 7)]
    assert len(flights[0].at_threshold(0.5)) == 3
    with pytest.raises(InputError, match="a on f2 has no layer detected at threshold\\(s\\) 0.5"):
        flights_from_runs(runs + [run("a", "f2", 0.3)], {"f1": np.zeros((0, 2)), "f2": np.zeros((0, 2))},
                          {"f1": 1, "f2": 1})
    with pytest.raises(InputError, match="a@f1@0.3 and again are both a on f1 at threshold 0.3"):
        flights_from_runs(runs + [run("a", "f1", 0.3, source="again")], {"f1": np.zeros((0, 2))}, {"f1": 1})
    with pytest.raises(InputError, match="lonely.*no detection threshold"):
        flights_from_runs([run("a", "f1", None, source="lonely")], {"f1": np.zeros((0, 2))}, {"f1": 1})


def test_checkpoints_must_share_their_flights():
    fl = [random_flight(1, [0.3]), random_flight(2, [0.3]), random_flight(11, [0.3], "b.onnx")]
    with pytest.raises(InputError, match="same flights: a.onnx on flight 1, flight 2, but b.onnx on flight 1"):
        sweep(fl, SweepGrid([0.3], [0.1], [2], [0.2]))

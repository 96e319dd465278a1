"""Clustering and the operating-point sweep at the method's scale.

1. **One million detections** de-duplicated (3 cm) and clustered (DBSCAN 0.10 m / 3), with the cluster
   summaries — goal: under 10 s. Baseline: scikit-learn's DBSCAN straight on the raw
   detections (no de-duplication), as one would write it first.
2. **A sweep of the method's 14,400 configurations** (here 10 thresholds × 12 EPS × 12 MIN_SAMPLES × 10
   EPS_PRED) on one simulated flight — goal: under 5 minutes. Baseline: recomputing everything per
   configuration (threshold filter, de-duplication, neighbour graph, DBSCAN, summaries, scoring), timed
   on a random subset of configurations and extrapolated; the subset is also checked to give exactly
   the sweep's numbers.

The simulated flight: a 60 m × 60 m plot flown in a lawnmower at 12 m with the deployed camera
(1920 × 1200 px, fx ≈ 4264 px: a 5.4 m × 3.4 m footprint), 80 % forward and 70 % side overlap;
300 surveyed burrows, 60 real but unsurveyed ones, 100 burrow-like clutter spots; every target in a
frame is detected with its own score distribution, positions carry a per-frame pose error (1.5 cm)
and a per-detection error (2.5 cm); 3 random false alarms per frame.
"""
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time

import _path  # noqa: F401
import numpy as np

from birdseye.birdseye_qgis.core.detect.clustering import (
    GroundPositions,
    cluster_detections,
    cluster_hulls,
    dbscan,
    deduplicate,
    neighbour_graph,
    summarize_clusters,
)
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses
from birdseye.birdseye_qgis.core.geometry.projection import project_in_view
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.scoring.matching import in_view
from birdseye.birdseye_qgis.core.scoring.pre_review import PreCounts, score_flight
from birdseye.birdseye_qgis.core.scoring.sweep import SweepFlight, SweepGrid, sweep

GOAL_MILLION_S = 10.0
GOAL_SWEEP_S = 300.0
SITE = LocalFrame(-27.55, 151.95, 400.0)


# ------------------------------------------------------------------------------ 1. a million detections
def million_detections(seed=0, n=1_000_000):
    """20,000 spots (targets and clutter) on a 100 m × 94 m field, 40 detections each on average
    (2 cm scatter), plus 200,000 scattered false alarms; 12,524 frames."""
    rng = np.random.default_rng(seed)
    spots = rng.uniform([0, 0], [100, 94], (20_000, 2))
    n_spot = int(0.8 * n)
    xy = np.concatenate([spots[rng.integers(0, len(spots), n_spot)] + rng.normal(0, 0.02, (n_spot, 2)),
                         rng.uniform([0, 0], [100, 94], (n - n_spot, 2))])
    return xy, rng.integers(0, 12_524, n), rng.uniform(0.3, 1.0, n)


def bench_million():
    xy, frame, score = million_detections()
    positions = GroundPositions.from_local(SITE, xy)
    cluster_detections(positions.subset(slice(0, 20_000)), frame[:20_000], score[:20_000])  # imports, caches
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    points = deduplicate(positions, 0.03)
    t1 = time.perf_counter()
    graph = neighbour_graph(points.xy, 0.10)
    t2 = time.perf_counter()
    result = dbscan(graph, 0.10, 3)
    t3 = time.perf_counter()
    summary = summarize_clusters(xy, result.labels[points.inverse], result.n_clusters, frame, score)
    t4 = time.perf_counter()
    cpu = time.process_time() - cpu0
    cluster_hulls(xy, result.labels[points.inverse], result.n_clusters)
    t5 = time.perf_counter()
    total = t4 - t0
    print(f"1. {len(xy):,} detections → {len(points):,} de-duplicated points → {result.n_clusters:,} clusters "
          f"({int((result.labels < 0).sum()):,} noise points)")
    print(f"   de-duplicate {t1 - t0:.2f} s, radius graph {t2 - t1:.2f} s, DBSCAN {t3 - t2:.2f} s, "
          f"summaries {t4 - t3:.2f} s  →  {total:.2f} s wall, {cpu:.2f} s CPU   (goal {GOAL_MILLION_S:.0f} s: "
          f"{total / GOAL_MILLION_S:.2f} × goal wall, {cpu / GOAL_MILLION_S:.2f} × goal CPU)")
    print(f"   cluster polygons (not in the goal): {t5 - t4:.2f} s; mean detections per cluster "
          f"{summary.n_detections.mean():.1f}")
    # Baseline: scikit-learn DBSCAN on the raw detections, on a slice of the field, extrapolated by count.
    from sklearn.cluster import DBSCAN

    part = xy[:, 0] < 20.0
    t0 = time.perf_counter()
    DBSCAN(eps=0.10, min_samples=3).fit(xy[part])
    t_part = time.perf_counter() - t0
    t_naive = t_part * len(xy) / part.sum()
    print(f"   baseline: scikit-learn DBSCAN on raw detections: {t_part:.2f} s for {part.sum():,} "
          f"(a 20 m strip) → ≈ {t_naive:.1f} s for all ({t_naive / total:.1f} × ours)")


# ------------------------------------------------------------------------------ 2. the sweep
def simulated_flight(seed=1):
    rng = np.random.default_rng(seed)
    t = np.eye(4)
    t[:3, :3] = [[0, 1, 0], [-1, 0, 0], [0, 0, 1]]
    cam = CameraModel(1920, 1200, 4264.4945, 4262.8927, 958.4594, 592.5033, (-0.08, 0.12, 4e-4, -3e-4, 0.0), t)
    local = SITE
    agl, plot = 12.0, 60.0
    along = 0.2 * agl * 1200 / 4263.0        # image height (px) along track, 80 % overlap
    across = 0.3 * agl * 1920 / 4264.0       # 70 % side overlap
    xs = np.arange(-2.0, plot + 2.0, across)
    ys = np.arange(-1.5, plot + 1.5, along)
    east = np.repeat(xs, len(ys))
    north = np.concatenate([ys if i % 2 == 0 else ys[::-1] for i in range(len(xs))])
    n = len(east)
    enu = np.column_stack([east + rng.normal(0, 0.05, n), north + rng.normal(0, 0.05, n),
                           agl + rng.normal(0, 0.1, n)])
    lat, lon, h = local.to_geodetic(enu)
    yaw = np.where(np.repeat(np.arange(len(xs)) % 2, len(ys)) == 0, 0.0, 180.0)
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians(rng.normal(0, 1.5, n)), np.radians(rng.normal(0, 1.5, n)),
                                           np.radians(yaw + rng.normal(0, 1.0, n))))
    poses = FramePoses(np.arange(n), lat, lon, h, q, np.full(n, local.h0), cam)
    surveyed = rng.uniform(0, plot, (300, 2))
    unsurveyed = rng.uniform(0, plot, (60, 2))
    clutter = rng.uniform(0, plot, (100, 2))
    spots = np.concatenate([surveyed, unsurveyed, clutter])
    kind = np.repeat([0, 1, 2], [300, 60, 100])
    geom = FrameGeometry(poses, local)
    proj = project_in_view(geom, np.column_stack([spots, np.zeros(len(spots))]), LevelPlaneGround(geom))
    # Scores: real targets mostly high, clutter mostly low; each frame detects a target independently.
    a = np.where(kind[proj.point_idx] == 2, 2.0, 5.0)
    b = np.where(kind[proj.point_idx] == 2, 3.5, 2.0)
    score = rng.beta(a, b)
    keep = score >= 0.1
    fi, pi, score = proj.frame_idx[keep], proj.point_idx[keep], score[keep]
    frame_error = rng.normal(0, 0.015, (n, 2))
    xy = spots[pi] + frame_error[fi] + rng.normal(0, 0.025, (len(pi), 2))
    # False alarms: 3 per frame at a random point of the frame's footprint, low scores.
    n_fa = 3 * n
    fa_frame = rng.integers(0, n, n_fa)
    half = np.array([agl * 960 / 4264.0, agl * 600 / 4263.0])
    fa_xy = enu[fa_frame, :2] + rng.uniform(-1, 1, (n_fa, 2)) * half
    fa_score = 0.1 + 0.6 * rng.beta(1.2, 4.0, n_fa)
    xy = np.concatenate([xy, fa_xy])
    score = np.concatenate([score, fa_score])
    view = in_view([poses], local, np.column_stack([surveyed, np.zeros(len(surveyed))]))
    return xy, score, surveyed[view.mask], n


def bench_sweep():
    xy, score, geotags, n_frames = simulated_flight()
    grid = SweepGrid(np.round(np.arange(0.10, 0.56, 0.05), 2), np.round(np.linspace(0.03, 0.25, 12), 3),
                     np.arange(1, 13), np.round(np.linspace(0.05, 0.50, 10), 3))
    # Each simulated detection is its own peak, so a run at threshold t keeps exactly those scored ≥ t.
    positions = GroundPositions.from_local(SITE, xy)
    flight = SweepFlight({t: positions.subset(score >= t) for t in grid.thresholds}, geotags, n_frames,
                         "simulated flight")
    print(f"2. simulated flight: {n_frames} frames, {len(xy):,} detections at threshold ≥ 0.1, "
          f"{len(flight.geotag_xy)} surveyed geotags in view; grid {' × '.join(map(str, grid.shape))} = "
          f"{grid.size:,} configurations")
    cpu0 = time.process_time()
    t0 = time.perf_counter()
    result = sweep([flight], grid)
    t_sweep = time.perf_counter() - t0
    cpu = time.process_time() - cpu0
    print(f"   sweep: {t_sweep:.1f} s wall ({cpu:.1f} s CPU) = {t_sweep / grid.size * 1e3:.2f} ms per "
          f"configuration   (goal {GOAL_SWEEP_S:.0f} s: {t_sweep / GOAL_SWEEP_S:.2f} × goal wall, "
          f"{cpu / GOAL_SWEEP_S:.2f} × goal CPU); {int(result.credible.sum()):,} credible, "
          f"{int(result.pareto.sum())} on the Pareto front")
    best = np.unravel_index(np.nanargmax(np.where(result.pareto, result.recall_pre + result.gmcf_pre, -1)),
                            result.shape)
    print(f"   e.g. a front configuration: threshold {grid.thresholds[best[1]]}, eps {grid.eps_m[best[2]]} m, "
          f"min_samples {grid.min_samples[best[3]]}, eps_pred {grid.eps_pred_m[best[4]]} m → recall_pre "
          f"{result.recall_pre[best]:.3f}, gmcf_pre {result.gmcf_pre[best]:.3f}")
    # Baseline: everything recomputed per configuration, on a random subset, extrapolated.
    rng = np.random.default_rng(0)
    subset = [tuple(int(rng.integers(0, s)) for s in grid.shape) for _ in range(60)]
    t0 = time.perf_counter()
    for ti, ei, mi, pi in subset:
        keep = score >= grid.thresholds[ti]
        c = cluster_detections(positions.subset(keep), None, None, grid.dedup_cm, grid.eps_m[ei],
                               int(grid.min_samples[mi]))
        k = score_flight(c, geotags, np.ones(len(geotags), bool), grid.eps_pred_m[pi]).counts
        assert_same(result, (0, ti, ei, mi, pi), k)
    t_each = (time.perf_counter() - t0) / len(subset)
    t_naive = t_each * grid.size
    print(f"   baseline: recompute per configuration: {t_each * 1e3:.0f} ms each → ≈ {t_naive:.0f} s for the grid "
          f"({t_naive / t_sweep:.1f} × the sweep); the {len(subset)} sampled configurations match the sweep exactly")


def assert_same(result, idx, counts: PreCounts):
    for key in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters", "n_geotag_matches"):
        assert result.counts[key][idx] == getattr(counts, key), (idx, key)
    assert abs(result.counts["sum_median_extent_m"][idx] - counts.sum_median_extent_m) < 1e-9


def main():
    load = os.getloadavg()[0] if hasattr(os, "getloadavg") else float("nan")
    print(f"load average {load:.1f} on {os.cpu_count()} CPU(s): wall times grow with it, CPU times much less")
    bench_million()
    bench_sweep()


if __name__ == "__main__":
    main()

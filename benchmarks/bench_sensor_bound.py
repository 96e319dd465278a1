"""Benchmark: full-resolution sensor bound for the deployed platform.

Run from the repository root:  .venv/bin/python benchmarks/bench_sensor_bound.py

Times ``sensor_bound.frame_suprema`` (sup of the trace and of λ_max over all (W+1)(H+1) grid points)
at 10 and 20 m against the 1 s/altitude goal and against a naive baseline — a Python loop building
each pixel's 2×6 Jacobian and calling ``np.linalg.eigvalsh``, timed on a random subsample and
extrapolated to the full grid. Also times the full ``evaluate_bound`` (with both balanced
allocations) and prints the deployed platform's verdicts.
"""
import sys
import time
from pathlib import Path

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[1]
PLUGIN_PATH = REPO_ROOT / "build" / "pluginpath"


def _import_plugin():
    """Import the plugin under its installed name through the same symlink tests/conftest.py makes."""
    PLUGIN_PATH.mkdir(parents=True, exist_ok=True)
    link = PLUGIN_PATH / "birdseye"
    if not link.is_symlink():
        link.symlink_to(REPO_ROOT, target_is_directory=True)
    sys.path.insert(0, str(PLUGIN_PATH))
    from birdseye.birdseye_qgis.core.design import sensor_bound
    return sensor_bound


sb = _import_plugin()

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]  # m, m, m, deg, deg, deg
TOLERANCE_PX = 30.0
ALTITUDES = (10.0, 20.0)
GOAL_S = 1.0
REPEATS = 7
NAIVE_SAMPLE = 20000


def naive_suprema(intr, depth, variances, us, vs):
    """Baseline: per pixel, J = ∂π/∂X_c · [I | −X_c^] as a 2×6 array, Σ = J diag(s) Jᵀ, eigvalsh."""
    s = np.diag(sb.METHOD_MOUNT.xi_variances(variances))
    best_tr = best_lm = 0.0
    for u, v in zip(us, vs):
        x, y = (u - intr.cx) / intr.fx * depth, (v - intr.cy) / intr.fy * depth
        dpi = np.array([[intr.fx / depth, 0.0, -intr.fx * x / depth ** 2],
                        [0.0, intr.fy / depth, -intr.fy * y / depth ** 2]])
        lift = np.hstack([np.eye(3), -np.array([[0.0, -depth, y], [depth, 0.0, -x], [-y, x, 0.0]])])
        j = dpi @ lift
        eig = np.linalg.eigvalsh(j @ s @ j.T)
        best_tr, best_lm = max(best_tr, eig.sum()), max(best_lm, eig[-1])
    return best_tr, best_lm


def main():
    us, vs = sb.frame_grid(DEPLOYED, 1)
    n_points = us.size * vs.size
    variances = sb.sigmas_to_variances(SIGMAS)
    rng = np.random.default_rng(0)
    sample_u = rng.choice(us, NAIVE_SAMPLE)
    sample_v = rng.choice(vs, NAIVE_SAMPLE)
    print(f"deployed camera {DEPLOYED.width}x{DEPLOYED.height}, grid {us.size}x{vs.size} = {n_points:,} points")

    fast_times = []
    for altitude in ALTITUDES:
        sb.frame_suprema(DEPLOYED, altitude, SIGMAS)  # warm-up
        times = []
        for _ in range(REPEATS):
            t0 = time.perf_counter()
            sup = sb.frame_suprema(DEPLOYED, altitude, SIGMAS)
            times.append(time.perf_counter() - t0)
        t = float(np.median(times))
        fast_times.append(t)
        t0 = time.perf_counter()
        naive_suprema(DEPLOYED, altitude, variances, sample_u, sample_v)
        naive = (time.perf_counter() - t0) * n_points / NAIVE_SAMPLE
        print(f"  {altitude:4.0f} m: sup trace {sup.sup_trace_px2:8.3f} px² at {sup.worst_pixel_trace}, "
              f"sup λmax {sup.sup_lmax_px2:8.3f} px² at {sup.worst_pixel}; "
              f"{t * 1e3:6.1f} ms (median of {REPEATS}), {n_points / t / 1e6:5.1f} M points/s; "
              f"naive per-pixel loop + eigvalsh (extrapolated from {NAIVE_SAMPLE:,} px): {naive:6.1f} s "
              f"-> {naive / t:,.0f}x")
    t = max(fast_times)
    print(f"sensorbound full-res: {t:.3f} s/altitude (goal {GOAL_S:g} s: {GOAL_S / t:.1f}x faster)")

    print(f"deployed platform verdicts (σ = {SIGMAS}, r = {TOLERANCE_PX:g} px at 3σ, full resolution):")
    for altitude in ALTITUDES:
        t0 = time.perf_counter()
        res = sb.evaluate_bound(DEPLOYED, altitude, SIGMAS, TOLERANCE_PX, stride_px=1)
        dt = time.perf_counter() - t0
        fmt = ", ".join
        print(f"  {altitude:4.0f} m: trace κ*={res.kappa_trace:.3f} {res.verdict_trace}, "
              f"exact κ*={res.kappa_exact:.3f} {res.verdict_exact} (worst pixel {res.worst_pixel}); "
              f"evaluate_bound incl. allocations {dt:.3f} s, {res.exact_iterations} cutting-plane iteration(s)")
        print(f"        balanced trace σ  = [{fmt(f'{s:.4g}' for s in res.balanced_trace_sigma)}]")
        print(f"        balanced exact σ  = [{fmt(f'{s:.4g}' for s in res.balanced_exact_sigma)}]")
        print(f"        budget share      = [{fmt(f'{s:.3f}' for s in res.budget_share)}] "
              f"({', '.join(sb.AXES)})")


if __name__ == "__main__":
    main()

"""Benchmark: import a pose log the size of the method's whole campaign.

46,205 frames at a 5 Hz strobe with 50 Hz INS rows between strobes (≈ 462k rows, ≈ 50 MB of CSV)
and an ``images.csv``. Times the core import (parse + sync + ground heights + geometry + footprints,
i.e. ``core.field.flight_log.import_pose_log``) and the process's peak resident memory, against the goal:
under 30 s and under 1 GB. Writing the QGIS layer is not included.

Run: ``.venv/bin/python benchmarks/bench_import_flightlog.py [--frames N]``
"""
from __future__ import annotations

import argparse
import resource
import subprocess
import sys
import tempfile
import time
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(REPO / "build" / "pluginpath"))
sys.path.insert(0, str(REPO / "tests" / "data"))
GOAL_SECONDS = 30.0
GOAL_RSS_MB = 1024.0
CAMPAIGN_FRAMES = 46_205


def peak_rss_mb() -> float:
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux reports KiB


def run_import(folder: Path) -> None:
    """The measured part, in a fresh process so the peak RSS is the import's alone."""
    from birdseye.birdseye_qgis.core.field.flight_log import import_pose_log
    from birdseye.birdseye_qgis.core.geometry.camera import load_calibration

    camera = load_calibration(folder / "camchain.yaml")
    t0 = time.perf_counter()
    result = import_pose_log(folder / "pose_log.csv", folder / "images", camera, fps=5.0)
    elapsed = time.perf_counter() - t0
    rss = peak_rss_mb()
    frames = len(result.frames)
    with_ring = sum(r is not None for r in result.footprints.rings)
    rows = result.report.counts["pose_rows"]
    print(f"imported: {frames} frames, {with_ring} footprints, {len(result.track)} flight-line segment(s)")
    print(f"core import time: {elapsed:.2f} s  (goal {GOAL_SECONDS:.0f} s, ratio {elapsed / GOAL_SECONDS:.3f})")
    print(f"peak RSS: {rss:.0f} MB  (goal {GOAL_RSS_MB:.0f} MB, ratio {rss / GOAL_RSS_MB:.3f})")
    print(f"throughput: {rows / elapsed / 1e3:.0f} k rows/s, {frames / elapsed:.0f} frames/s")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--frames", type=int, default=CAMPAIGN_FRAMES)
    parser.add_argument("--ins-hz", type=float, default=50.0)
    parser.add_argument("--run", type=Path, help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.run:
        run_import(args.run)
        return

    from synthetic_flight import make_flight

    with tempfile.TemporaryDirectory() as tmp:
        t0 = time.perf_counter()
        flight = make_flight(Path(tmp), n_frames=args.frames, images_csv=True, ins_hz=args.ins_hz)
        size_mb = flight["pose_log"].stat().st_size / 1e6
        print(f"pose log: {len(flight['cols']['time_s'])} rows, {size_mb:.1f} MB, {args.frames} strobes at 5 Hz, "
              f"INS {args.ins_hz:g} Hz, images.csv (written in {time.perf_counter() - t0:.1f} s)", flush=True)
        subprocess.run([sys.executable, __file__, "--run", tmp], check=True)


if __name__ == "__main__":
    main()

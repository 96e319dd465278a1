"""Benchmark: how long the review dock takes to show a unit's chips after the reviewer moves on.

The figures come from the review dock's own test run headless (tests/gui/test_review_dock.py, a simulated
flight of 480 × 300 frames, two detection layers, eight units): the whole review by keyboard records the
latency of every move with prefetch (the dock plans and reads the next unit's chips while the reviewer
looks at the current one), and the chips test one move with nothing prefetched and an empty image cache.
Goal: median latency with prefetch < 200 ms (a reviewer pressing a key every second or so never waits).
Baseline: the cold move, what every move would cost without prefetch; the ratio is cold / prefetched median.
The tests print the times and assert none (a test never asserts absolute times).
"""
from __future__ import annotations

import os
import re
import subprocess
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
PYTEST = Path(sys.executable).with_name("pytest")  # the venv's pytest script (docs/design.md §7)
GOAL_MS = 200.0


def main():
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    result = subprocess.run([str(PYTEST), "-q", "-s", "-p", "no:cacheprovider", "tests/gui/test_review_dock.py",
                             "-k", "whole_review_by_keyboard or chips_show_the_frames"], cwd=REPO, env=env,
                            capture_output=True, text=True, check=False)
    out = result.stdout
    prefetched = re.search(r"chip latency with prefetch: median ([\d.]+) ms, max ([\d.]+) ms over (\d+) moves", out)
    cold = re.search(r"chip latency without prefetch \(cold\): ([\d.]+) ms", out)
    if result.returncode != 0 or not prefetched or not cold:
        print(out[-3000:] + result.stderr[-2000:])
        sys.exit(f"the review dock tests failed or printed no latency (exit {result.returncode})")
    median, worst, moves = float(prefetched[1]), float(prefetched[2]), int(prefetched[3])
    cold_ms = float(cold[1])
    print(f"chip latency with prefetch: median {median:.1f} ms, max {worst:.1f} ms over {moves} moves "
          f"(goal: median < {GOAL_MS:.0f} ms: {'met' if median < GOAL_MS else 'MISSED'}, {median / GOAL_MS:.2f} of it)")
    print(f"baseline, without prefetch (cold cache): {cold_ms:.1f} ms; ratio cold / prefetched median: "
          f"{cold_ms / median:.1f}×")


if __name__ == "__main__":
    main()

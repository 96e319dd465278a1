"""Label writing at the scale of the method's largest field partition.

The method's post-processing took 14 min 27 s (867 s) for 3,976 frames and 25,315 labels at
1920×1200. Goal: the same work — projection, every soft-label raster written, labels.csv
and labels.txt — in under 30 s on one core (≥ 29× faster). Memory must not grow with the number of
frames: peak RSS is measured after a run of 1/4 of the frames and after the full run.
"""
import os

os.environ.setdefault("OMP_NUM_THREADS", "1")
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import resource
import shutil
import tempfile
import time
from pathlib import Path

import _path  # noqa: F401
import numpy as np
from _frames import random_frames, random_ground_points

from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.labels.training_set import LabelRequest, project_labels, write_label_set

N_FRAMES, TARGET_LABELS = 3_976, 25_315
BASELINE_S = 14 * 60 + 27


def partition(seed=0):
    """Frames over a field whose geotag density gives ~6.4 labels per frame, as in the method."""
    rng = np.random.default_rng(seed)
    side = 60.0
    poses, local = random_frames(rng, N_FRAMES, (side, side), height_m=(9.5, 10.5), tilt_sd_deg=1.5)
    # footprint ≈ 4.50 m × 2.81 m at 10 m ⇒ labels/frame ≈ n · 12.7 m² / side²
    n_geotags = int(round(TARGET_LABELS / N_FRAMES * side ** 2 / 12.66))
    geotags = Geotags(np.arange(n_geotags), *random_ground_points(rng, local, n_geotags, (side, side)),
                      np.full(n_geotags, "burrow"))
    images = [f"/data/frames/{i}.png" for i in range(N_FRAMES)]
    return poses, geotags, images


def run(poses, geotags, images, out_dir):
    t0 = time.perf_counter()
    frame_labels = project_labels(poses, geotags)
    result = write_label_set(poses, images, geotags, frame_labels, out_dir, LabelRequest(sigma_px=10.0))
    return time.perf_counter() - t0, result.summary


def main():
    poses, geotags, images = partition()
    tmp = Path(tempfile.mkdtemp(prefix="birdseye-bench-labels-"))
    try:
        quarter = N_FRAMES // 4
        run(poses.subset(slice(0, quarter)), geotags, images[:quarter], tmp / "quarter")
        rss_quarter = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        elapsed, summary = run(poses, geotags, images, tmp / "full")
        rss_full = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024
        size_mb = sum(p.stat().st_size for p in (tmp / "full").rglob("*") if p.is_file()) / 1e6
    finally:
        shutil.rmtree(tmp, ignore_errors=True)
    print(f"writelabels core: {summary['n_frames']} frames, {summary['n_labels']} labels "
          f"(method: {N_FRAMES} frames, {TARGET_LABELS} labels), {size_mb:.0f} MB written")
    print(f"  {elapsed:.2f} s = {summary['n_frames'] / elapsed:.0f} frames/s; baseline (the method's "
          f"post-processing) {BASELINE_S} s: {BASELINE_S / elapsed:.0f}x faster (goal ≥ 29x, < 30 s)")
    print(f"  peak RSS {rss_quarter:.0f} MB after {N_FRAMES // 4} frames, {rss_full:.0f} MB after {N_FRAMES}"
          f" (streaming: should not grow with frames)")


if __name__ == "__main__":
    main()

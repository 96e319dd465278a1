"""Benchmark: refineposes on the six real Brighton Beach DJI frames (4000 × 2250 px).

Uses ``../shared/data/brighton_beach`` when it is there (the original images), else the 960 × 540
copies in ``tests/data/brighton_beach_960``, and says which. Their camera is only nominal (no
DewarpData): refineposes estimates it and fixes the focal length by the flying height. Reported: frames
registered, mean reprojection error, images per minute, peak resident memory of the refinement, the
focal lengths. Baseline: pycolmap
with its default options on the same images (SIFT at COLMAP's default 3,200 px, every intrinsic
self-calibrated), as one would run it first; the ratio is refineposes' images per minute over the
baseline's.

Also the cancel: a second refinement is cancelled 1 s in (during feature extraction) and the time from
that request to refineposes' return is reported. Goal: < 10 s (the bound the unit test used to assert;
tests assert no times); baseline: the uncancelled feature extraction it interrupts.
"""
from __future__ import annotations

import resource
import shutil
import tempfile
import time
from pathlib import Path

import _path  # noqa: F401
import numpy as np

from birdseye.birdseye_qgis.core.field.dji import import_dji_images
from birdseye.birdseye_qgis.core.field.refinement import refine_frames

REPO = Path(__file__).resolve().parents[1]
ORIGINALS = REPO.parent / "shared" / "data" / "brighton_beach"
COPIES = REPO / "tests" / "data" / "brighton_beach_960"


def baseline(images: Path, work: Path):
    import pycolmap

    start = time.perf_counter()
    pycolmap.extract_features(work / "db.db", images, device=pycolmap.Device.cpu)
    pycolmap.match_exhaustive(work / "db.db", device=pycolmap.Device.cpu)
    (work / "sparse").mkdir()
    models = pycolmap.incremental_mapping(work / "db.db", images, work / "sparse")
    seconds = time.perf_counter() - start
    best = max(models.values(), key=lambda r: r.num_reg_images()) if models else None
    return (0 if best is None else best.num_reg_images(),
            float("nan") if best is None else best.compute_mean_reprojection_error(), seconds)


def cancel_latency(frames, work: Path, after_s: float = 1.0) -> float:
    """Seconds from the cancel request (``after_s`` into the run) to refine_frames raising Cancelled."""
    from birdseye.birdseye_qgis.core.errors import Cancelled

    start = time.perf_counter()
    try:
        refine_frames(frames, work, is_canceled=lambda: time.perf_counter() - start >= after_s)
    except Cancelled:
        return time.perf_counter() - start - after_s
    raise RuntimeError("the refinement finished before the cancel request")


def main():
    import pycolmap

    pycolmap.logging.minloglevel = 2
    folder = ORIGINALS if ORIGINALS.is_dir() else COPIES
    with tempfile.TemporaryDirectory() as tmp:
        images = Path(tmp) / "images"
        shutil.copytree(folder, images, ignore=shutil.ignore_patterns("*.md", "LICENSE"))
        frames = import_dji_images(images).frames
        size = f"{frames.cameras[0].width} × {frames.cameras[0].height}"
        start = time.perf_counter()
        _, refinement, values = refine_frames(frames, Path(tmp) / "ours")
        ours = time.perf_counter() - start
        rms = [v["reprojection_rms_px"] for v in values if v["registered"]]
        peak_mb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0  # Linux: KiB
        print(f"{len(frames)} frames of {size} px from {folder}")
        print(f"refineposes: {refinement.n_registered}/{len(frames)} registered, mean reprojection "
              f"{np.mean(rms):.2f} px, {ours:.1f} s = {60 * len(frames) / ours:.1f} images/min ("
              + ", ".join(f"{k} {v:.1f} s" for k, v in refinement.seconds.items()) + f"), peak {peak_mb:.0f} MB RSS")
        for fix in refinement.focal:
            print(f"nominal camera: focal {fix.nominal_px:.1f} px nominal, {fix.adjusted_px:.1f} px from the bundle "
                  f"adjustment, {fix.final_px:.1f} px " + ("fixed by the flying height" if fix.determined else
                                                          "kept nominal (the block cannot tell)")
                  + f"; depth ratio after {refinement.depth_ratio:.4f}")
        (Path(tmp) / "base").mkdir()
        n_base, rms_base, base = baseline(images, Path(tmp) / "base")
        print(f"baseline (pycolmap defaults): {n_base}/{len(frames)} registered, mean reprojection {rms_base:.2f} px, "
              f"{base:.1f} s = {60 * len(frames) / base:.1f} images/min")
        print(f"ratio (images/min, refineposes / baseline): {base / ours:.2f}×")
        latency = cancel_latency(frames, Path(tmp) / "cancelled")
        features = refinement.seconds.get("features", float("nan"))
        print(f"cancel 1 s into the run: returned {latency:.2f} s after the request (goal < 10 s: "
              f"{'met' if latency < 10 else 'MISSED'}); the feature extraction it stops takes {features:.1f} s")


if __name__ == "__main__":
    main()

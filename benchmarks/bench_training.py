"""Benchmark: training throughput of birdseye:traindetector against the bare recipe on the same data.

Baseline: ``training/train_heatmap.py train`` (the bare recipe, run as a script by the same Python with
torch) on the same tiles, budget, seed and threads. The algorithm runs through QGIS's Processing
registry (QGIS initialised in this process, which never imports torch) and trains in its child process;
its throughput is the training loop's tiles per second as the child measures it, and so is the
baseline's. Goal: the algorithm within 10 % of the baseline (ratio ≥ 0.90). The process boundary's
overhead is stated separately: the time to the child's first line (interpreter start and imports) and
each run's wall time outside the training loop (start-up, loading tiles, validation, export, card).

Data: a writelabels-like folder of synthetic tiles (tests/unit/train/fake_labels.py), made once in
build/bench_training.

    QT_QPA_PLATFORM=offscreen .venv/bin/python benchmarks/bench_training.py [--minutes 0.5] [--frames 40] \
        [--preset method]

``--preset method`` measures the method's preset (EfficientNetV2-S, 224 px
crops at the tiles' own GSD) the same way; ``make bench`` runs the default preset, whose throughput is
the issue's figure (the preset changes the network, not the process boundary).
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import time
from pathlib import Path

import _path

sys.path.insert(0, "/usr/share/qgis/python/plugins")  # QGIS's Processing framework

sys.path.insert(0, str(_path.REPO_ROOT / "tests" / "unit" / "train"))
from fake_labels import make_label_folder  # noqa: E402

from birdseye.birdseye_qgis.core.train.preset import PRESETS  # noqa: E402

WORK = _path.REPO_ROOT / "build" / "bench_training"


def labels(frames: int) -> Path:
    folder = WORK / f"labels_{frames}"
    if not (folder / "summary.json").is_file():
        make_label_folder(folder, n_frames=frames, tiles_per_frame=2, tile=128, seed=3)
    return folder


def bare_recipe(folder: Path, minutes: float, threads: int, preset: str = "fast") -> dict:
    out = WORK / "bare" / "model.onnx"
    started = time.perf_counter()
    subprocess.run([sys.executable, str(_path.REPO_ROOT / "training" / "train_heatmap.py"), "train", "--labels",
                    str(folder), "--gsd-cm", "1.0", "--minutes", str(minutes), "--threads", str(threads),
                    "--preset", preset, "--out", str(out)], check=True, capture_output=True, text=True)
    wall = time.perf_counter() - started
    report = json.loads(out.with_name("model.training.json").read_text(encoding="utf-8"))
    return {"wall": wall, "train": report["seconds"]["train"], "tiles_per_s": report["history"]["tiles_per_s"]}


_QGIS = {}


def _qgis() -> None:
    """QGIS, Processing and the birdseye provider, once per process."""
    if _QGIS:
        return
    from qgis.core import QgsApplication

    _QGIS["app"] = QgsApplication([], False)
    _QGIS["app"].initQgis()
    from processing.core.Processing import Processing

    from birdseye.processing.provider import BirdsEyeProvider

    Processing.initialize()
    _QGIS["provider"] = BirdsEyeProvider()  # kept referenced: the registry does not own a Python provider
    assert QgsApplication.processingRegistry().addProvider(_QGIS["provider"])


def algorithm(folder: Path, minutes: float, threads: int, preset: str = "fast") -> dict:
    import processing
    from qgis.core import QgsProcessingFeedback

    _qgis()

    class Timing(QgsProcessingFeedback):
        first = None

        def pushInfo(self, info):  # noqa: N802 — QGIS's name
            if self.first is None and info.startswith("Training process"):
                self.first = time.perf_counter()
            super().pushInfo(info)

    feedback = Timing()
    out = WORK / "algorithm" / "model.onnx"
    started = time.perf_counter()
    result = processing.run("birdseye:traindetector", {
        "LABELS": [str(folder)], "GSD_CM": 1.0, "MINUTES": minutes, "THREADS": threads, "PYTHON": sys.executable,
        "PRESET": [p.name for p in PRESETS].index(preset), "OUTPUT_MODEL": str(out)}, feedback=feedback)
    wall = time.perf_counter() - started
    assert "torch" not in sys.modules, "QGIS's process imported torch"
    return {"wall": wall, "train": result["TRAIN_SECONDS"], "tiles_per_s": result["TILES_PER_SECOND"],
            "first_line": feedback.first - started}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--minutes", type=float, default=0.3)
    parser.add_argument("--frames", type=int, default=40)
    parser.add_argument("--threads", type=int, default=1,
                        help="1 by default: on a shared 2-core machine more threads make OpenMP spin and the "
                             "figures noise")
    parser.add_argument("--repeat", type=int, default=2, help="alternating runs of each; the best counts")
    parser.add_argument("--preset", choices=[p.name for p in PRESETS], default="fast",
                        help="the training preset of both sides (method: EfficientNetV2-S)")
    args = parser.parse_args()
    folder = labels(args.frames)
    n_tiles = len(list((folder / "tiles" / "images").glob("*.png")))
    network = "small network" if args.preset == "fast" else "EfficientNetV2-S"
    print(f"data: {n_tiles} synthetic tiles of 128 px ({args.frames} frames), preset {args.preset}, {network}, "
          f"{args.minutes:g} min budget, {args.threads} threads")
    bases, algs = [], []
    for _ in range(args.repeat):  # alternate, so a burst of load elsewhere hits both
        bases.append(bare_recipe(folder, args.minutes, args.threads, args.preset))
        algs.append(algorithm(folder, args.minutes, args.threads, args.preset))
    base = max(bases, key=lambda r: r["tiles_per_s"])
    alg = max(algs, key=lambda r: r["tiles_per_s"])
    print("runs (tiles/s): bare " + ", ".join(f"{r['tiles_per_s']:.1f}" for r in bases) + "; algorithm "
          + ", ".join(f"{r['tiles_per_s']:.1f}" for r in algs) + " — the best of each counts")
    print(f"baseline  train_heatmap.py train (bare recipe):      {base['tiles_per_s']:7.1f} tiles/s in training "
          f"({base['train']:.1f} s), wall {base['wall']:.1f} s")
    print(f"traindetector (Processing → training process):     {alg['tiles_per_s']:7.1f} tiles/s in training "
          f"({alg['train']:.1f} s), wall {alg['wall']:.1f} s")
    print(f"ratio algorithm / baseline: {alg['tiles_per_s'] / base['tiles_per_s']:.2f}  (goal ≥ 0.90)")
    print(f"process boundary: first line from the child after {alg['first_line']:.1f} s (interpreter start, "
          f"imports, finding the Python); outside the training loop: algorithm {alg['wall'] - alg['train']:.1f} s, "
          f"bare recipe {base['wall'] - base['train']:.1f} s (start-up, tiles, validation, export, card) — "
          f"overhead of the boundary {(alg['wall'] - alg['train']) - (base['wall'] - base['train']):+.1f} s")


if __name__ == "__main__":
    main()

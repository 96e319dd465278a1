"""Benchmark: do the training run's validation figures predict a flight the model never saw?

One simulated campaign (``--seed``, 5 frames/s, the simulator's default overlap) is labelled and trained on
with the spatial-block split (``core.train.job.run_job``, frame records given: the held-out frames are scored
on the ground); a second campaign (``--unseen``) is then scored whole with the same code
(``ground_validation.ground_figures``, every target held out). Printed per threshold: the held-out tiles' F1
(the old figure, now a diagnostic), the ground F1 (recall of the held-out targets, GMCF) on the held-out
blocks, and the ground F1 on the unseen campaign; and the threshold each would choose. With ``--old-split``
the run before this validation instead: the labels folder without targets.csv, so frames are held out at random
(``recipe.split_tiles``) and only tile figures are measured.

    .venv/bin/python benchmarks/bench_ground_validation.py [--minutes 4] [--threads 2] [--old-split]

Campaigns and labels are kept in build/bench_ground_validation (a finished one is not redone).
"""
from __future__ import annotations

import argparse
import json
import os
import shutil
import sys
import time

import _path

sys.path.insert(0, str(_path.REPO_ROOT / "training"))
import train_heatmap as th  # noqa: E402

from birdseye.birdseye_qgis.core.train import ground_validation as gv  # noqa: E402
from birdseye.birdseye_qgis.core.train import recipe  # noqa: E402
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job  # noqa: E402

WORK = _path.REPO_ROOT / "build" / "bench_ground_validation"
CAMPAIGN = dict(n_targets=30, field_width_m=16.0, field_length_m=12.0)


def campaign(seed: int):
    th.DEMO_CAMPAIGN = CAMPAIGN
    c = th.load_campaign(th.simulate(WORK / f"campaign_{seed}", seed, None))
    return c, th.label_campaign(c, WORK / f"labels_{seed}", seed)


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=111)
    parser.add_argument("--unseen", type=int, default=112)
    parser.add_argument("--minutes", type=float, default=4.0)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--fraction", type=float, default=0.25)
    parser.add_argument("--old-split", action="store_true", help="frames held out at random, tile figures only")
    args = parser.parse_args(argv)
    t0 = time.perf_counter()
    train_c, labels = campaign(args.seed)
    unseen_c, _ = campaign(args.unseen)
    print(f"campaigns ready ({time.perf_counter() - t0:.0f} s): {len(train_c.records)} frames to train and validate "
          f"on, {len(unseen_c.records)} unseen", flush=True)
    name = "model"
    if args.old_split:
        name, old = "model_old_split", WORK / f"labels_{args.seed}_without_targets"
        if not old.is_dir():
            shutil.copytree(labels, old, copy_function=os.link, ignore=shutil.ignore_patterns("targets.csv"))
        labels = old
    job = TrainJob(sources=[Source(str(labels), gsd_cm=train_c.gsd_of, frames=train_c.records)],
                   out=str(WORK / f"{name}.onnx"), minutes=args.minutes, val_fraction=args.fraction,
                   threads=args.threads, seed=1, producer="benchmarks/bench_ground_validation.py")
    result = run_job(job, lambda e: print(e["text"], flush=True) if e["type"] == "message" else None)
    t1 = time.perf_counter()
    unseen = gv.ground_figures(result["model"], [gv.GroundFlight(
        unseen_c.name, unseen_c.records, unseen_c.geotags, [True] * len(unseen_c.geotags))])
    unseen_s = time.perf_counter() - t1
    tiles, ground = result["validation"], result["ground_validation"]
    if ground is None:  # the old split: tile figures only
        ground = {"frames": 0, "by_threshold": {t: {"recall": None, "gmcf": None, "f1": 0.0}
                                               for t in unseen["by_threshold"]}}
    print(f"\nsplit: {json.dumps(result['split'])}")
    print(f"ground scoring of {ground['frames']} held-out frames and {unseen['frames']} unseen frames "
          f"({unseen_s / max(1, unseen['frames']):.2f} s per frame)")
    print("threshold | tile F1 (held-out tiles) | ground recall / GMCF / F1 (held-out blocks) | "
          "ground recall / GMCF / F1 (unseen campaign)")
    for t in ground["by_threshold"]:
        g, u, k = ground["by_threshold"][t], unseen["by_threshold"][t], tiles["by_threshold"][t]
        print(f"{t:>9} | {k['f1']:.3f} | {g['recall']} / {g['gmcf']} / {g['f1']:.3f} | "
              f"{u['recall']} / {u['gmcf']} / {u['f1']:.3f}")
    chosen = {"tiles": recipe.best_threshold(tiles), "held-out blocks (ground)": result["threshold"],
              "unseen campaign (ground)": recipe.best_threshold(unseen)}
    print(f"thresholds chosen: {chosen}; rule: {result['threshold_rule']}")
    at = {name: {"tile_f1": tiles["by_threshold"][f"{t:g}"]["f1"],
                 "blocks_ground_f1": ground["by_threshold"][f"{t:g}"]["f1"],
                 "unseen_ground_f1": unseen["by_threshold"][f"{t:g}"]["f1"]} for name, t in chosen.items()}
    out = {"split": result["split"], "tiles": tiles, "ground_blocks": ground, "ground_unseen": unseen,
           "chosen": chosen, "at_chosen": at, "minutes": args.minutes, "train_seconds": result["seconds"]["train"]}
    (WORK / f"{name}_figures.json").write_text(json.dumps(out, indent=1))
    print(json.dumps(at, indent=1))
    print(f"wrote {WORK / f'{name}_figures.json'}")


if __name__ == "__main__":
    main()

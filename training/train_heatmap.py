"""Training recipe for BirdsEye heatmap detectors: PyTorch on the CPU, exported to ONNX with its metadata.

The network, in the spirit of the method: a small convolutional encoder (three stride-2 stages), a
transposed-convolution decoder back to the input resolution with skip connections, and a 3×3
convolution head giving one logit per pixel; trained with binary cross-entropy on the soft-label
rasters that ``writelabels`` writes (values / 255), first with the encoder frozen (decoder and head
learn to read its features), then fine-tuning every layer. No pretrained weights are downloaded:
the encoder starts from a random initialisation, or from an earlier checkpoint of this recipe
(``--init``), which is how a model trained on simulated campaigns is adapted to real labels.

Training data are the tiles of ``writelabels`` output folders (``tiles/images`` + ``tiles/labels``,
names ``<frame_id>_<y0>_<x0>.png``). Each tile is resampled from its frame's ground sample distance
to the model's ``--resolution-cm`` with the detector's own resampling, so targets cover as many
pixels in training as the detector later shows them; normalisation is the detector's too.

Commands (run with the plugin's venv python from the repository root)::

    # your own labels: writelabels folders (with tiles) and the frame layer(s) they came from
    python training/train_heatmap.py train --labels run1/ --labels run2/ --frames frames.gpkg \\
        --out my_model.onnx [--init checkpoint.pt] [--minutes 20]

    # the bundled demo model: simulate campaigns, label them, train, choose the threshold on a
    # tuning campaign, export, validate on campaigns it never saw, write models/demo_training.json
    python training/train_heatmap.py demo --work build/demo_training --out models/birdseye_demo_heatmap.onnx

The recipe itself (networks, tiles, augmentation, training loop, validation, export) lives in
``birdseye_qgis/core/train`` and is the one ``birdseye:traindetector`` runs in its training process:
``train`` here is that very run (``core.train.job.run_job``: model, ``.pt`` weights, model card, loss
plot). ``--backbone`` picks the small network (default) or a torchvision ImageNet encoder
(``--weights`` or torchvision's cache; nothing is downloaded).

``torch`` (and ``torchvision`` for a pretrained encoder) are a training extra (``requirements-train.txt``);
QGIS's own Python never imports them.
"""
from __future__ import annotations

import argparse
import json
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np

REPO_ROOT = Path(__file__).resolve().parents[1]


def _plugin_on_path() -> None:
    """Import the plugin as ``birdseye`` (the repository root is the plugin folder), as the tests do."""
    link_dir = REPO_ROOT / "build" / "pluginpath"
    link_dir.mkdir(parents=True, exist_ok=True)
    if not (link_dir / "birdseye").is_symlink():
        try:
            (link_dir / "birdseye").symlink_to(REPO_ROOT, target_is_directory=True)
        except FileExistsError:
            pass
    if str(link_dir) not in sys.path:
        sys.path.insert(0, str(link_dir))


_plugin_on_path()

from birdseye.birdseye_qgis.core.detect.detector import file_digest  # noqa: E402
from birdseye.birdseye_qgis.core.errors import InputError  # noqa: E402
from birdseye.birdseye_qgis.core.train.choices import SPLITS  # noqa: E402
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job  # noqa: E402
from birdseye.birdseye_qgis.core.train.preset import PRESETS  # noqa: E402
from birdseye.birdseye_qgis.core.train.recipe import (  # noqa: E402,F401 — the recipe's names, as before
    BACKBONES,
    CROP_PX,
    POSITIVE_WEIGHT,
    RESOLUTION_CM,
    TILE_SIZE,
    TILES_OVERLAP_PCT,
    WIDTH,
    Augmenter,
    TileSet,
    build_network,
    channel_stats,
    export_onnx,
    frame_gsd_from_gpkg,
    load_tiles,
    make_metadata,
    train_network,
)

PRODUCER = "BirdsEye training/train_heatmap.py"


# ====================================================================================== commands
def cmd_train(args) -> None:
    """Train on writelabels folders: the same run as birdseye:traindetector (core.train.job.run_job)."""
    label_dirs = [Path(p) for p in args.labels]
    if args.frames and len(args.frames) not in (1, len(label_dirs)):
        raise SystemExit("give one --frames layer per --labels folder (in the same order), one for all, or --gsd-cm")
    sources = []
    for i, folder in enumerate(label_dirs):
        if args.frames:
            layer = args.frames[min(i, len(args.frames) - 1)]
            sources.append(Source(str(folder), gsd_cm=frame_gsd_from_gpkg(layer),
                                  frames=frame_records_from_gpkg(layer)))
        elif args.gsd_cm:
            sources.append(Source(str(folder), gsd_default=args.gsd_cm))
        else:
            raise SystemExit("give the frames' GSD: --frames frames.gpkg (per --labels) or --gsd-cm")
    job = TrainJob(sources=sources, out=args.out, backbone=args.backbone, weights=args.weights, init=args.init,
                   minutes=args.minutes, steps=args.steps, resolution_cm=args.resolution_cm,
                   val_fraction=args.val_fraction, validation=args.validation, seed=args.seed, threads=args.threads,
                   threshold=args.threshold, width=args.width, producer="BirdsEye training/train_heatmap.py",
                   preset=args.preset,
                   description=f"trained by training/train_heatmap.py on {', '.join(p.name for p in label_dirs)}")
    print(f"training {args.backbone} (preset {args.preset}) for {args.minutes:g} min", flush=True)
    result = run_job(job, _print_event)
    out = Path(result["model"])
    print(f"wrote {out} ({out.stat().st_size / 1e6:.2f} MB), {result['weights']}, {result['card']}; "
          f"{result['history']['tiles_per_s']:.1f} tiles/s over {result['seconds']['train']:.1f} s", flush=True)


def frame_records_from_gpkg(path) -> list[dict] | None:
    """The frame records of a GeoPackage frame layer (the table with frame_id and camera), read with sqlite as
    ``qgis_io.layers.read_frame_layer`` reads them in QGIS: a camera split over camera, camera_2, … joined. None
    when no table has both (a table of GSDs alone trains, but is validated on tiles only)."""
    import sqlite3

    from birdseye.birdseye_qgis.core.field.frame_records import FRAME_FIELD_NAMES, join_camera

    con = sqlite3.connect(str(path))
    try:
        for (table,) in con.execute("SELECT table_name FROM gpkg_contents"):
            cols = [r[1] for r in con.execute(f'PRAGMA table_info("{table}")')]
            if "frame_id" in cols and "camera" in cols:
                parts = ["camera"] + sorted((c for c in cols if c.startswith("camera_")), key=lambda c: int(c[7:]))
                rows = con.execute(f'SELECT {", ".join(chr(34) + c + chr(34) for c in cols)} FROM "{table}"')
                records = []
                for row in rows:
                    rec = dict(zip(cols, row))
                    out = {n: rec[n] for n in FRAME_FIELD_NAMES if n in rec and n != "camera"}
                    out["camera"] = join_camera(rec[p] for p in parts)
                    records.append(out)
                return records
    finally:
        con.close()
    return None


def _print_event(event: dict) -> None:
    kind = event["type"]
    if kind == "message":
        _log(event["text"])
    elif kind == "point":
        val = event.get("val_loss")
        _log(f"  {event['stage']} step {event['step']}: loss {event['loss']:.4f}"
             + ("" if val is None else f", validation {val:.4f}") + f" ({event['seconds']:.0f} s)")
    elif kind == "start":
        _log(f"torch {event['torch']} on {event['device']} ({event['threads']} threads)")


def _log(message: str) -> None:
    print(message, flush=True)  # the log of a long run shows up while it runs


# ====================================================================================== the demo model
#: Simulated campaigns of the demo: different seeds → different soils, light, crops, targets, flights.
#: Training and tuning campaigns are flown at 2 frames/s (each target in fewer, less redundant frames,
#: so rendering time buys variety); validation campaigns at the simulator's default 5 frames/s.
TRAIN_SEEDS = tuple(range(101, 109))
TUNE_SEEDS = (201,)
VALIDATION_SEEDS = (301, 302)
DEMO_CAMPAIGN = dict(n_targets=20, field_width_m=8.0, field_length_m=6.0)
SPARSE_FPS = 2.0
NATIVE_TILE_PX = 448          # writelabels tile size: at the frames' ~0.23 cm/px, ~103 px at 1 cm/px
LABEL_SIGMA_PX = 10.0         # writelabels' default, px of the original frame (≈ 2.3 cm)
LABEL_EDGE_BUFFER_PX = 20.0   # targets cut by the frame border are not trained as positives
NEGATIVE_RATIO = 1.5
MATCH_RADIUS_M = 0.20         # a detection within this of a target recovers it
THRESHOLD_GRID = tuple(np.round(np.arange(0.05, 0.91, 0.05), 2).tolist())


@dataclass
class Campaign:
    """One simulated campaign imported as a user would: frames from the pose log, geotags from the
    rover CSV; ``truth`` holds every target (surveyed or not) from the simulator's truth files."""

    name: str
    poses: object
    images: list
    geotags: object
    truth: object
    gsd_of: dict
    records: list | None = None  # the frame-layer records (what traindetector passes its training process)


def simulate(folder: Path, seed: int, fps: float | None = None) -> Path:
    """Simulate one campaign into ``folder`` (kept: a finished folder is not redone)."""
    from birdseye.birdseye_qgis.core.sim.campaign import CampaignConfig, simulate_campaign

    done = folder / "simulated.ok"
    if not done.is_file():
        t0 = time.perf_counter()
        simulate_campaign(CampaignConfig(seed=seed, **DEMO_CAMPAIGN, **({"fps": fps} if fps else {})), folder)
        done.write_text(f"{time.perf_counter() - t0:.1f}\n")  # seconds it took
    return folder


def load_campaign(folder: Path) -> Campaign:
    """Import a simulated campaign with the plugin's own importers (as the toolbox does)."""
    import csv

    from birdseye.birdseye_qgis.core.field.flight_log import import_flight_log
    from birdseye.birdseye_qgis.core.field.frame_records import poses_from_records
    from birdseye.birdseye_qgis.core.field.frames import frame_records
    from birdseye.birdseye_qgis.core.field.geotags import Geotags, read_geotags
    from birdseye.birdseye_qgis.core.geometry.camera import load_calibration

    fps = json.loads((folder / "truth" / "campaign.json").read_text())["parameters"]["fps"]
    result = import_flight_log(folder / "poses.csv", folder, load_calibration(folder / "calibration.yaml"), fps=fps)
    records = list(frame_records(result.frames, result.footprints))
    (poses, index), = poses_from_records(records, str(folder))
    geotags = read_geotags(folder / "geotags.csv")
    rows = list(csv.DictReader(open(folder / "truth" / "targets.csv", encoding="utf-8")))
    truth = Geotags([int(r["id"]) for r in rows], [float(r["lat"]) for r in rows], [float(r["lon"]) for r in rows],
                    [float(r["h_ground"]) for r in rows], ["burrow"] * len(rows))
    return Campaign(folder.name, poses, [records[i]["image"] for i in index], geotags, truth,
                    {str(records[i]["frame_id"]): float(records[i]["gsd_cm"]) for i in index},
                    [records[i] for i in index])


def label_campaign(campaign: Campaign, out: Path, seed: int) -> Path:
    """writelabels' core on a campaign: tiles of NATIVE_TILE_PX with soft labels of LABEL_SIGMA_PX."""
    from birdseye.birdseye_qgis.core.labels.training_set import LabelRequest, project_labels, write_label_set

    if not (out / "summary.json").is_file():
        labels = project_labels(campaign.poses, campaign.geotags, LABEL_EDGE_BUFFER_PX)
        write_label_set(campaign.poses, campaign.images, campaign.geotags, labels, out,
                        LabelRequest(sigma_px=LABEL_SIGMA_PX, edge_buffer_px=LABEL_EDGE_BUFFER_PX,
                                     write_rasters=False, tile_size=NATIVE_TILE_PX,
                                     negative_ratio=NEGATIVE_RATIO, seed=seed))
    return out


def evaluate(model_path, campaigns, thresholds) -> dict:
    """Detection figures per threshold, pooled over campaigns (sums of counts, one division).

    * ``recall_pre``/``gmcf_pre``: the official scores (clusters of detections vs geotags,
      :func:`core.scoring.evaluation.evaluate_flights` with its default operating point);
    * ``truth_recall``: in-view simulated targets (surveyed or not) with a detection within
      MATCH_RADIUS_M in some frame; ``view_recall``: (frame, in-view target) pairs detected in that
      very frame; ``truth_precision``: detections matched to a true target within MATCH_RADIUS_M, one to one in
      each frame (a second detection of a target in one frame is a false one; :func:`pixel_matches`).
    Each frame's heatmap is computed once and its peaks extracted at every threshold
    (:func:`detect_frames_at_thresholds`): what a run at that threshold gives, not a score filter of a
    lower one (a blob splits at a higher threshold).
    """
    from scipy.spatial import cKDTree

    from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
    from birdseye.birdseye_qgis.core.labels.training_set import project_labels
    from birdseye.birdseye_qgis.core.scoring.evaluation import Flight, evaluate_flights
    from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint
    from birdseye.birdseye_qgis.core.scoring.screening import pixel_matches
    from birdseye.birdseye_qgis.core.train.ground_validation import detect_at_thresholds, detections_of

    model = HeatmapModel(model_path)
    totals = {t: dict(n_in_view=0, n_recovered=0, n_clusters=0, n_hit_clusters=0, truth_in_view=0,
                      truth_recovered=0, views=0, views_detected=0, detections=0, detections_on_target=0,
                      frames=0) for t in thresholds}
    seconds = 0.0
    for c in campaigns:
        local = LocalFrame.around(c.poses.lat, c.poses.lon, c.poses.ground_height)
        t0 = time.perf_counter()
        per_frame, _ = detect_at_thresholds(model, c.poses, c.images, thresholds, local)
        seconds += time.perf_counter() - t0
        truth_xy = local.from_geodetic(c.truth.lat, c.truth.lon, c.truth.height)[:, :2]
        views = project_labels(c.poses, c.truth, 0.0, local)
        in_view_truth = np.zeros(len(c.truth), bool)
        for fl in views:
            in_view_truth[fl.geotag_index[~fl.edge]] = True
        for k, t in enumerate(thresholds):
            tot = totals[t]
            found = [runs[k] for runs in per_frame]
            det_xy = np.concatenate([f.ground_local[:, :2] for f in found]) if found else np.zeros((0, 2))
            ev = evaluate_flights([Flight(detections_of(found), [c.poses], c.name)], c.geotags,
                                  OperatingPoint(threshold=t), local=local)
            for key in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters"):
                tot[key] += getattr(ev.pooled, key)
            recovered = np.zeros(len(c.truth), bool)
            if len(det_xy):
                d, _ = cKDTree(det_xy).query(truth_xy, distance_upper_bound=MATCH_RADIUS_M)
                recovered = d <= MATCH_RADIUS_M
                det_frame = np.concatenate([np.full(len(f), j) for j, f in enumerate(found)])
                tot["detections_on_target"] += pixel_matches(
                    det_frame, det_xy, np.repeat(np.arange(len(found)), len(truth_xy)),
                    np.tile(truth_xy, (len(found), 1)), MATCH_RADIUS_M)
            tot["truth_in_view"] += int(in_view_truth.sum())
            tot["truth_recovered"] += int((recovered & in_view_truth).sum())
            for f in found:
                targets = views[f.frame_index].geotag_index[~views[f.frame_index].edge]
                tot["views"] += len(targets)
                mine = f.ground_local[:, :2]
                if len(targets) and len(mine):
                    d, _ = cKDTree(mine).query(truth_xy[targets], distance_upper_bound=MATCH_RADIUS_M)
                    tot["views_detected"] += int((d <= MATCH_RADIUS_M).sum())
            tot["detections"] += len(det_xy)
            tot["frames"] += len(found)
    out = {}
    for t, tot in totals.items():
        out[t] = dict(tot, recall_pre=_ratio(tot["n_recovered"], tot["n_in_view"]),
                      gmcf_pre=_ratio(tot["n_hit_clusters"], tot["n_clusters"]),
                      truth_recall=_ratio(tot["truth_recovered"], tot["truth_in_view"]),
                      view_recall=_ratio(tot["views_detected"], tot["views"]),
                      truth_precision=_ratio(tot["detections_on_target"], tot["detections"]),
                      detections_per_frame=_ratio(tot["detections"], tot["frames"]))
    out["detect_seconds_per_frame"] = round(seconds / max(1, totals[thresholds[0]]["frames"]), 4)
    return out


def _ratio(a, b):
    return None if b == 0 else round(a / b, 4)


def choose_threshold(figures: dict, thresholds, min_recall: float = 0.9) -> float:
    """The threshold with the best per-view F1 (frame-level matches against the true targets) on
    the tuning campaign, among those that still recover ``min_recall`` of its in-view targets."""
    def f1(t):
        r, p = figures[t]["view_recall"] or 0.0, figures[t]["truth_precision"] or 0.0
        return 0.0 if r + p == 0 else 2 * r * p / (r + p)
    eligible = [t for t in thresholds if (figures[t]["truth_recall"] or 0.0) >= min_recall]
    return max(eligible, key=f1) if eligible else min(thresholds)


def cmd_demo(args) -> None:
    import torch

    torch.set_num_threads(args.threads)
    work = Path(args.work)
    report = {"recipe": "training/train_heatmap.py demo", "campaign": DEMO_CAMPAIGN,
              "fps": {"train_and_tune": SPARSE_FPS, "validation": "simulator default (5)"}, "seeds": {
        "train": TRAIN_SEEDS, "tune": TUNE_SEEDS, "validation": VALIDATION_SEEDS}, "seconds": {}}
    folders = {seed: simulate(work / f"campaign_{seed}", seed, None if seed in VALIDATION_SEEDS else SPARSE_FPS)
               for seed in VALIDATION_SEEDS + TUNE_SEEDS + TRAIN_SEEDS}
    report["seconds"]["simulate"] = round(sum(float((f / "simulated.ok").read_text()) for f in folders.values()), 1)
    t0 = time.perf_counter()
    campaigns = {seed: load_campaign(folder) for seed, folder in folders.items()}
    sources = [(label_campaign(campaigns[s], work / f"labels_{s}", s), campaigns[s].gsd_of) for s in TRAIN_SEEDS]
    report["seconds"]["import_and_label"] = round(time.perf_counter() - t0, 1)
    tiles = load_tiles(sources, RESOLUTION_CM)
    report["training_set"] = {"frames": sum(len(campaigns[s].poses) for s in TRAIN_SEEDS),
                              "tiles": len(tiles), "tiles_with_target": int(tiles.positive.sum()),
                              "native_gsd_cm": round(float(np.median(tiles.source_gsd_cm)), 4)}
    print(f"{len(tiles)} tiles ({int(tiles.positive.sum())} with a target) from {len(TRAIN_SEEDS)} campaigns")
    sigma = round(LABEL_SIGMA_PX * float(np.median(tiles.source_gsd_cm)) / RESOLUTION_CM, 3)
    description = (f"BirdsEye demo heatmap model: detects the SIMULATED burrows of birdseye:simulatecampaign "
                   f"(trained on seeds {TRAIN_SEEDS[0]}-{TRAIN_SEEDS[-1]}); real use needs a model trained on "
                   f"real labels with training/train_heatmap.py")
    meta = make_metadata(tiles, RESOLUTION_CM, 0.5, sigma, description)
    net = build_network("small", args.width)
    weights, trained = work / "demo.pt", work / "demo_training_run.json"
    if args.reuse_weights and weights.is_file() and trained.is_file():
        net.load_state_dict(torch.load(weights, weights_only=True))  # re-tune and re-validate only
        net.eval()
        report.update({k: v for k, v in json.loads(trained.read_text()).items() if k in ("training", "network")})
    else:
        history = train_network(net, tiles, meta, args.minutes, log=_log)
        report["training"] = {k: history[k] for k in ("frozen_steps", "finetune_steps", "train_seconds")}
        report["training"]["final_loss"] = history["loss"][-1] if history["loss"] else None
        report["training"]["threads"] = args.threads
        report["network"] = {"width": args.width, "parameters": int(sum(p.numel() for p in net.parameters()))}
        torch.save(net.state_dict(), weights)
        trained.write_text(json.dumps({k: report[k] for k in ("training", "network")}, indent=1))
    draft = export_onnx(net, meta, work / "draft.onnx", PRODUCER)
    tune = evaluate(draft, [campaigns[s] for s in TUNE_SEEDS], THRESHOLD_GRID)
    threshold = choose_threshold(tune, THRESHOLD_GRID)
    report["tuning"] = {"threshold": threshold, "at_threshold": tune[threshold],
                        "grid": {str(t): {k: tune[t][k] for k in ("truth_recall", "view_recall", "truth_precision")}
                                 for t in THRESHOLD_GRID}}
    meta = make_metadata(tiles, RESOLUTION_CM, threshold, sigma, description)
    out = export_onnx(net, meta, args.out, PRODUCER)
    validation = evaluate(out, [campaigns[s] for s in VALIDATION_SEEDS], THRESHOLD_GRID)
    exact = evaluate(out, [campaigns[s] for s in VALIDATION_SEEDS], (threshold,))  # the default alone: its time
    report["validation"] = {"threshold": threshold, "at_default_threshold": exact[threshold],
                            "detect_seconds_per_frame": exact["detect_seconds_per_frame"],
                            "by_threshold_note": "one heatmap per frame, peaks extracted at each threshold",
                            "by_threshold": {str(t): {k: validation[t][k] for k in
                                                      ("recall_pre", "gmcf_pre", "truth_recall", "view_recall",
                                                       "truth_precision", "detections_per_frame")}
                                             for t in THRESHOLD_GRID}}
    report["model"] = {"file": Path(out).name, "bytes": Path(out).stat().st_size, "sha256": file_digest(out),
                       "metadata": {k: json.loads(v) for k, v in meta.to_props().items()}}
    report_path = Path(out).with_suffix(".training.json")
    report_path.write_text(json.dumps(report, indent=1))
    v = exact[threshold]
    print(f"threshold {threshold}: recall_pre {v['recall_pre']}, truth recall {v['truth_recall']}, "
          f"view recall {v['view_recall']}, precision vs truth {v['truth_precision']}; wrote {out}, {report_path}")


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    sub = parser.add_subparsers(dest="command", required=True)
    t = sub.add_parser("train", help="train on writelabels output folders")
    t.add_argument("--labels", action="append", required=True, help="a writelabels output folder (with tiles)")
    t.add_argument("--frames", action="append", help="GeoPackage frame layer(s) with frame_id and gsd_cm")
    t.add_argument("--gsd-cm", type=float, help="one GSD (cm/px) for every frame, instead of --frames")
    t.add_argument("--resolution-cm", type=float,
                   help=f"the model's resolution (default: the --init model's, else {RESOLUTION_CM:g})")
    t.add_argument("--threshold", type=float,
                   help="default threshold written into the model (default: the highest threshold within one "
                        "held-out target of the best ground F1 on the held-out frames)")
    t.add_argument("--backbone", choices=BACKBONES, default="small",
                   help="small (from scratch) or a torchvision encoder with ImageNet weights")
    t.add_argument("--weights", help="ImageNet weights (.pth) of the encoder (default: torchvision's cache)")
    t.add_argument("--validation", choices=SPLITS, default="blocks",
                   help="hold out spatial blocks of targets (default), whole --labels folders, or nothing")
    t.add_argument("--val-fraction", type=float, default=0.15, help="share of the targets held out for validation")
    t.add_argument("--seed", type=int, default=0)
    t.add_argument("--steps", type=int, help="a fixed number of steps instead of --minutes")
    t.add_argument("--width", type=int, default=WIDTH)
    t.add_argument("--minutes", type=float, default=20.0)
    t.add_argument("--threads", type=int, default=2)
    t.add_argument("--init", help="a .pt checkpoint of this recipe (same backbone) or a BirdsEye ONNX model of the "
                                  "small network to start from; its resolution and normalisation are kept")
    t.add_argument("--preset", choices=[p.name for p in PRESETS], default="fast",
                   help="fast (the recipe's own settings) or method (EfficientNetV2, frames' own GSD, two stages, "
                        "AdamW 1e-5, plain cross-entropy, early stopping; sets the network and resolution)")
    t.add_argument("--out", required=True)
    t.set_defaults(func=cmd_train)
    d = sub.add_parser("demo", help="simulate campaigns, train, tune and validate the bundled demo model")
    d.add_argument("--work", default=str(REPO_ROOT / "build" / "demo_training"))
    d.add_argument("--out", default=str(REPO_ROOT / "models" / "birdseye_demo_heatmap.onnx"))
    d.add_argument("--width", type=int, default=WIDTH)
    d.add_argument("--minutes", type=float, default=20.0)
    d.add_argument("--threads", type=int, default=2)
    d.add_argument("--reuse-weights", action="store_true",
                   help="keep the weights of the last demo run (work/demo.pt): re-tune and re-validate only")
    d.set_defaults(func=cmd_demo)
    args = parser.parse_args(argv)
    try:
        args.func(args)
    except InputError as exc:
        raise SystemExit(str(exc)) from None


if __name__ == "__main__":
    main()

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

``torch`` is a training extra (``requirements-train.txt``); the plugin never needs it.
"""
from __future__ import annotations

import argparse
import json
import math
import sqlite3
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

from birdseye.birdseye_qgis.core.detect.detector import file_digest, model_size, normalise, resample  # noqa: E402
from birdseye.birdseye_qgis.core.detect.model_metadata import ModelMetadata, embed_metadata  # noqa: E402

#: Defaults of the demo model (and of ``train``): see models/README.md for why.
RESOLUTION_CM = 1.0
TILE_SIZE = 288
TILES_OVERLAP_PCT = 20.0
CROP_PX = 96
WIDTH = 16
#: Target pixels are ~0.1 % of a tile: weighting each pixel's cross-entropy by 1 + POSITIVE_WEIGHT·label
#: keeps them from drowning in background (it does not move the optimum: still p = label per pixel).
POSITIVE_WEIGHT = 10.0


# ====================================================================================== network
def build_network(width: int = WIDTH):
    """The encoder–decoder heatmap network (logits); input N×3×H×W with H, W multiples of 8."""
    import torch
    from torch import nn

    def conv_bn(cin, cout, stride=1):
        return nn.Sequential(nn.Conv2d(cin, cout, 3, stride, 1, bias=False), nn.BatchNorm2d(cout),
                             nn.ReLU(inplace=True))

    def up(cin, cout):
        return nn.Sequential(nn.ConvTranspose2d(cin, cout, 2, 2, bias=False), nn.BatchNorm2d(cout),
                             nn.ReLU(inplace=True))

    c1, c2, c3 = width, 2 * width, 4 * width

    class Encoder(nn.Module):
        def __init__(self):
            super().__init__()
            self.stage1 = nn.Sequential(conv_bn(3, c1, 2), conv_bn(c1, c1))             # 1/2
            self.stage2 = nn.Sequential(conv_bn(c1, c2, 2), conv_bn(c2, c2))            # 1/4
            self.stage3 = nn.Sequential(conv_bn(c2, c3, 2), conv_bn(c3, c3), conv_bn(c3, c3))  # 1/8

        def forward(self, x):
            f1 = self.stage1(x)
            f2 = self.stage2(f1)
            return f1, f2, self.stage3(f2)

    class HeatmapNet(nn.Module):
        def __init__(self):
            super().__init__()
            self.encoder = Encoder()
            self.up3, self.fuse2 = up(c3, c2), conv_bn(c2, c2)   # 1/8 → 1/4, + stage2 features
            self.up2, self.fuse1 = up(c2, c1), conv_bn(c1, c1)   # 1/4 → 1/2, + stage1 features
            self.up1 = up(c1, c1)                                # 1/2 → 1/1
            self.head = nn.Conv2d(c1, 1, 3, 1, 1)
            nn.init.constant_(self.head.bias, -4.0)  # start near "no target": most pixels are background

        def forward(self, x):
            f1, f2, f3 = self.encoder(x)
            y = self.fuse2(self.up3(f3) + f2)
            y = self.fuse1(self.up2(y) + f1)
            return self.head(self.up1(y))

        def decoder_parameters(self):
            return [p for n, p in self.named_parameters() if not n.startswith("encoder.")]

    torch.manual_seed(0)
    return HeatmapNet()


# ====================================================================================== data
@dataclass
class TileSet:
    """Training tiles at the model's resolution: BGR uint8 images and soft labels in [0, 1]."""

    images: list
    labels: list
    positive: np.ndarray
    source_gsd_cm: np.ndarray

    def __len__(self) -> int:
        return len(self.images)


def frame_gsd_from_gpkg(path) -> dict:
    """``{frame_id: gsd_cm}`` from a GeoPackage frame layer (any table with those two columns)."""
    con = sqlite3.connect(str(path))
    try:
        tables = [r[0] for r in con.execute("SELECT table_name FROM gpkg_contents")]
        for table in tables:
            cols = [r[1] for r in con.execute(f'PRAGMA table_info("{table}")')]
            if "frame_id" in cols and "gsd_cm" in cols:
                return {str(f): float(g) for f, g in con.execute(f'SELECT frame_id, gsd_cm FROM "{table}"')
                        if g is not None}
    finally:
        con.close()
    raise SystemExit(f"{path}: no layer with fields frame_id and gsd_cm (is it a BirdsEye frame layer?)")


def load_tiles(sources, resolution_cm: float, log=print) -> TileSet:
    """Every tile pair of writelabels folders, resampled to ``resolution_cm``.

    ``sources`` is a list of ``(folder, gsd_of)``: ``gsd_of`` maps the frame ids (as text) of that
    folder's tiles to the frame's ground sample distance (cm/px).
    """
    import cv2

    images, labels, positive, gsd = [], [], [], []
    missing = set()
    for folder, gsd_of in sources:
        tile_dir = Path(folder) / "tiles"
        names = sorted(p.name for p in (tile_dir / "images").glob("*.png"))
        if not names:
            raise SystemExit(f"{folder}: no tiles in tiles/images (run writelabels with a tile size)")
        for name in names:
            frame_id = name.rsplit("_", 2)[0]
            if frame_id not in gsd_of:
                missing.add(f"{Path(folder).name}:{frame_id}")
                continue
            img = cv2.imread(str(tile_dir / "images" / name), cv2.IMREAD_COLOR)
            lab = cv2.imread(str(tile_dir / "labels" / name), cv2.IMREAD_UNCHANGED)
            size = model_size(img.shape[1], img.shape[0], gsd_of[frame_id], resolution_cm)
            images.append(resample(img, size))
            labels.append(resample(lab.astype(np.float32) / 255.0, size))
            positive.append(lab.max() >= 250)  # the tile holds a target's centre
            gsd.append(gsd_of[frame_id])
    if missing:
        log(f"{len(missing)} frame(s) of the tiles have no GSD and were left out, e.g. {sorted(missing)[:3]}")
    if not images:
        raise SystemExit("no training tiles")
    return TileSet(images, labels, np.asarray(positive), np.asarray(gsd))


def channel_stats(tiles: TileSet, order: str = "RGB"):
    """Per-channel mean and std of pixel values / 255 over the tiles, in the model's channel order."""
    pix = np.concatenate([im.reshape(-1, 3)[::7] for im in tiles.images]).astype(np.float64) / 255.0
    if order == "RGB":
        pix = pix[:, ::-1]
    return tuple(np.round(pix.mean(axis=0), 4).tolist()), tuple(np.round(pix.std(axis=0) + 1e-3, 4).tolist())


class Augmenter:
    """Random crops with scale jitter, flips and quarter turns (nadir views have no up), and
    photometric jitter (exposure, white balance, contrast, noise) — what changes between flights."""

    def __init__(self, tiles: TileSet, meta: ModelMetadata, crop: int, seed: int, scale_jitter=0.15):
        self.tiles, self.meta, self.crop = tiles, meta, crop
        self.rng = np.random.default_rng(seed)
        self.scale_jitter = scale_jitter

    def sample(self, index: int):
        import cv2

        rng, c = self.rng, self.crop
        img, lab = self.tiles.images[index], self.tiles.labels[index]
        s = math.exp(rng.uniform(-self.scale_jitter, self.scale_jitter))
        if abs(s - 1.0) > 0.02:
            size = (max(c, int(round(img.shape[1] * s))), max(c, int(round(img.shape[0] * s))))
            img, lab = resample(img, size), resample(lab, size)
        h, w = lab.shape
        if h < c or w < c:  # pad small tiles (frame borders) with reflected content
            img = cv2.copyMakeBorder(img, 0, max(0, c - h), 0, max(0, c - w), cv2.BORDER_REFLECT)
            lab = cv2.copyMakeBorder(lab, 0, max(0, c - h), 0, max(0, c - w), cv2.BORDER_REFLECT)
            h, w = lab.shape
        # Keep a target in positive crops: centre the crop window near the label's maximum half the time.
        if lab.max() > 0.5 and rng.random() < 0.5:
            vy, vx = np.unravel_index(np.argmax(lab), lab.shape)
            y0 = int(np.clip(vy - rng.integers(c // 8, c - c // 8), 0, h - c))
            x0 = int(np.clip(vx - rng.integers(c // 8, c - c // 8), 0, w - c))
        else:
            y0, x0 = int(rng.integers(0, h - c + 1)), int(rng.integers(0, w - c + 1))
        img, lab = img[y0:y0 + c, x0:x0 + c], lab[y0:y0 + c, x0:x0 + c]
        k = int(rng.integers(4))
        img, lab = np.rot90(img, k), np.rot90(lab, k)
        if rng.random() < 0.5:
            img, lab = img[:, ::-1], lab[:, ::-1]
        x = img.astype(np.float32)
        x = x * rng.uniform(0.7, 1.35) * rng.uniform(0.92, 1.08, 3)          # exposure, white balance
        mean = x.mean()
        x = (x - mean) * rng.uniform(0.8, 1.2) + mean                      # contrast
        x = x + rng.normal(0.0, rng.uniform(0.0, 4.0), x.shape)            # sensor noise
        img = np.clip(x, 0, 255).astype(np.uint8)
        return normalise(np.ascontiguousarray(img), self.meta), np.ascontiguousarray(lab, dtype=np.float32)

    def batch(self, size: int):
        idx = self.rng.integers(0, len(self.tiles), size)
        xs, ys = zip(*(self.sample(i) for i in idx))
        return np.stack(xs), np.stack(ys)[:, None]


# ====================================================================================== training
def train_network(net, tiles: TileSet, meta: ModelMetadata, minutes: float, frozen_fraction: float = 0.2,
                  batch: int = 16, crop: int = CROP_PX, lr: float = 3e-3, seed: int = 0, steps: int | None = None,
                  log=print) -> dict:
    """Two stages on a time budget (or a fixed number of ``steps``): encoder frozen, then all layers.

    The encoder's weights are frozen in stage 1 (its batch-norm statistics still follow the data);
    stage 2 fine-tunes everything with a cosine-decaying learning rate. Returns the loss history.
    """
    import torch

    torch.manual_seed(seed)
    aug = Augmenter(tiles, meta, crop, seed)
    def loss_fn(logits, target):
        weight = 1.0 + POSITIVE_WEIGHT * target
        return torch.nn.functional.binary_cross_entropy_with_logits(logits, target, weight) / weight.mean()
    history = {"stage": [], "step": [], "loss": [], "seconds": []}
    start = time.perf_counter()
    budget = minutes * 60.0

    def run_stage(name, params, stage_steps, stage_seconds, lr0):
        opt = torch.optim.AdamW(params, lr=lr0, weight_decay=1e-4)
        t0 = time.perf_counter()
        step, smoothed = 0, None
        net.train()
        while (step < stage_steps) if stage_steps is not None else (time.perf_counter() - t0 < stage_seconds):
            frac = (step / stage_steps) if stage_steps else (time.perf_counter() - t0) / stage_seconds
            for group in opt.param_groups:
                group["lr"] = lr0 * 0.5 * (1.0 + math.cos(math.pi * min(1.0, frac))) + 1e-5
            x, y = aug.batch(batch)
            logits = net(torch.from_numpy(x))
            loss = loss_fn(logits, torch.from_numpy(y))
            opt.zero_grad()
            loss.backward()
            opt.step()
            step += 1
            smoothed = loss.item() if smoothed is None else 0.98 * smoothed + 0.02 * loss.item()
            if step % 50 == 0 or (stage_steps is not None and step == stage_steps):
                history["stage"].append(name)
                history["step"].append(step)
                history["loss"].append(round(smoothed, 5))
                history["seconds"].append(round(time.perf_counter() - start, 1))
                log(f"  {name} step {step}: loss {smoothed:.4f} ({time.perf_counter() - start:.0f} s)")
        return step

    for p in net.encoder.parameters():
        p.requires_grad_(False)
    n1 = None if steps is None else max(1, int(steps * frozen_fraction))
    history["frozen_steps"] = run_stage("frozen-encoder", net.decoder_parameters(), n1, budget * frozen_fraction, lr)
    for p in net.encoder.parameters():
        p.requires_grad_(True)
    n2 = None if steps is None else steps - n1
    history["finetune_steps"] = run_stage("fine-tune", list(net.parameters()), n2,
                                          budget * (1 - frozen_fraction), lr / 3)
    history["train_seconds"] = round(time.perf_counter() - start, 1)
    net.eval()
    return history


def export_onnx(net, meta: ModelMetadata, path) -> Path:
    """The network + a sigmoid (output: probabilities) as ONNX, dynamic batch and size, with ``meta``."""
    import io
    import warnings

    import onnx
    import torch

    class Probabilities(torch.nn.Module):
        def __init__(self, inner):
            super().__init__()
            self.inner = inner

        def forward(self, x):
            return torch.sigmoid(self.inner(x))

    wrapped = Probabilities(net).eval()  # eval: tracing in train mode would update batch-norm statistics
    buffer = io.BytesIO()
    with warnings.catch_warnings():  # the TorchScript exporter is deprecated but needs no onnxscript
        warnings.simplefilter("ignore")
        torch.onnx.export(wrapped, torch.zeros(1, 3, meta.tile_size, meta.tile_size), buffer,
                          input_names=["image"], output_names=["heatmap"], opset_version=17, dynamo=False,
                          dynamic_axes={"image": {0: "n", 2: "h", 3: "w"}, "heatmap": {0: "n", 2: "h", 3: "w"}})
    model = onnx.load_from_string(buffer.getvalue())
    model.producer_name = "BirdsEye training/train_heatmap.py"
    model.graph.name = "birdseye_heatmap"
    embed_metadata(model, meta)
    onnx.checker.check_model(model)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    onnx.save(model, str(path))
    return path


def make_metadata(tiles: TileSet, resolution_cm: float, threshold: float, label_sigma_px: float | None,
                  description: str) -> ModelMetadata:
    mean, std = channel_stats(tiles)
    return ModelMetadata(resolution_cm=resolution_cm, tile_size=TILE_SIZE, tiles_overlap_pct=TILES_OVERLAP_PCT,
                         output_kind="probability", default_threshold=threshold, standardization_mean=mean,
                         standardization_std=std, class_names=("burrow",), input_channel_order="RGB",
                         training_gsd_cm=round(float(np.median(tiles.source_gsd_cm)), 4),
                         label_sigma_px=label_sigma_px, description=description)


# ====================================================================================== commands
def cmd_train(args) -> None:
    import torch

    torch.set_num_threads(args.threads)
    label_dirs = [Path(p) for p in args.labels]
    if args.frames and len(args.frames) != len(label_dirs):
        raise SystemExit("give one --frames layer per --labels folder (in the same order), or --gsd-cm")
    sources = []
    for i, folder in enumerate(label_dirs):
        if args.frames:
            gsd_of = frame_gsd_from_gpkg(args.frames[i])
        elif args.gsd_cm:
            gsd_of = {p.name.rsplit("_", 2)[0]: args.gsd_cm for p in (folder / "tiles" / "images").glob("*.png")}
        else:
            raise SystemExit("give the frames' GSD: --frames frames.gpkg (per --labels) or --gsd-cm")
        sources.append((folder, gsd_of))
    tiles = load_tiles(sources, args.resolution_cm)
    meta = make_metadata(tiles, args.resolution_cm, args.threshold, _label_sigma(label_dirs, tiles, args.resolution_cm),
                         f"trained by training/train_heatmap.py on {', '.join(p.name for p in label_dirs)}")
    net = build_network(args.width)
    if args.init:
        net.load_state_dict(torch.load(args.init, weights_only=True))
    print(f"{len(tiles)} tiles ({int(tiles.positive.sum())} with a target); training {args.minutes:g} min")
    history = train_network(net, tiles, meta, args.minutes, log=_log)
    out = export_onnx(net, meta, args.out)
    torch.save(net.state_dict(), out.with_suffix(".pt"))
    out.with_suffix(".training.json").write_text(json.dumps(history, indent=1))
    print(f"wrote {out} ({out.stat().st_size / 1e6:.2f} MB) and {out.with_suffix('.pt')}")


def _log(message: str) -> None:
    print(message, flush=True)  # the log of a long run shows up while it runs


def _label_sigma(label_dirs, tiles: TileSet, resolution_cm: float):
    """σ of the soft labels at the model's resolution (from writelabels' summary.json), if known."""
    sigmas = []
    for folder in label_dirs:
        summary = Path(folder) / "summary.json"
        if summary.is_file():
            sigmas.append(float(json.loads(summary.read_text())["sigma_px"]))
    if not sigmas:
        return None
    scale = float(np.median(tiles.source_gsd_cm)) / resolution_cm
    return round(float(np.median(sigmas)) * scale, 3)


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
    from birdseye.birdseye_qgis.core.field.geotags import read_geotags
    from birdseye.birdseye_qgis.core.geometry.camera import load_calibration
    from birdseye.birdseye_qgis.core.labels.training_set import Geotags

    fps = json.loads((folder / "truth" / "campaign.json").read_text())["parameters"]["fps"]
    result = import_flight_log(folder / "poses.csv", folder, load_calibration(folder / "calibration.yaml"), fps=fps)
    records = list(frame_records(result.frames, result.footprints))
    (poses, index), = poses_from_records(records, str(folder))
    tags = read_geotags(folder / "geotags.csv")
    geotags = Geotags(np.arange(1, len(tags) + 1), tags.label, tags.lat, tags.lon, tags.h_ellipsoid)
    rows = list(csv.DictReader(open(folder / "truth" / "targets.csv", encoding="utf-8")))
    truth = Geotags([int(r["id"]) for r in rows], ["burrow"] * len(rows), [float(r["lat"]) for r in rows],
                    [float(r["lon"]) for r in rows], [float(r["h_ground"]) for r in rows])
    return Campaign(folder.name, poses, [records[i]["image"] for i in index], geotags, truth,
                    {str(records[i]["frame_id"]): float(records[i]["gsd_cm"]) for i in index})


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
      very frame; ``truth_precision``: detections within MATCH_RADIUS_M of a true target.
    Each frame's heatmap is computed once and its peaks extracted at every threshold
    (:func:`detect_frames_at_thresholds`): what a run at that threshold gives, not a score filter of a
    lower one (a blob splits at a higher threshold).
    """
    from scipy.spatial import cKDTree

    from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel, detect_frames_at_thresholds
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
    from birdseye.birdseye_qgis.core.labels.training_set import project_labels
    from birdseye.birdseye_qgis.core.scoring.evaluation import Detections, Flight, Geotags, evaluate_flights
    from birdseye.birdseye_qgis.core.scoring.operating_point import OperatingPoint

    model = HeatmapModel(model_path)
    totals = {t: dict(n_in_view=0, n_recovered=0, n_clusters=0, n_hit_clusters=0, truth_in_view=0,
                      truth_recovered=0, views=0, views_detected=0, detections=0, detections_on_target=0,
                      frames=0) for t in thresholds}
    seconds = 0.0
    for c in campaigns:
        local = LocalFrame.around(c.poses.lat, c.poses.lon, c.poses.ground_height)
        t0 = time.perf_counter()
        per_frame = [runs for runs in detect_frames_at_thresholds(model, c.poses, c.images, thresholds, local=local)
                     if runs[0].skipped is None]
        seconds += time.perf_counter() - t0
        truth_xy = local.from_geodetic(c.truth.lat, c.truth.lon, c.truth.height)[:, :2]
        views = project_labels(c.poses, c.truth, 0.0, local)
        in_view_truth = np.zeros(len(c.truth), bool)
        for fl in views:
            in_view_truth[fl.geotag_index[~fl.edge]] = True
        truth_tree = cKDTree(truth_xy)
        for k, t in enumerate(thresholds):
            tot = totals[t]
            found = [runs[k] for runs in per_frame]
            fid = np.concatenate([np.full(len(f), f.frame_id) for f in found]) if found else np.zeros(0)
            det = {key: np.concatenate([getattr(f, key) for f in found]) if found else np.zeros(0)
                   for key in ("lat", "lon", "height", "score")}
            det_xy = np.concatenate([f.ground_local[:, :2] for f in found]) if found else np.zeros((0, 2))
            ev = evaluate_flights(
                [Flight(Detections(det["lat"], det["lon"], det["height"], fid, det["score"]), [c.poses], c.name)],
                Geotags(c.geotags.ids, c.geotags.lat, c.geotags.lon, c.geotags.height),
                OperatingPoint(threshold=t), local=local)
            for key in ("n_in_view", "n_recovered", "n_clusters", "n_hit_clusters"):
                tot[key] += getattr(ev.pooled, key)
            recovered = np.zeros(len(c.truth), bool)
            if len(det_xy):
                d, _ = cKDTree(det_xy).query(truth_xy, distance_upper_bound=MATCH_RADIUS_M)
                recovered = d <= MATCH_RADIUS_M
                near_truth = truth_tree.query(det_xy, distance_upper_bound=MATCH_RADIUS_M)[0] <= MATCH_RADIUS_M
                tot["detections_on_target"] += int(near_truth.sum())
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
    net = build_network(args.width)
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
    draft = export_onnx(net, meta, work / "draft.onnx")
    tune = evaluate(draft, [campaigns[s] for s in TUNE_SEEDS], THRESHOLD_GRID)
    threshold = choose_threshold(tune, THRESHOLD_GRID)
    report["tuning"] = {"threshold": threshold, "at_threshold": tune[threshold],
                        "grid": {str(t): {k: tune[t][k] for k in ("truth_recall", "view_recall", "truth_precision")}
                                 for t in THRESHOLD_GRID}}
    meta = make_metadata(tiles, RESOLUTION_CM, threshold, sigma, description)
    out = export_onnx(net, meta, args.out)
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
    t.add_argument("--resolution-cm", type=float, default=RESOLUTION_CM)
    t.add_argument("--threshold", type=float, default=0.5, help="default threshold written into the model")
    t.add_argument("--width", type=int, default=WIDTH)
    t.add_argument("--minutes", type=float, default=20.0)
    t.add_argument("--threads", type=int, default=2)
    t.add_argument("--init", help="a .pt checkpoint of this recipe to start from")
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
    args.func(args)


if __name__ == "__main__":
    main()

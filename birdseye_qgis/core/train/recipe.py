"""The heatmap training recipe: networks, training tiles, augmentation, the training loop, validation
figures and ONNX export with BirdsEye/Deepness metadata.

One implementation for ``training/train_heatmap.py`` (``train`` and ``demo``) and for the child process
of ``birdseye:traindetector`` (:mod:`.job`, :mod:`.child`). torch, torchvision, onnx and OpenCV are
imported inside the functions that need them: importing this module costs nothing and never loads torch.

Networks (:data:`BACKBONES`):

* ``small`` — the recipe's own encoder–decoder (three stride-2 stages, a transposed-convolution
  decoder with skip connections, a 3×3 head giving one logit per pixel), from scratch; works offline;
* an ImageNet-pretrained torchvision encoder (EfficientNet or ResNet family) cut after its stride-16
  stage, with a light top-down decoder (1×1 laterals at strides 16, 8, 4, 2, transposed-convolution
  upsampling). The ImageNet weights come from torchvision's cache (``<torch hub dir>/checkpoints``,
  the file name torchvision would download) or from a file the user names; nothing is downloaded.

Training: binary cross-entropy on the soft labels of ``writelabels`` (values / 255), each pixel weighted
by ``1 + POSITIVE_WEIGHT·label``; first with the encoder frozen (decoder and head learn to read its
features), then fine-tuning every layer with a cosine-decaying learning rate; on a time budget or a
fixed number of steps; on the GPU when torch sees one. That is the ``fast`` preset; a
:class:`.preset.TrainingPreset` (``method``: the published method's recipe) sets every one of these
choices differently, and :func:`train_network` reads them from it.
"""
from __future__ import annotations

import json
import math
import os
import sqlite3
import sys
import time
import types
from dataclasses import dataclass
from dataclasses import replace as dataclass_replace
from pathlib import Path
from typing import Callable

import numpy as np

from ..detect.detector import find_peaks, model_size, normalise, resample
from ..detect.model_metadata import ModelMetadata, embed_metadata
from ..errors import InputError
from .choices import BACKBONES
from .onnx_init import freeze_batch_norm_stats, frozen_batch_norms, is_onnx, load_onnx_init
from .preset import FAST, TrainingPreset

#: Defaults of the demo model (and of ``train``): see models/README.md for why.
RESOLUTION_CM = 1.0
TILE_SIZE = 288
TILES_OVERLAP_PCT = 20.0
CROP_PX = FAST.crop_px
WIDTH = 16
#: Target pixels are ~0.1 % of a tile: weighting each pixel's cross-entropy by 1 + POSITIVE_WEIGHT·label
#: keeps them from drowning in background (it does not move the optimum: still p = label per pixel).
POSITIVE_WEIGHT = FAST.positive_weight
#: ImageNet statistics (RGB) the pretrained encoders were trained with.
IMAGENET_MEAN = (0.485, 0.456, 0.406)
IMAGENET_STD = (0.229, 0.224, 0.225)
#: Thresholds at which validation figures are given.
THRESHOLDS = tuple(np.round(np.arange(0.1, 0.91, 0.1), 2).tolist())
CHECKPOINT_FORMAT = "birdseye-heatmap-checkpoint"
#: The class a model is named for when its labels name none (folders without labels.csv).
DEFAULT_CLASS_NAMES = ("burrow",)
#: A label maximum at least this high is a target's centre in the validation figures. Labels peak at 1 in
#: the frame, but resampled from the frames' ground sample distance to the model's (¼ and less) the
#: Gaussian's peak is averaged with its neighbours (0.23 cm/px → 1 cm/px: 0.95 for σ = 10 px, 0.60 for 3 px).
CENTRE_MIN_LABEL = 0.25


# ====================================================================================== torchvision
def import_torchvision():
    """torchvision, for its model definitions only.

    A torchvision whose compiled operators do not match the torch beside it (PyPI's CUDA build of
    torchvision next to a CPU build of torch) fails on import while registering fake kernels for
    detection operators (``operator torchvision::nms does not exist``). The classification models
    need none of those operators, so the import is retried with that registration module left empty.
    """
    try:
        import torchvision
    except RuntimeError as exc:
        if "torchvision::" not in str(exc):
            raise
        for name in [n for n in sys.modules if n == "torchvision" or n.startswith("torchvision.")]:
            del sys.modules[name]
        sys.modules["torchvision._meta_registrations"] = types.ModuleType("torchvision._meta_registrations")
        import torchvision
    return torchvision


def cached_weights_path(backbone: str) -> tuple[Path, str]:
    """(where torchvision keeps ``backbone``'s ImageNet weights in its cache, the URL it would fetch)."""
    import torch

    tv = import_torchvision()
    url = tv.models.get_model_weights(backbone).DEFAULT.url
    return Path(torch.hub.get_dir()) / "checkpoints" / url.rsplit("/", 1)[-1], url


def read_state_dict(path) -> dict:
    """A state dict from a ``.pt``/``.pth`` file: a bare state dict, or one under ``state_dict``/``model``
    (this recipe's checkpoints, and common training scripts)."""
    import torch

    try:
        obj = torch.load(str(path), map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001 — any unreadable file is the user's to fix
        raise InputError(f"is not a PyTorch weights file ({exc})", source=str(path)) from exc
    if isinstance(obj, dict):
        for key in ("state_dict", "model"):
            if isinstance(obj.get(key), dict):
                return obj[key]
        return obj
    raise InputError("holds no state dict (a dict of tensors)", source=str(path))


# ====================================================================================== networks
def _layers():
    from torch import nn

    def conv_bn(cin, cout, stride=1):
        return nn.Sequential(nn.Conv2d(cin, cout, 3, stride, 1, bias=False), nn.BatchNorm2d(cout),
                             nn.ReLU(inplace=True))

    def up(cin, cout):
        return nn.Sequential(nn.ConvTranspose2d(cin, cout, 2, 2, bias=False), nn.BatchNorm2d(cout),
                             nn.ReLU(inplace=True))

    return conv_bn, up


def build_network(backbone: str = "small", width: int = WIDTH, weights=None, pretrained: bool = True, log=print):
    """The heatmap network (logits); input N×3×H×W with H, W multiples of ``net.input_multiple``.

    ``pretrained``: load ImageNet weights into a torchvision encoder (from ``weights`` or torchvision's
    cache); False when a checkpoint of this recipe replaces them anyway (``--init``).
    """
    if backbone == "small":
        return _small_network(width)
    if backbone not in BACKBONES:
        raise InputError(f"unknown backbone '{backbone}'; one of {', '.join(BACKBONES)}", field="BACKBONE")
    return _pretrained_network(backbone, weights, pretrained, log)


def _small_network(width: int):
    import torch
    from torch import nn

    conv_bn, up = _layers()
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
        input_multiple = 8

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


def _encoder_blocks(backbone: str, full) -> list:
    """The torchvision model's feature extractor as a list of sequential blocks."""
    from torch import nn

    if backbone.startswith("efficientnet"):
        return list(full.features.children())
    return [nn.Sequential(full.conv1, full.bn1, full.relu), full.maxpool, full.layer1, full.layer2, full.layer3,
            full.layer4]


def _pretrained_network(backbone: str, weights, pretrained: bool, log):
    import torch
    from torch import nn

    tv = import_torchvision()
    torch.manual_seed(0)
    full = getattr(tv.models, backbone)(weights=None)  # never torchvision's download
    if pretrained:
        if weights:
            path = Path(weights)
            if not path.is_file():
                raise InputError("does not exist", source=str(path), field="WEIGHTS")
        else:
            path, url = cached_weights_path(backbone)
            if not path.is_file():
                raise InputError(
                    f"the ImageNet weights of {backbone} are not in torchvision's cache and no weights file "
                    f"was given. Nothing is downloaded: put the file {path.name} (from {url}) into "
                    f"{path.parent}, or name a weights file (WEIGHTS, --weights); or train the 'small' "
                    "network, which needs none", field="WEIGHTS")
        try:
            full.load_state_dict(read_state_dict(path), strict=True)
        except RuntimeError as exc:
            raise InputError(f"does not hold {backbone} weights ({str(exc).splitlines()[0]})",
                             source=str(path), field="WEIGHTS") from exc
        log(f"ImageNet weights of {backbone}: {path}")
    blocks = _encoder_blocks(backbone, full)
    probe, sizes, channels = torch.zeros(1, 3, 64, 64), [], []
    with torch.no_grad():
        for block in blocks:
            block.eval()
            probe = block(probe)
            sizes.append(probe.shape[-1])
            channels.append(probe.shape[1])
    taps = [max(i for i, s in enumerate(sizes) if s == 64 // stride) for stride in (2, 4, 8, 16)]
    blocks = blocks[:taps[-1] + 1]
    tap_channels = [channels[i] for i in taps]
    conv_bn, up = _layers()
    width = 32

    class Encoder(nn.Module):
        def __init__(self):
            super().__init__()
            self.blocks = nn.ModuleList(blocks)

        def forward(self, x):
            out = []
            for i, block in enumerate(self.blocks):
                x = block(x)
                if i in taps:
                    out.append(x)
            return out

    class PretrainedHeatmapNet(nn.Module):
        input_multiple = 16

        def __init__(self):
            super().__init__()
            self.encoder = Encoder()
            self.lateral = nn.ModuleList(nn.Conv2d(c, width, 1) for c in tap_channels)
            self.ups = nn.ModuleList(up(width, width) for _ in tap_channels[1:])
            self.fuse = nn.ModuleList(conv_bn(width, width) for _ in tap_channels[1:])
            self.up_out = up(width, width)
            self.head = nn.Conv2d(width, 1, 3, 1, 1)
            nn.init.constant_(self.head.bias, -4.0)

        def forward(self, x):
            feats = self.encoder(x)
            y = self.lateral[-1](feats[-1])
            for i in range(len(feats) - 2, -1, -1):
                y = self.fuse[i](self.ups[i](y) + self.lateral[i](feats[i]))
            return self.head(self.up_out(y))

        def decoder_parameters(self):
            return [p for n, p in self.named_parameters() if not n.startswith("encoder.")]

    net = PretrainedHeatmapNet()
    net.train()
    return net


def standardization(backbone: str, tiles: "TileSet", init: "ModelInput | None" = None):
    """(mean, std) the model normalises with: the INIT model's (``init``) when it records them, else ImageNet's
    for a pretrained encoder, else the tiles'."""
    if init is not None:
        return init.mean, init.std
    return (IMAGENET_MEAN, IMAGENET_STD) if backbone != "small" else channel_stats(tiles)


@dataclass(frozen=True)
class ModelInput:
    """What a model's input is: its resolution (cm/px) and standardisation (per channel of pixel values / 255,
    in ``channel_order``), as an INIT model records them."""

    resolution_cm: float
    mean: tuple
    std: tuple
    channel_order: str = "RGB"

    @classmethod
    def of(cls, meta: ModelMetadata) -> "ModelInput":
        return cls(float(meta.resolution_cm), tuple(meta.standardization_mean), tuple(meta.standardization_std),
                   meta.input_channel_order)


def init_model_input(path) -> ModelInput | None:
    """The input the INIT model at ``path`` was trained on: a BirdsEye ONNX model's metadata, or what a checkpoint
    of this recipe records; None for a checkpoint written before they were recorded, or a bare state dict."""
    if is_onnx(path):
        from ..detect.model_metadata import read_onnx_metadata

        return ModelInput.of(read_onnx_metadata(path))
    record = _checkpoint_record(path)
    if record is None or record.get("resolution_cm") is None or record.get("standardization_mean") is None:
        return None
    return ModelInput(float(record["resolution_cm"]), tuple(float(x) for x in record["standardization_mean"]),
                      tuple(float(x) for x in record["standardization_std"]),
                      str(record.get("input_channel_order") or "RGB"))


def model_resolution(asked: float | None, init: ModelInput | None, init_path=None) -> float:
    """The resolution (cm/px) a run trains at: ``asked`` (RESOLUTION_CM, --resolution-cm), else the INIT model's
    (``init``), else :data:`RESOLUTION_CM`. Refuses an ``asked`` resolution the INIT model was not trained at: its
    filters have learnt targets of a size in pixels."""
    if init is None:
        return float(asked) if asked is not None else RESOLUTION_CM
    if asked is None or math.isclose(float(asked), init.resolution_cm, rel_tol=1e-6):
        return init.resolution_cm
    raise InputError(f"was trained at {init.resolution_cm:g} cm/px, but the resolution asked for is {float(asked):g} "
                     f"cm/px (RESOLUTION_CM, --resolution-cm): leave it empty to fine-tune at {init.resolution_cm:g} "
                     "cm/px, or start from a model trained at the resolution you want", source=str(init_path),
                     field="INIT")


def label_class_names(label_dirs, log=print) -> tuple:
    """The model's class names from the ``label`` column of the folders' labels.csv: the one class they all
    share, or — the heatmap has one output channel, which cannot tell classes apart — every class, sorted,
    joined by ``+`` into that channel's one name (said in the log). :data:`DEFAULT_CLASS_NAMES` when no folder
    names a class."""
    import csv

    names = set()
    for folder in label_dirs:
        path = Path(folder) / "labels.csv"
        if path.is_file():
            with open(path, newline="", encoding="utf-8") as f:
                names |= {str(row.get("label") or "").strip() for row in csv.DictReader(f)}
    names = sorted(n for n in names if n)
    if not names:
        return DEFAULT_CLASS_NAMES
    if len(names) > 1:
        log(f"the labels name {len(names)} classes ({', '.join(names)}); the heatmap has one output channel, "
            f"which detects them all alike: its class is named '{'+'.join(names)}'")
    return ("+".join(names),)


def encoder_units(net) -> list:
    """The encoder's blocks in forward order, down to single blocks: a stem, each inverted-residual block
    of an EfficientNet stage, each residual block of a ResNet layer, each convolution of the small
    network; modules without parameters (a max-pool) are left out. What a preset's unfrozen share counts."""
    from torch import nn

    units = []

    def visit(module, top=False):
        children = list(module.children())
        weighted = [c for c in children if any(True for _ in c.parameters())]
        of_blocks = weighted and all(any(True for _ in c.children()) for c in weighted)
        if top or isinstance(module, nn.ModuleList) or (isinstance(module, nn.Sequential) and of_blocks):
            for child in children:
                visit(child)
        elif any(True for _ in module.parameters()):
            units.append(module)

    visit(net.encoder, top=True)
    return units


def load_native_tiles(sources, log=print, is_canceled: Callable[[], bool] = lambda: False) -> "TileSet":
    """Every tile pair of writelabels folders at its frame's own ground sample distance: no tile is
    resampled (:func:`load_tiles` told that each frame's GSD is the model's); ``source_gsd_cm`` still
    holds each tile's frame GSD. ``sources`` as for :func:`load_tiles`; None when cancelled."""
    tiles = load_tiles([(folder, {frame: 1.0 for frame in gsd_of}) for folder, gsd_of in sources], 1.0,
                       log=log, is_canceled=is_canceled)
    if tiles is None:
        return None
    keys = [key.split(":", 1) for key in tiles.frame_key]
    tiles.source_gsd_cm = np.asarray([sources[int(k)][1][frame] for k, frame in keys], float)
    return tiles


# ====================================================================================== data
@dataclass
class TileSet:
    """Training tiles at the model's resolution: BGR uint8 images and soft labels in [0, 1]."""

    images: list
    labels: list
    positive: np.ndarray
    source_gsd_cm: np.ndarray
    frame_key: list | None = None  # "<folder index>:<frame id>" per tile (splits keep a frame together)

    def __len__(self) -> int:
        return len(self.images)

    def subset(self, index) -> "TileSet":
        index = [int(i) for i in index]
        keys = None if self.frame_key is None else [self.frame_key[i] for i in index]
        return TileSet([self.images[i] for i in index], [self.labels[i] for i in index], self.positive[index],
                       self.source_gsd_cm[index], keys)


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
    raise InputError("no layer with fields frame_id and gsd_cm (is it a BirdsEye frame layer?)", source=str(path))


def tile_names(folder) -> list[str]:
    """The tile file names of a writelabels folder (``tiles/images/<frame_id>_<y0>_<x0>.png``)."""
    tile_dir = Path(folder) / "tiles"
    names = sorted(p.name for p in (tile_dir / "images").glob("*.png"))
    if not names:
        raise InputError("no tiles in tiles/images (run Write training labels with a tile size)", source=str(folder))
    return names


def load_tiles(sources, resolution_cm: float, log=print, is_canceled: Callable[[], bool] = lambda: False) -> TileSet:
    """Every tile pair of writelabels folders, resampled to ``resolution_cm``.

    ``sources`` is a list of ``(folder, gsd_of)``: ``gsd_of`` maps the frame ids (as text) of that
    folder's tiles to the frame's ground sample distance (cm/px).
    """
    import cv2

    images, labels, positive, gsd, keys = [], [], [], [], []
    missing = set()
    for k, (folder, gsd_of) in enumerate(sources):
        tile_dir = Path(folder) / "tiles"
        centres = label_centres(folder)
        for name in tile_names(folder):
            if is_canceled():
                return None
            frame_id = name.rsplit("_", 2)[0]
            if frame_id not in gsd_of:
                missing.add(f"{Path(folder).name}:{frame_id}")
                continue
            img = cv2.imread(str(tile_dir / "images" / name), cv2.IMREAD_COLOR)
            lab = cv2.imread(str(tile_dir / "labels" / name), cv2.IMREAD_UNCHANGED)
            if img is None or lab is None:
                raise InputError("cannot be read as an image tile and its label tile",
                                 source=str(tile_dir / ("images" if img is None else "labels") / name))
            if lab.ndim == 3:
                lab = lab[..., 0]
            size = model_size(img.shape[1], img.shape[0], gsd_of[frame_id], resolution_cm)
            images.append(resample(img, size))
            labels.append(resample(lab.astype(np.float32) / 255.0, size))
            positive.append(tile_holds_centre(name, lab.shape, centres) if centres is not None
                            else lab.max() >= 250)  # no labels.csv: the raster's peak, missed under σ ≈ 3.5 px
            gsd.append(gsd_of[frame_id])
            keys.append(f"{k}:{frame_id}")
    if missing:
        log(f"{len(missing)} frame(s) of the tiles have no GSD and were left out, e.g. {sorted(missing)[:3]}")
    if not images:
        raise InputError("no training tiles: no tile's frame has a ground sample distance (give the frame "
                         "layers the labels were written from)", field="FRAMES")
    return TileSet(images, labels, np.asarray(positive, bool), np.asarray(gsd, float), keys)


def label_centres(folder) -> dict | None:
    """``{frame_id: (n, 2) array of u, v}`` of the labels in a writelabels folder's labels.csv (the labels its
    positive tiles were cut around), or None without labels.csv (or without those columns)."""
    import csv

    path = Path(folder) / "labels.csv"
    if not path.is_file():
        return None
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        if not {"frame_id", "u", "v"} <= set(reader.fieldnames or ()):
            return None
        rows = {}
        for row in reader:
            try:
                rows.setdefault(str(row["frame_id"]), []).append((float(row["u"]), float(row["v"])))
            except (TypeError, ValueError):
                continue
    return {frame: np.asarray(uv, float) for frame, uv in rows.items()}


def tile_holds_centre(name: str, shape, centres: dict) -> bool:
    """Whether the tile ``<frame_id>_<y0>_<x0>.png`` (square, ``shape[0]`` px) holds a label centre of its frame,
    by the rule writelabels cut it with (:func:`..labels.training_set.inside_tile`)."""
    from ..labels.training_set import inside_tile

    frame_id, y0, x0 = Path(name).stem.rsplit("_", 2)
    uv = centres.get(frame_id)
    return uv is not None and bool(inside_tile(uv, int(x0), int(y0), shape[0]).any())


def split_tiles(tiles: TileSet, fraction: float, seed: int) -> tuple[TileSet, TileSet | None]:
    """(training, validation): about ``fraction`` of the frames held out with all their tiles (a target
    seen twice in one frame's tiles never sits on both sides), drawn separately among frames with a
    target and frames without, so both sides get positives."""
    if fraction <= 0 or len(tiles) < 2:
        return tiles, None
    keys = tiles.frame_key or [str(i) for i in range(len(tiles))]
    frames = sorted(set(keys))
    has_target = {f: False for f in frames}
    for key, pos in zip(keys, tiles.positive):
        has_target[key] |= bool(pos)
    rng = np.random.default_rng(seed)
    held = set()
    for group in ([f for f in frames if has_target[f]], [f for f in frames if not has_target[f]]):
        n = int(round(fraction * len(group)))
        if group and n == 0 and fraction > 0 and len(group) >= 4:
            n = 1
        held |= {group[i] for i in rng.permutation(len(group))[:n]}
    val = [i for i, key in enumerate(keys) if key in held]
    train = [i for i, key in enumerate(keys) if key not in held]
    if not val or not train:
        return tiles, None
    return tiles.subset(train), tiles.subset(val)


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
def loss_fn(logits, target, positive_weight: float = POSITIVE_WEIGHT):
    """Binary cross-entropy on soft labels, each pixel weighted 1 + ``positive_weight``·label (weights
    normalised to mean 1); plain, unweighted binary cross-entropy for ``positive_weight`` 0."""
    import torch

    if not positive_weight:
        return torch.nn.functional.binary_cross_entropy_with_logits(logits, target)
    weight = 1.0 + positive_weight * target
    return torch.nn.functional.binary_cross_entropy_with_logits(logits, target, weight) / weight.mean()


def device():
    """The GPU when torch sees one, else the CPU."""
    import torch

    return torch.device("cuda" if torch.cuda.is_available() else "cpu")


def _padded(image: np.ndarray, multiple: int) -> np.ndarray:
    """(C, H, W) padded at the bottom and right by reflection to multiples of ``multiple``."""
    h, w = image.shape[-2:]
    ph, pw = (-h) % multiple, (-w) % multiple
    if ph or pw:
        mode = "reflect" if ph < h and pw < w else "edge"
        image = np.pad(image, [(0, 0)] * (image.ndim - 2) + [(0, ph), (0, pw)], mode=mode)
    return image


def predict_tiles(net, tiles: TileSet, meta: ModelMetadata, limit: int | None = None):
    """(logits, labels) per tile of ``tiles`` (at most ``limit``): each tile alone, padded to the network's
    input multiple, the logits cropped back to the tile."""
    import torch

    dev = next(net.parameters()).device
    multiple = getattr(net, "input_multiple", 8)
    was_training = net.training
    net.eval()
    out = []
    with torch.no_grad():
        for i in range(len(tiles) if limit is None else min(limit, len(tiles))):
            x = _padded(normalise(tiles.images[i], meta), multiple)
            logits = net(torch.from_numpy(np.ascontiguousarray(x))[None].to(dev))[0, 0]
            h, w = tiles.labels[i].shape
            out.append((logits[:h, :w].cpu().numpy(), tiles.labels[i]))
    net.train(was_training)
    return out


def validation_loss(net, tiles: TileSet, meta: ModelMetadata, limit: int | None = 32,
                    positive_weight: float = POSITIVE_WEIGHT) -> float:
    """Mean loss (:func:`loss_fn`) over up to ``limit`` held-out tiles (None: all), no augmentation."""
    import torch

    pairs = predict_tiles(net, tiles, meta, limit)
    return float(np.mean([loss_fn(torch.from_numpy(z), torch.from_numpy(y), positive_weight).item()
                          for z, y in pairs]))


def train_network(net, tiles: TileSet, meta: ModelMetadata, minutes: float, frozen_fraction: float = 0.2,
                  batch: int = 16, crop: int = CROP_PX, lr: float = 3e-3, seed: int = 0, steps: int | None = None,
                  log=print, val: TileSet | None = None, on_point: Callable[[dict], None] | None = None,
                  on_step: Callable[[dict], None] | None = None, should_stop: Callable[[], bool] = lambda: False,
                  checkpoint: Callable[[str, int], None] | None = None, checkpoint_every_s: float = 30.0,
                  preset: TrainingPreset | None = None, encoder_pretrained: bool = True) -> dict:
    """Two stages on a time budget (or a fixed number of ``steps``): encoder frozen, then all layers
    (or the top share of its blocks, :func:`encoder_units`).

    ``preset`` (:class:`.preset.TrainingPreset`) fixes the crop, batch (unless None), stage split, unfrozen
    share, optimiser, learning rates and schedule, loss and early stopping; without one, the ``fast``
    preset with ``frozen_fraction``, ``crop`` and ``lr``. The encoder's weights are frozen in stage 1; its
    batch-norm statistics follow the data unless the preset freezes them and the encoder starts from
    trained weights (``encoder_pretrained``). A point of the loss history is taken every 50 steps or every
    few seconds of a short budget and at each stage's end, with the validation loss on ``val`` (when
    given) — with early stopping instead at each epoch's end (one pass over ``tiles``). A stage with
    early stopping ends after ``patience_epochs`` epochs without a lower validation loss (training loss
    without ``val``) and, with ``restore_best``, ends on its best epoch's weights. ``on_point`` receives
    each point, ``on_step`` every step's progress, ``checkpoint(stage, step)`` is called at most every
    ``checkpoint_every_s`` and at each stage's end. ``should_stop()`` ends training early
    (history["stopped"]). Returns the history; ``history["stages"]`` says what ended each stage
    (``time budget``, ``steps``, ``early stopping``, ``stopped``) and ``history["ended_by"]`` the run.
    """
    import copy

    import torch

    if preset is None:
        preset = dataclass_replace(FAST, frozen_fraction=frozen_fraction, crop_px=crop, lr=lr)
    batch = preset.batch or batch
    crop = preset.crop_px
    frozen_fraction = preset.frozen_fraction
    torch.manual_seed(seed)
    dev = next(net.parameters()).device
    aug = Augmenter(tiles, meta, crop, seed)
    history = {"stage": [], "step": [], "loss": [], "val_loss": [], "seconds": [], "stopped": False,
               "stages": [], "loss_name": preset.loss_name()}
    start = time.perf_counter()
    budget = minutes * 60.0
    point_s = max(1.0, min(15.0, budget / 30.0))
    last_checkpoint = [start]
    total_steps = [0]
    units = encoder_units(net)
    n_top = len(units) if preset.unfrozen_fraction >= 1 else max(1, int(round(preset.unfrozen_fraction * len(units))))
    steps_per_epoch = max(1, math.ceil(len(tiles) / batch))
    patience = preset.patience_epochs
    freeze_bn = preset.freeze_batchnorm and encoder_pretrained
    history.update(encoder_blocks=len(units), unfrozen_blocks=n_top, steps_per_epoch=steps_per_epoch,
                   batchnorm_frozen=freeze_bn,
                   monitor=None if patience is None else ("validation loss" if val is not None and len(val)
                                                           else "training loss"))

    def val_loss_now():
        if val is None or not len(val):
            return None
        value = round(validation_loss(net, val, meta, preset.validation_tiles, preset.positive_weight), 5)
        set_modes()  # predict_tiles put every batch norm back into training mode
        return value

    def point(name, step, smoothed, val_loss="measure"):
        val_loss = val_loss_now() if val_loss == "measure" else val_loss
        record = {"stage": name, "step": step, "loss": round(smoothed, 5), "val_loss": val_loss,
                  "seconds": round(time.perf_counter() - start, 1)}
        for key, value in record.items():
            history[key].append(value)
        log(f"  {name} step {step}: loss {smoothed:.4f}" + ("" if val_loss is None else f", validation {val_loss:.4f}")
            + f" ({record['seconds']:.0f} s)")
        if on_point is not None:
            on_point(record)

    def set_modes():
        net.train()
        if freeze_bn:
            for module in net.encoder.modules():
                if isinstance(module, torch.nn.modules.batchnorm._BatchNorm):
                    module.eval()

    def run_stage(name, params, stage_steps, stage_seconds, lr0, base_fraction, stage_share):
        opt = torch.optim.AdamW(params, lr=lr0, betas=tuple(preset.betas), weight_decay=preset.weight_decay)
        t0 = time.perf_counter()
        last_point = t0
        step, smoothed = 0, None
        epoch, best, best_epoch, best_step, wait, best_state, epoch_losses = 0, math.inf, 0, 0, 0, None, []
        ended_by = "steps" if stage_steps is not None else "time budget"
        set_modes()
        while (step < stage_steps) if stage_steps is not None else (time.perf_counter() - t0 < stage_seconds):
            if should_stop():
                history["stopped"] = True
                ended_by = "stopped"
                break
            if preset.schedule == "cosine":
                frac = (step / stage_steps) if stage_steps else (time.perf_counter() - t0) / stage_seconds
                for group in opt.param_groups:
                    group["lr"] = lr0 * 0.5 * (1.0 + math.cos(math.pi * min(1.0, frac))) + 1e-5
            x, y = aug.batch(batch)
            logits = net(torch.from_numpy(x).to(dev))
            loss = loss_fn(logits, torch.from_numpy(y).to(dev), preset.positive_weight)
            opt.zero_grad()
            loss.backward()
            opt.step()
            step += 1
            total_steps[0] += 1
            smoothed = loss.item() if smoothed is None else 0.98 * smoothed + 0.02 * loss.item()
            now = time.perf_counter()
            if on_step is not None:
                done = (step / stage_steps) if stage_steps else (now - t0) / max(stage_seconds, 1e-9)
                on_step({"stage": name, "step": step, "loss": round(smoothed, 5),
                         "fraction": round(base_fraction + stage_share * min(1.0, done), 4),
                         "tiles_per_s": round(total_steps[0] * batch / max(now - start, 1e-9), 2)})
            if patience is not None:
                epoch_losses.append(loss.item())
                if step % steps_per_epoch == 0:  # an epoch's end: one pass over the training tiles
                    epoch += 1
                    val_loss = val_loss_now()
                    point(name, step, smoothed, val_loss)
                    monitored = float(np.mean(epoch_losses)) if val_loss is None else val_loss
                    epoch_losses = []
                    if monitored < best:
                        best, best_epoch, best_step, wait = monitored, epoch, step, 0
                        if preset.restore_best:
                            best_state = copy.deepcopy(net.state_dict())
                    else:
                        wait += 1
                        if wait >= patience:
                            ended_by = "early stopping"
                            break
            elif step % 50 == 0 or (stage_steps is None and now - last_point >= point_s):
                point(name, step, smoothed)
                last_point = time.perf_counter()
            if checkpoint is not None and time.perf_counter() - last_checkpoint[0] >= checkpoint_every_s:
                checkpoint(name, step)
                last_checkpoint[0] = time.perf_counter()
        restored = best_state is not None and ended_by != "stopped" and best_step != step
        if restored:
            net.load_state_dict(best_state)
            log(f"  {name}: the weights of epoch {best_epoch} (lowest {history['monitor']}) restored")
        if step and (restored or not history["step"] or history["stage"][-1] != name or history["step"][-1] != step):
            point(name, step, smoothed)
        if checkpoint is not None and step:
            checkpoint(name, step)
            last_checkpoint[0] = time.perf_counter()
        history["stages"].append({"stage": name, "steps": step, "epochs": epoch if patience is not None
                                  else round(step / steps_per_epoch, 2), "ended_by": ended_by,
                                  "best_epoch": best_epoch if patience is not None else None,
                                  "best_loss": None if best == math.inf else round(best, 5),
                                  "restored_best": restored, "lr": lr0,
                                  "seconds": round(time.perf_counter() - t0, 1)})
        return step

    for p in net.encoder.parameters():
        p.requires_grad_(False)
    n1 = None if steps is None else max(1, int(steps * frozen_fraction))
    history["frozen_steps"] = run_stage("frozen-encoder", net.decoder_parameters(), n1, budget * frozen_fraction,
                                        preset.lr, 0.0, frozen_fraction)
    # Stage 2: the top n_top encoder blocks learn with the decoder (every block: every parameter).
    for unit in units[len(units) - n_top:]:
        for p in unit.parameters():
            p.requires_grad_(True)
    if n_top == len(units):
        for p in net.encoder.parameters():
            p.requires_grad_(True)
    history["finetune_steps"] = 0
    if not history["stopped"]:
        n2 = None if steps is None else steps - history["frozen_steps"]
        # a stage 1 ended early leaves its unused time to stage 2
        seconds2 = max(budget * (1 - frozen_fraction), budget - (time.perf_counter() - start))
        params = list(net.parameters()) if n_top == len(units) else [p for p in net.parameters() if p.requires_grad]
        history["finetune_steps"] = run_stage("fine-tune", params, n2, seconds2, preset.lr * preset.finetune_lr_factor,
                                              frozen_fraction, 1 - frozen_fraction)
    for p in net.encoder.parameters():
        p.requires_grad_(True)
    history["ended_by"] = history["stages"][-1]["ended_by"] if history["stages"] else None
    history["train_seconds"] = round(time.perf_counter() - start, 1)
    history["batch"] = batch
    history["crop_px"] = crop
    history["tiles_per_s"] = round((history["frozen_steps"] + history["finetune_steps"]) * batch
                                   / max(history["train_seconds"], 1e-9), 2)
    net.eval()
    return history


# ====================================================================================== validation figures
def validation_figures(net, val: TileSet, meta: ModelMetadata, thresholds=THRESHOLDS,
                       match_radius_px: float | None = None) -> dict:
    """Detection figures per threshold on the held-out tiles, peaks found as the detector finds them
    (:func:`~..detect.detector.find_peaks`, the model's blur).

    Targets are the label maxima of at least :data:`CENTRE_MIN_LABEL` (centres); peaks and targets of a tile
    are matched one to one, nearest first, within ``match_radius_px`` (default 2·σ of the labels at the model's
    resolution, at least 3 px; :func:`..scoring.screening.pixel_matches`): a second peak on a target is a false
    one. Per threshold: ``recall`` (targets matched / targets), ``precision`` (peaks matched / peaks), ``f1``,
    ``false_per_tile`` (peaks not matched per tile). Neighbouring frames show the same targets: a diagnostic,
    not a prediction of a flight (:mod:`.ground_validation` is).
    """
    import cv2

    from ..scoring.screening import pixel_matches

    radius = match_radius_px or max(3.0, 2.0 * (meta.label_sigma_px or 1.5))
    pairs = predict_tiles(net, val, meta)
    heat = [1.0 / (1.0 + np.exp(-z)) for z, _ in pairs]
    targets = []
    for _, lab in pairs:
        peak = (lab >= CENTRE_MIN_LABEL) & (lab >= cv2.dilate(lab, np.ones((3, 3), np.uint8)))
        ys, xs = np.nonzero(peak)
        targets.append(np.column_stack([xs, ys]).astype(float))
    n_targets = int(sum(len(t) for t in targets))
    out = {"tiles": len(val), "tiles_with_target": int(val.positive.sum()), "targets": n_targets,
           "match_radius_px": round(radius, 2), "by_threshold": {}}
    target_tile = np.concatenate([np.full(len(tgt), i) for i, tgt in enumerate(targets)] + [np.zeros(0, int)])
    target_uv = np.concatenate(targets + [np.zeros((0, 2))])
    for t in thresholds:
        peaks = [find_peaks(h, t, meta.peak_blur_sigma_px)[0] for h in heat]
        found = int(sum(len(uv) for uv in peaks))
        peak_tile = np.concatenate([np.full(len(uv), i) for i, uv in enumerate(peaks)] + [np.zeros(0, int)])
        matched = pixel_matches(peak_tile, np.concatenate(peaks + [np.zeros((0, 2))]), target_tile, target_uv,
                                radius)
        recall = matched / n_targets if n_targets else None
        precision = matched / found if found else None
        f1 = (2 * recall * precision / (recall + precision)) if recall and precision else 0.0
        out["by_threshold"][f"{t:g}"] = {"recall": _round(recall), "precision": _round(precision),
                                         "f1": round(f1, 4), "detections": found,
                                         "false_per_tile": round((found - matched) / len(val), 4)}
    return out


def best_threshold(figures: dict | None, default: float = 0.5) -> float:
    """The highest threshold whose F1 is within one target's worth (1 / targets) of the best and whose recall
    is the best one's (``default`` without targets there). ``figures``: ``{"targets": n, "by_threshold": {t:
    {"f1": ..., "recall": ...}}}`` — the held-out tiles' (:func:`validation_figures`) or the ground figures of
    the held-out frames (:func:`.ground_validation.ground_figures`, F1 of recall and GMCF, ``targets`` the
    held-out targets in view).

    Held-out data hold a few dozen targets: F1 values closer than one target more or less found are not
    told apart by them, and measured over a run they swing from threshold to threshold (0.59–0.61 from
    0.2 to 0.5 on the loop demo's tiles). Among those, the highest threshold gives the fewest detections,
    so the fewest false clusters to review for the same F1; the best-F1 pick alone chose 0.2 in one run
    and 0.4 in the next, which halved or kept GMCF on the demo's test campaigns. A tie may trade false
    detections, never a target: with 6 held-out targets one target's worth is 0.17 of F1, and a tie that
    gave up one of them (recall 1 → 0.83) chose 0.6 where 0.3–0.5 found all six; on the test campaigns 0.6
    found 28 of 40 targets and 0.5 found 36, as the model before retraining did."""
    if not figures or not figures.get("targets"):
        return default
    rows = figures["by_threshold"]
    best = max(rows, key=lambda t: (rows[t]["f1"], float(t)))
    recall = rows[best].get("recall") or 0.0
    tied = [float(t) for t in rows if rows[t]["f1"] >= rows[best]["f1"] - 1.0 / figures["targets"]
            and (rows[t].get("recall") or 0.0) >= recall - 1e-9]
    return max(tied)


def _round(x):
    return None if x is None else round(x, 4)


# ====================================================================================== checkpoints, export
def save_checkpoint(net, path, backbone: str, width: int, extra: dict | None = None,
                    meta: ModelMetadata | None = None) -> Path:
    """The network's weights with what rebuilds it, written atomically (temporary file, then rename):
    a run killed while writing leaves the previous checkpoint whole.

    Besides the weights: the batch norms whose statistics are frozen (``frozen_stats_batch_norms``, from an ONNX
    INIT, :mod:`.onnx_init`) and, with ``meta``, the input the model was trained on (``resolution_cm``,
    ``standardization_mean``/``_std``, ``input_channel_order``: what INIT takes over) and its ``class_names``."""
    import torch

    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    state = {k: v.detach().cpu() for k, v in net.state_dict().items()}
    record = {"format": CHECKPOINT_FORMAT, "backbone": backbone, "width": width, "state_dict": state,
              "frozen_stats_batch_norms": frozen_batch_norms(net)}
    if meta is not None:
        record.update({"resolution_cm": float(meta.resolution_cm),
                       "standardization_mean": [float(x) for x in meta.standardization_mean],
                       "standardization_std": [float(x) for x in meta.standardization_std],
                       "input_channel_order": meta.input_channel_order, "class_names": list(meta.class_names)})
    torch.save({**record, **(extra or {})}, str(tmp))
    os.replace(tmp, path)
    return path


def _checkpoint_record(path) -> dict | None:
    """A checkpoint of this recipe as saved (None for an ONNX model or a bare state dict)."""
    import torch

    if is_onnx(path):
        return None
    try:
        obj = torch.load(str(path), map_location="cpu", weights_only=True)
    except Exception as exc:  # noqa: BLE001
        raise InputError(f"is not a PyTorch checkpoint ({exc})", source=str(path), field="INIT") from exc
    return obj if isinstance(obj, dict) and obj.get("format") == CHECKPOINT_FORMAT else None


def checkpoint_backbone(path) -> str | None:
    """The backbone a checkpoint of this recipe was trained with (None for a bare state dict)."""
    record = _checkpoint_record(path)
    return None if record is None else record.get("backbone")


def load_init(net, path) -> list[str]:
    """Start from a checkpoint of this recipe (or a bare state dict of the same network), or from a BirdsEye
    ONNX model of the same network (:mod:`.onnx_init`); returns the names of the batch norms whose statistics
    stay frozen: those the ONNX export folded, or those the checkpoint records (it was trained from such a
    model; a checkpoint written before they were recorded names none)."""
    if is_onnx(path):
        return load_onnx_init(net, path)
    record = _checkpoint_record(path)  # read once: the weights and what the checkpoint records beside them
    try:
        net.load_state_dict(record["state_dict"] if record is not None else read_state_dict(path))
    except RuntimeError as exc:
        raise InputError(f"does not fit the chosen network ({str(exc).splitlines()[0]}); train with the "
                         "backbone it was trained with", source=str(path), field="INIT") from exc
    frozen = list((record or {}).get("frozen_stats_batch_norms") or [])
    freeze_batch_norm_stats(net, frozen, source=str(path))
    return frozen


def export_onnx(net, meta: ModelMetadata, path, producer: str = "BirdsEye heatmap recipe") -> Path:
    """The network + a sigmoid (output: probabilities) as ONNX, with ``meta``; written to a temporary name
    and renamed, so no half-written model ever carries the final name.

    The batch is dynamic, the height and width fixed at ``meta.tile_size``: BirdsEye only ever runs tiles of
    that size, and Deepness's dock takes the tile size from the input's shape and refuses a named
    (dynamic) height or width, so a fixed size is what lets the model run there too."""
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

    net = net.to("cpu")
    wrapped = Probabilities(net).eval()  # eval: tracing in train mode would update batch-norm statistics
    buffer = io.BytesIO()
    with warnings.catch_warnings():  # the TorchScript exporter is deprecated but needs no onnxscript
        warnings.simplefilter("ignore")
        torch.onnx.export(wrapped, torch.zeros(1, 3, meta.tile_size, meta.tile_size), buffer,
                          input_names=["image"], output_names=["heatmap"], opset_version=17, dynamo=False,
                          dynamic_axes={"image": {0: "n"}, "heatmap": {0: "n"}})
    model = onnx.load_from_string(buffer.getvalue())
    model.producer_name = producer
    model.graph.name = "birdseye_heatmap"
    embed_metadata(model, meta)
    onnx.checker.check_model(model)
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    onnx.save(model, str(tmp))
    os.replace(tmp, path)
    return path


def make_metadata(tiles: TileSet, resolution_cm: float, threshold: float, label_sigma_px: float | None,
                  description: str, mean_std=None, class_names: tuple = DEFAULT_CLASS_NAMES,
                  channel_order: str = "RGB") -> ModelMetadata:
    """The model's metadata (§4.9); ``mean_std`` None: the tiles' channel statistics in ``channel_order``."""
    mean, std = channel_stats(tiles, channel_order) if mean_std is None else mean_std
    return ModelMetadata(resolution_cm=resolution_cm, tile_size=TILE_SIZE, tiles_overlap_pct=TILES_OVERLAP_PCT,
                         output_kind="probability", default_threshold=threshold, standardization_mean=tuple(mean),
                         standardization_std=tuple(std), class_names=tuple(class_names),
                         input_channel_order=channel_order,
                         training_gsd_cm=round(float(np.median(tiles.source_gsd_cm)), 4),
                         label_sigma_px=label_sigma_px, description=description)


def label_sigma(label_dirs, tiles: TileSet, resolution_cm: float):
    """σ of the soft labels at the model's resolution (from writelabels' summary.json), if known."""
    sigmas = []
    for folder in label_dirs:
        summary = Path(folder) / "summary.json"
        if summary.is_file():
            try:
                sigmas.append(float(json.loads(summary.read_text(encoding="utf-8"))["sigma_px"]))
            except (ValueError, KeyError, TypeError):
                continue
    if not sigmas:
        return None
    scale = float(np.median(tiles.source_gsd_cm)) / resolution_cm
    return round(float(np.median(sigmas)) * scale, 3)

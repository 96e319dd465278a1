"""One training run, from writelabels folders to a model, its checkpoint, model card and loss plot.

:func:`run_job` is what the child process of ``birdseye:traindetector`` runs (:mod:`.child`) and what
``training/train_heatmap.py train`` runs: load the tiles, hold out a share of the frames for
validation, train (:func:`.recipe.train_network`), choose the default threshold on the held-out tiles
(unless given), export the ONNX model and write the model card (:mod:`.report`) and the plot.

Files beside the model ``<name>.onnx``: ``<name>.pt`` (the final weights, a checkpoint ``--init``/INIT
takes), ``<name>.checkpoint.pt`` (the last good checkpoint while training; removed once the model is
written), ``<name>.md`` (model card), ``<name>_loss.png`` (plot), ``<name>.training.json`` (history and
figures). Every file is written under a temporary name and renamed.
"""
from __future__ import annotations

import csv
import json
import os
import platform
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Callable

import numpy as np

from ..errors import InputError
from . import recipe
from .preset import TrainingPreset
from .preset import preset as find_preset


@dataclass
class Source:
    """A writelabels folder and the GSD (cm/px) of its frames: per frame id, or one for all."""

    folder: str
    gsd_cm: dict | None = None
    gsd_default: float | None = None

    def gsd_of(self) -> dict:
        if self.gsd_cm is not None:
            return {str(k): float(v) for k, v in self.gsd_cm.items()}
        if self.gsd_default is None:
            raise InputError("no ground sample distance for the frames of these tiles (give their frame layer "
                             "or one GSD)", source=self.folder, field="FRAMES")
        return {name.rsplit("_", 2)[0]: float(self.gsd_default) for name in recipe.tile_names(self.folder)}


@dataclass
class TrainJob:
    """Everything a training run needs; JSON-able (the parent writes it, the child reads it)."""

    sources: list
    out: str
    backbone: str = "small"
    weights: str | None = None
    init: str | None = None
    minutes: float = 20.0
    steps: int | None = None
    resolution_cm: float | None = None  # None: the INIT model's, else recipe.RESOLUTION_CM
    val_fraction: float = 0.15
    seed: int = 0
    threads: int = 0
    threshold: float | None = None
    width: int = recipe.WIDTH
    batch: int = 16
    description: str = ""
    producer: str = "BirdsEye heatmap recipe"
    extra: dict = field(default_factory=dict)
    #: the training preset's name (:mod:`.preset`); jobs written before presets read as ``fast``
    preset: str = "fast"

    def __post_init__(self):
        self.sources = [s if isinstance(s, Source) else Source(**s) for s in self.sources]

    @classmethod
    def from_json(cls, text: str) -> "TrainJob":
        return cls(**json.loads(text))

    def to_json(self) -> str:
        return json.dumps(asdict(self), indent=1)

    # files beside the model
    @property
    def model_path(self) -> Path:
        return Path(self.out)

    def beside(self, suffix: str) -> Path:
        return self.model_path.with_name(self.model_path.stem + suffix)

    @property
    def checkpoint_path(self) -> Path:
        return self.beside(".checkpoint.pt")

    @property
    def weights_path(self) -> Path:
        return self.beside(".pt")

    @property
    def card_path(self) -> Path:
        return self.beside(".md")

    @property
    def plot_path(self) -> Path:
        return self.beside("_loss.png")

    @property
    def report_path(self) -> Path:
        return self.beside(".training.json")


def data_summary(job: TrainJob, tiles: recipe.TileSet, val: recipe.TileSet | None) -> dict:
    """Folders, tile counts and, where labels.csv has a ``provenance`` column, targets per provenance."""
    folders = []
    for source in job.sources:
        folder = Path(source.folder)
        entry = {"folder": str(folder), "tiles": len(list((folder / "tiles" / "images").glob("*.png")))}
        labels_csv = folder / "labels.csv"
        if labels_csv.is_file():
            with open(labels_csv, newline="", encoding="utf-8") as f:
                rows = list(csv.DictReader(f))
            entry["labels"] = len(rows)
            if rows and "provenance" in rows[0]:
                by = {}
                for r in rows:
                    p = r.get("provenance") or "unknown"
                    by.setdefault(p, {"labels": 0, "targets": set()})
                    by[p]["labels"] += 1
                    by[p]["targets"].add(r.get("geotag_id"))
                entry["provenance"] = {p: {"labels": v["labels"], "targets": len(v["targets"])} for p, v in by.items()}
        summary = folder / "summary.json"
        if summary.is_file():
            try:
                tiles_info = json.loads(summary.read_text(encoding="utf-8")).get("tiles") or {}
                if "hard_negative" in tiles_info:
                    entry["hard_negative_tiles"] = tiles_info["hard_negative"]
            except ValueError:
                pass
        folders.append(entry)
    n_val = 0 if val is None else len(val)
    return {"folders": folders, "tiles": len(tiles) + n_val, "positive_tiles": int(tiles.positive.sum())
            + (0 if val is None else int(val.positive.sum())),
            "negative_tiles": int((~tiles.positive).sum()) + (0 if val is None else int((~val.positive).sum())),
            "training_tiles": len(tiles), "validation_tiles": n_val,
            "validation_positive_tiles": 0 if val is None else int(val.positive.sum()),
            "native_gsd_cm": round(float(np.median(tiles.source_gsd_cm)), 4)}


def run_job(job: TrainJob, emit: Callable[[dict], None] = lambda event: None,
            should_stop: Callable[[], bool] = lambda: False) -> dict:
    """Train, export and document one model; ``emit`` receives the events of :mod:`.protocol`.

    Returns the result event (also emitted). When ``should_stop()`` turns true, training ends at the next
    step, the last checkpoint is written and the result has ``stopped`` set and no model.
    """
    import torch

    from . import report

    t_start = time.perf_counter()
    preset = find_preset(job.preset)
    job = replace(job, backbone=preset.backbone or job.backbone, batch=preset.batch or job.batch)

    def message(text: str) -> None:
        emit({"type": "message", "text": text})

    threads = job.threads or os.cpu_count() or 1
    torch.set_num_threads(threads)
    dev = recipe.device()
    emit({"type": "start", "torch": torch.__version__, "device": str(dev),
          "device_name": torch.cuda.get_device_name(0) if dev.type == "cuda" else platform.processor() or "CPU",
          "threads": threads, "backbone": job.backbone, "pid": os.getpid()})
    emit({"type": "progress", "stage": "loading tiles", "fraction": 0.0})
    init_input = recipe.init_model_input(job.init) if job.init else None  # INIT's resolution and normalisation
    job = replace(job, resolution_cm=recipe.model_resolution(job.resolution_cm, init_input, job.init))
    if job.init and init_input is None:
        message(f"{job.init} records no resolution or normalisation (written before they were recorded): training "
                f"at {job.resolution_cm:g} cm/px, normalised with the tiles' statistics")
    sources = [(s.folder, s.gsd_of()) for s in job.sources]
    if preset.native_resolution:  # the frames' own GSD: the model runs at the training frames' median
        tiles = recipe.load_native_tiles(sources, log=message, is_canceled=should_stop)
        if tiles is not None:
            job = replace(job, resolution_cm=round(float(np.median(tiles.source_gsd_cm)), 4))
    else:
        tiles = recipe.load_tiles(sources, job.resolution_cm, log=message, is_canceled=should_stop)
    if tiles is None:
        return _stopped(job, emit, None)
    train, val = recipe.split_tiles(tiles, job.val_fraction, job.seed)
    data = data_summary(job, train, val)
    emit({"type": "data", **data})
    message(f"{data['tiles']} tiles ({data['positive_tiles']} with a target): {len(train)} for training, "
            f"{data['validation_tiles']} held out for validation")
    sigma = recipe.label_sigma([s.folder for s in job.sources], tiles, job.resolution_cm)
    description = job.description or (f"BirdsEye heatmap model ({job.backbone}) trained on "
                                      + ", ".join(Path(s.folder).name for s in job.sources))
    mean_std = recipe.standardization(job.backbone, train, init_input)
    layout = {"class_names": recipe.label_class_names([s.folder for s in job.sources], log=message),
              "channel_order": init_input.channel_order if init_input else "RGB"}
    meta = recipe.make_metadata(train, job.resolution_cm, 0.5 if job.threshold is None else job.threshold,
                                sigma, description, mean_std, **layout)
    if job.init and job.backbone != (recipe.checkpoint_backbone(job.init) or job.backbone):
        raise InputError(f"was trained with the backbone '{recipe.checkpoint_backbone(job.init)}', not "
                         f"'{job.backbone}'", source=job.init, field="INIT")
    pretrained, encoder_start = _encoder_start(job, preset)
    message(f"preset {preset.name}: {job.backbone}, {encoder_start}")
    net = recipe.build_network(job.backbone, job.width, job.weights, pretrained=pretrained, log=message)
    if job.init:
        frozen = recipe.load_init(net, job.init)
        message(f"fine-tuning from {job.init} at {job.resolution_cm:g} cm/px"
                + (f"; {len(frozen)} batch norms keep their statistics frozen" if frozen else ""))
    net = net.to(dev)
    n_params = int(sum(p.numel() for p in net.parameters()))
    checkpoints = {"n": 0}

    def checkpoint(stage: str, step: int) -> None:
        recipe.save_checkpoint(net, job.checkpoint_path, job.backbone, job.width, {"stage": stage, "step": step},
                               meta=meta)
        checkpoints["n"] += 1
        emit({"type": "checkpoint", "path": str(job.checkpoint_path), "stage": stage, "step": step})

    last = {"t": 0.0}

    def on_step(state: dict) -> None:
        now = time.perf_counter()
        if now - last["t"] >= 0.5:
            last["t"] = now
            emit({"type": "progress", **state, "fraction": round(0.02 + 0.9 * state["fraction"], 4)})

    history = recipe.train_network(net, train, meta, job.minutes, steps=job.steps, batch=job.batch, seed=job.seed,
                                   log=lambda text: None, val=val, should_stop=should_stop, checkpoint=checkpoint,
                                   on_point=lambda record: emit({"type": "point", **record}), on_step=on_step,
                                   preset=preset, encoder_pretrained=pretrained or bool(job.init))
    if history["stopped"]:
        return _stopped(job, emit, history)
    message("; ".join(f"stage {s['stage']}: {s['steps']} steps, ended by {report.ENDED_BY.get(s['ended_by'])}"
                      for s in history["stages"]))
    emit({"type": "progress", "stage": "validating", "fraction": 0.93})
    figures = recipe.validation_figures(net, val, meta) if val is not None and len(val) else None
    threshold = job.threshold if job.threshold is not None else recipe.best_threshold(figures)
    threshold_rule = "given" if job.threshold is not None else (
        "highest threshold within one target of the best F1 on the held-out tiles"
        if figures and figures.get("targets") else "no held-out targets to choose by")
    meta = recipe.make_metadata(train, job.resolution_cm, threshold, sigma, description, mean_std, **layout)
    emit({"type": "progress", "stage": "exporting", "fraction": 0.96})
    model = recipe.export_onnx(net, meta, job.model_path, job.producer)
    recipe.save_checkpoint(net, job.weights_path, job.backbone, job.width,
                           {"stage": "final", "step": history["frozen_steps"] + history["finetune_steps"]}, meta=meta)
    if job.checkpoint_path.exists():
        job.checkpoint_path.unlink()
    result = {
        "type": "result", "stopped": False, "model": str(model), "weights": str(job.weights_path),
        "checkpoint": None, "card": str(job.card_path), "plot": None, "report": str(job.report_path),
        "device": str(dev), "torch": torch.__version__, "threads": threads, "parameters": n_params,
        "threshold": threshold, "threshold_rule": threshold_rule, "data": data, "validation": figures,
        "history": history, "settings": _settings(job, preset, encoder_start),
        "metadata": {k: json.loads(v) for k, v in meta.to_props().items()},
        "seconds": {"train": history["train_seconds"], "total": round(time.perf_counter() - t_start, 1)},
    }
    try:
        report.plot_losses(history, job.plot_path)
        result["plot"] = str(job.plot_path)
    except ImportError as exc:
        message(f"no loss plot: {exc}")
    result["seconds"]["total"] = round(time.perf_counter() - t_start, 1)
    report.write_text_atomic(job.card_path, report.model_card(result))
    report.write_text_atomic(job.report_path, json.dumps({k: v for k, v in result.items() if k != "type"}, indent=1))
    emit(result)
    return result


def _settings(job: TrainJob, preset: TrainingPreset, encoder_start: str) -> dict:
    return {"backbone": job.backbone, "weights": job.weights, "init": job.init, "minutes": job.minutes,
            "steps": job.steps, "resolution_cm": job.resolution_cm, "validation_fraction": job.val_fraction,
            "seed": job.seed, "batch": job.batch, "crop_px": preset.crop_px, "width": job.width,
            "tile_size": recipe.TILE_SIZE, "positive_weight": preset.positive_weight,
            "preset": preset.name, "preset_settings": preset.settings(), "encoder_start": encoder_start,
            "native_resolution": preset.native_resolution}


def _encoder_start(job: TrainJob, preset: TrainingPreset) -> tuple[bool, str]:
    """(load ImageNet weights into the encoder, how the encoder starts — for the log and the model card).

    A preset with ``random_init_without_weights`` trains from random initialisation when no weights file is
    named and torchvision's cache has none; any other run without them stops (:func:`.recipe.build_network`).
    """
    if job.init:
        return False, f"fine-tuned from {job.init}"
    if job.backbone == "small":
        return False, "trained from scratch (random initialisation)"
    if job.weights:
        return True, f"ImageNet weights from {job.weights}"
    cached, _ = recipe.cached_weights_path(job.backbone)
    if cached.is_file():
        return True, f"ImageNet weights from torchvision's cache ({cached})"
    if preset.random_init_without_weights:
        return False, ("random initialisation — NOT ImageNet-pretrained: no weights file was named and "
                       f"torchvision's cache has no {cached.name}")
    return True, "ImageNet weights"  # build_network stops, saying which file goes where


def _stopped(job: TrainJob, emit, history) -> dict:
    kept = job.checkpoint_path if job.checkpoint_path.exists() else None
    result = {"type": "result", "stopped": True, "model": None, "checkpoint": None if kept is None else str(kept),
              "history": history}
    emit(result)
    return result

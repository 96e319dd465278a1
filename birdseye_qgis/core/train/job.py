"""One training run, from writelabels folders to a model, its checkpoint, model card and loss plot.

:func:`run_job` is what the child process of ``birdseye:traindetector`` runs (:mod:`.child`) and what
``training/train_heatmap.py train`` runs: load the tiles, hold out a share of the frames for
validation — frames that share no targets with training (:mod:`.ground_validation`: spatial blocks, whole
flights or none) —, train (:func:`.recipe.train_network`), score the trained network on the held-out frames as
Detect and Evaluate detections score a flight and choose the default threshold from those ground figures (unless
given; on the held-out tiles, with a warning, when the frames' poses are not known), export the ONNX model and
write the model card (:mod:`.report`) and the plot.

Files beside the model ``<name>.onnx``: ``<name>.pt`` (the final weights, a checkpoint ``--init``/INIT
takes), ``<name>.checkpoint.pt`` (the last good checkpoint while training; removed once the model is
written), ``<name>.md`` (model card), ``<name>_loss.png`` (plot), ``<name>.training.json`` (history and
figures). Every file is written under a temporary name and renamed.
"""
from __future__ import annotations

import copy
import csv
import json
import os
import platform
import tempfile
import time
from dataclasses import asdict, dataclass, field, replace
from pathlib import Path
from typing import Callable

import numpy as np

from ..errors import Cancelled, InputError
from ..labels.raster_labels import raster_record
from . import ground_validation, recipe
from .preset import TrainingPreset
from .preset import preset as find_preset


@dataclass
class Source:
    """A writelabels folder and the GSD (cm/px) of its frames: per frame id, or one for all; ``frames``: the
    frame-layer records of its flight (``qgis_io.layers.read_frame_layer``), which the split's footprints and the
    ground validation need (None: a GSD alone, validated on tiles only). A folder written on a raster
    (:mod:`..labels.raster_labels`) carries its raster's GSD, which its tiles take whatever is given here: no frame
    layer describes a raster."""

    folder: str
    gsd_cm: dict | None = None
    gsd_default: float | None = None
    frames: list | None = None

    def gsd_of(self) -> dict:
        raster = raster_record(self.folder)
        if raster is not None:
            return {name.rsplit("_", 2)[0]: float(raster["gsd_cm"]) for name in recipe.tile_names(self.folder)}
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
    #: how frames are held out: "blocks", "flights" or "none" (:data:`.ground_validation.SPLITS`)
    validation: str = "blocks"
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
    ground_validation.require_positive_tiles(tiles.positive, [s.folder for s in job.sources])
    emit({"type": "progress", "stage": "splitting", "fraction": 0.01})
    plan, train, val, flights = split_job(job, tiles)
    warnings = list(plan.warnings)
    for text in plan.warnings:
        warn(emit, text)
    data = data_summary(job, train, val)
    data["dropped_tiles"] = plan.info.get("tiles", {}).get("dropped", 0)
    emit({"type": "data", **data})
    message(f"{data['tiles']} tiles ({data['positive_tiles']} with a target): {len(train)} for training, "
            f"{data['validation_tiles']} held out for validation ({describe_split(plan.info)})")
    sigma = recipe.label_sigma([s.folder for s in job.sources], tiles, job.resolution_cm)
    description = job.description or (f"BirdsEye heatmap model ({job.backbone}) trained on "
                                      + ", ".join(Path(s.folder).name for s in job.sources))
    mean_std = recipe.standardization(job.backbone, train, init_input)
    layout = {"class_names": recipe.label_class_names([s.folder for s in job.sources], log=message),
              "channel_order": init_input.channel_order if init_input else "RGB"}
    meta = recipe.make_metadata(train, job.resolution_cm, 0.5 if job.threshold is None else job.threshold,
                                sigma, description, mean_std, **layout)
    init_backbone = recipe.checkpoint_backbone(job.init) if job.init else None
    if init_backbone is not None and init_backbone != job.backbone:
        raise InputError(f"was trained with the backbone '{init_backbone}', not '{job.backbone}'", source=job.init,
                         field="INIT")
    pretrained, encoder_start = _encoder_start(job, preset)
    message(f"preset {preset.name}: {job.backbone}, {encoder_start}")
    net = recipe.build_network(job.backbone, job.width, job.weights, pretrained=pretrained, log=message)
    if job.init:
        frozen = recipe.load_init(net, job.init)
        message(f"fine-tuning from {job.init} at {job.resolution_cm:g} cm/px"
                + (f"; {len(frozen)} batch norms keep their statistics frozen" if frozen else ""))
    net = net.to(dev)
    n_params = int(sum(p.numel() for p in net.parameters()))
    start_ground = start_state = None
    if job.init and flights:  # the model it starts from, on the same held-out ground: what fine-tuning must keep
        emit({"type": "progress", "stage": "scoring the starting model on the ground", "fraction": 0.01})
        try:
            start_ground = score_on_ground(net, meta, job.producer, flights, should_stop, emit, 0.01, 0.01)
            start_state = copy.deepcopy(net.state_dict())
        except Cancelled:
            return _stopped(job, emit, None)
        except InputError:  # said once, after training, when the fine-tuned model cannot be scored either
            start_ground = None
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
    ground = None
    if flights:
        emit({"type": "progress", "stage": "validating on the ground", "fraction": 0.935})
        try:
            ground = score_on_ground(net, meta, job.producer, flights, should_stop, emit)
        except Cancelled:
            return _stopped(job, emit, history)
        except InputError as exc:  # no onnxruntime in the training Python, an image gone: say so, go on
            text = f"the held-out frames could not be scored on the ground ({exc})"
            warnings.append(text)
            warn(emit, text)
    text = start_kept_reason(job, ground, start_ground)
    start_kept = text is not None
    if start_kept:
        net.load_state_dict(start_state)
        ground = start_ground
        figures = recipe.validation_figures(net, val, meta) if figures is not None else None
        warnings.append(text)
        warn(emit, text)
    threshold, threshold_rule, validated_on = choose_threshold(job, plan, figures, ground)
    text = threshold_warning(job, plan, figures, ground, flights, validated_on)
    if text:
        warnings.append(text)
        warn(emit, text)
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
        "threshold": threshold, "threshold_rule": threshold_rule, "validated_on": validated_on,
        "split": plan.info, "ground_validation": ground, "starting_model_kept": start_kept,
        "starting_model_ground": start_ground, "warnings": warnings, "data": data, "validation": figures,
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
            "steps": job.steps, "resolution_cm": job.resolution_cm, "validation": job.validation,
            "validation_fraction": job.val_fraction,
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


def warn(emit, text: str) -> None:
    """A warning for the log (the parent shows it as one) and the model card."""
    emit({"type": "message", "level": "warning", "text": "Warning: " + text})


def split_job(job: TrainJob, tiles: recipe.TileSet):
    """(plan, training tiles, validation tiles or None, the :class:`.ground_validation.GroundFlight` of each
    folder with held-out frames whose records were given) — :func:`.ground_validation.plan_split` on the job's
    folders; folders without targets.csv fall back to :func:`.recipe.split_tiles`."""
    folders = [s.folder for s in job.sources]
    keys = [key.split(":", 1) for key in (tiles.frame_key or [])]
    with_tiles = [sorted({fid for j, fid in keys if j == str(k)}) for k in range(len(folders))]
    views, _, targets = ground_validation.folder_views(folders, [s.frames for s in job.sources], with_tiles)
    plan = ground_validation.plan_split(views, job.validation, job.val_fraction, job.seed)
    if plan.method == "frames":
        train, val = recipe.split_tiles(tiles, job.val_fraction, job.seed)
        plan.info.update({"held_out": val is not None, "tiles": {"train": len(train),
                                                                 "val": 0 if val is None else len(val)}})
        return plan, train, val, []
    sides = [plan.side.get((int(j), fid), ground_validation.TRAIN) for j, fid in keys]
    train_i = [i for i, side in enumerate(sides) if side == ground_validation.TRAIN]
    val_i = [i for i, side in enumerate(sides) if side == ground_validation.VAL]
    if val_i and not tiles.positive[train_i].any():
        plan = ground_validation.nothing_held({key: ground_validation.TRAIN for key in plan.side}, plan.method,
                                               f"the {plan.method} split left no tile with a target for training")
        train_i, val_i, sides = list(range(len(tiles))), [], [ground_validation.TRAIN] * len(tiles)
    train, val = tiles.subset(train_i), (tiles.subset(val_i) if val_i else None)
    plan.info["tiles"] = {"train": len(train_i), "val": len(val_i),
                          "dropped": sum(side == ground_validation.DROPPED for side in sides),
                          "train_positive": int(train.positive.sum()),
                          "val_positive": 0 if val is None else int(val.positive.sum())}
    flights = []
    for k, source in enumerate(job.sources):
        held_frames = set(plan.ground_frames(k))
        if not held_frames or not source.frames or targets[k] is None or raster_record(source.folder) is not None:
            continue  # a raster's tiles are no frames of a flight: nothing to detect on as Detect does
        records = [r for r in source.frames if str(r.get("frame_id")) in held_frames]
        held = np.isin(np.array([str(i) for i in targets[k].ids], dtype=object),
                       sorted(plan.held_targets.get(k, ())))
        if records:
            flights.append(ground_validation.GroundFlight(Path(source.folder).name, records, targets[k], held))
    return plan, train, val, flights


def score_on_ground(net, meta, producer: str, flights, should_stop, emit, start: float = 0.935,
                    span: float = 0.02) -> dict:
    """:func:`.ground_validation.ground_figures` of the network exported as the model will be (a temporary
    ONNX file through :func:`.recipe.export_onnx`), its progress reported from ``start`` over ``span`` of the
    job. A training Python without what Detect needs raises :class:`InputError` saying what to install."""
    import importlib.util

    missing = [name for name in ("onnxruntime", "scipy") if importlib.util.find_spec(name) is None]
    if missing:
        raise InputError(f"the training Python has no {' and no '.join(missing)}, which running the detector "
                         f"needs: install {' '.join(missing)} into it")
    with tempfile.TemporaryDirectory(prefix="birdseye-validation-") as scratch:
        model = recipe.export_onnx(net, meta, Path(scratch) / "validation.onnx", producer)
        return ground_validation.ground_figures(
            model, flights, is_canceled=should_stop,
            progress=lambda f: emit({"type": "progress", "stage": "validating on the ground",
                                     "fraction": round(start + span * f, 4)}))


def best_ground_f1(ground: dict | None) -> float | None:
    """The best F1 of recall and GMCF over the thresholds of ground figures; None without held-out targets."""
    if not ground or not ground.get("targets"):
        return None
    return max(row["f1"] for row in ground["by_threshold"].values())


def start_kept_reason(job: TrainJob, ground: dict | None, start_ground: dict | None) -> str | None:
    """Why the weights INIT started from are kept instead of the fine-tuned ones, or None to keep the
    fine-tuned ones. Both models are scored on the same held-out frames against the same targets; the
    fine-tuned model is kept unless its best F1 there is lower (a tie keeps it). So a round of the review loop
    never hands on a model that finds fewer of the held-out targets, or buries them in more false clusters,
    than the one before — provided the starting model never trained on these frames (its own model card lists
    the folders it trained on)."""
    new, old = best_ground_f1(ground), best_ground_f1(start_ground)
    if new is None or old is None or new >= old:
        return None
    return (f"the fine-tuned model's best F1 on the held-out ground ({new:.3f}) is below that of the model it "
            f"started from ({old:.3f}, {job.init}): the starting weights are kept, with their ground figures and "
            "threshold. Fine-tuning did not pay on these held-out frames; review more clusters (hard negatives, "
            "confirmed targets) before the next round. If the starting model was trained on these frames, its "
            "figures flatter it: hold out other flights, or train without INIT.")


#: The threshold rule: the same tie rule (:func:`.recipe.best_threshold`) on whichever figures were measured.
GROUND_RULE = ("highest threshold within one target of the best F1 of recall and GMCF, losing no target, scored on "
               "the ground over the held-out frames ({split})")
TILE_RULE = ("highest threshold within one target of the best F1, losing no target, on the held-out tiles (not "
             "validated on the ground)")


def choose_threshold(job: TrainJob, plan, figures: dict | None, ground: dict | None) -> tuple[float, str, str | None]:
    """(threshold, the rule that chose it, what it was validated on: "ground", "tiles" or None)."""
    if job.threshold is not None:
        return job.threshold, "given", None
    if _informative(ground):
        return (recipe.best_threshold(ground), GROUND_RULE.format(split=describe_split(plan.info)), "ground")
    if _informative(figures):
        return recipe.best_threshold(figures), TILE_RULE, "tiles"
    return 0.5, "not validated on held-out data: 0.5 (the warnings say why)", None


def _informative(figures: dict | None) -> bool:
    """Whether figures can choose a threshold: held-out targets, and one found at some threshold (F1 > 0)."""
    return bool(figures and figures.get("targets") and max(r["f1"] for r in figures["by_threshold"].values()) > 0)


def threshold_warning(job: TrainJob, plan, figures, ground, flights, validated_on) -> str | None:
    """What the log and the card say of the default threshold, if anything: not validated on the ground (when
    something was held out: else the split's warning says it), or validated on few held-out targets."""
    if validated_on == "ground" and ground["targets"] < ground_validation.FEW_HELD_OUT_TARGETS:
        return few_targets_warning(ground["targets"], plan)
    if validated_on != "ground" and job.threshold is None and plan.held_out:
        return not_validated_warning(plan, figures, ground, flights)
    return None


def few_targets_warning(targets: int, plan) -> str:
    """The ground figures rest on few held-out targets: how far one target moves them, and what gives more."""
    more = ("a larger VALIDATION_FRACTION, or whole flights (VALIDATION flights) when there are several"
            if plan.method == "blocks" else "a larger VALIDATION_FRACTION, or more flights")
    return (f"the default threshold rests on {targets} held-out target(s) in view: one target more or less found "
            f"moves their recall by {1 / targets:.2f}, so the validation figures and the threshold are rough. "
            f"For firmer figures hold out more targets ({more}), or score the model on a flight it never saw "
            "with Evaluate detections.")


def not_validated_warning(plan, figures, ground, flights) -> str:
    """Why the default threshold was not validated on the ground."""
    if not plan.held_out:
        why = "nothing was held out"
    elif plan.method == "frames":
        why = "the labels folders have no targets.csv to score the held-out frames against"
    elif ground is not None and ground.get("targets"):
        why = ("the model recovered no held-out target at any threshold (train longer, or on more labels, and look "
               "at the loss plot)")
    elif ground is not None:
        why = "no held-out target was in view of the held-out frames the detector could read"
    elif not flights:
        why = "the frames' poses are not known (no frame layer given, only a GSD)"
    else:
        why = "the held-out frames could not be scored on the ground"
    return (f"the default threshold was not validated on the ground: {why}; "
            + ("it was chosen on the held-out tiles, whose figures are optimistic."
               if _informative(figures) else "it is 0.5.")
            + " Score the model on a flight it never saw with Evaluate detections before relying on it.")


def describe_split(info: dict) -> str:
    """The split in a few words, for the log and the threshold rule."""
    method = info.get("method")
    if not info.get("held_out"):
        return f"nothing held out ({info.get('reason', method)})"
    if method == "blocks":
        return (f"{info['held_out_blocks']} of {info['blocks']} spatial blocks of {info['block_m']:g} m held out, "
                f"{info['frames_dropped']} frames seeing both sides kept out of the tiles, scored on the ground")
    if method == "flights":
        return "flights held out: " + ", ".join(info["held_out_folders"])
    return "frames held out at random"


def _stopped(job: TrainJob, emit, history) -> dict:
    kept = job.checkpoint_path if job.checkpoint_path.exists() else None
    result = {"type": "result", "stopped": True, "model": None, "checkpoint": None if kept is None else str(kept),
              "history": history}
    emit(result)
    return result

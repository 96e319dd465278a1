"""The model card (Markdown) and the loss plot (PNG) of a training run, from its result event
(:func:`.job.run_job`). matplotlib is imported inside :func:`plot_losses` (its Agg canvas, no pyplot)."""
from __future__ import annotations

import os
from pathlib import Path


def write_text_atomic(path, text: str) -> Path:
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    tmp.write_text(text, encoding="utf-8")
    os.replace(tmp, path)
    return path


def plot_losses(history: dict, path) -> Path:
    """Training loss (smoothed) and validation loss against training time, the stage change marked."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7.0, 4.0), dpi=100)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    seconds = history.get("seconds") or []
    ax.plot(seconds, history.get("loss") or [], "o-", ms=3, label="training loss (smoothed)")
    val = [(s, v) for s, v in zip(seconds, history.get("val_loss") or []) if v is not None]
    if val:
        ax.plot([s for s, _ in val], [v for _, v in val], "s-", ms=3, label="validation loss (held-out tiles)")
    stages = history.get("stage") or []
    change = next((seconds[i] for i in range(1, len(stages)) if stages[i] != stages[i - 1]), None)
    if change is not None:
        ax.axvline(change, color="0.6", ls="--", lw=1)
        top, blocks = history.get("unfrozen_blocks"), history.get("encoder_blocks")
        text = f"top {top}/{blocks} encoder blocks unfrozen" if top and blocks and top < blocks else "encoder unfrozen"
        ax.annotate(text, (change, 0.5), xycoords=("data", "axes fraction"), xytext=(-3, 0),
                    textcoords="offset points", rotation=90, ha="right", va="center", fontsize=8, color="0.4")
    ax.set_xlabel("training time (s)")
    ax.set_ylabel(history.get("loss_name") or "weighted binary cross-entropy")
    ax.set_title("Train detector: loss curves")
    ax.grid(True, alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    path = Path(path)
    tmp = path.with_name(f".{path.name}.{os.getpid()}.tmp.png")
    fig.savefig(str(tmp), format="png")
    os.replace(tmp, path)
    return path


def _fmt(x, digits=3) -> str:
    return "–" if x is None else (f"{x:.{digits}f}" if isinstance(x, float) else str(x))


def model_card(result: dict) -> str:
    """The model card: data, settings, time and device, validation figures per threshold, files."""
    data, settings, history = result["data"], result["settings"], result["history"]
    model = Path(result["model"]).name
    lines = [f"# Model card: {model}", "",
             result["metadata"].get("description", ""), "",
             "## Data", "",
             f"- Tiles: {data['tiles']} ({data['positive_tiles']} with a target, {data['negative_tiles']} without), "
             f"native ground sample distance {data['native_gsd_cm']} cm/px (median), "
             + ("kept at each frame's own ground sample distance (not resampled); the model runs at the median, "
                f"{settings['resolution_cm']:g} cm/px." if settings.get("native_resolution")
                else f"resampled to {settings['resolution_cm']:g} cm/px."),
             f"- Training: {data['training_tiles']} tiles; validation: {data['validation_tiles']} tiles "
             f"({data['validation_positive_tiles']} with a target).", ""]
    lines += ["| labels folder | tiles | labels | targets by provenance | hard-negative tiles |",
              "| --- | ---: | ---: | --- | ---: |"]
    for f in data["folders"]:
        prov = "; ".join(f"{p}: {v['targets']} targets, {v['labels']} labels"
                         for p, v in sorted((f.get("provenance") or {}).items())) or "–"
        lines.append(f"| `{f['folder']}` | {f['tiles']} | {f.get('labels', '–')} | {prov} | "
                     f"{f.get('hard_negative_tiles', '–')} |")
    lines += ["", "## Settings", ""] + _preset_lines(settings)
    lines += [f"- Network: `{settings['backbone']}` ({result['parameters']:,} parameters)"
              + (f"; encoder: {settings['encoder_start']}" if settings.get("encoder_start") else
                 (f", ImageNet weights from `{settings['weights']}`" if settings.get("weights") else "")
                 + (f", fine-tuned from `{settings['init']}`" if settings.get("init") else "")) + ".",
              f"- Budget: {settings['minutes']:g} min"
              + (f" ({settings['steps']} steps)" if settings.get("steps") else "")
              + f"; batch {settings['batch']} crops of {settings['crop_px']} px; seed {settings['seed']}; "
              + (f"positive weight {settings['positive_weight']:g}." if settings['positive_weight'] else
                 "plain binary cross-entropy (no positive weight)."),
              f"- Model tiles {settings['tile_size']} px at {settings['resolution_cm']:g} cm/px; default threshold "
              f"{result['threshold']:g} ({result['threshold_rule']}).", "",
              "## Training", "",
              f"- Device: {result['device']} (torch {result['torch']}, {result['threads']} threads).",
              f"- Time: {result['seconds']['train']:.1f} s training, {result['seconds']['total']:.1f} s in all; "
              f"{history['frozen_steps']} steps with the encoder frozen, {history['finetune_steps']} fine-tuning; "
              f"{history['tiles_per_s']:.1f} tiles/s.", *_stage_lines(history),
              f"- Final loss: training {_fmt(history['loss'][-1] if history['loss'] else None, 4)}, validation "
              f"{_fmt(history['val_loss'][-1] if history['val_loss'] else None, 4)}.", ""]
    lines += split_section(result) + ground_section(result)
    figures = result.get("validation")
    lines += ["## Validation (held-out tiles, a diagnostic)", ""]
    if not figures:
        lines += ["No tiles were held out.", ""]
    else:
        lines += [f"{figures['tiles']} tiles, {figures['targets']} target centres; peaks and centres matched one to "
                  f"one within {figures['match_radius_px']:g} px. Tiles are scored alone, not as Detect runs a "
                  "flight: these figures do not predict one.",
                  "", "| threshold | recall | precision | F1 | detections | false per tile |",
                  "| ---: | ---: | ---: | ---: | ---: | ---: |"]
        for t, row in figures["by_threshold"].items():
            mark = " **(default)**" if abs(float(t) - result["threshold"]) < 1e-9 else ""
            lines.append(f"| {t}{mark} | {_fmt(row['recall'])} | {_fmt(row['precision'])} | {row['f1']:.3f} | "
                         f"{row['detections']} | {row['false_per_tile']:.3f} |")
        lines.append("")
    lines += ["## Files", "", f"- `{model}`: the ONNX model with BirdsEye/Deepness metadata (Detect targets runs it).",
              f"- `{Path(result['weights']).name}`: the weights, to fine-tune from (INIT).",
              f"- `{Path(result['report']).name}`: the loss history and every figure above."]
    if result.get("plot"):
        plot = Path(result["plot"]).name
        lines += [f"- `{plot}`: the loss curves.", "", f"![loss curves]({plot})"]
    return "\n".join(lines) + "\n"


def _preset_lines(settings: dict) -> list[str]:
    """The preset and what it fixed (runs written before presets: nothing)."""
    p = settings.get("preset_settings")
    if not p:
        return []
    stage2 = ("every layer" if p["unfrozen_fraction"] >= 1
              else f"the top {p['unfrozen_fraction']:.0%} of the encoder's blocks unfrozen")
    stopping = "each stage runs its share of the budget"
    if p["patience_epochs"]:
        stopping = (f"each stage ends after {p['patience_epochs']} epochs (passes over the training tiles) without a "
                    "lower validation loss" + (", back on its best epoch's weights" if p["restore_best"] else "")
                    + ", or at its share of the budget")
    lines = [f"- Preset: **{p['title']}** (`{p['name']}`): stage 1 with the encoder frozen "
             f"({p['frozen_fraction']:.0%} of the budget), stage 2 with {stage2}; {p['optimizer']} at "
             f"{p['lr']:g}" + ("" if p["finetune_lr_factor"] == 1 else f" (stage 2: ×{p['finetune_lr_factor']:.3g})")
             + f", β {p['betas'][0]:g}/{p['betas'][1]:g}, weight decay {p['weight_decay']:g}, {p['schedule']} rate; "
             f"loss: {p['loss']}; {stopping}."]
    if p["name"] == "method" and p["backbone"] == "efficientnet_v2_s":
        lines.append("- The method's encoder is EfficientNetV2-B3; torchvision offers EfficientNetV2 from S up, so "
                     "this preset trains `efficientnet_v2_s`, the nearest, cut after its stride-16 stage.")
    return lines


#: What ended a training stage (``history["stages"][i]["ended_by"]``), in words.
ENDED_BY = {"steps": "its number of steps", "time budget": "the time budget",
             "early stopping": "early stopping (the preset's patience ran out without a lower loss)",
             "stopped": "a cancel"}


def _stage_lines(history: dict) -> list[str]:
    """What ended each stage and the run (runs written before presets: nothing)."""
    stages = history.get("stages")
    if not stages:
        return []
    lines = []
    for s in stages:
        best = (f"; best epoch {s['best_epoch']} ({history.get('monitor')} {_fmt(s['best_loss'], 4)})"
                + (", its weights restored" if s.get("restored_best") else "")) if s.get("best_epoch") else ""
        lines.append(f"- Stage `{s['stage']}`: {s['steps']} steps, epochs {s['epochs']}, ended by "
                     f"{ENDED_BY.get(s['ended_by'], s['ended_by'])}{best}.")
    lines.append(f"- The run was ended by {ENDED_BY.get(history.get('ended_by'), history.get('ended_by'))}.")
    return lines


def split_section(result: dict) -> list[str]:
    """How the frames were held out (:mod:`.ground_validation`), the counts on each side and the warnings."""
    split = result.get("split") or {}
    method = split.get("method")
    lines = ["## Validation split", ""]
    if not split.get("held_out"):
        lines.append(f"- Nothing held out ({split.get('reason', 'no split')}).")
    elif method == "blocks":
        lines.append(f"- Spatial blocks: the targets grouped into {split['blocks']} ground blocks of "
                     f"{split['block_m']:g} m; {split['held_out_blocks']} held out. Frames seeing only held-out "
                     "targets validate, frames seeing only training targets train, frames seeing both have no tile on "
                     "either side but are scored on the ground with the held-out frames.")
    elif method == "flights":
        lines.append("- Whole flights held out: " + ", ".join(f"`{n}`" for n in split["held_out_folders"]) + ".")
    else:
        lines.append("- Frames held out at random (the labels folders have no targets.csv): neighbouring frames show "
                     "the same targets.")
    if split.get("held_out") and method in ("blocks", "flights"):
        t, f = split["targets"], split["frames"]
        lines.append(f"- Targets: {t['train']} training, {t['val']} held out; frames: {f['train']} training, "
                     f"{f['val']} held out, {split['frames_dropped']} dropped (they see both sides).")
    tiles = split.get("tiles")
    if tiles and split.get("held_out"):
        lines.append(f"- Tiles: {tiles['train']} training, {tiles['val']} held out"
                     + (f", {tiles['dropped']} dropped" if tiles.get("dropped") else "") + ".")
    for text in result.get("warnings") or []:
        lines.append(f"- **Warning:** {text}")
    return lines + [""]


def ground_section(result: dict) -> list[str]:
    """The ground figures of the held-out frames (:func:`.ground_validation.ground_figures`)."""
    ground = result.get("ground_validation")
    lines = ["## Validation on the ground (held-out frames, as Detect and Evaluate detections score a flight)", ""]
    if not ground:
        note = ("the default threshold was chosen on the held-out tiles" if result.get("validated_on") == "tiles"
                else "the default threshold was not validated")
        return lines + [f"Not measured: {note}.", ""]
    lines += [f"{ground['frames']} frames that see held-out targets run whole through the detector "
              f"({ground['frames_skipped']} skipped), detections clustered and scored against {ground['targets']} "
              "held-out geotags in view, as Evaluate detections scores a flight against its survey. Recall: held-out "
              "geotags recovered; GMCF: clusters on a held-out geotag among the clusters not on a training target "
              "(a cluster on a target only a review confirmed is no geotag match, as on a flight whose survey "
              "missed it); F1: their harmonic mean.", "",
              "| threshold | recall | GMCF | F1 | clusters | of them on review targets | detections |",
              "| ---: | ---: | ---: | ---: | ---: | ---: | ---: |"]
    for t, row in ground["by_threshold"].items():
        mark = " **(default)**" if abs(float(t) - result["threshold"]) < 1e-9 else ""
        lines.append(f"| {t}{mark} | {_fmt(row['recall'])} | {_fmt(row['gmcf'])} | {row['f1']:.3f} | "
                     f"{row['clusters']} | {row.get('clusters_on_review_targets', '–')} | {row['detections']} |")
    return lines + [""]

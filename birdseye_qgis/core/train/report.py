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
        ax.annotate("encoder unfrozen", (change, 1.0), xycoords=("data", "axes fraction"), ha="left", va="top",
                    fontsize=8, color="0.4")
    ax.set_xlabel("training time (s)")
    ax.set_ylabel("weighted binary cross-entropy")
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
             f"native ground sample distance {data['native_gsd_cm']} cm/px (median), resampled to "
             f"{settings['resolution_cm']:g} cm/px.",
             f"- Training: {data['training_tiles']} tiles; validation: {data['validation_tiles']} tiles "
             f"({data['validation_positive_tiles']} with a target) — {settings['validation_fraction']:.0%} of the "
             "frames held out with all their tiles.", ""]
    lines += ["| labels folder | tiles | labels | targets by provenance | hard-negative tiles |",
              "| --- | ---: | ---: | --- | ---: |"]
    for f in data["folders"]:
        prov = "; ".join(f"{p}: {v['targets']} targets, {v['labels']} labels"
                         for p, v in sorted((f.get("provenance") or {}).items())) or "–"
        lines.append(f"| `{f['folder']}` | {f['tiles']} | {f.get('labels', '–')} | {prov} | "
                     f"{f.get('hard_negative_tiles', '–')} |")
    lines += ["", "## Settings", "",
              f"- Network: `{settings['backbone']}` ({result['parameters']:,} parameters)"
              + (f", ImageNet weights from `{settings['weights']}`" if settings.get("weights") else "")
              + (f", fine-tuned from `{settings['init']}`" if settings.get("init") else "") + ".",
              f"- Budget: {settings['minutes']:g} min"
              + (f" ({settings['steps']} steps)" if settings.get("steps") else "")
              + f"; batch {settings['batch']} crops of {settings['crop_px']} px; seed {settings['seed']}; "
              f"positive weight {settings['positive_weight']:g}.",
              f"- Model tiles {settings['tile_size']} px at {settings['resolution_cm']:g} cm/px; default threshold "
              f"{result['threshold']:g} ({result['threshold_rule']}).", "",
              "## Training", "",
              f"- Device: {result['device']} (torch {result['torch']}, {result['threads']} threads).",
              f"- Time: {result['seconds']['train']:.1f} s training, {result['seconds']['total']:.1f} s in all; "
              f"{history['frozen_steps']} steps with the encoder frozen, {history['finetune_steps']} fine-tuning; "
              f"{history['tiles_per_s']:.1f} tiles/s.",
              f"- Final loss: training {_fmt(history['loss'][-1] if history['loss'] else None, 4)}, validation "
              f"{_fmt(history['val_loss'][-1] if history['val_loss'] else None, 4)}.", ""]
    figures = result.get("validation")
    lines += ["## Validation (held-out tiles)", ""]
    if not figures:
        lines += ["No tiles were held out (validation fraction 0 or too few frames).", ""]
    else:
        lines += [f"{figures['tiles']} tiles, {figures['targets']} target centres; a peak within "
                  f"{figures['match_radius_px']:g} px of a centre detects it. Neighbouring frames overlap, so these "
                  "tile figures are optimistic: score the model on a flight it never saw with Evaluate detections.",
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

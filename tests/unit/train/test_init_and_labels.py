"""What INIT carries over and what the labels decide (issue 30 item 2), with torch: the INIT model's
resolution and normalisation (or a clear refusal), the batch norms an ONNX INIT froze staying frozen through
a .pt, class names from labels.csv, and positive tiles from labels.csv's rows rather than the raster's peak."""
from __future__ import annotations

import csv
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

from birdseye.birdseye_qgis.core.detect.model_metadata import read_onnx_metadata
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.train import recipe
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job
from birdseye.birdseye_qgis.core.train.onnx_init import frozen_batch_norms, frozen_stats_batch_norm

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fake_labels import make_label_folder  # noqa: E402


def short_job(folder, out, **kw) -> dict:
    job = TrainJob(sources=[Source(str(folder), gsd_default=1.0)], out=str(out), steps=2, batch=4, val_fraction=0.0,
                   threads=2, **kw)
    return run_job(job)


def load_checkpoint(path) -> dict:
    return torch.load(str(path), map_location="cpu", weights_only=True)


def test_init_keeps_the_models_input_and_its_frozen_batch_norms(tmp_path):
    """ONNX model A (1.25 cm/px, normalised with its own tiles) → fine-tuned B from A.onnx → C from B.pt."""
    first = make_label_folder(tmp_path / "first", n_frames=3, seed=0)
    second = make_label_folder(tmp_path / "second", n_frames=3, seed=7, class_name="nest")
    a = short_job(first, tmp_path / "a.onnx", resolution_cm=1.25)
    meta_a = read_onnx_metadata(a["model"])
    assert meta_a.resolution_cm == 1.25 and meta_a.class_names == ("burrow",)
    assert load_checkpoint(a["weights"])["frozen_stats_batch_norms"] == [], "trained from scratch: none frozen"

    # B from the ONNX model, on other tiles: A's resolution and normalisation, the new labels' class.
    b = short_job(second, tmp_path / "b.onnx", init=a["model"])
    meta_b = read_onnx_metadata(b["model"])
    tiles_b = recipe.load_tiles([(str(second), Source(str(second), gsd_default=1.0).gsd_of())], 1.25)
    assert recipe.channel_stats(tiles_b)[0] != meta_a.standardization_mean, "the test needs tiles that differ"
    assert (meta_b.resolution_cm, meta_b.standardization_mean, meta_b.standardization_std) == (
        1.25, meta_a.standardization_mean, meta_a.standardization_std)
    assert meta_b.input_channel_order == meta_a.input_channel_order and meta_b.class_names == ("nest",)

    # The batch norms the ONNX export folded are named in B.pt, their statistics untouched by training.
    net = recipe.build_network("small")
    folded = recipe.load_init(net, a["model"])
    record_b = load_checkpoint(b["weights"])
    assert folded and record_b["frozen_stats_batch_norms"] == folded
    assert record_b["resolution_cm"] == 1.25 and record_b["standardization_mean"] == list(meta_a.standardization_mean)
    for name in folded:
        assert torch.equal(record_b["state_dict"][name + ".running_mean"], torch.zeros_like(
            record_b["state_dict"][name + ".running_mean"]))
        assert torch.allclose(record_b["state_dict"][name + ".running_var"], torch.full_like(
            record_b["state_dict"][name + ".running_var"], 1.0 - 1e-5))

    # From B.pt: the same batch norms frozen again (the others not), and the same input.
    fresh = recipe.build_network("small")
    assert recipe.load_init(fresh, b["weights"]) == folded and frozen_batch_norms(fresh) == folded
    plain = [n for n, m in fresh.named_modules() if isinstance(m, torch.nn.BatchNorm2d) and n not in folded]
    assert plain and not any(isinstance(dict(fresh.named_modules())[n], frozen_stats_batch_norm()) for n in plain)
    assert recipe.init_model_input(b["weights"]) == recipe.ModelInput.of(meta_b)
    c = short_job(first, tmp_path / "c.onnx", init=b["weights"])
    record_c = load_checkpoint(c["weights"])
    assert record_c["frozen_stats_batch_norms"] == folded
    for name in folded:
        for buffer in ("running_mean", "running_var"):
            assert torch.equal(record_c["state_dict"][f"{name}.{buffer}"], record_b["state_dict"][f"{name}.{buffer}"])
    meta_c = read_onnx_metadata(c["model"])
    assert (meta_c.resolution_cm, meta_c.standardization_mean) == (1.25, meta_a.standardization_mean)

    # Asking for another resolution than the INIT model's is refused, naming both.
    with pytest.raises(InputError, match=r"a\.onnx.*INIT.*trained at 1\.25 cm/px.*asked for is 1 cm/px"):
        short_job(first, tmp_path / "d.onnx", init=a["model"], resolution_cm=1.0)
    with pytest.raises(InputError, match=r"b\.pt.*trained at 1\.25 cm/px.*asked for is 2 cm/px"):
        short_job(first, tmp_path / "d.onnx", init=b["weights"], resolution_cm=2.0)
    assert short_job(first, tmp_path / "e.onnx", init=b["weights"], resolution_cm=1.25)["model"]


def test_a_checkpoint_written_before_the_records_still_serves(tmp_path):
    net = recipe.build_network("small")
    old = tmp_path / "old.pt"
    torch.save({"format": recipe.CHECKPOINT_FORMAT, "backbone": "small", "width": recipe.WIDTH,
                "state_dict": net.state_dict()}, old)
    assert recipe.init_model_input(old) is None and recipe.checkpoint_backbone(old) == "small"
    fresh = recipe.build_network("small")
    assert recipe.load_init(fresh, old) == [] and frozen_batch_norms(fresh) == []
    assert recipe.model_resolution(None, None) == recipe.RESOLUTION_CM
    assert recipe.model_resolution(0.7, None) == 0.7
    bare = tmp_path / "bare.pt"
    torch.save(net.state_dict(), bare)
    assert recipe.init_model_input(bare) is None and recipe.load_init(recipe.build_network("small"), bare) == []


def test_a_checkpoint_naming_a_batch_norm_the_network_lacks_is_refused(tmp_path):
    net = recipe.build_network("small")
    path = recipe.save_checkpoint(net, tmp_path / "c.pt", "small", recipe.WIDTH)
    record = load_checkpoint(path)
    record["frozen_stats_batch_norms"] = ["head"]
    torch.save(record, path)
    with pytest.raises(InputError, match="names head as a batch norm"):
        recipe.load_init(recipe.build_network("small"), path)


def rewrite_labels(folder, names):
    """Give the rows of labels.csv the class names ``names`` in turn."""
    path = Path(folder) / "labels.csv"
    with open(path, newline="", encoding="utf-8") as f:
        rows = list(csv.DictReader(f))
    for i, row in enumerate(rows):
        row["label"] = names[i % len(names)]
    with open(path, "w", newline="", encoding="utf-8") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)


def test_class_names_come_from_the_labels(tmp_path):
    one = make_label_folder(tmp_path / "one", n_frames=2, class_name="nest")
    other = make_label_folder(tmp_path / "other", n_frames=2, class_name="burrow")
    logged = []
    assert recipe.label_class_names([one], log=logged.append) == ("nest",) and not logged
    assert recipe.label_class_names([one, other], log=logged.append) == ("burrow+nest",)
    assert "2 classes (burrow, nest)" in logged[0] and "one output channel" in logged[0]
    rewrite_labels(other, ["burrow", "target"])
    assert recipe.label_class_names([other], log=logged.append) == ("burrow+target",)
    (one / "labels.csv").unlink()
    assert recipe.label_class_names([one]) == recipe.DEFAULT_CLASS_NAMES


def test_positive_tiles_come_from_the_label_rows_not_the_rasters_peak(tmp_path):
    """σ = 2 px, every centre half a pixel off the grid in u and v: the raster peaks at
    255·exp(−0.5/(2·2²)) = 239 < 250, so the raster rule finds no positive tile; labels.csv's rows find each
    frame's first tile (the one holding its targets) and no other."""
    folder = make_label_folder(tmp_path / "labels", n_frames=4, tiles_per_frame=2, sigma_px=2.0,
                               centre_offset_px=0.5)
    gsd = Source(str(folder), gsd_default=1.0).gsd_of()
    tiles = recipe.load_tiles([(str(folder), gsd)], 1.0)
    names = recipe.tile_names(folder)
    expected = np.array([name.split("_")[1] == "0" for name in names])
    assert expected.sum() == 4 and np.array_equal(tiles.positive, expected)
    assert max(lab.max() for lab in tiles.labels) < 250 / 255
    (folder / "labels.csv").unlink()
    assert not recipe.load_tiles([(str(folder), gsd)], 1.0).positive.any(), "without labels.csv: the raster rule"


def test_a_tile_holds_the_centres_within_its_pixels_squares():
    """Pixel centres at integers: the tile at x0 = 96, 96 px wide, covers u in [95.5, 191.5)."""
    centres = {"7": np.array([[95.5, 10.0]]), "8": np.array([[191.5, 10.0]]), "9": np.array([[150.0, 95.5]])}
    assert recipe.tile_holds_centre("7_0_96.png", (96, 96), centres)
    assert not recipe.tile_holds_centre("8_0_96.png", (96, 96), centres)
    assert not recipe.tile_holds_centre("9_0_96.png", (96, 96), centres), "v beyond the last row"
    assert recipe.tile_holds_centre("9_0_96.png", (96, 96), {"9": np.array([[150.0, 95.49]])})
    assert not recipe.tile_holds_centre("6_0_96.png", (96, 96), centres), "a frame without labels"
    assert recipe.tile_holds_centre("a_b_0_0.png", (10, 10), {"a_b": np.array([[3.0, 3.0]])}), "'_' in frame ids"


def ground_with_best_f1(f1: float, targets: int = 10) -> dict:
    """Ground figures (the shape ground_figures returns) whose best F1 over the thresholds is ``f1``."""
    rows = {t: {"recall": f1 * s, "gmcf": f1 * s, "f1": round(f1 * s, 6), "clusters": 5, "detections": 9}
            for t, s in ((0.2, 0.9), (0.35, 1.0), (0.5, 0.8))}
    return {"frames": 4, "frames_skipped": 0, "targets": targets, "by_threshold": rows}


@pytest.mark.parametrize("start_f1, tuned_f1, kept", [(0.8, 0.6, True), (0.6, 0.8, False), (0.7, 0.7, False)])
def test_fine_tuning_that_scores_lower_on_the_held_out_ground_keeps_the_starting_weights(
        tmp_path, monkeypatch, start_f1, tuned_f1, kept):
    """Both models are scored on the same held-out ground (the first call scores INIT before training, the
    second the fine-tuned network); the .pt and the ONNX model hold INIT's weights exactly when the fine-tuned
    best F1 is lower, and the card says why."""
    from birdseye.birdseye_qgis.core.train import job as job_module

    first = make_label_folder(tmp_path / "first", n_frames=3, seed=0)
    a = short_job(first, tmp_path / "a.onnx")
    split = job_module.split_job
    monkeypatch.setattr(job_module, "split_job", lambda job, tiles: (*split(job, tiles)[:3], ["held-out flight"]))
    scores = iter([ground_with_best_f1(start_f1), ground_with_best_f1(tuned_f1)])
    monkeypatch.setattr(job_module, "score_on_ground", lambda *args, **kw: next(scores))
    events = []
    job = TrainJob(sources=[Source(str(first), gsd_default=1.0)], out=str(tmp_path / "b.onnx"), steps=3, batch=4,
                   val_fraction=0.0, threads=2, init=a["weights"])
    b = run_job(job, events.append)

    start, final = load_checkpoint(a["weights"])["state_dict"], load_checkpoint(b["weights"])["state_dict"]
    same = all(torch.equal(start[k], final[k]) for k in start)
    assert same is kept and b["starting_model_kept"] is kept
    assert b["ground_validation"]["by_threshold"][0.35]["f1"] == (start_f1 if kept else tuned_f1)
    warned = [e["text"] for e in events if e.get("level") == "warning" and "started from" in e["text"]]
    card = Path(b["card"]).read_text(encoding="utf-8")
    assert bool(warned) is kept and ("the starting weights are kept" in card) is kept

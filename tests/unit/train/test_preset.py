"""The training presets (core/train/preset.py) as the recipe and the job run them: the method preset's
network, its two stages (whole encoder frozen, then its top 30 % of blocks), AdamW 1e-5, plain binary
cross-entropy, early stopping after 15 epochs without a lower validation loss, native resolution, and
what the model card and training JSON say. Tiny crops and batches: the choices are tested, not the speed."""
from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
import pytest
import torch

from birdseye.birdseye_qgis.core.train import job as job_module
from birdseye.birdseye_qgis.core.train import recipe
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job
from birdseye.birdseye_qgis.core.train.preset import FAST, METHOD, PRESETS, preset

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fake_labels import make_label_folder  # noqa: E402


def tiny_tiles(n: int = 4, size: int = 32) -> recipe.TileSet:
    rng = np.random.default_rng(0)
    images = [rng.integers(0, 255, (size, size, 3), dtype=np.uint8) for _ in range(n)]
    labels = [np.zeros((size, size), np.float32) for _ in range(n)]
    labels[0][10:13, 10:13] = 1.0
    return recipe.TileSet(images, labels, np.array([True] + [False] * (n - 1)), np.full(n, 1.0),
                          [f"0:{i}" for i in range(n)])


def tiny_meta(tiles) -> object:
    return recipe.make_metadata(tiles, 1.0, 0.5, 1.5, "test", (recipe.IMAGENET_MEAN, recipe.IMAGENET_STD))


class OptimizerSpy:
    """Replaces torch.optim.AdamW: keeps each optimiser made (its settings and parameters)."""

    def __init__(self, monkeypatch):
        self.made = []
        real = torch.optim.AdamW
        spy = self

        class Recording(real):
            def __init__(self, params, **kwargs):
                params = list(params)
                super().__init__(params, **kwargs)
                spy.made.append(self)

        monkeypatch.setattr(torch.optim, "AdamW", Recording)
        self.cls = real


def test_presets_are_listed_by_name_and_old_jobs_read_as_fast():
    assert [p.name for p in PRESETS] == ["fast", "method"] and preset(None) is FAST and preset("method") is METHOD
    old = json.loads(TrainJob(sources=[Source("x", gsd_default=1.0)], out="m.onnx").to_json())
    del old["preset"]  # a job written before presets
    assert TrainJob.from_json(json.dumps(old)).preset == "fast"
    assert (FAST.crop_px, FAST.positive_weight, FAST.lr, FAST.patience_epochs) == (recipe.CROP_PX, 10.0, 3e-3, None)
    with pytest.raises(ValueError, match="unknown training preset"):
        preset("slow")


def test_method_builds_efficientnet_v2_under_a_transposed_convolution_decoder():
    efficientnet = recipe.import_torchvision().models.efficientnet  # not a bare import: see import_torchvision
    FusedMBConv, MBConv = efficientnet.FusedMBConv, efficientnet.MBConv  # noqa: N806 — torchvision's names
    net = recipe.build_network(METHOD.backbone, pretrained=False).eval()
    units = recipe.encoder_units(net)
    assert METHOD.backbone == "efficientnet_v2_s"
    assert sum(isinstance(u, FusedMBConv) for u in units) == 10 and sum(isinstance(u, MBConv) for u in units) == 15
    assert len(units) == 26, "stem + the blocks of stages 1–5 (cut after stride 16)"
    decoder = [m for name, m in net.named_modules() if not name.startswith("encoder")]
    assert sum(isinstance(m, torch.nn.ConvTranspose2d) for m in decoder) == 4
    assert net(torch.zeros(1, 3, 64, 64)).shape == (1, 1, 64, 64)


def test_method_stages_optimiser_and_batch_norm(monkeypatch):
    """Stage 1 trains the decoder with the whole encoder frozen; stage 2 adds exactly the top 8 of the
    26 encoder blocks (30 %); AdamW, lr 1e-5 constant, β (0.9, 0.999); frozen batch norms of a
    pretrained encoder stay in inference mode."""
    spy = OptimizerSpy(monkeypatch)
    tiles = tiny_tiles()
    meta = tiny_meta(tiles)
    net = recipe.build_network(METHOD.backbone, pretrained=False)
    units = recipe.encoder_units(net)
    bn_modes = []
    first_bn = next(m for m in net.encoder.modules() if isinstance(m, torch.nn.BatchNorm2d))
    first_bn.register_forward_pre_hook(lambda module, args: bn_modes.append(module.training))
    small = dataclasses.replace(METHOD, crop_px=32, batch=2)
    history = recipe.train_network(net, tiles, meta, 10.0, steps=4, preset=small, log=lambda m: None)
    assert len(spy.made) == 2
    encoder_ids = {id(p) for p in net.encoder.parameters()}
    stage1 = {id(p) for g in spy.made[0].param_groups for p in g["params"]}
    stage2 = {id(p) for g in spy.made[1].param_groups for p in g["params"]}
    assert not stage1 & encoder_ids and stage1 == {id(p) for p in net.decoder_parameters()}
    trained = [i for i, u in enumerate(units) if {id(p) for p in u.parameters()} <= stage2]
    untouched = [i for i, u in enumerate(units) if not {id(p) for p in u.parameters()} & stage2]
    assert trained == list(range(18, 26)) and untouched == list(range(18))
    assert stage2 - encoder_ids == stage1, "the decoder goes on learning"
    for opt in spy.made:
        assert isinstance(opt, spy.cls)
        group = opt.param_groups[0]
        assert (group["lr"], group["betas"], group["weight_decay"]) == (1e-5, (0.9, 0.999), 0.004)
    assert history["encoder_blocks"] == 26 and history["unfrozen_blocks"] == 8 and history["batchnorm_frozen"]
    assert bn_modes and not any(bn_modes[:4]), "batch norms in inference mode in the training steps"
    assert all(p.requires_grad for p in net.parameters()), "nothing is left frozen after training"


def test_fast_unfreezes_every_layer_on_a_cosine_rate(monkeypatch):
    spy = OptimizerSpy(monkeypatch)
    tiles = tiny_tiles()
    net = recipe.build_network("small")
    history = recipe.train_network(net, tiles, tiny_meta(tiles), 10.0, steps=4, batch=2, crop=32, log=lambda m: None)
    stage2 = {id(p) for g in spy.made[1].param_groups for p in g["params"]}
    assert stage2 == {id(p) for p in net.parameters()} and not history["batchnorm_frozen"]
    assert spy.made[0].param_groups[0]["weight_decay"] == 1e-4
    assert spy.made[1].param_groups[0]["lr"] == pytest.approx(1e-3 * 0.25 + 1e-5), "stage 2: a third, decaying"
    assert [s["ended_by"] for s in history["stages"]] == ["steps", "steps"] and history["monitor"] is None


def test_the_method_loss_is_plain_binary_cross_entropy():
    logits, target = torch.randn(2, 1, 8, 8), torch.rand(2, 1, 8, 8)
    plain = torch.nn.functional.binary_cross_entropy_with_logits(logits, target)
    assert torch.equal(recipe.loss_fn(logits, target, METHOD.positive_weight), plain)
    assert not torch.allclose(recipe.loss_fn(logits, target), plain), "fast weights target pixels"
    assert METHOD.loss_name() == "binary cross-entropy"


def test_early_stopping_after_15_epochs_without_a_lower_validation_loss(monkeypatch):
    """Validation loss 1.0, 0.9, 0.8, then 0.85 for ever: stage 1 stops at epoch 3 + 15 = 18 and goes back
    to epoch 3's weights; stage 2's first epoch is its best, so it stops at 1 + 15 = 16. One step per
    epoch (4 tiles, batch 4); a 10-minute budget that never ends a stage."""
    values = [1.0, 0.9, 0.8]
    calls = []

    def fake_validation_loss(net, tiles, meta, limit=32, positive_weight=recipe.POSITIVE_WEIGHT):
        calls.append((limit, positive_weight))
        return values.pop(0) if values else 0.85

    monkeypatch.setattr(recipe, "validation_loss", fake_validation_loss)
    tiles = tiny_tiles()
    net = recipe.build_network("small")
    small = dataclasses.replace(METHOD, backbone=None, crop_px=32, batch=4)
    snapshots = []
    history = recipe.train_network(net, tiles, tiny_meta(tiles), 10.0, preset=small, val=tiny_tiles(2),
                                   log=lambda m: None, on_point=lambda r: snapshots.append(
                                       (r["stage"], r["step"], net.head.bias.detach().clone())))
    first, second = history["stages"]
    assert (first["epochs"], first["best_epoch"], first["ended_by"], first["restored_best"]) == (
        18, 3, "early stopping", True)
    assert (second["epochs"], second["best_epoch"], second["ended_by"]) == (16, 1, "early stopping")
    assert history["ended_by"] == "early stopping" and history["monitor"] == "validation loss"
    assert history["steps_per_epoch"] == 1 and history["frozen_steps"] == 18 and history["finetune_steps"] == 16
    assert set(calls) == {(None, 0.0)}, "every held-out tile, plain cross-entropy"
    epoch3 = next(b for stage, step, b in snapshots if stage == "frozen-encoder" and step == 3)
    stage1_end = [b for stage, step, b in snapshots if stage == "frozen-encoder"][-1]
    assert torch.equal(stage1_end, epoch3), "stage 1 ends on its best epoch's weights"


def test_a_time_budget_ends_an_early_stopping_run_and_says_so():
    tiles = tiny_tiles()
    net = recipe.build_network("small")
    # Patience beyond any epoch count 1.2 s can reach: however fast the machine, the budget ends the run.
    small = dataclasses.replace(METHOD, backbone=None, crop_px=32, batch=2, patience_epochs=10**9)
    history = recipe.train_network(net, tiles, tiny_meta(tiles), 0.02, preset=small, val=tiny_tiles(2),
                                   log=lambda m: None)
    assert history["ended_by"] == "time budget"
    assert [stage["ended_by"] for stage in history["stages"]] == ["time budget", "time budget"]


def test_native_tiles_keep_their_frames_resolution(tmp_path):
    labels = make_label_folder(tmp_path / "labels", n_frames=2)
    gsd = {"1": 0.4, "2": 0.6}
    tiles = recipe.load_native_tiles([(labels, gsd)], log=lambda m: None)
    assert [im.shape[:2] for im in tiles.images] == [(96, 96)] * 4
    assert sorted(tiles.source_gsd_cm.tolist()) == [0.4, 0.4, 0.6, 0.6]
    assert recipe.load_tiles([(labels, gsd)], 1.0, log=lambda m: None).images[0].shape[0] < 96, "fast resamples"


def test_a_method_job_without_weights_trains_from_random_init_and_the_card_says_it(tmp_path, monkeypatch):
    """The job with the method preset (its crop and batch made tiny): the frames' own resolution, random
    initialisation named plainly, the preset and its settings and what ended the run in card and JSON."""
    monkeypatch.setattr(torch.hub, "get_dir", lambda: str(tmp_path / "hub"))  # no cached ImageNet weights
    monkeypatch.setattr(torch.hub, "load_state_dict_from_url", lambda *a, **k: pytest.fail("a download"))
    monkeypatch.setattr(job_module, "find_preset", lambda name: dataclasses.replace(METHOD, crop_px=32, batch=4))
    labels = make_label_folder(tmp_path / "labels", n_frames=6)
    job = TrainJob(sources=[Source(str(labels), gsd_default=0.5)], out=str(tmp_path / "m.onnx"), steps=4,
                   val_fraction=0.34, threads=2, preset="method")
    result = run_job(job)
    settings = json.loads(Path(result["report"]).read_text())["settings"]
    assert settings["preset"] == "method" and settings["backbone"] == "efficientnet_v2_s"
    assert settings["resolution_cm"] == 0.5 and settings["native_resolution"] and settings["positive_weight"] == 0
    assert settings["preset_settings"]["patience_epochs"] == 15 and settings["preset_settings"]["lr"] == 1e-5
    assert "NOT ImageNet-pretrained" in settings["encoder_start"]
    card = Path(result["card"]).read_text()
    assert "Method (EfficientNetV2, two stages, AdamW)" in card
    assert "NOT ImageNet-pretrained" in card and "EfficientNetV2-B3" in card and "not resampled" in card
    assert "AdamW" in card and "15 epochs" in card and "ended by" in card


def test_a_method_job_takes_the_encoder_weights_from_a_local_file(tmp_path, monkeypatch):
    """WEIGHTS (a torchvision efficientnet_v2_s state dict made here, standing in for ImageNet's): loaded,
    named in the card, and the pretrained encoder's batch norms kept in inference mode."""
    monkeypatch.setattr(torch.hub, "load_state_dict_from_url", lambda *a, **k: pytest.fail("a download"))
    monkeypatch.setattr(job_module, "find_preset", lambda name: dataclasses.replace(METHOD, crop_px=32, batch=4))
    tv = recipe.import_torchvision()
    torch.manual_seed(2)
    weights = tmp_path / "efficientnet_v2_s_random.pth"
    torch.save(tv.models.efficientnet_v2_s(weights=None).state_dict(), weights)
    labels = make_label_folder(tmp_path / "labels", n_frames=4)
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "w.onnx"), steps=2,
                   val_fraction=0.0, threads=2, preset="method", weights=str(weights))
    result = run_job(job)
    assert result["settings"]["encoder_start"] == f"ImageNet weights from {weights}"
    assert result["history"]["batchnorm_frozen"] and result["history"]["monitor"] == "training loss"
    assert f"ImageNet weights from {weights}" in Path(result["card"]).read_text()

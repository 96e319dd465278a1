"""The training recipe and job with torch (requirements-train.txt; these tests fail, not skip, without it):
networks, pretrained weights from a file made here, never a download, checkpoints, export, a short job."""
from __future__ import annotations

import dataclasses
import json
import sys
from pathlib import Path

import numpy as np
import pytest
import torch  # noqa: F401 — a missing torch must fail this module: CI installs requirements-train.txt

from birdseye.birdseye_qgis.core.detect.model_metadata import read_onnx_metadata
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.train import recipe
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job

sys.path.insert(0, str(Path(__file__).resolve().parent))
from fake_labels import make_label_folder  # noqa: E402


@pytest.fixture(scope="module")
def labels(tmp_path_factory):
    return make_label_folder(tmp_path_factory.mktemp("labels"), n_frames=8)


def test_small_network_gives_one_logit_per_pixel():
    net = recipe.build_network("small").eval()
    assert net(torch.zeros(2, 3, 96, 64)).shape == (2, 1, 96, 64)


@pytest.fixture(scope="module")
def resnet_weights(tmp_path_factory):
    """A randomly initialised torchvision ResNet-18's state dict, standing in for ImageNet weights."""
    tv = recipe.import_torchvision()
    torch.manual_seed(1)
    path = tmp_path_factory.mktemp("weights") / "resnet18_random.pth"
    torch.save(tv.models.resnet18(weights=None).state_dict(), path)
    return path


def test_a_pretrained_encoder_loads_the_named_weights(resnet_weights):
    net = recipe.build_network("resnet18", weights=resnet_weights, log=lambda m: None).eval()
    expected = torch.load(resnet_weights, weights_only=True)["layer1.0.conv1.weight"]
    assert torch.equal(net.encoder.blocks[2][0].conv1.weight, expected)
    assert net.input_multiple == 16 and net(torch.zeros(1, 3, 96, 96)).shape == (1, 1, 96, 96)


def test_efficientnet_taps_strides_2_to_16():
    net = recipe.build_network("efficientnet_b0", pretrained=False).eval()
    assert [f.shape[-1] for f in net.encoder(torch.zeros(1, 3, 64, 64))] == [32, 16, 8, 4]


def test_nothing_is_downloaded_the_message_says_which_file_goes_where(tmp_path, monkeypatch):
    monkeypatch.setattr(torch.hub, "get_dir", lambda: str(tmp_path / "hub"))
    monkeypatch.setattr(torch.hub, "load_state_dict_from_url", lambda *a, **k: pytest.fail("a download"))
    with pytest.raises(InputError, match=r"efficientnet_b0_rwightman-7f5810bc\.pth.*" + str(tmp_path / "hub")):
        recipe.build_network("efficientnet_b0")
    cached, _ = recipe.cached_weights_path("resnet18")
    cached.parent.mkdir(parents=True)
    tv = recipe.import_torchvision()
    torch.save(tv.models.resnet18(weights=None).state_dict(), cached)
    assert recipe.build_network("resnet18", log=lambda m: None) is not None, "found in torchvision's cache"


def test_weights_of_another_network_are_refused(resnet_weights):
    with pytest.raises(InputError, match="does not hold efficientnet_b0 weights"):
        recipe.build_network("efficientnet_b0", weights=resnet_weights)


def test_split_keeps_each_frame_on_one_side(labels):
    tiles = recipe.load_tiles([(labels, Source(str(labels), gsd_default=1.0).gsd_of())], 1.0)
    train, val = recipe.split_tiles(tiles, 0.25, seed=0)
    assert len(train) + len(val) == len(tiles) == 16 and val.positive.any() and train.positive.any()
    assert not set(train.frame_key) & set(val.frame_key)


def test_checkpoints_are_atomic_and_init_takes_them(tmp_path):
    net = recipe.build_network("small")
    path = recipe.save_checkpoint(net, tmp_path / "c.pt", "small", recipe.WIDTH, {"step": 3})
    assert recipe.checkpoint_backbone(path) == "small" and not list(tmp_path.glob(".*tmp"))
    other = recipe.build_network("small", width=8)
    with pytest.raises(InputError, match="does not fit"):
        recipe.load_init(other, path)
    fresh = recipe.build_network("small")
    with torch.no_grad():
        fresh.head.bias.fill_(1.0)
    recipe.load_init(fresh, path)
    assert torch.equal(fresh.head.bias, net.head.bias)


def test_a_short_job_writes_model_card_plot_and_weights(labels, tmp_path):
    events = []
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "m.onnx"), steps=6,
                   val_fraction=0.25, threads=2)
    result = run_job(job, events.append)
    meta = read_onnx_metadata(result["model"])
    assert meta.default_threshold == result["threshold"] and meta.label_sigma_px == 3.0
    kinds = [e["type"] for e in events]
    assert kinds[0] == "start" and kinds[-1] == "result" and "point" in kinds and "checkpoint" in kinds
    assert result["data"]["folders"][0]["provenance"]["review"]["targets"] > 0
    assert set(result["validation"]["by_threshold"]) == {f"{t:g}" for t in recipe.THRESHOLDS}
    assert Path(result["plot"]).stat().st_size > 1000 and "| threshold |" in Path(result["card"]).read_text()
    assert json.loads(Path(result["report"]).read_text())["history"]["tiles_per_s"] > 0
    assert not job.checkpoint_path.exists(), "the checkpoint of a finished run gives way to the final weights"
    # fine-tune from it
    again = TrainJob(sources=job.sources, out=str(tmp_path / "m2.onnx"), steps=2, init=result["weights"], threads=2)
    assert Path(run_job(again)["model"]).is_file()


def test_a_stopped_job_keeps_its_checkpoint_and_writes_no_model(labels, tmp_path):
    events = []
    job = TrainJob(sources=[Source(str(labels), gsd_default=1.0)], out=str(tmp_path / "s.onnx"), steps=50, threads=2)
    result = run_job(job, events.append, should_stop=lambda: sum(e["type"] == "point" for e in events) >= 1)
    assert result["stopped"] and result["model"] is None and Path(result["checkpoint"]).is_file()
    assert not (tmp_path / "s.onnx").exists()


class FixedHeatmap(torch.nn.Module):
    """A stand-in network whose logits are a given map, whatever the image."""

    input_multiple = 8

    def __init__(self, probabilities):
        super().__init__()
        p = torch.as_tensor(probabilities, dtype=torch.float32)
        self.logits = torch.nn.Parameter(torch.log(p / (1 - p))[None, None], requires_grad=False)

    def forward(self, x):
        return self.logits.expand(x.shape[0], 1, -1, -1)


def blob(shape, centre, peak, sigma=1.5):
    yy, xx = np.mgrid[0:shape[0], 0:shape[1]]
    return peak * np.exp(-((xx - centre[0]) ** 2 + (yy - centre[1]) ** 2) / (2 * sigma ** 2))


def test_validation_figures_count_peaks_against_label_centres_by_hand():
    """One 32 × 32 tile, two targets whose resampled labels peak at 0.95 and 0.6 (below 1, as every label
    resampled to the model's resolution does): centres (8, 8) and (24, 20). The network answers with
    peaks 0.8 on the first target, 0.45 two pixels off the second, and 0.65 on empty ground (4, 26).
    Match radius 3 px. At 0.3 all three peaks: recall 2/2, precision 2/3, one false alarm. At 0.5 the second
    target's peak is gone: recall 1/2, precision 1/2. At 0.7 only the first: recall 1/2, precision 1."""
    label = np.maximum(blob((32, 32), (8, 8), 0.95), blob((32, 32), (24, 20), 0.6)).astype(np.float32)
    heat = np.maximum.reduce([blob((32, 32), (8, 8), 0.8), blob((32, 32), (24, 22), 0.45),
                              blob((32, 32), (4, 26), 0.65), np.full((32, 32), 1e-4)])
    tiles = recipe.TileSet([np.zeros((32, 32, 3), np.uint8)], [label], np.array([True]), np.array([1.0]))
    # Without the detector's blur the peaks keep the heights given here.
    meta = dataclasses.replace(recipe.make_metadata(tiles, 1.0, 0.5, 1.0, "test"), peak_blur_sigma_px=0.0)
    figures = recipe.validation_figures(FixedHeatmap(heat), tiles, meta, thresholds=(0.3, 0.5, 0.7),
                                        match_radius_px=3.0)
    assert figures["targets"] == 2
    rows = figures["by_threshold"]
    assert (rows["0.3"]["recall"], rows["0.3"]["precision"], rows["0.3"]["false_per_tile"]) == (1.0, 0.6667, 1.0)
    assert (rows["0.5"]["recall"], rows["0.5"]["precision"]) == (0.5, 0.5)
    assert (rows["0.7"]["recall"], rows["0.7"]["precision"]) == (0.5, 1.0)
    # F1 0.8 at 0.3, 0.5 at 0.5, 0.667 at 0.7. Two targets cannot tell F1 values within 1/2 apart, but 0.5 and
    # 0.7 find one target of two where 0.3 finds both: a tie never gives up a target, so 0.3.
    assert recipe.best_threshold(figures) == 0.3
    # Recall kept, the highest threshold within one target's worth: 0.5 (F1 0.75, recall 1) over 0.3 (0.8).
    tied = {"targets": 2, "by_threshold": {"0.3": {"f1": 0.8, "recall": 1.0}, "0.5": {"f1": 0.75, "recall": 1.0},
                                           "0.7": {"f1": 0.667, "recall": 0.5}}}
    assert recipe.best_threshold(tied) == 0.5
    # With 50 targets only values within 0.02 tie: the loop demo's tiles (F1 0.559, 0.614, 0.594, 0.590,
    # 0.602, 0.406 at 0.1…0.6) give 0.5, where the best F1 alone gave 0.2.
    rows = dict(zip(("0.1", "0.2", "0.3", "0.4", "0.5", "0.6"), (0.559, 0.614, 0.594, 0.590, 0.602, 0.406)))
    assert recipe.best_threshold({"targets": 50, "by_threshold": {t: {"f1": f} for t, f in rows.items()}}) == 0.5
    assert recipe.best_threshold(None) == 0.5

"""BirdsEye's models in the Deepness QGIS plugin's own code, and Deepness's segmentors in BirdsEye.

Deepness (PUTvision) is not on PyPI, and CI reaches package registries only: its model classes are imported
from a checkout named by ``DEEPNESS_SRC`` (the repository's root), else from ``tests/data/deepness``, unchanged
copies of the files used, at one commit (``SOURCE.md`` there; ``scripts/deepness_snapshot.sh`` refreshes them).
Nothing of Deepness is reimplemented here: its ``ModelBase`` reads the metadata, its preprocessing and
``process`` run the tile, and the result is compared with BirdsEye's heatmap of the same tile.
"""
import hashlib
import os
import re
import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pytest
from test_raster_detect import deepness_segmentor

from birdseye.birdseye_qgis.core.detect.detector import HeatmapModel, frame_heatmap

SNAPSHOT = Path(__file__).resolve().parents[2] / "data" / "deepness"


def deepness_src() -> Path:
    """The folder holding Deepness's ``deepness`` package; the test fails, saying how to get it, without one."""
    given = os.environ.get("DEEPNESS_SRC")
    root = Path(given) if given else SNAPSHOT
    if not (root / "src" / "deepness" / "processing" / "models" / "model_base.py").is_file():
        pytest.fail(f"Deepness's source is not in {root}: set DEEPNESS_SRC to a clone of "
                    "https://github.com/PUTvision/qgis-plugin-deepness, or restore tests/data/deepness "
                    "(scripts/deepness_snapshot.sh <clone>)")
    return root / "src"


@pytest.fixture(scope="module")
def deepness():
    """Deepness's model classes, imported from its source; sys.path, sys.modules and the environment
    (Deepness's ``__init__`` sets an OpenCV limit) restored afterwards."""
    src = str(deepness_src())
    environ = dict(os.environ)
    sys.path.insert(0, src)
    try:
        from deepness.processing.models.model_base import ModelBase
        from deepness.processing.models.regressor import Regressor
        from deepness.processing.models.segmentor import Segmentor

        # Deepness's dock makes the class its ModelType names, and ModelType's values are the class names
        # (deepness/processing/models/model_types.py, which imports QGIS).
        yield SimpleNamespace(ModelBase=ModelBase, classes={c.__name__: c for c in (Regressor, Segmentor)})
    finally:
        sys.path.remove(src)
        for name in [m for m in sys.modules if m == "deepness" or m.startswith("deepness.")]:
            del sys.modules[name]
        os.environ.clear()
        os.environ.update(environ)


def load_as_deepness_does(deepness, path):
    """The model as Deepness's dock loads it: the class its metadata's model_type names, then its check."""
    model_type = deepness.ModelBase.get_model_type_from_metadata(str(path))
    model = deepness.classes[model_type](str(path))
    model.check_loaded_model_outputs()
    return model_type, model


def smooth_rgb(size, seed=0):
    """An RGB uint8 image (size, size, 3) with structure at several scales."""
    import cv2

    rng = np.random.default_rng(seed)
    noise = rng.uniform(0, 255, (size // 8, size // 8, 3)).astype(np.float32)
    img = cv2.resize(noise, (size, size), interpolation=cv2.INTER_CUBIC) + rng.normal(0, 12, (size, size, 3))
    return np.clip(np.rint(img), 0, 255).astype(np.uint8)


def test_the_snapshot_is_deepness_unchanged():
    """Every file of tests/data/deepness is the blob SOURCE.md names at Deepness's commit."""
    listed = re.findall(r"^\| ([0-9a-f]{40}) \| (\S+) \|$", (SNAPSHOT / "SOURCE.md").read_text(), re.M)
    files = sorted(p.relative_to(SNAPSHOT).as_posix() for p in (SNAPSHOT / "src").rglob("*.py"))
    assert sorted(f for _, f in listed) == files and len(files) == 11
    for blob, name in listed:
        data = (SNAPSHOT / name).read_bytes()
        assert hashlib.sha1(b"blob %d\0" % len(data) + data).hexdigest() == blob, name
    assert "Apache License" in (SNAPSHOT / "LICENSE").read_text()


def test_without_deepness_the_test_fails_saying_how_to_get_it(monkeypatch, tmp_path):
    monkeypatch.setenv("DEEPNESS_SRC", str(tmp_path))
    with pytest.raises(pytest.fail.Exception, match="set DEEPNESS_SRC to a clone of https://github.com"):
        deepness_src()


def test_a_model_train_detector_writes_runs_in_deepness(deepness, tmp_path):
    """Train detector's export (recipe.make_metadata + export_onnx) in Deepness: its metadata read by Deepness's
    getters, the tile run by Deepness's preprocessing and session, the output BirdsEye's heatmap."""
    import torch

    from birdseye.birdseye_qgis.core.train import recipe

    torch.manual_seed(0)
    net = recipe.build_network(width=4)
    with torch.no_grad():  # weights as training might leave them: a heatmap with structure, not the prior
        for p in net.parameters():
            p.add_(0.2 * torch.randn_like(p))
    tiles = SimpleNamespace(source_gsd_cm=np.array([0.31, 0.35]))  # what make_metadata reads of a TileSet
    meta = recipe.make_metadata(tiles, 0.5, 0.35, 4.0, "Deepness interop test",
                                mean_std=((0.41, 0.45, 0.39), (0.21, 0.2, 0.22)), class_names=("burrow",))
    path = recipe.export_onnx(net, meta, tmp_path / "trained.onnx")

    model_type, model = load_as_deepness_does(deepness, path)
    assert model_type == "Regressor"  # Deepness shows the heatmap as a raster
    assert model.get_input_shape()[1:] == [3, meta.tile_size, meta.tile_size]  # the dock's tile size: an int
    assert model.get_model_batch_size() is None
    assert model.get_metadata_resolution() == meta.resolution_cm
    assert model.get_metadata_tile_size() == meta.tile_size
    assert model.get_metadata_tiles_overlap() == meta.tiles_overlap_pct  # Deepness reads an integer percent
    np.testing.assert_allclose(model.standardization_parameters.mean, meta.standardization_mean, rtol=1e-6)
    np.testing.assert_allclose(model.standardization_parameters.std, meta.standardization_std, rtol=1e-6)
    assert model.get_outputs_channel_names() == [["burrow"]] and model.get_number_of_output_channels() == [1]

    rgb = smooth_rgb(meta.tile_size)
    theirs = model.process(rgb[None])[0][0, 0]  # Deepness: N×H×W×C RGB uint8 in, its outputs out
    ours = frame_heatmap(HeatmapModel(path), np.ascontiguousarray(rgb[:, :, ::-1]))  # BirdsEye: BGR in
    assert ours.std() > 0.01 and ours.max() < 0.99  # a heatmap with structure, not saturated
    np.testing.assert_allclose(theirs, ours, atol=2e-5)

    # Picked as a segmentation model, it is Deepness's one-channel sigmoid case: background and burrow.
    seg = deepness.classes["Segmentor"](str(path))
    assert seg.check_loaded_model_outputs() == [True] and seg.outputs_names == [["background", "burrow"]]
    np.testing.assert_allclose(seg.process(rgb[None])[0][0, 0], ours, atol=2e-5)


@pytest.mark.parametrize("props", [{}, {"standardization_mean": [0.5, 0.4, 0.3],
                                        "standardization_std": [0.2, 0.25, 0.3], "seg_thresh": 0.6}])
def test_a_deepness_segmentor_reads_the_same_in_both(deepness, tmp_path, props):
    """The Deepness-style background/target segmentor BirdsEye's raster Detect runs: Deepness's getters give
    the settings BirdsEye reads, and BirdsEye's heatmap is Deepness's target channel."""
    path = deepness_segmentor(tmp_path / "seg.onnx", tile=64, **props)
    ours = HeatmapModel(path)
    meta = ours.metadata
    model_type, model = load_as_deepness_does(deepness, path)
    assert model_type == "Segmentor" and model.check_loaded_model_outputs() == [False]
    assert model.get_outputs_channel_names() == [list(meta.class_names)] == [["background", "nest"]]
    assert model.get_metadata_segmentation_threshold() == meta.default_threshold
    assert model.get_metadata_resolution() == meta.resolution_cm and model.get_metadata_tile_size() is None
    assert model.get_input_size_in_pixels() == [meta.tile_size] * 2
    assert model.get_metadata_tiles_overlap() == meta.tiles_overlap_pct
    np.testing.assert_allclose(model.standardization_parameters.mean, meta.standardization_mean, rtol=1e-6)
    np.testing.assert_allclose(model.standardization_parameters.std, meta.standardization_std, rtol=1e-6)

    rgb = smooth_rgb(64, seed=1)
    theirs = model.process(rgb[None])[0][0, meta.output_channel]
    np.testing.assert_allclose(theirs, frame_heatmap(ours, np.ascontiguousarray(rgb[:, :, ::-1])), atol=2e-5)

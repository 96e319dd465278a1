"""A folder Write labels on a raster wrote is what Train detector reads: its tiles at the raster's GSD without a
frame layer or GSD_CM, positives told by labels.csv, spatial blocks that hold part of the raster out, and a
few-step training run to a model (torch: requirements-train.txt)."""
from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.train import ground_validation, recipe
from birdseye.birdseye_qgis.core.train.job import Source, TrainJob, run_job, split_job

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "labels"))
from test_raster_labels import ArrayReader, at_pixel, raster, survey  # noqa: E402

from birdseye.birdseye_qgis.core.labels.raster_labels import RasterLabelRequest, write_raster_labels  # noqa: E402


@pytest.fixture(scope="module")
def raster_folder(tmp_path_factory):
    """A 640 × 640 px raster at 2 cm/px with 16 dark round targets on a 4 × 4 grid, written as 96 px tiles."""
    grid, image = raster(640, 640, seed=1)
    yy, xx = np.mgrid[0:640, 0:640]
    for u, v in CENTRES:
        image[(xx - u) ** 2 + (yy - v) ** 2 <= 25] = (40, 45, 50)
    geotags, xy = survey([at_pixel(u, v) for u, v in CENTRES], heights=np.full(len(CENTRES), 44.0))
    folder = tmp_path_factory.mktemp("raster_labels")
    write_raster_labels(folder, grid, ArrayReader(image), geotags, xy[:, 0], xy[:, 1],
                        RasterLabelRequest(sigma_cm=6.0, tile_size=96, negative_ratio=1.0))
    return folder


#: Tiles holding a target centre, counted here: 96 px tiles start every 96 px and the last one is flush with the
#: border (544), so targets in the overlap (544…575) lie in two tiles.
CENTRES = [(80.0 + 160 * i + 7.3, 80.0 + 160 * j - 11.6) for i in range(4) for j in range(4)]
ORIGINS = [0, 96, 192, 288, 384, 480, 544]
POSITIVE_TILES = sum(any(x0 - 0.5 <= u < x0 + 95.5 and y0 - 0.5 <= v < y0 + 95.5 for u, v in CENTRES)
                     for x0 in ORIGINS for y0 in ORIGINS)


def test_the_tiles_load_at_the_rasters_gsd_with_their_positives(raster_folder):
    source = Source(str(raster_folder))  # no frame layer, no GSD: the folder records its raster's
    gsd_of = source.gsd_of()
    assert set(gsd_of.values()) == {2.0}
    tiles = recipe.load_tiles([(str(raster_folder), gsd_of)], 1.0)
    assert POSITIVE_TILES > 16  # the test's premise: some targets in two tiles
    # negative ratio 1 asks for as many negatives as positives; there are fewer: every tile of the grid is written
    assert len(tiles) == len(ORIGINS) ** 2 and tiles.positive.sum() == POSITIVE_TILES
    assert tiles.images[0].shape == (192, 192, 3)  # 96 px at 2 cm/px resampled to 1 cm/px
    native = recipe.load_native_tiles([(str(raster_folder), gsd_of)])
    assert native.images[0].shape == (96, 96, 3) and set(native.source_gsd_cm) == {2.0}


def test_spatial_blocks_hold_part_of_the_raster_out(raster_folder):
    job = TrainJob(sources=[Source(str(raster_folder))], out="unused.onnx", val_fraction=0.25)
    tiles = recipe.load_tiles([(str(raster_folder), job.sources[0].gsd_of())], 1.0)
    plan, train, val, flights = split_job(job, tiles)
    assert plan.method == "blocks" and plan.held_out
    # blocks of one tile's ground diagonal (96 px · √2 · 2 cm): the held-out targets' tiles sit on one side only
    assert plan.info["block_m"] == pytest.approx(96 * np.sqrt(2) * 0.02, abs=1e-3)
    assert val.positive.any() and train.positive.any() and flights == []
    held = plan.held_targets[0]
    views, _, _ = ground_validation.folder_views([str(raster_folder)], [None], [sorted({k.split(":")[1]
                                                                                       for k in tiles.frame_key})])
    for fid, seen in views[0].frame_targets.items():
        side = plan.side[(0, fid)]
        if side == ground_validation.VAL:
            assert seen <= held
        elif side == ground_validation.TRAIN:
            assert not seen & held


def test_a_few_step_run_trains_a_model_on_the_folder(raster_folder, tmp_path):
    job = TrainJob(sources=[Source(str(raster_folder))], out=str(tmp_path / "m.onnx"), steps=3, threads=2,
                   val_fraction=0.25)
    result = run_job(job)
    assert Path(result["model"]).is_file()
    assert result["data"]["positive_tiles"] == POSITIVE_TILES and result["data"]["native_gsd_cm"] == 2.0
    assert result["split"]["method"] == "blocks" and result["split"]["held_out"]
    assert result["metadata"]["label_sigma_px"] == pytest.approx(6.0)  # 3 px at 2 cm/px = 6 px at 1 cm/px

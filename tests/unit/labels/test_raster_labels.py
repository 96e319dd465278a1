"""Write labels on a raster (core/labels/raster_labels.py), against derivations made here: the geotransform's
pixel of a map position, the Gaussian's value at a distance, the tile grid at the raster's border, the surveyed
area and the negative sample."""
from __future__ import annotations

import csv
import json

import cv2
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.detect.raster_detect import RasterGrid
from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.field.geotags import Geotags
from birdseye.birdseye_qgis.core.field.surveyed_area import surveyed_area
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.labels.raster_labels import RasterLabelRequest, raster_record, write_raster_labels
from birdseye.birdseye_qgis.core.labels.training_set import read_targets

#: The raster's map: metres east and north of a local frame (a projected CRS in all but name).
LOCAL = LocalFrame(52.0, 5.0, 40.0)
ORIGIN_X, ORIGIN_Y, PIXEL = 1000.0, 2000.0, 0.02  # 2 cm/px


def to_lat_lon(x, y):
    lat, lon, _ = LOCAL.to_geodetic(np.column_stack([np.ravel(x), np.ravel(y), np.zeros(np.size(x))]))
    return np.atleast_1d(lat), np.atleast_1d(lon)


class ArrayReader:
    """A ReadWindow over an (H, W, 3) uint8 array; ``valid`` marks nodata; counts the pixels read."""

    def __init__(self, image, valid=None):
        self.image = image
        self.valid = np.ones(image.shape[:2], bool) if valid is None else valid
        self.windows = []

    def __call__(self, col0, row0, cols, rows):
        self.windows.append((col0, row0, cols, rows))
        planes = np.zeros((3, rows, cols), np.uint8)
        valid = np.zeros((rows, cols), bool)
        h, w = self.valid.shape
        c0, r0, c1, r1 = max(col0, 0), max(row0, 0), min(col0 + cols, w), min(row0 + rows, h)
        if c1 > c0 and r1 > r0:
            planes[:, r0 - row0:r1 - row0, c0 - col0:c1 - col0] = self.image[r0:r1, c0:c1].transpose(2, 0, 1)
            valid[r0 - row0:r1 - row0, c0 - col0:c1 - col0] = self.valid[r0:r1, c0:c1]
        return planes, valid


def raster(width=250, height=230, seed=0):
    image = np.random.default_rng(seed).integers(60, 200, (height, width, 3), dtype=np.uint8)
    return RasterGrid(width, height, ORIGIN_X, ORIGIN_Y, PIXEL, PIXEL), image


def survey(xy, heights=None, labels=None):
    """Geotags at map positions ``xy``: their WGS84 positions through the same local frame."""
    xy = np.asarray(xy, float).reshape(-1, 2)
    lat, lon = to_lat_lon(xy[:, 0], xy[:, 1])
    h = np.full(len(xy), np.nan) if heights is None else heights
    return Geotags([f"g{i + 1}" for i in range(len(xy))], lat, lon, h, labels), xy


def at_pixel(col, row):
    """Map position of a point at (col, row) in the pixel-centre convention, from the geotransform's definition:
    pixel i covers [origin + i·size, origin + (i + 1)·size), so its centre is at i + 0.5 pixel sizes."""
    return ORIGIN_X + (col + 0.5) * PIXEL, ORIGIN_Y - (row + 0.5) * PIXEL


def rows_of(folder):
    with open(folder / "labels.csv", newline="", encoding="utf-8") as f:
        return list(csv.DictReader(f))


def test_a_target_lands_at_the_geotransforms_pixel_with_sigma_from_cm(tmp_path):
    grid, image = raster()
    geotags, xy = survey([at_pixel(37.25, 52.0)], heights=np.array([45.5]))
    summary = write_raster_labels(tmp_path, grid, ArrayReader(image), geotags, xy[:, 0], xy[:, 1],
                                  RasterLabelRequest(sigma_cm=6.0, tile_size=100, negative_ratio=0))
    assert summary["sigma_px"] == pytest.approx(3.0)  # 6 cm at 2 cm/px
    assert summary["raster"]["gsd_cm"] == pytest.approx(2.0)
    (row,) = rows_of(tmp_path)
    assert (float(row["u"]), float(row["v"])) == pytest.approx((37.25, 52.0), abs=1e-3)
    assert row["frame_id"] == "0" and row["sigma_px"] == "3" and row["provenance"] == "survey"
    label = cv2.imread(str(tmp_path / "tiles" / "labels" / "0_0_0.png"), cv2.IMREAD_UNCHANGED)
    tile = cv2.imread(str(tmp_path / "tiles" / "images" / "0_0_0.png"), cv2.IMREAD_COLOR)
    assert np.array_equal(tile, image[:100, :100, ::-1])  # the raster's pixels as they are, BGR on disk
    # 255·exp(−r²/2σ²) at r = 0.25 px and r = 3 px from the centre (37.25, 52); zero beyond 3σ = 9 px
    assert label[52, 37] == round(255 * np.exp(-0.25 ** 2 / 18))
    assert label[55, 37] == round(255 * np.exp(-(3 ** 2 + 0.25 ** 2) / 18))
    assert label[52, 47] == 0 and label.max() == label[52, 37]
    targets = read_targets(tmp_path)
    assert list(targets.ids) == ["g1"] and targets.height[0] == pytest.approx(45.5)


def test_tiles_at_the_border_are_flush_and_a_label_reaching_in_is_listed(tmp_path):
    grid, image = raster(250, 230)  # tile origins 0, 100, 150 across and 0, 100, 130 down
    geotags, xy = survey([at_pixel(245.0, 225.0), at_pixel(148.0, 20.0)])
    summary = write_raster_labels(tmp_path, grid, ArrayReader(image), geotags, xy[:, 0], xy[:, 1],
                                  RasterLabelRequest(sigma_cm=4.0, tile_size=100, negative_ratio=0))
    names = sorted(p.name for p in (tmp_path / "tiles" / "images").glob("*.png"))
    # frame ids count tiles row by row on the 3 × 3 grid: (y 130, x 150) is 8, (y 0, x 100) is 1
    assert names == ["1_0_100.png", "8_130_150.png"]
    corner = cv2.imread(str(tmp_path / "tiles" / "images" / "8_130_150.png"), cv2.IMREAD_COLOR)
    assert corner.shape == (100, 100, 3) and np.array_equal(corner, image[130:, 150:, ::-1])
    label = cv2.imread(str(tmp_path / "tiles" / "labels" / "8_130_150.png"), cv2.IMREAD_UNCHANGED)
    assert label[225 - 130, 245 - 150] == 255
    by_frame = {(r["frame_id"], r["geotag_id"]): float(r["margin_px"]) for r in rows_of(tmp_path)}
    # g2 at u = 148 lies in tile 1 (x 100..199) 48.5 px from its left edge... and 2.5 px from tile 2's (x 150)
    assert by_frame[("1", "g2")] == pytest.approx(min(148 - 99.5, 20 + 0.5), abs=0.05)
    assert by_frame[("8", "g1")] == pytest.approx(249.5 - 245, abs=0.05)
    assert summary["tiles"]["positive"] == 2 and summary["n_frames"] == 2


def test_a_target_beyond_the_border_or_on_nodata_is_not_labelled_and_its_tiles_are_skipped(tmp_path):
    grid, image = raster(300, 300)
    valid = np.ones((300, 300), bool)
    valid[240:260, 40:60] = False  # a hole in the orthomosaic
    geotags, xy = survey([at_pixel(150.0, 150.0), at_pixel(302.0, 50.0), at_pixel(50.0, 250.0)])
    summary = write_raster_labels(tmp_path, grid, ArrayReader(image, valid), geotags, xy[:, 0], xy[:, 1],
                                  RasterLabelRequest(sigma_cm=4.0, tile_size=100, negative_ratio=10))
    assert summary["geotags_outside_raster"] == ["g2"] and summary["geotags_on_nodata"] == ["g3"]
    names = {p.name for p in (tmp_path / "tiles" / "images").glob("*.png")}
    # g2 (2.5 px beyond the right border, σ 2 px: its disc reaches in) spoils tile (0, 200); g3 tile (200, 0)
    assert "2_0_200.png" not in names and "6_200_0.png" not in names
    assert summary["tiles"]["skipped"]["unlabelled_target"] == 2
    assert summary["tiles"]["positive"] == 1 and summary["tiles"]["negative"] == 6
    assert [t for t in read_targets(tmp_path).ids] == ["g1"]


def test_negatives_only_inside_the_surveyed_area_and_drawn_up_to_the_ratio(tmp_path):
    grid, image = raster(400, 400)
    geotags, xy = survey([at_pixel(50.0, 50.0), at_pixel(250.0, 50.0)])
    # the area: the top half of the raster and a quarter pixel more (a tile's outline touching it is not inside)
    x0, x1 = ORIGIN_X - 1, ORIGIN_X + 401 * PIXEL
    y_top, y_mid = ORIGIN_Y + 1, ORIGIN_Y - 200.25 * PIXEL
    ring = to_lat_lon(np.array([x0, x1, x1, x0]), np.array([y_top, y_top, y_mid, y_mid]))
    area = surveyed_area([], [], drawn=[ring])
    reader = ArrayReader(image)
    summary = write_raster_labels(tmp_path, grid, reader, geotags, xy[:, 0], xy[:, 1],
                                  RasterLabelRequest(sigma_cm=4.0, tile_size=100, negative_ratio=1.0, seed=3),
                                  surveyed=area, to_lat_lon=to_lat_lon)
    tiles = summary["tiles"]
    # 16 tiles: 2 positive (row 0); of the others 6 inside the area (rows 0-1), 8 reaching below it (rows 2-3)
    assert tiles["positive"] == 2 and tiles["skipped"]["outside_surveyed_area"] == 8
    assert tiles["negative"] == 2  # ratio 1 × 2 positives, from the 6 inside
    negatives = [p.name for p in (tmp_path / "tiles" / "images").glob("*.png")
                 if p.name not in ("0_0_0.png", "2_0_200.png")]
    assert len(negatives) == 2 and all(int(n.split("_")[1]) < 200 for n in negatives)
    for name in negatives:
        assert cv2.imread(str(tmp_path / "tiles" / "labels" / name), cv2.IMREAD_UNCHANGED).max() == 0
    tile_reads = [w for w in reader.windows if w[2] == 100]
    assert len(tile_reads) == 4  # only the tiles written were read, each once: never the whole raster
    assert summary["surveyed_area"] == {"source": "drawn", "rings": 1}


def test_sixteen_bit_values_map_through_the_range_and_the_record_is_read_back(tmp_path):
    grid, _ = raster(120, 120)
    image16 = np.full((120, 120, 3), 3000, np.uint16)

    def read(col0, row0, cols, rows):
        return np.full((3, rows, cols), 3000, np.uint16), np.ones((rows, cols), bool)

    geotags, xy = survey([at_pixel(60.0, 60.0)])
    write_raster_labels(tmp_path, grid, read, geotags, xy[:, 0], xy[:, 1],
                        RasterLabelRequest(sigma_cm=4.0, tile_size=100, negative_ratio=0),
                        value_range=[(1000.0, 5000.0)], raster={"source": "ortho.tif", "crs": "EPSG:32631"})
    tile = cv2.imread(str(tmp_path / "tiles" / "images" / "0_0_0.png"), cv2.IMREAD_COLOR)
    assert image16.dtype == np.uint16 and np.all(tile == round(255 * 2000 / 4000))
    record = raster_record(tmp_path)
    assert record["gsd_cm"] == pytest.approx(2.0) and record["source"] == "ortho.tif"
    assert record["tile_diagonal_m"] == pytest.approx(100 * np.sqrt(2) * 0.02, abs=1e-4)
    assert json.loads((tmp_path / "summary.json").read_text())["tiles"]["size"] == 100


def test_a_geotag_without_a_map_position_is_refused_by_its_row(tmp_path):
    grid, image = raster()
    geotags, xy = survey([at_pixel(10.0, 10.0), at_pixel(20.0, 20.0)])
    xy[1, 0] = np.nan
    with pytest.raises(InputError, match="row 2"):
        write_raster_labels(tmp_path, grid, ArrayReader(image), geotags, xy[:, 0], xy[:, 1],
                            RasterLabelRequest(sigma_cm=4.0, tile_size=100))


def test_hard_negative_tiles_come_first_and_no_tile_near_an_unresolved_cluster(tmp_path):
    grid, image = raster(400, 400)  # 16 tiles of 100 px
    geotags, xy = survey([at_pixel(50.0, 50.0)])
    hard = np.array([at_pixel(350.0, 350.0), at_pixel(150.0, 350.0)]).T  # tiles 15 (300, 300) and 13 (300, 100)
    unresolved = np.array([at_pixel(299.0, 199.0)]).T  # 0.5 px from a tile corner (299.5, 199.5)
    summary = write_raster_labels(tmp_path, grid, ArrayReader(image), geotags, xy[:, 0], xy[:, 1],
                                  RasterLabelRequest(sigma_cm=4.0, tile_size=100, negative_ratio=2.0, seed=5),
                                  hard_negatives=hard, unresolved=unresolved)
    names = {p.name for p in (tmp_path / "tiles" / "images").glob("*.png")}
    assert names == {"0_0_0.png", "13_300_100.png", "15_300_300.png"}  # the two negatives allowed are the hard ones
    tiles = summary["tiles"]
    assert tiles["hard_negative"] == 2 and tiles["negative"] == 2
    # within 3σ = 6 px of (299, 199): the four tiles meeting at that corner, (y0, x0) = (100 or 200, 200 or 300)
    assert tiles["skipped"]["unlabelled_target"] == 4
    assert summary["hard_negatives"] == {"n_clusters": 2, "n_in_raster": 2} and summary["n_unresolved_in_raster"] == 1

"""birdseye:writelabelsraster through the registry: a GeoTIFF written by GDAL and a geotag layer in WGS84 in, the
label folder Train detector reads out. Each target's pixel is checked with GDAL's geotransform (not ours)."""
from __future__ import annotations

import csv
import json
from pathlib import Path

import cv2
import numpy as np
import pytest
from osgeo import gdal
from qgis.core import (
    QgsApplication,
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsField,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingContext,
    QgsProcessingException,
    QgsProject,
    QgsVectorLayer,
)
from qgis.PyQt.QtCore import QVariant
from raster_scene import map_of, write_geotiff

from birdseye.birdseye_qgis.core.labels.training_set import read_targets
from birdseye.birdseye_qgis.core.train.job import Source

pytestmark = pytest.mark.usefixtures("birdseye_provider")
#: Target pixels (col, row) in the 400 × 300 px raster at 1 cm/px.
TARGETS = [(50.3, 60.7), (250.0, 120.5), (380.2, 280.0)]


def run(params):
    import processing

    return processing.run("birdseye:writelabelsraster", params)


def geotag_layer(path, pixels, height=31.5):
    """Points at the GeoTIFF's pixels (GDAL's geotransform), in WGS84, with an id and an ellipsoidal height."""
    layer = QgsVectorLayer("PointZ?crs=EPSG:4326", "geotags", "memory")
    layer.dataProvider().addAttributes([QgsField("id", QVariant.String), QgsField("h_ellipsoid", QVariant.Double)])
    layer.updateFields()
    to_wgs84 = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:32756"),
                                      QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    for k, (col, row) in enumerate(pixels):
        point = to_wgs84.transform(QgsPointXY(*map_of(path, col, row)))
        feature = QgsFeature(layer.fields())
        feature.setGeometry(QgsGeometry.fromPointXY(point))
        feature["id"], feature["h_ellipsoid"] = f"T{k + 1}", height
        layer.dataProvider().addFeature(feature)
    return layer


@pytest.fixture
def orthomosaic(tmp_path):
    rng = np.random.default_rng(4)
    bands = [rng.integers(50, 200, (300, 400)).astype(np.uint8) for _ in range(3)]
    return write_geotiff(tmp_path / "ortho.tif", bands), bands


def test_targets_land_at_gdals_pixels_and_train_detector_reads_the_folder(orthomosaic, tmp_path):
    path, bands = orthomosaic
    out = tmp_path / "labels"
    result = run({"RASTER": path, "GEOTAGS": geotag_layer(path, TARGETS), "SIGMA_CM": 3.0, "TILE_SIZE": 100,
                  "NEGATIVE_RATIO": 1.0, "SURVEY_MARGIN_M": 5.0, "OUTPUT_FOLDER": str(out)})
    assert result["SIGMA_USED_PX"] == pytest.approx(3.0) and result["GEOTAGS_NOT_LABELLED"] == 0
    with open(out / "labels.csv", newline="", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if float(r["margin_px"]) >= 0]  # the rows of each target's own tile
    placed = {r["geotag_id"]: (float(r["u"]), float(r["v"])) for r in rows}
    for k, (col, row) in enumerate(TARGETS):
        assert placed[f"T{k + 1}"] == pytest.approx((col, row), abs=0.01)
    # the tile of T2 (col 250, row 120.5: x0 200, y0 100 on the 4 × 3 grid of 100 px tiles → frame 1·4 + 2 = 6)
    image = cv2.imread(str(out / "tiles" / "images" / "6_100_200.png"), cv2.IMREAD_COLOR)
    assert np.array_equal(image[..., ::-1], np.dstack(bands)[100:200, 200:300])
    label = cv2.imread(str(out / "tiles" / "labels" / "6_100_200.png"), cv2.IMREAD_UNCHANGED)
    assert label[20, 50] == round(255 * np.exp(-0.5 ** 2 / (2 * 3.0 ** 2)))  # 0.5 px from (250, 120.5)
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["raster"]["gsd_cm"] == pytest.approx(1.0) and summary["raster"]["crs"] == "EPSG:32756"
    assert summary["tiles"]["positive"] == result["POSITIVE_TILES"] == 3
    assert result["NEGATIVE_TILES"] == 3
    targets = read_targets(out)
    assert sorted(targets.ids) == ["T1", "T2", "T3"] and np.allclose(targets.height, 31.5)
    assert set(Source(str(out)).gsd_of().values()) == {1.0}  # Train detector's GSD, with no frame layer
    train = QgsApplication.processingRegistry().createAlgorithmById("birdseye:traindetector")
    (source,) = train._sources({"LABELS": [str(out)]}, QgsProcessingContext(), [out])  # neither FRAMES nor GSD_CM
    assert source.frames is None and set(source.gsd_of().values()) == {1.0}


def test_sixteen_bit_bands_take_the_value_range_and_a_geotag_outside_is_named(tmp_path):
    band = np.full((300, 400), 3000, np.uint16)
    path = write_geotiff(tmp_path / "ortho16.tif", [band] * 3, dtype=gdal.GDT_UInt16)
    result = run({"RASTER": path, "GEOTAGS": geotag_layer(path, TARGETS[:1] + [(420.0, 10.0)]), "SIGMA_CM": 3.0,
                  "TILE_SIZE": 100, "NEGATIVE_RATIO": 0.0, "VALUE_RANGE": [1000, 5000],
                  "OUTPUT_FOLDER": str(tmp_path / "out")})
    image = cv2.imread(str(Path(tmp_path / "out" / "tiles" / "images" / "0_0_0.png")), cv2.IMREAD_COLOR)
    assert np.all(image == round(255 * 2000 / 4000))
    summary = json.loads((tmp_path / "out" / "summary.json").read_text(encoding="utf-8"))
    assert summary["geotags_outside_raster"] == ["T2"] and result["GEOTAGS_NOT_LABELLED"] == 1


def test_a_raster_in_degrees_is_refused(tmp_path):
    band = np.zeros((50, 50), np.uint8)
    path = write_geotiff(tmp_path / "deg.tif", [band] * 3, epsg=4326, pixel=1e-6, origin=(150.0, -30.0))
    with pytest.raises(QgsProcessingException, match="degrees"):
        run({"RASTER": path, "GEOTAGS": geotag_layer(tmp_path / "deg.tif", []), "OUTPUT_FOLDER": str(tmp_path / "o")})


def test_a_review_adds_its_targets_hard_negatives_first_and_no_tile_near_an_unresolved_cluster(tmp_path):
    """The review scene of test_review_loop (clusters A–F around a site in EPSG:32756) on a 20 × 20 m raster at
    2 cm/px whose top-left corner is 10 m west and north of the site."""
    from test_cluster_algorithms import frame_layer, geotag_layer, utm_of
    from test_review_loop import SPOTS, UNRESOLVED, scene

    x0, y0, _ = utm_of((-10.0, 10.0))
    band = np.full((1000, 1000), 90, np.uint8)
    path = write_geotiff(tmp_path / "site.tif", [band] * 3, pixel=0.02, origin=(float(x0[0]), float(y0[0])))
    det, verdicts = scene()
    out = tmp_path / "labels"
    result = run({"RASTER": path, "GEOTAGS": geotag_layer(), "SIGMA_CM": 10.0, "TILE_SIZE": 100,
                  "NEGATIVE_RATIO": 1.0, "SURVEY_MARGIN_M": 20.0, "REVIEW": verdicts, "REVIEW_DETECTIONS": [det],
                  "REVIEW_FRAMES": [frame_layer()], "OUTPUT_FOLDER": str(out)})
    assert (result["REVIEW_TARGETS"], result["HARD_NEGATIVES"]) == (1, 1)
    with open(out / "labels.csv", newline="", encoding="utf-8") as f:
        rows = [r for r in csv.DictReader(f) if float(r["margin_px"]) >= 0]
    review = next(r for r in rows if r["provenance"] == "review")
    gt = gdal.Open(path).GetGeoTransform()
    bx, by, _ = utm_of(SPOTS["B"])  # the cluster's centroid, at GDAL's pixel
    assert (float(review["u"]), float(review["v"])) == pytest.approx(
        ((bx[0] - gt[0]) / gt[1] - 0.5, (by[0] - gt[3]) / gt[5] - 0.5), abs=0.05)
    summary = json.loads((out / "summary.json").read_text(encoding="utf-8"))
    assert summary["provenance"]["review"] == {"n_targets": 1, "n_in_view": 1}
    assert summary["geotags_outside_raster"] == [3]  # 15 m east of the site
    # C's tile (its centroid 16 m east and 7 m south of the corner: col ≈ 800, row ≈ 350) is the hard one, first
    assert summary["tiles"]["hard_negative"] == 1 and summary["tiles"]["negative"] == summary["tiles"]["positive"]
    written = [p.name for p in (out / "tiles" / "images").glob("*.png")]
    cx, cy, _ = utm_of(SPOTS["C"])
    c_col, c_row = (cx[0] - gt[0]) / gt[1] - 0.5, (cy[0] - gt[3]) / gt[5] - 0.5
    tile_c = f"{int(c_row // 100) * 10 + int(c_col // 100)}_{int(c_row // 100) * 100}_{int(c_col // 100) * 100}.png"
    assert tile_c in written
    # no written tile lies within 3σ = 15 px of an unresolved cluster
    for name in UNRESOLVED:
        ux, uy, _ = utm_of(SPOTS[name])
        u, v = (ux[0] - gt[0]) / gt[1] - 0.5, (uy[0] - gt[3]) / gt[5] - 0.5
        for tile in written:
            ty, tx = (int(k) for k in tile[:-4].split("_")[1:])
            du, dv = max(tx - 0.5 - u, u - (tx + 99.5), 0.0), max(ty - 0.5 - v, v - (ty + 99.5), 0.0)
            assert np.hypot(du, dv) > 15.0, (name, tile)

"""birdseye:detectraster through the registry: GeoTIFFs written by GDAL in, detections on the map out.

The model's heatmap is the image itself (``raster_scene.identity_model``), so every detection is where a hump
was painted: its map position is checked with the GeoTIFF's own geotransform (GDAL's, not ours).
"""
from __future__ import annotations

import numpy as np
import pytest
from osgeo import gdal
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsFeature,
    QgsGeometry,
    QgsPointXY,
    QgsProcessingException,
    QgsProject,
    QgsRasterLayer,
    QgsVectorLayer,
)
from raster_scene import ORIGIN, PIXEL_M, TARGETS, humps, identity_model, map_of, rgba_orthomosaic, write_geotiff
from test_cluster_algorithms import frame_layer, point_layer, utm_of

pytestmark = pytest.mark.usefixtures("birdseye_provider")


def run(params):
    import processing

    return processing.run("birdseye:detectraster", params)


def targets_found(result):
    """The TARGETS the detections lie on (within 0.3 px), each once, and no other detection."""
    found = detections(result)
    on = [next(t for t in TARGETS if abs(f["u"] - t[0]) < 0.3 and abs(f["v"] - t[1]) < 0.3) for f in found]
    assert len(set(on)) == len(on)
    return sorted(on)


def detections(result):
    layer = QgsVectorLayer(result["OUTPUT"], "d", "ogr") if isinstance(result["OUTPUT"], str) else result["OUTPUT"]
    return [f for f in layer.getFeatures()]


@pytest.fixture
def rgba_ortho(tmp_path):
    """An 8-bit RGBA orthomosaic, 1200 × 640 px at 1 cm, transparent over the last target."""
    return rgba_orthomosaic(tmp_path / "ortho.tif")


def test_an_orthomosaic_gives_one_detection_per_target_where_gdal_puts_it(rgba_ortho, tmp_path):
    model = identity_model(tmp_path / "m.onnx")
    result = run({"RASTER": rgba_ortho, "MODEL": model, "OUTPUT": str(tmp_path / "det.gpkg")})
    found = detections(result)
    kept = TARGETS[:-1]  # the last one is transparent
    assert result["DETECTION_COUNT"] == len(found) == len(kept) and result["WINDOWS_READ"] >= 4
    for u, v in kept:
        x, y = map_of(rgba_ortho, u, v)
        near = [f for f in found if abs(f["u"] - u) < 0.2 and abs(f["v"] - v) < 0.2]
        assert len(near) == 1, (u, v)
        point = near[0].geometry().constGet()
        assert point.x() == pytest.approx(x, abs=0.2 * PIXEL_M) and point.y() == pytest.approx(y, abs=0.2 * PIXEL_M)
        assert near[0]["ground"] == "raster" and near[0]["height_ref"] == "unknown" and near[0]["frame_id"] == 0
        assert near[0]["dem_source"].endswith("ortho.tif") and near[0]["threshold"] == pytest.approx(0.3)


def test_sixteen_bit_single_band_rasters_are_stretched_from_their_statistics(tmp_path):
    img = (humps(700, 300, TARGETS[:2], amplitude=1.0) * 3000 + 800).astype(np.uint16)
    path = write_geotiff(tmp_path / "ms.tif", [img], dtype=gdal.GDT_UInt16)
    model = identity_model(tmp_path / "m.onnx", threshold=0.5)
    result = run({"RASTER": path, "MODEL": model, "OUTPUT": str(tmp_path / "d16.gpkg")})
    found = detections(result)
    assert sorted(round(f["u"]) for f in found) == [60, 544]
    # A range given: a range that leaves the humps below the threshold finds nothing.
    result = run({"RASTER": path, "MODEL": model, "VALUE_RANGE": [0, 65535], "OUTPUT": str(tmp_path / "e.gpkg")})
    assert result["DETECTION_COUNT"] == 0


def test_a_mask_and_an_extent_keep_their_inside_only(rgba_ortho, tmp_path):
    model = identity_model(tmp_path / "m.onnx")
    mask = QgsVectorLayer("Polygon?crs=EPSG:4326", "field", "memory")  # another CRS than the raster's
    to_wgs84 = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:32756"),
                                      QgsCoordinateReferenceSystem("EPSG:4326"), QgsProject.instance())
    x0, y0 = map_of(rgba_ortho, 0, 0)
    x1, y1 = map_of(rgba_ortho, 600, 300)
    corners = [to_wgs84.transform(QgsPointXY(x, y)) for x, y in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]
    feature = QgsFeature()
    feature.setGeometry(QgsGeometry.fromPolygonXY([corners]))
    mask.dataProvider().addFeatures([feature])
    result = run({"RASTER": rgba_ortho, "MODEL": model, "MASK": mask, "OUTPUT": str(tmp_path / "m.gpkg")})
    assert targets_found(result) == sorted(TARGETS[:2])
    assert result["WINDOWS_READ"] < 6
    extent = f"{ORIGIN[0]},{ORIGIN[0] + 6.0},{ORIGIN[1] - 6.0},{ORIGIN[1]} [EPSG:32756]"
    result = run({"RASTER": rgba_ortho, "MODEL": model, "EXTENT": extent, "OUTPUT": str(tmp_path / "x.gpkg")})
    assert targets_found(result) == sorted(TARGETS[:2] + TARGETS[3:4])


def test_a_raster_in_degrees_is_refused_saying_how_to_reproject(tmp_path):
    img = np.zeros((50, 50), np.uint8)
    path = write_geotiff(tmp_path / "deg.tif", [img, img, img], epsg=4326, pixel=1e-7, origin=(151.0, -27.0))
    assert QgsRasterLayer(path, "deg").isValid()
    with pytest.raises(QgsProcessingException, match="degrees.*Warp"):
        run({"RASTER": path, "MODEL": identity_model(tmp_path / "m.onnx"), "OUTPUT": "memory:"})


def test_two_bands_need_to_be_told_which_feed_the_model(tmp_path):
    img = np.zeros((50, 50), np.uint8)
    path = write_geotiff(tmp_path / "two.tif", [img, img])
    model = identity_model(tmp_path / "m.onnx")
    with pytest.raises(QgsProcessingException, match="2 bands.*BANDS"):
        run({"RASTER": path, "MODEL": model, "OUTPUT": "memory:"})
    assert run({"RASTER": path, "MODEL": model, "BANDS": [2], "OUTPUT": "memory:"})["DETECTION_COUNT"] == 0


def test_cluster_and_evaluate_count_the_geotags_the_raster_covers(rgba_ortho, tmp_path):
    """Geotags on every painted target and one 40 m east, off the raster: the transparent target and the far one
    are not in view; each of the 5 detections is a cluster by itself (a raster shows a target once) on a geotag."""
    import processing
    from qgis.core import QgsField
    from qgis.PyQt.QtCore import QVariant

    detections_path = run({"RASTER": rgba_ortho, "MODEL": identity_model(tmp_path / "m.onnx"),
                           "OUTPUT": str(tmp_path / "det.gpkg")})["OUTPUT"]
    xy = [map_of(rgba_ortho, u, v) for u, v in TARGETS] + [map_of(rgba_ortho, 600.0, 300.0)]
    xy[-1] = (xy[-1][0] + 40.0, xy[-1][1])
    site_x, site_y = (float(v[0]) for v in utm_of([(0.0, 0.0)])[:2])
    en = [(x - site_x, y - site_y) for x, y in xy]  # near the site, the local offsets are the UTM ones to < 1 mm
    geotags = point_layer("geotags", [QgsField("id", QVariant.Int), QgsField("label", QVariant.String)],
                          [[k + 1, "burrow"] for k in range(len(en))], en)
    clusters = processing.run("birdseye:clusterdetections", {"DETECTIONS": detections_path, "GEOTAGS": geotags,
                                                             "OUTPUT": "memory:"})
    assert (clusters["CLUSTER_COUNT"], clusters["HIT_COUNT"]) == (5, 5)
    scores = processing.run("birdseye:evaluatedetections", {
        "DETECTIONS": [detections_path], "GEOTAGS": geotags, "FRAMES": [frame_layer()],
        "OUTPUT_JSON": str(tmp_path / "e.json")})
    assert (scores["N_IN_VIEW"], scores["N_RECOVERED"], scores["N_CLUSTERS"], scores["N_HIT_CLUSTERS"]) == (5, 5, 5, 5)
    # An orthomosaic user has no frame layer: the raster alone says which geotags are in view.
    mosaic_only = processing.run("birdseye:evaluatedetections", {
        "DETECTIONS": [detections_path], "GEOTAGS": geotags, "OUTPUT_JSON": str(tmp_path / "m.json")})
    assert {k: mosaic_only[k] for k in ("N_IN_VIEW", "N_RECOVERED", "N_CLUSTERS", "N_HIT_CLUSTERS")} == \
        {k: scores[k] for k in ("N_IN_VIEW", "N_RECOVERED", "N_CLUSTERS", "N_HIT_CLUSTERS")}


def test_a_windowed_read_holds_gdals_block_cache_and_gives_it_back():
    """Each block is read once, so the cache is held small while reading (its default, 5 % of the RAM, was most
    of the peak memory on a 20,000 × 20,000 px raster), and a smaller cache than the bound is left alone."""
    from osgeo import gdal

    from birdseye.birdseye_qgis.qgis_io.raster_reader import WINDOWED_READ_CACHE_MB, bounded_block_cache

    before = gdal.GetCacheMax()
    try:
        gdal.SetCacheMax(4 * WINDOWED_READ_CACHE_MB * 1024 * 1024)
        with bounded_block_cache():
            assert gdal.GetCacheMax() == WINDOWED_READ_CACHE_MB * 1024 * 1024
        assert gdal.GetCacheMax() == 4 * WINDOWED_READ_CACHE_MB * 1024 * 1024
        gdal.SetCacheMax(64 * 1024 * 1024)
        with bounded_block_cache():
            assert gdal.GetCacheMax() == 64 * 1024 * 1024
        with pytest.raises(RuntimeError), bounded_block_cache(1):
            raise RuntimeError("a failed run gives the cache back too")
        assert gdal.GetCacheMax() == 64 * 1024 * 1024
    finally:
        gdal.SetCacheMax(before)

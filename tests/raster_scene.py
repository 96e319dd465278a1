"""An orthomosaic made for tests, and a model that finds what is painted on it: shared by the suites that detect on
a raster (tests/qgis/test_detect_raster.py, test_write_labels_raster.py) and review what was found there
(tests/gui/test_review_dock.py).

The raster is a GeoTIFF written by GDAL in UTM zone 56 S, its top-left corner at the site near Dalby; the model's
heatmap is the image itself (:func:`identity_model`), so every detection is where a hump was painted.
"""
from __future__ import annotations

import numpy as np
import onnx
from onnx import TensorProto, helper
from osgeo import gdal, osr

from birdseye.birdseye_qgis.core.detect.model_metadata import ModelMetadata, embed_metadata
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame, ProjectedCRS

#: The site of the synthetic surveys (tests/qgis/test_cluster_algorithms.py's SITE) and its UTM zone.
SITE = LocalFrame(-27.55, 151.95, 400.0)
UTM_EPSG = 32756
#: The top-left corner of the test rasters: the site, floored to the metre, in EPSG:32756.
ORIGIN = tuple(float(np.floor(v[0])) for v in ProjectedCRS(UTM_EPSG).from_geodetic(np.array([SITE.lat0]),
                                                                                      np.array([SITE.lon0])))
PIXEL_M = 0.01


def identity_model(path, threshold=0.3, **changes):
    """Heatmap = mean of the channels / 255 (a 1×1 convolution), 1 cm/px, 64 px tiles."""
    x = helper.make_tensor_value_info("image", TensorProto.FLOAT, ["n", 3, "h", "w"])
    y = helper.make_tensor_value_info("heat", TensorProto.FLOAT, ["n", 1, "h", "w"])
    w = helper.make_tensor("k", TensorProto.FLOAT, [1, 3, 1, 1], [1 / 3] * 3)
    graph = helper.make_graph([helper.make_node("Conv", ["image", "k"], ["heat"])], "g", [x], [y], [w])
    # IR 8 is opset 17's: left to itself, a newer onnx stamps its own IR version, which onnxruntime
    # releases older than it refuse (onnx 1.20 writes 13, onnxruntime 1.20 reads up to 10).
    model = helper.make_model(graph, opset_imports=[helper.make_opsetid("", 17)], ir_version=8)
    embed_metadata(model, ModelMetadata(**{**dict(resolution_cm=1.0, tile_size=64, tiles_overlap_pct=12.5,
                                                  output_kind="probability", default_threshold=threshold), **changes}))
    onnx.save(model, str(path))
    return str(path)


def humps(width, height, centres, sigma=2.5, amplitude=0.9):
    yy, xx = np.mgrid[0:height, 0:width]
    img = np.zeros((height, width))
    for u, v in centres:
        img = np.maximum(img, amplitude * np.exp(-((xx - u) ** 2 + (yy - v) ** 2) / (2 * sigma ** 2)))
    return img


def write_geotiff(path, bands, epsg=UTM_EPSG, dtype=gdal.GDT_Byte, alpha=None, pixel=PIXEL_M, origin=ORIGIN):
    """A GeoTIFF (tiled, as orthomosaics are) with ``bands`` (list of 2-D arrays), an optional alpha band."""
    height, width = bands[0].shape
    count = len(bands) + (alpha is not None)
    ds = gdal.GetDriverByName("GTiff").Create(str(path), width, height, count, dtype, ["TILED=YES"])
    ds.SetGeoTransform((origin[0], pixel, 0.0, origin[1], 0.0, -pixel))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(epsg)
    ds.SetProjection(srs.ExportToWkt())
    for k, band in enumerate(bands):
        ds.GetRasterBand(k + 1).WriteArray(band)
    if alpha is not None:
        ds.GetRasterBand(count).WriteArray(alpha)
        ds.GetRasterBand(count).SetColorInterpretation(gdal.GCI_AlphaBand)
    ds.FlushCache()
    ds = None
    return str(path)


def map_of(path, col, row):
    """GDAL's geotransform applied to pixel centres."""
    gt = gdal.Open(str(path)).GetGeoTransform()
    return gt[0] + (col + 0.5) * gt[1], gt[3] + (row + 0.5) * gt[5]


# Window seams of the default windows (8 tiles of 64 px, a tile of overlap) lie near 544 and 1024 px.
TARGETS = [(60.0, 70.0), (543.5, 200.0), (1023.5, 120.0), (300.0, 543.5), (800.0, 400.0), (1100.0, 560.0)]


def rgba_orthomosaic(path):
    """An 8-bit RGBA orthomosaic, 1200 × 640 px at 1 cm, a hump on each of :data:`TARGETS`, transparent over the
    last target."""
    img = np.rint(255 * humps(1200, 640, TARGETS)).astype(np.uint8)
    alpha = np.full(img.shape, 255, np.uint8)
    alpha[540:640, 1040:1200] = 0
    return write_geotiff(path, [img, img, img], alpha=alpha)

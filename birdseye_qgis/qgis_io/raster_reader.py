"""A QGIS raster layer read window by window for :mod:`..core.detect.raster_detect` and the review's chips.

Pixels are read through the layer's data provider (``QgsRasterDataProvider.block``) on the raster's own pixel
grid — never resampled by the provider, never the whole band: each call reads the bands asked for over one
window, clipped to the raster, and pads the rest as invalid.
"""
from __future__ import annotations

import threading
from contextlib import contextmanager

import numpy as np
from qgis.core import (
    QgsCoordinateReferenceSystem,
    QgsCoordinateTransform,
    QgsPointXY,
    QgsRasterBandStats,
    QgsRasterLayer,
    QgsRectangle,
    QgsUnitTypes,
)

from ..core.detect.raster_detect import RasterGrid, to_8bit
from ..core.errors import InputError
from ..core.review.chips import RasterIndex
from ..qgis_enums import DISTANCE_METERS

#: numpy types of QGIS's raster data types (``Qgis.DataType``'s values, the same in QGIS 3.22 to 3.44).
_NUMPY_TYPES = {1: np.uint8, 2: np.uint16, 3: np.int16, 4: np.uint32, 5: np.int32, 6: np.float32, 7: np.float64,
                14: np.int8}

#: GDAL's block cache (MB) while a raster is read window by window: each block is read once, so a larger cache
#: only grows (GDAL's default, 5 % of the RAM, made most of the peak memory on a 20,000 × 20,000 px raster).
WINDOWED_READ_CACHE_MB = 256


@contextmanager
def bounded_block_cache(limit_mb: int = WINDOWED_READ_CACHE_MB):
    """Hold GDAL's block cache (process-wide) to at most ``limit_mb`` while the block runs, then restore it; a
    smaller cache is left as it is."""
    from osgeo import gdal

    before = gdal.GetCacheMax()
    limit = int(limit_mb) * 1024 * 1024
    if before > limit:
        gdal.SetCacheMax(limit)
    try:
        yield
    finally:
        if before > limit:
            gdal.SetCacheMax(before)


def raster_grid(layer) -> RasterGrid:
    """The pixel grid of a north-up raster layer in a projected CRS; an unprojected one is refused, saying how
    to reproject it."""
    crs = layer.crs()
    if not crs.isValid():
        raise InputError("the raster has no coordinate reference system: set it (Layer Properties › Source)",
                         source=layer.source())
    if crs.isGeographic():
        raise InputError(f"the raster is in {crs.authid() or crs.description()}, whose units are degrees: pixels "
                         "then have no one size on the ground. Reproject it to a projected CRS in metres (the UTM "
                         "zone of the field) with Raster › Projections › Warp (Reproject), and run this again",
                         source=layer.source())
    extent = layer.extent()
    unit_factor = QgsUnitTypes.fromUnitToUnitFactor(crs.mapUnits(), DISTANCE_METERS)
    return RasterGrid(layer.width(), layer.height(), extent.xMinimum(), extent.yMaximum(),
                      layer.rasterUnitsPerPixelX(), layer.rasterUnitsPerPixelY(), unit_factor)


def band_choice(layer, bands) -> list[int]:
    """The bands that feed the model's red, green and blue (1-based): ``bands`` as given (three, or one for all
    three), else 1, 2, 3 of a raster with three or more bands and band 1 three times of a single-band one."""
    count = layer.bandCount()
    bands = [int(b) for b in (bands or [])]
    if not bands:
        if count >= 3:
            return [1, 2, 3]
        if count == 1:
            return [1, 1, 1]
        raise InputError(f"the raster has {count} bands: say which feed the model's red, green and blue (BANDS)",
                         source=layer.source(), field="BANDS")
    if len(bands) == 1:
        bands = bands * 3
    if len(bands) != 3:
        raise InputError(f"{len(bands)} bands given: the model reads three (red, green, blue), or give one band "
                         "for all three", field="BANDS")
    wrong = [b for b in bands if not 1 <= b <= count]
    if wrong:
        raise InputError(f"band {wrong[0]} does not exist: the raster has {count}", source=layer.source(),
                         field="BANDS")
    return bands


def needs_value_range(layer, bands) -> bool:
    """Whether the bands are anything but 8-bit unsigned (their values need a range to become 0..255)."""
    provider = layer.dataProvider()
    return any(_NUMPY_TYPES.get(int(provider.dataType(b))) is not np.uint8 for b in set(bands))


def statistics_value_range(layer, bands, extent=None, sample_size: int = 250_000) -> list[tuple[float, float]]:
    """Per band, the 2 % and 98 % cumulative cut of its values (QGIS's own default stretch), from a sample
    of the raster (or ``extent``): what an orthomosaic's 16-bit values map to 0..255 by. Where the cut is one
    value (a band of mostly one background value), its minimum and maximum instead."""
    provider = layer.dataProvider()
    area = extent or QgsRectangle()
    out = []
    for b in bands:
        low, high = provider.cumulativeCut(b, 0.02, 0.98, area, sample_size)
        if not high > low:
            stats = provider.bandStatistics(b, QgsRasterBandStats.Min | QgsRasterBandStats.Max, area, sample_size)
            low, high = stats.minimumValue, stats.maximumValue
        if not high > low:
            raise InputError(f"band {b} holds one value ({low:g}) over the area: nothing to detect on",
                             source=layer.source(), field="BANDS")
        out.append((float(low), float(high)))
    return out


class ProviderWindows:
    """``read(col0, row0, cols, rows)`` of :data:`..core.detect.raster_detect.ReadWindow` over a raster layer's
    provider: the bands in ``bands`` order; pixels at a band's no-data value, or transparent in an alpha band,
    invalid."""

    def __init__(self, layer, grid: RasterGrid, bands):
        self.provider = layer.dataProvider().clone()  # a provider of its own: reads may run off the main thread
        self.grid, self.bands = grid, list(bands)
        self.alpha = [b for b in range(1, self.provider.bandCount() + 1)
                      if self.provider.colorInterpretationName(b) == "Alpha"]
        self.dtypes = {}
        for b in set(self.bands) | set(self.alpha):
            dtype = _NUMPY_TYPES.get(int(self.provider.dataType(b)))
            if dtype is None:
                raise InputError(f"band {b}'s data type ({self.provider.dataType(b)}) is not a plain number type",
                                 source=layer.source(), field="BANDS")
            self.dtypes[b] = dtype

    def _band(self, b: int, extent, cols: int, rows: int) -> np.ndarray:
        block = self.provider.block(b, extent, cols, rows)
        if not block.isValid():
            raise InputError(f"band {b} could not be read over {cols} × {rows} px at {extent.toString(2)}",
                             source=self.provider.dataSourceUri())
        return np.frombuffer(bytes(block.data()), dtype=self.dtypes[b]).reshape(rows, cols)

    def __call__(self, col0: int, row0: int, cols: int, rows: int):
        grid = self.grid
        dtype = np.result_type(*self.dtypes.values())
        planes = np.zeros((3, rows, cols), dtype=dtype)
        valid = np.zeros((rows, cols), dtype=bool)
        c0, r0 = max(col0, 0), max(row0, 0)
        c1, r1 = min(col0 + cols, grid.width), min(row0 + rows, grid.height)
        if c1 <= c0 or r1 <= r0:
            return planes, valid
        extent = QgsRectangle(grid.origin_x + c0 * grid.pixel_x, grid.origin_y - r1 * grid.pixel_y,
                              grid.origin_x + c1 * grid.pixel_x, grid.origin_y - r0 * grid.pixel_y)
        inside = np.ones((r1 - r0, c1 - c0), dtype=bool)
        read = {b: self._band(b, extent, c1 - c0, r1 - r0) for b in set(self.bands) | set(self.alpha)}
        for b in set(self.bands):
            if self.provider.sourceHasNoDataValue(b) and self.provider.useSourceNoDataValue(b):
                inside &= read[b] != self.provider.sourceNoDataValue(b)
        for b in self.alpha:  # an orthomosaic's alpha band (OpenDroneMap's RGBA): transparent is no data
            inside &= read[b] > 0
        for k, b in enumerate(self.bands):
            planes[k, r0 - row0:r1 - row0, c0 - col0:c1 - col0] = read[b]
        valid[r0 - row0:r1 - row0, c0 - col0:c1 - col0] = inside
        return planes, valid


def _recorded_raster(source: str, why: str):
    """The raster layer raster detections record (``dem_source``); gone or unreadable, it is refused, naming it."""
    layer = QgsRasterLayer(source, "raster")
    if not layer.isValid():
        raise InputError(f"the raster these detections were found on cannot be opened (moved or deleted?): {why}",
                         source=source)
    return layer


def _pixels_of(layer, grid: RasterGrid, lat, lon, transform_context) -> tuple[np.ndarray, np.ndarray]:
    """Raster pixels (col, row; pixel-centre convention, fractional) of WGS84 points ``lat``, ``lon``."""
    to_raster = QgsCoordinateTransform(QgsCoordinateReferenceSystem("EPSG:4326"), layer.crs(), transform_context)
    points = [to_raster.transform(QgsPointXY(float(lo), float(la))) for la, lo in zip(lat, lon)]
    return grid.to_pixel([p.x() for p in points], [p.y() for p in points])


def covered_geotags(source: str, lat, lon, transform_context) -> np.ndarray:
    """Which points (WGS84 ``lat``, ``lon``) lie on valid pixels of the raster at ``source`` — inside it and
    valid as :class:`ProviderWindows` reads them (band 1's no-data value, an alpha band): the geotags a mosaic
    could show. The raster is the one raster detections record (``dem_source``); gone or unreadable, it is
    refused, naming it."""
    layer = _recorded_raster(source, "the geotags it covers are counted from it")
    grid = raster_grid(layer)
    read = ProviderWindows(layer, grid, [1])
    cols, rows = _pixels_of(layer, grid, lat, lon, transform_context)
    out = np.zeros(len(cols), dtype=bool)
    for k, (c, r) in enumerate(zip(cols.tolist(), rows.tolist())):
        out[k] = bool(read(int(np.floor(c + 0.5)), int(np.floor(r + 0.5)), 1, 1)[1][0, 0])  # outside: invalid
    return out


#: What a chip shows where the raster has no valid pixel (no data, transparent, off the raster): the grey of
#: an "image missing" chip, so it is not mistaken for dark ground.
NO_DATA_BGR = (90, 90, 90)


class RasterPixels:
    """The raster detections were found on, as the review's chips read it: :meth:`to_pixel` places WGS84 points on
    its pixels (main thread: it transforms coordinates), :meth:`index` is the chip planning's
    :class:`..core.review.chips.RasterIndex`, and :meth:`window` reads one chip plan's window — that window alone,
    through :class:`ProviderWindows` — as 8-bit BGR, the bands Detect targets on a raster reads by default (1, 2,
    3, or band 1 for all three) mapped to 0..255 as it maps them (16-bit: the bands' 2–98 % cut)."""

    def __init__(self, source: str, transform_context):
        layer = _recorded_raster(source, "the review's chips are cut from it")
        self.source, self.grid = source, raster_grid(layer)
        self._layer, self._context = layer, transform_context
        bands = band_choice(layer, None)
        self.value_range = statistics_value_range(layer, bands) if needs_value_range(layer, bands) else None
        self._read = ProviderWindows(layer, self.grid, bands)
        # The chip loader's two worker threads share this reader's provider, which reads one block at a time.
        self._lock = threading.Lock()

    def to_pixel(self, lat, lon) -> tuple[np.ndarray, np.ndarray]:
        """The raster pixels (col, row) of WGS84 points (main thread only)."""
        return _pixels_of(self._layer, self.grid, lat, lon, self._context)

    def index(self, geotags) -> RasterIndex:
        """The chip planning's view of the raster with ``geotags`` placed on its pixels (main thread only)."""
        cols, rows = self.to_pixel(geotags.lat, geotags.lon)
        return RasterIndex(self.source, self.grid.width, self.grid.height, np.column_stack([cols, rows]),
                           [str(i) for i in geotags.ids])

    def window(self, plan) -> np.ndarray:
        """The pixels of ``plan.window`` (x0, y0, x1, y1 in raster pixels) as OpenCV reads an image: (h, w, 3)
        uint8 BGR; invalid pixels :data:`NO_DATA_BGR`. Safe to call from worker threads."""
        x0, y0, x1, y1 = plan.window
        with self._lock:
            planes, valid = self._read(x0, y0, x1 - x0, y1 - y0)
        rgb = to_8bit(planes, self.value_range)
        bgr = np.ascontiguousarray(np.transpose(rgb[::-1], (1, 2, 0)))
        bgr[~valid] = NO_DATA_BGR
        return bgr

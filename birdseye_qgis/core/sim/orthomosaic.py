"""An orthomosaic of the simulated field: the field model seen straight down, as a map GeoTIFF.

A drone survey's usual by-product is an orthomosaic, the map every other layer is drawn over. The
simulator renders it from the same :class:`~.field.FieldScene` its frames show, not from the frames:
every map pixel's centre (a north-up grid in the site's UTM zone) is turned into its ground point in
the site's :class:`~.geodesy.LocalFrame` and shaded there by :meth:`FieldScene.radiance`, so a target
lies in the map exactly where its geotag says, and nothing a mosaicking step would add (seams,
relief displacement, blur) is in it. The pixel is coarser than a frame's (centimetres, not
millimetres); the field model fades the detail finer than a pixel, so the map does not alias.

Map pixel → ground point: UTM (x, y) → WGS84 latitude and longitude (PROJ) → local (east, north) at
the terrain's height there. PROJ runs on a lattice of nodes every :data:`LATTICE_PX` pixels; the
pixels between are interpolated bilinearly. Over a lattice cell of L metres the map projection bends
by about L²/R (R the Earth's radius): 0.1 µm for the default 0.64 m cells. The terrain's height moves
a ground point's local east and north only through the tilt of the ellipsoid normal, d/R per metre
of height at a distance d from the site (2 mm for 50 m of relief 250 m away), and is applied at the
lattice nodes.

Exposure is that of the frames at their base gain (:func:`base_exposure_gain`) under the sky of the
flight's middle moment (moving cloud shadows included), through the camera's tone curve; no
vignetting, blur or sensor noise. The map covers the field's whole simulated ground (every point a
frame sees); pixels outside it are transparent (alpha band).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

import numpy as np

from ..errors import Cancelled, InputError
from ..geometry.geodesy import LocalFrame, ProjectedCRS
from .field import FieldScene
from .render import base_exposure_gain, tone_curve, tone_map
from .terrain import Terrain

#: Ground size of a map pixel (m) when none is given: a few centimetres, so a 3–8 cm burrow is a
#: dark spot of a few pixels at the farm's scale.
ORTHO_PIXEL_M = 0.02
#: The pixel size doubles while the map would exceed this many pixels (a 25 ha field at 2 cm).
ORTHO_MAX_PIXELS = 64_000_000
LATTICE_PX = 32          # PROJ runs on every LATTICE_PX-th pixel; the rest is bilinear
TILE_PX = 512            # rendered and written in square tiles of this many pixels
COARSE = 4               # the field's smooth layers are shaded on a grid this many times coarser


@dataclass(frozen=True)
class OrthoGrid:
    """A north-up map grid: ``crs`` (e.g. ``EPSG:32756``), upper-left corner (x0, y0), pixel size
    (m) and size in pixels."""

    crs: str
    x0: float
    y0: float
    pixel_m: float
    width: int
    height: int

    @property
    def geotransform(self) -> tuple:
        """GDAL's geotransform: x = x0 + (col)·pixel, y = y0 − (row)·pixel at pixel corners."""
        return (self.x0, self.pixel_m, 0.0, self.y0, 0.0, -self.pixel_m)

    def map_xy(self, rows, cols):
        """Map coordinates (x, y) of the centres of pixels (row, col), float64."""
        return (self.x0 + (np.asarray(cols, float) + 0.5) * self.pixel_m,
                self.y0 - (np.asarray(rows, float) + 0.5) * self.pixel_m)

    def pixel_of(self, x, y):
        """(row, col) as fractional pixel coordinates (centre of the top-left pixel = (0, 0))."""
        return ((self.y0 - np.asarray(y, float)) / self.pixel_m - 0.5,
                (np.asarray(x, float) - self.x0) / self.pixel_m - 0.5)

    def to_dict(self) -> dict:
        return {"crs": self.crs, "pixel_m": self.pixel_m, "size_px": [self.width, self.height],
                "extent": {"xmin": self.x0, "ymin": self.y0 - self.height * self.pixel_m,
                           "xmax": self.x0 + self.width * self.pixel_m, "ymax": self.y0}}


def ortho_grid(scene: FieldScene, local: LocalFrame, crs: str, pixel_m: float = ORTHO_PIXEL_M) -> OrthoGrid:
    """The map grid covering the field's simulated ground (``scene.domain``, a local rectangle, turned
    against the map grid by the meridian convergence), its corners on whole multiples of the pixel
    so the maps of neighbouring fields share one grid. ``pixel_m`` doubles while the map would
    exceed :data:`ORTHO_MAX_PIXELS` pixels."""
    if not (pixel_m > 0 and math.isfinite(pixel_m)):
        raise InputError(f"the orthomosaic's pixel must be a positive size in metres, got {pixel_m}",
                         field="ORTHO_PIXEL_M")
    e0, e1, n0, n1 = scene.domain
    corners = np.array([[e0, n0, 0.0], [e1, n0, 0.0], [e1, n1, 0.0], [e0, n1, 0.0]])
    lat, lon, _ = local.to_geodetic(corners)
    x, y = ProjectedCRS(crs).from_geodetic(lat, lon)
    pixel = float(pixel_m)
    while True:
        x0, x1 = math.floor(x.min() / pixel) * pixel, math.ceil(x.max() / pixel) * pixel
        y0, y1 = math.floor(y.min() / pixel) * pixel, math.ceil(y.max() / pixel) * pixel
        width, height = int(round((x1 - x0) / pixel)), int(round((y1 - y0) / pixel))
        if width * height <= ORTHO_MAX_PIXELS:
            return OrthoGrid(str(crs), x0, y1, pixel, width, height)
        pixel *= 2.0


class _GroundLattice:
    """Local (east, north) of the ground under map pixels of one tile: exact at lattice nodes,
    bilinear between them (see the module docstring)."""

    def __init__(self, grid: OrthoGrid, proj: ProjectedCRS, local: LocalFrame, terrain: Terrain,
                 rows: slice, cols: slice):
        self.r0, self.c0 = rows.start, cols.start
        node_rows = self.r0 + LATTICE_PX * np.arange(-(-(rows.stop - self.r0) // LATTICE_PX) + 1)
        node_cols = self.c0 + LATTICE_PX * np.arange(-(-(cols.stop - self.c0) // LATTICE_PX) + 1)
        x, y = grid.map_xy(node_rows[:, None], node_cols[None, :])
        x, y = np.broadcast_arrays(x, y)
        lat, lon = proj.to_geodetic(x, y)
        # The ground's height under a node is needed before its local position is known: take the
        # site's, then the terrain's under that first position (it moves the position by µm).
        enu = local.from_geodetic(lat, lon, np.full(lat.shape, local.h0))
        height = terrain.height_at(enu[..., 0], enu[..., 1])
        height = np.where(np.isfinite(height), height, local.h0)  # past a DEM's edge: off the field anyway
        enu = local.from_geodetic(lat, lon, height)
        self.east, self.north = enu[..., 0], enu[..., 1]

    def at(self, rows, cols):
        """Ground (east, north) float32 grids at fractional pixel coordinates (rows (H, 1), cols (1, W))."""
        fr = (np.asarray(rows, float) - self.r0) / LATTICE_PX
        fc = (np.asarray(cols, float) - self.c0) / LATTICE_PX
        i = np.clip(np.floor(fr).astype(int), 0, self.east.shape[0] - 2)
        j = np.clip(np.floor(fc).astype(int), 0, self.east.shape[1] - 2)
        wr, wc = fr - i, fc - j
        out = []
        for node in (self.east, self.north):
            top = node[i, j] * (1.0 - wc) + node[i, j + 1] * wc
            bottom = node[i + 1, j] * (1.0 - wc) + node[i + 1, j + 1] * wc
            out.append((top * (1.0 - wr) + bottom * wr).astype(np.float32))
        return out[0], out[1]


def render_orthomosaic(path, scene: FieldScene, terrain: Terrain, local: LocalFrame, grid: OrthoGrid,
                       feature_geodetic, time_s: float,
                       progress: Optional[Callable[[float], None]] = None,
                       is_canceled: Optional[Callable[[], bool]] = None) -> str:
    """Render the field into ``grid`` and write it as an RGBA GeoTIFF (DEFLATE, tiled, with
    overviews) at ``path``; return the path.

    ``feature_geodetic``: (lat, lon) of every scene feature's ground point, placing the features on
    the map; ``time_s``: the moment of the moving cloud shadows (seconds from the flight's start).
    Progress is reported and cancel checked per tile.
    """
    try:
        from osgeo import gdal, osr
    except ImportError as exc:  # GDAL's Python bindings come with QGIS
        raise InputError("writing the orthomosaic needs GDAL's Python bindings (osgeo), which QGIS installs") from exc
    proj = ProjectedCRS(grid.crs)
    feature_rc = np.stack(grid.pixel_of(*proj.from_geodetic(*feature_geodetic)), -1).reshape(-1, 2)
    feature_half_px = scene.features.extent / grid.pixel_m * 1.1 + 3.0
    gain = np.float32(base_exposure_gain(scene))
    tone = tone_curve()

    options = ["TILED=YES", f"BLOCKXSIZE={TILE_PX // 2}", f"BLOCKYSIZE={TILE_PX // 2}", "COMPRESS=DEFLATE",
               "PREDICTOR=2", "PHOTOMETRIC=RGB", "ALPHA=YES"]
    dataset = gdal.GetDriverByName("GTiff").Create(str(path), grid.width, grid.height, 4, gdal.GDT_Byte, options)
    if dataset is None:
        raise InputError("cannot create the orthomosaic GeoTIFF (disk full or no permission?)", source=str(path))
    dataset.SetGeoTransform(grid.geotransform)
    srs = osr.SpatialReference()
    srs.SetFromUserInput(grid.crs)
    dataset.SetProjection(srs.ExportToWkt())
    dataset.SetMetadataItem("TIFFTAG_IMAGEDESCRIPTION", "BirdsEye simulated field, orthomosaic")
    for band, colour in zip(range(1, 5), (gdal.GCI_RedBand, gdal.GCI_GreenBand, gdal.GCI_BlueBand,
                                          gdal.GCI_AlphaBand)):
        dataset.GetRasterBand(band).SetColorInterpretation(colour)

    tiles = [(r, c) for r in range(0, grid.height, TILE_PX) for c in range(0, grid.width, TILE_PX)]
    for k, (r, c) in enumerate(tiles):
        if is_canceled is not None and is_canceled():
            dataset = None
            Path(path).unlink(missing_ok=True)  # half a map would pass for the whole field
            raise Cancelled()
        rows, cols = slice(r, min(r + TILE_PX, grid.height)), slice(c, min(c + TILE_PX, grid.width))
        rgba = _render_tile(scene, grid, proj, local, terrain, rows, cols, feature_rc, feature_half_px, gain,
                            tone, time_s)
        for band in range(4):
            dataset.GetRasterBand(band + 1).WriteArray(rgba[band], cols.start, rows.start)
        if progress is not None:
            progress(0.9 * (k + 1) / len(tiles))
    factors, size = [], max(grid.width, grid.height)
    while size > 256:
        factors.append(2 ** (len(factors) + 1))
        size //= 2
    if factors:
        dataset.BuildOverviews("AVERAGE", factors)
    dataset.FlushCache()
    dataset = None  # closes and writes the file
    if progress is not None:
        progress(1.0)
    return str(path)


def _render_tile(scene, grid, proj, local, terrain, rows: slice, cols: slice, feature_rc, feature_half_px,
                 gain, tone, time_s) -> np.ndarray:
    """One tile as (4, H, W) uint8: R, G, B and alpha (0 off the field's simulated ground)."""
    lattice = _GroundLattice(grid, proj, local, terrain, rows, cols)
    h, w = rows.stop - rows.start, cols.stop - cols.start
    east, north = lattice.at(np.arange(rows.start, rows.stop)[:, None], np.arange(cols.start, cols.stop)[None, :])
    # The coarse grid sits where cv2.resize (in FieldScene.radiance) maps its cells back onto the tile.
    hc, wc = -(-h // COARSE), -(-w // COARSE)
    east_c, north_c = lattice.at(rows.start + (np.arange(hc)[:, None] + 0.5) * (h / hc) - 0.5,
                                 cols.start + (np.arange(wc)[None, :] + 0.5) * (w / wc) - 0.5)
    windows = []
    for index in np.flatnonzero((feature_rc[:, 0] + feature_half_px > rows.start)
                                & (feature_rc[:, 0] - feature_half_px < rows.stop)
                                & (feature_rc[:, 1] + feature_half_px > cols.start)
                                & (feature_rc[:, 1] - feature_half_px < cols.stop)):
        (fr, fc), half = feature_rc[index], feature_half_px[index]
        r0, r1 = max(0, int(math.floor(fr - half)) - rows.start), min(h, int(math.ceil(fr + half)) + 1 - rows.start)
        c0, c1 = max(0, int(math.floor(fc - half)) - cols.start), min(w, int(math.ceil(fc + half)) + 1 - cols.start)
        if r0 < r1 and c0 < c1:
            windows.append((int(index), slice(r0, r1), slice(c0, c1)))
    rgb = scene.radiance(east, north, east_c, north_c, grid.pixel_m, time_s, windows, gain=gain)
    e0, e1, n0, n1 = scene.domain
    inside = (east >= e0) & (east <= e1) & (north >= n0) & (north <= n1)
    out = np.zeros((4, h, w), np.uint8)
    for band in range(3):
        out[band] = tone_map(rgb[band], tone)
    out[:3, ~inside] = 0
    out[3] = np.where(inside, 255, 0)
    return out

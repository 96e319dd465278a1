"""The simulated world's ground surface: where a viewing ray meets the terrain.

This is the *truth* the simulator renders and measures with its radar altimeter, not the ground model
the labelling uses (that is :mod:`.ground`, estimated from the logged altimeter): keeping the two apart
is what lets a campaign show the error a level-plane assumption makes over real terrain.

Coordinates are the site's :class:`~.geodesy.LocalFrame` (east, north, up; metres). A terrain
implements :meth:`Terrain.height_at` (ellipsoidal height under a local point), :meth:`Terrain.intersect`
(rays with their own origins, e.g. the altimeter beam), :meth:`Terrain.intersect_grid` (one camera's
whole pixel grid, the renderer's hot path) and :meth:`Terrain.ground_model` (the same surface behind
the :class:`~.ground.GroundModel` interface, for footprints).

* :class:`FlatTerrain` — a field of constant ellipsoidal height (the default campaign).
* :class:`DemTerrain` — a DEM (:class:`~.dem.DemRaster`, e.g. from :func:`~.dem.synthetic_terrain`)
  resampled once into the local frame as a :class:`~.dem.Heightfield`; rays are cast with
  :func:`~.dem.intersect_heightfield` (first hit, bilinear heights), the same code the DEM ground
  model of the label writer uses. The surface the frames show is that heightfield: bilinear between
  its nodes, exactly the DEM's plane on planar terrain and within the DEM's own interpolation error
  (cell²·|curvature|/8, well under a millimetre for the simulator's hills) elsewhere.
"""
from __future__ import annotations

import math

import numpy as np

from ..errors import InputError
from ..geometry.dem import DemGround, DemRaster, heightfield_from_dem, intersect_heightfield
from ..geometry.geodesy import LocalFrame, ProjectedCRS, meridian_convergence_deg
from ..geometry.ground import GroundModel, LevelPlaneGround
from ..geometry.poses import FrameGeometry


class Terrain:
    """Interface of the simulated ground surface (local frame, metres)."""

    #: Boundary pixels per image edge that outline a frame's footprint on this terrain.
    edge_samples = 2

    def height_at(self, east, north) -> np.ndarray:
        """Ellipsoidal height (m) of the ground under local horizontal positions."""
        raise NotImplementedError

    def intersect(self, origins, directions) -> np.ndarray:
        """Ray parameters t (N,) with ``origins + t·directions`` on the ground (NaN: no hit)."""
        raise NotImplementedError

    def intersect_grid(self, centre, r_local_cam, xn, yn):
        """Local east, north (float32 arrays shaped like ``xn``) where the camera's pixel rays meet the
        ground. ``centre`` is the camera centre (3,), ``r_local_cam`` its camera→local rotation, and
        ``(xn, yn, 1)`` the camera-frame ray of each pixel (ideal normalised coordinates)."""
        raise NotImplementedError

    def ground_model(self, geometry: FrameGeometry) -> GroundModel:
        """This surface as the ground model of ``geometry``'s frames (footprints, visibility)."""
        raise NotImplementedError


class FlatTerrain(Terrain):
    """The surface of constant ellipsoidal height ``height_m`` (a level field).

    Each query uses the plane tangent to that surface under the ray origin (normal = the ellipsoid
    normal there); the surface departs from that plane by d²/2R, under 10 µm within a 10 m footprint.
    """

    def __init__(self, local: LocalFrame, height_m: float):
        self.local = local
        self.height_m = float(height_m)

    def height_at(self, east, north) -> np.ndarray:
        return np.full(np.shape(east), self.height_m)

    def _tangent_planes(self, origins):
        """Point on the ground under each origin and the surface normal there, both (N, 3)."""
        lat, lon, _ = self.local.to_geodetic(origins)
        lat, lon = np.atleast_1d(lat), np.atleast_1d(lon)
        point = self.local.from_geodetic(lat, lon, np.full(lat.shape, self.height_m)).reshape(-1, 3)
        return point, self.local.up_at(lat, lon).reshape(-1, 3)

    def intersect(self, origins, directions) -> np.ndarray:
        origins = np.asarray(origins, dtype=float).reshape(-1, 3)
        directions = np.asarray(directions, dtype=float).reshape(-1, 3)
        point, normal = self._tangent_planes(origins)
        denom = np.einsum("ni,ni->n", normal, directions)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.einsum("ni,ni->n", normal, point - origins) / denom
        return np.where(np.isfinite(t) & (t > 0), t, np.nan)

    def intersect_grid(self, centre, r_local_cam, xn, yn):
        centre = np.asarray(centre, dtype=float)
        point, normal = self._tangent_planes(centre[None])
        point, normal = point[0], normal[0]
        # Ray d = R (xn, yn, 1); hit = C + t d with t = n·(P − C) / n·d. Folding R into the three
        # dot products keeps the per-pixel work at a homography (float32 is ample: the offsets from
        # the camera centre are metres, the rounding micrometres).
        r = np.asarray(r_local_cam, dtype=float)
        m = r.T @ normal
        height = float(normal @ (point - centre))
        denom = xn * np.float32(m[0]) + yn * np.float32(m[1]) + np.float32(m[2])
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.float32(height) / denom
        scale[~(scale > 0)] = np.nan
        east = (xn * np.float32(r[0, 0]) + yn * np.float32(r[0, 1]) + np.float32(r[0, 2])) * scale
        north = (xn * np.float32(r[1, 0]) + yn * np.float32(r[1, 1]) + np.float32(r[1, 2])) * scale
        east += np.float32(centre[0])
        north += np.float32(centre[1])
        return east, north

    def ground_model(self, geometry: FrameGeometry) -> GroundModel:
        """The level plane at each frame's ground height (the frames fly over this very surface)."""
        return LevelPlaneGround(geometry)


class DemTerrain(Terrain):
    """Terrain from a DEM, resampled once into ``local`` over ``extent`` (local east_min, east_max,
    north_min, north_max; m) at the DEM's cell size. The DEM's heights must be ellipsoidal (the
    simulator's poses are) and cover the extent without no-data: rays leaving it are reported as
    misses (NaN), never guessed."""

    edge_samples = 8
    #: Rays per call of the ray caster (bounds its temporaries to some hundred MB per million pixels).
    CHUNK_RAYS = 1 << 18

    def __init__(self, local: LocalFrame, dem: DemRaster, extent):
        if dem.vertical_datum != "ellipsoidal":
            raise InputError(f"the simulator's terrain must hold ellipsoidal heights, not {dem.vertical_datum}",
                             source=dem.source)
        self.local = local
        self.dem = dem
        self.heightfield = heightfield_from_dem(dem, local, extent, dem.cell_size_m)
        if np.isnan(self.heightfield.z).any():
            raise InputError("the DEM does not cover the whole area of the flight", source=dem.source)

    def height_at(self, east, north) -> np.ndarray:
        """Ellipsoidal height of the terrain point at local (east, north) (NaN off the terrain)."""
        east, north = np.broadcast_arrays(np.asarray(east, dtype=float), np.asarray(north, dtype=float))
        up = self.heightfield.height_at(east, north)
        _, _, h = self.local.to_geodetic(np.stack([east, north, up], axis=-1))
        return np.asarray(h).reshape(east.shape)

    def intersect(self, origins, directions) -> np.ndarray:
        origins = np.asarray(origins, dtype=float).reshape(-1, 3)
        directions = np.asarray(directions, dtype=float).reshape(-1, 3)
        t = np.full(len(origins), np.nan)
        for a in range(0, len(origins), self.CHUNK_RAYS):
            o, d = origins[a:a + self.CHUNK_RAYS], directions[a:a + self.CHUNK_RAYS]
            hits = intersect_heightfield(self.heightfield, o, d, self.heightfield.height_at(o[:, 0], o[:, 1]))
            t[a:a + len(o)] = np.where(hits.valid, hits.t, np.nan)
        return t

    def intersect_grid(self, centre, r_local_cam, xn, yn):
        centre = np.asarray(centre, dtype=float)
        r = np.asarray(r_local_cam, dtype=float)
        shape = np.shape(xn)
        xn, yn = np.ravel(xn).astype(float), np.ravel(yn).astype(float)
        east = np.full(xn.size, np.nan, dtype=np.float32)
        north = np.full(xn.size, np.nan, dtype=np.float32)
        start = self.heightfield.height_at(centre[0], centre[1])
        for a in range(0, xn.size, self.CHUNK_RAYS):
            rays = np.stack([xn[a:a + self.CHUNK_RAYS], yn[a:a + self.CHUNK_RAYS],
                             np.ones(min(self.CHUNK_RAYS, xn.size - a))], axis=-1) @ r.T
            hits = intersect_heightfield(self.heightfield, np.broadcast_to(centre, rays.shape), rays,
                                         np.full(len(rays), start))
            east[a:a + len(rays)] = np.where(hits.valid, hits.points[:, 0], np.nan)
            north[a:a + len(rays)] = np.where(hits.valid, hits.points[:, 1], np.nan)
        return east.reshape(shape), north.reshape(shape)

    def ground_model(self, geometry: FrameGeometry) -> GroundModel:
        return DemGround(geometry, self.heightfield)


def write_dem_geotiff(dem: DemRaster, path) -> str:
    """Write ``dem`` as a single-band Float64 GeoTIFF (heights in metres, its CRS and geotransform;
    the vertical reference in the metadata) with GDAL, and return the path."""
    try:
        from osgeo import gdal, osr
    except ImportError as exc:  # GDAL's Python bindings come with QGIS
        raise InputError("writing the DEM needs GDAL's Python bindings (osgeo), which QGIS installs") from exc
    rows, cols = dem.heights.shape
    x0, dx, y0, dy = dem.geotransform
    dataset = gdal.GetDriverByName("GTiff").Create(str(path), cols, rows, 1, gdal.GDT_Float64)
    if dataset is None:
        raise InputError("cannot create the GeoTIFF (disk full or no permission?)", source=str(path))
    dataset.SetGeoTransform((x0, dx, 0.0, y0, 0.0, dy))
    srs = osr.SpatialReference()
    srs.SetFromUserInput(f"EPSG:{dem.crs}" if isinstance(dem.crs, int) else str(dem.crs))
    dataset.SetProjection(srs.ExportToWkt())
    dataset.SetMetadataItem("VERTICAL_DATUM", {"ellipsoidal": "WGS84 ellipsoid", "msl": "mean sea level"}
                            .get(dem.vertical_datum, "unknown"))
    band = dataset.GetRasterBand(1)
    band.SetUnitType("m")
    band.SetDescription("terrain height")
    band.WriteArray(np.asarray(dem.heights, dtype=float))
    band.FlushCache()
    dataset = None  # closes and writes the file
    return str(path)


def synthetic_terrain(lat: float, lon: float, kind: str = "plane", slope_deg: float = 0.0,
                      aspect_deg: float = 0.0, relief_m: float = 0.0, base_height_m: float = 0.0,
                      size_m=500.0, cell_m: float = 1.0, wavelength_m: float = 60.0, seed: int = 0,
                      crs: str | int | None = None, vertical_datum: str = "ellipsoidal",
                      geoid_undulation_m: float | None = None) -> DemRaster:
    """A DEM centred on (lat, lon) in ``crs`` (default: the site's UTM zone), for tests and the simulator.

    ``kind='plane'``: height = ``base_height_m`` at the centre, rising at ``slope_deg`` towards the
    azimuth ``aspect_deg + 180°`` (``aspect_deg`` = direction the slope faces, clockwise from true
    north; the meridian convergence is applied, so the azimuth is true, the slope per grid metre —
    the map scale factor, within ±0.04 % in UTM, scales tan(slope) alike).
    ``kind='hills'``: the same plane plus smooth random hills (Gaussian-filtered noise, one hill and
    valley every ``wavelength_m`` on average) scaled to ``relief_m`` peak to peak. ``size_m``: side (or
    (east, north) sides) in metres; ``cell_m``: cell size. Heights are in ``vertical_datum``.
    """
    if kind not in ("plane", "hills"):
        raise InputError(f"terrain kind {kind!r} is not 'plane' or 'hills'")
    if not (0.0 <= slope_deg < 90.0) or relief_m < 0 or not cell_m > 0:
        raise InputError("slope must lie in [0°, 90°), relief be non-negative and the cell size positive")
    proj = ProjectedCRS.for_site(lat, lon) if crs is None else ProjectedCRS(crs)
    xc, yc = (float(v) for v in proj.from_geodetic(lat, lon))
    size_e, size_n = np.broadcast_to(np.asarray(size_m, dtype=float), (2,))
    cols, rows = max(int(round(size_e / cell_m)), 2), max(int(round(size_n / cell_m)), 2)
    x0, y0 = xc - 0.5 * cols * cell_m, yc + 0.5 * rows * cell_m
    x = x0 + (np.arange(cols) + 0.5) * cell_m
    y = y0 - (np.arange(rows) + 0.5) * cell_m
    xx, yy = np.meshgrid(x - xc, y - yc)
    uphill_grid = math.radians(aspect_deg + 180.0 - float(meridian_convergence_deg(lat, lon, proj.crs)))
    heights = base_height_m + math.tan(math.radians(slope_deg)) * (xx * math.sin(uphill_grid)
                                                                   + yy * math.cos(uphill_grid))
    if kind == "hills" and relief_m > 0:
        from scipy.ndimage import gaussian_filter

        # Filtered white noise has a Gaussian autocorrelation of std σ√2; by Rice's formula its level
        # crossings along a line come every π√2·σ, i.e. one hill-and-valley every 2π√2·σ.
        sigma_cells = wavelength_m / (2.0 * math.pi * math.sqrt(2.0) * cell_m)
        noise = gaussian_filter(np.random.default_rng(seed).standard_normal((rows, cols)), sigma=sigma_cells)
        noise -= 0.5 * (noise.max() + noise.min())
        heights = heights + noise * (relief_m / (noise.max() - noise.min()))
    return DemRaster(heights, (x0, cell_m, y0, -cell_m), proj.crs, vertical_datum, geoid_undulation_m,
                     source=f"synthetic {kind} terrain")

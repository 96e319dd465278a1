"""Terrain-aware ground: a DEM behind the :class:`~.ground.GroundModel` interface.

The level plane (:class:`~.ground.LevelPlaneGround`) holds up to about 10° of slope; beyond that labels
drift off their targets. :class:`DemGround` replaces it with real terrain:

* world → pixel (:meth:`DemGround.place`) puts a geotag on the terrain height under it;
* pixel → ground (:meth:`DemGround.intersect`) meets each viewing ray with the terrain, at its *first*
  hit (a ridge hides what lies behind it).

Frames and units
----------------
* :class:`DemRaster` is the DEM as the algorithms read it (QGIS/GDAL hand over arrays; this module never
  imports them): heights in metres on a north-up grid of a projected CRS, GDAL geotransform
  ``(x0, dx, y0, dy)`` — ``x0, y0`` the outer corner of the top-left cell, ``dy < 0`` for rows running
  south. Heights are cell-centre values (GDAL "area" pixels), interpolated bilinearly between cell
  centres; no-data is NaN. The vertical reference is declared (``ellipsoidal``, ``msl`` with the geoid
  undulation N, ellipsoidal = MSL + N, or ``unknown``), converted into the frames' own reference
  (``heights.height_shift``) and checked against their ground (:func:`check_vertical_datum`): a DEM that then
  disagrees with the flight is a configuration error.
* :class:`Heightfield` is the DEM resampled once into the site's :class:`~.geodesy.LocalFrame` (ENU
  tangent frame at the origin): ``U = H(E, N)`` on a regular grid of local east/north, bilinear between
  nodes. All ray work happens there, in straight lines.
* "Vertical" for :meth:`DemGround.place` is the frame's up (the ellipsoid normal under the frame), as in
  :meth:`~.ground.LevelPlaneGround.place`; it differs from the normal at the geotag itself by d/R
  (d = horizontal distance to the frame, R ≈ 6371 km), < 0.1 mm per 10 m of vertical move at d = 60 m.

Ray–terrain intersection (:func:`intersect_heightfield`)
--------------------------------------------------------
Along a ray ``p(t) = o + t·d`` the height above terrain is ``f(t) = U(t) − H(E(t), N(t))``; the hit is
the smallest ``t ≥ 0`` with ``f = 0``. Only the part of the ray inside the slab ``min H ≤ U ≤ max H``
can hit. Two paths:

* **Certified fast path** (near-nadir rays, the vast majority): the heightfield keeps, per tile of
  cells, an exact bound G on the bilinear surface's gradient (dilated over the neighbouring tiles). If
  the ray's slab segment stays within that neighbourhood and the ray descends more steeply than the
  terrain can rise (``|d_U| > G·|d_h|``), then ``f`` is strictly decreasing on the segment: there is
  exactly one crossing, so it is the first. It is found by Newton's height iteration from the level-
  plane estimate (the terrain height under the camera), safeguarded by the bracket [slab top, slab
  bottom]; rays that do not converge go to the robust path.
* **Robust path** (oblique, grazing, ascending rays, rays near no-data or the DEM edge): from the
  ray's entry into the slab, skip empty space (while the ray is above the highest terrain within a
  tile of it, advance by up to a tile, no lower than that height), then march to the slab's exit with
  steps of at most half a cell horizontally, stop at the first sample at or below the terrain, and
  refine in that bracket (the same safeguarded Newton with bisection). A ray that is inside the
  terrain for less than half a cell horizontally — clipping a crest — can pass between two samples:
  its first hit is then the next one.

Unknown terrain is reported, not guessed. A ray that is inside the slab while outside the DEM's extent
is invalid (it may meet terrain the DEM does not hold). No-data holes are assumed to hold terrain no
higher than the valid terrain around them (the highest valid node within a tile's reach; a hole wider
than that is bounded by the DEM's highest node): a ray crossing a hole above that ceiling passes on, one
crossing it lower might have hit it and is invalid, as is a ray landing in a cell next to no-data or
within half a cell of the hole it crossed.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..errors import InputError, check_cancel
from .geodesy import LocalFrame, ProjectedCRS, on_python_thread
from .ground import GroundModel
from .heights import (
    CONTROL_POINTS,
    ELLIPSOIDAL_REFERENCE,
    FLIGHT_HEIGHT,
    GEOTAGS,
    GIVEN,
    MAX_UNDULATION_M,
    MSL_REFERENCE,
    SITE_LEVEL_SOURCES,
    TAKEOFF,
    UNDER_FRAME_SOURCES,
    UNKNOWN,
    UNKNOWN_REFERENCE,
    VerticalReference,
    height_shift,
)
from .poses import FrameGeometry, FramePoses

#: What a DEM's heights may be declared as measured from (the DEM_VERTICAL_DATUM choices, in order).
VERTICAL_DATUMS = ("ellipsoidal", "msl", "unknown")
#: How far (m) from the frames a drone's take-off point may lie when its height is checked against a DEM.
TAKEOFF_REACH_M = 500.0


# --------------------------------------------------------------------------- the DEM as read
@dataclass
class DemRaster:
    """A north-up DEM in a projected CRS (see the module docstring for the conventions).

    ``heights`` (rows, cols) metres, row 0 = northernmost when ``dy < 0``; ``nodata`` values (and any
    non-finite value) become NaN. ``geoid_undulation_m`` is N at the site (ellipsoidal = MSL + N),
    needed whenever the DEM and the poses use different vertical references.
    """

    heights: np.ndarray
    geotransform: tuple
    crs: str | int
    vertical_datum: str = "unknown"
    geoid_undulation_m: float | None = None
    nodata: float | None = None
    source: str = "DEM"

    def __post_init__(self):
        z = np.array(self.heights, dtype=float)
        if z.ndim != 2 or min(z.shape) < 2:
            raise InputError(f"heights must be a 2-D grid of at least 2 × 2 cells, got shape {z.shape}",
                             source=self.source)
        if self.nodata is not None and np.isfinite(self.nodata):
            z[z == self.nodata] = np.nan
        z[~np.isfinite(z)] = np.nan
        if np.all(np.isnan(z)):
            raise InputError("every cell is no-data", source=self.source)
        self.heights = z
        try:
            x0, dx, y0, dy = (float(v) for v in self.geotransform)
        except (TypeError, ValueError) as exc:
            raise InputError(f"geotransform must be (x0, dx, y0, dy), got {self.geotransform!r}",
                             source=self.source) from exc
        if not (dx > 0 and dy != 0 and all(map(math.isfinite, (x0, y0, dx, dy)))):
            raise InputError(f"geotransform (x0, dx, y0, dy) = {self.geotransform!r} is not a north-up grid "
                             "(dx must be positive, dy non-zero; rotated rasters must be warped first)",
                             source=self.source)
        self.geotransform = (x0, dx, y0, dy)
        _require_projected(self.crs, self.source)
        if self.vertical_datum not in VERTICAL_DATUMS:
            raise InputError(f"vertical datum {self.vertical_datum!r} is not one of {', '.join(VERTICAL_DATUMS)}",
                             source=self.source)

    @property
    def cell_size_m(self) -> float:
        return min(self.geotransform[1], abs(self.geotransform[3]))

    def cell_centres(self):
        """Projected x (cols,) and y (rows,) of the cell centres."""
        x0, dx, y0, dy = self.geotransform
        rows, cols = self.heights.shape
        return x0 + (np.arange(cols) + 0.5) * dx, y0 + (np.arange(rows) + 0.5) * dy

    def sample(self, x, y) -> np.ndarray:
        """Bilinear heights (m, the DEM's own vertical reference) at projected x, y; NaN off the grid
        of cell centres or next to no-data."""
        x0, dx, y0, dy = self.geotransform
        col = (np.asarray(x, dtype=float) - x0) / dx - 0.5
        row = (np.asarray(y, dtype=float) - y0) / dy - 0.5
        return _bilinear_nodes(self.heights, row, col)

    def sample_geodetic(self, lat, lon) -> np.ndarray:
        """Bilinear heights (m, the DEM's own vertical reference) at WGS84 latitude/longitude (deg)."""
        x, y = ProjectedCRS(self.crs).from_geodetic(lat, lon)
        return self.sample(x, y)


@on_python_thread
def _require_projected(crs, source) -> None:
    """The DEM's cells must be metres: a geographic CRS (degrees) has to be warped by the caller."""
    try:
        ProjectedCRS(crs)  # also points pyproj at the PROJ data
        import pyproj

        geographic = pyproj.CRS.from_user_input(crs).is_geographic
    except Exception as exc:  # pyproj raises CRSError or ProjError for unusable definitions
        raise InputError(f"the CRS {_crs_name(crs)} is not usable ({exc})", source=source) from exc
    if geographic:
        raise InputError(f"the DEM is in a geographic CRS ({_crs_name(crs)}, cells in degrees): reproject it to a "
                         "projected CRS in metres, e.g. the site's UTM zone", source=source)


def _bilinear_nodes(z: np.ndarray, row, col) -> np.ndarray:
    """Bilinear interpolation of node values z[row, col] at fractional indices; NaN outside."""
    rows, cols = z.shape
    row, col = np.broadcast_arrays(np.asarray(row, dtype=float), np.asarray(col, dtype=float))
    inside = (row >= 0) & (row <= rows - 1) & (col >= 0) & (col <= cols - 1)
    r = np.clip(np.floor(np.where(inside, row, 0)), 0, rows - 2).astype(np.intp)
    c = np.clip(np.floor(np.where(inside, col, 0)), 0, cols - 2).astype(np.intp)
    fr, fc = np.where(inside, row - r, 0.0), np.where(inside, col - c, 0.0)
    out = ((z[r, c] * (1 - fc) + z[r, c + 1] * fc) * (1 - fr)
           + (z[r + 1, c] * (1 - fc) + z[r + 1, c + 1] * fc) * fr)
    return np.where(inside, out, np.nan)


# --------------------------------------------------------------------------- vertical datum
#: The DEM check's tolerance (:func:`dem_tolerance_m`): this share of the flight's height above its ground, and
#: at least :data:`DEM_TOLERANCE_MIN_M`. A DEM dz off moves a label at distance ρ·depth from the nadir by
#: about ρ·dz/depth of ρ·depth: a few per cent of the depth is where labels at the image edge start to move
#: by more than a label's radius, and well below any datum mix-up (tens of metres).
DEM_TOLERANCE_FRACTION = 0.03
DEM_TOLERANCE_MIN_M = 0.2


def dem_tolerance_m(depth_m: float) -> float:
    """How far (m) a DEM may lie from a flight's ground at ``depth_m`` m above it before it is refused."""
    depth = float(depth_m) if depth_m is not None and math.isfinite(float(depth_m)) else 0.0
    return max(DEM_TOLERANCE_MIN_M, DEM_TOLERANCE_FRACTION * depth)


def dem_reference(dem: "DemRaster") -> VerticalReference:
    """What the DEM's heights are measured from, as the user declared it."""
    return {"ellipsoidal": ELLIPSOIDAL_REFERENCE, "msl": MSL_REFERENCE}.get(dem.vertical_datum, UNKNOWN_REFERENCE)


@dataclass(frozen=True)
class DemCheck:
    """A DEM against a flight (:func:`check_vertical_datum`).

    ``offset_m``: added to the DEM's heights to express them in the flight's vertical reference; ``conversion``:
    how it was found, in words (empty: the same reference). What the flight's ground says of the converted DEM:
    ``measured_m``, the median of DEM − ground under the frames whose ground was measured there (altimeter, tie
    points, a DEM; NaN: none), and ``takeoff_miss_m``, how far the site-level ground (a take-off point, a flight
    height, control points) lies outside the heights the terrain around the frames has (0: inside; NaN: none);
    ``tolerance_m`` for both, from the flight's ``depth_m`` (median height above its ground)."""

    offset_m: float
    conversion: str
    measured_m: float
    takeoff_miss_m: float
    tolerance_m: float
    depth_m: float
    n_under: int = 0
    n_site: int = 0

    def describe(self) -> str:
        """The check's result in words, for the log."""
        parts = [self.conversion or "DEM and frames in the same vertical reference"]
        if math.isfinite(self.measured_m):
            parts.append(f"terrain under {self.n_under} frame(s) {self.measured_m:+.2f} m from their measured ground "
                         "(median)")
        if math.isfinite(self.takeoff_miss_m):
            parts.append("the take-off height is one the terrain around has" if abs(self.takeoff_miss_m) < 0.005 else
                         f"the take-off height lies {abs(self.takeoff_miss_m):.2f} m "
                         f"{'above' if self.takeoff_miss_m > 0 else 'below'} the terrain around")
        parts.append(f"tolerance ±{self.tolerance_m:.2f} m at {self.depth_m:.1f} m above ground" if
                     math.isfinite(self.depth_m) else f"tolerance ±{self.tolerance_m:.2f} m")
        return "; ".join(parts)


def check_vertical_datum(dem: "DemRaster", poses: FramePoses, tolerance_m: float | None = None) -> DemCheck:
    """The DEM converted into the flight's vertical reference and checked against the flight's own ground.

    The conversion is :func:`.heights.height_shift` from the DEM's declared reference to the frames'
    (``poses.reference``), with the DEM's ``geoid_undulation_m`` as the N given, evaluated at the frames'
    median position (N changes by centimetres over a few kilometres). A DEM or a flight whose reference is
    unknown is taken as the other's and must then be confirmed by the flight's ground.

    The check stands on each frame's ground source (``poses.ground_source``), over the whole flight (pass every
    frame): where the ground was measured under the frame (altimeter, tie points, a DEM) the DEM's terrain there
    must agree with it, median within the tolerance; where it is one height for the site (take-off, flight
    height, control points, geotags) the terrain under the frames honestly lies above or below it by the site's
    relief, so that height must be one the DEM's terrain has within :data:`TAKEOFF_REACH_M` of the frames, give
    or take the tolerance (a mix-up smaller than the relief there cannot be told from relief). The tolerance
    follows the flight's height above its ground (:func:`dem_tolerance_m`) unless ``tolerance_m`` is given.

    Raises :class:`~.errors.InputError` when the references cannot be converted, when an unknown reference has
    no ground to be checked against, and when the DEM fails the check (another vertical reference, wrong units,
    or heights that do not cover the flight)."""
    source, target = dem_reference(dem), poses.reference
    lat, lon = np.asarray(poses.lat, dtype=float), np.asarray(poses.lon, dtype=float)
    ground = np.asarray(poses.ground_height, dtype=float)
    known = np.isfinite(ground)
    under = known & np.isin(poses.ground_source, UNDER_FRAME_SOURCES)
    site = known & np.isin(poses.ground_source, SITE_LEVEL_SOURCES)
    if UNKNOWN in (source.kind, target.kind):
        if not (under.any() or site.any()):
            side = "DEM's" if source.kind == UNKNOWN else "flight's"
            raise InputError(
                f"the {side} vertical reference is not stated and the flight has no ground heights to check it "
                f"against; state what the DEM's heights are measured from (the flight's are {target.describe()})",
                source=dem.source)
        offset, conversion = 0.0, (f"the DEM's heights ({source.describe()}) taken as the flight's "
                                   f"({target.describe()}), to be confirmed by the flight's ground")
    else:
        try:
            shift = height_shift(source, target, np.median(lat), np.median(lon), dem.geoid_undulation_m)
        except InputError as exc:
            raise InputError(f"the DEM's heights are {source.describe()}, the flight's {target.describe()}: "
                             f"{exc}", source=dem.source, field=exc.field) from None
        offset, conversion = shift.median_m, (f"DEM {shift.note}" if shift.note else "")
    depth = float(np.median(poses.height[known] - ground[known])) if known.any() else math.nan
    tolerance = dem_tolerance_m(depth) if tolerance_m is None else float(tolerance_m)
    measured = _check_against_ground(dem, lat[under], lon[under], ground[under], offset, target, tolerance,
                                     depth, conversion) if under.any() else math.nan
    miss = _check_against_takeoff(dem, lat[site], lon[site], ground[site], poses.ground_source[site], offset,
                                  target, tolerance, depth, conversion) if site.any() else math.nan
    return DemCheck(offset, conversion, measured, miss, tolerance, depth, int(under.sum()), int(site.sum()))


def check_flight(dem: "DemRaster", pose_groups, tolerance_m: float | None = None) -> DemCheck:
    """:func:`check_vertical_datum` over every frame of a flight given as its camera groups
    (``FramePoses`` sharing one vertical reference, as ``frame_records.poses_from_records`` gives them)."""
    groups = list(pose_groups)
    if not groups:
        raise InputError("no frames to check the DEM against", source=dem.source)
    first = groups[0]

    def joined(name):
        return np.concatenate([np.asarray(getattr(p, name)) for p in groups])

    flight = FramePoses(joined("frame_id"), joined("lat"), joined("lon"), joined("height"), joined("quat"),
                        joined("ground_height"), first.camera, first.reference, joined("ground_source"))
    return check_vertical_datum(dem, flight, tolerance_m)


def _hint(offset_m: float) -> str:
    if abs(offset_m) <= MAX_UNDULATION_M:
        return (f" A near-constant offset of {offset_m:+.1f} m is what mixing mean-sea-level and ellipsoidal "
                "heights gives (the geoid undulation); check the DEM's vertical reference and the undulation given.")
    return " An offset this large is not a geoid undulation: check the DEM's units, CRS and no-data value."


def _no_frame_over_the_dem(dem, n_frames):
    x, y = dem.cell_centres()
    return InputError(
        f"none of the {n_frames} frames with a ground height lies over (or, for a take-off ground, within "
        f"{TAKEOFF_REACH_M:g} m of) the DEM's terrain "
        f"(DEM extent x {x.min():.1f}…{x.max():.1f}, y {min(y):.1f}…{max(y):.1f} in {_crs_name(dem.crs)}): "
        "check the DEM's CRS and that it covers the flight", source=dem.source)


def _at_depth(tolerance_m, depth_m) -> str:
    return (f"the ±{tolerance_m:.2f} m tolerance at {depth_m:.1f} m above ground" if math.isfinite(depth_m)
            else f"the ±{tolerance_m:.2f} m tolerance")


def _check_against_ground(dem, lat, lon, ground, offset, target, tolerance_m, depth_m, conversion) -> float:
    """Median DEM − ground (m) under frames whose ground was measured there; refused beyond the tolerance."""
    terrain = dem.sample_geodetic(lat, lon) + offset
    both = np.isfinite(terrain)
    if not np.any(both):
        raise _no_frame_over_the_dem(dem, len(ground))
    diff = terrain[both] - ground[both]
    median = float(np.median(diff))
    if abs(median) <= tolerance_m:
        return median
    raise InputError(
        f"under {int(both.sum())} frames the DEM's terrain is {median:+.2f} m off the ground measured under them "
        f"(DEM − frames' ground, median; range {diff.min():+.2f} … {diff.max():+.2f} m), more than "
        f"{_at_depth(tolerance_m, depth_m)}{_converted(conversion)}: the DEM ({_datum_words(dem)}) is probably in "
        f"another vertical reference than the flight ({target.describe()}), or its heights are off.{_hint(median)}",
        source=dem.source)


def _converted(conversion: str) -> str:
    return f" (converted: {conversion})" if conversion else ""


def _datum_words(dem) -> str:
    words = dem_reference(dem).describe()
    return words if dem.geoid_undulation_m is None else f"{words}, N = {dem.geoid_undulation_m:g} m given"


#: What a site-level ground height is, in words, by its source.
_SITE_GROUND_WORDS = {TAKEOFF: "take-off height", FLIGHT_HEIGHT: "take-off height (camera height − flight height)",
                      GIVEN: "ground height given", CONTROL_POINTS: "control points' height",
                      GEOTAGS: "geotags' height"}


def _check_against_takeoff(dem, lat, lon, ground, sources, offset, target, tolerance_m, depth_m,
                           conversion) -> float:
    """How far (m) the site-level ground lies outside the terrain around the frames; refused beyond the
    tolerance."""
    x, y = ProjectedCRS(dem.crs).from_geodetic(lat, lon)
    cx, cy = dem.cell_centres()
    cols = (cx >= np.min(x) - TAKEOFF_REACH_M) & (cx <= np.max(x) + TAKEOFF_REACH_M)
    rows = (cy >= np.min(y) - TAKEOFF_REACH_M) & (cy <= np.max(y) + TAKEOFF_REACH_M)
    around = dem.heights[np.ix_(rows, cols)] + offset
    # The terrain around, not only under the cameras: a DSM of the field may leave out the take-off point.
    if not np.any(np.isfinite(around)):
        raise _no_frame_over_the_dem(dem, len(ground))
    lowest, highest = float(np.nanmin(around)), float(np.nanmax(around))
    takeoff = float(np.median(ground))
    miss = takeoff - highest if takeoff > highest else takeoff - lowest if takeoff < lowest else 0.0
    if abs(miss) <= tolerance_m:
        return miss
    words = " or ".join(dict.fromkeys(_SITE_GROUND_WORDS[s] for s in sources))
    raise InputError(
        f"the flight's {words} ({takeoff:.2f} m, the median over {len(ground)} frames) lies {abs(miss):.2f} m "
        f"{'above the highest' if miss > 0 else 'below the lowest'} terrain the DEM holds within "
        f"{TAKEOFF_REACH_M:g} m of the frames ({lowest:.2f} … {highest:.2f} m in the flight's reference, "
        f"{target.describe()}), more than {_at_depth(tolerance_m, depth_m)}{_converted(conversion)}: the DEM "
        f"({_datum_words(dem)}) is probably in another vertical reference than the flight, or the flight's absolute "
        "heights are off (a drone without RTK measures them barometrically, often tens of metres off; its heights "
        "above the take-off point are good). Use a DEM made from this flight (e.g. OpenDroneMap's DSM, in the "
        f"frames' own heights), or refine the poses.{_hint(miss)}", source=dem.source)


def _crs_name(crs) -> str:
    text = f"EPSG:{crs}" if isinstance(crs, int) else str(crs)
    return text if len(text) <= 40 else text[:37] + "…"


# --------------------------------------------------------------------------- heightfield
class Heightfield:
    """Terrain ``U = H(E, N)`` in a local ENU frame (metres) on a regular grid, bilinear between nodes.

    Nodes are ``E_j = east0 + j·step``, ``N_i = north0 + i·step`` (row i grows *north*, unlike a
    raster), ``z[i, j]`` = local up coordinate of the terrain, NaN for no-data. Each cell is stored as
    its bilinear coefficients, so one gather evaluates height and gradient. Per tile of
    ``tile_cells × tile_cells`` cells the heightfield keeps an exact bound on the gradient magnitude of
    the bilinear surface, dilated over the 3 × 3 neighbouring tiles (infinite next to no-data): the
    certificate of the fast intersection path — and, per tile, the highest valid node over the 3 × 3
    neighbouring tiles: the ceiling marching rays skip down to, and that of the unknown terrain in
    no-data holes.
    """

    def __init__(self, east0: float, north0: float, step: float, z: np.ndarray, tile_cells: int | None = None):
        z = np.array(z, dtype=float)
        if z.ndim != 2 or min(z.shape) < 2:
            raise ValueError(f"heightfield needs at least 2 × 2 nodes, got shape {z.shape}")
        if not step > 0:
            raise ValueError(f"heightfield step must be positive, got {step}")
        if np.all(np.isnan(z)):
            raise ValueError("heightfield has no valid node")
        self.east0, self.north0, self.step = float(east0), float(north0), float(step)
        self.z = z
        self.shape = z.shape
        self.z_min, self.z_max = float(np.nanmin(z)), float(np.nanmax(z))
        z00, z10, z01, z11 = z[:-1, :-1], z[:-1, 1:], z[1:, :-1], z[1:, 1:]
        # H = z00 + b·x + c·y + d·x·y in cell units (x east, y north, both in [0, 1]).
        self._coef = np.stack([z00, z10 - z00, z01 - z00, z11 - z10 - z01 + z00], axis=-1).reshape(-1, 4)
        # |∂H/∂x| ≤ max(|b|, |b + d|), |∂H/∂y| ≤ max(|c|, |c + d|) over the cell: an exact bound.
        gx = np.maximum(np.abs(z10 - z00), np.abs(z11 - z01))
        gy = np.maximum(np.abs(z01 - z00), np.abs(z11 - z10))
        cell_grad = np.hypot(gx, gy) / self.step
        cell_grad[np.isnan(cell_grad)] = np.inf
        if tile_cells is None:
            # Tiles wide enough that a 35°-off-nadir ray's slab segment (relief · tan 35°) spans at most
            # two of them, so its gradient bound comes from one 3 × 3 neighbourhood.
            relief = self.z_max - self.z_min
            tile_cells = int(np.clip(math.ceil(0.5 * relief * math.tan(math.radians(35.0)) / self.step), 4, 64))
        self.tile_cells = int(tile_cells)
        self.tile_m = self.tile_cells * self.step
        self.tile_gradient = _dilated_tile_max(cell_grad, self.tile_cells)
        cell_top = np.fmax(np.fmax(z00, z10), np.fmax(z01, z11))  # NaN only where all four are no-data
        ceiling = _dilated_tile_max(np.where(np.isnan(cell_top), -np.inf, cell_top), self.tile_cells)
        self.tile_ceiling = np.where(np.isfinite(ceiling), ceiling, self.z_max)

    @property
    def east_max(self) -> float:
        return self.east0 + (self.shape[1] - 1) * self.step

    @property
    def north_max(self) -> float:
        return self.north0 + (self.shape[0] - 1) * self.step

    def node_coordinates(self):
        """Local east (cols,) and north (rows,) of the nodes."""
        return (self.east0 + np.arange(self.shape[1]) * self.step,
                self.north0 + np.arange(self.shape[0]) * self.step)

    def _cells(self, east, north):
        """Flat cell index, in-cell offsets (x, y in [0, 1]) and an inside-the-grid mask."""
        ny, nx = self.shape
        x = (np.asarray(east, dtype=float) - self.east0) / self.step
        y = (np.asarray(north, dtype=float) - self.north0) / self.step
        # A hair of slack so samples on the outer edge (rounding) still count as inside.
        inside = (x >= -1e-9) & (x <= nx - 1 + 1e-9) & (y >= -1e-9) & (y <= ny - 1 + 1e-9)
        j = np.clip(np.floor(np.where(inside, x, 0.0)), 0, nx - 2).astype(np.intp)
        i = np.clip(np.floor(np.where(inside, y, 0.0)), 0, ny - 2).astype(np.intp)
        return i * (nx - 1) + j, x - j, y - i, inside

    def height_at(self, east, north) -> np.ndarray:
        """Terrain U (m, local frame) at local east, north; NaN outside the grid or next to no-data."""
        cell, fx, fy, inside = self._cells(east, north)
        c = np.take(self._coef, cell, axis=0)  # far faster than fancy indexing for (N, 4) rows
        h = c[..., 0] + fx * (c[..., 1] + fy * c[..., 3]) + fy * c[..., 2]
        return np.where(inside, h, np.nan)

    def height_and_gradient(self, east, north):
        """Terrain U and its gradient ∂U/∂E, ∂U/∂N (dimensionless) at local east, north; NaN outside."""
        cell, fx, fy, inside = self._cells(east, north)
        c = np.take(self._coef, cell, axis=0)
        h = c[..., 0] + fx * (c[..., 1] + fy * c[..., 3]) + fy * c[..., 2]
        ge = (c[..., 1] + fy * c[..., 3]) / self.step
        gn = (c[..., 2] + fx * c[..., 3]) / self.step
        return np.where(inside, h, np.nan), ge, gn

    def _tile(self, east, north):
        ty, tx = self.tile_gradient.shape
        j = np.clip(np.floor((np.asarray(east) - self.east0) / self.tile_m), 0, tx - 1).astype(np.intp)
        i = np.clip(np.floor((np.asarray(north) - self.north0) / self.tile_m), 0, ty - 1).astype(np.intp)
        return i, j

    def gradient_bound(self, east, north) -> np.ndarray:
        """Bound on |∇H| over every point within ``tile_m`` of each (east, north) (inf near no-data)."""
        return self.tile_gradient[self._tile(east, north)]

    def terrain_ceiling(self, east, north) -> np.ndarray:
        """Highest valid terrain U within ``tile_m`` of each (east, north) — also the height no-data
        holes there are assumed not to exceed (the DEM's highest node where no valid node is that near)."""
        return self.tile_ceiling[self._tile(east, north)]


def _dilated_tile_max(cell_values: np.ndarray, tile: int) -> np.ndarray:
    """Max over tiles of ``tile × tile`` cells, then over each tile's 3 × 3 neighbourhood."""
    from scipy.ndimage import maximum_filter

    ny, nx = cell_values.shape
    ty, tx = -(-ny // tile), -(-nx // tile)
    padded = np.zeros((ty * tile, tx * tile))
    padded[:ny, :nx] = cell_values
    tiles = padded.reshape(ty, tile, tx, tile).max(axis=(1, 3))
    return maximum_filter(tiles, size=3, mode="nearest")


def heightfield_from_dem(dem: DemRaster, local: LocalFrame, extent=None, step_m: float | None = None,
                         vertical_offset_m: float = 0.0, max_nodes: int = 8_000_000) -> Heightfield:
    """Resample the DEM once into ``local``: nodes on a regular local E, N grid, bilinear from the DEM.

    ``extent`` = (east_min, east_max, north_min, north_max) in local metres (default: the DEM's cell-
    centre extent); ``step_m`` the node spacing (default: the DEM's cell size);
    ``vertical_offset_m`` is added to the DEM heights (from :func:`check_vertical_datum`).

    Each node is the exact local position of the DEM surface point whose local E, N is the node: local →
    geodetic (through ECEF) → the DEM's CRS → bilinear height → back, iterated on the node's U until the
    ellipsoidal heights agree to 1 µm (the local up and the ellipsoid normal differ by d/R, so U shifts
    E, N by ~1e-4 of its change: two or three rounds). Hence:

    * Earth curvature is represented, not approximated: a surface of constant ellipsoidal height drops
      d²/2R below the tangent plane (2 cm at 500 m, 8 cm at 1 km), exactly at the nodes; bilinear
      interpolation between nodes misses that curvature by step²/8R (20 nm for 1 m cells).
    * The local grid is turned against the DEM grid by the meridian convergence and scaled by the map's
      scale factor, so between nodes the heightfield is a bilinear resampling of the DEM's bilinear
      surface: exact on planar terrain, otherwise off by at most the DEM's own interpolation error
      (cell²·|curvature|/8).
    """
    crs = ProjectedCRS(dem.crs)
    step = float(step_m or dem.cell_size_m)
    if extent is None:
        extent = _dem_extent_local(dem, local, crs, vertical_offset_m)
    e_min, e_max, n_min, n_max = (float(v) for v in extent)
    nx = int(math.floor((e_max - e_min) / step)) + 1
    ny = int(math.floor((n_max - n_min) / step)) + 1
    if nx < 2 or ny < 2:
        raise InputError(f"the area to cover ({e_max - e_min:.1f} m × {n_max - n_min:.1f} m) is smaller than two "
                         f"DEM cells of {step:g} m", source=dem.source)
    if nx * ny > max_nodes:
        raise InputError(f"resampling the DEM at {step:g} m over {e_max - e_min:.0f} m × {n_max - n_min:.0f} m "
                         f"needs {nx * ny:,} nodes (limit {max_nodes:,}): clip the DEM to the flight or "
                         "resample it coarser", source=dem.source)
    east = e_min + np.arange(nx) * step
    z = np.empty((ny, nx))
    rows_per_chunk = max(1, 1_000_000 // nx)  # bounds the memory of the geodesy temporaries
    for r0 in range(0, ny, rows_per_chunk):
        north = n_min + np.arange(r0, min(r0 + rows_per_chunk, ny)) * step
        ee, nn = np.meshgrid(east, north)
        enu = np.column_stack([ee.ravel(), nn.ravel(), np.zeros(ee.size)])
        for _ in range(5):
            lat, lon, h_node = local.to_geodetic(enu)
            h_dem = dem.sample(*crs.from_geodetic(lat, lon)) + vertical_offset_m
            miss = np.where(np.isfinite(h_dem), h_dem - h_node, 0.0)
            enu[:, 2] += miss  # ∂h/∂U = 1 − O(d²/R²)
            if np.max(np.abs(miss)) < 1e-6:
                break
        z[r0:r0 + len(north)] = np.where(np.isfinite(h_dem), enu[:, 2], np.nan).reshape(len(north), nx)
    if np.all(np.isnan(z)):
        raise InputError("the DEM has no data inside the area of the flight; check its CRS and extent",
                         source=dem.source)
    return Heightfield(e_min, n_min, step, z)


def _dem_extent_local(dem, local, crs, vertical_offset_m):
    """Local bounding box (east_min, east_max, north_min, north_max) of the DEM's cell-centre grid."""
    x, y = dem.cell_centres()
    t = np.linspace(0.0, 1.0, 33)
    xs = np.concatenate([x[0] + t * (x[-1] - x[0]), np.full(33, x[-1]), x[-1] + t * (x[0] - x[-1]), np.full(33, x[0])])
    ys = np.concatenate([np.full(33, y[0]), y[0] + t * (y[-1] - y[0]), np.full(33, y[-1]), y[-1] + t * (y[0] - y[-1])])
    lat, lon = crs.to_geodetic(xs, ys)
    h = np.full(len(xs), float(np.nanmedian(dem.heights)) + vertical_offset_m)
    enu = local.from_geodetic(lat, lon, h)
    return enu[:, 0].min(), enu[:, 0].max(), enu[:, 1].min(), enu[:, 1].max()


# --------------------------------------------------------------------------- ray casting
@dataclass
class RayHits:
    """Result of :func:`intersect_heightfield`: ray parameters, points (local, m), validity, and which
    rays took the robust marching path."""

    t: np.ndarray
    points: np.ndarray
    valid: np.ndarray
    marched: np.ndarray


def _slab(origin, direction, lo, hi):
    """Parameter interval [t0, t1] where lo ≤ origin + t·direction ≤ hi (empty: t0 > t1)."""
    with np.errstate(divide="ignore", invalid="ignore"):
        ta = (lo - origin) / direction
        tb = (hi - origin) / direction
    t0, t1 = np.minimum(ta, tb), np.maximum(ta, tb)
    parallel = direction == 0
    inside = (origin >= lo) & (origin <= hi)
    t0 = np.where(parallel, np.where(inside, -np.inf, np.inf), t0)
    t1 = np.where(parallel, np.where(inside, np.inf, -np.inf), t1)
    return t0, t1


def intersect_heightfield(hf: Heightfield, origins, directions, start_height=None, fast: bool = True,
                          tol_m: float = 1e-7, max_iter: int = 60) -> RayHits:
    """First intersection of rays ``origins + t·directions`` (t ≥ 0, local frame) with the terrain.

    ``start_height`` (N,) is the level-plane estimate of each ray's terrain height (local U), e.g. the
    terrain under the camera; NaN or None: the middle of the slab. ``fast=False`` sends every ray down
    the robust marching path (for tests and comparisons). Convergence: |U − H| ≤ ``tol_m`` or a bracket
    shorter than ``tol_m`` along the ray. See the module docstring for the method and its guarantees.
    """
    o = np.asarray(origins, dtype=float).reshape(-1, 3)
    d = np.asarray(directions, dtype=float).reshape(-1, 3)
    n = len(o)
    # Contiguous columns: 1-D gathers are several times faster than row gathers of (N, 3) arrays.
    oe, on, ou = np.ascontiguousarray(o.T)
    de, dn, du = np.ascontiguousarray(d.T)
    t_hit = np.full(n, np.nan)
    marched = np.zeros(n, dtype=bool)
    d_h = np.hypot(de, dn)
    t_e0, t_e1 = _slab(oe, de, hf.east0, hf.east_max)
    t_n0, t_n1 = _slab(on, dn, hf.north0, hf.north_max)
    t_u0, t_u1 = _slab(ou, du, hf.z_min, hf.z_max)
    box_in, box_out = np.maximum(t_e0, t_n0), np.minimum(t_e1, t_n1)
    start, end = np.maximum(t_u0, 0.0), t_u1
    # A hit needs the ray inside the slab, and over the DEM from the moment it enters the slab.
    candidate = (start <= end) & (box_in <= start) & (start <= box_out)
    stop = np.minimum(end, box_out)

    # A camera inside the slab must be above the terrain (or above the ceiling of a hole under it).
    idx = np.flatnonzero(candidate & (start == 0.0))
    if len(idx):
        below = hf.height_at(oe[idx], on[idx])
        below = np.where(np.isnan(below), hf.terrain_ceiling(oe[idx], on[idx]), below)
        candidate[idx[~(ou[idx] >= below)]] = False

    todo = np.flatnonzero(candidate)
    if fast and len(todo):
        sel = todo[(du[todo] < 0) & (box_out[todo] >= end[todo])]
        lo, hi, dh = start[sel], end[sel], d_h[sel]
        t_mid = 0.5 * (lo + hi)
        g = hf.gradient_bound(oe[sel] + t_mid * de[sel], on[sel] + t_mid * dn[sel])
        good = ((hi - lo) * dh <= 2.0 * hf.tile_m) & (g * dh < -du[sel])
        certified, lo, hi = sel[good], lo[good], hi[good]
        if len(certified):
            z0 = np.full(len(certified), 0.5 * (hf.z_min + hf.z_max))
            if start_height is not None:
                sh = np.broadcast_to(np.asarray(start_height, dtype=float), (n,))[certified]
                z0 = np.where(np.isfinite(sh), sh, z0)
            columns = (oe, on, ou, de, dn, du)
            rays = columns if len(certified) == n else tuple(c[certified] for c in columns)
            t0 = np.clip((z0 - rays[2]) / rays[5], lo, hi)
            t, ok = _refine(hf, rays, lo, hi, t0, tol_m, max_iter)
            t_hit[certified[ok]] = t[ok]
            candidate[certified[ok]] = False
    rest = np.flatnonzero(candidate)
    if len(rest):
        marched[rest] = True
        rays = tuple(c[rest] for c in (oe, on, ou, de, dn, du))
        t_hit[rest] = _march(hf, rays, d_h[rest], start[rest], stop[rest], tol_m, max_iter)
    valid = np.isfinite(t_hit)
    points = o + np.where(valid, t_hit, np.nan)[:, None] * d
    return RayHits(t_hit, points, valid, marched)


def _refine(hf, rays, lo, hi, t0, tol_m, max_iter):
    """Root of f(t) = U(t) − H(E, N) in [lo, hi] with f(lo) ≥ 0 ≥ f(hi), from t0, for ``rays`` given as
    columns (oe, on, ou, de, dn, du): a Newton step; where it leaves the bracket, the height-iteration
    step t + f/|d_U| (Newton with the terrain taken as level); where that leaves it too, bisection.
    Returns t and a converged mask (a NaN height on the way or no convergence: not converged)."""
    n = len(lo)
    t_out = np.full(n, np.nan)
    ok = np.zeros(n, dtype=bool)
    oe, on, ou, de, dn, du = rays
    speed = np.sqrt(de * de + dn * dn + du * du)
    act = np.arange(n)
    lo, hi, t = lo.copy(), hi.copy(), t0.copy()
    for _ in range(max_iter):
        h, ge, gn = hf.height_and_gradient(oe + t * de, on + t * dn)
        f = ou + t * du - h
        above = f > 0
        lo = np.where(above, t, lo)
        hi = np.where(above, hi, t)
        with np.errstate(divide="ignore", invalid="ignore"):
            t_new = t - f / (du - ge * de - gn * dn)
            t_level = t - f / du
        t_new = np.where((t_new > lo) & (t_new < hi), t_new,
                         np.where((t_level > lo) & (t_level < hi), t_level, 0.5 * (lo + hi)))
        on_surface = np.abs(f) <= tol_m
        done = on_surface | ((hi - lo) * speed <= tol_m)
        finished = done | np.isnan(f)
        if np.any(finished):
            idx = np.flatnonzero(done)
            t_out[act[idx]] = np.where(on_surface[idx], t[idx], t_new[idx])
            ok[act[idx]] = True
            keep = ~finished
            act, lo, hi, t_new = act[keep], lo[keep], hi[keep], t_new[keep]
            oe, on, ou, de, dn, du, speed = (c[keep] for c in (oe, on, ou, de, dn, du, speed))
        t = t_new
        if len(act) == 0:
            break
    return t_out, ok


def _skip_empty_space(hf, rays, d_h, start, stop, max_rounds: int = 64):
    """Advance each ray while it is above the highest terrain within ``tile_m`` of it (the tile
    ceiling): by at most ``tile_m`` horizontally, and no lower than that ceiling — so it meets no
    terrain on the way and stays above the terrain where it stops."""
    oe, on, ou, de, dn, du = rays
    start = start.copy()
    act = np.arange(len(start))
    for _ in range(max_rounds):
        t = start[act]
        u = ou[act] + t * du[act]
        room = u - hf.terrain_ceiling(oe[act] + t * de[act], on[act] + t * dn[act])
        with np.errstate(divide="ignore", invalid="ignore"):
            by_reach = hf.tile_m / d_h[act]
            by_height = np.where(du[act] < 0, room / -du[act], np.inf)
        dt = np.where(room > 0, np.minimum(by_reach, by_height), 0.0)
        start[act] = np.minimum(t + dt, stop[act])
        # Keep skipping only where the step was worth a few samples of the fine march.
        act = act[(dt * d_h[act] > 2.0 * hf.step) & (start[act] < stop[act])]
        if len(act) == 0:
            break
    return start


def _march(hf, rays, d_h, start, stop, tol_m, max_iter):
    """Robust path: skip the empty space above the terrain tile by tile, then sample f up to ``stop``
    every half cell (horizontally), take the first sample at or below the terrain — or over no-data
    below the hole's ceiling, where the ray may have hit unknown terrain — and refine in its bracket.
    NaN: no (known) hit over the DEM."""
    oe, on, ou, de, dn, du = rays
    n = len(start)
    t_hit = np.full(n, np.nan)
    start = _skip_empty_space(hf, rays, d_h, start, stop)
    n_steps = np.maximum(np.ceil((stop - start) * d_h / (0.5 * hf.step)), 1.0)
    dt = (stop - start) / n_steps
    lo_t = np.full(n, np.nan)
    hi_t = np.full(n, np.nan)
    act = np.arange(n)
    k0, block = 0, 8
    while len(act):
        ks = np.minimum(k0 + np.arange(block)[None, :], n_steps[act, None])
        t = start[act, None] + ks * dt[act, None]
        e, nn, u = (o[act, None] + t * dd[act, None] for o, dd in ((oe, de), (on, dn), (ou, du)))
        f = u - hf.height_at(e, nn)
        unknown = np.isnan(f)
        if np.any(unknown):
            unknown[unknown] = u[unknown] <= hf.terrain_ceiling(e[unknown], nn[unknown])
        stopped = (f <= 0) | unknown
        first = np.argmax(stopped, axis=1)
        found = stopped[np.arange(len(act)), first]
        rows = np.flatnonzero(found)
        hit = rows[f[rows, first[rows]] <= 0]  # NaN: the ray may have hit a hole's unknown terrain first
        k_hit = first[hit] + k0
        idx = act[hit]
        lo_t[idx] = start[idx] + np.maximum(k_hit - 1, 0) * dt[idx]
        hi_t[idx] = start[idx] + k_hit * dt[idx]
        exhausted = ~found & (k0 + block > n_steps[act])  # left the DEM (or the slab) without a hit
        act = act[~(found | exhausted)]
        k0 += block
        # Longer blocks for the long (grazing) rays that remain, within ~2 M samples per block.
        block = int(min(2 * block, 256, max(8, 2_000_000 // max(len(act), 1))))
    bracket = np.flatnonzero(np.isfinite(hi_t))
    if len(bracket):
        lo, hi = lo_t[bracket], hi_t[bracket]
        t, ok = _refine(hf, tuple(c[bracket] for c in rays), lo, hi, hi.copy(), tol_m, max_iter)
        t_hit[bracket[ok]] = t[ok]
    return t_hit


# --------------------------------------------------------------------------- the ground model
class DemGround(GroundModel):
    """Terrain from a DEM heightfield, per frame of a :class:`~.poses.FrameGeometry`.

    ``intersect`` casts each ray to its first terrain hit (invalid: misses the DEM, leaves its extent
    or reaches no-data first); ``place`` moves points along their frame's up onto the terrain (NaN off
    the DEM). The fast path starts from the level plane through the terrain under each camera.
    Frames without a ground height are placed like the others (the terrain is known without one).
    """

    needs_ground_height = False

    def __init__(self, geometry: FrameGeometry, heightfield: Heightfield):
        self.geometry = geometry
        self.heightfield = heightfield
        self.up = geometry.up
        below = heightfield.height_at(geometry.C[:, 0], geometry.C[:, 1])
        # Per frame, the level-plane estimate the fast path starts from: the terrain under the camera
        # (the altimeter's level ground where the DEM has none there).
        self.nadir_height = np.where(np.isfinite(below), below, geometry.ground_point[:, 2])

    @classmethod
    def from_dem(cls, geometry: FrameGeometry, dem: DemRaster, tolerance_m: float | None = None,
                 step_m: float | None = None, vertical_offset_m: float | None = None) -> "DemGround":
        """Convert the DEM into the poses' vertical reference and check it against their ground
        (:func:`check_vertical_datum`), resample it into the geometry's local frame over the area the frames can
        see, and build the ground model.

        ``vertical_offset_m``: the offset :func:`check_vertical_datum` already gave for the whole flight
        (the check is then not repeated on this geometry's frames alone)."""
        offset = (check_vertical_datum(dem, geometry.poses, tolerance_m).offset_m
                  if vertical_offset_m is None else float(vertical_offset_m))
        full = _dem_extent_local(dem, geometry.local, ProjectedCRS(dem.crs), offset)
        seen = _visible_extent(geometry, float(np.nanmin(dem.heights)) + offset - geometry.local.h0)
        step = float(step_m or dem.cell_size_m)
        extent = full if seen is None else (max(full[0], seen[0] - 2 * step), min(full[1], seen[1] + 2 * step),
                                            max(full[2], seen[2] - 2 * step), min(full[3], seen[3] + 2 * step))
        if extent[0] >= extent[1] or extent[2] >= extent[3]:
            raise InputError("no frame sees the DEM: check the DEM's CRS and that it covers the flight",
                             source=dem.source)
        return cls(geometry, heightfield_from_dem(dem, geometry.local, extent, step, offset))

    def intersect(self, frame_idx, origins, directions):
        frame_idx = np.asarray(frame_idx, dtype=np.int64)
        hits = intersect_heightfield(self.heightfield, origins, directions, self.nadir_height[frame_idx])
        return hits.points, hits.valid

    def place(self, frame_idx, points):
        """Points moved along their frame's up n until U = H(E, N): s = (H(P + s·n) − U_P) / n_U,
        iterated (the horizontal drift s·n_h is ~1e-4·s, so two rounds reach nanometres)."""
        frame_idx = np.asarray(frame_idx, dtype=np.int64)
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        n = self.up[frame_idx]
        s = np.zeros(len(p))
        for _ in range(4):
            q = p + s[:, None] * n
            s_new = (self.heightfield.height_at(q[:, 0], q[:, 1]) - p[:, 2]) / n[:, 2]
            converged = np.nanmax(np.abs(s_new - s), initial=0.0) < 1e-10
            s = s_new
            if converged:
                break
        return p + s[:, None] * n

    def occluded(self, frame_idx, points, tolerance_m: float = 0.05) -> np.ndarray:
        """True where the terrain hides a ground point (N, 3) from its frame's camera: the ray from the
        camera towards the point hits the terrain more than ``tolerance_m`` before it (or misses it).
        Points are used as given: place them on the terrain first."""
        frame_idx = np.asarray(frame_idx, dtype=np.int64)
        p = np.asarray(points, dtype=float).reshape(-1, 3)
        c = self.geometry.C[frame_idx]
        hits = intersect_heightfield(self.heightfield, c, p - c, self.nadir_height[frame_idx])
        short = (1.0 - hits.t) * np.linalg.norm(p - c, axis=1)  # distance from the hit on to the point
        return ~(hits.valid & (short <= tolerance_m))


@dataclass(frozen=True, eq=False)
class DemGroundFactory:
    """The ground-model factory (``FrameGeometry -> DemGround``) core code takes as ``ground`` for a DEM:
    :meth:`DemGround.from_dem`, the DEM converted into each geometry's vertical reference and checked against its
    ground (``tolerance_m``: None follows the flight's height above ground), or shifted by ``vertical_offset_m``
    when the whole flight was checked once already (:func:`check_vertical_datum`)."""

    dem: DemRaster
    tolerance_m: float | None = None
    vertical_offset_m: float | None = None
    needs_ground_height = False

    def __call__(self, geometry: FrameGeometry) -> DemGround:
        return DemGround.from_dem(geometry, self.dem, self.tolerance_m, vertical_offset_m=self.vertical_offset_m)


def _visible_extent(geometry: FrameGeometry, lowest_u: float, per_edge: int = 8):
    """Local (east_min, east_max, north_min, north_max) the frames' image borders can reach down to the
    height ``lowest_u``; None when some frame sees the horizon (then any part of the DEM may be seen)."""
    border = geometry.camera.boundary_pixels(per_edge)
    f, k = len(geometry), len(border)
    fi = np.repeat(np.arange(f), k)
    d = geometry.rays(fi, np.tile(border, (f, 1)))
    c = geometry.C[fi]
    drop = c[:, 2] - lowest_u + 1.0  # +1 m: the curvature drop of the far DEM, and rounding
    if np.any(d[:, 2] >= 0) or np.any(drop <= 0):
        return None
    reach = c[:, :2] + (drop / -d[:, 2])[:, None] * d[:, :2]
    lo = np.minimum(reach.min(axis=0), geometry.C[:, :2].min(axis=0))
    hi = np.maximum(reach.max(axis=0), geometry.C[:, :2].max(axis=0))
    return lo[0], hi[0], lo[1], hi[1]


# --------------------------------------------------------------------------- terrain slope per frame
@dataclass
class FrameSlope:
    """Terrain plane under each frame's footprint: slope (deg from the frame's level), aspect (deg
    clockwise from true north, the direction the slope faces = downhill), RMS of the terrain about the
    plane (m), and the number of terrain samples fitted (NaN slope: fewer than 3 samples)."""

    slope_deg: np.ndarray
    aspect_deg: np.ndarray
    rms_m: np.ndarray
    n_samples: np.ndarray


def terrain_in_view(geometry: FrameGeometry, ground: DemGround, grid=(9, 7), progress=None, is_canceled=None,
                    chunk: int = 2000) -> np.ndarray:
    """Local points (F, K, 3) where a ``grid`` (columns × rows, K = columns·rows) of pixels spread over the whole
    image meets the terrain, per frame; NaN where the ray misses it — so they lie inside the footprint, on the
    visible terrain, at any DEM resolution."""
    cam = geometry.camera
    uu, vv = np.meshgrid(np.linspace(-0.5, cam.width - 0.5, grid[0]), np.linspace(-0.5, cam.height - 0.5, grid[1]))
    uv = np.column_stack([uu.ravel(), vv.ravel()])
    k = len(uv)
    f_total = len(geometry)
    pts = np.full((f_total, k, 3), np.nan)
    for a in range(0, f_total, chunk):
        check_cancel(is_canceled)
        frames = np.arange(a, min(a + chunk, f_total))
        fi = np.repeat(frames, k)
        p, ok = ground.intersect(fi, geometry.C[fi], geometry.rays(fi, np.tile(uv, (len(frames), 1))))
        pts[frames] = np.where(ok[:, None], p, np.nan).reshape(len(frames), k, 3)
        if progress is not None:
            progress(frames[-1] / max(f_total - 1, 1))
    return pts


def frame_terrain_slope(geometry: FrameGeometry, ground: DemGround, grid=(9, 7), progress=None,
                        is_canceled=None, chunk: int = 2000) -> FrameSlope:
    """Fit a plane to the terrain each frame sees and return its slope and aspect.

    The samples are :func:`terrain_in_view`'s. The plane ``U = a + b·E + c·N`` is fitted by least squares in the
    local frame; the slope is the angle between its normal and the frame's up (the level plane's normal).
    """
    pts = terrain_in_view(geometry, ground, grid, progress, is_canceled, chunk)
    f_total, k = pts.shape[:2]
    valid = np.isfinite(pts[..., 2])
    count = valid.sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = np.nansum(pts, axis=1) / count[:, None]
        c = np.where(valid[..., None], pts - mean[:, None, :], 0.0)
        see, snn, sen = (c[..., 0] ** 2).sum(1), (c[..., 1] ** 2).sum(1), (c[..., 0] * c[..., 1]).sum(1)
        seu, snu = (c[..., 0] * c[..., 2]).sum(1), (c[..., 1] * c[..., 2]).sum(1)
        det = see * snn - sen ** 2
        b = (snn * seu - sen * snu) / det
        cc = (see * snu - sen * seu) / det
        resid = np.where(valid, c[..., 2] - b[:, None] * c[..., 0] - cc[:, None] * c[..., 1], 0.0)
        rms = np.sqrt((resid ** 2).sum(1) / count)
    normal = np.column_stack([-b, -cc, np.ones(f_total)])
    normal /= np.linalg.norm(normal, axis=1, keepdims=True)
    slope = np.degrees(np.arccos(np.clip(np.einsum("fi,fi->f", normal, geometry.up), -1.0, 1.0)))
    ned = geometry.local.rotation_from_ned(geometry.poses.lat, geometry.poses.lon)  # columns: N, E, D
    aspect = np.degrees(np.arctan2(np.einsum("fi,fi->f", normal, ned[:, :, 1]),
                                   np.einsum("fi,fi->f", normal, ned[:, :, 0]))) % 360.0
    fitted = (count >= 3) & (np.abs(det) > 1e-12)
    nan = np.full(f_total, np.nan)
    return FrameSlope(np.where(fitted, slope, nan), np.where(fitted, aspect, nan), np.where(fitted, rms, nan), count)


def exceeds_flat_envelope(slope: FrameSlope, envelope_deg: float = 10.0) -> np.ndarray:
    """Frames (bool mask) whose terrain is steeper than the level plane's envelope (NaN slope: False)."""
    with np.errstate(invalid="ignore"):
        return np.asarray(slope.slope_deg) > float(envelope_deg)


def flat_envelope_warning(frame_ids, slope: FrameSlope, envelope_deg: float = 10.0) -> str | None:
    """A message for the user when frames lie on terrain steeper than the envelope, else None."""
    steep = exceeds_flat_envelope(slope, envelope_deg)
    if not np.any(steep):
        return None
    ids = np.asarray(frame_ids)[steep]
    shown = ", ".join(str(i) for i in ids[:8]) + (", …" if len(ids) > 8 else "")
    return (f"{int(steep.sum())} of {len(steep)} frames lie on terrain steeper than {envelope_deg:g}° (up to "
            f"{np.nanmax(slope.slope_deg[steep]):.1f}°; frames {shown}): the level-plane ground model puts their "
            "labels off target there — give a DEM to project onto the terrain.")

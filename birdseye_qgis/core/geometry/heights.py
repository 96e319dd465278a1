"""Heights: what each one is measured from, its unit, and the one place that converts between them.

A height without its reference is a bug waiting for a real file (docs/design.md#heights). Every height
BirdsEye reads is tagged with a :class:`VerticalReference`:

* ``ellipsoidal`` — above the WGS84 ellipsoid: RTK rovers, INS pose logs, geocentric camera solutions;
* a **named geoid** (``EGM96``, ``EGM2008``) — above mean sea level as that geoid model defines it: DJI's
  ``AbsoluteAltitude`` and EXIF ``GPSAltitude`` (GNSS receivers report MSL with EGM96), images' GPS heights
  a photogrammetry package aligned to;
* ``msl`` — above mean sea level, the geoid not named (a national height system, a DEM's "MSL");
* ``unknown`` — nobody said; such heights can only be checked against another source, never converted.

Conversion: ``h_ellipsoidal = h_geoid + N(lat, lon)`` with N the geoid undulation. N of a named geoid comes
from PROJ and its geoid grid (Debian's ``proj-data`` ships EGM96 as ``egm96_15.gtx``; PROJ's CDN names it
``us_nga_egm96_15.tif``), unless the user gives N (``GEOID_UNDULATION_M``), which then stands for every
mean-sea-level height of the run. Where the grid is missing and no N is given the conversion stops, naming
the grid and how to install it (:class:`GeoidGridMissing`): it never falls back to N = 0, as PROJ's
"ballpark" operation would. Two heights in the same reference are compared without any N; an unnamed
``msl`` and a named geoid are taken as the same mean sea level when no N is given, and the conversion says
so (:attr:`HeightShift.note`).

Units: metres inside ``core``; :func:`metres_per_unit` knows the international foot (0.3048 m) and the US
survey foot (1200/3937 m), 2 ppm apart — 2 mm per km of height, but 4 m on a State Plane easting.

A flight's frames carry their camera heights' reference and, per frame, where the ground height came from
(:data:`GROUND_SOURCES`; ``poses.FramePoses``): the DEM check (``dem.check_vertical_datum``) compares a DEM
with a ground measured under the frame (altimeter, tie points, a DEM) frame by frame, and with a take-off
point's height (take-off, flight height, control points) only as a height the terrain around has.
"""
from __future__ import annotations

import functools
import math
import re
import warnings
from dataclasses import dataclass

import numpy as np

from ..errors import InputError
from .geodesy import ensure_proj_data, on_python_thread

ELLIPSOIDAL, GEOID, MSL, UNKNOWN = "ellipsoidal", "geoid", "msl", "unknown"
#: Geoid models BirdsEye converts with PROJ: name → (EPSG code of the vertical CRS, grid file names PROJ
#: knows it by, newest first).
GEOID_MODELS = {
    "EGM96": (5773, ("us_nga_egm96_15.tif", "egm96_15.gtx")),
    "EGM2008": (3855, ("us_nga_egm08_25.tif", "egm08_25.gtx")),
}
#: Geoid undulations lie within about −107 m … +86 m (EGM2008): a larger N is not an undulation.
MAX_UNDULATION_M = 110.0


@dataclass(frozen=True)
class VerticalReference:
    """What a height is measured from: ``kind`` (``ellipsoidal``, ``geoid``, ``msl``, ``unknown``) and, for a
    geoid, its model name (one of :data:`GEOID_MODELS`)."""

    kind: str = ELLIPSOIDAL
    geoid: str = ""

    def __post_init__(self):
        if self.kind not in (ELLIPSOIDAL, GEOID, MSL, UNKNOWN):
            raise InputError(f"vertical reference kind {self.kind!r} is not one of ellipsoidal, geoid, msl, unknown")
        if (self.kind == GEOID) != bool(self.geoid):
            raise InputError("a geoid reference names its geoid model, and only a geoid reference does")
        if self.geoid and self.geoid not in GEOID_MODELS:
            raise InputError(f"geoid model {self.geoid!r} is not one of {', '.join(GEOID_MODELS)}")

    @classmethod
    def parse(cls, text, source: str | None = None, row: int | None = None,
              field: str | None = None) -> "VerticalReference":
        """The reference a text names: ``ellipsoidal``, ``msl``, ``unknown`` or a geoid model name
        (``EGM96``; case ignored). Empty or None: :data:`UNKNOWN`."""
        value = str(text or "").strip()
        lowered = value.lower()
        if lowered in ("", UNKNOWN):
            return UNKNOWN_REFERENCE
        if lowered in (ELLIPSOIDAL, "wgs84", "ellipsoid"):
            return ELLIPSOIDAL_REFERENCE
        if lowered in (MSL, "mean sea level", "orthometric"):
            return MSL_REFERENCE
        for name in GEOID_MODELS:
            if lowered == name.lower():
                return cls(GEOID, name)
        raise InputError(f"{value!r} is not a vertical reference (ellipsoidal, msl, unknown, or a geoid model: "
                         f"{', '.join(GEOID_MODELS)})", source=source, row=row, field=field)

    @property
    def text(self) -> str:
        """The reference as a frame layer stores it (:meth:`parse` reads it back)."""
        return self.geoid or self.kind

    @property
    def above_sea_level(self) -> bool:
        return self.kind in (GEOID, MSL)

    def describe(self) -> str:
        """The reference in words, for messages."""
        if self.kind == GEOID:
            return f"above mean sea level ({self.geoid} geoid)"
        return {ELLIPSOIDAL: "ellipsoidal (WGS84)", MSL: "above mean sea level (geoid not named)",
                UNKNOWN: "in an unstated reference"}[self.kind]


ELLIPSOIDAL_REFERENCE = VerticalReference(ELLIPSOIDAL)
MSL_REFERENCE = VerticalReference(MSL)
UNKNOWN_REFERENCE = VerticalReference(UNKNOWN)
EGM96_REFERENCE = VerticalReference(GEOID, "EGM96")

# ------------------------------------------------------------------------------------------ ground sources
#: Where a frame's ground height came from. Under the frame: measured there (radar altimeter; the median
#: height of the tie points it sees; a DEM). Site level: one height for the site that the terrain under a
#: frame may lie above or below (the take-off point: DJI's AbsoluteAltitude − RelativeAltitude; the camera
#: heights minus a flight height the user gave; a ground height the user gave; the median surveyed height of
#: control points or geotags). None: no ground.
ALTIMETER, TIE_POINTS, DEM_GROUND = "altimeter", "tie_points", "dem"
TAKEOFF, FLIGHT_HEIGHT, GIVEN = "takeoff", "flight_height", "given"
CONTROL_POINTS, GEOTAGS = "control_points", "geotags"
NO_GROUND = ""
UNDER_FRAME_SOURCES = (ALTIMETER, TIE_POINTS, DEM_GROUND)
SITE_LEVEL_SOURCES = (TAKEOFF, FLIGHT_HEIGHT, GIVEN, CONTROL_POINTS, GEOTAGS)
GROUND_SOURCES = UNDER_FRAME_SOURCES + SITE_LEVEL_SOURCES + (NO_GROUND,)


def parse_ground_source(text, source: str | None = None, row: int | None = None, field: str | None = None) -> str:
    """A frame's ground source as a frame layer stores it (empty or None: none)."""
    value = str(text or "").strip().lower()
    if value not in GROUND_SOURCES:
        raise InputError(f"{text!r} is not a ground source ({', '.join(s for s in GROUND_SOURCES if s)}, or empty)",
                         source=source, row=row, field=field)
    return value


# ------------------------------------------------------------------------------------------ units
#: Metres per unit, by the names files give units (lower case). The US survey foot is 1200/3937 m exactly.
US_SURVEY_FOOT_M = 1200.0 / 3937.0
INTERNATIONAL_FOOT_M = 0.3048
_UNITS = {
    "m": 1.0, "metre": 1.0, "meter": 1.0, "metres": 1.0, "meters": 1.0,
    "ft": INTERNATIONAL_FOOT_M, "foot": INTERNATIONAL_FOOT_M, "feet": INTERNATIONAL_FOOT_M,
    "international foot": INTERNATIONAL_FOOT_M, "intl ft": INTERNATIONAL_FOOT_M, "ift": INTERNATIONAL_FOOT_M,
    "us survey foot": US_SURVEY_FOOT_M, "us survey feet": US_SURVEY_FOOT_M, "us-ft": US_SURVEY_FOOT_M,
    "ftus": US_SURVEY_FOOT_M, "us_survey_foot": US_SURVEY_FOOT_M, "foot_us": US_SURVEY_FOOT_M,
    "us foot": US_SURVEY_FOOT_M, "us ft": US_SURVEY_FOOT_M, "usft": US_SURVEY_FOOT_M, "sft": US_SURVEY_FOOT_M,
}
#: The unit names :func:`metres_per_unit` takes, for messages and choices.
UNIT_NAMES = {"metre": 1.0, "international foot": INTERNATIONAL_FOOT_M, "US survey foot": US_SURVEY_FOOT_M}


def metres_per_unit(unit: str, source: str | None = None, row: int | None = None, field: str | None = None) -> float:
    """Metres in one ``unit`` (a name such as ``m``, ``ft``, ``ftUS``, ``US survey foot``; case ignored).
    An unknown unit is refused, naming it."""
    factor = _UNITS.get(str(unit or "").strip().lower())
    if factor is None:
        raise InputError(f"'{unit}' is not a length unit BirdsEye knows (metres, international feet 'ft', US survey "
                         "feet 'ftUS')", source=source, row=row, field=field)
    return factor


_CRS_UNIT = re.compile(r"\((ftUS|US survey foot|US ft|ft|foot|feet|m|metre|meter)\)\s*$", re.IGNORECASE)


def crs_name_units(name: str) -> tuple[float | None, float | None]:
    """Metres per unit of a coordinate-system name's horizontal and vertical parts, as surveying apps write
    them (``NAD83(2011) / Illinois West (ftUS) + NAVD88(GEOID18) height (ftUS)``): each part's trailing unit in
    parentheses; None where a part names none (or there is no vertical part)."""
    parts = [p.strip() for p in str(name or "").split(" + ", 1)]
    found = []
    for part in parts:
        match = _CRS_UNIT.search(part)
        found.append(metres_per_unit(match.group(1)) if match else None)
    return found[0], (found[1] if len(found) > 1 else None)


# ------------------------------------------------------------------------------------------ geoid undulation
class GeoidGridMissing(InputError):
    """The geoid grid a conversion needs is not installed, and no undulation was given."""


@on_python_thread
@functools.lru_cache(maxsize=None)
def _geoid_transformer(geoid: str):
    """PROJ's best transformation from WGS84 ellipsoidal heights to ``geoid`` heights, or GeoidGridMissing."""
    ensure_proj_data()
    from pyproj.transformer import TransformerGroup

    epsg, grids = GEOID_MODELS[geoid]
    with warnings.catch_warnings():  # pyproj warns of the missing grid; the error below says more
        warnings.simplefilter("ignore", UserWarning)
        group = TransformerGroup("EPSG:4979", f"EPSG:4326+{epsg}", always_xy=True)
    usable = [t for t in group.transformers if "ballpark" not in (t.description or "").lower()]
    if not group.best_available or not usable:
        raise GeoidGridMissing(
            f"converting between ellipsoidal and {geoid} heights needs PROJ's {geoid} geoid grid "
            f"({' or '.join(grids)}), which is not installed. Install it (Debian/Ubuntu: the package proj-data; "
            f"OSGeo4W: proj-data; or copy https://cdn.proj.org/{grids[0]} into PROJ's user folder, "
            f"{_proj_user_folder()}), or give the geoid undulation N at the site (GEOID_UNDULATION_M, ellipsoidal = "
            "MSL + N)", field="GEOID_UNDULATION_M")
    return usable[0]


@on_python_thread
def _proj_user_folder() -> str:
    from pyproj.datadir import get_user_data_dir  # pyproj ≥ 3.0, older than any QGIS 3.22 ships

    return get_user_data_dir()


@on_python_thread
def geoid_undulation(lat, lon, geoid: str = "EGM96") -> np.ndarray:
    """N (m) of geoid model ``geoid`` at WGS84 latitudes/longitudes (deg): ellipsoidal = geoid height + N.
    Through PROJ and the geoid grid; :class:`GeoidGridMissing` when the grid is not installed."""
    transformer = _geoid_transformer(geoid)
    lat, lon = np.broadcast_arrays(np.asarray(lat, dtype=float), np.asarray(lon, dtype=float))
    _, _, geoid_height = transformer.transform(lon.ravel(), lat.ravel(), np.zeros(lat.size))
    undulation = -np.asarray(geoid_height, dtype=float).reshape(lat.shape)
    if not np.all(np.isfinite(undulation) & (np.abs(undulation) <= MAX_UNDULATION_M)):
        raise GeoidGridMissing(f"PROJ gave no usable {geoid} undulation at some of these positions (outside its grid?)",
                               field="GEOID_UNDULATION_M")
    return undulation


def geoid_grid_installed(geoid: str = "EGM96") -> bool:
    try:
        _geoid_transformer(geoid)
    except GeoidGridMissing:
        return False
    return True


# ------------------------------------------------------------------------------------------ conversion
@dataclass(frozen=True)
class HeightShift:
    """What to add to heights in ``source`` to express them in ``target``, at the positions it was asked for
    (``offset_m``, an array), and how it was found, in words (``note``: empty when nothing was converted)."""

    source: VerticalReference
    target: VerticalReference
    offset_m: np.ndarray
    note: str = ""

    @property
    def median_m(self) -> float:
        return float(np.median(self.offset_m)) if np.size(self.offset_m) else 0.0


def undulation(reference: VerticalReference, lat, lon, given_m: float | None = None) -> tuple[np.ndarray, str]:
    """N (m) of ``reference`` at the positions (ellipsoidal = height + N) and where it came from, in words.

    Ellipsoidal: 0. A named geoid: ``given_m`` when given, else PROJ's grid (:func:`geoid_undulation`). ``msl``:
    ``given_m``, else refused (no model to compute it from). ``unknown``: refused."""
    lat = np.asarray(lat, dtype=float)
    if reference.kind == ELLIPSOIDAL:
        return np.zeros(lat.shape), ""
    if reference.kind == UNKNOWN:
        raise InputError("heights in an unstated vertical reference cannot be converted: state what they are "
                         "measured from")
    if given_m is not None and math.isfinite(float(given_m)):
        return np.full(lat.shape, float(given_m)), f"N = {float(given_m):+.2f} m as given"
    if reference.kind == MSL:
        hint = ""
        try:
            hint = f" (EGM96 puts it at {float(np.median(geoid_undulation(lat, lon))):+.2f} m here)"
        except GeoidGridMissing:
            pass
        raise InputError("heights above mean sea level with no geoid named: give the geoid undulation N at the site "
                         f"(GEOID_UNDULATION_M, ellipsoidal = MSL + N){hint}", field="GEOID_UNDULATION_M")
    n = geoid_undulation(lat, lon, reference.geoid)
    return n, f"N = {float(np.median(n)):+.2f} m from the {reference.geoid} grid (PROJ)"


def height_shift(source: VerticalReference, target: VerticalReference, lat, lon,
                 given_undulation_m: float | None = None) -> HeightShift:
    """The shift taking heights in ``source`` to ``target`` at the positions (``h_target = h_source + offset``).

    The same reference: 0, nothing asked. An unnamed ``msl`` against a named geoid with no N given: 0, the
    same mean sea level assumed (said in the note). Otherwise through the ellipsoid, ``N_source − N_target``
    (:func:`undulation`); an ``unknown`` side is refused, as is a conversion whose N is nowhere to be had."""
    lat = np.asarray(lat, dtype=float)
    if source == target:
        return HeightShift(source, target, np.zeros(lat.shape))
    given = given_undulation_m is not None and math.isfinite(float(given_undulation_m))
    if source.above_sea_level and target.above_sea_level and not given:
        return HeightShift(source, target, np.zeros(lat.shape),
                           f"both {source.describe()} and {target.describe()}: the same mean sea level assumed")
    n_source, why_source = undulation(source, lat, lon, given_undulation_m)
    n_target, why_target = undulation(target, lat, lon, given_undulation_m)
    why = "; ".join(dict.fromkeys(w for w in (why_source, why_target) if w))
    return HeightShift(source, target, n_source - n_target,
                       f"{source.describe()} → {target.describe()}: {why}")


def convert_heights(heights, lat, lon, source: VerticalReference, target: VerticalReference,
                    given_undulation_m: float | None = None) -> np.ndarray:
    """Heights (m) in ``source`` expressed in ``target`` (:func:`height_shift`)."""
    return np.asarray(heights, dtype=float) + height_shift(source, target, lat, lon, given_undulation_m).offset_m


@on_python_thread
def crs_vertical_reference(crs) -> VerticalReference | None:
    """The vertical reference a CRS's heights are measured from: a compound CRS's vertical part (EGM96 and
    EGM2008 by their EPSG codes, any other vertical CRS as ``msl``), ellipsoidal for a 3D geographic or
    geocentric CRS, None when the CRS has no vertical axis (a plain projected CRS says nothing of heights)."""
    ensure_proj_data()
    import pyproj

    crs = pyproj.CRS.from_user_input(crs)
    vertical = next((sub for sub in crs.sub_crs_list if sub.is_vertical), None) if crs.is_compound else \
        (crs if crs.is_vertical else None)
    if vertical is not None:
        epsg = vertical.to_epsg()
        return next((VerticalReference(GEOID, name) for name, (code, _) in GEOID_MODELS.items() if code == epsg),
                    MSL_REFERENCE)
    if crs.is_geocentric or (crs.is_geographic and len(crs.axis_info) == 3):
        return ELLIPSOIDAL_REFERENCE
    return None

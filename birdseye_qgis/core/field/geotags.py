"""Rover geotags: read the survey files into one table, keep file order, flag what needs a look.

Formats (docs/design.md#geotags):

* **BirdsEye rover CSV** (no header): ``lat, lon, altWGS84, altMSL, gpsStatus, label`` — degrees,
  metres; ``gpsStatus`` is the NMEA GGA fix quality (4 RTK fixed, 5 RTK float, 2 DGPS, 1 autonomous).
  A label that contains commas may be quoted or simply left unquoted (the rest of the line is the label).
* **CSV with a header**: Emlid Flow's point export (:data:`EMLID_FLOW_COLUMNS`) and ReachView 3's
  (:data:`REACHVIEW_COLUMNS`) read with no mapping, other rovers' CSVs by common column names
  (:data:`_COLUMN_NAMES`) or a column mapping (:class:`ColumnMapping`), by the rules below.
* **NMEA GGA** logs (any talker: ``$GPGGA``, ``$GNGGA``…): every GGA sentence with a position is one
  geotag; ellipsoidal height = MSL altitude + geoid separation (fields 9 and 11).
* Any QGIS point layer, read by ``qgis_io/layers.py`` and handed over as columns: its fields by meaning
  (:func:`layer_fields`: heights and accuracies by the names below, fix, label, capture time and worker by the
  geotag layer's and a field package's names), read by :func:`geotags_from_layer`. A field package's geotags
  (``field_survey.GEOTAG_TABLE``, QField's records) are such a layer: QField's quality description
  ("Fixed RTK", "Unknown (4)") is a fix word (:func:`.field_survey.fix_from_description`), ``h_msl`` an
  orthometric height converted like a CSV's, ``time_utc`` a UTC time.

Rules of a CSV with a header, so a height always says what it is measured from (docs/design.md#heights):

* **Height.** A column named ellipsoidal (``Ellipsoidal height``, ``altWGS84``, ``HAE``, …) is the height. An
  ``Elevation`` is orthometric when the row's coordinate-system name (Emlid's ``CS name``) has a vertical part
  (``… + NAVD88(GEOID18) height (ftUS)``) and is then kept as ``h_msl``, never taken as ellipsoidal; with a
  coordinate system without one it is the ellipsoidal height (Emlid writes the ellipsoidal height there).
  A column whose name says neither (``height``, ``alt``, ``z``, an ``Elevation`` with no coordinate system)
  is taken as ellipsoidal, as every BirdsEye input is unless stated (docs/design.md#world), and the notes say
  so. With no ellipsoidal column at all, an orthometric height is converted with the geoid: the undulation
  the caller gives, else EGM96 from PROJ's grid (``geometry/heights``); without either the height stays
  unknown (NaN) and the notes say why.
* **Units** of heights and accuracies: the caller's ``units``; else a unit the column's own name gives
  (``alt (ft)``, ``ELLIPSOIDAL_M``, ``[EllipsoidHeight:Meter:3]``); else the row's coordinate-system name (its
  vertical part for heights and the vertical accuracy; a vertical part that names no unit is in metres, as EPSG
  names it; without a vertical part, the horizontal part's unit; the horizontal part's for horizontal
  accuracies); else a units column (``Units``: m, ft, ftUS); else metres. Emlid's ``Antenna height units`` is
  the unit of the antenna height alone and is not used.
* **Ground.** An Emlid export's heights are of the ground point: Emlid removes the antenna height it records
  (``Antenna height``). :attr:`Geotags.ground_heights` says so and :func:`prepare_geotags` refuses to remove a
  pole height a second time. Another file with an antenna-height column does not say whether its heights have
  it removed (Bad Elf's ``ELLIPSOIDAL_M`` has not); the notes say so and the pole height is the user's call.
* **Fix** from the rover's own words (Emlid's FIX, FLOAT, SINGLE, DGPS; "RTK Fixed", "Float", …) or an NMEA
  code, as the NMEA GGA fix quality. **Accuracy** (m): horizontal from a lateral/horizontal RMS column, else
  √(E² + N²) of the easting and northing RMS; vertical from an elevation/vertical RMS column. **Capture
  time**: Emlid's ``Averaging start`` (or a ``time`` column) with its time zone, as ISO 8601 UTC (a column whose
  name says UTC needs none); another time is not kept (the notes count them).
* **Positions** are kept as written, in the datum of the file's coordinate system (Emlid's latitude and
  longitude in ``NAD83(2011) / …`` are NAD83(2011)); the notes name a datum other than WGS 84.

Rows are numbered as lines of the file (1 = first line), so a message's "row N" is the line a user
sees in a text editor or spreadsheet. A file with some bad rows keeps the good ones; the bad ones are
collected in :attr:`Geotags.problems` (one :class:`InputError` each, naming file, row and field). What the
reader decided (height column and why, units, conversions) is in :attr:`Geotags.notes`.
"""

from __future__ import annotations

import csv
import math
import re
from dataclasses import dataclass, field
from datetime import datetime, timedelta, timezone
from pathlib import Path

import numpy as np

from ..errors import InputError, detached
from ..geometry import heights
from .field_survey import fix_from_description

#: NMEA GGA fix quality codes (field 6) and what users call them.
FIX_NAMES = {0: "unknown", 1: "autonomous", 2: "DGPS", 3: "PPS", 4: "RTK fixed", 5: "RTK float",
             6: "dead reckoning", 7: "manual", 8: "simulated"}
FIX_RTK_FIXED = 4
FIX_RTK_FLOAT = 5
#: Geotags closer than this horizontally (m) to an earlier geotag are flagged ``duplicate_2cm``.
DUPLICATE_DISTANCE_M = 0.02

#: The geotag-layer schema: (name, type, description); type is "int", "double" or "string".
GEOTAG_FIELDS = [
    ("id", "int", "geotag number, 1.. in file order, kept whatever the fix filter drops"),
    ("label", "string", "target class or name from the rover"),
    ("fix_quality", "int", "NMEA GGA fix quality: 4 RTK fixed, 5 RTK float, 2 DGPS, 1 autonomous, 0 unknown"),
    ("lat", "double", "latitude, WGS84 (deg)"),
    ("lon", "double", "longitude, WGS84 (deg)"),
    ("h_ellipsoid", "double", "ellipsoidal height of the ground point (m), pole height removed"),
    ("h_msl", "double", "height above mean sea level of the ground point (m), pole height removed"),
    ("h_acc_m", "double", "horizontal accuracy the rover reported (m): a lateral RMS, else the root sum of "
                          "squares of the easting and northing RMS; NULL when unknown"),
    ("v_acc_m", "double", "vertical accuracy the rover reported (m): an elevation RMS; NULL when unknown"),
    ("time_utc", "string", "capture time, ISO 8601 UTC (Emlid: Averaging start); NULL when unknown"),
    ("source_row", "int", "line of the input file (or feature number of the input layer)"),
    ("flags", "string", "comma-separated warnings: rtk_float, no_rtk, fix_unknown, duplicate_2cm, no_height"),
    ("worker", "string", "who recorded the geotag (a field package's worker); NULL when unknown"),
]
GEOTAG_FIELD_NAMES = [f[0] for f in GEOTAG_FIELDS]

FORMATS = ("auto", "rover", "header", "nmea")

#: Emlid Flow's point export (Reach RS2/RS3/RS4, Emlid Flow 360), 42 columns.
EMLID_FLOW_COLUMNS = (
    "Name", "Code", "Code description", "Easting", "Northing", "Elevation", "Description", "Longitude", "Latitude",
    "Ellipsoidal height", "Origin", "Tilt angle", "Easting RMS", "Northing RMS", "Elevation RMS", "Lateral RMS",
    "Antenna height", "Antenna height units", "Solution status", "Correction type", "Averaging start",
    "Averaging end", "Samples", "PDOP", "GDOP", "Base easting", "Base northing", "Base elevation", "Base longitude",
    "Base latitude", "Base ellipsoidal height", "Baseline", "Mount point", "CS name", "GPS Satellites",
    "GLONASS Satellites", "Galileo Satellites", "BeiDou Satellites", "QZSS Satellites", "Device type",
    "Device serial number", "Author")
#: The older ReachView 3 point export, 27 columns.
REACHVIEW_COLUMNS = (
    "Name", "Easting", "Northing", "Elevation", "Description", "Longitude", "Latitude", "Ellipsoidal height",
    "Easting RMS", "Northing RMS", "Elevation RMS", "Lateral RMS", "Antenna height", "Antenna height units",
    "Solution status", "Averaging start", "Averaging end", "Samples", "PDOP", "Base easting", "Base northing",
    "Base elevation", "Base longitude", "Base latitude", "Base ellipsoidal height", "Baseline", "CS name")

#: Column names by meaning, as :func:`_normal_name` writes them (lower case; ``_``, ``-``, ``.`` and runs of
#: spaces as one space; a trailing unit, ``(ft)``, ``[m]`` or a last word ``m``/``ft``/``ftUS``, cut off). The
#: first present wins. Real exports behind them: Emlid Flow and ReachView 3, SW Maps (``Elevation``, ``Ortho
#: Height``, ``Fix ID``, ``Horizontal Accuracy``), Bad Elf (``ELLIPSOIDAL_M``, ``ELEVATION_MSL``, ``H_RMS``,
#: ``QUALITY``), Trimble Penmap (``EllipsoidHeight``, ``Rms2D``, ``SatQuality``, ``UtcDateTime``), GPSLogger.
_COLUMN_NAMES = {
    "lat": ("lat", "latitude", "lat deg", "latitude deg", "y lat", "wgs84 latitude", "point wgs84 latitude"),
    "lon": ("lon", "lng", "long", "longitude", "lon deg", "longitude deg", "x lon", "wgs84 longitude",
            "point wgs84 longitude"),
    # Heights whose name says what they are measured from (a surveying app's "final" one has the pole removed) …
    "ellipsoidal": ("final ellipsoidal", "ellipsoidal height", "ellipsoidal", "altwgs84", "alt wgs84",
                    "h ellipsoid", "height ellipsoid", "ellipsoid height", "ellipsoidheight", "ellipsoid elevation",
                    "ellipsoidal h", "ellipsoid ht", "ellipsoidal ht", "h ell", "ellh", "ell height", "hae",
                    "height above ellipsoid", "wgs84 height", "point wgs84 height", "ellipsoidal altitude"),
    "orthometric": ("final ortho height", "altmsl", "alt msl", "h msl", "msl", "height msl", "msl height",
                    "orthometric height", "ortho height", "ortho ht", "h ortho", "orthometric", "ortho",
                    "elevation msl", "msl elevation", "altitude msl"),
    # … a surveyor's elevation, whose meaning the coordinate system gives, and heights that say nothing.
    "elevation": ("elevation", "elev", "ele"),
    "unstated": ("h", "height", "alt", "altitude", "z"),
    "fix": ("solution status", "gpsstatus", "gps status", "fix quality", "fix id", "fix", "quality", "fixtype",
            "fix type", "solution", "solution type", "status", "rtk status", "satquality", "sat quality",
            "position quality", "quality description", "corr fix"),
    "label": ("label", "name", "point name", "point", "point id", "pointid", "class", "code", "description", "desc",
              "comment", "remarks"),
    "h_acc": ("lateral rms", "hrms", "h rms", "horizontal rms", "horizontal accuracy", "h acc", "hacc",
              "horizontal precision", "hprec", "h prec", "rms2d", "rms 2d", "horizontal error", "accuracy"),
    "e_rms": ("easting rms", "e rms", "east rms"),
    "n_rms": ("northing rms", "n rms", "north rms"),
    "v_acc": ("elevation rms", "vrms", "v rms", "vertical rms", "vertical accuracy", "v acc", "vacc",
              "vertical precision", "vprec", "v prec", "vertical error", "height rms"),
    "time": ("averaging start", "time utc", "utc time", "utcdatetime", "utc date time", "date time utc",
             "timestamp", "datetime", "date time", "time", "start time"),
    # Who recorded the point: Emlid Flow's "Author" (the account that collected it), a field package's "worker".
    "worker": ("worker", "author", "surveyor", "observer", "collected by", "recorded by"),
    "cs": ("cs name", "coordinate system", "coordinate system name", "crs name"),
    "units": ("units", "unit", "height units", "linear units", "length units", "coordinate units"),
    "antenna": ("antenna height", "ant height", "antheight", "antenna h", "instrument ht", "instrument height"),
}
#: Plausible values (m) of heights and of accuracies; beyond them a value is a wrong column or a wrong unit.
_HEIGHT_RANGE_M = (-1000.0, 10000.0)
_ACCURACY_RANGE_M = (0.0, 1000.0)
#: The length units of the UNITS choice, by the names :func:`heights.metres_per_unit` knows.
LENGTH_UNITS = ("m", "ft", "ftUS")
_UNIT_WORDS = {1.0: "metres", heights.INTERNATIONAL_FOOT_M: "international feet",
               heights.US_SURVEY_FOOT_M: "US survey feet"}


@dataclass
class ColumnMapping:
    """Header names of a CSV's columns; None = find the column by its common names. ``height`` names an
    ellipsoidal height, ``msl`` a height above mean sea level (orthometric)."""

    lat: str | None = None
    lon: str | None = None
    height: str | None = None
    msl: str | None = None
    fix: str | None = None
    label: str | None = None


#: Where a target to label or score comes from: the survey (a geotag) or a review (a cluster a person
#: confirmed real, or rejected, that no geotag matches).
SURVEY, REVIEW = "survey", "review"
PROVENANCES = (SURVEY, REVIEW)
#: The class of a target whose survey gives none.
UNLABELLED = "target"


@dataclass
class Geotags:
    """Surveyed targets: the one geotag type of import, labels, scoring, the review and planning.

    ``ids`` name the targets in every output (labels.csv, matched clusters, waypoints, the review);
    a geotag layer's ids follow one rule (``qgis_io.layers.read_geotag_layer``, docs/design.md#geotags).
    ``lat``, ``lon`` WGS84 (deg); ``height`` ellipsoidal (m), NaN where unknown (the ground model
    places the target); ``h_msl`` likewise. ``labels``: target class (default :data:`UNLABELLED`);
    ``provenance``: :data:`SURVEY` or :data:`REVIEW`; ``fix_quality``: NMEA GGA code (0 unknown);
    ``source_row``: line of the file or row (1..) of the layer each came from; ``flags``: warnings per
    geotag; ``problems``: the bad rows left out when reading (one :class:`InputError` each).
    ``h_acc``, ``v_acc``: the rover's horizontal and vertical accuracy (m), NaN where unknown; ``time_utc``:
    capture time as ISO 8601 UTC text, "" where unknown; ``worker``: who recorded each geotag, "" where
    unknown; ``notes``: what reading decided (height column and why, units, conversions), for the log;
    ``ground_heights``: the heights are of the ground point already (the file records an antenna height the
    rover removed), so no pole height may be removed again.
    """

    ids: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    labels: np.ndarray | None = None
    provenance: np.ndarray | None = None
    h_msl: np.ndarray | None = None
    fix_quality: np.ndarray | None = None
    source_row: np.ndarray | None = None
    flags: list | None = None
    source: str = ""
    problems: list = field(default_factory=list)
    h_acc: np.ndarray | None = None
    v_acc: np.ndarray | None = None
    time_utc: np.ndarray | None = None
    notes: list = field(default_factory=list)
    ground_heights: bool = False
    worker: np.ndarray | None = None

    def __post_init__(self):
        for name in ("lat", "lon", "height"):
            setattr(self, name, np.asarray(getattr(self, name), dtype=float).reshape(-1))
        n = len(self.lat)
        self.ids = _objects(self.ids)
        self.labels = _objects([UNLABELLED] * n if self.labels is None else [str(v) for v in self.labels])
        self.provenance = _objects([SURVEY] * n if self.provenance is None else self.provenance)
        for name in ("h_msl", "h_acc", "v_acc"):
            value = getattr(self, name)
            setattr(self, name, np.full(n, np.nan) if value is None else np.asarray(value, dtype=float).reshape(-1))
        self.fix_quality = np.asarray(np.zeros(n) if self.fix_quality is None else self.fix_quality,
                                      dtype=np.int64).reshape(-1)
        self.source_row = np.asarray(np.arange(1, n + 1) if self.source_row is None else self.source_row,
                                     dtype=np.int64).reshape(-1)
        self.time_utc = _objects([""] * n if self.time_utc is None else [str(v or "") for v in self.time_utc])
        self.worker = _objects([""] * n if self.worker is None else [str(v or "") for v in self.worker])
        self.flags = [[] for _ in range(n)] if self.flags is None else [list(f) for f in self.flags]

    def __len__(self) -> int:
        return len(self.lat)

    def in_local(self, local) -> np.ndarray:
        """The geotags in ``local`` (a :class:`..geometry.geodesy.LocalFrame`) as (G, 3) east, north, up; a
        geotag without a height stands at the frame's own height (``local.h0``)."""
        if not len(self):
            return np.empty((0, 3))
        return local.from_geodetic(self.lat, self.lon, np.where(np.isfinite(self.height), self.height, local.h0))

    #: The per-geotag arrays, in the order of the constructor.
    _COLUMNS = ("ids", "lat", "lon", "height", "labels", "provenance", "h_msl", "fix_quality", "source_row",
                "h_acc", "v_acc", "time_utc", "worker")

    def subset(self, index) -> "Geotags":
        """The geotags at ``index`` (integer positions or a boolean mask), ids and rows kept."""
        index = np.asarray(index)
        if index.dtype == bool:
            index = np.flatnonzero(index)
        index = index.astype(np.int64).reshape(-1)
        return Geotags(**{n: getattr(self, n)[index] for n in self._COLUMNS},
                       flags=[self.flags[i] for i in index], source=self.source, problems=list(self.problems),
                       notes=list(self.notes), ground_heights=self.ground_heights)

    def __add__(self, other: "Geotags") -> "Geotags":
        """These geotags followed by ``other``'s (e.g. the survey and a review's targets)."""
        return Geotags(**{n: np.concatenate([getattr(self, n), getattr(other, n)]) for n in self._COLUMNS},
                       flags=self.flags + other.flags, source=self.source, problems=self.problems + other.problems,
                       notes=self.notes + other.notes, ground_heights=self.ground_heights and other.ground_heights)

    def records(self):
        """One dict per geotag with the :data:`GEOTAG_FIELD_NAMES`."""
        for i in range(len(self)):
            yield {"id": int(self.ids[i]), "label": self.labels[i], "fix_quality": int(self.fix_quality[i]),
                   "lat": float(self.lat[i]), "lon": float(self.lon[i]),
                   "h_ellipsoid": _none_if_nan(self.height[i]), "h_msl": _none_if_nan(self.h_msl[i]),
                   "h_acc_m": _none_if_nan(self.h_acc[i]), "v_acc_m": _none_if_nan(self.v_acc[i]),
                   "time_utc": self.time_utc[i] or None,
                   "source_row": int(self.source_row[i]), "flags": ",".join(self.flags[i]),
                   "worker": self.worker[i] or None}


def geotag_ids(values, rows, source: str = "", field_name: str = "id") -> np.ndarray:
    """The ids of a geotag layer's features, by the one rule (docs/design.md#geotags).

    ``values``: the id field's value per feature (None: the layer has no id field); ``rows``: each
    feature's row, 1.. in the layer's feature order. With an id field, each geotag's id is its value
    (a whole number as an int, text stripped); an empty id or one shared by two geotags is refused,
    naming the rows. Without one, a geotag's id is its row, whatever the format the layer is saved in.
    """
    rows = np.asarray(rows, dtype=np.int64).reshape(-1)
    if values is None:
        return _objects(rows.tolist())
    ids = [_id_value(v) for v in values]
    empty = [int(r) for r, v in zip(rows, ids) if v is None]
    if empty:
        raise InputError(f"has {len(empty)} geotag(s) without an id (row(s) {_rows_text(empty)}): give every "
                         f"geotag its own id, or rename the field '{field_name}' so geotags are numbered by row",
                         source=source, row=empty[0], field=field_name)
    seen: dict = {}
    for r, v in zip(rows.tolist(), ids):
        seen.setdefault(v, []).append(r)
    shared = {v: rs for v, rs in seen.items() if len(rs) > 1}
    if shared:
        v, rs = next(iter(shared.items()))
        more = f" ({len(shared) - 1} more id(s) are shared too)" if len(shared) > 1 else ""
        raise InputError(f"gives id {v} to {len(rs)} geotags (rows {_rows_text(rs)}){more}: labels, scores and "
                         "waypoints name a target by its id, so each geotag needs its own", source=source,
                         row=rs[0], field=field_name)
    return _objects(ids)


def _id_value(value):
    """An id as written in a layer: a whole number as an int (7.0 → 7), text stripped; None if empty."""
    if value is None:
        return None
    if isinstance(value, float):
        return int(value) if value.is_integer() else (value if np.isfinite(value) else None)
    if isinstance(value, (int, np.integer)):
        return int(value)
    text = str(value).strip()
    return text or None


def _rows_text(rows, shown: int = 10) -> str:
    return ", ".join(str(r) for r in rows[:shown]) + (" …" if len(rows) > shown else "")


def _objects(values) -> np.ndarray:
    """A 1-D object array (ids and texts keep their Python types: 7 stays 7, "A7" stays "A7")."""
    out = np.empty(len(values), dtype=object)
    out[:] = list(values)
    return out


def _none_if_nan(value):
    value = float(value)
    return None if np.isnan(value) else value


# ---------------------------------------------------------------------------------------- reading
def read_geotags(path, fmt: str = "auto", mapping: ColumnMapping | None = None, units: str | None = None,
                 geoid_undulation_m: float | None = None) -> Geotags:
    """Read a geotag file of format ``fmt`` (one of :data:`FORMATS`; "auto" looks at the content).

    ``units`` (one of :data:`LENGTH_UNITS`; None: from the file) is the unit of a header CSV's heights and
    accuracies; the BirdsEye rover CSV and NMEA are in metres by definition. ``geoid_undulation_m`` (N, m;
    ellipsoidal = orthometric + N) converts the orthometric heights of a header CSV without an ellipsoidal
    height; None: EGM96 from PROJ's grid. The module docstring gives the rules; the result's ``notes`` say
    what was decided for this file.
    """
    path = Path(path)
    lines = _read_lines(path)
    if fmt not in FORMATS:
        raise ValueError(f"unknown geotag format {fmt!r}; expected one of {FORMATS}")
    if units is not None and units not in LENGTH_UNITS:
        raise ValueError(f"unknown length unit {units!r}; expected None or one of {LENGTH_UNITS}")
    if geoid_undulation_m is not None and not abs(geoid_undulation_m) <= heights.MAX_UNDULATION_M:
        raise InputError(f"{geoid_undulation_m} m is not a geoid undulation (N lies within ±"
                         f"{heights.MAX_UNDULATION_M:g} m)", field="GEOID_UNDULATION_M")
    if fmt == "auto":
        fmt = detect_format(lines, path)
    if fmt == "header":
        tags = _parse_header(lines, str(path), mapping, units, geoid_undulation_m)
    else:
        tags = {"rover": _parse_rover, "nmea": _parse_nmea}[fmt](lines, str(path))
        if units not in (None, "m"):
            tags.notes.append(f"the length unit asked for ({units}) is not used: this format is in metres")
    if len(tags) == 0:
        if tags.problems:
            raise InputError(f"no usable geotag: all {len(tags.problems)} row(s) are bad; the first: "
                             f"{tags.problems[0]}", source=str(path))
        raise InputError("has no geotags (the file is empty)", source=str(path))
    return tags


def read_rover_csv(path) -> Geotags:
    return read_geotags(path, "rover")


def read_header_csv(path, mapping: ColumnMapping | None = None, units: str | None = None,
                    geoid_undulation_m: float | None = None) -> Geotags:
    return read_geotags(path, "header", mapping, units, geoid_undulation_m)


def read_nmea(path) -> Geotags:
    return read_geotags(path, "nmea")


def _read_lines(path: Path) -> list[str]:
    if not path.is_file():
        raise InputError("file not found", source=str(path))
    data = path.read_bytes()
    kind = binary_kind(data)
    if kind is not None:
        raise InputError(f"is not a text CSV ({kind}); give the rover's CSV or NMEA log, or load a point layer "
                         "and use it as the input layer", source=str(path))
    return split_lines(data)


#: File signatures of what users pick by mistake instead of a CSV.
_SIGNATURES = ((b"\x89PNG", "a PNG image"), (b"\xff\xd8\xff", "a JPEG image"), (b"PK\x03\x04", "a ZIP archive"),
               (b"%PDF", "a PDF document"), (b"SQLite format 3\x00", "an SQLite database or GeoPackage"),
               (b"II*\x00", "a TIFF image"), (b"MM\x00*", "a TIFF image"), (b"\xd0\xcf\x11\xe0", "an old Office file"))


def binary_kind(data: bytes) -> str | None:
    """What a file that is not text looks like ("a PNG image", …, "binary data"), or None for text.

    Text may hold a BOM and the odd undecodable byte (they fail later as values, with their row); a known
    signature, a NUL byte or mostly control bytes in the first 4 kB mean the file is not text at all.
    """
    for signature, kind in _SIGNATURES:
        if data.startswith(signature):
            return kind
    head = data[:4096]
    if b"\x00" in head:
        return "binary data"
    control = sum(b < 32 and b not in (9, 10, 13, 12) for b in head)
    return "binary data" if head and control > 0.1 * len(head) else None


def split_lines(data: bytes) -> list[str]:
    """Lines of a text file as an editor numbers them: split at \\n, \\r\\n or \\r only (not at the
    form feeds and Unicode separators ``str.splitlines`` also breaks on). utf-8-sig drops a
    spreadsheet's BOM; undecodable bytes become U+FFFD and then fail as values."""
    text = data.decode("utf-8-sig", errors="replace").replace("\x00", "\ufffd")
    return text.replace("\r\n", "\n").replace("\r", "\n").split("\n")


def detect_format(lines: list[str], path: Path | str = "") -> str:
    """"nmea" if the content holds NMEA sentences, "header" if its first row is not numbers, else "rover"."""
    content = [ln for ln in lines if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        return "rover"
    if sum("$" in ln and "GGA," in ln.upper() for ln in content[:50]) > 0:
        return "nmea"
    first = _split_csv(content[0])
    if len(first) >= 2 and not (_is_number(first[0]) and _is_number(first[1])):
        return "header"
    return "rover"


def _is_number(text: str) -> bool:
    try:
        float(text)
        return True
    except ValueError:
        return False


def _split_csv(line: str) -> list[str]:
    try:
        return next(csv.reader([line], skipinitialspace=True), [])
    except csv.Error:
        return line.split(",")


def _content_rows(lines):
    """(line number, line) of every non-blank, non-comment line."""
    for number, line in enumerate(lines, start=1):
        if line.strip() and not line.lstrip().startswith("#"):
            yield number, line


def _number(text: str, source: str, row: int, field_name: str, what: str,
            lo: float | None = None, hi: float | None = None, allow_empty: bool = False) -> float:
    text = text.strip()
    if text == "" and allow_empty:
        return float("nan")
    try:
        value = float(text)
    except ValueError:
        raise InputError(f"{text!r} is not a number; expected {what}", source=source, row=row,
                         field=field_name) from None
    if not np.isfinite(value):
        if allow_empty:
            return float("nan")
        raise InputError(f"{text!r} is not a finite number; expected {what}", source=source, row=row,
                         field=field_name)
    if (lo is not None and value < lo) or (hi is not None and value > hi):
        raise InputError(f"{value:g} is out of range; expected {what}", source=source, row=row,
                         field=field_name)
    return value


#: A rover's words for its solution (lower case, runs of spaces, ``_`` and ``-`` as one space) as NMEA GGA codes.
#: PPP and Trimble RTX are corrected solutions but not RTK: code 2, flagged ``no_rtk`` like DGPS.
_FIX_WORDS = {
    **dict.fromkeys(("fixed", "fix", "rtk fixed", "rtk fix", "rtkfix", "rtk", "rtk int", "fixed rtk", "rtk fixed "
                     "solution"), FIX_RTK_FIXED),
    **dict.fromkeys(("float", "rtk float", "float rtk", "rtkfloat"), FIX_RTK_FLOAT),
    **dict.fromkeys(("dgps", "dgnss", "differential", "sbas", "waas", "code diff", "ppp", "rtx"), 2),
    **dict.fromkeys(("single", "autonomous", "auto", "nav", "navigated", "gps", "gnss", "standalone", "spp", "3d",
                     "3d fix"), 1),
    **dict.fromkeys(("none", "no fix", "invalid", "unknown"), 0),
}


def _fix_code(text: str, source: str, row: int, field_name: str) -> int:
    """A fix quality from a GGA code ("4"), a rover's word ("FIX", "RTK Fixed", "float", "single", "dgps") or
    QField's quality description ("Fixed RTK", "Unknown (4)", "Float RTK - IMU active"), read as
    :func:`.field_survey.fix_from_description` reads it; anything else is an :class:`InputError` naming
    ``source``, ``row`` and ``field_name``."""
    text = text.strip()
    if text == "":
        return 0
    try:
        value = float(text)
    except ValueError:
        word = " ".join(re.split(r"[\s_\-]+", text.lower())).strip()
        if word in _FIX_WORDS:
            return _FIX_WORDS[word]
        qfield = fix_from_description(text)
        if qfield is not None:
            return qfield
        raise InputError(f"{text!r} is not a fix quality; expected an NMEA GGA code (4 RTK fixed, "
                         "5 RTK float, 1 autonomous), a rover's word such as FIX/FLOAT/SINGLE, 'RTK Fixed', "
                         "'Float', 'DGPS', 'Autonomous', or QField's 'Fixed RTK', 'Float RTK'",
                         source=source, row=row, field=field_name) from None
    if value != int(value) or not 0 <= value <= 9:
        raise InputError(f"{text!r} is not a fix quality; expected an NMEA GGA code 0–9 "
                         "(4 RTK fixed, 5 RTK float, 1 autonomous)", source=source, row=row, field=field_name)
    return int(value)


_TIME = re.compile(r"(\d{4})[-/](\d{2})[-/](\d{2})[T ](\d{2}):(\d{2}):(\d{2})(\.\d+)?\s*(Z|UTC|GMT)?\s*"
                   r"(?:([+-])(\d{2})(?::?(\d{2}))?)?", re.IGNORECASE)


def utc_text(text: str, zone_less_is_utc: bool = False) -> str | None:
    """A date and time with its zone ("2026-05-20 10:27:09.4 UTC-05:00", "…T15:27:09Z", "… +02:00") as ISO 8601
    UTC to the millisecond ("2026-05-20T15:27:09.400Z"); None when the text has no date or no time, has no zone
    (unless ``zone_less_is_utc``: its column's name says UTC), or is not a valid date."""
    match = _TIME.fullmatch(str(text or "").strip())
    if not match:
        return None
    year, month, day, hour, minute, second, fraction, utc, sign, off_h, off_m = match.groups()
    if utc is None and sign is None and not zone_less_is_utc:
        return None
    offset = 0 if sign is None else (int(off_h) * 60 + int(off_m or 0)) * (-1 if sign == "-" else 1)
    try:
        moment = datetime(int(year), int(month), int(day), int(hour), int(minute), int(second),
                          tzinfo=timezone(timedelta(minutes=offset)))
    except ValueError:
        return None
    moment = (moment + timedelta(seconds=float(fraction or 0))).astimezone(timezone.utc)
    return moment.strftime("%Y-%m-%dT%H:%M:%S") + f".{moment.microsecond // 1000:03d}Z"


def _capture_time(out: "_Collector", text, name: str) -> str:
    """The capture time ``text`` of the column or field ``name`` as ISO 8601 UTC (:func:`utc_text`; a time
    without a zone is UTC when ``name`` says UTC or GMT); "" when empty, or when it is no date and time with
    its zone, which ``out``'s notes count."""
    if not str(text or "").strip():
        return ""
    time_utc = utc_text(text, zone_less_is_utc=bool(re.search(r"utc|gmt", name, re.IGNORECASE)))
    if time_utc is None:
        out.note(f"capture time: '{name}' not kept where it is not a date and time with its zone "
                 "(expected e.g. 2026-05-20 10:27:09.4 UTC-05:00 or 2026-05-20T15:27:09Z)")
    return time_utc or ""


class _Collector:
    """Accumulates good rows, bad-row errors and notes of one file."""

    def __init__(self, source: str):
        self.source = source
        self.rows: list[tuple] = []
        self.problems: list[InputError] = []
        self.remarks: list[str] = []
        self.notes: dict[str, int] = {}

    def add(self, lat, lon, h, msl, fix, label, row, h_acc=math.nan, v_acc=math.nan, time_utc="", worker=""):
        self.rows.append((lat, lon, h, msl, fix, label, row, h_acc, v_acc, time_utc, worker))

    def problem(self, error: InputError) -> None:
        """A bad row, left out (:func:`..errors.detached`)."""
        self.problems.append(detached(error))

    def note(self, text: str, rows: int = 1) -> None:
        """A decision taken for ``rows`` row(s); the notes count the rows it was taken for."""
        self.notes[text] = self.notes.get(text, 0) + rows

    def remark(self, text: str) -> None:
        """A decision about the whole file."""
        self.remarks.append(text)

    def geotags(self, ground_heights: bool = False) -> Geotags:
        """The good rows, numbered 1.. in file order (the ids Import geotags writes); a note taken for only some
        of the rows says for how many."""
        lat, lon, h, msl, fix, label, row, h_acc, v_acc, time_utc, worker = zip(*self.rows) if self.rows else ([],) * 11
        total = len(self.rows) + len(self.problems)
        notes = self.remarks + [text if count >= len(self.rows) else f"{text} ({count} of {total} rows)"
                                for text, count in self.notes.items()]
        return Geotags(np.arange(1, len(lat) + 1), lat, lon, h, label, None, msl, fix, row, source=self.source,
                       problems=self.problems, h_acc=h_acc, v_acc=v_acc, time_utc=time_utc, notes=notes,
                       ground_heights=ground_heights, worker=worker)


def _parse_rover(lines, source: str) -> Geotags:
    out = _Collector(source)
    names = ("lat", "lon", "altWGS84", "altMSL", "gpsStatus", "label")
    for row, line in _content_rows(lines):
        cells = _split_csv(line)
        try:
            if len(cells) < 5:
                raise InputError(f"has {len(cells)} column(s); expected 6: {', '.join(names)}",
                                 source=source, row=row)
            lat = _number(cells[0], source, row, "lat", "latitude in degrees, -90…90", -90, 90)
            lon = _number(cells[1], source, row, "lon", "longitude in degrees, -180…180", -180, 180)
            h = _number(cells[2], source, row, "altWGS84", "ellipsoidal height in metres", *_HEIGHT_RANGE_M,
                        allow_empty=True)
            msl = _number(cells[3], source, row, "altMSL", "height above MSL in metres", *_HEIGHT_RANGE_M,
                          allow_empty=True)
            fix = _fix_code(cells[4], source, row, "gpsStatus")
        except InputError as exc:
            out.problem(exc)
            continue
        label = ",".join(c.strip() for c in cells[5:])
        out.add(lat, lon, h, msl, fix, label, row)
    out.remark("read as the BirdsEye rover CSV: height = altWGS84 (ellipsoidal, m); altMSL kept as h_msl (m)")
    return out.geotags()


# ------------------------------------------------------------------------------------ CSV with a header
@dataclass(frozen=True)
class _Column:
    """A column of a header CSV: its position, its name as the header writes it, the unit (m per unit) its name
    gives in parentheses (``alt (ft)``; None: none), and whether the column mapping named it."""

    index: int
    name: str
    unit_m: float | None = None
    mapped: bool = False


def _normal_name(name: str) -> tuple[str, float | None]:
    """A header name as :data:`_COLUMN_NAMES` writes it, and the length unit (m per unit) a trailing
    ``(unit)`` or ``[unit]``, or a last word ``m``, ``ft`` or ``ftUS`` after others, gives (None: none, or not
    a length unit such as ``(deg)``). A name in Trimble Penmap's brackets, ``[EllipsoidHeight:Meter:3]``, is
    its first part, with the unit of the others."""
    text = str(name).strip().lower()
    unit = None
    penmap = re.fullmatch(r"\[([^\]:]+)((?::[^\]:]*)*)\]", text)
    if penmap:
        text = penmap.group(1)
        unit = next((u for u in map(_length_unit, penmap.group(2).split(":")[1:]) if u is not None), None)
    match = re.search(r"\s*[(\[]([^)\]]*)[)\]]\s*$", text)
    if match:
        text = text[:match.start()]
        unit = _length_unit(match.group(1))
    words = re.sub(r"[\s_.\-]+", " ", text).strip().split(" ")
    if unit is None and len(words) > 1 and words[-1] in ("m", "ft", "ftus", "usft"):
        unit = heights.metres_per_unit(words.pop())
    return " ".join(words), unit


def _length_unit(text: str) -> float | None:
    """Metres per unit of a unit name (``m``, ``Meter``, ``ft``, ``ftUS``, …), None when it names no length."""
    try:
        return heights.metres_per_unit(text)
    except InputError:
        return None


def _header_columns(header: list[str], mapping: ColumnMapping, source: str) -> dict[str, _Column]:
    """The columns by meaning (keys of :data:`_COLUMN_NAMES`): the mapping's first (``height`` is an ellipsoidal
    height, ``msl`` an orthometric one), then the first common name present of each meaning, a column taken
    once. No latitude or longitude column, or a mapped name the header lacks, is refused."""
    names = [h.strip() for h in header]
    normal = [_normal_name(h) for h in header]
    found: dict[str, _Column] = {}
    mapped = {"lat": mapping.lat, "lon": mapping.lon, "ellipsoidal": mapping.height, "orthometric": mapping.msl,
              "fix": mapping.fix, "label": mapping.label}
    for role, wanted in mapped.items():
        if not wanted:
            continue
        lowered = [n.lower() for n in names]
        key = wanted.strip().lower()
        if key not in lowered:
            what = {"ellipsoidal": "ellipsoidal height", "orthometric": "MSL height"}.get(role, role)
            raise InputError(f"has no column '{wanted}' for the {what}; its columns are: {', '.join(names)}",
                             source=source, row=1)
        i = lowered.index(key)
        found[role] = _Column(i, names[i], normal[i][1], True)
    used = {c.index for c in found.values()}
    for role, candidates in _COLUMN_NAMES.items():
        if role in found:
            continue
        for candidate in candidates:
            i = next((i for i, (n, _) in enumerate(normal) if n == candidate and i not in used), None)
            if i is not None:
                found[role] = _Column(i, names[i], normal[i][1])
                used.add(i)
                break
    for role, what in (("lat", "latitude"), ("lon", "longitude")):
        if role not in found:
            raise InputError(f"has no {what} column; name it with the column mapping (found columns: "
                             f"{', '.join(names)})", source=source, row=1)
    return found


def _layout(header: list[str]) -> str:
    """The export a header is, in words, for the notes."""
    normal = [h.strip().lower() for h in header]
    if normal == [c.lower() for c in EMLID_FLOW_COLUMNS]:
        return "an Emlid Flow export (42 columns)"
    if normal == [c.lower() for c in REACHVIEW_COLUMNS]:
        return "a ReachView 3 export (27 columns)"
    if {"solution status", "cs name", "ellipsoidal height", "antenna height"} <= set(normal):
        return f"an Emlid export ({len(header)} columns)"
    return "a CSV with a header"


def _cs_parts(cs_name: str) -> tuple[str, str | None]:
    """A coordinate-system name's horizontal part and its vertical part (None: it has none), split as
    ``heights.crs_name_units`` splits them (``A + B``)."""
    parts = [p.strip() for p in cs_name.split(" + ", 1)]
    return parts[0], (parts[1] if len(parts) > 1 else None)


@dataclass(frozen=True)
class _Units:
    """Metres per unit of a row's horizontal lengths (accuracies) and vertical ones (heights, vertical
    accuracy), and where they came from, in words."""

    horizontal: float
    vertical: float
    why: str


def _row_units(units: str | None, cs_name: str, units_text: str, units_column: _Column | None, source: str,
               row: int) -> _Units:
    """The units of a row's lengths by the rules of the module docstring (a column's own unit aside)."""
    if units is not None:
        factor = heights.metres_per_unit(units)
        return _Units(factor, factor, "as asked (UNITS)")
    if cs_name:
        horizontal, vertical = heights.crs_name_units(cs_name)
        horizontal = horizontal or 1.0
        has_vertical = _cs_parts(cs_name)[1] is not None
        return _Units(horizontal, (vertical or 1.0) if has_vertical else horizontal,
                      f"from the coordinate system '{cs_name}'")
    if units_text:
        factor = heights.metres_per_unit(units_text, source, row, units_column.name)
        return _Units(factor, factor, f"from the column '{units_column.name}'")
    return _Units(1.0, 1.0, "as the file names no unit")


def _unit_words(factor: float) -> str:
    return _UNIT_WORDS.get(factor, f"units of {factor:g} m")


def _own_unit(column: _Column, units: str | None) -> str:
    """", in <unit> as its name says" when a column's name gives the unit its values are read in."""
    return f", in {_unit_words(column.unit_m)} as its name says" if column.unit_m is not None and units is None else ""


def _length(cells, column: _Column, factor: float, units: str | None, source: str, row: int, what: str,
            limits_m: tuple[float, float]) -> float:
    """A length (m) from a cell in the column's own unit (its name's, unless ``units`` was asked for) or
    ``factor`` (m per unit); empty: NaN."""
    factor = column.unit_m if column.unit_m is not None and units is None else factor
    value = _number(cells[column.index], source, row, column.name, f"{what} in {_unit_words(factor)}",
                    limits_m[0] / factor, limits_m[1] / factor, allow_empty=True)
    return value * factor


def _parse_header(lines, source: str, mapping: ColumnMapping | None = None, units: str | None = None,
                  geoid_undulation_m: float | None = None) -> Geotags:
    """A CSV with a header, by the rules of the module docstring."""
    mapping = mapping or ColumnMapping()
    rows = _content_rows(lines)
    try:
        _, header_line = next(rows)
    except StopIteration:
        return _Collector(source).geotags()
    header = _split_csv(header_line)
    col = _header_columns(header, mapping, source)
    out = _Collector(source)
    needed = max(c.index for c in col.values())
    ortho_rows, datums = [], set()
    for row, line in rows:
        cells = _split_csv(line)
        try:
            if len(cells) <= needed:
                raise InputError(f"has {len(cells)} column(s); the header has {len(header)}", source=source, row=row)
            lat = _number(cells[col["lat"].index], source, row, col["lat"].name, "latitude in degrees, -90…90",
                          -90, 90)
            lon = _number(cells[col["lon"].index], source, row, col["lon"].name, "longitude in degrees, -180…180",
                          -180, 180)
            cs_name = cells[col["cs"].index].strip() if "cs" in col else ""
            unit = _row_units(units, cs_name, cells[col["units"].index].strip() if "units" in col else "",
                              col.get("units"), source, row)
            h, msl, h_note, msl_note, msl_column = _row_heights(cells, col, unit, units, cs_name, source, row)
            h_acc, v_acc, acc_note = _row_accuracy(cells, col, unit, units, source, row)
            fix = _fix_code(cells[col["fix"].index], source, row, col["fix"].name) if "fix" in col else 0
        except InputError as exc:
            out.problem(exc)
            continue
        time_utc = _capture_time(out, cells[col["time"].index], col["time"].name) if "time" in col else ""
        label = cells[col["label"].index].strip() if "label" in col else ""
        worker = cells[col["worker"].index].strip() if "worker" in col else ""
        out.add(lat, lon, h, msl, fix, label, row, h_acc, v_acc, time_utc, worker)
        for text in (h_note, msl_note, acc_note):
            if text:
                out.note(text)
        if msl_column is not None and not _has_ellipsoidal_column(col, cs_name):
            ortho_rows.append(len(out.rows) - 1)
            if cs_name and _cs_parts(cs_name)[1]:
                datums.add(_cs_parts(cs_name)[1])
        out.note(f"lengths in {_unit_words(unit.vertical)}" +
                 (f" (horizontal accuracies in {_unit_words(unit.horizontal)})"
                  if unit.horizontal != unit.vertical and ("h_acc" in col or "e_rms" in col) else "") +
                 f", {unit.why}")
        if cs_name:
            _note_datum(out, cs_name)
    layout = _layout(header)
    out.remark(f"read as {layout}" + (", which needs no column mapping" if layout != "a CSV with a header" else ""))
    if ortho_rows:
        _convert_orthometric(out, ortho_rows, geoid_undulation_m, datums)
    # Emlid applies the antenna height it records; another app's file does not say whether it did.
    ground = "antenna" in col and layout != "a CSV with a header"
    if ground:
        out.remark(f"heights are of the ground point: the file records the antenna height ('{col['antenna'].name}'), "
                   "which the rover has already removed; no pole height is removed again")
    elif "antenna" in col:
        out.remark(f"the file records an antenna height ('{col['antenna'].name}') but does not say whether its "
                   "heights have it removed: if they are of the antenna, give the pole height (POLE_HEIGHT_M)")
    return out.geotags(ground_heights=ground)


def _has_ellipsoidal_column(col: dict, cs_name: str) -> bool:
    """Whether a row has a column that gives its ellipsoidal height (whether or not this row's cell is empty)."""
    return ("ellipsoidal" in col or "unstated" in col
            or ("elevation" in col and _cs_parts(cs_name)[1] is None))


def _row_heights(cells, col: dict, unit: _Units, units: str | None, cs_name: str, source: str, row: int):
    """(ellipsoidal height, orthometric height (m, NaN where none), note on the height, note on h_msl, the
    orthometric column or None) of one row."""
    vertical = _cs_parts(cs_name)[1] if cs_name else None

    def read(column, what):
        return _length(cells, column, unit.vertical, units, source, row, what, _HEIGHT_RANGE_M)

    h, msl, h_note, msl_note = math.nan, math.nan, "", ""
    elevation = col.get("elevation")
    elevation_orthometric = elevation is not None and vertical is not None
    if "ellipsoidal" in col:
        c = col["ellipsoidal"]
        h = read(c, "ellipsoidal height")
        h_note = (f"height: '{c.name}', ellipsoidal as the column mapping says" if c.mapped
                  else f"height: '{c.name}', ellipsoidal by its name") + _own_unit(c, units)
    elif elevation is not None and not elevation_orthometric:
        h = read(elevation, "ellipsoidal height")
        h_note = (f"height: '{elevation.name}', ellipsoidal: the coordinate system '{cs_name}' has no vertical part"
                  if cs_name else
                  f"height: '{elevation.name}' taken as ellipsoidal: neither its name nor a coordinate system says "
                  "what it is measured from (name it as the MSL height column if it is above sea level)"
                  ) + _own_unit(elevation, units)
    elif "unstated" in col:
        c = col["unstated"]
        h = read(c, "ellipsoidal height")
        h_note = (f"height: '{c.name}' taken as ellipsoidal: its name does not say what it is measured from (name "
                  "it as the MSL height column if it is above sea level)") + _own_unit(c, units)
    msl_column = col.get("orthometric") or (elevation if elevation_orthometric else None)
    if msl_column is not None:
        msl = read(msl_column, "height above mean sea level")
        why = (f"orthometric: the coordinate system has a vertical part, '{vertical}'" if msl_column is elevation
               else "as the column mapping says" if msl_column.mapped else "above mean sea level by its name")
        msl_note = f"h_msl: '{msl_column.name}', {why}{_own_unit(msl_column, units)}"
        if elevation_orthometric and "ellipsoidal" in col:
            msl_note += f"; never taken as the ellipsoidal height, which is '{col['ellipsoidal'].name}'"
    return h, msl, h_note, msl_note, msl_column


def _row_accuracy(cells, col: dict, unit: _Units, units: str | None, source: str, row: int):
    """(horizontal accuracy, vertical accuracy (m, NaN where unknown), note) of one row."""

    def read(role, factor, what):
        return _length(cells, col[role], factor, units, source, row, what, _ACCURACY_RANGE_M)

    h_acc, v_acc, notes = math.nan, math.nan, []
    if "h_acc" in col:
        h_acc = read("h_acc", unit.horizontal, "horizontal accuracy")
        notes.append(f"h_acc_m: '{col['h_acc'].name}'")
    elif "e_rms" in col and "n_rms" in col:
        e = read("e_rms", unit.horizontal, "easting accuracy")
        n = read("n_rms", unit.horizontal, "northing accuracy")
        h_acc = math.hypot(e, n)
        notes.append(f"h_acc_m: √('{col['e_rms'].name}'² + '{col['n_rms'].name}'²)")
    if "v_acc" in col:
        v_acc = read("v_acc", unit.vertical, "vertical accuracy")
        notes.append(f"v_acc_m: '{col['v_acc'].name}'")
    return h_acc, v_acc, "; ".join(notes)


def _note_datum(out: _Collector, cs_name: str) -> None:
    """Say when positions are in a datum other than WGS 84: they are kept as the file gives them."""
    datum = _cs_parts(cs_name)[0].split(" / ", 1)[0].strip()
    if datum and not re.sub(r"\s", "", datum).upper().startswith("WGS84"):
        out.note(f"positions and ellipsoidal heights are kept as the file gives them, in {datum}, the datum of its "
                 "coordinate system, and used as WGS84: a datum other than WGS 84 may lie a metre or more from it, "
                 "so the drone's positions must be in the same datum as the rover's")


def _convert_orthometric(out: _Collector, index: list[int], given_m: float | None, datums: set) -> None:
    """Ellipsoidal heights of the rows at ``index`` from their orthometric ones (the file has no ellipsoidal
    height): h = H + N, N as given or EGM96 from PROJ's grid; without either the heights stay unknown."""
    rows = [list(r) for r in out.rows]
    lat = np.array([rows[i][0] for i in index])
    lon = np.array([rows[i][1] for i in index])
    given = given_m is not None
    source = heights.MSL_REFERENCE if given else heights.EGM96_REFERENCE
    try:
        shift = heights.height_shift(source, heights.ELLIPSOIDAL_REFERENCE, lat, lon, given_m)
    except heights.GeoidGridMissing as exc:
        out.note(f"height unknown: the file gives only heights above mean sea level, and they cannot be converted "
                 f"to ellipsoidal ones: {exc}", len(index))
        return
    for i, offset in zip(index, shift.offset_m.tolist()):
        rows[i][2] = rows[i][3] + offset
    out.rows = [tuple(r) for r in rows]
    text = (f"height: the file has no ellipsoidal height; its heights above mean sea level converted, h = H + N, "
            f"{shift.note}")
    others = sorted(d for d in datums if "EGM96" not in d.upper())
    if not given and (others or not datums):
        text += (f"; EGM96 stands in for the file's height system ({', '.join(others)}), which may differ from it "
                 "by a metre or more: give that system's N at the site (GEOID_UNDULATION_M) to do better"
                 if others else "; the file does not name its geoid: give N at the site (GEOID_UNDULATION_M) if its "
                 "heights are not EGM96's")
    out.note(text, len(index))


_GGA = re.compile(r"\$(?P<body>[A-Z]{2}GGA,[^*\r\n]*)(?:\*(?P<sum>[0-9A-Fa-f]{2}))?")


def _nmea_angle(value: str, hemi: str, degree_digits: int, source: str, row: int, field_name: str,
                limit: float) -> float:
    value, hemi = value.strip(), hemi.strip().upper()
    expected = "ddmm.mmmm" if degree_digits == 2 else "dddmm.mmmm"
    if not re.fullmatch(r"\d{%d}\d{2}(\.\d*)?" % degree_digits, value):
        raise InputError(f"{value!r} is not an NMEA angle; expected {expected}", source=source, row=row,
                         field=field_name)
    degrees = int(value[:degree_digits]) + float(value[degree_digits:]) / 60.0
    if float(value[degree_digits:]) >= 60.0 or degrees > limit:
        raise InputError(f"{value!r} is out of range; expected {expected} with minutes < 60",
                         source=source, row=row, field=field_name)
    signs = {"N": 1.0, "E": 1.0, "S": -1.0, "W": -1.0}
    allowed = "NS" if degree_digits == 2 else "EW"
    if hemi not in allowed:
        raise InputError(f"{hemi!r} is not a hemisphere; expected {' or '.join(allowed)}", source=source,
                         row=row, field=field_name + " hemisphere")
    return signs[hemi] * degrees


def _parse_nmea(lines, source: str) -> Geotags:
    out = _Collector(source)
    for row, line in _content_rows(lines):
        match = _GGA.search(line.upper())
        if not match:
            continue  # other sentence types (RMC, GSA, …) carry no new position
        body, checksum = match.group("body"), match.group("sum")
        try:
            if checksum is not None:
                computed = 0
                for ch in body:
                    computed ^= ord(ch)
                if computed != int(checksum, 16):
                    raise InputError(f"checksum *{checksum} does not match the sentence (computed "
                                     f"*{computed:02X}); the line is corrupt", source=source, row=row,
                                     field="checksum")
            cells = body.split(",")
            if len(cells) < 12:
                raise InputError(f"GGA sentence has {len(cells) - 1} field(s); expected 14", source=source,
                                 row=row)
            fix = _fix_code(cells[6], source, row, "fix quality")
            if fix == 0 or not cells[2].strip():
                raise InputError("GGA sentence has no position (fix quality 0)", source=source, row=row,
                                 field="fix quality")
            lat = _nmea_angle(cells[2], cells[3], 2, source, row, "latitude", 90.0)
            lon = _nmea_angle(cells[4], cells[5], 3, source, row, "longitude", 180.0)
            msl = _number(cells[9], source, row, "altitude", "altitude above MSL in metres", -1000, 10000,
                          allow_empty=True)
            sep = _number(cells[11], source, row, "geoid separation", "geoid separation in metres",
                          -200, 200, allow_empty=True)
        except InputError as exc:
            out.problem(exc)
            continue
        out.add(lat, lon, msl + sep, msl, fix, "", row)
    out.remark("read as an NMEA GGA log: height = MSL altitude + geoid separation (fields 9 and 11, m); the MSL "
               "altitude kept as h_msl")
    return out.geotags()


def accuracy_fields(names) -> tuple[str | None, str | None]:
    """The fields of a point layer that hold the horizontal and the vertical accuracy, by the common names
    a CSV's columns are found by (``h_acc_m``, ``hrms``, ``Lateral RMS``, …; None: none)."""
    normal = {_normal_name(n)[0]: n for n in names}
    found = [next((normal[c] for c in _COLUMN_NAMES[role] if c in normal), None) for role in ("h_acc", "v_acc")]
    return found[0], found[1]


#: A point layer's fix, label, capture time and worker fields, as :func:`_normal_name` writes them: the names the
#: geotag layer (:data:`GEOTAG_FIELDS`) and a field package (``field_survey.GNSS_FIELDS``) give them. A CSV's
#: common names are not used for these: a layer's ``status``, ``name`` or ``time`` may mean anything.
_LAYER_FIELD_NAMES = {"fix": ("fix quality", "fix"), "label": ("label",), "time": ("time utc",),
                      "worker": ("worker",)}


def layer_fields(names, mapping: ColumnMapping | None = None) -> dict[str, str]:
    """The fields of a point layer (field ``names``) by meaning, keyed as :func:`geotags_from_layer` reads them:
    ``height`` (ellipsoidal), ``msl`` (orthometric), ``fix``, ``label``, ``h_acc``, ``v_acc``, ``time``,
    ``worker``; a meaning without a field is left out.

    The mapping's fields come first (its ``height`` states an ellipsoidal height, ``msl`` an orthometric one);
    then heights by the common names a CSV's columns are found by (``h_ellipsoid``, ``altWGS84``, ``HAE`` …;
    ``h_msl``, ``altMSL``, ``ortho_ht`` …), accuracies as :func:`accuracy_fields` finds them, and the rest by
    :data:`_LAYER_FIELD_NAMES`. A field is taken for one meaning only."""
    mapping = mapping or ColumnMapping()
    found = {key: name for key, name in (("height", mapping.height), ("msl", mapping.msl), ("fix", mapping.fix),
                                         ("label", mapping.label)) if name}
    normal: dict[str, str] = {}
    for name in names:
        normal.setdefault(_normal_name(name)[0], name)

    def free(name):
        return name is not None and name not in found.values()

    for key, wanted in (("height", _COLUMN_NAMES["ellipsoidal"]), ("msl", _COLUMN_NAMES["orthometric"]),
                        *_LAYER_FIELD_NAMES.items()):
        name = next((normal[c] for c in wanted if c in normal and free(normal[c])), None)
        if key not in found and name is not None:
            found[key] = name
    for key, name in zip(("h_acc", "v_acc"), accuracy_fields(names)):
        if free(name):
            found[key] = name
    return found


def geotags_from_layer(columns: dict, fields: dict, source: str = "point layer", unit_m: float = 1.0,
                       geoid_undulation_m: float | None = None) -> Geotags:
    """Geotags from a point layer read into columns: ``columns`` as ``qgis_io.layers.read_point_layer`` returns
    them (``lat``, ``lon``, ``z``, ``row`` and ``attributes`` by field name; times as ISO 8601 text), ``fields``
    the layer's fields by meaning (:func:`layer_fields`).

    The height is the ``height`` field (ellipsoidal); without one, the ``msl`` field converted with the geoid as
    a CSV's orthometric heights are (:func:`geotags_from_columns`), the geometry's Z being of unknown reference
    then; without either, the geometry's Z taken as ellipsoidal. The notes say which."""
    values = columns["attributes"]

    def column(key):
        return values[fields[key]] if key in fields else None

    if "height" in fields:
        height, note = column("height"), f"height: '{fields['height']}', ellipsoidal"
    elif "msl" in fields:
        height, note = None, f"height: from '{fields['msl']}' (above mean sea level); the geometry's Z is not used"
    else:
        height, note = columns["z"].tolist(), "height: the geometry's Z, taken as ellipsoidal"
    tags = geotags_from_columns(
        columns["lat"], columns["lon"], height, column("msl"), column("fix"), column("label"), columns["row"],
        source=source, field_names={k: v for k, v in fields.items() if k != "label"}, h_acc=column("h_acc"),
        v_acc=column("v_acc"), unit_m=unit_m, time_utc=column("time"), worker=column("worker"),
        geoid_undulation_m=geoid_undulation_m)
    tags.notes.insert(0, note)
    return tags


def geotags_from_columns(lat, lon, h_ellipsoid=None, h_msl=None, fix_quality=None, label=None,
                         source_row=None, source: str = "point layer", field_names=None, h_acc=None, v_acc=None,
                         unit_m: float = 1.0, time_utc=None, worker=None,
                         geoid_undulation_m: float | None = None) -> Geotags:
    """Geotags from columns of raw values (a point layer already transformed to WGS84).

    Heights, accuracies and fix qualities may be numbers, numeric text or None (unknown); a row with a value
    that is none of these is reported in ``problems`` (naming ``field_names[column]``: keys ``height``, ``msl``,
    ``fix``, ``h_acc``, ``v_acc``) and left out. Heights and accuracies are in units of ``unit_m`` metres. Without
    ``h_ellipsoid`` the ``h_msl`` heights are converted to ellipsoidal ones as a CSV's orthometric-only heights
    are: h = H + N, N = ``geoid_undulation_m``, else EGM96 from PROJ's grid, else unknown (the notes say which).
    ``time_utc``: capture times as text with their zone, or None; read as a CSV's (a time without a zone is UTC
    when ``field_names["time"]`` says UTC, e.g. ``time_utc``; another is not kept, and the notes count it).
    ``worker``: who recorded each geotag, or None.
    """
    lat = np.asarray(lat, dtype=float)
    n = len(lat)
    lon = np.asarray(lon, dtype=float)
    rows = np.arange(1, n + 1) if source_row is None else np.asarray(source_row, dtype=np.int64)
    names = {**{k: k for k in ("height", "msl", "fix", "h_acc", "v_acc", "time")}, **(field_names or {})}
    out = _Collector(source)
    unknown_words: dict[str, int] = {}

    def length(column, i, row, key, what, limits_m):
        raw = None if column is None else column[i]
        return _raw_number(raw, source, row, names[key], f"{what} in {_unit_words(unit_m)}",
                           limits_m[0] / unit_m, limits_m[1] / unit_m) * unit_m

    def text(column, i):
        return "" if column is None or column[i] is None else str(column[i])

    for i in range(n):
        row = int(rows[i])
        try:
            if not (np.isfinite(lat[i]) and abs(lat[i]) <= 90 and np.isfinite(lon[i]) and abs(lon[i]) <= 180):
                raise InputError("has no valid position (empty geometry or outside -90…90°, -180…180°)",
                                 source=source, row=row, field="geometry")
            h = length(h_ellipsoid, i, row, "height", "ellipsoidal height", _HEIGHT_RANGE_M)
            msl = length(h_msl, i, row, "msl", "height above MSL", _HEIGHT_RANGE_M)
            horizontal = length(h_acc, i, row, "h_acc", "horizontal accuracy", _ACCURACY_RANGE_M)
            vertical = length(v_acc, i, row, "v_acc", "vertical accuracy", _ACCURACY_RANGE_M)
            raw_fix = None if fix_quality is None else fix_quality[i]
            fix = 0 if raw_fix is None else _layer_fix(str(raw_fix), source, row, names["fix"], unknown_words)
        except InputError as exc:
            out.problem(exc)
            continue
        out.add(float(lat[i]), float(lon[i]), h, msl, fix, text(label, i), row, horizontal, vertical,
                _capture_time(out, text(time_utc, i), names["time"]), text(worker, i).strip())
    if unknown_words:
        listed = ", ".join(f"{word!r} ×{n}" for word, n in sorted(unknown_words.items()))
        out.remark(f"the field '{names['fix']}' describes the fix of {sum(unknown_words.values())} geotag(s) in "
                   f"words BirdsEye does not read ({listed}; QField translates its descriptions into the phone's "
                   "language): they are kept with the fix unknown (flag fix_unknown), and the fix filter "
                   "'RTK fixed only' leaves them out")
    if h_ellipsoid is None and h_msl is not None:
        orthometric = [i for i, r in enumerate(out.rows) if np.isfinite(r[3])]
        if orthometric:
            _convert_orthometric(out, orthometric, geoid_undulation_m, set())
    return out.geotags()


def _layer_fix(text: str, source: str, row: int, field_name: str, unknown_words: dict) -> int:
    """A layer's fix as :func:`_fix_code` reads it, except that words it does not know (QField's descriptions in
    another language) give 0, the fix unknown, counted in ``unknown_words``: the point a worker recorded is
    kept. A number that is no GGA code is still an error."""
    try:
        return _fix_code(text, source, row, field_name)
    except InputError:
        if _is_number(text.strip()):
            raise
        unknown_words[text.strip()] = unknown_words.get(text.strip(), 0) + 1
        return 0


def _raw_number(value, source, row, field_name, what, lo, hi) -> float:
    """A layer's value as a number: numbers as they are (not finite: NaN), numeric text checked against lo…hi."""
    if value is None:
        return float("nan")
    if isinstance(value, (int, float)):
        return float(value) if np.isfinite(value) else float("nan")
    return _number(str(value), source, row, field_name, what, lo, hi, allow_empty=True)


# ---------------------------------------------------------------------------------------- checking
@dataclass
class PreparedGeotags:
    """Geotags ready to write, and what was done to them (for the Processing log): the geotags the fix filter
    dropped, those the accuracy filter dropped (of the ones the fix filter kept), those kept with no accuracy to
    filter by, the duplicates flagged and the fix qualities of the input."""

    geotags: Geotags
    dropped_not_fixed: int
    duplicates: int
    counts_by_fix: dict
    dropped_accuracy: int = 0
    unknown_accuracy: int = 0


def prepare_geotags(tags: Geotags, fixed_only: bool = False, pole_height_m: float = 0.0,
                    duplicate_distance_m: float = DUPLICATE_DISTANCE_M,
                    max_h_accuracy_m: float | None = None) -> PreparedGeotags:
    """Apply the fix and accuracy filters and the antenna pole height, and flag what needs a look.

    ``pole_height_m`` (m) is subtracted from both heights: the rover measures its antenna, the target
    is on the ground; refused for geotags whose heights are of the ground already
    (:attr:`Geotags.ground_heights`). With ``fixed_only`` the geotags without an RTK fixed solution are
    dropped (and counted); otherwise they are kept and flagged ``rtk_float`` / ``no_rtk`` / ``fix_unknown``.
    With ``max_h_accuracy_m`` (m) the geotags whose horizontal accuracy is worse are dropped (and counted);
    those without one are kept (and counted). A geotag within ``duplicate_distance_m`` horizontally of an
    earlier kept one is flagged ``duplicate_2cm`` (the earlier one is left unflagged: it is the original press).
    """
    if not np.isfinite(pole_height_m) or pole_height_m < 0 or pole_height_m > 10:
        raise InputError(f"pole height {pole_height_m} m is not a plausible antenna pole (0–10 m)",
                         field="POLE_HEIGHT_M")
    if pole_height_m > 0 and tags.ground_heights:
        raise InputError(f"the heights of this file are of the ground point already (it records the antenna height "
                         f"the rover removed); removing a pole height of {pole_height_m:g} m again would put every "
                         "target too low: set the pole height to 0", source=tags.source, field="POLE_HEIGHT_M")
    if max_h_accuracy_m is not None and not (np.isfinite(max_h_accuracy_m) and max_h_accuracy_m > 0):
        raise InputError(f"{max_h_accuracy_m} m is not a horizontal accuracy to keep geotags within; expected a "
                         "positive number of metres", field="MAX_H_ACCURACY_M")
    counts = {FIX_NAMES.get(int(k), f"code {int(k)}"): int(v)
              for k, v in zip(*np.unique(tags.fix_quality, return_counts=True))}
    fixed = tags.fix_quality == FIX_RTK_FIXED if fixed_only else np.ones(len(tags), dtype=bool)
    coarse = (tags.h_acc > max_h_accuracy_m if max_h_accuracy_m is not None
              else np.zeros(len(tags), dtype=bool))  # NaN > x is False: an unknown accuracy is kept
    keep = fixed & ~coarse
    unknown = int(np.count_nonzero(keep & np.isnan(tags.h_acc))) if max_h_accuracy_m is not None else 0
    out = tags.subset(keep)
    out.height = out.height - pole_height_m
    out.h_msl = out.h_msl - pole_height_m
    for i, fix in enumerate(out.fix_quality):
        if fix == FIX_RTK_FLOAT:
            out.flags[i].append("rtk_float")
        elif fix == 0:
            out.flags[i].append("fix_unknown")
        elif fix != FIX_RTK_FIXED:
            out.flags[i].append("no_rtk")
        if not np.isfinite(out.height[i]):
            out.flags[i].append("no_height")
    duplicates = _flag_duplicates(out, duplicate_distance_m)
    return PreparedGeotags(out, int(np.count_nonzero(~fixed)), duplicates, counts,
                           int(np.count_nonzero(fixed & coarse)), unknown)


def _flag_duplicates(tags: Geotags, distance_m: float) -> int:
    if len(tags) < 2:
        return 0
    from scipy.spatial import cKDTree

    from ..geometry.geodesy import LocalFrame

    local = LocalFrame.around(tags.lat, tags.lon)
    enu = local.from_geodetic(tags.lat, tags.lon, np.zeros(len(tags)))
    pairs = cKDTree(enu[:, :2]).query_pairs(distance_m, output_type="ndarray")
    later = np.unique(pairs.max(axis=1)) if len(pairs) else np.empty(0, dtype=int)
    for i in later:
        tags.flags[int(i)].append("duplicate_2cm")
    return len(later)

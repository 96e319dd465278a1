"""Rover geotags: read the survey files into one table, keep file order, flag what needs a look.

Formats (docs/design.md#geotags):

* **BirdsEye rover CSV** (no header): ``lat, lon, altWGS84, altMSL, gpsStatus, label`` — degrees,
  metres; ``gpsStatus`` is the NMEA GGA fix quality (4 RTK fixed, 5 RTK float, 2 DGPS, 1 autonomous).
  A label that contains commas may be quoted or simply left unquoted (the rest of the line is the label).
* **CSV with a header** and a column mapping (:class:`ColumnMapping`); unmapped columns are found by
  common names (``lat``/``latitude``, ``lon``/``lng``/``longitude``, ``h``/``height``/``alt``, …).
* **NMEA GGA** logs (any talker: ``$GPGGA``, ``$GNGGA``…): every GGA sentence with a position is one
  geotag; ellipsoidal height = MSL altitude + geoid separation (fields 9 and 11).
* Any QGIS point layer, read by ``qgis_io/layers.py`` and handed over as columns (:func:`geotags_from_columns`).

Rows are numbered as lines of the file (1 = first line), so a message's "row N" is the line a user
sees in a text editor or spreadsheet. A file with some bad rows keeps the good ones; the bad ones are
collected in :attr:`Geotags.problems` (one :class:`InputError` each, naming file, row and field).
"""
from __future__ import annotations

import csv
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError

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
    ("source_row", "int", "line of the input file (or feature number of the input layer)"),
    ("flags", "string", "comma-separated warnings: rtk_float, no_rtk, fix_unknown, duplicate_2cm, no_height"),
]
GEOTAG_FIELD_NAMES = [f[0] for f in GEOTAG_FIELDS]

FORMATS = ("auto", "rover", "header", "nmea")

_LAT_NAMES = ("lat", "latitude", "lat_deg", "latitude_deg", "y_lat")
_LON_NAMES = ("lon", "lng", "long", "longitude", "lon_deg", "longitude_deg", "x_lon")
_HEIGHT_NAMES = ("altwgs84", "alt_wgs84", "h_ellipsoid", "ellipsoidal_height", "height_ellipsoid",
                 "h_ell", "ellh", "h", "height", "height_m", "alt", "altitude", "elevation", "z")
_MSL_NAMES = ("altmsl", "alt_msl", "h_msl", "msl", "height_msl", "orthometric_height", "h_ortho")
_FIX_NAMES = ("gpsstatus", "gps_status", "fix_quality", "fix", "quality", "fixtype", "fix_type",
              "solution", "status", "rtk_status")
_LABEL_NAMES = ("label", "name", "class", "code", "description", "desc", "comment")


@dataclass
class ColumnMapping:
    """Header names of a CSV's columns; None = find the column by its common names."""

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

    def __post_init__(self):
        for name in ("lat", "lon", "height"):
            setattr(self, name, np.asarray(getattr(self, name), dtype=float).reshape(-1))
        n = len(self.lat)
        self.ids = _objects(self.ids)
        self.labels = _objects([UNLABELLED] * n if self.labels is None else [str(v) for v in self.labels])
        self.provenance = _objects([SURVEY] * n if self.provenance is None else self.provenance)
        self.h_msl = np.full(n, np.nan) if self.h_msl is None else np.asarray(self.h_msl, dtype=float).reshape(-1)
        self.fix_quality = np.asarray(np.zeros(n) if self.fix_quality is None else self.fix_quality,
                                      dtype=np.int64).reshape(-1)
        self.source_row = np.asarray(np.arange(1, n + 1) if self.source_row is None else self.source_row,
                                     dtype=np.int64).reshape(-1)
        self.flags = [[] for _ in range(n)] if self.flags is None else [list(f) for f in self.flags]

    def __len__(self) -> int:
        return len(self.lat)

    def subset(self, index) -> "Geotags":
        """The geotags at ``index`` (integer positions or a boolean mask), ids and rows kept."""
        index = np.asarray(index)
        if index.dtype == bool:
            index = np.flatnonzero(index)
        index = index.astype(np.int64).reshape(-1)
        return Geotags(self.ids[index], self.lat[index], self.lon[index], self.height[index], self.labels[index],
                       self.provenance[index], self.h_msl[index], self.fix_quality[index], self.source_row[index],
                       [self.flags[i] for i in index], self.source, list(self.problems))

    def __add__(self, other: "Geotags") -> "Geotags":
        """These geotags followed by ``other``'s (e.g. the survey and a review's targets)."""
        return Geotags(*(np.concatenate([getattr(self, n), getattr(other, n)])
                         for n in ("ids", "lat", "lon", "height", "labels", "provenance", "h_msl", "fix_quality",
                                   "source_row")),
                       self.flags + other.flags, self.source, self.problems + other.problems)

    def records(self):
        """One dict per geotag with the :data:`GEOTAG_FIELD_NAMES`."""
        for i in range(len(self)):
            yield {"id": int(self.ids[i]), "label": self.labels[i], "fix_quality": int(self.fix_quality[i]),
                   "lat": float(self.lat[i]), "lon": float(self.lon[i]),
                   "h_ellipsoid": _none_if_nan(self.height[i]), "h_msl": _none_if_nan(self.h_msl[i]),
                   "source_row": int(self.source_row[i]), "flags": ",".join(self.flags[i])}


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
def read_geotags(path, fmt: str = "auto", mapping: ColumnMapping | None = None) -> Geotags:
    """Read a geotag file of format ``fmt`` (one of :data:`FORMATS`; "auto" looks at the content)."""
    path = Path(path)
    lines = _read_lines(path)
    if fmt not in FORMATS:
        raise ValueError(f"unknown geotag format {fmt!r}; expected one of {FORMATS}")
    if fmt == "auto":
        fmt = detect_format(lines, path)
    reader = {"rover": _parse_rover, "header": _parse_header, "nmea": _parse_nmea}[fmt]
    tags = reader(lines, str(path), mapping) if fmt == "header" else reader(lines, str(path))
    if len(tags) == 0:
        if tags.problems:
            raise InputError(f"no usable geotag: all {len(tags.problems)} row(s) are bad; the first: "
                             f"{tags.problems[0]}", source=str(path))
        raise InputError("has no geotags (the file is empty)", source=str(path))
    return tags


def read_rover_csv(path) -> Geotags:
    return read_geotags(path, "rover")


def read_header_csv(path, mapping: ColumnMapping | None = None) -> Geotags:
    return read_geotags(path, "header", mapping)


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


_FIX_WORDS = {
    **dict.fromkeys(("fixed", "fix", "rtk fixed", "rtk fix", "rtk", "rtk int", "fixed rtk"), FIX_RTK_FIXED),
    **dict.fromkeys(("float", "rtk float", "float rtk"), FIX_RTK_FLOAT),
    **dict.fromkeys(("dgps", "dgnss", "differential", "sbas"), 2),
    **dict.fromkeys(("single", "autonomous", "gps", "gnss", "standalone", "spp", "3d", "3d fix"), 1),
    **dict.fromkeys(("none", "no fix", "invalid", "unknown"), 0),
}


def _fix_code(text: str, source: str, row: int, field_name: str) -> int:
    """A fix quality from a GGA code ("4") or a word ("fixed", "float", "single", "dgps")."""
    text = text.strip()
    if text == "":
        return 0
    try:
        value = float(text)
    except ValueError:
        word = " ".join(re.split(r"[\s_\-]+", text.lower()))
        if word in _FIX_WORDS:
            return _FIX_WORDS[word]
        raise InputError(f"{text!r} is not a fix quality; expected an NMEA GGA code (4 RTK fixed, "
                         "5 RTK float, 1 autonomous) or a word such as 'fixed'/'float'/'single'",
                         source=source, row=row, field=field_name) from None
    if value != int(value) or not 0 <= value <= 9:
        raise InputError(f"{text!r} is not a fix quality; expected an NMEA GGA code 0–9 "
                         "(4 RTK fixed, 5 RTK float, 1 autonomous)", source=source, row=row, field=field_name)
    return int(value)


class _Collector:
    """Accumulates good rows and bad-row errors of one file."""

    def __init__(self, source: str):
        self.source = source
        self.rows: list[tuple] = []
        self.problems: list[InputError] = []

    def geotags(self) -> Geotags:
        """The good rows, numbered 1.. in file order (the ids Import geotags writes)."""
        lat, lon, h, msl, fix, label, row = zip(*self.rows) if self.rows else ([],) * 7
        return Geotags(np.arange(1, len(lat) + 1), lat, lon, h, label, None, msl, fix, row, source=self.source,
                       problems=self.problems)


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
            h = _number(cells[2], source, row, "altWGS84", "ellipsoidal height in metres", -1000, 10000,
                        allow_empty=True)
            msl = _number(cells[3], source, row, "altMSL", "height above MSL in metres", -1000, 10000,
                          allow_empty=True)
            fix = _fix_code(cells[4], source, row, "gpsStatus")
        except InputError as exc:
            out.problems.append(exc)
            continue
        label = ",".join(c.strip() for c in cells[5:])
        out.rows.append((lat, lon, h, msl, fix, label, row))
    return out.geotags()


def _find_column(header: list[str], wanted: str | None, candidates, source: str, what: str,
                 required: bool) -> int | None:
    lowered = [h.strip().lower() for h in header]
    if wanted:
        key = wanted.strip().lower()
        if key not in lowered:
            raise InputError(f"has no column '{wanted}' for the {what}; its columns are: "
                             f"{', '.join(h.strip() for h in header)}", source=source, row=1)
        return lowered.index(key)
    for name in candidates:
        if name in lowered:
            return lowered.index(name)
    if required:
        raise InputError(f"has no {what} column; name it with the column mapping (found columns: "
                         f"{', '.join(h.strip() for h in header)})", source=source, row=1)
    return None


def _parse_header(lines, source: str, mapping: ColumnMapping | None = None) -> Geotags:
    mapping = mapping or ColumnMapping()
    rows = _content_rows(lines)
    try:
        header_row, header_line = next(rows)
    except StopIteration:
        return _Collector(source).geotags()
    header = _split_csv(header_line)
    lat_i = _find_column(header, mapping.lat, _LAT_NAMES, source, "latitude", True)
    lon_i = _find_column(header, mapping.lon, _LON_NAMES, source, "longitude", True)
    msl_i = _find_column(header, mapping.msl, _MSL_NAMES, source, "MSL height", False)
    height_candidates = tuple(n for n in _HEIGHT_NAMES if msl_i is None or n != header[msl_i].strip().lower())
    h_i = _find_column(header, mapping.height, height_candidates, source, "ellipsoidal height", False)
    if h_i is not None and h_i == msl_i:
        h_i = None
    fix_i = _find_column(header, mapping.fix, _FIX_NAMES, source, "fix quality", False)
    label_i = _find_column(header, mapping.label, _LABEL_NAMES, source, "label", False)
    names = [h.strip() for h in header]
    out = _Collector(source)
    for row, line in rows:
        cells = _split_csv(line)
        try:
            needed = max(i for i in (lat_i, lon_i, h_i, msl_i, fix_i, label_i) if i is not None)
            if len(cells) <= needed:
                raise InputError(f"has {len(cells)} column(s); the header has {len(header)}",
                                 source=source, row=row)
            lat = _number(cells[lat_i], source, row, names[lat_i], "latitude in degrees, -90…90", -90, 90)
            lon = _number(cells[lon_i], source, row, names[lon_i], "longitude in degrees, -180…180",
                          -180, 180)
            h = (float("nan") if h_i is None else
                 _number(cells[h_i], source, row, names[h_i], "ellipsoidal height in metres", -1000, 10000,
                         allow_empty=True))
            msl = (float("nan") if msl_i is None else
                   _number(cells[msl_i], source, row, names[msl_i], "height above MSL in metres",
                           -1000, 10000, allow_empty=True))
            fix = 0 if fix_i is None else _fix_code(cells[fix_i], source, row, names[fix_i])
        except InputError as exc:
            out.problems.append(exc)
            continue
        label = "" if label_i is None else cells[label_i].strip()
        out.rows.append((lat, lon, h, msl, fix, label, row))
    return out.geotags()


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
            out.problems.append(exc)
            continue
        out.rows.append((lat, lon, msl + sep, msl, fix, "", row))
    return out.geotags()


def geotags_from_columns(lat, lon, h_ellipsoid=None, h_msl=None, fix_quality=None, label=None,
                         source_row=None, source: str = "point layer", field_names=None) -> Geotags:
    """Geotags from columns of raw values (a point layer already transformed to WGS84).

    Heights and fix qualities may be numbers, numeric text or None (unknown); a row with a value that
    is none of these is reported in ``problems`` (naming ``field_names[column]``) and left out.
    """
    lat = np.asarray(lat, dtype=float)
    n = len(lat)
    lon = np.asarray(lon, dtype=float)
    rows = np.arange(1, n + 1) if source_row is None else np.asarray(source_row, dtype=np.int64)
    names = {"height": "height", "msl": "msl", "fix": "fix", **(field_names or {})}
    out = _Collector(source)
    for i in range(n):
        row = int(rows[i])
        try:
            if not (np.isfinite(lat[i]) and abs(lat[i]) <= 90 and np.isfinite(lon[i]) and abs(lon[i]) <= 180):
                raise InputError("has no valid position (empty geometry or outside -90…90°, -180…180°)",
                                 source=source, row=row, field="geometry")
            h = _raw_number(None if h_ellipsoid is None else h_ellipsoid[i], source, row, names["height"],
                            "ellipsoidal height in metres")
            msl = _raw_number(None if h_msl is None else h_msl[i], source, row, names["msl"],
                              "height above MSL in metres")
            raw_fix = None if fix_quality is None else fix_quality[i]
            fix = 0 if raw_fix is None else _fix_code(str(raw_fix), source, row, names["fix"])
        except InputError as exc:
            out.problems.append(exc)
            continue
        text = "" if label is None or label[i] is None else str(label[i])
        out.rows.append((float(lat[i]), float(lon[i]), h, msl, fix, text, row))
    return out.geotags()


def _raw_number(value, source, row, field_name, what) -> float:
    if value is None:
        return float("nan")
    if isinstance(value, (int, float)):
        return float(value) if np.isfinite(value) else float("nan")
    return _number(str(value), source, row, field_name, what, -1000, 10000, allow_empty=True)


# ---------------------------------------------------------------------------------------- checking
@dataclass
class PreparedGeotags:
    """Geotags ready to write, and what was done to them (for the Processing log)."""

    geotags: Geotags
    dropped_not_fixed: int
    duplicates: int
    counts_by_fix: dict


def prepare_geotags(tags: Geotags, fixed_only: bool = False, pole_height_m: float = 0.0,
                    duplicate_distance_m: float = DUPLICATE_DISTANCE_M) -> PreparedGeotags:
    """Apply the fix filter and the antenna pole height, and flag what needs a look.

    ``pole_height_m`` (m) is subtracted from both heights: the rover measures its antenna, the target
    is on the ground. With ``fixed_only`` the geotags without an RTK fixed solution are dropped (and
    counted); otherwise they are kept and flagged ``rtk_float`` / ``no_rtk`` / ``fix_unknown``.
    A geotag within ``duplicate_distance_m`` horizontally of an earlier kept one is flagged
    ``duplicate_2cm`` (the earlier one is left unflagged: it is the original press).
    """
    if not np.isfinite(pole_height_m) or pole_height_m < 0 or pole_height_m > 10:
        raise InputError(f"pole height {pole_height_m} m is not a plausible antenna pole (0–10 m)",
                         field="POLE_HEIGHT_M")
    counts = {FIX_NAMES.get(int(k), f"code {int(k)}"): int(v)
              for k, v in zip(*np.unique(tags.fix_quality, return_counts=True))}
    keep = tags.fix_quality == FIX_RTK_FIXED if fixed_only else np.ones(len(tags), dtype=bool)
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
    return PreparedGeotags(out, int(np.count_nonzero(~keep)), duplicates, counts)


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

"""Flight logs → frames: pose-log parsing, strobe↔image sync, ground heights, footprints, frame records.

Inputs (DESIGN §4):

* **BirdsEye pose log**: CSV with a header, one row per INS message:
  ``time_s, lat_deg, lon_deg, height_m, qw, qx, qy, qz, rtk_status, radalt_m, radalt_snr, strobe``
  (WGS84 degrees, ellipsoidal metres, body FRD → NED quaternion, ``rtk_status`` 3 fixed / 2 float /
  1 none, radar altimeter range (m) and SNR (dB), ``strobe`` = 1 on the camera's exposure event).
  Columns may come in any order; extra columns are ignored; ``radalt_m``/``radalt_snr`` may be empty
  on rows without an altimeter reading. Parsing is vectorised (``numpy.loadtxt`` on chunks of lines)
  and falls back to line-by-line parsing only for a chunk that holds a bad row, so every bad row is
  still reported with its line number and field.
* **Images**: a folder with ``images.csv`` (``time_s, file``), else files named
  ``<sec>.<nsec>.png|jpg`` (``nsec`` = integer nanoseconds, as the payload writes ROS stamps).
* **The reference payload's** ``flight_data.db`` (SQLite, table ``cam0_images_flight_data``): one
  row per saved frame with UTM ``x, y, z``, quaternion ``q, u, a, t`` = (x, y, z, w), ``rtk_status``,
  ``radalt``, ``save_loc``. The table has no UTM zone, so the caller names the CRS. Assumed, as the
  pose log: ``z`` ellipsoidal height, quaternion body FRD → NED, ``rtk_status`` 3/2/1.

Rows are numbered as lines of the file (1 = the header line), so "row N" is what an editor shows.

Frames (the frame layer, :mod:`.frame_records`) are assembled in :class:`Frames`; footprints are the
ground intersection of each image border (:func:`compute_footprints`), written in the output CRS.
"""
from __future__ import annotations

import csv
import math
import os
import re
import sqlite3
from dataclasses import dataclass, field
from itertools import islice
from pathlib import Path

import numpy as np

from ..geometry.camera import CameraModel
from ..errors import Cancelled, InputError
from .frame_records import FRAME_FIELDS, euler_degrees
from ..geometry.geodesy import LocalFrame, ProjectedCRS
from .geotags import split_lines
from ..geometry.ground import LevelPlaneGround
from ..geometry.poses import FrameGeometry, FramePoses, ground_height_from_altimeter
from ..geometry.projection import footprints

POSE_LOG_COLUMNS = ("time_s", "lat_deg", "lon_deg", "height_m", "qw", "qx", "qy", "qz", "rtk_status",
                    "radalt_m", "radalt_snr", "strobe")
#: Columns that may be missing from the header (then every altimeter reading counts as good).
_OPTIONAL_COLUMNS = ("radalt_snr",)
#: Columns that may be empty on a row (an INS message without an altimeter reading).
_MAY_BE_EMPTY = ("radalt_m", "radalt_snr")

RTK_FIXED, RTK_FLOAT, RTK_NONE = 3, 2, 1
#: Examples of bad rows kept for the log; the count of bad rows is always complete.
MAX_EXAMPLES = 20
#: A strobe row whose altimeter reading is bad takes the ground height interpolated from good
#: readings at most this far (s) before and after it; beyond, the frame has no ground height.
RADALT_WINDOW_S = 1.0
#: Terrain slope (deg) up to which the method measured the level-plane ground model to hold.
FLAT_ENVELOPE_DEG = 10.0
#: The flight line is split where the pose log has a gap longer than this (s).
TRACK_GAP_S = 2.0

#: Frame-layer fields beyond :data:`.frame_records.FRAME_FIELDS` (DJI RTK accuracy; NULL otherwise).
FRAME_EXTRA_FIELDS = [
    ("rtk_std_lon_m", "double", "RTK standard deviation east-west (m), DJI RtkStdLon"),
    ("rtk_std_lat_m", "double", "RTK standard deviation north-south (m), DJI RtkStdLat"),
    ("rtk_std_hgt_m", "double", "RTK standard deviation of height (m), DJI RtkStdHgt"),
    ("terrain_slope_deg", "double", "terrain slope under the footprint from the DEM (deg; NULL without a DEM)"),
]
FRAME_LAYER_FIELDS = FRAME_FIELDS + FRAME_EXTRA_FIELDS

TRACK_FIELDS = [
    ("segment", "int", "flight line segment, 1.. in time order"),
    ("label", "string", "segment summary for the map label"),
    ("start_s", "double", "first pose time (s, pose log clock)"),
    ("end_s", "double", "last pose time (s)"),
    ("duration_s", "double", "end − start (s)"),
    ("n_frames", "int", "frames exposed on this segment"),
    ("length_m", "double", "horizontal length (m)"),
]


class RowProblems:
    """Bad rows of one input: a complete count and the first :data:`MAX_EXAMPLES` errors."""

    def __init__(self):
        self.count = 0
        self.examples: list[InputError] = []

    def add(self, error: InputError) -> None:
        self.count += 1
        if len(self.examples) < MAX_EXAMPLES:
            self.examples.append(error)

    def summary(self, what: str) -> str | None:
        if not self.count:
            return None
        first = "; ".join(str(e) for e in self.examples[:3])
        return f"{self.count} bad {what} left out; first: {first}"


def _check_cancel(is_canceled) -> None:
    if is_canceled is not None and is_canceled():
        raise Cancelled()


# ============================================================================ pose log
@dataclass
class PoseLog:
    """INS rows of a pose log (length N arrays) and the rows that had to be left out."""

    time_s: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    quat: np.ndarray
    rtk_status: np.ndarray
    radalt: np.ndarray
    radalt_snr: np.ndarray
    strobe: np.ndarray
    row: np.ndarray
    source: str = ""
    problems: RowProblems = field(default_factory=RowProblems)

    def __len__(self) -> int:
        return len(self.time_s)


def read_pose_log(path, chunk_lines: int = 65536, progress=None, is_canceled=None) -> PoseLog:
    """Read a BirdsEye pose-log CSV; bad rows are left out and counted in ``problems``."""
    path = Path(path)
    source = str(path)
    if not path.is_file():
        raise InputError("pose log not found", source=source)
    size = max(path.stat().st_size, 1)
    with open(path, encoding="utf-8-sig", errors="replace", newline="") as f:
        header_row, header = 0, None
        for header_row, line in enumerate(f, start=1):
            if line.strip() and not line.lstrip().startswith("#"):
                header = [c.strip().strip('"').lower() for c in line.strip().split(",")]
                break
        if header is None:
            raise InputError("is empty; expected a header line "
                             f"'{','.join(POSE_LOG_COLUMNS)}' and one row per INS message", source=source)
        present = [c for c in POSE_LOG_COLUMNS if c in header]
        missing = [c for c in POSE_LOG_COLUMNS if c not in header and c not in _OPTIONAL_COLUMNS]
        if missing:
            raise InputError(f"header has no column(s) {', '.join(missing)}; expected the BirdsEye pose "
                             f"log header {','.join(POSE_LOG_COLUMNS)} (found: {', '.join(header)})",
                             source=source, row=header_row)
        usecols = [header.index(c) for c in present]
        problems = RowProblems()
        parts, rows = [], []
        line_no, done_chars = header_row, 0
        while True:
            _check_cancel(is_canceled)
            chunk = list(islice(f, chunk_lines))
            if not chunk:
                break
            numbers = np.arange(line_no + 1, line_no + 1 + len(chunk))
            line_no += len(chunk)
            done_chars += sum(map(len, chunk))
            keep = [i for i, ln in enumerate(chunk) if ln.strip() and not ln.lstrip().startswith("#")]
            lines = [chunk[i] for i in keep]
            values, good_numbers = _parse_chunk(lines, numbers[keep], usecols, present, len(header),
                                                source, problems)
            parts.append(values)
            rows.append(good_numbers)
            if progress is not None:
                progress(min(1.0, done_chars / size))
    data = np.concatenate(parts) if parts else np.empty((0, len(present)))
    row = np.concatenate(rows) if rows else np.empty(0, dtype=np.int64)
    cols = {name: data[:, k] for k, name in enumerate(present)}
    if "radalt_snr" not in cols:
        cols["radalt_snr"] = np.full(len(data), np.inf)  # no SNR column: every reading counts as good
    good = _validate_pose_rows(cols, row, source, problems)
    if not np.all(good):
        cols = {k: v[good] for k, v in cols.items()}
        row = row[good]
    if len(row) == 0:
        detail = f"; the first bad row: {problems.examples[0]}" if problems.examples else ""
        raise InputError(f"has no usable pose rows ({problems.count} bad){detail}", source=source)
    order = np.argsort(cols["time_s"], kind="stable")
    if np.any(order != np.arange(len(order))):
        cols = {k: v[order] for k, v in cols.items()}
        row = row[order]
    quat = np.stack([cols["qw"], cols["qx"], cols["qy"], cols["qz"]], axis=1)
    return PoseLog(cols["time_s"], cols["lat_deg"], cols["lon_deg"], cols["height_m"], quat,
                   cols["rtk_status"].astype(np.int64), cols["radalt_m"], cols["radalt_snr"],
                   cols["strobe"] == 1, row, source, problems)


def _float_or_nan(text: str) -> float:
    text = text.strip()
    return float(text) if text else math.nan


def _parse_chunk(lines, numbers, usecols, names, ncols, source, problems):
    """Numbers (n, len(usecols)) of the good lines and their line numbers; bad lines are reported."""
    if not lines:
        return np.empty((0, len(usecols))), np.empty(0, dtype=np.int64)
    try:
        values = np.loadtxt(lines, delimiter=",", usecols=usecols, dtype=float, ndmin=2, comments=None)
        if values.shape[0] == len(lines):
            return values, numbers
    except ValueError:
        pass
    converters = {k: _float_or_nan for k, name in zip(usecols, names) if name in _MAY_BE_EMPTY}
    if converters:
        try:
            values = np.loadtxt(lines, delimiter=",", usecols=usecols, dtype=float, ndmin=2, comments=None,
                                converters=converters)
            if values.shape[0] == len(lines):
                return values, numbers
        except ValueError:
            pass
    # Slow path, only for a chunk with a bad line: find and report each one precisely.
    out = np.empty((len(lines), len(usecols)))
    ok = np.ones(len(lines), dtype=bool)
    need = max(usecols) + 1
    for i, line in enumerate(lines):
        cells = line.rstrip("\r\n").split(",")
        if len(cells) < need:
            problems.add(InputError(f"has {len(cells)} column(s); the header has {ncols}", source=source,
                                    row=int(numbers[i])))
            ok[i] = False
            continue
        for k, (col, name) in enumerate(zip(usecols, names)):
            text = cells[col].strip().strip('"')
            try:
                out[i, k] = float(text) if text or name not in _MAY_BE_EMPTY else math.nan
            except ValueError:
                problems.add(InputError(f"{text!r} is not a number; expected {_EXPECTED[name]}",
                                        source=source, row=int(numbers[i]), field=name))
                ok[i] = False
                break
    return out[ok], numbers[ok]


_EXPECTED = {
    "time_s": "the time in seconds",
    "lat_deg": "latitude in degrees, -90…90",
    "lon_deg": "longitude in degrees, -180…180",
    "height_m": "ellipsoidal height in metres",
    "qw": "a unit quaternion component", "qx": "a unit quaternion component",
    "qy": "a unit quaternion component", "qz": "a unit quaternion component",
    "rtk_status": "3 (fixed), 2 (float) or 1 (none)",
    "radalt_m": "the radar altimeter range in metres (or empty)",
    "radalt_snr": "the altimeter SNR in dB (or empty)",
    "strobe": "1 on the exposure event, else 0",
}


def _validate_pose_rows(cols, row, source, problems) -> np.ndarray:
    """Mask of rows whose values are plausible; the others are reported (first failing field)."""
    qnorm = np.sqrt(cols["qw"] ** 2 + cols["qx"] ** 2 + cols["qy"] ** 2 + cols["qz"] ** 2)
    with np.errstate(invalid="ignore"):
        checks = [
            ("time_s", ~np.isfinite(cols["time_s"]), "expected a finite time in seconds"),
            ("lat_deg", ~(np.abs(cols["lat_deg"]) <= 90), "expected latitude -90…90°"),
            ("lon_deg", ~(np.abs(cols["lon_deg"]) <= 180), "expected longitude -180…180°"),
            ("height_m", ~((cols["height_m"] > -1000) & (cols["height_m"] < 20000)),
             "expected an ellipsoidal height in metres (-1000…20000)"),
            ("qw", ~(np.abs(qnorm - 1.0) < 0.05), "expected a unit quaternion (qw, qx, qy, qz)"),
            ("rtk_status", ~np.isin(cols["rtk_status"], (0, 1, 2, 3, 4, 5, 6)),
             "expected 3 (fixed), 2 (float) or 1 (none)"),
            ("strobe", ~np.isin(cols["strobe"], (0, 1)), "expected 1 on the exposure event, else 0"),
        ]
    bad = np.zeros(len(row), dtype=bool)
    for name, mask, expected in checks:
        new = np.flatnonzero(mask & ~bad)
        for i in new:
            value = f"norm {qnorm[i]:.3f}" if name == "qw" else f"{cols[name][i]:g}"
            problems.add(InputError(f"{value} is out of range; {expected}", source=source, row=int(row[i]),
                                    field=name))
        bad[new] = True
    return ~bad


# ============================================================================ images
_STAMP_NAME = re.compile(r"^(\d+)\.(\d+)\.(png|jpe?g|tiff?)$", re.IGNORECASE)


@dataclass
class ImageList:
    """Images and their exposure times (s, the payload clock)."""

    time_s: np.ndarray
    path: list
    source: str = ""
    problems: RowProblems = field(default_factory=RowProblems)
    ignored: list = field(default_factory=list)

    def __len__(self) -> int:
        return len(self.time_s)


def list_images(folder) -> ImageList:
    """Images of a folder: from its ``images.csv`` if present, else from ``<sec>.<nsec>.ext`` names."""
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError("image folder not found", source=str(folder))
    csv_path = folder / "images.csv"
    if csv_path.is_file():
        images = _read_images_csv(csv_path, folder)
    else:
        root = folder.resolve()
        times, paths, ignored = [], [], []
        with os.scandir(folder) as entries:
            names = sorted(e.name for e in entries if e.is_file())
        for name in names:
            match = _STAMP_NAME.match(name)
            if match:
                times.append(int(match.group(1)) + int(match.group(2)) * 1e-9)
                paths.append(os.path.join(root, name))
            else:
                ignored.append(name)
        images = ImageList(np.asarray(times, dtype=float), paths, str(folder), ignored=ignored)
    if len(images) == 0:
        hint = f" ({len(images.ignored)} other file(s), e.g. {images.ignored[0]})" if images.ignored else ""
        bad = f"; {images.problems.summary('rows')}" if images.problems.count else ""
        raise InputError("holds no images: expected an images.csv (time_s, file) or image files named "
                         f"<sec>.<nsec>.png|jpg{hint}{bad}", source=str(folder))
    return images


def _read_images_csv(path: Path, folder: Path) -> ImageList:
    source = str(path)
    problems = RowProblems()
    times, paths = [], []
    lines = split_lines(path.read_bytes())
    content = [(n, ln) for n, ln in enumerate(lines, start=1) if ln.strip() and not ln.lstrip().startswith("#")]
    if not content:
        return ImageList(np.empty(0), [], source, problems)
    header_row, header_line = content[0]
    header = [c.strip().lower() for c in next(csv.reader([header_line]))]
    for name in ("time_s", "file"):
        if name not in header:
            raise InputError(f"header has no column '{name}'; expected 'time_s,file' (found: "
                             f"{', '.join(header)})", source=source, row=header_row)
    ti, fi = header.index("time_s"), header.index("file")
    root = str(folder.resolve())
    with os.scandir(folder) as entries:
        present = {e.name for e in entries}
    for row, line in content[1:]:
        try:
            cells = next(csv.reader([line]))
        except csv.Error as exc:
            problems.add(InputError(f"is not valid CSV ({exc})", source=source, row=row))
            continue
        if len(cells) <= max(ti, fi):
            problems.add(InputError(f"has {len(cells)} column(s); expected time_s, file", source=source, row=row))
            continue
        try:
            t = float(cells[ti])
            if not math.isfinite(t):
                raise ValueError
        except ValueError:
            problems.add(InputError(f"{cells[ti].strip()!r} is not a number; expected the exposure time in "
                                    "seconds", source=source, row=row, field="time_s"))
            continue
        name = cells[fi].strip()
        if not name:
            problems.add(InputError("is empty; expected an image file name", source=source, row=row,
                                    field="file"))
            continue
        if os.path.isabs(name):
            found = os.path.isfile(name)
            file_path = name
        else:
            found = name in present or os.path.isfile(os.path.join(root, name))
            file_path = os.path.join(root, name)
        if not found:
            problems.add(InputError(f"image '{name}' not found in {folder}", source=source, row=row,
                                    field="file"))
            continue
        times.append(t)
        paths.append(file_path)
    return ImageList(np.asarray(times, dtype=float), paths, source, problems)


# ============================================================================ sync
@dataclass
class SyncResult:
    """Pairing of S strobes with images: ``image_of[s]`` (−1 = none) and ``offset_s[s]`` = t_img − t_strobe."""

    image_of: np.ndarray
    offset_s: np.ndarray
    duplicate_strobes: np.ndarray
    duplicate_images: np.ndarray
    unmatched_strobes: np.ndarray
    unmatched_images: np.ndarray


def _duplicated(t: np.ndarray) -> np.ndarray:
    """True for every entry whose value occurs more than once."""
    order = np.argsort(t, kind="stable")
    ts = t[order]
    same = np.zeros(len(t), dtype=bool)
    if len(t) > 1:
        eq = ts[1:] == ts[:-1]
        same[1:] |= eq
        same[:-1] |= eq
    out = np.zeros(len(t), dtype=bool)
    out[order] = same
    return out


def sync_strobes(strobe_t, image_t, fps: float) -> SyncResult:
    """Each strobe takes the nearest unpaired image within 1/fps (s); globally nearest pairs first.

    Strobes (or images) sharing a timestamp cannot be told apart: all of them are left out and listed
    in ``duplicate_strobes`` / ``duplicate_images``.
    """
    if not fps > 0:
        raise InputError(f"frame rate {fps} is not positive; expected frames per second", field="FPS")
    strobe_t = np.asarray(strobe_t, dtype=float)
    image_t = np.asarray(image_t, dtype=float)
    tol = 1.0 / fps
    dup_s, dup_i = _duplicated(strobe_t), _duplicated(image_t)
    s_idx, i_idx = np.flatnonzero(~dup_s), np.flatnonzero(~dup_i)
    order = np.argsort(image_t[i_idx], kind="stable")
    it, i_sorted = image_t[i_idx][order], i_idx[order]
    st = strobe_t[s_idx]
    lo = np.searchsorted(it, st - tol, side="left")
    hi = np.searchsorted(it, st + tol, side="right")
    counts = hi - lo
    pair_s = np.repeat(np.arange(len(s_idx)), counts)
    pair_i = np.repeat(lo, counts) + (np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts))
    dt = it[pair_i] - st[pair_s]
    by_distance = np.lexsort((pair_i, pair_s, np.abs(dt)))
    image_of = np.full(len(strobe_t), -1, dtype=np.int64)
    offset = np.full(len(strobe_t), np.nan)
    taken_s = np.zeros(len(s_idx), dtype=bool)
    taken_i = np.zeros(len(it), dtype=bool)
    for s, i, d in zip(pair_s[by_distance].tolist(), pair_i[by_distance].tolist(), dt[by_distance].tolist()):
        if taken_s[s] or taken_i[i]:
            continue
        taken_s[s] = taken_i[i] = True
        image_of[s_idx[s]] = i_sorted[i]
        offset[s_idx[s]] = d
    return SyncResult(image_of, offset, np.flatnonzero(dup_s), np.flatnonzero(dup_i),
                      s_idx[~taken_s], np.sort(i_sorted[~taken_i]))


# ============================================================================ ground heights
def ground_heights(time_s, height, quat, radalt, good, query, t_imu_rad=None,
                   window_s: float = RADALT_WINDOW_S):
    """Ellipsoidal ground heights (m) at rows ``query`` and whether each was interpolated.

    Rows with a ``good`` altimeter reading give the tilt-corrected ground height
    (:func:`.poses.ground_height_from_altimeter`); a queried row without one takes the linear
    interpolation in time between the nearest good readings before and after it, or the nearer one
    alone, provided they lie within ``window_s``; otherwise NaN.
    """
    time_s = np.asarray(time_s, dtype=float)
    query = np.asarray(query, dtype=np.int64)
    good_idx = np.flatnonzero(good)
    out = np.full(len(query), np.nan)
    interpolated = np.zeros(len(query), dtype=bool)
    if len(good_idx) == 0 or len(query) == 0:
        return out, interpolated
    g_t = time_s[good_idx]
    g_h = ground_height_from_altimeter(height[good_idx], quat[good_idx], radalt[good_idx], t_imu_rad)
    own = np.asarray(good)[query]
    own_pos = np.searchsorted(good_idx, query[own])
    out[own] = g_h[own_pos]
    need = np.flatnonzero(~own)
    if len(need):
        t = time_s[query[need]]
        after = np.searchsorted(g_t, t, side="left")
        before = after - 1
        has_b = before >= 0
        has_a = after < len(g_t)
        tb = np.where(has_b, g_t[np.clip(before, 0, None)], -np.inf)
        ta = np.where(has_a, g_t[np.clip(after, None, len(g_t) - 1)], np.inf)
        ok_b = has_b & (t - tb <= window_s)
        ok_a = has_a & (ta - t <= window_s)
        hb = g_h[np.clip(before, 0, None)]
        ha = g_h[np.clip(after, None, len(g_t) - 1)]
        with np.errstate(invalid="ignore", divide="ignore"):
            w = np.where(ta > tb, (t - tb) / (ta - tb), 0.5)
        both = ok_b & ok_a
        value = np.where(both, hb + w * (ha - hb), np.where(ok_b, hb, np.where(ok_a, ha, np.nan)))
        out[need] = value
        interpolated[need] = np.isfinite(value)
    return out, interpolated


# ============================================================================ frames
@dataclass
class Frames:
    """F frames, everything the frame layer carries (arrays of length F; heights ellipsoidal, m).

    ``cameras[f]`` is the camera model of frame f (frames of one camera share the object);
    ``euler_deg`` (F, 3) overrides the roll/pitch/yaw derived from ``quat`` (DJI writes the gimbal
    angles exactly, where a nadir gimbal sits at the ZYX singularity); ``extra`` holds
    :data:`FRAME_EXTRA_FIELDS` columns.
    """

    frame_id: np.ndarray
    image: list
    time_s: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    quat: np.ndarray
    ground_h: np.ndarray
    rtk_status: np.ndarray
    sync_offset_s: np.ndarray
    cameras: list
    flags: list
    euler_deg: np.ndarray | None = None
    extra: dict = field(default_factory=dict)

    def __len__(self) -> int:
        return len(self.frame_id)

    def subset(self, index) -> "Frames":
        index = np.asarray(index)
        if index.dtype == bool:
            index = np.flatnonzero(index)
        return Frames(self.frame_id[index], [self.image[i] for i in index], self.time_s[index],
                      self.lat[index], self.lon[index], self.height[index], self.quat[index],
                      self.ground_h[index], self.rtk_status[index], self.sync_offset_s[index],
                      [self.cameras[i] for i in index], [list(self.flags[i]) for i in index],
                      None if self.euler_deg is None else self.euler_deg[index],
                      {k: v[index] for k, v in self.extra.items()})


@dataclass
class Footprints:
    """Per frame: the border's ground ring (K, 3) as output-CRS x, y and ellipsoidal z, or None."""

    rings: list
    depth_m: np.ndarray
    gsd_cm: np.ndarray
    crs: ProjectedCRS
    slope_deg: np.ndarray | None = None


def compute_footprints(frames: Frames, crs: ProjectedCRS, per_edge: int = 4, block: int = 4096,
                       progress=None, is_canceled=None, ground=None) -> Footprints:
    """Ground footprints of every frame, in ``crs``: over its level ground, or draped on a DEM.

    Geometry runs in one :class:`.geodesy.LocalFrame` around all frames (true-north attitudes, no
    grid convergence); ring points go local → WGS84 → ``crs``. ``ground`` builds another ground model
    from a :class:`FrameGeometry` (a DEM's ``DemGround.from_dem``); with it every frame is placed and
    the terrain slope under each footprint is measured. A frame without a ground height (level plane),
    or whose border rays do not all reach the ground (a view above the horizon), gets no ring and the
    flag ``no_ground_height`` / ``footprint_unbounded`` (added to ``frames.flags``).
    """
    n = len(frames)
    rings: list = [None] * n
    depth = np.full(n, np.nan)
    gsd = np.full(n, np.nan)
    slope = np.full(n, np.nan)
    if n == 0:
        return Footprints(rings, depth, gsd, crs, slope)
    local = LocalFrame.around(frames.lat, frames.lon, frames.height)
    placeable = np.isfinite(frames.ground_h) | (ground is not None)
    for i in np.flatnonzero(~placeable):
        frames.flags[i].append("no_ground_height")
    by_camera: dict[int, list[int]] = {}
    for i in np.flatnonzero(placeable):
        by_camera.setdefault(id(frames.cameras[i]), []).append(int(i))
    total, done = max(int(np.count_nonzero(placeable)), 1), 0
    for members in by_camera.values():
        camera = frames.cameras[members[0]]
        members = np.asarray(members)
        for start in range(0, len(members), block):
            _check_cancel(is_canceled)
            idx = members[start:start + block]
            poses = FramePoses(frames.frame_id[idx], frames.lat[idx], frames.lon[idx], frames.height[idx],
                               frames.quat[idx], frames.ground_h[idx], camera)
            geometry = FrameGeometry(poses, local)
            model = LevelPlaneGround(geometry) if ground is None else ground(geometry)
            pts, complete = footprints(geometry, model, per_edge)
            if ground is None:
                depth[idx] = geometry.depth_below()
            else:
                depth[idx], slope[idx] = _terrain_depth_and_slope(geometry, model)
                for f in idx[np.nan_to_num(slope[idx]) > FLAT_ENVELOPE_DEG]:
                    frames.flags[f].append("steep_terrain")
            gsd[idx] = depth[idx] / np.sqrt(camera.fx * camera.fy) * 100.0
            k = pts.shape[1]
            ok = np.flatnonzero(complete)
            if len(ok):
                lat, lon, h = local.to_geodetic(pts[ok].reshape(-1, 3))
                x, y = crs.from_geodetic(lat, lon)
                xyz = np.stack([x, y, h], axis=-1).reshape(len(ok), k, 3)
                for j, f in enumerate(idx[ok]):
                    rings[f] = xyz[j]
            for f in idx[~complete]:
                frames.flags[f].append("footprint_unbounded")
            done += len(idx)
            if progress is not None:
                progress(done / total)
    return Footprints(rings, depth, gsd, crs, slope)


def _terrain_depth_and_slope(geometry: FrameGeometry, model):
    """Depth along the local vertical to the terrain under each camera, and the footprint's slope."""
    from ..geometry.dem import frame_terrain_slope

    below, valid = model.intersect(np.arange(len(geometry)), geometry.C, -geometry.up)
    depth = np.where(valid, np.einsum("fi,fi->f", geometry.C - below, geometry.up), np.nan)
    return depth, frame_terrain_slope(geometry, model).slope_deg


def frame_records(frames: Frames, fp: Footprints):
    """One dict per frame with the :data:`FRAME_LAYER_FIELDS` names (None for unknown values)."""
    if frames.euler_deg is not None:
        roll, pitch, yaw = frames.euler_deg.T
    else:
        roll, pitch, yaw = euler_degrees(frames.quat) if len(frames) else (np.empty(0),) * 3
    quat = frames.quat / np.linalg.norm(frames.quat, axis=1, keepdims=True)
    json_of: dict[int, str] = {}
    for i in range(len(frames)):
        cam = frames.cameras[i]
        if id(cam) not in json_of:
            json_of[id(cam)] = cam.to_json()
        rec = {"frame_id": int(frames.frame_id[i]), "image": frames.image[i],
               "time_s": _value(frames.time_s[i]), "lat": float(frames.lat[i]), "lon": float(frames.lon[i]),
               "height_m": float(frames.height[i]),
               "qw": float(quat[i, 0]), "qx": float(quat[i, 1]), "qy": float(quat[i, 2]), "qz": float(quat[i, 3]),
               "roll_deg": float(roll[i]), "pitch_deg": float(pitch[i]), "yaw_deg": float(yaw[i]),
               "ground_h_m": _value(frames.ground_h[i]), "depth_m": _value(fp.depth_m[i]),
               "rtk_status": int(frames.rtk_status[i]), "sync_offset_s": _value(frames.sync_offset_s[i]),
               "gsd_cm": _value(fp.gsd_cm[i]), "camera": json_of[id(cam)],
               "flags": ",".join(dict.fromkeys(frames.flags[i]))}
        for name, _, _ in FRAME_EXTRA_FIELDS:
            rec[name] = _value(frames.extra[name][i]) if name in frames.extra else None
        if fp.slope_deg is not None:
            rec["terrain_slope_deg"] = _value(fp.slope_deg[i])
        yield rec


def _value(x):
    x = float(x)
    return None if math.isnan(x) else x


def rtk_flags(rtk_status: np.ndarray) -> list[list[str]]:
    return [["rtk_float"] if s == RTK_FLOAT else ([] if s == RTK_FIXED else ["rtk_none"])
            for s in np.asarray(rtk_status).tolist()]


# ============================================================================ import: pose log
@dataclass
class ImportReport:
    """Counts and sentences for the Processing log.

    ``errors``: input that was left out because it is bad (rows, images), with count and first
    examples; ``notes``: everything else a user should know (unmatched frames, flags, filters).
    """

    source: str
    counts: dict = field(default_factory=dict)
    errors: list = field(default_factory=list)
    notes: list = field(default_factory=list)
    unplaced: list = field(default_factory=list)


@dataclass
class FlightImport:
    frames: Frames
    footprints: Footprints
    track: list
    report: ImportReport


def _names(paths, limit=3) -> str:
    return ", ".join(Path(p).name for p in list(paths)[:limit])


def import_pose_log(pose_log, images_folder, camera: CameraModel, fps: float = 5.0,
                    radalt_snr_min: float = 13.0, fixed_only: bool = False, crs: ProjectedCRS | None = None,
                    with_track: bool = True, progress=None, is_canceled=None, ground=None) -> FlightImport:
    """Pose log + image folder + camera → frames with footprints, flight line and a report.

    ``crs`` None: the UTM zone of the site. Progress: parsing 0–45 %, sync/ground 45–50 %,
    footprints 50–100 %.
    """
    def sub(a, b):
        return None if progress is None else (lambda f: progress(a + (b - a) * f))

    log = read_pose_log(pose_log, progress=sub(0.0, 0.45), is_canceled=is_canceled)
    images = list_images(images_folder)
    report = ImportReport(str(pose_log))
    summary = log.problems.summary("pose-log rows")
    if summary:
        report.errors.append(summary)
    if images.problems.count:
        report.errors.append(images.problems.summary("images.csv rows"))
    if images.ignored:
        report.notes.append(f"{len(images.ignored)} file(s) in the image folder are not named "
                            f"<sec>.<nsec>.png|jpg and were ignored: {', '.join(images.ignored[:3])}")
    strobe_rows = np.flatnonzero(log.strobe)
    report.counts.update(pose_rows=len(log), bad_rows=log.problems.count, strobes=len(strobe_rows),
                         images=len(images))
    if len(strobe_rows) == 0:
        raise InputError("has no strobe rows (strobe = 1 marks each camera exposure); without them no "
                         "image can be given a pose — check the strobe wiring or that this is the log of "
                         "the imaging flight", source=log.source)
    sync = sync_strobes(log.time_s[strobe_rows], images.time_s, fps)
    matched = np.flatnonzero(sync.image_of >= 0)
    _report_sync(report, log, images, strobe_rows, sync, fps)
    if len(matched) == 0:
        st = log.time_s[strobe_rows]
        raise InputError(
            f"no image matches a strobe within 1/fps = {1 / fps:.3g} s: the strobes span "
            f"{st.min():.3f}–{st.max():.3f} s, the images {images.time_s.min():.3f}–{images.time_s.max():.3f} s. "
            "Are pose log and images from the same flight and clock, and is FPS right?", source=str(images_folder))
    _check_cancel(is_canceled)
    rows = strobe_rows[matched]
    good = (np.isfinite(log.radalt) & (log.radalt > 0)
            & (np.nan_to_num(log.radalt_snr, nan=-np.inf) >= radalt_snr_min))
    ground_h, interpolated = ground_heights(log.time_s, log.height, log.quat, log.radalt, good, rows,
                                            camera.t_imu_rad)
    flags = rtk_flags(log.rtk_status[rows])
    for i in np.flatnonzero(interpolated):
        flags[i].append("radalt_interpolated")
    frames = Frames(frame_id=matched.astype(np.int64), image=[images.path[sync.image_of[s]] for s in matched],
                    time_s=log.time_s[rows], lat=log.lat[rows], lon=log.lon[rows], height=log.height[rows],
                    quat=log.quat[rows], ground_h=ground_h, rtk_status=log.rtk_status[rows],
                    sync_offset_s=sync.offset_s[matched], cameras=[camera] * len(rows), flags=flags)
    report.counts.update(radalt_interpolated=int(interpolated.sum()),
                         no_ground_height=int(np.count_nonzero(~np.isfinite(ground_h))))
    if interpolated.any():
        report.notes.append(f"{int(interpolated.sum())} frame(s) had an altimeter reading below SNR "
                            f"{radalt_snr_min:g} dB (or none); their ground height was interpolated from "
                            f"good readings within {RADALT_WINDOW_S:g} s (flag radalt_interpolated)")
    frames = _apply_rtk_filter(frames, fixed_only, report)
    if len(frames) == 0:
        raise InputError("no frame is left after the RTK filter (no frame has an RTK fixed solution); "
                         "choose 'all' to import float frames flagged", source=log.source)
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    fp = compute_footprints(frames, crs, progress=sub(0.5, 0.97), is_canceled=is_canceled, ground=ground)
    _report_ground(report, frames)
    track = []
    if with_track:
        track = flight_track(log.time_s, log.lat, log.lon, log.height, crs, frames.time_s)
    if progress is not None:
        progress(1.0)
    return FlightImport(frames, fp, track, report)


def _report_sync(report, log, images, strobe_rows, sync, fps):
    st = log.time_s[strobe_rows]
    n_match = int(np.count_nonzero(sync.image_of >= 0))
    report.counts.update(matched=n_match, unmatched_strobes=len(sync.unmatched_strobes),
                         unmatched_images=len(sync.unmatched_images),
                         duplicate_strobes=len(sync.duplicate_strobes), duplicate_images=len(sync.duplicate_images))
    if len(sync.duplicate_strobes):
        rows = log.row[strobe_rows[sync.duplicate_strobes]]
        report.notes.append(f"{len(sync.duplicate_strobes)} strobe row(s) share a timestamp with another "
                            f"strobe and were left out (rows {', '.join(map(str, rows[:5]))})")
    if len(sync.duplicate_images):
        report.notes.append(f"{len(sync.duplicate_images)} image(s) share a timestamp with another image and "
                            f"were left out: {_names(images.path[i] for i in sync.duplicate_images)}")
    if len(sync.unmatched_strobes):
        rows = log.row[strobe_rows[sync.unmatched_strobes]]
        times = st[sync.unmatched_strobes]
        report.notes.append(f"{len(sync.unmatched_strobes)} strobe(s) found no image within 1/fps = "
                            f"{1 / fps:.3g} s and were left out (rows {', '.join(map(str, rows[:5]))}; "
                            f"t = {', '.join(f'{t:.3f}' for t in times[:3])} s)")
    if len(sync.unmatched_images):
        report.notes.append(f"{len(sync.unmatched_images)} image(s) found no strobe within 1/fps and were "
                            f"left out: {_names(images.path[i] for i in sync.unmatched_images)}")
    offsets = sync.offset_s[sync.image_of >= 0]
    if len(offsets):
        report.counts.update(sync_offset_median_s=float(np.median(offsets)),
                             sync_offset_max_s=float(np.max(np.abs(offsets))))


def _apply_rtk_filter(frames: Frames, fixed_only: bool, report: ImportReport) -> Frames:
    not_fixed = frames.rtk_status != RTK_FIXED
    report.counts.update(rtk_fixed=int(np.count_nonzero(~not_fixed)), rtk_not_fixed=int(not_fixed.sum()))
    if fixed_only and not_fixed.any():
        report.notes.append(f"{int(not_fixed.sum())} frame(s) without an RTK fixed solution were left out "
                            "(RTK filter: fixed only)")
        report.counts["dropped_not_fixed"] = int(not_fixed.sum())
        return frames.subset(~not_fixed)
    if not_fixed.any():
        report.notes.append(f"{int(not_fixed.sum())} frame(s) have no RTK fixed solution; kept and "
                            "flagged rtk_float / rtk_none")
    return frames


def _report_ground(report: ImportReport, frames: Frames) -> None:
    for flag, text in (("no_ground_height", "have no ground height (no good altimeter reading nearby); "
                        "they are kept without a footprint"),
                       ("footprint_unbounded", "look above the horizon; they are kept without a footprint"),
                       ("steep_terrain", f"lie on terrain steeper than the level plane's {FLAT_ENVELOPE_DEG:g}° "
                                         "envelope; give the DEM to Write labels and Detect too")):
        n = sum(flag in f for f in frames.flags)
        report.counts[flag] = n
        if n:
            first = [int(frames.frame_id[i]) for i, f in enumerate(frames.flags) if flag in f][:5]
            report.notes.append(f"{n} frame(s) {text} (flag {flag}; frame ids {', '.join(map(str, first))})")


# ============================================================================ flight line
@dataclass
class TrackSegment:
    xyz: np.ndarray
    attributes: dict


def flight_track(time_s, lat, lon, height, crs: ProjectedCRS, frame_times=(), gap_s: float = TRACK_GAP_S,
                 min_interval_s: float = 0.2) -> list[TrackSegment]:
    """The flight line as segments split at gaps > ``gap_s``, thinned to one vertex per ``min_interval_s``."""
    time_s = np.asarray(time_s, dtype=float)
    if len(time_s) < 2:
        return []
    keep = np.zeros(len(time_s), dtype=bool)
    keep[0] = keep[-1] = True
    bucket = np.floor((time_s - time_s[0]) / min_interval_s)
    keep[1:] |= bucket[1:] != bucket[:-1]
    gaps = np.flatnonzero(np.diff(time_s) > gap_s)
    keep[gaps] = keep[gaps + 1] = True
    idx = np.flatnonzero(keep)
    t, la, lo, h = time_s[idx], np.asarray(lat)[idx], np.asarray(lon)[idx], np.asarray(height)[idx]
    x, y = crs.from_geodetic(la, lo)
    local = LocalFrame.around(la, lo, h)
    enu = local.from_geodetic(la, lo, h)
    breaks = np.flatnonzero(np.diff(t) > gap_s) + 1
    frame_times = np.sort(np.asarray(frame_times, dtype=float))
    segments = []
    for number, part in enumerate(np.split(np.arange(len(t)), breaks), start=1):
        if len(part) < 2:
            continue
        start, end = float(t[part[0]]), float(t[part[-1]])
        n_frames = int(np.searchsorted(frame_times, end, "right") - np.searchsorted(frame_times, start, "left"))
        length = float(np.sum(np.linalg.norm(np.diff(enu[part, :2], axis=0), axis=1)))
        label = f"Flight line {number}: {n_frames} frames, {(end - start) / 60:.1f} min, {length:.0f} m"
        segments.append(TrackSegment(np.stack([x[part], y[part], h[part]], axis=1),
                                     {"segment": number, "label": label, "start_s": start, "end_s": end,
                                      "duration_s": end - start, "n_frames": n_frames, "length_m": length}))
    return segments


# ============================================================================ flight_data.db
FLIGHT_DB_TABLE = "cam0_images_flight_data"
_DB_REQUIRED = ("x", "y", "z", "q", "u", "a", "t", "rtk_status", "radalt", "save_loc")
_DB_TIME_COLUMNS = ("time_s", "time", "timestamp", "stamp", "t_img")


def read_flight_db_frames(path, camera: CameraModel, utm_crs=None, images_folder=None,
                          radalt_snr_min: float = 13.0, fixed_only: bool = False,
                          crs: ProjectedCRS | None = None, with_track: bool = True,
                          progress=None, is_canceled=None, ground=None) -> FlightImport:
    """Frames from the reference payload's ``flight_data.db`` (already one row per saved image).

    ``utm_crs`` (EPSG code or WKT) is the projected CRS of the table's ``x, y``; it is required
    because the table stores no zone. ``save_loc`` is used as written if that file exists, else its
    file name is looked up in ``images_folder``. Time comes from a time column if the table has one,
    else from a ``<sec>.<nsec>`` image name.
    """
    path = Path(path)
    source = str(path)
    if not path.is_file():
        raise InputError("flight database not found", source=source)
    try:
        con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
        try:
            columns = [r[1] for r in con.execute(f"PRAGMA table_info({FLIGHT_DB_TABLE})")]
            if not columns:
                tables = [r[0] for r in con.execute("SELECT name FROM sqlite_master WHERE type='table'")]
                raise InputError(f"has no table '{FLIGHT_DB_TABLE}' (tables: {', '.join(tables) or 'none'}); "
                                 "expected the reference payload's flight_data.db", source=source)
            lower = {c.lower(): c for c in columns}
            missing = [c for c in _DB_REQUIRED if c not in lower]
            if missing:
                raise InputError(f"table '{FLIGHT_DB_TABLE}' has no column(s) {', '.join(missing)}; expected "
                                 f"{', '.join(_DB_REQUIRED)}", source=source)
            time_col = next((lower[c] for c in _DB_TIME_COLUMNS if c in lower), None)
            snr_col = lower.get("radalt_snr")
            wanted = [lower[c] for c in _DB_REQUIRED] + [time_col or "NULL", snr_col or "NULL"]
            rows = con.execute(f"SELECT rowid, {', '.join(wanted)} FROM {FLIGHT_DB_TABLE} ORDER BY rowid").fetchall()
        finally:
            con.close()
    except sqlite3.DatabaseError as exc:
        raise InputError(f"is not a readable SQLite database ({exc})", source=source) from exc
    if not rows:
        raise InputError(f"table '{FLIGHT_DB_TABLE}' has no rows", source=source)
    if utm_crs is None:
        raise InputError("stores UTM x, y without a zone: choose the UTM CRS the payload logged in "
                         "(parameter UTM_CRS)", source=source, field="UTM_CRS")
    grid = ProjectedCRS(utm_crs)
    problems = RowProblems()
    names = ("x", "y", "z", "q", "u", "a", "t", "rtk_status", "radalt")
    good_rows, values, save_locs, times, snrs = [], [], [], [], []
    for r in rows:
        rowid, vals, save_loc, t, snr = r[0], r[1:10], r[10], r[11], r[12]
        try:
            nums = []
            for name, v in zip(names, vals):
                try:
                    nums.append(float(v) if not (v is None and name == "radalt") else math.nan)
                except (TypeError, ValueError):
                    raise InputError(f"{v!r} is not a number", source=source, row=rowid, field=name) from None
            if not all(math.isfinite(v) for v in nums[:7]):
                bad = names[[math.isfinite(v) for v in nums[:7]].index(False)]
                raise InputError("is not a finite number", source=source, row=rowid, field=bad)
            qn = math.sqrt(sum(v * v for v in nums[3:7]))
            if abs(qn - 1.0) > 0.05:
                raise InputError(f"quaternion (q, u, a, t) has norm {qn:.3f}; expected a unit quaternion",
                                 source=source, row=rowid, field="q")
        except InputError as exc:
            problems.add(exc)
            continue
        good_rows.append(rowid)
        values.append(nums)
        save_locs.append("" if save_loc is None else str(save_loc))
        times.append(_db_time(t, save_loc))
        snrs.append(math.inf if snr_col is None else (math.nan if snr is None else float(snr)))
    if not values:
        raise InputError(f"has no usable rows ({problems.count} bad); the first: {problems.examples[0]}",
                         source=source)
    v = np.asarray(values)
    lat, lon = grid.to_geodetic(v[:, 0], v[:, 1])
    if not (np.all(np.isfinite(lat)) and np.all(np.abs(lat) <= 84.5) and np.all(np.isfinite(lon))):
        raise InputError(f"x, y do not convert to valid positions with {grid.crs}: is UTM_CRS the zone the "
                         "payload logged in?", source=source, field="UTM_CRS")
    report = ImportReport(source)
    summary = problems.summary("database rows")
    if summary:
        report.errors.append(summary)
    quat_wxyz = v[:, [6, 3, 4, 5]]
    time_s = np.asarray(times)
    image_paths, missing_images = [], []
    folder = Path(images_folder) if images_folder else None
    for s in save_locs:
        p = Path(s)
        if s and p.is_file():
            image_paths.append(str(p.resolve()))
        elif s and folder is not None and (folder / p.name).is_file():
            image_paths.append(str((folder / p.name).resolve()))
        else:
            image_paths.append(str(folder / p.name) if folder is not None and s else s)
            missing_images.append(s)
    rtk = v[:, 7].astype(np.int64)
    radalt = v[:, 8]
    snr = np.asarray(snrs)
    good = np.isfinite(radalt) & (radalt > 0) & (np.nan_to_num(snr, nan=-np.inf) >= radalt_snr_min)
    # Interpolation across frames needs their times; without them each frame stands alone.
    timed = bool(np.all(np.isfinite(time_s)))
    order = np.argsort(time_s, kind="stable") if timed else np.arange(len(time_s))
    inv = np.empty_like(order)
    inv[order] = np.arange(len(order))
    gh_sorted, interp_sorted = ground_heights(
        time_s[order] if timed else order.astype(float), v[order, 2], quat_wxyz[order], radalt[order],
        good[order], np.arange(len(order)), camera.t_imu_rad, window_s=RADALT_WINDOW_S if timed else -1.0)
    ground_h, interpolated = gh_sorted[inv], interp_sorted[inv]
    flags = rtk_flags(rtk)
    for i in np.flatnonzero(interpolated):
        flags[i].append("radalt_interpolated")
    for i, s in enumerate(save_locs):
        if s in missing_images:
            flags[i].append("image_missing")
    frames = Frames(frame_id=np.asarray(good_rows, dtype=np.int64), image=image_paths, time_s=time_s,
                    lat=lat, lon=lon, height=v[:, 2], quat=quat_wxyz, ground_h=ground_h, rtk_status=rtk,
                    sync_offset_s=np.full(len(v), np.nan), cameras=[camera] * len(v), flags=flags)
    report.counts.update(rows=len(rows), bad_rows=problems.count, frames=len(frames),
                         images_missing=len(missing_images), radalt_interpolated=int(interpolated.sum()))
    if missing_images:
        report.notes.append(f"{len(missing_images)} image(s) named in save_loc were not found (flag "
                            f"image_missing): {_names(missing_images)}")
    frames = _apply_rtk_filter(frames, fixed_only, report)
    if len(frames) == 0:
        raise InputError("no frame is left after the RTK filter", source=source)
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    fp = compute_footprints(frames, crs, progress=progress, is_canceled=is_canceled, ground=ground)
    _report_ground(report, frames)
    track = []
    if with_track and np.all(np.isfinite(frames.time_s)):
        order = np.argsort(frames.time_s, kind="stable")
        track = flight_track(frames.time_s[order], frames.lat[order], frames.lon[order], frames.height[order],
                             crs, frames.time_s)
    return FlightImport(frames, fp, track, report)


def _db_time(value, save_loc) -> float:
    if value is not None:
        try:
            return float(value)
        except (TypeError, ValueError):
            pass
    match = _STAMP_NAME.match(Path(str(save_loc or "")).name)
    if match:
        return int(match.group(1)) + int(match.group(2)) * 1e-9
    return math.nan


def import_flight_log(pose_log, images_folder, camera: CameraModel, **kwargs) -> FlightImport:
    """Dispatch on the file: a SQLite ``flight_data.db`` or a pose-log CSV."""
    path = Path(pose_log)
    utm_crs = kwargs.pop("utm_crs", None)
    if path.is_file() and path.read_bytes()[:16] == b"SQLite format 3\x00":
        kwargs.pop("fps", None)
        return read_flight_db_frames(path, camera, utm_crs=utm_crs, images_folder=images_folder, **kwargs)
    if images_folder is None or str(images_folder) == "":
        raise InputError("a pose log needs the folder of its images (IMAGES)", source=str(path), field="IMAGES")
    return import_pose_log(path, images_folder, camera, **kwargs)


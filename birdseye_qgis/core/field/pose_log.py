"""The BirdsEye pose log: vectorised CSV parsing that still reports every bad row by line and field."""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from itertools import islice
from pathlib import Path

import numpy as np

from ..errors import InputError, check_cancel, detached

POSE_LOG_COLUMNS = ("time_s", "lat_deg", "lon_deg", "height_m", "qw", "qx", "qy", "qz", "rtk_status",
                    "radalt_m", "radalt_snr", "strobe")
#: Columns that may be missing from the header (then every altimeter reading counts as good).
_OPTIONAL_COLUMNS = ("radalt_snr",)
#: Columns that may be empty on a row (an INS message without an altimeter reading).
_MAY_BE_EMPTY = ("radalt_m", "radalt_snr")
RTK_FIXED, RTK_FLOAT, RTK_NONE = 3, 2, 1
#: Examples of bad rows kept for the log; the count of bad rows is always complete.
MAX_EXAMPLES = 20
class RowProblems:
    """Bad rows of one input: a complete count and the first :data:`MAX_EXAMPLES` errors."""

    def __init__(self):
        self.count = 0
        self.examples: list[InputError] = []

    def add(self, error: InputError) -> None:
        self.count += 1
        if len(self.examples) < MAX_EXAMPLES:
            self.examples.append(detached(error))

    def summary(self, what: str) -> str | None:
        if not self.count:
            return None
        first = "; ".join(str(e) for e in self.examples[:3])
        return f"{self.count} bad {what} left out; first: {first}"

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
            check_cancel(is_canceled)
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

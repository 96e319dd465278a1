"""Frame images: the image list of a flight (images.csv or time-stamped names) and strobe ↔ image sync."""
from __future__ import annotations

import csv
import math
import os
import re
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ..errors import InputError
from .geotags import split_lines
from .pose_log import RowProblems

STAMP_NAME = re.compile(r"^(\d+)\.(\d+)\.(png|jpe?g|tiff?)$", re.IGNORECASE)


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
            match = STAMP_NAME.match(name)
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

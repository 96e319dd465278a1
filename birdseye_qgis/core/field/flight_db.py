"""The reference payload's SQLite flight_data.db: saved frames with UTM poses."""
from __future__ import annotations

import math
import sqlite3
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..geometry.camera import CameraModel
from ..geometry.geodesy import ProjectedCRS
from ..geometry.heights import ELLIPSOIDAL_REFERENCE
from .flight_track import flight_track
from .frames import RADALT_WINDOW_S, Frames, compute_footprints, dem_ground_for, ground_heights, rtk_flags
from .images import STAMP_NAME
from .import_report import FlightImport, ImportReport, apply_rtk_filter, name_list, report_ground
from .pose_log import RowProblems

FLIGHT_DB_TABLE = "cam0_images_flight_data"
_DB_REQUIRED = ("x", "y", "z", "q", "u", "a", "t", "rtk_status", "radalt", "save_loc")
_DB_TIME_COLUMNS = ("time_s", "time", "timestamp", "stamp", "t_img")


def read_flight_db_frames(path, camera: CameraModel, utm_crs=None, images_folder=None,
                          radalt_snr_min: float = 13.0, fixed_only: bool = False,
                          crs: ProjectedCRS | None = None, with_track: bool = True,
                          progress=None, is_canceled=None, dem=None) -> FlightImport:
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
                    sync_offset_s=np.full(len(v), np.nan), cameras=[camera] * len(v), flags=flags,
                    reference=ELLIPSOIDAL_REFERENCE)  # the payload's INS heights (assumed: the db does not say)
    report.counts.update(rows=len(rows), bad_rows=problems.count, frames=len(frames),
                         images_missing=len(missing_images), radalt_interpolated=int(interpolated.sum()))
    if missing_images:
        report.notes.append(f"{len(missing_images)} image(s) named in save_loc were not found (flag "
                            f"image_missing): {name_list(missing_images)}")
    frames = apply_rtk_filter(frames, fixed_only, report)
    if len(frames) == 0:
        raise InputError("no frame is left after the RTK filter", source=source)
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    ground = dem_ground_for(frames, dem, report)
    fp = compute_footprints(frames, crs, progress=progress, is_canceled=is_canceled, ground=ground)
    report_ground(report, frames)
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
    match = STAMP_NAME.match(Path(str(save_loc or "")).name)
    if match:
        return int(match.group(1)) + int(match.group(2)) * 1e-9
    return math.nan

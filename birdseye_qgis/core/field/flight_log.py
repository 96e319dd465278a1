"""Flight logs → frames: pose-log parsing, strobe↔image sync, ground heights, footprints, frame records.

Inputs (docs/design.md §4.2–§4.3):

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

from pathlib import Path

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.camera import CameraModel
from ..geometry.geodesy import ProjectedCRS
from ..geometry.heights import ELLIPSOIDAL_REFERENCE
from .flight_db import read_flight_db_frames
from .flight_track import flight_track
from .frames import RADALT_WINDOW_S, Frames, compute_footprints, dem_ground_for, ground_heights, rtk_flags
from .images import list_images, sync_strobes
from .import_report import FlightImport, ImportReport, apply_rtk_filter, name_list, report_ground
from .pose_log import read_pose_log


def import_pose_log(pose_log, images_folder, camera: CameraModel, fps: float = 5.0,
                    radalt_snr_min: float = 13.0, fixed_only: bool = False, crs: ProjectedCRS | None = None,
                    with_track: bool = True, progress=None, is_canceled=None, dem=None) -> FlightImport:
    """Pose log + image folder + camera → frames with footprints, flight line and a report.

    ``crs`` None: the UTM zone of the site; ``dem``: a DEM the footprints drape on (converted into the log's
    ellipsoidal heights, checked against the altimeter's ground). Progress: parsing 0–45 %, sync/ground
    45–50 %, footprints 50–100 %.
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
    check_cancel(is_canceled)
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
                    sync_offset_s=sync.offset_s[matched], cameras=[camera] * len(rows), flags=flags,
                    reference=ELLIPSOIDAL_REFERENCE)
    report.counts.update(radalt_interpolated=int(interpolated.sum()),
                         no_ground_height=int(np.count_nonzero(~np.isfinite(ground_h))))
    if interpolated.any():
        report.notes.append(f"{int(interpolated.sum())} frame(s) had an altimeter reading below SNR "
                            f"{radalt_snr_min:g} dB (or none); their ground height was interpolated from "
                            f"good readings within {RADALT_WINDOW_S:g} s (flag radalt_interpolated)")
    frames = apply_rtk_filter(frames, fixed_only, report)
    if len(frames) == 0:
        raise InputError("no frame is left after the RTK filter (no frame has an RTK fixed solution); "
                         "choose 'all' to import float frames flagged", source=log.source)
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    ground = dem_ground_for(frames, dem, report)
    fp = compute_footprints(frames, crs, progress=sub(0.5, 0.97), is_canceled=is_canceled, ground=ground)
    report_ground(report, frames)
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
                            f"were left out: {name_list(images.path[i] for i in sync.duplicate_images)}")
    if len(sync.unmatched_strobes):
        rows = log.row[strobe_rows[sync.unmatched_strobes]]
        times = st[sync.unmatched_strobes]
        report.notes.append(f"{len(sync.unmatched_strobes)} strobe(s) found no image within 1/fps = "
                            f"{1 / fps:.3g} s and were left out (rows {', '.join(map(str, rows[:5]))}; "
                            f"t = {', '.join(f'{t:.3f}' for t in times[:3])} s)")
    if len(sync.unmatched_images):
        report.notes.append(f"{len(sync.unmatched_images)} image(s) found no strobe within 1/fps and were "
                            f"left out: {name_list(images.path[i] for i in sync.unmatched_images)}")
    offsets = sync.offset_s[sync.image_of >= 0]
    if len(offsets):
        report.counts.update(sync_offset_median_s=float(np.median(offsets)),
                             sync_offset_max_s=float(np.max(np.abs(offsets))))


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

"""Camera solutions of photogrammetry packages → frames (docs/design.md#camera-solutions).

A camera solution is what a bundle adjustment knows about each aligned image: the calibrated camera and
its exact pose in a georeferenced frame. Each format's reader (:mod:`.metashape`, :mod:`.opensfm`,
:mod:`.colmap`, :mod:`.pix4d`) converts its package's conventions — which way a transform points, where the principal
point is measured from, the order of the tangential terms — into one :class:`CameraSolution`: OpenCV
cameras (pixel-centre origin, ``k1 k2 p1 p2 k3`` plus ``k4``/skew/fisheye where the package has them)
and camera → ECEF poses. :func:`import_camera_solution` turns that into a frame layer with the same
contract as the other importers.

Heights (docs/design.md#camera-solutions). There is no altimeter. Where the solution's heights are
ellipsoidal for certain — Metashape's geocentric export, a COLMAP model in ECEF or a stated ENU frame —
labels use the geotags' own surveyed heights (flag ``geotag_heights``;
:func:`..labels.training_set.project_labels`). Where they are whatever the images' GPS tags said (an
OpenSfM/ODM reference, a COLMAP model aligned to the images' GPS: usually above mean sea level, and
biased as the drone's GNSS is) or in a reference the files do not state (a Pix4D project's), the
geotags are placed on the ground the solution itself saw: the median height of its tie points in each
frame's view, a datum-free reference. Frames without tie points in view take the DEM, else
``ground_height`` (a level plane).
"""
from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from ...errors import InputError, check_cancel
from ...geometry.camera import CameraModel
from ...geometry.dem import DemRaster
from ...geometry.geodesy import LocalFrame, ProjectedCRS, ecef_to_geodetic, rotation_ecef_enu
from ...geometry.heights import (
    CONTROL_POINTS,
    EGM96_REFERENCE,
    ELLIPSOIDAL_REFERENCE,
    GIVEN,
    NO_GROUND,
    TIE_POINTS,
    VerticalReference,
)
from ...geometry.poses import FramePoses, indices_by_camera
from ...geometry.rotations import R_ENU_NED, rotmat_to_quat
from ..dji import T_CAM_GIMBAL
from ..frame_records import GEOTAG_HEIGHTS_FLAG
from ..frames import Frames, compute_footprints, dem_ground_for
from ..geotags import Geotags
from ..import_report import FlightImport, ImportReport
from ..pose_log import RTK_NONE

#: The flag every frame of a camera solution carries.
SOLUTION_FLAG = "camera_solution"
#: Image files a solution's camera names are matched with (case-insensitive).
IMAGE_SUFFIXES = (".jpg", ".jpeg", ".tif", ".tiff", ".png", ".dng")
#: Tie points a solution needs, and a frame needs in view, for its ground height (else: DEM or level plane).
MIN_GROUND_POINTS = MIN_GROUND_POINTS_IN_VIEW = 5


@dataclass
class SolvedCamera:
    """One aligned image: its name in the solution, OpenCV camera, and camera → ECEF pose."""

    name: str
    camera: CameraModel
    R_ecef_cam: np.ndarray
    centre_ecef: np.ndarray


@dataclass
class ControlMarks:
    """Surveyed control points of a solution and where a person marked them in its images.

    ``points``: the surveyed positions (WGS 84, ellipsoidal heights; ids 1..). Mark ``k`` is point
    ``point_idx[k]`` seen in the solution's camera ``camera[k]`` at ``uv[k]`` (px, OpenCV's pixel-centre
    origin).
    """

    points: Geotags
    point_idx: np.ndarray
    camera: list
    uv: np.ndarray


@dataclass
class CameraSolution:
    """Every image of a solution file; ``unaligned`` holds (name, reason) of images without a pose.

    ``reference``: what the solution's heights are measured from — ellipsoidal (geocentric, a stated ENU
    frame), the images' GPS reference (EGM96, as GNSS receivers report heights above sea level) for solutions
    aligned to the images' GPS tags, or what the solution's CRS says. ``marks``: control points with image
    marks, where the solution has them; ``photos``: camera name → image file the solution itself names (where
    it exists). ``notes``: what the reader found and chose (the chunk read, a copy preferred, an alignment's
    figures), the import report's findings.
    """

    format: str
    source: str
    cameras: list
    unaligned: list = field(default_factory=list)
    points_ecef: np.ndarray | None = None
    notes: list = field(default_factory=list)
    reference: VerticalReference = EGM96_REFERENCE
    marks: ControlMarks | None = None
    photos: dict = field(default_factory=dict)

    @property
    def ellipsoidal(self) -> bool:
        """The solution's heights are ellipsoidal for certain (geocentric, a stated ENU frame)."""
        return self.reference == ELLIPSOIDAL_REFERENCE


def read_camera_solution(path, images_folder=None, colmap_reference: str = "gps",
                         solution_crs: ProjectedCRS | None = None) -> CameraSolution:
    """Read a Metashape project (.psx, .psz) or camera XML, an OpenSfM/OpenDroneMap reconstruction, a COLMAP
    model or Pix4D's calibrated camera parameters.

    ``path`` is the file, or a folder holding one (an ODM project's ``opensfm/``, a COLMAP ``sparse/0``).
    ``colmap_reference`` tells where a COLMAP model's frame is (:func:`.colmap.read_colmap`);
    ``solution_crs`` is the projected CRS a Pix4D project's coordinates are in (:func:`.pix4d.read_pix4d`).
    """
    from . import colmap, metashape, opensfm, pix4d

    path = Path(path)
    if not path.exists():
        raise InputError("camera solution not found", source=str(path))
    if path.is_dir():
        found = (opensfm.find_reconstruction(path) or colmap.find_model(path) or metashape.find_xml(path)
                 or pix4d.find_parameters(path))
        if found is None:
            raise InputError("holds no camera solution: expected a Metashape project (.psx, .psz) or cameras XML, "
                             "an OpenSfM/ODM reconstruction.json, a COLMAP model (cameras.bin/images.bin or "
                             ".txt), or Pix4D's <project>_calibrated_camera_parameters.txt", source=str(path))
        path = found
    if path.is_dir() or path.name in colmap.MODEL_FILES:
        return colmap.read_colmap(path if path.is_dir() else path.parent, images_folder, colmap_reference)
    if path.suffix.lower() in metashape.SUFFIXES:
        return metashape.read_metashape(path)
    if path.suffix.lower() == ".json":
        return opensfm.read_reconstruction(path)
    if path.name.endswith(pix4d.PARAMETERS_SUFFIX):
        return pix4d.read_pix4d(path, solution_crs)
    raise InputError("is not a camera solution this plugin reads (Metashape .psx, .psz or cameras .xml, "
                     "OpenSfM/ODM .json, COLMAP cameras/images .bin or .txt, Pix4D "
                     "<project>_calibrated_camera_parameters.txt)", source=str(path))


def match_images(names, folder) -> dict:
    """Solution image name → file in ``folder``: same file name, else same stem (case-insensitive)."""
    if not folder:
        return {}
    folder = Path(folder)
    if not folder.is_dir():
        raise InputError("image folder not found", source=str(folder))
    files = [p for p in folder.rglob("*") if p.is_file() and p.suffix.lower() in IMAGE_SUFFIXES]
    by_name = {p.name.lower(): p for p in files}
    by_stem = {p.stem.lower(): p for p in files}
    matched = {}
    for name in names:
        key = Path(name).name.lower()
        hit = by_name.get(key) or by_stem.get(Path(key).stem) or by_stem.get(key)
        if hit is not None:
            matched[name] = hit
    return matched


def solution_frames(solution: CameraSolution, images: dict, ground_height: float | None = None,
                    ground_height_source: str = GIVEN) -> Frames:
    """Frames (body = the camera's gimbal frame, as for DJI images) of every aligned camera; frames without
    tie points in view stand on ``ground_height`` (in the solution's reference) where it is given, a ground of
    source ``ground_height_source`` (the user's, or the control points' median)."""
    cams = solution.cameras
    n = len(cams)
    centres = np.array([c.centre_ecef for c in cams], dtype=float).reshape(n, 3)
    lat, lon, h = ecef_to_geodetic(centres)
    lat, lon, h = (np.atleast_1d(np.asarray(a, dtype=float)) for a in (lat, lon, h))
    r_ecef_ned = rotation_ecef_enu(lat, lon) @ R_ENU_NED
    r_ecef_cam = np.array([c.R_ecef_cam for c in cams], dtype=float).reshape(n, 3, 3)
    # body (gimbal: forward-right-down) → NED; the camera sits in the body by T_CAM_GIMBAL.
    r_ned_body = np.einsum("nji,njk->nik", r_ecef_ned, r_ecef_cam) @ T_CAM_GIMBAL[:3, :3]
    mounted: dict[int, CameraModel] = {}
    for c in cams:
        if id(c.camera) not in mounted:
            mounted[id(c.camera)] = CameraModel.from_dict({**c.camera.to_dict(), "T_cam_imu": T_CAM_GIMBAL.tolist()})
    cameras = [mounted[id(c.camera)] for c in cams]
    ground = _tie_point_ground(solution, lat, lon, h, r_ned_body, cameras)
    flags = [[SOLUTION_FLAG] + ([GEOTAG_HEIGHTS_FLAG] if solution.ellipsoidal else []) for _ in range(n)]
    source = np.where(np.isfinite(ground), TIE_POINTS, NO_GROUND).astype(object)
    if ground_height is not None:
        source[~np.isfinite(ground)] = ground_height_source
        ground = np.where(np.isfinite(ground), ground, float(ground_height))
    return Frames(
        frame_id=np.arange(n, dtype=np.int64),
        image=[str(images[c.name].resolve()) if c.name in images else c.name for c in cams],
        time_s=np.full(n, np.nan), lat=lat, lon=lon, height=h, quat=rotmat_to_quat(r_ned_body),
        ground_h=ground, rtk_status=np.full(n, RTK_NONE), sync_offset_s=np.full(n, np.nan),
        cameras=cameras, flags=flags, reference=solution.reference, ground_source=list(source))


def _tie_point_ground(solution, lat, lon, h, r_ned_body, cameras) -> np.ndarray:
    """Per frame, the median height of the solution's tie points inside its image (the solution's reference)."""
    from scipy.spatial import cKDTree

    from ...geometry.poses import FrameGeometry

    ground = np.full(len(lat), np.nan)
    pts = solution.points_ecef
    if pts is None or len(pts) < MIN_GROUND_POINTS:
        return ground
    local = LocalFrame.around(lat, lon, h)
    p_lat, p_lon, p_h = ecef_to_geodetic(pts)
    local_pts = local.from_geodetic(p_lat, p_lon, p_h)
    tree = cKDTree(local_pts[:, :2])
    depth = np.maximum(h - np.median(p_h), 1.0)
    for idx in indices_by_camera(cameras):
        cam = cameras[idx[0]]
        geometry = FrameGeometry(FramePoses(idx, lat[idx], lon[idx], h[idx], rotmat_to_quat(r_ned_body[idx]),
                                            np.full(len(idx), np.nan), cam), local)
        # A disc around each camera that holds its whole view of the ground (half diagonal, 50 % margin).
        radius = depth[idx] * 0.75 * np.hypot(cam.width, cam.height) / min(cam.fx, cam.fy) + 1.0
        near = tree.query_ball_point(geometry.C[:, :2], radius)
        counts = np.fromiter((len(n) for n in near), dtype=np.int64, count=len(near))
        frame_of = np.repeat(np.arange(len(idx)), counts)
        point_of = np.fromiter((j for n in near for j in n), dtype=np.int64, count=int(counts.sum()))
        p_cam = geometry.to_camera(frame_of, local_pts[point_of])
        seen = (p_cam[:, 2] > 0) & cam.in_frame(cam.project(p_cam))
        frame_of, heights = frame_of[seen], p_h[point_of[seen]]
        order = np.lexsort((heights, frame_of))
        frame_of, heights = frame_of[order], heights[order]
        bounds = np.searchsorted(frame_of, np.arange(len(idx) + 1))
        for k, (a, b) in enumerate(zip(bounds[:-1], bounds[1:])):
            if b - a >= MIN_GROUND_POINTS_IN_VIEW:
                ground[idx[k]] = float(np.median(heights[a:b]))
    return ground


def import_camera_solution(path, images_folder=None, crs: ProjectedCRS | None = None, dem: DemRaster | None = None,
                           ground_height: float | None = None, colmap_reference: str = "gps",
                           solution_crs: ProjectedCRS | None = None, progress=None,
                           is_canceled=None) -> FlightImport:
    """Frames with footprints from a camera solution; what cannot be placed is reported, not guessed."""
    solution = read_camera_solution(path, images_folder, colmap_reference, solution_crs)
    check_cancel(is_canceled)
    report = ImportReport(solution.source)
    report.findings.extend(solution.notes)
    if not solution.cameras:
        raise InputError(f"has no aligned camera ({len(solution.unaligned)} not aligned)", source=solution.source)
    images = {**solution.photos, **match_images([c.name for c in solution.cameras], images_folder)}
    surveyed = _control_ground(solution) if ground_height is None else None
    frames = solution_frames(solution, images, ground_height if surveyed is None else surveyed,
                             GIVEN if surveyed is None else CONTROL_POINTS)
    report.counts.update({"format": solution.format, "aligned": len(solution.cameras),
                          "not_aligned": len(solution.unaligned)})
    if solution.unaligned:
        report.notes.append(f"{len(solution.unaligned)} camera(s) are not aligned in the solution and are left "
                            "out: " + "; ".join(f"{name} ({why})" for name, why in solution.unaligned[:5]))
    if images_folder:
        missing = [c.name for c in solution.cameras if c.name not in images]
        report.counts["images_matched"] = len(solution.cameras) - len(missing)
        if missing:
            report.notes.append(f"{len(missing)} aligned camera(s) have no image in {images_folder} (matched by "
                                f"file name or stem): {', '.join(missing[:5])}; their frames keep the name only")
    n_ground = int(np.count_nonzero(np.isfinite(frames.ground_h)))
    report.counts["frames_with_ground"] = n_ground
    if surveyed is not None:
        report.findings.append(f"Frames without tie points in view stand on the control points' median surveyed "
                            f"height, {surveyed:.2f} m (ellipsoidal), for their footprints; give a DEM or "
                            "GROUND_HEIGHT_M on uneven ground")
    if n_ground < len(frames) and dem is None:
        report.notes.append(f"{len(frames) - n_ground} frame(s) have no ground height: the solution has no tie "
                            "points in their view and neither DEM nor GROUND_HEIGHT_M was given: they get no footprint "
                            "and Detect cannot place their detections on the ground (labels still use the geotags' "
                            "own heights). Give a DEM or the ground height")
    if progress is not None:
        progress(0.3)
    crs = crs or ProjectedCRS.for_site(frames.lat, frames.lon)
    sub = None if progress is None else (lambda f: progress(0.3 + 0.7 * f))
    ground = dem_ground_for(frames, dem, report)
    fp = compute_footprints(frames, crs, progress=sub, is_canceled=is_canceled, ground=ground)
    control = solution.marks
    check = _check_marks(control, solution, frames, fp, report) if control is not None else None
    return FlightImport(frames, fp, [], report, control.points if control is not None else None, check)


def _control_ground(solution: CameraSolution) -> float | None:
    """The median surveyed height of the solution's control points (its ground), if it has any."""
    if solution.marks is None or not solution.ellipsoidal:
        return None
    heights = solution.marks.points.height
    heights = heights[np.isfinite(heights)]
    return float(np.median(heights)) if len(heights) else None


def _check_marks(control: ControlMarks, solution: CameraSolution, frames: Frames, fp, report: ImportReport):
    """Labels of the control points against their pinned marks (:mod:`...labels.mark_check`), reported."""
    from ...labels.mark_check import check_marks, describe
    from ..frames import frame_records

    frame_of = {c.name: i for i, c in enumerate(solution.cameras)}
    on_aligned = np.array([name in frame_of for name in control.camera], dtype=bool)
    report.counts["control_points"] = len(control.points)
    if (~on_aligned).any():
        report.notes.append(f"{int((~on_aligned).sum())} image mark(s) are in cameras the solution did not align "
                            "and cannot be checked")
    if not on_aligned.any():
        return None
    check = check_marks(list(frame_records(frames, fp)), control.points, control.point_idx[on_aligned],
                        [frame_of[name] for name, ok in zip(control.camera, on_aligned) if ok],
                        control.uv[on_aligned])
    summary = check.summary()
    report.counts.update({k if k == "marks" else f"marks_{k}": v for k, v in summary.items()})
    findings, notes = describe(check, frames.frame_id)
    report.findings.extend(findings)
    report.notes.extend(notes)
    return check

"""PIX4Dmapper calibrated camera parameters (``<project>_calibrated_camera_parameters.txt`` and
``<project>_offset.xyz``, both in the project's ``1_initial/params`` folder).

Conventions converted here (the file's own header; Pix4D's articles "What does the Output Params Folder
contain?" — which calls these files "not supported, for experimental use only" — and "How are the
Internal and External Camera Parameters defined?"):

* After a 7-line header and a blank line, ten lines per calibrated image: ``name width height``; K
  (3 lines); radial ``R1 R2 R3``; tangential ``T1 T2``; camera position t (3); rotation R (3 lines).
  Images Pix4D could not calibrate are not listed.
* ``m = K [R | −R t] X`` (the header): R maps project axes to camera axes, t is the camera centre.
  K is positive and a nadir image's third row of R points down, so the camera axes are OpenCV's.
  ``<project>_pmatrix.txt`` holds exactly these products: P-matrices carry no distortion.
* Project coordinates X, and t, are relative to ``<project>_offset.xyz`` in the project's output
  CRS: easting, northing and height, treated by Pix4D as one Cartesian frame. The files do not name
  that CRS (``<project>_wkt.prj`` and the quality report do): the caller must give it.
* Grid axes are not true east/north and grid distances are not true ones. Around each camera the CRS is
  stepped ±50 m and taken through ECEF: that gives the angle γ of grid north from true north (the
  camera's rotation turns by it) and the scale k of grid over true distances at the camera's height
  (the projection's scale factor times R/(R + h)). Pix4D fitted K to images in grid units, so the true
  focal length is k·f (k: median over the cameras); without it a point r px from the principal point
  would move by (1 − k)·r px: 0.7 px at this project's image corners, ~3 px near a UTM zone's edge.
  Left over, as no pinhole camera holds them: d/R of r for points d m above or below the cameras
  (0.025 px at the corners 40 m down) and the unscaled heights in a tilted camera's rays.
* Distortion (the "perspective lens" model of Pix4D's article):
  ``xd = x(1 + R1r² + R2r⁴ + R3r⁶) + 2T1xy + T2(r² + 2x²)``, ``yd = y(…) + T1(r² + 2y²) + 2T2xy``:
  OpenCV's ``k1 k2 p1 p2 k3`` = ``R1 R2 T1 T2 R3``, applied to (x, y) of the file's K/R frame, as
  EasyIDP applies it to these files. The article writes the formula in its own camera frame (y up,
  image origin at the lower-left corner); were T1/T2 given for that frame and not converted for this
  file, one of them would change sign. No file here holds an image observation that could tell; for
  this project's camera the tangential terms move the image corners by up to 26 px, so a wrong sign
  would misplace points there by up to 29 px (7–8 px in the median over the image).
* Pixel origin: a P-matrix maps to Pix4D's pixels whatever their origin, so the P-matrices cannot say
  whether Pix4D's (0, 0) is the centre or the corner of the top-left pixel. Two hints, neither proof:
  Pix4D's ``calibrated_internal_camera_parameters.cam`` of the same project gives the principal-point
  offset in pixels as exactly W/2 − cx, H/2 − cy, i.e. its image centre is (W/2, H/2), the corner
  convention (with pixel centres at integers it would be ((W − 1)/2, (H − 1)/2)); and Pix4D's article
  puts the origin of its image coordinates "at the lower-left corner of the image". So, as for
  Metashape and COLMAP, ``cx_cv = cx − 0.5``, ``cy_cv = cy − 0.5``; the other choice would move every
  pixel by 0.7 px.
* Heights are those of the project's output CRS: ellipsoidal or above a geoid, as the Pix4D project
  was set up, and the files do not say which. The CRS the user names (``SOLUTION_CRS``) says it when it has
  a vertical part (a compound CRS such as ``EPSG:32654+5773``, EGM96); otherwise the heights are taken as
  above mean sea level, geoid not named (Pix4D's usual output). Labels do not use the geotags' own heights
  (not ``ellipsoidal``), and since these files hold no tie points, frames take their ground from the DEM or
  ``ground_height``.
"""
from __future__ import annotations

from dataclasses import dataclass
from pathlib import Path

import numpy as np

from ...errors import InputError
from ...geometry.camera import CameraModel
from ...geometry.geodesy import (
    ProjectedCRS,
    ensure_proj_data,
    geodetic_to_ecef,
    on_python_thread,
    rotation_ecef_enu,
)
from ...geometry.heights import MSL_REFERENCE, crs_vertical_reference
from . import CameraSolution, SolvedCamera

PARAMETERS_SUFFIX = "calibrated_camera_parameters.txt"
OFFSET_SUFFIX = "offset.xyz"
#: (field name as the file's header gives it, number of lines, numbers per line) of one image's block.
BLOCK = (("camera matrix K", 3, 3), ("radial distortion", 1, 3), ("tangential distortion", 1, 2),
         ("camera position t", 1, 3), ("camera rotation R", 3, 3))
BLOCK_LINES = 1 + sum(n for _, n, _ in BLOCK)
#: How far R may be from a rotation: Pix4D writes 20 digits.
ROTATION_TOLERANCE = 1e-6
#: Half the baseline (m) over which the CRS is differenced around each camera: long enough that PROJ's
#: rounding (~1e-9 m) is below 1e-10 of it, short enough that the map's curvature cancels.
GRID_STEP_M = 50.0
#: Degrees by which a CRS's area of use is widened before the cameras are refused as outside it.
AREA_MARGIN_DEG = 1.0


@dataclass
class Pix4DImage:
    """One image of the file as Pix4D wrote it."""

    name: str
    width: int
    height: int
    K: np.ndarray
    radial: np.ndarray
    tangential: np.ndarray
    t: np.ndarray
    R: np.ndarray


def find_parameters(folder: Path) -> Path | None:
    for candidate in (folder, folder / "params", folder / "1_initial" / "params"):
        found = sorted(candidate.glob(f"*{PARAMETERS_SUFFIX}")) if candidate.is_dir() else []
        if len(found) == 1:
            return found[0]
    return None


def offset_path(path: Path) -> Path:
    """``<project>_offset.xyz`` beside ``<project>_calibrated_camera_parameters.txt``."""
    return path.parent / (path.name[:-len(PARAMETERS_SUFFIX)] + OFFSET_SUFFIX)


def _numbers(text: str, count: int, source: str, row: int, what: str) -> np.ndarray:
    try:
        values = np.array([float(v) for v in text.split()])
    except ValueError:
        raise InputError(f"expected {count} numbers, got {text.strip()!r}", source=source, row=row,
                         field=what) from None
    if values.size != count or not np.all(np.isfinite(values)):
        raise InputError(f"expected {count} finite numbers, got {text.strip()!r}", source=source, row=row,
                         field=what)
    return values


def read_parameters(path) -> list[Pix4DImage]:
    """Every image of a ``calibrated_camera_parameters.txt`` file, checked and unconverted."""
    path = Path(path)
    source = str(path)
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"is not a readable text file ({exc})", source=source) from exc
    model = next((k for k, line in enumerate(lines) if line.strip().startswith("camera model")), None)
    if not lines or not lines[0].strip().startswith("fileName") or model is None:
        raise InputError("is not a Pix4D calibrated camera parameters file (expected a header from 'fileName "
                         "imageWidth imageHeight' to 'camera model m = K [R|-Rt] X')", source=source)
    rows = [(k + 1, line) for k, line in enumerate(lines) if k > model and line.strip()]
    images = []
    for start in range(0, len(rows), BLOCK_LINES):
        block = rows[start:start + BLOCK_LINES]
        row, head = block[0]
        parts = head.split()
        try:
            name, width, height = " ".join(parts[:-2]), int(parts[-2]), int(parts[-1])
        except (IndexError, ValueError):
            raise InputError(f"expected 'fileName imageWidth imageHeight', got {head.strip()!r}", source=source,
                             row=row, field="fileName imageWidth imageHeight") from None
        if not name or width <= 0 or height <= 0:
            raise InputError(f"expected an image name and a positive width and height, got {head.strip()!r}",
                             source=source, row=row, field="fileName imageWidth imageHeight")
        if len(block) < BLOCK_LINES:
            raise InputError(f"image '{name}' has {len(block)} of its {BLOCK_LINES} lines: the file is truncated",
                             source=source, row=row)
        values, k = {}, 1
        for what, n_lines, per_line in BLOCK:
            values[what] = np.array([_numbers(block[k + j][1], per_line, source, block[k + j][0], what)
                                     for j in range(n_lines)]).squeeze()
            k += n_lines
        k_matrix, rotation = values["camera matrix K"], values["camera rotation R"]
        if (k_matrix[0, 0] <= 0 or k_matrix[1, 1] <= 0 or k_matrix[1, 0] != 0
                or np.any(k_matrix[2] != (0.0, 0.0, 1.0))):
            raise InputError(f"image '{name}': expected [[fx, s, cx], [0, fy, cy], [0, 0, 1]] with positive focal "
                             f"lengths, got {k_matrix.tolist()}", source=source, row=block[1][0],
                             field="camera matrix K")
        if np.abs(rotation @ rotation.T - np.eye(3)).max() > ROTATION_TOLERANCE or np.linalg.det(rotation) <= 0:
            raise InputError(f"image '{name}': expected a rotation matrix (orthonormal, determinant +1)",
                             source=source, row=block[7][0], field="camera rotation R")
        images.append(Pix4DImage(name, width, height, k_matrix, values["radial distortion"],
                                 values["tangential distortion"], values["camera position t"], rotation))
    if not images:
        raise InputError("lists no calibrated image", source=source)
    return images


def read_offset(path: Path) -> np.ndarray:
    source = str(path)
    if not path.is_file():
        raise InputError("not found: Pix4D writes the offset of the project's coordinates there, beside "
                         "the calibrated camera parameters (1_initial/params); copy it beside them", source=source)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"is not a readable text file ({exc})", source=source) from exc
    return _numbers(text, 3, source, 1, "offset x y z")


@on_python_thread
def _in_area_of_use(crs: ProjectedCRS, lat, lon) -> bool:
    """Whether the cameras lie in the CRS's area of use (widened), where one is known: a wrong CRS would
    otherwise place the flight on another continent without a word."""
    ensure_proj_data()
    import pyproj

    area = pyproj.CRS.from_user_input(crs.crs).area_of_use
    if area is None:
        return True
    m = AREA_MARGIN_DEG
    # An area crossing the antimeridian has west > east.
    in_lon = ((lon >= area.west - m) & (lon <= area.east + m) if area.west <= area.east
              else (lon >= area.west - m) | (lon <= area.east + m))
    return bool(np.all(in_lon & (lat >= area.south - m) & (lat <= area.north + m)))


def _grid_factors(crs: ProjectedCRS, centres: np.ndarray, lat, lon):
    """Per camera: the angle γ (rad) by which grid north lies clockwise of true north, and the scale k of
    grid distances over true ones, both at the camera's position and height.

    Measured by stepping the CRS around each camera and going through ECEF, so that k holds the height's
    share (h/R: 1.6e-5 at 100 m) as well as the projection's scale factor, whatever the CRS.
    """
    step = GRID_STEP_M
    around = np.repeat(centres, 4, axis=0)
    around[:, :2] += np.tile([[step, 0.0], [-step, 0.0], [0.0, step], [0.0, -step]], (len(centres), 1))
    a_lat, a_lon = crs.to_geodetic(around[:, 0], around[:, 1])
    ecef = geodetic_to_ecef(a_lat, a_lon, around[:, 2]).reshape(-1, 4, 3)
    enu = np.einsum("nji,nkj->nki", rotation_ecef_enu(lat, lon), ecef)
    east, north = (enu[:, 0] - enu[:, 1]) / (2 * step), (enu[:, 2] - enu[:, 3]) / (2 * step)
    gamma = np.arctan2(north[:, 0] - east[:, 1], east[:, 0] + north[:, 1])
    return gamma, 1.0 / np.sqrt(east[:, 0] * north[:, 1] - east[:, 1] * north[:, 0])


def read_pix4d(path, solution_crs: ProjectedCRS | None) -> CameraSolution:
    path = Path(path)
    source = str(path)
    if solution_crs is None:
        raise InputError("is a Pix4D solution in the project's output coordinate system, which its files do not "
                         "name: set SOLUTION_CRS to that projected CRS (Pix4D writes it in <project>_wkt.prj "
                         "beside this file and in the quality report)", source=source, field="SOLUTION_CRS")
    images = read_parameters(path)
    offset = read_offset(offset_path(path))
    centres = offset + np.array([im.t for im in images])
    try:
        lat, lon = solution_crs.to_geodetic(centres[:, 0], centres[:, 1])
    except Exception as exc:  # noqa: BLE001 — pyproj raises its own error types for impossible coordinates
        raise InputError(f"camera positions cannot be converted from {solution_crs.crs} ({exc}); is SOLUTION_CRS "
                         "the project's output CRS?", source=source, field="SOLUTION_CRS") from exc
    if not (np.all(np.isfinite(lat)) and np.all(np.isfinite(lon))) or not _in_area_of_use(solution_crs, lat, lon):
        raise InputError(f"camera positions (offset {offset.tolist()} + t) are not coordinates of {solution_crs.crs} "
                         "inside its area of use; is SOLUTION_CRS the project's output CRS?", source=source,
                         field="SOLUTION_CRS")
    gamma, scale = _grid_factors(solution_crs, centres, lat, lon)
    c, s = np.cos(gamma), np.sin(gamma)
    # Columns: grid east, grid north, up in local ENU; grid north lies γ clockwise of true north.
    r_enu_grid = np.zeros((len(images), 3, 3))
    r_enu_grid[:, 0, 0], r_enu_grid[:, 0, 1], r_enu_grid[:, 1, 0], r_enu_grid[:, 1, 1] = c, s, -s, c
    r_enu_grid[:, 2, 2] = 1.0
    r_grid_cam = np.swapaxes(np.array([im.R for im in images]), 1, 2)
    r_ecef_cam = rotation_ecef_enu(lat, lon) @ r_enu_grid @ r_grid_cam
    centres_ecef = geodetic_to_ecef(lat, lon, centres[:, 2]).reshape(-1, 3)
    k = float(np.median(scale))
    models: dict[tuple, CameraModel] = {}
    cameras = []
    for im, r, x in zip(images, r_ecef_cam, centres_ecef):
        key = (im.width, im.height, *im.K.ravel(), *im.radial, *im.tangential)
        if key not in models:
            (r1, r2, r3), (t1, t2) = im.radial, im.tangential
            models[key] = CameraModel(im.width, im.height, k * im.K[0, 0], k * im.K[1, 1], im.K[0, 2] - 0.5,
                                      im.K[1, 2] - 0.5, (r1, r2, t1, t2, r3), skew=k * im.K[0, 1],
                                      source=f"pix4d:{path.name} camera {len(models) + 1}")
        cameras.append(SolvedCamera(im.name, models[key], r, x))
    stated = crs_vertical_reference(solution_crs.crs)
    reference = stated or MSL_REFERENCE
    how = "as the CRS states" if stated else "the CRS has no vertical part; a compound CRS states it, e.g. +5773 EGM96"
    notes = [f"Pix4D coordinates in {solution_crs.crs} (offset {offset[0]:.3f}, {offset[1]:.3f}, {offset[2]:.3f}); "
             f"focal lengths × {k:.6f}, the CRS's grid scale at the cameras (projection and height). Heights "
             f"{reference.describe()} ({how}): labels do not use the geotags' own heights. These files hold no tie "
             "points: give a DEM or GROUND_HEIGHT_M (in the project's height reference) for footprints"]
    return CameraSolution("pix4d", source, cameras, [], None, notes, reference=reference)

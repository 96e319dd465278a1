"""COLMAP sparse models (``cameras``/``images``/``points3D`` as .bin or .txt), read with pycolmap.

Conventions converted here (COLMAP's documentation, "Output format" and "Camera models"):

* An image's pose ``cam_from_world`` (quaternion + translation in images.txt) maps world to camera:
  ``x_cam = R·x_world + t``; camera axes are OpenCV's.
* COLMAP's pixel coordinates have their origin at the top-left *corner* of the image (the centre of
  the top-left pixel is (0.5, 0.5)): ``cx_cv = cx − 0.5``, ``cy_cv = cy − 0.5``.
* ``OPENCV`` is OpenCV's ``k1 k2 p1 p2``; ``FULL_OPENCV`` adds k3 and the rational k4–k6 (read only when
  those are zero); ``SIMPLE_RADIAL``/``RADIAL`` are k1 (k2); ``OPENCV_FISHEYE`` is OpenCV's fisheye and
  ``SIMPLE_RADIAL_FISHEYE``/``RADIAL_FISHEYE`` are the same equidistant model with k1 (k2).
* A COLMAP model has no geographic frame of its own. ``reference``: ``ecef`` when the model was
  georegistered into ECEF (``colmap model_aligner --alignment_type ecef``); ``enu:lat,lon,h`` when it
  is in an east-north-up frame at that origin; ``gps`` to align it here to the images' own GPS
  positions (EXIF/XMP of the images in the image folder) by a similarity transform.
"""
from __future__ import annotations

from pathlib import Path

import numpy as np

from ...errors import InputError
from ...geometry.camera import CameraModel
from ...geometry.geodesy import geodetic_to_ecef, rotation_ecef_enu
from ...geometry.heights import EGM96_REFERENCE, ELLIPSOIDAL_REFERENCE
from ...geometry.rigid import RigidTransform
from ...geometry.similarity import fit_similarity_robust
from . import CameraSolution, SolvedCamera, match_images

MODEL_FILES = ("cameras.bin", "images.bin", "points3D.bin", "cameras.txt", "images.txt", "points3D.txt")
#: COLMAP model name → (parameter names, how they map onto :class:`CameraModel`).
SUPPORTED_MODELS = ("SIMPLE_PINHOLE", "PINHOLE", "SIMPLE_RADIAL", "RADIAL", "OPENCV", "FULL_OPENCV",
                    "OPENCV_FISHEYE", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE")


def find_model(folder: Path) -> Path | None:
    for candidate in (folder, folder / "sparse" / "0", folder / "sparse", folder / "0"):
        if any((candidate / name).is_file() for name in ("cameras.bin", "cameras.txt")):
            return candidate
    return None


def camera_from_colmap(model: str, width: int, height: int, params, label: str) -> CameraModel:
    """An OpenCV-convention :class:`CameraModel` from a COLMAP camera model's name and parameters."""
    p = [float(v) for v in params]
    if model not in SUPPORTED_MODELS:
        raise InputError(f"camera model {model} is not supported (supported: {', '.join(SUPPORTED_MODELS)})",
                         source=label)
    if model in ("SIMPLE_PINHOLE", "SIMPLE_RADIAL", "RADIAL", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE"):
        fx = fy = p[0]
        cx, cy, extra = p[1], p[2], p[3:]
    else:
        fx, fy, cx, cy, extra = p[0], p[1], p[2], p[3], p[4:]
    common = dict(width=width, height=height, fx=fx, fy=fy, cx=cx - 0.5, cy=cy - 0.5, source=f"colmap:{label}")
    if model in ("OPENCV_FISHEYE", "SIMPLE_RADIAL_FISHEYE", "RADIAL_FISHEYE"):
        return CameraModel(dist=tuple(extra) + (0.0,) * (4 - len(extra)), fisheye=True, **common)
    if model == "FULL_OPENCV":
        if any(extra[5:]):
            raise InputError("FULL_OPENCV camera uses the rational terms k4–k6; only k1 k2 p1 p2 k3 are supported",
                             source=label)
        return CameraModel(dist=tuple(extra[:5]), **common)
    if model == "OPENCV":
        return CameraModel(dist=tuple(extra), **common)
    radial = tuple(extra) + (0.0,) * (2 - len(extra))
    return CameraModel(dist=(radial[0], radial[1], 0.0, 0.0, 0.0), **common)


def colmap_camera(camera: CameraModel) -> tuple[str, list]:
    """The COLMAP model name and parameters of a :class:`CameraModel` (inverse of :func:`camera_from_colmap`)."""
    if camera.k4 or camera.skew:
        raise InputError(f"camera '{camera.source}' has an r⁸ term or skew, which no COLMAP camera model holds")
    fx, fy, cx, cy = camera.fx, camera.fy, camera.cx + 0.5, camera.cy + 0.5
    if camera.fisheye:
        return "OPENCV_FISHEYE", [fx, fy, cx, cy, *camera.dist[:4]]
    k1, k2, p1, p2, k3 = camera.dist
    if k3:
        return "FULL_OPENCV", [fx, fy, cx, cy, k1, k2, p1, p2, k3, 0.0, 0.0, 0.0]
    return "OPENCV", [fx, fy, cx, cy, k1, k2, p1, p2]


def _reference_transform(reference: str, source: str) -> RigidTransform:
    """The transform taking model coordinates to ECEF for ``ecef`` / ``enu:lat,lon,h`` references."""
    if reference == "ecef":
        return RigidTransform(np.eye(3), np.zeros(3))
    if reference.startswith("enu:"):
        try:
            lat, lon, h = (float(v) for v in reference[4:].split(","))
        except ValueError:
            raise InputError(f"the ENU origin must be 'lat,lon,h' in degrees and metres, got {reference[4:]!r}",
                             source=source) from None
        return RigidTransform(rotation_ecef_enu(lat, lon), geodetic_to_ecef(lat, lon, h).reshape(3))
    raise InputError(f"reference {reference!r} is not 'gps', 'ecef' or 'enu:lat,lon,h'", source=source)


def image_gps(path: Path):
    """(lat, lon, height) of an image's GPS tags (DJI XMP first, then EXIF), or None."""
    from ..dji import read_dji_metadata

    meta = read_dji_metadata(path)
    (lat, lon), height = meta.gps_lat_lon, meta.gps_height
    if lat is None or lon is None or height is None:
        return None
    return float(lat), float(lon), float(height)


def read_colmap(folder, images_folder=None, reference: str = "gps") -> CameraSolution:
    import pycolmap

    folder = Path(folder)
    source = str(folder)
    try:
        rec = pycolmap.Reconstruction(str(folder))
    except Exception as exc:  # noqa: BLE001 — pycolmap raises its own error types for unreadable models
        raise InputError(f"is not a readable COLMAP model ({exc})", source=source) from exc
    models = {cid: camera_from_colmap(cam.model.name, cam.width, cam.height, cam.params, f"{folder.name} camera {cid}")
              for cid, cam in rec.cameras.items()}
    names, rotations, centres, unaligned, cams = [], [], [], [], []
    for image in sorted(rec.images.values(), key=lambda im: im.name):
        if not image.has_pose:
            unaligned.append((image.name, "not registered"))
            continue
        world_from_cam = RigidTransform.from_matrix(image.cam_from_world().matrix()).inverse()
        names.append(image.name)
        rotations.append(world_from_cam.rotation)
        centres.append(world_from_cam.translation)
        cams.append(models[image.camera_id])
    rotations, centres = np.asarray(rotations).reshape(-1, 3, 3), np.asarray(centres).reshape(-1, 3)
    points = np.array([p.xyz for p in rec.points3D.values()]).reshape(-1, 3) if rec.num_points3D() else None
    notes = []
    if reference == "gps":
        sim, residual, kept = _gps_alignment(names, centres, images_folder, source)
        notes.append(f"aligned to the GPS positions of {kept} images: scale {sim.scale:.6g}, residual RMS "
                     f"{residual:.3f} m (heights as the images' GPS gives them)")
        r_ecef, centres_ecef = sim.rotate(rotations), sim.apply(centres)
        points = None if points is None else sim.apply(points)
    else:
        ecef_from_world = _reference_transform(reference, source)
        ecef_from_cam = ecef_from_world @ RigidTransform(rotations, centres)
        r_ecef, centres_ecef = ecef_from_cam.rotation, ecef_from_cam.translation
        points = None if points is None else ecef_from_world.apply(points)
    cameras = [SolvedCamera(n, c, r, x) for n, c, r, x in zip(names, cams, r_ecef, centres_ecef)]
    return CameraSolution("colmap", source, cameras, unaligned, points, notes,
                          reference=EGM96_REFERENCE if reference == "gps" else ELLIPSOIDAL_REFERENCE)


def _gps_alignment(names, centres, images_folder, source):
    if not images_folder:
        raise InputError("names no geographic reference: a COLMAP model is in its own frame. Give the image "
                         "folder (its GPS tags align the model), or say the model is already in ECEF or in an "
                         "ENU frame at a stated origin", source=source)
    files = match_images(names, images_folder)
    pairs = [(k, image_gps(files[n])) for k, n in enumerate(names) if n in files]
    pairs = [(k, g) for k, g in pairs if g is not None]
    if len(pairs) < 3:
        raise InputError(f"only {len(pairs)} registered image(s) have GPS tags in {images_folder}; at least 3 are "
                         "needed to georeference the COLMAP model", source=source)
    idx = np.array([k for k, _ in pairs])
    gps = np.array([g for _, g in pairs])
    target = geodetic_to_ecef(gps[:, 0], gps[:, 1], gps[:, 2])
    # Consumer GPS tags hold the odd jump of tens of metres; the robust fit leaves those images out.
    fit = fit_similarity_robust(centres[idx], target)
    residual = float(np.sqrt(np.mean(fit.residual[fit.inliers] ** 2)))
    return fit.similarity, residual, int(fit.inliers.sum())

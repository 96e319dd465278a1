"""OpenSfM / OpenDroneMap ``reconstruction.json`` (as WebODM and ODM's ``opensfm/`` folder hold it).

Conventions converted here (OpenSfM's documentation and ``opensfm/types``, ``geo`` modules):

* A shot's ``rotation`` (axis-angle) and ``translation`` map world to camera:
  ``x_cam = R(rotation)·x_world + translation``; camera axes are OpenCV's.
* The world is topocentric east-north-up at ``reference_lla`` (in the file in recent OpenSfM, else in
  ``reference_lla.json`` beside it). ODM overwrites ``reconstruction.json`` with UTM coordinates and
  keeps the topocentric one as ``reconstruction.topocentric.json``: that file is read when present.
* Intrinsics are normalised by the image's larger side ``s = max(w, h)``; the principal point
  (``c_x``, ``c_y``) is an offset from the image centre in those units and pixel centres sit at
  ``u = s·x_n + w/2 − 0.5``. So ``fx = focal_x·s`` and ``cx = w/2 − 0.5 + c_x·s`` in OpenCV's convention.
* ``brown``: ``k1 k2 k3`` radial and ``p1 p2`` tangential in OpenCV's order; ``perspective``: one
  focal, ``k1 k2``; ``fisheye``: equidistant with ``k1 k2`` (OpenCV fisheye k1, k2);
  ``fisheye_opencv``: ``k1…k4``; ``radial``/``simple_radial``: ``k1 (k2)``. ``perspective`` and
  ``fisheye`` have one ``focal``, the others ``focal_x`` and ``focal_y``.
"""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np

from ...errors import InputError
from ...geometry.camera import CameraModel
from ...geometry.geodesy import geodetic_to_ecef, rotation_ecef_enu
from ...geometry.rigid import RigidTransform
from ...geometry.rotations import so3_exp
from . import CameraSolution, SolvedCamera

TOPOCENTRIC = "reconstruction.topocentric.json"


def find_reconstruction(folder: Path) -> Path | None:
    for candidate in (folder / TOPOCENTRIC, folder / "reconstruction.json",
                      folder / "opensfm" / TOPOCENTRIC, folder / "opensfm" / "reconstruction.json"):
        if candidate.is_file():
            return candidate
    return None


def _camera(key: str, spec: dict, source: str) -> CameraModel:
    kind = spec.get("projection_type", "perspective")
    try:
        width, height = int(spec["width"]), int(spec["height"])
        size = float(max(width, height))

        def get(name, default=0.0):
            return float(spec.get(name, default))

        if kind in ("perspective", "fisheye"):
            fx = fy = float(spec["focal"]) * size
            cx, cy = width / 2.0 - 0.5, height / 2.0 - 0.5
        elif kind in ("brown", "fisheye_opencv", "radial", "simple_radial"):
            # OpenSfM writes focal_x and focal_y for all four (opensfm/io.py, camera_to_json).
            fx, fy = float(spec["focal_x"]) * size, float(spec["focal_y"]) * size
            cx, cy = width / 2.0 - 0.5 + get("c_x") * size, height / 2.0 - 0.5 + get("c_y") * size
        else:
            raise InputError(f"camera '{key}' has projection_type '{kind}'; supported: perspective, brown, "
                             "fisheye, fisheye_opencv, radial, simple_radial", source=source)
        label = f"opensfm:{key}"
        if kind == "brown":
            return CameraModel(width, height, fx, fy, cx, cy,
                               (get("k1"), get("k2"), get("p1"), get("p2"), get("k3")), source=label)
        if kind == "fisheye":
            return CameraModel(width, height, fx, fy, cx, cy, (get("k1"), get("k2"), 0.0, 0.0), fisheye=True,
                               source=label)
        if kind == "fisheye_opencv":
            return CameraModel(width, height, fx, fy, cx, cy, (get("k1"), get("k2"), get("k3"), get("k4")),
                               fisheye=True, source=label)
        return CameraModel(width, height, fx, fy, cx, cy, (get("k1"), get("k2"), 0.0, 0.0, 0.0), source=label)
    except (KeyError, TypeError, ValueError) as exc:
        raise InputError(f"camera '{key}' is incomplete or malformed ({exc})", source=source) from exc


def _reference(doc: dict, path: Path):
    ref = doc.get("reference_lla")
    beside = path.parent / "reference_lla.json"
    if ref is None and beside.is_file():
        try:
            ref = json.loads(beside.read_text(encoding="utf-8"))
        except json.JSONDecodeError as exc:
            raise InputError(f"is not valid JSON ({exc})", source=str(beside)) from exc
    if not isinstance(ref, dict) or not {"latitude", "longitude", "altitude"} <= set(ref):
        raise InputError("names no geographic reference: no 'reference_lla' (latitude, longitude, altitude) in the "
                         "reconstruction and no reference_lla.json beside it. Was the reconstruction made from "
                         "images with GPS positions?", source=str(path))
    return float(ref["latitude"]), float(ref["longitude"]), float(ref["altitude"])


def read_reconstruction(path) -> CameraSolution:
    path = Path(path)
    notes = []
    if path.name == "reconstruction.json" and (path.parent / TOPOCENTRIC).is_file():
        notes.append(f"read {TOPOCENTRIC} beside {path.name}: OpenDroneMap rewrites reconstruction.json in UTM "
                     "coordinates and keeps the topocentric one, which carries the geographic reference")
        path = path.parent / TOPOCENTRIC
    source = str(path)
    try:
        doc = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, json.JSONDecodeError) as exc:
        raise InputError(f"is not a readable JSON file ({exc})", source=source) from exc
    if isinstance(doc, dict):
        doc = [doc]
    if not isinstance(doc, list) or not doc or not all(isinstance(r, dict) and "shots" in r for r in doc):
        raise InputError("is not an OpenSfM reconstruction (expected a list of objects with 'cameras' and 'shots')",
                         source=source)
    if len(doc) > 1:
        notes.append(f"the file holds {len(doc)} separate reconstructions (partial alignment); all are read, each in "
                     "the same geographic reference")
    lat0, lon0, h0 = _reference(doc[0], path)
    ecef_from_world = RigidTransform(rotation_ecef_enu(lat0, lon0), geodetic_to_ecef(lat0, lon0, h0).reshape(3))
    names, rotvecs, translations, models_of, points = [], [], [], [], []
    for rec in doc:
        models = {key: _camera(key, spec, source) for key, spec in rec.get("cameras", {}).items()}
        for name, shot in rec["shots"].items():
            try:
                rotvecs.append(shot["rotation"])
                translations.append(shot["translation"])
                models_of.append(models[shot["camera"]])
            except KeyError as exc:
                raise InputError(f"shot '{name}' lacks {exc} or names an unknown camera", source=source) from exc
            names.append(name)
        points.extend(point["coordinates"] for point in rec.get("points", {}).values())
    try:
        r_cam_world = so3_exp(np.asarray(rotvecs, dtype=float).reshape(-1, 3))
        t = np.asarray(translations, dtype=float).reshape(-1, 3)
    except ValueError as exc:
        raise InputError(f"a shot's rotation or translation is not three numbers ({exc})", source=source) from exc
    ecef_from_cam = ecef_from_world @ RigidTransform(r_cam_world, t).inverse()
    cameras = [SolvedCamera(n, m, r, c) for n, m, r, c in zip(names, models_of, ecef_from_cam.rotation,
                                                                ecef_from_cam.translation)]
    pts = ecef_from_world.apply(np.asarray(points, dtype=float).reshape(-1, 3)) if points else None
    return CameraSolution("opensfm", source, cameras, [], pts, notes)

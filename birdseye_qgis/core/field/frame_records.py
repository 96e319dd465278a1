"""The frame-layer contract: what every frame carries so later steps need no source files.

Both importers (BirdsEye pose log, DJI images) and the simulator write frames with these fields;
``writelabels`` and ``detect`` read them back with :func:`poses_from_records`. One module owns the
schema so writer and readers never drift apart.
"""
from __future__ import annotations

import json

import numpy as np

from ..errors import InputError
from ..geometry.camera import CameraModel
from ..geometry.geodesy import LocalFrame
from ..geometry.heights import ALTIMETER, ELLIPSOIDAL_REFERENCE, VerticalReference, parse_ground_source
from ..geometry.poses import FramePoses, indices_by_camera
from ..geometry.rotations import quat_to_rotmat, rotmat_to_euler_zyx

#: (name, type, description) — type is one of "int", "double", "string".
FRAME_FIELDS = [
    ("frame_id", "int", "frame number, unique within the flight"),
    ("image", "string", "absolute path of the image file"),
    ("time_s", "double", "exposure time (s, the pose log's clock)"),
    ("lat", "double", "IMU latitude, WGS84 (deg)"),
    ("lon", "double", "IMU longitude, WGS84 (deg)"),
    ("height_m", "double", "IMU height (m), measured from height_ref"),
    ("qw", "double", "attitude quaternion w (body FRD → NED)"),
    ("qx", "double", "attitude quaternion x"),
    ("qy", "double", "attitude quaternion y"),
    ("qz", "double", "attitude quaternion z"),
    ("roll_deg", "double", "roll (deg, ZYX; yaw-roll-pitch when looking down)"),
    ("pitch_deg", "double", "pitch (deg, ZYX; yaw-roll-pitch when looking down)"),
    ("yaw_deg", "double", "yaw from true north (deg, ZYX; yaw-roll-pitch when looking down)"),
    ("ground_h_m", "double", "height of the level ground under the frame (m), measured from height_ref"),
    ("depth_m", "double", "camera height above that ground (m)"),
    ("height_ref", "string", "what height_m and ground_h_m are measured from: ellipsoidal, a geoid (EGM96: above "
                             "mean sea level), msl (geoid not named) or unknown"),
    ("ground_src", "string", "where ground_h_m came from: altimeter, tie_points, dem (under the frame); takeoff, "
                             "flight_height, control_points, geotags (one height for the site); empty: none"),
    ("rtk_status", "int", "3 fixed, 2 float, 1 none"),
    ("sync_offset_s", "double", "image time minus strobe time (s)"),
    ("gsd_cm", "double", "ground sample distance at the image centre (cm/px)"),
    ("camera", "string", "camera model as JSON (intrinsics, distortion, T_cam_imu)"),
    ("flags", "string", "comma-separated warnings (e.g. rtk_float, non_nadir, yaw_mismatch)"),
]
FRAME_FIELD_NAMES = [f[0] for f in FRAME_FIELDS]

#: A camera model longer than the text fields of the format a frame layer is written to (an ESRI Shapefile
#: keeps 254 characters; a camera model needs about 500) goes on in fields ``camera_2``, ``camera_3``, …
CAMERA_FIELD = "camera"


def camera_part_fields(n_parts: int) -> list[tuple[str, str, str]]:
    """The schema of the fields after ``camera`` that hold the rest of a camera model in ``n_parts`` parts."""
    return [(f"{CAMERA_FIELD}_{k}", "string", f"camera model as JSON, part {k} (continues field camera)")
            for k in range(2, n_parts + 1)]


def split_camera(text: str, max_chars: int) -> list[str]:
    """``text`` in parts of at most ``max_chars`` characters, for ``camera``, ``camera_2``, …"""
    return [text[i:i + max_chars] for i in range(0, len(text), max_chars)] or [text]


def split_cameras(records, max_chars: int) -> tuple[list[tuple[str, str, str]], list[dict]]:
    """Frame records for text fields of ``max_chars`` characters: the fields their cameras need after the
    frame-layer fields (none when every camera fits) and the records with ``camera``, ``camera_2``, … set."""
    records = list(records)
    parts = [split_camera(r[CAMERA_FIELD] or "", max_chars) for r in records]
    extra = camera_part_fields(max((len(p) for p in parts), default=1))
    names = [CAMERA_FIELD] + [f[0] for f in extra]
    return extra, [{**r, **dict(zip(names, p))} for r, p in zip(records, parts)]


def join_camera(parts) -> str:
    """A frame's camera model from its parts (``camera``, ``camera_2``, …; empty ones skipped)."""
    return "".join(p for p in parts if p)


def camera_cut_at(parts, field_lengths) -> int | None:
    """The field length (characters) at which a camera model was cut, or None.

    A format with short text fields cuts a longer value without a word (QGIS's Save Features As… to an ESRI
    Shapefile keeps 254 characters): the camera was cut when its parts do not join into JSON and one of them
    fills its field. ``field_lengths``: each part's field length, 0 where the format sets none.
    """
    try:
        json.loads(join_camera(parts))
        return None
    except ValueError:
        return next((n for p, n in zip(parts, field_lengths) if n > 0 and p and len(p) >= n), None)


def euler_degrees(quat) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(roll, pitch, yaw) in degrees of body → NED quaternions (N, 4), the frame layer's attitude fields.

    ZYX (yaw, pitch, roll), except for a body looking more than 45° down (a gimbal camera): there the
    gimbal's own order, yaw, roll, pitch (``Rz(yaw)·Rx(roll)·Ry(pitch)``, DJI's motor order; the two agree
    whenever roll is 0). ZYX is singular at pitch −90°: a nadir camera refined half a degree off the vertical
    would read yaw 4°, roll 40° for a heading of 44°, the split set by the direction of that half degree.
    The gimbal order keeps the heading in yaw and is singular only at roll ±90°.
    """
    r = quat_to_rotmat(quat)
    roll, pitch, yaw = rotmat_to_euler_zyx(r)
    down = r[..., 2, 0] > np.sqrt(0.5)
    roll = np.where(down, np.arcsin(np.clip(r[..., 2, 1], -1.0, 1.0)), roll)
    pitch = np.where(down, np.arctan2(-r[..., 2, 0], r[..., 2, 2]), pitch)
    yaw = np.where(down, np.arctan2(-r[..., 0, 1], r[..., 1, 1]), yaw)
    return np.degrees(roll), np.degrees(pitch), np.degrees(yaw) % 360.0


#: Frames of a camera solution whose heights are ellipsoidal: labels use the geotags' surveyed heights.
GEOTAG_HEIGHTS_FLAG = "geotag_heights"


def uses_geotag_heights(records, indices) -> bool:
    """Whether the frames ``records[indices]`` all carry :data:`GEOTAG_HEIGHTS_FLAG`."""
    return all(GEOTAG_HEIGHTS_FLAG in (records[i].get("flags") or "").split(",") for i in indices)


def poses_from_records(records, source: str = "frame layer") -> list[tuple[FramePoses, np.ndarray]]:
    """Frame poses from frame-layer records (mappings with :data:`FRAME_FIELD_NAMES`).

    Frames are grouped by camera model; returns ``[(poses, record_indices), ...]`` where
    ``record_indices`` say which input records each group holds, in input order.
    """
    records = list(records)
    if not records:
        raise InputError("has no frames", source=source)
    missing = [n for n in ("frame_id", "lat", "lon", "height_m", "qw", "qx", "qy", "qz", "ground_h_m",
                           "camera") if n not in records[0]]
    if missing:
        raise InputError(f"is not a BirdsEye frame layer: missing field(s) {', '.join(missing)} (make it with "
                         "Import flight log, Import drone images or Import camera solution)", source=source)
    cameras = [rec["camera"] for rec in records]
    empty = next((i for i, cam in enumerate(cameras) if not cam), None)
    if empty is not None:
        raise InputError("is empty; the frame has no camera model", source=source, row=empty + 1, field="camera")
    reference = flight_reference(records, source)
    ground_source = [_ground_source(rec, row, source) for row, rec in enumerate(records, start=1)]
    out = []
    for idx in indices_by_camera(cameras):
        camera = CameraModel.from_json(cameras[idx[0]], source=f"{source}, row {idx[0] + 1}, field 'camera'")
        try:
            cols = {n: np.array([_number(records[i][n]) for i in idx], dtype=float)
                    for n in ("lat", "lon", "height_m", "qw", "qx", "qy", "qz", "ground_h_m")}
        except (TypeError, ValueError) as exc:
            raise InputError(f"has a non-numeric pose value ({exc})", source=source) from exc
        for n, values in cols.items():
            if n != "ground_h_m" and not np.all(np.isfinite(values)):
                row = int(idx[np.flatnonzero(~np.isfinite(values))[0]]) + 1
                raise InputError("is empty or not a number", source=source, row=row, field=n)
        quat = np.stack([cols["qw"], cols["qx"], cols["qy"], cols["qz"]], axis=1)
        poses = FramePoses(np.array([records[i]["frame_id"] for i in idx]), cols["lat"], cols["lon"],
                           cols["height_m"], quat, cols["ground_h_m"], camera, reference,
                           [ground_source[i] for i in idx])
        out.append((poses, idx))
    return out


def flight_reference(records, source: str = "frame layer") -> VerticalReference:
    """What the frames' heights are measured from (field ``height_ref``). A layer written before the field
    existed reads as ellipsoidal, as it always was; one that mixes references is refused: a DEM or a geotag
    height can be converted into one reference, and a flight's frames are compared with each other."""
    if not records or "height_ref" not in records[0]:
        return ELLIPSOIDAL_REFERENCE
    found: dict = {}
    for row, rec in enumerate(records, start=1):
        found.setdefault(VerticalReference.parse(rec.get("height_ref"), source, row, "height_ref"), []).append(row)
    if len(found) > 1:
        listed = "; ".join(f"{ref.describe()} (rows {', '.join(map(str, rows[:3]))}{' …' if len(rows) > 3 else ''})"
                           for ref, rows in found.items())
        raise InputError(f"mixes vertical references: {listed}. Import each flight into its own frame layer, or "
                         "import them again so they state one reference", source=source, field="height_ref")
    return next(iter(found))


def _ground_source(record, row: int, source: str) -> str:
    """A frame's ground source (field ``ground_src``; a layer without it: the altimeter, as it always was)."""
    if "ground_src" not in record:
        return ALTIMETER
    return parse_ground_source(record.get("ground_src"), source, row, "ground_src")


def local_frame_around(groups, lat=(), lon=()):
    """The local ENU frame of camera groups (:func:`poses_from_records`) and the points ``lat``/``lon``
    beside them: every step that projects into those frames works in the same one."""
    return LocalFrame.around(np.concatenate([p.lat for p, _ in groups] + [np.asarray(lat, dtype=float)]),
                             np.concatenate([p.lon for p, _ in groups] + [np.asarray(lon, dtype=float)]),
                             np.concatenate([p.height for p, _ in groups]))


def _number(value) -> float:
    if value is None or value == "":
        return float("nan")
    return float(value)


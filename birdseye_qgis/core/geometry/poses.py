"""Frame poses and the per-frame camera geometry derived from them.

A :class:`FramePoses` is what a frame layer carries (docs/design.md#frame-layer): the IMU/body position in WGS84
(lat, lon, height), the attitude quaternion ``q = (qw, qx, qy, qz)`` with ``v_ned = R(q) v_body`` (body =
forward-right-down = the IMU frame of ``T_cam_imu``), the height of the level ground under the frame (NaN
when none is known; a DEM then supplies the ground), what the heights are measured from and where each
ground height came from (``heights.VerticalReference``, ``heights.GROUND_SOURCES``).

The geometry treats the heights as ellipsoidal: a flight in another reference (DJI's mean-sea-level
heights) is shifted by N along the vertical as a whole, which moves nothing in the image as long as every
height it is compared with is in the same reference: the level ground is its own, geotags are placed on the
ground the frame sees, and a DEM is converted into the flight's reference (``dem.check_vertical_datum``).

:class:`FrameGeometry` turns these into camera centres and orientations in a
:class:`~.geodesy.LocalFrame`, vectorised over frames.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .camera import CameraModel
from .geodesy import LocalFrame
from .heights import ALTIMETER, ELLIPSOIDAL_REFERENCE, VerticalReference
from .rigid import RigidTransform
from .rotations import quat_to_rotmat


@dataclass
class FramePoses:
    """Poses of F frames taken by one camera. Arrays have length F.

    ``reference``: what ``height`` and ``ground_height`` are measured from (default ellipsoidal, an RTK/INS
    flight's); ``ground_source``: per frame, where its ground height came from (default: the altimeter).
    """

    frame_id: np.ndarray
    lat: np.ndarray
    lon: np.ndarray
    height: np.ndarray
    quat: np.ndarray
    ground_height: np.ndarray
    camera: CameraModel
    reference: VerticalReference = ELLIPSOIDAL_REFERENCE
    ground_source: np.ndarray | None = None

    def __post_init__(self):
        self.frame_id = np.asarray(self.frame_id)
        for name in ("lat", "lon", "height", "ground_height"):
            setattr(self, name, np.asarray(getattr(self, name), dtype=float).reshape(-1))
        self.quat = np.asarray(self.quat, dtype=float).reshape(-1, 4)
        n = len(self.lat)
        self.ground_source = np.asarray([ALTIMETER] * n if self.ground_source is None else self.ground_source,
                                        dtype=object).reshape(-1)
        for name in ("frame_id", "lon", "height", "quat", "ground_height", "ground_source"):
            if len(getattr(self, name)) != n:
                raise ValueError(f"FramePoses.{name} has {len(getattr(self, name))} entries, expected {n}")

    def __len__(self) -> int:
        return len(self.lat)

    def subset(self, index) -> "FramePoses":
        return FramePoses(self.frame_id[index], self.lat[index], self.lon[index], self.height[index],
                          self.quat[index], self.ground_height[index], self.camera, self.reference,
                          self.ground_source[index])


def indices_by_camera(cameras) -> list[np.ndarray]:
    """The frames of each camera, for per-frame ``cameras``: index arrays in order of first appearance.

    Frames whose cameras are equal form one group, whether the cameras are :class:`CameraModel` objects
    (equal when their JSON is) or a frame layer's camera JSON strings; frames of one camera usually share the
    object, so each object is compared once rather than each frame.
    """
    by_object: dict[int, list[int]] = {}
    by_camera: dict = {}
    for i, camera in enumerate(cameras):
        members = by_object.get(id(camera))
        if members is None:
            members = by_object[id(camera)] = by_camera.setdefault(camera, [])
        members.append(i)
    return [np.asarray(members) for members in by_camera.values()]


def ground_height_from_altimeter(height, quat, radalt, t_imu_rad=None) -> np.ndarray:
    """Ellipsoidal height of the level ground: ``h_rad − radalt·cos(roll)·cos(pitch)``.

    The radar ranges along the body z axis; ``cos(roll)·cos(pitch)`` is the vertical component of
    that axis, i.e. element (2, 2) of R(q). ``t_imu_rad`` is the altimeter position in the body frame
    (metres); its vertical offset in NED is applied to the IMU height first.
    """
    r = quat_to_rotmat(quat)
    return _altimeter_height(height, r, t_imu_rad) - np.asarray(radalt, dtype=float) * r[..., 2, 2]


def altimeter_range(height, quat, ground_height, t_imu_rad=None) -> np.ndarray:
    """The altimeter's raw range along body z to the level ground: ``ground_height_from_altimeter`` undone.

    ``(h_rad − ground_h) / cos(roll)·cos(pitch)``; infinite or negative where body z is horizontal or
    points up (no radar looks there).
    """
    r = quat_to_rotmat(quat)
    with np.errstate(divide="ignore", invalid="ignore"):
        return (_altimeter_height(height, r, t_imu_rad) - np.asarray(ground_height, dtype=float)) / r[..., 2, 2]


def _altimeter_height(height, r_ned_body, t_imu_rad) -> np.ndarray:
    """Ellipsoidal height of the altimeter: the IMU height moved by the lever arm ``t_imu_rad`` (body, m)."""
    h_rad = np.asarray(height, dtype=float)
    if t_imu_rad is not None:
        h_rad = h_rad - (r_ned_body @ np.asarray(t_imu_rad, dtype=float))[..., 2]
    return h_rad


class FrameGeometry:
    """Camera centres and camera→local rotations of F frames in a local metric frame.

    ``R_local_cam[f] @ X_cam + C[f]`` maps camera-frame points of frame f into the local frame.
    """

    def __init__(self, poses: FramePoses, local: LocalFrame):
        self.poses = poses
        self.local = local
        self.camera = poses.camera
        self.imu_position = local.from_geodetic(poses.lat, poses.lon, poses.height)
        self.up = local.up_at(poses.lat, poses.lon)
        self.R_local_body = local.rotation_from_ned(poses.lat, poses.lon) @ quat_to_rotmat(poses.quat)
        local_from_body = RigidTransform(self.R_local_body, self.imu_position)
        local_from_cam = local_from_body @ RigidTransform.from_matrix(self.camera.T_imu_cam)
        self.R_local_cam = local_from_cam.rotation
        self.C = local_from_cam.translation
        # Level ground under each frame: normal to the ellipsoid at the IMU, at the ground height.
        self.ground_point = self.imu_position - (poses.height - poses.ground_height)[:, None] * self.up

    def __len__(self) -> int:
        return len(self.C)

    def to_camera(self, frame_idx: np.ndarray, points: np.ndarray) -> np.ndarray:
        """Camera-frame coordinates (N, 3) of local points (N, 3), one frame index per point."""
        d = np.asarray(points, dtype=float) - self.C[frame_idx]
        return np.einsum("nji,nj->ni", self.R_local_cam[frame_idx], d)

    def rays(self, frame_idx: np.ndarray, uv: np.ndarray) -> np.ndarray:
        """Local-frame ray directions (N, 3) (not unit length) through pixels uv (N, 2)."""
        d_cam = self.camera.pixel_rays(uv)
        return np.einsum("nij,nj->ni", self.R_local_cam[frame_idx], d_cam)

    def depth_below(self) -> np.ndarray:
        """Vertical distance (m) from each camera centre down to its level ground."""
        return np.einsum("fi,fi->f", self.C - self.ground_point, self.up)

    def gsd_m(self) -> np.ndarray:
        """Ground sample distance (m/px) at the image centre over the level ground."""
        return self.depth_below() / np.sqrt(self.camera.fx * self.camera.fy)


def body_pose_from_camera(local: LocalFrame, centre: np.ndarray, r_local_cam: np.ndarray, camera: CameraModel):
    """The frame-layer pose (lat, lon, h of the IMU/body, body → NED quaternion) of cameras whose centres
    (F, 3) and camera → local rotations (F, 3, 3) are known: :class:`FrameGeometry` run backwards."""
    from .rotations import rotmat_to_quat

    local_from_body = RigidTransform(r_local_cam, centre) @ RigidTransform.from_matrix(camera.T_cam_imu)
    lat, lon, h = (np.atleast_1d(np.asarray(a, dtype=float)) for a in local.to_geodetic(local_from_body.translation))
    r_ned_body = np.swapaxes(local.rotation_from_ned(lat, lon), -1, -2) @ local_from_body.rotation
    return lat, lon, h, rotmat_to_quat(r_ned_body)

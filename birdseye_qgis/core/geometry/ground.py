"""Ground models behind one interface.

A ground model answers two questions for a frame:

* :meth:`GroundModel.intersect` — where does a viewing ray from the camera meet the ground?
  (pixel → ground back-projection, footprints)
* :meth:`GroundModel.place` — where is the ground under a surveyed point? (world → pixel uses the
  ground the frame sees, not the rover's antenna height, so RTK height offsets between rover and
  drone do not move labels.)

:class:`LevelPlaneGround` (the default): per frame, a plane normal to the ellipsoid at the
tilt-corrected altimeter depth. :class:`MethodPlaneGround`: the method's own plane, normal to the
optical axis at the raw altimeter range, kept to reproduce its figures. A DEM model implements the
same methods.
"""
from __future__ import annotations

import numpy as np

from ..errors import InputError
from .poses import FrameGeometry, altimeter_range

#: Largest angle (degrees) between the altimeter's axis (body z) and the vertical for which a frame's
#: ground height is taken to come from a radar range. DJI frames, whose "body" is the gimbal (z = image
#: down, horizontal when the camera looks down), are far beyond it.
METHOD_PLANE_MAX_AXIS_TILT_DEG = 45.0


class GroundModel:
    """Interface: ``intersect`` rays and ``place`` points, one frame index per ray/point.

    ``needs_ground_height``: the model stands on each frame's ground height (``FramePoses.ground_height``),
    so frames without one cannot be placed; a terrain model does not. Ground-model factories (a model
    class, or :class:`~.dem.DemGroundFactory`) carry it too: :func:`needs_ground_height` asks them.
    """

    needs_ground_height = True

    def intersect(self, frame_idx, origins, directions):
        """Points (N, 3) where rays hit the ground, and a validity mask (N,) (False: missed)."""
        raise NotImplementedError

    def place(self, frame_idx, points):
        """Points (N, 3) moved along the local vertical onto the ground seen by their frame."""
        raise NotImplementedError

    def occluded(self, frame_idx, points) -> np.ndarray:
        """True where the ground hides a ground point (N, 3) from its frame's camera; a plane hides nothing."""
        return np.zeros(len(np.asarray(points).reshape(-1, 3)), dtype=bool)


def needs_ground_height(ground) -> bool:
    """Whether the ground-model factory ``ground`` (``FrameGeometry -> GroundModel``; None = the level
    plane) needs each frame's ground height: frames without one are then left out (not processed by
    Detect, not counted in view), while a DEM places them."""
    return getattr(ground or LevelPlaneGround, "needs_ground_height", True)


def placeable_frames(poses, ground) -> np.ndarray:
    """Mask (F,) of the frames of ``poses`` (:class:`~.poses.FramePoses`) the ground-model factory ``ground``
    can place points on: those with a ground height, or all when it needs none (a DEM)."""
    return np.isfinite(poses.ground_height) | (not needs_ground_height(ground))


class LevelPlaneGround(GroundModel):
    """A level plane per frame: through ``geometry.ground_point[f]`` with normal ``geometry.up[f]``."""

    def __init__(self, geometry: FrameGeometry):
        if not np.all(np.isfinite(geometry.ground_point)):
            bad = np.flatnonzero(~np.all(np.isfinite(geometry.ground_point), axis=1))
            ids = ", ".join(str(geometry.poses.frame_id[i]) for i in bad[:5])
            raise ValueError(f"{len(bad)} frame(s) have no ground height (no altimeter reading): {ids}")
        self.point = geometry.ground_point
        self.normal = geometry.up

    def intersect(self, frame_idx, origins, directions):
        n = self.normal[frame_idx]
        denom = np.einsum("ni,ni->n", n, directions)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.einsum("ni,ni->n", n, self.point[frame_idx] - origins) / denom
        valid = np.isfinite(t) & (t > 0)
        pts = origins + np.where(valid, t, np.nan)[:, None] * directions
        return pts, valid

    def place(self, frame_idx, points):
        n = self.normal[frame_idx]
        offset = np.einsum("ni,ni->n", n, points - self.point[frame_idx])
        return points - offset[:, None] * n


class MethodPlaneGround(GroundModel):
    """The method's ground: per frame, the plane normal to the optical axis at the raw altimeter range.

    The method gives every pixel the same depth ``r`` along the optical axis, ``r`` the altimeter's
    reading without the tilt correction, so its ground is ``{X : a·(X − C) = r}`` with ``a`` the
    optical axis and ``C`` the camera centre (local frame). ``r`` is recovered from the frame's level
    ground height (``poses.altimeter_range``). Over level ground with the camera tilted by α, this plane
    is tilted by α against the true ground, through about the point where the optical axis meets it:
    a label at distance ρ·depth from there moves by about ``f·ρ²·tan α`` px against
    :class:`LevelPlaneGround`. ``place`` moves points along the local vertical, as the level plane does.

    Frames without a ground height, or whose body z axis is more than
    ``METHOD_PLANE_MAX_AXIS_TILT_DEG`` from the vertical (no radar range), are refused with their ids.
    """

    def __init__(self, geometry: FrameGeometry):
        poses = geometry.poses
        _refuse(poses.frame_id, ~np.isfinite(poses.ground_height),
                "have no ground height (no usable altimeter reading, flag no_ground_height), which the "
                "method's plane is measured from: leave them out of the frame layer or use the level ground")
        down_cosine = -np.einsum("fi,fi->f", geometry.R_local_body[:, :, 2], geometry.up)
        axis_tilt = np.degrees(np.arccos(np.clip(down_cosine, -1.0, 1.0)))
        _refuse(poses.frame_id, axis_tilt > METHOD_PLANE_MAX_AXIS_TILT_DEG,
                f"have their altimeter axis (body z) more than {METHOD_PLANE_MAX_AXIS_TILT_DEG:g}° from the "
                f"vertical (up to {np.max(axis_tilt):.0f}°), so there is no radar range to build the method's "
                "plane from (DJI frames carry the gimbal's attitude and no radar): use the level ground")
        self.range_m = altimeter_range(poses.height, poses.quat, poses.ground_height, poses.camera.t_imu_rad)
        self.centre = geometry.C
        self.axis = geometry.R_local_cam[:, :, 2]
        self.up = geometry.up

    def intersect(self, frame_idx, origins, directions):
        a = self.axis[frame_idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            t = (self.range_m[frame_idx] - np.einsum("ni,ni->n", a, origins - self.centre[frame_idx])) / np.einsum(
                "ni,ni->n", a, directions)
        valid = np.isfinite(t) & (t > 0)
        return origins + np.where(valid, t, np.nan)[:, None] * directions, valid

    def place(self, frame_idx, points):
        a, up = self.axis[frame_idx], self.up[frame_idx]
        with np.errstate(divide="ignore", invalid="ignore"):
            s = (self.range_m[frame_idx] - np.einsum("ni,ni->n", a, points - self.centre[frame_idx])) / np.einsum(
                "ni,ni->n", a, up)
        return points + s[:, None] * up


def _refuse(frame_id, bad, why: str) -> None:
    if np.any(bad):
        ids = ", ".join(str(i) for i in np.asarray(frame_id)[bad][:5])
        raise InputError(f"{int(np.count_nonzero(bad))} frame(s) (first: {ids}) {why}", field="GROUND_MODEL")

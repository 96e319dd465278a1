"""Ground models behind one interface.

A ground model answers two questions for a frame:

* :meth:`GroundModel.intersect` — where does a viewing ray from the camera meet the ground?
  (pixel → ground back-projection, footprints)
* :meth:`GroundModel.place` — where is the ground under a surveyed point? (world → pixel uses the
  ground the frame sees, not the rover's antenna height, so RTK height offsets between rover and
  drone do not move labels.)

:class:`LevelPlaneGround` is the method's model: per frame, a plane normal to the ellipsoid at the
tilt-corrected altimeter depth. A DEM model implements the same methods.
"""
from __future__ import annotations

import numpy as np

from .poses import FrameGeometry


class GroundModel:
    """Interface: ``intersect`` rays and ``place`` points, one frame index per ray/point."""

    def intersect(self, frame_idx, origins, directions):
        """Points (N, 3) where rays hit the ground, and a validity mask (N,) (False: missed)."""
        raise NotImplementedError

    def place(self, frame_idx, points):
        """Points (N, 3) moved along the local vertical onto the ground seen by their frame."""
        raise NotImplementedError


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

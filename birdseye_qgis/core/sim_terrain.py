"""The simulated world's ground surface: where a viewing ray meets the terrain.

This is the *truth* the simulator renders and measures with its radar altimeter, not the ground model
the labelling uses (that is :mod:`.ground`, estimated from the logged altimeter): keeping the two apart
is what lets a campaign show the error a level-plane assumption makes over real terrain.

Coordinates are the site's :class:`~.geodesy.LocalFrame` (east, north, up; metres). A terrain
implements :meth:`Terrain.height_at` (ellipsoidal height under a local point), :meth:`Terrain.intersect`
(rays with their own origins, e.g. the altimeter beam) and :meth:`Terrain.intersect_grid` (one camera's
whole pixel grid, the renderer's hot path). A DEM terrain (ray marching + refinement) can replace
:class:`FlatTerrain` behind these three methods.
"""
from __future__ import annotations

import numpy as np

from .geodesy import LocalFrame


class Terrain:
    """Interface of the simulated ground surface (local frame, metres)."""

    def height_at(self, east, north) -> np.ndarray:
        """Ellipsoidal height (m) of the ground under local horizontal positions."""
        raise NotImplementedError

    def intersect(self, origins, directions) -> np.ndarray:
        """Ray parameters t (N,) with ``origins + t·directions`` on the ground (NaN: no hit)."""
        raise NotImplementedError

    def intersect_grid(self, centre, r_local_cam, xn, yn):
        """Local east, north (float32 arrays shaped like ``xn``) where the camera's pixel rays meet the
        ground. ``centre`` is the camera centre (3,), ``r_local_cam`` its camera→local rotation, and
        ``(xn, yn, 1)`` the camera-frame ray of each pixel (ideal normalised coordinates)."""
        raise NotImplementedError


class FlatTerrain(Terrain):
    """The surface of constant ellipsoidal height ``height_m`` (a level field).

    Each query uses the plane tangent to that surface under the ray origin (normal = the ellipsoid
    normal there); the surface departs from that plane by d²/2R, under 10 µm within a 10 m footprint.
    """

    def __init__(self, local: LocalFrame, height_m: float):
        self.local = local
        self.height_m = float(height_m)

    def height_at(self, east, north) -> np.ndarray:
        return np.full(np.shape(east), self.height_m)

    def _tangent_planes(self, origins):
        """Point on the ground under each origin and the surface normal there, both (N, 3)."""
        lat, lon, _ = self.local.to_geodetic(origins)
        lat, lon = np.atleast_1d(lat), np.atleast_1d(lon)
        point = self.local.from_geodetic(lat, lon, np.full(lat.shape, self.height_m)).reshape(-1, 3)
        return point, self.local.up_at(lat, lon).reshape(-1, 3)

    def intersect(self, origins, directions) -> np.ndarray:
        origins = np.asarray(origins, dtype=float).reshape(-1, 3)
        directions = np.asarray(directions, dtype=float).reshape(-1, 3)
        point, normal = self._tangent_planes(origins)
        denom = np.einsum("ni,ni->n", normal, directions)
        with np.errstate(divide="ignore", invalid="ignore"):
            t = np.einsum("ni,ni->n", normal, point - origins) / denom
        return np.where(np.isfinite(t) & (t > 0), t, np.nan)

    def intersect_grid(self, centre, r_local_cam, xn, yn):
        centre = np.asarray(centre, dtype=float)
        point, normal = self._tangent_planes(centre[None])
        point, normal = point[0], normal[0]
        # Ray d = R (xn, yn, 1); hit = C + t d with t = n·(P − C) / n·d. Folding R into the three
        # dot products keeps the per-pixel work at a homography (float32 is ample: the offsets from
        # the camera centre are metres, the rounding micrometres).
        r = np.asarray(r_local_cam, dtype=float)
        m = r.T @ normal
        height = float(normal @ (point - centre))
        denom = xn * np.float32(m[0]) + yn * np.float32(m[1]) + np.float32(m[2])
        with np.errstate(divide="ignore", invalid="ignore"):
            scale = np.float32(height) / denom
        scale[~(scale > 0)] = np.nan
        east = (xn * np.float32(r[0, 0]) + yn * np.float32(r[0, 1]) + np.float32(r[0, 2])) * scale
        north = (xn * np.float32(r[1, 0]) + yn * np.float32(r[1, 1]) + np.float32(r[1, 2])) * scale
        east += np.float32(centre[0])
        north += np.float32(centre[1])
        return east, north

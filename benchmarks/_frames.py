"""Random nadir frames over a square field, for benchmarks at the method's campaign scale."""
import _path  # noqa: F401
import numpy as np

from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.poses import FramePoses
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat
from birdseye.birdseye_qgis.core.sim.campaign import deployed_camera

SITE = (-27.55, 151.95, 400.0)


def random_frames(rng, n_frames, extent_m, height_m=(9.0, 11.0), tilt_sd_deg=2.0):
    """(poses, local): the deployed camera at random positions, heights and headings over level ground."""
    local = LocalFrame(*SITE)
    enu = np.column_stack([rng.uniform(0, extent_m[0], n_frames), rng.uniform(0, extent_m[1], n_frames),
                           rng.uniform(*height_m, n_frames)])
    lat, lon, h = local.to_geodetic(enu)
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians(rng.normal(0, tilt_sd_deg, n_frames)),
                                           np.radians(rng.normal(0, tilt_sd_deg, n_frames)),
                                           np.radians(rng.uniform(0, 360, n_frames))))
    return FramePoses(np.arange(n_frames), lat, lon, h, q, np.full(n_frames, SITE[2]), deployed_camera()), local


def random_ground_points(rng, local, n_points, extent_m, height_sd_m=0.0):
    """WGS84 (lat, lon, h) of points spread over the field."""
    pts = np.column_stack([rng.uniform(0, extent_m[0], n_points), rng.uniform(0, extent_m[1], n_points),
                           rng.normal(0, height_sd_m, n_points) if height_sd_m else np.zeros(n_points)])
    return local.to_geodetic(pts)

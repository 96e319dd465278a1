"""The method's ground plane (normal to the optical axis at the raw altimeter range) against closed forms."""
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry import geodesy
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround, MethodPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import (
    FrameGeometry,
    FramePoses,
    altimeter_range,
    ground_height_from_altimeter,
)
from birdseye.birdseye_qgis.core.geometry.projection import pixel_to_ground, project_pairs
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat

# Nadir mounting: camera x = body right, camera y = −body forward (image top = forward), z = body down.
NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
LOCAL = geodesy.LocalFrame(-27.55, 151.95, 400.0)
FX, FY, CX, CY = 4264.4945, 4262.8927, 958.4594, 592.5033


def camera(lever=(0.0, 0.0, 0.0), radar=None):
    t = np.eye(4)
    t[:3, :3] = NADIR
    t[:3, 3] = -NADIR @ np.asarray(lever)
    return CameraModel(1920, 1200, FX, FY, CX, CY, (0.0,) * 5, t, radar)


def frame(cam, roll, pitch, yaw, radalt, east=0.0, north=0.0, agl=None):
    """One frame whose ground height comes from the altimeter reading ``radalt`` (m, along body z)."""
    q = rotmat_to_quat(euler_zyx_to_rotmat(*np.radians([roll, pitch, yaw])))[None]
    height = radalt if agl is None else agl
    lat, lon, h = LOCAL.to_geodetic(np.array([[east, north, 400.0 + height]]))
    ground = ground_height_from_altimeter(h, q, [radalt], cam.t_imu_rad)
    return FrameGeometry(FramePoses(np.array([11]), lat, lon, h, q, ground, cam), LOCAL)


def test_the_plane_lies_at_the_raw_range_along_the_optical_axis():
    cam = camera(lever=(0.10, -0.04, 0.06), radar=(-0.12, 0.03, 0.09))
    radalt = 12.3
    geom = frame(cam, roll=4.0, pitch=-2.5, yaw=130.0, radalt=radalt, east=35.0, north=-80.0, agl=12.0)
    ground = MethodPlaneGround(geom)
    # The raw reading comes back from the tilt-corrected ground height.
    assert ground.range_m == pytest.approx([radalt], rel=1e-12)
    assert altimeter_range(geom.poses.height, geom.poses.quat, geom.poses.ground_height,
                           cam.t_imu_rad) == pytest.approx([radalt], rel=1e-12)
    # Every pixel's ray meets it at depth r along the optical axis (camera z), corners included.
    u, v = np.meshgrid(np.linspace(-0.5, 1919.5, 9), np.linspace(-0.5, 1199.5, 7))
    uv = np.column_stack([u.ravel(), v.ravel()])
    frames = np.zeros(len(uv), int)
    points, valid = pixel_to_ground(geom, ground, frames, uv)
    assert valid.all()
    np.testing.assert_allclose(geom.to_camera(frames, points)[:, 2], radalt, rtol=1e-12)
    np.testing.assert_allclose(project_pairs(geom, frames, points).uv, uv, atol=1e-6)
    # place() moves points along the local vertical onto the same plane.
    rng = np.random.default_rng(3)
    scattered = points + rng.uniform(-2.0, 2.0, points.shape)
    placed = ground.place(frames, scattered)
    np.testing.assert_allclose(geom.to_camera(frames, placed)[:, 2], radalt, rtol=1e-12)
    moved = placed - scattered
    np.testing.assert_allclose(moved - np.einsum("ni,ni->n", moved, geom.up[frames])[:, None] * geom.up[frames],
                               0.0, atol=1e-9)


def method_shift_px(focal, normalised, tilt_rad):
    """Closed form, in the vertical plane through the optical axis: the axis tilted by α towards +x,
    a ground point seen at normalised x = tan θ on level ground (true depth along the axis varies),
    placed vertically onto the plane z_cam = r = h / cos α, is seen at x' = tan(θ + α) − tan α;
    the label moves by f (x' − x) px."""
    theta = math.atan(normalised)
    return focal * (math.tan(theta + tilt_rad) - math.tan(tilt_rad) - normalised)


@pytest.mark.parametrize("roll, pitch", [(3.0, 0.0), (0.0, 3.0), (-3.0, 0.0)])
def test_against_the_level_plane_at_3_degrees_of_tilt(roll, pitch):
    """A target on level ground, labelled through each ground model, at the frame's edge midpoints.
    Positive roll tilts the optical axis towards −camera x (the left wing), positive pitch towards
    body forward = −camera y."""
    cam = camera()
    geom = frame(cam, roll=roll, pitch=pitch, yaw=30.0, radalt=10.0 / math.cos(math.radians(3.0)))
    level, method = LevelPlaneGround(geom), MethodPlaneGround(geom)
    edges = np.array([(0.0, CY), (1919.0, CY), (CX, 0.0), (CX, 1199.0)])
    corners = np.array([(0.0, 0.0), (1919.0, 0.0), (0.0, 1199.0), (1919.0, 1199.0)])
    frames = np.zeros(len(edges) + len(corners), int)
    targets, _ = pixel_to_ground(geom, level, frames, np.vstack([edges, corners]))  # the true ground here
    np.testing.assert_allclose(project_pairs(geom, frames, targets, level).uv, np.vstack([edges, corners]), atol=1e-6)
    shift = project_pairs(geom, frames, targets, method).uv - np.vstack([edges, corners])
    shift, corner_shift = shift[:4], np.hypot(*shift[4:].T)
    along_u = [method_shift_px(FX, (u - CX) / FX, -math.radians(roll)) for u in edges[:2, 0]]
    along_v = [method_shift_px(FY, (v - CY) / FY, -math.radians(pitch)) for v in edges[2:, 1]]
    np.testing.assert_allclose(shift[:2, 0], along_u, atol=1e-6)
    np.testing.assert_allclose(shift[2:, 1], along_v, atol=1e-6)
    np.testing.assert_allclose([shift[:2, 1], shift[2:, 0]], 0.0, atol=1e-6)
    # The figures the help states for the deployed camera (any altitude): 3° of roll moves the left and
    # right edge labels by 14.1 and 8.6 px and the corner ones by 11–16 px, 3° of pitch the top and
    # bottom ones by 6.0 and 2.8 px and the corner ones by 8–9 px.
    stated = {(3.0, 0.0): [14.1, 8.6, 0.0, 0.0], (-3.0, 0.0): [8.6, 14.1, 0.0, 0.0], (0.0, 3.0): [0.0, 0.0, 6.0, 2.8]}
    assert np.round(np.hypot(*shift.T), 1).tolist() == stated[(roll, pitch)]
    corners_stated = {(3.0, 0.0): (11, 16), (-3.0, 0.0): (11, 16), (0.0, 3.0): (8, 9)}
    assert (round(corner_shift.min()), round(corner_shift.max())) == corners_stated[(roll, pitch)]


def test_frames_without_a_radar_range_are_refused_with_their_ids():
    cam = camera()
    geom = frame(cam, roll=0.0, pitch=0.0, yaw=0.0, radalt=10.0)
    geom.poses.ground_height[:] = np.nan
    with pytest.raises(InputError, match=r"1 frame\(s\) \(first: 11\) have no ground height"):
        MethodPlaneGround(geom)
    # A DJI-like frame: the "body" is the gimbal, whose z axis (image down) is horizontal at nadir.
    gimbal = frame(cam, roll=0.0, pitch=-90.0, yaw=0.0, radalt=10.0, agl=10.0)
    with pytest.raises(InputError, match="GROUND_MODEL.*altimeter axis.*90°"):
        MethodPlaneGround(gimbal)

"""World ↔ pixel for frames × points: independent formulations, conventions, round trips."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.geometry import geodesy
from birdseye.birdseye_qgis.core.geometry.camera import CameraModel
from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame
from birdseye.birdseye_qgis.core.geometry.ground import LevelPlaneGround
from birdseye.birdseye_qgis.core.geometry.poses import FrameGeometry, FramePoses, ground_height_from_altimeter
from birdseye.birdseye_qgis.core.geometry.projection import (
    candidate_pairs,
    footprints,
    pixel_to_ground,
    project_all,
    project_in_view,
    project_pairs,
)
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, rotmat_to_quat, so3_exp

# Nadir mounting: camera x = body right, camera y = −body forward (image top = forward), z = body down.
NADIR = np.array([[0.0, 1.0, 0.0], [-1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
SITE = (-27.55, 151.95, 400.0)


def make_camera(lever=(0.0, 0.0, 0.0), dist=(-0.08, 0.12, 4e-4, -3e-4, 0.01)):
    t = np.eye(4)
    t[:3, :3] = NADIR
    t[:3, 3] = -NADIR @ np.asarray(lever)  # camera centre at `lever` in the body frame
    return CameraModel(1920, 1200, 4264.4945, 4262.8927, 958.4594, 592.5033, dist, t)


def make_poses(camera, roll=0.0, pitch=0.0, yaw=0.0, north=0.0, east=0.0, agl=10.0, lat0=SITE[0],
               lon0=SITE[1], ground=SITE[2]):
    """Frames at a metric offset from a site, attitudes in degrees, ground level at `ground`."""
    roll, pitch, yaw, north, east, agl = np.broadcast_arrays(*(np.atleast_1d(np.asarray(a, float)) for a in
                                                               (roll, pitch, yaw, north, east, agl)))
    local = geodesy.LocalFrame(lat0, lon0, ground)
    lat, lon, h = local.to_geodetic(np.column_stack([east, north, agl]))
    q = rotmat_to_quat(euler_zyx_to_rotmat(*np.radians([roll, pitch, yaw])))
    gh = np.full(len(lat), ground)
    return FramePoses(np.arange(len(lat)), lat, lon, h, q, gh, camera), local


def geometry(camera, **kw):
    poses, local = make_poses(camera, **kw)
    return FrameGeometry(poses, local), local


def test_projection_agrees_with_an_independent_ecef_and_opencv_chain():
    import cv2
    cam = make_camera(lever=(0.12, -0.05, 0.08))
    poses, local = make_poses(cam, roll=[3.0, -7.0], pitch=[-2.0, 5.0], yaw=[37.0, 211.0],
                              north=[250.0, -400.0], east=[-300.0, 120.0], agl=[10.0, 20.0])
    geom = FrameGeometry(poses, local)
    rng = np.random.default_rng(7)
    # Targets around each frame's nadir, given as WGS84 like rover geotags.
    pts_local = geom.ground_point[:, None, :] + np.concatenate(
        [rng.uniform(-4, 4, (2, 30, 2)), rng.uniform(-0.2, 0.2, (2, 30, 1))], axis=2)
    lat, lon, h = local.to_geodetic(pts_local.reshape(-1, 3))
    for f in range(2):
        # Independent chain: ECEF → NED at the IMU (closed-form rotation) → body → camera → OpenCV.
        imu_ecef = geodesy.geodetic_to_ecef(poses.lat[f], poses.lon[f], poses.height[f]).reshape(3)
        la, lo = np.radians(poses.lat[f]), np.radians(poses.lon[f])
        r_ned_ecef = np.array([[-np.sin(la) * np.cos(lo), -np.sin(la) * np.sin(lo), np.cos(la)],
                               [-np.sin(lo), np.cos(lo), 0.0],
                               [-np.cos(la) * np.cos(lo), -np.cos(la) * np.sin(lo), -np.sin(la)]])
        r_body_ned = euler_zyx_to_rotmat(*np.radians([[3.0, -7.0][f], [-2.0, 5.0][f], [37.0, 211.0][f]])).T
        sel = slice(30 * f, 30 * f + 30)
        x_ecef = geodesy.geodetic_to_ecef(lat[sel], lon[sel], h[sel])
        x_body = (x_ecef - imu_ecef) @ (r_body_ned @ r_ned_ecef).T
        x_cam = x_body @ cam.T_cam_imu[:3, :3].T + cam.T_cam_imu[:3, 3]
        expected, _ = cv2.projectPoints(x_cam, np.zeros(3), np.zeros(3), cam.K, np.array(cam.dist))
        got = project_pairs(geom, np.full(30, f), pts_local[f])
        np.testing.assert_allclose(got.uv, expected[:, 0, :], atol=1e-6)


def test_pixel_to_ground_to_pixel_round_trip_over_the_frame():
    cam = make_camera(lever=(0.1, 0.0, 0.05))
    geom, _ = geometry(cam, roll=[4.0, 0.0], pitch=[-3.0, 0.0], yaw=[120.0, 0.0], agl=[10.0, 20.0])
    ground = LevelPlaneGround(geom)
    u, v = np.meshgrid(np.linspace(-0.5, 1919.5, 25), np.linspace(-0.5, 1199.5, 17))
    uv = np.column_stack([u.ravel(), v.ravel()])
    for f in range(2):
        pts, ok = pixel_to_ground(geom, ground, np.full(len(uv), f), uv)
        assert ok.all()
        np.testing.assert_allclose(np.einsum("ni,i->n", pts - geom.ground_point[f], geom.up[f]), 0, atol=1e-9)
        back = project_pairs(geom, np.full(len(uv), f), pts)
        assert np.max(np.abs(back.uv - uv)) < 1e-3


def test_nadir_conventions_north_east_and_heading():
    cam = make_camera(dist=(0, 0, 0, 0, 0))
    # Heading north: a point 1 m north is above the image centre, 1 m east is right of it.
    geom, local = geometry(cam, yaw=0.0)
    pts = geom.ground_point[0] + np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0]])
    uv = project_pairs(geom, [0, 0], pts).uv
    assert uv[0, 1] == pytest.approx(cam.cy - cam.fy * 0.1, abs=1e-6) and uv[0, 0] == pytest.approx(cam.cx, abs=1e-6)
    assert uv[1, 0] == pytest.approx(cam.cx + cam.fx * 0.1, abs=1e-6) and uv[1, 1] == pytest.approx(cam.cy, abs=1e-6)
    # Heading east (yaw 90°): the point east is now above the centre, the point north to the left.
    geom, _ = geometry(cam, yaw=90.0)
    uv = project_pairs(geom, [0, 0], geom.ground_point[0] + np.array([[1.0, 0, 0], [0, 1.0, 0]])).uv
    assert uv[0, 1] < cam.cy - 400 and abs(uv[0, 0] - cam.cx) < 1e-6
    assert uv[1, 0] < cam.cx - 400 and abs(uv[1, 1] - cam.cy) < 1e-6


def test_attitude_moves_the_nadir_point_the_right_way():
    cam = make_camera(dist=(0, 0, 0, 0, 0))
    below = lambda g: project_pairs(g, [0], g.ground_point[:1]).uv[0]
    # Roll right (right wing down) turns the belly, and the camera, to the left: the point below
    # appears right of centre, by f·tan(roll).
    u, v = below(geometry(cam, roll=5.0)[0])
    assert u == pytest.approx(cam.cx + cam.fx * np.tan(np.radians(5.0)), abs=1e-6)
    assert v == pytest.approx(cam.cy, abs=1e-6)
    # Pitch up turns the camera forward: the point below appears towards the image bottom (behind).
    u, v = below(geometry(cam, pitch=5.0)[0])
    assert v == pytest.approx(cam.cy + cam.fy * np.tan(np.radians(5.0)), abs=1e-6)
    assert u == pytest.approx(cam.cx, abs=1e-6)


def test_camera_lever_arm_moves_the_camera_centre():
    cam = make_camera(lever=(1.0, 0.0, 0.0), dist=(0, 0, 0, 0, 0))
    geom, _ = geometry(cam, yaw=0.0)
    # The camera sits 1 m ahead (north) of the IMU: the point under the IMU appears 1 m behind.
    u, v = project_pairs(geom, [0], geom.ground_point[:1]).uv[0]
    assert v == pytest.approx(cam.cy + cam.fy * 1.0 / 10.0, abs=1e-6)
    np.testing.assert_allclose(geom.C[0] - geom.imu_position[0], [0.0, 1.0, 0.0], atol=1e-9)


def test_tilt_corrected_altimeter_with_lever_arm():
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians(10.0), np.radians(-4.0), 0.3))
    h = ground_height_from_altimeter(50.0, q, 12.0)
    assert h == pytest.approx(50.0 - 12.0 * np.cos(np.radians(10.0)) * np.cos(np.radians(4.0)))
    level = rotmat_to_quat(np.eye(3))
    # An altimeter 0.3 m below the IMU (body z down): the ground is 0.3 m closer to the IMU height.
    assert ground_height_from_altimeter(50.0, level, 10.0, (0.0, 0.0, 0.3)) == pytest.approx(39.7)


def test_ground_placement_uses_the_frame_ground_not_the_rover_height():
    cam = make_camera()
    geom, _ = geometry(cam)
    ground = LevelPlaneGround(geom)
    pt = geom.ground_point[:1] + np.array([[0.7, -0.4, 1.8]])  # rover antenna 1.8 m up a pole
    placed = project_pairs(geom, [0], pt, ground).uv
    on_ground = project_pairs(geom, [0], pt - np.array([[0, 0, 1.8]])).uv
    np.testing.assert_allclose(placed, on_ground, atol=1e-9)


def test_prefilter_keeps_exactly_the_pairs_in_view():
    cam = make_camera()
    rng = np.random.default_rng(11)
    n = 300
    geom, local = geometry(cam, roll=rng.normal(0, 2, n), pitch=rng.normal(0, 2, n),
                           yaw=rng.uniform(0, 360, n), north=rng.uniform(-60, 60, n),
                           east=rng.uniform(-60, 60, n), agl=rng.uniform(8, 25, n))
    ground = LevelPlaneGround(geom)
    pts = np.column_stack([rng.uniform(-70, 70, 800), rng.uniform(-70, 70, 800), rng.normal(0, 0.05, 800)])
    dense = project_all(geom, pts, ground, edge_buffer_px=20)
    dense_pairs = set(zip(dense.frame_idx[dense.in_view].tolist(), dense.point_idx[dense.in_view].tolist()))
    fast = project_in_view(geom, pts, ground, edge_buffer_px=20)
    assert len(dense_pairs) > 100
    assert set(zip(fast.frame_idx.tolist(), fast.point_idx.tolist())) == dense_pairs
    fi, _ = candidate_pairs(geom, pts, ground)
    assert len(fi) < 0.1 * n * len(pts)


def test_frames_that_see_the_horizon_are_never_filtered_out():
    cam = make_camera(dist=(0, 0, 0, 0, 0))
    geom, _ = geometry(cam, pitch=[0.0, 85.0])  # the second frame's top edge is above the horizon
    ground = LevelPlaneGround(geom)
    _, complete = footprints(geom, ground)
    assert complete.tolist() == [True, False]
    far = geom.ground_point[1] + np.array([[0.0, 60.0, 0.0]])  # 60 m ahead, seen by the tilted frame
    proj = project_in_view(geom, far, ground)
    assert proj.frame_idx.tolist() == [1]


def test_utm_zone_edge_true_north_versus_grid_north():
    """Yaw is about true north; a naive grid-north placement is off by the meridian convergence."""
    cam = make_camera(dist=(0, 0, 0, 0, 0))
    lat0, lon0 = 45.0, 11.95  # 2.95° east of zone 32's central meridian
    geom, local = geometry(cam, yaw=0.0, lat0=lat0, lon0=lon0, ground=100.0)
    ground = LevelPlaneGround(geom)
    utm = geodesy.ProjectedCRS(geodesy.utm_epsg(lat0, lon0))
    cam_lat, cam_lon, _ = local.to_geodetic(geom.C[0])
    x0, y0 = utm.from_geodetic(cam_lat, cam_lon)
    # 3 m grid-north of the camera, in UTM coordinates:
    lat_g, lon_g = utm.to_geodetic(x0, y0 + 3.0)
    pt = local.from_geodetic(lat_g, lon_g, 100.0)
    u, v = project_pairs(geom, [0], pt, ground).uv[0]
    gamma = np.radians(geodesy.meridian_convergence_deg(lat0, lon0, utm.crs))
    # East of the central meridian (northern hemisphere) grid north is clockwise of true north by γ,
    # so a point grid-north of a north-facing camera appears right of the centre column.
    expected_u = cam.cx + cam.fx * 3.0 * np.sin(gamma) / 10.0
    assert abs(u - cam.cx) > 40.0  # tens of pixels: what ignoring convergence would cost
    assert u == pytest.approx(expected_u, abs=0.5)


def test_body_pose_from_camera_inverts_frame_geometry():
    from birdseye.birdseye_qgis.core.geometry.poses import body_pose_from_camera

    t = np.eye(4)
    t[:3, :3] = so3_exp(np.array([1.2, -0.4, 0.3]))
    t[:3, 3] = [0.05, -0.1, 0.2]  # a lever arm, so position and attitude both matter
    cam = CameraModel(640, 480, 500.0, 500.0, 319.5, 239.5, T_cam_imu=t)
    local = LocalFrame(47.0, 8.0, 400.0)
    rng = np.random.default_rng(4)
    lat, lon, h = 47.0 + rng.normal(scale=1e-3, size=5), 8.0 + rng.normal(scale=1e-3, size=5), 430 + rng.normal(size=5)
    quat = np.stack([np.append(np.cos(a / 2), np.sin(a / 2) * np.array([0.3, -0.5, 0.81]) / 1.0)
                     for a in rng.uniform(0, 3, 5)])
    quat /= np.linalg.norm(quat, axis=1, keepdims=True)
    geometry = FrameGeometry(FramePoses(np.arange(5), lat, lon, h, quat, np.full(5, 400.0), cam), local)
    back = body_pose_from_camera(local, geometry.C, geometry.R_local_cam, cam)
    np.testing.assert_allclose(back[0], lat, atol=1e-10)
    np.testing.assert_allclose(back[1], lon, atol=1e-10)
    np.testing.assert_allclose(back[2], h, atol=1e-6)
    np.testing.assert_allclose(np.abs(np.einsum("ni,ni->n", back[3], quat)), 1.0, atol=1e-10)

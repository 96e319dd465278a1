"""Rotation conventions and geodesy, pinned against independent constructions."""
import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from birdseye.birdseye_qgis.core.geometry import geodesy
from birdseye.birdseye_qgis.core.geometry.rigid import RigidTransform
from birdseye.birdseye_qgis.core.geometry.rotations import (
    euler_zyx_to_rotmat,
    hat,
    quat_to_rotmat,
    rotmat_to_euler_zyx,
    rotmat_to_quat,
    se3_exp,
    so3_exp,
)


def test_quaternion_matches_scipy_and_round_trips():
    rng = np.random.default_rng(1)
    q = rng.normal(size=(200, 4))
    q /= np.linalg.norm(q, axis=1, keepdims=True)
    ref = Rotation.from_quat(q[:, [1, 2, 3, 0]]).as_matrix()  # scipy is scalar-last
    np.testing.assert_allclose(quat_to_rotmat(q), ref, atol=1e-12)
    back = rotmat_to_quat(ref)
    np.testing.assert_allclose(np.abs(np.einsum("ni,ni->n", back, q)), 1.0, atol=1e-12)


def test_euler_zyx_matches_intrinsic_scipy_and_round_trips():
    rng = np.random.default_rng(2)
    roll, pitch, yaw = rng.uniform(-np.pi, np.pi, 50), rng.uniform(-1.5, 1.5, 50), rng.uniform(-np.pi, np.pi, 50)
    ref = Rotation.from_euler("ZYX", np.column_stack([yaw, pitch, roll])).as_matrix()
    r = euler_zyx_to_rotmat(roll, pitch, yaw)
    np.testing.assert_allclose(r, ref, atol=1e-12)
    np.testing.assert_allclose(np.column_stack(rotmat_to_euler_zyx(r)), np.column_stack([roll, pitch, yaw]),
                               atol=1e-9)


def test_attitude_sign_conventions_body_frd_to_ned():
    forward, right = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
    # Yaw 90° (heading east): body forward points east in NED.
    np.testing.assert_allclose(euler_zyx_to_rotmat(0, 0, np.pi / 2) @ forward, [0, 1, 0], atol=1e-12)
    # Pitch up: forward axis gains a negative down component.
    assert (euler_zyx_to_rotmat(0, 0.2, 0) @ forward)[2] < 0
    # Roll right (right wing down): the right axis gains a positive down component.
    assert (euler_zyx_to_rotmat(0.2, 0, 0) @ right)[2] > 0


def test_se3_exp_matches_matrix_exponential():
    rng = np.random.default_rng(4)
    for xi in rng.normal(scale=[1, 1, 1, 0.5, 0.5, 0.5], size=(20, 6)):
        twist = np.zeros((4, 4))
        twist[:3, :3] = hat(xi[3:])
        twist[:3, 3] = xi[:3]
        np.testing.assert_allclose(se3_exp(xi), expm(twist), atol=1e-10)
    np.testing.assert_allclose(so3_exp(np.zeros(3)), np.eye(3))
    t = se3_exp(rng.normal(size=6))
    np.testing.assert_allclose(RigidTransform.from_matrix(t).inverse().matrix @ t, np.eye(4), atol=1e-12)
    a, b = rng.normal(size=3), rng.normal(size=3)
    np.testing.assert_allclose(hat(a) @ b, np.cross(a, b))


def test_local_frame_round_trip_and_axes():
    import pyproj
    # Heights 0: geodesic distances are measured on the ellipsoid (at 400 m they would be 63 ppm longer).
    frame = geodesy.LocalFrame(-27.55, 151.95, 0.0)
    geod = pyproj.Geod(ellps="WGS84")
    lon_n, lat_n, _ = geod.fwd(151.95, -27.55, 0.0, 100.0)   # 100 m true north
    lon_e, lat_e, _ = geod.fwd(151.95, -27.55, 90.0, 100.0)  # 100 m true east
    enu = frame.from_geodetic([lat_n, lat_e], [lon_n, lon_e], [0.0, 0.0])
    np.testing.assert_allclose(enu[0, :2], [0.0, 100.0], atol=2e-3)
    np.testing.assert_allclose(enu[1, :2], [100.0, 0.0], atol=2e-3)
    # Earth curvature: 100 m away the ellipsoid has dropped by d²/2R ≈ 0.8 mm.
    assert -1.2e-3 < enu[0, 2] < -0.4e-3
    lat, lon, h = frame.to_geodetic(enu)
    np.testing.assert_allclose(lat, [lat_n, lat_e], atol=1e-10)
    np.testing.assert_allclose(h, 0.0, atol=1e-6)
    # At the origin, NED maps to ENU by the fixed permutation.
    np.testing.assert_allclose(frame.rotation_from_ned(-27.55, 151.95),
                               [[0, 1, 0], [1, 0, 0], [0, 0, -1]], atol=1e-12)


@pytest.mark.parametrize("lat, lon, epsg", [
    (-27.55, 151.95, 32756), (52.2, 0.12, 32631), (52.2, -0.12, 32630),
    (60.0, 5.5, 32632),   # Norway exception (would be 31)
    (78.0, 15.0, 32633),  # Svalbard exception
    (-33.9, 18.4, 32734),
])
def test_utm_zone_selection(lat, lon, epsg):
    assert geodesy.utm_epsg(lat, lon) == epsg


def test_meridian_convergence_near_zone_edge_matches_closed_form():
    # γ ≈ Δλ·sin φ on the ellipsoid to first order; 2.9° east of the central meridian at 45°N.
    gamma = geodesy.meridian_convergence_deg(45.0, 9.0 + 2.9, 32632)
    assert gamma == pytest.approx(2.9 * np.sin(np.radians(45.0)), abs=0.02)
    crs = geodesy.ProjectedCRS(32632)
    x, y = crs.from_geodetic(45.0, 11.9)
    lat, lon = crs.to_geodetic(x, y)
    assert (float(lat), float(lon)) == pytest.approx((45.0, 11.9), abs=1e-9)


def test_quaternion_euler_quaternion_round_trips_including_nadir_gimbals():
    rng = np.random.default_rng(7)
    q = rng.normal(size=(500, 4))
    nadir = rotmat_to_quat(euler_zyx_to_rotmat(rng.uniform(-np.pi, np.pi, 50), -np.pi / 2,
                                               rng.uniform(-np.pi, np.pi, 50)))
    up = rotmat_to_quat(euler_zyx_to_rotmat(0.3, np.pi / 2, 1.0))
    q = np.vstack([q / np.linalg.norm(q, axis=1, keepdims=True), nadir, up[None],
                   nadir.astype(np.float32).astype(float)])
    roll, pitch, yaw = rotmat_to_euler_zyx(quat_to_rotmat(q))
    back = rotmat_to_quat(euler_zyx_to_rotmat(roll, pitch, yaw))
    np.testing.assert_allclose(np.abs(np.einsum("ni,ni->n", back, q / np.linalg.norm(q, axis=1, keepdims=True))),
                               1.0, atol=1e-12)


def test_a_nadir_frame_heading_30_degrees_reads_yaw_30_roll_0():
    from birdseye.birdseye_qgis.core.field.frame_records import euler_degrees

    q = rotmat_to_quat(euler_zyx_to_rotmat(0.0, np.radians(-90.0), np.radians(30.0)))
    for quat in (q, q.astype(np.float32).astype(float)):  # float32: how many tools store attitudes
        roll, pitch, yaw = (a[0] for a in euler_degrees(quat[None]))
        assert (roll, pitch, yaw) == pytest.approx((0.0, -90.0, 30.0), abs=1e-5)
    # Roll and yaw of a nadir gimbal turn about the same (vertical) axis: the sum is the heading.
    q = rotmat_to_quat(euler_zyx_to_rotmat(np.radians(12.0), np.radians(-90.0), np.radians(30.0)))
    assert [a[0] for a in euler_degrees(q[None])] == pytest.approx([0.0, -90.0, 42.0], abs=1e-9)


def test_a_gimbal_refined_off_nadir_keeps_its_heading_in_yaw():
    """Refined nadir frames tilt a few tenths of a degree either way; the frame layer's fields must keep the
    heading in yaw and roll small, in the gimbal's order yaw–roll–pitch, and rebuild the quaternion."""
    from birdseye.birdseye_qgis.core.field.frame_records import euler_degrees

    rng = np.random.default_rng(3)
    roll, pitch, yaw = rng.uniform(-5, 5, 60), rng.uniform(-96, -84, 60), rng.uniform(0, 360, 60)
    pitch[:20] = -90.0 + rng.uniform(-0.5, 0.5, 20)
    q = Rotation.from_euler("ZXY", np.column_stack([yaw, roll, pitch]), degrees=True).as_quat()[:, [3, 0, 1, 2]]
    got = np.column_stack(euler_degrees(q))
    np.testing.assert_allclose(got, np.column_stack([roll, pitch, yaw]), atol=1e-6)
    # Half a degree off nadir, heading 44°: ZYX alone would split it into some yaw and a large roll.
    q = Rotation.from_euler("ZXY", [44.0, 0.3, -90.4], degrees=True).as_quat()[[3, 0, 1, 2]]
    zyx_roll = np.degrees(rotmat_to_euler_zyx(quat_to_rotmat(q))[0])
    assert abs(zyx_roll) > 30
    assert [a[0] for a in euler_degrees(q[None])] == pytest.approx([0.3, -90.4, 44.0], abs=1e-9)
    # Level bodies (pose logs) keep aerospace ZYX.
    q = rotmat_to_quat(euler_zyx_to_rotmat(*np.radians([3.0, -2.0, 120.0])))
    assert [a[0] for a in euler_degrees(q[None])] == pytest.approx([3.0, -2.0, 120.0], abs=1e-9)

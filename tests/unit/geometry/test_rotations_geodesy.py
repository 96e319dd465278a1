"""Rotation conventions and geodesy, pinned against independent constructions."""
import numpy as np
import pytest
from scipy.linalg import expm
from scipy.spatial.transform import Rotation

from birdseye.birdseye_qgis.core.geometry import geodesy
from birdseye.birdseye_qgis.core.geometry.rotations import (
    euler_zyx_to_rotmat,
    hat,
    invert_transform,
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
    np.testing.assert_allclose(invert_transform(t) @ t, np.eye(4), atol=1e-12)
    a, b = rng.normal(size=3), rng.normal(size=3)
    np.testing.assert_allclose(hat(a) @ b, np.cross(a, b))


def test_local_frame_round_trip_and_axes():
    pyproj = pytest.importorskip("pyproj")
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

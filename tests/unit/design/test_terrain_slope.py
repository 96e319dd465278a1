"""Level-plane ground model on sloped terrain: label error in pixels."""
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.design import terrain_slope as ts
from birdseye.birdseye_qgis.core.errors import InputError

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
SLOPES = np.linspace(0, 45, 46)
RATIOS = np.linspace(0, 0.3, 31)


def test_zero_without_slope_or_distance_and_monotone_in_both():
    err = ts.slope_error_grid(DEPLOYED, 10.0, SLOPES, RATIOS)
    assert err.shape == (46, 31)
    assert np.all(err[0] == 0) and np.all(err[:, 0] == 0)
    assert np.all(np.diff(err[:, 1:], axis=0) > 0)
    assert np.all(np.diff(err[1:], axis=1) > 0)


def test_matches_the_closed_form_and_is_altitude_invariant():
    f = max(DEPLOYED.fx, DEPLOYED.fy)
    t = np.tan(np.radians(SLOPES))[:, None]
    expected = f * RATIOS ** 2 * t / (1 - RATIOS * t)
    for altitude in (5.0, 10.0, 20.0):
        np.testing.assert_allclose(ts.slope_error_grid(DEPLOYED, altitude, SLOPES, RATIOS), expected, rtol=1e-9,
                                   atol=1e-9)


def test_matches_a_direct_projection_of_the_uphill_target():
    # Camera 10 m above the nadir point, ground rising 10° towards image right: the target 2 m right
    # of nadir is 2·tan 10° m nearer the camera than the level plane assumes.
    h, d, slope = 10.0, 2.0, math.radians(10.0)
    # The camera frame has z down, so the sloped plane through N = (0, 0, h) with normal
    # (sin α, 0, cos α) holds the target at (d, 0, h − d tan α).
    normal = np.array([math.sin(slope), 0.0, math.cos(slope)])
    z = h - normal[0] * d / normal[2]
    model_u = DEPLOYED.fx * d / h + DEPLOYED.cx
    true_u = DEPLOYED.fx * d / z + DEPLOYED.cx
    assert DEPLOYED.fx >= DEPLOYED.fy  # image u is the worst-case direction for this camera
    assert ts.slope_error_px(DEPLOYED, h, 10.0, d / h) == pytest.approx(true_u - model_u, rel=1e-12)


def test_target_above_the_camera_is_nan_and_inputs_are_checked():
    assert np.isnan(ts.slope_error_px(DEPLOYED, 10.0, 45.0, 1.2))
    with pytest.raises(InputError):
        ts.slope_error_px(DEPLOYED, 10.0, -1.0, 0.1)
    with pytest.raises(InputError):
        ts.slope_error_px(DEPLOYED, 0.0, 5.0, 0.1)


def test_max_slope_inverts_the_error():
    for rho in (0.05, 0.14, 0.27):
        alpha = ts.max_slope_deg(DEPLOYED, 30.0, rho)
        assert ts.slope_error_px(DEPLOYED, 10.0, alpha, rho) == pytest.approx(30.0)
    assert ts.max_slope_deg(DEPLOYED, 30.0, 0.0) == 90.0


def test_ten_degree_claim_for_the_deployed_camera():
    """At 10° the level plane keeps labels within 30 px only out to ρ ≈ 0.196, not over the whole frame."""
    frame = ts.frame_distance_ratios(DEPLOYED)
    # The outermost pixel centres: 1919 − cx and 1199 − cy from the principal point.
    assert frame["corner"] == pytest.approx(math.hypot(960.5406 / 4264.4945, 606.4967 / 4262.8927))
    assert ts.slope_error_px(DEPLOYED, 10.0, 10.0, frame["edge_v"]) < 30.0
    assert ts.slope_error_px(DEPLOYED, 10.0, 10.0, frame["edge_u"]) > 30.0
    assert ts.slope_error_px(DEPLOYED, 10.0, 10.0, frame["corner"]) > 50.0
    assert ts.max_slope_deg(DEPLOYED, 30.0, frame["corner"]) == pytest.approx(5.5, abs=0.1)


def test_contour_plot(tmp_path):
    out = ts.plot_slope_error(DEPLOYED, 10.0, tmp_path / "slope.png", tolerance_px=30.0)
    assert (tmp_path / "slope.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out == tmp_path / "slope.png"

"""Monte Carlo check of the linearised sensor bound against the exact SE(3) re-projection, on the ground grid."""
import dataclasses
import json
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.design import monte_carlo_bound as mc
from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]
# Roll six times pitch, so a mount that swaps them gives a visibly different label covariance.
UNEQUAL_SIGMAS = [0.010, 0.020, 0.060, 0.30, 0.05, 0.13]
# Camera axes (columns x, y, z) in the forward-right-down body, written from the mounts' descriptions:
# the method's (image right towards the nose) and the nadir mount (image top towards the nose).
CAMERA_IN_BODY = {"method": np.eye(3),
                  "nadir_top_forward": np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])}


def sampled_label_covariance(intr, altitude, sigmas, camera_in_body, pixels, n_samples=20000, seed=5):
    """Label covariance (N, 2, 2) px² by simulation alone: draw body Euler-angle errors and camera-frame
    position errors, turn the camera with the body, re-project the level-ground points the nominal
    camera sees at ``pixels`` and take the second moment of the pixel shift."""
    rng = np.random.default_rng(seed)
    draws = rng.standard_normal((n_samples, 6)) * np.r_[sigmas[:3], np.radians(sigmas[3:])]
    heading = math.radians(35.0)
    nominal = euler_zyx_to_rotmat(0.0, 0.0, heading) @ camera_in_body             # camera → NED
    rays = np.c_[(pixels[:, 0] - intr.cx) / intr.fx, (pixels[:, 1] - intr.cy) / intr.fy, np.ones(len(pixels))]
    ground = altitude * rays @ nominal.T                                          # NED, from the camera
    turned = euler_zyx_to_rotmat(draws[:, 3], draws[:, 4], heading + draws[:, 5]) @ camera_in_body
    seen = np.einsum("sji,nj->sni", turned, ground) - draws[:, None, :3]
    shift = np.stack([intr.fx * seen[..., 0] / seen[..., 2] + intr.cx - pixels[:, 0],
                      intr.fy * seen[..., 1] / seen[..., 2] + intr.cy - pixels[:, 1]], axis=-1)
    return np.einsum("sni,snj->nij", shift, shift) / n_samples


@pytest.mark.parametrize("mount", sb.MOUNTS, ids=lambda m: m.key)
def test_simulated_attitude_noise_follows_the_linearised_bound_of_its_mount(mount):
    pixels = mc.ground_grid(DEPLOYED, 10.0).pixels
    sampled = sampled_label_covariance(DEPLOYED, 10.0, UNEQUAL_SIGMAS, CAMERA_IN_BODY[mount.key], pixels)
    variances = sb.sigmas_to_variances(UNEQUAL_SIGMAS)
    for other in sb.MOUNTS:
        skld = mc.symmetric_kl(sampled, sb.pixel_covariance(DEPLOYED, pixels[:, 0], pixels[:, 1], 10.0, variances,
                                                            other))
        # Its own mount within sampling noise (≈ 3/n); the other mount, with roll and pitch swapped, far off.
        assert (skld.max() < 1e-3) if other is mount else (skld.max() > 1.0)
    # The module's own check draws through the mount's rotation and agrees too.
    assert mc.monte_carlo_check(DEPLOYED, 10.0, UNEQUAL_SIGMAS, n_samples=20000, seed=3, mount=mount).max_skld < 1e-3


@pytest.mark.parametrize("altitude", [10.0, 20.0])
def test_linearisation_holds_for_the_deployed_platform(altitude):
    res = mc.monte_carlo_check(DEPLOYED, altitude, DEPLOYED_SIGMAS, n_samples=20000, seed=3)
    assert res.max_skld < 1e-2
    np.testing.assert_allclose(res.model_cov, sb.pixel_covariance(DEPLOYED, res.pixels[:, 0], res.pixels[:, 1],
                                                                  altitude, sb.sigmas_to_variances(DEPLOYED_SIGMAS)))
    # Same moments to within sampling error (≈ 1/√n relative).
    np.testing.assert_allclose(np.trace(res.sample_cov, axis1=1, axis2=2),
                               np.trace(res.model_cov, axis1=1, axis2=2), rtol=0.05)
    json.dumps(res.to_json_dict(), allow_nan=False)


# A camera whose footprint is easy to count by hand: 2000 × 1000 px at f = 1000 px sees 20 m × 10 m from 10 m.
ROUND = sb.Intrinsics(fx=1000.0, fy=1000.0, cx=999.5, cy=499.5, width=2000, height=1000)


@pytest.mark.parametrize("intr, altitude, spacing, shape", [
    # 20 m × 10 m: nodes every metre from edge to edge, both edges included.
    (ROUND, 10.0, 1.0, (11, 21)),
    # ±10 m / 3 m → 3 nodes each side of the centre across, ±5 m / 3 m → 1 down.
    (ROUND, 10.0, 3.0, (3, 7)),
    # Coarser than the footprint: its centre alone.
    (ROUND, 10.0, 25.0, (1, 1)),
    # The method's grid on its platform: 1920 px · 10 m / 4264.49 px = 4.502 m → ±2.251 m / 0.67 m → 3 each side;
    # 1200 px · 10 m / 4262.89 px = 2.815 m → ±1.408 m / 0.67 m → 2 each side.
    (DEPLOYED, 10.0, 0.67, (5, 7)),
    # From 20 m: 9.005 m → ±4.502 / 0.67 → 6 each side; 5.630 m → ±2.815 / 0.67 → 4.
    (DEPLOYED, 20.0, 0.67, (9, 13)),
])
def test_ground_grid_counts_the_nodes_inside_the_footprint(intr, altitude, spacing, shape):
    grid = mc.ground_grid(intr, altitude, spacing)
    assert grid.shape == shape and len(grid.points) == shape[0] * shape[1] == len(grid.pixels)
    # The footprint is the frame's outer edges (−0.5 … W − 0.5 px) at the flight height.
    (x0, x1), (y0, y1) = grid.footprint_m
    assert (x1 - x0, y1 - y0) == pytest.approx((intr.width * altitude / intr.fx, intr.height * altitude / intr.fy))
    assert np.all(grid.points[:, 2] == altitude)
    # Nodes spaced as asked along image x (row-major) and y, centred on the frame centre, all in the frame.
    rows = grid.pixels.reshape(shape + (2,))
    np.testing.assert_allclose(np.diff(rows[..., 0], axis=1), spacing * intr.fx / altitude)
    np.testing.assert_allclose(np.diff(rows[..., 1], axis=0), spacing * intr.fy / altitude)
    np.testing.assert_allclose(grid.pixels.mean(axis=0), [(intr.width - 1) / 2, (intr.height - 1) / 2], atol=1e-9)
    assert np.all((grid.pixels >= -0.5 - 1e-6) & (grid.pixels <= [intr.width - 0.5 + 1e-6, intr.height - 0.5 + 1e-6]))


def test_edge_nodes_are_on_the_frame_edges():
    pixels = mc.ground_grid(ROUND, 10.0, 1.0).pixels
    assert pixels[:, 0].min() == pytest.approx(-0.5) and pixels[:, 0].max() == pytest.approx(1999.5)
    assert pixels[:, 1].min() == pytest.approx(-0.5) and pixels[:, 1].max() == pytest.approx(999.5)


def test_error_ellipse_semi_major_axis_at_three_sigma_and_anisotropy():
    turn = np.array([[math.cos(0.4), -math.sin(0.4)], [math.sin(0.4), math.cos(0.4)]])
    # Standard deviations 3 and 1 px along two perpendicular directions: 3σ semi-major 9 px, ratio 3.
    major, ratio = mc.error_ellipse(np.stack([turn @ np.diag([9.0, 1.0]) @ turn.T, np.diag([4.0, 4.0]),
                                              np.diag([4.0, 0.0]), np.zeros((2, 2))]))
    np.testing.assert_allclose(major, [9.0, 6.0, 6.0, 0.0])
    np.testing.assert_allclose(ratio[:2], [3.0, 1.0])
    assert ratio[2] == np.inf and np.isnan(ratio[3])
    assert mc.ELLIPSE_SIGMAS == 3.0


def test_isotropic_horizontal_translation_gives_round_ellipses_of_f_sigma_over_depth():
    """A camera shifted sideways by t moves every ground point's pixel by f·t/Z exactly (Z the depth), so with
    σx = σy = σ every label's ellipse is a circle of 3σ semi-axis 3·f·σ/Z px (fx ≈ fy here)."""
    sigma, altitude = 0.02, 10.0
    res = mc.monte_carlo_check(DEPLOYED, altitude, [sigma, sigma, 0, 0, 0, 0], n_samples=20000, seed=2)
    expected = 3.0 * max(DEPLOYED.fx, DEPLOYED.fy) * sigma / altitude       # 25.6 px
    # Sampling error of a standard deviation from 20 000 draws: 0.5 % (1σ).
    np.testing.assert_allclose(res.major_axis_px, expected, rtol=0.03)
    assert np.all((res.anisotropy >= 1.0) & (res.anisotropy < 1.05))
    summary = res.summary()
    assert summary["major_axis_px_max"] == pytest.approx(expected, rel=0.03)
    assert 1.0 <= summary["anisotropy_median"] <= summary["anisotropy_max"] < 1.05
    # Exactly linear: the divergence is sampling noise (≈ 3/n), far below the threshold.
    assert summary["max_skld"] < 1e-3 and summary["fraction_over_skld"] == {"0.01": 0.0}


def test_depth_noise_gives_radial_ellipses_growing_with_the_distance_from_the_principal_point():
    """Raising the camera by t moves the pixel of a ground point seen at u by −(u − c)·t/(Z + t): along the
    ray from the principal point c, by (|u − c|/Z)·t to first order. A line, not an ellipse: semi-major
    axis 3·σz·|u − c|/Z, minor 0."""
    sigma_z, altitude = 0.2, 10.0
    res = mc.monte_carlo_check(DEPLOYED, altitude, [0, 0, sigma_z, 0, 0, 0], n_samples=20000, seed=4)
    offset = res.pixels - [DEPLOYED.cx, DEPLOYED.cy]
    radius = np.hypot(offset[:, 0], offset[:, 1])
    # Second-order bias 3σz²/Z² = 0.1 %, sampling error 0.5 %.
    np.testing.assert_allclose(res.major_axis_px, 3.0 * sigma_z * radius / altitude, rtol=0.03)
    # Every point shares the draws' factor t/(Z + t), so the axis is proportional to |u − c| to rounding.
    np.testing.assert_allclose(res.major_axis_px / radius, res.major_axis_px[0] / radius[0], rtol=1e-9)
    direction = np.linalg.eigh(res.sample_cov)[1][..., 1]
    np.testing.assert_allclose(np.abs(np.einsum("ni,ni->n", direction, offset / radius[:, None])), 1.0, atol=1e-9)
    far = radius > 10.0
    assert np.all(res.anisotropy[far] > 1e3)
    # Both covariances are singular along the tangent: the divergence is infinite (where rounding leaves a
    # determinant above 0, merely large), every point is over the cut-off, and infinity is written as null.
    assert np.all(res.skld > 1.0) and np.isinf(res.skld).any() and res.summary()["max_skld"] is None
    written = json.loads(json.dumps(res.to_json_dict(), allow_nan=False))
    assert written["points"][0]["skld"] is None and written["summary"]["fraction_over_skld"] == {"0.01": 1.0}


def test_deployed_platform_at_10_m_ellipses_stay_inside_the_tolerance():
    res = mc.monte_carlo_check(DEPLOYED, 10.0, DEPLOYED_SIGMAS, n_samples=20000, seed=3, skld_cutoffs=(0.01, 0.1))
    bound = sb.evaluate_bound(DEPLOYED, 10.0, DEPLOYED_SIGMAS)
    summary = res.summary()
    # The grid lies inside the frame, whose worst pixel has λ_max = λ_target/κ*: 3σ axis 30 px / √κ*.
    assert summary["major_axis_px_max"] < 30.0 / math.sqrt(bound.kappa_exact) * 1.03
    # …and the linear model's own ellipses agree with the sampled ones.
    np.testing.assert_allclose(res.major_axis_px, mc.error_ellipse(res.model_cov)[0], rtol=0.03)
    np.testing.assert_allclose(res.anisotropy, mc.error_ellipse(res.model_cov)[1], rtol=0.05)
    assert summary["n_points"] == 35 and summary["major_axis_px_median"] <= summary["major_axis_px_max"]
    assert summary["fraction_over_skld"] == {"0.01": 0.0, "0.1": 0.0} and res.linearisation_holds


def test_the_user_guides_figures_for_the_deployed_platform():
    """docs/user-guide.md, Reproducing the method's tables: the algorithm's defaults (20 000 samples, seed 0)."""
    printed = {10.0: (35, 24.7, 19.6, 1.45, 1.21, 4.3e-4), 20.0: (117, 14.9, 12.4, 1.15, 1.06, 3.5e-4)}
    for altitude, (n, major_max, major_median, ratio_max, ratio_median, skld) in printed.items():
        summary = mc.monte_carlo_check(DEPLOYED, altitude, DEPLOYED_SIGMAS, skld_cutoffs=(0.01, 0.1)).summary()
        assert summary["n_points"] == n
        assert (round(summary["major_axis_px_max"], 1), round(summary["major_axis_px_median"], 1)) == (
            major_max, major_median)
        assert (round(summary["anisotropy_max"], 2), round(summary["anisotropy_median"], 2)) == (
            ratio_max, ratio_median)
        assert float(f"{summary['max_skld']:.1e}") == skld
        assert summary["fraction_over_skld"] == {"0.01": 0.0, "0.1": 0.0}


def test_fraction_over_each_cutoff_counts_grid_points():
    res = mc.monte_carlo_check(ROUND, 10.0, DEPLOYED_SIGMAS, n_samples=100, spacing_m=5.0, seed=0,
                               skld_cutoffs=(0.01, 0.1))
    assert len(res.skld) == 15                                                # 5 × 3 nodes
    skld = np.r_[np.full(9, 0.001), np.full(3, 0.05), np.full(3, 0.5)]
    forged = dataclasses.replace(res, skld=skld)
    assert forged.summary()["fraction_over_skld"] == {"0.01": 0.4, "0.1": 0.2}
    assert forged.max_skld == 0.5 and not forged.linearisation_holds


@pytest.mark.parametrize("kwargs, says", [({"spacing_m": 0.0}, "spacing"), ({"spacing_m": float("nan")}, "spacing"),
                                          ({"skld_cutoffs": (0.01, -1.0)}, "cut-offs"),
                                          ({"skld_cutoffs": ()}, "cut-offs"), ({"n_samples": 5}, "samples")])
def test_bad_grid_and_cutoffs_are_refused(kwargs, says):
    with pytest.raises(InputError, match=says):
        mc.monte_carlo_check(DEPLOYED, 10.0, DEPLOYED_SIGMAS, **kwargs)


def test_divergence_grows_once_the_budget_leaves_the_linear_regime():
    study = mc.scaling_study(DEPLOYED, 10.0, DEPLOYED_SIGMAS, scales=[1.0, 1e3], per_axis=True,
                             n_samples=10000, seed=1)
    small, large = study.skld_max
    assert small < 1e-2 < large and large > 10 * small
    # Translation across the optical axis is exactly linear in the pinhole model, so scaling x or y
    # alone leaves only sampling noise; depth (z) and yaw are where the linearisation breaks.
    for axis in ("x", "y"):
        assert study.per_axis[axis][1] < 2 * study.per_axis[axis][0] + 1e-3
    assert study.per_axis["z"][1] > 10 * study.per_axis["z"][0]
    assert study.per_axis["yaw"][1] > 10 * study.per_axis["yaw"][0]
    json.dumps(study.to_json_dict(), allow_nan=False)


def test_results_are_deterministic_for_a_seed():
    a = mc.monte_carlo_check(DEPLOYED, 15.0, DEPLOYED_SIGMAS, n_samples=2000, seed=11)
    b = mc.monte_carlo_check(DEPLOYED, 15.0, DEPLOYED_SIGMAS, n_samples=2000, seed=11)
    c = mc.monte_carlo_check(DEPLOYED, 15.0, DEPLOYED_SIGMAS, n_samples=2000, seed=12)
    np.testing.assert_array_equal(a.sample_cov, b.sample_cov)
    assert not np.array_equal(a.sample_cov, c.sample_cov)


def test_symmetric_kl_values():
    eye = np.eye(2)
    assert mc.symmetric_kl(eye, eye) == pytest.approx(0.0)
    # tr(Q⁻¹P) = 1, tr(P⁻¹Q) = 4 → ½·5 − 2.
    assert mc.symmetric_kl(eye, 2 * eye) == pytest.approx(0.5)
    p = np.array([[3.0, 1.0], [1.0, 2.0]])
    q = np.array([[1.0, -0.2], [-0.2, 0.5]])
    assert mc.symmetric_kl(p, q) == pytest.approx(mc.symmetric_kl(q, p))
    assert mc.symmetric_kl(np.diag([1.0, 0.0]), eye) == np.inf


def test_scaling_plot_and_cancel(tmp_path):
    study = mc.scaling_study(DEPLOYED, 20.0, DEPLOYED_SIGMAS, scales=[0.5, 1.0, 10.0], per_axis=True,
                             n_samples=500, seed=0)
    out = mc.plot_scaling_study(study, tmp_path / "scaling.png", kappa=2.0)
    assert (tmp_path / "scaling.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out == tmp_path / "scaling.png"
    with pytest.raises(Cancelled):
        mc.scaling_study(DEPLOYED, 20.0, DEPLOYED_SIGMAS, n_samples=100, is_canceled=lambda: True)
    with pytest.raises(Cancelled):
        mc.monte_carlo_check(DEPLOYED, 20.0, DEPLOYED_SIGMAS, n_samples=100, is_canceled=lambda: True)
    with pytest.raises(InputError):
        mc.scaling_study(DEPLOYED, 20.0, DEPLOYED_SIGMAS, scales=[0.0, 1.0], n_samples=100)

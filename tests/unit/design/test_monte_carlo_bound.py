"""Monte Carlo check of the linearised sensor bound against the exact SE(3) re-projection."""
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
    pixels = mc.default_pixels(DEPLOYED)
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


def test_default_pixels_cover_corners_edges_centre_and_principal_point():
    px = {tuple(p) for p in mc.default_pixels(DEPLOYED)}
    # Pixel centres of the frame: the last column is u = W − 1, the last row v = H − 1.
    assert {(0.0, 0.0), (1919.0, 0.0), (0.0, 1199.0), (1919.0, 1199.0), (959.5, 599.5)} <= px
    assert (DEPLOYED.cx, DEPLOYED.cy) in px and len(px) == 10


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
    with pytest.raises(InputError):
        mc.scaling_study(DEPLOYED, 20.0, DEPLOYED_SIGMAS, scales=[0.0, 1.0], n_samples=100)

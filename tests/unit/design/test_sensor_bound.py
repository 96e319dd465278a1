"""Sensor-bound calculator: Jacobian, grid, criteria, κ*, balanced allocations, API contract."""
import json
import math
from types import SimpleNamespace

import numpy as np
import pytest
from scipy.optimize import minimize

from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.errors import Cancelled, InputError
from birdseye.birdseye_qgis.core.geometry.rigid import RigidTransform
from birdseye.birdseye_qgis.core.geometry.rotations import euler_zyx_to_rotmat, se3_exp

DEPLOYED = sb.Intrinsics(fx=4264.4945, fy=4262.8927, cx=958.4594, cy=592.5033, width=1920, height=1200)
DEPLOYED_SIGMAS = [0.010, 0.010, 0.060, 0.04, 0.04, 0.13]
# A skewed camera (fy ≠ fx, principal point far off-centre) on which the exact allocation needs
# several cutting-plane iterations.
SKEWED = sb.Intrinsics(fx=943.96, fy=1354.81, cx=1398.03, cy=1007.78, width=1800, height=1644)


def _project(intr, xc):
    return np.stack([intr.fx * xc[..., 0] / xc[..., 2] + intr.cx, intr.fy * xc[..., 1] / xc[..., 2] + intr.cy], -1)


def _back_project(intr, u, v, depth):
    return np.array([(u - intr.cx) / intr.fx * depth, (v - intr.cy) / intr.fy * depth, depth])


@pytest.mark.parametrize("depth", [3.0, 10.0, 20.0, 80.0])
def test_jacobian_matches_central_differences_of_the_full_projection(depth):
    t_cam_world = se3_exp(np.array([0.3, -0.2, 1.5, 0.1, -0.2, 0.3]))
    t_world_cam = RigidTransform.from_matrix(t_cam_world).inverse().matrix
    pixels = [(0, 0), (1920, 0), (0, 1200), (1920, 1200), (DEPLOYED.cx, DEPLOYED.cy), (300.5, 950.25)]
    h = 1e-6
    for u, v in pixels:
        x_world = t_world_cam @ np.append(_back_project(DEPLOYED, u, v, depth), 1.0)
        fd = np.empty((2, 6))
        for k in range(6):
            step = np.zeros(6)
            step[k] = h
            plus = (se3_exp(step) @ t_cam_world @ x_world)[:3]
            minus = (se3_exp(-step) @ t_cam_world @ x_world)[:3]
            fd[:, k] = (_project(DEPLOYED, plus) - _project(DEPLOYED, minus)) / (2 * h)
        jac = sb.pixel_jacobian(DEPLOYED, u, v, depth)[0]
        np.testing.assert_allclose(jac, fd, rtol=1e-6, atol=1e-4)


@pytest.mark.parametrize("mount, roll_gain, pitch_gain", [(sb.METHOD_MOUNT, "fy", "fx"), (sb.NADIR_MOUNT, "fx", "fy")])
def test_closed_forms_at_the_principal_point(mount, roll_gain, pitch_gain):
    z = 12.0
    jac = sb.pixel_jacobian(DEPLOYED, DEPLOYED.cx, DEPLOYED.cy, z)[0]
    # Translation across the optical axis moves the centre by f/Z px per metre, along it not at all.
    assert jac[0, 0] == pytest.approx(DEPLOYED.fx / z) and jac[1, 0] == 0
    assert jac[1, 1] == pytest.approx(DEPLOYED.fy / z) and jac[0, 1] == 0
    assert np.all(jac[:, 2] == 0)
    # Rotation about x_c tilts the centre ray along v by fy px/rad, about y_c along u by fx px/rad;
    # rotation about the optical axis leaves the centre in place.
    np.testing.assert_allclose(jac[:, 3], [0.0, -DEPLOYED.fy], atol=1e-9)
    np.testing.assert_allclose(jac[:, 4], [DEPLOYED.fx, 0.0], atol=1e-9)
    np.testing.assert_allclose(jac[:, 5], [0.0, 0.0], atol=1e-9)
    # In interface order. The method's mount: roll turns the camera about x, so it moves the centre
    # along v; pitch along u. The nadir mount (image top = nose): roll along u, pitch along v. Yaw
    # turns about the optical axis and leaves the centre in place on both.
    g = sb.gains(DEPLOYED, DEPLOYED.cx, DEPLOYED.cy, z, mount)[0]
    focal = {"fx": DEPLOYED.fx, "fy": DEPLOYED.fy}
    np.testing.assert_allclose(g, [(DEPLOYED.fx / z) ** 2, (DEPLOYED.fy / z) ** 2, 0, focal[roll_gain] ** 2,
                                   focal[pitch_gain] ** 2, 0], atol=1e-6)


# Camera axes in the FRD body (columns: camera x, y, z) and the sign with which a body Euler error
# δ (roll, pitch, yaw) appears in the camera rotation φ: a body-frame right perturbation seen as a
# left perturbation of T_cam_world. Method: camera x = body forward (image right to the nose), so
# roll δ → φ_x = −δ, pitch δ → φ_y = −δ, yaw δ → φ_z = −δ. Nadir, image top = nose: camera x = body
# right, y = −body forward, so roll δ → φ_y = +δ, pitch δ → φ_x = −δ, yaw δ → φ_z = −δ.
PHYSICAL_MOUNTS = [
    (sb.METHOD_MOUNT, np.eye(3), (-1.0, -1.0, -1.0)),
    (sb.NADIR_MOUNT, np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]]), (1.0, -1.0, -1.0)),
]


@pytest.mark.parametrize("mount, r_body_cam, signs", PHYSICAL_MOUNTS, ids=lambda m: getattr(m, "key", ""))
def test_roll_pitch_yaw_map_to_camera_rotations_as_documented(mount, r_body_cam, signs):
    """Perturb body Euler angles (FRD body, the mount's nadir camera) and re-project."""
    yaw0, z, h = math.radians(35.0), 15.0, 1e-7
    pixels = [(0, 0), (1920, 1200), (DEPLOYED.cx, DEPLOYED.cy), (1500, 200)]
    jac = sb.pixel_jacobian(DEPLOYED, [p[0] for p in pixels], [p[1] for p in pixels], z)[..., mount.input_to_xi]
    for axis, sign in zip((3, 4, 5), signs):
        for k, (u, v) in enumerate(pixels):
            x_ned = euler_zyx_to_rotmat(0.0, 0.0, yaw0) @ r_body_cam @ _back_project(DEPLOYED, u, v, z)

            def pixel(delta):
                angles = [0.0, 0.0, yaw0]
                angles[axis - 3] += delta
                x_cam = r_body_cam.T @ euler_zyx_to_rotmat(*angles).T @ x_ned
                return _project(DEPLOYED, x_cam)

            fd = (pixel(h) - pixel(-h)) / (2 * h)
            np.testing.assert_allclose(fd, sign * jac[k, :, axis], rtol=1e-5, atol=1e-2)


def test_grid_is_the_pixel_centres_with_both_edges():
    small = sb.Intrinsics(fx=50.0, fy=55.0, cx=9.7, cy=6.2, width=20, height=13)
    us, vs = sb.frame_grid(small, 1)
    np.testing.assert_array_equal(us, np.arange(20))   # every pixel centre, the last one at W − 1
    np.testing.assert_array_equal(vs, np.arange(13))
    assert sb.lmax_field(small, 10.0, DEPLOYED_SIGMAS, 1).shape == (13, 20)
    us, vs = sb.frame_grid(small, 7)
    np.testing.assert_array_equal(us, [0, 7, 14, 19])
    np.testing.assert_array_equal(vs, [0, 7, 12])
    us, vs = sb.frame_grid(DEPLOYED, 1)
    assert (us.size, vs.size) == (1920, 1200)


@pytest.mark.parametrize("stride", [1, 7, 64])
@pytest.mark.parametrize("intr", [DEPLOYED, SKEWED, sb.Intrinsics(fx=50.0, fy=55.0, cx=15.0, cy=2.0, width=20,
                                                                  height=13)])
def test_the_worst_pixels_are_pixels_of_the_frame(intr, stride):
    """A W × H image spans u ∈ [−0.5, W − 0.5] (docs/design.md §3.3): every reported pixel is one of its centres."""
    res = sb.evaluate_bound(intr, 10.0, [0.02, 0.01, 0.05, 0.05, 0.1, 0.2], 30.0, stride_px=stride)
    for u, v in (res.worst_pixel, res.worst_pixel_trace, sb.trace_binding_corner(intr)):
        assert 0 <= u <= intr.width - 1 and 0 <= v <= intr.height - 1
        assert u == int(u) and v == int(v)
    # The far corners are the image's last pixels: the bound grows towards the edges.
    assert sb.trace_binding_corner(intr)[0] in (0.0, intr.width - 1.0)


def test_separable_sweep_matches_per_pixel_eigenvalues():
    sigmas = [0.03, 0.012, 0.08, 0.1, 0.02, 0.3]
    us, vs = sb.frame_grid(DEPLOYED, 40)
    uu, vv = np.meshgrid(us, vs)
    cov = sb.pixel_covariance(DEPLOYED, uu.ravel(), vv.ravel(), 11.0, sb.sigmas_to_variances(sigmas))
    eig = np.linalg.eigvalsh(cov)
    np.testing.assert_allclose(sb.lmax_field(DEPLOYED, 11.0, sigmas, 40).ravel(), eig[:, -1], rtol=1e-12)
    np.testing.assert_allclose(sb.trace_field(DEPLOYED, 11.0, sigmas, 40).ravel(), eig.sum(axis=1), rtol=1e-12)


def test_evaluate_bound_reports_grid_suprema_and_their_pixels():
    sigmas = [0.02, 0.005, 0.03, 0.2, 0.01, 0.05]
    res = sb.evaluate_bound(SKEWED, 9.0, sigmas, 30.0, stride_px=12)
    us, vs = sb.frame_grid(SKEWED, 12)
    for field, sup, pixel in ((sb.lmax_field(SKEWED, 9.0, sigmas, 12), res.sup_lmax_px2, res.worst_pixel),
                              (sb.trace_field(SKEWED, 9.0, sigmas, 12), res.sup_trace_px2, res.worst_pixel_trace)):
        row, col = np.unravel_index(np.argmax(field), field.shape)
        assert sup == pytest.approx(field.max(), rel=1e-12)
        assert pixel == (us[col], vs[row])
    assert res.kappa_exact == pytest.approx(res.lambda_target_px2 / res.sup_lmax_px2)
    assert res.lambda_target_px2 == pytest.approx(100.0)


def test_kappa_is_homogeneous_in_the_variances():
    base = sb.evaluate_bound(DEPLOYED, 10.0, DEPLOYED_SIGMAS, 30.0, stride_px=16)
    for c in (0.25, 3.0, 40.0):
        scaled = sb.evaluate_bound(DEPLOYED, 10.0, np.array(DEPLOYED_SIGMAS) * math.sqrt(c), 30.0, stride_px=16)
        assert scaled.sup_trace_px2 == pytest.approx(c * base.sup_trace_px2, rel=1e-12)
        assert scaled.sup_lmax_px2 == pytest.approx(c * base.sup_lmax_px2, rel=1e-12)
        assert scaled.kappa_exact == pytest.approx(base.kappa_exact / c, rel=1e-12)
        assert scaled.kappa_trace == pytest.approx(base.kappa_trace / c, rel=1e-12)
        assert scaled.verdict_exact == ("accept" if base.kappa_exact / c >= 1 else "reject")
    # Scaling by exactly κ* puts the budget on the boundary.
    edge = sb.evaluate_bound(DEPLOYED, 10.0, np.array(DEPLOYED_SIGMAS) * math.sqrt(base.kappa_exact), 30.0, 16)
    assert edge.sup_lmax_px2 == pytest.approx(edge.lambda_target_px2, rel=1e-12)


def test_altitude_scaling_translation_only_and_rotation_only():
    translation = [0.01, 0.02, 0.06, 0, 0, 0]
    rotation = [0, 0, 0, 0.04, 0.04, 0.13]
    sups_t = [sb.evaluate_bound(DEPLOYED, z, translation, stride_px=24).sup_lmax_px2 * z ** 2 for z in (5, 10, 20, 40)]
    sups_r = [sb.evaluate_bound(DEPLOYED, z, rotation, stride_px=24).sup_lmax_px2 for z in (5, 10, 20, 40)]
    np.testing.assert_allclose(sups_t, sups_t[0], rtol=1e-12)
    np.testing.assert_allclose(sups_r, sups_r[0], rtol=1e-12)


def test_trace_dominates_lmax_for_random_budgets():
    rng = np.random.default_rng(7)
    for _ in range(20):
        sigmas = rng.uniform(0, 1, 6) * [0.1, 0.1, 0.2, 0.5, 0.5, 1.0]
        z = rng.uniform(2, 60)
        tr = sb.trace_field(SKEWED, z, sigmas, 50)
        lm = sb.lmax_field(SKEWED, z, sigmas, 50)
        assert np.all(tr >= lm * (1 - 1e-12))
        assert np.all(tr <= 2 * lm * (1 + 1e-12))


def test_trace_allocation_binds_at_the_far_corner_with_equal_shares():
    for intr, z in ((DEPLOYED, 10.0), (SKEWED, 7.0)):
        s = sb.balanced_trace_variances(intr, z, 30.0)
        corner = sb.trace_binding_corner(intr)
        res = sb.evaluate_bound(intr, z, sb.variances_to_sigmas(s), 30.0, stride_px=1 if intr is DEPLOYED else 3)
        assert res.sup_trace_px2 == pytest.approx(100.0, rel=1e-12)
        assert res.worst_pixel_trace == corner
        contrib = sb.gains(intr, *corner, z)[0] * s
        np.testing.assert_allclose(contrib, 100.0 / 6, rtol=1e-12)
    assert sb.trace_binding_corner(DEPLOYED) == (1919.0, 1199.0)
    assert sb.trace_binding_corner(SKEWED) == (0.0, 0.0)


def _independent_exact_allocation(intr, z, lam, stride, n_dirs=90):
    """max Σ log s under λ_max ≤ λ imposed along many fixed directions at every grid pixel (a relaxation)."""
    us, vs = sb.frame_grid(intr, stride)
    uu, vv = np.meshgrid(us, vs)
    jac = sb.pixel_jacobian(intr, uu.ravel(), vv.ravel(), z)[..., sb.METHOD_MOUNT.input_to_xi]
    theta = np.linspace(0, np.pi, n_dirs, endpoint=False)
    dirs = np.stack([np.cos(theta), np.sin(theta)], 1)
    cuts = (np.einsum("kd,ndi->nki", dirs, jac) ** 2).reshape(-1, 6)
    scale = sb.balanced_trace_variances(intr, z, 3 * math.sqrt(lam))
    m = cuts * scale / lam
    # Any subset of constraints is still a relaxation; keep those that bind for a balanced budget.
    m = m[m.sum(axis=1) > 0.5 * m.sum(axis=1).max()]
    res = minimize(lambda t: -t.sum(), np.zeros(6), jac=lambda t: -np.ones(6), method="SLSQP",
                   constraints=[{"type": "ineq", "fun": lambda t: 1 - m @ np.exp(t), "jac": lambda t: -m * np.exp(t)}],
                   options={"ftol": 1e-14, "maxiter": 1000})
    return scale * np.exp(res.x)


@pytest.mark.parametrize("intr,z,stride", [(DEPLOYED, 10.0, 8), (SKEWED, 12.0, 8)])
def test_exact_allocation_is_feasible_tight_and_optimal(intr, z, stride):
    lam = 100.0
    s, iterations = sb.balanced_exact_variances(intr, z, 30.0, stride)
    sup = sb.lmax_field(intr, z, sb.variances_to_sigmas(s), stride).max()
    assert sup == pytest.approx(lam, rel=1e-9)
    trace_alloc = sb.balanced_trace_variances(intr, z, 30.0)
    assert np.log(s).sum() > np.log(trace_alloc).sum() + 0.1
    # Against an independent relaxation (coarser pixels, fixed directions): its optimum may only be
    # higher, and scaled back to feasibility it may only be lower.
    other = _independent_exact_allocation(intr, z, lam, 4 * stride)
    other_sup = sb.lmax_field(intr, z, sb.variances_to_sigmas(other), stride).max()
    assert np.log(other).sum() >= np.log(s).sum() - 1e-5
    assert np.log(other * lam / other_sup).sum() <= np.log(s).sum() + 1e-5
    assert abs(np.log(other).sum() - np.log(s).sum()) < 1e-2
    if intr is SKEWED:
        assert iterations > 2  # the cutting-plane loop itself was exercised


def test_deployed_platform_verdicts_and_json_contract():
    out = sb.evaluate_bounds(DEPLOYED, [10.0, 20.0], DEPLOYED_SIGMAS, tolerance_px=30.0, stride_px=4)
    json.dumps(out, allow_nan=False)
    required = {"altitude_m", "sup_trace_px2", "sup_lmax_px2", "kappa_trace", "kappa_exact", "verdict_trace",
                "verdict_exact", "worst_pixel", "balanced_trace_sigma", "balanced_exact_sigma", "budget_share"}
    at10, at20 = out["altitudes"]
    assert required <= set(at10)
    # At 10 m the linear trace condition is too pessimistic while the exact bound accepts.
    assert (at10["verdict_trace"], at10["verdict_exact"]) == ("reject", "accept")
    assert at10["kappa_trace"] < 1 < at10["kappa_exact"]
    assert (at20["verdict_trace"], at20["verdict_exact"]) == ("accept", "accept")
    assert at20["kappa_exact"] > at10["kappa_exact"]
    assert at10["worst_pixel"] == [1919.0, 1199.0]   # the bottom-right pixel of the 1920 × 1200 frame
    assert sum(at10["budget_share"]) == pytest.approx(1.0)
    # z dominates the deployed budget at 10 m; at 20 m translation matters less, rotation more.
    assert np.argmax(at10["budget_share"]) == 2
    assert sum(at20["budget_share"][3:]) > sum(at10["budget_share"][3:])
    assert out["inputs"]["sigmas"] == pytest.approx(DEPLOYED_SIGMAS)
    assert out["inputs"]["lambda_target_px2"] == pytest.approx(100.0)


def test_budget_share_uses_gains_at_the_exact_worst_pixel():
    res = sb.evaluate_bound(SKEWED, 8.0, [0.02, 0.01, 0.05, 0.05, 0.1, 0.2], 30.0, stride_px=20)
    contrib = sb.gains(SKEWED, *res.worst_pixel, 8.0)[0] * sb.sigmas_to_variances([0.02, 0.01, 0.05, 0.05, 0.1, 0.2])
    np.testing.assert_allclose(res.budget_share, contrib / contrib.sum(), rtol=1e-12)


def test_zero_budget_is_accepted_with_null_kappa_in_json():
    res = sb.evaluate_bound(DEPLOYED, 10.0, [0] * 6, stride_px=64)
    assert res.kappa_exact == math.inf and res.verdict_exact == "accept"
    d = res.to_json_dict()
    assert d["kappa_exact"] is None and d["budget_share"] == [0.0] * 6
    json.dumps(d, allow_nan=False)


def test_progress_cancel_and_duck_typed_intrinsics():
    cam = SimpleNamespace(fx=800.0, fy=810.0, cx=320.0, cy=240.0, width=640, height=480, dist=(0.1, 0, 0, 0, 0))
    seen = []
    out = sb.evaluate_bounds(cam, [5, 10, 20], DEPLOYED_SIGMAS, 20.0, 8, progress=seen.append)
    assert seen == pytest.approx([1 / 3, 2 / 3, 1.0])
    assert [a["altitude_m"] for a in out["altitudes"]] == [5.0, 10.0, 20.0]
    calls = []

    def cancel_second():
        calls.append(1)
        return len(calls) > 1

    with pytest.raises(Cancelled):
        sb.evaluate_bounds(cam, [5, 10, 20], DEPLOYED_SIGMAS, 20.0, 8, is_canceled=cancel_second)


def test_units_and_input_validation():
    s = sb.sigmas_to_variances([1, 2, 3, 1, 2, 180])
    np.testing.assert_allclose(s, [1, 4, 9, (math.pi / 180) ** 2, (2 * math.pi / 180) ** 2, math.pi ** 2])
    np.testing.assert_allclose(sb.variances_to_sigmas(s), [1, 2, 3, 1, 2, 180])
    with pytest.raises(InputError):
        sb.sigmas_to_variances([0.01, 0.01, -0.06, 0.04, 0.04, 0.13])
    with pytest.raises(InputError):
        sb.sigmas_to_variances([0.01, 0.01, 0.06])
    with pytest.raises(InputError):
        sb.evaluate_bound(DEPLOYED, 0.0, DEPLOYED_SIGMAS)
    with pytest.raises(InputError):
        sb.evaluate_bound(DEPLOYED, 10.0, DEPLOYED_SIGMAS, tolerance_px=0)
    with pytest.raises(InputError):
        sb.frame_grid(DEPLOYED, 2.5)
    with pytest.raises(InputError):
        sb.evaluate_bounds(DEPLOYED, [], DEPLOYED_SIGMAS)


def _printed(camera, mount):
    """The balanced exact budget and the deployed budget's shares at 10 m, printed as the method prints them."""
    from birdseye.birdseye_qgis.core.design.platforms import DEPLOYED as PRESET

    budget, _ = sb.balanced_exact_variances(camera, 10.0, PRESET.tolerance_px, mount=mount)
    sigmas = sb.variances_to_sigmas(budget)
    shares = sb.evaluate_bound(camera, 10.0, PRESET.sigmas, PRESET.tolerance_px, mount=mount).budget_share
    return {"budget": [f"{1000 * s:.2f} mm" for s in sigmas[:3]] + [f"{s:.4f}°" for s in sigmas[3:]],
            "share": [f"{100 * s:.1f} %" for s in shares]}


def test_the_deployed_preset_gives_the_methods_table_to_the_printed_digit():
    """The method's table at 10 m (r = 30 px): the balanced exact budget and the shares of the deployed
    budget, as the method prints them. The method evaluated u = 0…W, v = 0…H, one pixel beyond the last
    pixel centre: the pixel centres of a frame one pixel wider and taller. Its mount applies roll to camera
    x and pitch to camera y; on the nadir mount (image top = nose) the two trade places, roll and pitch
    swapped."""
    from dataclasses import replace

    from birdseye.birdseye_qgis.core.design.platforms import DEPLOYED as PRESET

    assert PRESET.mount is sb.METHOD_MOUNT
    methods_grid = replace(PRESET.camera, width=PRESET.camera.width + 1, height=PRESET.camera.height + 1)
    table = {"budget": ["13.64 mm", "13.45 mm", "49.12 mm", "0.0753°", "0.0741°", "0.3013°"],
             "share": ["16.7 %", "16.7 %", "42.9 %", "8.5 %", "9.0 %", "6.1 %"]}
    swapped = {key: column[:3] + [column[4], column[3], column[5]] for key, column in table.items()}
    for mount, expected in ((PRESET.mount, table), (sb.NADIR_MOUNT, swapped)):
        assert _printed(methods_grid, mount) == expected
    # On the frame's own pixels the corners are a pixel closer to the centre: z and yaw may grow a little.
    assert _printed(PRESET.camera, PRESET.mount) == {
        "budget": ["13.64 mm", "13.45 mm", "49.19 mm", "0.0753°", "0.0741°", "0.3016°"],
        "share": ["16.8 %", "16.8 %", "42.8 %", "8.5 %", "9.0 %", "6.1 %"]}


def test_mounts_are_signed_axis_permutations():
    assert sb.METHOD_MOUNT.input_to_xi.tolist() == [0, 1, 2, 3, 4, 5]
    assert sb.NADIR_MOUNT.input_to_xi.tolist() == [0, 1, 2, 4, 3, 5]
    np.testing.assert_array_equal(sb.NADIR_MOUNT.xi_variances([1, 2, 3, 4, 5, 6]), [1, 2, 3, 5, 4, 6])
    assert sb.camera_mount("nadir_top_forward") is sb.NADIR_MOUNT
    with pytest.raises(InputError, match="method, nadir_top_forward"):
        sb.camera_mount("sideways")
    tilted = ((1.0, 0.0, 0.0), (0.0, math.cos(0.3), -math.sin(0.3)), (0.0, math.sin(0.3), math.cos(0.3)))
    with pytest.raises(InputError, match="signed permutation"):
        sb.CameraMount("tilted", "tilted", tilted, "")
    with pytest.raises(InputError, match="signed permutation"):
        sb.CameraMount("doubled", "doubled", ((1.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 0.0, 1.0)), "")

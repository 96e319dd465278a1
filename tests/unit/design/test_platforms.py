"""Platform presets: the DJI metadata preset from its published figures, and why it fails the label
tolerance — checked by moving a nadir camera by each axis's 1σ and re-projecting (no Jacobian)."""
import math

import numpy as np
import pytest

from birdseye.birdseye_qgis.core.design import sensor_bound as sb
from birdseye.birdseye_qgis.core.design.platforms import DEPLOYED, DJI_METADATA, PLATFORMS, platform
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp


def test_the_dji_preset_is_the_published_camera_and_rtk_figures():
    cam = DJI_METADATA.camera
    assert (cam.width, cam.height) == (5280, 3956)
    # 84° diagonal field of view: the corner rays lie 42° off the optical axis.
    corner = math.hypot(cam.width / 2.0, cam.height / 2.0)
    assert math.degrees(math.atan(corner / cam.fx)) == pytest.approx(42.0, abs=1e-6) and cam.fx == cam.fy
    # RTK 1 cm + 1 ppm horizontal, 1.5 cm + 1 ppm vertical, at a 1 km baseline.
    assert DJI_METADATA.sigmas[:3] == pytest.approx((0.011, 0.011, 0.016))
    assert DJI_METADATA.sigmas[3:] == (0.5, 0.5, 1.0)
    assert platform("dji_metadata") is DJI_METADATA and PLATFORMS[0] is DEPLOYED
    with pytest.raises(KeyError, match="deployed, dji_metadata"):
        platform("mavic")


def displacement_px(cam, altitude, u, v, axis, sigma):
    """Pixel shift of the ground point seen at (u, v) when a nadir camera at ``altitude`` moves by
    ``sigma`` along one interface axis (x, y, z in m; roll, pitch, yaw in degrees), by re-projection.
    Camera frame: x image right, y image down, z down; roll about −y (body forward = image up),
    pitch about x, yaw about z (the module's convention)."""
    ground = np.array([(u - cam.cx) / cam.fx * altitude, (v - cam.cy) / cam.fy * altitude, altitude])
    shift, turn = np.zeros(3), np.zeros(3)
    if axis < 3:
        shift[axis] = sigma
    else:
        turn[{3: 1, 4: 0, 5: 2}[axis]] = math.radians(sigma) * (-1.0 if axis == 3 else 1.0)
    seen = so3_exp(turn).T @ (ground - shift)   # the ground point in the moved camera's frame
    moved = np.array([cam.fx * seen[0] / seen[2] + cam.cx, cam.fy * seen[1] / seen[2] + cam.cy])
    return float(np.hypot(*(moved - [u, v])))


def test_the_dji_metadata_preset_fails_the_default_tolerance_at_10_m_because_of_its_attitude():
    cam, sigmas = DJI_METADATA.camera, DJI_METADATA.sigmas
    bound = sb.evaluate_bound(cam, 10.0, sigmas, DJI_METADATA.tolerance_px, stride_px=8, mount=DJI_METADATA.mount)
    sigma_label = DJI_METADATA.tolerance_px / 3.0
    assert bound.verdict_exact == "reject" and bound.kappa_exact < 0.05
    # Why: at the worst pixel (a frame corner) one σ of each axis alone moves the label by …
    u, v = bound.worst_pixel
    assert u in (0.0, cam.width - 1.0) and v in (0.0, cam.height - 1.0)
    moves = [displacement_px(cam, 10.0, u, v, axis, s) for axis, s in enumerate(sigmas)]
    print("1σ label displacement at the worst pixel (x, y, z, roll, pitch, yaw):",
          ", ".join(f"{m:.1f} px" for m in moves))
    # … the heading most: yaw dominates, and each attitude axis alone exceeds σ_label = r/3 = 10 px,
    # while the RTK position (x, y, z) moves it by a few pixels.
    assert int(np.argmax(moves)) == 5 and all(m > sigma_label for m in moves[3:])
    assert math.hypot(*moves[:3]) < sigma_label
    # The bound's own share of the budget agrees: attitude carries nearly all of it, yaw the most.
    share = bound.budget_share
    assert int(np.argmax(share)) == 5 and sum(share[3:]) > 0.95
    # The RTK position alone passes; any one attitude axis alone fails.
    position_only = sb.evaluate_bound(cam, 10.0, list(sigmas[:3]) + [0.0] * 3, 30.0, stride_px=8,
                                      mount=DJI_METADATA.mount)
    assert position_only.verdict_exact == "accept"
    for axis in (3, 4, 5):
        alone = [0.0] * 6
        alone[axis] = sigmas[axis]
        alone_bound = sb.evaluate_bound(cam, 10.0, alone, 30.0, stride_px=8, mount=DJI_METADATA.mount)
        assert alone_bound.verdict_exact == "reject"
    # Roll and pitch share one sigma, so the method's mount (roll and pitch swapped) gives the same bound.
    assert DJI_METADATA.mount is sb.NADIR_MOUNT
    on_method_mount = sb.evaluate_bound(cam, 10.0, sigmas, 30.0, stride_px=8, mount=sb.METHOD_MOUNT)
    assert on_method_mount.sup_lmax_px2 == pytest.approx(bound.sup_lmax_px2, rel=1e-12)


def test_displacement_agrees_with_the_bound_jacobian():
    """The re-projection above and the sensor bound's first-order Jacobian describe the same moves."""
    cam = DJI_METADATA.camera
    for axis, s in enumerate(DJI_METADATA.sigmas):
        step = [0.0] * 6
        step[axis] = s
        for u, v in ((0.0, 0.0), (cam.width, cam.height), (1200.0, 3100.0)):
            linear = math.sqrt(float(sb.gains(cam, u, v, 10.0, DJI_METADATA.mount)[0] @ sb.sigmas_to_variances(step)))
            assert displacement_px(cam, 10.0, u, v, axis, s) == pytest.approx(linear, rel=0.03)

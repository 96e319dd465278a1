"""Rotation and pose conventions used throughout BirdsEye.

Conventions (docs/design.md#attitude), stated once here:

* Body / INS frame: x forward, y right, z down (FRD).
* Attitude quaternion ``q = (qw, qx, qy, qz)`` (Hamilton, scalar first) with
  ``v_ned = R(q) @ v_body``.
* Euler angles are the aerospace ZYX sequence: ``R = Rz(yaw) @ Ry(pitch) @ Rx(roll)``;
  yaw is measured clockwise from *true* north (towards east), pitch positive nose up,
  roll positive right wing down.
* NED ↔ ENU: ``v_enu = R_ENU_NED @ v_ned`` with the fixed permutation/flip below.
* SE(3) perturbations ξ = [ρ, φ] (translation first, rotation second) act on the left:
  ``T' = exp(ξ^) @ T``.

All functions are vectorised over leading dimensions; angles are radians.
"""
from __future__ import annotations

import numpy as np

R_ENU_NED = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])


def quat_to_rotmat(q: np.ndarray) -> np.ndarray:
    """Rotation matrices (..., 3, 3) from quaternions (..., 4) in (w, x, y, z) order.

    Quaternions are normalised first, so slightly drifted INS output is accepted.
    """
    q = np.asarray(q, dtype=float)
    q = q / np.linalg.norm(q, axis=-1, keepdims=True)
    w, x, y, z = np.moveaxis(q, -1, 0)
    r = np.empty(q.shape[:-1] + (3, 3))
    r[..., 0, 0] = 1 - 2 * (y * y + z * z)
    r[..., 0, 1] = 2 * (x * y - w * z)
    r[..., 0, 2] = 2 * (x * z + w * y)
    r[..., 1, 0] = 2 * (x * y + w * z)
    r[..., 1, 1] = 1 - 2 * (x * x + z * z)
    r[..., 1, 2] = 2 * (y * z - w * x)
    r[..., 2, 0] = 2 * (x * z - w * y)
    r[..., 2, 1] = 2 * (y * z + w * x)
    r[..., 2, 2] = 1 - 2 * (x * x + y * y)
    return r


def rotmat_to_quat(r: np.ndarray) -> np.ndarray:
    """Quaternions (..., 4) in (w, x, y, z) order with w ≥ 0 from rotation matrices (..., 3, 3)."""
    r = np.asarray(r, dtype=float)
    m = r.reshape(-1, 3, 3)
    out = np.empty((m.shape[0], 4))
    trace = np.trace(m, axis1=1, axis2=2)
    # Pick, per matrix, the numerically largest of w, x, y, z to divide by (Shepperd's method).
    cand = np.stack([trace, m[:, 0, 0], m[:, 1, 1], m[:, 2, 2]], axis=1)
    k = np.argmax(cand, axis=1)
    for case in range(4):
        sel = k == case
        if not np.any(sel):
            continue
        a = m[sel]
        if case == 0:
            s = np.sqrt(1.0 + trace[sel]) * 2
            q = np.stack([0.25 * s, (a[:, 2, 1] - a[:, 1, 2]) / s,
                          (a[:, 0, 2] - a[:, 2, 0]) / s, (a[:, 1, 0] - a[:, 0, 1]) / s], 1)
        elif case == 1:
            s = np.sqrt(1.0 + a[:, 0, 0] - a[:, 1, 1] - a[:, 2, 2]) * 2
            q = np.stack([(a[:, 2, 1] - a[:, 1, 2]) / s, 0.25 * s,
                          (a[:, 0, 1] + a[:, 1, 0]) / s, (a[:, 0, 2] + a[:, 2, 0]) / s], 1)
        elif case == 2:
            s = np.sqrt(1.0 + a[:, 1, 1] - a[:, 0, 0] - a[:, 2, 2]) * 2
            q = np.stack([(a[:, 0, 2] - a[:, 2, 0]) / s, (a[:, 0, 1] + a[:, 1, 0]) / s,
                          0.25 * s, (a[:, 1, 2] + a[:, 2, 1]) / s], 1)
        else:
            s = np.sqrt(1.0 + a[:, 2, 2] - a[:, 0, 0] - a[:, 1, 1]) * 2
            q = np.stack([(a[:, 1, 0] - a[:, 0, 1]) / s, (a[:, 0, 2] + a[:, 2, 0]) / s,
                          (a[:, 1, 2] + a[:, 2, 1]) / s, 0.25 * s], 1)
        out[sel] = q
    out *= np.where(out[:, :1] < 0, -1.0, 1.0)
    return out.reshape(r.shape[:-2] + (4,))


def euler_zyx_to_rotmat(roll, pitch, yaw) -> np.ndarray:
    """``Rz(yaw) @ Ry(pitch) @ Rx(roll)`` (body → NED), shape broadcast(...) + (3, 3)."""
    roll, pitch, yaw = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (roll, pitch, yaw)))
    cr, sr = np.cos(roll), np.sin(roll)
    cp, sp = np.cos(pitch), np.sin(pitch)
    cy, sy = np.cos(yaw), np.sin(yaw)
    r = np.empty(roll.shape + (3, 3))
    r[..., 0, 0] = cy * cp
    r[..., 0, 1] = cy * sp * sr - sy * cr
    r[..., 0, 2] = cy * sp * cr + sy * sr
    r[..., 1, 0] = sy * cp
    r[..., 1, 1] = sy * sp * sr + cy * cr
    r[..., 1, 2] = sy * sp * cr - cy * sr
    r[..., 2, 0] = -sp
    r[..., 2, 1] = cp * sr
    r[..., 2, 2] = cp * cr
    return r


#: Below this cos(pitch) the attitude is in gimbal lock (pitch ±90°, a nadir gimbal): roll and yaw turn about
#: the same axis, and the entries that would split them are rounding noise (float32 quaternions: ~1e-7).
GIMBAL_LOCK_COS = 1e-6


def rotmat_to_euler_zyx(r: np.ndarray):
    """(roll, pitch, yaw) in radians from body → NED rotation matrices (..., 3, 3).

    At gimbal lock (|pitch| = 90° within :data:`GIMBAL_LOCK_COS`) the whole turn about the vertical is yaw
    and roll is 0, as DJI writes a nadir gimbal: only yaw ± roll is defined there, and splitting it from
    noise would turn a heading of 30° into, say, yaw 90°, roll 60°.
    """
    r = np.asarray(r, dtype=float)
    cos_pitch = np.hypot(r[..., 0, 0], r[..., 1, 0])
    pitch = np.arctan2(-r[..., 2, 0], cos_pitch)
    locked = cos_pitch < GIMBAL_LOCK_COS
    roll = np.where(locked, 0.0, np.arctan2(r[..., 2, 1], r[..., 2, 2]))
    # Locked: R = Rz(yaw ± roll)·Ry(±90°), whose first and second rows give that angle as atan2(−r01, r11).
    yaw = np.where(locked, np.arctan2(-r[..., 0, 1], r[..., 1, 1]), np.arctan2(r[..., 1, 0], r[..., 0, 0]))
    return roll, pitch, yaw


def hat(v: np.ndarray) -> np.ndarray:
    """Skew-symmetric matrices (..., 3, 3) with ``hat(a) @ b == cross(a, b)``."""
    v = np.asarray(v, dtype=float)
    x, y, z = np.moveaxis(v, -1, 0)
    zero = np.zeros_like(x)
    return np.stack([np.stack([zero, -z, y], -1),
                     np.stack([z, zero, -x], -1),
                     np.stack([-y, x, zero], -1)], -2)


def so3_exp(phi: np.ndarray) -> np.ndarray:
    """Rodrigues' formula: rotation matrices (..., 3, 3) from rotation vectors (..., 3)."""
    phi = np.asarray(phi, dtype=float)
    theta = np.linalg.norm(phi, axis=-1)[..., None, None]
    k = hat(phi)
    small = theta < 1e-8
    safe = np.where(small, 1.0, theta)
    a = np.where(small, 1.0 - theta ** 2 / 6.0, np.sin(safe) / safe)
    b = np.where(small, 0.5 - theta ** 2 / 24.0, (1.0 - np.cos(safe)) / safe ** 2)
    return np.eye(3) + a * k + b * (k @ k)


def so3_left_jacobian(phi: np.ndarray) -> np.ndarray:
    """Left Jacobian of SO(3) (..., 3, 3), used by the SE(3) exponential."""
    phi = np.asarray(phi, dtype=float)
    theta = np.linalg.norm(phi, axis=-1)[..., None, None]
    k = hat(phi)
    small = theta < 1e-6
    safe = np.where(small, 1.0, theta)
    b = np.where(small, 0.5 - theta ** 2 / 24.0, (1.0 - np.cos(safe)) / safe ** 2)
    c = np.where(small, 1.0 / 6.0 - theta ** 2 / 120.0, (safe - np.sin(safe)) / safe ** 3)
    return np.eye(3) + b * k + c * (k @ k)


def se3_exp(xi: np.ndarray) -> np.ndarray:
    """Homogeneous transforms (..., 4, 4) from twists ξ = [ρ, φ] (..., 6), exact exponential."""
    xi = np.asarray(xi, dtype=float)
    rho, phi = xi[..., :3], xi[..., 3:]
    t = np.eye(4) * np.ones(xi.shape[:-1] + (1, 1))
    t[..., :3, :3] = so3_exp(phi)
    t[..., :3, 3] = (so3_left_jacobian(phi) @ rho[..., None])[..., 0]
    return t


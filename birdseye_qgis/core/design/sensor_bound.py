"""Sensor-bound calculator: which pose-noise budget keeps every label inside its tolerance.

Model
-----
A nadir pinhole camera (``fx, fy, cx, cy`` in px, frame ``width × height`` px; the bound ignores lens
distortion) looks down on a level plane at depth ``Z`` = the flying altitude in metres. The ground
point seen at pixel ``u = (u, v)`` lies at ``X_c = Z · (x, y, 1)`` in the camera frame (OpenCV optical
frame: x right, y down, z forward), with normalised coordinates ``x = (u − cx)/fx``, ``y = (v − cy)/fy``.

Pose error is a *left* perturbation of ``T_cam_world`` (docs/design.md#pose-noise): ``X_c' = exp(ξ^) X_c`` with the
twist ``ξ = [ρ, φ]`` (ρ in metres, φ in radians, both in the camera frame). To first order the label
moves by ``J(u) ξ`` px with

    J(u) = ∂π/∂X_c · [I | −X_c^]
         = [[fx/Z,  0,    −fx·x/Z, −fx·x·y,      fx·(1 + x²), −fx·y],
            [0,     fy/Z, −fy·y/Z, −fy·(1 + y²), fy·x·y,      fy·x ]]

and, for ``Σ0 = diag(s)``, the label covariance is ``Σ_u = J diag(s) Jᵀ`` (px²). Writing ``j_i`` for the
i-th column of J, the gain of axis i at pixel u is ``g_i(u) = ‖j_i‖²`` and ``tr Σ_u = sᵀ g(u)``.

Criteria
--------
A label drawn with radius ``r`` px at 3σ asks for a per-direction variance of at most
``λ_target = (r/3)²`` px². Over the frame grid (below):

* **trace bound** ``sup_u sᵀ g(u) ≤ λ_target`` — linear in s, sufficient (``tr ≥ λ_max``);
* **exact bound** ``sup_u λ_max(Σ_u) ≤ λ_target`` — necessary and sufficient, convex in s (a supremum
  of the linear functions ``s ↦ Σ_i s_i (wᵀ j_i)²`` over unit ``w`` and pixels ``u``).

``κ* = λ_target / sup`` is the largest factor by which all variances of the deployed budget may be
scaled (sigmas by ``√κ*``) while the criterion still holds; the verdict is *accept* iff ``κ* ≥ 1``.

Balanced allocations maximise ``Σ_i log s_i`` (no axis is starved) under each criterion:

* Trace: every gain ``g_i`` is non-decreasing in ``|x|`` and in ``|y|`` (see ``pixel_jacobian``), so for
  *every* budget the trace binds at the corner pixel farthest from the principal point in both
  directions, ``u* = (argmax_{0,W−1} |u − cx|, argmax_{0,H−1} |v − cy|)``. With ``g* = g(u*)`` the
  Lagrange conditions give ``s_i = λ_target / (6 g*_i)``: each axis takes one sixth of the budget.
* Exact: solved by cutting planes (Kelley). Each cut is the tangent plane of ``λ_max(Σ_u(s))`` at the
  current iterate's worst pixel, ``Σ_i (wᵀ j_i)² s_i ≤ λ_target`` with ``w`` the top eigenvector there;
  the concave ``max Σ log s`` over the accumulated cuts is solved by SLSQP in ``t = log s``. Iteration
  stops when the relative violation ``sup λ_max / λ_target − 1`` drops below ``EXACT_TOLERANCE``; the
  iterate is then scaled onto the boundary, so the reported budget has ``sup λ_max = λ_target``.

Axis convention (interface order ``x, y, z, roll, pitch, yaw``; metres and degrees)
-----------------------------------------------------------------------------------
* ``x, y, z`` are the translation ρ in the camera frame. For a nadir camera x = image right and
  y = image down are horizontal, z (the optical axis) is vertical. RTK horizontal noise is normally
  isotropic (σx = σy), which makes the heading irrelevant.
* ``roll, pitch, yaw`` are attitude errors about the three axes of the frame the attitude is given in;
  a :class:`CameraMount` says how they turn the camera. A small rotation φ_b of those axes turns the
  camera by ``φ_c = R_cam_body φ_b``, so ``Σ_φc = R_cam_body diag(s_roll, s_pitch, s_yaw) R_cam_bodyᵀ``.
  Mounts are signed axis permutations, which keep that covariance diagonal (signs drop out of a
  diagonal Σ0): ``mount.input_to_xi[i]`` is the index in ξ = [ρx, ρy, ρz, φx, φy, φz] of interface
  axis i. Two mounts are offered (docs/design.md#pose-noise):

  - ``METHOD_MOUNT`` (the default): the method applies roll, pitch and yaw directly to the camera-frame
    rotation vector, roll → φ_x, pitch → φ_y, yaw → φ_z (``R_cam_body = I``). Physically this is a
    nadir camera whose image right points to the nose (camera x = body forward, y = body right,
    z = body down). With it the deployed budget's balanced allocation and shares are the method's
    table to the printed digit (tested).
  - ``NADIR_MOUNT``: a forward-right-down body (docs/design.md#attitude) carrying a nadir camera with
    the image top towards the nose: camera x = body right, camera y = −body forward, camera z = body
    down. Roll (about body forward) turns the camera about −y_c → φ_y, pitch (about body right) about
    x_c → φ_x, yaw (about body down) about the optical axis → φ_z. At level flight small Euler-angle
    errors equal body rotation-vector components. Consequence (tested): at the principal point a roll
    error moves the label along u by fx px/rad, pitch along v by fy px/rad, yaw not at all.

  The two differ only by swapping roll and pitch: with σ_roll = σ_pitch they give the same numbers.

Frame grid
----------
The pixel centres (docs/design.md#camera: pixel (0, 0) is the centre of the top-left pixel, the last one of a
``W × H`` frame is ``(W − 1, H − 1)``): ``u ∈ {0, stride, …, W − 1}``, ``v ∈ {0, stride, …, H − 1}``, the
last row and column included even when the stride does not divide ``W − 1`` or ``H − 1``; stride 1 gives
``W·H`` points, every pixel, and the worst pixel reported is always one of the frame's. (The method evaluated
``0…W × 0…H``, one pixel beyond the last centre on each side: its table is this grid on a frame one pixel
wider and taller.)
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Callable, Optional, Sequence

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.camera import NADIR_ROTATION
from ..geometry.rotations import hat
from ..labels.training_set import label_sigma_px

AXES = ("x", "y", "z", "roll", "pitch", "yaw")
SIGMA_UNITS = ("m", "m", "m", "deg", "deg", "deg")
TRANSLATION_CONVENTION = ("x, y, z: translation in the camera frame (x image right, y image down, z optical axis = "
                          "vertical for a nadir camera)")


@dataclass(frozen=True)
class CameraMount:
    """How attitude errors (roll, pitch, yaw) turn the camera: ``φ_cam = R_cam_body φ_body``.

    ``R_cam_body`` (3×3, rows = camera axes in body coordinates) must be a signed axis permutation,
    so that a diagonal Σ0 stays diagonal in the camera frame (see the module's axis convention).
    ``name`` is what a user picks from; ``convention`` spells the axes out for reports and JSON.
    """

    key: str
    name: str
    R_cam_body: tuple
    convention: str

    def __post_init__(self):
        r = np.asarray(self.R_cam_body, dtype=float)
        if r.shape != (3, 3) or not np.array_equal(np.abs(r) @ np.abs(r).T, np.eye(3)) or not np.all(
                np.isin(r, (-1.0, 0.0, 1.0))):
            raise InputError(f"camera mount {self.key!r}: R_cam_body must be a signed permutation of the axes, "
                             f"got {r.tolist()}")

    @property
    def input_to_xi(self) -> np.ndarray:
        """Index in ξ = [ρx, ρy, ρz, φx, φy, φz] of each interface axis (x, y, z, roll, pitch, yaw)."""
        camera_axis = np.argmax(np.abs(np.asarray(self.R_cam_body, dtype=float)), axis=0)
        return np.concatenate([[0, 1, 2], 3 + camera_axis])

    def xi_variances(self, variances) -> np.ndarray:
        """Pose variances (6,) in interface order, rearranged into ξ order."""
        s_xi = np.empty(6)
        s_xi[self.input_to_xi] = np.asarray(variances, dtype=float).reshape(6)
        return s_xi


METHOD_MOUNT = CameraMount(
    key="method", name="As the method: roll, pitch, yaw about camera x, y, z",
    R_cam_body=((1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)),
    convention=TRANSLATION_CONVENTION + "; roll, pitch, yaw -> rotations about camera x (image right), y (image "
               "down) and z (optical axis), applied to the camera-frame rotation vector as the method does")
NADIR_MOUNT = CameraMount(
    key="nadir_top_forward", name="Nadir camera, image top towards the nose",
    R_cam_body=tuple(map(tuple, NADIR_ROTATION.tolist())),
    convention=TRANSLATION_CONVENTION + "; roll, pitch, yaw: forward-right-down body attitude errors of a nadir "
               "camera with the image top towards the nose: roll -> rotation about camera y, pitch -> about "
               "camera x, yaw -> about the optical axis z")
MOUNTS = (METHOD_MOUNT, NADIR_MOUNT)


def camera_mount(key: str) -> CameraMount:
    """The mount called ``key``; InputError naming the known ones otherwise."""
    for mount in MOUNTS:
        if mount.key == key:
            return mount
    raise InputError(f"no camera mount {key!r}; known: {', '.join(m.key for m in MOUNTS)}")


EXACT_TOLERANCE = 1e-6
EXACT_MAX_ITERATIONS = 200
# Grid points evaluated at once: 64k float64 values (512 kB) keep every temporary array in cache.
_CHUNK_POINTS = 1 << 16


@dataclass
class Intrinsics:
    """Pinhole intrinsics: focal lengths and principal point in px, frame size in px.

    Any object with these attributes (e.g. ``camera.CameraModel``) is accepted wherever an
    ``Intrinsics`` is expected; distortion is ignored by the bound.
    """

    fx: float
    fy: float
    cx: float
    cy: float
    width: int
    height: int


def _camera(intr) -> tuple[float, float, float, float, int, int]:
    """Validated ``(fx, fy, cx, cy, width, height)`` from any object with those attributes."""
    fx, fy, cx, cy = (float(getattr(intr, k)) for k in ("fx", "fy", "cx", "cy"))
    width, height = int(intr.width), int(intr.height)
    if not (fx > 0 and fy > 0 and math.isfinite(fx) and math.isfinite(fy)):
        raise InputError(f"focal lengths must be positive, got fx={fx}, fy={fy}")
    if not (math.isfinite(cx) and math.isfinite(cy)):
        raise InputError(f"principal point must be finite, got ({cx}, {cy})")
    if width < 1 or height < 1:
        raise InputError(f"frame size must be positive, got {width}×{height} px")
    return fx, fy, cx, cy, width, height


def _altitude(altitude_m) -> float:
    z = float(altitude_m)
    if not (z > 0 and math.isfinite(z)):
        raise InputError(f"altitude must be a positive number of metres, got {altitude_m}")
    return z


def _stride(stride_px) -> int:
    if int(stride_px) != stride_px or stride_px < 1:
        raise InputError(f"grid stride must be a positive whole number of pixels, got {stride_px}")
    return int(stride_px)


def lambda_target(tolerance_px) -> float:
    """Per-direction variance budget ``σ_label² = (r/3)²`` px² for a label radius ``r`` px drawn at 3σ."""
    r = float(tolerance_px)
    if not (r > 0 and math.isfinite(r)):
        raise InputError(f"label tolerance must be a positive number of pixels, got {tolerance_px}")
    return label_sigma_px(r) ** 2


def sigmas_to_variances(sigmas_m_deg) -> np.ndarray:
    """Variances (6,) in m², m², m², rad², rad², rad² from sigmas (x, y, z m; roll, pitch, yaw deg)."""
    sig = np.asarray(sigmas_m_deg, dtype=float).reshape(-1)
    if sig.shape != (6,) or not np.all(np.isfinite(sig)) or np.any(sig < 0):
        raise InputError("pose sigmas must be six finite non-negative numbers "
                         f"(x, y, z in m; roll, pitch, yaw in degrees), got {list(np.ravel(sigmas_m_deg))}")
    scale = np.array([1.0, 1.0, 1.0, math.pi / 180.0, math.pi / 180.0, math.pi / 180.0])
    return (sig * scale) ** 2


def variances_to_sigmas(variances) -> np.ndarray:
    """Sigmas (6,) in m, m, m, deg, deg, deg from variances (m², m², m², rad², rad², rad²)."""
    s = np.asarray(variances, dtype=float).reshape(6)
    scale = np.array([1.0, 1.0, 1.0, 180.0 / math.pi, 180.0 / math.pi, 180.0 / math.pi])
    return np.sqrt(s) * scale


def frame_grid(intr, stride_px: int = 1) -> tuple[np.ndarray, np.ndarray]:
    """Grid columns ``u`` and rows ``v`` (px): pixel centres every ``stride_px``, the last pixel included."""
    _, _, _, _, width, height = _camera(intr)
    stride = _stride(stride_px)
    return _grid_axis(width, stride), _grid_axis(height, stride)


def _grid_axis(n: int, stride: int) -> np.ndarray:
    axis = np.arange(0, n, stride, dtype=float)
    return axis if axis[-1] == n - 1 else np.append(axis, float(n - 1))


def pixel_jacobian(intr, u, v, depth) -> np.ndarray:
    """``∂u/∂ξ`` (N, 2, 6): pixel motion per unit twist ξ = [ρx, ρy, ρz, φx, φy, φz] (camera frame).

    ``u, v`` (px) and ``depth`` (m) broadcast together and are flattened to N points. Evaluated as the
    product ``∂π/∂X_c · [I | −X_c^]`` at the back-projected point ``X_c = depth · (x, y, 1)``; the module
    docstring gives the closed form that the grid sweep uses. Columns are in ξ order: use
    ``J[..., mount.input_to_xi]`` for the interface order (x, y, z, roll, pitch, yaw).
    """
    fx, fy, cx, cy, _, _ = _camera(intr)
    u, v, z = (np.ravel(a) for a in np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (u, v, depth))))
    x, y = (u - cx) / fx, (v - cy) / fy
    xc = np.stack([x * z, y * z, z], axis=-1)
    dpi = np.zeros((u.size, 2, 3))
    dpi[:, 0, 0] = fx / z
    dpi[:, 0, 2] = -fx * x / z
    dpi[:, 1, 1] = fy / z
    dpi[:, 1, 2] = -fy * y / z
    lift = np.concatenate([np.broadcast_to(np.eye(3), (u.size, 3, 3)), -hat(xc)], axis=-1)
    return dpi @ lift


def gains(intr, u, v, depth, mount: CameraMount = METHOD_MOUNT) -> np.ndarray:
    """Gain vectors ``g_i = ‖j_i‖²`` (N, 6), interface order, in px²/m² and px²/rad²."""
    j = pixel_jacobian(intr, u, v, depth)[..., mount.input_to_xi]
    return np.sum(j * j, axis=-2)


def pixel_covariance(intr, u, v, depth, variances, mount: CameraMount = METHOD_MOUNT) -> np.ndarray:
    """Linearised label covariance ``Σ_u = J diag(s) Jᵀ`` (N, 2, 2) px².

    ``variances`` are the six pose variances in interface order (m², rad²), e.g. from
    ``sigmas_to_variances``; ``mount`` says how roll, pitch and yaw turn the camera.
    """
    j = pixel_jacobian(intr, u, v, depth)[..., mount.input_to_xi]
    s = np.asarray(variances, dtype=float).reshape(6)
    return (j * s) @ np.swapaxes(j, -1, -2)


class _GridCovariance:
    """``Σ_u = [[a, b], [b, c]]`` over a grid, from the separable closed form of J.

    With ``s`` in ξ order (s1..s3 translation, s4..s6 rotation about x_c, y_c, z_c):

        a = fx²[s1/Z² + s3 x²/Z² + s5 (1 + x²)²] + y² · fx²[s6 + s4 x²]
        c = fy²[s2/Z² + s3 y²/Z² + s4 (1 + y²)²] + x² · fy²[s6 + s5 y²]
        b = fx fy x y [s3/Z² + s4 + s5 − s6 + s4 y² + s5 x²]

    so each entry is an outer combination of per-column and per-row vectors and a frame chunk
    costs a handful of passes over memory instead of a 2×6 matrix product per pixel.
    """

    def __init__(self, cam, us: np.ndarray, vs: np.ndarray, depth: float, s_xi: np.ndarray):
        fx, fy, cx, cy = cam[:4]
        s1, s2, s3, s4, s5, s6 = s_xi
        iz2 = 1.0 / depth ** 2
        x, y = (us - cx) / fx, (vs - cy) / fy
        x2, y2 = x * x, y * y
        self.x, self.x2, self.y, self.y2 = x, x2, y, y2
        self.a_col = fx * fx * (s1 * iz2 + s3 * x2 * iz2 + s5 * (1.0 + x2) ** 2)
        self.a_col_y2 = fx * fx * (s6 + s4 * x2)
        self.c_row = fy * fy * (s2 * iz2 + s3 * y2 * iz2 + s4 * (1.0 + y2) ** 2)
        self.c_row_x2 = fy * fy * (s6 + s5 * y2)
        # b = y·[fx fy x (K + s5 x²)] + [fx fy s4 y³]·x with K = s3/Z² + s4 + s5 − s6.
        self.b_col = fx * fy * x * (s3 * iz2 + s4 + s5 - s6 + s5 * x2)
        self.b_row_x = fx * fy * s4 * y * y2

    def rows(self, r0: int, r1: int):
        """``(a, b, c)`` arrays of shape (r1 − r0, n_u) for grid rows r0..r1."""
        a = np.multiply.outer(self.y2[r0:r1], self.a_col_y2)
        a += self.a_col
        c = np.multiply.outer(self.c_row_x2[r0:r1], self.x2)
        c += self.c_row[r0:r1, None]
        b = np.multiply.outer(self.y[r0:r1], self.b_col)
        b += np.multiply.outer(self.b_row_x[r0:r1], self.x)
        return a, b, c


def _row_chunk(n_u: int) -> int:
    return max(1, _CHUNK_POINTS // n_u)


def _sweep(cam, us, vs, depth, s_xi, *, with_trace: bool = True):
    """Suprema over the grid: ``(sup_trace, (u, v)), (sup_lmax, (u, v))`` (trace part None if skipped).

    λ_max of the 2×2 block is ``(a + c)/2 + √(((a − c)/2)² + b²)``: no cancellation, so float64 keeps
    full relative precision.
    """
    grid = _GridCovariance(cam, us, vs, depth, s_xi)
    best_tr, at_tr, best_lm, at_lm = -1.0, (0, 0), -1.0, (0, 0)
    step = _row_chunk(us.size)
    for r0 in range(0, vs.size, step):
        a, b, c = grid.rows(r0, r0 + step)
        tr = a + c
        if with_trace:
            k = int(np.argmax(tr))
            if tr.flat[k] > best_tr:
                best_tr, at_tr = float(tr.flat[k]), (r0 + k // us.size, k % us.size)
        lm = _lmax_inplace(a, b, c, tr)
        k = int(np.argmax(lm))
        if lm.flat[k] > best_lm:
            best_lm, at_lm = float(lm.flat[k]), (r0 + k // us.size, k % us.size)
    trace = (best_tr, (float(us[at_tr[1]]), float(vs[at_tr[0]]))) if with_trace else None
    return trace, (best_lm, (float(us[at_lm[1]]), float(vs[at_lm[0]])))


def _lmax_inplace(a, b, c, tr):
    """λ_max from the entries, overwriting ``a`` and ``b`` (``tr = a + c`` is left intact)."""
    a -= c
    a *= 0.5
    a *= a
    b *= b
    a += b
    np.sqrt(a, out=a)
    a += 0.5 * tr
    return a


@dataclass
class FrameSuprema:
    """Suprema of both criteria over the frame grid (px²) and the pixels (u, v) where they occur."""

    sup_trace_px2: float
    worst_pixel_trace: tuple
    sup_lmax_px2: float
    worst_pixel: tuple


def frame_suprema(intr, altitude_m, sigmas, stride_px: int = 1, *,
                  mount: CameraMount = METHOD_MOUNT) -> FrameSuprema:
    """``sup_u tr Σ_u`` and ``sup_u λ_max(Σ_u)`` over the frame grid, without the allocations.

    ``sigmas``: pose sigmas (x, y, z in m; roll, pitch, yaw in degrees) on ``mount``. Cheap enough
    (tens of ms at full resolution) to re-run on every edit in a dock.
    """
    s_xi = mount.xi_variances(sigmas_to_variances(sigmas))
    us, vs = frame_grid(intr, stride_px)
    (sup_tr, px_tr), (sup_lm, px_lm) = _sweep(_camera(intr), us, vs, _altitude(altitude_m), s_xi)
    return FrameSuprema(sup_tr, px_tr, sup_lm, px_lm)


def _fields(intr, altitude_m, sigmas, stride_px, mount):
    cam = _camera(intr)
    depth = _altitude(altitude_m)
    s_xi = mount.xi_variances(sigmas_to_variances(sigmas))
    us, vs = frame_grid(intr, stride_px)
    grid = _GridCovariance(cam, us, vs, depth, s_xi)
    trace = np.empty((vs.size, us.size))
    lmax = np.empty((vs.size, us.size))
    step = _row_chunk(us.size)
    for r0 in range(0, vs.size, step):
        a, b, c = grid.rows(r0, r0 + step)
        trace[r0:r0 + step] = a + c
        lmax[r0:r0 + step] = _lmax_inplace(a, b, c, trace[r0:r0 + step])
    return trace, lmax


def lmax_field(intr, altitude_m, sigmas, stride_px: int = 1, *, mount: CameraMount = METHOD_MOUNT) -> np.ndarray:
    """``λ_max(Σ_u)`` px² on the frame grid: rows follow ``v``, columns ``u`` (see ``frame_grid``).

    ``sigmas`` are the six pose sigmas (x, y, z in m; roll, pitch, yaw in degrees) on ``mount``.
    """
    return _fields(intr, altitude_m, sigmas, stride_px, mount)[1]


def trace_field(intr, altitude_m, sigmas, stride_px: int = 1, *, mount: CameraMount = METHOD_MOUNT) -> np.ndarray:
    """``tr Σ_u = sᵀ g(u)`` px² on the frame grid, laid out like ``lmax_field``."""
    return _fields(intr, altitude_m, sigmas, stride_px, mount)[0]


def trace_binding_corner(intr) -> tuple[float, float]:
    """The corner pixel where the trace bound binds for every budget (farthest from (cx, cy) per axis)."""
    _, _, cx, cy, width, height = _camera(intr)
    last_u, last_v = width - 1.0, height - 1.0
    return (last_u if last_u - cx >= cx else 0.0, last_v if last_v - cy >= cy else 0.0)


def balanced_trace_variances(intr, altitude_m, tolerance_px, *, mount: CameraMount = METHOD_MOUNT) -> np.ndarray:
    """Balanced budget under the trace bound: ``s_i = λ_target / (6 g*_i)`` (6,) m², rad².

    ``g*`` is the gain vector at ``trace_binding_corner``, where the trace of every budget peaks, so
    this budget has ``sup_u tr Σ_u = λ_target`` exactly, each axis contributing a sixth.
    """
    lam = lambda_target(tolerance_px)
    g = gains(intr, *trace_binding_corner(intr), _altitude(altitude_m), mount)[0]
    return lam / (6.0 * g)


def _top_eigenvector(cov: np.ndarray) -> np.ndarray:
    return np.linalg.eigh(cov)[1][:, -1]


def _cut(intr, pixel, depth, s_input, mount) -> np.ndarray:
    """Tangent plane of λ_max(Σ_u(s)) at ``s_input``: coefficients ``(wᵀ j_i)²`` (interface order)."""
    j = pixel_jacobian(intr, pixel[0], pixel[1], depth)[0][:, mount.input_to_xi]
    w = _top_eigenvector((j * s_input) @ j.T)
    return (w @ j) ** 2


def _max_log_under_cuts(cuts: np.ndarray, t0: np.ndarray) -> np.ndarray:
    """``argmax Σ t_i`` s.t. ``cuts @ exp(t) ≤ 1`` (the max-log-det problem in log coordinates).

    In ``t = log s`` the objective is linear and each constraint convex, which SLSQP handles well; the
    cuts are normalised so that the trace allocation is ``t = 0`` and every coefficient is O(1).
    """
    from scipy.optimize import minimize

    ones = np.ones(6)
    res = minimize(lambda t: -t.sum(), t0, jac=lambda t: -ones, method="SLSQP",
                   constraints=[{"type": "ineq", "fun": lambda t: 1.0 - cuts @ np.exp(t),
                                 "jac": lambda t: -cuts * np.exp(t)}],
                   options={"ftol": 1e-13, "maxiter": 500})
    t = res.x
    # SLSQP may stop a hair outside the cuts; pull back onto them so the next cut is informative.
    worst = float(np.max(cuts @ np.exp(t)))
    return t - math.log(worst) if worst > 1.0 else t


def balanced_exact_variances(intr, altitude_m, tolerance_px, stride_px: int = 1, tol: float = EXACT_TOLERANCE, *,
                             mount: CameraMount = METHOD_MOUNT) -> tuple[np.ndarray, int]:
    """Balanced budget under the exact bound: ``max Σ log s_i`` s.t. ``λ_max(Σ_u(s)) ≤ λ_target`` ∀u.

    Returns ``(variances (6,) m², rad², iterations)``. Kelley's cutting planes over the frame grid,
    started from tangent cuts at the four corner pixels along u, v and the diagonals; stops when the
    relative violation is below ``tol`` and then scales the budget onto the boundary
    (``sup λ_max = λ_target``), so its ``Σ log s`` is within ``6·log(1 + tol)`` of the optimum.
    """
    cam = _camera(intr)
    depth = _altitude(altitude_m)
    lam = lambda_target(tolerance_px)
    us, vs = frame_grid(intr, stride_px)
    base = balanced_trace_variances(intr, depth, tolerance_px, mount=mount)
    cuts = []
    last_u, last_v = us[-1], vs[-1]
    for corner in ((0.0, 0.0), (last_u, 0.0), (0.0, last_v), (last_u, last_v)):
        j = pixel_jacobian(intr, corner[0], corner[1], depth)[0][:, mount.input_to_xi]
        for w in ((1.0, 0.0), (0.0, 1.0), (math.sqrt(0.5), math.sqrt(0.5)), (math.sqrt(0.5), -math.sqrt(0.5))):
            cuts.append((np.asarray(w) @ j) ** 2)
    t = np.zeros(6)
    for iteration in range(1, EXACT_MAX_ITERATIONS + 1):
        # Normalised cuts: the trace allocation (t = 0) satisfies every one of them, since
        # (wᵀj_i)² ≤ ‖j_i‖² ≤ g*_i on the grid.
        t = _max_log_under_cuts(np.asarray(cuts) * base / lam, t)
        s = base * np.exp(t)
        _, (sup, pixel) = _sweep(cam, us, vs, depth, mount.xi_variances(s), with_trace=False)
        if sup <= lam * (1.0 + tol):
            break
        cuts.append(_cut(intr, pixel, depth, s, mount))
    return s * (lam / sup), iteration


@dataclass
class AltitudeBound:
    """Sensor-bound verdict at one altitude.

    Suprema and ``λ_target`` are px²; sigma lists are in interface order (x, y, z in m; roll, pitch,
    yaw in degrees); pixels are (u, v). ``κ = λ_target / sup`` is ``inf`` for an all-zero budget.
    ``budget_share`` is each axis's share ``g*_i s_i / Σ_j g*_j s_j`` of the deployed budget's trace at
    the exact criterion's worst pixel. ``exact_iterations`` counts cutting-plane rounds; reaching
    ``EXACT_MAX_ITERATIONS`` means the tolerance was not met (the reported budget is still feasible).
    """

    altitude_m: float
    lambda_target_px2: float
    sup_trace_px2: float
    sup_lmax_px2: float
    kappa_trace: float
    kappa_exact: float
    verdict_trace: str
    verdict_exact: str
    worst_pixel_trace: tuple
    worst_pixel: tuple
    balanced_trace_sigma: list
    balanced_exact_sigma: list
    budget_share: list
    stride_px: int
    exact_iterations: int

    def to_json_dict(self) -> dict:
        """Plain JSON-ready dict; non-finite numbers (κ of a zero budget) become ``None``."""
        def num(x):
            return float(x) if math.isfinite(x) else None

        return {
            "altitude_m": num(self.altitude_m),
            "sup_trace_px2": num(self.sup_trace_px2),
            "sup_lmax_px2": num(self.sup_lmax_px2),
            "kappa_trace": num(self.kappa_trace),
            "kappa_exact": num(self.kappa_exact),
            "verdict_trace": self.verdict_trace,
            "verdict_exact": self.verdict_exact,
            "worst_pixel": [float(c) for c in self.worst_pixel],
            "balanced_trace_sigma": [float(c) for c in self.balanced_trace_sigma],
            "balanced_exact_sigma": [float(c) for c in self.balanced_exact_sigma],
            "budget_share": [float(c) for c in self.budget_share],
            "worst_pixel_trace": [float(c) for c in self.worst_pixel_trace],
            "lambda_target_px2": num(self.lambda_target_px2),
            "stride_px": self.stride_px,
            "exact_iterations": self.exact_iterations,
        }


def evaluate_bound(intr, altitude_m, sigmas, tolerance_px: float = 30.0, stride_px: int = 1, *,
                   mount: CameraMount = METHOD_MOUNT) -> AltitudeBound:
    """Trace and exact bounds, κ*, verdicts and balanced budgets at one altitude.

    ``intr``: intrinsics (px); ``altitude_m``: depth of the level ground (m); ``sigmas``: deployed pose
    sigmas (x, y, z in m; roll, pitch, yaw in degrees, see the module's axis convention);
    ``tolerance_px``: label radius r at 3σ; ``stride_px``: grid stride (1 = every pixel); ``mount``:
    how roll, pitch and yaw turn the camera.
    """
    depth = _altitude(altitude_m)
    lam = lambda_target(tolerance_px)
    s = sigmas_to_variances(sigmas)
    sup = frame_suprema(intr, depth, sigmas, stride_px, mount=mount)
    sup_tr, px_tr, sup_lm, px_lm = sup.sup_trace_px2, sup.worst_pixel_trace, sup.sup_lmax_px2, sup.worst_pixel
    kappa_tr = lam / sup_tr if sup_tr > 0 else math.inf
    kappa_lm = lam / sup_lm if sup_lm > 0 else math.inf
    g = gains(intr, px_lm[0], px_lm[1], depth, mount)[0]
    contrib = g * s
    share = contrib / contrib.sum() if contrib.sum() > 0 else np.zeros(6)
    exact, iterations = balanced_exact_variances(intr, depth, tolerance_px, stride_px, mount=mount)
    return AltitudeBound(
        altitude_m=depth, lambda_target_px2=lam,
        sup_trace_px2=sup_tr, sup_lmax_px2=sup_lm, kappa_trace=kappa_tr, kappa_exact=kappa_lm,
        verdict_trace="accept" if kappa_tr >= 1.0 else "reject",
        verdict_exact="accept" if kappa_lm >= 1.0 else "reject",
        worst_pixel_trace=px_tr, worst_pixel=px_lm,
        balanced_trace_sigma=variances_to_sigmas(balanced_trace_variances(intr, depth, tolerance_px,
                                                                          mount=mount)).tolist(),
        balanced_exact_sigma=variances_to_sigmas(exact).tolist(),
        budget_share=share.tolist(), stride_px=_stride(stride_px), exact_iterations=iterations,
    )


def evaluate_bounds(intr, altitudes: Sequence[float], sigmas, tolerance_px: float = 30.0, stride_px: int = 1,
                    progress: Optional[Callable[[float], None]] = None,
                    is_canceled: Optional[Callable[[], bool]] = None, *,
                    mount: CameraMount = METHOD_MOUNT) -> dict:
    """``evaluate_bound`` at each altitude: ``{"altitudes": [to_json_dict, …], "inputs": {…}}``.

    ``progress(fraction)`` is called after each altitude; ``is_canceled()`` is polled before each one
    and a True answer raises ``errors.Cancelled``.
    """
    fx, fy, cx, cy, width, height = _camera(intr)
    altitudes = [float(a) for a in altitudes]
    if not altitudes:
        raise InputError("give at least one altitude")
    sig = sigmas_to_variances(sigmas)  # validates before any work is done
    results = []
    for k, altitude in enumerate(altitudes):
        check_cancel(is_canceled)
        results.append(evaluate_bound(intr, altitude, sigmas, tolerance_px, stride_px, mount=mount).to_json_dict())
        if progress is not None:
            progress((k + 1) / len(altitudes))
    return {
        "altitudes": results,
        "inputs": {
            "intrinsics": {"fx": fx, "fy": fy, "cx": cx, "cy": cy, "width": width, "height": height},
            "sigmas": variances_to_sigmas(sig).tolist(),
            "axes": list(AXES),
            "sigma_units": list(SIGMA_UNITS),
            "mount": mount.key,
            "axis_convention": mount.convention,
            "tolerance_px": float(tolerance_px),
            "lambda_target_px2": lambda_target(tolerance_px),
            "stride_px": _stride(stride_px),
        },
    }

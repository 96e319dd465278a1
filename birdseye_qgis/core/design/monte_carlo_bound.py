"""Monte Carlo check of the linearised sensor bound, on a ground grid as the method runs it.

``sensor_bound`` predicts the label covariance ``Σ_u = J diag(s) Jᵀ`` from a first-order expansion.
Here the same pose errors are pushed through the exact geometry instead: ξ ~ N(0, Σ0) is drawn, the
perturbed pose is the exact SE(3) exponential ``exp(ξ^) · T_cam_world`` (left perturbation, ξ = [ρ, φ]
in the camera frame, ``rotations.se3_exp``), and every point of a ground grid is re-projected.

Ground grid
-----------
The nadir camera of the sensor bound (pinhole, distortion ignored) at depth ``Z`` = the flight height
over level ground sees the footprint spanned by its image corners (``CameraModel.corner_pixels``, the
outer edges of the frame) on the plane ``z_c = Z``. Grid nodes lie every ``spacing_m`` along image x and
y, centred on the footprint's centre and kept where they fall inside it: ``2⌊L/(2·spacing)⌋ + 1`` nodes
across a footprint side of length ``L``; rows follow image v, columns image u. Each node's pixel is its
projection into the nominal camera (``CameraModel.project``).

Per grid point
--------------
* ``S``: the sample second moment of the pixel displacement, taken about zero — the nominal
  projection — so a bias from the non-linearity counts as error, as it would for a label.
* The error ellipse of ``S``: semi-major axis ``k·√λ_max(S)`` px with ``k = ELLIPSE_SIGMAS`` = 3, the
  same 3σ at which a label's tolerance r is drawn (``training_set.LABEL_RADIUS_SIGMAS``), so it reads
  directly against r; anisotropy ``√(λ_max/λ_min)`` = major / minor axis, 1 for a circle.
* The symmetric Kullback–Leibler (Jeffreys) divergence between ``S`` and the linearised ``Σ_u`` as
  zero-mean 2D Gaussians,

      sKLD = KL(S‖Σ) + KL(Σ‖S) = ½ [tr(Σ⁻¹S) + tr(S⁻¹Σ)] − 2     (nats; log-determinants cancel),

  which is 0 when the linearisation is exact and is dominated by sampling noise (≈ 3/n) when it holds.
  The linearised bound holds when the largest sKLD over the grid is below ``SKLD_THRESHOLD``; the
  fraction of grid points over each of ``SKLD_CUTOFFS`` is reported.

Sigmas follow ``sensor_bound``'s interface: (x, y, z in m; roll, pitch, yaw in degrees). The attitude
draws are turned into the camera frame by the mount's rotation, ``φ_c = R_cam_body φ_b``
(``sensor_bound.CameraMount``), not by the axis permutation the linear model uses, so the check also
covers that the permutation describes the mount. Scaling factors multiply the variances, like κ*.
All draws come from ``numpy.random.default_rng(seed)``; one set of standard normal draws is reused for
every scale and axis (common random numbers), so curves are smooth and results reproducible.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.camera import CameraModel
from ..geometry.rotations import se3_exp
from ..labels.training_set import LABEL_RADIUS_SIGMAS
from .sensor_bound import (
    AXES,
    METHOD_MOUNT,
    CameraMount,
    _altitude,
    _camera,
    pixel_covariance,
    sigmas_to_variances,
)

#: Spacing (m) of the ground grid the method evaluates the check on.
GROUND_SPACING_M = 0.67
#: sKLD (nats) below which, at every grid point, the linearised bound is taken to hold.
SKLD_THRESHOLD = 1e-2
#: sKLD cut-offs (nats) whose exceedance is reported as a fraction of the grid points.
SKLD_CUTOFFS = (SKLD_THRESHOLD,)
#: Error ellipses are drawn at the labels' 3σ, so their semi-major axis compares with the tolerance r.
ELLIPSE_SIGMAS = LABEL_RADIUS_SIGMAS
# Pose draws × grid points re-projected at once: 2¹⁹ (4 MB per coordinate, 12 MB a pass) bound the memory
# of one pass whatever the grid, and let a long run be cancelled between passes.
_CHUNK_VALUES = 1 << 19


def symmetric_kl(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Jeffreys divergence between zero-mean Gaussians with covariances ``p, q`` (..., d, d), in nats.

    ``inf`` where either covariance is singular or not finite.
    """
    p, q = np.asarray(p, dtype=float), np.asarray(q, dtype=float)
    d = p.shape[-1]
    ok = (np.linalg.det(p) > 0) & (np.linalg.det(q) > 0)
    eye = np.eye(d)
    p_safe = np.where(ok[..., None, None], p, eye)
    q_safe = np.where(ok[..., None, None], q, eye)
    tr_qp = np.trace(np.linalg.solve(q_safe, p_safe), axis1=-2, axis2=-1)
    tr_pq = np.trace(np.linalg.solve(p_safe, q_safe), axis1=-2, axis2=-1)
    return np.where(ok, 0.5 * (tr_qp + tr_pq) - d, np.inf)


def error_ellipse(cov, sigmas: float = ELLIPSE_SIGMAS) -> tuple[np.ndarray, np.ndarray]:
    """Semi-major axis (px) at ``sigmas`` σ and anisotropy of label covariances ``cov`` (..., 2, 2) px².

    Semi-major axis ``sigmas · √λ_max``; anisotropy ``√(λ_max / λ_min)`` (major / minor axis): 1 for a
    circle, +inf when the label moves along one line only (λ_min = 0), NaN when it does not move at all.
    """
    lam = np.linalg.eigvalsh(np.asarray(cov, dtype=float))
    low, high = np.clip(lam[..., 0], 0.0, None), np.clip(lam[..., 1], 0.0, None)
    with np.errstate(divide="ignore", invalid="ignore"):
        return sigmas * np.sqrt(high), np.sqrt(high / low)


def _pinhole(intr) -> CameraModel:
    """The sensor bound's camera: ``intr``'s intrinsics without distortion."""
    fx, fy, cx, cy, width, height = _camera(intr)
    return CameraModel(width=width, height=height, fx=fx, fy=fy, cx=cx, cy=cy)


@dataclass(frozen=True)
class GroundGrid:
    """Level-ground points every ``spacing_m`` over a nadir camera's footprint at depth ``altitude_m``.

    ``footprint_m`` ((x_min, x_max), (y_min, y_max)) and ``points`` (N, 3) are in the camera frame, metres
    (x image right, y image down, z = depth); ``pixels`` (N, 2) are their nominal projections;
    ``shape`` = (rows, columns), points in row-major order.
    """

    spacing_m: float
    altitude_m: float
    footprint_m: tuple
    shape: tuple
    points: np.ndarray
    pixels: np.ndarray


def ground_grid(intr, altitude_m, spacing_m=GROUND_SPACING_M) -> GroundGrid:
    """The grid of the module docstring for camera ``intr`` at ``altitude_m`` (m), nodes every ``spacing_m`` (m)."""
    depth = _altitude(altitude_m)
    spacing = float(spacing_m)
    if not (spacing > 0 and math.isfinite(spacing)):
        raise InputError(f"ground grid spacing must be a positive number of metres, got {spacing_m}")
    cam = _pinhole(intr)
    corners = depth * cam.pixel_rays(cam.corner_pixels())
    low, high = corners[:, :2].min(axis=0), corners[:, :2].max(axis=0)
    centre = 0.5 * (low + high)
    # Nodes on the footprint's edge stay in, whatever the rounding of the division.
    half_count = np.floor(0.5 * (high - low) / spacing + 1e-9).astype(int)
    xs, ys = (centre[i] + spacing * np.arange(-half_count[i], half_count[i] + 1) for i in (0, 1))
    gx, gy = np.meshgrid(xs, ys)
    points = np.stack([gx.ravel(), gy.ravel(), np.full(gx.size, depth)], axis=-1)
    return GroundGrid(spacing, depth, ((low[0], high[0]), (low[1], high[1])), gx.shape, points, cam.project(points))


def _second_moment(cam: CameraModel, grid: GroundGrid, std_normal, variances, mount: CameraMount,
                   is_canceled=None) -> np.ndarray:
    """``E[δu δuᵀ]`` (N, 2, 2) px² over the draws ``std_normal · √s`` (interface order), exactly applied.

    The translation draws are in the camera frame already; the attitude draws are rotated into it.
    ``is_canceled()`` is polled between passes over the grid.
    """
    draws = std_normal * np.sqrt(variances)
    xi = np.concatenate([draws[:, :3], draws[:, 3:] @ np.asarray(mount.R_cam_body, dtype=float).T], axis=1)
    t = se3_exp(xi)
    n_draws = len(xi)
    # All draws' rotations stacked into one (3·S, 3) matrix: one BLAS product per pass instead of S small ones.
    rotations, shift = t[:, :3, :3].reshape(3 * n_draws, 3), t[:, :3, 3, None]
    moment = np.empty((len(grid.points), 2, 2))
    step = max(1, _CHUNK_VALUES // n_draws)
    for start in range(0, len(grid.points), step):
        check_cancel(is_canceled)
        part = slice(start, start + step)
        moved = (rotations @ grid.points[part].T).reshape(n_draws, 3, -1) + shift
        # The distortion-free pinhole of ``cam`` (u = fx·x/z + cx, as CameraModel.project for this camera),
        # written out: its generic distortion pass costs five times this whole loop.
        inverse_depth = 1.0 / moved[:, 2]
        du = cam.fx * moved[:, 0] * inverse_depth + cam.cx - grid.pixels[part, 0]
        dv = cam.fy * moved[:, 1] * inverse_depth + cam.cy - grid.pixels[part, 1]
        moment[part, 0, 0] = np.einsum("sn,sn->n", du, du)
        moment[part, 0, 1] = moment[part, 1, 0] = np.einsum("sn,sn->n", du, dv)
        moment[part, 1, 1] = np.einsum("sn,sn->n", dv, dv)
    return moment / n_draws


def _draws(n_samples, seed) -> np.ndarray:
    if int(n_samples) != n_samples or n_samples < 10:
        raise InputError(f"Monte Carlo needs a whole number of at least 10 samples, got {n_samples}")
    return np.random.default_rng(seed).standard_normal((int(n_samples), 6))


def _cutoffs(skld_cutoffs) -> tuple:
    cutoffs = tuple(float(c) for c in np.ravel(skld_cutoffs))
    if not cutoffs or not all(c > 0 and math.isfinite(c) for c in cutoffs):
        raise InputError(f"sKLD cut-offs must be positive numbers of nats, got {list(cutoffs)}")
    return cutoffs


def _json_number(value) -> Optional[float]:
    """A float for JSON, None where it is not finite (an infinite anisotropy or sKLD)."""
    return float(value) if np.isfinite(value) else None


@dataclass
class MonteCarloResult:
    """Per grid point: the sampled and linearised label covariances (px²), their sKLD (nats) and the
    sampled error ellipse (``error_ellipse``: 3σ semi-major axis in px, anisotropy)."""

    altitude_m: float
    n_samples: int
    seed: Optional[int]
    grid: GroundGrid
    sample_cov: np.ndarray
    model_cov: np.ndarray
    skld: np.ndarray
    skld_cutoffs: tuple = SKLD_CUTOFFS

    @property
    def pixels(self) -> np.ndarray:
        return self.grid.pixels

    @property
    def major_axis_px(self) -> np.ndarray:
        return error_ellipse(self.sample_cov)[0]

    @property
    def anisotropy(self) -> np.ndarray:
        return error_ellipse(self.sample_cov)[1]

    @property
    def max_skld(self) -> float:
        return float(np.max(self.skld))

    @property
    def worst_pixel(self) -> tuple:
        return tuple(float(c) for c in self.pixels[int(np.argmax(self.skld))])

    @property
    def linearisation_holds(self) -> bool:
        return self.max_skld < SKLD_THRESHOLD

    def fraction_over(self, cutoff: float) -> float:
        """Fraction of the grid points whose sKLD exceeds ``cutoff`` (nats)."""
        return float(np.mean(self.skld > cutoff))

    def summary(self) -> dict:
        """Max and median of the 3σ semi-major axis (px) and anisotropy (points that do not move left out),
        max sKLD, and the fraction of points over each cut-off (keyed by the cut-off written with ``g``)."""
        major, ratio = error_ellipse(self.sample_cov)
        return {
            "n_points": int(len(self.skld)), "ellipse_sigmas": ELLIPSE_SIGMAS,
            "major_axis_px_max": float(np.max(major)), "major_axis_px_median": float(np.median(major)),
            "anisotropy_max": _json_number(np.nanmax(ratio)), "anisotropy_median": _json_number(np.nanmedian(ratio)),
            "max_skld": _json_number(self.max_skld),
            "fraction_over_skld": {f"{c:g}": self.fraction_over(c) for c in self.skld_cutoffs},
        }

    def to_json_dict(self) -> dict:
        major, ratio = error_ellipse(self.sample_cov)
        return {
            "altitude_m": self.altitude_m, "n_samples": self.n_samples, "seed": self.seed,
            "spacing_m": self.grid.spacing_m, "grid_shape": list(self.grid.shape),
            "footprint_m": [list(map(float, axis)) for axis in self.grid.footprint_m],
            "skld_cutoffs": list(self.skld_cutoffs), "summary": self.summary(), "worst_pixel": list(self.worst_pixel),
            "points": [{"x_m": float(g[0]), "y_m": float(g[1]), "u": float(p[0]), "v": float(p[1]),
                        "major_axis_px": float(a), "anisotropy": _json_number(r), "skld": _json_number(k),
                        "sample_cov_px2": s.tolist(), "model_cov_px2": m.tolist()}
                       for g, p, a, r, k, s, m in zip(self.grid.points, self.pixels, major, ratio, self.skld,
                                                      self.sample_cov, self.model_cov)],
        }


def monte_carlo_check(intr, altitude_m, sigmas, n_samples: int = 20000, spacing_m=GROUND_SPACING_M,
                      seed: Optional[int] = 0, *, mount: CameraMount = METHOD_MOUNT, skld_cutoffs=SKLD_CUTOFFS,
                      is_canceled=None) -> MonteCarloResult:
    """Sampled vs linearised label covariance at every point of ``ground_grid(intr, altitude_m, spacing_m)``.

    ``sigmas``: pose sigmas (x, y, z in m; roll, pitch, yaw in degrees) on ``mount``; ``altitude_m``:
    depth of the level ground (m); ``skld_cutoffs`` (nats): those the summary counts points over.
    Deterministic for a given ``seed``; ``is_canceled()`` True raises ``errors.Cancelled``.
    """
    grid = ground_grid(intr, altitude_m, spacing_m)
    s = sigmas_to_variances(sigmas)
    cutoffs = _cutoffs(skld_cutoffs)
    z = _draws(n_samples, seed)
    sample = _second_moment(_pinhole(intr), grid, z, s, mount, is_canceled)
    model = pixel_covariance(intr, grid.pixels[:, 0], grid.pixels[:, 1], grid.altitude_m, s, mount)
    return MonteCarloResult(grid.altitude_m, int(n_samples), seed, grid, sample, model, symmetric_kl(sample, model),
                            cutoffs)


@dataclass
class ScalingStudy:
    """Max sKLD over the ground grid vs the factor applied to the variances.

    ``skld_max[k]``: all six variances scaled by ``scales[k]``. ``per_axis[name][k]`` (when computed):
    only that axis's variance scaled, the others kept at the deployed budget — isolating which axis
    breaks the linearisation first.
    """

    altitude_m: float
    n_samples: int
    seed: Optional[int]
    spacing_m: float
    n_points: int
    scales: np.ndarray
    skld_max: np.ndarray
    per_axis: Optional[dict]

    def to_json_dict(self) -> dict:
        return {
            "altitude_m": self.altitude_m, "n_samples": self.n_samples, "seed": self.seed,
            "spacing_m": self.spacing_m, "n_points": self.n_points,
            "scales": self.scales.tolist(), "skld_max": [_json_number(v) for v in self.skld_max],
            "per_axis": None if self.per_axis is None else {
                k: [_json_number(x) for x in v] for k, v in self.per_axis.items()},
        }


def scaling_study(intr, altitude_m, sigmas, scales=np.logspace(-1, 2, 25), per_axis: bool = False,
                  n_samples: int = 20000, spacing_m=GROUND_SPACING_M, seed: Optional[int] = 0,
                  is_canceled=None, *, mount: CameraMount = METHOD_MOUNT) -> ScalingStudy:
    """sKLD vs variance scale on the ground grid, overall and (``per_axis=True``) per axis; see ``ScalingStudy``.

    ``is_canceled()`` is polled before each scale and between passes over the grid; a True answer
    raises ``errors.Cancelled``.
    """
    grid = ground_grid(intr, altitude_m, spacing_m)
    s = sigmas_to_variances(sigmas)
    scales = np.asarray(scales, dtype=float).reshape(-1)
    if scales.size == 0 or np.any(~(scales > 0)):
        raise InputError("variance scales must be positive numbers")
    cam = _pinhole(intr)
    z = _draws(n_samples, seed)

    def max_skld(variances):
        check_cancel(is_canceled)
        sample = _second_moment(cam, grid, z, variances, mount, is_canceled)
        model = pixel_covariance(intr, grid.pixels[:, 0], grid.pixels[:, 1], grid.altitude_m, variances, mount)
        return float(np.max(symmetric_kl(sample, model)))

    overall = np.array([max_skld(c * s) for c in scales])
    axes = None
    if per_axis:
        axes = {}
        for i, name in enumerate(AXES):
            factor = np.ones(6)
            values = []
            for c in scales:
                factor[i] = c
                values.append(max_skld(factor * s))
            axes[name] = np.array(values)
    return ScalingStudy(grid.altitude_m, int(n_samples), seed, grid.spacing_m, len(grid.points), scales, overall, axes)


def plot_scaling_study(study: ScalingStudy, path, cutoffs=SKLD_CUTOFFS, kappa: Optional[float] = None,
                       title: Optional[str] = None):
    """Write a log–log PNG of sKLD vs variance scale to ``path`` and return ``path``.

    Uses matplotlib's object API on an Agg canvas, so the host application's (QGIS's) backend is
    left alone. ``cutoffs`` (nats) draw the acceptance lines; ``kappa`` (e.g. κ* of the exact bound)
    marks the largest admissible scale.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(7, 4.5), dpi=120)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    ax.loglog(study.scales, study.skld_max, "k-", lw=2, label="all axes")
    if study.per_axis:
        for name, values in study.per_axis.items():
            ax.loglog(study.scales, values, "--", lw=1.2, label=f"{name} only")
    # Dotted and dash-dotted in a colour outside matplotlib's cycle, so no cut-off reads as a per-axis curve.
    styles = ("-", ":", "-.", (0, (1, 4)))
    for k, cutoff in enumerate(_cutoffs(cutoffs)):
        ax.axhline(cutoff, color="darkred", lw=1.2, ls=styles[k % len(styles)], label=f"sKLD = {cutoff:g}")
    if kappa is not None and np.isfinite(kappa):
        ax.axvline(kappa, color="tab:green", lw=1, label=f"κ* = {kappa:.3g}")
    ax.axvline(1.0, color="0.6", lw=0.8)
    ax.set_xlabel("variance scale (× deployed Σ0)")
    ax.set_ylabel("max symmetric KL divergence over the grid [nats]")
    ax.set_title(title or f"Linearisation check at {study.altitude_m:g} m ({study.n_points} ground points every "
                          f"{study.spacing_m:g} m, {study.n_samples} samples)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path)
    return path

"""Monte Carlo check of the linearised sensor bound.

``sensor_bound`` predicts the label covariance ``Σ_u = J diag(s) Jᵀ`` from a first-order expansion.
Here the same pose errors are pushed through the exact geometry instead: ξ ~ N(0, Σ0) is drawn, the
perturbed pose is the exact SE(3) exponential ``exp(ξ^) · T_cam_world`` (left perturbation, ξ = [ρ, φ]
in the camera frame, ``rotations.se3_exp``), and the ground point seen at each test pixel (level plane
at depth = altitude) is re-projected. The sample covariance ``S`` of the pixel displacement is taken
about zero — the nominal projection — so a bias from the non-linearity counts as error, as it would
for a label. ``S`` and ``Σ_u`` are compared as zero-mean 2D Gaussians by the symmetric
Kullback–Leibler (Jeffreys) divergence

    sKLD = KL(S‖Σ) + KL(Σ‖S) = ½ [tr(Σ⁻¹S) + tr(S⁻¹Σ)] − 2     (nats; log-determinants cancel),

which is 0 when the linearisation is exact and is dominated by sampling noise (≈ 3/n) when it holds.

Sigmas follow ``sensor_bound``'s interface: (x, y, z in m; roll, pitch, yaw in degrees). The attitude
draws are turned into the camera frame by the mount's rotation, ``φ_c = R_cam_body φ_b``
(``sensor_bound.CameraMount``), not by the axis permutation the linear model uses, so the check also
covers that the permutation describes the mount. Scaling factors multiply the variances, like κ*.
All draws come from ``numpy.random.default_rng(seed)``; one set of standard normal draws is reused for
every scale and axis (common random numbers), so curves are smooth and results reproducible.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Optional

import numpy as np

from ..errors import InputError, check_cancel
from ..geometry.rotations import se3_exp
from .sensor_bound import (
    AXES,
    METHOD_MOUNT,
    CameraMount,
    _altitude,
    _camera,
    pixel_covariance,
    sigmas_to_variances,
)

SKLD_THRESHOLD = 1e-2


def default_pixels(intr) -> np.ndarray:
    """Test pixels (10, 2): the four corners, the edge midpoints, the frame centre and the principal point.

    Corners and edges are the sensor bound's pixel centres, ``0…W − 1 × 0…H − 1`` (design.md §3.3).
    """
    _, _, cx, cy, width, height = _camera(intr)
    us, vs = (0.0, (width - 1) / 2.0, float(width - 1)), (0.0, (height - 1) / 2.0, float(height - 1))
    grid = [(u, v) for v in vs for u in us]
    return np.array(grid + [(cx, cy)])


def symmetric_kl(p: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Jeffreys divergence between zero-mean Gaussians with covariances ``p, q`` (..., d, d), in nats.

    ``inf`` where either covariance is singular.
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


def _ground_points(intr, pixels: np.ndarray, depth: float) -> np.ndarray:
    fx, fy, cx, cy, _, _ = _camera(intr)
    x, y = (pixels[:, 0] - cx) / fx, (pixels[:, 1] - cy) / fy
    return np.stack([x * depth, y * depth, np.full_like(x, depth)], axis=-1)


def _second_moment(intr, pixels, points, std_normal, variances, mount: CameraMount) -> np.ndarray:
    """``E[δu δuᵀ]`` (N, 2, 2) over the draws ``std_normal · √s`` (interface order), exactly applied.

    The translation draws are in the camera frame already; the attitude draws are rotated into it.
    """
    fx, fy, cx, cy, _, _ = _camera(intr)
    draws = std_normal * np.sqrt(variances)
    xi = np.concatenate([draws[:, :3], draws[:, 3:] @ np.asarray(mount.R_cam_body, dtype=float).T], axis=1)
    t = se3_exp(xi)
    moved = np.einsum("sij,nj->sni", t[:, :3, :3], points) + t[:, None, :3, 3]
    du = np.stack([fx * moved[..., 0] / moved[..., 2] + cx - pixels[:, 0],
                   fy * moved[..., 1] / moved[..., 2] + cy - pixels[:, 1]], axis=-1)
    return np.einsum("sni,snj->nij", du, du) / xi.shape[0]


def _draws(n_samples, seed) -> np.ndarray:
    if int(n_samples) != n_samples or n_samples < 10:
        raise InputError(f"Monte Carlo needs a whole number of at least 10 samples, got {n_samples}")
    return np.random.default_rng(seed).standard_normal((int(n_samples), 6))


def _pixels(intr, pixels) -> np.ndarray:
    px = default_pixels(intr) if pixels is None else np.asarray(pixels, dtype=float).reshape(-1, 2)
    if px.shape[0] == 0:
        raise InputError("give at least one test pixel")
    return px


@dataclass
class MonteCarloResult:
    """Per-pixel comparison of the sampled and linearised label covariances (px²)."""

    altitude_m: float
    n_samples: int
    seed: Optional[int]
    pixels: np.ndarray
    sample_cov: np.ndarray
    model_cov: np.ndarray
    skld: np.ndarray

    @property
    def max_skld(self) -> float:
        return float(np.max(self.skld))

    @property
    def worst_pixel(self) -> tuple:
        return tuple(float(c) for c in self.pixels[int(np.argmax(self.skld))])

    def to_json_dict(self) -> dict:
        return {
            "altitude_m": self.altitude_m, "n_samples": self.n_samples, "seed": self.seed,
            "max_skld": self.max_skld, "worst_pixel": list(self.worst_pixel),
            "pixels": [{"u": float(p[0]), "v": float(p[1]), "skld": float(k),
                        "sample_cov_px2": s.tolist(), "model_cov_px2": m.tolist()}
                       for p, k, s, m in zip(self.pixels, self.skld, self.sample_cov, self.model_cov)],
        }


def monte_carlo_check(intr, altitude_m, sigmas, n_samples: int = 20000, pixels=None,
                      seed: Optional[int] = 0, *, mount: CameraMount = METHOD_MOUNT) -> MonteCarloResult:
    """Sampled vs linearised label covariance at ``pixels`` (default ``default_pixels``).

    ``sigmas``: pose sigmas (x, y, z in m; roll, pitch, yaw in degrees) on ``mount``; ``altitude_m``:
    depth of the level ground (m). Deterministic for a given ``seed``.
    """
    depth = _altitude(altitude_m)
    s = sigmas_to_variances(sigmas)
    px = _pixels(intr, pixels)
    z = _draws(n_samples, seed)
    sample = _second_moment(intr, px, _ground_points(intr, px, depth), z, s, mount)
    model = pixel_covariance(intr, px[:, 0], px[:, 1], depth, s, mount)
    return MonteCarloResult(depth, int(n_samples), seed, px, sample, model, symmetric_kl(sample, model))


@dataclass
class ScalingStudy:
    """Max sKLD over the test pixels vs the factor applied to the variances.

    ``skld_max[k]``: all six variances scaled by ``scales[k]``. ``per_axis[name][k]`` (when computed):
    only that axis's variance scaled, the others kept at the deployed budget — isolating which axis
    breaks the linearisation first.
    """

    altitude_m: float
    n_samples: int
    seed: Optional[int]
    scales: np.ndarray
    skld_max: np.ndarray
    per_axis: Optional[dict]

    def to_json_dict(self) -> dict:
        return {
            "altitude_m": self.altitude_m, "n_samples": self.n_samples, "seed": self.seed,
            "scales": self.scales.tolist(), "skld_max": self.skld_max.tolist(),
            "per_axis": None if self.per_axis is None else {k: v.tolist() for k, v in self.per_axis.items()},
        }


def scaling_study(intr, altitude_m, sigmas, scales=np.logspace(-1, 2, 25), per_axis: bool = False,
                  n_samples: int = 20000, pixels=None, seed: Optional[int] = 0,
                  is_canceled=None, *, mount: CameraMount = METHOD_MOUNT) -> ScalingStudy:
    """sKLD vs variance scale, overall and (``per_axis=True``) per axis; see ``ScalingStudy``.

    ``is_canceled()`` is polled before each scale and a True answer raises ``errors.Cancelled``.
    """
    depth = _altitude(altitude_m)
    s = sigmas_to_variances(sigmas)
    scales = np.asarray(scales, dtype=float).reshape(-1)
    if scales.size == 0 or np.any(~(scales > 0)):
        raise InputError("variance scales must be positive numbers")
    px = _pixels(intr, pixels)
    points = _ground_points(intr, px, depth)
    z = _draws(n_samples, seed)

    def max_skld(variances):
        check_cancel(is_canceled)
        sample = _second_moment(intr, px, points, z, variances, mount)
        model = pixel_covariance(intr, px[:, 0], px[:, 1], depth, variances, mount)
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
    return ScalingStudy(depth, int(n_samples), seed, scales, overall, axes)


def plot_scaling_study(study: ScalingStudy, path, threshold: float = SKLD_THRESHOLD, kappa: Optional[float] = None,
                       title: Optional[str] = None):
    """Write a log–log PNG of sKLD vs variance scale to ``path`` and return ``path``.

    Uses matplotlib's object API on an Agg canvas, so the host application's (QGIS's) backend is
    left alone. ``threshold`` draws the acceptance line; ``kappa`` (e.g. κ* of the exact bound)
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
    ax.axhline(threshold, color="tab:red", lw=1, label=f"sKLD = {threshold:g}")
    if kappa is not None and np.isfinite(kappa):
        ax.axvline(kappa, color="tab:green", lw=1, label=f"κ* = {kappa:.3g}")
    ax.axvline(1.0, color="0.6", lw=0.8)
    ax.set_xlabel("variance scale (× deployed Σ0)")
    ax.set_ylabel("max symmetric KL divergence [nats]")
    ax.set_title(title or f"Linearisation check at {study.altitude_m:g} m ({study.n_samples} samples)")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    fig.tight_layout()
    fig.savefig(path)
    return path

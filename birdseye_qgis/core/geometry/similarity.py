"""Similarity transforms ``y = s·R·x + t`` fitted to point pairs (weighted Umeyama).

Structure from motion knows its cameras only up to a similarity; the frames' GNSS positions fix it.
Positions of different accuracy (RTK fixed vs float vs single point) weigh ``1/σ²``. When every
camera centre lies on one line (a single flight line), positions leave the rotation about that line
free; the caller then supplies rotation pairs (SfM vs metadata attitudes) to fix it
(:func:`fit_similarity` ``rotation_pairs``).

:func:`fit_similarity_robust` is the one robust fit (pose refinement and COLMAP's GPS alignment): a
least-median start that gross outliers cannot drag, then least squares refitted on the inliers until
the inlier set stops changing.
"""
from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations

import numpy as np

from ..errors import InputError

#: Camera centres whose spread across the main line is below this fraction of the spread along it
#: count as collinear: their positions cannot fix the rotation about that line.
COLLINEAR_RATIO = 0.02
#: A position whose residual exceeds this many times the inliers' median residual (and 5 σ) is an outlier.
OUTLIER_FACTOR = 5.0
#: Minimal samples tried for the least-median start (all of them when there are fewer).
ROBUST_SAMPLES = 300
#: Refits before the inlier set must have settled.
MAX_REFITS = 20
#: How well metadata attitudes fix the rotation about a flight line (rad, ~2°): positions fix it better only
#: where their spread across the line, times this, exceeds their σ.
ATTITUDE_SIGMA_RAD = 0.03


@dataclass(frozen=True)
class Similarity:
    scale: float
    rotation: np.ndarray
    translation: np.ndarray

    def apply(self, points: np.ndarray) -> np.ndarray:
        return self.scale * np.asarray(points, dtype=float) @ self.rotation.T + self.translation

    def rotate(self, rotations: np.ndarray) -> np.ndarray:
        """Rotations (..., 3, 3) expressed in the target frame: ``R · M``."""
        return np.einsum("ij,...jk->...ik", self.rotation, rotations)


def _orthonormal(m: np.ndarray) -> np.ndarray:
    u, _, vt = np.linalg.svd(m)
    d = np.sign(np.linalg.det(u @ vt)) or 1.0
    return u @ np.diag([1.0, 1.0, d]) @ vt


def is_collinear(points: np.ndarray, weights=None) -> bool:
    points = np.asarray(points, dtype=float)
    w = np.ones(len(points)) if weights is None else np.asarray(weights, dtype=float)
    centred = points - np.average(points, axis=0, weights=w)
    sv = np.linalg.svd(centred * np.sqrt(w)[:, None], compute_uv=False)
    return len(points) < 3 or sv[1] < COLLINEAR_RATIO * sv[0]


def fit_similarity(source: np.ndarray, target: np.ndarray, weights=None, rotation_pairs=None,
                   line: bool | None = None) -> Similarity:
    """Least-squares ``target ≈ s·R·source + t`` with per-pair ``weights``.

    ``rotation_pairs`` (``R_source``, ``R_target``), arrays (N, 3, 3) of the same bodies' orientations
    in both frames, fix the rotation when the positions cannot (``line``; None: the source positions are
    collinear or fewer than three): it is then the chordal mean of ``R_target · R_sourceᵀ`` and only scale
    and translation come from positions.
    """
    source = np.asarray(source, dtype=float)
    target = np.asarray(target, dtype=float)
    w = np.ones(len(source)) if weights is None else np.asarray(weights, dtype=float)
    if len(source) < 2:
        raise InputError(f"a similarity needs at least 2 positions, got {len(source)}")
    mu_s = np.average(source, axis=0, weights=w)
    mu_t = np.average(target, axis=0, weights=w)
    xs, xt = source - mu_s, target - mu_t
    var_s = np.average(np.sum(xs * xs, axis=1), weights=w)
    if var_s <= 0:
        raise InputError("the positions to align all coincide; their scale is unknown")
    if is_collinear(source, w) if line is None else line:
        if rotation_pairs is None:
            raise InputError("the camera centres lie on one line; the rotation about it is undetermined")
        r_source, r_target = (np.asarray(r, dtype=float) for r in rotation_pairs)
        rotation = _orthonormal(np.einsum("nij,nkj->ik", r_target, r_source))
        rotated = xs @ rotation.T
        scale = float(np.sum(w * np.sum(rotated * xt, axis=1)) / np.sum(w * np.sum(rotated * rotated, axis=1)))
    else:
        cov = (xt * w[:, None]).T @ xs / w.sum()
        u, d, vt = np.linalg.svd(cov)
        flip = np.diag([1.0, 1.0, np.sign(np.linalg.det(u) * np.linalg.det(vt)) or 1.0])
        rotation = u @ flip @ vt
        scale = float(np.trace(np.diag(d) @ flip) / var_s)
    return Similarity(scale, rotation, mu_t - scale * rotation @ mu_s)


@dataclass(frozen=True)
class RobustFit:
    """The fit, which positions it kept, every position's residual (m), refits until the inliers settled
    (``converged``; else :data:`MAX_REFITS`), and whether the rotation came from the attitudes (``line``)."""

    similarity: Similarity
    inliers: np.ndarray
    residual: np.ndarray
    refits: int
    converged: bool
    line: bool


def _across_line_rms(points: np.ndarray, weights: np.ndarray) -> float:
    centred = points - np.average(points, axis=0, weights=weights)
    sv = np.linalg.svd(centred * np.sqrt(weights / weights.sum())[:, None], compute_uv=False)
    return float(np.hypot(sv[1], sv[2]))


def _minimal_samples(n: int, size: int, rng) -> list:
    total = 1
    for k in range(size):
        total = total * (n - k) // (k + 1)
    if total <= ROBUST_SAMPLES:
        return [list(c) for c in combinations(range(n), size)]
    return [sorted(rng.choice(n, size, replace=False)) for _ in range(ROBUST_SAMPLES)]


def fit_similarity_robust(source, target, sigma=None, rotation_pairs=None) -> RobustFit:
    """:func:`fit_similarity` (weights 1/σ²) that leaves out positions disagreeing with the rest.

    Start: of the fits to minimal samples (3 positions, 2 with ``rotation_pairs`` on a line), the one with
    the least median σ-normalised residual; it tolerates up to half the positions being gross outliers,
    where a least-squares start would be dragged towards them. Then repeatedly: inliers are the positions
    within max(:data:`OUTLIER_FACTOR` × the inliers' median residual, 5 σ), least squares on them, until the
    set no longer changes. ``sigma`` None: equal weights and no σ floor. Positions that are not finite are
    refused (:class:`.errors.InputError`).

    The positions count as one line (rotation from ``rotation_pairs``) when either set is collinear or, with
    ``sigma`` and ``rotation_pairs``, when the targets' RMS spread across their main line is too small for
    their σ to fix the rotation about it better than attitudes do (:data:`ATTITUDE_SIGMA_RAD`): a single
    flight line of single-point GNSS, metres of noise on half a metre of sideways drift, would otherwise turn
    the block about the line at random.
    """
    source = np.asarray(source, dtype=float)
    target = np.asarray(target, dtype=float)
    if not (np.isfinite(source).all() and np.isfinite(target).all()):
        raise InputError("the positions to align are not all finite numbers")
    n = len(source)
    # Exact positions leave residuals of rounding size, some more than 5× their median: a numerical floor.
    floor = 1e-6 * float(np.ptp(target, axis=0).max()) if n else 0.0
    given_sigma = sigma is not None
    if given_sigma:
        floor = np.maximum(5.0 * np.asarray(sigma, dtype=float), floor)
    sigma = np.ones(n) if sigma is None else np.asarray(sigma, dtype=float)
    weights = 1.0 / sigma ** 2
    pairs = None if rotation_pairs is None else tuple(np.asarray(r, dtype=float) for r in rotation_pairs)
    line = is_collinear(source, weights) or is_collinear(target, weights)
    if not line and pairs is not None and given_sigma:
        line = _across_line_rms(target, weights) * ATTITUDE_SIGMA_RAD < float(np.median(sigma))
    size = 2 if line else 3

    def fit(use):
        return fit_similarity(source[use], target[use], weights[use],
                              None if pairs is None else (pairs[0][use], pairs[1][use]), line=line)

    def residual_of(sim):
        return np.linalg.norm(sim.apply(source) - target, axis=1)

    use = np.ones(n, dtype=bool)
    if n > size + 1:
        best, best_cost = None, np.inf
        for sample in _minimal_samples(n, size, np.random.default_rng(0)):
            if not line and is_collinear(source[sample]):
                continue  # three positions on a line leave the rotation about it free
            cost = float(np.median(residual_of(fit(sample)) / sigma))
            if cost < best_cost:
                best, best_cost = sample, cost
        if best is not None:
            residual = residual_of(fit(best))
            use = residual <= np.maximum(OUTLIER_FACTOR * np.median(residual), floor)
            if use.sum() < size:
                use[:] = True
    sim = fit(use)
    residual = residual_of(sim)
    for refit in range(1, MAX_REFITS + 1):
        new_use = residual <= np.maximum(OUTLIER_FACTOR * np.median(residual[use]), floor)
        if new_use.sum() < size or np.array_equal(new_use, use):
            return RobustFit(sim, use, residual, refit - 1, True, line)
        use = new_use
        sim = fit(use)
        residual = residual_of(sim)
    return RobustFit(sim, use, residual, MAX_REFITS, False, line)

"""Similarity transforms ``y = s·R·x + t`` fitted to point pairs (weighted Umeyama).

Structure from motion knows its cameras only up to a similarity; the frames' GNSS positions fix it.
Positions of different accuracy (RTK fixed vs float vs single point) weigh ``1/σ²``. When every
camera centre lies on one line (a single flight line), positions leave the rotation about that line
free; the caller then supplies rotation pairs (SfM vs metadata attitudes) to fix it
(:func:`fit_similarity` ``rotation_pairs``).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..errors import InputError

#: Camera centres whose spread across the main line is below this fraction of the spread along it
#: count as collinear: their positions cannot fix the rotation about that line.
COLLINEAR_RATIO = 0.02


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


def fit_similarity(source: np.ndarray, target: np.ndarray, weights=None, rotation_pairs=None) -> Similarity:
    """Least-squares ``target ≈ s·R·source + t`` with per-pair ``weights``.

    ``rotation_pairs`` (``R_source``, ``R_target``), arrays (N, 3, 3) of the same bodies' orientations
    in both frames, fix the rotation when the positions cannot (collinear or fewer than three): it is
    then the chordal mean of ``R_target · R_sourceᵀ`` and only scale and translation come from positions.
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
    if is_collinear(source, w):
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

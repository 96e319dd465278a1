"""Rigid transforms ``x ↦ R x + t``: a rotation and a translation, inverted and composed in one place.

Naming follows ``T_a_b`` (docs/design.md#camera): a transform called ``a_from_b`` takes points given in
frame b into frame a, so ``a_from_b @ b_from_c`` is ``a_from_c`` and ``a_from_b.inverse()`` is ``b_from_a``.
The inverse of a camera pose ``cam_from_world`` is ``world_from_cam``: its rotation is the camera → world
rotation and its translation the camera centre.

Every operation is vectorised over leading dimensions: a transform may hold one rotation (3, 3) and
translation (3,), or F of them (F, 3, 3) and (F, 3), e.g. one per frame.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class RigidTransform:
    """``apply(x) = rotation @ x + translation``; rotation (..., 3, 3) orthonormal, translation (..., 3)."""

    rotation: np.ndarray
    translation: np.ndarray

    def __post_init__(self):
        object.__setattr__(self, "rotation", np.asarray(self.rotation, dtype=float))
        object.__setattr__(self, "translation", np.asarray(self.translation, dtype=float))

    @classmethod
    def from_matrix(cls, matrix) -> "RigidTransform":
        """From homogeneous matrices (..., 4, 4), or their top three rows (..., 3, 4) as COLMAP gives them."""
        m = np.asarray(matrix, dtype=float)
        return cls(m[..., :3, :3], m[..., :3, 3])

    @property
    def matrix(self) -> np.ndarray:
        """Homogeneous matrices (..., 4, 4), a new array."""
        out = np.zeros(self.translation.shape[:-1] + (4, 4))
        out[..., :3, :3] = self.rotation
        out[..., :3, 3] = self.translation
        out[..., 3, 3] = 1.0
        return out

    def inverse(self) -> "RigidTransform":
        """``x ↦ Rᵀ (x − t)``: rotation Rᵀ, translation −Rᵀ t."""
        rt = np.swapaxes(self.rotation, -1, -2)
        return RigidTransform(rt, -_rotate(rt, self.translation))

    def __matmul__(self, other: "RigidTransform") -> "RigidTransform":
        """``self ∘ other``: ``other`` applied first, as the product of their matrices."""
        return RigidTransform(self.rotation @ other.rotation,
                              _rotate(self.rotation, other.translation) + self.translation)

    def apply(self, points) -> np.ndarray:
        """Points (..., 3) transformed; they broadcast against the transform's leading dimensions."""
        return _rotate(self.rotation, np.asarray(points, dtype=float)) + self.translation


def _rotate(rotation: np.ndarray, vectors: np.ndarray) -> np.ndarray:
    """``rotation @ v`` for vectors (..., 3), broadcast against rotations (..., 3, 3)."""
    return (rotation @ vectors[..., None])[..., 0]

"""RigidTransform: inverse, composition and application against plain 4×4 homogeneous matrices."""
import numpy as np

from birdseye.birdseye_qgis.core.geometry.rigid import RigidTransform
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp


def random_transforms(rng, *shape) -> RigidTransform:
    return RigidTransform(so3_exp(rng.normal(size=shape + (3,))), rng.normal(scale=50.0, size=shape + (3,)))


def homogeneous(points: np.ndarray) -> np.ndarray:
    return np.concatenate([points, np.ones(points.shape[:-1] + (1,))], axis=-1)


def test_matrix_round_trip_and_colmap_three_by_four():
    t = random_transforms(np.random.default_rng(1))
    m = t.matrix
    np.testing.assert_array_equal(m[3], [0.0, 0.0, 0.0, 1.0])
    back = RigidTransform.from_matrix(m)
    np.testing.assert_array_equal(back.rotation, t.rotation)
    np.testing.assert_array_equal(back.translation, t.translation)
    top = RigidTransform.from_matrix(m[:3])
    np.testing.assert_array_equal(top.matrix, m)


def test_inverse_round_trip_and_matches_the_matrix_inverse():
    t = random_transforms(np.random.default_rng(2))
    np.testing.assert_allclose((t @ t.inverse()).matrix, np.eye(4), atol=1e-12)
    np.testing.assert_allclose((t.inverse() @ t).matrix, np.eye(4), atol=1e-12)
    np.testing.assert_allclose(t.inverse().inverse().matrix, t.matrix, atol=1e-12)
    np.testing.assert_allclose(t.inverse().matrix, np.linalg.inv(t.matrix), atol=1e-12)
    # Rᵀ exactly, and the camera centre −Rᵀt of a cam_from_world pose.
    np.testing.assert_array_equal(t.inverse().rotation, t.rotation.T)
    np.testing.assert_allclose(t.inverse().translation, -t.rotation.T @ t.translation, atol=1e-12)


def test_composition_is_the_product_of_matrices():
    rng = np.random.default_rng(3)
    a, b, c = (random_transforms(rng) for _ in range(3))
    np.testing.assert_allclose((a @ b).matrix, a.matrix @ b.matrix, atol=1e-12)
    np.testing.assert_allclose(((a @ b) @ c).matrix, (a @ (b @ c)).matrix, atol=1e-12)
    np.testing.assert_allclose((a @ b).inverse().matrix, (b.inverse() @ a.inverse()).matrix, atol=1e-12)


def test_apply_matches_the_matrix_on_homogeneous_points():
    rng = np.random.default_rng(4)
    t = random_transforms(rng)
    points = rng.normal(scale=20.0, size=(50, 3))
    expected = (homogeneous(points) @ t.matrix.T)[:, :3]
    np.testing.assert_allclose(t.apply(points), expected, atol=1e-12)
    np.testing.assert_allclose(t.apply(points[0]), expected[0], atol=1e-12)
    np.testing.assert_allclose(t.inverse().apply(t.apply(points)), points, atol=1e-12)
    np.testing.assert_allclose((t @ t).apply(points), t.apply(t.apply(points)), atol=1e-12)


def test_batched_transforms_act_frame_by_frame():
    rng = np.random.default_rng(5)
    frames = random_transforms(rng, 7)
    mount = random_transforms(rng)
    points = rng.normal(size=(7, 3))
    composed = frames @ mount
    inverse = frames.inverse()
    assert frames.matrix.shape == (7, 4, 4)
    for f in range(7):
        one = RigidTransform(frames.rotation[f], frames.translation[f])
        np.testing.assert_allclose(composed.matrix[f], one.matrix @ mount.matrix, atol=1e-12)
        np.testing.assert_allclose(inverse.matrix[f], np.linalg.inv(one.matrix), atol=1e-12)
        np.testing.assert_allclose(frames.apply(points)[f], one.apply(points[f]), atol=1e-12)

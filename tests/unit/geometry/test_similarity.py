"""Weighted similarity fit: exact recovery, weights, the collinear case."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp
from birdseye.birdseye_qgis.core.geometry.similarity import fit_similarity, is_collinear

TRUE_R = so3_exp(np.array([0.3, -0.2, 1.1]))


def test_recovers_an_exact_similarity():
    rng = np.random.default_rng(1)
    src = rng.normal(size=(20, 3)) * [30, 20, 2]
    dst = 2.5 * src @ TRUE_R.T + [100.0, -40.0, 7.0]
    fit = fit_similarity(src, dst)
    assert fit.scale == pytest.approx(2.5, abs=1e-12)
    np.testing.assert_allclose(fit.rotation, TRUE_R, atol=1e-12)
    np.testing.assert_allclose(fit.apply(src), dst, atol=1e-9)


def test_weights_follow_the_accurate_positions():
    """One gross outlier with weight 1e-6 barely moves the fit; with equal weights it moves it."""
    rng = np.random.default_rng(2)
    src = rng.normal(size=(12, 3)) * [30, 20, 2]
    dst = 1.7 * src @ TRUE_R.T + [5.0, 6.0, 7.0]
    dst[0] += [3.0, -2.0, 4.0]
    w = np.ones(12)
    w[0] = 1e-6
    weighted = fit_similarity(src, dst, w)
    plain = fit_similarity(src, dst)
    err_w = np.abs(weighted.apply(src[1:]) - dst[1:]).max()
    err_p = np.abs(plain.apply(src[1:]) - dst[1:]).max()
    assert err_w < 1e-4 < 0.1 < err_p


def test_collinear_centres_need_rotation_pairs():
    t = np.linspace(0, 50, 10)
    src = np.column_stack([t, 0.001 * np.sin(t), np.zeros_like(t)])
    dst = 0.9 * src @ TRUE_R.T + [1.0, 2.0, 3.0]
    assert is_collinear(src)
    with pytest.raises(InputError, match="one line"):
        fit_similarity(src, dst)
    bodies = np.stack([so3_exp(np.array([0.1 * k, 0.05, -0.2])) for k in range(10)])
    fit = fit_similarity(src, dst, rotation_pairs=(bodies, np.einsum("ij,njk->nik", TRUE_R, bodies)))
    np.testing.assert_allclose(fit.rotation, TRUE_R, atol=1e-9)
    assert fit.scale == pytest.approx(0.9, abs=1e-9)
    np.testing.assert_allclose(fit.apply(src), dst, atol=1e-6)

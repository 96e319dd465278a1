"""Weighted similarity fit: exact recovery, weights, the collinear case; the robust fit (outliers left
out, refit to a fixed point) shared by pose refinement and COLMAP's GPS alignment."""
import numpy as np
import pytest

from birdseye.birdseye_qgis.core.errors import InputError
from birdseye.birdseye_qgis.core.geometry.rotations import so3_exp
from birdseye.birdseye_qgis.core.geometry.similarity import fit_similarity, fit_similarity_robust, is_collinear

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


def noisy_block(n=20, seed=4, sigma=0.03):
    rng = np.random.default_rng(seed)
    src = rng.normal(size=(n, 3)) * [30, 20, 1]
    dst = 3.2 * src @ TRUE_R.T + [100.0, -40.0, 7.0] + rng.normal(scale=sigma, size=(n, 3))
    return src, dst, np.full(n, sigma)


@pytest.mark.parametrize("bad", [[3], [0, 5, 11, 17], [1, 2, 3, 4, 5, 6, 7]])
def test_outliers_injected_give_the_fit_of_the_clean_set(bad):
    src, dst, sigma = noisy_block()
    clean = np.setdiff1d(np.arange(len(src)), bad)
    reference = fit_similarity(src[clean], dst[clean], 1.0 / sigma[clean] ** 2)
    # Coherent jumps (one direction, 4–12 m): a least-squares start would lean towards them.
    dst[bad] += np.outer(np.linspace(4.0, 12.0, len(bad)), [0.6, -0.8, 0.0])
    fit = fit_similarity_robust(src, dst, sigma)
    assert np.flatnonzero(~fit.inliers).tolist() == bad
    assert fit.converged
    assert fit.similarity.scale == pytest.approx(reference.scale, abs=1e-12)
    np.testing.assert_allclose(fit.similarity.rotation, reference.rotation, atol=1e-12)
    np.testing.assert_allclose(fit.similarity.translation, reference.translation, atol=1e-9)


def test_the_refit_loop_ends_at_a_fixed_point():
    """Residuals of the final fit select exactly the inliers it was fitted on."""
    src, dst, sigma = noisy_block(n=30, seed=8, sigma=0.5)
    dst[[2, 9]] += [[15.0, 0, 0], [0, -9.0, 3.0]]
    dst[14] += [2.6, 0, 0]  # borderline: ~5 σ
    fit = fit_similarity_robust(src, dst, sigma)
    assert fit.converged and fit.refits < 20
    again = fit_similarity(src[fit.inliers], dst[fit.inliers], 1.0 / sigma[fit.inliers] ** 2)
    residual = np.linalg.norm(again.apply(src) - dst, axis=1)
    limit = np.maximum(5.0 * np.median(residual[fit.inliers]), 5.0 * sigma)
    np.testing.assert_array_equal(residual <= limit, fit.inliers)
    assert not fit.inliers[2] and not fit.inliers[9]


def test_a_single_line_with_an_outlier_takes_its_rotation_from_the_attitudes():
    t = np.linspace(0, 80, 12)
    src = np.column_stack([t, np.zeros_like(t), np.zeros_like(t)])
    dst = 0.9 * src @ TRUE_R.T + [1.0, 2.0, 3.0]
    dst[6] += [0.0, 5.0, 0.0]
    bodies = np.stack([so3_exp(np.array([0.1 * k, 0.05, -0.2])) for k in range(12)])
    fit = fit_similarity_robust(src, dst, np.full(12, 0.03),
                                rotation_pairs=(bodies, np.einsum("ij,njk->nik", TRUE_R, bodies)))
    assert np.flatnonzero(~fit.inliers).tolist() == [6]
    np.testing.assert_allclose(fit.similarity.rotation, TRUE_R, atol=1e-9)
    assert fit.similarity.scale == pytest.approx(0.9, abs=1e-9)


def test_colmap_gps_alignment_is_the_same_robust_fit(monkeypatch, tmp_path):
    """An image whose GPS tag jumped 40 m is left out of a COLMAP model's georeferencing."""
    from birdseye.birdseye_qgis.core.field.solutions import colmap
    from birdseye.birdseye_qgis.core.geometry.geodesy import LocalFrame

    rng = np.random.default_rng(5)
    enu = rng.normal(size=(9, 3)) * [40, 30, 1] + [0, 0, 50]
    local = LocalFrame.around(np.array([51.0]), np.array([-1.0]), np.array([80.0]))
    lat, lon, h = local.to_geodetic(enu)
    tags = {f"IMG_{k}.JPG": (lat[k], lon[k], h[k]) for k in range(9)}
    lat4, lon4, h4 = local.to_geodetic(enu[4:5] + [40.0, 0, 0])
    tags["IMG_4.JPG"] = (lat4[0], lon4[0], h4[0])
    monkeypatch.setattr(colmap, "match_images", lambda names, folder: {n: n for n in names})
    monkeypatch.setattr(colmap, "image_gps", lambda name: tags[name])
    sfm = (enu - [5.0, 5.0, 0]) @ TRUE_R / 4.0
    sim, residual, kept = colmap._gps_alignment(list(tags), sfm, tmp_path, "model")
    assert kept == 8 and residual < 1e-3

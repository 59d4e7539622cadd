"""Image metrics against hand-computed values."""

import numpy as np
import pytest

from glshade.compare import metrics


def test_psnr_of_known_noise_level(rng):
    a = np.full((64, 64, 3), 100.0)
    noise = rng.choice([-5.0, 5.0], size=a.shape)  # |noise| = 5 everywhere: RMSE = 5
    assert metrics.rmse(a + noise, a) == pytest.approx(5.0)
    assert metrics.psnr(a + noise, a) == pytest.approx(20 * np.log10(255 / 5))
    assert metrics.psnr(a, a) == float("inf")


def test_ssim_is_one_on_identical_images_and_matches_the_noise_formula(rng):
    a = rng.uniform(0, 255, (96, 96))
    assert metrics.ssim(a, a) == pytest.approx(1.0)
    # y = x + independent noise: SSIM -> (2 var_x + C2) / (2 var_x + var_n + C2) (means equal)
    var_x, var_n, c2 = 255**2 / 12, 30.0**2, (0.03 * 255) ** 2
    expected = (2 * var_x + c2) / (2 * var_x + var_n + c2)
    assert metrics.ssim(a, a + rng.normal(0, 30, a.shape)) == pytest.approx(expected, abs=0.02)


def test_one_pixel_change():
    a = np.zeros((10, 10, 3))
    b = a.copy()
    b[3, 4, 1] = 40
    assert metrics.max_error(a, b) == 40
    assert metrics.mae(a, b) == pytest.approx(40 / 300)
    err = metrics.abs_error(a, b)
    assert err[3, 4] == 40 and err.sum() == 40
    mask = np.zeros((10, 10), bool)
    mask[0] = True
    assert metrics.max_error(a, b, mask) == 0  # the change is outside the mask


def test_mach_band_strength_measures_jumps_across_polygon_edges():
    ids = np.zeros((8, 8), int)
    ids[:, 4:] = 1
    img = np.zeros((8, 8, 3))
    img[:, 4:] = 30.0  # a 30-unit step at the edge between polygons 0 and 1
    assert metrics.mach_band_strength(img, ids) == pytest.approx(30.0)
    smooth = np.tile(np.arange(8.0)[None, :, None] * 2, (8, 1, 3))
    assert metrics.mach_band_strength(smooth, ids, reference=smooth) == 0.0
    ids[:, :2] = -1  # background never counts
    assert metrics.mach_band_strength(img, ids) == pytest.approx(30.0)


def test_shape_mismatch():
    from glshade import GlshadeError

    with pytest.raises(GlshadeError, match=r"differ in shape"):
        metrics.mae(np.zeros((2, 2, 3)), np.zeros((3, 2, 3)))

"""Similar surfaces (method §3): random phases, longer surfaces (3.6), IAAFT."""

from __future__ import annotations

import numpy as np
import pytest
from scipy import stats

from stochfric.surface.io import SurfaceError, default_surface_path, read_surface, surface_from_array
from stochfric.surface.preprocess import prepare
from stochfric.surface.surrogates import similar_surface
from stochfric.surface.synthesis import (
    amplitude_error,
    amplitude_spectrum,
    iaaft_heights,
    interpolate_amplitudes,
    longer_surface,
    random_phase_heights,
)


@pytest.fixture(scope="module")
def shipped() -> np.ndarray:
    fine, _ = prepare(read_surface(default_surface_path()))
    return np.asarray(fine.heights_m)


def _aniso(shape: tuple[int, int], seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    z = rng.standard_normal(shape)
    # anisotropic smoothing + an offset and skew: not Gaussian, not isotropic
    z = np.cumsum(z, axis=1) * 0.1 + z
    return np.exp(0.5 * z) + 3.0


@pytest.mark.parametrize("shape", [(32, 48), (31, 47), (32, 47), (31, 48)])
def test_random_phase_keeps_amplitudes_exactly(shape: tuple[int, int]) -> None:
    z = _aniso(shape, 1)
    s = random_phase_heights(z, 7, amplitude="raw")
    assert s.shape == z.shape and s.dtype == np.float64
    np.testing.assert_allclose(np.abs(np.fft.fft2(s)), np.abs(np.fft.fft2(z)), rtol=1e-10, atol=1e-10 * z.size)
    # every estimate: the surrogate's amplitudes are the estimate's exactly, variance restored
    for method in ("tukey", "hann"):
        t = random_phase_heights(z, 7, amplitude=method)
        np.testing.assert_allclose(
            np.abs(np.fft.fft2(t)) / np.sqrt(z.size), amplitude_spectrum(z, method), rtol=1e-10, atol=1e-10
        )
        assert t.var() == pytest.approx(z.var(), rel=1e-10)
    assert s.mean() == pytest.approx(z.mean(), rel=1e-12)
    assert s.var() == pytest.approx(z.var(), rel=1e-10)
    assert not np.allclose(s, z)


def test_random_phase_reproducible_and_seed_dependent() -> None:
    z = _aniso((20, 30), 2)
    np.testing.assert_array_equal(random_phase_heights(z, 3), random_phase_heights(z, np.random.default_rng(3)))
    assert not np.allclose(random_phase_heights(z, 3), random_phase_heights(z, 4))


def test_random_phase_is_gaussian_and_phases_uniform() -> None:
    # the heights of a phase surrogate of a skewed map are close to Gaussian (central limit)
    z = _aniso((64, 64), 5)
    s = random_phase_heights(z, 11)
    assert abs(stats.skew(z.ravel())) > 1.0
    assert abs(stats.skew(s.ravel())) < 0.3
    phases = np.angle(np.fft.rfft2(s - s.mean())[1:31, 1:31]).ravel()
    assert stats.kstest(phases, stats.uniform(loc=-np.pi, scale=2 * np.pi).cdf).pvalue > 1e-3


def test_interpolated_amplitudes_point_symmetric() -> None:
    z = _aniso((12, 16), 3)
    a1 = interpolate_amplitudes(amplitude_spectrum(z), 5)
    assert a1.shape == (12, 80)
    mirror = np.roll(np.flip(a1, axis=(0, 1)), 1, axis=(0, 1))  # A(−m, −l)
    np.testing.assert_allclose(a1, mirror, rtol=1e-13)
    # every 5th column is an original column (DC element zeroed)
    a = amplitude_spectrum(z)
    a[0, 0] = 0.0
    np.testing.assert_allclose(a1[:, ::5], a, rtol=1e-13)


@pytest.mark.parametrize("factor", [1, 2, 3, 10])
def test_longer_surface_keeps_variance_and_mean(shipped: np.ndarray, factor: int) -> None:
    surf = surface_from_array(shipped, physical_size_m=(87.6e-6, 129.7e-6))
    long = longer_surface(surf, factor, 1)
    assert long.heights_m.shape == (shipped.shape[0], factor * shipped.shape[1])
    assert long.physical_size_m[1] == pytest.approx(factor * 129.7e-6)
    assert long.grid_spacing_m == pytest.approx(surf.grid_spacing_m)
    assert long.heights_m.var() == pytest.approx(shipped.var(), rel=1e-10)
    assert long.heights_m.mean() == pytest.approx(shipped.mean(), abs=1e-12 * shipped.std())


def test_longer_surface_without_rescaling_would_change_variance(shipped: np.ndarray) -> None:
    # the rescaling step matters: plain interpolation of |Z| changes Σ|Z|² (so the test above can fail)
    a = amplitude_spectrum(shipped)
    a[0, 0] = 0.0
    a1 = interpolate_amplitudes(a, 10)
    ratio = float(np.sum(a1**2)) / (10 * float(np.sum(a**2)))
    assert abs(ratio - 1.0) > 1e-3


def test_iaaft_keeps_heights_exactly_and_spectrum_within_bound(shipped: np.ndarray) -> None:
    res = iaaft_heights(shipped, 5, tol=1e-3)
    np.testing.assert_array_equal(np.sort(res.heights.ravel()), np.sort(shipped.ravel()))
    ks = stats.ks_2samp(res.heights.ravel(), shipped.ravel())
    assert ks.statistic == 0.0
    # documented bound: ε <= 1 % of the amplitude spectrum (measured 1e-4 … 4e-4 on this surface)
    # the target is the default (Tukey) amplitude estimate, rfft2 layout, unnormalised
    target = amplitude_spectrum(shipped, "tukey")[:, : shipped.shape[1] // 2 + 1] * np.sqrt(shipped.size)
    assert res.amplitude_error == pytest.approx(amplitude_error(res.heights, target))
    assert res.amplitude_error < 0.01
    # the iteration matters: one rank remap of a phase surrogate is worse
    one = iaaft_heights(shipped, 5, max_iter=1)
    assert one.amplitude_error > 3 * res.amplitude_error
    assert not np.allclose(res.heights, shipped)


def test_iaaft_longer_surface_repeats_the_heights(shipped: np.ndarray) -> None:
    small = shipped[:60, :80]
    res = iaaft_heights(small, 2, factor=3, tol=1e-3)
    assert res.heights.shape == (60, 240)
    np.testing.assert_array_equal(np.sort(res.heights.ravel()), np.sort(np.repeat(small.ravel(), 3)))
    assert res.amplitude_error < 0.05


def test_similar_surface_methods_and_errors(shipped: np.ndarray) -> None:
    surf = surface_from_array(shipped[:40, :50], physical_size_m=(1e-5, 2e-5))
    assert similar_surface(surf, 1, method="iaaft").heights_m.shape == (40, 50)
    with pytest.raises(SurfaceError, match="surrogate method"):
        similar_surface(surf, 1, method="gauss")
    with pytest.raises(SurfaceError, match="factor"):
        longer_surface(surf, 0, 1)
    with pytest.raises(SurfaceError, match="NaN"):
        random_phase_heights(np.full((4, 4), np.nan), 1)


def test_gaussian_field_draws_new_amplitudes_around_the_windowed_periodogram() -> None:
    """gaussian_field_heights: real, the map's mean, reproducible; |DFT|² varies from draw to draw (unlike
    random phases) and averages to the tapered periodogram in Welch's normalisation, |DFT((h − h̄)w)|²/mean(w²)
    (computed here from scipy's Tukey window, not through the package)."""
    from scipy.signal import windows

    from stochfric.surface.synthesis import TUKEY_ALPHA, gaussian_field_heights, windowed_periodogram

    z = np.random.default_rng(4).standard_normal((24, 32)).cumsum(axis=0).cumsum(axis=1) + 5.0
    a = gaussian_field_heights(z, 11)
    assert a.shape == z.shape and np.isrealobj(a) and a.mean() == pytest.approx(z.mean(), abs=1e-9)
    np.testing.assert_array_equal(a, gaussian_field_heights(z, 11))
    assert not np.array_equal(np.abs(np.fft.fft2(a)), np.abs(np.fft.fft2(gaussian_field_heights(z, 12))))
    w = windows.tukey(24, TUKEY_ALPHA, sym=False)[:, None] * windows.tukey(32, TUKEY_ALPHA, sym=False)[None, :]
    expected = np.abs(np.fft.fft2((z - z.mean()) * w)) ** 2 / np.mean(w**2)
    expected[0, 0] = 0.0
    np.testing.assert_allclose(windowed_periodogram(z), expected, rtol=1e-12, atol=1e-12 * expected.max())
    draws = np.array([np.abs(np.fft.fft2(gaussian_field_heights(z, s) - z.mean())) ** 2 for s in range(1000)])
    mean = draws.mean(axis=0)
    # each bin of a draw is the expected power times an exponential variable: over 1000 draws the mean of a
    # bin is within 3 SE (3/sqrt(1000) ~ 10 %) of it, and the total (a few bins dominate) within 5 %
    assert mean.sum() == pytest.approx(expected.sum(), rel=0.05)
    band = expected > np.quantile(expected, 0.5)
    ratio = mean[band] / expected[band]
    assert np.median(ratio) == pytest.approx(1.0, abs=0.03)
    assert np.mean(np.abs(ratio - 1.0) < 0.1) > 0.95
    with pytest.raises(SurfaceError, match="unknown amplitude"):
        windowed_periodogram(z, "boxcar")

"""ACF, correlation length, PSD along the path (3.17–3.20) and the ergodicity verdict."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.friction_process.spectra import (
    autocorrelation,
    correlation_length,
    integral_correlation_length,
    mean_psd,
    normalise,
    psd_level,
)
from stochfric.process.checks import ergodicity_check
from stochfric.process.estimators import linear_fit, mean_and_std_errors


def test_normalise_and_acf_of_white_noise() -> None:
    rng = np.random.default_rng(1)
    mu = 0.3 + 0.05 * rng.standard_normal((20, 400))
    bar = normalise(mu)
    assert bar.mean() == pytest.approx(0.0, abs=1e-12) and bar.std() == pytest.approx(1.0)
    r = autocorrelation(mu)
    assert r.shape == (201,)
    assert r[0] == pytest.approx(1.0, rel=1e-12)
    # lags > 0 of white noise: mean 0, SE ≈ 1/√(records·(W − k))
    assert np.all(np.abs(r[1:20]) < 4.0 / np.sqrt(20 * 380))


def test_correlation_length_of_a_moving_average() -> None:
    # μ = moving sum of L white values: ACF (1 − k/L) → first zero at lag L
    rng = np.random.default_rng(2)
    length = 8
    w = rng.standard_normal((30, 2000 + length))
    mu = np.stack([np.convolve(row, np.ones(length), mode="valid")[:2000] for row in w])
    r = autocorrelation(mu, max_lag=20)
    np.testing.assert_allclose(r[:9], 1.0 - np.arange(9) / length, atol=0.03)
    assert correlation_length(r, 2.5e-6) == pytest.approx(length * 2.5e-6, rel=0.05)


def test_integral_correlation_length_of_a_moving_average_is_stable() -> None:
    """ℓ_int = aL/2 for a moving sum of L white values; its scatter between records is a few per cent,
    the first zero crossing of each record's own ACF scatters several times more."""
    rng = np.random.default_rng(4)
    length, a = 8, 2.5e-6
    w = rng.standard_normal((40, 4000 + length))
    mu = np.stack([np.convolve(row, np.ones(length), mode="valid")[:4000] for row in w])
    ell = np.array([integral_correlation_length(r, a, length * a) for r in mu])
    assert ell.mean() == pytest.approx(length * a / 2, rel=0.05)
    zero = np.array([correlation_length(autocorrelation(r[None, :], max_lag=60), a) for r in mu])
    assert ell.std() / ell.mean() < 0.1
    assert ell.std() / ell.mean() < 0.5 * np.nanstd(zero) / np.nanmean(zero)
    assert np.isnan(integral_correlation_length(np.ones(10), a, a))


def test_correlation_length_interpolates_and_reports_none() -> None:
    assert correlation_length([1.0, 0.5, -0.5], 2.0) == pytest.approx(3.0)
    assert np.isnan(correlation_length([1.0, 0.5, 0.2], 2.0))


@pytest.mark.parametrize("n", [64, 65])
def test_mean_psd_parseval_and_white_level(n: int) -> None:
    rng = np.random.default_rng(3)
    mu = rng.standard_normal((400, n))
    f, s, se = mean_psd(mu, 1e-5)
    df = 1.0 / (n * 1e-5)
    np.testing.assert_allclose(f, np.arange(1, n // 2 + 1) * df)
    assert np.sum(s) * df == pytest.approx(mu.var(axis=1).mean(), rel=1e-12)
    # white samples at spacing a_y = ℓ (non-overlapping windows): S(f → 0) = 2ℓσ² divided by
    # the boxcar response over f ≤ 1/(4ℓ); within 4 SE of the mean of the bins used
    level = psd_level(f, s, 1e-5)
    keep = f * 1e-5 <= 0.25
    expected = float(np.mean(2e-5 * (1.0 - 1.0 / n) / np.sinc(f[keep] * 1e-5) ** 2))
    assert abs(level - expected) < 4.0 * float(np.mean(se[keep])) / np.sqrt(keep.sum())
    assert np.all(se > 0)


def test_psd_level_of_a_moving_average_is_its_zero_frequency_level() -> None:
    """μ(y) of windows of length ℓ shifted by a_y ≪ ℓ: S(f → 0) = 2σ_local² ℓ_local for any a_y."""
    rng = np.random.default_rng(8)
    dy, ell_pts = 1e-6, 100
    local = rng.standard_normal((200, 4000))  # white local friction at spacing dy
    csum = np.concatenate((np.zeros((200, 1)), np.cumsum(local, axis=1)), axis=1)
    levels = []
    for shift in (5, 50):
        starts = np.arange(0, 4000 - ell_pts + 1, shift)
        mu = (csum[:, starts + ell_pts] - csum[:, starts]) / ell_pts
        f, s, _se = mean_psd(mu, shift * dy)
        levels.append(psd_level(f, s, ell_pts * dy))
    expected = 2.0 * dy  # S_local(0) = 2 σ² dy for white samples of unit variance
    assert levels[0] == pytest.approx(expected, rel=0.1)
    assert levels[1] == pytest.approx(expected, rel=0.1)


def test_mean_and_std_errors_match_the_scatter() -> None:
    rng = np.random.default_rng(4)
    data = rng.exponential(size=(400, 200, 2))  # 200 experiments of 400 samples, skewed
    m, s, sem, ses = mean_and_std_errors(data)
    assert np.std(m, axis=0, ddof=1) == pytest.approx(sem.mean(axis=0), rel=0.15)
    assert np.std(s, axis=0, ddof=1) == pytest.approx(ses.mean(axis=0), rel=0.15)


def test_ergodicity_verdict() -> None:
    rng = np.random.default_rng(5)
    ergodic = 0.3 + 0.05 * rng.standard_normal((10, 10, 6))  # K surfaces × J windows × U
    same = ergodicity_check(ergodic)
    assert same.consistent and same.max_abs_z <= same.threshold
    assert same.threshold == pytest.approx(2.865, abs=0.01)  # Φ⁻¹(1 − 0.05/24): 2U = 12 two-sided tests
    # a non-ergodic process: every realisation has its own mean (offset per surface)
    offsets = 0.05 * rng.standard_normal((10, 1, 6))
    biased = ergodicity_check(ergodic + offsets)
    assert not biased.consistent and max(biased.z_mean) > biased.threshold
    # along one surface the scatter is smaller than across surfaces -> z_std negative
    assert np.mean(biased.z_std) < -2.0
    with pytest.raises(ValueError):
        ergodicity_check(ergodic[:2])


def test_linear_fit() -> None:
    x = np.linspace(1.0, 10.0, 8)
    fit = linear_fit(x, 2.0 * x + 1.0)
    assert fit["slope"] == pytest.approx(2.0) and fit["intercept"] == pytest.approx(1.0)
    assert fit["r_squared"] == pytest.approx(1.0)


def test_memory_estimate_refuses_before_work() -> None:
    from stochfric.errors import AnalysisError
    from stochfric.process.memory import check_memory, estimate_peak_memory_bytes, workers_that_fit

    # the thesis's 1700² map with 10 lengths: measured peak 1118 MiB, estimate above it and < 4 GiB
    est = estimate_peak_memory_bytes((1700, 1700), 10)
    assert 1118 * 2**20 < est < 4 * 2**30
    assert check_memory((200, 296), 10, available=2**30) == estimate_peak_memory_bytes((200, 296), 10)
    # two long surfaces of 1700 x 17000 points at once need 2 x 1.3 GiB: with 2 GiB only one worker builds them
    assert workers_that_fit((1700, 1700), 10, 2, available=2 * 2**30) == 1
    assert workers_that_fit((1700, 1700), 10, 2, available=8 * 2**30) == 2
    assert workers_that_fit((1700, 1700), 10, 4, available=2**20) == 1
    with pytest.raises(AnalysisError, match=r"GB.*--length-factor"):
        check_memory((1700, 1700), 100, available=8 * 2**30)

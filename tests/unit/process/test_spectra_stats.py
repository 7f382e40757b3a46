"""ACF, correlation length, PSD along the path (3.17–3.20) and the ergodicity verdict."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.process.spectra import autocorrelation, correlation_length, mean_psd, normalise, psd_level
from stochfric.process.statistics import ergodicity_check, linear_fit, mean_and_std_errors


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
    # white noise: E[S] = 2 a_y σ² (1 − 1/n for the removed record mean), within 4 SE of the mean
    level = psd_level(f, s, 1e-5)
    expected = 2e-5 * (1.0 - 1.0 / n)
    assert abs(level - expected) < 4.0 * np.mean(se) / np.sqrt(s.size)
    assert np.all(se > 0)


def test_mean_and_std_errors_match_the_scatter() -> None:
    rng = np.random.default_rng(4)
    data = rng.exponential(size=(400, 200, 2))  # 200 experiments of 400 samples, skewed
    m, s, sem, ses = mean_and_std_errors(data)
    assert np.std(m, axis=0, ddof=1) == pytest.approx(sem.mean(axis=0), rel=0.15)
    assert np.std(s, axis=0, ddof=1) == pytest.approx(ses.mean(axis=0), rel=0.15)


def test_ergodicity_verdict() -> None:
    rng = np.random.default_rng(5)
    a = 0.3 + 0.05 * rng.standard_normal((100, 6))
    b = 0.3 + 0.05 * rng.standard_normal((60, 6))
    same = ergodicity_check(a, b)
    assert same.consistent and same.max_abs_z <= same.threshold
    assert same.threshold == pytest.approx(2.865, abs=0.01)  # Φ⁻¹(1 − 0.05/24)
    shifted = ergodicity_check(a, b + 0.03)
    assert not shifted.consistent and shifted.max_abs_z > 4
    wider = ergodicity_check(a, 0.3 + 2.0 * (b - 0.3))
    assert not wider.consistent and max(np.abs(wider.z_std)) > wider.threshold


def test_linear_fit() -> None:
    x = np.linspace(1.0, 10.0, 8)
    fit = linear_fit(x, 2.0 * x + 1.0)
    assert fit["slope"] == pytest.approx(2.0) and fit["intercept"] == pytest.approx(1.0)
    assert fit["r_squared"] == pytest.approx(1.0)

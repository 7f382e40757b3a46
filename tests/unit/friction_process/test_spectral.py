"""Unit tests of the PSD estimate and the spectral representation (method §0, eq. 2.48)."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.friction_process import spectral
from stochfric.friction_process.spectral import (
    band_limited_frequencies,
    generate_process,
    nyquist_frequency,
    one_sided_psd,
    spectral_representation,
)


@pytest.mark.parametrize("n", [2, 3, 64, 65, 1000, 1001])
def test_parseval_exact_for_odd_and_even_n(n: int) -> None:
    rng = np.random.default_rng(1234 + n)
    values = 0.3 + rng.standard_normal(n) * 0.07
    dx = 3e-4
    f, s = one_sided_psd(values, dx)
    df = 1.0 / (n * dx)
    assert f.shape == s.shape == (n // 2,)
    assert np.sum(s) * df == pytest.approx(np.var(values), rel=1e-12, abs=0.0)


def test_parseval_batched_along_last_axis() -> None:
    rng = np.random.default_rng(7)
    values = rng.standard_normal((5, 3, 40))
    f, s = one_sided_psd(values, 0.01)
    assert s.shape == (5, 3, 20)
    np.testing.assert_allclose(np.sum(s, axis=-1) * (f[1] - f[0]), values.var(axis=-1), rtol=1e-12)


def test_psd_frequencies_and_a_pure_harmonic() -> None:
    n, dx, k0, amp = 50, 2e-3, 7, 0.4
    x = np.arange(n) * dx
    values = amp * np.cos(2 * np.pi * k0 * x / (n * dx) + 0.3) + 5.0  # mean removed
    f, s = one_sided_psd(values, dx)
    np.testing.assert_allclose(f, np.arange(1, 26) / (n * dx), rtol=1e-15)
    df = 1.0 / (n * dx)
    expected = np.zeros(25)
    expected[k0 - 1] = amp**2 / 2 / df  # variance A²/2 in one bin of width Δf
    np.testing.assert_allclose(s, expected, rtol=1e-12, atol=1e-12 * expected.max())


def test_nyquist_bin_of_even_n_has_half_weight() -> None:
    values = (-1.0) ** np.arange(8)  # pure Nyquist oscillation, variance 1
    f, s = one_sided_psd(values, 0.5)
    assert f[-1] == pytest.approx(nyquist_frequency(0.5))
    assert s[-1] * (f[1] - f[0]) == pytest.approx(1.0, rel=1e-14)
    np.testing.assert_allclose(s[:-1], 0.0, atol=1e-14)


def test_one_sided_psd_refuses_bad_input() -> None:
    with pytest.raises(ValueError, match="at least 2"):
        one_sided_psd(np.ones(1), 1.0)
    with pytest.raises(ValueError, match="NaN"):
        one_sided_psd(np.array([1.0, np.nan, 2.0]), 1.0)
    with pytest.raises(ValueError, match="dx"):
        one_sided_psd(np.ones(4), 0.0)


def _harmonic_setup(
    n: int = 60, dx: float = 5e-4, seed: int = 3
) -> tuple[np.ndarray, np.ndarray, np.ndarray, float]:
    length = n * dx
    f = band_limited_frequencies(dx, length)
    rng = np.random.default_rng(seed)
    psd = rng.uniform(0.1, 2.0, f.size) * 1e-5
    phases = rng.uniform(0.0, 2 * np.pi, f.size)
    return f, psd, phases, length


@pytest.mark.parametrize("n", [60, 61])
def test_variance_over_one_period_is_exact(n: int) -> None:
    dx = 5e-4
    f, psd, phases, _ = _harmonic_setup(n, dx)
    x = np.arange(n) * dx
    mu = spectral_representation(f, psd, x, phases)
    target = np.sum(psd) * (f[1] - f[0])
    assert np.var(mu) == pytest.approx(target, rel=1e-12)
    assert abs(np.mean(mu)) < 1e-13 * np.sqrt(target)


def test_matches_direct_sum_and_blocking(monkeypatch: pytest.MonkeyPatch) -> None:
    f, psd, phases, _ = _harmonic_setup()
    x = np.linspace(-0.01, 0.07, 37).reshape(37, 1) * np.ones((1, 3))
    df = f[1] - f[0]
    direct = np.zeros_like(x)
    for fi, si, pi in zip(f, psd, phases, strict=True):
        direct += np.sqrt(2.0) * np.sqrt(si * df) * np.cos(2 * np.pi * fi * x + pi)
    full = spectral_representation(f, psd, x, phases)
    monkeypatch.setattr(spectral, "_BLOCK_ELEMENTS", 7)  # forces many small blocks
    blocked = spectral_representation(f, psd, x, phases)
    assert full.shape == x.shape
    np.testing.assert_allclose(full, direct, rtol=1e-10, atol=1e-12)
    np.testing.assert_allclose(blocked, full, rtol=1e-12, atol=1e-15)


def test_periodic_with_period_length() -> None:
    f, psd, phases, length = _harmonic_setup()
    x = np.linspace(0.0, length, 101)
    a = spectral_representation(f, psd, x, phases)
    b = spectral_representation(f, psd, x + length, phases)
    c = spectral_representation(f, psd, x + 3 * length, phases)
    np.testing.assert_allclose(b, a, atol=1e-12)
    np.testing.assert_allclose(c, a, atol=1e-12)
    assert a[-1] == pytest.approx(a[0], abs=1e-12)


def test_generate_process_periodic_repetition_and_exact_variance() -> None:
    dx, n = 4e-4, 50
    length = n * dx
    f = band_limited_frequencies(dx, length)
    psd = np.linspace(2.0, 1.0, f.size) * 1e-5
    two_periods = generate_process(f, psd, dx, 2 * length, np.random.default_rng(11))
    assert two_periods.shape == (2 * n,)
    np.testing.assert_allclose(two_periods[n:], two_periods[:n], atol=1e-12)
    one = generate_process(f, psd, dx, length, np.random.default_rng(11))
    np.testing.assert_allclose(one, two_periods[:n], atol=1e-14)
    assert np.var(one) == pytest.approx(np.sum(psd) / length, rel=1e-12)
    # each realisation's periodogram over one period IS the target (phases drop out)
    f_est, s_est = one_sided_psd(one, dx)
    np.testing.assert_allclose(s_est[: f.size], psd, rtol=1e-10)
    np.testing.assert_allclose(f_est[: f.size], f, rtol=1e-12)


def test_generate_process_draws_uniform_phases_from_rng() -> None:
    dx, length = 1e-3, 0.03
    f = band_limited_frequencies(dx, length)
    psd = np.full(f.size, 2e-5)
    got = generate_process(f, psd, dx, length, np.random.default_rng(5))
    phases = np.random.default_rng(5).uniform(0.0, 2 * np.pi, f.size)
    expected = spectral_representation(f, psd, np.arange(30) * dx, phases)
    np.testing.assert_allclose(got, expected, rtol=0, atol=1e-15)
    # a seed is normalised through stochfric.random.as_generator: reproducible
    np.testing.assert_array_equal(
        generate_process(f, psd, dx, length, 42), generate_process(f, psd, dx, length, 42)
    )


@pytest.mark.parametrize("factor", [1.0, 1.0 - 1e-12, 1.3])
def test_frequencies_at_or_above_nyquist_are_refused(factor: float) -> None:
    dx = 1e-3
    f = np.array([100.0, 200.0, 300.0, 400.0, 500.0 * factor])
    with pytest.raises(ValueError, match="Nyquist"):
        generate_process(f, np.ones(5) * 1e-6, dx, 0.01, np.random.default_rng(0))


def test_band_limited_frequencies_strictly_below_nyquist() -> None:
    # length/(2 dx) = 10 exactly: the 10th harmonic is the Nyquist frequency -> excluded
    f = band_limited_frequencies(1e-3, 0.02)
    np.testing.assert_allclose(f, np.arange(1, 10) / 0.02)
    # non-integer ratio: K = floor(length / (2 dx))
    assert band_limited_frequencies(6.3e-4, 0.05).size == 39
    assert band_limited_frequencies(3e-4, 0.02).size == 33
    assert np.all(band_limited_frequencies(6.3e-4, 0.05) < nyquist_frequency(6.3e-4))
    with pytest.raises(ValueError, match="exceed"):
        band_limited_frequencies(1e-3, 2e-3)


def test_spectral_representation_refuses_bad_input() -> None:
    f = np.array([10.0, 20.0, 30.0])
    with pytest.raises(ValueError, match="uniform"):
        spectral_representation(np.array([10.0, 20.0, 35.0]), np.ones(3), 0.0, np.zeros(3))
    with pytest.raises(ValueError, match=">= 0"):
        spectral_representation(f, np.array([1.0, -1.0, 1.0]), 0.0, np.zeros(3))
    with pytest.raises(ValueError, match="phases"):
        spectral_representation(f, np.ones(3), 0.0, np.zeros(2))
    with pytest.raises(ValueError, match="must match"):
        spectral_representation(f, np.ones(2), 0.0, np.zeros(3))


def test_single_frequency_uses_first_harmonic_as_step() -> None:
    value = spectral_representation(np.array([50.0]), np.array([2e-4]), 0.0, np.array([0.0]))
    assert float(value) == pytest.approx(np.sqrt(2 * 2e-4 * 50.0))
    explicit = spectral_representation(
        np.array([50.0]), np.array([2e-4]), 0.0, np.array([0.0]), df=25.0
    )
    assert float(explicit) == pytest.approx(np.sqrt(2 * 2e-4 * 25.0))

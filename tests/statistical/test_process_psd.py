"""Seeded Monte Carlo checks of generated friction processes (method §0, §4e, Fig. 3.23/3.33).

Tolerances are 4 standard errors of the ensemble mean, the SE estimated from the
ensemble itself.  Two properties are exact rather than statistical, and are tested as
such: over exactly one period (harmonics k/ℓ, ℓ/Δx integer) every realisation has the
target variance, and its periodogram equals the target PSD bin by bin (the random
phases drop out of |X_k|), so the ensemble SE of the periodogram there is ~0.  The
genuinely random second-order check is therefore done on a window that is *not* a period,
against the exact expectation of its periodogram (target smeared by the Fejér kernel).
"""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.friction_process.model import BandLimitedProcessModel, ModelFunction
from stochfric.friction_process.spectral import generate_process, one_sided_psd
from stochfric.random import spawn_generators

N_REAL = 400
DX = 3e-4
N_GRID = 70
LENGTH = N_GRID * DX  # ℓ/Δx integer: the grid spans exactly one period
PRESSURE = 5e5


def _model() -> BandLimitedProcessModel:
    # the sheet fits with a falling spectrum, on a grid that closes on one period
    return BandLimitedProcessModel(
        name="sheet-like",
        mu_mean=ModelFunction(a=28.3661, b=-0.4786, c=0.2194),
        mu_std=ModelFunction(a=-1.0185, b=0.0120, c=1.2689),
        dx=DX,
        length=LENGTH,
        spectrum_shape="falling",
        falling_ratio=0.5,
    )


@pytest.fixture(scope="module")
def ensemble() -> np.ndarray:
    model = _model()
    assert model.grid_is_periodic
    return np.stack([model.generate(PRESSURE, g) for g in spawn_generators(20240611, N_REAL)])


def test_ensemble_periodogram_matches_target(ensemble: np.ndarray) -> None:
    model = _model()
    f_target = model.frequencies()
    target = model.spectrum(f_target, PRESSURE)
    f, s = one_sided_psd(ensemble, DX)
    np.testing.assert_allclose(f[: f_target.size], f_target, rtol=1e-12)
    mean = s.mean(axis=0)
    se = s.std(axis=0, ddof=1) / np.sqrt(N_REAL)
    k = f_target.size
    roundoff = 1e-9 * target.max()
    assert np.all(np.abs(mean[:k] - target) <= 4 * se[:k] + roundoff)
    # above the band (only the Nyquist bin here) there is no power
    assert np.all(mean[k:] <= roundoff)
    # stronger, exact: every realisation's periodogram over one period is the target
    np.testing.assert_allclose(s[:, :k], np.broadcast_to(target, (N_REAL, k)), rtol=1e-9)


def test_each_realisation_has_exact_target_variance(ensemble: np.ndarray) -> None:
    sigma = _model().std(PRESSURE)
    np.testing.assert_allclose(ensemble.var(axis=1), sigma**2, rtol=1e-12)
    np.testing.assert_allclose(ensemble.mean(axis=1), 0.0, atol=1e-14)


def test_pointwise_mean_and_variance_over_the_ensemble(ensemble: np.ndarray) -> None:
    """At each x_j: E[μ̂] = 0 and Var[μ̂] = σ_μ² over the random phases (4 SE)."""
    sigma2 = _model().std(PRESSURE) ** 2
    mean = ensemble.mean(axis=0)
    se_mean = ensemble.std(axis=0, ddof=1) / np.sqrt(N_REAL)
    assert np.all(np.abs(mean) <= 4 * se_mean)
    sq = ensemble**2
    se_var = sq.std(axis=0, ddof=1) / np.sqrt(N_REAL)
    assert np.all(np.abs(sq.mean(axis=0) - sigma2) <= 4 * se_var)
    # the ensemble mean over all points and realisations (4 SE of the grand mean,
    # realisations independent, points of one realisation averaged first)
    per_real = ensemble[:, : N_GRID // 2].mean(axis=1)
    assert abs(per_real.mean()) <= 4 * per_real.std(ddof=1) / np.sqrt(N_REAL)


def test_windowed_periodogram_matches_its_exact_expectation() -> None:
    """A window of m ≠ n points: random periodogram, mean = target ⊛ Fejér kernel."""
    model = _model()
    f = model.frequencies()
    psd = model.spectrum(f, PRESSURE)
    df = 1.0 / LENGTH
    m = 47  # window length in grid points, not a divisor of the period
    window = np.stack(
        [generate_process(f, psd, DX, m * DX, g) for g in spawn_generators(99, N_REAL)]
    )
    f_w, s_w = one_sided_psd(window, DX)
    # expected periodogram: E|X'_k|² = Σ_i a_i²/4 (|G(f_i − f'_k)|² + |G(f_i + f'_k)|²),
    # G(ν) = Σ_j exp(2πi ν j Δx), a_i = √(2 S_i Δf); S'_k = 2Δx E|X'_k|²/m (k < m/2)
    j = np.arange(m)
    amp2 = 2.0 * psd * df

    def g2(nu: np.ndarray) -> np.ndarray:
        return np.abs(np.exp(2j * np.pi * np.multiply.outer(nu, j) * DX).sum(axis=-1)) ** 2

    diff = np.subtract.outer(f, f_w)
    summ = np.add.outer(f, f_w)
    expected = (2.0 * DX / m) * np.sum(amp2[:, None] / 4.0 * (g2(diff) + g2(summ)), axis=0)
    mean = s_w.mean(axis=0)
    se = s_w.std(axis=0, ddof=1) / np.sqrt(N_REAL)
    assert se.min() > 0.01 * expected.min()  # genuinely random here
    assert np.all(np.abs(mean - expected) <= 4 * se)
    # and the expectation is close to the target where both grids agree in level
    assert expected.mean() == pytest.approx(psd.mean(), rel=0.1)

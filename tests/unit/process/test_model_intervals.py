"""The model's E[μ](p), σ_μ(p) intervals: Monte Carlo and the measurement's sampling uncertainty (issue 29,
item 1; stochfric.process.model_intervals)."""

from __future__ import annotations

import math

import numpy as np
import scipy.stats as sps

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.holdout import MeasuredWindows, measured_windows
from stochfric.process.model_intervals import Z95, model_intervals
from stochfric.surface.summits import summits_of
from synthetic_maps import as_surface, gaussian_heights  # tests/synthetic_maps.py


def _windows(mean_ci: list[list[float]], std: list[float], std_ci: list[list[float]]) -> MeasuredWindows:
    n = len(std)
    return MeasuredWindows(tiles=4, window_size_m=(1e-4, 1e-4), windows=16, mu=np.zeros((16, n)),
                           mu_mean=np.array([0.5 * sum(c) for c in mean_ci]), mu_mean_ci95=np.array(mean_ci),
                           mu_std=np.array(std), mu_std_ci95=np.array(std_ci), neighbour_correlation=np.zeros(n),
                           effective_windows=np.array([16.0, 12.0][:n]))


def test_intervals_combine_monte_carlo_and_sampling_by_hand() -> None:
    mw = _windows([[0.30, 0.40], [0.20, 0.24]], [0.10, 0.05], [[0.06, 0.16], [0.04, 0.055]])
    mi = model_intervals(pressure_pa=[1e6, 2e6], mu_mean=[0.5, 0.3], mu_mean_se=[0.01, 0.0],
                         mu_std=[0.2, 0.1], mu_std_se=[0.0, 0.01], measured=mw)
    h0 = math.sqrt(0.05**2 + (Z95 * 0.01) ** 2)
    np.testing.assert_allclose(mi.mu_mean_ci95[0], [0.5 - h0, 0.5 + h0], rtol=1e-12)
    np.testing.assert_allclose(mi.mu_mean_ci95[1], [0.28, 0.32], rtol=1e-12)  # no MC error: sampling alone
    np.testing.assert_allclose(mi.mu_std_ci95[0], [0.2 * (1 - 0.4), 0.2 * (1 + 0.6)], rtol=1e-12)
    r_mc = Z95 * 0.01 / 0.1
    expected = [0.1 * (1 - math.hypot(0.2, r_mc)), 0.1 * (1 + math.hypot(0.1, r_mc))]
    expected = [0.1 * (1 - math.hypot(0.2, r_mc)), 0.1 * (1 + math.hypot(0.1, r_mc))]
    np.testing.assert_allclose(mi.mu_std_ci95[1], expected, rtol=1e-12)
    assert mi.includes_sampling and mi.effective_windows == 12.0
    np.testing.assert_allclose(mi.sampling_share()[1], 1.0)
    assert mi.to_dict()["includes_sampling"] is True


def test_without_measured_windows_the_interval_is_monte_carlo_only() -> None:
    mi = model_intervals(pressure_pa=[1e6], mu_mean=[0.5], mu_mean_se=[0.02], mu_std=[0.1], mu_std_se=[0.08],
                         measured=None)
    np.testing.assert_allclose(mi.mu_mean_ci95[0], [0.5 - Z95 * 0.02, 0.5 + Z95 * 0.02])
    assert mi.mu_std_ci95[0][0] == 0.0  # clipped: an sd is not negative
    assert not mi.includes_sampling and mi.to_dict()["sampling_share"] == [None]


def test_correlated_windows_widen_the_measured_interval() -> None:
    """The jackknife half-width is scaled by sqrt(J/n_eff) with the t quantile at n_eff - 1 (holdout.py)."""
    s = as_surface(gaussian_heights((320, 320), 1.5, 2))
    u = default_approach_m(summits_of(s), num=4)
    mw = measured_windows([s], get_material("brake-pad"), u, rule="thesis")
    assert mw is not None
    j, n_eff = mw.windows, np.asarray(mw.effective_windows)
    mu = np.asarray(mw.mu)
    loo = np.stack([np.nanmean(np.delete(mu, i, axis=0), axis=0) for i in range(j)])
    se = np.sqrt((j - 1) / j * np.sum((loo - loo.mean(axis=0)) ** 2, axis=0))
    half = 0.5 * (mw.mu_mean_ci95[:, 1] - mw.mu_mean_ci95[:, 0])
    expected = sps.t.ppf(0.975, np.maximum(n_eff - 1, 1)) * se * np.sqrt(j / n_eff)
    np.testing.assert_allclose(half, expected, rtol=1e-10)
    assert np.all(half >= sps.t.ppf(0.975, j - 1) * se * (1 - 1e-12))

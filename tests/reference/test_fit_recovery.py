"""Model-function fit f(p) = a p^b + c (3.21): known parameters recovered within their errors."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION, fit_mask, fit_model_function

TRUE = {"brake E[mu] (Table 3.3)": (5.8574, -0.4478, 0.2603), "brake sigma (Table 3.3)": (1.6063, -0.4163, 0.0663)}


@pytest.mark.parametrize("name", sorted(TRUE))
def test_exact_data_are_reproduced(name: str) -> None:
    a, b, c = TRUE[name]
    p = np.geomspace(3e4, 1.25e6, 10)
    fit = fit_model_function(p, a * p**b + c)
    assert (fit.a, fit.b, fit.c) == pytest.approx((a, b, c), rel=1e-5)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_noisy_data_recovered_within_three_standard_errors(seed: int) -> None:
    a, b, c = TRUE["brake E[mu] (Table 3.3)"]
    p = np.geomspace(5e3, 2e6, 12)
    sigma = 0.004 * np.ones_like(p)
    y = a * p**b + c + sigma * np.random.default_rng(seed).standard_normal(p.size)
    fit = fit_model_function(p, y, sigma)
    for est, se, true in ((fit.a, fit.a_se, a), (fit.b, fit.b_se, b), (fit.c, fit.c_se, c)):
        assert np.isfinite(se) and se > 0
        assert abs(est - true) < 3.0 * se, (est, se, true)
    assert fit.model_function()(1e5) == pytest.approx(float(fit(np.array([1e5]))[0]))


def test_standard_errors_are_calibrated_over_many_data_sets() -> None:
    a, b, c = 1.6063, -0.4163, 0.0663
    p = np.geomspace(5e3, 2e6, 12)
    sigma = 0.002 * np.ones_like(p)
    rng = np.random.default_rng(7)
    z = []
    for _ in range(200):
        fit = fit_model_function(p, a * p**b + c + sigma * rng.standard_normal(p.size), sigma)
        z.append((fit.c - c) / fit.c_se)
    # pulls: mean 0, standard deviation 1 (within the sampling error of 200 fits, ~0.05; nonlinearity)
    assert abs(np.mean(z)) < 0.3
    assert 0.75 < np.std(z) < 1.3


def test_outlier_rule_and_minimum_points() -> None:
    # fractions around the default limit (DEFAULT_MAX_AREA_FRACTION = 0.1, the end of the GW/BEM
    # plateau at equal load): the two points beyond it are excluded
    frac = np.array([1e-3, 1e-2, 5e-2, 8e-2, 0.1, 0.14, 0.3])
    p = np.arange(1.0, 8.0) * 1e5
    assert DEFAULT_MAX_AREA_FRACTION == pytest.approx(0.1)
    mask, note = fit_mask(frac, p)
    np.testing.assert_array_equal(mask, [True] * 5 + [False] * 2)
    assert note == ""
    mask, note = fit_mask(frac, p, max_area_fraction=1e-2)
    np.testing.assert_array_equal(mask, [True] * 4 + [False] * 3)
    assert "lowest pressures" in note
    y = 2.0 * p**-0.5 + 0.1
    y[5:] += 1.0  # high-pressure outliers
    fit = fit_model_function(p, y, mask=fit_mask(frac, p)[0])
    assert fit.b == pytest.approx(-0.5, rel=1e-4)
    assert fit.to_dict()["n_excluded"] == 2
    with pytest.raises(ValueError, match="at least 4"):
        fit_model_function(p[:3], y[:3])

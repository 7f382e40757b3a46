"""D_max(α) and the binomial intervals it is read from (issue 19): reference values and closed forms."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.stats import beta, norm

from stochfric.studies.stats import clopper_pearson, risk_limit, runs_to_resolve, wilson

GRID = np.round(np.linspace(0.05, 0.25, 41), 6)


@pytest.mark.parametrize("conf", [0.9, 0.95, 0.99])
@pytest.mark.parametrize(("k", "n"), [(0, 10), (1, 10), (5, 10), (10, 10), (3, 300), (0, 1), (1, 1)])
def test_clopper_pearson_is_the_beta_quantiles(k: int, n: int, conf: float) -> None:
    a = 1 - conf
    lo, hi = clopper_pearson(k, n, conf)
    want_lo = 0.0 if k == 0 else beta.ppf(a / 2, k, n - k + 1)
    want_hi = 1.0 if k == n else beta.ppf(1 - a / 2, k + 1, n - k)
    assert float(lo) == pytest.approx(want_lo, rel=1e-12, abs=1e-15)
    assert float(hi) == pytest.approx(want_hi, rel=1e-12, abs=1e-15)
    # closed forms at the ends: 0 of n → upper 1 − (a/2)^{1/n}; n of n → lower (a/2)^{1/n}
    if k == 0:
        assert float(hi) == pytest.approx(1 - (a / 2) ** (1 / n), rel=1e-10)
    if k == n:
        assert float(lo) == pytest.approx((a / 2) ** (1 / n), rel=1e-10)


@pytest.mark.parametrize(("k", "n"), [(0, 10), (2, 10), (7, 20), (50, 100), (100, 100)])
def test_wilson_is_the_score_formula(k: int, n: int) -> None:
    z = norm.ppf(0.975)
    p = k / n
    centre = (p + z * z / (2 * n)) / (1 + z * z / n)
    half = z / (1 + z * z / n) * math.sqrt(p * (1 - p) / n + z * z / (4 * n * n))
    lo, hi = wilson(k, n, 0.95)
    assert float(lo) == pytest.approx(max(0.0, centre - half), abs=1e-14)
    assert float(hi) == pytest.approx(min(1.0, centre + half), abs=1e-14)
    if k == 0:  # closed form: upper = z²/(n + z²)
        assert float(hi) == pytest.approx(z * z / (n + z * z), rel=1e-12)
    if 0 < k < n:  # Clopper–Pearson is the wider (conservative) one away from the ends
        clo, chi = clopper_pearson(k, n, 0.95)
        assert float(clo) <= float(lo) + 1e-12 and float(chi) >= float(hi) - 1e-12


def test_runs_to_resolve_is_the_zero_count_boundary() -> None:
    for a in (0.1, 0.05, 0.01):
        n = runs_to_resolve(a)
        assert float(clopper_pearson(0, n, 0.95)[1]) < a <= float(clopper_pearson(0, n - 1, 0.95)[1])
    assert (runs_to_resolve(0.1), runs_to_resolve(0.01)) == (36, 368)


def _k(p: list[float], n: int) -> np.ndarray:
    return np.round(np.asarray(p) * n)


def test_risk_limit_reads_the_bands() -> None:
    n = 100
    p = [1.0] * 20 + [0.6, 0.3, 0.15, 0.08, 0.02, 0.0, 0.01] + [0.0] * 14
    k = _k(p, n)
    lo, hi = clopper_pearson(k, n)
    r = risk_limit(GRID, k, n, 0.1)
    assert r.value == GRID[22]  # the last D with k/n ≥ 0.1
    assert r.low == GRID[np.nonzero(lo >= 0.1)[0].max()]
    assert r.high == GRID[np.nonzero(hi >= 0.1)[0].max()]
    assert r.low <= r.value <= r.high and not r.high_open and r.resolved
    # 1 %: 100 runs cannot exclude P ≥ 1 % at a zero count (upper bound 3.6 %): the upper end is open
    r1 = risk_limit(GRID, k, n, 0.01)
    assert r1.high == GRID[-1] and r1.high_open and not r1.resolved
    assert r1.value == GRID[26] and r1.low <= r1.value


def test_risk_limit_edges() -> None:
    n = 50
    none = risk_limit(GRID, np.zeros(GRID.size), n, 0.1)  # resolved, and nothing at risk anywhere
    assert math.isnan(none.value) and math.isnan(none.low) and math.isnan(none.high) and not none.high_open
    every = risk_limit(GRID, np.full(GRID.size, n), n, 0.1)  # sticks at the grid end: beyond the grid
    assert every.value == every.low == every.high == GRID[-1] and every.high_open and every.resolved
    few = risk_limit(GRID, np.zeros(GRID.size), 10, 0.1)  # 0 of 10 cannot exclude 10 %
    assert math.isnan(few.value) and math.isnan(few.low) and few.high == GRID[-1] and few.high_open
    assert not few.resolved and few.to_dict()["value"] is None
    with pytest.raises(ValueError, match="risk level"):
        risk_limit(GRID, np.zeros(GRID.size), 10, 1.0)

"""Coverage of the D_max(α) interval on known P(stick-slip | D) curves (issue 19).

Synthetic Bernoulli data with fixed seeds (deterministic, not flaky): per replicate k(D) of n runs stick,
either independently per D or with one uniform per run shared by all D (the damping study's common
random numbers: run r sticks at D iff U_r < P(D)).  The interval [low, high] of
:func:`~stochfric.studies.stats.risk_limit` must contain the true D_max(α) (the largest grid D with
P ≥ α) at least at the nominal rate minus 3 standard errors of the Monte Carlo estimate of the rate.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.studies.stats import risk_limit, runs_to_resolve

GRID = np.round(np.linspace(0.05, 0.25, 41), 6)
M = 400  # replicates per case


def _draw(rng: np.random.Generator, p: np.ndarray, n: int, common: bool) -> np.ndarray:
    if common:
        u = rng.random(n)
        return (u[:, None] < p[None, :]).sum(axis=0)
    return rng.binomial(n, p)


def _coverage(p: np.ndarray, n: int, a: float, common: bool, seed: int) -> tuple[float, float, float]:
    """(joint, low end, high end) coverage of the true D_max(α) over M replicates."""
    true = float(GRID[p >= a].max())
    rng = np.random.default_rng(seed)
    both = lo_ok = hi_ok = 0
    for _ in range(M):
        r = risk_limit(GRID, _draw(rng, p, n, common), n, a)
        lo = not math.isfinite(r.low) or r.low <= true + 1e-12
        hi = r.high_open or (math.isfinite(r.high) and r.high >= true - 1e-12)
        both, lo_ok, hi_ok = both + (lo and hi), lo_ok + lo, hi_ok + hi
    return both / M, lo_ok / M, hi_ok / M


def _floor(nominal: float) -> float:
    return nominal - 3 * math.sqrt(nominal * (1 - nominal) / M)


@pytest.mark.parametrize("common", [False, True], ids=["independent", "common-random-numbers"])
@pytest.mark.parametrize(("n", "a"), [(30, 0.1), (100, 0.1), (100, 0.01), (400, 0.01)])
def test_coverage_on_a_logistic_curve(n: int, a: float, common: bool) -> None:
    p = 1.0 / (1.0 + np.exp((GRID - 0.16) / 0.012))
    both, _, _ = _coverage(p, n, a, common, seed=n + int(1000 * a) + common)
    assert both >= _floor(0.95), both  # each end ≥ 97.5 %, jointly ≥ 95 %


@pytest.mark.parametrize("common", [False, True], ids=["independent", "common-random-numbers"])
@pytest.mark.parametrize(("n", "a"), [(100, 0.1), (1000, 0.1), (1000, 0.01)])
def test_upper_end_at_the_worst_case(n: int, a: float, common: bool) -> None:
    """P(D*) = α exactly and P = α/2 above: only the upper bound at D* decides the upper end (≥ 97.5 %)."""
    p = np.where(GRID < 0.15, 0.5, 0.0)
    p[GRID == 0.15] = a
    p[(GRID > 0.15) & (GRID <= 0.2)] = a / 2
    _, _, hi = _coverage(p, n, a, common, seed=7 + n + common)
    assert hi >= _floor(0.975), hi


def test_unresolvable_risk_level_is_always_open() -> None:
    """Below the runs α needs, the upper end is the grid end in every replicate (never a false limit)."""
    p = 1.0 / (1.0 + np.exp((GRID - 0.16) / 0.012))
    rng = np.random.default_rng(3)
    for n, a in ((10, 0.1), (30, 0.1), (300, 0.01)):
        assert n < runs_to_resolve(a)
        for _ in range(50):
            r = risk_limit(GRID, _draw(rng, p, n, True), n, a)
            assert r.high_open and not r.resolved and r.high == GRID[-1]


def test_point_estimate_converges() -> None:
    """With many runs the point estimate is the true D_max(α) and the interval closes around it."""
    p = 1.0 / (1.0 + np.exp((GRID - 0.16) / 0.012))
    rng = np.random.default_rng(4)
    for a in (0.1, 0.01):
        true = float(GRID[p >= a].max())
        r = risk_limit(GRID, _draw(rng, p, 20000, False), 20000, a)
        assert r.value == true and r.low >= true - 0.0051 and r.high <= true + 0.0051

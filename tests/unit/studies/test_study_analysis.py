"""Unit tests of the study analysis functions (pure functions, closed forms)."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from stochfric.oscillator.parameters import OscillatorParameters
from stochfric.studies.damping import d_max_deterministic, d_max_stochastic
from stochfric.studies.errors import StudyError
from stochfric.studies.grids import parse_grid, window_mask
from stochfric.studies.lyapunov import RESOLVED_CONTRACTION, lyapunov_exponent, lyapunov_rate, resolved_prefix
from stochfric.studies.stats import clopper_pearson, sample_summary, zero_count_upper_bound
from stochfric.studies.tasks import cell_stream_key


def test_parse_grid_forms() -> None:
    assert parse_grid("0.05:0.25:5") == (0.05, 0.1, 0.15, 0.2, 0.25)
    assert parse_grid("1, 2,3") == (1.0, 2.0, 3.0)
    assert parse_grid(5600) == (5600.0,)
    assert parse_grid([1, 2]) == (1.0, 2.0)
    assert len(parse_grid("0.05:0.25:41")) == 41
    for bad in ("1:2", "a:b:3", "1:2:0", "x,y", "", "nan"):
        with pytest.raises(StudyError):
            parse_grid(bad)


def test_cell_stream_key_depends_on_the_cells_values_only() -> None:
    p = OscillatorParameters(gamma0=0.5, n=0.01, damping_ratio=0.1, q=1e-4, eta=1.2, omega0=700.0)
    k = cell_stream_key("contact", p)
    assert k == cell_stream_key("contact", OscillatorParameters(**p.__dict__))  # a fresh, equal object
    assert all(0 <= w < 2**32 for w in k)
    others = {cell_stream_key("white", p), cell_stream_key("contact", replace(p, eta=1.25)),
              cell_stream_key("contact", replace(p, damping_ratio=0.1 + 1e-12)),
              cell_stream_key("contact", replace(p, n=0.02))}
    assert k not in others and len(others) == 4
    # common random numbers over D: D is left out of the key
    assert cell_stream_key("contact", p, ("damping_ratio",)) == cell_stream_key(
        "contact", replace(p, damping_ratio=0.2), ("damping_ratio",))


def test_window_mask() -> None:
    t = np.array([[10.0, 25.0, 25.5, np.nan]])
    assert window_mask(t, 50.0, 0.5).tolist() == [[False, False, True, False]]
    with pytest.raises(StudyError):
        window_mask(t, 50.0, 1.0)


def test_d_max_deterministic() -> None:
    d = np.array([0.1, 0.2, 0.3, 0.4])
    assert d_max_deterministic(d, [True, True, False, False]) == 0.2
    assert math.isnan(d_max_deterministic(d, [False] * 4))


def test_d_max_stochastic_interval_closed_form() -> None:
    d = np.round(np.arange(0.1, 1.0, 0.05), 10)
    k = np.zeros(d.size)
    k[:5] = 3
    k[6] = 1  # non-monotone: the largest D with k > 0 counts
    point, lo, hi = d_max_stochastic(d, k, 10, confidence=0.95, p_detect=0.1)
    assert point == lo == d[6]
    # pooled bound after m zero-count points: 1 - 0.05^(1/(10 m)) < 0.1 first for m = 3
    m = next(m for m in range(1, 20) if 1 - 0.05 ** (1 / (10 * m)) < 0.1)
    assert m == 3
    assert hi == d[6 + m]
    # grid ends before the bound is reached
    assert math.isnan(d_max_stochastic(d[:8], k[:8], 10)[2])
    assert all(math.isnan(v) for v in d_max_stochastic(d, np.zeros(d.size), 10))


def test_clopper_pearson_closed_forms() -> None:
    n = 10
    lo, hi = clopper_pearson([0, n, 4], [n, n, n], 0.95)
    assert lo[0] == 0.0 and hi[1] == 1.0
    assert hi[0] == pytest.approx(1 - 0.025 ** (1 / n), rel=1e-10)
    assert lo[1] == pytest.approx(0.025 ** (1 / n), rel=1e-10)
    assert lo[2] < 0.4 < hi[2]
    assert zero_count_upper_bound(10, 0.95) == pytest.approx(1 - 0.05 ** 0.1)


def test_lyapunov_formula_443() -> None:
    a, k = 0.3, 12
    w = 1e-6 * np.exp(a * np.arange(k))
    lam, status, kk = lyapunov_exponent(w)
    assert status == "ok" and kk == k
    # (1/K) Σ ln(w(i)/w(1)) = a (K − 1)/2 for exponential growth
    assert lam == pytest.approx(a * (k - 1) / 2, rel=1e-12)
    assert lyapunov_exponent(1e-6 * np.exp(-a * np.arange(k)))[0] < 0
    lam, status, _ = lyapunov_exponent([1e-6, 2e-6, 0.0, 0.0])
    assert status == "merged" and math.isnan(lam)
    assert lyapunov_exponent([1e-6, np.nan])[1] == "too-few-transitions"
    assert lyapunov_exponent([0.0, 0.0, 0.0])[1] == "merged"


def test_a_contracting_pair_is_fitted_above_the_resolution_floor_only() -> None:
    """A pair contracting e^−2 per transition reaches the rounding floor (w ≈ 1e-17, then scatter and
    exact zeros, as the brake 4000 N, q = 5e-4, η = 1.4 pair does with DOP853): the slope is fitted
    before w falls 10⁶-fold below its running maximum, so it is −2 whatever the floor points are (the
    integrator's accuracy and τ_end decide how many there are); before, they pulled it to ≈ −0.9."""
    rng = np.random.default_rng(3)
    clean = 1e-6 * np.exp(-2.0 * np.arange(9))  # down to 1.1e-13 < 1e-6 · 1e-6 at i = 7
    for floor in (np.zeros(20), 1e-17 * rng.random(20), 1e-16 * rng.random(5)):
        w = np.concatenate([clean, floor])
        rate, se, status, k = lyapunov_rate(w)
        assert status == "ok" and k == resolved_prefix(w) == 7
        assert rate == pytest.approx(-2.0, abs=1e-9) and se < 1e-9
    # δ-independent: scaling w scales the floor with it
    assert resolved_prefix(1e-3 * np.concatenate([clean, np.zeros(3)])) == 7
    assert clean[7] < RESOLVED_CONTRACTION * clean[0] < clean[6]
    # contracting to the floor within fewer than 5 transitions: merged, no value
    assert lyapunov_rate([1e-6, 1e-9, 1e-13, 0.0, 0.0, 0.0])[2] == "merged"
    # a growing or level pair is fitted over all its transitions
    assert resolved_prefix(1e-6 * np.exp(0.3 * np.arange(12))) == 12


def test_sample_summary_closed_forms() -> None:
    x = [np.array([1.0, 2.0]), np.array([3.0, 4.0]), np.array([np.nan])]
    s = sample_summary(x, n_boot=50)
    assert s.n == 4 and s.n_runs == 2
    assert s.mean == 2.5
    sd = float(np.std([1, 2, 3, 4], ddof=1))
    assert s.std == pytest.approx(sd)
    assert s.vark == pytest.approx(sd / 2.5)
    assert s.se_mean_iid == pytest.approx(sd / 2)
    assert s.se_std_iid == pytest.approx(sd / math.sqrt(6))
    empty = sample_summary([np.array([np.nan])])
    assert empty.n == 0 and math.isnan(empty.mean)
    assert empty.to_dict()["mean"] is None

"""Seeded Monte Carlo checks of the study estimators against closed forms.

Tolerances come from the estimators' own standard errors (ARCHITECTURE habit 11).
"""

from __future__ import annotations

import math

import numpy as np

from stochfric.studies.stats import clopper_pearson, sample_summary


def test_clopper_pearson_coverage() -> None:
    rng = np.random.default_rng(20130501)
    n, trials = 10, 4000
    for p in (0.05, 0.3, 0.7):
        k = rng.binomial(n, p, size=trials)
        lo, hi = clopper_pearson(k, np.full(trials, n), 0.95)
        cover = np.mean((lo <= p) & (p <= hi))
        # exact intervals are conservative: coverage >= 95 % up to Monte Carlo error (4 SE)
        assert cover >= 0.95 - 4 * math.sqrt(0.95 * 0.05 / trials), (p, cover)


def test_standard_errors_match_their_sampling_distribution() -> None:
    rng = np.random.default_rng(7)
    mu, sigma, n_runs, per_run, reps = 2.0e-3, 3.0e-4, 10, 3, 600
    means, stds, varks, se_m, se_s, se_v = [], [], [], [], [], []
    for _ in range(reps):
        runs = [rng.normal(mu, sigma, per_run) for _ in range(n_runs)]
        s = sample_summary(runs, n_boot=0)
        means.append(s.mean)
        stds.append(s.std)
        varks.append(s.vark)
        se_m.append(s.se_mean_iid)
        se_s.append(s.se_std_iid)
        se_v.append(s.se_vark_iid)
    # the spread of each estimate over repetitions equals its closed-form SE; the sample SD of
    # `reps` values has a relative SE of ≈ 1/√(2 reps) = 2.9 %, allow 4 of those
    tol = 4 / math.sqrt(2 * reps)
    for est, se in ((means, se_m), (stds, se_s), (varks, se_v)):
        assert abs(np.std(est, ddof=1) / np.mean(se) - 1) < tol


def test_bootstrap_over_runs_agrees_with_closed_form_for_independent_runs() -> None:
    rng = np.random.default_rng(11)
    runs = [rng.normal(1.0, 0.2, 1) for _ in range(400)]
    s = sample_summary(runs, n_boot=800, rng=np.random.default_rng(3))
    # bootstrap SE of an SE estimate: relative error ≈ 1/√(2 · 800) = 2.5 %; allow 4 SE + O(1/n)
    assert abs(s.se_mean_boot / s.se_mean_iid - 1) < 0.12
    assert abs(s.se_std_boot / s.se_std_iid - 1) < 0.2

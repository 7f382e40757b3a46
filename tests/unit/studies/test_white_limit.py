"""The white-limit study (issue 19): fit, statistics, configuration, a small run."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.oscillator.case import CaseError
from stochfric.studies.white_limit import (
    WhiteLimitConfig,
    ensemble_statistics,
    power_law_fit,
    white_limit_study,
)


def test_power_law_fit_recovers_the_exponent_and_its_error() -> None:
    rng = np.random.default_rng(1)
    ell = np.geomspace(1e-6, 1e-3, 7)
    betas = []
    ses = []
    for _ in range(400):
        rel = 0.03
        sigma = 2e-5 * ell**-0.25 * (1 + rel * rng.standard_normal(ell.size))
        fit = power_law_fit(ell, sigma, rel * sigma)
        betas.append(fit.beta)
        ses.append(fit.beta_se)
    betas_a = np.asarray(betas)
    assert betas_a.mean() == pytest.approx(-0.25, abs=0.003)
    # the weighted SE is the scatter of β over repetitions
    assert np.mean(ses) == pytest.approx(betas_a.std(), rel=0.15)
    exact = power_law_fit(ell, 3.0 * ell**0.5, 0.01 * ell**0.5)
    assert exact.beta == pytest.approx(0.5, abs=1e-12) and exact.prefactor == pytest.approx(3.0)
    assert exact.local_slopes is not None and len(exact.local_slopes) == 6
    assert all(s.slope == pytest.approx(0.5) for s in exact.local_slopes)
    assert power_law_fit([1e-3], [1.0], [0.1]).beta is None


def test_ensemble_statistics_pairs_the_runs() -> None:
    rng = np.random.default_rng(2)
    x = rng.standard_normal((200, 5))
    x[:, 4] = np.nan
    c, _fine, diff, se = ensemble_statistics(x, x * 1.01, rng)
    assert c["x_gh_std"] == pytest.approx(float(np.nanstd(x, ddof=1)))
    assert diff == pytest.approx(-0.01 * c["x_gh_std"])
    # the same realisations at both steps: the paired SE is far below the SE of either σ
    assert se < 0.05 * c["x_gh_std_se"]
    assert c["n_events"] == 800
    assert c["x_gh_mean_se"] == pytest.approx(1 / math.sqrt(800), rel=0.2)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"correlation_lengths": (1e-3,)}, "at least two"),
        ({"correlation_lengths": (1e-3, -1e-4)}, "positive"),
        ({"correlation_lengths": (1e-3, 1e-3)}, "twice"),
        ({"correlation_lengths": (1.0, 1e-3)}, "0.1 m"),
        ({"runs": 1}, "runs"),
        ({"path_coordinate": "position"}, "path coordinate"),
        ({"steps_per_cell": 0.5}, "steps per grid cell"),
        ({"refine": 1}, "refine"),
        ({"stick_window": 1.0}, "stick window"),
        ({"level_factor": 0.0}, "level_factor"),
        ({"dt_max": float("nan")}, "dt_max"),
        ({"normal_force": -3.0}, "normal_force "),
    ],
)
def test_config_refuses_bad_settings(kwargs, match) -> None:  # type: ignore[no-untyped-def]
    with pytest.raises(CaseError, match=match):
        WhiteLimitConfig(**kwargs)


def test_a_small_study_runs_and_never_repeats_the_process() -> None:
    cfg = WhiteLimitConfig(preset="brake", normal_force=2720.0, correlation_lengths=(1e-3, 1e-4),
                           runs=24, tau_end=20.0, seed=5, workers=1)
    res = white_limit_study(cfg)
    s = res.summary
    assert [r.correlation_length_m for r in s.table] == [1e-3, 1e-4]
    for row in s.table:
        assert row.fine.dt == pytest.approx(row.coarse.dt / 4)
        assert row.fine.max_path_over_length < 1.0
        assert "process-exhausted" not in row.fine.warnings
        assert row.fine.n_events > 24
        assert row.low_frequency_psd_m == pytest.approx(s.low_frequency_psd_m, rel=1e-9)
    assert s.fit.beta is not None and s.units["correlation_length_m"] == "m"
    assert s.seed == 5 and "numpy" in s.versions
    js = s.to_json()  # the record the files and --json carry
    assert js["table"][0]["fine"]["dt"] == s.table[0].fine.dt and js["config"]["runs"] == 24
    ds = res.dataset()
    assert ds["x_gh_std"].shape == (2, 2) and ds["correlation_length"].attrs["units"] == "m"

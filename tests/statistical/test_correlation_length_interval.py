"""The correlation length's standard error and 95 % interval (issue 19 §4): coverage on records of
known integral correlation length, and the interval in the output of ``friction-process``."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from stochfric.friction_process.spectra import correlation_length_interval, integral_correlation_length


def test_interval_covers_the_known_correlation_length() -> None:
    """Moving sums of L white values (spacing a): ℓ_int = aL/2.  K = 10 records per analysis (the
    default number of long surfaces), 300 analyses: the 95 % interval covers aL/2 in 0.88–0.99 of
    them (binomial sd 0.013 at 0.95) and the SE is the scatter of the mean."""
    rng = np.random.default_rng(5)
    length, a, k, n = 8, 2.5e-6, 10, 4000
    truth = length * a / 2
    hits, means, ses = 0, [], []
    for _ in range(300):
        w = rng.standard_normal((k, n + length - 1))
        mu = np.stack([np.convolve(row, np.ones(length), mode="valid") for row in w])
        mean, se, lo, hi = correlation_length_interval([integral_correlation_length(x, a, length * a) for x in mu])
        hits += lo <= truth <= hi
        means.append(mean)
        ses.append(se)
    assert 0.88 <= hits / 300 <= 0.99
    assert np.mean(means) == pytest.approx(truth, rel=0.01)
    assert np.mean(ses) == pytest.approx(np.std(means), rel=0.2)


def test_interval_edge_cases() -> None:
    m, se, lo, hi = correlation_length_interval([1.0, 2.0, 3.0, math.nan])
    assert m == 2.0 and se == pytest.approx(1 / math.sqrt(3))
    assert hi - m == pytest.approx(4.302653 * se, rel=1e-6)  # t(0.975, 2)
    assert lo < m < hi
    assert math.isnan(correlation_length_interval([1.0])[1]) and correlation_length_interval([1.0])[0] == 1.0
    assert all(math.isnan(v) for v in correlation_length_interval([math.nan]))
    with pytest.raises(ValueError, match="level"):
        correlation_length_interval([1.0, 2.0], level=1.0)


def test_friction_process_prints_and_writes_the_interval(tmp_path) -> None:  # type: ignore[no-untyped-def]
    from stochfric.cli.process import register

    app = typer.Typer()
    register(app)

    @app.command("noop")
    def _noop() -> None:
        pass

    small = ["--realizations", "8", "--long-surfaces", "3", "--length-factor", "4", "--accept-not-credible"]
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", *small, "--seed", "2", "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["correlation_length_surfaces"] == 3
    for ell, se, (lo, hi) in zip(d["correlation_length_m"], d["correlation_length_se_m"],
                                 d["correlation_length_ci95_m"], strict=True):
        assert lo < ell < hi and se > 0
        assert hi - ell == pytest.approx(4.302653 * se, rel=1e-5)  # t(0.975, K − 1 = 2)
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", *small, "--seed", "2"])
    assert res.exit_code == 0, res.output
    assert "ℓ_corr ± SE [µm]" in res.stdout and "95 % interval over 3 long surfaces" in res.stdout

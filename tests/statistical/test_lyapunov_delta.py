"""The Lyapunov study measures something that does not depend on the perturbation δ (issue 10).

For δ = 1e-8 … 1e-4 every reported exponent ``lyapunov`` (per slip→stick transition) must agree
with every other δ's within 4 combined standard errors, or be a lower bound (``diverging``) or NaN
with a reason (``nonlinear``, ``merged``, ``too-few-transitions``).  Brake, N = 4000 N, both forcing
amplitudes, three η, all three models, R = 10, fixed seed.
"""

from __future__ import annotations

import itertools
import math
import warnings

import numpy as np
import pytest

from stochfric.studies.config import LyapunovConfig
from stochfric.studies.lyapunov import STATUS, lyapunov_study

DELTAS = (1e-8, 1e-7, 1e-6, 1e-5, 1e-4)


@pytest.fixture(scope="module")
def summaries() -> dict[float, dict]:
    out = {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for d in DELTAS:
            cfg = LyapunovConfig(normal_forces=(4000.0,), forcing_q=(5e-5, 5e-4), eta=(0.7, 1.2, 2.0), runs=10,
                                 seed=1, perturbation=d)
            out[d] = lyapunov_study(cfg).to_json_dict()
    return out


def _arr(s: dict, key: str, m: str) -> np.ndarray:
    return np.array(s[key][m], dtype=float).ravel()


@pytest.mark.parametrize("model", ["deterministic", "white", "contact"])
def test_rate_is_delta_independent_or_undefined(summaries: dict[float, dict], model: str) -> None:
    for d1, d2 in itertools.combinations(DELTAS, 2):
        r1, r2 = _arr(summaries[d1], "lyapunov", model), _arr(summaries[d2], "lyapunov", model)
        s1, s2 = _arr(summaries[d1], "lyapunov_se", model), _arr(summaries[d2], "lyapunov_se", model)
        ok1 = np.array(summaries[d1]["status"][model]).ravel() == "ok"
        ok2 = np.array(summaries[d2]["status"][model]).ravel() == "ok"
        both = ok1 & ok2  # a diverging cell's value is a lower bound (its linear prefix depends on δ)
        tol = 4 * np.sqrt(s1[both] ** 2 + s2[both] ** 2)
        assert np.all(np.abs(r1[both] - r2[both]) <= tol), (model, d1, d2, r1, r2)
    for d in DELTAS:
        st = np.array(summaries[d]["status"][model]).ravel()
        r = _arr(summaries[d], "lyapunov", model)
        assert set(st) <= set(STATUS)
        np.testing.assert_array_equal(np.isfinite(r), np.isin(st, ("ok", "diverging")))  # undefined has a reason


def test_the_check_is_not_vacuous(summaries: dict[float, dict]) -> None:
    # the deterministic model is linear at small δ in most cells, so most rates are defined …
    assert np.sum(np.isfinite(_arr(summaries[1e-8], "lyapunov", "deterministic"))) >= 5
    assert np.sum(np.isfinite(_arr(summaries[1e-8], "lyapunov", "white"))) >= 4
    # … and the printed formula itself *does* depend on δ where the twin check fails (contact, q = 5e-4)
    sep = np.array([_arr(summaries[d], "separation_index_443", "contact")[3:] for d in DELTAS])
    st = np.array([np.array(summaries[d]["separation_index_status"]["contact"]).ravel()[3:] for d in DELTAS])
    assert np.all(st != "ok")  # … and it is flagged
    finite = sep[np.isfinite(sep)]
    assert finite.size >= 5 and np.ptp(finite) > 1.0
    assert not math.isnan(float(np.nanmax(sep)))

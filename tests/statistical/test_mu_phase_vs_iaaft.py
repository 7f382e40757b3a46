"""Phase vs IAAFT surrogates on a non-Gaussian measured surface (frt-1: skewness 1.5, kurtosis 11).

Uses ``../shared/data/topographies/frt-1.frt`` (undefined points filled); skipped if absent.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from scipy import stats

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.ensemble import ensemble_contact
from stochfric.process.estimators import mean_and_std_errors
from stochfric.surface.io import read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of
from stochfric.surface.synthesis import iaaft_heights, random_phase_heights

FRT = Path(__file__).resolve().parents[3] / "shared" / "data" / "topographies" / "frt-1.frt"


@pytest.fixture(scope="module")
def frt():  # type: ignore[no-untyped-def]
    if not FRT.exists():
        pytest.skip(f"measured surface {FRT} not available")
    # a part outline (refused by default): the test is about the height distribution, not about contact
    _fine, coarse = prepare(read_surface(FRT, fill_undefined=True),
                            Preparation(detrend="plane", step=4, rough_check=False, max_undefined=0.5))
    return coarse


def test_iaaft_keeps_the_non_gaussian_heights_phase_does_not(frt) -> None:  # type: ignore[no-untyped-def]
    z = frt.heights_m
    assert stats.skew(z.ravel()) > 1.0
    ph = random_phase_heights(z, 1)
    ia = iaaft_heights(z, 1, tol=1e-3)
    assert stats.ks_2samp(ia.heights.ravel(), z.ravel()).statistic == 0.0
    assert stats.ks_2samp(ph.ravel(), z.ravel()).pvalue < 1e-6
    assert abs(stats.skew(ph.ravel())) < 0.5
    assert ia.amplitude_error < 0.05


def test_mu_statistics_phase_vs_iaaft(frt) -> None:  # type: ignore[no-untyped-def]
    mat = get_material("brake-pad")
    u = default_approach_m(summits_of(frt), num=6, rule="sigma")
    res = {}
    for method in ("phase", "iaaft"):
        e = ensemble_contact(frt, mat, u, realizations=8, method=method, seed=4, iaaft_tol=1e-2)
        res[method] = (*mean_and_std_errors(e.mu), e.area_fraction.mean(axis=0))
    m_ph, _, se_ph, _, _ = res["phase"]
    m_ia, _, se_ia, _, _ = res["iaaft"]
    z = (m_ia - m_ph) / np.sqrt(se_ph**2 + se_ia**2)
    # the heavy upper tail of frt-1 (skewness 1.5) changes the contact: μ differs by many SE
    assert np.max(np.abs(z)) > 4.0, z

"""The spectrum level E[S] = S(f → 0) and σ_ζ belong to the surface, not to the window shift.

Windows shifted by a_y ≪ ℓ are a moving average: above 1/ℓ the μ(y) spectrum is the window's,
and the old band-mean level scaled with a_y (E[S] ≈ 2 a_y σ_μ²: 70× between a_y = 1.75 and 130 µm).
Here the same long surfaces (same seed) are analysed with a_y = 3 and 30 grid points (10×):
E[S], the σ_ζ of the ``spectral_level`` rule, σ_μ and ℓ_corr must agree within their standard
errors (from the scatter between the independent long surfaces) at every approach.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.statistics import AnalysisConfig, StatisticalContactAnalysis, analyse
from stochfric.surface.io import default_surface_path, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of


def _run(shift: int) -> StatisticalContactAnalysis:
    fine, _ = prepare(read_surface(default_surface_path()))
    u = default_approach_m(summits_of(fine), num=6)
    cfg = AnalysisConfig(realizations=4, long_surfaces=8, length_factor=10, window_shift_points=shift, seed=11,
                         check_realizations=20)  # fmt: skip
    return analyse(fine, get_material("brake-pad"), u, cfg)


@pytest.fixture(scope="module")
def pair() -> tuple[StatisticalContactAnalysis, StatisticalContactAnalysis]:
    return _run(3), _run(30)


def test_psd_level_does_not_move_with_a_tenfold_shift(pair) -> None:  # type: ignore[no-untyped-def]
    fine, coarse = pair
    se = np.sqrt(fine.psd_level_se**2 + coarse.psd_level_se**2)
    z = (fine.psd_level - coarse.psd_level) / se
    assert np.all(np.abs(z) < 3.0), z
    # the old band mean differed by the shift ratio; the level at f -> 0 differs by a few per cent
    assert np.all(np.abs(fine.psd_level / coarse.psd_level - 1.0) < 0.25)


def test_sigma_zeta_spectral_level_does_not_move(pair) -> None:  # type: ignore[no-untyped-def]
    fine, coarse = pair
    ratios = []
    for k in range(2):  # the two lowest pressures lie inside both fits' ranges
        p = float(fine.pressure_pa[k])
        a = replace(fine.model, sigma_zeta_rule="spectral_level").sigma_zeta(p)
        b = replace(coarse.model, sigma_zeta_rule="spectral_level").sigma_zeta(p)
        ratios.append(a / b)
        # σ_ζ = S(0)/2 with the model's S scaled to σ_μ(p)²: compare with the measured level's SE
        rel_se = float(np.hypot(fine.psd_level_se[k] / fine.psd_level[k], coarse.psd_level_se[k] / coarse.psd_level[k]))
        assert abs(a / b - 1.0) < 3.0 * rel_se + 0.05, (a, b, rel_se)
    assert np.all(np.isfinite(ratios))


def test_sigma_mu_and_correlation_length_do_not_move(pair) -> None:  # type: ignore[no-untyped-def]
    fine, coarse = pair
    se = np.sqrt(fine.mu_std_se**2 + coarse.mu_std_se**2)
    assert np.all(np.abs(fine.mu_std - coarse.mu_std) < 3.0 * se)

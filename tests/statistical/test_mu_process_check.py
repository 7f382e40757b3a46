"""The generated process against its target (Fig. 3.23 analogue), fixed seeds, SE tolerances."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.checks import check_generated_process
from stochfric.process.statistics import AnalysisConfig, analyse
from stochfric.surface.io import default_surface_path, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of


@pytest.fixture(scope="module")
def analysis():  # type: ignore[no-untyped-def]
    fine, _ = prepare(read_surface(default_surface_path()))
    u = default_approach_m(summits_of(fine), num=8)
    cfg = AnalysisConfig(realizations=30, long_surfaces=4, length_factor=6, seed=3,
                         check_realizations=300)
    return analyse(fine, get_material("brake-pad"), u, cfg, name="al3d-1")


def test_generated_std_matches_target_within_standard_errors(analysis) -> None:  # type: ignore[no-untyped-def]
    chk = analysis.process_check
    assert chk.max_std_z() < 4.0
    # grid standard deviation is exact for a periodic grid
    np.testing.assert_allclose(chk.std_grid_mean, chk.target_std, rtol=1e-10)
    # and the target is σ_μ(p) of the fit (variance rule "sigma_mu")
    for p, t in zip(chk.pressure_pa, chk.target_std, strict=True):
        assert t == pytest.approx(analysis.model.std(p), rel=1e-10)


def test_generated_spectrum_matches_target(analysis) -> None:  # type: ignore[no-untyped-def]
    chk = analysis.process_check
    target = np.asarray(chk.target_psd)
    gen = np.asarray(chk.generated_psd)
    inside = target > 0
    np.testing.assert_allclose(gen[inside], target[inside], rtol=1e-8)


def test_tabulated_variance_reproduces_the_measured_path_spectrum(analysis) -> None:  # type: ignore[no-untyped-def]
    from dataclasses import replace

    m = replace(analysis.model, variance_rule="tabulated")
    k = 3
    p = analysis.pressure_pa[k]
    chk = check_generated_process(m, [p], realizations=400, seed=9)
    # pointwise standard deviation over realisations vs the measured path variance (bins below Nyquist)
    assert abs(chk.std_pointwise[0] - chk.target_std[0]) < 4.0 * chk.std_pointwise_se[0]
    measured = analysis.psd[k]
    f = analysis.frequencies
    band = f < 0.5 / analysis.path.window_shift_m * (1 - 1e-9)
    np.testing.assert_allclose(m.spectrum(f[band], p), measured[band], rtol=1e-10)


def test_statistics_are_sane(analysis) -> None:  # type: ignore[no-untyped-def]
    a = analysis
    assert np.all(np.diff(a.pressure_pa) > 0)
    assert np.all(a.mu_std > 0) and np.all(a.mu_mean > 0)
    fit = a.fits["mu_mean"]
    assert fit.a * fit.b < 0  # μ falls with pressure (Hertz → GW, thesis §3.2.4): d(a p^b)/dp = a b p^(b-1) < 0
    assert a.contact_fraction_fit["r_squared"] > 0.95  # A_c ∝ p (Fig. 3.17)
    # correlation length: shorter than the window but several window shifts (overlapping windows)
    cl = a.correlation_length_m[np.isfinite(a.correlation_length_m)]
    assert cl.size > 0 and np.all(cl < 2.0 * a.path.window_length_m) and np.all(cl > 2 * a.path.window_shift_m)
    assert a.ergodicity.threshold > 2.5
    ds = a.to_dataset()
    assert ds["path_mu"].shape == (4, a.path.samples.mu.shape[1], 8)
    assert ds["psd"].attrs["units"] == "m"

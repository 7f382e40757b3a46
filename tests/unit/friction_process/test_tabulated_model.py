"""TabulatedProcessModel (spectra at the analysed pressures) and the σ_ζ rules."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from stochfric.friction_process.model import (
    BandLimitedProcessModel,
    ModelFunction,
    TabulatedProcessModel,
    load_process_model,
    low_frequency_level,
    process_model_from_dict,
)
from stochfric.friction_process.spectral import one_sided_psd
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions
from stochfric.oscillator.parameters import PhysicalParameters
from stochfric.oscillator.presets import brake

DX = 1e-3
LENGTH = 0.04  # 40 points, band k/ℓ for k = 1..19
F = np.arange(1, 20) / LENGTH


def _model(**changes: object) -> TabulatedProcessModel:
    table = np.stack([np.full(F.size, 1e-5), 4e-5 * (1.0 - 0.5 * F / F[-1]), np.full(F.size, 1.6e-4)])
    kwargs: dict[str, object] = dict(
        name="tab",
        mu_mean=ModelFunction(a=2.0, b=-0.3, c=0.2),
        mu_std=ModelFunction(a=0.4, b=-0.17, c=0.0),
        dx=DX,
        length=LENGTH,
        pressures_pa=(1e4, 1e5, 1e6),
        table_frequencies=tuple(F),
        table_psd=tuple(tuple(r) for r in table),
    )
    kwargs.update(changes)
    return TabulatedProcessModel(**kwargs)  # type: ignore[arg-type]


def test_nearest_rule_picks_the_nearest_pressure_in_log_p() -> None:
    m = _model(variance_rule="tabulated")
    np.testing.assert_allclose(m.table_spectrum(2.9e4), m.table_psd[0])
    np.testing.assert_allclose(m.table_spectrum(3.3e4), m.table_psd[1])
    np.testing.assert_allclose(m.table_spectrum(1e9), m.table_psd[2])


def test_interpolate_rule_log_log_and_clamped() -> None:
    m = _model(pressure_rule="interpolate", variance_rule="tabulated")
    np.testing.assert_allclose(m.table_spectrum(1e5), m.table_psd[1], rtol=1e-12)
    # halfway in log p between flat 4e-5·(…) and 1.6e-4: geometric mean
    mid = np.sqrt(np.asarray(m.table_psd[1]) * np.asarray(m.table_psd[2]))
    np.testing.assert_allclose(m.table_spectrum(np.sqrt(1e5 * 1e6)), mid, rtol=1e-12)
    np.testing.assert_allclose(m.table_spectrum(10.0), m.table_psd[0], rtol=1e-12)
    np.testing.assert_allclose(m.table_spectrum(1e8), m.table_psd[2], rtol=1e-12)
    # continuous in p, unlike "nearest"
    near = _model(variance_rule="tabulated")
    assert abs(m.variance(3.1e4) - m.variance(3.2e4)) < 0.02 * m.variance(3.1e4)
    assert abs(near.variance(3.1e4) - near.variance(3.2e4)) > 0.5 * near.variance(3.1e4)


@pytest.mark.parametrize("rule", ["nearest", "interpolate"])
def test_variance_rules(rule: str) -> None:
    m = _model(pressure_rule=rule)
    for p in (5e3, 3e4, 2e5, 2e6):
        assert m.variance(p) == pytest.approx(m.std(p) ** 2, rel=1e-12)
        x = m.generate(p, 1)
        assert x.shape == (40,) and m.grid_is_periodic
        assert x.var() == pytest.approx(m.std(p) ** 2, rel=1e-10)  # exact on a periodic grid
    t = _model(pressure_rule=rule, variance_rule="tabulated")
    assert t.variance(1e5) == pytest.approx(float(np.sum(t.table_psd[1])) / LENGTH, rel=1e-12)
    # the shape is the tabulated one (falling by half over the band)
    s = m.spectrum(m.frequencies(), 1e5)
    assert s[-1] / s[0] == pytest.approx(t.table_psd[1][-1] / t.table_psd[1][0], rel=1e-12)


def test_periodogram_of_a_realisation_is_the_target() -> None:
    m = _model(variance_rule="tabulated")
    f, s = one_sided_psd(m.generate(1e5, 3), DX)
    np.testing.assert_allclose(s[:-1], m.spectrum(f[:-1], 1e5), rtol=1e-9)
    assert s[-1] == pytest.approx(0.0, abs=1e-20)  # Nyquist bin is outside the band


def test_longer_process_by_replace_clamps_low_frequencies() -> None:
    m = dataclasses.replace(_model(variance_rule="tabulated"), length=0.08, dx=0.08 / 80)
    f = m.frequencies()
    s = m.spectrum(f, 1e4)
    assert s[0] == pytest.approx(1e-5)  # 12.5 1/m < first tabulated 25 1/m: clamped
    assert m.generate(1e4, 1).shape == (80,)
    with pytest.raises(ValueError, match="zero over the band"):
        dataclasses.replace(_model(), length=1e-3, dx=1e-5).spectrum([1e3], 1e5)


def test_sigma_zeta_rules() -> None:
    m = _model()
    assert m.sigma_zeta(1e5) == pytest.approx(m.std(1e5))
    sl = _model(sigma_zeta_rule="spectral_level")
    s = sl.spectrum(sl.frequencies(), 1e5)
    assert sl.sigma_zeta(1e5) == pytest.approx(0.5 * np.mean(s[:4]), rel=1e-12)  # lowest quarter of 19 bins
    assert low_frequency_level([3.0, 1.0]) == 3.0
    # brake preset (flat): S0 = σ_μ² ℓ/K, σ_ζ = S0/2
    bp = dataclasses.replace(brake().process, sigma_zeta_rule="spectral_level")
    p = 3.5e5
    k = bp.frequencies().size
    assert bp.sigma_zeta(p) == pytest.approx(0.5 * bp.std(p) ** 2 * bp.length / k, rel=1e-12)


def test_validation() -> None:
    with pytest.raises(ValueError, match="increasing"):
        _model(pressures_pa=(1e5, 1e4, 1e6))
    with pytest.raises(ValueError, match="shape"):
        _model(table_psd=((1.0,),))
    with pytest.raises(ValueError, match=">= 0"):
        _model(table_psd=tuple(tuple(-np.ones(F.size)) for _ in range(3)))
    with pytest.raises(ValueError, match="pressure_rule"):
        _model(pressure_rule="spline")
    with pytest.raises(ValueError, match="variance_rule"):
        _model(variance_rule="x")
    with pytest.raises(ValueError, match="sigma_zeta_rule"):
        _model(sigma_zeta_rule="x")
    with pytest.raises(ValueError, match="p must be > 0"):
        _model().spectrum(F, 0.0)


def test_round_trip_save_load_dispatch(tmp_path: Path) -> None:
    m = _model(pressure_rule="interpolate", psd_level=ModelFunction(a=1e-6, b=-0.4, c=0.0))
    data = json.loads(json.dumps(m.to_dict()))
    assert data["kind"] == "tabulated"
    assert process_model_from_dict(data) == m
    path = m.save(tmp_path / "fp.json")
    loaded = load_process_model(path)
    assert loaded == m and isinstance(loaded, TabulatedProcessModel)
    np.testing.assert_array_equal(loaded.generate(2e5, 4), m.generate(2e5, 4))
    with pytest.raises(ValueError, match="kind 'tabulated'"):
        process_model_from_dict({"kind": "tabulated", "name": "x"})
    assert isinstance(load_process_model(brake().process.save(tmp_path / "b.json")), BandLimitedProcessModel)


def test_model_plugs_into_simulate() -> None:
    m = _model()
    phys = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0, contact_area=0.016)
    params = phys.to_dimensionless()
    assert params.pressure_pa == pytest.approx(3.5e5)
    res = simulate(params, model="contact", process=m, runs=2, seed=1, integration=IntegrationOptions(tau_end=5.0))
    assert res.process is not None and res.process["kind"] == "tabulated"
    white = simulate(params, model="white", process=_model(sigma_zeta_rule="spectral_level"), runs=1, seed=1,
                     integration=IntegrationOptions(tau_end=2.0))
    assert white.sigma_zeta[0] == pytest.approx(_model(sigma_zeta_rule="spectral_level").sigma_zeta(3.5e5))

"""Unit tests of the friction-process model (method §4d/e, eq. 3.21/3.22)."""

from __future__ import annotations

import dataclasses
import json
from pathlib import Path

import numpy as np
import pytest

from stochfric.friction_process.model import (
    BandLimitedProcessModel,
    FrictionProcessModel,
    ModelFunction,
    process_model_from_dict,
)
from stochfric.oscillator.options import IntegrationOptions


def _model(**changes: object) -> BandLimitedProcessModel:
    kwargs: dict[str, object] = dict(
        name="test",
        mu_mean=ModelFunction(a=5.8574, b=-0.4478, c=0.2603),
        mu_std=ModelFunction(a=1.6063, b=-0.4163, c=0.0663),
        dx=5e-4,
        length=0.04,  # 80 grid points, one period
        spectrum_shape="falling",
        falling_ratio=0.3,
    )
    kwargs.update(changes)
    return BandLimitedProcessModel(**kwargs)  # type: ignore[arg-type]


def test_model_function_values() -> None:
    f = ModelFunction(a=2.0, b=0.5, c=1.0)
    assert f(4.0) == pytest.approx(5.0)
    assert isinstance(f(4.0), float)
    np.testing.assert_allclose(f(np.array([1.0, 9.0, 16.0])), [3.0, 7.0, 9.0])
    brake_mean = ModelFunction(a=5.8574, b=-0.4478, c=0.2603)
    assert brake_mean(1e6) == pytest.approx(5.8574 * 1e6**-0.4478 + 0.2603, rel=1e-15)
    assert brake_mean(1e6) == pytest.approx(0.27231, abs=5e-5)


@pytest.mark.parametrize("p", [0.0, -1.0, float("nan"), float("inf")])
def test_model_function_refuses_bad_pressure(p: float) -> None:
    f = ModelFunction(a=1.0, b=-0.5, c=0.0)
    with pytest.raises(ValueError, match=r"> 0 Pa|finite"):
        f(p)
    with pytest.raises(ValueError):
        f(np.array([1.0, p]))


def test_model_function_dict_round_trip_and_validation() -> None:
    f = ModelFunction(a=-1.0185, b=0.0120, c=1.2689)
    assert f.to_dict() == {"a": -1.0185, "b": 0.0120, "c": 1.2689}
    assert ModelFunction.from_dict(f.to_dict()) == f
    with pytest.raises(ValueError, match="finite"):
        ModelFunction(a=float("nan"), b=1.0, c=0.0)
    with pytest.raises(dataclasses.FrozenInstanceError):
        f.a = 2.0  # type: ignore[misc]


@pytest.mark.parametrize("shape", ["flat", "falling"])
@pytest.mark.parametrize("p", [3e4, 5e5, 1.25e6])
def test_spectrum_variance_equals_std_squared(shape: str, p: float) -> None:
    model = _model(spectrum_shape=shape)
    f = model.frequencies()
    s = model.spectrum(f, p)
    assert np.sum(s) * (1.0 / model.length) == pytest.approx(model.std(p) ** 2, rel=1e-13)
    assert model.variance(p) == pytest.approx(model.std(p) ** 2, rel=1e-13)
    assert np.all(s > 0)


def test_spectrum_shapes() -> None:
    p = 5e5
    flat = _model(spectrum_shape="flat")
    f = flat.frequencies()
    s_flat = flat.spectrum(f, p)
    np.testing.assert_allclose(s_flat, s_flat[0], rtol=1e-14)
    assert s_flat[0] == pytest.approx(flat.std(p) ** 2 / (f.size / flat.length), rel=1e-13)
    falling = _model(spectrum_shape="falling", falling_ratio=0.3)
    s = falling.spectrum(f, p)
    assert s[-1] / s[0] == pytest.approx(0.3, rel=1e-13)
    np.testing.assert_allclose(np.diff(s), np.diff(s)[0], rtol=1e-10)  # linear in f
    assert np.all(np.diff(s) < 0)
    # band-limited: zero outside [f_1, f_K]
    outside = falling.spectrum(np.array([0.5 * f[0], 1.01 * f[-1], 5e4]), p)
    np.testing.assert_array_equal(outside, 0.0)


def test_generate_has_exact_variance_on_a_periodic_grid_and_is_reproducible() -> None:
    model = _model()
    assert model.grid_is_periodic and model.n_points == 80
    mu = model.generate(5e5, np.random.default_rng(3))
    assert mu.shape == (80,)
    assert np.var(mu) == pytest.approx(model.std(5e5) ** 2, rel=1e-12)
    np.testing.assert_array_equal(mu, model.generate(5e5, np.random.default_rng(3)))
    assert not np.array_equal(mu, model.generate(5e5, np.random.default_rng(4)))
    np.testing.assert_allclose(model.grid(), np.arange(80) * 5e-4)


def test_sigma_zeta_follows_the_thesis_rule() -> None:
    model = _model()
    for p in (1e5, 5e5, 1e6):
        assert model.sigma_zeta(p) == model.std(p)


def test_negative_std_fit_is_refused() -> None:
    sheet_like = _model(mu_std=ModelFunction(a=-1.0185, b=0.0120, c=1.2689))
    assert sheet_like.std(1e6) > 0
    with pytest.raises(ValueError, match="range of validity"):
        sheet_like.std(1e9)


@pytest.mark.parametrize(
    ("changes", "match"),
    [
        ({"dx": 0.0}, "dx"),
        ({"length": -1.0}, "length"),
        ({"length": 1e-3, "dx": 5e-4}, "exceed"),
        ({"spectrum_shape": "pink"}, "spectrum_shape"),
        ({"falling_ratio": 1.5}, "falling_ratio"),
        ({"sigma_zeta_rule": "other"}, "sigma_zeta_rule"),
        ({"name": ""}, "name"),
    ],
)
def test_invalid_models_are_refused(changes: dict[str, object], match: str) -> None:
    with pytest.raises(ValueError, match=match):
        _model(**changes)


def test_save_load_round_trip(tmp_path: Path) -> None:
    model = _model(dx=6.3e-4, length=0.05, spectrum_shape="flat")
    path = model.save(tmp_path / "process.json")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["process.json"]  # no temp left
    loaded = BandLimitedProcessModel.load(path)
    assert loaded == model
    data = json.loads(path.read_text(encoding="utf-8"))
    assert data["kind"] == "band_limited" and data["units"]["dx"] == "m"
    assert process_model_from_dict(data) == model
    np.testing.assert_array_equal(
        loaded.generate(2e5, np.random.default_rng(1)),
        model.generate(2e5, np.random.default_rng(1)),
    )
    model2 = _model(name="other")
    model2.save(path)  # overwrite in place
    assert BandLimitedProcessModel.load(path) == model2


def test_from_dict_refuses_other_kinds() -> None:
    data = _model().to_dict()
    with pytest.raises(ValueError, match="kind"):
        process_model_from_dict({**data, "kind": "tabulated"})
    with pytest.raises(ValueError, match="schema_version"):
        BandLimitedProcessModel.from_dict({**data, "schema_version": 99})


@pytest.mark.parametrize("kind", ["band_limited", "tabulated", "psd_level"])
def test_every_process_model_drives_the_contact_oscillator(kind: str) -> None:
    """Each kind of friction-process model does what the oscillator needs (the Protocol): E[μ](p)
    for the pressure law, a realisation on its grid with the model's variance, and a run of the
    contact model that sticks and slips."""
    from stochfric.contact.asperity import default_approach_m
    from stochfric.contact.materials import get_material
    from stochfric.oscillator.friction_laws import pressure_law
    from stochfric.oscillator.integrate import simulate
    from stochfric.oscillator.parameters import PhysicalParameters
    from stochfric.oscillator.presets import brake
    from stochfric.process.statistics import AnalysisConfig, analyse
    from stochfric.surface.io import default_surface_path, read_surface
    from stochfric.surface.preprocess import prepare
    from stochfric.surface.summits import summits_of

    pre = brake()
    if kind == "band_limited":
        model: FrictionProcessModel = pre.process
    elif kind == "psd_level":
        model = pre.process_with_level("psd_level")
    else:
        fine, _ = prepare(read_surface(default_surface_path()))
        cfg = AnalysisConfig(realizations=3, long_surfaces=3, length_factor=3, window_shift_points=37, seed=1,
                             check_realizations=5)
        u = default_approach_m(summits_of(fine), num=5, rule="sigma")
        model = analyse(fine, get_material("brake-pad"), u, cfg).model
        model = dataclasses.replace(model, length=0.05, dx=0.05 / round(0.05 / model.dx))  # type: ignore[arg-type]
    params = PhysicalParameters(
        mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed, normal_force=5600.0,
        damping_ratio=5e-6, contact_area=pre.contact_area,
    ).to_dimensionless()
    p = params.pressure_pa
    assert p is not None and 0.0 < model.mean(p) < 1.0
    x = model.generate(p, 3)
    n = round(model.length / model.dx)
    assert x.size == n
    f = model.frequencies()
    variance = float(np.sum(model.spectrum(f, p))) / model.length  # Σ S Δf, Δf = 1/ℓ
    periodic = abs(model.length / model.dx - n) < 1e-9 * n
    assert float(np.mean(x**2)) == pytest.approx(variance, rel=1e-9 if periodic else 0.3)
    # the thesis's μ0 = 0.4 is below E[μ] of the shipped surface (0.62 at 0.35 MPa): the static value
    # of the pressure law (4.13) must exceed the drop E[μ](p)
    law = pressure_law(model.mean(p), mu0=max(0.4, model.mean(p) + 0.2))
    res = simulate(params, law=law, model="contact", process=model, runs=2, seed=1,
                   integration=IntegrationOptions(tau_end=10.0, dt=0.005))
    assert np.all(res.stick_count >= 1)

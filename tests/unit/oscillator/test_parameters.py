"""Parameters: physical ↔ dimensionless (below eq. 4.7) and validation."""

from __future__ import annotations

import math
import re

import pytest

from stochfric.oscillator.friction_laws import (
    FRICTION_LAWS,
    get_law,
    law_I,
    law_II,
    law_III,
    pressure_law,
)
from stochfric.oscillator.parameters import (
    OscillatorParameters,
    ParameterError,
    PhysicalParameters,
)


def test_brake_dimensionless_values_match_method_section_6() -> None:
    p = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0,
                           damping_ratio=0.15, forcing_amplitude=50.0,
                           forcing_frequency=1.2 * math.sqrt(5e5), contact_area=0.016)
    d = p.to_dimensionless()
    assert d.omega0 == pytest.approx(707.1068, rel=1e-6)
    assert d.gamma0 == pytest.approx(1.4142e-3, rel=1e-4)
    assert d.n == pytest.approx(5.6e-3)
    assert d.q == pytest.approx(5e-5)  # method §6: brake Q = 50 N ↔ q = 5e-5
    assert d.eta == pytest.approx(1.2)
    assert d.damping_ratio == 0.15
    assert d.normal_force == pytest.approx(5600.0)
    assert d.pressure_pa == pytest.approx(5600.0 / 0.016)
    assert d.belt_speed == pytest.approx(1.0)


def test_damping_coefficient_converts_to_ratio() -> None:
    p = PhysicalParameters(mass=1.0, stiffness=1e5, belt_speed=1.0, normal_force=100.0,
                           damping_coefficient=2 * 0.17 * math.sqrt(1e5))
    assert p.to_dimensionless().damping_ratio == pytest.approx(0.17)
    assert p.to_dimensionless().gamma0 == pytest.approx(3.1623e-3, rel=1e-4)


@pytest.mark.parametrize(
    ("kwargs", "fragment"),
    [
        ({"gamma0": -1.0, "n": 1.0}, "gamma0"),
        ({"gamma0": 1.0, "n": 0.0}, "n (dimensionless normal force"),
        ({"gamma0": 1.0, "n": 1.0, "damping_ratio": float("nan")}, "finite"),
        ({"gamma0": 1.0, "n": 1.0, "damping_ratio": 1.5}, "underdamped"),
        ({"gamma0": 1.0, "n": 1.0, "q": -0.1}, "forcing amplitude"),
        ({"gamma0": 1.0, "n": 1.0, "contact_area": 0.0}, "contact_area"),
    ],
)
def test_invalid_dimensionless_parameters_are_refused(kwargs: dict, fragment: str) -> None:
    with pytest.raises(ParameterError, match=re.escape(fragment)):
        OscillatorParameters(**kwargs)


def test_invalid_physical_parameters_are_refused() -> None:
    with pytest.raises(ParameterError, match="mass"):
        PhysicalParameters(mass=-2.0, stiffness=1e6, belt_speed=1.0, normal_force=1.0)
    with pytest.raises(ParameterError, match="not both"):
        PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=1.0,
                           damping_coefficient=1.0, damping_ratio=0.1)
    with pytest.raises(ParameterError, match="stiffness"):
        OscillatorParameters(gamma0=1, n=1).with_normal_force(100.0)


def test_with_normal_force() -> None:
    p = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=1.0,
                           contact_area=0.016).to_dimensionless()
    assert p.with_normal_force(8000.0).n == pytest.approx(8e-3)


def test_friction_laws_table_4_1() -> None:
    assert law_I()(0.0) == 0.25 and law_I()(3.0) == 0.25
    assert law_II()(0.0) == 0.4 and law_II()(1e-9) == 0.25
    l3 = law_III()
    v = 0.7
    assert l3(v) == pytest.approx(0.3 / (1 + 1.42 * v) + 0.1 + 0.01 * v * v, rel=1e-15)
    assert l3(0.0) == 0.4 and l3.kinetic(0.0) == pytest.approx(0.4)
    h = 1e-6
    assert l3.derivative(v) == pytest.approx((l3(v + h) - l3(v - h)) / (2 * h), rel=1e-7)


def test_pressure_law_eq_4_13() -> None:
    law = pressure_law(0.28)
    v = 1.0
    assert law(v) == pytest.approx(0.28 / 2.42 + 0.4 - 0.28 + 0.01, rel=1e-15)
    assert law(0.0) == 0.4
    with pytest.raises(ValueError, match="exceeds mu0"):
        pressure_law(0.5)


def test_registry() -> None:
    assert set(FRICTION_LAWS) >= {"I", "II", "III", "pressure"}
    assert get_law("III") == law_III()
    with pytest.raises(ValueError, match="unknown friction law"):
        get_law("IV")

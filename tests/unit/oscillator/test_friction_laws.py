"""Friction laws (stochfric.oscillator.friction_laws) against Table 4.1 and eq. (4.13).

Reference values are exact rational evaluations of the thesis's formulas (docs/method.md §5), done
by hand with ``fractions.Fraction`` and written here as decimals:

* law III  μ(v) = (μ0 − μ1)/(1 + 1.42|v|) + μ1 + 0.01 v², μ0 = 0.4, μ1 = 0.1;
  μ'(v) = −0.3·1.42/(1 + 1.42 v)² + 0.02 v;
* pressure law (4.13)  μ_D(v) = μ_fit/(1 + 1.42|v|) + μ0 − μ_fit + 0.01 v², μ0 = 0.4.

tests/unit/oscillator/test_parameters.py already checks one value of each law; here: several speeds,
the slopes (the falling branch that drives the Hopf instability, and where it ends), the limits and
continuity at v → 0, and every invalid parameter refused with a message.
"""

from __future__ import annotations

import math
import re

import numpy as np
import pytest

from stochfric.oscillator.friction_laws import (
    SHAPE_CONSTANT,
    FrictionLaw,
    get_law,
    law_I,
    law_II,
    law_III,
    pressure_law,
)

#: v [m/s] → (μ, dμ/dv [s/m]) of law III, exact to the printed digits
LAW_III_VALUES = {
    0.5: (0.2779385964912281, -0.1356858520570432),
    1.0: (0.23396694214876032, -0.05274093299638003),
    2.0: (0.218125, 0.011110026041666667),
    10.0: (1.1197368421052631, 0.19815616343490305),
}


@pytest.mark.parametrize("v", sorted(LAW_III_VALUES))
def test_law_III_values_and_slopes(v: float) -> None:
    law = law_III()
    mu, dmu = LAW_III_VALUES[v]
    assert law(v) == pytest.approx(mu, rel=1e-14)
    assert law(-v) == law(v)  # the law takes |v_rel|; the sign is the integrators' job
    assert law.derivative(v) == pytest.approx(dmu, rel=1e-12)


def test_law_III_at_rest_and_its_stribeck_minimum() -> None:
    law = law_III()
    assert law(0.0) == 0.4 and law.kinetic(0.0) == pytest.approx(0.4, rel=1e-15)  # continuous at 0
    assert law.derivative(0.0) == pytest.approx(-0.3 * 1.42, rel=1e-14)  # −0.426 s/m
    # falling below ≈ 1.7 m/s (negative damping of steady sliding), rising above: the minimum
    # lies where 0.426/(1 + 1.42 v)² = 0.02 v, between the tabulated 1 and 2 m/s
    v = np.linspace(1.0, 2.0, 1001)
    d = np.array([law.derivative(x) for x in v])
    v_min = v[np.argmax(d > 0)]
    assert 0.426 / (1 + 1.42 * v_min) ** 2 == pytest.approx(0.02 * v_min, rel=2e-3)
    assert float(law.kinetic(v_min)) < min(law(1.0), law(2.0))


def test_law_III_is_vectorised_and_keeps_the_shape() -> None:
    v = np.array([[0.0, 0.5], [-1.0, 2.0]])
    out = law_III()(v)
    assert out.shape == (2, 2)
    np.testing.assert_allclose(out, [[0.4, LAW_III_VALUES[0.5][0]], [LAW_III_VALUES[1.0][0], 0.218125]],
                               rtol=1e-14)


def test_laws_I_and_II_static_and_kinetic_values() -> None:
    one, two = law_I(), law_II()
    assert (one.static, float(one.kinetic(0.0)), float(one(7.0))) == (0.25, 0.25, 0.25)
    # law II: a jump at v = 0, μ(0) = 0.4 bounds the sticking force, 0.25 while slipping at any speed
    assert two(0.0) == 0.4 and two.static == 0.4
    assert float(two.kinetic(0.0)) == 0.25 and float(two(1e-300)) == 0.25 and float(two(-50.0)) == 0.25
    assert one.derivative(3.0) == 0.0 and two.derivative(0.0) == 0.0


@pytest.mark.parametrize(("mu_fit", "v", "expected"), [
    (0.28, 0.5, 0.2862426900584795),
    (0.28, 2.0, 0.23291666666666666),
    (0.1, 0.5, 0.3609795321637427),
    (0.1, 2.0, 0.36604166666666665),
])
def test_pressure_law_eq_4_13_values(mu_fit: float, v: float, expected: float) -> None:
    assert pressure_law(mu_fit)(v) == pytest.approx(expected, rel=1e-14)


@pytest.mark.parametrize("mu_fit", [0.05, 0.28, 0.4])
def test_pressure_law_is_continuous_at_rest_whatever_the_pressure(mu_fit: float) -> None:
    """μ_D(0⁺) = μ_fit + μ0 − μ_fit = μ0 = μ_D(0): the pressure only shapes the falling branch,
    whose initial slope is −1.42 μ_fit; far out it approaches μ0 − μ_fit + 0.01 v²."""
    law = pressure_law(mu_fit)
    assert float(law.kinetic(0.0)) == pytest.approx(0.4, abs=1e-15) and law.static == 0.4
    assert law.derivative(0.0) == pytest.approx(-1.42 * mu_fit, rel=1e-14)
    v = 1e4
    assert float(law(v)) - 0.01 * v * v == pytest.approx(0.4 - mu_fit, abs=1e-4)
    if mu_fit == 0.4:  # the boundary μ_fit = μ0 is allowed and never negative
        assert float(np.min(law.kinetic(np.linspace(0, 20, 201)))) >= 0.0


def test_pressure_law_with_its_own_mu0() -> None:
    law = pressure_law(0.3, mu0=0.5)
    assert law.static == 0.5 and float(law.kinetic(0.0)) == pytest.approx(0.5, abs=1e-15)
    assert float(law(1.0)) == pytest.approx(0.3 / 2.42 + 0.2 + 0.01, rel=1e-14)


@pytest.mark.parametrize(("mu_fit", "fragment"), [
    (0.0, "positive finite"),
    (-0.1, "positive finite"),
    (float("nan"), "positive finite"),
    (float("inf"), "positive finite"),
    (0.41, "exceeds mu0 = 0.4"),
])
def test_pressure_law_refuses_impossible_mu_fit(mu_fit: float, fragment: str) -> None:
    with pytest.raises(ValueError, match=re.escape(fragment)):
        pressure_law(mu_fit)


@pytest.mark.parametrize(("kwargs", "fragment"), [
    ({"shape": 7, "params": (0.2,), "static": 0.3}, "unknown friction-law shape code 7"),
    ({"shape": SHAPE_CONSTANT, "params": (0.2, 0.1), "static": 0.3}, "shape needs 1 parameters"),
    ({"shape": SHAPE_CONSTANT, "params": (math.nan,), "static": 0.3}, "must be finite"),
    ({"shape": SHAPE_CONSTANT, "params": (0.2,), "static": math.inf}, "must be finite"),
    ({"shape": SHAPE_CONSTANT, "params": (0.2,), "static": -0.1}, "static coefficient must be >= 0"),
    ({"shape": SHAPE_CONSTANT, "params": (-0.2,), "static": 0.3}, "negative kinetic coefficient"),
])
def test_invalid_laws_are_refused_with_a_message(kwargs: dict, fragment: str) -> None:
    with pytest.raises(ValueError, match=re.escape(fragment)):
        FrictionLaw(name="x", **kwargs)


def test_law_III_with_parameters_that_turn_negative_is_refused() -> None:
    # μ1 = −0.2: μ(2 m/s) = 0.6/3.84 − 0.2 + 0.04 = −0.00375
    with pytest.raises(ValueError, match="negative kinetic coefficient"):
        law_III(mu1=-0.2)
    with pytest.raises(ValueError, match="static coefficient"):
        law_I(-0.1)


def test_registry_builds_laws_with_parameters_and_describes_them() -> None:
    assert get_law("pressure", mu_fit=0.28) == pressure_law(0.28)
    assert get_law("I", mu=0.3).static == 0.3
    with pytest.raises(ValueError, match=r"choose one of \['I', 'II', 'III', 'pressure'\]"):
        get_law("Coulomb")
    d = law_III().to_dict()
    assert d["shape"] == "rational" and d["static"] == 0.4 and d["params"] == pytest.approx([0.3, 1.42, 0.1, 0.01])
    assert law_I().to_dict()["shape"] == "constant"

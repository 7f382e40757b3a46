"""One case, built once (issue 12): :func:`build_case` and :class:`CaseSetup` give the same case; a
:class:`Case` runs in :func:`simulate` as its parameters, law, process and time grid do."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest

from stochfric.oscillator.case import (
    CaseError,
    DimensionlessInput,
    FrictionInput,
    PhysicalInput,
    build_case,
    case_setup,
    physical_parameters,
)
from stochfric.oscillator.friction_laws import law_III
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions, Model, NoiseOptions, WhiteIncrement, white_increment_of
from stochfric.oscillator.parameters import ParameterError
from stochfric.oscillator.presets import get_preset


def test_cli_case_equals_study_case() -> None:
    pre = get_preset("brake")
    d = pre.study_parameters.damping_undamped
    a = build_case("brake", physical=PhysicalInput(normal_force=4000.0, forcing_amplitude=500.0),
                   dimensionless=DimensionlessInput(eta=1.2))
    b = case_setup("brake").case(4000.0, d, 500.0, 1.2)
    assert a.params == b.params and a.law == b.law
    assert a.params.eta == 1.2  # η exactly as given
    assert a.process == b.process == pre.process
    assert (a.tau_end, a.dt) == (b.tau_end, b.dt) == (pre.tau_end, pre.dt)


def test_input_forms_agree() -> None:
    pre = get_preset("sheet")
    a = build_case("sheet", dimensionless=DimensionlessInput(n=1e-3, damping_ratio=0.1))
    b = build_case(physical=PhysicalInput(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                                          normal_force=1e-3 * pre.stiffness, contact_area=pre.contact_area),
                   dimensionless=DimensionlessInput(damping_ratio=0.1), friction=FrictionInput(friction_law="III"))
    assert a.params == b.params
    assert b.process is None and b.law == law_III()
    c = build_case(dimensionless=DimensionlessInput(gamma0=b.params.gamma0, n=b.params.n, damping_ratio=0.1,
                                                    omega0=b.params.omega0))
    assert c.params.n == b.params.n and c.law == law_III()
    p = physical_parameters(pre.mass, pre.stiffness, pre.belt_speed, 880.0, damping_coefficient=10.0)
    assert p.damping_ratio == pytest.approx(10.0 / (2 * (pre.stiffness * pre.mass) ** 0.5))


def test_rules_and_process_length() -> None:
    c = build_case("sheet", model="white", friction=FrictionInput(process_level="psd_level",  # type: ignore[arg-type]
                                                                  white_intensity="thesis", process_length=0.05))
    assert c.process.to_dict()["kind"] == "psd_level" and c.process.sigma_zeta_rule == "sigma_mu"
    assert c.process.length == pytest.approx(0.05) and c.white_increment("white") == "thesis"
    assert c.white_increment("contact") == "ito"
    assert case_setup("sheet", white_intensity="spectral_level").process.sigma_zeta_rule == "spectral_level"


def test_white_increment_is_one_rule() -> None:
    assert white_increment_of(Model.WHITE, "thesis") is WhiteIncrement.THESIS
    for model, rule in [("white", "sigma_mu"), ("white", None), ("contact", "thesis"), ("deterministic", "thesis")]:
        assert white_increment_of(model, rule) is WhiteIncrement.ITO
    st = case_setup("brake", white_intensity="thesis")
    assert st.white_increment is WhiteIncrement.THESIS


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"preset": "brake", "dimensionless": DimensionlessInput(gamma0=1.0)}, "dimensionless input"),
    ({"model": "white"}, "give either a `preset`"),
    ({"dimensionless": DimensionlessInput(gamma0=1.0, n=1.0), "friction": FrictionInput(friction_law="pressure")},
     "needs E"),
    ({"dimensionless": DimensionlessInput(gamma0=1.0, n=1.0), "friction": FrictionInput(white_intensity="thesis")},  # type: ignore[arg-type]
     "needs a friction-process model"),
    ({"dimensionless": DimensionlessInput(gamma0=1.0, n=1.0), "model": "contact"}, "contact model needs"),
    ({"preset": "brake", "friction": FrictionInput(mu0=0.1)}, "larger static coefficient `mu0`"),
    ({"preset": "brake", "friction": FrictionInput(process_level="loud")}, "`process_level`"),  # type: ignore[arg-type]
    ({"preset": "brake", "physical": PhysicalInput(normal_force=1.0), "dimensionless": DimensionlessInput(n=1.0)},
     "`normal_force` N"),
    ({"preset": "pad"}, "pad"),
])
def test_errors_name_the_field(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(CaseError, match=match):
        build_case(**kwargs)  # type: ignore[arg-type]


def test_a_case_runs_as_its_parts() -> None:
    """simulate(case) = simulate(params, law, process, its σ_ζ rule and time grid); several cases of one
    setup run as the parameter sets of one call."""
    case = build_case("brake", model="white", physical=PhysicalInput(normal_force=2720.0),
                      friction=FrictionInput(white_intensity="thesis"), tau_end=5.0)  # type: ignore[arg-type]
    a = simulate(case, model="white", runs=3, seed=2)
    b = simulate(case.params, model="white", law=case.law, process=case.process, runs=3, seed=2,
                 noise=NoiseOptions(white_increment=WhiteIncrement.THESIS),
                 integration=IntegrationOptions(tau_end=5.0, dt=case.dt))
    np.testing.assert_array_equal(a.x_gh, b.x_gh)
    assert a.settings["white_increment"] == "thesis"
    st = case_setup("brake", tau_end=5.0)
    cases = [st.case(2720.0, 5e-6), st.case(5600.0, 5e-6)]
    both = simulate(cases, model="contact", runs=2, seed=1)
    alone = simulate(cases[1], model="contact", runs=2, seed=1,
                     noise=NoiseOptions(stream_keys=((1,),)))
    np.testing.assert_array_equal(both.x_gh[1], alone.x_gh[0])
    with pytest.raises(ParameterError, match=r"a Case fixes law, integration\.tau_end"):
        simulate(case, law=law_III(), integration=IntegrationOptions(tau_end=1.0))
    with pytest.raises(ParameterError, match="must share"):
        simulate([cases[0], replace(cases[1], dt=0.001)])
    with pytest.raises(ParameterError, match="not both"):
        simulate([cases[0], cases[1].params])  # type: ignore[list-item]

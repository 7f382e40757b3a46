"""One case, built once (issue 12): :func:`build_case` and :class:`CaseSetup` give the same case."""

from __future__ import annotations

import pytest

from stochfric.oscillator.case import CaseError, build_case, case_setup, physical_parameters
from stochfric.oscillator.friction_laws import law_III
from stochfric.process.presets import get_preset


def test_cli_case_equals_study_case() -> None:
    pre = get_preset("brake")
    d = float(pre.study_parameters["damping_undamped"])
    a = build_case("brake", normal_force=4000.0, forcing_amplitude=500.0, eta=1.2)
    b = case_setup("brake").case(4000.0, d, 500.0, 1.2)
    assert a.params == b.params and a.law == b.law
    assert a.params.eta == 1.2  # η exactly as given
    assert a.process == b.process == pre.process
    assert (a.tau_end, a.dt) == (b.tau_end, b.dt) == (pre.tau_end, pre.dt)


def test_input_forms_agree() -> None:
    pre = get_preset("sheet")
    a = build_case("sheet", n=1e-3, damping_ratio=0.1)
    b = build_case(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                   normal_force=1e-3 * pre.stiffness, damping_ratio=0.1, contact_area=pre.contact_area_m2,
                   process_file=None, friction_law="III")
    assert a.params == b.params
    assert b.process is None and b.law == law_III()
    c = build_case(gamma0=b.params.gamma0, n=b.params.n, damping_ratio=0.1, omega0=b.params.omega0)
    assert c.params.n == b.params.n and c.law == law_III()
    p = physical_parameters(pre.mass, pre.stiffness, pre.belt_speed, 880.0, damping_coefficient=10.0)
    assert p.damping_ratio == pytest.approx(10.0 / (2 * (pre.stiffness * pre.mass) ** 0.5))


def test_rules_and_process_length() -> None:
    c = build_case("sheet", process_level="psd_level", white_intensity="thesis", process_length=0.05,
                   model="white")
    assert c.process.to_dict()["kind"] == "psd_level" and c.process.sigma_zeta_rule == "sigma_mu"
    assert c.process.length == pytest.approx(0.05) and c.white_increment("white") == "thesis"
    assert c.white_increment("contact") == "ito"
    assert case_setup("sheet", white_intensity="spectral_level").process.sigma_zeta_rule == "spectral_level"


@pytest.mark.parametrize(("kwargs", "match"), [
    ({"preset": "brake", "gamma0": 1.0}, "dimensionless input"),
    ({"model": "white"}, "give either --preset"),
    ({"gamma0": 1.0, "n": 1.0, "friction_law": "pressure"}, "needs E"),
    ({"gamma0": 1.0, "n": 1.0, "white_intensity": "thesis"}, "needs a friction-process model"),
    ({"gamma0": 1.0, "n": 1.0, "model": "contact"}, "contact model needs"),
    ({"preset": "brake", "mu0": 0.1}, "larger static coefficient"),
    ({"preset": "brake", "process_level": "loud"}, "process level"),
    ({"preset": "pad"}, "pad"),
])
def test_errors_name_the_option(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(CaseError, match=match):
        build_case(**kwargs)  # type: ignore[arg-type]

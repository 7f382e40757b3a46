"""Machine descriptions (issue 30 item 1): the shipped brake and sheet are the thesis's presets, a machine
round-trips through TOML, and every bad value is refused on one line that names the key, the value, the
unit and the allowed range."""

from __future__ import annotations

import dataclasses
import json
import math
import pickle
import tomllib
from pathlib import Path
from typing import Any

import pytest

from stochfric.errors import InputError
from stochfric.friction_process.presets import (
    BRAKE_PSD_LEVEL_FIT,
    SHEET_PSD_LEVEL_FIT,
    brake_process,
    sheet_process,
)
from stochfric.oscillator.case import case_setup, law_for, physical_parameters
from stochfric.oscillator.friction_laws import law_III
from stochfric.oscillator.machine import (
    SPECS,
    Machine,
    MachineError,
    load_machine,
    machine_names,
    parse_machine,
)
from stochfric.oscillator.presets import Preset, brake, sheet

DOCS = Path(__file__).resolve().parents[3] / "docs" / "machines.md"

THESIS = {
    "brake": (brake, brake_process, BRAKE_PSD_LEVEL_FIT),
    "sheet": (sheet, sheet_process, SHEET_PSD_LEVEL_FIT),
}


def _calliper() -> dict[str, Any]:
    return {
        "name": "c", "mass_kg": 5.0, "stiffness_n_per_m": 3e6, "belt_speed_m_s": 0.3,
        "contact_area_m2": 4e-3, "normal_force_n": [500.0, 4000.0], "default_normal_force_n": 2000.0,
        "damping_ratio": 0.05,
    }


def _refused(data: dict[str, Any]) -> str:
    with pytest.raises(MachineError) as info:
        Machine.model_validate(data)
    msg = str(info.value)
    assert isinstance(info.value, InputError)
    assert "\n" not in msg
    return msg


# -- the shipped machines are the thesis's presets ----------------------------------------------------


def test_shipped_names() -> None:
    assert {"brake", "sheet", "example-calliper"} <= set(machine_names())
    assert load_machine("BRAKE") == load_machine("brake") == load_machine(" Brake ")


@pytest.mark.parametrize("name", ["brake", "sheet"])
def test_shipped_machine_is_the_preset(name: str) -> None:
    factory, process, fit = THESIS[name]
    pre = factory()
    machine = load_machine(name)
    built = machine.to_preset(process(), fit)
    for f in dataclasses.fields(Preset):
        assert getattr(built, f.name) == getattr(pre, f.name), f.name
    assert built == pre
    assert built.study_parameters == pre.study_parameters
    assert machine.omega0 == pre.omega0 and machine.gamma0 == pre.gamma0
    assert machine.pressure_range_pa == pre.pressure_range_pa
    assert machine.pressure(pre.default_normal_force) == pre.pressure(pre.default_normal_force)
    assert Machine.from_preset(pre) == machine


@pytest.mark.parametrize("name", ["brake", "sheet"])
def test_shipped_machine_gives_the_study_parameters(name: str) -> None:
    pre = THESIS[name][0]()
    machine = load_machine(name)
    setup = case_setup(name)
    sp = pre.study_parameters
    forces = (*pre.normal_force_range, pre.default_normal_force, *sp.normal_force_study_forces)
    for n in forces:
        for d in (sp.damping_undamped, sp.damping_damped):
            assert machine.oscillator_parameters(n, d) == setup.parameters(n, d)
    q_force = sp.forcing_study_force
    assert machine.oscillator_parameters(q_force, sp.damping_undamped, forcing_amplitude=50.0, eta=1.2) == \
        setup.parameters(q_force, sp.damping_undamped, 50.0, 1.2)
    # the defaults: the preset's N and undamped D (as build_case takes them)
    assert machine.oscillator_parameters() == setup.parameters(pre.default_normal_force, sp.damping_undamped)


def test_shipped_pressure_law_is_law_for() -> None:
    machine = load_machine("brake")
    setup = case_setup("brake")
    params = machine.oscillator_parameters(4000.0)
    assert params.pressure_pa is not None
    assert machine.law(setup.process.mean(params.pressure_pa)) == law_for(setup.process, params)
    with pytest.raises(MachineError, match="mu_fit"):
        machine.law()


def test_example_calliper() -> None:
    m = load_machine("example-calliper")
    assert (m.mass, m.stiffness, m.belt_speed, m.contact_area) == (5.0, 3e6, 0.3, 4e-3)
    assert m.normal_force_range == (500.0, 4000.0) and m.damping_ratio == 0.05
    assert m.damping_ratio_range == (0.0, 0.3)
    assert m.omega0 == math.sqrt(3e6 / 5.0) and m.gamma0 == 0.3 / math.sqrt(3e6 / 5.0)
    assert m.pressure_range_pa == (500.0 / 4e-3, 4000.0 / 4e-3)
    sp = m.study_parameters()  # derived without [study_defaults]
    assert sp.normal_force_study_forces == (500.0, 2000.0, 4000.0) and sp.damping_damped == 0.05
    assert m.oscillator_parameters(1000.0) == physical_parameters(5.0, 3e6, 0.3, 1000.0, damping_ratio=0.05,
                                                                  contact_area=4e-3)


def test_defaults_are_the_thesis_values() -> None:
    data = _calliper()
    del data["default_normal_force_n"], data["damping_ratio"]
    m = Machine.model_validate(data)
    assert m.default_normal_force == 2250.0 and m.damping_ratio == 5e-6 and (m.tau_end, m.dt) == (50.0, 0.005)
    assert m.friction_law.law == "III" and m.law() == law_III()
    assert m.forcing is None and m.q == 0.0


# -- round trips -------------------------------------------------------------------------------------


@pytest.mark.parametrize("name", ["brake", "sheet", "example-calliper"])
def test_toml_round_trip(name: str, tmp_path: Path) -> None:
    m = load_machine(name)
    path = tmp_path / "m.toml"
    path.write_text(m.to_toml(), encoding="utf-8")
    assert load_machine(path) == m
    assert load_machine(str(path)) == m
    assert Machine.model_validate(json.loads(m.to_json())) == m
    assert Machine.model_validate(m.to_dict()) == m


def test_round_trip_of_omega0_forcing_and_odd_text(tmp_path: Path) -> None:
    data = _calliper()
    del data["stiffness_n_per_m"]
    data |= {"omega0_rad_s": 700.0, "description": 'a "quoted" \\ back\nslash\t ü', "forcing":
             {"amplitude_n": 50.0, "eta": 1.15}, "friction_law": {"law": "III", "mu1": 0.12, "mu0": 0.35}}
    m = Machine.model_validate(data)
    assert m.stiffness == 5.0 * 700.0**2 and m.omega0 == 700.0
    assert m.q == 50.0 / m.stiffness
    assert "omega0_rad_s" in m.to_dict() and "stiffness_n_per_m" not in m.to_dict()
    path = tmp_path / "m.toml"
    path.write_text(m.to_toml(), encoding="utf-8")
    back = load_machine(path)
    assert back == m and back.description == data["description"]
    params = m.oscillator_parameters()
    assert (params.q, params.eta) == (50.0 / m.stiffness, 1.15)


def test_python_field_names_and_keyword_construction() -> None:
    a = Machine.model_validate({"name": "c", "mass": 5.0, "stiffness": 3e6, "belt_speed": 0.3,
                                "contact_area": 4e-3, "normal_force_range": (500.0, 4000.0),
                                "default_normal_force": 2000.0, "damping_ratio": 0.05})
    assert a == Machine.model_validate(_calliper())
    with pytest.raises(MachineError, match="mass_kg"):
        Machine(name="x")


# -- the [machine] table of a larger file ------------------------------------------------------------


def test_machine_table_in_a_study_file(tmp_path: Path) -> None:
    m = load_machine("example-calliper")
    study = '\n[defaults]\nseed = 1\n\n[[study]]\nkind = "damping"\n'
    path = tmp_path / "study.toml"
    path.write_text(m.to_toml("machine") + study, encoding="utf-8")
    assert load_machine(path) == m
    bad = m.to_toml("machine").replace("mass_kg = 5.0", "mass_kg = -5.0") + study
    path.write_text(bad, encoding="utf-8")
    with pytest.raises(MachineError, match=r"study\.toml: machine\.mass_kg: mass m = -5\.0 kg .*\[1e-06, 100000\]"):
        load_machine(path)
    with pytest.raises(MachineError, match=r"unknown key 'colour' in machine\.friction_law; allowed keys: law"):
        parse_machine(tomllib.loads(m.to_toml("machine") + "colour = 1\n"))


def test_machine_reference_in_a_study_file(tmp_path: Path) -> None:
    (tmp_path / "rig.toml").write_text(load_machine("sheet").to_toml(), encoding="utf-8")
    (tmp_path / "a.toml").write_text('machine = "Brake"\n', encoding="utf-8")
    (tmp_path / "b.toml").write_text('machine = "rig.toml"\n', encoding="utf-8")
    (tmp_path / "c.toml").write_text('machine = "c.toml"\n', encoding="utf-8")
    assert load_machine(tmp_path / "a.toml") == load_machine("brake")
    assert load_machine(tmp_path / "b.toml") == load_machine("sheet")
    with pytest.raises(MachineError, match="machine must be a table"):
        load_machine(tmp_path / "c.toml")


def test_file_errors(tmp_path: Path) -> None:
    with pytest.raises(MachineError, match=r"not a shipped machine .*brake"):
        load_machine("lathe")
    with pytest.raises(MachineError, match="cannot read machine file"):
        load_machine(tmp_path / "missing.toml")
    (tmp_path / "x.toml").write_text("mass_kg = [", encoding="utf-8")
    with pytest.raises(MachineError, match="not valid TOML"):
        load_machine(tmp_path / "x.toml")
    with pytest.raises(MachineError, match="a machine is a file"):
        load_machine(3)  # type: ignore[arg-type]


# -- validation ---------------------------------------------------------------------------------------

_SCALARS = ["mass_kg", "stiffness_n_per_m", "belt_speed_m_s", "contact_area_m2", "default_normal_force_n",
            "damping_ratio", "tau_end", "dt"]


@pytest.mark.parametrize("key", _SCALARS)
@pytest.mark.parametrize("value", [0.0, -1.0, math.nan, math.inf, "2", True, [1.0], 1e300, 10**400])
def test_bad_scalar_is_refused_naming_the_key(key: str, value: Any) -> None:
    if key == "damping_ratio" and value == 0.0:
        return  # D = 0 is allowed
    data = _calliper() | {key: value}
    msg = _refused(data)
    assert msg.startswith(key), msg


@pytest.mark.parametrize(("key", "value", "text"), [
    ("mass_kg", -2.0, "mass_kg: mass m = -2.0 kg is outside the allowed range [1e-06, 100000] kg"),
    ("mass_kg", math.nan, "mass_kg: mass m must be finite, got nan; allowed [1e-06, 100000] kg"),
    ("mass_kg", "5", "mass_kg: mass m must be a number, got '5'; allowed [1e-06, 100000] kg"),
    ("stiffness_n_per_m", 0.5, "stiffness_n_per_m: stiffness c = 0.5 N/m is outside the allowed range [1, 1e+12] N/m"),
    ("belt_speed_m_s", 2e3, "belt speed v0 = 2000.0 m/s is outside the allowed range [1e-06, 1000] m/s"),
    ("contact_area_m2", 20.0, "nominal contact area A = 20.0 m² is outside the allowed range [1e-12, 10] m²"),
    ("damping_ratio", 1.0, "damping_ratio: damping ratio D = 1.0 is outside the allowed range [0, 1)"),
    ("damping_ratio", 0.5, "damping_ratio = 0.5 lies outside damping_ratio_range [0, 0.3]"),
    ("default_normal_force_n", 5000.0, "default_normal_force_n = 5000.0 N lies outside normal_force_n [500, 4000] N"),
    ("dt", 2.0, "dt: dimensionless time step Δτ = 2.0 is outside the allowed range (0, 1]"),
    ("tau_end", 0.001, "dt = 0.005 must be smaller than tau_end = 0.001"),
    ("normal_force_n", [4000.0, 500.0], "normal_force_n: normal force N range [4000, 500] must have low < high"),
    ("normal_force_n", [0.0, 500.0], "normal_force_n: normal force N = 0.0 N is outside the allowed range (0, 1e+09]"),
    ("normal_force_n", 500.0, "normal_force_n: normal force N range must be [low, high]"),
    ("damping_ratio_range", [0.0, 1.0], "damping_ratio_range: damping ratio D = 1.0 is outside the allowed range"),
    ("damping_ratio_range", [0.2, 0.1], "damping_ratio_range: damping ratio D range [0.2, 0.1] must have low < high"),
    ("name", "", "name: must be a non-empty single line"),
    ("name", 3, "name: must be a string, got 3"),
    ("friction_law", 3, "friction_law: must be a table with the keys law, mu0, mu1, decay_s_per_m, quad_s2_per_m2"),
    ("friction_law", {"law": "IV"}, "friction_law.law: Input should be 'III' or 'pressure', got 'IV'"),
    ("friction_law", {"mu0": 0.0}, "friction_law.mu0: static coefficient μ0 = μ_D(0) = 0.0 is outside the allowed"),
    ("friction_law", {"mu1": -0.1}, "friction_law.mu1: law III's high-speed level μ1 = -0.1 is outside"),
    ("friction_law", {"decay_s_per_m": math.nan}, "friction_law.decay_s_per_m: decay rate of μ_D(v) must be finite"),
    ("friction_law", {"quad_s2_per_m2": -1.0}, "quad_s2_per_m2: quadratic coefficient of μ_D(v) = -1.0 s²/m² is"),
    ("friction_law", {"law": "pressure", "mu1": 0.1}, "friction_law: mu1 is law III's"),
    ("forcing", {"amplitude_n": -1.0, "eta": 1.0}, "forcing.amplitude_n: forcing amplitude Q = -1.0 N is outside"),
    ("forcing", {"amplitude_n": 1.0, "eta": "fast"}, "forcing.eta: forcing frequency ratio η = Ω/ω0 must be a number"),
    ("forcing", {"amplitude_n": 1.0}, "forcing.eta: missing: give forcing frequency ratio η = Ω/ω0 in [0, 1000]"),
    ("study_defaults", {"damping_damped": 0.1, "damping_study_force_n": 9000.0, "forcing_study_force_n": 600.0,
                        "normal_force_study_forces_n": [600.0]},
     "study_defaults.damping_study_force_n = 9000.0 N lies outside normal_force_n [500, 4000] N"),
    ("study_defaults", {"damping_damped": 0.5, "damping_study_force_n": 900.0, "forcing_study_force_n": 600.0,
                        "normal_force_study_forces_n": [600.0]},
     "study_defaults.damping_damped = 0.5 lies outside damping_ratio_range [0, 0.3]"),
    ("study_defaults", {"damping_damped": 0.1, "damping_study_force_n": 900.0, "forcing_study_force_n": 600.0,
                        "normal_force_study_forces_n": [600.0, 600.0]}, "a value is listed twice"),
])
def test_error_messages(key: str, value: Any, text: str) -> None:
    assert text in _refused(_calliper() | {key: value})


def test_missing_keys_are_named_with_unit_and_range() -> None:
    msg = _refused({"name": "x", "stiffness_n_per_m": 1e6})
    for part in ("mass_kg: missing: give mass m in [1e-06, 100000] kg",
                 "belt_speed_m_s: missing", "contact_area_m2: missing",
                 "normal_force_n: missing: give [low, high] of the normal force N in (0, 1e+09] N"):
        assert part in msg


def test_unknown_keys_are_refused_with_the_allowed_keys() -> None:
    msg = _refused(_calliper() | {"colour": "red", "mass": 5.0})
    assert msg.startswith("unknown keys 'colour', 'mass' in the machine; allowed keys: name, description, mass_kg")
    assert "omega0_rad_s" in msg and "study_defaults" in msg
    msg = _refused(_calliper() | {"forcing": {"amplitude_n": 1.0, "eta": 1.0, "q": 2.0}})
    assert "unknown key 'q' in forcing; allowed keys: amplitude_n, eta" in msg


def test_stiffness_or_omega0() -> None:
    both = _calliper() | {"omega0_rad_s": 700.0}
    assert "give exactly one of stiffness_n_per_m [N/m] and omega0_rad_s [rad/s]" in _refused(both)
    neither = _calliper()
    del neither["stiffness_n_per_m"]
    assert "got neither" in _refused(neither)
    assert "got neither" in _refused(neither | {"omega0_rad_s": None})
    too_stiff = neither | {"omega0_rad_s": 1e9}
    assert "gives stiffness c = m ω0² = 5e+18 N/m, outside the allowed range [1, 1e+12] N/m" in _refused(too_stiff)
    assert "omega0_rad_s: natural circular frequency" in _refused(neither | {"omega0_rad_s": -1.0})
    m = Machine.model_validate(neither | {"omega0_rad_s": 700.0})
    assert m.stiffness == 5.0 * 700.0**2


def test_envelope_and_pressure() -> None:
    m = Machine.model_validate(_calliper())
    m.check_envelope([500.0, 4000.0], [0.0, 0.3])
    with pytest.raises(MachineError, match=r"normal force 4500 N lies outside machine 'c'"):
        m.check_envelope([4500.0])
    with pytest.raises(MachineError, match=r"damping ratio 0.4 lies outside machine 'c'"):
        m.check_envelope(damping_ratios=[0.4])
    assert m.pressure(1000.0) == 1000.0 / 4e-3
    with pytest.raises(MachineError, match=r"normal_force: normal force N = -1.0 N is outside"):
        m.pressure(-1.0)


def test_machine_is_frozen_and_its_error_pickles() -> None:
    m = load_machine("brake")
    with pytest.raises(Exception, match="frozen"):
        m.mass = 3.0  # type: ignore[misc]
    with pytest.raises(MachineError) as info:
        Machine.model_validate(_calliper() | {"mass_kg": 0.0})
    back = pickle.loads(pickle.dumps(info.value))
    assert isinstance(back, MachineError) and str(back) == str(info.value)


def test_docs_list_every_key() -> None:
    text = DOCS.read_text(encoding="utf-8")
    for key in [*SPECS, "name", "description", "law", "[friction_law]", "[forcing]", "[study_defaults]"]:
        assert f"`{key}`" in text, key

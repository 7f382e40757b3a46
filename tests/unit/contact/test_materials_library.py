"""Materials a user can trust (issue 30 item 6): case-insensitive names, the library of sourced
pairings, plausible ranges for every field and the two rules of physics (H ≥ R_p, τ_max ≤ R_p)."""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from stochfric.contact.materials import (
    HARDNESS_FACTOR,
    MATERIALS,
    Material,
    MaterialError,
    canonical_material_name,
    get_material,
    load_material,
    material_names,
    material_table,
)

BASE: dict[str, Any] = {
    "name": "x", "e1_pa": 1e9, "nu1": 0.3, "e2_pa": 210e9, "nu2": 0.3,
    "yield_strength_pa": 1e9, "shear_strength_pa": 1e8, "hardness_pa": 3e9,
}  # fmt: skip


def _make(**changes: Any) -> Material:
    return Material(**{**BASE, **changes})


def _e_star(e1: float, nu1: float, e2: float, nu2: float) -> float:
    """(3.10) by hand: 1/E* = (1 − ν1²)/E1 + (1 − ν2²)/E2."""
    return 1.0 / ((1.0 - nu1**2) / e1 + (1.0 - nu2**2) / e2)


# --- names -------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("spelling", "canonical"),
    [
        ("DC04", "dc04"), ("Dc04", "dc04"), (" dc04 ", "dc04"),
        ("Brake_Pad", "brake-pad"), ("BRAKE PAD", "brake-pad"), ("brake__pad", "brake-pad"),
        ("Steel_S235", "steel-s235"), ("Pad Grey Iron", "pad-grey-iron"), ("ALUMINIUM-STEEL", "aluminium-steel"),
    ],
)  # fmt: skip
def test_names_are_case_and_separator_insensitive(spelling: str, canonical: str) -> None:
    assert canonical_material_name(spelling) == canonical
    assert get_material(spelling) is MATERIALS[canonical]
    assert load_material(spelling) is MATERIALS[canonical]
    assert get_material(spelling).name == canonical  # the canonical name is what outputs record
    assert get_material(spelling).to_dict()["name"] == canonical


def test_unknown_name_is_one_line_with_the_names_and_the_file_option() -> None:
    with pytest.raises(MaterialError) as err:
        get_material("steel")
    msg = str(err.value)
    assert "\n" not in msg
    assert msg.startswith("unknown material 'steel'")
    assert "did you mean 'steel-s235'" in msg
    for name in material_names():
        assert name in msg
    assert "JSON file" in msg and "SI" in msg
    with pytest.raises(MaterialError, match="unknown material 'granite'"):
        load_material("granite")
    with pytest.raises(MaterialError, match="must be a string"):
        get_material(4)  # type: ignore[arg-type]


def test_material_names_are_canonical_and_sorted() -> None:
    names = material_names()
    assert names == sorted(MATERIALS)
    assert {"brake-pad", "dc04", "pad-grey-iron", "steel-s235", "aluminium-steel"} <= set(names)
    for name in names:
        assert canonical_material_name(name) == name
        assert MATERIALS[name].name == name


def test_material_table_lists_every_entry_with_bodies_and_sources() -> None:
    rows = material_table()
    assert [r["name"] for r in rows] == material_names()
    for row in rows:
        m = MATERIALS[row["name"]]
        assert row["rough_body"] and row["counter_body"] and row["sources"] and row["description"]
        assert row["e_star_pa"] == m.e_star_pa
        assert row["hardness_pa"] == m.hardness
        assert row["shear_strength_pa"] == m.shear_strength_pa
        assert row["hardness_tabulated"] is (m.hardness_pa is not None)
        assert row["e2_pa"] is None if math.isinf(m.e2_pa) else row["e2_pa"] == m.e2_pa
    json.dumps(rows)  # printable / JSON-safe


# --- the library -------------------------------------------------------------------------------


def test_thesis_entries_are_unchanged() -> None:
    brake = MATERIALS["brake-pad"]
    assert (brake.e1_pa, brake.nu1, brake.e2_pa, brake.nu2) == (1e9, 0.3, math.inf, 0.3)
    assert (brake.yield_strength_pa, brake.shear_strength_pa, brake.hardness_pa) == (305e6, 35e6, 1708e6)
    assert brake.e_star_pa == pytest.approx(1.099e9, rel=5e-4)  # docs: 1.099 GPa
    dc04 = MATERIALS["dc04"]
    assert (dc04.e1_pa, dc04.nu1, dc04.e2_pa, dc04.nu2) == (210e9, 0.3, 210e9, 0.3)
    assert (dc04.yield_strength_pa, dc04.shear_strength_pa, dc04.hardness_pa) == (860e6, 500e6, 4850e6)
    assert dc04.e_star_pa == pytest.approx(115.4e9, rel=5e-4)  # docs: 115.4 GPa (thesis misprint 1.15)


@pytest.mark.parametrize(
    ("name", "e1", "nu1", "e2", "nu2", "e_star_documented"),
    [
        ("pad-grey-iron", 1e9, 0.3, 110e9, 0.26, 1.089e9),  # pad (thesis) on EN-GJL-250 (EN 1561)
        ("steel-s235", 210e9, 0.3, 210e9, 0.3, 115.4e9),  # EN 1993-1-1 3.2.6
        ("aluminium-steel", 70e9, 0.3, 210e9, 0.3, 57.69e9),  # EN 1999-1-1 3.2.5 on EN 1993-1-1
    ],
)
def test_library_e_star_by_hand(name: str, e1: float, nu1: float, e2: float, nu2: float,
                                e_star_documented: float) -> None:  # fmt: skip
    m = get_material(name)
    assert (m.e1_pa, m.nu1, m.e2_pa, m.nu2) == (e1, nu1, e2, nu2)
    assert m.e_star_pa == pytest.approx(_e_star(e1, nu1, e2, nu2), rel=1e-12)
    assert m.e_star_pa == pytest.approx(e_star_documented, rel=5e-4)


def test_pad_on_grey_iron_differs_from_the_thesis_pad_only_by_the_elastic_disc() -> None:
    pad, disc = MATERIALS["brake-pad"], MATERIALS["pad-grey-iron"]
    for key in ("e1_pa", "nu1", "yield_strength_pa", "shear_strength_pa", "hardness_pa"):
        assert getattr(pad, key) == getattr(disc, key)
    assert disc.e_star_pa / pad.e_star_pa == pytest.approx(0.9907, abs=1e-4)  # the disc lowers E* by 0.9 %


@pytest.mark.parametrize(("name", "rp"), [("steel-s235", 235e6), ("aluminium-steel", 250e6)])
def test_standard_entries_follow_the_thesis_conventions(name: str, rp: float) -> None:
    m = get_material(name)
    assert m.yield_strength_pa == rp  # EN 10025-2 R_eH of S235 / EN 1999-1-1 f_o of 6082-T6
    assert m.hardness_pa is None and m.hardness == pytest.approx(HARDNESS_FACTOR * rp)  # H = 5.6 R_p
    assert m.shear_strength_pa == pytest.approx(rp / math.sqrt(3.0))  # von Mises shear yield


@pytest.mark.parametrize("name", sorted(MATERIALS))
def test_every_entry_has_a_source_and_survives_a_json_round_trip(name: str, tmp_path: Path) -> None:
    m = MATERIALS[name]
    assert m.description
    p = tmp_path / "m.json"
    p.write_text(json.dumps(m.to_dict()), encoding="utf-8")
    assert load_material(p) == m


# --- ranges ------------------------------------------------------------------------------------

_BAD: list[tuple[str, Any, str]] = []
for _key, _small, _large in [
    ("e1_pa", 1.0, 2.1e14), ("e2_pa", 2.1e5, 1.3e12), ("yield_strength_pa", 235.0, 2e11),
    ("shear_strength_pa", 35.0, 2e11), ("hardness_pa", 1708.0, 2e11),
]:  # fmt: skip
    _BAD += [
        (_key, 0.0, "zero"), (_key, -2.0e9, "negative"), (_key, math.nan, "nan"), (_key, -math.inf, "-inf"),
        (_key, _small, "too small"), (_key, _large, "too large"), (_key, "210e9", "string"),
        (_key, True, "bool"), (_key, [1e9], "list"),
    ]  # fmt: skip
    if _key != "e2_pa":  # e2_pa = inf is a rigid counter-body
        _BAD.append((_key, math.inf, "inf"))
for _key in ("nu1", "nu2"):
    _BAD += [
        (_key, 0.0, "zero"), (_key, -0.3, "negative (auxetic)"), (_key, math.nan, "nan"), (_key, math.inf, "inf"),
        (_key, -1.5, "too small"), (_key, 0.6, "too large"), (_key, 30.0, "percent"), (_key, "0.3", "string"),
        (_key, None, "None"), (_key, False, "bool"),
    ]  # fmt: skip


@pytest.mark.parametrize(("key", "value", "case"), _BAD, ids=[f"{k}-{c}" for k, _, c in _BAD])
def test_each_field_is_range_and_type_checked(key: str, value: Any, case: str) -> None:
    with pytest.raises(MaterialError) as err:
        _make(**{key: value})
    msg = str(err.value)
    assert key in msg, msg
    assert "\n" not in msg
    assert "'x'" in msg  # names the material


@pytest.mark.parametrize(
    ("key", "value", "says"),
    [
        ("e1_pa", 1.0, "e1_pa = 1 Pa is not a plausible Young's modulus of the rough body (1)"),
        ("e1_pa", 1.0, "(plausible 1e6 … 1.2e12 Pa: soft elastomers ~1 MPa to diamond ~1.2 TPa)"),
        ("e1_pa", 1.0, "if 1 GPa is meant, write 1e9"),
        ("e1_pa", 210.0, "if 210 GPa is meant, write 2.1e11"),
        ("e1_pa", 210000.0, "if 210000 MPa is meant, write 2.1e11"),
        ("e2_pa", 2.1e14, "values are in Pa (210 GPa is 2.1e11)"),
        ("e1_pa", math.inf, "only the counter-body may be rigid"),
        ("e2_pa", 0.0, "it must be positive"),
        ("yield_strength_pa", 235.0, "if 235 MPa is meant, write 2.35e8"),
        ("shear_strength_pa", 35.0, "if 35 MPa is meant, write 3.5e7"),
        ("hardness_pa", 1.7, "if 1.7 GPa is meant, write 1.7e9"),
        ("hardness_pa", 1708.0, "if 1708 MPa is meant, write 1.708e9"),
        ("nu1", 30.0, "a percentage? 30 % is 0.3"),
        ("nu2", 0.0, "0 is most likely a missing value"),
        ("nu1", -0.3, "auxetic"),
        ("nu1", 0.6, "0 < nu1 <= 0.5"),
        ("e1_pa", "210e9", "e1_pa must be a number in Pa, got '210e9' (str)"),
    ],
)  # fmt: skip
def test_range_errors_say_value_unit_range_and_likely_mistake(key: str, value: Any, says: str) -> None:
    with pytest.raises(MaterialError) as err:
        _make(**{key: value})
    assert says in str(err.value), str(err.value)


@pytest.mark.parametrize(
    "changes",
    [
        {"e1_pa": 1e6, "e2_pa": 1.2e12},  # the ends of the E range
        {"e2_pa": math.inf},  # rigid counter-body
        {"nu1": 0.5, "nu2": 0.03},  # incompressible; beryllium's small ratio
        {"yield_strength_pa": 1e6, "shear_strength_pa": 1e5, "hardness_pa": None},  # soft ends
        {"yield_strength_pa": 1e11, "shear_strength_pa": 1e11, "hardness_pa": 1.5e11},  # hard ends
        {"e1_pa": np.float64(2e9), "nu1": np.float32(0.25), "yield_strength_pa": np.int64(10**9)},
    ],
)
def test_plausible_values_are_accepted(changes: dict[str, Any]) -> None:
    m = _make(**changes)
    for key in ("e1_pa", "nu1", "e2_pa", "nu2", "yield_strength_pa", "shear_strength_pa"):
        assert type(getattr(m, key)) is float  # numbers are stored as float


@pytest.mark.parametrize("name", ["", "   ", 3, None])
def test_a_material_needs_a_name(name: Any) -> None:
    with pytest.raises(MaterialError, match="needs a name"):
        _make(name=name)


# --- rules of physics --------------------------------------------------------------------------


def test_hardness_below_the_yield_strength_is_refused() -> None:
    with pytest.raises(MaterialError) as err:
        _make(yield_strength_pa=1e9, hardness_pa=0.5e9)
    msg = str(err.value)
    assert "hardness_pa = 500 MPa is below yield_strength_pa = 1000 MPa" in msg
    _make(yield_strength_pa=1e9, hardness_pa=1e9)  # H = R_p: the lowest possible constraint factor


def test_shear_strength_above_the_yield_strength_is_refused() -> None:
    with pytest.raises(MaterialError) as err:
        _make(yield_strength_pa=1e8, shear_strength_pa=2e8)
    msg = str(err.value)
    assert "shear_strength_pa = 200 MPa exceeds yield_strength_pa = 100 MPa" in msg
    assert "R_p/sqrt(3) = 57.74 MPa" in msg
    _make(yield_strength_pa=1e8, shear_strength_pa=1e8)  # τ_max = R_p: allowed
    # the rule is τ_max ≤ R_p, not ≤ R_p/√3: the thesis rounds DC04's 860/√3 = 496.5 MPa up to 500 MPa
    dc04 = MATERIALS["dc04"]
    assert dc04.shear_strength_pa > dc04.yield_strength_pa / math.sqrt(3.0)


def test_shear_strength_never_exceeds_the_hardness_used() -> None:
    """τ_max ≤ H follows from the two rules, for tabulated and 5.6 R_p hardness alike."""
    for m in MATERIALS.values():
        assert m.shear_strength_pa <= m.yield_strength_pa <= m.hardness


# --- files ------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("key", "value", "says"),
    [
        ("e1_pa", 210, "if 210 GPa is meant, write 2.1e11"),
        ("nu1", 30, "a percentage?"),
        ("shear_strength_pa", 9e8, "exceeds yield_strength_pa"),
        ("hardness_pa", 1e8, "is below yield_strength_pa"),
    ],
)
def test_material_file_with_an_implausible_value_names_file_and_field(
    tmp_path: Path, key: str, value: float, says: str
) -> None:
    data = {**MATERIALS["dc04"].to_dict(), "name": "mine", key: value}
    p = tmp_path / "mine.json"
    p.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(MaterialError) as err:
        load_material(p)
    msg = str(err.value)
    assert msg.startswith(f"material file {p}: material 'mine': {key}"), msg
    assert says in msg

"""Materials: E* (3.10), hardness, presets, user-defined pairings."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from stochfric.contact.materials import (
    Material,
    MaterialError,
    get_material,
    load_material,
    material_names,
)


def test_presets_match_the_thesis_tables() -> None:
    brake = get_material("brake-pad")
    assert brake.e_star_pa == pytest.approx(1.0e9 / (1 - 0.3**2))  # 1.099 GPa ≈ 1.1 GPa
    assert brake.e_star_pa == pytest.approx(1.1e9, rel=0.01)
    assert brake.hardness == pytest.approx(5.6 * 305e6)  # 1708 MPa
    assert brake.shear_strength_pa == 35e6
    dc04 = get_material("dc04")
    assert dc04.e_star_pa == pytest.approx(210e9 / (2 * (1 - 0.3**2)))
    assert dc04.e_star_pa == pytest.approx(115e9, rel=0.005)  # not the misprinted 1.15 GPa
    assert dc04.hardness == 4850e6
    assert dc04.shear_strength_pa == 500e6
    assert {"brake-pad", "dc04"} <= set(material_names())


def test_hardness_defaults_to_5p6_rp() -> None:
    m = Material(name="x", e1_pa=2e9, nu1=0.25, yield_strength_pa=100e6, shear_strength_pa=50e6)
    assert m.hardness == pytest.approx(560e6)
    assert m.e_star_pa == pytest.approx(2e9 / (1 - 0.0625))  # rigid counter-body


@pytest.mark.parametrize(
    "kwargs",
    [
        {"e1_pa": -1.0},
        {"e1_pa": math.nan},
        {"nu1": 0.6},
        {"e2_pa": 0.0},
        {"shear_strength_pa": 0.0},
        {"hardness_pa": -5.0},
        {"name": ""},
    ],
)
def test_invalid_material_is_refused(kwargs: dict[str, object]) -> None:
    base: dict[str, object] = {
        "name": "x", "e1_pa": 1e9, "nu1": 0.3, "yield_strength_pa": 1e8, "shear_strength_pa": 1e7,
    }  # fmt: skip
    base.update(kwargs)
    with pytest.raises(MaterialError):
        Material(**base)  # type: ignore[arg-type]


def test_user_material_from_json(tmp_path: Path) -> None:
    p = tmp_path / "m.json"
    data = get_material("dc04").to_dict()
    p.write_text(json.dumps(data))
    m = load_material(p)
    assert m == get_material("dc04")
    brake = get_material("brake-pad").to_dict()
    assert brake["e2_pa"] is None  # rigid, JSON-safe
    p.write_text(json.dumps(brake))
    assert load_material(str(p)).e2_pa == math.inf
    p.write_text(json.dumps({"name": "x", "e1_pa": 1e9}))
    with pytest.raises(MaterialError, match="missing"):
        load_material(p)
    p.write_text(json.dumps({**data, "colour": "grey"}))
    with pytest.raises(MaterialError, match="unknown material field"):
        load_material(p)
    with pytest.raises(MaterialError, match="not found"):
        load_material(tmp_path / "nope.json")


def test_unknown_preset() -> None:
    with pytest.raises(MaterialError, match="unknown material 'steel'"):
        load_material("steel")

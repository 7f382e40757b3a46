"""Validity warnings of a contact result (issue 9 §6): each check fires exactly where it should."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.contact.asperity import asperity_contact
from stochfric.contact.materials import get_material
from stochfric.contact.validity import (
    MIN_CONTACTS,
    ValidityWarning,
    contact_validity,
    plasticity_validity,
    result_validity,
)
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION
from stochfric.surface.io import Surface
from stochfric.surface.summits import summits_of

GOOD = {"mu": [0.3, 0.4, 0.5], "area_fraction": [1e-3, 5e-3, 1e-2], "n_contacts": [20, 50, 90]}


def _codes(ws: list[ValidityWarning]) -> list[str]:
    return [w.code for w in ws]


def test_a_result_inside_the_model_gives_no_warning() -> None:
    assert contact_validity(**GOOD, plasticity_index=0.1) == []  # type: ignore[arg-type]


def test_each_check_fires_at_its_own_points() -> None:
    ws = contact_validity(
        mu=[0.5, 1.2, 0.8, 0.4],
        area_fraction=[1e-3, 1e-3, min(0.99, 2 * DEFAULT_MAX_AREA_FRACTION), 80.0],
        n_contacts=[3, 50, 60, 400],
        approach_m=[1e-7, 2e-7, 3e-7, 4e-7],
        name="f.plu",
    )
    by = {w.code: w for w in ws}
    assert set(by) == {"mu-above-one", "area-fraction-above-one", "beyond-non-interaction", "few-contacts"}
    assert by["mu-above-one"].indices == (1,)
    assert by["area-fraction-above-one"].indices == (3,)
    assert by["beyond-non-interaction"].indices == (2,)
    assert by["few-contacts"].indices == (0,)
    for w in ws:
        assert w.message.startswith("f.plu: ")
        d = w.to_dict()
        assert d["code"] == w.code and isinstance(d["indices"], list)
    # each message says what to change
    assert "material" in by["mu-above-one"].message
    assert "smaller approaches" in by["area-fraction-above-one"].message
    assert "--method halfspace" in by["beyond-non-interaction"].message
    assert "larger approaches" in by["few-contacts"].message
    assert "u = 0.1 µm" in by["few-contacts"].message


def test_boundaries_are_strict() -> None:
    # exactly 1, exactly the limit and exactly MIN_CONTACTS do not warn
    ws = contact_validity(mu=[1.0], area_fraction=[DEFAULT_MAX_AREA_FRACTION], n_contacts=[MIN_CONTACTS])
    assert ws == []
    ws = contact_validity(mu=[1.0001], area_fraction=[1e-3], n_contacts=[MIN_CONTACTS - 1])
    assert _codes(ws) == ["mu-above-one", "few-contacts"]


def test_custom_limits_and_nan_are_respected() -> None:
    ws = contact_validity(mu=[np.nan, 0.2], area_fraction=[0.05, 0.05], n_contacts=[5, 5], max_area_fraction=0.01,
                          min_contacts=3)  # fmt: skip
    assert _codes(ws) == ["beyond-non-interaction"]
    with pytest.raises(ValueError, match="same length"):
        contact_validity(mu=[1.0], area_fraction=[0.1, 0.2], n_contacts=[1])


@pytest.mark.parametrize(
    ("gamma", "codes"),
    [(0.1, []), (0.59, []), (0.6, ["elastic-plastic"]), (1.0, ["elastic-plastic"]), (1.01, ["plastic"]),
     (3.5, ["plastic"]), (float("nan"), [])],
)  # fmt: skip
def test_plasticity_index_classes(gamma: float, codes: list[str]) -> None:
    assert _codes(plasticity_validity(gamma)) == codes
    assert _codes(contact_validity(**GOOD, plasticity_index=gamma)) == codes  # type: ignore[arg-type]


def test_single_hertz_asperity_gives_mu_above_one_and_few_contacts() -> None:
    """One paraboloid, nm approach, soft pad: μ = 3πτ√β/(4E*√d) > 1 (closed form) → warned."""
    n, size, radius = 33, 50e-6, 20e-6
    x = (np.arange(n) - n // 2) * size / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    s = Surface(heights_m=-(xx**2 + yy**2) / (2 * radius), physical_size_m=(size, size))
    mat = get_material("brake-pad")
    d = 1e-9
    res = asperity_contact(s, summits_of(s), mat, [d])
    beta = float(summits_of(s).radius_m[0])
    mu_closed = 3 * np.pi * mat.shear_strength_pa * np.sqrt(beta) / (4 * mat.e_star_pa * np.sqrt(d))
    assert res.mu[0] == pytest.approx(mu_closed, rel=1e-9)
    assert mu_closed > 1
    assert _codes(result_validity(res)) == ["mu-above-one", "few-contacts"]

"""Boundary-element reference through ContactMechanics (optional dependency)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from stochfric.contact.asperity import ContactError, asperity_contact
from stochfric.contact.halfspace import halfspace_contact
from stochfric.contact.materials import get_material
from stochfric.contact.reference import hertz_contact
from stochfric.surface.io import Surface
from stochfric.surface.summits import summits_of


def _paraboloid(n: int = 65, size: float = 100e-6, radius: float = 50e-6) -> Surface:
    x = (np.arange(n) - n // 2) * size / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    return Surface(heights_m=-(xx**2 + yy**2) / (2 * radius), physical_size_m=(size, size))


def test_hertz_paraboloid_force_and_area() -> None:
    pytest.importorskip("ContactMechanics")
    s = _paraboloid()
    mat = get_material("brake-pad")
    u = np.array([0.2e-6, 0.4e-6])
    res = halfspace_contact(s, mat, u, summits=summits_of(s))
    assert res.preparation["reference"] == "highest summit"
    for k, uk in enumerate(u):
        hz = hertz_contact(radius_m=50e-6, e_star_pa=mat.e_star_pa, indentation_m=uk)
        assert res.normal_force_n[k] == pytest.approx(hz.normal_force_n, rel=0.03)
        # pixel-counted area: within a few pixels of π a²
        assert res.contact_area_m2[k] == pytest.approx(hz.contact_area_m2, rel=0.2)
        assert res.n_contacts[k] == 1
    # the GW sum on the same single summit gives the Hertz values exactly
    gw = asperity_contact(s, summits_of(s), mat, u)
    hz = hertz_contact(radius_m=50e-6, e_star_pa=mat.e_star_pa, indentation_m=u[1])
    assert gw.normal_force_n[1] == pytest.approx(hz.normal_force_n, rel=1e-9)


def test_missing_contactmechanics_is_a_clear_error(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "ContactMechanics", None)
    with pytest.raises(ContactError, match=r"pip install 'stochfric\[halfspace\]'"):
        halfspace_contact(_paraboloid(17), get_material("dc04"), [1e-7])

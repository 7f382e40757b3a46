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


def test_load_control_reproduces_hertz_approach_and_area() -> None:
    """Prescribed force = Hertz force at d: the solved approach is d and the area π a² (Hertz)."""
    pytest.importorskip("ContactMechanics")
    s = _paraboloid()
    mat = get_material("brake-pad")
    d = np.array([0.2e-6, 0.4e-6])
    hz = [hertz_contact(radius_m=50e-6, e_star_pa=mat.e_star_pa, indentation_m=v) for v in d]
    res = halfspace_contact(s, mat, normal_force_n=[h.normal_force_n for h in hz], summits=summits_of(s))
    assert res.preparation["halfspace"]["control"] == "load"
    np.testing.assert_allclose(res.normal_force_n, [h.normal_force_n for h in hz], rtol=1e-6)
    np.testing.assert_allclose(res.approach_m, d, rtol=0.03)
    np.testing.assert_allclose(res.contact_area_m2, [h.contact_area_m2 for h in hz], rtol=0.2)


def test_border_frame_hides_asperities_the_summit_rule_cannot_see() -> None:
    """A border point above the highest summit touches first unless the frame is lowered."""
    pytest.importorskip("ContactMechanics")
    base = _paraboloid(33)
    h = np.array(base.heights_m)
    h[0, 16] = h.max() + 0.5e-6  # on the border: no summit for the thesis rule
    s = Surface(heights_m=h, physical_size_m=base.physical_size_m)
    sm = summits_of(s)
    assert sm.count == 1 and sm.i[0] == 16
    mat = get_material("brake-pad")
    framed = halfspace_contact(s, mat, [0.1e-6], summits=sm)
    bare = halfspace_contact(s, mat, [0.1e-6], summits=sm, frame_points=0)
    assert framed.preparation["halfspace"]["frame_points"] == 2
    assert framed.n_contacts[0] == 1
    assert bare.n_contacts[0] == 2 and bare.normal_force_n[0] > framed.normal_force_n[0]


def test_compare_equal_load_carries_the_gw_forces_on_refined_grids() -> None:
    pytest.importorskip("ContactMechanics")
    from stochfric.contact.halfspace import compare_equal_load

    rng = np.random.default_rng(5)
    from scipy import ndimage

    z = ndimage.gaussian_filter(rng.normal(size=(32, 32)), 2.0) * 1e-6
    s = Surface(heights_m=z, physical_size_m=(64e-6, 64e-6))
    sm = summits_of(s)
    mat = get_material("brake-pad")
    cmp = compare_equal_load(s, sm, mat, np.array([0.5, 1.0]) * float(np.std(sm.heights_m)), refine=(1, 2))
    for k in (1, 2):
        res = cmp.halfspace[k]
        np.testing.assert_allclose(res.normal_force_n, cmp.asperity.normal_force_n, rtol=1e-6)
        assert res.preparation["halfspace"]["grid"] == [32 * k, 32 * k]
        np.testing.assert_allclose(cmp.area_ratio(k), res.contact_area_m2 / cmp.asperity.contact_area_m2)
        # equal load: the mu ratio is the area ratio
        np.testing.assert_allclose(res.mu / cmp.asperity.mu, cmp.area_ratio(k), rtol=1e-6)
    d = cmp.to_dict()
    assert d["comparison"] == "equal load" and set(d["halfspace"]) == {"1", "2"}
    assert len(d["halfspace"]["2"]["area_ratio_halfspace_to_asperity"]) == 2


def test_halfspace_argument_errors() -> None:
    s = _paraboloid(17)
    mat = get_material("dc04")
    pytest.importorskip("ContactMechanics")
    with pytest.raises(ContactError, match="either approach_m or normal_force_n"):
        halfspace_contact(s, mat)
    with pytest.raises(ContactError, match="either approach_m or normal_force_n"):
        halfspace_contact(s, mat, [1e-7], normal_force_n=[1.0])
    with pytest.raises(ContactError, match="normal forces must be"):
        halfspace_contact(s, mat, normal_force_n=[0.0])
    with pytest.raises(ContactError, match="refine must be an integer"):
        halfspace_contact(s, mat, [1e-7], refine=0)
    with pytest.raises(ContactError, match="frame_points"):
        halfspace_contact(s, mat, [1e-7], frame_points=9)

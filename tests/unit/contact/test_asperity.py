"""GW/Hertz sums vectorised over u, the result object, netCDF round trip."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from stochfric.contact import asperity as asp
from stochfric.contact.asperity import (
    ContactError,
    asperity_contact,
    asperity_sums,
    default_approach_m,
    read_contact_result,
)
from stochfric.contact.materials import get_material
from stochfric.surface.io import Surface
from stochfric.surface.summits import find_summits, summits_of


def _loop(z: np.ndarray, beta: np.ndarray, u: np.ndarray, e_star: float):  # type: ignore[no-untyped-def]
    """Plain per-approach, per-summit loop of (3.11)–(3.13)."""
    zmax = z.max()
    areas, forces, counts = [], [], []
    for uk in u:
        a = f = 0.0
        n = 0
        for zi, bi in zip(z, beta, strict=True):
            d = zi - (zmax - uk)
            if d > 0:
                a += math.pi * bi * d
                f += 4.0 / 3.0 * e_star * math.sqrt(bi * d**3)
                n += 1
        areas.append(a)
        forces.append(f)
        counts.append(n)
    return np.array(areas), np.array(forces), np.array(counts)


def test_vectorised_sums_equal_the_plain_loop() -> None:
    rng = np.random.default_rng(4)
    z = rng.normal(0.0, 1e-6, 500)
    beta = rng.uniform(5e-6, 50e-6, 500)
    u = np.array([2.5e-6, 0.1e-6, 1e-6, 4e-6, 0.5e-6])  # unsorted on purpose
    a, f, n = asperity_sums(z, beta, u, e_star_pa=1.1e9)
    a0, f0, n0 = _loop(z, beta, u, 1.1e9)
    np.testing.assert_allclose(a, a0, rtol=1e-10)
    np.testing.assert_allclose(f, f0, rtol=1e-10)
    np.testing.assert_array_equal(n, n0)


def test_blocking_does_not_change_the_result(monkeypatch: pytest.MonkeyPatch) -> None:
    rng = np.random.default_rng(5)
    z, beta = rng.normal(size=300), rng.uniform(1.0, 2.0, 300)
    u = np.linspace(0.1, 3.0, 17)
    ref = asperity_sums(z, beta, u, e_star_pa=1.0)
    monkeypatch.setattr(asp, "_BLOCK_ELEMENTS", 50)
    out = asperity_sums(z, beta, u, e_star_pa=1.0)
    for x, y in zip(ref, out, strict=True):
        np.testing.assert_allclose(x, y, rtol=1e-12)


def test_monotone_in_approach_and_first_contact() -> None:
    rng = np.random.default_rng(6)
    z, beta = rng.normal(size=400), rng.uniform(1.0, 2.0, 400)
    u = np.linspace(1e-3, 3.0, 40)
    a, f, n = asperity_sums(z, beta, u, e_star_pa=1.0)
    assert np.all(np.diff(a) > 0) and np.all(np.diff(f) > 0) and np.all(np.diff(n) >= 0)
    gap = np.sort(z)[-1] - np.sort(z)[-2]
    _, _, n_small = asperity_sums(z, beta, [gap / 2], e_star_pa=1.0)
    assert n_small[0] == 1  # only the highest summit


@pytest.mark.parametrize("u", [[0.0], [-1e-6], [np.nan], []])
def test_bad_approach_is_refused(u: list[float]) -> None:
    with pytest.raises(ContactError):
        asperity_sums([0.0, 1.0], [1.0, 1.0], u, e_star_pa=1.0)


def test_bad_summits_are_refused() -> None:
    with pytest.raises(ContactError, match="no summit"):
        asperity_sums([], [], [1.0], e_star_pa=1.0)
    with pytest.raises(ContactError, match="radii"):
        asperity_sums([0.0, 1.0], [1.0], [1.0], e_star_pa=1.0)
    with pytest.raises(ContactError):
        asperity_sums([0.0, 1.0], [1.0, -1.0], [1.0], e_star_pa=1.0)


def _surface(seed: int = 0) -> Surface:
    z = np.random.default_rng(seed).normal(size=(40, 50)) * 1e-6
    return Surface(heights_m=z, physical_size_m=(4e-4, 5e-4))


def test_contact_result_quantities() -> None:
    s = _surface()
    sm = summits_of(s)
    mat = get_material("brake-pad")
    res = asperity_contact(s, sm, mat, preparation={"step": 1})
    np.testing.assert_allclose(res.approach_m, default_approach_m(sm))
    assert res.approach_m.size == 12
    assert res.n_contacts[0] == 20
    np.testing.assert_allclose(res.pressure_pa, res.normal_force_n / 2e-7)
    np.testing.assert_allclose(res.area_fraction, res.contact_area_m2 / 2e-7)
    np.testing.assert_allclose(res.mu, res.contact_area_m2 * 35e6 / res.normal_force_n)
    np.testing.assert_allclose(res.friction_force_n, res.contact_area_m2 * 35e6)
    assert res.preparation["step"] == 1
    assert res.preparation["summit_rule"] == "thesis"
    d = res.to_dict()
    json.dumps(d, allow_nan=False)
    assert set(d) >= {"approach_m", "contact_area_m2", "pressure_pa", "n_contacts", "mu"}


def test_no_summit_is_an_error() -> None:
    s = Surface(heights_m=np.zeros((20, 20)), physical_size_m=(1e-3, 1e-3))
    sm = find_summits(s.heights_m, s.grid_spacing_m)
    with pytest.raises(ContactError, match="no summit found"):
        asperity_contact(s, sm, get_material("dc04"))


def test_dataset_units_and_netcdf_round_trip(tmp_path: Path) -> None:
    s = _surface(1)
    res = asperity_contact(s, summits_of(s), get_material("dc04"), preparation={"detrend": "plane"})
    ds = res.to_dataset()
    assert ds["pressure_pa"].attrs["units"] == "Pa"
    assert ds["contact_area_m2"].attrs["units"] == "m2"
    assert ds["approach_m"].attrs["units"] == "m"
    assert json.loads(ds.attrs["preparation"])["detrend"] == "plane"
    path = res.to_netcdf(tmp_path / "out" / "contact.nc")
    assert sorted(p.name for p in path.parent.iterdir()) == ["contact.nc"]  # no temp file left
    back = read_contact_result(path)
    for name in ("approach_m", "contact_area_m2", "normal_force_n", "n_contacts", "mu"):
        np.testing.assert_allclose(getattr(back, name), getattr(res, name))
    assert back.material == res.material
    assert back.preparation == res.preparation
    assert back.method == "asperity"


def test_failed_write_leaves_no_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    s = _surface(2)
    res = asperity_contact(s, summits_of(s), get_material("dc04"))

    def boom(self: object, *args: object, **kwargs: object) -> None:
        raise OSError("disk full")

    import xarray as xr

    monkeypatch.setattr(xr.Dataset, "to_netcdf", boom)
    with pytest.raises(OSError, match="disk full"):
        res.to_netcdf(tmp_path / "c.nc")
    assert list(tmp_path.iterdir()) == []


def test_default_range_reaches_the_bulk_when_the_highest_summit_is_an_outlier() -> None:
    """u_hi = max(3 σ_S, z_max − z̄_s): unchanged for Gaussian-like summits, stretched by an outlier."""
    s = _surface()
    sm = summits_of(s)
    z = sm.heights_m
    sigma = float(np.std(z))
    assert z.max() - z.mean() < 3 * sigma  # Gaussian-like: the 3 σ_S branch
    np.testing.assert_allclose(default_approach_m(sm, rule="sigma"), np.linspace(sigma / 4, 3 * sigma, 12))
    h = np.array(s.heights_m)
    i, j = int(sm.i[0]), int(sm.j[0])
    h[i, j] += 30 * sigma  # one summit 30 σ_S up (a dust grain)
    sm2 = summits_of(Surface(heights_m=h, physical_size_m=s.physical_size_m))
    z2 = sm2.heights_m
    u = default_approach_m(sm2, rule="sigma")
    assert u[-1] == pytest.approx(z2.max() - z2.mean()) and u[-1] > 3 * float(np.std(z2))
    assert u[0] == pytest.approx(u[-1] / 12)
    res = asperity_contact(Surface(heights_m=h, physical_size_m=s.physical_size_m), sm2, get_material("dc04"),
                           approach_m=u)
    assert res.n_contacts[0] == 1 and res.n_contacts[-1] >= 10


def _area_fraction(sm, u):  # type: ignore[no-untyped-def]
    area, _force, count = asperity_sums(sm.heights_m, sm.radius_m, u, e_star_pa=1e9)
    return area / sm.area_m2, count


def test_contacts_rule_spans_twenty_contacts_to_the_non_interaction_limit() -> None:
    """The default rule: from 20 touching summits to A_c/A_nom = 0.1 or half the summits touching."""
    sm = summits_of(Surface(heights_m=np.random.default_rng(3).normal(size=(120, 150)) * 1e-6,
                            physical_size_m=(1.2e-3, 1.5e-3)))
    u = default_approach_m(sm)
    frac, count = _area_fraction(sm, u)
    assert count[0] == 20
    half = count[-1] >= (sm.count - 1) // 2 and count[-1] <= sm.count // 2 + 1
    assert frac[-1] == pytest.approx(0.1, rel=1e-8) or (half and frac[-1] < 0.1)
    # never past the limit that the validity check (beyond-non-interaction) tests, not even by rounding
    assert np.all(frac <= 0.1) and np.all(np.diff(u) > 0)
    for fraction in (0.002, 0.01):  # a smaller limit ends the range where the area reaches it
        frac_f, _ = _area_fraction(sm, default_approach_m(sm, max_area_fraction=fraction))
        assert frac_f[-1] == pytest.approx(fraction, rel=1e-8) and frac_f[-1] <= fraction


def test_contacts_rule_is_shifted_but_not_widened_by_a_spike() -> None:
    s = _surface(4)
    sm = summits_of(s)
    u = default_approach_m(sm, max_area_fraction=0.02)
    h = np.array(s.heights_m)
    k = int(np.argmax(sm.heights_m))
    h[int(sm.i[k]), int(sm.j[k])] += 30 * float(np.std(sm.heights_m))
    sm2 = summits_of(Surface(heights_m=h, physical_size_m=s.physical_size_m))
    u2 = default_approach_m(sm2, max_area_fraction=0.02)
    shift = float(sm2.heights_m.max() - sm.heights_m.max())
    # the spike's summit is summit k raised: every depth below it grows by the same shift
    np.testing.assert_allclose(u2, u + shift, rtol=1e-9)


def test_unknown_approach_rule_is_refused() -> None:
    with pytest.raises(ContactError, match="approach rule"):
        default_approach_m(summits_of(_surface()), rule="nope")

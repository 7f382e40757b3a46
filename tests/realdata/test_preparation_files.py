"""Preparation on the seven shared instrument files: form degree, outliers, ties, undefined points,
rough-surface verdict (docs/surface_contact.md, "Preparation")."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from stochfric.surface.io import SurfaceError, read_surface
from stochfric.surface.preprocess import Preparation, preparation_report

#: name → (form degree chosen by auto, outliers replaced, quantised warning)
EXPECTED = {
    "al3d-1.al3d": (1, 0, False), "mnt-1.mnt": (2, 2890, False), "opd-1.opd": (1, 1, False),
    "plu-1.plu": (1, 35, True), "sur-2.sur": (2, 113, True), "x3p-2.x3p": (1, 0, False),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(EXPECTED))
def test_rough_files_are_prepared_by_the_stated_rules(name: str, shared_file: Callable[[str], Path]) -> None:
    rep = preparation_report(read_surface(shared_file(name), fill_undefined=True))
    degree, outliers, quantised = EXPECTED[name]
    assert rep.form["degree"] == degree
    assert rep.outliers["count"] == outliers
    assert len(rep.outliers["positions"]) == min(outliers, 100)
    assert rep.quantisation["quantised"] is quantised
    assert rep.rough_surface["rough"] is True
    assert rep.undefined["fraction"] < 0.001


def test_default_surface_is_unchanged_by_the_new_steps(shared_file: Callable[[str], Path]) -> None:
    s = read_surface(shared_file("al3d-1.al3d"))
    rep = preparation_report(s)
    assert rep.form["applied"] == "plane" and rep.outliers["count"] == 0
    assert rep.form["sq_after_m"] == pytest.approx(0.2898e-6, rel=1e-3)


def test_plu1_ties_are_measured(shared_file: Callable[[str], Path]) -> None:
    q = preparation_report(read_surface(shared_file("plu-1.plu"))).quantisation
    assert q["tie_fraction_y"] == pytest.approx(0.453, abs=0.005)
    assert q["quantum_m"] == pytest.approx(3.91e-9, rel=0.01)


def test_frt1_part_outline_is_refused(shared_file: Callable[[str], Path]) -> None:
    s = read_surface(shared_file("frt-1.frt"), fill_undefined=True)
    with pytest.raises(SurfaceError, match=r"not a rough surface .part outline: 30.6 %"):
        preparation_report(s)
    with pytest.raises(SurfaceError, match=r"30.6 % undefined points, more than the limit 5 %"):
        preparation_report(s, Preparation(rough_check=False))

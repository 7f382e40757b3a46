"""GW vs the elastic half-space at equal load on the shipped surface (issue 9 §5).

The evidence behind the fits' exclusion rule A_c/A_nom ≤ 0.1 (process/fit.py) and the
``beyond-non-interaction`` warning: the BEM/GW area ratio at equal load sits on a plateau at
low and middle loads and leaves it by more than 10 % only beyond the limit — on the shipped
surface (coarsened ×3 to keep this fast, 67 × 99 points, ~2 s) and on the grooved x3p-2
(coarsened ×4, 163 × 163 points, ~20 s, slow), where the plateau ends soonest.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from stochfric.contact.halfspace import compare_equal_load
from stochfric.contact.materials import get_material
from stochfric.contact.validity import MIN_CONTACTS, NON_INTERACTION_AREA_FRACTION
from stochfric.surface.io import default_surface_path, read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of


def test_area_ratio_plateau_ends_beyond_the_non_interaction_limit() -> None:
    pytest.importorskip("ContactMechanics")
    _fine, coarse = prepare(read_surface(default_surface_path()), Preparation(step=3))
    sm = summits_of(coarse)
    u = np.array([1.0, 1.5, 2.0, 2.5, 4.0, 6.0, 7.0]) * float(np.std(sm.heights_m))  # f: 0.004 ... 1.0
    cmp = compare_equal_load(coarse, sm, get_material("brake-pad"), u)
    frac = cmp.asperity.area_fraction
    ratio = cmp.area_ratio(1)
    np.testing.assert_allclose(cmp.halfspace[1].normal_force_n, cmp.asperity.normal_force_n, rtol=1e-6)
    # the plateau: loads with >= 10 contacts (MIN_CONTACTS) up to the limit
    inside = (cmp.asperity.n_contacts >= MIN_CONTACTS) & (frac <= NON_INTERACTION_AREA_FRACTION)
    outside = frac > 0.7
    assert inside.sum() >= 3 and outside.sum() >= 1
    plateau = float(np.median(ratio[inside]))
    # GW under-predicts the area (and mu) by a roughly constant factor inside ...
    assert 1.15 < plateau < 1.7
    assert np.all(np.abs(ratio[inside] / plateau - 1.0) < 0.10)
    # ... and departs from it by more than 10 % beyond the limit
    assert np.all(ratio[outside] / plateau < 0.9)
    # equal load: mu ratio = area ratio
    np.testing.assert_allclose(cmp.halfspace[1].mu / cmp.asperity.mu, ratio, rtol=1e-6)


SHARED = Path(__file__).resolve().parents[3] / "shared" / "data" / "topographies"


@pytest.mark.slow
def test_plateau_on_a_grooved_surface_holds_to_the_limit_and_ends_soon_after() -> None:
    pytest.importorskip("ContactMechanics")
    path = SHARED / "x3p-2.x3p"
    if not path.is_file():
        if os.environ.get("CI"):
            pytest.fail(f"{path} is missing (CI is set)")
        pytest.skip(f"{path} not available")
    _fine, coarse = prepare(read_surface(path), Preparation(step=4))
    sm = summits_of(coarse)
    u = np.array([1.5, 2.0, 2.5, 3.0, 4.0, 5.0]) * float(np.std(sm.heights_m))  # f: 0.0065 ... 0.42
    cmp = compare_equal_load(coarse, sm, get_material("dc04"), u)
    frac, ratio = cmp.asperity.area_fraction, cmp.area_ratio(1)
    inside = (cmp.asperity.n_contacts >= MIN_CONTACTS) & (frac <= NON_INTERACTION_AREA_FRACTION)
    assert inside.sum() >= 3 and (frac > 0.2).sum() >= 2
    plateau = float(np.median(ratio[inside]))
    assert np.all(np.abs(ratio[inside] / plateau - 1.0) < 0.10)
    assert np.all(ratio[frac > 0.2] / plateau < 0.9)

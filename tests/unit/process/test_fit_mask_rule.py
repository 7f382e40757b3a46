"""The fits' high-pressure exclusion rule (issue 9 §5): A_c/A_nom ≤ 0.1, the measured end of the
non-interaction range; its evidence is tests/reference/test_bem_equal_load.py."""

from __future__ import annotations

import numpy as np

from stochfric.contact.validity import NON_INTERACTION_AREA_FRACTION
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION, fit_mask


def test_default_is_the_measured_non_interaction_limit() -> None:
    assert DEFAULT_MAX_AREA_FRACTION == NON_INTERACTION_AREA_FRACTION == 0.1


def test_points_beyond_the_limit_are_excluded() -> None:
    frac = np.array([1e-3, 1e-2, 1.5e-2, 0.05, 0.1, 0.15, 0.8])
    p = np.arange(1.0, 8.0) * 1e6
    mask, note = fit_mask(frac, p)
    np.testing.assert_array_equal(mask, [True] * 5 + [False] * 2)
    assert note == ""
    # the former 1.5 % cut-off is still available explicitly (with the lowest-pressure fallback)
    mask, note = fit_mask(frac, p, max_area_fraction=0.012)
    np.testing.assert_array_equal(mask, [True] * 4 + [False] * 3)
    assert "lowest pressures" in note


def test_non_finite_and_non_positive_pressures_are_never_used() -> None:
    frac = np.array([1e-3, 2e-3, np.nan, 4e-3, 5e-3, 6e-3])
    p = np.array([1e5, -1.0, 3e5, 4e5, 5e5, 6e5])
    mask, _ = fit_mask(frac, p)
    np.testing.assert_array_equal(mask, [True, False, False, True, True, True])

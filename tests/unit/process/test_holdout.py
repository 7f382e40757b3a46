"""Out-of-sample validation of a surrogate model and the measured windows (issue 29, items 1, 2, 6)."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.ensemble import SurrogateOptions
from stochfric.process.holdout import (
    REQUIRED_SCATTER_RATIO,
    HoldoutValidation,
    holdout_validation,
    measured_windows,
    split_halves,
)
from stochfric.surface.io import Surface
from stochfric.surface.summits import summits_of
from synthetic_maps import as_surface, gaussian_heights, spiky_heights  # tests/synthetic_maps.py

MAT = get_material("brake-pad")


def _field(shape: tuple[int, int], corr: float, seed: int = 0) -> Surface:
    return as_surface(gaussian_heights(shape, corr, seed))


def _spiky(shape: tuple[int, int], seed: int = 0) -> Surface:
    return as_surface(spiky_heights(shape, seed))


def _u(s: Surface) -> np.ndarray:
    return default_approach_m(summits_of(s), num=5)


def test_halves_split_the_longer_side() -> None:
    a, b = split_halves(_field((101, 60), 1.0))
    assert a.nb_grid_pts == b.nb_grid_pts == (50, 60)
    np.testing.assert_array_equal(a.heights_m, _field((101, 60), 1.0).heights_m[:50])


def test_random_phases_of_a_strongly_non_gaussian_map_fail_out_of_sample() -> None:
    s = _spiky((400, 400))
    v = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=1, max_realizations=48)
    assert v.verdict == "not credible", v.reason
    assert v.max_abs_z > v.threshold and v.tiles >= 2 and v.held_out_windows == v.tiles**2
    assert any(t.quantity.startswith("summit") for t in v.tests if abs(t.z) > v.threshold)


@pytest.mark.parametrize("seed", [1, 2, 3])
def test_random_phases_of_a_gaussian_map_are_not_refused_and_the_verdict_does_not_move(seed: int) -> None:
    s = _field((400, 400), 1.5, seed=7)
    v = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=seed, max_realizations=48)
    assert v.verdict in ("credible", "undecided"), v.reason
    assert v.detectable_scatter_ratio > 1.0
    if v.verdict == "undecided":
        assert "scans" in v.reason or "surrogates" in v.reason


def test_a_test_that_cannot_see_a_factor_two_leaves_the_model_undecided_and_says_how_many_scans() -> None:
    s = _field((100, 100), 1.5, seed=3)  # few summits per half: 2 x 2 windows
    v = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=1, max_realizations=96)
    assert v.tiles == 2
    assert v.verdict == "undecided" and v.detectable_scatter_ratio > REQUIRED_SCATTER_RATIO, v.reason
    assert "scans of this size" in v.reason


def test_a_map_too_small_to_hold_out_half_is_reported_not_raised() -> None:
    u = HoldoutValidation.unavailable("phase", "too small")
    assert u.verdict == "undecided" and not u.credible and u.to_dict()["tests"] == []


def test_the_first_surrogates_do_not_depend_on_the_budget() -> None:
    """A validation that grew from 8 to R surrogates per fold equals one that made R at once: surrogate k of a
    fold is fixed by the seed, the fold and k (fold 2's depended on the budget before 2026-11-28)."""
    s = _field((300, 300), 1.5, seed=5)
    b = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=4, realizations=8,
                           max_realizations=64)
    c = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=4, realizations=b.realizations,
                           max_realizations=b.realizations)
    a = holdout_validation([s], MAT, _u(s), SurrogateOptions(method="phase"), seed=4, realizations=8,
                           max_realizations=8)
    assert b.tests == c.tests
    assert a.tests[0].held_out == b.tests[0].held_out  # the held-out data never depend on the seed


def test_measured_windows_rest_on_the_measurement_with_intervals() -> None:
    s = _field((320, 320), 1.5, seed=2)
    mw = measured_windows([s], MAT, _u(s), rule="thesis")
    assert mw is not None and mw.windows == mw.tiles**2 and mw.source == "measurement"
    assert np.all(mw.mu_mean_ci95[:, 0] <= mw.mu_mean) and np.all(mw.mu_mean <= mw.mu_mean_ci95[:, 1])
    assert np.all(mw.effective_windows <= mw.windows) and np.all(mw.effective_windows > 0)
    assert measured_windows([_field((40, 40), 1.5)], MAT, _u(_field((40, 40), 1.5)), rule="thesis") is None


def test_the_threshold_is_student_t_for_a_prediction_from_r_draws() -> None:
    """z = (x − mean)/(sd √(1 + 1/R)) of a new Gaussian value against R draws is Student-t with R − 1 degrees of
    freedom: the threshold is its Bonferroni quantile (3.84 for 60 tests and R = 24; the normal 3.34 had 3.4 times
    the tail).  Checked by simulation: 20,000 predictions at R = 24, the rate beyond the t quantile at 1 % is
    1 % within 3 binomial SE (the normal quantile's rate is 1.9 %)."""
    from scipy import stats as sps

    from stochfric.process.holdout import student_threshold

    assert student_threshold(0.05, 60, 24) == pytest.approx(float(sps.t.isf(0.05 / 120, 23)))
    assert 3.8 < student_threshold(0.05, 60, 24) < 3.9 and student_threshold(0.05, 60, 10**6) == pytest.approx(3.34,
                                                                                                              abs=0.01)
    rng = np.random.default_rng(5)
    draws = rng.standard_normal((20_000, 24))
    new = rng.standard_normal(20_000)
    z = (new - draws.mean(axis=1)) / (draws.std(axis=1, ddof=1) * np.sqrt(1 + 1 / 24))
    rate = float(np.mean(np.abs(z) > student_threshold(0.01, 1, 24)))
    assert abs(rate - 0.01) < 3 * np.sqrt(0.01 * 0.99 / 20_000), rate
    assert float(np.mean(np.abs(z) > 2.5758)) > 0.015  # the normal quantile: too thin a tail


def test_pooled_scans_get_their_own_surrogate_streams(monkeypatch: pytest.MonkeyPatch) -> None:
    """Surrogate k of each pooled scan comes from its own stream (they shared one before 2026-11-28, so the
    pooled statistics did not average and the test's power did not grow with the scans); scan 0 keeps the fold's
    stream, so a single scan's surrogates are unchanged."""
    from stochfric.surface import surrogates

    first: list[float] = []

    def recording(self, heights, rng, *, settings):  # type: ignore[no-untyped-def]
        first.append(float(rng.standard_normal()))
        return heights + 1e-9 * rng.standard_normal(heights.shape)

    monkeypatch.setattr(surrogates.PhaseSurrogate, "predictive_heights", recording)
    a, b = _field((300, 300), 1.5, seed=1), _field((300, 300), 1.5, seed=2)
    holdout_validation([a, b], MAT, _u(a), SurrogateOptions(method="phase"), seed=4, realizations=4,
                       max_realizations=4)
    pooled = first[:]
    first.clear()
    holdout_validation([a], MAT, _u(a), SurrogateOptions(method="phase"), seed=4, realizations=4, max_realizations=4)
    assert len(set(pooled)) == len(pooled) == 16  # 2 folds × 4 surrogates × 2 scans, all different
    assert pooled[0::2] == first  # scan 0's draws are the single scan's

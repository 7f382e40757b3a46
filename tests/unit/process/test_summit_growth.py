"""The summit check grows its own ensemble (issue 29 item 6): realisations are added (doubled) while its
Monte Carlo rank test is within its binomial error of the level (records from before the rank test: a quantity
within the decision margin of the limit), until the check decides or ``summit_max_realizations`` (default: by the
map's size, 4 R … 32 R) is spent; a grown ensemble equals a fresh one of that size, so the numbers do not depend on
how it grew."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.errors import AnalysisError
from stochfric.process import statistics
from stochfric.process.analysis_config import (
    SUMMIT_GROWTH,
    SUMMIT_MAX_GROWTH,
    SUMMIT_WORK_POINTS,
    AnalysisConfig,
    summit_budget,
)
from stochfric.process.checks import SurrogateCheck
from stochfric.process.ensemble import ensemble_contact
from stochfric.random import as_seed_sequence
from stochfric.surface.io import Surface, default_surface_path, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of

MAT = get_material("brake-pad")


@pytest.fixture(scope="module")
def coarse() -> Surface:
    _, c = prepare(read_surface(default_surface_path()))
    return c


def test_an_extended_ensemble_equals_a_fresh_one(coarse: Surface) -> None:
    u = default_approach_m(summits_of(coarse))[:4]
    small = ensemble_contact(coarse, MAT, u, realizations=3, seed=7, tiles=2)
    grown = ensemble_contact(coarse, MAT, u, realizations=6, seed=7, tiles=2, extend=small)
    fresh = ensemble_contact(coarse, MAT, u, realizations=6, seed=7, tiles=2)
    for name in ("contact_area_m2", "normal_force_n", "n_contacts", "summit_stats"):
        np.testing.assert_array_equal(getattr(grown, name), getattr(fresh, name), err_msg=name)
    assert grown.tile_samples is not None and fresh.tile_samples is not None
    np.testing.assert_array_equal(grown.tile_samples.normal_force_n, fresh.tile_samples.normal_force_n)
    assert grown.info["scan"] == fresh.info["scan"] and grown.info["realizations"] == 6
    with pytest.raises(AnalysisError, match="cannot be extended"):
        ensemble_contact(coarse, MAT, u, realizations=2, seed=7, extend=small)


def _run(coarse: Surface, monkeypatch: pytest.MonkeyPatch, undecided_below: int, **cfg: int) -> tuple[int, list[int]]:
    """Run the growth loop with a summit check that stays undecided below ``undecided_below`` realisations."""
    seen: list[int] = []
    looks_seen: list[int] = []

    def decided(self: SurrogateCheck, realizations: int, margin: float | None = None,
                looks: int = 1) -> tuple[list[str], list[str]]:
        seen.append(realizations)
        looks_seen.append(looks)
        return [], (["mu(u_0)"] if realizations < undecided_below else [])

    monkeypatch.setattr(SurrogateCheck, "decided", decided)
    u = default_approach_m(summits_of(coarse))[:3]
    config = AnalysisConfig(seed=3, **cfg).with_summit_budget(coarse.heights_m.size)  # as analyse resolves it
    opts = config.surrogate_options
    ens, _ = statistics._decided_ensemble([coarse], MAT, u, config, opts, None, as_seed_sequence(3), None, 1)
    assert set(looks_seen) == {config.summit_looks}
    return int(ens.contact_area_m2.shape[0]), seen


def test_grows_until_decided(coarse: Surface, monkeypatch: pytest.MonkeyPatch) -> None:
    n, seen = _run(coarse, monkeypatch, undecided_below=10, realizations=3, summit_max_realizations=24)
    assert seen == [3, 6, 12] and n == 12


def test_stops_at_the_budget(coarse: Surface, monkeypatch: pytest.MonkeyPatch) -> None:
    n, seen = _run(coarse, monkeypatch, undecided_below=10**6, realizations=3, summit_max_realizations=12)
    assert seen == [3, 6, 12] and n == 12
    n, seen = _run(coarse, monkeypatch, undecided_below=10**6, realizations=3)  # default on a small map: 32 R
    assert coarse.heights_m.size * 96 <= SUMMIT_WORK_POINTS
    assert seen == [3, 6, 12, 24, 48, 96] and n == 96
    n, seen = _run(coarse, monkeypatch, undecided_below=10**6, realizations=3, summit_max_realizations=3)
    assert seen == [3] and n == 3


def test_budget_below_the_realisations_is_refused() -> None:
    with pytest.raises(AnalysisError, match=r"summit_max_realizations \(5\) must be at least realizations"):
        AnalysisConfig(realizations=10, summit_max_realizations=5)
    assert AnalysisConfig(realizations=10).summit_max_realizations is None  # resolved for the map by analyse


def test_the_default_budget_is_a_bounded_amount_of_work() -> None:
    """32 R on small maps, 4 R on a thesis-size one, and in between the largest doubling whose ensemble holds at most
    SUMMIT_WORK_POINTS points; a budget the user gives is kept."""
    assert summit_budget(100, 200 * 296) == 3200  # the shipped al3d-1
    assert summit_budget(100, 512 * 512) == 3200
    assert summit_budget(100, 960 * 600) == 1600  # 3200 × 576,000 > 2³⁰ ≥ 1600 × 576,000
    assert summit_budget(100, 1700 * 1700) == 400
    assert summit_budget(7, 10**12) == 28
    for r, points in ((100, 59_200), (40, 576_000), (3, 10**7)):
        b = summit_budget(r, points)
        assert b % r == 0 and SUMMIT_GROWTH * r <= b <= SUMMIT_MAX_GROWTH * r
        assert b == SUMMIT_GROWTH * r or b * points <= SUMMIT_WORK_POINTS
        assert b == SUMMIT_MAX_GROWTH * r or 2 * b * points > SUMMIT_WORK_POINTS
    cfg = AnalysisConfig(realizations=100)
    assert cfg.with_summit_budget(59_200).summit_max_realizations == 3200
    assert cfg.with_summit_budget(59_200).summit_looks == 6
    assert AnalysisConfig(realizations=100, summit_max_realizations=400).with_summit_budget(59_200) \
        .summit_max_realizations == 400


def test_the_margin_counts_quantities_and_looks() -> None:
    """k = Φ⁻¹(1 − 0.05/(m L)): the family-wise bound on a decision another seed would reverse."""
    from scipy import stats as sps

    from stochfric.process.decisions import decision_margin, looks_within

    assert looks_within(3, 3) == 1 and looks_within(3, 5) == 1 and looks_within(3, 12) == 3
    assert looks_within(24, 96) == 3 and looks_within(40, 160) == 3
    for m, n in ((1, 1), (16, 1), (16, 3), (60, 3)):
        k = decision_margin(m, n)
        assert sps.norm.sf(k) * m * n == pytest.approx(0.05, rel=1e-9)
    assert decision_margin(16, 3) > decision_margin(16, 1) > 2.0
    with pytest.raises(AnalysisError, match="decision margin"):
        decision_margin(0, 1)
    # a check's default margin is the family's: a quantity 2.5 SE past the limit is decided with one
    # quantity, undecided among sixteen
    one = SurrogateCheck(measured={}, ensemble_mean={}, ensemble_std={}, z={"n": 3.5}, mu_measured=(),
                         mu_z=(), limit=3.0, credible=False, surrogate="phase", amplitude="raw",
                         z_se={"n": 0.2})
    assert one.decided(100) == (["n"], [])
    many = SurrogateCheck(measured={}, ensemble_mean={}, ensemble_std={},
                          z={"n": 3.5, **{f"q{i}": 0.0 for i in range(15)}},
                          mu_measured=(), mu_z=(), limit=3.0, credible=False, surrogate="phase", amplitude="raw",
                          z_se={"n": 0.2, **{f"q{i}": 0.1 for i in range(15)}})
    assert many.decided(100) == ([], ["n"])


def test_realisations_to_decide_scale_with_the_gap() -> None:
    """R' = R (k SE/δ)², rounded up to R·2^j: a quantity 0.4 beyond the limit with SE 0.3 at R = 100 and one
    quantity (k = Φ⁻¹(1 − 0.05) = 1.645) needs (1.645 × 0.3/0.4)² = 1.52 → 200; with SE 0.6, 6.1 → 800."""
    def check(se: float, z: float = 3.4) -> SurrogateCheck:
        return SurrogateCheck(measured={}, ensemble_mean={}, ensemble_std={}, z={"n": z}, mu_measured=(), mu_z=(),
                              limit=3.0, credible=False, surrogate="phase", amplitude="raw", z_se={"n": se})

    assert check(0.3).realizations_to_decide(100) == 200
    assert check(0.6).realizations_to_decide(100) == 800
    assert check(0.1).realizations_to_decide(100) is None  # decided already
    assert check(0.3, z=3.0).realizations_to_decide(100) is None  # on the limit: nothing decides it


def test_the_rank_decision_follows_the_binomial_error_of_its_p_value() -> None:
    """K of R draws reach the data: decided 'fail' when the Clopper–Pearson upper bound of p (confidence
    1 − 0.05/looks) lies below α (and the exact test rejects), 'pass' when the lower bound lies above it."""
    from scipy import stats as sps

    from stochfric.process.decisions import (
        critical_value,
        monte_carlo_draws_to_decide,
        monte_carlo_rank_decision,
    )

    assert monte_carlo_rank_decision(0, 100, 0.05, looks=3) == "fail"  # bound 1 − (0.05/3)^(1/100) = 0.040
    assert 1 - (0.05 / 3) ** (1 / 100) < 0.05 < 1 - (0.05 / 3) ** (1 / 48)
    assert monte_carlo_rank_decision(0, 48, 0.05, looks=3) == "undecided"
    assert monte_carlo_rank_decision(0, 12, 0.05) == "undecided"  # the exact test cannot reject with 12 draws
    assert monte_carlo_rank_decision(11, 100, 0.05, looks=3) == "pass"
    assert sps.beta.ppf(0.05 / 3, 11, 90) > 0.05 > sps.beta.ppf(0.05 / 3, 10, 91)
    assert monte_carlo_rank_decision(10, 100, 0.05, looks=3) == "undecided"
    need = monte_carlo_draws_to_decide(2, 100, 0.05, looks=3)
    assert need is not None and need > 100 and monte_carlo_draws_to_decide(0, 100, 0.05, looks=3) is None
    assert monte_carlo_draws_to_decide(5, 100, 0.05) is None  # p̂ = α: no affordable number decides it
    # the critical value: the exact test rejects iff (1 + K)/(R + 1) <= α iff T > the ⌊α(R + 1)⌋-th largest T_j
    t = np.arange(1.0, 100.0)  # 99 draws: ⌊0.05 × 100⌋ = 5 → the 5th largest, 95
    assert critical_value(t, 0.05) == 95.0
    assert critical_value(t[:10], 0.05) == 10.0  # too few to reject at all: the envelope


def test_the_summit_check_has_its_stated_false_alarm_rate() -> None:
    """Exactness of the rank test: a 'map' drawn from the same (skewed, correlated) distribution as its R
    realisations is called not credible with probability ≤ α at any R.  400 trials at R = 39, α = 0.05: the
    exact rate of (1 + K)/(R + 1) ≤ α is 2/40 = 0.05; the count must lie within the binomial 99.9 % range of 20."""
    from stochfric.process.checks import _max_abs, _pooled_z
    from stochfric.process.decisions import critical_value

    rng = np.random.default_rng(11)
    cov = np.full((6, 6), 0.6) + 0.4 * np.eye(6)
    rejections = 0
    for _ in range(400):
        rows = np.exp(rng.multivariate_normal(np.zeros(6), cov, size=40))  # row 0 is the "map"
        t = _max_abs(_pooled_z(rows))
        k = int(np.sum(t[1:] >= t[0]))
        rejections += (1 + k) / 40 <= 0.05
        assert (t[0] > critical_value(t[1:], 0.05)) == ((1 + k) / 40 <= 0.05)
    assert 7 <= rejections <= 36, rejections

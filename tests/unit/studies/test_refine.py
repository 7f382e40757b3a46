"""Closing the D_max(α) interval (issue 30): the refinement's decision rule on hand-made counts — which cells
get runs, how many, the stop rules, the budget — and its options (config and command line)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.errors import InputError
from stochfric.studies.config import DampingConfig
from stochfric.studies.errors import StudyConfigError
from stochfric.studies.refine import (
    BELOW_GRID,
    BEYOND_GRID,
    CLOSED,
    OPEN,
    RefineRule,
    fund,
    interval_width,
    refine_counts,
    runs_to_settle,
    wanted_runs,
    width_text,
)
from stochfric.studies.stats import clopper_pearson, risk_limit, runs_to_resolve

GRID = np.round(np.linspace(0.10, 0.20, 11), 6)  # step 0.01
#: a falling P(D): 1 … 0 through α = 10 % between D = 0.15 and 0.16
P_TRUE = np.array([1.0, 1.0, 0.9, 0.7, 0.4, 0.2, 0.06, 0.01, 0.0, 0.0, 0.0])


def _counts(p: np.ndarray, n: int) -> np.ndarray:
    return np.round(p * n)


def test_width_and_status_of_hand_made_counts() -> None:
    many = interval_width(GRID, _counts(P_TRUE, 400), 400, 0.1)
    r = risk_limit(GRID, _counts(P_TRUE, 400), 400, 0.1)
    assert (r.low, r.high) == (0.15, 0.15) and many.status == CLOSED and many.closed
    assert many.width_steps == 0 and many.straddling == () and many.runs_needed == 0
    # 10 runs: 0 of 10 does not exclude P ≥ 10 % → upper end at the grid end: open, every D above low straddles
    few = interval_width(GRID, _counts(P_TRUE, 10), 10, 0.1)
    low = risk_limit(GRID, _counts(P_TRUE, 10), 10, 0.1).low
    assert few.status == OPEN and not few.closed
    assert few.straddling == tuple(float(d) for d in GRID if d > low + 1e-9)
    assert few.width_steps == 10 - int(np.argmin(np.abs(GRID - low)))
    assert few.unestimated == 1  # 1 of 10 at D = 0.16: p̂ = α, no run count settles it at that fraction
    assert few.runs_needed == sum(runs_to_settle(round(P_TRUE[j] * 10), 10, 0.1) - 10 for j in range(11)
                                  if GRID[j] in few.straddling and j != 6)
    assert "1 of them at a fraction of 10 % not counted" in width_text(few)
    twenty = interval_width(GRID, _counts(P_TRUE, 20), 20, 0.1)
    assert twenty.status == OPEN and twenty.runs_needed == sum(
        runs_to_settle(round(P_TRUE[j] * 20), 20, 0.1) - 20 for j in range(11) if GRID[j] in twenty.straddling)
    # P ≥ α with confidence at the grid end: runs cannot help
    top = interval_width(GRID, np.full(11, 400.0), 400, 0.1)
    assert top.status == BEYOND_GRID and top.runs_needed == 0
    # P < α with confidence everywhere: below the grid start
    none = interval_width(GRID, np.zeros(11), 400, 0.1)
    assert none.status == BELOW_GRID and none.width_steps == 0
    # a wider target closes what a narrower one leaves open: 100 runs give [0.15, 0.16], one grid step
    k = _counts(P_TRUE, 100)
    assert (risk_limit(GRID, k, 100, 0.1).low, risk_limit(GRID, k, 100, 0.1).high) == (0.15, 0.16)
    w0, w1 = interval_width(GRID, k, 100, 0.1, target_steps=0), interval_width(GRID, k, 100, 0.1, target_steps=1)
    assert w0.width_steps == w1.width_steps == 1 and w0.straddling == w1.straddling == (0.16,)
    assert w0.status == OPEN and w1.status == CLOSED
    assert w0.runs_needed == runs_to_settle(6, 100, 0.1) - 100 and w1.runs_needed == 0
    assert "closed, 1 grid step" in width_text(w1) and "open" in width_text(w0) and "beyond" in width_text(top)


def test_only_straddling_cells_between_the_ends_get_runs() -> None:
    rule = RefineRule(risk_level=0.1)
    k, n = _counts(P_TRUE, 10), np.full(11, 10.0)
    k[1] = 1  # a cell *below* low whose band holds α: it moves neither end, so it gets no runs
    lo, hi = clopper_pearson(k[1], 10)
    assert lo < 0.1 <= hi
    low = risk_limit(GRID, k, n, 0.1).low
    want = wanted_runs(GRID, k, n, rule)
    assert list(want) == sorted(want, reverse=True)  # highest D first
    assert set(want) == {j for j in range(11) if GRID[j] > low + 1e-9}
    assert set(want.values()) == {runs_to_resolve(0.1)}  # 10 → max(2·10, 36) = 36
    # growth and cap
    assert rule.next_runs(36) == 72 and RefineRule(max_runs_per_cell=50).next_runs(36) == 50
    # a closed interval wants nothing; neither does one beyond or below the grid
    assert wanted_runs(GRID, _counts(P_TRUE, 400), 400, rule) == {}
    assert wanted_runs(GRID, np.full(11, 400.0), 400, rule) == {}
    assert wanted_runs(GRID, np.zeros(11), 400, rule) == {}
    # cells at max_runs_per_cell get no more
    assert wanted_runs(GRID, k, n, RefineRule(max_runs_per_cell=10)) == {}


def test_fund_respects_the_budget_round_robin() -> None:
    n = np.full((2, 11), 10)
    wanted = [{10: 36, 9: 36, 8: 36}, {10: 36, 9: 36}]
    assert fund(wanted, n, 10_000) == wanted
    got = fund(wanted, n, 70)  # 26 per cell: group 0 top, group 1 top, then 18 for group 0's second
    assert got == [{10: 36, 9: 28}, {10: 36}]
    assert sum(m - 10 for g in got for m in g.values()) == 70
    assert fund(wanted, n, 0) == [{}, {}]


def _bernoulli(p: np.ndarray, n_max: int = 5000, seed: int = 7) -> np.ndarray:
    """Run r of cell (g, j) sticks iff u[g, j, r] < p[g, j]: run-indexed numbers, as the study's seed rule."""
    u = np.random.default_rng(seed).random((*p.shape, n_max))
    return u < p[..., None]


@pytest.mark.parametrize("target", [1, 2])
def test_refined_counts_are_a_fixed_run_count_per_cell(target: int) -> None:
    p = np.stack([P_TRUE, np.clip(P_TRUE * 1.3, 0, 1)])
    runs = _bernoulli(p)
    n0 = np.full(p.shape, 10.0)
    calls: list[list[dict[int, int]]] = []

    def add_runs(granted: list[dict[int, int]]) -> tuple[np.ndarray, np.ndarray]:
        calls.append(granted)
        for g, cells in enumerate(granted):
            for j, m in cells.items():
                n[g, j] = m
        return np.array([[runs[g, j, : int(n[g, j])].sum() for j in range(11)] for g in range(2)]), n.copy()

    n = n0.copy()
    k0 = np.array([[runs[g, j, :10].sum() for j in range(11)] for g in range(2)], dtype=float)
    log = refine_counts(GRID, k0, n0, RefineRule(target_steps=target), 100_000, add_runs)
    assert log.stop == "done" and log.rounds == len(calls) > 0
    assert log.runs_added == int(np.sum(log.n - n0))
    for g in range(2):
        w = interval_width(GRID, log.k[g], log.n[g], 0.1, target_steps=target)
        assert w.status == CLOSED and w.width_steps <= target
        # the counts are those of the first n runs of each cell (a fixed-n study, cell by cell)
        assert all(log.k[g, j] == runs[g, j, : int(log.n[g, j])].sum() for j in range(11))


def test_stop_rules_budget_and_max_runs() -> None:
    p = np.array([P_TRUE])
    runs = _bernoulli(p)
    n = np.full((1, 11), 10.0)
    k0 = np.array([[runs[0, j, :10].sum() for j in range(11)]], dtype=float)

    def add_runs(granted: list[dict[int, int]]) -> tuple[np.ndarray, np.ndarray]:
        for j, m in granted[0].items():
            n[0, j] = m
        return np.array([[runs[0, j, : int(n[0, j])].sum() for j in range(11)]]), n.copy()

    log = refine_counts(GRID, k0, n.copy(), RefineRule(), 50, add_runs)
    assert log.stop == "budget" and log.runs_added == 50
    n[:] = 10.0
    log = refine_counts(GRID, k0, n.copy(), RefineRule(target_steps=0, max_runs_per_cell=20), 100_000, add_runs)
    assert log.stop == "max-runs" and log.n.max() == 20
    assert interval_width(GRID, log.k[0], log.n[0], 0.1, target_steps=0).status == OPEN


def test_runs_to_settle_is_the_first_settled_count() -> None:
    for k, n in ((0, 10), (2, 40), (3, 10), (5, 40), (30, 100)):
        m = runs_to_settle(k, n, 0.1)
        assert m is not None and m >= n
        p = k / n
        lo, hi = clopper_pearson(p * m, m)
        lo1, hi1 = clopper_pearson(p * (m - 1), m - 1)
        if p > 0.1:
            assert lo >= 0.1 and (m == n or lo1 < 0.1)
        else:
            assert hi < 0.1 and (m == n or hi1 >= 0.1)
    assert runs_to_settle(0, 10, 0.1) == runs_to_resolve(0.1)
    assert runs_to_settle(1, 10, 0.1) is None  # p̂ = α: no run count settles it


def test_resolved_reads_the_cells_above_low() -> None:
    k = _counts(P_TRUE, 10)
    uniform = risk_limit(GRID, k, 10, 0.1)
    assert not uniform.resolved and uniform.high_open  # 10 runs cannot resolve 10 %
    n = np.full(11, 10.0)
    n[GRID > uniform.low + 1e-9] = 36  # the cells that decide the upper end have R_α runs
    kk = np.where(n == 36, np.round(P_TRUE * 36), k)
    r = risk_limit(GRID, kk, n, 0.1)
    assert r.resolved and r.n_runs == 10 and not r.high_open
    assert risk_limit(GRID, k, np.full(11, 10), 0.1) == uniform  # same runs everywhere: as before
    # low at the grid end: P ≥ α there with confidence; open because of the grid, not the runs
    end = risk_limit(GRID, np.full(11, 5.0), 10, 0.1)
    assert end.low == end.high == GRID[-1] and end.high_open and end.resolved


def test_rule_and_config_refuse_bad_values() -> None:
    for bad in ({"risk_level": 0.0}, {"confidence": 1.0}, {"target_steps": -1}, {"max_runs_per_cell": 0},
                {"growth": 1.0}):
        with pytest.raises(InputError):
            RefineRule(**bad)  # type: ignore[arg-type]
    for bad in ({"run_budget": 0}, {"run_budget": -1}, {"max_runs_per_cell": 1}, {"target_steps": -1},
                {"refine_risk_level": math.nan}, {"refine_risk_level": 0.0}, {"refine_risk_level": 0.05},
                {"refine": True, "runs": 1000}, {"run_budget": "many"}, {"target_steps": 1.5}):
        with pytest.raises(StudyConfigError):
            DampingConfig(**bad)  # type: ignore[arg-type]
    cfg = DampingConfig(risk_levels="0.2,0.05")
    assert cfg.refined_risk_level == 0.2 and DampingConfig(refine_risk_level=0.01).refined_risk_level == 0.01


def test_the_refined_risk_level_is_in_the_checkpoint_key() -> None:
    """risk_levels are analysis only (not in the key), but with refine the refined α picks the runs."""
    assert DampingConfig(risk_levels="0.2,0.1").hash_config() == DampingConfig().hash_config()
    on = DampingConfig(refine=True).hash_config()
    assert on["refine"] is True and on["refine_risk_level"] == 0.1 and on["run_budget"] == 20_000
    assert DampingConfig(refine=True, risk_levels="0.2,0.1").hash_config() != on
    assert DampingConfig(refine=True, risk_levels="0.1,0.2").hash_config() == on


@pytest.mark.parametrize(("args", "needle"), [
    (["study", "damping", "--refine", "--run-budget", "0"], "--run-budget: Input should be greater than or equal to 1"),
    (["study", "damping", "--refine", "--run-budget", "-5"], "--run-budget: Input should be greater than or equal"),
    (["study", "damping", "--refine", "--run-budget", "nan"], "--run-budget: Input should be a valid integer"),
    (["study", "damping", "--refine", "--run-budget", "lots"], "--run-budget: Input should be a valid integer"),
    (["study", "damping", "--refine", "--max-runs-per-cell", "0"], "--max-runs-per-cell: Input should be greater"),
    (["study", "damping", "--refine", "--max-runs-per-cell", "1e3"], "--max-runs-per-cell: Input should be a valid"),
    (["study", "damping", "--target-steps", "-1"], "--target-steps: Input should be greater than or equal to 0"),
    (["study", "damping", "--target-steps", "two"], "--target-steps: Input should be a valid integer"),
    (["study", "damping", "--refine", "--refine-risk-level", "nan"], "--refine-risk-level: Input should be a finite"),
    (["study", "damping", "--refine", "--refine-risk-level", "0"], "--refine-risk-level: Input should be greater"),
    (["study", "damping", "--refine", "--refine-risk-level", "0.3"], "is not one of the risk levels"),
    (["study", "damping", "--run-budget", "100"], "--run-budget: it sets the refinement; give --refine"),
    (["reproduce", "--runs", "0"], "--runs: Input should be greater than or equal to 1"),
    (["reproduce", "--runs", "-2"], "--runs: Input should be greater than or equal to 1"),
    (["reproduce", "--runs", "nan"], "--runs: 'nan' is not a whole number"),
    (["reproduce", "--runs", "ten"], "--runs: 'ten' is not a whole number"),
    (["reproduce", "--refine", "--run-budget", "0"], "--run-budget: Input should be greater than or equal to 1"),
    (["reproduce", "--refine", "--run-budget", "x"], "--run-budget: 'x' is not a whole number"),
    (["reproduce", "--run-budget", "100"], "--run-budget: it bounds the refinement; give --refine"),
])
def test_cli_options_fail_in_one_line(args: list[str], needle: str, tmp_path: object) -> None:
    res = CliRunner().invoke(app, [*args, *(["--out", f"{tmp_path}/r"] if args[0] == "reproduce" else [])])
    assert res.exit_code == 2, res.output
    assert needle in res.output and "Traceback" not in res.output
    assert len(res.output.strip().splitlines()) == 1, res.output


def test_refined_study_resumes_from_its_checkpoints(tmp_path: object) -> None:
    """The refinement's tasks are checkpointed like the grid's (indices after the phase tasks): a rerun loads
    every task and gives the same counts; fixed-mode numbers other than P and D_max(α) are untouched."""
    from stochfric.studies.damping import damping_study

    cfg = DampingConfig(normal_forces=(5600.0,), damping_ratios="0.13:0.17:5", models=("deterministic", "white"),
                        runs=4, tau_end=20.0, phase_runs=1, refine=True, run_budget=300)
    first = damping_study(cfg, checkpoint=str(tmp_path))
    again = damping_study(cfg, checkpoint=str(tmp_path))
    assert again.stats.computed == 0 and again.stats.loaded == first.stats.computed > 4  # grid 2 + phase 2 + refine
    np.testing.assert_array_equal(first.dataset["refine_has_cycle"].values, again.dataset["refine_has_cycle"].values)
    r = first.summary.refinement
    assert r is not None and r.runs_added <= 300
    assert r.runs_per_cell["white"][0] == first.dataset["n_runs"].values[1, 0].tolist()
    fixed = damping_study(cfg.model_copy(update={"refine": False}))
    for name in ("stick_count_mean", "x_gh_mean", "phase_trajectory"):
        np.testing.assert_array_equal(first.dataset[name].values, fixed.dataset[name].values, err_msg=name)


def test_reproduce_configure_sets_runs_everywhere_and_refines_the_damping_studies() -> None:
    from stochfric.studies.reproduce import configure, plan

    thesis = plan(True)
    assert configure(thesis) == thesis  # the default: the thesis's fixed runs, unchanged
    out = configure(thesis, runs=7, refine=True, run_budget=500)
    assert all(c.runs == 7 for c in out)
    assert all(c.refine and c.run_budget == 500 for c in out if c.kind == "damping")
    assert [c.kind for c in out] == [c.kind for c in thesis]
    with pytest.raises(StudyConfigError, match="runs"):
        configure(thesis, runs=0)

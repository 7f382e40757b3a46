"""Closing the D_max(α) interval: adaptive refinement of P(stick-slip | D) (docs/studies.md, "Closing the
D_max(α) interval").

D_max(α) and its interval [low, high] are read off the per-D Clopper–Pearson bands of P(stick-slip | D)
(:func:`~stochfric.studies.stats.risk_limit`, unchanged here): low = the largest grid D whose lower bound is
≥ α, high = the largest grid D whose upper bound is ≥ α.  The interval's **width** is counted in grid steps,
index(high) − index(low) (a NaN low counts as the index −1, "below the grid start").  Its **status**
(:class:`IntervalWidth`):

* ``closed`` — low and high on the grid, high below the grid end, width ≤ ``target_steps``;
* ``open`` — anything else that more runs can change: some grid D in (low, high] *straddles* α (its band
  holds α: lower < α ≤ upper);
* ``beyond-grid`` — low is the grid end: P ≥ α there with confidence, D_max(α) lies at or beyond the grid
  end; runs cannot help, a longer grid can;
* ``below-grid`` — high is NaN: every grid D has P < α with confidence (D_max(α) below the grid start).

**Which cells get runs** (:func:`wanted_runs`): only the straddling grid D in (low, high] of an ``open``
interval.  A grid D at or below low moves neither end, and one above high has an upper bound < α already.
Nothing is assumed about the shape of P(D) (no monotonicity): every straddling D in the range is refined.
**How many**: a refined cell goes from n to min(``max_runs_per_cell``, max(⌈``growth``·n⌉, R_α)) runs,
R_α = :func:`~stochfric.studies.stats.runs_to_resolve` (α) — the fewest runs at which 0 sticking runs exclude
P ≥ α (36 for 10 % at 95 %), so a zero count settles in one round.  **Budget** (:func:`fund`): the runs added
(new minus old runs, summed) of all rounds stay within ``run_budget``; when a round asks for more than is
left, the cells are served round-robin over the groups (one group per model and force), the highest D of
each group first, the last one in part.  **Stop** (:func:`refine_counts`): no group asks for runs (each is
closed, beyond or below the grid, or its straddling cells are at ``max_runs_per_cell``), or the budget is
spent.

**The same numbers as a fixed run count.**  Run r of a cell draws from (seed, cell key, r), whatever the
run count (:mod:`~stochfric.studies.tasks`), so a cell refined to n runs holds exactly the runs 0 … n − 1
of a fixed-n study; the counts (k, n) of a refined grid are those of a fixed-run study in every cell, each
at its own n (tests/statistical/test_dmax_refinement.py).
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..errors import InputError
from .stats import _JsonRecord, clopper_pearson, risk_limit, runs_to_resolve

#: Statuses of a D_max(α) interval (module docstring).
CLOSED, OPEN, BEYOND_GRID, BELOW_GRID = "closed", "open", "beyond-grid", "below-grid"

#: Most total runs :func:`runs_to_settle` looks at before it calls a cell unsettled for good.
SETTLE_CAP = 10_000_000


@dataclass(frozen=True)
class RefineRule:
    """The refinement's rule (module docstring): ``risk_level`` α and ``confidence`` of the bands, the target
    width ``target_steps`` [grid steps], the most runs of one cell ``max_runs_per_cell``, the ``growth`` of a
    refined cell's runs per round."""

    risk_level: float = 0.1
    confidence: float = 0.95
    target_steps: int = 2
    max_runs_per_cell: int = 1000
    growth: float = 2.0

    def __post_init__(self) -> None:
        if not 0.0 < self.risk_level < 1.0 or not 0.0 < self.confidence < 1.0:
            raise InputError(f"risk level and confidence must lie in (0, 1), got {self.risk_level}, "
                             f"{self.confidence}")
        if self.target_steps < 0 or self.max_runs_per_cell < 1 or not self.growth > 1.0:
            raise InputError("target_steps must be >= 0, max_runs_per_cell >= 1 and growth > 1")

    def next_runs(self, n: int) -> int:
        """The runs of a cell refined from ``n``: min(max_runs_per_cell, max(⌈growth·n⌉, R_α))."""
        grown = max(math.ceil(self.growth * n), runs_to_resolve(self.risk_level, self.confidence))
        return int(min(self.max_runs_per_cell, grown))


@dataclass(frozen=True)
class IntervalWidth(_JsonRecord):
    """How far the D_max(α) interval at one force is closed (module docstring): ``width_steps`` =
    index(high) − index(low) [grid steps] (a NaN low counts as −1; with ``status`` ``beyond-grid`` or an upper
    end at the grid end it is a lower bound), ``target_steps``, ``status``, ``closed`` (status ``closed``),
    ``straddling`` — the grid D [-] in (low, high] whose band still holds α — and ``runs_needed``: for an
    ``open`` interval the runs those D would need in all, beyond the runs they have, to settle at their observed
    fractions (:func:`runs_to_settle`; more than closing needs when settling some of them suffices), else 0
    (closed, or runs cannot help); ``unestimated``: the straddling D left out of it, whose observed fraction is
    α itself (no run count settles it at that fraction) or needs more than :data:`SETTLE_CAP` runs."""

    risk_level: float
    width_steps: int
    target_steps: int
    status: str
    closed: bool
    straddling: tuple[float, ...]
    runs_needed: int
    unestimated: int = 0


def _index(damping: npt.NDArray[np.float64], value: float) -> int:
    """Grid index of ``value`` (−1 for NaN: below the grid start)."""
    return int(np.argmin(np.abs(damping - value))) if math.isfinite(value) else -1


def _state(damping: npt.ArrayLike, k: npt.ArrayLike, n: npt.ArrayLike, risk_level: float, confidence: float,
           target_steps: int) -> tuple[int, str, list[int]]:
    """(width in grid steps, status, straddling grid indices in (low, high]) of one force's counts."""
    d = np.asarray(damping, dtype=float)
    kk = np.asarray(k, dtype=float)
    nn = np.broadcast_to(np.asarray(n, dtype=float), kk.shape)
    r = risk_limit(d, kk, nn, risk_level, confidence)
    j_lo, j_hi = _index(d, r.low), _index(d, r.high)
    lo, hi = clopper_pearson(kk, np.where(nn > 0, nn, 1.0), confidence)
    straddle = [j for j in range(j_lo + 1, j_hi + 1) if nn[j] > 0 and lo[j] < risk_level <= hi[j]]
    if j_hi < 0:
        status = BELOW_GRID
    elif j_lo == d.size - 1:
        status = BEYOND_GRID
    elif j_lo >= 0 and not r.high_open and j_hi - j_lo <= target_steps:
        status = CLOSED
    else:
        status = OPEN
    return j_hi - j_lo, status, straddle


def runs_to_settle(k: float, n: float, risk_level: float, confidence: float = 0.95) -> int | None:
    """The fewest total runs m ≥ n at which a cell with the observed fraction p̂ = k/n (kept) has a band that
    excludes α: lower bound ≥ α if p̂ > α, upper bound < α if p̂ < α; ``None`` if p̂ = α or m > :data:`SETTLE_CAP`.
    An estimate of the runs a straddling cell still needs (the true P decides)."""
    if not n > 0:
        return None
    p = float(k) / float(n)
    if math.isclose(p, risk_level, rel_tol=1e-12, abs_tol=1e-15):
        return None

    def settled(m: int) -> bool:
        lo, hi = clopper_pearson(p * m, m, confidence)
        return bool(lo >= risk_level) if p > risk_level else bool(hi < risk_level)

    m = int(n)
    if settled(m):
        return m
    lo_m = m
    while not settled(m):
        lo_m, m = m, 2 * m
        if m > SETTLE_CAP:
            return None
    while m - lo_m > 1:  # settled(m), not settled(lo_m)
        mid = (lo_m + m) // 2
        lo_m, m = (lo_m, mid) if settled(mid) else (mid, m)
    return m


def interval_width(damping: npt.ArrayLike, k: npt.ArrayLike, n: npt.ArrayLike, risk_level: float,
                   confidence: float = 0.95, target_steps: int = 2) -> IntervalWidth:
    """The :class:`IntervalWidth` of one force's counts: ``k[j]`` of ``n[j]`` (or ``n``) runs stuck at
    ``damping[j]`` (increasing)."""
    d = np.asarray(damping, dtype=float)
    kk = np.asarray(k, dtype=float)
    nn = np.broadcast_to(np.asarray(n, dtype=float), kk.shape)
    width, status, straddle = _state(d, kk, nn, risk_level, confidence, target_steps)
    counted = straddle if status == OPEN else []
    settle = [runs_to_settle(kk[j], nn[j], risk_level, confidence) for j in counted]
    needed = sum(m - int(nn[j]) for j, m in zip(counted, settle, strict=True) if m is not None)
    return IntervalWidth(risk_level=float(risk_level), width_steps=int(width), target_steps=int(target_steps),
                         status=status, closed=status == CLOSED, straddling=tuple(float(d[j]) for j in straddle),
                         runs_needed=int(needed), unestimated=sum(m is None for m in settle))


def wanted_runs(damping: npt.ArrayLike, k: npt.ArrayLike, n: npt.ArrayLike, rule: RefineRule) -> dict[int, int]:
    """The cells of one force that want runs, ``{grid index: new total runs}`` (:meth:`RefineRule.next_runs`),
    highest D first: the straddling D of an ``open`` interval that are below ``max_runs_per_cell``."""
    nn = np.broadcast_to(np.asarray(n, dtype=float), np.shape(k))
    _, status, straddle = _state(damping, k, nn, rule.risk_level, rule.confidence, rule.target_steps)
    if status != OPEN:
        return {}
    return {j: rule.next_runs(int(nn[j])) for j in reversed(straddle) if nn[j] < rule.max_runs_per_cell}


def fund(wanted: Sequence[dict[int, int]], n: npt.ArrayLike, budget_left: int) -> list[dict[int, int]]:
    """The runs granted of ``wanted`` (one dict per group, :func:`wanted_runs`; ``n[group, cell]`` the runs
    now) within ``budget_left`` added runs: round-robin over the groups in the order of each group's dict,
    the last cell granted in part."""
    nn = np.asarray(n)
    out: list[dict[int, int]] = [{} for _ in wanted]
    left = int(budget_left)
    queues = [list(w.items()) for w in wanted]
    for rank in range(max((len(q) for q in queues), default=0)):
        for g, q in enumerate(queues):
            if rank >= len(q) or left <= 0:
                continue
            j, target = q[rank]
            add = min(target - int(nn[g, j]), left)
            if add > 0:
                out[g][j] = int(nn[g, j]) + add
                left -= add
    return out


@dataclass(frozen=True)
class RefineLog:
    """What :func:`refine_counts` did: the final counts ``k``, ``n`` ``[group, cell]``, ``runs_added`` (new
    minus old runs, summed over all rounds), ``rounds`` and the ``stop`` reason: ``done`` (no group asks for
    runs: each is closed, beyond or below the grid), ``budget`` (spent while a group asked for runs) or
    ``max-runs`` (open groups whose straddling cells are all at ``max_runs_per_cell``)."""

    k: npt.NDArray[np.float64]
    n: npt.NDArray[np.float64]
    runs_added: int
    rounds: int
    stop: str


#: ``add_runs(granted)`` of :func:`refine_counts`: run the cells to their new totals (``granted[group]``:
#: ``{cell: runs}``) and return the new counts ``(k, n)`` ``[group, cell]``.
AddRuns = Callable[[list[dict[int, int]]], tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]]


def refine_counts(damping: npt.ArrayLike, k: npt.ArrayLike, n: npt.ArrayLike, rule: RefineRule, budget: int,
                  add_runs: AddRuns) -> RefineLog:
    """Refine until no group asks for runs or ``budget`` added runs are spent (module docstring).

    ``k``, ``n``: runs with a cycle and runs ``[group, cell]`` over the grid ``damping`` (one group per model
    and force); ``add_runs`` runs the granted cells and returns the new counts."""
    kk = np.array(k, dtype=float, ndmin=2)
    nn = np.array(np.broadcast_to(np.asarray(n, dtype=float), kk.shape), ndmin=2)
    added = rounds = 0
    while True:
        wanted = [wanted_runs(damping, kk[g], nn[g], rule) for g in range(kk.shape[0])]
        if not any(wanted):
            opened = any(_state(damping, kk[g], nn[g], rule.risk_level, rule.confidence, rule.target_steps)[1]
                         == OPEN for g in range(kk.shape[0]))
            return RefineLog(kk, nn, added, rounds, "max-runs" if opened else "done")
        granted = fund(wanted, nn, budget - added)
        if not any(granted):
            return RefineLog(kk, nn, added, rounds, "budget")
        before = nn.copy()
        kk, nn = (np.array(a, dtype=float) for a in add_runs(granted))
        for g, cells in enumerate(granted):
            for j, m in cells.items():
                if nn[g, j] != m:
                    raise RuntimeError(f"add_runs gave {nn[g, j]:g} runs for cell ({g}, {j}), {m} asked")
        added += int(np.sum(nn - before))
        rounds += 1


def width_text(w: IntervalWidth) -> str:
    """One phrase on how far a D_max(α) interval is closed: "closed, 2 grid steps (target ≤ 2)", "open, 7 grid
    steps: 3 grid D still straddle 10 % (≈ 1200 more runs)", or why runs cannot close it (beyond or below the
    grid)."""
    pct = f"{100 * w.risk_level:g} %"
    steps = f"{w.width_steps} grid step{'' if w.width_steps == 1 else 's'}"
    if w.status == CLOSED:
        return f"closed, {steps} (target ≤ {w.target_steps})"
    if w.status == BEYOND_GRID:
        return f"P ≥ {pct} at the grid end with confidence: D_max({pct}) lies at or beyond it (extend the grid)"
    if w.status == BELOW_GRID:
        return f"P < {pct} at every grid D with confidence: D_max({pct}) lies below the grid start (extend the grid)"
    need = f"≈ {w.runs_needed} more runs to settle them"
    if w.unestimated:
        need += f", {w.unestimated} of them at a fraction of {pct} not counted"
    return (f"open, {steps} (target ≤ {w.target_steps}): {len(w.straddling)} grid D still straddle {pct} "
            f"({need})")

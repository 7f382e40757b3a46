"""Damping study (method §6.2; thesis 4.2.2 brake, 4.3.2 sheet; Fig. 4.23–4.29, 4.54–4.60).

Grid D × N, three models.  Per cell: deterministic X_gh and M_d; stochastic (R runs)
E[X_gh], σ(X_gh), E[M_s]; M_diff = M_d − E[M_s] (4.41), M_quot = E[M_s]/M_d (4.42).

**How D_max is read off** (method §7.9, our choice, ``docs/studies.md``):

* a run *has a stick-slip cycle* when it has at least one slip→stick transition with
  τ ∈ (w τ_end, τ_end] (the *stick window*, default w = 0.5: after the transient);
* D_max^d(N) = the largest grid D at which the deterministic run has a cycle; the true
  boundary lies in [D_max^d, next grid D);
* P(stick-slip | D) = probability of a cycle, estimated per grid D by k/R with a two-sided
  Clopper–Pearson interval at ``confidence`` (``stick_probability``, ``_low``, ``_high``);
* **D_max(α)** = the largest grid D with P(stick-slip | D) ≥ α, for each risk level α
  of ``risk_levels`` (default 10 %, 1 %), with the interval [low, high] read off the per-D bands
  (:func:`~stochfric.studies.stats.risk_limit`): low = the largest D whose lower bound is ≥ α,
  high = the largest D whose upper bound is ≥ α; high at the grid end = open ("≥ grid end"),
  which is always so when R runs cannot resolve α (0 of R sticking does not exclude P ≥ α);
* the thesis's D_max^s is kept as ``d_max_sample_extreme`` = the largest grid D at which *any* of the
  R runs stuck — a sample extreme that grows with R (it estimates D_max(α) for α → 0, at no stated
  risk); its bar [D_max^s, D_hi]: D_hi is the first grid D above it at which the one-sided upper bound
  on P pooled over the zero-count grid points in (D_max^s, D] (runs taken as independent across D)
  falls below ``p_detect``; ``None`` if the grid ends first;
* ``refine``: runs are added where the band of P still holds α between the ends of the D_max(α) interval of
  ``refine_risk_level``, until it is at most ``target_steps`` grid steps wide or ``run_budget`` runs are added
  (:mod:`~stochfric.studies.refine`, :meth:`DampingStudy.refine`); P, its bands and D_max(α) then count every
  run of a cell (``n_runs``), everything else the grid's ``runs``; ``d_max_risk_width`` says per force how far
  each interval is closed (with or without ``refine``);
* D_H(N) from the linearisation (:func:`~stochfric.oscillator.reference.hopf_damping`);
  the Hopf bifurcation is subcritical, so D_max^d ≥ D_H (stick-slip from a large start).

X_gh maps use the thesis convention (0 where no stick occurs, ``x_gh_mean``) and NaN-aware
variants (``x_gh_mean_nan``).  Initial state: sticking at the origin, (0, γ0), unless ``x0``.

**Phase diagrams over D at one force** (thesis Fig. 4.22/4.24/4.27 brake N = 5600 N,
4.53/4.55/4.58 sheet N = 1400 N): after the grid, one extra task per model runs the phase
force (``phase_force_n``; default the preset's damping-study force if it is one of the grid
forces, else the middle grid force) at a few D (``phase_damping``) and keeps the decimated
trajectories (every ``save_every``-th step) of ``phase_runs`` runs (deterministic: one).
Default D (:func:`auto_phase_damping`): 5 values evenly spaced from the lowest grid D to
D_top, snapped to the grid, where D_top is the first grid D above the largest D_max (of any
model) at the phase force — so the curves go from a large stick-slip cycle to decay onto
steady sliding (the grid's largest D if no grid D lies above); D_max here is the sample extreme.  Only these tasks keep
trajectories; they use task indices after the grid tasks (own seeds, checkpointed too).
"""

from __future__ import annotations

import contextlib
import math
import warnings
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from ..oscillator.options import Model
from ..oscillator.reference import hopf_damping
from ..random import BOOTSTRAP_KEY, child_generator
from .base import Progress, Study, StudyResult, sweep
from .config import DampingConfig
from .errors import StudyError
from .executors import Executor, SweepStats
from .grids import window_mask
from .refine import IntervalWidth, RefineRule, interval_width, refine_counts
from .stats import clopper_pearson, pooled_bootstrap_se, risk_limit, runs_to_resolve
from .summary import OPTIONAL, StudySummary, Table
from .tasks import TaskSpec, runs_for, task_for


def d_max_deterministic(damping: npt.ArrayLike, has_cycle: npt.ArrayLike) -> float:
    """Largest D with a cycle (NaN if none)."""
    d = np.asarray(damping, dtype=float)
    h = np.asarray(has_cycle, dtype=bool)
    return float(d[h].max()) if h.any() else math.nan


def d_max_stochastic(
    damping: npt.ArrayLike, k: npt.ArrayLike, n: int, *, confidence: float = 0.95, p_detect: float = 0.1
) -> tuple[float, float, float]:
    """(D_max^s, low, high) of the sample extreme: see the module docstring; NaN where undefined.

    ``high`` pools the zero-count grid points above D_max^s: after m of them (m·n runs,
    no cycle) the one-sided bound is 1 − (1 − confidence)^{1/(m n)}; ``high`` is the first
    D where that is < ``p_detect`` (NaN when the grid ends before).
    """
    d = np.asarray(damping, dtype=float)
    kk = np.asarray(k, dtype=float)
    hit = kk > 0
    if not hit.any():
        return math.nan, math.nan, math.nan
    j = int(np.max(np.nonzero(hit)[0]))
    point = float(d[j])
    high = math.nan
    for m, jj in enumerate(range(j + 1, d.size), start=1):
        bound = 1.0 - (1.0 - confidence) ** (1.0 / (m * n))
        if bound < p_detect:
            high = float(d[jj])
            break
    return point, point, high


#: number of D values of the automatic phase-diagram choice
N_PHASE_DAMPING = 5


def default_phase_force(preset_force: float, forces: tuple[float, ...]) -> float:
    """The preset's damping-study force if it is one of ``forces``, else the middle force."""
    if any(math.isclose(preset_force, f, rel_tol=1e-12) for f in forces):
        return float(preset_force)
    return float(forces[(len(forces) - 1) // 2])


def auto_phase_damping(damping: npt.ArrayLike, d_max: npt.ArrayLike, n: int = N_PHASE_DAMPING) -> tuple[float, ...]:
    """Default D of the phase diagrams: ``n`` values evenly spaced from the lowest grid D to
    D_top, snapped to the grid (duplicates dropped), increasing.

    D_top = the first grid D above max(``d_max``) (the largest D with a cycle over the models at
    the phase force), or the largest grid D if none lies above or no model has a cycle.
    """
    grid = np.asarray(damping, dtype=float)
    dm = np.asarray(d_max, dtype=float)
    dm = dm[np.isfinite(dm)]
    top = float(grid[-1])
    if dm.size:
        above = grid[grid > float(dm.max()) + 1e-12]
        if above.size:
            top = float(above[0])
    targets = np.linspace(float(grid[0]), top, n) if n > 1 else np.array([top])
    picked = sorted({float(grid[int(np.argmin(np.abs(grid - t)))]) for t in targets})
    return tuple(picked)


Array = npt.NDArray[np.float64]


@dataclass(frozen=True)
class DMaxRisk:
    """D_max(α) at one normal force and risk level α (``risk_level``, a probability): ``value`` [-] the
    largest grid D with estimated P(stick-slip) ≥ α, ``interval`` (low, high) [-] from the per-D
    Clopper–Pearson bands (:class:`~stochfric.studies.stats.RiskLimit`); ``None``: below the grid start.
    ``high_open``: the upper end is the grid end; ``resolved``: the runs can resolve α at all."""

    risk_level: float
    value: float | None
    interval: tuple[float | None, float | None]
    high_open: bool
    resolved: bool


@dataclass(frozen=True)
class SampleExtreme:
    """The thesis's D_max^s at one normal force: ``value`` [-] the largest grid D at which any run stuck
    (grows with the runs), ``interval`` (D_max^s, D_hi) [-]; ``None``: undefined (module docstring)."""

    value: float | None
    interval: tuple[float | None, float | None]


@dataclass(frozen=True)
class StickProbability:
    """P(stick-slip | D) of one model, tables ``[normal_force_n][damping_ratio]`` [-]: the fraction of runs
    with a slip→stick transition in the stick window (``value``) and its two-sided Clopper–Pearson bounds."""

    value: Table
    low: Table
    high: Table


@dataclass(frozen=True)
class PhaseSummary:
    """The phase diagrams over D: at ``normal_force_n`` [N], the D in ``damping_ratio`` [-] chosen by
    ``damping_rule`` (``auto`` | ``given``); runs kept per model, ``save_every`` (steps between saved
    samples) and per model and D the fraction of runs with a cycle after the transient."""

    normal_force_n: float
    damping_ratio: list[float]
    damping_rule: str
    runs: dict[str, int]
    save_every: int
    has_cycle_fraction: dict[str, list[float]]


@dataclass(frozen=True)
class RefinementSummary:
    """What the adaptive refinement did (:mod:`~stochfric.studies.refine`): the α it closes
    (``risk_level``), ``target_steps`` [grid steps], ``max_runs_per_cell``, ``run_budget`` and the runs it
    added (``runs_added``, new minus old runs), ``rounds``, why it stopped (``stop``: ``done`` | ``budget`` |
    ``max-runs``) and the runs behind P(stick-slip | D) per stochastic model, ``runs_per_cell`` ``[N][D]``."""

    risk_level: float
    target_steps: int
    max_runs_per_cell: int
    run_budget: int
    runs_added: int
    rounds: int
    stop: str
    runs_per_cell: dict[str, list[list[int]]]


@dataclass(frozen=True, kw_only=True)
class DampingSummary(StudySummary, kind="damping"):
    """The damping study's summary (module docstring).

    Grid: ``normal_force_n`` [N], ``damping_ratio`` [-]; ``d_hopf`` [-] per force; σ_ζ, σ_ζ,eff [-] per
    force; ``stick_window`` (τ from, τ to), dimensionless.  Per stochastic model and force:
    ``d_max_risk`` (one :class:`DMaxRisk` per risk level of ``risk_levels``) and ``d_max_sample_extreme``;
    with the deterministic model ``d_max_deterministic`` [-] per force (``None``: below the grid start)
    and the next grid D above it.  Per model: ``stick_probability`` and the tables ``[N][D]`` of E[M]
    (``stick_count_mean``), its SE and the bootstrap SEs of E[X_gh] and σ(X_gh) [-]; ``m_diff``
    (M_d − E[M_s], eq. 4.41) per stochastic model where the deterministic model ran; ``phase`` where
    phase diagrams were drawn.  ``d_max_risk_width``: per stochastic model, force and risk level how far
    the D_max(α) interval is closed (:class:`~stochfric.studies.refine.IntervalWidth`, closed at
    ``target_steps`` grid steps); ``refinement`` where the study refined adaptively (``refine``).
    """

    normal_force_n: list[float]
    damping_ratio: list[float]
    d_hopf: list[float]
    sigma_zeta: list[float]
    sigma_zeta_effective: list[float]
    stick_window: tuple[float, float]
    confidence: float
    p_detect: float
    risk_levels: list[float]
    risk_levels_runs_to_resolve: list[int]
    stick_probability_interval: str
    d_max_deterministic: list[float | None] | None = field(default=None, metadata=OPTIONAL)
    d_max_deterministic_next_grid: list[float | None] | None = field(default=None, metadata=OPTIONAL)
    d_max_risk: dict[str, list[list[DMaxRisk]]]
    d_max_sample_extreme: dict[str, list[SampleExtreme]]
    stick_probability: dict[str, StickProbability]
    stick_count_mean: dict[str, Table]
    stick_count_mean_se: dict[str, Table]
    x_gh_mean_se: dict[str, Table]
    x_gh_std_se: dict[str, Table]
    m_diff: dict[str, Table] | None = field(default=None, metadata=OPTIONAL)
    phase: PhaseSummary | None = field(default=None, metadata=OPTIONAL)
    d_max_risk_width: dict[str, list[list[IntervalWidth]]] = field(default_factory=dict)
    refinement: RefinementSummary | None = field(default=None, metadata=OPTIONAL)
    checkpoint_hash: str | None = None


@dataclass(frozen=True)
class _Cycles:
    """Per-run arrays of the grid ``[model, N, D, run(, event)]`` (NaN: a run not done)."""

    stick_count: Array
    passes_without_stick: Array
    x_gh: Array
    t_gh: Array
    in_window: npt.NDArray[np.bool_]
    has_cycle: Array
    window_count: Array
    n_runs: npt.NDArray[np.int64]
    k: Array  #: runs with a cycle, per cell


def sample_extremes(models: Sequence[str], damping: Array, k: Array, n_runs: npt.NDArray[np.int64], *,
                    confidence: float, p_detect: float) -> tuple[Array, Array, Array]:
    """D_max^s with its interval per model and force ``[model, N]`` (deterministic: D_max^d and the next
    grid D), from the runs with a cycle ``k[model, N, D]`` of ``n_runs``."""
    nm, nn = k.shape[:2]
    dmax, dlo, dhi = (np.full((nm, nn), np.nan) for _ in range(3))
    for mi, model in enumerate(models):
        for ni in range(nn):
            if model == Model.DETERMINISTIC:
                v = d_max_deterministic(damping, k[mi, ni] > 0)
                dmax[mi, ni] = v
                dlo[mi, ni] = v
                above = damping[damping > v] if math.isfinite(v) else damping
                dhi[mi, ni] = float(above.min()) if above.size else math.nan
            else:
                dmax[mi, ni], dlo[mi, ni], dhi[mi, ni] = d_max_stochastic(
                    damping, k[mi, ni], int(n_runs[mi, ni, 0]), confidence=confidence, p_detect=p_detect)
    return dmax, dlo, dhi


def risk_limits(models: Sequence[str], damping: Array, k: Array, n_runs: npt.NDArray[Any], d_max: Array,
                risk_levels: Sequence[float], confidence: float) -> dict[str, npt.NDArray[Any]]:
    """D_max(α) ``[model, N, risk level]``: ``value``, ``low``, ``high``, ``high_open``, ``resolved``
    (:func:`~stochfric.studies.stats.risk_limit`; deterministic: D_max^d, exact)."""
    nm, nn, na = len(models), k.shape[1], len(risk_levels)
    rk: dict[str, npt.NDArray[Any]] = {f: np.full((nm, nn, na), np.nan) for f in ("value", "low", "high")}
    rk["high_open"] = np.zeros((nm, nn, na), dtype=np.int8)
    rk["resolved"] = np.ones((nm, nn, na), dtype=np.int8)
    for mi, model in enumerate(models):
        for ni in range(nn):
            for ai, a in enumerate(risk_levels):
                if model == Model.DETERMINISTIC:
                    for f in ("value", "low", "high"):
                        rk[f][mi, ni, ai] = d_max[mi, ni]
                    rk["high_open"][mi, ni, ai] = int(math.isfinite(d_max[mi, ni])
                                                      and d_max[mi, ni] >= damping[-1] - 1e-12)
                    continue
                r = risk_limit(damping, k[mi, ni], n_runs[mi, ni], a, confidence)
                rk["value"][mi, ni, ai], rk["low"][mi, ni, ai], rk["high"][mi, ni, ai] = r.value, r.low, r.high
                rk["high_open"][mi, ni, ai], rk["resolved"][mi, ni, ai] = int(r.high_open), int(r.resolved)
    return rk


def risk_widths(models: Sequence[str], damping: Array, k: Array, n: npt.NDArray[Any], risk_levels: Sequence[float],
                confidence: float, target_steps: int) -> dict[str, list[list[IntervalWidth]]]:
    """How far each D_max(α) interval is closed, per stochastic model ``[N][risk level]``
    (:func:`~stochfric.studies.refine.interval_width` of the counts ``k``, ``n`` ``[model, N, D]``)."""
    return {m: [[interval_width(damping, k[mi, ni], n[mi, ni], a, confidence, target_steps) for a in risk_levels]
                for ni in range(k.shape[1])]
            for mi, m in enumerate(models) if m != Model.DETERMINISTIC}


def _width_variables(models: Sequence[str], widths: dict[str, list[list[IntervalWidth]]], shape: tuple[int, ...]
                     ) -> dict[str, Any]:
    """The widths of :func:`risk_widths` as variables ``[model, N, risk level]`` (deterministic: NaN, status
    ``exact``)."""
    width, needed = np.full(shape, np.nan), np.full(shape, np.nan)
    status = np.full(shape, "exact", dtype=object)
    for m, per_force in widths.items():
        mi = list(models).index(m)
        for ni, row in enumerate(per_force):
            for ai, w in enumerate(row):
                width[mi, ni, ai], status[mi, ni, ai] = w.width_steps, w.status
                needed[mi, ni, ai] = w.runs_needed
    return {
        "d_max_risk_width": (_DIMS_RISK, width, {
            "units": "1", "long_name": "width of the D_max(alpha) interval in grid steps, index(high) - index(low) "
                                       "(low below the grid start: index -1)"}),
        "d_max_risk_status": (_DIMS_RISK, status.astype(str), {
            "long_name": "closed | open | beyond-grid | below-grid (docs/studies.md, 'Closing the D_max(alpha) "
                         "interval'); deterministic: exact"}),
        "d_max_risk_runs_needed": (_DIMS_RISK, needed, {
            "units": "1", "long_name": "estimated further runs of the grid D whose band still holds alpha between "
                                       "the ends, at their observed fractions (those at alpha itself left out)"}),
    }


@contextlib.contextmanager
def _quiet_nan_statistics() -> Iterator[None]:
    """Silence the all-NaN warnings of the per-cell statistics (cells without events are NaN)."""
    with np.errstate(invalid="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        yield


def cell_statistics(c: _Cycles, seed: int) -> dict[str, Array]:
    """Per cell ``[model, N, D]``: E[X_gh], σ(X_gh) in the window (NaN where undefined, and the thesis's 0),
    E[M] with its SE (s/√R, runs independent) and the bootstrap SEs of E[X_gh], σ(X_gh) (runs resampled)."""
    xw = np.where(c.in_window, c.x_gh, np.nan)
    with _quiet_nan_statistics():
        xmean_nan = np.nanmean(xw, axis=(-2, -1))
        xstd_nan = np.nanstd(xw, axis=(-2, -1), ddof=1)
        m_mean = np.nanmean(c.stick_count, axis=-1)
    with _quiet_nan_statistics():
        m_se = np.nanstd(c.stick_count, axis=-1, ddof=1) / np.sqrt(c.n_runs)
    x_se_mean, x_se_std = pooled_bootstrap_se(xw, n_boot=200, rng=child_generator(seed, BOOTSTRAP_KEY))
    return {"x_gh_mean_nan": xmean_nan, "x_gh_std_nan": xstd_nan, "stick_count_mean": m_mean,
            "stick_count_mean_se": m_se, "x_gh_mean_se": x_se_mean, "x_gh_std_se": x_se_std,
            "x_gh_mean": np.where(np.isfinite(xmean_nan), xmean_nan, 0.0),
            "x_gh_std": np.where(np.isfinite(xstd_nan), xstd_nan, 0.0)}


_DIMS5 = ("model", "normal_force_n", "damping_ratio", "run", "event")
_DIMS_LIMIT = ("model", "normal_force_n")
_DIMS_RISK = ("model", "normal_force_n", "risk_level")


def _run_variables(c: _Cycles, k: Array, n: npt.NDArray[Any], confidence: float) -> dict[str, Any]:
    """The per-run and per-cell cycle variables: X_gh, τ_gh, M, cycles, P(stick-slip | D) = k/n with its bands
    (``k`` of ``n`` runs with a cycle per cell: the grid's runs, or all runs of a refined cell)."""
    dims4, dims3 = _DIMS5[:4], _DIMS5[:3]
    bound = f"of P(stick-slip | D) at confidence {confidence:g}"
    prob = k / n
    lo, hi = clopper_pearson(k, n, confidence)
    return {
        "x_gh": (_DIMS5, c.x_gh, {"units": "1", "long_name": "slip->stick position X_gh = y/L"}),
        "t_gh": (_DIMS5, c.t_gh, {"units": "1", "long_name": "tau of slip->stick"}),
        "stick_count": (dims4, c.stick_count, {"units": "1",
                                               "long_name": "M: slip->stick transitions in (0, tau_end]"}),
        "stick_count_window": (dims4, c.window_count, {"units": "1", "long_name": "transitions in the stick window"}),
        "n_belt_speed_without_stick": (dims4, c.passes_without_stick, {"units": "1"}),
        "has_cycle": (dims4, c.has_cycle, {"units": "1",
                                           "long_name": "1 if a slip->stick transition in the stick window"}),
        "n_runs": (dims3, n, {"units": "1", "long_name": "runs behind P(stick-slip | D) (refined cells: all their "
                                                         "runs; the per-run variables hold the first runs)"}),
        "n_stuck": (dims3, k, {"units": "1", "long_name": "runs with a slip->stick transition in the stick window"}),
        "stick_probability": (dims3, prob, {"units": "1", "long_name": "P(stick-slip | D): fraction of runs with "
                                            "a slip->stick transition in the stick window"}),
        "stick_probability_low": (dims3, lo, {"units": "1",
                                              "long_name": f"two-sided Clopper-Pearson lower bound {bound}"}),
        "stick_probability_high": (dims3, hi, {"units": "1",
                                               "long_name": f"two-sided Clopper-Pearson upper bound {bound}"}),
    }


def _statistics_variables(st: dict[str, Array]) -> dict[str, Any]:
    """The per-cell statistics of :func:`cell_statistics` as dataset variables ``[model, N, D]``."""
    names = {
        "stick_count_mean": "E[M] (deterministic: M_d)",
        "stick_count_mean_se": "standard error of E[M] (runs independent)",
        "x_gh_mean_se": "bootstrap SE of E[X_gh] (NaN: undefined)",
        "x_gh_std_se": "bootstrap SE of sigma(X_gh)",
        "x_gh_mean": "E[X_gh] in the window, 0 where no stick (thesis)",
        "x_gh_std": "sigma(X_gh) in the window, 0 where none",
        "x_gh_mean_nan": "E[X_gh] in the window, NaN where none",
        "x_gh_std_nan": "sigma(X_gh), NaN where undefined",
    }
    return {k: (_DIMS5[:3], st[k], {"units": "1", "long_name": v}) for k, v in names.items()}


def _limit_variables(sig: Array, extreme: tuple[Array, Array, Array], rk: dict[str, npt.NDArray[Any]]
                     ) -> dict[str, Any]:
    """σ_ζ, the sample extreme D_max^s with its interval ``[model, N]`` and D_max(α) ``[model, N, α]``."""
    dmax, dlo, dhi = extreme
    return {
        "sigma_zeta": (_DIMS_LIMIT, sig, {"units": "1", "long_name": "white-noise intensity"}),
        "d_max_sample_extreme": (_DIMS_LIMIT, dmax, {
            "units": "1", "long_name": "largest D at which any of the R runs stuck (grows with R; thesis D_max^s; "
                                       "deterministic: D_max^d)"}),
        "d_max_sample_extreme_low": (_DIMS_LIMIT, dlo, {"units": "1"}),
        "d_max_sample_extreme_high": (_DIMS_LIMIT, dhi, {
            "units": "1", "long_name": "deterministic: next grid D; stochastic: D_hi (pooled bound < p_detect)"}),
        "d_max_risk": (_DIMS_RISK, rk["value"], {
            "units": "1", "long_name": "D_max(alpha): largest grid D with estimated P(stick-slip) >= alpha "
                                       "(deterministic: D_max^d; NaN: below the grid start)"}),
        "d_max_risk_low": (_DIMS_RISK, rk["low"], {
            "units": "1", "long_name": "lower end of D_max(alpha): largest grid D whose Clopper-Pearson lower "
                                       "bound is >= alpha (NaN: none, below the grid start)"}),
        "d_max_risk_high": (_DIMS_RISK, rk["high"], {
            "units": "1", "long_name": "upper end of D_max(alpha): largest grid D whose Clopper-Pearson upper "
                                       "bound is >= alpha (open when d_max_risk_high_open)"}),
        "d_max_risk_high_open": (_DIMS_RISK, rk["high_open"], {
            "units": "1", "long_name": "1: the upper end is the grid end, D_max(alpha) may lie beyond it"}),
        "d_max_risk_resolved": (_DIMS_RISK, rk["resolved"], {
            "units": "1", "long_name": "1: R runs can resolve alpha (upper bound after 0 of R sticking < alpha)"}),
    }


def _add_m_diff(data: dict[str, Any], coords: dict[str, Any], models: list[str], m_mean: Array) -> None:
    """M_diff = M_d − E[M_s] (4.41) and M_quot = E[M_s]/M_d (4.42) per stochastic model, where the
    deterministic model ran."""
    if Model.DETERMINISTIC not in models:
        return
    md = m_mean[models.index(Model.DETERMINISTIC)]
    stoch = [m for m in models if m != Model.DETERMINISTIC]
    if not stoch:
        return
    ms = np.stack([m_mean[models.index(m)] for m in stoch])
    with np.errstate(invalid="ignore", divide="ignore"):
        quot = np.where(md > 0, ms / np.where(md > 0, md, 1.0), np.nan)
    coords["stochastic_model"] = stoch
    dims = ("stochastic_model", "normal_force_n", "damping_ratio")
    data["m_diff"] = (dims, md[None] - ms, {"units": "1", "long_name": "M_diff = M_d - E[M_s] (4.41)"})
    data["m_quot"] = (dims, quot, {"units": "1", "long_name": "M_quot = E[M_s]/M_d (4.42), NaN where M_d = 0"})


@dataclass
class _Tally:
    """The study's progress over its stages (grid, refinement rounds, phase diagrams): ``total`` tasks known so
    far, ``done`` those of the stages begun before."""

    progress: Progress | None
    total: int
    done: int = 0

    def stage(self, n: int, *, new: bool = False) -> Callable[[int, int], None] | None:
        """The ``progress`` of a sweep of ``n`` tasks (``new``: not yet in ``total``, a refinement round)."""
        self.total += n if new else 0
        start, self.done = self.done, self.done + n
        if self.progress is None:
            return None
        progress, tally = self.progress, self

        def report(done: int, _n: int) -> None:
            progress(start + done, tally.total)

        return report


@dataclass
class _RefineState:
    """The refinement's running state: per run whether it has a cycle ``[model, N, D, run]`` (NaN: not run), the
    next task index, the sweeps' statistics and warnings so far."""

    has_cycle: Array
    index: int
    stats: SweepStats = field(default_factory=SweepStats)
    warnings: list[dict[str, str]] = field(default_factory=list)

    def grow(self, runs: int) -> None:
        """Room for ``runs`` runs per cell (NaN: not run)."""
        extra = runs - self.has_cycle.shape[-1]
        if extra > 0:
            pad = np.full((*self.has_cycle.shape[:-1], extra), np.nan)
            self.has_cycle = np.concatenate([self.has_cycle, pad], axis=-1)


def _add_stats(a: SweepStats, b: SweepStats) -> SweepStats:
    return SweepStats(computed=a.computed + b.computed, loaded=a.loaded + b.loaded)


@dataclass(frozen=True)
class _Refined:
    """The adaptive refinement's outcome: per run whether it has a cycle ``[model, N, D, run]`` (NaN: not run;
    every run of every cell, the grid's first), the counts ``k``, ``n`` ``[model, N, D]``, the log, the sweeps'
    statistics and the simulation warnings of its tasks."""

    has_cycle: Array
    k: Array
    n: Array
    runs_added: int
    rounds: int
    stop: str
    stats: SweepStats
    warnings: list[dict[str, str]]


class DampingStudy(Study[DampingConfig]):
    """One task per (model, N): all D of that N batched into one simulate call (the grid); after
    the grid one phase-diagram task per model (:meth:`phase_tasks`), whose D may depend on the grid."""

    kind = "damping"

    def __init__(self, config: DampingConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.forces: tuple[float, ...] = config.normal_forces or (sp.damping_study_force,)
        self.phase_force_n = float(config.phase_normal_force if config.phase_normal_force is not None
                                   else default_phase_force(sp.damping_study_force, tuple(self.forces)))

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "normal_force_n": self.forces}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        return self.task_for(index, point, [self.setup.parameters(point["normal_force_n"], d)
                                            for d in self.config.damping_ratios],
                             common_random_numbers=self.config.common_random_numbers)

    def phase_tasks(self, dampings: tuple[float, ...], first_index: int) -> list[TaskSpec]:
        """One task per model at the phase force: the D in ``dampings``, trajectories kept."""
        config, nf = self.config, self.phase_force_n
        tasks = []
        for k, model in enumerate(config.models):
            runs = min(runs_for(model, config.runs), config.phase_runs)
            tasks.append(task_for(
                config, self.setup, index=first_index + k, label=f"{model} phase N={nf:g}", model=model,
                params=[self.setup.parameters(nf, d) for d in dampings], runs=runs,
                common_random_numbers=config.common_random_numbers, keep_trajectory_runs=runs,
                save_every=config.save_every,
            ))
        return tasks

    def run(self, *, executor: Executor | None = None, checkpoint: str | None = None,
            progress: Progress | None = None) -> StudyResult[DampingSummary]:
        """The grid, its adaptive refinement (``refine``), then the phase diagrams (progress counts all),
        analysed (module docstring).  Task indices: the grid's, the phase diagrams', then the refinement's."""
        config = self.config
        tasks = self.tasks()
        n_phase = len(config.models) if config.phase_runs > 0 else 0
        tally = _Tally(progress, len(tasks) + n_phase)
        results, stats, chash = sweep(self.kind, config, tasks, executor, checkpoint, tally.stage(len(tasks)))
        warns = self.warnings(tasks, results)
        base = self.cycles(tasks, results)
        refined = None
        if config.refine:
            refined = self.refine(base, len(tasks) + n_phase, executor, checkpoint, tally)
            stats = _add_stats(stats, refined.stats)
            warns += refined.warnings
        coords, data, d_max = self.grid_variables(base, tasks, results, refined)
        data["d_hopf"] = (("normal_force_n",), self.hopf_dampings(warns),
                          {"units": "1", "long_name": "D_H = -n mu'(v0) v0/(2 gamma0)"})
        _add_m_diff(data, coords, list(config.models), data["stick_count_mean"][1])
        phase_rule = "none"
        if n_phase:
            phase_d, phase_rule = self.phase_dampings(d_max)
            ptasks = self.phase_tasks(phase_d, first_index=len(tasks))
            presults, pstats, _ = sweep("damping", config, ptasks, executor, checkpoint, tally.stage(n_phase))
            stats = _add_stats(stats, pstats)
            self.add_phase(data, coords, ptasks, presults, phase_d)
            warns += self.warnings(ptasks, presults)
        ds = self.dataset(data, coords, executor, chash, stick_window=config.stick_window)
        ds.attrs["phase_damping_rule"] = phase_rule
        if refined is not None:
            ds.attrs.update({"refine_risk_level": config.refined_risk_level, "refine_target_steps": config.target_steps,
                             "refine_max_runs_per_cell": config.max_runs_per_cell,
                             "refine_run_budget": config.run_budget, "refine_runs_added": refined.runs_added,
                             "refine_rounds": refined.rounds, "refine_stop": refined.stop})
        return StudyResult(self.kind, ds, self.summarise(ds, warns), stats)

    def refine(self, base: _Cycles, first_index: int, executor: Executor | None, checkpoint: str | None,
               tally: _Tally) -> _Refined:
        """Adaptive refinement of the grid (:func:`~stochfric.studies.refine.refine_counts`): each round runs the
        granted cells of one (model, N) to their new run count, one task per count (task indices from
        ``first_index``); a refined cell's first runs are checked to be the grid's (the seed rule)."""
        config, models = self.config, list(self.config.models)
        groups = [(mi, ni) for mi, m in enumerate(models) if m != Model.DETERMINISTIC for ni in range(len(self.forces))]
        st = _RefineState(base.has_cycle.copy(), first_index)

        def counts() -> tuple[Array, Array]:
            return (np.array([np.nansum(st.has_cycle[mi, ni], axis=-1) for mi, ni in groups]),
                    np.array([np.isfinite(st.has_cycle[mi, ni]).sum(axis=-1) for mi, ni in groups], dtype=float))

        def add_runs(granted: list[dict[int, int]]) -> tuple[Array, Array]:
            tasks, where = self.refine_tasks(granted, groups, st.index)
            st.index += len(tasks)
            results, stats, _ = sweep(self.kind, config, tasks, executor, checkpoint,
                                      tally.stage(len(tasks), new=True))
            st.stats = _add_stats(st.stats, stats)
            st.warnings += self.warnings(tasks, results)
            st.grow(max(t.runs for t in tasks))
            for t, (mi, ni, js) in zip(tasks, where, strict=True):
                cyc = window_mask(results[t.index]["t_gh"], self.setup.tau_end, config.stick_window).any(axis=-1)
                old = st.has_cycle[mi, ni, js, : t.runs]
                if np.any((old != cyc) & np.isfinite(old)):
                    raise StudyError(f"refinement task {t.label!r}: its first runs differ from the grid's (the seed "
                                     "rule is broken: run r of a cell must not depend on the run count)")
                st.has_cycle[mi, ni, js, : t.runs] = cyc
            return counts()

        hc = st.has_cycle
        if groups:
            rule = RefineRule(risk_level=config.refined_risk_level, confidence=config.confidence,
                              target_steps=config.target_steps, max_runs_per_cell=config.max_runs_per_cell)
            log = refine_counts(np.asarray(config.damping_ratios, float), *counts(), rule, config.run_budget,
                                add_runs)
            added, rounds, stop, hc = log.runs_added, log.rounds, log.stop, st.has_cycle
        else:
            added, rounds, stop = 0, 0, "done"
        return _Refined(has_cycle=hc, k=np.nansum(hc, axis=-1), n=np.isfinite(hc).sum(axis=-1).astype(float),
                        runs_added=added, rounds=rounds, stop=stop, stats=st.stats, warnings=st.warnings)

    def refine_tasks(self, granted: list[dict[int, int]], groups: list[tuple[int, int]], first_index: int
                     ) -> tuple[list[TaskSpec], list[tuple[int, int, list[int]]]]:
        """The tasks of one refinement round: per group (model, N) one task per new run count, over the granted
        D of that count (runs 0 … count − 1: the cells' own streams, as in the grid), and where each goes
        ``(model index, force index, D indices)``."""
        config, dgrid = self.config, self.config.damping_ratios
        tasks: list[TaskSpec] = []
        where: list[tuple[int, int, list[int]]] = []
        for g, cells in enumerate(granted):
            mi, ni = groups[g]
            model, nf = config.models[mi], self.forces[ni]
            for runs in sorted(set(cells.values())):
                js = sorted(j for j, m in cells.items() if m == runs)
                tasks.append(task_for(
                    config, self.setup, index=first_index + len(tasks), label=f"{model} N={nf:g} refine {runs} runs",
                    model=model, params=[self.setup.parameters(nf, dgrid[j]) for j in js], runs=runs,
                    common_random_numbers=config.common_random_numbers))
                where.append((mi, ni, js))
        return tasks, where

    def cycles(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]]) -> _Cycles:
        """The grid's per-run arrays and which runs have a cycle in the stick window."""
        sc = self.stack(tasks, results, "stick_count")
        t_gh = self.stack(tasks, results, "t_gh")
        valid = np.isfinite(sc)  # which runs exist (deterministic: run 0 only)
        inwin = window_mask(t_gh, self.setup.tau_end, self.config.stick_window)
        late = np.where(valid, inwin.any(axis=-1), np.nan)
        return _Cycles(stick_count=sc, passes_without_stick=self.stack(tasks, results, "n_belt_speed_without_stick"),
                       x_gh=self.stack(tasks, results, "x_gh"), t_gh=t_gh, in_window=inwin, has_cycle=late,
                       window_count=np.where(valid, inwin.sum(axis=-1), np.nan), n_runs=valid.sum(axis=-1),
                       k=np.nansum(late, axis=-1))

    def grid_variables(self, c: _Cycles, tasks: list[TaskSpec], results: dict[int, dict[str, Any]],
                       refined: _Refined | None = None) -> tuple[dict[str, Any], dict[str, Any], Array]:
        """Coordinates and variables of the grid's analysis, and D_max^s ``[model, N]`` (module docstring).

        P(stick-slip | D), D_max(α) and the interval widths come from all runs of a cell (``refined``: the
        refinement's); the per-run variables, E[M], X_gh and the sample extreme from the grid's ``runs``."""
        config, models = self.config, list(self.config.models)
        dgrid = np.asarray(config.damping_ratios)
        k, n = (c.k, c.n_runs) if refined is None else (refined.k, refined.n)
        extreme = sample_extremes(models, dgrid, c.k, c.n_runs, confidence=config.confidence,
                                  p_detect=config.p_detect)
        rk = risk_limits(models, dgrid, k, n, extreme[0], tuple(config.risk_levels), config.confidence)
        widths = risk_widths(models, dgrid, k, n, config.risk_levels, config.confidence, config.target_steps)
        sig = np.array([float(results[t.index]["sigma_zeta"][0]) for t in tasks]).reshape(len(models),
                                                                                             len(self.forces))
        coords: dict[str, Any] = {
            "model": models,
            "normal_force_n": ("normal_force_n", np.asarray(self.forces, float),
                               {"units": "N", "long_name": "normal force N"}),
            "damping_ratio": ("damping_ratio", dgrid, {"units": "1", "long_name": "damping ratio D"}),
            "run": np.arange(config.runs),
            "event": np.arange(c.x_gh.shape[-1]),
            "risk_level": ("risk_level", np.asarray(tuple(config.risk_levels), float),
                           {"units": "1", "long_name": "risk level alpha: tolerated P(stick-slip)"}),
        }
        data = {**_run_variables(c, k, n, config.confidence),
                **_statistics_variables(cell_statistics(c, config.seed)),
                **_limit_variables(sig, extreme, rk),
                **_width_variables(models, widths, rk["value"].shape)}
        if refined is not None:
            coords["refine_run"] = np.arange(refined.has_cycle.shape[-1])
            data["refine_has_cycle"] = ((*_DIMS5[:3], "refine_run"), refined.has_cycle, {
                "units": "1", "long_name": "1 if a slip->stick transition in the stick window, every run of a cell "
                                           "(refinement; NaN: not run)"})
        return coords, data, extreme[0]

    def hopf_dampings(self, warns: list[dict[str, str]]) -> Array:
        """D_H per force (:func:`~stochfric.oscillator.reference.hopf_damping`); a warning in ``warns``
        for each D_H > 1."""
        d0 = float(self.config.damping_ratios[0])
        d_hopf = np.array([hopf_damping(c.params, c.law) for c in (self.setup.case(nf, d0) for nf in self.forces)])
        for nf, dh in zip(self.forces, d_hopf, strict=True):
            if dh > 1.0:  # beyond critical damping: no oscillator of this field, a typing slip in N or the case
                warns.append({"code": "hopf-damping-above-one",
                              "message": f"N = {nf:g} N gives a Hopf damping ratio D_H = {dh:.3g} > 1 (beyond critical "
                                         "damping): check the normal force and the case's parameters"})
        return d_hopf

    def phase_dampings(self, d_max: Array) -> tuple[tuple[float, ...], str]:
        """The D of the phase diagrams and their rule: the config's (``given``) or :func:`auto_phase_damping`
        from D_max^s ``[model, N]`` at the phase force (``auto``)."""
        if self.config.phase_damping_ratios is not None:
            return tuple(self.config.phase_damping_ratios), "given"
        fi = int(np.argmin(np.abs(np.asarray(self.forces, float) - self.phase_force_n)))
        return auto_phase_damping(np.asarray(self.config.damping_ratios), d_max[:, fi]), "auto"

    def add_phase(self, data: dict[str, Any], coords: dict[str, Any], ptasks: list[TaskSpec],
                  presults: dict[int, dict[str, Any]], phase_d: tuple[float, ...]) -> None:
        """Phase-diagram variables: trajectories [model, phase_damping, phase_run, sample, component]."""
        config = self.config
        nm, npd, npr = len(config.models), len(phase_d), max(1, config.phase_runs)
        trs = [presults[t.index].get("trajectory") for t in ptasks]
        nsamp = max((tr.shape[2] for tr in trs if tr is not None), default=0)
        traj = np.full((nm, npd, npr, nsamp, 3), np.nan)
        cyc = np.full((nm, npd, npr), np.nan)
        sc = np.full((nm, npd, npr), np.nan)
        for mi, (t, tr) in enumerate(zip(ptasks, trs, strict=True)):
            r = presults[t.index]
            if tr is not None:
                traj[mi, :, : tr.shape[1], : tr.shape[2]] = tr
            cyc[mi, :, : t.runs] = window_mask(r["t_gh"], self.setup.tau_end, config.stick_window).any(axis=-1)
            sc[mi, :, : t.runs] = r["stick_count"]
        coords["phase_damping"] = ("phase_damping", np.asarray(phase_d, float),
                                   {"units": "1", "long_name": "damping ratio D of the phase diagrams"})
        coords["phase_run"] = ("phase_run", np.arange(npr), {"units": "1"})
        coords["sample"] = ("sample", np.arange(nsamp), {"units": "1", "long_name": "saved time step"})
        coords["component"] = ("component", ["tau", "x1", "x2"],
                               {"long_name": "tau = omega0 t, x1 = y/L, x2 = x1' (dimensionless, L = 1 m)"})
        pdims = ("model", "phase_damping", "phase_run")
        data["phase_normal_force_n"] = ((), float(self.phase_force_n), {"units": "N", "long_name": "normal force of "
                                                                                                 "the phase diagrams"})
        data["phase_trajectory"] = ((*pdims, "sample", "component"), traj,
                                    {"units": "1", "long_name": "decimated trajectory (tau, x1, x2) at the phase "
                                                                "force; NaN: run not kept (deterministic: run 0 only)"})
        data["phase_has_cycle"] = (pdims, cyc, {"units": "1", "long_name": "1 if a slip->stick transition in the "
                                                                            "stick window"})
        data["phase_stick_count"] = (pdims, sc, {"units": "1", "long_name": "M: slip->stick transitions in "
                                                                             "(0, tau_end]"})

    def summarise(self, ds: xr.Dataset, warns: list[dict[str, str]]) -> DampingSummary:
        """The :class:`DampingSummary` of the study's dataset."""
        config, setup, models = self.config, self.setup, list(self.config.models)
        stoch = [m for m in models if m != Model.DETERMINISTIC]
        ex = "d_max_sample_extreme"
        det = ds[ex].sel(model=Model.DETERMINISTIC).values if Model.DETERMINISTIC in models else None
        det_next = ds[f"{ex}_high"].sel(model=Model.DETERMINISTIC).values if Model.DETERMINISTIC in models else None

        def per_model(name: str) -> dict[str, Table]:
            return {m: ds[name].sel(model=m).values.tolist() for m in models}

        return DampingSummary(
            **self.summary_head(self.forces, warns),
            normal_force_n=list(self.forces), damping_ratio=list(config.damping_ratios),
            d_hopf=[float(v) for v in ds["d_hopf"].values],
            stick_window=(config.stick_window * setup.tau_end, setup.tau_end), confidence=config.confidence,
            p_detect=config.p_detect, risk_levels=list(config.risk_levels),
            risk_levels_runs_to_resolve=[runs_to_resolve(a, config.confidence) for a in config.risk_levels],
            stick_probability_interval="clopper-pearson",
            d_max_deterministic=None if det is None else [_none(v) for v in det],
            d_max_deterministic_next_grid=None if det_next is None else [_none(v) for v in det_next],
            d_max_risk={m: _risk_entries(ds, m, config.risk_levels, len(self.forces)) for m in stoch},
            d_max_sample_extreme={m: [SampleExtreme(_none(float(ds[ex].sel(model=m).values[i])),
                                                    (_none(float(ds[f"{ex}_low"].sel(model=m).values[i])),
                                                     _none(float(ds[f"{ex}_high"].sel(model=m).values[i]))))
                                      for i in range(len(self.forces))] for m in stoch},
            stick_probability={m: StickProbability(*(ds[f"stick_probability{s}"].sel(model=m).values.tolist()
                                                     for s in ("", "_low", "_high"))) for m in models},
            stick_count_mean=per_model("stick_count_mean"), stick_count_mean_se=per_model("stick_count_mean_se"),
            x_gh_mean_se=per_model("x_gh_mean_se"), x_gh_std_se=per_model("x_gh_std_se"),
            m_diff=({m: ds["m_diff"].sel(stochastic_model=m).values.tolist()
                     for m in ds["stochastic_model"].values.tolist()} if "m_diff" in ds else None),
            phase=_phase_summary(ds, models, config.save_every) if "phase_trajectory" in ds else None,
            d_max_risk_width=risk_widths(models, np.asarray(config.damping_ratios), ds["n_stuck"].values,
                                         ds["n_runs"].values, config.risk_levels, config.confidence,
                                         config.target_steps),
            refinement=_refinement_summary(ds, stoch) if "refine_has_cycle" in ds else None,
            checkpoint_hash=ds.attrs.get("checkpoint_hash") or None,
        )


def damping_tasks(config: DampingConfig) -> tuple[list[TaskSpec], dict[str, Any]]:
    """The grid tasks of :class:`DampingStudy` and its setup, forces and phase force."""
    study = DampingStudy(config)
    return study.tasks(), {"setup": study.setup, "forces": study.forces, "phase_force_n": study.phase_force_n}


#: Run the damping study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
damping_study = DampingStudy.study


def _none(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def _risk_entries(ds: xr.Dataset, model: str, risk_levels: Sequence[float], n_forces: int) -> list[list[DMaxRisk]]:
    """D_max(α) of ``model`` per force and risk level, from the dataset's ``d_max_risk*`` variables."""
    def at(name: str, i: int, j: int) -> Any:
        return ds[name].sel(model=model).values[i, j]

    return [[DMaxRisk(risk_level=float(a), value=_none(float(at("d_max_risk", i, j))),
                      interval=(_none(float(at("d_max_risk_low", i, j))), _none(float(at("d_max_risk_high", i, j)))),
                      high_open=bool(at("d_max_risk_high_open", i, j)), resolved=bool(at("d_max_risk_resolved", i, j)))
             for j, a in enumerate(risk_levels)]
            for i in range(n_forces)]


def _refinement_summary(ds: xr.Dataset, stoch: Sequence[str]) -> RefinementSummary:
    """The :class:`RefinementSummary` of a refined study's dataset (its ``refine_*`` attributes, ``n_runs``)."""
    a = ds.attrs
    return RefinementSummary(
        risk_level=float(a["refine_risk_level"]), target_steps=int(a["refine_target_steps"]),
        max_runs_per_cell=int(a["refine_max_runs_per_cell"]), run_budget=int(a["refine_run_budget"]),
        runs_added=int(a["refine_runs_added"]), rounds=int(a["refine_rounds"]), stop=str(a["refine_stop"]),
        runs_per_cell={m: ds["n_runs"].sel(model=m).values.astype(int).tolist() for m in stoch})


def _phase_summary(ds: xr.Dataset, models: Sequence[str], save_every: int) -> PhaseSummary:
    """The :class:`PhaseSummary` of the dataset's phase-diagram variables."""
    return PhaseSummary(
        normal_force_n=float(ds["phase_normal_force_n"].values),
        damping_ratio=[float(v) for v in ds["phase_damping"].values],
        damping_rule=ds.attrs.get("phase_damping_rule", "auto"),
        runs={m: int(np.isfinite(ds["phase_has_cycle"].sel(model=m).values[0]).sum()) for m in models},
        save_every=save_every,
        has_cycle_fraction={m: [float(np.nanmean(v)) for v in ds["phase_has_cycle"].sel(model=m).values]
                            for m in models},
    )

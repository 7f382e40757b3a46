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
* **D_max(α)** (issue 19) = the largest grid D with P(stick-slip | D) ≥ α, for each risk level α
  of ``risk_levels`` (default 10 %, 1 %), with the interval [low, high] read off the per-D bands
  (:func:`~stochfric.studies.stats.risk_limit`): low = the largest D whose lower bound is ≥ α,
  high = the largest D whose upper bound is ≥ α; high at the grid end = open ("≥ grid end"),
  which is always so when R runs cannot resolve α (0 of R sticking does not exclude P ≥ α);
* the thesis's D_max^s is kept as ``d_max_sample_extreme`` = the largest grid D at which *any* of the
  R runs stuck — a sample extreme that grows with R (it estimates D_max(α) for α → 0, at no stated
  risk); its bar [D_max^s, D_hi]: D_hi is the first grid D above it at which the one-sided upper bound
  on P pooled over the zero-count grid points in (D_max^s, D] (runs taken as independent across D)
  falls below ``p_detect``; ``None`` if the grid ends first;
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

import math
import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from ..io_utils import package_versions
from ..oscillator.reference import hopf_damping
from ..random import BOOTSTRAP_KEY, child_generator
from .base import Progress, Study, StudyResult, sweep, warning_counts
from .config import DampingConfig
from .executors import Executor, SweepStats
from .grids import window_mask
from .stats import clopper_pearson, pooled_bootstrap_se, risk_limit, runs_to_resolve
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


class DampingStudy(Study):
    """One task per (model, N): all D of that N batched into one simulate call (the grid); after
    the grid one phase-diagram task per model (:meth:`phase_tasks`), whose D may depend on the grid."""

    kind = "damping"

    def __init__(self, config: DampingConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.forces: tuple[float, ...] = config.normal_force_n or (float(sp["damping_study_force_n"]),)
        self.phase_force_n = float(config.phase_force_n if config.phase_force_n is not None else default_phase_force(
            float(sp["damping_study_force_n"]), tuple(self.forces)))

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "normal_force_n": self.forces}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        return self.task_for(index, point, [self.setup.parameters(point["normal_force_n"], d)
                                            for d in self.config.damping_ratio],
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
            progress: Progress | None = None) -> StudyResult:
        """The grid, then the phase diagrams (progress counts both), analysed (module docstring)."""
        config, setup, forces, phase_force = self.config, self.setup, self.forces, self.phase_force_n
        tasks = self.tasks()
        n_phase = len(config.models) if config.phase_runs > 0 else 0
        total = len(tasks) + n_phase

        def grid_progress(done: int, _n: int) -> None:
            if progress is not None:
                progress(done, total)

        results, stats, chash = sweep(self.kind, config, tasks, executor, checkpoint,
                                      grid_progress if progress is not None else None)
        models: list[str] = list(config.models)
        dgrid = np.asarray(config.damping_ratio)
        nm, nn, nr = len(models), len(forces), config.runs
        sc = self.stack(tasks, results, "stick_count")
        nbs = self.stack(tasks, results, "n_belt_speed_without_stick")
        sig = np.array([float(results[t.index]["sigma_zeta"][0]) for t in tasks]).reshape(nm, nn)
        warns = self.warnings(tasks, results)
        x_gh = self.stack(tasks, results, "x_gh")
        t_gh = self.stack(tasks, results, "t_gh")
        nev = x_gh.shape[-1]
        valid = np.isfinite(sc)  # which runs exist (deterministic: run 0 only)
        inwin = window_mask(t_gh, setup.tau_end, config.stick_window)
        late = np.where(valid, inwin.any(axis=-1), np.nan)
        m_late = np.where(valid, inwin.sum(axis=-1), np.nan)
        n_runs = valid.sum(axis=-1)
        k = np.nansum(late, axis=-1)
        prob = k / n_runs
        lo, hi = clopper_pearson(k, n_runs, config.confidence)
        xw = np.where(inwin, x_gh, np.nan)
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            xmean_nan = np.nanmean(xw, axis=(-2, -1))
            xstd_nan = np.nanstd(xw, axis=(-2, -1), ddof=1)
            m_mean = np.nanmean(sc, axis=-1)  # E[M]
        # Monte Carlo uncertainty: E[M] over independent runs (s/√R); E[X_gh], σ(X_gh) by a bootstrap over runs
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            m_se = np.nanstd(sc, axis=-1, ddof=1) / np.sqrt(n_runs)
        x_se_mean, x_se_std = pooled_bootstrap_se(
            xw, n_boot=200, rng=child_generator(config.seed, BOOTSTRAP_KEY))
        xmean = np.where(np.isfinite(xmean_nan), xmean_nan, 0.0)
        xstd = np.where(np.isfinite(xstd_nan), xstd_nan, 0.0)
        # D_max per model and force
        dmax = np.full((nm, nn), np.nan)
        dlo = np.full((nm, nn), np.nan)
        dhi = np.full((nm, nn), np.nan)
        for mi, model in enumerate(models):
            for ni in range(nn):
                if model == "deterministic":
                    v = d_max_deterministic(dgrid, k[mi, ni] > 0)
                    dmax[mi, ni] = v
                    dlo[mi, ni] = v
                    above = dgrid[dgrid > v] if math.isfinite(v) else dgrid
                    dhi[mi, ni] = float(above.min()) if above.size else math.nan
                else:
                    dmax[mi, ni], dlo[mi, ni], dhi[mi, ni] = d_max_stochastic(
                        dgrid, k[mi, ni], int(n_runs[mi, ni, 0]), confidence=config.confidence,
                        p_detect=config.p_detect)
        # D_max(α) per model, force and risk level (deterministic: D_max^d, exact)
        alphas = tuple(config.risk_levels)
        na = len(alphas)
        rk = {f: np.full((nm, nn, na), np.nan) for f in ("value", "low", "high")}
        rk_open = np.zeros((nm, nn, na), dtype=np.int8)
        rk_res = np.ones((nm, nn, na), dtype=np.int8)
        for mi, model in enumerate(models):
            for ni in range(nn):
                for ai, a in enumerate(alphas):
                    if model == "deterministic":
                        for f in rk:
                            rk[f][mi, ni, ai] = dmax[mi, ni]
                        rk_open[mi, ni, ai] = int(math.isfinite(dmax[mi, ni]) and dmax[mi, ni] >= dgrid[-1] - 1e-12)
                        continue
                    r = risk_limit(dgrid, k[mi, ni], n_runs[mi, ni], a, config.confidence)
                    rk["value"][mi, ni, ai], rk["low"][mi, ni, ai], rk["high"][mi, ni, ai] = r.value, r.low, r.high
                    rk_open[mi, ni, ai], rk_res[mi, ni, ai] = int(r.high_open), int(r.resolved)
        d_hopf = np.array([hopf_damping(c.params, c.law) for c in (setup.case(nf, float(dgrid[0])) for nf in forces)])
        for nf, dh in zip(forces, d_hopf, strict=True):
            if dh > 1.0:  # beyond critical damping: no oscillator of this field, a typing slip in N or the case
                warns.append({"code": "hopf-damping-above-one",
                              "message": f"N = {nf:g} N gives a Hopf damping ratio D_H = {dh:.3g} > 1 (beyond critical "
                                         "damping): check the normal force and the case's parameters"})
        coords: dict[str, Any] = {
            "model": models,
            "normal_force_n": ("normal_force_n", np.asarray(forces, float),
                               {"units": "N", "long_name": "normal force N"}),
            "damping_ratio": ("damping_ratio", dgrid, {"units": "1", "long_name": "damping ratio D"}),
            "run": np.arange(nr),
            "event": np.arange(nev),
            "risk_level": ("risk_level", np.asarray(alphas, float),
                           {"units": "1", "long_name": "risk level alpha: tolerated P(stick-slip)"}),
        }
        dims5 = ("model", "normal_force_n", "damping_ratio", "run", "event")
        dims4 = dims5[:4]
        dims3 = dims5[:3]
        data: dict[str, Any] = {
            "x_gh": (dims5, x_gh, {"units": "1", "long_name": "slip->stick position X_gh = y/L"}),
            "t_gh": (dims5, t_gh, {"units": "1", "long_name": "tau of slip->stick"}),
            "stick_count": (dims4, sc, {"units": "1", "long_name": "M: slip->stick transitions in (0, tau_end]"}),
            "stick_count_window": (dims4, m_late, {"units": "1", "long_name": "transitions in the stick window"}),
            "n_belt_speed_without_stick": (dims4, nbs, {"units": "1"}),
            "has_cycle": (dims4, late, {"units": "1",
                                        "long_name": "1 if a slip->stick transition in the stick window"}),
            "n_runs": (dims3, n_runs, {"units": "1"}),
            "stick_probability": (dims3, prob, {"units": "1", "long_name": "P(stick-slip | D): fraction of runs with "
                                                "a slip->stick transition in the stick window"}),
            "stick_probability_low": (dims3, lo, {"units": "1", "long_name": "two-sided Clopper-Pearson lower bound "
                                                  f"of P(stick-slip | D) at confidence {config.confidence:g}"}),
            "stick_probability_high": (dims3, hi, {"units": "1", "long_name": "two-sided Clopper-Pearson upper bound "
                                                   f"of P(stick-slip | D) at confidence {config.confidence:g}"}),
            "stick_count_mean": (dims3, m_mean, {"units": "1", "long_name": "E[M] (deterministic: M_d)"}),
            "stick_count_mean_se": (dims3, m_se, {"units": "1",
                                                  "long_name": "standard error of E[M] (runs independent)"}),
            "x_gh_mean_se": (dims3, x_se_mean, {"units": "1", "long_name": "bootstrap SE of E[X_gh] (NaN: undefined)"}),
            "x_gh_std_se": (dims3, x_se_std, {"units": "1", "long_name": "bootstrap SE of sigma(X_gh)"}),
            "x_gh_mean": (dims3, xmean, {"units": "1",
                                         "long_name": "E[X_gh] in the window, 0 where no stick (thesis)"}),
            "x_gh_std": (dims3, xstd, {"units": "1", "long_name": "sigma(X_gh) in the window, 0 where none"}),
            "x_gh_mean_nan": (dims3, xmean_nan, {"units": "1", "long_name": "E[X_gh] in the window, NaN where none"}),
            "x_gh_std_nan": (dims3, xstd_nan, {"units": "1", "long_name": "sigma(X_gh), NaN where undefined"}),
            "sigma_zeta": (("model", "normal_force_n"), sig, {"units": "1", "long_name": "white-noise intensity"}),
            "d_max_sample_extreme": (("model", "normal_force_n"), dmax, {
                "units": "1", "long_name": "largest D at which any of the R runs stuck (grows with R; thesis D_max^s; "
                                           "deterministic: D_max^d)"}),
            "d_max_sample_extreme_low": (("model", "normal_force_n"), dlo, {"units": "1"}),
            "d_max_sample_extreme_high": (("model", "normal_force_n"), dhi, {
                "units": "1", "long_name": "deterministic: next grid D; stochastic: D_hi (pooled bound < p_detect)"}),
            "d_max_risk": (("model", "normal_force_n", "risk_level"), rk["value"], {
                "units": "1", "long_name": "D_max(alpha): largest grid D with estimated P(stick-slip) >= alpha "
                                           "(deterministic: D_max^d; NaN: below the grid start)"}),
            "d_max_risk_low": (("model", "normal_force_n", "risk_level"), rk["low"], {
                "units": "1", "long_name": "lower end of D_max(alpha): largest grid D whose Clopper-Pearson lower "
                                           "bound is >= alpha (NaN: none, below the grid start)"}),
            "d_max_risk_high": (("model", "normal_force_n", "risk_level"), rk["high"], {
                "units": "1", "long_name": "upper end of D_max(alpha): largest grid D whose Clopper-Pearson upper "
                                           "bound is >= alpha (open when d_max_risk_high_open)"}),
            "d_max_risk_high_open": (("model", "normal_force_n", "risk_level"), rk_open, {
                "units": "1", "long_name": "1: the upper end is the grid end, D_max(alpha) may lie beyond it"}),
            "d_max_risk_resolved": (("model", "normal_force_n", "risk_level"), rk_res, {
                "units": "1", "long_name": "1: R runs can resolve alpha (upper bound after 0 of R sticking < alpha)"}),
            "d_hopf": (("normal_force_n",), d_hopf, {"units": "1", "long_name": "D_H = -n mu'(v0) v0/(2 gamma0)"}),
        }
        if "deterministic" in models:
            di = models.index("deterministic")
            md = m_mean[di]
            stoch = [m for m in models if m != "deterministic"]
            if stoch:
                ms = np.stack([m_mean[models.index(m)] for m in stoch])
                with np.errstate(invalid="ignore", divide="ignore"):
                    quot = np.where(md > 0, ms / np.where(md > 0, md, 1.0), np.nan)
                coords["stochastic_model"] = stoch
                data["m_diff"] = (("stochastic_model", "normal_force_n", "damping_ratio"), md[None] - ms,
                                  {"units": "1", "long_name": "M_diff = M_d - E[M_s] (4.41)"})
                data["m_quot"] = (("stochastic_model", "normal_force_n", "damping_ratio"), quot,
                                  {"units": "1", "long_name": "M_quot = E[M_s]/M_d (4.42), NaN where M_d = 0"})
        phase_rule = "none"
        if n_phase:
            if config.phase_damping is not None:
                phase_d, phase_rule = tuple(config.phase_damping), "given"
            else:
                fi = int(np.argmin(np.abs(np.asarray(forces, float) - phase_force)))
                phase_d, phase_rule = auto_phase_damping(dgrid, dmax[:, fi]), "auto"
            ptasks = self.phase_tasks(phase_d, first_index=len(tasks))

            def phase_progress(done: int, _n: int) -> None:
                if progress is not None:
                    progress(len(tasks) + done, total)

            presults, pstats, _ = sweep("damping", config, ptasks, executor, checkpoint,
                                        phase_progress if progress is not None else None)
            stats = SweepStats(computed=stats.computed + pstats.computed, loaded=stats.loaded + pstats.loaded)
            _add_phase(data, coords, models, ptasks, presults, phase_force, phase_d, setup.tau_end,
                       config.stick_window, max(1, config.phase_runs))
            warns += self.warnings(ptasks, presults)
        ds = self.dataset(data, coords, executor, chash, stick_window=config.stick_window)
        ds.attrs["phase_damping_rule"] = phase_rule
        summary = _summary(self, ds, warns)
        return StudyResult(self.kind, ds, summary, stats)


def damping_tasks(config: DampingConfig) -> tuple[list[TaskSpec], dict[str, Any]]:
    """The grid tasks of :class:`DampingStudy` and its setup, forces and phase force."""
    study = DampingStudy(config)
    return study.tasks(), {"setup": study.setup, "forces": study.forces, "phase_force_n": study.phase_force_n}


#: Run the damping study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
damping_study = DampingStudy.study


def _add_phase(data: dict[str, Any], coords: dict[str, Any], models: list[str], ptasks: list[TaskSpec],
               presults: dict[int, dict[str, Any]], phase_force: float, phase_d: tuple[float, ...],
               tau_end: float, window: float, npr: int) -> None:
    """Phase-diagram variables: trajectories [model, phase_damping, phase_run, sample, component]."""
    nm, npd = len(models), len(phase_d)
    trs = [presults[t.index].get("trajectory") for t in ptasks]
    nsamp = max((tr.shape[2] for tr in trs if tr is not None), default=0)
    traj = np.full((nm, npd, npr, nsamp, 3), np.nan)
    cyc = np.full((nm, npd, npr), np.nan)
    sc = np.full((nm, npd, npr), np.nan)
    for mi, (t, tr) in enumerate(zip(ptasks, trs, strict=True)):
        r = presults[t.index]
        if tr is not None:
            traj[mi, :, : tr.shape[1], : tr.shape[2]] = tr
        cyc[mi, :, : t.runs] = window_mask(r["t_gh"], tau_end, window).any(axis=-1)
        sc[mi, :, : t.runs] = r["stick_count"]
    coords["phase_damping"] = ("phase_damping", np.asarray(phase_d, float),
                               {"units": "1", "long_name": "damping ratio D of the phase diagrams"})
    coords["phase_run"] = ("phase_run", np.arange(npr), {"units": "1"})
    coords["sample"] = ("sample", np.arange(nsamp), {"units": "1", "long_name": "saved time step"})
    coords["component"] = ("component", ["tau", "x1", "x2"],
                           {"long_name": "tau = omega0 t, x1 = y/L, x2 = x1' (dimensionless, L = 1 m)"})
    pdims = ("model", "phase_damping", "phase_run")
    data["phase_normal_force_n"] = ((), float(phase_force), {"units": "N", "long_name": "normal force of the "
                                                                                      "phase diagrams"})
    data["phase_trajectory"] = ((*pdims, "sample", "component"), traj,
                                {"units": "1", "long_name": "decimated trajectory (tau, x1, x2) at the phase force; "
                                                            "NaN: run not kept (deterministic: run 0 only)"})
    data["phase_has_cycle"] = (pdims, cyc, {"units": "1", "long_name": "1 if a slip->stick transition in the "
                                                                        "stick window"})
    data["phase_stick_count"] = (pdims, sc, {"units": "1", "long_name": "M: slip->stick transitions in "
                                                                         "(0, tau_end]"})


def _none(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


def _summary(study: DampingStudy, ds: xr.Dataset, warns: list[dict[str, str]]) -> dict[str, Any]:
    config, setup, models, forces = study.config, study.setup, list(study.config.models), study.forces
    out = study.summary_head(
        forces, {"normal_force_n": list(forces), "damping_ratio": list(config.damping_ratio),
                 "d_hopf": [float(v) for v in ds["d_hopf"].values]},
        stick_window=[config.stick_window * setup.tau_end, setup.tau_end], confidence=config.confidence,
        p_detect=config.p_detect, risk_levels=list(config.risk_levels),
        risk_levels_runs_to_resolve=[runs_to_resolve(a, config.confidence) for a in config.risk_levels],
        stick_probability_interval="clopper-pearson")
    ex = "d_max_sample_extreme"
    if "deterministic" in models:
        out["d_max_deterministic"] = [_none(v) for v in ds[ex].sel(model="deterministic").values]
        out["d_max_deterministic_next_grid"] = [_none(v) for v in ds[f"{ex}_high"].sel(model="deterministic").values]
    stoch = [m for m in models if m != "deterministic"]
    out["d_max_risk"] = {
        m: [[{"risk_level": float(a),
              "value": _none(float(ds["d_max_risk"].sel(model=m).values[i, j])),
              "interval": [_none(float(ds["d_max_risk_low"].sel(model=m).values[i, j])),
                           _none(float(ds["d_max_risk_high"].sel(model=m).values[i, j]))],
              "high_open": bool(ds["d_max_risk_high_open"].sel(model=m).values[i, j]),
              "resolved": bool(ds["d_max_risk_resolved"].sel(model=m).values[i, j])}
             for j, a in enumerate(config.risk_levels)]
            for i in range(len(forces))]
        for m in stoch
    }
    out[ex] = {
        m: [
            {"value": _none(float(ds[ex].sel(model=m).values[i])),
             "interval": [_none(float(ds[f"{ex}_low"].sel(model=m).values[i])),
                          _none(float(ds[f"{ex}_high"].sel(model=m).values[i]))]}
            for i in range(len(forces))
        ]
        for m in stoch
    }
    out["stick_probability"] = {
        m: {"value": ds["stick_probability"].sel(model=m).values.tolist(),
            "low": ds["stick_probability_low"].sel(model=m).values.tolist(),
            "high": ds["stick_probability_high"].sel(model=m).values.tolist()}
        for m in models
    }
    out["stick_count_mean"] = {m: ds["stick_count_mean"].sel(model=m).values.tolist() for m in models}
    out["stick_count_mean_se"] = {m: ds["stick_count_mean_se"].sel(model=m).values.tolist() for m in models}
    out["x_gh_mean_se"] = {m: ds["x_gh_mean_se"].sel(model=m).values.tolist() for m in models}
    out["x_gh_std_se"] = {m: ds["x_gh_std_se"].sel(model=m).values.tolist() for m in models}
    if "m_diff" in ds:
        out["m_diff"] = {m: ds["m_diff"].sel(stochastic_model=m).values.tolist()
                         for m in ds["stochastic_model"].values.tolist()}
    if "phase_trajectory" in ds:
        out["phase"] = {
            "normal_force_n": float(ds["phase_normal_force_n"].values),
            "damping_ratio": [float(v) for v in ds["phase_damping"].values],
            "damping_rule": ds.attrs.get("phase_damping_rule", "auto"),
            "runs": {m: int(np.isfinite(ds["phase_has_cycle"].sel(model=m).values[0]).sum()) for m in models},
            "save_every": config.save_every,
            "has_cycle_fraction": {m: [float(np.nanmean(v)) for v in ds["phase_has_cycle"].sel(model=m).values]
                                   for m in models},
        }
    out["warnings"] = warning_counts(warns)
    out["versions"] = package_versions()
    out["checkpoint_hash"] = ds.attrs.get("checkpoint_hash") or None
    return out

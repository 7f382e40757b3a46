"""Is white noise the small-ℓ limit of the contact process for X_gh?  (issue 19, docs/studies.md §7)

A path-domain friction fluctuation of correlation length ℓ and low-frequency one-sided PSD level S0
tends, as ℓ → 0 at fixed S0, to white noise in the path of level S0/2 per unit length — and then,
in time, to white noise of intensity (S0/2)/|v_rel| (docs/method.md §5.1a).  This study measures
what the product's contact model (:func:`~stochfric.oscillator.integrate.simulate`,
``model="contact"``) does along that limit: for each ℓ it builds the preset's process rescaled in
path (:func:`~stochfric.process.rescaled.rescaled_process`: ζ_ℓ(x) = √(ℓ0/ℓ) ζ0(x ℓ0/ℓ), S0 fixed,
σ² ∝ 1/ℓ), runs R runs at two time steps Δτ and Δτ/``refine`` with the same realisations (the same
seed), and reports E[X_gh] and σ(X_gh) of the X_gh in the stick window with bootstrap standard
errors over runs, the paired difference between the two time steps (convergence in Δτ), and the
weighted power-law fit σ(X_gh) ∝ ℓ^β with its standard error.  If σ converges as ℓ → 0, β → 0;
a β significantly below 0 means there is no white-noise limit for X_gh.

The time step follows the process grid: Δτ = min(preset Δτ, ``dt_max``, Δx/(``steps_per_cell`` · 2γ0)), so
that a slip step moving at up to twice the belt speed advances the path by at most 1/``steps_per_cell``
of a grid spacing.  The process is generated over at least ``process_length_m`` (default 2 γ0 τ_end L,
twice the belt's travel); a run whose path exceeds it is repeated with a process twice as long, so
no result reads a repeated process.
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from ..io_utils import package_versions, write_json_atomic, write_netcdf_atomic
from ..oscillator.case import CaseError, case_setup
from ..oscillator.integrate import simulate
from ..process.rescaled import band_correlation_length, low_frequency_psd, rescaled_process
from ..random import BOOTSTRAP_KEY, child_generator, child_seed
from .grids import window_mask

__all__ = ["WhiteLimitConfig", "WhiteLimitResult", "power_law_fit", "white_limit_study"]

PATH_COORDINATES = ("relative", "mass")
#: Most doublings of the process length when a run's path exceeds it.
MAX_EXTENSIONS = 4
#: Convergence in Δτ: |σ(Δτ) − σ(Δτ/refine)| at most this many SE(σ(Δτ/refine)).
DT_TOLERANCE_SE = 2.0
#: Most Euler steps (all runs, ℓ and both time steps) a study may take: ~3·10⁷ steps/s were measured
#: on 2 cores, so this is about ten minutes there.
MAX_STEPS = 2e10
#: Bootstrap replicates (runs resampled) for the standard errors.
N_BOOT = 400


@dataclass(frozen=True)
class WhiteLimitConfig:
    """Settings of the white-limit study; SI units (lengths in m, force in N)."""

    preset: str = "brake"
    normal_force_n: float | None = None  #: default: the preset's middle normal-force study force
    correlation_lengths_m: tuple[float, ...] = (1e-3, 1e-4, 1e-5, 1e-6)
    runs: int = 300
    seed: int = 19
    damping_ratio: float = 5e-6
    tau_end: float | None = None  #: default: the preset's (50)
    stick_window: float = 0.5
    path_coordinate: str = "relative"
    process_length_m: float | None = None  #: default 2 γ0 τ_end (L = 1 m)
    steps_per_cell: float = 4.0
    dt_max: float = 0.001  #: the largest Δτ used (the preset's 0.005 is not converged to the paired SE)
    refine: int = 4
    level_factor: float = 1.0  #: S0 of the rescaled processes = level_factor × the preset's
    fit_min_length_m: float | None = None  #: fit σ ∝ ℓ^β over ℓ >= this only (default: all ℓ)
    workers: int | None = None

    def __post_init__(self) -> None:
        lengths = tuple(float(v) for v in self.correlation_lengths_m)
        object.__setattr__(self, "correlation_lengths_m", lengths)
        if len(lengths) < 2:
            raise CaseError("give at least two correlation lengths (--lengths 1e-3,1e-4,...)")
        if any(not (math.isfinite(v) and v > 0.0) for v in lengths):
            raise CaseError(f"correlation lengths must be positive numbers [m], got {list(lengths)}")
        if len(set(lengths)) != len(lengths):
            raise CaseError(f"correlation lengths listed twice: {list(lengths)}")
        if any(v > 0.1 for v in lengths):
            raise CaseError(f"correlation lengths above 0.1 m are not a small-ℓ limit, got {list(lengths)}")
        if isinstance(self.runs, bool) or not isinstance(self.runs, int) or self.runs < 2:
            raise CaseError(f"runs must be an integer >= 2 (standard errors over runs), got {self.runs!r}")
        if self.path_coordinate not in PATH_COORDINATES:
            raise CaseError(f"path coordinate must be one of {list(PATH_COORDINATES)}, got {self.path_coordinate!r}")
        if not (math.isfinite(self.steps_per_cell) and self.steps_per_cell >= 1.0):
            raise CaseError(f"steps per grid cell must be >= 1, got {self.steps_per_cell!r}")
        if isinstance(self.refine, bool) or not isinstance(self.refine, int) or self.refine < 2:
            raise CaseError(f"refine must be an integer >= 2 (Δτ and Δτ/refine), got {self.refine!r}")
        if not 0.0 <= self.stick_window < 1.0:
            raise CaseError(f"stick window fraction must be in [0, 1), got {self.stick_window!r}")
        if not (math.isfinite(self.damping_ratio) and self.damping_ratio >= 0.0):
            raise CaseError(f"damping ratio must be >= 0, got {self.damping_ratio!r}")
        for name in ("normal_force_n", "tau_end", "process_length_m", "dt_max", "level_factor", "fit_min_length_m"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0.0):
                raise CaseError(f"{name} must be a positive number, got {v!r}")


@dataclass
class WhiteLimitResult:
    """Per correlation length ℓ (index i) and time step (j = 0: Δτ, 1: Δτ/refine): the statistics of
    X_gh in the stick window; ``summary`` is the JSON record (units in ``summary["units"]``)."""

    summary: dict[str, Any]
    x_gh: list[list[npt.NDArray[np.float64]]] = field(repr=False)  #: [i][j] (runs, events), NaN-padded
    t_gh: list[list[npt.NDArray[np.float64]]] = field(repr=False)

    def dataset(self) -> Any:
        """xarray Dataset of the tables (dims ``correlation_length``, ``dt_level``)."""
        import xarray as xr

        s = self.summary
        rows = s["table"]
        ell = np.array([r["correlation_length_m"] for r in rows])
        coords = {"correlation_length": ("correlation_length", ell, {"units": "m"}),
                  "dt_level": ("dt_level", np.array(["dt", f"dt/{s['config']['refine']}"]))}
        data: dict[str, Any] = {}

        def both(key: str, units: str, long_name: str) -> None:
            arr = np.array([[r["coarse"][key], r["fine"][key]] for r in rows], dtype=float)
            data[key] = (("correlation_length", "dt_level"), arr, {"units": units, "long_name": long_name})

        both("dt", "1", "dimensionless time step")
        both("x_gh_mean", "1", "E[X_gh] in the stick window (X = y/L, L = 1 m)")
        both("x_gh_mean_se", "1", "bootstrap SE of E[X_gh] (runs resampled)")
        both("x_gh_std", "1", "sigma(X_gh) in the stick window")
        both("x_gh_std_se", "1", "bootstrap SE of sigma(X_gh) (runs resampled)")
        both("n_events", "1", "X_gh in the stick window, all runs")
        both("slip_shorter_than_grid_fraction", "1", "slip phases shorter than one grid spacing")
        both("max_path_over_length", "1", "longest path of a run / process length (< 1: never repeated)")
        both("sticks_per_run", "1", "slip->stick transitions per run")
        both("passes_without_stick_per_run", "1", "passes of v_rel = 0 without sticking per run")
        for key, units, name in (("dx_m", "m", "process grid spacing"), ("process_length_m", "m", "process length"),
                                 ("sigma_mu", "1", "std of the rescaled process at p"),
                                 ("std_difference", "1", "sigma(dt) - sigma(dt/refine), same realisations"),
                                 ("std_difference_se", "1", "paired bootstrap SE of std_difference")):
            data[key] = (("correlation_length",), np.array([r[key] for r in rows], dtype=float),
                         {"units": units, "long_name": name})
        attrs = {"study": "white-limit", "summary_json": _json_text(s)}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def save(self, out: str | Path) -> dict[str, Path]:
        """Write ``white_limit_<preset>.json`` and ``.nc`` into ``out`` (atomic writes)."""
        d = Path(out)
        stem = f"white_limit_{self.summary['config']['preset']}"
        paths = {"json": write_json_atomic(d / f"{stem}.json", self.summary),
                 "netcdf": write_netcdf_atomic(d / f"{stem}.nc", self.dataset())}
        return paths


def _json_text(obj: Any) -> str:
    import json

    return json.dumps(obj, allow_nan=True)


def _pooled_std(x: npt.NDArray[np.float64]) -> float:
    v = x[np.isfinite(x)]
    return float(np.std(v, ddof=1)) if v.size > 1 else math.nan


def _run_sums(xw: npt.NDArray[np.float64]) -> tuple[npt.NDArray[np.float64], ...]:
    """Per run: count, sum, sum of squares of the finite entries (rows = runs)."""
    ok = np.isfinite(xw)
    z = np.where(ok, xw, 0.0)
    return ok.sum(axis=1).astype(float), z.sum(axis=1), (z * z).sum(axis=1)


def _boot_moments(sums: tuple[npt.NDArray[np.float64], ...], idx: npt.NDArray[np.int64]) -> tuple[Any, Any]:
    n, s1, s2 = (a[idx].sum(axis=1) for a in sums)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = s1 / n
        var = (s2 - n * mean * mean) / (n - 1)
    return mean, np.sqrt(np.maximum(var, 0.0))


def ensemble_statistics(
    xw_coarse: npt.NDArray[np.float64], xw_fine: npt.NDArray[np.float64], rng: np.random.Generator
) -> tuple[dict[str, Any], dict[str, Any], float, float]:
    """E[X_gh], σ(X_gh) with bootstrap SEs (runs resampled) at both time steps, and the paired
    difference σ(Δτ) − σ(Δτ/refine) with its SE (the same run indices in each replicate)."""
    runs = xw_coarse.shape[0]
    idx = rng.integers(0, runs, size=(N_BOOT, runs))
    out = []
    boot_std = []
    for xw in (xw_coarse, xw_fine):
        v = xw[np.isfinite(xw)]
        bm, bs = _boot_moments(_run_sums(xw), idx)
        boot_std.append(bs)
        out.append({"x_gh_mean": float(v.mean()) if v.size else math.nan,
                    "x_gh_mean_se": float(np.nanstd(bm, ddof=1)),
                    "x_gh_std": _pooled_std(xw), "x_gh_std_se": float(np.nanstd(bs, ddof=1)),
                    "n_events": int(v.size)})
    diff = out[0]["x_gh_std"] - out[1]["x_gh_std"]
    diff_se = float(np.nanstd(boot_std[0] - boot_std[1], ddof=1))
    return out[0], out[1], diff, diff_se


def power_law_fit(lengths: Sequence[float], sigma: Sequence[float], sigma_se: Sequence[float]) -> dict[str, Any]:
    """Weighted least squares of log σ on log ℓ (weights 1/(SE(σ)/σ)²): σ = A ℓ^β.

    ``beta_se`` is the SE from the weights; where the residuals scatter more than the SEs allow
    (χ²/dof > 1), ``beta_se_scaled`` multiplies it by √(χ²/dof) (the conservative SE, the one
    reported as ``beta_se_reported``).  Also the local slopes between neighbouring ℓ.
    """
    x = np.log(np.asarray(lengths, dtype=float))
    y = np.log(np.asarray(sigma, dtype=float))
    sy = np.asarray(sigma_se, dtype=float) / np.asarray(sigma, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y) & np.isfinite(sy) & (sy > 0)
    x, y, sy = x[ok], y[ok], sy[ok]
    if x.size < 2:
        return {"beta": None, "beta_se": None, "note": "fewer than two usable points"}
    w = 1.0 / sy**2
    xm = float(np.sum(w * x) / np.sum(w))
    ym = float(np.sum(w * y) / np.sum(w))
    sxx = float(np.sum(w * (x - xm) ** 2))
    beta = float(np.sum(w * (x - xm) * (y - ym)) / sxx)
    intercept = ym - beta * xm
    se = math.sqrt(1.0 / sxx)
    dof = x.size - 2
    chi2 = float(np.sum(w * (y - intercept - beta * x) ** 2))
    scale = math.sqrt(chi2 / dof) if dof > 0 else math.nan
    scaled = se * max(1.0, scale) if math.isfinite(scale) else se
    order = np.argsort(x)
    xs, ys, ss = x[order], y[order], sy[order]
    local = [{"from_m": float(math.exp(xs[i])), "to_m": float(math.exp(xs[i + 1])),
              "slope": float((ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i])),
              "slope_se": float(math.hypot(ss[i], ss[i + 1]) / abs(xs[i + 1] - xs[i]))}
             for i in range(xs.size - 1)]
    return {"beta": beta, "beta_se": se, "chi2": chi2, "dof": dof, "beta_se_scaled": scaled,
            "beta_se_reported": scaled, "prefactor": math.exp(intercept), "z_beta_vs_0": beta / scaled,
            "local_slopes": local, "model": "sigma(X_gh) = prefactor * l**beta, l in m"}


def _simulate_once(case: Any, process: Any, cfg: WhiteLimitConfig, tau_end: float, dt: float,
                   seed: np.random.SeedSequence) -> Any:
    return simulate(case.params, model="contact", law=case.law, process=process, tau_end=tau_end, dt=dt,
                    runs=cfg.runs, seed=seed, path_coordinate=cfg.path_coordinate, workers=cfg.workers)


def _slip_short_fraction(res: Any) -> float:
    d = res.diagnostics
    n = float(np.sum(d["n_slip_phases"]))
    return float(np.sum(d["n_short_slip_phases"]) / n) if n > 0 else math.nan


def white_limit_study(cfg: WhiteLimitConfig, progress: Callable[[str], None] | None = None) -> WhiteLimitResult:
    """Run the study (module docstring) and return its tables, fit and provenance."""
    t_start = time.perf_counter()
    setup = case_setup(cfg.preset)
    pre = setup.preset
    force = cfg.normal_force_n if cfg.normal_force_n is not None else float(
        pre.study_parameters["normal_force_study_forces_n"][1])
    case = setup.case(force, cfg.damping_ratio)
    p_pa = force / pre.contact_area_m2
    tau_end = cfg.tau_end if cfg.tau_end is not None else setup.tau_end
    base = pre.process
    ell0 = band_correlation_length(base)
    s0 = low_frequency_psd(base, p_pa)
    gamma0 = case.params.gamma0
    lmin = (cfg.process_length_m if cfg.process_length_m is not None
            else 2.0 * gamma0 * tau_end * case.params.length_scale)
    _check_size(cfg, base, lmin, setup.dt, gamma0 * case.params.length_scale, tau_end)
    rows: list[dict[str, Any]] = []
    xs: list[list[npt.NDArray[np.float64]]] = []
    ts: list[list[npt.NDArray[np.float64]]] = []
    for i, ell in enumerate(cfg.correlation_lengths_m):
        length = lmin
        for _ in range(MAX_EXTENSIONS + 1):
            proc = rescaled_process(base, ell, length, cfg.level_factor)
            dt = min(setup.dt, cfg.dt_max, proc.dx / (cfg.steps_per_cell * 2.0 * gamma0 * case.params.length_scale))
            seed = child_seed(cfg.seed, i)
            pair, t_pair = [], []
            results = []
            for step in (dt, dt / cfg.refine):
                if progress is not None:
                    progress(f"l = {ell:.3g} m: {cfg.runs} runs at dt = {step:.3g} ({proc.n_points} process points)")
                res = _simulate_once(case, proc, cfg, tau_end, step, seed)
                results.append(res)
            worst = max(float(np.max(r.diagnostics["path"])) * case.params.length_scale for r in results)
            if worst < proc.length:
                break
            length = 2.0 * max(length, worst)
        else:
            raise CaseError(f"the runs' path at l = {ell:.3g} m keeps exceeding the process length "
                            f"({worst:.3g} m > {proc.length:.3g} m); give a longer --process-length")
        for res in results:
            win = window_mask(res.t_gh[0], tau_end, cfg.stick_window)
            pair.append(np.where(win, res.x_gh[0], np.nan))
            t_pair.append(res.t_gh[0])
        coarse, fine, diff, diff_se = ensemble_statistics(pair[0], pair[1],
                                                          child_generator(cfg.seed, BOOTSTRAP_KEY, i))
        for stats, res, step in ((coarse, results[0], dt), (fine, results[1], dt / cfg.refine)):
            stats["dt"] = step
            stats["slip_shorter_than_grid_fraction"] = _slip_short_fraction(res)
            path_m = float(np.max(res.diagnostics["path"])) * case.params.length_scale
            stats["max_path_over_length"] = path_m / proc.length
            stats["warnings"] = sorted({w.code for w in res.warnings})
            # slip→stick transitions per run, and passes of v_rel = 0 where static friction could not hold
            stats["sticks_per_run"] = float(np.mean(res.stick_count))
            stats["passes_without_stick_per_run"] = float(np.mean(res.diagnostics["n_belt_speed_without_stick"]))
        rows.append({
            "correlation_length_m": ell, "dx_m": proc.dx, "process_length_m": proc.length,
            "process_points": proc.n_points, "sigma_mu": proc.std(p_pa),
            "low_frequency_psd_m": low_frequency_psd(proc, p_pa),
            "coarse": coarse, "fine": fine, "std_difference": diff, "std_difference_se": diff_se,
            "std_difference_z": diff / diff_se if diff_se > 0 else math.nan,
            "std_difference_over_se": diff / fine["x_gh_std_se"] if fine["x_gh_std_se"] > 0 else math.nan,
        })
        xs.append(pair)
        ts.append(t_pair)
    fine_sigma = [r["fine"]["x_gh_std"] for r in rows]
    fine_se = [r["fine"]["x_gh_std_se"] for r in rows]
    use = [j for j, v in enumerate(cfg.correlation_lengths_m)
           if cfg.fit_min_length_m is None or v >= cfg.fit_min_length_m * (1 - 1e-9)]
    fit = power_law_fit([cfg.correlation_lengths_m[j] for j in use], [fine_sigma[j] for j in use],
                        [fine_se[j] for j in use])
    fit["lengths_m"] = [cfg.correlation_lengths_m[j] for j in use]
    summary: dict[str, Any] = {
        "study": "white-limit",
        "config": asdict(cfg),
        "preset": pre.name, "normal_force_n": force, "pressure_pa": p_pa, "damping_ratio": cfg.damping_ratio,
        "tau_end": tau_end, "gamma0": gamma0, "n": case.params.n,
        "preset_correlation_length_m": ell0, "preset_low_frequency_psd_m": s0,
        "low_frequency_psd_m": s0 * cfg.level_factor, "white_path_level_m": s0 * cfg.level_factor / 2.0,
        "rule": "zeta_l(x) = sqrt(l0/l) * zeta0(x l0/l): S(f_1) fixed, integral correlation length "
                "l = S0/(4 sigma^2); dt = min(preset dt, dx/(steps_per_cell * 2 gamma0)); statistics of X_gh "
                "in the stick window tau > stick_window*tau_end over all runs; SEs by bootstrap over runs",
        "table": rows,
        "fit": fit,
        "verdict": _verdict(fit, rows),
        "seed": cfg.seed,
        "versions": package_versions(),
        "units": {"correlation_length_m": "m", "dx_m": "m", "process_length_m": "m",
                  "low_frequency_psd_m": "m (one-sided PSD, method §0)", "x_gh": "1 (X = y/L, L = 1 m, i.e. metres)",
                  "dt": "1 (tau = omega0 t)", "normal_force_n": "N", "pressure_pa": "Pa"},
        "elapsed_s": time.perf_counter() - t_start,
    }
    return WhiteLimitResult(summary=summary, x_gh=xs, t_gh=ts)


def _check_size(cfg: WhiteLimitConfig, base: Any, lmin: float, preset_dt: float, speed: float,
                tau_end: float) -> None:
    """Refuse, before any work, a study whose process or number of steps is out of reach."""
    steps = 0.0
    for ell in cfg.correlation_lengths_m:
        proc = rescaled_process(base, ell, lmin, cfg.level_factor)  # ValueError beyond MAX_POINTS
        dt = min(preset_dt, cfg.dt_max, proc.dx / (cfg.steps_per_cell * 2.0 * speed))
        steps += cfg.runs * tau_end / dt * (1.0 + cfg.refine)
    if steps > MAX_STEPS:
        raise CaseError(
            f"the study would take {steps:.2g} Euler steps (about {steps / 3e7 / 60:.0f} min on 2 cores; "
            f"at most {MAX_STEPS:.0e}): use fewer --runs, larger --lengths or a shorter --tau-end"
        )


def _verdict(fit: dict[str, Any], rows: list[dict[str, Any]]) -> str:
    beta, se = fit.get("beta"), fit.get("beta_se_reported")
    if beta is None or se is None:
        return "no fit"
    fitted = set(fit.get("lengths_m", []))
    over = [abs(r["std_difference_over_se"]) for r in rows
            if math.isfinite(r["std_difference_over_se"]) and r["correlation_length_m"] in fitted]
    worst_dt = max(over) if over else math.nan
    dt_note = (f"time step converged over the fitted l: |sigma(dt) - sigma(dt/refine)| <= {worst_dt:.1f} SE(sigma)"
               if worst_dt <= DT_TOLERANCE_SE else
               f"time step NOT converged at some fitted l: |sigma(dt) - sigma(dt/refine)| up to {worst_dt:.1f} "
               "SE(sigma)")
    rest = [r["correlation_length_m"] for r in rows if r["correlation_length_m"] not in fitted
            and abs(r["std_difference_over_se"]) > DT_TOLERANCE_SE]
    if rest:
        dt_note += f"; outside the fit NOT converged at l = {', '.join(f'{v:.3g}' for v in rest)} m"
    if abs(beta) > 3.0 * se:
        trend = "grows" if beta < 0 else "falls"
        return (f"sigma(X_gh) {trend} as l -> 0: beta = {beta:.3f} +- {se:.3f} ({abs(beta) / se:.1f} SE from 0); "
                f"no white-noise limit for X_gh; {dt_note}")
    return f"sigma(X_gh) consistent with convergence: beta = {beta:.3f} +- {se:.3f}; {dt_note}"


def white_limit_figure(results: Sequence[WhiteLimitResult], path: str | Path) -> Path:
    """σ(X_gh) over ℓ, log–log, with error bars (±1 SE, Δτ/refine) and the fitted power law, one
    series per result (preset)."""
    from ..plotting import new_subplots, save_figure

    fig, ax = new_subplots(1, 1, figsize=(5.6, 4.0), layout="constrained")
    for k, res in enumerate(results):
        s = res.summary
        ell = np.array([r["correlation_length_m"] for r in s["table"]])
        sig = np.array([r["fine"]["x_gh_std"] for r in s["table"]])
        se = np.array([r["fine"]["x_gh_std_se"] for r in s["table"]])
        col = f"C{k}"
        label = f"{s['preset']} {s['normal_force_n']:g} N"
        fit = s["fit"]
        used = np.isin(ell, fit.get("lengths_m", list(ell)))
        ax.errorbar(ell[used], sig[used], yerr=se[used], fmt="o", color=col, capsize=3, label=label)
        if not np.all(used):
            ax.errorbar(ell[~used], sig[~used], yerr=se[~used], fmt="o", mfc="none", color=col, capsize=3,
                        label=f"{s['preset']}: not in the fit")
        if fit.get("beta") is not None:
            grid = np.geomspace(min(fit["lengths_m"]), max(fit["lengths_m"]), 50)
            ax.plot(grid, fit["prefactor"] * grid ** fit["beta"], "-", color=col, lw=1,
                    label=f"fit β = {fit['beta']:.3f} ± {fit['beta_se_reported']:.3f}")
        ax.axvline(s["preset_correlation_length_m"], color=col, ls=":", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("correlation length ℓ [m] (dotted: the preset's)")
    ax.set_ylabel("σ(X_gh) [-]")
    head = results[0].summary if results else {}
    ax.set_title(f"contact model, S0 = {head.get('low_frequency_psd_m', math.nan):.2g} m fixed, "
                 f"{head.get('config', {}).get('path_coordinate', '')} path, ℓ → 0", fontsize=10)
    ax.legend(fontsize=8)
    return save_figure(fig, path)

"""Is white noise the small-ℓ limit of the contact process for X_gh?  (docs/studies.md)

A path-domain friction fluctuation of correlation length ℓ and low-frequency one-sided PSD level S0
tends, as ℓ → 0 at fixed S0, to white noise in the path of level S0/2 per unit length — and then,
in time, to white noise of intensity (S0/2)/|v_rel| (docs/method.md §5.1a).  This study measures
what the product's contact model (:func:`~stochfric.oscillator.integrate.simulate`,
``model="contact"``) does along that limit: for each ℓ it builds the preset's process rescaled in
path (:func:`~stochfric.friction_process.rescaled.rescaled_process`: ζ_ℓ(x) = √(ℓ0/ℓ) ζ0(x ℓ0/ℓ), S0 fixed,
σ² ∝ 1/ℓ), runs R runs at two time steps Δτ and Δτ/``refine`` with the same realisations (the same
seed), and reports E[X_gh] and σ(X_gh) of the X_gh in the stick window with bootstrap standard
errors over runs, the paired difference between the two time steps (convergence in Δτ), and the
weighted power-law fit σ(X_gh) ∝ ℓ^β with its standard error.  If σ converges as ℓ → 0, β → 0;
a β significantly below 0 means there is no white-noise limit for X_gh.

The time step follows the process grid: Δτ = min(preset Δτ, ``dt_max``, Δx/(``steps_per_cell`` · 2γ0)), so
that a slip step moving at up to twice the belt speed advances the path by at most 1/``steps_per_cell``
of a grid spacing.  The process is generated over at least ``process_length`` (default 2 γ0 τ_end L,
twice the belt's travel); a run whose path exceeds it is repeated with a process twice as long, so
no result reads a repeated process.
"""

from __future__ import annotations

import json
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import Any, Self

import numpy as np
import numpy.typing as npt

from ..friction_process.rescaled import band_correlation_length, low_frequency_psd, rescaled_process
from ..io_utils import (
    ResultFileError,
    package_versions,
    read_json_file,
    read_netcdf,
    write_json_atomic,
    write_netcdf_atomic,
)
from ..oscillator.case import CaseError, case_setup
from ..oscillator.integrate import simulate
from ..oscillator.options import ExecutionOptions, Model, NoiseOptions, PathCoordinate
from ..random import BOOTSTRAP_KEY, child_generator, child_seed
from .grids import window_mask
from .summary import OPTIONAL, from_json, to_json

__all__ = ["WhiteLimitConfig", "WhiteLimitResult", "WhiteLimitSummary", "power_law_fit", "white_limit_study"]

#: The path coordinates the study reads the process at (``position`` reads a periodic process: no limit ℓ → 0).
PATH_COORDINATES = (PathCoordinate.RELATIVE, PathCoordinate.MASS)
#: Most doublings of the process length when a run's path exceeds it.
MAX_EXTENSIONS = 4
#: Convergence in Δτ: |σ(Δτ) − σ(Δτ/refine)| at most this many SE(σ(Δτ/refine)).
DT_TOLERANCE_SE = 2.0
#: Most Euler steps (all runs, ℓ and both time steps) a study may take: ~3·10⁷ steps/s were measured
#: on 2 cores, so this is about ten minutes there.
MAX_STEPS = 2e10
#: Bootstrap replicates (runs resampled) for the standard errors.
N_BOOT = 400

#: The ``study`` stamp of the white-limit summary and dataset.
WHITE_LIMIT = "white-limit"


@dataclass(frozen=True)
class WhiteLimitConfig:
    """Settings of the white-limit study; SI units (lengths in m, force in N)."""

    preset: str = "brake"
    normal_force: float | None = None  #: default: the preset's middle normal-force study force
    correlation_lengths: tuple[float, ...] = (1e-3, 1e-4, 1e-5, 1e-6)
    runs: int = 300
    seed: int = 19
    damping_ratio: float = 5e-6
    tau_end: float | None = None  #: default: the preset's (50)
    stick_window: float = 0.5
    path_coordinate: PathCoordinate = PathCoordinate.RELATIVE  #: one of :data:`PATH_COORDINATES`
    process_length: float | None = None  #: default 2 γ0 τ_end (L = 1 m)
    steps_per_cell: float = 4.0
    dt_max: float = 0.001  #: the largest Δτ used (the preset's 0.005 is not converged to the paired SE)
    refine: int = 4
    level_factor: float = 1.0  #: S0 of the rescaled processes = level_factor × the preset's
    fit_min_length: float | None = None  #: fit σ ∝ ℓ^β over ℓ >= this only (default: all ℓ)
    workers: int | None = None

    def __post_init__(self) -> None:
        lengths = tuple(float(v) for v in self.correlation_lengths)
        object.__setattr__(self, "correlation_lengths", lengths)
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
            raise CaseError(f"path coordinate must be one of {[str(p) for p in PATH_COORDINATES]}, "
                            f"got {self.path_coordinate!r}")
        object.__setattr__(self, "path_coordinate", PathCoordinate(self.path_coordinate))
        if not (math.isfinite(self.steps_per_cell) and self.steps_per_cell >= 1.0):
            raise CaseError(f"steps per grid cell must be >= 1, got {self.steps_per_cell!r}")
        if isinstance(self.refine, bool) or not isinstance(self.refine, int) or self.refine < 2:
            raise CaseError(f"refine must be an integer >= 2 (Δτ and Δτ/refine), got {self.refine!r}")
        if not 0.0 <= self.stick_window < 1.0:
            raise CaseError(f"stick window fraction must be in [0, 1), got {self.stick_window!r}")
        if not (math.isfinite(self.damping_ratio) and self.damping_ratio >= 0.0):
            raise CaseError(f"damping ratio must be >= 0, got {self.damping_ratio!r}")
        for name in ("normal_force", "tau_end", "process_length", "dt_max", "level_factor", "fit_min_length"):
            v = getattr(self, name)
            if v is not None and not (math.isfinite(v) and v > 0.0):
                raise CaseError(f"{name} must be a positive number, got {v!r}")


@dataclass(frozen=True)
class StepStatistics:
    """The X_gh in the stick window at one time step, all runs: E[X_gh], σ(X_gh) [-] (X = y/L, L = 1 m) with
    bootstrap SEs (runs resampled), their number, the time step ``dt`` (τ = ω0 t), the fraction of slip
    phases shorter than one grid spacing, the longest path over the process length (< 1: never repeated),
    warning codes, slip→stick transitions and passes of v_rel = 0 without sticking per run."""

    x_gh_mean: float
    x_gh_mean_se: float
    x_gh_std: float
    x_gh_std_se: float
    n_events: int
    dt: float
    slip_shorter_than_grid_fraction: float
    max_path_over_length: float
    warnings: list[str]
    sticks_per_run: float
    passes_without_stick_per_run: float


@dataclass(frozen=True)
class LengthRow:
    """One correlation length ℓ [m]: the rescaled process (grid spacing ``dx_m``, length [m], points,
    σ_μ at p [-], low-frequency one-sided PSD [m]), the statistics at Δτ (``coarse``) and Δτ/refine
    (``fine``), and σ(Δτ) − σ(Δτ/refine) on the same realisations with its paired SE, as z and over
    SE(σ(Δτ/refine))."""

    correlation_length_m: float
    dx_m: float
    process_length_m: float
    process_points: int
    sigma_mu: float
    low_frequency_psd_m: float
    coarse: StepStatistics
    fine: StepStatistics
    std_difference: float
    std_difference_se: float
    std_difference_z: float
    std_difference_over_se: float


@dataclass(frozen=True)
class LocalSlope:
    """The slope of log σ over log ℓ between two neighbouring ℓ [m], with its SE."""

    from_m: float
    to_m: float
    slope: float
    slope_se: float


@dataclass(frozen=True)
class PowerLawFit:
    """σ(X_gh) = ``prefactor`` · ℓ^``beta`` (ℓ in m), weighted least squares of log σ on log ℓ
    (:func:`power_law_fit`); ``beta``/``beta_se`` ``None`` with a ``note`` where fewer than two points
    could be used.  ``lengths_m``: the ℓ fitted."""

    beta: float | None
    beta_se: float | None
    lengths_m: list[float]
    note: str | None = field(default=None, metadata=OPTIONAL)
    chi2: float | None = field(default=None, metadata=OPTIONAL)
    dof: int | None = field(default=None, metadata=OPTIONAL)
    beta_se_scaled: float | None = field(default=None, metadata=OPTIONAL)
    beta_se_reported: float | None = field(default=None, metadata=OPTIONAL)
    prefactor: float | None = field(default=None, metadata=OPTIONAL)
    z_beta_vs_0: float | None = field(default=None, metadata=OPTIONAL)
    local_slopes: list[LocalSlope] | None = field(default=None, metadata=OPTIONAL)
    model: str | None = field(default=None, metadata=OPTIONAL)


@dataclass(frozen=True)
class WhiteLimitSummary:
    """The white-limit study's record (module docstring): its ``config``; the case (``normal_force_n``
    [N], ``pressure_pa`` [Pa], ``damping_ratio`` [-], ``tau_end``, γ0 and n, dimensionless); the preset
    process's correlation length [m] and low-frequency PSD [m], the fixed level S0 [m] and the white
    path level S0/2 [m]; one :class:`LengthRow` per ℓ, the :class:`PowerLawFit`, the ``verdict``, the
    seed, versions, ``units`` and the wall time [s]."""

    study: str
    config: WhiteLimitConfig
    preset: str
    normal_force_n: float
    pressure_pa: float
    damping_ratio: float
    tau_end: float
    gamma0: float
    n: float
    preset_correlation_length_m: float
    preset_low_frequency_psd_m: float
    low_frequency_psd_m: float
    white_path_level_m: float
    rule: str
    table: list[LengthRow]
    fit: PowerLawFit
    verdict: str
    seed: int
    versions: dict[str, str]
    units: dict[str, str]
    elapsed_s: float

    def to_json(self) -> dict[str, Any]:
        """The record as one JSON object (NaN kept as NaN, as the files and ``--json`` have it)."""
        out: dict[str, Any] = to_json(self, nan_as_null=False)
        return out


@dataclass
class WhiteLimitResult:
    """Per correlation length ℓ (index i) and time step (j = 0: Δτ, 1: Δτ/refine): the statistics of
    X_gh in the stick window; ``summary`` is the typed record (units in ``summary.units``)."""

    summary: WhiteLimitSummary
    x_gh: list[list[npt.NDArray[np.float64]]] = field(repr=False)  #: [i][j] (runs, events), NaN-padded
    t_gh: list[list[npt.NDArray[np.float64]]] = field(repr=False)

    def dataset(self) -> Any:
        """xarray Dataset of the tables (dims ``correlation_length``, ``dt_level``)."""
        import xarray as xr

        s = self.summary
        rows = s.table
        ell = np.array([r.correlation_length_m for r in rows])
        coords = {"correlation_length": ("correlation_length", ell, {"units": "m"}),
                  "dt_level": ("dt_level", np.array(["dt", f"dt/{s.config.refine}"]))}
        data: dict[str, Any] = {}

        def both(key: str, units: str, long_name: str) -> None:
            arr = np.array([[getattr(r.coarse, key), getattr(r.fine, key)] for r in rows], dtype=float)
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
            data[key] = (("correlation_length",), np.array([getattr(r, key) for r in rows], dtype=float),
                         {"units": units, "long_name": name})
        attrs = {"study": WHITE_LIMIT, "summary_json": json.dumps(s.to_json(), allow_nan=True)}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def save(self, out: str | Path) -> dict[str, Path]:
        """Write ``white_limit_<preset>.json`` and ``.nc`` into ``out`` (atomic writes)."""
        d = Path(out)
        stem = f"white_limit_{self.summary.config.preset}"
        paths = {"json": write_json_atomic(d / f"{stem}.json", self.summary.to_json()),
                 "netcdf": write_netcdf_atomic(d / f"{stem}.nc", self.dataset())}
        return paths

    @classmethod
    def load(cls, path: str | Path) -> Self:
        """The study :meth:`save` wrote, from either file (``white_limit_<preset>.json``, or the ``.nc``
        whose ``summary_json`` holds the same record): the typed :attr:`summary` and so :meth:`dataset`.
        The per-run X_gh are not saved: :attr:`x_gh` and :attr:`t_gh` are empty.  A missing file is a
        :class:`FileNotFoundError`, a file of another kind an :class:`~stochfric.errors.InputError`."""
        what = "white-limit study (white_limit_<preset>.json or .nc of stochfric white-limit --out)"
        if Path(path).suffix == ".nc":
            attrs = read_netcdf(path, what).attrs
            stamped = attrs.get("study") == WHITE_LIMIT and "summary_json" in attrs
            data = json.loads(attrs["summary_json"]) if stamped else None
        else:
            data = read_json_file(path, what)
        if not isinstance(data, dict) or data.get("study") != WHITE_LIMIT:
            raise ResultFileError(f"{path} is not a {what}; stochfric.load reads any saved result")
        try:
            summary = from_json(WhiteLimitSummary, data)
        except (KeyError, TypeError, ValueError) as exc:
            raise ResultFileError(f"{path} is not a white-limit summary this stochfric reads ({exc!r}): rerun "
                                  "stochfric white-limit") from None
        return cls(summary=summary, x_gh=[], t_gh=[])


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


def power_law_fit(lengths: Sequence[float], sigma: Sequence[float], sigma_se: Sequence[float]) -> PowerLawFit:
    """Weighted least squares of log σ on log ℓ (weights 1/(SE(σ)/σ)²): σ = A ℓ^β.

    ``beta_se`` is the SE from the weights; where the residuals scatter more than the SEs allow
    (χ²/dof > 1), ``beta_se_scaled`` multiplies it by √(χ²/dof) (the conservative SE, the one
    reported as ``beta_se_reported``).  Also the local slopes between neighbouring ℓ; ``lengths_m``: the ℓ given.
    """
    x = np.log(np.asarray(lengths, dtype=float))
    y = np.log(np.asarray(sigma, dtype=float))
    sy = np.asarray(sigma_se, dtype=float) / np.asarray(sigma, dtype=float)
    ok = np.isfinite(x) & np.isfinite(y) & np.isfinite(sy) & (sy > 0)
    x, y, sy = x[ok], y[ok], sy[ok]
    if x.size < 2:
        return PowerLawFit(beta=None, beta_se=None, note="fewer than two usable points",
                           lengths_m=[float(v) for v in lengths])
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
    local = [LocalSlope(from_m=float(math.exp(xs[i])), to_m=float(math.exp(xs[i + 1])),
                        slope=float((ys[i + 1] - ys[i]) / (xs[i + 1] - xs[i])),
                        slope_se=float(math.hypot(ss[i], ss[i + 1]) / abs(xs[i + 1] - xs[i])))
             for i in range(xs.size - 1)]
    return PowerLawFit(beta=beta, beta_se=se, chi2=chi2, dof=dof, beta_se_scaled=scaled, beta_se_reported=scaled,
                       prefactor=math.exp(intercept), z_beta_vs_0=beta / scaled, local_slopes=local,
                       model="sigma(X_gh) = prefactor * l**beta, l in m", lengths_m=[float(v) for v in lengths])


def _simulate_once(case: Any, process: Any, cfg: WhiteLimitConfig, tau_end: float, dt: float,
                   seed: np.random.SeedSequence) -> Any:
    return simulate(replace(case, process=process, tau_end=tau_end, dt=dt), model=Model.CONTACT, runs=cfg.runs,
                    seed=seed, noise=NoiseOptions(path_coordinate=cfg.path_coordinate),
                    execution=ExecutionOptions(workers=cfg.workers))


def _slip_short_fraction(res: Any) -> float:
    d = res.diagnostics
    n = float(np.sum(d["n_slip_phases"]))
    return float(np.sum(d["n_short_slip_phases"]) / n) if n > 0 else math.nan


@dataclass(frozen=True)
class _Setting:
    """The case of a white-limit study: preset setup, normal force N [N], case, contact pressure [Pa],
    τ_end, the preset's process, the least process length [m] and L [m]."""

    setup: Any
    force: float
    case: Any
    pressure_pa: float
    tau_end: float
    base: Any
    least_length_m: float
    length_scale: float


def _setting(cfg: WhiteLimitConfig) -> _Setting:
    """The :class:`_Setting` of ``cfg`` (defaults from the preset), its size checked (:func:`_check_size`)."""
    setup = case_setup(cfg.preset)
    pre = setup.preset
    force = cfg.normal_force if cfg.normal_force is not None else float(
        pre.study_parameters.normal_force_study_forces[1])
    case = setup.case(force, cfg.damping_ratio)
    tau_end = cfg.tau_end if cfg.tau_end is not None else setup.tau_end
    scale = case.params.length_scale
    lmin = (cfg.process_length if cfg.process_length is not None
            else 2.0 * case.params.gamma0 * tau_end * scale)
    _check_size(cfg, pre.process, lmin, setup.dt, case.params.gamma0 * scale, tau_end)
    return _Setting(setup=setup, force=force, case=case, pressure_pa=force / pre.contact_area, tau_end=tau_end,
                    base=pre.process, least_length_m=lmin, length_scale=scale)


def _runs_at(st: _Setting, cfg: WhiteLimitConfig, i: int, ell: float,
             progress: Callable[[str], None] | None) -> tuple[Any, float, list[Any]]:
    """The rescaled process at ``ell`` and the runs at Δτ and Δτ/refine on it (the same seed); the process
    is doubled in length until no run's path exceeds it (:data:`MAX_EXTENSIONS`)."""
    gamma0 = st.case.params.gamma0
    length = st.least_length_m
    for _ in range(MAX_EXTENSIONS + 1):
        proc = rescaled_process(st.base, ell, length, cfg.level_factor)
        dt = min(st.setup.dt, cfg.dt_max, proc.dx / (cfg.steps_per_cell * 2.0 * gamma0 * st.length_scale))
        seed = child_seed(cfg.seed, i)
        results = []
        for step in (dt, dt / cfg.refine):
            if progress is not None:
                progress(f"l = {ell:.3g} m: {cfg.runs} runs at dt = {step:.3g} ({proc.n_points} process points)")
            results.append(_simulate_once(st.case, proc, cfg, st.tau_end, step, seed))
        worst = max(float(np.max(r.diagnostics["path"])) * st.length_scale for r in results)
        if worst < proc.length:
            return proc, dt, results
        length = 2.0 * max(length, worst)
    raise CaseError(f"the runs' path at l = {ell:.3g} m keeps exceeding the process length "
                    f"({worst:.3g} m > {proc.length:.3g} m); give a longer --process-length")


def _step_statistics(moments: dict[str, Any], res: Any, dt: float, proc: Any, length_scale: float
                     ) -> StepStatistics:
    """:class:`StepStatistics` of one time step from its moments (:func:`ensemble_statistics`) and run."""
    path_m = float(np.max(res.diagnostics["path"])) * length_scale
    return StepStatistics(
        **moments, dt=dt, slip_shorter_than_grid_fraction=_slip_short_fraction(res),
        max_path_over_length=path_m / proc.length, warnings=sorted({w.code for w in res.warnings}),
        # slip→stick transitions per run, and passes of v_rel = 0 where static friction could not hold
        sticks_per_run=float(np.mean(res.stick_count)),
        passes_without_stick_per_run=float(np.mean(res.diagnostics["n_belt_speed_without_stick"])))


def _length_row(st: _Setting, cfg: WhiteLimitConfig, i: int, ell: float, progress: Callable[[str], None] | None
                ) -> tuple[LengthRow, list[npt.NDArray[np.float64]], list[npt.NDArray[np.float64]]]:
    """The :class:`LengthRow` of ``ell`` and the X_gh in the stick window and τ_gh of both time steps."""
    proc, dt, results = _runs_at(st, cfg, i, ell, progress)
    pair = [np.where(window_mask(r.t_gh[0], st.tau_end, cfg.stick_window), r.x_gh[0], np.nan) for r in results]
    coarse, fine, diff, diff_se = ensemble_statistics(pair[0], pair[1], child_generator(cfg.seed, BOOTSTRAP_KEY, i))
    c = _step_statistics(coarse, results[0], dt, proc, st.length_scale)
    f = _step_statistics(fine, results[1], dt / cfg.refine, proc, st.length_scale)
    row = LengthRow(
        correlation_length_m=ell, dx_m=proc.dx, process_length_m=proc.length, process_points=proc.n_points,
        sigma_mu=proc.std(st.pressure_pa), low_frequency_psd_m=low_frequency_psd(proc, st.pressure_pa),
        coarse=c, fine=f, std_difference=diff, std_difference_se=diff_se,
        std_difference_z=diff / diff_se if diff_se > 0 else math.nan,
        std_difference_over_se=diff / f.x_gh_std_se if f.x_gh_std_se > 0 else math.nan)
    return row, pair, [r.t_gh[0] for r in results]


def white_limit_study(cfg: WhiteLimitConfig, progress: Callable[[str], None] | None = None) -> WhiteLimitResult:
    """Run the study (module docstring) and return its tables, fit and provenance."""
    t_start = time.perf_counter()
    st = _setting(cfg)
    rows: list[LengthRow] = []
    xs: list[list[npt.NDArray[np.float64]]] = []
    ts: list[list[npt.NDArray[np.float64]]] = []
    for i, ell in enumerate(cfg.correlation_lengths):
        row, pair, t_pair = _length_row(st, cfg, i, ell, progress)
        rows.append(row)
        xs.append(pair)
        ts.append(t_pair)
    use = [j for j, v in enumerate(cfg.correlation_lengths)
           if cfg.fit_min_length is None or v >= cfg.fit_min_length * (1 - 1e-9)]
    fit = power_law_fit([cfg.correlation_lengths[j] for j in use], [rows[j].fine.x_gh_std for j in use],
                        [rows[j].fine.x_gh_std_se for j in use])
    s0 = low_frequency_psd(st.base, st.pressure_pa)
    summary = WhiteLimitSummary(
        study=WHITE_LIMIT, config=cfg, preset=st.setup.preset.name, normal_force_n=st.force,
        pressure_pa=st.pressure_pa, damping_ratio=cfg.damping_ratio, tau_end=st.tau_end,
        gamma0=st.case.params.gamma0, n=st.case.params.n,
        preset_correlation_length_m=band_correlation_length(st.base), preset_low_frequency_psd_m=s0,
        low_frequency_psd_m=s0 * cfg.level_factor, white_path_level_m=s0 * cfg.level_factor / 2.0,
        rule="zeta_l(x) = sqrt(l0/l) * zeta0(x l0/l): S(f_1) fixed, integral correlation length "
             "l = S0/(4 sigma^2); dt = min(preset dt, dx/(steps_per_cell * 2 gamma0)); statistics of X_gh "
             "in the stick window tau > stick_window*tau_end over all runs; SEs by bootstrap over runs",
        table=rows, fit=fit, verdict=_verdict(fit, rows), seed=cfg.seed, versions=package_versions(),
        units={"correlation_length_m": "m", "dx_m": "m", "process_length_m": "m",
               "low_frequency_psd_m": "m (one-sided PSD, method §0)", "x_gh": "1 (X = y/L, L = 1 m, i.e. metres)",
               "dt": "1 (tau = omega0 t)", "normal_force_n": "N", "pressure_pa": "Pa"},
        elapsed_s=time.perf_counter() - t_start,
    )
    return WhiteLimitResult(summary=summary, x_gh=xs, t_gh=ts)


def _check_size(cfg: WhiteLimitConfig, base: Any, lmin: float, preset_dt: float, speed: float,
                tau_end: float) -> None:
    """Refuse, before any work, a study whose process or number of steps is out of reach."""
    steps = 0.0
    for ell in cfg.correlation_lengths:
        proc = rescaled_process(base, ell, lmin, cfg.level_factor)  # ValueError beyond MAX_POINTS
        dt = min(preset_dt, cfg.dt_max, proc.dx / (cfg.steps_per_cell * 2.0 * speed))
        steps += cfg.runs * tau_end / dt * (1.0 + cfg.refine)
    if steps > MAX_STEPS:
        raise CaseError(
            f"the study would take {steps:.2g} Euler steps (about {steps / 3e7 / 60:.0f} min on 2 cores; "
            f"at most {MAX_STEPS:.0e}): use fewer --runs, larger --lengths or a shorter --tau-end"
        )


def _verdict(fit: PowerLawFit, rows: list[LengthRow]) -> str:
    beta, se = fit.beta, fit.beta_se_reported
    if beta is None or se is None:
        return "no fit"
    fitted = set(fit.lengths_m)
    over = [abs(r.std_difference_over_se) for r in rows
            if math.isfinite(r.std_difference_over_se) and r.correlation_length_m in fitted]
    worst_dt = max(over) if over else math.nan
    dt_note = (f"time step converged over the fitted l: |sigma(dt) - sigma(dt/refine)| <= {worst_dt:.1f} SE(sigma)"
               if worst_dt <= DT_TOLERANCE_SE else
               f"time step NOT converged at some fitted l: |sigma(dt) - sigma(dt/refine)| up to {worst_dt:.1f} "
               "SE(sigma)")
    rest = [r.correlation_length_m for r in rows if r.correlation_length_m not in fitted
            and abs(r.std_difference_over_se) > DT_TOLERANCE_SE]
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
        ell = np.array([r.correlation_length_m for r in s.table])
        sig = np.array([r.fine.x_gh_std for r in s.table])
        se = np.array([r.fine.x_gh_std_se for r in s.table])
        col = f"C{k}"
        label = f"{s.preset} {s.normal_force_n:g} N"
        fit = s.fit
        used = np.isin(ell, fit.lengths_m)
        ax.errorbar(ell[used], sig[used], yerr=se[used], fmt="o", color=col, capsize=3, label=label)
        if not np.all(used):
            ax.errorbar(ell[~used], sig[~used], yerr=se[~used], fmt="o", mfc="none", color=col, capsize=3,
                        label=f"{s.preset}: not in the fit")
        if fit.beta is not None and fit.prefactor is not None and fit.beta_se_reported is not None:
            grid = np.geomspace(min(fit.lengths_m), max(fit.lengths_m), 50)
            ax.plot(grid, fit.prefactor * grid ** fit.beta, "-", color=col, lw=1,
                    label=f"fit β = {fit.beta:.3f} ± {fit.beta_se_reported:.3f}")
        ax.axvline(s.preset_correlation_length_m, color=col, ls=":", lw=0.8)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("correlation length ℓ [m] (dotted: the preset's)")
    ax.set_ylabel("σ(X_gh) [-]")
    if results:
        head = results[0].summary
        ax.set_title(f"contact model, S0 = {head.low_frequency_psd_m:.2g} m fixed, {head.config.path_coordinate} "
                     "path, ℓ → 0", fontsize=10)
    ax.legend(fontsize=8)
    return save_figure(fig, path)

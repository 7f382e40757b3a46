"""``stochfric assess``: from a user's scans and machine to a stick-slip answer (issue 30, item 2).

One call: prepare the scans, analyse them **at the machine's nominal pressures** (the approach range chosen
so that the GW pressure of the measured map covers N/A_nom over the machine's force range, refused with a
reason where the measurement cannot reach those pressures with enough contacts or within the
non-interaction range), build the friction-process model, run the damping study over the machine's force
and damping range (D_max(α) refined adaptively until its interval closes or the budget is spent) and the
normal-force study at the machine's damping, and say per force: the stick-slip risk at the machine's
damping, D_max(α) with its interval, the deterministic limit, and whether the deterministic answer is safe.

How sure it is, by source: Monte Carlo (the Clopper–Pearson intervals of P and D_max(α)), surface sampling
(the model's E[μ](p), σ_μ(p) intervals from the measured windows, docs/statistical_contact.md §0e) and
model choice (the contact model: GW by default; ``contact_model`` takes another's E[μ](p), σ_μ(p), or ``all``
reports the spread of every model on the same surfaces, :mod:`stochfric.process.contact_models`).

Exit codes of the command: 0 a verdict; 3 the surface analysis is not credible or does not cover the
machine's pressures (no study runs unless ``accept_not_credible``; then every output says so); 2 bad input.
"""

from __future__ import annotations

import json
import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..arrays import FloatArray
from ..contact.materials import Material, load_material
from ..contact.validity import MIN_CONTACTS
from ..errors import AnalysisError, InputError
from ..friction_process.model_base import check_pressure_range
from ..io_utils import check_output_path, package_versions, write_text_atomic
from ..oscillator.machine import Machine, load_machine
from ..process.analysis_config import AnalysisConfig
from ..process.checks import window_tiles
from ..process.contact_models import parse_contact_models
from ..process.pipeline import MODEL_FILE, ScanAnalysis, analyse_scans, cap_on_windows
from ..surface.io import Surface
from ..surface.summits import summits_of

__all__ = ["ASSESS_SCHEMA", "AssessSettings", "Assessment", "ForceVerdict", "approach_for_pressures", "assess"]

ASSESS_SCHEMA = "stochfric.assess/1"
#: The approach range reaches this factor beyond the machine's pressures at both ends, so that the fitted
#: range (path-window mean pressures) still covers them.
PRESSURE_MARGIN = 1.1
#: Contacts needed on the measured map at the lowest pressure (μ a statistic of many asperities).
MIN_ASSESS_CONTACTS = 2 * MIN_CONTACTS
#: Trial approaches between 0 and the map's full contact.
_PROBE = 96


class PressureCoverageError(AnalysisError):
    """The measurement cannot be analysed at the machine's pressures (the message says why)."""


@dataclass(frozen=True, kw_only=True)
class AssessSettings:
    """The knobs of :func:`assess` (defaults: the library's; ``quick`` for a smoke run)."""

    runs: int = 10
    refine: bool = True
    run_budget: int = 20_000
    risk_level: float = 0.1
    seed: int = 0
    forces: int = 5
    damping_points: int = 21
    models: tuple[str, ...] = ("deterministic", "contact")
    analysis: AnalysisConfig = field(default_factory=AnalysisConfig)
    tau_end: float | None = None
    accept_not_credible: bool = False
    allow_extrapolation: bool = False
    workers: int | None = None
    normal_force_study: bool = True
    #: ``gw`` (the thesis), ``bem``, ``bem-plastic``, ``persson`` or ``all``: the model whose E[μ](p), σ_μ(p)
    #: the studies read (``all``: GW, with the spread of every model reported; issue 31).
    contact_model: str = "gw"

    def __post_init__(self) -> None:
        for name, low in (("runs", 1), ("run_budget", 1), ("forces", 1), ("damping_points", 2)):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < low:
                raise InputError(f"{name} must be an integer >= {low}, got {v!r}")
        if not (isinstance(self.risk_level, float | int) and 0.0 < float(self.risk_level) < 1.0):
            raise InputError(f"risk_level must lie in (0, 1), got {self.risk_level!r}")
        parse_contact_models(self.contact_model)  # an unknown model is refused before the surface analysis
        if self.tau_end is not None and not (math.isfinite(self.tau_end) and self.tau_end > 0.0):
            raise InputError(f"tau_end (--tau-end) must be a finite simulated time > 0, got {self.tau_end!r}")


@dataclass(frozen=True)
class ForceVerdict:
    """The answer at one normal force [N] (pressure [Pa]): P(stick-slip) at the machine's D with its 95 %
    interval, D_max(α) of the contact model with its interval, the deterministic limit D_max^d, and the
    verdicts ``risk`` (``stick-slip`` | ``no stick-slip`` | ``undecided``) and ``deterministic_safe``."""

    normal_force_n: float
    pressure_pa: float
    damping_ratio: float
    stick_probability: float | None
    stick_probability_interval: tuple[float | None, float | None]
    d_max: float | None
    d_max_interval: tuple[float | None, float | None]
    d_max_closed: bool
    d_max_deterministic: float | None
    risk: str
    deterministic_safe: bool | None

    def line(self, alpha: float) -> str:
        """One line of the first screen (user's units: N, MPa)."""
        p = _fmt(self.stick_probability, ".2f")
        lo, hi = (_fmt(v, ".2f") for v in self.stick_probability_interval)
        dlo, dhi = (_fmt(v, ".3g") for v in self.d_max_interval)
        safe = {True: "yes", False: "NO", None: "n/a"}[self.deterministic_safe]
        return (f"N = {self.normal_force_n:7.5g} N (p = {self.pressure_pa / 1e6:.3g} MPa): {self.risk.upper():14s} "
                f"P(stick-slip | D = {self.damping_ratio:.3g}) = {p} [{lo}, {hi}]; D_max({alpha:.0%}) = "
                f"{_fmt(self.d_max, '.3g')} [{dlo}, {dhi}]{'' if self.d_max_closed else ' (open)'}; "
                f"deterministic D_max = {_fmt(self.d_max_deterministic, '.3g')}; deterministic answer safe: {safe}")


@dataclass(frozen=True, kw_only=True, eq=False)
class Assessment:
    """The result of :func:`assess`: status (``verdict`` | ``not credible`` | ``undecided`` | ``not covered``), the
    reasons, the verdict per force, the scan analysis and the study results (None where not run)."""

    status: str
    reasons: list[str]
    machine: Machine
    material: dict[str, Any]
    scans: list[str]
    approach_m: FloatArray | None
    analysis: ScanAnalysis | None
    forces: list[ForceVerdict]
    risk_level: float
    studies: dict[str, Any]
    files: dict[str, str]
    forced: bool = False

    @property
    def exit_code(self) -> int:
        """0 with a verdict, 3 otherwise (the analysis not credible, the pressures not covered)."""
        return 0 if self.status == "verdict" else 3

    def first_screen(self) -> list[str]:
        """The report's first lines, in the user's units."""
        m = self.machine
        lo, hi = m.normal_force_range
        head = []
        if self.forced:
            head.append("WARNING: the surface analysis is NOT credible; this assessment was forced "
                        "(--accept-not-credible) and rests on an unvalidated friction model")
        head += [
            f"surface(s): {', '.join(self.scans)}",
            f"material:   {self.material.get('name')} (E* = {self.material.get('e_star_pa', math.nan) / 1e9:.3g} GPa, "
            f"τ_max = {self.material.get('shear_strength_pa', math.nan) / 1e6:.3g} MPa)",
            f"machine:    {m.name}: m = {m.mass:g} kg, c = {m.stiffness:g} N/m, v0 = {m.belt_speed:g} m/s, "
            f"A_nom = {m.contact_area:g} m², N = {lo:g}–{hi:g} N (p = {lo / m.contact_area / 1e6:.3g}–"
            f"{hi / m.contact_area / 1e6:.3g} MPa), D = {m.damping_ratio:g}",
            self._contact_line(),
            f"status:     {self.status}" + (f" — {'; '.join(self.reasons)}" if self.reasons else self._credible_why()),
        ]
        head += [f.line(self.risk_level) for f in self.forces]
        head += self.how_sure()
        return head

    def _credible_why(self) -> str:
        """Why a verdict's surface model was called credible: the summit check and the held-out test, in numbers."""
        run = self.analysis
        if self.status != "verdict" or run is None:
            return ""
        a = run.analysis
        sc, ho = a.surrogate_check, a.holdout
        r = int(a.ensemble.contact_area_m2.shape[0])
        parts = []
        if sc.global_exceed is not None:
            parts.append(f"summit check passed ({sc.global_exceed} of {r} surrogates as extreme as the map)")
        if ho is not None and ho.tests:
            parts.append(f"held-out test passed (largest |z| {ho.max_abs_z:.2f} against {ho.threshold:.2f} on the "
                         f"unseen halves, {ho.realizations} surrogates per fold; it detects a factor "
                         f"{ho.detectable_scatter_ratio:.2g} in σ_μ)")
        return (" — the surface model is credible: " + "; ".join(parts)) if parts else ""

    def _contact_line(self) -> str:
        """Which contact model the studies read, and the spread where the other models were solved."""
        run = self.analysis
        names = {"gw": "Greenwood–Williamson (the thesis's model)", "bem": "elastic boundary elements",
                 "bem-plastic": "elastic–plastic boundary elements (pressure capped at H)",
                 "persson": "Persson's theory"}
        if run is None:
            return "contact:    Greenwood–Williamson (the thesis's model)"
        used = run.model.contact_model
        line = f"contact:    {names.get(used, used)}"
        spread = run.contact_models
        if spread is None:
            return line + "; other models not run (--contact-model all gives their spread)"
        env = spread.envelope()
        worst = 100 * float(np.max(env["relative_spread"]))
        return (line + f"; models {', '.join(spread.models)} differ by up to {worst:.0f} % "
                f"in E[μ]; γ = {_fmt(spread.plasticity_index, '.3g')} recommends {', '.join(spread.recommended)}")

    def how_sure(self) -> list[str]:
        """Where the uncertainty comes from (Monte Carlo, surface sampling, model choice)."""
        out = []
        if self.forces:
            closed = sum(f.d_max_closed for f in self.forces)
            out.append(f"Monte Carlo: D_max({self.risk_level:.0%}) closed to the target width at {closed} of "
                       f"{len(self.forces)} forces; P(stick-slip) with 95 % Clopper–Pearson intervals")
        a = None if self.analysis is None else self.analysis.analysis
        if a is not None and a.model_intervals is not None:
            mi = a.model_intervals
            rel = np.nanmax((mi.mu_mean_ci95[:, 1] - mi.mu_mean_ci95[:, 0]) / 2 / np.abs(mi.mu_mean))
            share = float(np.nanmean(mi.sampling_share())) if mi.includes_sampling else math.nan
            out.append(f"surface sampling: E[μ] known to ±{100 * rel:.2g} % (95 %), of which "
                       f"{_fmt(100 * share, '.2g')} % of the variance is the measurement's (more measured area "
                       "narrows it, more runs do not)")
        spread = None if self.analysis is None else self.analysis.contact_models
        if spread is None:
            out.append("model choice: GW only (--contact-model all solves the same surfaces by every model); GW and "
                       "boundary-element μ differ 1.0–1.5× at equal load on the resolved shared files "
                       "(docs/contact_models.md)")
        else:
            split = spread.uncertainty_split()
            share = float(np.nanmean(split["model_share_of_variance"]))
            out.append(f"model choice: E[μ] over {', '.join(spread.models)} spans ±"
                       f"{_fmt(float(np.nanmax(split['model_half_width'])), '.3g')} (half range), "
                       f"{_fmt(100 * share, '.2g')} % of the variance of E[μ] against the surface sampling "
                       f"(±{_fmt(float(np.nanmax(split['sampling_half_width'])), '.3g')})"
                       + ("" if split["discretisation_half_width"] is None else
                          f"; the boundary-element grid alone (corrected area against pixel count) ±"
                          f"{_fmt(float(np.nanmax(split['discretisation_half_width'])), '.3g')}"))
        return out

    def to_json_dict(self) -> dict[str, Any]:
        """The JSON record (SI units) with provenance."""
        return {
            "schema": ASSESS_SCHEMA, "status": self.status, "reasons": self.reasons, "forced": self.forced,
            "machine": self.machine.to_dict(), "material": self.material, "scans": self.scans,
            "approach_m": None if self.approach_m is None else [float(v) for v in self.approach_m],
            "risk_level": self.risk_level,
            "forces": [_verdict_dict(f) for f in self.forces],
            "first_screen": self.first_screen(),
            "analysis": None if self.analysis is None else self.analysis.to_json_dict(),
            "studies": self.studies, "files": self.files, "versions": package_versions(),
        }


def _fmt(v: float | None, spec: str) -> str:
    return "—" if v is None or not math.isfinite(float(v)) else format(float(v), spec)


def _verdict_dict(f: ForceVerdict) -> dict[str, Any]:
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in f.__dict__.items()}


def approach_for_pressures(
    surfaces: Sequence[Surface], material: Material, pressures_pa: tuple[float, float], config: AnalysisConfig,
    *, num: int = 12,
) -> FloatArray:
    """The approaches u [m] at which the *model's* nominal pressure covers ``pressures_pa`` (p_lo, p_hi) [Pa],
    widened by :data:`PRESSURE_MARGIN`.

    The model's pressure at u is that of its long surfaces' windows (each referenced to its own highest
    summit, which the surrogates of a spiky map place lower than the map: at equal u they carry more load),
    so the u → p curve is read from the analysis's own long surfaces (same seed stream) on a probe grid; a
    window of the measured size must carry :data:`MIN_ASSESS_CONTACTS` contacts at
    u_lo (μ a statistic of many asperities: the surrogates' mean contact count) and their mean A_c/A_nom within
    ``config.max_area_fraction`` at u_hi, else :class:`PressureCoverageError` says what is missing.  The
    range is then capped on the measured windows (:func:`~stochfric.process.pipeline.cap_on_windows`)."""
    p_lo, p_hi = pressures_pa[0] / PRESSURE_MARGIN, pressures_pa[1] * PRESSURE_MARGIN
    rule = config.summit_rule
    summits = [summits_of(s, rule=rule) for s in surfaces]
    if not all(sm.count for sm in summits):
        raise PressureCoverageError("a prepared scan has no summits to carry a load")
    depth = max(float(np.ptp(sm.heights_m)) for sm in summits) * 1.5
    probe = np.linspace(0.0, depth, _PROBE + 1)[1:]
    pressure, area, contacts = _model_pressure_curve(surfaces, material, probe, config)
    k_hi = int(np.searchsorted(pressure, p_hi))
    if k_hi >= probe.size or area[k_hi] > config.max_area_fraction:
        inside = area <= config.max_area_fraction
        reach = float(pressure[inside].max()) if inside.any() else 0.0
        raise PressureCoverageError(
            f"the surface cannot carry the machine's highest pressure {pressures_pa[1] / 1e6:.3g} MPa within "
            f"the non-interaction range of the GW model (A_c/A_nom <= {config.max_area_fraction:g}): its model "
            f"reaches {reach / 1e6:.3g} MPa there with {material.name}; a stiffer pairing, a larger nominal area or "
            "a contact model with asperity interaction (issue 31) is needed")
    k_lo = max(int(np.searchsorted(pressure, p_lo)) - 1, 0)  # the last probe below p_lo: the range brackets it
    if contacts[k_lo] < MIN_ASSESS_CONTACTS:
        need = int(np.searchsorted(contacts, MIN_ASSESS_CONTACTS))
        p_ok = pressure[need] if need < probe.size else math.nan
        raise PressureCoverageError(
            f"at the machine's lowest pressure {pressures_pa[0] / 1e6:.3g} MPa only {contacts[k_lo]:.0f} summits "
            f"of a map of the measured size touch (at least {MIN_ASSESS_CONTACTS} are needed for μ to be a "
            f"statistic of many asperities; reached from {p_ok / 1e6:.3g} MPa): measure a larger area (larger "
            "scans) or raise the machine's lowest force")
    u = np.linspace(float(probe[k_lo]), float(probe[k_hi]), num)
    tiles = window_tiles(min(sm.count for sm in summits), config.window_tiles) or 1
    return cap_on_windows(surfaces, u, summit_rule=rule, tiles=tiles, mean_area_fraction=None)


def _model_pressure_curve(surfaces: Sequence[Surface], material: Material, probe: FloatArray,
                          config: AnalysisConfig) -> tuple[FloatArray, FloatArray, FloatArray]:
    """The model's mean path-window pressure [Pa], A_c/A_nom and contact count over the probe approaches: the
    long surfaces of the analysis itself (the same seed stream and surrogate method, so the analysis at any of
    these u reports exactly these pressures; made monotone in u)."""
    from ..process.ensemble import path_contact
    from ..process.pipeline import window_shift_points
    from ..random import as_seed_sequence, spawn_seed_sequences

    options, _why = config.surrogate_for([np.asarray(s.heights_m) for s in surfaces])
    s_path = spawn_seed_sequences(as_seed_sequence(config.seed), 4)[2]  # the analysis's path stream
    path = path_contact(list(surfaces), material, probe, long_surfaces=config.long_surfaces,
                        length_factor=config.length_factor,
                        shift_points=window_shift_points(surfaces[0], None, config.length_factor), seed=s_path,
                        options=options)
    smp = path.samples
    pressure = np.maximum.accumulate(np.asarray(smp.normal_force_n).mean(axis=(0, 1)) / smp.nominal_area_m2)
    area = np.maximum.accumulate(np.asarray(smp.area_fraction).mean(axis=(0, 1)))
    contacts = np.maximum.accumulate(np.asarray(smp.n_contacts, dtype=np.float64).mean(axis=(0, 1)))
    return pressure, area, contacts


def _force_grid(machine: Machine, n: int) -> list[float]:
    """n normal forces [N] log-spaced over the machine's range, with its default force."""
    lo, hi = machine.normal_force_range
    default = float(machine.default_normal_force or 0.5 * (lo + hi))
    grid = np.geomspace(lo, hi, n) if n > 1 else np.array([default])
    return sorted({float(f"{v:.6g}") for v in grid} | {default})


def _damping_grid(machine: Machine, n: int) -> list[float]:
    """n damping ratios over the machine's range (0 replaced by 5·10⁻⁶, the thesis's undamped D), with its D."""
    lo, hi = machine.damping_ratio_range
    grid = np.linspace(max(lo, 5e-6), hi, n)
    return sorted({float(f"{v:.6g}") for v in grid} | {float(machine.damping_ratio)})


def _verdicts(summary: Any, machine: Machine, alpha: float) -> list[ForceVerdict]:
    """One :class:`ForceVerdict` per force of the damping study's summary (contact model; the deterministic
    limit from the deterministic model)."""
    forces, damping = list(summary.normal_force_n), list(summary.damping_ratio)
    j = int(np.argmin(np.abs(np.asarray(damping) - machine.damping_ratio)))
    k = list(summary.risk_levels).index(alpha) if alpha in summary.risk_levels else 0
    sp = summary.stick_probability.get("contact")
    risks = summary.d_max_risk.get("contact")
    widths = summary.d_max_risk_width.get("contact") if summary.d_max_risk_width else None
    det = summary.d_max_deterministic
    out = []
    for i, nf in enumerate(forces):
        p = lo = hi = None
        if sp is not None:
            p, lo, hi = sp.value[i][j], sp.low[i][j], sp.high[i][j]
        r = risks[i][k] if risks is not None else None
        d_det = det[i] if det is not None else None
        closed = bool(widths[i][k].closed) if widths else bool(r is not None and not r.high_open)
        if lo is not None and lo >= alpha:
            risk = "stick-slip"
        elif hi is not None and hi < alpha:
            risk = "no stick-slip"
        else:
            risk = "undecided"
        r_hi = None if r is None else r.interval[1]
        safe = None
        if r is not None and closed:
            # the deterministic design is safe when D_max(α) of the random friction lies at or below D_max^d
            if r.value is None and r_hi is None:  # no risk at α anywhere on the grid
                safe = True
            else:
                safe = r_hi is not None and d_det is not None and r_hi <= d_det
        out.append(ForceVerdict(
            normal_force_n=float(nf), pressure_pa=float(nf) / machine.contact_area, damping_ratio=float(damping[j]),
            stick_probability=p, stick_probability_interval=(lo, hi), d_max=None if r is None else r.value,
            d_max_interval=(None, None) if r is None else r.interval, d_max_closed=closed,
            d_max_deterministic=d_det, risk=risk, deterministic_safe=safe))
    return out


def _run_studies(machine_file: Path, model_file: Path, machine: Machine, settings: AssessSettings,
                 out: Path, progress: Callable[[str], None] | None) -> tuple[dict[str, Any], Any]:
    """The damping study over the machine's forces and damping range (refined) and the normal-force study at
    the machine's damping; saved under ``out``; (JSON summaries, the damping summary)."""
    from .config import DampingConfig, NormalForceConfig
    from .damping import DampingStudy
    from .executors import make_executor
    from .normal_force import NormalForceStudy

    common: dict[str, Any] = dict(machine=str(machine_file), process_file=str(model_file), seed=settings.seed,
                  runs=settings.runs, models=settings.models, allow_extrapolation=settings.allow_extrapolation,
                  tau_end=settings.tau_end)
    forces = _force_grid(machine, settings.forces)
    damping = DampingConfig(**common, normal_forces=tuple(forces),
                            damping_ratios=tuple(_damping_grid(machine, settings.damping_points)),
                            risk_levels=(settings.risk_level,), refine=settings.refine,
                            run_budget=settings.run_budget, phase_runs=0)
    executor = make_executor("processes" if (settings.workers or 2) > 1 else "serial", workers=settings.workers)
    if progress:
        progress(f"damping study: {len(forces)} forces × {len(damping.damping_ratios)} D, {settings.runs} runs "
                 f"per cell{' (refined)' if settings.refine else ''}")
    res = DampingStudy.study(damping, executor=executor)
    res.save(out / "damping")
    studies: dict[str, Any] = {"damping": res.summary.to_json()}
    if settings.normal_force_study:
        if progress:
            progress("normal-force study at the machine's damping")
        nf = NormalForceConfig(**{**common, "runs": max(settings.runs, 30)}, normal_forces=tuple(forces),
                               damping_ratios=(float(machine.damping_ratio),), phase_runs=0)
        res_nf = NormalForceStudy.study(nf, executor=executor)
        res_nf.save(out / "normal_force")
        studies["normal-force"] = res_nf.summary.to_json()
    return studies, res.summary


def assess(
    scans: Sequence[str | os.PathLike[str]], material: str | Material, machine: str | os.PathLike[str] | Machine,
    *, out: str | os.PathLike[str], settings: AssessSettings | None = None,
    progress: Callable[[str], None] | None = None, **scan_options: Any,
) -> Assessment:
    """Assess stick-slip of ``machine`` with the surface of ``scans`` and ``material`` (module docstring).

    ``out``: the output directory (checked before any work): ``assess.json``, ``report.html``,
    ``machine.toml``, ``friction_process/`` (the analysis and the model file), ``damping/``, ``normal_force/``.
    ``scan_options`` go to :func:`~stochfric.process.pipeline.analyse_scans` (``preparation``,
    ``fill_undefined``, ``physical_size_m``, ``height_unit``, ``resample``).  Raises a
    :class:`~stochfric.errors.StochfricError` for bad input; a not credible or not covered analysis is a
    result (``status``), not an exception."""
    cfg = settings if settings is not None else AssessSettings()
    directory = Path(out)
    check_output_path(directory, option="--out")
    m = load_machine(machine if isinstance(machine, str | Machine) else Path(machine))
    mat = load_material(material) if isinstance(material, str) else material
    if not scans:
        raise InputError("assess needs at least one scan")
    directory.mkdir(parents=True, exist_ok=True)
    machine_file = directory / "machine.toml"
    write_text_atomic(machine_file, m.to_toml())
    files = {"machine": str(machine_file)}
    names = [Path(s).name for s in scans]
    base: dict[str, Any] = dict(machine=m, material=mat.to_dict(), scans=names, risk_level=cfg.risk_level, files=files)
    an_cfg = cfg.analysis
    try:
        from ..surface.scans import load_scan, pool_scans

        pooled = pool_scans([load_scan(p, summit_rule=an_cfg.summit_rule, **{k: v for k, v in scan_options.items()
                                                                               if k != "resample"}) for p in scans],
                            resample=bool(scan_options.get("resample", False)))
        u = approach_for_pressures(list(pooled.surfaces), mat, m.pressure_range_pa, an_cfg)
    except PressureCoverageError as exc:
        result = Assessment(status="not covered", reasons=[str(exc)], approach_m=None, analysis=None, forces=[],
                            studies={}, **base)
        return _finish(result, directory)
    if progress:
        progress(f"surface analysis at {m.pressure_range_pa[0] / 1e6:.3g}–{m.pressure_range_pa[1] / 1e6:.3g} MPa "
                 f"(approach {u[0] * 1e6:.3g}–{u[-1] * 1e6:.3g} µm)")
    run = analyse_scans(scans, mat, config=an_cfg, approach_m=u, workers=cfg.workers,
                        contact_model=cfg.contact_model, **scan_options)
    written = run.write(directory / "friction_process", model=True)
    files.update(written)
    cred = run.analysis.credibility
    stamp = check_pressure_range(run.model, list(m.pressure_range_pa), allow=True)
    if stamp is not None and not cfg.allow_extrapolation:
        result = Assessment(status="not covered", reasons=[stamp + " (the approach range did not reach them)"],
                            approach_m=u, analysis=run, forces=[], studies={}, **base)
        return _finish(result, directory)
    mu_top = max(run.model.mean(p) for p in m.pressure_range_pa)
    if m.friction_law.law == "pressure" and mu_top > m.friction_law.mu0:
        raise InputError(
            f"the surface's E[mu] reaches {mu_top:.3g} over the machine's pressures, above the static coefficient "
            f"mu0 = {m.friction_law.mu0:g} of its pressure law (4.13), which needs E[mu] <= mu0: give the machine "
            f"a measured static coefficient ([friction_law] mu0 = {mu_top + 0.2:.2g} or more) or law = \"III\"")
    if not cred.credible and not cfg.accept_not_credible:
        reasons = [f"[{r.code}] {r.message}" for r in cred.reasons]
        # "undecided" is said as such: the same exit 3, but what would decide it differs (more runs, more area)
        result = Assessment(status="undecided" if cred.status == "undecided" else "not credible", reasons=reasons,
                            approach_m=u, analysis=run, forces=[], studies={}, **base)
        return _finish(result, directory)
    studies, summary = _run_studies(machine_file, directory / "friction_process" / MODEL_FILE, m, cfg, directory,
                                    progress)
    forced = not cred.credible
    result = Assessment(status="verdict", reasons=[f"[{r.code}] {r.message}" for r in cred.reasons] if forced else [],
                        approach_m=u, analysis=run, forces=_verdicts(summary, m, cfg.risk_level), studies=studies,
                        forced=forced, **base)
    return _finish(result, directory)


def _finish(result: Assessment, directory: Path) -> Assessment:
    """Write ``assess.json`` and ``report.html`` (atomically) and return ``result`` with their paths."""
    result.files["json"] = str(directory / "assess.json")
    result.files["report"] = str(directory / "report.html")
    write_text_atomic(directory / "assess.json", json.dumps(result.to_json_dict(), indent=1, default=str))
    write_text_atomic(directory / "report.html", _html(result))
    return result


def _html(result: Assessment) -> str:
    """A one-page HTML report whose first lines are :meth:`Assessment.first_screen`."""
    import html as _h

    lines = result.first_screen()
    banner = ("<p style='color:#b00;font-weight:bold'>" + _h.escape(lines[0]) + "</p>") if result.forced else ""
    rows = "".join(f"<li>{_h.escape(x)}</li>" for x in (lines[1:] if result.forced else lines))
    return ("<!doctype html><html><head><meta charset='utf-8'><title>stochfric assess</title>"
            "<style>body{font-family:sans-serif;max-width:70em;margin:2em}li{margin:.3em 0;"
            "font-family:monospace;white-space:pre-wrap}</style></head><body>"
            f"<h1>Will it stick-slip? {_h.escape(result.machine.name)}</h1>{banner}<ul>{rows}</ul>"
            f"<p>Files: {_h.escape(', '.join(f'{k}: {v}' for k, v in result.files.items()))}</p>"
            "<p>How to read it: docs/assess.md.</p></body></html>")

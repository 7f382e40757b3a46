"""μ at prescribed nominal pressures by a choice of contact model, and the spread between the models
(issue 31; docs/contact_models.md).

Every μ of the thesis comes from Greenwood–Williamson (GW): Hertz at every summit, no interaction, purely
elastic (3.11–3.16).  Here the same samples — the disjoint windows of the measurement and the R surrogates
of the analysis (the same seed streams, so the same surfaces as :func:`~stochfric.process.statistics.analyse`)
— are solved by each of

* ``gw``: the thesis's summit sums, the approach u of every sample found so that N(u) = p A_nom (the GW sums
  are monotone in u: bisection to 1e-10 relative);
* ``bem``: the elastic half-space by boundary elements at the prescribed force (:mod:`stochfric.contact.bem`);
* ``bem-plastic``: the same with the contact pressure capped at the hardness H of the softer body
  (elastic–perfectly plastic);
* ``persson``: Persson's theory from the sample's rms gradient ḡ alone, A/A_nom = erf(√2 p/(E* ḡ))
  (:mod:`stochfric.contact.persson`; no summit detection);

and μ = τ_max A_c / N (3.16) in every case, so the models differ only in A_c at equal load.  All models are
**load controlled**: they are solved at the nominal pressures p = N/A_nom asked for (the machine's pressures),
not on an approach range.

:func:`contact_model_spread` returns a :class:`ContactModelSpread`: per model and pressure E[μ] and σ_μ over
the surrogates with their Monte Carlo errors, the same over the measured windows with their 95 % intervals
(jackknife × √(J/n_eff), :func:`~stochfric.process.holdout.window_summary`), the envelope over the models, the
split of the uncertainty of E[μ] into surface sampling and model choice, the GW/BEM ratio, the plasticity
index and the models it recommends.
"""

from __future__ import annotations

import dataclasses
import json
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Self

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import ContactError, asperity_sums
from stochfric.contact.bem import check_nominal_pressures
from stochfric.contact.materials import Material
from stochfric.errors import AnalysisError
from stochfric.friction_process.spectra import (
    correlation_length_interval,
    integral_correlation_length,
    mean_psd,
)
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.io_utils import ResultFileError, read_json_file, read_netcdf
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.ensemble import SurrogateOptions, tile_grid, window_starts
from stochfric.process.estimators import mean_and_std_errors
from stochfric.process.holdout import choose_tiles, window_summary
from stochfric.process.parallel import map_indexed
from stochfric.process.statistics import ENSEMBLE_STREAM, PATH_STREAM, plasticity_index_of
from stochfric.random import as_seed_sequence, child_seed, seed_entropy, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.summits import SUMMIT_RULES, find_summits

__all__ = [
    "ALL_MODELS",
    "BEM_AREAS",
    "STATISTICAL_CONTACT_MODELS",
    "ContactModelSpread",
    "LoadControl",
    "ModelPath",
    "ModelSamples",
    "contact_model_spread",
    "gw_at_pressures",
    "parse_contact_models",
    "process_model_for",
    "sample_contact",
]

#: The boundary-element contact areas (:class:`LoadControl`.bem_area).
BEM_AREAS: tuple[str, ...] = ("corrected", "pixels")
#: The contact models of the statistical analysis, in the order they are reported.
STATISTICAL_CONTACT_MODELS: tuple[str, ...] = ("gw", "bem", "bem-plastic", "persson")
#: ``--contact-model all``: every model of :data:`STATISTICAL_CONTACT_MODELS`.
ALL_MODELS = "all"
#: The ``kind`` stamp of the spread's summary and per-sample file; the per-sample file's name is the summary's
#: stem with this suffix (``contact_models.json``, ``contact_models_samples.nc``).
SPREAD_KIND = "contact_model_spread"
SAMPLES_SUFFIX = "_samples"

#: Relative tolerance of the GW bisection on the approach (N(u) = p A_nom).
GW_TOLERANCE = 1e-10


def parse_contact_models(spec: str | Sequence[str]) -> tuple[str, ...]:
    """The models of ``spec``: ``"all"``, one name, a comma-separated list or a sequence of names, in the
    order of :data:`STATISTICAL_CONTACT_MODELS`; :class:`AnalysisError` naming the known ones otherwise."""
    names = [s.strip().lower() for s in (spec.split(",") if isinstance(spec, str) else spec) if s.strip()]
    if not names:
        raise AnalysisError(f"no contact model given; use {ALL_MODELS!r} or some of "
                            f"{', '.join(STATISTICAL_CONTACT_MODELS)}")
    if ALL_MODELS in names:
        return STATISTICAL_CONTACT_MODELS
    unknown = [n for n in names if n not in STATISTICAL_CONTACT_MODELS]
    if unknown:
        raise AnalysisError(f"unknown contact model(s) {', '.join(map(repr, unknown))}; use {ALL_MODELS!r} or some of "
                            f"{', '.join(STATISTICAL_CONTACT_MODELS)}")
    return tuple(m for m in STATISTICAL_CONTACT_MODELS if m in names)


@dataclass(frozen=True, kw_only=True)
class LoadControl:
    """How the load-controlled models are solved.

    ``bem_solver``: ``"auto"`` (Tamaas for the elastic model, ContactMechanics for the capped one: the faster of
    the two for each, docs/bem_validation.md), ``"tamaas"`` or ``"contactmechanics"``
    (:data:`~stochfric.contact.bem.BEM_SOLVERS`);
    ``tolerance``, ``max_iterations``, ``time_limit_s``: the limits of every boundary-element solve (one
    sample, all pressures; reported in the output); ``frame_points``: border frame lowered out of reach
    (``None``: the summit rule's margin, so that every model sees the asperities GW sees);
    ``persson_corrected``: the small-load slope κ = 2 instead of Persson's √(8/π)
    (:data:`~stochfric.contact.persson.CORRECTED_KAPPA`); ``gradient_method``: the estimator of ḡ;
    ``bem_area``: the boundary-element contact area, ``"corrected"`` (the pixel count less Yastrebov et al.'s
    (2017) perimeter correction, :attr:`~stochfric.contact.bem.BemSolution.corrected_area_m2`: it brings the
    small-load slope κ of the elastic BEM to 2.01–2.14 at 512², where the pixel count gives 2.18–2.62,
    docs/bem_validation.md §4) or ``"pixels"`` (the count, as saved before this option; a file without the
    key loads as ``"pixels"``).
    """

    bem_solver: str = "auto"
    tolerance: float = 1e-8
    max_iterations: int = 5000
    time_limit_s: float = 600.0
    frame_points: int | None = None
    persson_corrected: bool = False
    gradient_method: str = "finite-difference"
    bem_area: str = "corrected"

    def __post_init__(self) -> None:
        from stochfric.contact.bem import BEM_SOLVERS

        if self.bem_area not in BEM_AREAS:
            raise AnalysisError(f"unknown boundary-element area {self.bem_area!r}; use one of {', '.join(BEM_AREAS)}")
        if self.bem_solver != "auto" and self.bem_solver not in BEM_SOLVERS:
            raise AnalysisError(f"unknown boundary-element solver {self.bem_solver!r}; use auto or one of "
                                f"{', '.join(BEM_SOLVERS)}")
        if not (0.0 < self.tolerance < 1.0):
            raise AnalysisError(f"tolerance must lie in (0, 1), got {self.tolerance!r}")
        if int(self.max_iterations) < 1 or not (self.time_limit_s > 0.0):
            raise AnalysisError("max_iterations must be >= 1 and time_limit_s > 0 s")
        if self.frame_points is not None and int(self.frame_points) < 0:
            raise AnalysisError(f"frame_points must be >= 0, got {self.frame_points!r}")

    def frame_for(self, rule: str) -> int:
        """The border frame in points: given, or the summit rule's margin."""
        return int(self.frame_points) if self.frame_points is not None else SUMMIT_RULES[rule].margin

    def to_dict(self) -> dict[str, Any]:
        return dict(self.__dict__)


@dataclass(frozen=True, kw_only=True)
class _One:
    """One sample solved by one model at P pressures."""

    area_fraction: FloatArray
    n_contacts: FloatArray
    iterations: FloatArray
    seconds: float
    warnings: tuple[str, ...] = ()
    solver: str = "closed form"
    #: The boundary-element models: A_c/A_nom by the other area estimator (the pixel count when the corrected
    #: area is used, and the other way round); None for the others.
    other_area_fraction: FloatArray | None = None


def gw_at_pressures(heights_m: FloatArray, spacing_m: tuple[float, float], material: Material,
                    pressures_pa: FloatArray, *, rule: str) -> tuple[FloatArray, FloatArray, FloatArray]:
    """GW/Hertz (3.11–3.13) of one sample at prescribed nominal pressures: ``(A_c/A_nom, n_contacts, u [m])``.

    The sample is referenced to its own highest summit (as in the thesis); N(u) = (4/3) E* Σ √β d^{3/2} grows
    monotonically and without bound in u, so u with N(u) = p A_nom is bracketed by doubling and found by
    bisection to :data:`GW_TOLERANCE` relative in u."""
    s = find_summits(heights_m, spacing_m, rule=rule)
    if s.count == 0:
        raise AnalysisError(f"a {heights_m.shape[0]}×{heights_m.shape[1]} sample has no summit (rule {rule!r})")
    a_nom = heights_m.shape[0] * spacing_m[0] * heights_m.shape[1] * spacing_m[1]
    target = np.asarray(pressures_pa, dtype=np.float64) * a_nom
    e_star = material.e_star_pa

    def force(u: FloatArray) -> FloatArray:
        return asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=e_star)[1]

    scale = max(float(np.ptp(s.heights_m)), float(np.std(heights_m)), 1e-12)
    hi = np.full(target.shape, scale)
    for _ in range(200):
        short = force(hi) < target
        if not np.any(short):
            break
        hi = np.where(short, 2.0 * hi, hi)
    lo = np.zeros_like(hi)
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        below = force(mid) < target
        lo, hi = np.where(below, mid, lo), np.where(below, hi, mid)
        if np.all(hi - lo <= GW_TOLERANCE * hi):
            break
    area, _f, count = asperity_sums(s.heights_m, s.radius_m, hi, e_star_pa=e_star)
    return area / a_nom, count.astype(np.float64), hi


def sample_contact(heights_m: FloatArray, physical_size_m: tuple[float, float], material: Material,
                   pressures_pa: FloatArray, model: str, *, rule: str, control: LoadControl) -> _One:
    """One sample (heights [m] of the given physical size) solved by ``model`` at the nominal pressures."""
    h = np.ascontiguousarray(heights_m, dtype=np.float64)
    p = np.asarray(pressures_pa, dtype=np.float64)
    start = time.perf_counter()
    spacing = (physical_size_m[0] / h.shape[0], physical_size_m[1] / h.shape[1])
    if model == "gw":
        frac, count, _u = gw_at_pressures(h, spacing, material, p, rule=rule)
        return _One(area_fraction=frac, n_contacts=count, iterations=np.zeros(p.size),
                    seconds=time.perf_counter() - start)
    if model in ("bem", "bem-plastic"):
        from stochfric.contact.bem import BemSettings, bem_contact

        settings = BemSettings(solver=control.bem_solver, periodic=True, frame_points=control.frame_for(rule),
                               tolerance=control.tolerance, max_iterations=control.max_iterations,
                               time_limit_s=control.time_limit_s,
                               hardness_pa=material.hardness if model == "bem-plastic" else None)
        sol = bem_contact(h, physical_size_m, material.e_star_pa, p, settings=settings)
        corrected = control.bem_area == "corrected"
        area, other = ((sol.corrected_area_fraction, sol.area_fraction) if corrected
                       else (sol.area_fraction, sol.corrected_area_fraction))
        return _One(area_fraction=np.asarray(area, dtype=np.float64),
                    other_area_fraction=np.asarray(other, dtype=np.float64),
                    n_contacts=np.asarray(sol.n_patches, dtype=np.float64),
                    iterations=np.asarray(sol.iterations, dtype=np.float64), seconds=time.perf_counter() - start,
                    warnings=tuple(sol.warnings), solver=str(sol.settings.get("method", sol.solver)))
    if model == "persson":
        from stochfric.contact.persson import persson_contact

        frame = control.frame_for(rule)
        inner = h[frame: h.shape[0] - frame, frame: h.shape[1] - frame] if frame else h
        inner_size = (inner.shape[0] * spacing[0], inner.shape[1] * spacing[1])
        res = persson_contact(inner, inner_size, material.e_star_pa, p, corrected=control.persson_corrected,
                              gradient_method=control.gradient_method)
        return _One(area_fraction=np.asarray(res.area_fraction, dtype=np.float64), n_contacts=np.full(p.size, np.nan),
                    iterations=np.zeros(p.size), seconds=time.perf_counter() - start)
    raise AnalysisError(f"unknown contact model {model!r}; use one of {', '.join(STATISTICAL_CONTACT_MODELS)}")


@dataclass(frozen=True, kw_only=True, eq=False)
class ModelSamples:
    """One contact model on every sample: arrays (samples, P); ``mu`` = τ_max (A_c/A_nom) / p (3.16)."""

    model: str
    pressure_pa: FloatArray
    area_fraction: FloatArray
    n_contacts: FloatArray
    mu: FloatArray
    iterations: FloatArray
    seconds: FloatArray
    warnings: tuple[str, ...]
    #: The solver(s) that solved the samples (a sample may fall back to the other boundary-element solver).
    solvers: tuple[str, ...] = ()
    #: The boundary-element models: μ with the other area estimator (:class:`LoadControl`.bem_area), the
    #: discretisation part of the model uncertainty; None for the other models and for older files.
    mu_other: FloatArray | None = None

    @classmethod
    def of(cls, model: str, pressure_pa: FloatArray, solved: Sequence[_One], tau_pa: float) -> ModelSamples:
        frac = np.stack([o.area_fraction for o in solved])
        warnings = tuple(dict.fromkeys(w for o in solved for w in o.warnings))
        others = [o.other_area_fraction for o in solved]
        mu_other = (None if not others or any(v is None for v in others)
                    else tau_pa * np.stack([np.asarray(v) for v in others]) / pressure_pa)
        return cls(model=model, pressure_pa=pressure_pa, area_fraction=frac,
                   n_contacts=np.stack([o.n_contacts for o in solved]), mu=tau_pa * frac / pressure_pa,
                   iterations=np.stack([o.iterations for o in solved]),
                   seconds=np.array([o.seconds for o in solved]), warnings=warnings,
                   solvers=tuple(dict.fromkeys(o.solver for o in solved)), mu_other=mu_other)


@dataclass(frozen=True, kw_only=True, eq=False)
class ModelPath:
    """μ along the path of K long surfaces at P pressures by one model (method §4c): windows of the original
    size shifted by a_y; per pressure the mean one-sided PSD (3.19–3.20) and the integral correlation length
    S(0)/(4σ_μ²) per long surface.  ``mu`` is (K, W, P); :attr:`pressure_pa` is the middle pressure, the one
    :meth:`spectrum` and :meth:`correlation_length` use unless given an index (a file saved before the path had
    several pressures loads with P = 1)."""

    model: str
    pressures_pa: FloatArray  # (P,), ascending
    mu: FloatArray  # (K, W, P)
    window_shift_m: float
    window_length_m: float

    @property
    def middle(self) -> int:
        """Index of the middle pressure."""
        return int(self.pressures_pa.size // 2)

    @property
    def pressure_pa(self) -> float:
        """The middle pressure [Pa]."""
        return float(self.pressures_pa[self.middle])

    def spectrum(self, k: int | None = None) -> tuple[FloatArray, FloatArray, FloatArray]:
        """``(f [1/m], mean S [m], SE of S)`` over the K long surfaces at pressure index ``k`` (default: middle)."""
        return mean_psd(self.mu[:, :, self.middle if k is None else k], self.window_shift_m)

    def correlation_length(self, k: int | None = None) -> tuple[float, float, float, float]:
        """Integral correlation length [m] at pressure index ``k`` (default: middle): mean, SE, 95 % interval
        over the K long surfaces."""
        mu = self.mu[:, :, self.middle if k is None else k]
        per = [integral_correlation_length(r, self.window_shift_m, self.window_length_m) for r in mu]
        return correlation_length_interval(per)

    def _at(self, k: int) -> dict[str, Any]:
        mu = self.mu[:, :, k]
        mean, cl_se, lo, hi = self.correlation_length(k)
        return {"pressure_pa": float(self.pressures_pa[k]), "mu_mean": float(mu.mean()),
                "mu_std": float(mu.std(ddof=1)), "correlation_length_m": _finite(mean),
                "correlation_length_se_m": _finite(cl_se), "correlation_length_ci95_m": [_finite(lo), _finite(hi)]}

    def to_dict(self) -> dict[str, Any]:
        """The middle pressure's spectrum and correlation length at the top level, every pressure's
        correlation length under ``by_pressure``."""
        f, psd, se = self.spectrum()
        by_pressure = [self._at(k) for k in range(self.pressures_pa.size)]
        return {**by_pressure[self.middle], "long_surfaces": int(self.mu.shape[0]), "windows": int(self.mu.shape[1]),
                "window_shift_m": self.window_shift_m, "frequencies_per_m": f.tolist(), "psd_m": psd.tolist(),
                "psd_se_m": se.tolist(), "by_pressure": by_pressure}


def _other(ds: Any, kind: str, i: int) -> FloatArray | None:
    """The saved μ of model i with the other boundary-element area, None where absent (all NaN or an older file)."""
    if f"{kind}_mu_other" not in ds:
        return None
    v = np.asarray(ds[f"{kind}_mu_other"].values[i], dtype=np.float64)
    return None if np.all(np.isnan(v)) else v


def _finite(v: float) -> float | None:
    return float(v) if math.isfinite(v) else None


@dataclass(frozen=True, kw_only=True, eq=False)
class ContactModelSpread:
    """μ at the prescribed pressures by every model on the same samples (module docstring).

    ``surrogates[m]`` and ``windows[m]`` are the :class:`ModelSamples` of model m on the R surrogates and on the
    J disjoint measured windows (``windows`` empty when the map holds too few summits for 2 × 2 windows).
    """

    pressure_pa: FloatArray
    models: tuple[str, ...]
    surrogates: dict[str, ModelSamples]
    windows: dict[str, ModelSamples]
    window_tiles: int | None
    window_size_m: tuple[float, float] | None
    plasticity_index: float | None
    recommended: tuple[str, ...]
    recommendation: str
    surrogate_method: str
    surrogate_choice: str
    realizations: int
    control: LoadControl
    material: dict[str, Any]
    seed_entropy: Any
    surface_info: dict[str, Any]
    paths: dict[str, ModelPath] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    # --- statistics ------------------------------------------------------------------

    def surrogate_statistics(self, model: str) -> dict[str, FloatArray]:
        """E[μ], σ_μ and their Monte Carlo standard errors over the surrogates (delta method), per pressure."""
        mean, std, mean_se, std_se = mean_and_std_errors(self.surrogates[model].mu)
        return {"mu_mean": mean, "mu_std": std, "mu_mean_se": mean_se, "mu_std_se": std_se,
                "area_fraction": self.surrogates[model].area_fraction.mean(axis=0)}

    def window_statistics(self, model: str) -> dict[str, FloatArray] | None:
        """E[μ] and σ_μ over the measured windows with their 95 % intervals (None without windows)."""
        if model not in self.windows or self.window_tiles is None:
            return None
        mu = self.windows[model].mu
        per_scan = mu.shape[0] // (self.window_tiles**2)
        blocks = np.split(mu, per_scan) if per_scan > 1 else [mu]
        _all, mean, mean_ci, std, std_ci, rho1, n_eff = window_summary(blocks, self.window_tiles)
        return {"mu_mean": mean, "mu_mean_ci95": mean_ci, "mu_std": std, "mu_std_ci95": std_ci,
                "neighbour_correlation": rho1, "effective_windows": n_eff}

    def envelope(self) -> dict[str, FloatArray]:
        """Per pressure: the lowest and the highest E[μ] (surrogates) over the models and the relative
        spread (max − min)/mean of the models' E[μ]."""
        means = np.stack([self.surrogate_statistics(m)["mu_mean"] for m in self.models])
        return {"mu_min": means.min(axis=0), "mu_max": means.max(axis=0),
                "relative_spread": (means.max(axis=0) - means.min(axis=0)) / means.mean(axis=0)}

    def ratio(self, numerator: str, denominator: str) -> FloatArray | None:
        """E[μ] of one model over another's at every pressure (equal load: the ratio of the mean contact
        areas); None when one of them was not run."""
        if numerator not in self.models or denominator not in self.models:
            return None
        return self.surrogate_statistics(numerator)["mu_mean"] / self.surrogate_statistics(denominator)["mu_mean"]

    def uncertainty_split(self) -> dict[str, Any]:
        """How sure E[μ] is, split into surface sampling and model choice, per pressure.

        *Sampling*: the half-width of the measured windows' 95 % interval of E[μ] under the reference model
        (the first recommended model that was run) — what one measurement can say; without windows, 1.96 × the
        surrogates' Monte Carlo SE (a lower bound, stated).  *Model*: half the range of E[μ] over the models
        that were run (on the same surrogates).  The model share is model² / (model² + sampling²)."""
        reference = next((m for m in self.recommended if m in self.models), self.models[0])
        windows = self.window_statistics(reference)
        if windows is not None:
            ci = windows["mu_mean_ci95"]
            sampling = 0.5 * (ci[:, 1] - ci[:, 0])
            source = f"measured windows ({reference}): half-width of the 95 % interval of E[mu]"
        else:
            sampling = 1.96 * self.surrogate_statistics(reference)["mu_mean_se"]
            source = f"surrogates ({reference}): 1.96 x the Monte Carlo SE (no measured windows; a lower bound)"
        env = self.envelope()
        model = 0.5 * (env["mu_max"] - env["mu_min"])
        with np.errstate(invalid="ignore", divide="ignore"):
            share = model**2 / (model**2 + sampling**2)
        return {"reference_model": reference, "sampling_half_width": sampling, "sampling_source": source,
                "model_half_width": model, "model_share_of_variance": share,
                "discretisation_half_width": self.discretisation_half_width()}

    def discretisation_half_width(self) -> FloatArray | None:
        """Per pressure, the largest half difference of E[μ] (surrogates) of a boundary-element model between its
        two area estimators — the perimeter-corrected area and the pixel count (docs/bem_validation.md §4): how
        much of that model's E[μ] rests on the grid rather than the contact.  None without a boundary-element
        model (or in a file saved before both areas were kept)."""
        halves = [0.5 * np.abs(self.surrogates[m].mu.mean(axis=0) - other.mean(axis=0))
                  for m in self.models if (other := self.surrogates[m].mu_other) is not None]
        return np.max(np.stack(halves), axis=0) if halves else None

    # --- output ----------------------------------------------------------------------

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (SI units in the keys; per-sample arrays are in the NetCDF file)."""
        def lst(a: npt.ArrayLike) -> list[Any]:
            return [None if not math.isfinite(float(v)) else float(v) for v in np.ravel(np.asarray(a, dtype=float))]

        per_model: dict[str, Any] = {}
        for m in self.models:
            sur = self.surrogate_statistics(m)
            win = self.window_statistics(m)
            samples = self.surrogates[m]
            per_model[m] = {
                "surrogates": {k: lst(v) for k, v in sur.items()},
                "measured_windows": None if win is None else {
                    "mu_mean": lst(win["mu_mean"]), "mu_mean_ci95": [lst(r) for r in win["mu_mean_ci95"]],
                    "mu_std": lst(win["mu_std"]), "mu_std_ci95": [lst(r) for r in win["mu_std_ci95"]],
                    "effective_windows": lst(win["effective_windows"])},
                "mean_contacts": lst(np.nanmean(samples.n_contacts, axis=0)) if np.any(np.isfinite(samples.n_contacts))
                else None,
                "mu_mean_other_area": None if samples.mu_other is None else {
                    "area": "pixels" if self.control.bem_area == "corrected" else "corrected",
                    "mu_mean": lst(samples.mu_other.mean(axis=0))},
                "solver": {"used": list(dict.fromkeys(
                               samples.solvers + (self.windows[m].solvers if m in self.windows else ()))),
                           "max_iterations_used": int(np.max(samples.iterations)) if samples.iterations.size else 0,
                           "seconds_total": float(samples.seconds.sum() + (self.windows[m].seconds.sum()
                                                                           if m in self.windows else 0.0)),
                           "seconds_per_sample_max": float(samples.seconds.max()),
                           "warnings": list(dict.fromkeys(
                               samples.warnings + (self.windows[m].warnings if m in self.windows else ())))},
            }
        split = self.uncertainty_split()
        env = self.envelope()
        gw_bem = self.ratio("gw", "bem")
        return {
            "kind": SPREAD_KIND,
            "pressure_pa": lst(self.pressure_pa),
            "models": list(self.models),
            "per_model": per_model,
            "envelope": {k: lst(v) for k, v in env.items()},
            "ratio_gw_to_bem": None if gw_bem is None else lst(gw_bem),
            "uncertainty": {k: (lst(v) if isinstance(v, np.ndarray) else v) for k, v in split.items()},
            "plasticity_index": self.plasticity_index,
            "recommended_models": list(self.recommended),
            "recommendation": self.recommendation,
            "surrogate_method": self.surrogate_method,
            "surrogate_choice": self.surrogate_choice,
            "realizations": self.realizations,
            "measured_windows": None if self.window_tiles is None else {
                "tiles": self.window_tiles, "windows": int(next(iter(self.windows.values())).mu.shape[0]),
                "window_size_m": list(self.window_size_m or ())},
            "path": {m: v.to_dict() for m, v in self.paths.items()},
            "load_control": self.control.to_dict(),
            "material": self.material,
            "seed_entropy": self.seed_entropy,
            "surface": self.surface_info,
            "notes": list(self.notes),
        }

    def to_dataset(self) -> Any:
        """Per-sample arrays as an :class:`xarray.Dataset` (dims model, sample / window, pressure)."""
        import xarray as xr

        data: dict[str, Any] = {}
        for kind, group in (("surrogate", self.surrogates), ("window", self.windows)):
            if not group:
                continue
            for q in ("mu", "area_fraction", "n_contacts", "iterations"):
                data[f"{kind}_{q}"] = (("model", kind, "pressure"),
                                       np.stack([getattr(group[m], q) for m in self.models]))
            if any(group[m].mu_other is not None for m in self.models):
                other = [np.full_like(g.mu, np.nan) if g.mu_other is None else g.mu_other
                         for g in (group[m] for m in self.models)]
                data[f"{kind}_mu_other"] = (("model", kind, "pressure"), np.stack(other),
                                            {"units": "1", "long_name": "mu with the other boundary-element area "
                                                                        "estimator (NaN: not a BEM model)"})
        coords: dict[str, Any] = {"model": list(self.models), "pressure": self.pressure_pa}
        groups = {"surrogate": self.surrogates, "window": self.windows}
        for kind, group in groups.items():
            if group:
                data[f"{kind}_seconds"] = (("model", kind), np.stack([group[m].seconds for m in self.models]),
                                           {"units": "s", "long_name": "wall time of each sample"})
        if self.paths:
            coords["path_model"] = list(self.paths)
            coords["path_pressure"] = next(iter(self.paths.values())).pressures_pa
            data["path_mu"] = (("path_model", "long_surface", "path_window", "path_pressure"),
                               np.stack([v.mu for v in self.paths.values()]),
                               {"units": "1", "long_name": "mu along the windows of the long surfaces (ModelPath)"})
        ds = xr.Dataset(data, coords=coords)
        ds["pressure"].attrs["units"] = "Pa"
        ds.attrs["kind"] = SPREAD_KIND
        ds.attrs["seed_entropy"] = str(self.seed_entropy)
        ds.attrs["solvers_json"] = json.dumps({k: {m: list(g[m].solvers) for m in g} for k, g in groups.items()})
        ds.attrs["warnings_json"] = json.dumps({k: {m: list(g[m].warnings) for m in g} for k, g in groups.items()})
        ds.attrs["paths_json"] = json.dumps({m: {"pressures_pa": v.pressures_pa.tolist(),
                                                 "window_shift_m": v.window_shift_m,
                                                 "window_length_m": v.window_length_m} for m, v in self.paths.items()})
        return ds

    @classmethod
    def load(cls, path: str | Path) -> Self:
        """The spread :func:`~stochfric.process.pipeline.write_spread` wrote (``stochfric contact-models --out``,
        ``friction-process --contact-model … --out``), from either of its files: the summary
        ``contact_models.json`` and the per-sample ``contact_models_samples.nc`` beside it (both are read).
        A missing file is a :class:`FileNotFoundError`, a file of another kind an
        :class:`~stochfric.errors.InputError`.  A file of a stochfric before the per-sample wall times and the
        path arrays were saved reads with NaN wall times and without :attr:`paths`."""
        p = Path(path).expanduser()
        stem = p.stem.removesuffix(SAMPLES_SUFFIX) if p.suffix == ".nc" else p.stem
        summary_path, samples_path = p.with_name(f"{stem}.json"), p.with_name(f"{stem}{SAMPLES_SUFFIX}.nc")
        what = "contact-model spread (contact_models.json with contact_models_samples.nc)"
        d = read_json_file(summary_path, what)
        if not isinstance(d, dict) or d.get("kind") != SPREAD_KIND:
            raise ResultFileError(f"{summary_path} is not the summary of a {what}; stochfric.load reads any "
                                  "saved result")
        ds = read_netcdf(samples_path, what)
        if ds.attrs.get("kind") != SPREAD_KIND:
            raise ResultFileError(f"{samples_path} is not the per-sample file of a {what}")
        models = tuple(str(m) for m in ds["model"].values)
        p_pa = np.asarray(ds["pressure"].values, dtype=np.float64)
        solvers = json.loads(ds.attrs.get("solvers_json", "{}"))
        warnings = json.loads(ds.attrs.get("warnings_json", "{}"))

        def samples(kind: str) -> dict[str, ModelSamples]:
            if f"{kind}_mu" not in ds:
                return {}
            n = ds.sizes[kind]
            return {m: ModelSamples(
                model=m, pressure_pa=p_pa, **{q: np.asarray(ds[f"{kind}_{q}"].values[i], dtype=np.float64)
                                             for q in ("area_fraction", "n_contacts", "mu", "iterations")},
                seconds=(np.asarray(ds[f"{kind}_seconds"].values[i], dtype=np.float64) if f"{kind}_seconds" in ds
                         else np.full(n, np.nan)),
                warnings=tuple(warnings.get(kind, {}).get(m, ())), solvers=tuple(solvers.get(kind, {}).get(m, ())),
                mu_other=_other(ds, kind, i),
            ) for i, m in enumerate(models)}  # fmt: skip

        paths: dict[str, ModelPath] = {}
        if "path_mu" in ds:
            record = json.loads(ds.attrs["paths_json"])
            for i, m in enumerate(str(v) for v in ds["path_model"].values):
                mu = np.asarray(ds["path_mu"].values[i], dtype=np.float64)
                rec = dict(record[m])
                if "pressure_pa" in rec:  # saved with one path pressure
                    rec["pressures_pa"] = [rec.pop("pressure_pa")]
                    mu = mu[:, :, None]
                paths[m] = ModelPath(model=m, mu=mu, pressures_pa=np.asarray(rec.pop("pressures_pa"), dtype=np.float64),
                                     **rec)
        windows = d.get("measured_windows")
        return cls(
            pressure_pa=p_pa, models=models, surrogates=samples("surrogate"), windows=samples("window"),
            window_tiles=None if windows is None else int(windows["tiles"]),
            window_size_m=tuple(windows["window_size_m"]) if windows and windows.get("window_size_m") else None,
            plasticity_index=d.get("plasticity_index"), recommended=tuple(d.get("recommended_models", ())),
            recommendation=d.get("recommendation", ""), surrogate_method=d.get("surrogate_method", ""),
            surrogate_choice=d.get("surrogate_choice", ""), realizations=int(d["realizations"]),
            control=LoadControl(**{"bem_area": "pixels", **d["load_control"]}), material=d.get("material", {}),
            seed_entropy=d.get("seed_entropy"), surface_info=d.get("surface", {}), paths=paths,
            notes=list(d.get("notes", [])),
        )  # fmt: skip


def _check_pressures(pressures_pa: npt.ArrayLike, material: Material, models: Sequence[str]) -> FloatArray:
    """The pressures sorted, checked once before any sample is solved (the boundary-element layer's rule,
    :func:`~stochfric.contact.bem.check_nominal_pressures`, with the hardness when ``bem-plastic`` is run)."""
    try:
        p = check_nominal_pressures(pressures_pa, material.hardness if "bem-plastic" in models else None)
    except ContactError as exc:
        raise AnalysisError(str(exc)) from None
    return np.sort(p)


def contact_model_spread(
    surface: Surface | Sequence[Surface],
    material: Material,
    pressures_pa: npt.ArrayLike,
    models: str | Sequence[str] = ALL_MODELS,
    config: AnalysisConfig | None = None,
    *,
    control: LoadControl | None = None,
    path_surfaces: int = 0,
    path_pressure_pa: float | npt.ArrayLike | None = None,
    workers: int | None = 1,
    progress: Callable[[str, int, int], None] | None = None,
) -> ContactModelSpread:
    """Solve the measured windows and the surrogates of ``surface`` (one prepared map or pooled scans on one
    grid) by every contact model of ``models`` at the nominal ``pressures_pa`` [Pa] (module docstring).

    The surrogates are those of :func:`~stochfric.process.statistics.analyse` with the same ``config``
    (method, realisations, seed: realisation r is scan r mod S with child stream r of the ensemble stream), so
    this is the model spread of exactly the analysed ensemble.  ``workers`` processes share the samples; the
    numbers do not depend on it.  ``progress(stage, done, total)`` after every sample.

    ``path_surfaces`` > 0: also μ along the windows of that many of the analysis's long surfaces (its path
    stream, so the first K of its long surfaces) at ``path_pressure_pa`` [Pa] (one or several; default: the
    lowest, the geometric mean and the highest of the pressures) by every model — the path spectrum and
    correlation length per model and pressure (:class:`ModelPath`)."""
    cfg = config if config is not None else AnalysisConfig()
    ctl = control if control is not None else LoadControl()
    scans = [surface] if isinstance(surface, Surface) else list(surface)
    if not scans:
        raise AnalysisError("no surface to analyse")
    chosen = parse_contact_models(models)
    p = _check_pressures(pressures_pa, material, chosen)
    if any(m.startswith("bem") for m in chosen):
        from stochfric.contact.bem import bem_available

        auto = {"bem": "tamaas", "bem-plastic": "contactmechanics"}
        needed = {ctl.bem_solver if ctl.bem_solver != "auto" else auto[m] for m in chosen if m in auto}
        for solver in sorted(needed):
            if not bem_available(solver):
                raise AnalysisError(f"the boundary-element models need the solver {solver!r}: "
                                    "pip install 'stochfric[halfspace]'")
    rule = cfg.summit_rule
    options, choice = cfg.surrogate_for([s.heights_m for s in scans])
    root = as_seed_sequence(cfg.seed)
    s_ens = child_seed(root, ENSEMBLE_STREAM)  # the ensemble stream of analyse()
    r_count = cfg.realizations
    seeds = spawn_seed_sequences(s_ens, r_count)
    found = [find_summits(s.heights_m, s.grid_spacing_m, rule=rule) for s in scans]
    counts = [f.count for f in found]
    tiles = choose_tiles(min(counts))
    boxes = tile_grid(scans[0].nb_grid_pts, tiles) if tiles is not None else []
    size = scans[0].physical_size_m
    dx, dy = scans[0].grid_spacing_m
    window_jobs = [(k, b) for k in range(len(scans)) for b in boxes]

    def solve_all(h: FloatArray, phys: tuple[float, float]) -> dict[str, _One]:
        try:
            return {m: sample_contact(h, phys, material, p, m, rule=rule, control=ctl) for m in chosen}
        except ContactError as exc:
            raise AnalysisError(str(exc)) from None

    def surrogate(r: int) -> dict[str, _One]:
        sim = _similar(options, scans[r % len(scans)], seeds[r])
        return solve_all(sim, size)

    def window(w: int) -> dict[str, _One]:
        k, (i0, i1, j0, j1) = window_jobs[w]
        return solve_all(np.ascontiguousarray(scans[k].heights_m[i0:i1, j0:j1]), ((i1 - i0) * dx, (j1 - j0) * dy))

    def done(stage: str, total: int) -> Callable[[int], None] | None:
        return None if progress is None else (lambda k: progress(stage, k, total))

    paths = _paths(scans, material, chosen, cfg, options, root, path_surfaces, path_pressure_pa, p, rule, ctl,
                   workers, progress)
    win = map_indexed(window, len(window_jobs), workers=workers, done=done("measured windows", len(window_jobs)))
    sur = map_indexed(surrogate, r_count, workers=workers, done=done("surrogates", r_count))
    tau = material.shear_strength_pa
    surrogates = {m: ModelSamples.of(m, p, [o[m] for o in sur], tau) for m in chosen}
    windows = {m: ModelSamples.of(m, p, [o[m] for o in win], tau) for m in chosen} if win else {}
    psi = plasticity_index_of(found, material)
    from stochfric.contact.persson import recommend_contact_models

    recommended, why = recommend_contact_models(psi)
    notes = []
    if tiles is None:
        notes.append(f"the map holds {min(counts)} summits, too few for 2 x 2 measured windows: the sampling "
                     "uncertainty is the surrogates' Monte Carlo error only (a lower bound)")
    window_size = None
    if boxes:
        i0, i1, j0, j1 = boxes[0]
        window_size = ((i1 - i0) * dx, (j1 - j0) * dy)
    info = {"source": scans[0].source, "grid": list(scans[0].nb_grid_pts),
            "physical_size_m": list(scans[0].physical_size_m), "scans": [s.source for s in scans]}
    return ContactModelSpread(
        pressure_pa=p, models=chosen, surrogates=surrogates, windows=windows, window_tiles=tiles,
        window_size_m=window_size, plasticity_index=psi, recommended=tuple(recommended), recommendation=why,
        surrogate_method=options.method, surrogate_choice=choice, realizations=r_count, control=ctl,
        material=material.to_dict(), seed_entropy=seed_entropy(root), surface_info=info, paths=paths, notes=notes,
    )  # fmt: skip


def _paths(scans: list[Surface], material: Material, chosen: tuple[str, ...], cfg: AnalysisConfig,
           options: SurrogateOptions, root: np.random.SeedSequence, surfaces: int,
           pressure_pa: float | npt.ArrayLike | None,
           p: FloatArray, rule: str, ctl: LoadControl, workers: int | None,
           progress: Callable[[str, int, int], None] | None) -> dict[str, ModelPath]:
    """μ along the windows of the first ``surfaces`` long surfaces of the analysis at the path pressures (all in
    one solve per window, warm-started), per model."""
    if surfaces <= 0:
        return {}
    if surfaces < 2:
        raise AnalysisError("path_surfaces must be 0 (no path) or >= 2 (the correlation length needs a scatter)")
    if pressure_pa is None:
        p_path = np.unique([float(p.min()), float(np.exp(np.mean(np.log(p)))), float(p.max())])
    else:
        p_path = np.unique(np.atleast_1d(np.asarray(pressure_pa, dtype=np.float64)))
    p_path = _check_pressures(p_path, material, chosen)
    seeds = spawn_seed_sequences(child_seed(root, PATH_STREAM), surfaces)  # the long surfaces of analyse()
    nx, ny = scans[0].nb_grid_pts
    dx, dy = scans[0].grid_spacing_m
    shift = cfg.window_shift_points

    def one(k: int) -> dict[str, FloatArray]:
        rng = np.random.Generator(np.random.PCG64(seeds[k]))
        long = options.similar(scans[k % len(scans)], rng, cfg.length_factor).heights_m
        starts = window_starts(long.shape[1], ny, shift)
        out = {m: np.empty((starts.size, p_path.size)) for m in chosen}
        for w, s0 in enumerate(starts):
            h = np.ascontiguousarray(long[:, s0: s0 + ny])
            for m in chosen:
                try:
                    frac = sample_contact(h, (nx * dx, ny * dy), material, p_path, m, rule=rule, control=ctl)
                except ContactError as exc:
                    raise AnalysisError(str(exc)) from None
                out[m][w] = material.shear_strength_pa * frac.area_fraction / p_path
        return out

    done = None if progress is None else (lambda k: progress("path", k, surfaces))
    per = map_indexed(one, surfaces, workers=workers, done=done)
    return {m: ModelPath(model=m, pressures_pa=p_path, mu=np.stack([r[m] for r in per]), window_shift_m=shift * dy,
                         window_length_m=ny * dy) for m in chosen}


def _similar(options: SurrogateOptions, scan: Surface, seed: np.random.SeedSequence) -> FloatArray:
    """The heights of one surrogate of ``scan`` with the analysis's options and child stream ``seed``."""
    return np.ascontiguousarray(options.similar(scan, np.random.Generator(np.random.PCG64(seed))).heights_m)


def process_model_for(model: TabulatedProcessModel, spread: ContactModelSpread, contact_model: str,
                      *, reference: str = "gw") -> tuple[TabulatedProcessModel, dict[str, Any]]:
    """The friction-process model of the analysis (GW) with its E[μ](p) and σ_μ(p) from ``contact_model``.

    E[μ] and σ_μ of the model's surrogates at the spread's pressures are fitted by f(p) = a p^b + c (3.21)
    with their Monte Carlo errors, as the GW fits are.  The *shape* of the path spectrum stays the GW
    analysis's (K long surfaces × all windows at every pressure is beyond a boundary-element budget); its
    level is scaled by (σ_μ,model/σ_μ,GW)² at every tabulated pressure (log-p interpolation of the ratio,
    clamped), so the tabulated variance matches the model too.  Whether the shape carries over is checked
    where the spread holds a path (:class:`ModelPath`): the correlation lengths of both models at its middle
    pressure (``correlation_length_m``) and at every path pressure (``path_check``; by default the lowest,
    middle and highest of the spread's) are returned in the record.  Returns the model and that record."""
    from stochfric.process.fit import fit_model_function

    if contact_model == reference:
        return model, {"contact_model": reference}
    if contact_model not in spread.models or reference not in spread.models:
        raise AnalysisError(f"the spread holds {', '.join(spread.models)}; it needs {contact_model} and {reference}")
    p = spread.pressure_pa
    if p.size < 4:
        raise AnalysisError(f"a fit of a p^b + c needs at least 4 pressures, the spread has {p.size}")
    mine, ref = spread.surrogate_statistics(contact_model), spread.surrogate_statistics(reference)
    rule = {"contact_model": contact_model, "pressures": "the spread's (load control)"}
    mean_fit = fit_model_function(p, mine["mu_mean"], mine["mu_mean_se"], rule=rule)
    std_fit = fit_model_function(p, mine["mu_std"], mine["mu_std_se"], rule=rule)
    ratio2 = (mine["mu_std"] / ref["mu_std"]) ** 2
    table_p = np.asarray(model.pressures_pa, dtype=np.float64)
    scale = np.exp(np.interp(np.log(table_p), np.log(p), np.log(ratio2)))
    table = np.asarray(model.table_psd, dtype=np.float64) * scale[:, None]
    level = model.psd_level
    if level is not None:
        values = np.array([level(float(v)) for v in p]) * ratio2
        level = fit_model_function(p, values, None, rule=rule).model_function()
    record: dict[str, Any] = {
        "contact_model": contact_model, "reference": reference, "pressure_pa": p.tolist(),
        "mu_mean_ratio_to_reference": (mine["mu_mean"] / ref["mu_mean"]).tolist(),
        "mu_std_ratio_to_reference": np.sqrt(ratio2).tolist(),
        "spectrum_shape": f"from the {reference} path analysis, level scaled by (sigma_mu ratio)^2",
    }
    if contact_model in spread.paths and reference in spread.paths:
        mine_path, ref_path = spread.paths[contact_model], spread.paths[reference]
        record["correlation_length_m"] = {m: spread.paths[m].correlation_length()[:2]
                                          for m in (reference, contact_model)}
        # the check of the GW shape over the path pressures: the model's correlation length over GW's, per pressure
        record["path_check"] = [
            {"pressure_pa": float(pk), "correlation_length_m": {reference: ref_path.correlation_length(k)[:2],
                                                                 contact_model: mine_path.correlation_length(k)[:2]}}
            for k, pk in enumerate(mine_path.pressures_pa)]
    new = dataclasses.replace(
        model, name=f"{model.name} [{contact_model}]", mu_mean=mean_fit.model_function(),
        mu_std=std_fit.model_function(), psd_level=level,
        table_psd=tuple(tuple(float(v) for v in row) for row in table),
        fitted_range_pa=(float(p.min()), float(p.max())), contact_model=contact_model,
    )  # fmt: skip
    return new, record

"""The statistical contact analysis: from one measured surface to a friction-process model.

method §3–§4 (thesis 3.1.4, 3.2.4, 3.2.5, 3.3.3, 3.3.4).  :func:`analyse` runs

a) the **ensemble** (:func:`~stochfric.process.ensemble.ensemble_contact`): R surrogates of
   original size → E[μ], σ_μ, PDFs of μ per approach, mean A_c/A_nom over the mean pressure
   E[N]/A_nom with a linear fit (Fig. 3.16–3.18a);
b) the **ergodicity check** (:func:`~stochfric.process.checks.ergodicity_check`): non-overlapping windows of original
   size along each of K long surfaces against the same windows across the independent
   surfaces, all from one generator (Fig. 3.18b; the thesis compared with a), whose
   realisations come from another generator — see the class docstring);
c) **μ along the path** (:func:`~stochfric.process.ensemble.path_contact`): K long surfaces,
   windows shifted by a_y → μ(y), autocorrelation, correlation length, PSD (method §0),
   averaged over the surfaces (Fig. 3.19–3.21);
d) the **model functions** f(p) = a p^b + c for E[μ], σ_μ and the PSD level over the mean
   pressure of c), high-pressure points excluded (:mod:`stochfric.process.fit`; Fig. 3.22);
e) the **friction-process model** (:class:`~stochfric.process.model.TabulatedProcessModel`)
   and the check of generated realisations against it
   (:func:`~stochfric.process.checks.check_generated_process`, Fig. 3.23);
f) the check that the surrogates resemble the measured map
   (:func:`~stochfric.process.checks.surrogate_check`) and the validity warnings of the model on
   this surface (:mod:`stochfric.contact.validity`).  Memory is estimated before any work
   (:mod:`stochfric.process.memory`).

Standard errors.  Windows on one long surface overlap and are correlated, so the standard
errors of the path statistics (E[μ], σ_μ, PSD level) are taken from the scatter between the K
independent long surfaces: SE = sd(per-surface values)/√K.  Ensemble statistics use the R
independent realisations: SE(E[μ]) = s/√R, SE(σ_μ) = √((m4 − s⁴)/R)/(2s) (delta method with the
sample fourth central moment m4; no Gaussian assumption).
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from stochfric.contact.asperity import ContactError
from stochfric.contact.materials import Material
from stochfric.contact.validity import ValidityWarning, contact_validity
from stochfric.io_utils import package_versions, write_netcdf_atomic
from stochfric.process.checks import (
    ErgodicityCheck,
    ProcessCheck,
    SurrogateCheck,
    check_generated_process,
    ergodicity_check,
    surrogate_check,
)
from stochfric.process.ensemble import ContactSamples, PathContact, ensemble_contact, path_contact
from stochfric.process.estimators import linear_fit, mean_and_std_errors
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION, ModelFit, fit_mask, fit_model_function
from stochfric.process.memory import check_memory
from stochfric.process.model import TabulatedProcessModel
from stochfric.process.spectra import autocorrelation, correlation_length, mean_psd, psd_level
from stochfric.process.spectral import one_sided_psd
from stochfric.progress import StagedProgress
from stochfric.random import as_seed_sequence, seed_entropy, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.statistics import plasticity_index
from stochfric.surface.summits import find_summits
from stochfric.surface.synthesis import AMPLITUDE_METHODS, DEFAULT_AMPLITUDE

__all__ = [
    "AnalysisConfig",
    "StatisticalContactAnalysis",
    "analyse",
]

FloatArray = npt.NDArray[np.float64]


@dataclass(frozen=True, kw_only=True)
class AnalysisConfig:
    """Settings of :func:`analyse` (defaults: the thesis's proportions, §3.2.4–3.2.5).

    ``window_shift_points`` is a_y in grid points of y; ``length_factor`` the long surfaces'
    length in units of the original (thesis: 53 mm / 5.3 mm = 10), which is also the number of
    non-overlapping windows per long surface in the ergodicity check; ``amplitude`` the
    amplitude estimate of the measured map (``"hann"``: edge jump removed, default; ``"raw"``:
    the thesis's DFT of the map as it is, :func:`stochfric.surface.synthesis.amplitude_spectrum`).
    """

    realizations: int = 100
    long_surfaces: int = 10
    length_factor: int = 10
    window_shift_points: int = 16
    surrogate: str = "phase"
    amplitude: str = DEFAULT_AMPLITUDE
    summit_rule: str = "thesis"
    iaaft_tol: float = 1e-3
    max_area_fraction: float = DEFAULT_MAX_AREA_FRACTION
    pressure_rule: str = "nearest"
    variance_rule: str = "sigma_mu"
    sigma_zeta_rule: str = "sigma_mu"
    pdf_bins: int = 30
    check_realizations: int = 200
    seed: int | None = None

    def __post_init__(self) -> None:
        for name in ("realizations", "long_surfaces", "window_shift_points", "pdf_bins", "check_realizations"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 1:
                raise ContactError(f"{name} must be an integer >= 1, got {v!r}")
        v = self.length_factor
        if isinstance(v, bool) or not isinstance(v, int) or v < 2:
            raise ContactError(f"length_factor must be an integer >= 2, got {v!r}")
        if self.realizations < 2:
            raise ContactError("realizations must be >= 2 (a standard deviation needs two)")
        if self.long_surfaces < 3:
            raise ContactError(
                f"long_surfaces must be >= 3 (the ergodicity check and the standard errors of the path "
                f"statistics use the scatter between independent long surfaces), got {self.long_surfaces}"
            )
        if self.amplitude not in AMPLITUDE_METHODS:
            raise ContactError(f"amplitude must be one of {AMPLITUDE_METHODS}, got {self.amplitude!r}")
        if not 0.0 < self.max_area_fraction <= 1.0:
            raise ContactError(f"max_area_fraction must lie in (0, 1], got {self.max_area_fraction!r}")

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary (JSON / netCDF attributes)."""
        return dict(self.__dict__)


@dataclass(frozen=True, kw_only=True, eq=False)
class StatisticalContactAnalysis:
    """All results of :func:`analyse` (SI units; arrays over the approach u last)."""

    config: AnalysisConfig
    seed_entropy: int
    material: dict[str, Any]
    surface_info: dict[str, Any]
    ensemble: ContactSamples
    path: PathContact
    # ensemble statistics (a)
    ensemble_mu_mean: FloatArray
    ensemble_mu_std: FloatArray
    ensemble_mu_mean_se: FloatArray
    ensemble_mu_std_se: FloatArray
    ensemble_pressure_pa: FloatArray
    ensemble_area_fraction: FloatArray
    pdf_edges: FloatArray
    pdf_density: FloatArray
    contact_fraction_fit: dict[str, float]
    ergodicity: ErgodicityCheck
    surrogate_check: SurrogateCheck
    # path statistics (c)
    pressure_pa: FloatArray
    area_fraction: FloatArray
    mu_mean: FloatArray
    mu_std: FloatArray
    mu_mean_se: FloatArray
    mu_std_se: FloatArray
    lags_m: FloatArray
    acf: FloatArray
    correlation_length_m: FloatArray
    frequencies: FloatArray
    psd: FloatArray
    psd_se: FloatArray
    psd_level: FloatArray
    psd_level_se: FloatArray
    # fits (d) and model (e)
    fits: dict[str, ModelFit]
    model: TabulatedProcessModel
    process_check: ProcessCheck
    notes: list[str] = field(default_factory=list)
    #: Validity of the model on this surface (:mod:`stochfric.contact.validity`): μ > 1,
    #: A_c/A_nom > 1 or beyond the non-interaction range, too few contacts, plasticity index.
    warnings: list[ValidityWarning] = field(default_factory=list)

    def sigma_zeta_table(self) -> dict[str, list[float]]:
        """σ_ζ at the analysed pressures by both rules (``sigma_mu`` and ``spectral_level``)."""
        from dataclasses import replace

        out: dict[str, list[float]] = {"pressure_pa": [float(p) for p in self.pressure_pa]}
        for rule in ("sigma_mu", "spectral_level"):
            m = replace(self.model, sigma_zeta_rule=rule)
            vals: list[float] = []
            for p in self.pressure_pa:
                try:
                    vals.append(m.sigma_zeta(float(p)))
                except ValueError:
                    vals.append(math.nan)
            out[rule] = vals
        return out

    def to_json_dict(self) -> dict[str, Any]:
        """The JSON summary of the command line (SI units, p in Pa)."""

        def lst(a: npt.ArrayLike) -> list[float | None]:
            return [None if not math.isfinite(float(v)) else float(v) for v in np.ravel(a)]

        finite_cl = self.correlation_length_m[np.isfinite(self.correlation_length_m)]
        return {
            "approach_m": lst(self.ensemble.approach_m),
            "pressure_pa": lst(self.pressure_pa),
            "area_fraction": lst(self.area_fraction),
            "mu_mean": lst(self.mu_mean),
            "mu_std": lst(self.mu_std),
            "mu_mean_se": lst(self.mu_mean_se),
            "mu_std_se": lst(self.mu_std_se),
            "psd_level_m": lst(self.psd_level),
            "correlation_length_m": lst(self.correlation_length_m),
            "correlation_length_mean_m": float(finite_cl.mean()) if finite_cl.size else None,
            "window_shift_m": self.path.window_shift_m,
            "window_length_m": self.path.window_length_m,
            "long_surface_length_m": self.path.surface_length_m,
            "fit": {name: f.to_dict() for name, f in self.fits.items()},
            "ensemble": {
                "pressure_pa": lst(self.ensemble_pressure_pa),
                "mu_mean": lst(self.ensemble_mu_mean),
                "mu_std": lst(self.ensemble_mu_std),
                "area_fraction": lst(self.ensemble_area_fraction),
                "contact_fraction_fit": self.contact_fraction_fit,
            },
            "ergodicity": self.ergodicity.to_dict(),
            "surrogate_check": self.surrogate_check.to_dict(),
            "sigma_zeta": self.sigma_zeta_table(),
            "process_check": self.process_check.to_dict(),
            "model": self.model.to_dict(),
            "config": self.config.to_dict(),
            "seed_entropy": self.seed_entropy,
            "material": self.material,
            "surface": self.surface_info,
            "notes": list(self.notes),
            "warnings": [w.to_dict() for w in self.warnings],
        }

    def to_dataset(self) -> Any:
        """All statistics as an :class:`xarray.Dataset` (units and provenance in ``attrs``)."""
        ens, blocks, path = self.ensemble, self.path.blocks, self.path.samples
        u = ("approach",)

        def var(dims: tuple[str, ...], data: npt.ArrayLike, units: str, long_name: str) -> Any:
            return (dims, np.asarray(data), {"units": units, "long_name": long_name})

        data_vars = {
            "ensemble_mu": var(("realization", *u), ens.mu, "1", "mu of each realisation (3.16)"),
            "ensemble_pressure_pa": var(("realization", *u), ens.pressure_pa, "Pa", "p = N/A_nom per realisation"),
            "ensemble_area_fraction": var(("realization", *u), ens.area_fraction, "1", "A_c/A_nom per realisation"),
            "ensemble_mu_mean": var(u, self.ensemble_mu_mean, "1", "E[mu] over the ensemble"),
            "ensemble_mu_std": var(u, self.ensemble_mu_std, "1", "sigma_mu over the ensemble (ddof=1)"),
            "ensemble_mean_pressure_pa": var(u, self.ensemble_pressure_pa, "Pa", "E[N]/A_nom over the ensemble"),
            "ensemble_mean_area_fraction": var(u, self.ensemble_area_fraction, "1", "E[A_c]/A_nom"),
            "mu_pdf": var((*u, "pdf_bin"), self.pdf_density, "1", "PDF of mu over the ensemble"),
            "mu_pdf_edges": var((*u, "pdf_edge"), self.pdf_edges, "1", "bin edges of mu_pdf"),
            "block_mu": var(("surface", "block", *u), blocks.mu, "1",
                            "mu of the non-overlapping windows of the long surfaces (ergodicity check)"),
            "ergodic_z_mean": var(u, self.ergodicity.z_mean, "1", "ANOVA of the path means, as a two-sided z"),
            "ergodic_z_std": var(u, self.ergodicity.z_std, "1", "(sd along - sd across surfaces)/jackknife SE"),
            "surrogate_summit_stats": var(("realization", "summit_stat"),
                                          ens.summit_stats if ens.summit_stats is not None else np.empty((0, 3)),
                                          "mixed",
                                          "summit count [1], mean radius [m], summit-height sd [m] per realisation"),
            "measured_mu": var(u, self.surrogate_check.mu_measured, "1", "mu of the measured map itself"),
            "measured_mu_z": var(u, self.surrogate_check.mu_z, "1", "(measured - ensemble mean)/ensemble sd"),
            "path_mu": var(("surface", "window", *u), path.mu, "1", "mu(y) along the path (windows shifted by a_y)"),
            "path_pressure_pa": var(("surface", "window", *u), path.pressure_pa, "Pa", "p(y) of each window"),
            "pressure_pa": var(u, self.pressure_pa, "Pa", "mean pressure p(u) of the path windows"),
            "area_fraction": var(u, self.area_fraction, "1", "mean A_c/A_nom of the path windows"),
            "mu_mean": var(u, self.mu_mean, "1", "E[mu] along the path"),
            "mu_std": var(u, self.mu_std, "1", "sigma_mu along the path"),
            "mu_mean_se": var(u, self.mu_mean_se, "1", "SE of E[mu] from the K surfaces"),
            "mu_std_se": var(u, self.mu_std_se, "1", "SE of sigma_mu from the K surfaces"),
            "acf": var((*u, "lag"), self.acf, "1", "autocorrelation of normalised mu (3.17/3.18)"),
            "correlation_length_m": var(u, self.correlation_length_m, "m", "first zero crossing of the ACF"),
            "psd": var((*u, "frequency"), self.psd, "m", "one-sided PSD of mu-hat (method 0), surface mean"),
            "psd_se": var((*u, "frequency"), self.psd_se, "m", "SE of psd over surfaces"),
            "psd_level": var(u, self.psd_level, "m", "low-frequency PSD level E[S] = S(f->0)"),
            "psd_level_se": var(u, self.psd_level_se, "m", "SE of E[S] over surfaces"),
            "fit_used": var(u, np.asarray(self.fits["mu_mean"].used, dtype=np.int8), "1", "point used in the fits"),
        }
        attrs: dict[str, Any] = {
            "title": "stochfric statistical contact analysis (docs/method.md sections 3-4)",
            "config": json.dumps(self.config.to_dict(), sort_keys=True),
            "seed_entropy": str(self.seed_entropy),
            "material": json.dumps(self.material, sort_keys=True),
            "surface": json.dumps(self.surface_info, sort_keys=True, default=str),
            "fits": json.dumps({k: f.to_dict() for k, f in self.fits.items()}, sort_keys=True),
            "ergodicity": json.dumps(self.ergodicity.to_dict(), sort_keys=True),
            "surrogate_check": json.dumps(self.surrogate_check.to_dict(), sort_keys=True),
            "contact_fraction_fit": json.dumps(self.contact_fraction_fit, sort_keys=True),
            "window_shift_m": self.path.window_shift_m,
            "window_length_m": self.path.window_length_m,
            "long_surface_length_m": self.path.surface_length_m,
            "psd_convention": "one-sided, S_k = 2 dy |X_k|^2 / N, sum S df = variance (docs/method.md section 0)",
            "versions": json.dumps(package_versions(), sort_keys=True),
        }
        return xr.Dataset(
            data_vars=data_vars,
            coords={
                "approach_m": (u, ens.approach_m, {"units": "m", "long_name": "approach u (3.11)"}),
                "lag_m": (("lag",), self.lags_m, {"units": "m"}),
                "frequency_per_m": (("frequency",), self.frequencies, {"units": "1/m"}),
                "window_y_m": (("window",), self.path.positions_m, {"units": "m"}),
            },
            attrs=attrs,
        )

    def to_netcdf(self, path: str | Path) -> Path:
        """Write :meth:`to_dataset` atomically; a full disk is a clean ``OSError`` (``write_netcdf_atomic``)."""
        return write_netcdf_atomic(path, self.to_dataset())


def _pdfs(mu: FloatArray, bins: int) -> tuple[FloatArray, FloatArray]:
    n_u = mu.shape[1]
    edges = np.empty((n_u, bins + 1))
    dens = np.empty((n_u, bins))
    for k in range(n_u):
        col = mu[:, k][np.isfinite(mu[:, k])]
        lo, hi = (float(col.min()), float(col.max())) if col.size else (0.0, 1.0)
        if hi <= lo:
            hi = lo + 1e-12
        dens[k], edges[k] = np.histogram(col, bins=bins, range=(lo, hi), density=True)
    return edges, dens


def analyse(
    surface: Surface,
    material: Material,
    approach_m: npt.ArrayLike,
    config: AnalysisConfig | None = None,
    *,
    name: str | None = None,
    progress: StagedProgress | None = None,
) -> StatisticalContactAnalysis:
    """Run the statistical contact analysis a)–e) of the module docstring on ``surface``.

    ``surface`` is the prepared (detrended, filtered, coarsened) surface; windows run along y
    (axis 1).  Independent child streams of ``config.seed`` drive the ensemble, the long
    surfaces and the process check; inside each, realisation / surface k has its own child
    stream.  ``progress(stage, done, total)`` is called after every realisation / surface.
    """
    cfg = config if config is not None else AnalysisConfig()
    check_memory(surface.nb_grid_pts, cfg.length_factor)
    root = as_seed_sequence(cfg.seed)
    s_ens, _s_unused, s_path, s_check = spawn_seed_sequences(root, 4)  # stream 1: retired one-surface check
    u = np.asarray(approach_m, dtype=np.float64)

    def stage(label: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress(label, done, total)

    ens = ensemble_contact(
        surface, material, u, realizations=cfg.realizations, method=cfg.surrogate, seed=s_ens,
        rule=cfg.summit_rule, iaaft_tol=cfg.iaaft_tol, amplitude=cfg.amplitude, progress=stage("ensemble"),
    )  # fmt: skip
    path = path_contact(
        surface, material, u, long_surfaces=cfg.long_surfaces, length_factor=cfg.length_factor,
        shift_points=cfg.window_shift_points, method=cfg.surrogate, seed=s_path, rule=cfg.summit_rule,
        iaaft_tol=cfg.iaaft_tol, amplitude=cfg.amplitude, progress=stage("long surfaces"),
    )  # fmt: skip
    notes: list[str] = []
    mu_e = ens.mu
    if not np.all(np.isfinite(mu_e)):
        raise ContactError("a realisation carries no load at some approach (μ undefined); use larger approaches")
    e_mean, e_std, e_mean_se, e_std_se = mean_and_std_errors(mu_e)
    e_p = ens.normal_force_n.mean(axis=0) / ens.nominal_area_m2
    e_frac = ens.contact_area_m2.mean(axis=0) / ens.nominal_area_m2
    edges, dens = _pdfs(mu_e, cfg.pdf_bins)
    erg_check = ergodicity_check(path.blocks.mu)
    s_check_result = surrogate_check(surface, material, ens, rule=cfg.summit_rule)
    if not s_check_result.credible:
        notes.append(
            "the measured map lies outside its surrogate ensemble (|z| >= 3) for "
            + ", ".join(s_check_result.failures())
            + ": the surrogates do not resemble this surface, so the statistics describe the surrogates, not it "
            "(try --surrogate iaaft for a non-Gaussian height distribution, or check the preparation)"
        )

    # --- path statistics (c) --------------------------------------------------------------
    mu_p = path.samples.mu  # (K, W, U)
    k_count, n_win, n_u = mu_p.shape
    pooled = mu_p.reshape(-1, n_u)
    mu_mean = pooled.mean(axis=0)
    mu_std = pooled.std(axis=0, ddof=1)
    per_mean = mu_p.mean(axis=1)
    per_std = mu_p.std(axis=1, ddof=1)
    root_k = math.sqrt(k_count)
    mu_mean_se = per_mean.std(axis=0, ddof=1) / root_k if k_count > 1 else np.full(n_u, np.nan)
    mu_std_se = per_std.std(axis=0, ddof=1) / root_k if k_count > 1 else np.full(n_u, np.nan)
    p_path = path.samples.normal_force_n.mean(axis=(0, 1)) / path.samples.nominal_area_m2
    frac_path = path.samples.contact_area_m2.mean(axis=(0, 1)) / path.samples.nominal_area_m2
    a_y = path.window_shift_m
    acfs = np.stack([autocorrelation(mu_p[:, :, k]) for k in range(n_u)])
    lags = np.arange(acfs.shape[1], dtype=np.float64) * a_y
    corr = np.array([correlation_length(acfs[k], a_y) for k in range(n_u)])
    psd_rows, psd_se_rows, levels, level_se = [], [], [], []
    freqs: FloatArray = np.empty(0)
    for k in range(n_u):
        freqs, s_mean, s_se = mean_psd(mu_p[:, :, k], a_y)
        psd_rows.append(s_mean)
        psd_se_rows.append(s_se)
        levels.append(psd_level(freqs, s_mean, path.window_length_m))
        per_surface = [
            psd_level(freqs, one_sided_psd(mu_p[j, :, k], a_y)[1], path.window_length_m) for j in range(k_count)
        ]
        level_se.append(float(np.std(per_surface, ddof=1) / root_k) if k_count > 1 else math.nan)
    psd = np.stack(psd_rows)
    psd_se = np.stack(psd_se_rows)

    # --- fits (d) --------------------------------------------------------------------------
    mask, mask_note = fit_mask(frac_path, p_path, max_area_fraction=cfg.max_area_fraction)
    if mask_note:
        notes.append(mask_note)
    rule = {"exclude": "mean A_c/A_nom > max_area_fraction", "max_area_fraction": cfg.max_area_fraction}
    se_or_none = (lambda a: a) if k_count > 1 else (lambda a: None)
    fits = {
        "mu_mean": fit_model_function(p_path, mu_mean, se_or_none(mu_mean_se), mask=mask, note=mask_note, rule=rule),
        "mu_std": fit_model_function(p_path, mu_std, se_or_none(mu_std_se), mask=mask, note=mask_note, rule=rule),
        "psd_level": fit_model_function(
            p_path, np.asarray(levels), se_or_none(np.asarray(level_se)), mask=mask, note=mask_note, rule=rule
        ),
    }
    # --- the model (e) ---------------------------------------------------------------------
    order = np.argsort(p_path)
    model = TabulatedProcessModel(
        name=name or "measured surface",
        mu_mean=fits["mu_mean"].model_function(),
        mu_std=fits["mu_std"].model_function(),
        dx=a_y,
        length=n_win * a_y,
        pressures_pa=tuple(float(v) for v in p_path[order]),
        table_frequencies=tuple(float(v) for v in freqs),
        table_psd=tuple(tuple(float(v) for v in psd[k]) for k in order),
        pressure_rule=cfg.pressure_rule,  # type: ignore[arg-type]
        variance_rule=cfg.variance_rule,  # type: ignore[arg-type]
        sigma_zeta_rule=cfg.sigma_zeta_rule,  # type: ignore[arg-type]
        psd_level=fits["psd_level"].model_function(),
        window_length_m=path.window_length_m,
    )
    measured = find_summits(surface.heights_m, surface.grid_spacing_m, rule=cfg.summit_rule)
    gamma = None
    if measured.count > 1:
        gamma = plasticity_index(
            e_star_pa=material.e_star_pa, hardness_pa=material.hardness,
            sigma_s_m=float(measured.heights_m.std()), beta_mean_m=float(measured.radius_m.mean()),
        )  # fmt: skip
    validity = contact_validity(
        mu=mu_mean, area_fraction=frac_path, n_contacts=path.samples.n_contacts.mean(axis=(0, 1)), approach_m=u,
        plasticity_index=gamma, max_area_fraction=cfg.max_area_fraction, name=name or "",
    )  # fmt: skip
    used_p = p_path[mask]
    check_p = np.unique(np.array([used_p.min(), float(np.exp(np.mean(np.log(used_p)))), used_p.max()]))
    try:
        check = check_generated_process(model, check_p, realizations=cfg.check_realizations, seed=s_check)
    except ValueError as exc:
        raise ContactError(f"the fitted model cannot generate a process: {exc}") from None
    return StatisticalContactAnalysis(
        config=cfg,
        seed_entropy=seed_entropy(root),
        material=material.to_dict(),
        surface_info={"source": surface.source, "grid": list(surface.nb_grid_pts),
                      "physical_size_m": list(surface.physical_size_m), **surface.info},
        ensemble=ens,
        path=path,
        ensemble_mu_mean=e_mean,
        ensemble_mu_std=e_std,
        ensemble_mu_mean_se=e_mean_se,
        ensemble_mu_std_se=e_std_se,
        ensemble_pressure_pa=e_p,
        ensemble_area_fraction=e_frac,
        pdf_edges=edges,
        pdf_density=dens,
        contact_fraction_fit=linear_fit(e_p, e_frac),
        ergodicity=erg_check,
        surrogate_check=s_check_result,
        pressure_pa=p_path,
        area_fraction=frac_path,
        mu_mean=mu_mean,
        mu_std=mu_std,
        mu_mean_se=mu_mean_se,
        mu_std_se=mu_std_se,
        lags_m=lags,
        acf=acfs,
        correlation_length_m=corr,
        frequencies=freqs,
        psd=psd,
        psd_se=psd_se,
        psd_level=np.asarray(levels),
        psd_level_se=np.asarray(level_se),
        fits=fits,
        model=model,
        process_check=check,
        notes=notes,
        warnings=validity,
    )

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
   averaged over the surfaces (Fig. 3.19–3.21).  The correlation length is the integral scale
   ℓ_corr = ∫₀^∞ ρ(y) dy = S(0)/(4σ_μ²) per long surface (S(0) the low-frequency level, stable
   between realisations), with its standard error and 95 % Student-t interval over the K surfaces
   (:func:`~stochfric.process.spectra.correlation_length_interval`); the thesis's first zero
   crossing of the averaged ACF is kept as ``zero_crossing_m`` (it jumps between realisations
   and is undefined when the ACF stays positive);
d) the **model functions** f(p) = a p^b + c for E[μ], σ_μ and the PSD level over the mean
   pressure of c), high-pressure points excluded (:mod:`stochfric.process.fit`; Fig. 3.22);
e) the **friction-process model** (:class:`~stochfric.process.tabulated.TabulatedProcessModel`)
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

import math
from collections.abc import Callable, Sequence
from dataclasses import replace
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.contact.asperity import ContactError, asperity_sums, bowden_tabor_mu
from stochfric.contact.materials import Material
from stochfric.contact.validity import contact_validity
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.analysis_result import StatisticalContactAnalysis
from stochfric.process.checks import (
    WINDOW_MIN_SUMMITS,
    check_generated_process,
    copy_check,
    ergodicity_check,
    surrogate_check,
    window_scatter_check,
    window_tiles,
)
from stochfric.process.credibility import assess_credibility
from stochfric.process.ensemble import ensemble_contact, path_contact, tile_contact, tile_grid
from stochfric.process.estimators import linear_fit, mean_and_std_errors, mu_pdfs
from stochfric.process.fit import fit_mask, fit_model_function
from stochfric.process.memory import check_memory, sample_arrays_bytes, workers_that_fit
from stochfric.process.parallel import default_workers
from stochfric.process.spectra import (
    autocorrelation,
    correlation_length,
    correlation_length_interval,
    integral_correlation_length,
    mean_psd,
    psd_level,
)
from stochfric.process.spectral import one_sided_psd
from stochfric.process.tabulated import TabulatedProcessModel
from stochfric.progress import StagedProgress
from stochfric.random import as_seed_sequence, seed_entropy, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.statistics import plasticity_index
from stochfric.surface.summits import Summits, find_summits

__all__ = [
    "AnalysisConfig",
    "StatisticalContactAnalysis",
    "analyse",
]

FloatArray = npt.NDArray[np.float64]


def _measured_tiles(scans: list[Surface], material: Material, u: FloatArray, tiles: int, rule: str) -> FloatArray:
    """μ of the disjoint ``tiles × tiles`` windows of every scan, shape (scans·tiles², U)."""
    rows = []
    for scan in scans:
        area, force, _count = tile_contact(scan.heights_m, scan.grid_spacing_m, material, u, tiles=tiles, rule=rule)
        rows.append(bowden_tabor_mu(area, force, material.shear_strength_pa))
    return np.concatenate(rows)


def _full_map_mu(found: list[Summits], material: Material, u: FloatArray) -> FloatArray:
    """μ(u) of every whole scan from its summits (referenced to its own highest summit), shape (scans, U)."""
    rows = []
    for s in found:
        area, force, _count = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=material.e_star_pa)
        rows.append(bowden_tabor_mu(area, force, material.shear_strength_pa))
    return np.stack(rows)


def _scan_scatter(scan_mu: FloatArray, tile_mu: FloatArray, scans: int, ensemble_mu: FloatArray) -> dict[str, Any]:
    """Between-scan scatter (sd over the scans of the whole-map μ) beside the within-scan scatter
    (sd over the disjoint windows of each scan, averaged over the scans) and the ensemble's scatter
    of whole maps (sd of μ over the surrogates of original size), per approach."""

    def lst(a: FloatArray) -> list[float | None]:
        return [float(v) if math.isfinite(float(v)) else None for v in a]

    n_u = scan_mu.shape[1]
    between = scan_mu.std(axis=0, ddof=1) if scans > 1 else np.full(n_u, np.nan)
    if tile_mu.shape[0] >= 2 * scans:
        within = np.nanmean(np.stack([t.std(axis=0, ddof=1) for t in np.split(tile_mu, scans)]), axis=0)
    else:
        within = np.full(n_u, np.nan)
    return {
        "scans": scans,
        "scan_mu": [lst(r) for r in scan_mu],
        "between_scan_std": lst(between),
        "within_scan_window_std": lst(within),
        "ensemble_std": lst(np.nanstd(ensemble_mu, axis=0, ddof=1)),
        "rule": "between: sd over scans of mu of each whole scan; within: sd over the disjoint windows of one "
        "scan, mean over scans; ensemble: sd of mu over the surrogates of original size",
    }


def analyse(
    surface: Surface | Sequence[Surface],
    material: Material,
    approach_m: npt.ArrayLike,
    config: AnalysisConfig | None = None,
    *,
    name: str | None = None,
    progress: StagedProgress | None = None,
    workers: int | None = 1,
) -> StatisticalContactAnalysis:
    """Run the statistical contact analysis a)–e) of the module docstring on ``surface``.

    ``surface`` is the prepared (detrended, filtered, coarsened) surface, or several prepared scans
    of one surface on the same grid (pooled: realisation / long surface k is made from scan
    k mod S; the checks compare every scan); windows run along y (axis 1).  Independent child
    streams of ``config.seed`` drive the ensemble, the long
    surfaces and the process check; inside each, realisation / surface k has its own child
    stream.  ``progress(stage, done, total)`` is called after every realisation / surface.
    ``workers`` processes share the realisations and long surfaces (``None``: all cores); the
    numbers do not depend on it.
    """
    cfg = config if config is not None else AnalysisConfig()
    scans = [surface] if isinstance(surface, Surface) else list(surface)
    if not scans:
        raise ContactError("no surface to analyse")
    surface = scans[0]
    windows = (cfg.length_factor - 1) * surface.nb_grid_pts[1] // cfg.window_shift_points + 1
    check_memory(surface.nb_grid_pts, cfg.length_factor, samples_bytes=sample_arrays_bytes(
        cfg.realizations, cfg.long_surfaces, windows, np.asarray(approach_m).size, cfg.window_tiles))
    long_workers = workers_that_fit(surface.nb_grid_pts, cfg.length_factor,
                                    default_workers() if workers is None else workers)
    root = as_seed_sequence(cfg.seed)
    s_ens, _s_unused, s_path, s_check = spawn_seed_sequences(root, 4)  # stream 1: retired one-surface check
    u = np.asarray(approach_m, dtype=np.float64)

    def stage(label: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress(label, done, total)

    options, surrogate_choice = cfg.surrogate_for([s.heights_m for s in scans])
    found = [find_summits(s.heights_m, s.grid_spacing_m, rule=cfg.summit_rule) for s in scans]
    measured_counts = [f.count for f in found]
    tiles = window_tiles(min(measured_counts), cfg.window_tiles)
    ens = ensemble_contact(
        scans, material, u, realizations=cfg.realizations, seed=s_ens, progress=stage("ensemble"), options=options,
        tiles=tiles, workers=workers,
    )  # fmt: skip
    path = path_contact(
        scans, material, u, long_surfaces=cfg.long_surfaces, length_factor=cfg.length_factor,
        shift_points=cfg.window_shift_points, seed=s_path, progress=stage("long surfaces"), options=options,
        workers=long_workers,
    )  # fmt: skip
    notes: list[str] = []
    mu_e = ens.mu
    if not np.all(np.isfinite(mu_e)):
        raise ContactError("a realisation carries no load at some approach (μ undefined); use larger approaches")
    e_mean, e_std, e_mean_se, e_std_se = mean_and_std_errors(mu_e)
    e_p = ens.normal_force_n.mean(axis=0) / ens.nominal_area_m2
    e_frac = ens.contact_area_m2.mean(axis=0) / ens.nominal_area_m2
    edges, dens = mu_pdfs(mu_e, cfg.pdf_bins)
    erg_check = ergodicity_check(path.blocks.mu)
    s_check_result = surrogate_check(scans, material, ens, rule=cfg.summit_rule)
    window_check = None
    scan_mu = _full_map_mu(found, material, u)
    measured_tile_mu = np.empty((0, u.size))
    if tiles is not None and ens.tile_samples is not None:
        measured_tile_mu = _measured_tiles(scans, material, u, tiles, cfg.summit_rule)
        i0, i1, j0, j1 = tile_grid(surface.nb_grid_pts, tiles)[0]
        dx, dy = surface.grid_spacing_m
        window_check = window_scatter_check(
            measured_tile_mu, ens.tile_samples.mu, tiles=tiles, window_size_m=((i1 - i0) * dx, (j1 - j0) * dy)
        )
    else:
        notes.append(
            f"the measured-window check needs at least {4 * WINDOW_MIN_SUMMITS} summits for 2 x 2 windows; "
            f"the map has {min(measured_counts)}: the scatter across windows could not be checked"
        )
    scan_scatter = _scan_scatter(scan_mu, measured_tile_mu, len(scans), ens.mu)
    copies = copy_check(scans, options, spawn_seed_sequences(s_ens, cfg.realizations))

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
    zero_crossing = np.array([correlation_length(acfs[k], a_y) for k in range(n_u)])
    psd_rows, psd_se_rows, levels, level_se, corr, corr_se = [], [], [], [], [], []
    corr_ci: list[tuple[float, float]] = []
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
        per_len = np.array([integral_correlation_length(mu_p[j, :, k], a_y, path.window_length_m)
                            for j in range(k_count)])
        cl_mean, cl_se, cl_lo, cl_hi = correlation_length_interval(per_len)
        corr.append(cl_mean)
        corr_se.append(cl_se)
        corr_ci.append((cl_lo, cl_hi))
    psd = np.stack(psd_rows)
    psd_se = np.stack(psd_se_rows)

    # --- fits (d) --------------------------------------------------------------------------
    mask, mask_note = fit_mask(frac_path, p_path, max_area_fraction=cfg.max_area_fraction)
    valid_points = int(np.count_nonzero(np.isfinite(frac_path) & (frac_path <= cfg.max_area_fraction)))
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
    summit_heights = np.concatenate([f.heights_m for f in found])
    summit_radii = np.concatenate([f.radius_m for f in found])
    gamma = None
    if summit_heights.size > 1:
        gamma = plasticity_index(
            e_star_pa=material.e_star_pa, hardness_pa=material.hardness,
            sigma_s_m=float(summit_heights.std()), beta_mean_m=float(summit_radii.mean()),
        )  # fmt: skip
    validity = contact_validity(
        mu=mu_mean, area_fraction=frac_path, n_contacts=path.samples.n_contacts.mean(axis=(0, 1)), approach_m=u,
        plasticity_index=gamma, max_area_fraction=cfg.max_area_fraction, name=name or "",
    )  # fmt: skip
    credibility = assess_credibility(
        name=name or "measured surface", approach_m=u, surrogate_ok=s_check_result.credible,
        surrogate_failures=s_check_result.failures(),
        window_ok=None if window_check is None else window_check.consistent,
        window_max_z=None if window_check is None else window_check.max_abs_z, copies=copies,
        mu_means=[mu_mean, e_mean], area_fractions=[frac_path, e_frac], fit_mask=mask, valid_fit_points=valid_points,
    )  # fmt: skip
    if not credibility.credible:
        model = replace(model, not_credible=tuple(f"[{r.code}] {r.message}" for r in credibility.reasons))
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
                      "physical_size_m": list(surface.physical_size_m), **surface.info,
                      "scans": [s.source for s in scans]},
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
        window_check=window_check,
        scan_scatter=scan_scatter,
        credibility=credibility,
        surrogate_choice=surrogate_choice,
        copy_check=copies,
        pressure_pa=p_path,
        area_fraction=frac_path,
        mu_mean=mu_mean,
        mu_std=mu_std,
        mu_mean_se=mu_mean_se,
        mu_std_se=mu_std_se,
        lags_m=lags,
        acf=acfs,
        correlation_length_m=np.asarray(corr),
        correlation_length_se_m=np.asarray(corr_se),
        correlation_length_ci95_m=np.asarray(corr_ci, dtype=np.float64).reshape(-1, 2),
        zero_crossing_m=zero_crossing,
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

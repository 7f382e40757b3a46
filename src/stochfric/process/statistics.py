"""The statistical contact analysis: from measured surfaces to a friction-process model.

method §3–§4 (thesis 3.1.4, 3.2.4, 3.2.5, 3.3.3, 3.3.4; Fig. 3.16–3.23).  :func:`analyse` runs the
ensemble of surrogates (§4a), the ergodicity check (§4b), μ along the path with its ACF,
correlation length and PSD (§4c, eq. 3.17–3.20), the fits f(p) = a p^b + c (§4d, eq. 3.21), the
friction-process model and its checks (§4e); docs/statistical_contact.md §0–§4 states the rules.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import fields, replace
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import asperity_sums, bowden_tabor_mu
from stochfric.contact.materials import Material
from stochfric.contact.validity import contact_validity
from stochfric.errors import AnalysisError
from stochfric.friction_process.spectra import (
    autocorrelation,
    correlation_length,
    correlation_length_interval,
    integral_correlation_length,
    mean_psd,
    psd_level,
)
from stochfric.friction_process.spectral import one_sided_psd
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.analysis_result import (
    EnsembleStatistics,
    PathMoments,
    PathSpectra,
    StatisticalContactAnalysis,
    SurrogateChecks,
)
from stochfric.process.checks import (
    WINDOW_MIN_SUMMITS,
    ProcessCheck,
    ScanScatter,
    SurrogateCheck,
    WindowScatterCheck,
    check_generated_process,
    copy_check,
    ergodicity_check,
    surrogate_check,
    window_scatter_check,
    window_tiles,
)
from stochfric.process.credibility import Credibility, assess_credibility
from stochfric.process.ensemble import (
    ContactSamples,
    PathContact,
    SurrogateOptions,
    ensemble_contact,
    path_contact,
    tile_grid,
)
from stochfric.process.estimators import linear_fit, mean_and_std_errors, mu_pdfs
from stochfric.process.fit import ModelFit, fit_mask, fit_model_function
from stochfric.process.holdout import HoldoutValidation, holdout_validation, measured_windows
from stochfric.process.memory import check_memory, sample_arrays_bytes, workers_that_fit
from stochfric.process.model_intervals import model_intervals
from stochfric.process.parallel import default_workers
from stochfric.process.pooling import BetweenScanTest, between_scan_test, measured_window_mu
from stochfric.progress import Progress, StagedProgress
from stochfric.random import as_seed_sequence, child_seed, seed_entropy, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.statistics import plasticity_index
from stochfric.surface.summits import Summits, find_summits

__all__ = [
    "AnalysisConfig",
    "StatisticalContactAnalysis",
    "analyse",
    "plasticity_index_of",
]


def _full_map_mu(found: list[Summits], material: Material, u: FloatArray) -> FloatArray:
    """μ(u) of every whole scan from its summits (referenced to its own highest summit), shape (scans, U)."""
    rows = []
    for s in found:
        area, force, _count = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=material.e_star_pa)
        rows.append(bowden_tabor_mu(area, force, material.shear_strength_pa))
    return np.stack(rows)


def _scan_scatter(scan_mu: FloatArray, tile_mu: FloatArray, scans: int, ensemble_mu: FloatArray) -> ScanScatter:
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
    return ScanScatter(scans=scans, scan_mu=[lst(r) for r in scan_mu], between_scan_std=lst(between),
                       within_scan_window_std=lst(within), ensemble_std=lst(np.nanstd(ensemble_mu, axis=0, ddof=1)))


class _Fits(NamedTuple):
    """The fits f(p) = a p^b + c (§4d) and the points they use."""

    fits: dict[str, ModelFit]
    mask: npt.NDArray[np.bool_]
    valid_points: int
    note: str


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
    """Run the statistical contact analysis of the module docstring on ``surface``.

    ``surface`` is the prepared (detrended, filtered, coarsened) surface, or several prepared scans
    of one surface on the same grid (pooled: realisation / long surface k is made from scan
    k mod S; the checks compare every scan); windows run along y (axis 1).  Independent child
    streams of ``config.seed`` drive the ensemble, the long surfaces and the process check; inside
    each, realisation / surface k has its own child stream.  ``progress(stage, done, total)`` is
    called after every realisation / surface.  ``workers`` processes share the realisations and
    long surfaces (``None``: all cores); the numbers do not depend on it.
    """
    cfg = config if config is not None else AnalysisConfig()
    scans = [surface] if isinstance(surface, Surface) else list(surface)
    if not scans:
        raise AnalysisError("no surface to analyse")
    # the summit check's default budget, a bounded amount of work on these scans (recorded in the result's config)
    cfg = cfg.with_summit_budget(sum(int(np.asarray(s.heights_m).size) for s in scans))
    u = np.asarray(approach_m, dtype=np.float64)
    long_workers = _long_surface_workers(scans[0], cfg, u.size, workers)
    root = as_seed_sequence(cfg.seed)
    # child k of the root is spawn_seed_sequences(root, n)[k]; stream 1 (a retired one-surface check) is unused
    s_ens, s_path, s_check = (child_seed(root, k) for k in (ENSEMBLE_STREAM, PATH_STREAM, CHECK_STREAM))
    options, surrogate_choice = cfg.surrogate_for([s.heights_m for s in scans])
    found = [find_summits(s.heights_m, s.grid_spacing_m, rule=cfg.summit_rule) for s in scans]
    tiles = window_tiles(min(f.count for f in found), cfg.window_tiles)
    ens, surrogates = _decided_ensemble(scans, material, u, cfg, options, tiles, s_ens, progress, workers)
    realizations = int(ens.contact_area_m2.shape[0])
    path = path_contact(
        scans, material, u, long_surfaces=cfg.long_surfaces, length_factor=cfg.length_factor,
        shift_points=cfg.window_shift_points, seed=s_path, progress=_stage(progress, "long surfaces"),
        options=options, workers=long_workers,
    )  # fmt: skip
    ens_stats = _ensemble_statistics(ens, cfg.pdf_bins)
    ergodicity = ergodicity_check(path.blocks.mu)
    window_check, scan_scatter, notes = _window_checks(scans, found, material, u, tiles, ens, cfg.summit_rule)
    copies = copy_check(scans, options, spawn_seed_sequences(s_ens, cfg.realizations))
    holdout = _holdout(scans, material, u, options, cfg, child_seed(root, HOLDOUT_STREAM), progress)
    checks = SurrogateChecks(ergodicity=ergodicity, surrogate_check=surrogates, window_check=window_check,
                             scan_scatter=scan_scatter, copy_check=copies, holdout=holdout,
                             measured_windows=measured_windows(scans, material, u, rule=cfg.summit_rule),
                             between_scans=_between_scans(scans, material, u, cfg.summit_rule))
    moments, spectra = _path_moments(path), _path_spectra(path)
    intervals = model_intervals(pressure_pa=moments.pressure_pa, mu_mean=moments.mu_mean,
                                mu_mean_se=moments.mu_mean_se, mu_std=moments.mu_std, mu_std_se=moments.mu_std_se,
                                measured=checks.measured_windows)
    fits = _fit_all(moments, spectra, path.samples.mu.shape[0], cfg)
    notes += [fits.note] if fits.note else []
    notes += _uncertain_fits(fits.fits)[1]
    if copies.verbatim is not None and copies.verbatim.is_resampling:
        notes.append(f"the {options.method} surrogates are a resampling of the measurement: "
                     f"{copies.verbatim.summary()}")
    model = _process_model(name or "measured surface", fits.fits, moments.pressure_pa, spectra, path, cfg)
    validity = contact_validity(
        mu=moments.mu_mean, area_fraction=moments.area_fraction,
        n_contacts=path.samples.n_contacts.mean(axis=(0, 1)), approach_m=u,
        plasticity_index=plasticity_index_of(found, material), max_area_fraction=cfg.max_area_fraction, name=name or "",
    )  # fmt: skip
    credibility = _credibility(name or "measured surface", u, checks, moments, ens_stats, fits, realizations,
                               cfg.summit_looks)
    if realizations > cfg.realizations:
        still = checks.surrogate_check.decided(realizations, looks=cfg.summit_looks)[1]
        notes.append(f"the summit check grew the ensemble from {cfg.realizations} to {realizations} realisations "
                     f"(budget {cfg.summit_max_realizations}, --summit-budget): "
                     + ("still undecided, the budget is spent" if still else "decided"))
    if not credibility.credible:
        model = replace(model, not_credible=tuple(f"[{r.code}] {r.message}" for r in credibility.reasons))
    return StatisticalContactAnalysis(
        config=cfg, seed_entropy=seed_entropy(root), material=material.to_dict(), surface_info=_surface_info(scans),
        ensemble=ens, path=path, **_fields(ens_stats), **_fields(checks), credibility=credibility,
        surrogate_choice=surrogate_choice, **_fields(moments), **_fields(spectra), fits=fits.fits, model=model,
        process_check=_process_check(model, moments.pressure_pa[fits.mask], cfg, s_check), notes=notes,
        warnings=validity, model_intervals=intervals,
    )  # fmt: skip


def _decided_ensemble(
    scans: list[Surface], material: Material, u: FloatArray, cfg: AnalysisConfig, options: SurrogateOptions,
    tiles: int | None, seed: np.random.SeedSequence, progress: StagedProgress | None, workers: int | None,
) -> tuple[ContactSamples, SurrogateCheck]:
    """The ensemble of ``cfg.realizations`` and its summit check (:func:`~stochfric.process.checks.surrogate_check`),
    doubled while the check is undecided — a quantity within the decision margin
    (:func:`~stochfric.process.decisions.decision_margin`, Monte Carlo SE) of its limit and no decided
    failure (:meth:`~stochfric.process.checks.SurrogateCheck.decided`) — and the doubled size stays within
    ``cfg.summit_max_realizations`` (issue 29 item 6: realisations are added until the decision is made or the
    stated budget is spent).  Realisation r depends on the seed and r only, so a grown ensemble starts with
    the smaller one and the numbers do not depend on how it grew.  ``cfg`` carries the budget resolved for these
    scans (:func:`analyse`, :meth:`~stochfric.process.analysis_config.AnalysisConfig.with_summit_budget`)."""
    r = cfg.realizations
    ens: ContactSamples | None = None
    while True:
        ens = ensemble_contact(
            scans, material, u, realizations=r, seed=seed, progress=_stage(progress, "ensemble"), options=options,
            tiles=tiles, workers=workers, extend=ens,
        )  # fmt: skip
        check = surrogate_check(scans, material, ens, rule=cfg.summit_rule)
        failed, near = check.decided(r, looks=cfg.summit_looks)
        if failed or not near or 2 * r > int(cfg.summit_max_realizations or r):
            return ens, check
        r *= 2


#: The children of the root seed that drive the ensemble, the long surfaces and the out-of-sample validation
#: (1: retired, 3: the process check); :mod:`~stochfric.process.contact_models` solves the same surrogates.
ENSEMBLE_STREAM = 0
PATH_STREAM = 2
CHECK_STREAM = 3
HOLDOUT_STREAM = 4


def _holdout(scans: list[Surface], material: Material, u: FloatArray, options: SurrogateOptions, cfg: AnalysisConfig,
             seed: np.random.SeedSequence, progress: StagedProgress | None) -> HoldoutValidation:
    """The surrogate model on held-out halves (:func:`~stochfric.process.holdout.holdout_validation`), or why
    it could not be tested."""
    try:
        return holdout_validation(scans, material, u, options, seed=seed, realizations=cfg.holdout_start,
                                  max_realizations=cfg.holdout_budget,
                                  progress=_stage(progress, "held-out validation"))
    except AnalysisError as exc:
        return HoldoutValidation.unavailable(options.method, str(exc))


def _between_scans(scans: list[Surface], material: Material, u: FloatArray, rule: str) -> BetweenScanTest | None:
    """Pooled scans: the random-effects test of one surface (:func:`~stochfric.process.pooling.between_scan_test`)
    on μ of their disjoint windows; None for one scan."""
    if len(scans) < 2:
        return None
    return between_scan_test(measured_window_mu(scans, material, u, rule=rule), approach_m=u)


def _uncertain_fits(fits: dict[str, ModelFit]) -> tuple[list[str], list[str]]:
    """The fits of E[μ] and σ_μ that say nothing, and notes on the ones whose coefficients are not
    identifiable one by one.

    A fit says nothing when the standard error of the fitted *value* f(p) = a p^b + c (delta method with
    the fit's covariance) reaches |f(p)| at a pressure it was fitted on.  Coefficients with standard errors
    above their values but a determined curve (a flat E[μ] has a ≈ 0 and any b) are no reason to refuse
    the model; they mean the curve must not be extrapolated, which a note says."""
    refused, notes = [], []
    for key, label in (("mu_mean", "E[mu]"), ("mu_std", "sigma_mu")):
        f = fits.get(key)
        if f is None:
            continue
        p = np.asarray(f.pressure_pa, dtype=np.float64)[np.asarray(f.used, dtype=bool)]
        cov = np.asarray(f.covariance, dtype=np.float64)
        if p.size == 0 or cov.shape != (3, 3) or not np.all(np.isfinite(cov)):
            refused.append(f"the fit of {label} has no covariance (its parameters are not determined)")
            continue
        pb = p**f.b
        grad = np.stack([pb, f.a * pb * np.log(p), np.ones_like(p)], axis=1)
        se = np.sqrt(np.maximum(np.einsum("ij,jk,ik->i", grad, cov, grad), 0.0))
        value = np.abs(f.a * pb + f.c)
        worst = int(np.argmax(se / np.maximum(value, 1e-300)))
        if se[worst] >= value[worst]:
            refused.append(f"the fit of {label} at p = {p[worst] / 1e6:.3g} MPa is {value[worst]:.3g} ± "
                           f"{se[worst]:.2g} (a = {f.a:.4g} ± {f.a_se:.2g}, b = {f.b:.4g} ± {f.b_se:.2g})")
        elif not all(math.isfinite(s_) and abs(s_) <= abs(v) for v, s_ in ((f.a, f.a_se), (f.b, f.b_se))):
            notes.append(f"the fit of {label}: a = {f.a:.4g} ± {f.a_se:.2g}, b = {f.b:.4g} ± {f.b_se:.2g} are not "
                         f"determined one by one; the curve is (its SE ≤ {np.max(se / value):.0%} of its value on "
                         f"{p.min() / 1e6:.3g}–{p.max() / 1e6:.3g} MPa) but must not be extrapolated beyond them")
    return refused, notes


def _fields(section: EnsembleStatistics | SurrogateChecks | PathMoments | PathSpectra) -> dict[str, Any]:
    """The fields of one section of the result, by name (no copies)."""
    return {f.name: getattr(section, f.name) for f in fields(section)}


def _stage(progress: StagedProgress | None, label: str) -> Progress | None:
    """``progress`` bound to one stage (``None`` without a callback)."""
    if progress is None:
        return None
    return lambda done, total: progress(label, done, total)


def _long_surface_workers(surface: Surface, cfg: AnalysisConfig, approaches: int, workers: int | None) -> int:
    """Refuse a request that does not fit in memory (:mod:`stochfric.process.memory`); the workers
    whose long surfaces fit at once."""
    windows = (cfg.length_factor - 1) * surface.nb_grid_pts[1] // cfg.window_shift_points + 1
    check_memory(surface.nb_grid_pts, cfg.length_factor, samples_bytes=sample_arrays_bytes(
        cfg.realizations, cfg.long_surfaces, windows, approaches, cfg.window_tiles))
    return workers_that_fit(surface.nb_grid_pts, cfg.length_factor, default_workers() if workers is None else workers)


def _ensemble_statistics(ens: ContactSamples, pdf_bins: int) -> EnsembleStatistics:
    """E[μ], σ_μ and their standard errors (delta method, :func:`mean_and_std_errors`), the mean
    pressure E[N]/A_nom and A_c/A_nom with its line fit, the PDFs of μ, per approach (§4a, Fig. 3.16–3.18a)."""
    mu = ens.mu
    if not np.all(np.isfinite(mu)):
        raise AnalysisError("a realisation carries no load at some approach (μ undefined); use larger approaches")
    mean, std, mean_se, std_se = mean_and_std_errors(mu)
    pressure = ens.normal_force_n.mean(axis=0) / ens.nominal_area_m2
    fraction = ens.contact_area_m2.mean(axis=0) / ens.nominal_area_m2
    edges, density = mu_pdfs(mu, pdf_bins)
    return EnsembleStatistics(
        ensemble_mu_mean=mean, ensemble_mu_std=std, ensemble_mu_mean_se=mean_se, ensemble_mu_std_se=std_se,
        ensemble_pressure_pa=pressure, ensemble_area_fraction=fraction, pdf_edges=edges, pdf_density=density,
        contact_fraction_fit=linear_fit(pressure, fraction),
    )  # fmt: skip


def _window_checks(
    scans: list[Surface], found: list[Summits], material: Material, u: FloatArray, tiles: int | None,
    ens: ContactSamples, rule: str,
) -> tuple[WindowScatterCheck | None, ScanScatter, list[str]]:
    """The measured-window check (None, with a note, when the map is too small for 2 × 2 windows)
    and the between- / within-scan scatter of μ."""
    notes: list[str] = []
    window_check = None
    scan_mu = _full_map_mu(found, material, u)
    measured_tile_mu = np.empty((0, u.size))
    if tiles is not None and ens.tile_samples is not None:
        measured_tile_mu = np.concatenate(measured_window_mu(scans, material, u, tiles=tiles, rule=rule))
        i0, i1, j0, j1 = tile_grid(scans[0].nb_grid_pts, tiles)[0]
        dx, dy = scans[0].grid_spacing_m
        window_check = window_scatter_check(
            measured_tile_mu, ens.tile_samples.mu, tiles=tiles, window_size_m=((i1 - i0) * dx, (j1 - j0) * dy)
        )
    else:
        notes.append(
            f"the measured-window check needs at least {4 * WINDOW_MIN_SUMMITS} summits for 2 x 2 windows; "
            f"the map has {min(f.count for f in found)}: the scatter across windows could not be checked"
        )
    return window_check, _scan_scatter(scan_mu, measured_tile_mu, len(scans), ens.mu), notes


def _path_moments(path: PathContact) -> PathMoments:
    """E[μ], σ_μ pooled over the K long surfaces with standard errors from the scatter between them
    (sd/√K: windows of one surface overlap), the mean pressure and A_c/A_nom, the averaged
    autocorrelation (3.18) and its first zero crossing [m]."""
    mu_p = path.samples.mu  # (K, W, U)
    k_count, _n_win, n_u = mu_p.shape
    pooled = mu_p.reshape(-1, n_u)
    per_mean = mu_p.mean(axis=1)
    per_std = mu_p.std(axis=1, ddof=1)
    root_k = math.sqrt(k_count)
    a_y = path.window_shift_m
    acfs = np.stack([autocorrelation(mu_p[:, :, k]) for k in range(n_u)])
    return PathMoments(
        pressure_pa=path.samples.normal_force_n.mean(axis=(0, 1)) / path.samples.nominal_area_m2,
        area_fraction=path.samples.contact_area_m2.mean(axis=(0, 1)) / path.samples.nominal_area_m2,
        mu_mean=pooled.mean(axis=0),
        mu_std=pooled.std(axis=0, ddof=1),
        mu_mean_se=per_mean.std(axis=0, ddof=1) / root_k if k_count > 1 else np.full(n_u, np.nan),
        mu_std_se=per_std.std(axis=0, ddof=1) / root_k if k_count > 1 else np.full(n_u, np.nan),
        lags_m=np.arange(acfs.shape[1], dtype=np.float64) * a_y,
        acf=acfs,
        zero_crossing_m=np.array([correlation_length(acfs[k], a_y) for k in range(n_u)]),
    )


def _path_spectra(path: PathContact) -> PathSpectra:
    """Per approach: the PSD averaged over the K long surfaces (3.19–3.20, method §0), its level
    S(f → 0) [m] and the integral correlation length S(0)/(4σ_μ²) [m] with their standard errors
    over the surfaces and the 95 % Student-t interval of the correlation length."""
    mu_p = path.samples.mu  # (K, W, U)
    k_count, _n_win, n_u = mu_p.shape
    root_k = math.sqrt(k_count)
    a_y, length = path.window_shift_m, path.window_length_m
    psd_rows, psd_se_rows, levels, level_se, corr, corr_se = [], [], [], [], [], []
    corr_ci: list[tuple[float, float]] = []
    freqs: FloatArray = np.empty(0)
    for k in range(n_u):
        freqs, s_mean, s_se = mean_psd(mu_p[:, :, k], a_y)
        psd_rows.append(s_mean)
        psd_se_rows.append(s_se)
        levels.append(psd_level(freqs, s_mean, length))
        per_surface = [psd_level(freqs, one_sided_psd(mu_p[j, :, k], a_y)[1], length) for j in range(k_count)]
        level_se.append(float(np.std(per_surface, ddof=1) / root_k) if k_count > 1 else math.nan)
        per_len = np.array([integral_correlation_length(mu_p[j, :, k], a_y, length) for j in range(k_count)])
        cl_mean, cl_se, cl_lo, cl_hi = correlation_length_interval(per_len)
        corr.append(cl_mean)
        corr_se.append(cl_se)
        corr_ci.append((cl_lo, cl_hi))
    return PathSpectra(
        frequencies=freqs, psd=np.stack(psd_rows), psd_se=np.stack(psd_se_rows), psd_level=np.asarray(levels),
        psd_level_se=np.asarray(level_se), correlation_length_m=np.asarray(corr),
        correlation_length_se_m=np.asarray(corr_se),
        correlation_length_ci95_m=np.asarray(corr_ci, dtype=np.float64).reshape(-1, 2),
    )  # fmt: skip


def _fit_all(moments: PathMoments, spectra: PathSpectra, surfaces: int, cfg: AnalysisConfig) -> _Fits:
    """f(p) = a p^b + c (3.21) for E[μ], σ_μ and the PSD level over the path's mean pressure,
    points beyond ``cfg.max_area_fraction`` left out (:func:`~stochfric.process.fit.fit_mask`)."""
    p, fraction = moments.pressure_pa, moments.area_fraction
    mask, note = fit_mask(fraction, p, max_area_fraction=cfg.max_area_fraction)
    valid_points = int(np.count_nonzero(np.isfinite(fraction) & (fraction <= cfg.max_area_fraction)))
    rule = {"exclude": "mean A_c/A_nom > max_area_fraction", "max_area_fraction": cfg.max_area_fraction}

    def fit(values: FloatArray, se: FloatArray) -> ModelFit:
        return fit_model_function(p, values, se if surfaces > 1 else None, mask=mask, note=note, rule=rule)

    fits = {
        "mu_mean": fit(moments.mu_mean, moments.mu_mean_se),
        "mu_std": fit(moments.mu_std, moments.mu_std_se),
        "psd_level": fit(spectra.psd_level, spectra.psd_level_se),
    }
    return _Fits(fits, mask, valid_points, note)


def _process_model(
    name: str, fits: dict[str, ModelFit], pressure_pa: FloatArray, spectra: PathSpectra, path: PathContact,
    cfg: AnalysisConfig,
) -> TabulatedProcessModel:
    """The friction-process model (§4e): the fitted E[μ], σ_μ and PSD level, the measured PSDs
    tabulated at the analysed pressures (ascending), Δx = a_y over the length W·a_y."""
    order = np.argsort(pressure_pa)
    a_y = path.window_shift_m
    return TabulatedProcessModel(
        name=name,
        mu_mean=fits["mu_mean"].model_function(),
        mu_std=fits["mu_std"].model_function(),
        dx=a_y,
        length=path.samples.mu.shape[1] * a_y,
        pressures_pa=tuple(float(v) for v in pressure_pa[order]),
        table_frequencies=tuple(float(v) for v in spectra.frequencies),
        table_psd=tuple(tuple(float(v) for v in spectra.psd[k]) for k in order),
        pressure_rule=cfg.pressure_rule,
        variance_rule=cfg.variance_rule,
        sigma_zeta_rule=cfg.sigma_zeta_rule,
        psd_level=fits["psd_level"].model_function(),
        window_length_m=path.window_length_m,
        fitted_range_pa=_fitted_range(fits),
    )


def _fitted_range(fits: dict[str, ModelFit]) -> tuple[float, float]:
    """(p_min, p_max) [Pa] of the pressures both the E[μ] and the σ_μ fit used (issue 30, item 3)."""
    used = np.ones(len(fits["mu_mean"].pressure_pa), dtype=bool)
    for key in ("mu_mean", "mu_std"):
        used &= np.asarray(fits[key].used, dtype=bool)
    p = np.asarray(fits["mu_mean"].pressure_pa, dtype=np.float64)[used]
    if p.size == 0:
        p = np.asarray(fits["mu_mean"].pressure_pa, dtype=np.float64)
    return float(p.min()), float(p.max())


def plasticity_index_of(found: Sequence[Summits], material: Material) -> float | None:
    """γ (3.7) of the summits of all scans together (None with fewer than two summits)."""
    heights = np.concatenate([f.heights_m for f in found])
    radii = np.concatenate([f.radius_m for f in found])
    if heights.size <= 1:
        return None
    return plasticity_index(
        e_star_pa=material.e_star_pa, hardness_pa=material.hardness,
        sigma_s_m=float(heights.std()), beta_mean_m=float(radii.mean()),
    )  # fmt: skip


def _credibility(
    name: str, u: FloatArray, checks: SurrogateChecks, moments: PathMoments, ens_stats: EnsembleStatistics, fits: _Fits,
    realizations: int, looks: int = 1,
) -> Credibility:
    """The gate (:mod:`stochfric.process.credibility`) on the checks, E[μ] and A_c/A_nom of the path
    and the ensemble, and the points the fits use; the summit check decided against its Monte Carlo error
    (:meth:`~stochfric.process.checks.SurrogateCheck.decided`)."""
    decided = checks.surrogate_check.decided(realizations, looks=looks)
    window = checks.window_check
    return assess_credibility(
        holdout=checks.holdout, uncertain_fits=_uncertain_fits(fits.fits)[0], between_scans=checks.between_scans,
        name=name, approach_m=u, surrogate_ok=not decided[0], surrogate_failures=decided[0],
        surrogate_undecided=decided[1], realizations=realizations,
        realizations_to_decide=checks.surrogate_check.realizations_to_decide(realizations, looks),
        window_ok=None if window is None else window.consistent,
        window_max_z=None if window is None else window.max_abs_z, copies=checks.copy_check,
        mu_means=[moments.mu_mean, ens_stats.ensemble_mu_mean],
        area_fractions=[moments.area_fraction, ens_stats.ensemble_area_fraction], fit_mask=fits.mask,
        valid_fit_points=fits.valid_points,
    )  # fmt: skip


def _process_check(
    model: TabulatedProcessModel, used_p: FloatArray, cfg: AnalysisConfig, seed: np.random.SeedSequence
) -> ProcessCheck:
    """Realisations of ``model`` against their target (Fig. 3.23) at the lowest, the geometric-mean
    and the highest pressure the fits use."""
    check_p = np.unique(np.array([used_p.min(), float(np.exp(np.mean(np.log(used_p)))), used_p.max()]))
    try:
        return check_generated_process(model, check_p, realizations=cfg.check_realizations, seed=seed)
    except ValueError as exc:
        raise AnalysisError(f"the fitted model cannot generate a process: {exc}") from None


def _surface_info(scans: list[Surface]) -> dict[str, Any]:
    """Source, grid and size of the first scan, its reader's info and the sources of all scans."""
    surface = scans[0]
    return {"source": surface.source, "grid": list(surface.nb_grid_pts),
            "physical_size_m": list(surface.physical_size_m), **surface.info, "scans": [s.source for s in scans]}

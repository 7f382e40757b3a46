"""The statistical contact analysis: from one measured surface to a friction-process model.

METHOD.md §3–§4 (thesis 3.1.4, 3.2.4, 3.2.5, 3.3.3, 3.3.4).  :func:`analyse` runs

a) the **ensemble** (:func:`~stochfric.process.ensemble.ensemble_contact`): R surrogates of
   original size → E[μ], σ_μ, PDFs of μ per approach, mean A_c/A_nom over the mean pressure
   E[N]/A_nom with a linear fit (Fig. 3.16–3.18a);
b) the **ergodicity check** (:func:`ergodicity_check`): windows of original size shifted by
   their own length over one long surface against a) (Fig. 3.18b);
c) **μ along the path** (:func:`~stochfric.process.ensemble.path_contact`): K long surfaces,
   windows shifted by a_y → μ(y), autocorrelation, correlation length, PSD (METHOD §0),
   averaged over the surfaces (Fig. 3.19–3.21);
d) the **model functions** f(p) = a p^b + c for E[μ], σ_μ and the PSD level over the mean
   pressure of c), high-pressure points excluded (:mod:`stochfric.process.fit`; Fig. 3.22);
e) the **friction-process model** (:class:`~stochfric.process.model.TabulatedProcessModel`)
   and the check of generated realisations against it (:func:`check_generated_process`,
   Fig. 3.23).

Standard errors.  Windows on one long surface overlap and are correlated, so the standard
errors of the path statistics (E[μ], σ_μ, PSD level) are taken from the scatter between the K
independent long surfaces: SE = sd(per-surface values)/√K.  Ensemble statistics use the R
independent realisations: SE(E[μ]) = s/√R, SE(σ_μ) = √((m4 − s⁴)/R)/(2s) (delta method with the
sample fourth central moment m4; no Gaussian assumption).
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import stats as sps

from stochfric.contact.asperity import ContactError
from stochfric.contact.materials import Material
from stochfric.process.ensemble import (
    ContactSamples,
    PathContact,
    ensemble_contact,
    ergodic_contact,
    path_contact,
)
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION, ModelFit, fit_mask, fit_model_function
from stochfric.process.model import FrictionProcessModel, TabulatedProcessModel
from stochfric.process.spectra import autocorrelation, correlation_length, mean_psd, psd_level
from stochfric.process.spectral import one_sided_psd
from stochfric.random import SeedLike, as_seed_sequence, seed_entropy, spawn_generators, spawn_seed_sequences
from stochfric.surface.io import Surface

__all__ = [
    "AnalysisConfig",
    "ErgodicityCheck",
    "ProcessCheck",
    "StatisticalContactAnalysis",
    "analyse",
    "check_generated_process",
    "ergodicity_check",
    "linear_fit",
    "mean_and_std_errors",
]

FloatArray = npt.NDArray[np.float64]
Progress = Callable[[str, int, int], None]

#: Family-wise false-alarm probability of the ergodicity verdict (two-sided, Bonferroni).
ERGODICITY_ALPHA = 0.05


@dataclass(frozen=True, kw_only=True)
class AnalysisConfig:
    """Settings of :func:`analyse` (defaults: the thesis's proportions, §3.2.4–3.2.5).

    ``window_shift_points`` is a_y in grid points of y; ``length_factor`` the long surfaces'
    length in units of the original (thesis: 53 mm / 5.3 mm = 10); ``ergodic_windows`` the
    number of windows of the ergodicity surface.
    """

    realizations: int = 100
    long_surfaces: int = 10
    length_factor: int = 10
    window_shift_points: int = 16
    ergodic_windows: int = 50
    surrogate: str = "phase"
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
        for name in ("length_factor", "ergodic_windows"):
            v = getattr(self, name)
            if isinstance(v, bool) or not isinstance(v, int) or v < 2:
                raise ContactError(f"{name} must be an integer >= 2, got {v!r}")
        if self.realizations < 2:
            raise ContactError("realizations must be >= 2 (a standard deviation needs two)")
        if not 0.0 < self.max_area_fraction <= 1.0:
            raise ContactError(f"max_area_fraction must lie in (0, 1], got {self.max_area_fraction!r}")

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary (JSON / netCDF attributes)."""
        return dict(self.__dict__)


def mean_and_std_errors(samples: npt.ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Mean, standard deviation (ddof = 1) and their standard errors over axis 0.

    SE(mean) = s/√n; SE(s) = √((m4 − s⁴)/n) / (2s) (delta method, m4 the fourth central moment).
    """
    x = np.asarray(samples, dtype=np.float64)
    n = x.shape[0]
    if n < 2:
        raise ValueError("need at least two samples")
    mean = x.mean(axis=0)
    sd = x.std(axis=0, ddof=1)
    m4 = np.mean((x - mean) ** 4, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        se_sd = np.sqrt(np.maximum(m4 - sd**4, 0.0) / n) / (2.0 * sd)
    return mean, sd, sd / math.sqrt(n), np.where(sd > 0.0, se_sd, 0.0)


@dataclass(frozen=True, kw_only=True)
class ErgodicityCheck:
    """Ensemble vs windows on one long surface (METHOD §4b), per approach.

    ``z_mean``/``z_std``: difference of the estimators in units of their combined standard
    error, (θ_win − θ_ens)/√(SE_win² + SE_ens²).  Verdict: ergodic (consistent) if every |z| ≤
    ``threshold`` = Φ⁻¹(1 − α/(2m)) with m = 2U comparisons and α = 0.05 (Bonferroni: the chance
    that an ergodic process fails is at most 5 %).
    """

    z_mean: tuple[float, ...]
    z_std: tuple[float, ...]
    threshold: float
    consistent: bool
    max_abs_z: float
    windows: int
    realizations: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {
            "z_mean": list(self.z_mean),
            "z_std": list(self.z_std),
            "threshold": self.threshold,
            "max_abs_z": self.max_abs_z,
            "consistent": self.consistent,
            "verdict": "consistent with ergodicity" if self.consistent else "NOT consistent with ergodicity",
            "rule": "|difference| / combined standard error <= Bonferroni threshold (alpha = 0.05, 2U tests)",
            "windows": self.windows,
            "realizations": self.realizations,
        }


def ergodicity_check(
    ensemble_mu: npt.ArrayLike, window_mu: npt.ArrayLike, *, alpha: float = ERGODICITY_ALPHA
) -> ErgodicityCheck:
    """Compare E[μ] and σ_μ of the ensemble (R, U) with those of the windows (W, U)."""
    e = np.asarray(ensemble_mu, dtype=np.float64)
    w = np.asarray(window_mu, dtype=np.float64)
    if e.ndim != 2 or w.ndim != 2 or e.shape[1] != w.shape[1]:
        raise ValueError("ensemble and window μ must be (samples, approaches) with the same approaches")
    me, se_, sme, sse = mean_and_std_errors(e)
    mw, sw, smw, ssw = mean_and_std_errors(w)
    with np.errstate(invalid="ignore", divide="ignore"):
        z_mean = (mw - me) / np.sqrt(smw**2 + sme**2)
        z_std = (sw - se_) / np.sqrt(ssw**2 + sse**2)
    m = 2 * e.shape[1]
    threshold = float(sps.norm.ppf(1.0 - alpha / (2.0 * m)))
    all_z = np.concatenate((z_mean, z_std))
    max_abs = float(np.nanmax(np.abs(all_z)))
    return ErgodicityCheck(
        z_mean=tuple(float(v) for v in z_mean),
        z_std=tuple(float(v) for v in z_std),
        threshold=threshold,
        consistent=bool(max_abs <= threshold),
        max_abs_z=max_abs,
        windows=int(w.shape[0]),
        realizations=int(e.shape[0]),
    )


def linear_fit(x: npt.ArrayLike, y: npt.ArrayLike) -> dict[str, float]:
    """Least-squares line y = slope·x + intercept with standard errors (Fig. 3.17)."""
    xa = np.asarray(x, dtype=np.float64)
    ya = np.asarray(y, dtype=np.float64)
    coef, cov = np.polyfit(xa, ya, 1, cov=True) if xa.size > 3 else (np.polyfit(xa, ya, 1), np.full((2, 2), np.nan))
    pred = np.polyval(coef, xa)
    ss_res = float(np.sum((ya - pred) ** 2))
    ss_tot = float(np.sum((ya - ya.mean()) ** 2))
    return {
        "slope": float(coef[0]),
        "intercept": float(coef[1]),
        "slope_se": float(np.sqrt(cov[0, 0])),
        "intercept_se": float(np.sqrt(cov[1, 1])),
        "r_squared": 1.0 - ss_res / ss_tot if ss_tot > 0 else math.nan,
    }


@dataclass(frozen=True, kw_only=True)
class ProcessCheck:
    """Generated process vs its target at some pressures (Fig. 3.23 analogue).

    Per pressure: target σ = √variance(p) and the generated standard deviation of μ̂ at one grid
    point over the realisations (``std_pointwise``, with its standard error from the fourth
    moment) and the mean grid standard deviation of the realisations; the target spectrum and
    the realisations' mean periodogram (METHOD §0) with its standard error.
    """

    pressure_pa: tuple[float, ...]
    target_std: tuple[float, ...]
    std_pointwise: tuple[float, ...]
    std_pointwise_se: tuple[float, ...]
    std_grid_mean: tuple[float, ...]
    frequencies: tuple[float, ...]
    target_psd: tuple[tuple[float, ...], ...]
    generated_psd: tuple[tuple[float, ...], ...]
    generated_psd_se: tuple[tuple[float, ...], ...]
    realizations: int

    def max_std_z(self) -> float:
        """Largest |std_pointwise − target| / SE over the pressures."""
        z = [abs(g - t) / s for g, t, s in zip(self.std_pointwise, self.target_std, self.std_pointwise_se, strict=True)]
        return float(max(z))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no spectra)."""
        return {
            "pressure_pa": list(self.pressure_pa),
            "target_std": list(self.target_std),
            "generated_std_pointwise": list(self.std_pointwise),
            "generated_std_pointwise_se": list(self.std_pointwise_se),
            "generated_std_grid_mean": list(self.std_grid_mean),
            "max_std_z": self.max_std_z(),
            "realizations": self.realizations,
        }


def check_generated_process(
    model: FrictionProcessModel,
    pressures_pa: npt.ArrayLike,
    *,
    realizations: int = 200,
    seed: SeedLike = None,
) -> ProcessCheck:
    """Generate ``realizations`` processes per pressure and compare with the target (Fig. 3.23).

    Realisation r uses the r-th child stream of ``seed`` (the same streams at every pressure).
    """
    ps = np.atleast_1d(np.asarray(pressures_pa, dtype=np.float64))
    gens_seed = as_seed_sequence(seed)
    t_std: list[float] = []
    g_std: list[float] = []
    g_se: list[float] = []
    g_grid: list[float] = []
    t_psd: list[tuple[float, ...]] = []
    g_psd: list[tuple[float, ...]] = []
    g_psd_se: list[tuple[float, ...]] = []
    freqs: FloatArray = np.empty(0)
    for p in ps:
        vals = np.stack([model.generate(float(p), g) for g in spawn_generators(gens_seed, realizations)])
        target_var = float(np.sum(model.spectrum(model.frequencies(), float(p))) / model.length)
        t_std.append(math.sqrt(target_var))
        # pointwise (x = 0) variance over the realisations: E[μ̂] = 0 is known
        x0 = vals[:, 0]
        s2 = float(np.mean(x0**2))
        se_s2 = math.sqrt(max(float(np.mean(x0**4)) - s2**2, 0.0) / realizations)
        g_std.append(math.sqrt(s2))
        g_se.append(se_s2 / (2.0 * math.sqrt(s2)) if s2 > 0 else 0.0)
        g_grid.append(float(np.mean(vals.std(axis=1))))
        freqs, per = one_sided_psd(vals, model.dx)
        t_psd.append(tuple(float(v) for v in model.spectrum(freqs, float(p))))
        g_psd.append(tuple(float(v) for v in per.mean(axis=0)))
        g_psd_se.append(tuple(float(v) for v in per.std(axis=0, ddof=1) / math.sqrt(realizations)))
    return ProcessCheck(
        pressure_pa=tuple(float(v) for v in ps),
        target_std=tuple(t_std),
        std_pointwise=tuple(g_std),
        std_pointwise_se=tuple(g_se),
        std_grid_mean=tuple(g_grid),
        frequencies=tuple(float(v) for v in freqs),
        target_psd=tuple(t_psd),
        generated_psd=tuple(g_psd),
        generated_psd_se=tuple(g_psd_se),
        realizations=realizations,
    )


@dataclass(frozen=True, kw_only=True, eq=False)
class StatisticalContactAnalysis:
    """All results of :func:`analyse` (SI units; arrays over the approach u last)."""

    config: AnalysisConfig
    seed_entropy: int
    material: dict[str, Any]
    surface_info: dict[str, Any]
    ensemble: ContactSamples
    ergodic: ContactSamples
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
            "sigma_zeta": self.sigma_zeta_table(),
            "process_check": self.process_check.to_dict(),
            "model": self.model.to_dict(),
            "config": self.config.to_dict(),
            "seed_entropy": self.seed_entropy,
            "material": self.material,
            "surface": self.surface_info,
            "notes": list(self.notes),
        }

    def to_dataset(self) -> Any:
        """All statistics as an :class:`xarray.Dataset` (units and provenance in ``attrs``)."""
        import json

        import xarray as xr

        from stochfric.io_utils import package_versions

        ens, erg, path = self.ensemble, self.ergodic, self.path.samples
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
            "ergodic_mu": var(("ergodic_window", *u), erg.mu, "1", "mu of the windows of one long surface"),
            "ergodic_z_mean": var(u, self.ergodicity.z_mean, "1", "(E_win - E_ens)/combined SE"),
            "ergodic_z_std": var(u, self.ergodicity.z_std, "1", "(sd_win - sd_ens)/combined SE"),
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
            "psd": var((*u, "frequency"), self.psd, "m", "one-sided PSD of mu-hat, METHOD 0, mean over surfaces"),
            "psd_se": var((*u, "frequency"), self.psd_se, "m", "SE of psd over surfaces"),
            "psd_level": var(u, self.psd_level, "m", "mean PSD level E[S]"),
            "psd_level_se": var(u, self.psd_level_se, "m", "SE of E[S] over surfaces"),
            "fit_used": var(u, np.asarray(self.fits["mu_mean"].used, dtype=np.int8), "1", "point used in the fits"),
        }
        attrs: dict[str, Any] = {
            "title": "stochfric statistical contact analysis (METHOD 3-4)",
            "config": json.dumps(self.config.to_dict(), sort_keys=True),
            "seed_entropy": str(self.seed_entropy),
            "material": json.dumps(self.material, sort_keys=True),
            "surface": json.dumps(self.surface_info, sort_keys=True, default=str),
            "fits": json.dumps({k: f.to_dict() for k, f in self.fits.items()}, sort_keys=True),
            "ergodicity": json.dumps(self.ergodicity.to_dict(), sort_keys=True),
            "contact_fraction_fit": json.dumps(self.contact_fraction_fit, sort_keys=True),
            "window_shift_m": self.path.window_shift_m,
            "window_length_m": self.path.window_length_m,
            "long_surface_length_m": self.path.surface_length_m,
            "psd_convention": "one-sided, S_k = 2 dy |X_k|^2 / N, sum S df = variance (METHOD 0)",
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
        """Write :meth:`to_dataset` atomically (temporary file + :func:`os.replace`)."""
        from stochfric.io_utils import write_atomic

        ds = self.to_dataset()
        return write_atomic(path, lambda p: ds.to_netcdf(p, engine="h5netcdf"))


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
    progress: Progress | None = None,
) -> StatisticalContactAnalysis:
    """Run the statistical contact analysis a)–e) of the module docstring on ``surface``.

    ``surface`` is the prepared (detrended, filtered, coarsened) surface; windows run along y
    (axis 1).  Three independent child streams of ``config.seed`` drive the ensemble, the
    ergodicity surface and the long surfaces; inside each, realisation / surface k has its own
    child stream.  ``progress(stage, done, total)`` is called after every realisation / surface.
    """
    cfg = config if config is not None else AnalysisConfig()
    root = as_seed_sequence(cfg.seed)
    s_ens, s_erg, s_path, s_check = spawn_seed_sequences(root, 4)
    u = np.asarray(approach_m, dtype=np.float64)

    def stage(label: str) -> Callable[[int, int], None] | None:
        if progress is None:
            return None
        return lambda done, total: progress(label, done, total)

    ens = ensemble_contact(
        surface, material, u, realizations=cfg.realizations, method=cfg.surrogate, seed=s_ens,
        rule=cfg.summit_rule, iaaft_tol=cfg.iaaft_tol, progress=stage("ensemble"),
    )  # fmt: skip
    erg = ergodic_contact(
        surface, material, u, windows=cfg.ergodic_windows, method=cfg.surrogate, seed=s_erg,
        rule=cfg.summit_rule, iaaft_tol=cfg.iaaft_tol,
    )  # fmt: skip
    if progress is not None:
        progress("ergodicity", 1, 1)
    path = path_contact(
        surface, material, u, long_surfaces=cfg.long_surfaces, length_factor=cfg.length_factor,
        shift_points=cfg.window_shift_points, method=cfg.surrogate, seed=s_path, rule=cfg.summit_rule,
        iaaft_tol=cfg.iaaft_tol, progress=stage("long surfaces"),
    )  # fmt: skip
    notes: list[str] = []
    mu_e = ens.mu
    if not np.all(np.isfinite(mu_e)):
        raise ContactError("a realisation carries no load at some approach (μ undefined); use larger approaches")
    e_mean, e_std, e_mean_se, e_std_se = mean_and_std_errors(mu_e)
    e_p = ens.normal_force_n.mean(axis=0) / ens.nominal_area_m2
    e_frac = ens.contact_area_m2.mean(axis=0) / ens.nominal_area_m2
    edges, dens = _pdfs(mu_e, cfg.pdf_bins)
    erg_check = ergodicity_check(mu_e, erg.mu)

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
        levels.append(psd_level(freqs, s_mean, a_y))
        per_surface = [psd_level(freqs, one_sided_psd(mu_p[j, :, k], a_y)[1], a_y) for j in range(k_count)]
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
    )
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
        ergodic=erg,
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
    )

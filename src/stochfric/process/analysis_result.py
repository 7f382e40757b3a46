"""The result of the statistical contact analysis and its files (JSON summary, NetCDF).

:class:`StatisticalContactAnalysis` holds everything :func:`stochfric.process.statistics.analyse`
computes (SI units; arrays over the approach u last), with the fields of the sections its steps return
(:class:`EnsembleStatistics`, :class:`SurrogateChecks`, :class:`PathMoments`, :class:`PathSpectra`);
:meth:`~StatisticalContactAnalysis.to_json_dict`
is the command line's summary, :meth:`~StatisticalContactAnalysis.to_dataset` /
:meth:`~StatisticalContactAnalysis.to_netcdf` the full statistics with units and provenance.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from stochfric.arrays import FloatArray
from stochfric.contact.validity import ValidityWarning
from stochfric.friction_process.model_base import SigmaZetaRule
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.io_utils import package_versions, write_netcdf_atomic
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.checks import (
    CopyCheck,
    ErgodicityCheck,
    ProcessCheck,
    ScanScatter,
    SurrogateCheck,
    WindowScatterCheck,
)
from stochfric.process.credibility import Credibility
from stochfric.process.ensemble import ContactSamples, PathContact
from stochfric.process.fit import ModelFit
from stochfric.process.holdout import HoldoutValidation, MeasuredWindows
from stochfric.process.model_intervals import ModelIntervals
from stochfric.process.pooling import BetweenScanTest

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["EnsembleStatistics", "PathMoments", "PathSpectra", "StatisticalContactAnalysis", "SurrogateChecks"]


@dataclass(frozen=True, kw_only=True, eq=False)
class EnsembleStatistics:
    """Statistics of the surrogate ensemble per approach u (§4a, Fig. 3.16–3.18a): E[μ], σ_μ and their
    standard errors, the mean pressure [Pa] and A_c/A_nom with its line fit, the PDFs of μ."""

    ensemble_mu_mean: FloatArray
    ensemble_mu_std: FloatArray
    ensemble_mu_mean_se: FloatArray
    ensemble_mu_std_se: FloatArray
    ensemble_pressure_pa: FloatArray
    ensemble_area_fraction: FloatArray
    pdf_edges: FloatArray
    pdf_density: FloatArray
    contact_fraction_fit: dict[str, float]


@dataclass(frozen=True, kw_only=True, eq=False)
class SurrogateChecks:
    """The checks of the surrogates against the measurement and themselves (§4b)."""

    ergodicity: ErgodicityCheck
    surrogate_check: SurrogateCheck
    #: The measured-window check (None when the map is too small for 2 × 2 windows).
    window_check: WindowScatterCheck | None
    #: Between-scan, within-scan and ensemble scatter of μ (:func:`~stochfric.process.statistics.analyse`).
    scan_scatter: ScanScatter
    #: Overlap of the first surrogates with the map and each other (:func:`~stochfric.process.checks.copy_check`).
    copy_check: CopyCheck | None = None
    #: The surrogate model tested on held-out halves of the map (:mod:`stochfric.process.holdout`).
    holdout: HoldoutValidation | None = None
    #: μ(u) over disjoint windows of the measurement itself, with intervals (rests on the measurement alone).
    measured_windows: MeasuredWindows | None = None
    #: Pooled scans: are they of one surface?  (:func:`~stochfric.process.pooling.between_scan_test`)
    between_scans: BetweenScanTest | None = None


@dataclass(frozen=True, kw_only=True, eq=False)
class PathMoments:
    """Moments and autocorrelation of μ along the path per approach u (§4c, eq. 3.17–3.18)."""

    pressure_pa: FloatArray
    area_fraction: FloatArray
    mu_mean: FloatArray
    mu_std: FloatArray
    mu_mean_se: FloatArray
    mu_std_se: FloatArray
    lags_m: FloatArray
    acf: FloatArray
    #: The thesis's correlation length: first zero crossing of the averaged ACF [m] (NaN: none).
    zero_crossing_m: FloatArray


@dataclass(frozen=True, kw_only=True, eq=False)
class PathSpectra:
    """PSD, its level and the correlation length of μ along the path per approach u (§4c, eq. 3.19–3.20)."""

    frequencies: FloatArray
    psd: FloatArray
    psd_se: FloatArray
    psd_level: FloatArray
    psd_level_se: FloatArray
    #: Integral correlation length S(0)/(4σ_μ²) along the path [m], mean over the K surfaces, and its SE.
    correlation_length_m: FloatArray
    correlation_length_se_m: FloatArray
    #: 95 % interval [lo, hi] of the correlation length per u (Student t over the K surfaces), shape (U, 2).
    correlation_length_ci95_m: FloatArray = field(default_factory=lambda: np.empty((0, 2)))


@dataclass(frozen=True, kw_only=True, eq=False)
class StatisticalContactAnalysis(EnsembleStatistics, SurrogateChecks, PathMoments, PathSpectra):
    """All results of :func:`analyse` (SI units; arrays over the approach u last): the fields of its
    sections (ensemble (a), checks (b), path (c)) and the ones below."""

    config: AnalysisConfig
    seed_entropy: int
    material: dict[str, Any]
    surface_info: dict[str, Any]
    ensemble: ContactSamples
    path: PathContact
    #: The gate: the reasons why this analysis is not credible (:mod:`stochfric.process.credibility`).
    credibility: Credibility
    #: The surrogate method used and why (``"auto"`` resolved by the map, or the user's choice).
    surrogate_choice: str = ""
    # fits (d) and model (e)
    fits: dict[str, ModelFit]
    model: TabulatedProcessModel
    process_check: ProcessCheck
    notes: list[str] = field(default_factory=list)
    #: Validity of the model on this surface (:mod:`stochfric.contact.validity`): μ > 1,
    #: A_c/A_nom > 1 or beyond the non-interaction range, too few contacts, plasticity index.
    warnings: list[ValidityWarning] = field(default_factory=list)
    #: 95 % intervals of the model's E[μ](p), σ_μ(p): Monte Carlo and surface sampling (issue 29, item 1).
    model_intervals: ModelIntervals | None = None

    def __repr__(self) -> str:
        p = np.asarray(self.pressure_pa) / 1e6
        mu = np.asarray(self.mu_mean)
        ell = np.asarray(self.correlation_length_m) * 1e3
        verdict = ("credible" if self.credibility.credible
                   else f"NOT credible ({', '.join(self.credibility.codes())})")
        return (f"StatisticalContactAnalysis({self.config.surrogate} → {self.surrogate_choice or '?'} surrogates, "
                f"{self.config.realizations} realisations, seed {self.seed_entropy}: p {np.nanmin(p):.3g}…"
                f"{np.nanmax(p):.3g} MPa, E[μ] {np.nanmin(mu):.3g}…{np.nanmax(mu):.3g}, correlation length "
                f"{np.nanmin(ell):.3g}…{np.nanmax(ell):.3g} mm; {verdict})")

    def _correlation_length_ci95(self) -> FloatArray:
        """The (U, 2) interval array (NaN where it was not computed)."""
        ci = np.asarray(self.correlation_length_ci95_m, dtype=np.float64)
        n_u = np.asarray(self.correlation_length_m).size
        return ci if ci.shape == (n_u, 2) else np.full((n_u, 2), np.nan)

    def plot(self, which: str | None = None) -> Figure:
        """A figure of the analysis as a matplotlib figure (save it with ``fig.savefig(path)``): ``which`` is the
        name of one of the figures ``friction-process --plot`` writes, without ``.png``
        (:data:`~stochfric.process.figures.ANALYSIS_FIGURES`); default ``model_functions``: E[μ], σ_μ and E[S]
        over p with the fitted model functions a p^b + c."""
        from stochfric.process.figures import analysis_figure

        return analysis_figure(self, which)

    def sigma_zeta_table(self) -> dict[str, list[float]]:
        """σ_ζ at the analysed pressures by both rules (``sigma_mu`` and ``spectral_level``)."""
        out: dict[str, list[float]] = {"pressure_pa": [float(p) for p in self.pressure_pa]}
        for rule in SigmaZetaRule:
            m = replace(self.model, sigma_zeta_rule=rule)
            vals: list[float] = []
            for p in self.pressure_pa:
                try:
                    vals.append(m.sigma_zeta(float(p)))
                except ValueError:
                    vals.append(math.nan)
            out[rule.value] = vals
        return out

    def sources(self) -> dict[str, str]:
        """Which numbers rest on the measurement and which on the surrogate model (for every output)."""
        model = f"surrogate model ({self.surrogate_choice.split(' ')[0] or self.config.surrogate})"
        return {
            "measured_windows": "measurement: disjoint windows of the prepared map(s), no model",
            "model_intervals": ("surrogate-model values; 95 % intervals from the Monte Carlo error and the "
                                "measurement's sampling uncertainty (measured_windows)"),
            "surrogate_check.measured": "measurement: the whole prepared map(s)",
            "holdout": "measurement (held-out half) against the surrogate model built from the other half",
            "ensemble": f"{model}: {self.config.realizations} surrogates of the map's size",
            "mu_mean, mu_std, correlation_length, psd_level, fit, model": (
                f"{model}: {self.config.long_surfaces} long surfaces of {self.config.length_factor} map lengths"),
        }

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
            "correlation_length_se_m": lst(self.correlation_length_se_m),
            "correlation_length_ci95_m": [lst(row) for row in self._correlation_length_ci95()],
            "correlation_length_surfaces": int(self.path.samples.mu.shape[0]),
            "correlation_length_rule": "integral scale S(0)/(4 sigma_mu^2) per long surface, mean and SE over them; "
                                       "95 % interval mean +- t(K-1) SE",
            "zero_crossing_m": lst(self.zero_crossing_m),
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
            "window_check": None if self.window_check is None else self.window_check.to_dict(),
            "scan_scatter": self.scan_scatter.to_dict(),
            "credibility": self.credibility.to_dict(),
            "surrogate_choice": self.surrogate_choice,
            "copy_check": self.copy_check.to_dict() if self.copy_check is not None else {},
            "holdout": None if self.holdout is None else self.holdout.to_dict(),
            "between_scans": None if self.between_scans is None else self.between_scans.to_dict(),
            "measured_windows": None if self.measured_windows is None else self.measured_windows.to_dict(),
            "model_intervals": None if self.model_intervals is None else self.model_intervals.to_dict(),
            "sources": self.sources(),
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
            "correlation_length_m": var(u, self.correlation_length_m, "m",
                                        "integral correlation length S(0)/(4 sigma_mu^2), mean over surfaces"),
            "correlation_length_se_m": var(u, self.correlation_length_se_m, "m", "SE of correlation_length_m"),
            "correlation_length_ci95_m": var((*u, "bound"), self._correlation_length_ci95(), "m",
                                             "95 % Student-t interval of correlation_length_m over the surfaces"),
            "zero_crossing_m": var(u, self.zero_crossing_m, "m", "first zero crossing of the averaged ACF (thesis)"),
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
            "window_check": json.dumps(None if self.window_check is None else self.window_check.to_dict(),
                                       sort_keys=True),
            "scan_scatter": json.dumps(self.scan_scatter.to_dict(), sort_keys=True),
            "credibility": json.dumps(self.credibility.to_dict(), sort_keys=True),
            "surrogate_choice": self.surrogate_choice,
            "copy_check": json.dumps(self.copy_check.to_dict() if self.copy_check is not None else {},
                                     sort_keys=True),
            "holdout": json.dumps(None if self.holdout is None else self.holdout.to_dict(), sort_keys=True),
            "measured_windows": json.dumps(None if self.measured_windows is None else self.measured_windows.to_dict(),
                                           sort_keys=True),
            "model_intervals": json.dumps(None if self.model_intervals is None else self.model_intervals.to_dict(),
                                          sort_keys=True),
            "sources": json.dumps(self.sources(), sort_keys=True),
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

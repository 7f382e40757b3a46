"""Intervals of the model's E[μ](p) and σ_μ(p) that include what one measurement cannot know (issue 29, item 1).

The surrogate model's E[μ] and σ_μ (along the long surfaces, §4c) carry two uncertainties:

* **Monte Carlo** — a finite number K of long surfaces: the standard errors ``mu_mean_se``/``mu_std_se``
  of :class:`~stochfric.process.analysis_result.PathMoments`;
* **surface sampling** — the surrogates are made from *one* measured area, which holds only a few
  independent windows (:class:`~stochfric.process.holdout.MeasuredWindows`, effective number n_eff).  More
  surrogates cannot shrink this part; only more measured area can.

Rules (stated approximations, docs/statistical_contact.md §0e):

* E[μ]: the measured window mean estimates the surface's mean μ with the 95 % jackknife half-width h_m
  (t quantile, J − 1).  The mean of μ over windows hardly depends on the window size, so the model's
  interval is ``E_model ± sqrt(h_m² + (1.96 SE_MC)²)``.
* σ_μ: the scatter depends on the window size (the measured windows are smaller than the model's), so
  the measurement's interval enters as a *relative* one: ``σ_model (1 − sqrt(r_lo² + r_MC²))`` …
  ``σ_model (1 + sqrt(r_hi² + r_MC²))`` with ``r_lo = 1 − lo_m/σ_m``, ``r_hi = hi_m/σ_m − 1`` (the
  measured sd's 95 % jackknife interval relative to its value) and ``r_MC = 1.96 SE_MC/σ_model``;
  the lower bound is clipped at 0.

Where the measurement has no windows (a map with too few summits for 2 × 2 windows), the intervals are
the Monte Carlo ones and :attr:`ModelIntervals.includes_sampling` is False, which every output says.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.process.holdout import MeasuredWindows

__all__ = ["Z95", "ModelIntervals", "model_intervals"]

#: Two-sided 95 % normal quantile of the Monte Carlo part.
Z95 = 1.959963984540054


@dataclass(frozen=True, kw_only=True, eq=False)
class ModelIntervals:
    """95 % intervals of the model's E[μ](p) and σ_μ(p) per approach (module docstring for the rules)."""

    pressure_pa: FloatArray
    mu_mean: FloatArray
    mu_mean_ci95: FloatArray
    mu_std: FloatArray
    mu_std_ci95: FloatArray
    #: Half-width of E[μ] from the surface sampling alone (NaN: no measured windows).
    mu_mean_sampling_halfwidth: FloatArray
    #: Half-width of E[μ] from the Monte Carlo error alone.
    mu_mean_mc_halfwidth: FloatArray
    #: True when the measured windows entered (else the intervals are Monte Carlo only).
    includes_sampling: bool
    effective_windows: float | None
    rule: str = ("E[mu]: model +- sqrt(h_meas^2 + (1.96 SE_MC)^2), h_meas the 95 % jackknife half-width of the "
                 "measured window mean; sigma_mu: model x (1 -+ sqrt(r_meas^2 + r_MC^2)), r_meas the measured "
                 "window sd's relative 95 % interval, r_MC = 1.96 SE_MC / sigma_model; lower bound >= 0")

    def sampling_share(self) -> FloatArray:
        """Share of the E[μ] interval's variance that is surface sampling (0 … 1; NaN without windows)."""
        s = np.asarray(self.mu_mean_sampling_halfwidth) ** 2
        m = np.asarray(self.mu_mean_mc_halfwidth) ** 2
        with np.errstate(invalid="ignore", divide="ignore"):
            return np.asarray(s / (s + m), dtype=np.float64)

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (SI; None for undefined values)."""

        def lst(a: npt.ArrayLike) -> list[Any]:
            arr = np.asarray(a, dtype=np.float64)
            if arr.ndim == 2:
                return [lst(row) for row in arr]
            return [float(v) if math.isfinite(float(v)) else None for v in arr]

        return {
            "pressure_pa": lst(self.pressure_pa), "mu_mean": lst(self.mu_mean),
            "mu_mean_ci95": lst(self.mu_mean_ci95), "mu_std": lst(self.mu_std), "mu_std_ci95": lst(self.mu_std_ci95),
            "mu_mean_sampling_halfwidth": lst(self.mu_mean_sampling_halfwidth),
            "mu_mean_mc_halfwidth": lst(self.mu_mean_mc_halfwidth),
            "sampling_share": lst(self.sampling_share()),
            "includes_sampling": self.includes_sampling, "effective_windows": self.effective_windows,
            "source": "surrogate model values; intervals: Monte Carlo and, where includes_sampling, the sampling "
                      "uncertainty of the measurement (measured_windows)",
            "rule": self.rule,
        }  # fmt: skip


def model_intervals(
    *, pressure_pa: npt.ArrayLike, mu_mean: npt.ArrayLike, mu_mean_se: npt.ArrayLike, mu_std: npt.ArrayLike,
    mu_std_se: npt.ArrayLike, measured: MeasuredWindows | None,
) -> ModelIntervals:
    """95 % intervals of the model's E[μ] and σ_μ per approach (module docstring); arrays over the approaches.

    ``measured`` must be over the same approaches (same length) or None."""
    m = np.asarray(mu_mean, dtype=np.float64)
    s = np.asarray(mu_std, dtype=np.float64)
    h_mc = Z95 * np.asarray(mu_mean_se, dtype=np.float64)
    with np.errstate(invalid="ignore", divide="ignore"):
        r_mc = Z95 * np.asarray(mu_std_se, dtype=np.float64) / s
    if measured is not None and np.asarray(measured.mu_mean).shape == m.shape:
        mean_ci = np.asarray(measured.mu_mean_ci95, dtype=np.float64)
        h_meas = 0.5 * (mean_ci[:, 1] - mean_ci[:, 0])
        std_ci = np.asarray(measured.mu_std_ci95, dtype=np.float64)
        sm = np.asarray(measured.mu_std, dtype=np.float64)
        with np.errstate(invalid="ignore", divide="ignore"):
            r_lo = np.clip(1.0 - std_ci[:, 0] / sm, 0.0, None)
            r_hi = np.clip(std_ci[:, 1] / sm - 1.0, 0.0, None)
        n_eff: float | None = float(np.nanmin(measured.effective_windows))
        sampling = True
    else:
        h_meas = np.full_like(m, np.nan)
        r_lo = r_hi = np.zeros_like(m)
        n_eff, sampling = None, False
    h = np.sqrt(np.nan_to_num(h_meas) ** 2 + h_mc**2)
    lo_rel = np.sqrt(r_lo**2 + r_mc**2)
    hi_rel = np.sqrt(r_hi**2 + r_mc**2)
    return ModelIntervals(
        pressure_pa=np.asarray(pressure_pa, dtype=np.float64), mu_mean=m,
        mu_mean_ci95=np.stack([m - h, m + h], axis=1), mu_std=s,
        mu_std_ci95=np.stack([np.clip(s * (1.0 - lo_rel), 0.0, None), s * (1.0 + hi_rel)], axis=1),
        mu_mean_sampling_halfwidth=h_meas, mu_mean_mc_halfwidth=h_mc, includes_sampling=sampling,
        effective_windows=n_eff,
    )  # fmt: skip

"""The friction process with spectra tabulated at the analysed pressures (method §4d/e).

What the statistical contact analysis (:func:`stochfric.process.statistics.analyse`, command
``stochfric friction-process``) produces: fitted E[μ](p), σ_μ(p) and the measured one-sided PSDs of
μ along the path at the analysed mean pressures.
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.errors import InputError, InputTypeError, ProcessModelError
from stochfric.friction_process.model_base import ProcessModelBase, SigmaZetaRule, low_frequency_level
from stochfric.friction_process.model_function import ModelFunction, checked_pressure
from stochfric.friction_process.spectra import psd_level
from stochfric.validation import finite_tuple, positive

__all__ = ["PressureRule", "TabulatedProcessModel", "VarianceRule"]

class PressureRule(StrEnum):
    """How a tabulated spectrum is read between the analysed pressures: ``nearest`` (the thesis) or
    ``interpolate`` (log-log in p)."""

    NEAREST = "nearest"
    INTERPOLATE = "interpolate"


class VarianceRule(StrEnum):
    """The variance of a tabulated process: ``sigma_mu`` (scaled to the σ_μ(p) fit) or ``tabulated``."""

    SIGMA_MU = "sigma_mu"
    TABULATED = "tabulated"



@dataclass(frozen=True, kw_only=True)
class TabulatedProcessModel(ProcessModelBase):
    """Friction process with spectra tabulated at the analysed pressures (method §4d/e).

    Built from the statistical contact analysis (``stochfric friction-process``): the mean and
    standard deviation follow fitted model functions, the spectrum shape comes from the one-sided
    PSDs of μ along the path (method §0) measured at the analysed mean pressures.

    Parameters
    ----------
    name:
        Label.
    mu_mean, mu_std:
        Fitted model functions E[μ](p), σ_μ(p) (eq. 3.21), p in Pa.
    dx, length:
        Process grid spacing Δx and length ℓ [m]; the band is f_k = k/ℓ < 1/(2Δx).  The analysis
        uses Δx = a_y and ℓ = (number of windows) · a_y, so the band equals the measured one.
    pressures_pa:
        The analysed mean pressures p_j [Pa] (> 0, strictly increasing).
    table_frequencies:
        Path frequencies of the tabulated spectra [1/m] (> 0, strictly increasing).
    table_psd:
        One-sided PSD S_j(f) [m] (method §0), one row per pressure, one column per frequency.
    pressure_rule:
        ``"nearest"`` (thesis §3.3.4: the spectrum of the analysed pressure nearest to p, nearest
        in log p) or ``"interpolate"`` (pressure-continuous, missing in the thesis): log S is
        interpolated linearly in log p for every tabulated frequency, clamped to the end rows
        outside [p_1, p_n].
    variance_rule:
        ``"sigma_mu"`` (default): only the *shape* of the chosen spectrum is used; it is scaled so
        that Σ_band S Δf = σ_μ(p)² from the fitted model function (method §4d; the fit smooths
        the scatter and excludes the high-pressure outliers).  ``"tabulated"``: the tabulated
        levels are used as they are (variance = the measured path variance at that pressure).
    sigma_zeta_rule:
        ``"sigma_mu"`` or ``"spectral_level"`` (see :meth:`sigma_zeta`).
    psd_level:
        Optional fitted E[S](p) = S(f → 0) [m] (method §0 convention), recorded as metadata.
    window_length_m:
        Length ℓ of the contact windows whose μ the spectra describe [m] (the analysis's window
        = the measured map's length).  μ of a window is a moving average over ℓ, so the
        tabulated spectra carry the window's low-pass ≈ 1/(πfℓ)² above 1/ℓ; it is kept as
        physics (a contact patch of length ℓ averages its friction) and made explicit here.  The
        ``"spectral_level"`` σ_ζ rule uses S(f → 0) below 1/(4ℓ) (:meth:`sigma_zeta`).

    Notes
    -----
    Between tabulated frequencies S is interpolated linearly in f; below the first tabulated
    frequency the first value is used (clamped), above the last S = 0 (nothing was measured
    there).  This matters only when ``dx``/``length`` differ from the analysis (e.g. a longer
    process through ``dataclasses.replace``).
    """

    name: str
    mu_mean: ModelFunction
    mu_std: ModelFunction
    dx: float
    length: float
    pressures_pa: tuple[float, ...]
    table_frequencies: tuple[float, ...]
    table_psd: tuple[tuple[float, ...], ...]
    pressure_rule: PressureRule = PressureRule.NEAREST
    variance_rule: VarianceRule = VarianceRule.SIGMA_MU
    sigma_zeta_rule: SigmaZetaRule = SigmaZetaRule.SIGMA_MU
    psd_level: ModelFunction | None = None
    window_length_m: float | None = None
    #: Why the analysis that made this model was not credible (empty: it was); a model written
    #: with ``--accept-not-credible`` carries the reasons and every command that reads it warns.
    not_credible: tuple[str, ...] = ()
    #: (p_min, p_max) [Pa] of the pressures the model functions were fitted on (None: the tabulated
    #: pressures' range, for files written before it was recorded); use outside it is refused
    #: (:func:`~stochfric.friction_process.model_base.check_pressure_range`).
    fitted_range_pa: tuple[float, float] | None = None
    #: The contact model E[μ](p) and σ_μ(p) come from (``gw``, ``bem``, ``bem-plastic``, ``persson``;
    #: :mod:`stochfric.process.contact_models`); files written before it was recorded are GW.
    contact_model: str = "gw"

    def __post_init__(self) -> None:
        if self.window_length_m is not None:
            window = positive("window_length_m", self.window_length_m, "m", error=ProcessModelError)
            object.__setattr__(self, "window_length_m", window)
        self._check_common()
        if self.psd_level is not None and not isinstance(self.psd_level, ModelFunction):
            raise InputTypeError(f"psd_level must be a ModelFunction or None, got {self.psd_level!r}")
        p = finite_tuple("pressures_pa", self.pressures_pa, error=ProcessModelError)
        f = finite_tuple("table_frequencies", self.table_frequencies, error=ProcessModelError)
        if min(p) <= 0.0 or any(b <= a for a, b in itertools.pairwise(p)):
            raise ProcessModelError("pressures_pa must be > 0 Pa and strictly increasing")
        if min(f) <= 0.0 or any(b <= a for a, b in itertools.pairwise(f)):
            raise ProcessModelError("table_frequencies must be > 0 [1/m] and strictly increasing")
        try:
            table = np.asarray(self.table_psd, dtype=np.float64)
        except (TypeError, ValueError):
            raise ProcessModelError("table_psd must be a (pressures × frequencies) table of numbers") from None
        if table.shape != (len(p), len(f)):
            raise ProcessModelError(
                f"table_psd has shape {table.shape}, expected ({len(p)}, {len(f)}) = (pressures, frequencies)"
            )
        if not (np.all(np.isfinite(table)) and np.all(table >= 0.0)):
            raise ProcessModelError("table_psd must be finite and >= 0 [m]")
        object.__setattr__(self, "pressures_pa", p)
        object.__setattr__(self, "table_frequencies", f)
        if self.fitted_range_pa is not None:
            rng = finite_tuple("fitted_range_pa", self.fitted_range_pa, error=ProcessModelError)
            lo, hi = (rng[0], rng[-1]) if len(rng) == 2 else (math.nan, math.nan)
            if not 0.0 < lo <= hi:
                raise ProcessModelError(f"fitted_range_pa must be (p_min, p_max) with 0 < p_min <= p_max Pa, "
                                        f"got {self.fitted_range_pa!r}")
            object.__setattr__(self, "fitted_range_pa", (lo, hi))
        object.__setattr__(self, "table_psd", tuple(tuple(float(v) for v in row) for row in table))
        for attr, rule in (("pressure_rule", PressureRule), ("variance_rule", VarianceRule)):
            if getattr(self, attr) not in tuple(rule):
                raise ProcessModelError(
                    f"{attr} must be one of {tuple(str(r) for r in rule)}, got {getattr(self, attr)!r}")
            object.__setattr__(self, attr, rule(getattr(self, attr)))

    # --- the spectrum ------------------------------------------------------------------

    def table_spectrum(self, p_pa: float) -> NDArray[np.float64]:
        """The tabulated spectrum at pressure p by :attr:`pressure_rule` [m], at the table's frequencies."""
        p = checked_pressure(p_pa)
        table = np.asarray(self.table_psd, dtype=np.float64)
        logp = np.log(np.asarray(self.pressures_pa))
        if self.pressure_rule == "nearest" or len(self.pressures_pa) == 1:
            return np.asarray(table[int(np.argmin(np.abs(logp - math.log(p))))])
        tiny = np.finfo(np.float64).tiny
        logs = np.log(np.maximum(table, tiny))
        x = min(max(math.log(p), float(logp[0])), float(logp[-1]))
        j = int(np.clip(np.searchsorted(logp, x, side="right") - 1, 0, len(logp) - 2))
        t = (x - logp[j]) / (logp[j + 1] - logp[j])
        out = np.exp((1.0 - t) * logs[j] + t * logs[j + 1])
        return np.asarray(np.where(out <= tiny * 1.0001, 0.0, out))

    def _shape(self, f: NDArray[np.float64], p_pa: float) -> NDArray[np.float64]:
        tf = np.asarray(self.table_frequencies)
        row = self.table_spectrum(p_pa)
        vals = np.interp(f, tf, row, left=float(row[0]), right=0.0)
        return np.asarray(np.where(f > tf[-1] * (1.0 + 1e-9), 0.0, vals))

    def spectrum(self, f: ArrayLike, p_pa: float) -> NDArray[np.float64]:
        """One-sided PSD S(f; p) [m] at path frequencies f [1/m] (method §0), 0 outside the band.

        ``variance_rule = "sigma_mu"``: S = σ_μ(p)² g(f) / (Δf Σ_band g), g the tabulated shape at
        p (:meth:`table_spectrum`, interpolated in f); ``"tabulated"``: S = g.
        """
        freq = np.asarray(f, dtype=np.float64)
        if not np.all(np.isfinite(freq)):
            raise InputError("frequencies f must be finite [1/m]")
        band = self.frequencies()
        g = self._shape(freq, p_pa)
        if self.variance_rule == "sigma_mu":
            total = float(np.sum(self._shape(band, p_pa)))
            if total <= 0.0:
                raise InputError(
                    f"the tabulated spectrum is zero over the band {band[0]:.4g} … {band[-1]:.4g} 1/m; "
                    "dx/length do not overlap the measured frequencies"
                )
            g = g * (self.std(p_pa) ** 2 / (self.frequency_step * total))
        inside = (freq >= band[0] * (1.0 - 1e-9)) & (freq <= band[-1] * (1.0 + 1e-9))
        return np.asarray(np.where(inside, g, 0.0))

    def sigma_zeta(self, p_pa: float) -> float:
        """White-noise intensity σ_ζ(p) for the white-noise model (method §5.1, eq. 4.17).

        ``"sigma_mu"`` (thesis §4.1.2): σ_ζ = σ_μ(p).  ``"spectral_level"``: the noise term of
        eq. (4.17) has a one-sided PSD 2σ_ζ at every f (see
        :meth:`BandLimitedProcessModel.sigma_zeta`), matched to the process's level at f → 0:
        σ_ζ = S(0)/2.  With :attr:`window_length_m` known, S(0) is
        :func:`stochfric.friction_process.spectra.psd_level` of the model spectrum (bins f ≤ 1/(4ℓ),
        window response divided out), which does not depend on the window shift of the
        analysis; without it, the mean over the lowest quarter of the band.
        """
        if self.sigma_zeta_rule == "sigma_mu":
            return self.std(p_pa)
        band = self.frequencies()
        spec = self.spectrum(band, p_pa)
        if self.window_length_m is None:
            return 0.5 * low_frequency_level(spec)
        return 0.5 * psd_level(band, spec, self.window_length_m)

    def pressure_range_pa(self) -> tuple[float, float]:
        """(p_min, p_max) [Pa] the model was fitted on (:attr:`fitted_range_pa`, else the tabulated range)."""
        if self.fitted_range_pa is not None:
            return self.fitted_range_pa
        return self.pressures_pa[0], self.pressures_pa[-1]

    # --- serialisation -----------------------------------------------------------------

    def to_dict(self) -> dict[str, Any]:
        """JSON-compatible dict (``kind = "tabulated"``, SI units recorded)."""
        return {
            **self._dict_head("tabulated"),
            "pressures_pa": list(self.pressures_pa),
            "table_frequencies": list(self.table_frequencies),
            "table_psd": [list(row) for row in self.table_psd],
            "pressure_rule": self.pressure_rule,
            "variance_rule": self.variance_rule,
            "sigma_zeta_rule": self.sigma_zeta_rule,
            "psd_level": None if self.psd_level is None else self.psd_level.to_dict(),
            "window_length_m": self.window_length_m,
            "not_credible": list(self.not_credible),
            "fitted_range_pa": None if self.fitted_range_pa is None else list(self.fitted_range_pa),
            "contact_model": self.contact_model,
            **self._dict_tail(),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> TabulatedProcessModel:
        """Inverse of :meth:`to_dict`; ValueError naming the missing fields otherwise."""
        cls._check_kind(data, "tabulated")
        required = ("name", "mu_mean", "mu_std", "dx", "length", "pressures_pa", "table_frequencies", "table_psd")
        missing = [k for k in required if k not in data]
        if missing:
            raise ProcessModelError(f"a process model of kind 'tabulated' needs the field(s) {', '.join(missing)}")
        level = data.get("psd_level")
        return cls(
            **cls._head_fields(data),
            pressures_pa=tuple(data["pressures_pa"]),
            table_frequencies=tuple(data["table_frequencies"]),
            table_psd=tuple(tuple(row) for row in data["table_psd"]),
            pressure_rule=data.get("pressure_rule", "nearest"),
            variance_rule=data.get("variance_rule", "sigma_mu"),
            sigma_zeta_rule=data.get("sigma_zeta_rule", "sigma_mu"),
            not_credible=tuple(str(r) for r in data.get("not_credible", ())),
            psd_level=None if level is None else ModelFunction.from_dict(level),
            window_length_m=data.get("window_length_m"),
            fitted_range_pa=None if data.get("fitted_range_pa") is None else tuple(data["fitted_range_pa"]),
            contact_model=str(data.get("contact_model", "gw")),
        )

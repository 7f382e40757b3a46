"""The band-limited friction process with model-function statistics (method §4d/e).

S(f; p) flat or falling linearly over the band, scaled so that its variance is σ_μ(p)² exactly;
the thesis's presets (:mod:`stochfric.friction_process.presets`) are of this kind.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, Literal, get_args

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.errors import InputError, ProcessModelError
from stochfric.friction_process.model_base import ProcessModelBase, SigmaZetaRule, low_frequency_level
from stochfric.friction_process.model_function import ModelFunction
from stochfric.validation import finite

__all__ = ["BandLimitedProcessModel", "SpectrumShape"]

SpectrumShape = Literal["flat", "falling"]

_SPECTRUM_SHAPES: tuple[str, ...] = get_args(SpectrumShape)


@dataclass(frozen=True, kw_only=True)
class BandLimitedProcessModel(ProcessModelBase):
    """Band-limited friction process with model-function statistics (method §4d/e).

    Parameters
    ----------
    name:
        Label (e.g. ``"brake"``).
    mu_mean, mu_std:
        Model functions E[μ](p) and σ_μ(p), p in Pa (eq. 3.21, Tables 3.3/3.6).
    dx:
        Process grid spacing Δx [m]; the band ends strictly below 1/(2Δx).
    length:
        Process length ℓ [m]; the band starts at Δf = 1/ℓ (harmonics k/ℓ).
    spectrum_shape:
        ``"flat"``: S constant over the band (the thesis found the brake spectrum
        flat, §3.2.4).  ``"falling"``: S falls linearly from 1 at f_min to
        ``falling_ratio`` at f_max (relative), our documented stand-in for the sheet
        spectrum, which the thesis only describes as falling slightly with frequency
        (§3.3.3), until measured spectra are tabulated.
    falling_ratio:
        S(f_max)/S(f_min) of the ``"falling"`` shape, in [0, 1]; ignored for ``"flat"``.
    sigma_zeta_rule:
        How the white-noise intensity σ_ζ(p) of the white-noise model (§5.1, eq. 4.17)
        follows from this model; ``"sigma_mu"``: σ_ζ = σ_μ(p), the thesis's rule
        (§4.1.2: "σ_ζ ist gleich der Standardabweichung des ortsabhängigen Prozesses");
        ``"spectral_level"``: σ_ζ = S0/2, white noise with the process's low-frequency
        one-sided PSD level S0 (see :meth:`sigma_zeta`).

    Notes
    -----
    The spectrum is scaled so that Σ_i S(f_i; p) Δf = σ_μ(p)² exactly over the band
    f_i = k/ℓ, k = 1..K (method §4d), so a realisation on a grid with ℓ/Δx an integer has
    variance σ_μ(p)² exactly.  If ℓ/Δx is not an integer (both thesis presets), the n =
    round(ℓ/Δx) grid points do not cover exactly one period ℓ; see :attr:`grid_is_periodic`.
    """

    name: str
    mu_mean: ModelFunction
    mu_std: ModelFunction
    dx: float
    length: float
    spectrum_shape: SpectrumShape = "flat"
    falling_ratio: float = 0.5
    sigma_zeta_rule: SigmaZetaRule = SigmaZetaRule.SIGMA_MU

    def __post_init__(self) -> None:
        self._check_common()
        if self.spectrum_shape not in _SPECTRUM_SHAPES:
            raise ProcessModelError(
                f"spectrum_shape must be one of {_SPECTRUM_SHAPES}, got {self.spectrum_shape!r}"
            )
        ratio = finite("falling_ratio", self.falling_ratio, error=ProcessModelError)
        if not 0.0 <= ratio <= 1.0:
            raise ProcessModelError(f"falling_ratio must lie in [0, 1], got {self.falling_ratio!r}")
        object.__setattr__(self, "falling_ratio", ratio)

    def sigma_zeta(self, p_pa: float) -> float:
        """White-noise intensity σ_ζ(p) [-] for the white-noise model (method §5.1, eq. 4.17).

        Rule ``"sigma_mu"`` (thesis §4.1.2): σ_ζ = σ_μ(p), the standard deviation of the
        path-dependent process.  Rule ``"spectral_level"``: σ_ζ = S0/2 with S0 the mean
        one-sided PSD over the lowest quarter of the band (:func:`low_frequency_level`; for
        the flat shape the level σ_μ(p)²/(K Δf)); see ``docs/statistical_contact.md``.
        """
        if self.sigma_zeta_rule == "sigma_mu":
            return self.std(p_pa)
        if self.sigma_zeta_rule == "spectral_level":
            return 0.5 * low_frequency_level(self.spectrum(self.frequencies(), p_pa))
        raise AssertionError(f"unhandled sigma_zeta_rule {self.sigma_zeta_rule!r}")

    # --- the spectrum ------------------------------------------------------------------

    def _shape(self, f: NDArray[np.float64]) -> NDArray[np.float64]:
        """Relative spectrum shape g(f) over the band (1 at f_min)."""
        if self.spectrum_shape == "flat":
            return np.ones_like(f)
        band = self.frequencies()
        f_min, f_max = float(band[0]), float(band[-1])
        if f_max == f_min:
            return np.ones_like(f)
        return 1.0 + (self.falling_ratio - 1.0) * (f - f_min) / (f_max - f_min)

    def spectrum(self, f: ArrayLike, p_pa: float) -> NDArray[np.float64]:
        """One-sided PSD S(f; p) [m] of μ̂_SD at path frequencies f [1/m] (method §0, §4d).

        S(f; p) = σ_μ(p)² g(f) / (Δf Σ_i g(f_i)), so that Σ_i S(f_i; p) Δf = σ_μ(p)² over
        the band f_i = k/ℓ; g = 1 (``"flat"``) or linear from 1 at f_min to
        ``falling_ratio`` at f_max (``"falling"``).  Band-limited: S = 0 outside
        [f_min, f_max] (relative tolerance 1e-9).  Units: f in 1/m, S in m (variance per
        1/m), p in Pa.
        """
        freq = np.asarray(f, dtype=np.float64)
        if not np.all(np.isfinite(freq)):
            raise InputError("frequencies f must be finite [1/m]")
        band = self.frequencies()
        variance = self.std(p_pa) ** 2
        scale = variance / (self.frequency_step * float(np.sum(self._shape(band))))
        inside = (freq >= band[0] * (1.0 - 1e-9)) & (freq <= band[-1] * (1.0 + 1e-9))
        result: NDArray[np.float64] = np.where(inside, scale * self._shape(freq), 0.0)
        return result

    # --- serialisation -----------------------------------------------------------------

    def to_dict(self) -> dict[str, Any]:
        """JSON-compatible dict (``kind = "band_limited"``, SI units recorded)."""
        return {
            **self._dict_head("band_limited"),
            "spectrum_shape": self.spectrum_shape,
            "falling_ratio": self.falling_ratio,
            "sigma_zeta_rule": self.sigma_zeta_rule,
            **self._dict_tail(),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> BandLimitedProcessModel:
        """Inverse of :meth:`to_dict` (derived entries such as ``units`` are ignored)."""
        cls._check_kind(data, "band_limited")
        return cls(
            **cls._head_fields(data),
            spectrum_shape=data.get("spectrum_shape", "flat"),
            falling_ratio=data.get("falling_ratio", 0.5),
            sigma_zeta_rule=data.get("sigma_zeta_rule", "sigma_mu"),
        )

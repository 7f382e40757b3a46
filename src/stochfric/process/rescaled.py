"""A band-limited friction process rescaled in path to another correlation length (issue 19).

The white-noise limit of a path-domain process: ζ_ℓ(x) = √(ℓ0/ℓ) · ζ0(x ℓ0/ℓ) has the correlation
length ℓ and the same low-frequency one-sided PSD level S0 = S(f → 0) as ζ0, its variance
σ_ℓ² = S0/(4ℓ) grows as 1/ℓ, and as ℓ → 0 it tends to white noise of path level S0/2 (per unit
path: Var ∫₀^X ζ dx → X S0/2).  :func:`rescaled_process` builds it from a
:class:`~stochfric.process.band_limited.BandLimitedProcessModel` (the presets' kind): the same
spectrum shape over a band that reaches 1/(2Δx_ℓ), Δx_ℓ ∝ ℓ, generated over a length of at least
``min_length_m`` so that no run's path exceeds it.

The correlation length is the integral scale of the analysis (``friction-process``'s ℓ_corr,
:func:`stochfric.process.spectra.integral_correlation_length`): ℓ = ∫₀^∞ ρ(y) dy = S0/(4σ²), with
S0 the level at the lowest band frequency f_1 = 1/length.  For the band-limited shapes it does
not depend on the pressure: ℓ = length/(4 Σ_k g(f_k)) (flat: length/(4K), falling with ratio r:
length/(2K(1 + r))).

:class:`FftBandLimitedProcessModel` evaluates the spectral representation (eq. 2.48/4.32) by one
real inverse FFT instead of the O(nK) sum: the same phases (``rng.uniform(0, 2π, K)``) and the
same values to rounding (tested), at O(n log n) — a process of 10⁵ points costs milliseconds.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import NDArray

from stochfric.process.band_limited import BandLimitedProcessModel
from stochfric.process.model_function import ModelFunction
from stochfric.random import SeedLike, as_generator

__all__ = [
    "FftBandLimitedProcessModel",
    "band_correlation_length",
    "low_frequency_psd",
    "rescaled_process",
]

#: Most grid points of a rescaled process: a realisation of 10⁶ points is 8 MB, and ``simulate`` holds one
#: per trajectory of a batch (up to 256 with one worker: 2 GB).
MAX_POINTS = 1_000_000


@dataclass(frozen=True, kw_only=True)
class FftBandLimitedProcessModel(BandLimitedProcessModel):
    """A :class:`BandLimitedProcessModel` whose realisations are computed by an inverse FFT.

    Needs a grid that spans exactly one period (``length = n·dx``): then f_k x_j = k j/n and
    μ̂(x_j) = Σ_k a_k cos(2π k j/n + ψ_k) = (n/2)·irfft(c)_j with c_k = a_k e^{iψ_k}.  The phases
    are drawn exactly as :meth:`BandLimitedProcessModel.generate` draws them, so a realisation
    equals the base class's to rounding (~1e-15 relative).
    """

    def __post_init__(self) -> None:
        super().__post_init__()
        if not self.grid_is_periodic:
            raise ValueError(f"an FFT process needs length = n·dx; got length {self.length!r} m, dx {self.dx!r} m")

    def generate(self, p_pa: float, rng: np.random.Generator | SeedLike) -> NDArray[np.float64]:
        """One realisation of μ̂ on :meth:`grid` (eq. 2.48/4.32) by an inverse real FFT."""
        f = self.frequencies()
        s = self.spectrum(f, p_pa)
        phases = as_generator(rng).uniform(0.0, 2.0 * np.pi, size=f.size)
        n = self.n_points
        coeff = np.zeros(n // 2 + 1, dtype=np.complex128)
        coeff[1 : f.size + 1] = np.sqrt(2.0 * s * self.frequency_step) * np.exp(1j * phases)
        out: NDArray[np.float64] = np.fft.irfft(coeff, n) * (n / 2.0)
        return out

    def to_dict(self) -> dict[str, Any]:
        """As the base class (``kind = "band_limited"``), with ``"evaluation": "fft"``."""
        return {**super().to_dict(), "evaluation": "fft"}


def _shape_sum(model: BandLimitedProcessModel) -> float:
    """Σ_k g(f_k) over the band (g = 1 at f_1)."""
    return float(np.sum(model._shape(model.frequencies())))


def band_correlation_length(model: BandLimitedProcessModel) -> float:
    """Integral correlation length ℓ = S(f_1)/(4σ²) = length/(4 Σ_k g(f_k)) [m] of a band-limited model."""
    return model.length / (4.0 * _shape_sum(model))


def low_frequency_psd(model: BandLimitedProcessModel, p_pa: float) -> float:
    """S0 = S(f_1; p) [m]: the one-sided PSD at the lowest band frequency (the f → 0 level)."""
    return float(model.spectrum(model.frequencies()[:1], p_pa)[0])


def _shape_sum_for(k: int, shape: str, ratio: float) -> float:
    """Σ_k g(f_k) of a band of K = k harmonics (flat: K; falling linearly to ``ratio``: K(1 + r)/2)."""
    if shape == "flat" or k == 1:
        return float(k)
    return k * (1.0 + ratio) / 2.0


def rescaled_process(
    model: BandLimitedProcessModel, correlation_length_m: float, min_length_m: float, level_factor: float = 1.0
) -> FftBandLimitedProcessModel:
    """``model`` rescaled in path to the correlation length ℓ with its low-frequency level S0 kept.

    The band has K harmonics of Δf = 1/length and n = 2K + 1 grid points (so f_K < 1/(2Δx));
    K is the least with length = 4ℓ Σ_k g(f_k) ≥ ``min_length_m``, which makes the integral
    correlation length exactly ℓ.  σ_μ(p) is multiplied by √(ℓ0/ℓ) · (correction for the
    discrete band) so that S(f_1; p) equals the model's at every pressure (times ``level_factor``,
    default 1: the level itself kept); E[μ](p), the spectrum shape and the σ_ζ rule are kept.
    Units: lengths in m.
    """
    ell = float(correlation_length_m)
    lmin = float(min_length_m)
    if not (math.isfinite(ell) and ell > 0.0):
        raise ValueError(f"correlation length must be a positive number [m], got {correlation_length_m!r}")
    if not (math.isfinite(lmin) and lmin > 0.0):
        raise ValueError(f"process length must be a positive number [m], got {min_length_m!r}")
    if not (math.isfinite(level_factor) and level_factor > 0.0):
        raise ValueError(f"level factor must be a positive number, got {level_factor!r}")
    shape, ratio = model.spectrum_shape, model.falling_ratio
    per_k = 4.0 * ell * _shape_sum_for(2, shape, ratio) / 2.0  # length per harmonic (exact for flat)
    k = max(1, math.ceil(lmin / per_k))
    while 4.0 * ell * _shape_sum_for(k, shape, ratio) < lmin:
        k += 1
    n = 2 * k + 1
    if n > MAX_POINTS:
        raise ValueError(
            f"a process of correlation length {ell:.3g} m over {lmin:.3g} m needs {n} grid points "
            f"(at most {MAX_POINTS}); choose a larger correlation length or a shorter process"
        )
    length = 4.0 * ell * _shape_sum_for(k, shape, ratio)
    trial = FftBandLimitedProcessModel(
        name=f"{model.name} (l={ell:.3g} m)", mu_mean=model.mu_mean, mu_std=model.mu_std, dx=length / n,
        length=length, spectrum_shape=shape, falling_ratio=ratio, sigma_zeta_rule=model.sigma_zeta_rule,
    )
    # S(f_1) ∝ σ²/(Δf Σg): the factor on σ_μ that keeps S(f_1; p) at every p
    ratio_band = (trial.frequency_step * _shape_sum(trial)) / (model.frequency_step * _shape_sum(model))
    gain = math.sqrt(level_factor * ratio_band)
    mf = model.mu_std
    return dataclasses.replace(trial, mu_std=ModelFunction(a=gain * mf.a, b=mf.b, c=gain * mf.c))

"""Autocorrelation, correlation length and PSD of μ along the path (METHOD §0, §4c).

Thesis eq. (3.17)–(3.20).  Input: μ(y) on windows shifted by a_y, shape (..., W) with the
window index last (K long surfaces × W windows per approach).

* (3.17) μ̄ = (μ − E[μ]) / σ_μ with E[μ], σ_μ over **all** records passed (all surfaces), so
  that the records share one normalisation;
* (3.18) R(k) = (1/(W − k)) Σ_{i<W−k} μ̄_i μ̄_{i+k} (the thesis's 1/n with n the number of pairs
  at lag k), lags k = 0..⌊W/2⌋, averaged over the records;
* correlation length ℓ_corr = first zero crossing of the averaged R, by linear interpolation
  between the last positive and the first non-positive lag (thesis §3.2.4, Fig. 3.19), in m;
  NaN if R stays positive;
* (3.19)/(3.20) μ̂ = μ − mean → one-sided PSD in the convention of METHOD §0
  (:func:`stochfric.process.spectral.one_sided_psd`: S_k = 2 a_y |X_k|²/W, Σ_k S_k Δf = sample
  variance), averaged over the records; frequencies f_k = k/(W a_y) [1/m], S in m.
  Each record's own mean is removed (this only affects the DC bin, which is not returned).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from stochfric.process.spectral import one_sided_psd

__all__ = [
    "autocorrelation",
    "correlation_length",
    "mean_psd",
    "normalise",
    "psd_level",
]

FloatArray = npt.NDArray[np.float64]


def normalise(mu: npt.ArrayLike) -> FloatArray:
    """μ̄ = (μ − E[μ]) / σ_μ (eq. 3.17), E and σ over all elements of ``mu`` (ddof = 0)."""
    m = np.asarray(mu, dtype=np.float64)
    if not np.all(np.isfinite(m)):
        raise ValueError("μ(y) contains NaN or infinity (a window without load?)")
    sd = float(m.std())
    if sd == 0.0:
        return np.zeros_like(m)
    return np.asarray((m - m.mean()) / sd)


def autocorrelation(mu: npt.ArrayLike, max_lag: int | None = None) -> FloatArray:
    """Averaged autocorrelation R(k), k = 0..max_lag (eq. 3.18) of μ̄ = normalise(μ).

    ``mu`` has the path (window) index last; leading axes are records (surfaces) and are
    averaged.  R(0) = 1 when all records are passed together.  ``max_lag`` defaults to ⌊W/2⌋.
    """
    bar = normalise(mu)
    w = bar.shape[-1]
    if w < 2:
        raise ValueError(f"need at least 2 windows along the path, got {w}")
    lag_max = w // 2 if max_lag is None else int(max_lag)
    if not 0 <= lag_max < w:
        raise ValueError(f"max_lag must lie in [0, {w - 1}], got {max_lag}")
    rec = bar.reshape(-1, w)
    out = np.empty(lag_max + 1)
    for k in range(lag_max + 1):
        out[k] = float(np.mean(np.sum(rec[:, : w - k] * rec[:, k:], axis=1) / (w - k)))
    return out


def correlation_length(acf: npt.ArrayLike, spacing_m: float) -> float:
    """First zero crossing of ``acf`` (lags k·spacing), linearly interpolated [m]; NaN if none."""
    r = np.asarray(acf, dtype=np.float64)
    below = np.nonzero(r <= 0.0)[0]
    if below.size == 0 or below[0] == 0:
        return math.nan
    k = int(below[0])
    r0, r1 = float(r[k - 1]), float(r[k])
    frac = r0 / (r0 - r1) if r0 != r1 else 0.0
    return (k - 1 + frac) * float(spacing_m)


def mean_psd(mu: npt.ArrayLike, spacing_m: float) -> tuple[FloatArray, FloatArray, FloatArray]:
    """One-sided PSD of μ̂ along the path averaged over the records (eq. 3.20, METHOD §0).

    Returns ``(f [1/m], mean S [m], standard error of the mean S [m])``; the standard error is
    the scatter between records / √(records) (NaN for a single record).  Convention:
    S_k = 2 a_y |X_k|²/W for 0 < k < W/2 (Nyquist bin of even W with half the weight), so
    Σ_k S_k Δf = the record's sample variance.
    """
    m = np.asarray(mu, dtype=np.float64)
    f, s = one_sided_psd(m.reshape(-1, m.shape[-1]), spacing_m)
    n = s.shape[0]
    se = s.std(axis=0, ddof=1) / math.sqrt(n) if n > 1 else np.full(f.shape, np.nan)
    return f, s.mean(axis=0), se


def psd_level(frequencies: npt.ArrayLike, psd: npt.ArrayLike, spacing_m: float) -> float:
    """Spectrum level E[S] [m]: the mean of S over the bins 0 < f_k < 1/(2 a_y).

    The thesis's constant approximation of a flat spectrum (Fig. 3.20/3.21).  The Nyquist bin
    of an even record (half weight in the convention of METHOD §0) is left out, so a white
    record of variance σ² has E[S] = 2 a_y σ² in expectation for either parity.
    """
    f = np.asarray(frequencies, dtype=np.float64)
    s = np.asarray(psd, dtype=np.float64)
    keep = f * (2.0 * float(spacing_m)) < 1.0 - 1e-9
    if s.ndim != 1 or s.shape != f.shape:
        raise ValueError("psd must be 1-D with one value per frequency")
    if not np.any(keep):
        raise ValueError("no frequency bin below the Nyquist frequency")
    return float(np.mean(s[keep]))

"""Autocorrelation, correlation length and PSD of μ along the path (method §0, §4c, thesis eq. 3.17–3.20).

Input: μ(y) on windows shifted by a_y, shape (..., W) with the window index last (K long surfaces
× W windows per approach).  The normalisation (3.17), the autocorrelation averaged over the records
(3.18), the integral correlation length S(0)/(4σ²) per record and the thesis's first zero crossing,
the one-sided PSD (3.19–3.20) in the convention of method §0 and its level S(f → 0)
(docs/statistical_contact.md §2).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.errors import InputError
from stochfric.friction_process.spectral import one_sided_psd

__all__ = [
    "LOW_FREQUENCY_LIMIT",
    "autocorrelation",
    "correlation_length",
    "correlation_length_interval",
    "integral_correlation_length",
    "mean_psd",
    "normalise",
    "psd_level",
    "window_response",
]


def normalise(mu: npt.ArrayLike) -> FloatArray:
    """μ̄ = (μ − E[μ]) / σ_μ (eq. 3.17), E and σ over all elements of ``mu`` (ddof = 0)."""
    m = np.asarray(mu, dtype=np.float64)
    if not np.all(np.isfinite(m)):
        raise InputError("μ(y) contains NaN or infinity (a window without load?)")
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
        raise InputError(f"need at least 2 windows along the path, got {w}")
    lag_max = w // 2 if max_lag is None else int(max_lag)
    if not 0 <= lag_max < w:
        raise InputError(f"max_lag must lie in [0, {w - 1}], got {max_lag}")
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
    """One-sided PSD of μ̂ along the path averaged over the records (eq. 3.20, method §0).

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


#: Upper end of the band used for the low-frequency level S(f → 0), in units of 1/ℓ (ℓ = window
#: length): there the window's response sinc²(fℓ) is still ≥ 0.81.
LOW_FREQUENCY_LIMIT = 0.25


def window_response(frequencies: npt.ArrayLike, window_length_m: float) -> FloatArray:
    """|H(f)|² = sinc²(fℓ) = (sin(πfℓ)/(πfℓ))² of a moving average over a window of length ℓ."""
    return np.asarray(np.sinc(np.asarray(frequencies, dtype=np.float64) * float(window_length_m)) ** 2)


def psd_level(frequencies: npt.ArrayLike, psd: npt.ArrayLike, window_length_m: float) -> float:
    """Low-frequency level S(f → 0) [m] of μ along the path (the E[S] of eq. 3.21 / Table 3.3).

    μ(y) of windows of length ℓ is a moving average of the surface's local friction over ℓ:
    above 1/ℓ its spectrum is the window's (≈ 1/(πfℓ)²), and a mean over the whole band
    0 < f < 1/(2a_y) would scale with the window shift a_y (E[S] ≈ 2a_y σ_μ²).  The level that
    belongs to the surface is the one at f → 0, where the moving average passes everything:
    the mean of S(f)/sinc²(fℓ) over the bins 0 < f ≤ ``LOW_FREQUENCY_LIMIT``/ℓ (the boxcar
    correction is at most 1/0.81; at least the lowest bin is used).  It does not depend on a_y
    (tests/statistical/test_psd_shift.py).  For white local friction S(0) = 2σ_μ²ℓ.
    """
    f = np.asarray(frequencies, dtype=np.float64)
    s = np.asarray(psd, dtype=np.float64)
    if s.ndim != 1 or s.shape != f.shape:
        raise InputError("psd must be 1-D with one value per frequency")
    ell = float(window_length_m)
    if not (math.isfinite(ell) and ell > 0.0):
        raise InputError(f"window length must be > 0 m, got {window_length_m!r}")
    pos = f > 0.0
    if not np.any(pos):
        raise InputError("no frequency bin above f = 0")
    keep = pos & (f * ell <= LOW_FREQUENCY_LIMIT * (1.0 + 1e-9))
    if not np.any(keep):
        keep = pos & (f == f[pos].min())
    return float(np.mean(s[keep] / window_response(f[keep], ell)))


def integral_correlation_length(record: npt.ArrayLike, spacing_m: float, window_length_m: float) -> float:
    """Integral correlation length ℓ_int = ∫₀^∞ ρ(y) dy = S(0)/(4σ²) of one record μ(y) [m].

    S(0) is the low-frequency level of the record's one-sided PSD (:func:`psd_level`, window
    response divided out; the one-sided S(0) is 4σ²∫₀^∞ρ dy), σ² its sample variance.  It is an
    average over the whole ACF, so it varies smoothly between realisations, unlike the first zero
    crossing (:func:`correlation_length`); for a moving average over L points of spacing a it is
    aL/2.  NaN for a constant record.
    """
    r = np.asarray(record, dtype=np.float64)
    var = float(r.var(ddof=1)) if r.size > 1 else 0.0
    if not var > 0.0:
        return math.nan
    f, s = one_sided_psd(r, spacing_m)
    return psd_level(f, s, window_length_m) / (4.0 * var)


def correlation_length_interval(per_record: npt.ArrayLike, level: float = 0.95) -> tuple[float, float, float, float]:
    """Mean, standard error and two-sided ``level`` interval [lo, hi] of the correlation length from
    independent records (the K long surfaces of the analysis) [m].

    SE = sd/√K over the finite values; the interval is the Student-t interval mean ± t_{K−1} SE
    (the per-surface values are averages over the whole ACF and close to normal; tested for
    coverage on records of known ℓ, tests/statistical/test_correlation_length_interval.py).
    NaN where fewer than two values are finite (the mean alone where one is).
    """
    from scipy import stats

    v = np.asarray(per_record, dtype=np.float64).ravel()
    v = v[np.isfinite(v)]
    if not 0.0 < level < 1.0:
        raise InputError(f"level must lie in (0, 1), got {level!r}")
    if v.size == 0:
        return math.nan, math.nan, math.nan, math.nan
    mean = float(v.mean())
    if v.size < 2:
        return mean, math.nan, math.nan, math.nan
    se = float(v.std(ddof=1) / math.sqrt(v.size))
    half = float(stats.t.ppf(0.5 + level / 2.0, v.size - 1)) * se
    return mean, se, mean - half, mean + half

"""One-sided PSD estimate and the spectral representation of a path-dependent process (method §0, eq. 2.48).

A real, zero-mean process μ̂(x) along the path x [m] has a one-sided PSD S(f) [m] with
σ² = ∫₀^∞ S(f) df; :func:`one_sided_psd` estimates it so that Σ_k S_k Δf is the sample variance, and
the spectral representation μ̂(x) = √2 Σ_i √(S(f_i) Δf) cos(2π f_i x + ψ_i) (thesis 2.48; (4.32) as
printed misplaces Δf and the phase) generates realisations with variance Σ_i S(f_i) Δf
(docs/friction_process.md §1–§2).  Pure functions: randomness only through ``rng``.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.errors import InputError
from stochfric.random import SeedLike, as_generator

__all__ = [
    "band_limited_frequencies",
    "generate_process",
    "generate_process_batch",
    "nyquist_frequency",
    "one_sided_psd",
    "spectral_representation",
]

#: Relative tolerance with which a frequency counts as "at the Nyquist frequency".
#: A harmonic that lies on the Nyquist frequency up to round-off (e.g. 499.99999999 for
#: a Nyquist of 500) would break the exact-variance property, so it is refused too.
_NYQUIST_RTOL = 1e-9

#: Largest number of matrix elements (points × frequencies) formed at once by
#: :func:`spectral_representation`; bounds the memory to ~ 2 × 8 × this many bytes.
_BLOCK_ELEMENTS = 2**21


def _positive_finite(name: str, value: float) -> float:
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise InputError(f"{name} must be a positive finite number, got {value!r}")
    return v


def nyquist_frequency(dx: float) -> float:
    """Nyquist path frequency 1/(2 Δx) [1/m] of a grid with spacing ``dx`` [m]."""
    return 0.5 / _positive_finite("dx", dx)


def _at_or_above_nyquist(frequencies: NDArray[np.float64], dx: float) -> NDArray[np.bool_]:
    """Mask of frequencies f with f ≥ 1/(2Δx) (up to a relative round-off tolerance)."""
    return frequencies * (2.0 * dx) >= 1.0 - _NYQUIST_RTOL


def one_sided_psd(values: ArrayLike, dx: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """One-sided periodogram of a sampled path-dependent process (method §0, eq. 3.20).

    Parameters
    ----------
    values:
        Samples μ_j at x_j = j Δx, j = 0..N−1, along the **last** axis (leading axes are
        independent records, e.g. an ensemble).  N ≥ 2.  The mean of each record is
        removed first (μ̂ = μ − mean, eq. 3.19), so the DC bin is not returned.
    dx:
        Sample spacing Δx [m].

    Returns
    -------
    frequencies:
        f_k = k / (N Δx) [1/m] for k = 1..⌊N/2⌋, shape (⌊N/2⌋,); Δf = 1/(N Δx).
    psd:
        One-sided PSD S_k [m] (variance per 1/m), shape ``values.shape[:-1] + (⌊N/2⌋,)``:
        S_k = 2 Δx |X_k|² / N for 0 < k < N/2 with X_k = Σ_j μ̂_j exp(−2πi jk/N).
        For **even** N the Nyquist bin k = N/2 (which has no mirror image) is included
        with half that weight, S_{N/2} = Δx |X_{N/2}|² / N.

    Notes
    -----
    Parseval holds exactly (up to round-off) for both parities:
    Σ_k S_k Δf = (1/N) Σ_j μ̂_j², the sample variance with the 1/N normalisation
    (``numpy.var`` with ``ddof=0``).  For odd N this needs no special term; for even N it
    needs the Nyquist bin with the weight above.
    """
    dx = _positive_finite("dx", dx)
    arr = np.asarray(values, dtype=np.float64)
    if arr.ndim == 0:
        raise InputError("values must have at least one axis (samples along the last axis)")
    n = arr.shape[-1]
    if n < 2:
        raise InputError(f"need at least 2 samples along the last axis, got {n}")
    if not np.all(np.isfinite(arr)):
        raise InputError("values contain NaN or infinity; fill or remove them first")
    centred = arr - arr.mean(axis=-1, keepdims=True)
    spectrum = np.fft.rfft(centred, axis=-1)[..., 1:]  # k = 1..floor(N/2)
    psd = (2.0 * dx / n) * (spectrum.real**2 + spectrum.imag**2)
    if n % 2 == 0:
        psd[..., -1] *= 0.5  # Nyquist bin k = N/2: weight Δx|X|²/N
    k = np.arange(1, n // 2 + 1, dtype=np.float64)
    return k / (n * dx), psd


def _check_spectrum(
    frequencies: ArrayLike, psd: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    f = np.asarray(frequencies, dtype=np.float64)
    s = np.asarray(psd, dtype=np.float64)
    if f.ndim != 1 or f.size == 0:
        raise InputError(f"frequencies must be a non-empty 1-D array, got shape {f.shape}")
    if s.shape != f.shape:
        raise InputError(f"psd has shape {s.shape}, frequencies {f.shape}: they must match")
    if not (np.all(np.isfinite(f)) and np.all(f > 0.0)):
        raise InputError("frequencies must be finite and > 0 [1/m]")
    if not (np.all(np.isfinite(s)) and np.all(s >= 0.0)):
        raise InputError("psd must be finite and >= 0 [m]")
    return f, s


def _frequency_step(f: NDArray[np.float64]) -> float:
    """Δf of a uniform frequency grid; a single frequency is taken as f_1 = Δf."""
    if f.size == 1:
        return float(f[0])
    steps = np.diff(f)
    df = float(steps.mean())
    if df <= 0.0 or not np.allclose(steps, df, rtol=1e-9, atol=0.0):
        raise InputError(
            "frequencies must form a uniform, increasing grid f_i = f_1 + (i−1)Δf "
            "(eq. 2.48 with constant Δf); pass df explicitly for other grids"
        )
    return df


def spectral_representation(
    frequencies: ArrayLike,
    psd: ArrayLike,
    x: ArrayLike,
    phases: ArrayLike,
    *,
    df: float | None = None,
) -> NDArray[np.float64]:
    """Evaluate the spectral representation μ̂(x) (thesis eq. 2.48 / 4.32, method §0).

    μ̂(x) = √2 Σ_i √(S(f_i) Δf) cos(2π f_i x + ψ_i).

    Parameters
    ----------
    frequencies:
        Path frequencies f_i [1/m], 1-D, > 0, uniformly spaced.
    psd:
        One-sided PSD S(f_i) [m] at those frequencies (method §0), same shape.
    x:
        Positions [m], any shape.
    phases:
        Phases ψ_i [rad], same shape as ``frequencies`` (uniform in [0, 2π) for a
        random realisation).
    df:
        Frequency step Δf [1/m].  By default the (checked) uniform step of
        ``frequencies``; a single frequency is taken as the first harmonic, Δf = f_1.

    Returns
    -------
    μ̂ at ``x``, same shape as ``x``.  Its variance over the phases is Σ_i S(f_i) Δf.

    Notes
    -----
    Evaluated as cos(2π x fᵀ) @ (a cos ψ) − sin(2π x fᵀ) @ (a sin ψ) with a = √(2 S Δf),
    in blocks of positions so that at most ~2²¹ matrix elements exist at a time
    (:func:`_evaluate`).
    """
    f, s = _check_spectrum(frequencies, psd)
    psi = np.asarray(phases, dtype=np.float64)
    if psi.shape != f.shape:
        raise InputError(f"phases have shape {psi.shape}, frequencies {f.shape}: they must match")
    if not np.all(np.isfinite(psi)):
        raise InputError("phases must be finite")
    step = _frequency_step(f) if df is None else _positive_finite("df", df)
    xs = np.asarray(x, dtype=np.float64)
    if not np.all(np.isfinite(xs)):
        raise InputError("x must be finite")
    return _evaluate(f, s, step, xs.ravel(), psi[np.newaxis, :])[0].reshape(xs.shape)


def _evaluate(
    f: NDArray[np.float64], s: NDArray[np.float64], step: float, flat: NDArray[np.float64],
    phases: NDArray[np.float64],
) -> NDArray[np.float64]:
    """μ̂ at the positions ``flat`` for every row of ``phases`` (shape (b, K)); shape (b, n).

    cos(2π x fᵀ) @ (a cos ψ) − sin(2π x fᵀ) @ (a sin ψ), a = √(2 S Δf), in blocks of positions
    of at most ~2²¹ matrix elements.  The matrices are formed once per block for all rows, and
    each row is one matrix–vector product (``np.matmul`` over a stack of vectors calls the same
    BLAS ``gemv`` as a single ``@``), so row ``r`` is bit for bit the result for its phases
    alone.
    """
    amplitude = np.sqrt(2.0 * s * step)
    a_cos = amplitude * np.cos(phases)
    a_sin = amplitude * np.sin(phases)
    omega = 2.0 * np.pi * f
    out = np.empty((phases.shape[0], flat.size), dtype=np.float64)
    block = max(1, _BLOCK_ELEMENTS // f.size)
    for start in range(0, flat.size, block):
        arg = np.multiply.outer(flat[start : start + block], omega)
        out[:, start : start + block] = (np.matmul(np.cos(arg), a_cos[:, :, np.newaxis])[:, :, 0]
                                         - np.matmul(np.sin(arg), a_sin[:, :, np.newaxis])[:, :, 0])
    return out


def generate_process(
    frequencies: ArrayLike,
    psd: ArrayLike,
    dx: float,
    length: float,
    rng: np.random.Generator | SeedLike,
) -> NDArray[np.float64]:
    """One random realisation of μ̂ on the grid x_j = j Δx (eq. 2.48, method §4e).

    Parameters
    ----------
    frequencies, psd:
        Path frequencies f_i [1/m] (uniform grid, all strictly below the Nyquist
        frequency 1/(2Δx)) and the one-sided PSD S(f_i) [m] (method §0).
    dx:
        Grid spacing Δx [m].
    length:
        Process length ℓ [m]; the grid has n = round(ℓ/Δx) points, j = 0..n−1.
    rng:
        A :class:`numpy.random.Generator` (or a seed, normalised by
        :func:`stochfric.random.as_generator`).  Exactly ``len(frequencies)`` phases
        ψ_i ~ U[0, 2π) are drawn from it, in frequency order.

    Returns
    -------
    μ̂_j, shape (n,), zero-mean in the ensemble.

    Raises
    ------
    ValueError
        If a frequency is at or above the Nyquist frequency 1/(2Δx) (it would alias and
        the grid variance would no longer equal Σ S Δf), or if n < 1.

    Notes
    -----
    If the frequencies are the harmonics k/ℓ (k = 1..K, see
    :func:`band_limited_frequencies`) and ℓ/Δx is an integer, the realisation is exactly
    periodic with period ℓ = nΔx, its grid mean is 0 and its grid variance
    (1/n) Σ_j μ̂_j² equals Σ_i S(f_i) Δf up to round-off, for every realisation.  If ℓ/Δx
    is not an integer the values are still the exact spectral representation at x_j,
    but the n grid points do not cover exactly one period.
    """
    f, s, x = _process_grid(frequencies, psd, dx, length)
    generator = as_generator(rng)
    phases = generator.uniform(0.0, 2.0 * np.pi, size=f.size)
    return spectral_representation(f, s, x, phases)


def generate_process_batch(
    frequencies: ArrayLike,
    psd: ArrayLike,
    dx: float,
    length: float,
    phases: ArrayLike,
) -> NDArray[np.float64]:
    """Realisations of μ̂ on the grid x_j = j Δx for given phases, one per row (eq. 2.48).

    Row ``r`` equals, bit for bit, ``generate_process(frequencies, psd, dx, length, rng)`` for
    a generator ``rng`` whose ``uniform(0, 2π, K)`` returns ``phases[r]``: the same spectral
    representation, evaluated for the whole batch with one set of cos/sin matrices (an
    ensemble's trajectories share the grid and the frequencies), so it costs one matrix–vector
    product per realisation instead of a Python call chain per realisation.

    Parameters
    ----------
    frequencies, psd, dx, length:
        As for :func:`generate_process` (f_i [1/m] below the Nyquist frequency, S [m], Δx [m],
        ℓ [m]).
    phases:
        ψ [rad], shape (b, K) with K = len(frequencies).

    Returns
    -------
    μ̂, shape (b, n), n = round(ℓ/Δx).
    """
    f, s, x = _process_grid(frequencies, psd, dx, length)
    psi = np.asarray(phases, dtype=np.float64)
    if psi.ndim != 2 or psi.shape[1] != f.size:
        raise InputError(f"phases must have shape (b, {f.size}), got {psi.shape}")
    if not np.all(np.isfinite(psi)):
        raise InputError("phases must be finite")
    return _evaluate(f, s, _frequency_step(f), x, psi)


def _process_grid(
    frequencies: ArrayLike, psd: ArrayLike, dx: float, length: float
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Checked (f, S) and the grid x_j = j Δx of :func:`generate_process`."""
    dx = _positive_finite("dx", dx)
    length = _positive_finite("length", length)
    f, s = _check_spectrum(frequencies, psd)
    bad = _at_or_above_nyquist(f, dx)
    if np.any(bad):
        raise InputError(
            f"{int(bad.sum())} frequenc{'y is' if bad.sum() == 1 else 'ies are'} at or above "
            f"the Nyquist frequency 1/(2·dx) = {nyquist_frequency(dx):.6g} 1/m "
            f"(largest: {float(f.max()):.6g} 1/m); they would alias on the grid of "
            "spacing dx. Drop them (see band_limited_frequencies) or use a smaller dx."
        )
    n = round(length / dx)
    if n < 1:
        raise InputError(f"length {length!r} m is shorter than half a grid step dx {dx!r} m")
    return f, s, np.arange(n, dtype=np.float64) * dx


def band_limited_frequencies(dx: float, length: float) -> NDArray[np.float64]:
    """Harmonics f_k = k/ℓ [1/m], k = 1..K, with K the largest integer with f_K < 1/(2Δx).

    The band of a process of length ℓ = ``length`` [m] resolved at Δx = ``dx`` [m]:
    the longest wavelength is ℓ (Δf = 1/ℓ), the shortest is above 2Δx (strictly below
    the Nyquist frequency, up to a relative round-off tolerance of 1e-9, the same test
    :func:`generate_process` applies).  Raises ValueError if the band is empty (ℓ ≤ 2Δx).
    """
    dx = _positive_finite("dx", dx)
    length = _positive_finite("length", length)
    k_max = math.floor(length / (2.0 * dx)) + 1
    f = np.arange(1, k_max + 1, dtype=np.float64) / length
    f = f[~_at_or_above_nyquist(f, dx)]
    if f.size == 0:
        raise InputError(
            f"no harmonic k/length lies below the Nyquist frequency: length {length!r} m "
            f"must exceed 2·dx = {2 * dx!r} m"
        )
    return f

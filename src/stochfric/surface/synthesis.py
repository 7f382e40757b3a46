"""Stochastically similar surfaces from the amplitude spectrum (method §3, thesis 3.1.2, eq. 3.2–3.6).

Generators, pure functions of a height map and ``rng`` (a :class:`numpy.random.Generator` or a
seed): :func:`random_phase_surface`, the thesis's random-phase surrogate (3.4–3.5, the amplitude
matrix kept, hence the variance and the anisotropy); :func:`longer_surface`, the thesis's longer
surfaces (3.6, variance kept exactly); :func:`iaaft_surface`, beyond the thesis, the height
distribution kept exactly and the spectrum approximately (docs/statistical_contact.md §1).  The
surrogate methods by name (these two, quilting and any other) are the registry of
:mod:`stochfric.surface.surrogates`, one floor module above this one and :mod:`.quilting`.
"""

from __future__ import annotations

from dataclasses import dataclass
from enum import StrEnum

import numpy as np
import numpy.typing as npt
from scipy.signal import windows as sig_windows

from stochfric.arrays import FloatArray
from stochfric.random import SeedLike, as_generator
from stochfric.surface.io import Surface, SurfaceError

__all__ = [
    "AMPLITUDE_METHODS",
    "DEFAULT_AMPLITUDE",
    "IAAFT_METHOD",
    "PHASE_METHOD",
    "TUKEY_ALPHA",
    "AmplitudeEstimate",
    "IaaftResult",
    "amplitude_error",
    "amplitude_spectrum",
    "checked_heights",
    "gaussian_field_heights",
    "iaaft_heights",
    "iaaft_longer_heights",
    "iaaft_surface",
    "interpolate_amplitudes",
    "longer_surface",
    "phase_longer_heights",
    "random_phase_heights",
    "random_phase_surface",
    "surrogate_surface",
    "windowed_periodogram",
]


class AmplitudeEstimate(StrEnum):
    """Amplitude estimates of a measured map (:func:`amplitude_spectrum`): ``tukey`` (default) and
    ``hann`` remove the edge jump, ``raw`` is the thesis's DFT of the map as it is."""

    TUKEY = "tukey"
    HANN = "hann"
    RAW = "raw"


AMPLITUDE_METHODS: tuple[str, ...] = tuple(AmplitudeEstimate)
#: The registry names of the two generators of this module (:mod:`stochfric.surface.surrogates`).
PHASE_METHOD = "phase"
IAAFT_METHOD = "iaaft"
DEFAULT_AMPLITUDE = AmplitudeEstimate.TUKEY
#: Fraction of each axis inside the cosine tapers of the ``"tukey"`` estimate (half at each edge).
TUKEY_ALPHA = 0.2

ComplexArray = npt.NDArray[np.complex128]


def checked_heights(z: npt.ArrayLike, what: str = "a surrogate") -> FloatArray:
    """``z`` as a finite 2-D float64 map of at least 2×2 points (SurfaceError naming ``what`` otherwise)."""
    h = np.asarray(z, dtype=np.float64)
    if h.ndim != 2 or min(h.shape) < 2:
        raise SurfaceError(f"{what} needs a 2-D height map of at least 2×2 points, got shape {h.shape}")
    if not np.all(np.isfinite(h)):
        raise SurfaceError("heights contain NaN or infinity; fill undefined points first")
    return h


def _check_factor(factor: int) -> int:
    if isinstance(factor, bool) or not isinstance(factor, int | np.integer) or factor < 1:
        raise SurfaceError(f"the length factor must be an integer >= 1, got {factor!r}")
    return int(factor)


def amplitude_spectrum(heights: npt.ArrayLike, method: str = AmplitudeEstimate.RAW) -> FloatArray:
    """Normalised amplitude matrix ``|Z(m, n)| = |DFT2(z)| / √(MN)`` (eq. 3.2–3.3), full M × N.

    ``method="raw"`` is the thesis's estimate, the DFT of the map as it is.  A measured map is
    not periodic: its DFT also carries the jump between opposite edges, a ridge of spurious
    power ∝ 1/k² along both wavenumber axes, and surrogates built from it have far more and
    sharper summits than the map itself.  ``"tukey"`` (the default of every generator) and
    ``"hann"`` remove it: the mean-free map is multiplied by a separable periodic window before
    the DFT — a Tukey window that tapers the outer ``TUKEY_ALPHA``/2 = 10 % at each edge with a
    half cosine, or a full Hann window — and the amplitudes are rescaled so that
    Σ_{(m,n)≠0}|Z|²/(MN) equals the map's height variance exactly (the variance is restored).
    The Hann window weights the centre of the map and, on the shipped surface, gives surrogates
    13 % smoother (RMS slope) than the map; the Tukey window keeps 80 % of each axis at full
    weight and reproduces the map's RMS slope, summit count and mean summit radius within the
    ensemble's spread (docs/statistical_contact.md, "Surrogates of a non-periodic map").  The DC
    element is |mean|·√(MN) for every method.
    """
    z = checked_heights(heights)
    return np.asarray(_full_amplitudes(z, method) / np.sqrt(z.size))


def _full_amplitudes(z: FloatArray, method: str) -> FloatArray:
    """Unnormalised full-plane amplitudes |DFT2| (DC = |Σz|) of the estimate ``method``."""
    if method == AmplitudeEstimate.RAW:
        return np.asarray(np.abs(np.fft.fft2(z)))
    if method not in AMPLITUDE_METHODS:
        raise SurfaceError(f"unknown amplitude estimate {method!r}; use one of {', '.join(AMPLITUDE_METHODS)}")
    mean = float(z.mean())
    z0 = z - mean
    amp = np.abs(np.fft.fft2(z0 * _taper(z.shape, method)))
    amp[0, 0] = 0.0
    power = float(np.sum(amp**2))
    target = float(np.sum(z0**2)) * z.size  # Parseval: Σ|X|² = MN Σ z0²
    if power > 0.0:
        amp *= np.sqrt(target / power)
    amp[0, 0] = abs(mean) * z.size
    return np.asarray(amp)


def _taper(shape: tuple[int, ...], method: str) -> FloatArray:
    """The separable periodic taper of ``method``: Tukey with :data:`TUKEY_ALPHA`, or Hann (Tukey with α = 1)."""
    alpha = 1.0 if method == AmplitudeEstimate.HANN else TUKEY_ALPHA
    wx, wy = (sig_windows.tukey(n, alpha, sym=False) for n in shape)
    return np.asarray(wx[:, None] * wy[None, :])


def _half_amplitudes(z: FloatArray, method: str) -> FloatArray:
    """rfft2-layout (M × (N//2 + 1)) unnormalised amplitudes of the estimate ``method``."""
    if method == AmplitudeEstimate.RAW:
        return np.asarray(np.abs(np.fft.rfft2(z)))
    return np.asarray(_full_amplitudes(z, method)[:, : z.shape[1] // 2 + 1])


def _white_phases(shape: tuple[int, int], rng: np.random.Generator) -> ComplexArray:
    """``exp(iφ)`` in the rfft2 layout, φ the phases of the rfft2 of a white Gaussian field.

    Uniform on [−π, π) and independent for each conjugate pair, Hermitian where the rfft2
    layout needs it (columns 0 and N/2), exactly ±1 at the self-conjugate frequencies.
    """
    w = np.fft.rfft2(rng.standard_normal(shape))
    mag = np.abs(w)
    mag[mag == 0.0] = 1.0  # probability zero; keeps the division finite
    return np.asarray(w / mag)


def _phase_from_half_amplitudes(
    half_amp: FloatArray, shape: tuple[int, int], mean: float, rng: np.random.Generator
) -> FloatArray:
    """Inverse rfft2 of ``half_amp · exp(iφ)`` with the DC coefficient set to ``mean · size``."""
    coef = half_amp * _white_phases(shape, rng)
    coef[0, 0] = mean * shape[0] * shape[1]
    return np.asarray(np.fft.irfft2(coef, s=shape))


def random_phase_heights(
    heights: npt.ArrayLike, rng: np.random.Generator | SeedLike = None, *, amplitude: str = DEFAULT_AMPLITUDE
) -> FloatArray:
    """Random-phase surrogate of a height map (eq. 3.4–3.5, method §3).

    Returns a real map of the same shape whose amplitude spectrum ``|DFT2|`` equals the
    estimate ``amplitude`` of the original (:func:`amplitude_spectrum`) coefficient by
    coefficient (to round-off), hence the same mean and variance.  With ``amplitude="raw"``
    that is the original's own DFT amplitude (thesis).
    """
    z = checked_heights(heights)
    gen = as_generator(rng)
    half = _half_amplitudes(z, amplitude)
    return _phase_from_half_amplitudes(half, z.shape, float(z.mean()), gen)


def gaussian_field_heights(
    heights: npt.ArrayLike, rng: np.random.Generator | SeedLike = None, *, amplitude: str = DEFAULT_AMPLITUDE,
) -> FloatArray:
    """A new sample of the Gaussian random field whose spectrum is estimated from ``heights`` [m].

    The random-phase surrogate (:func:`random_phase_heights`, thesis 3.4–3.5) keeps the map's amplitude
    |Z| exactly: it is the Gaussian model *conditioned on the map's periodogram*, right for statistics of
    the map itself, but every surrogate then has the map's own realised low-wavenumber power.  An
    independent sample of the same surface (a held-out half, another scan) has its own: its |Z|² scatter
    about the spectrum S as a χ²₂/2 (exponential) variable per bin.  This generator draws that sample from
    the plug-in spectrum Ŝ = P, the tapered periodogram of the map (:func:`windowed_periodogram`, Welch's
    normalisation): coefficients √P · W/√(MN), W the DFT of white Gaussian noise (complex Gaussian: Rayleigh
    amplitudes, uniform phases, Hermitian), so E|DFT2(h)|² = P.

    Why the periodogram itself, unsmoothed: P = S·E₁ scatters about S as a new sample's does (E₁ exponential),
    and a draw's power P·E₂ then scatters about a map's expectation with E[P²E₂²] − S² = 3S² against the
    2S² of (new sample − estimate) = S(E₃ − E₁): on average over maps the draws' spread of a sum over many bins
    matches the prediction error, the estimate's own error included.  Measured on exact Gaussian maps (docs
    §0a, ``benchmarks/holdout_calibration.py``): smoothing P by a 3 × 3 box and re-drawing the estimate
    (the design until 2026-11-28) biased the summit count of the draws by −5 % at 128-point halves (a box
    average changes the shape of a steep spectrum) and set the window-mean summit radius 0.6 sd off.

    Why Welch's normalisation (P = |DFT((h − h̄)·w)|² / mean(w²)), not :func:`amplitude_spectrum`'s: that one
    rescales the tapered spectrum so that its total equals the map's variance.  The taper weights the
    centre, so that factor depends on where the map's long waves happen to lie and multiplies the *whole*
    spectrum — its curvature too: the window mean of the summit radius then scattered 1.7–1.9 times wider
    from map to map than the draws predicted (Hann: 6.4 times).  The mean is the map's mean.
    """
    z = checked_heights(heights)
    gen = as_generator(rng)
    power = windowed_periodogram(z, amplitude)
    white = np.fft.fft2(gen.standard_normal(z.shape)) / np.sqrt(z.size)
    return np.asarray(np.fft.ifft2(np.sqrt(power) * white).real + float(z.mean()))


def windowed_periodogram(heights: npt.ArrayLike, method: str = DEFAULT_AMPLITUDE) -> FloatArray:
    """The periodogram |DFT2((h − h̄)·w)|² / mean(w²), full M × N, DC bin 0 [m² · MN]: Welch's normalisation of
    the taper ``w`` of ``method`` (``"tukey"``, ``"hann"``; ``"raw"``: w = 1), unbiased for a stationary field's
    spectrum away from the lowest bins and free of the map's own weighting by the taper
    (:func:`gaussian_field_heights`)."""
    z = checked_heights(heights)
    if method not in AMPLITUDE_METHODS:
        raise SurfaceError(f"unknown amplitude estimate {method!r}; use one of {', '.join(AMPLITUDE_METHODS)}")
    z0 = z - float(z.mean())
    w = np.ones_like(z0) if method == AmplitudeEstimate.RAW else _taper(z.shape, method)
    power = np.abs(np.fft.fft2(z0 * w)) ** 2 / float(np.mean(w**2))
    power[0, 0] = 0.0
    return np.asarray(power)


def interpolate_amplitudes(amplitude: npt.ArrayLike, factor: int) -> FloatArray:
    """Amplitude matrix on a ``factor``-times finer frequency grid in y (axis 1), eq. (3.6).

    ``amplitude`` is the full M × N matrix ``|Z|`` (DC at [0, 0]); the result is M × (factor·N).
    New column ``l`` sits at the original (fractional) index ``l/factor``; the value is the
    linear interpolation between the neighbouring columns, periodic in the index (the DFT is
    periodic), so ``A(−m, −l) = A(m, l)`` is kept.  The DC element [0, 0] is treated as 0 (the
    mean is handled separately).  No rescaling here: see :func:`longer_surface`.
    """
    a = np.array(amplitude, dtype=np.float64)
    factor = _check_factor(factor)
    if a.ndim != 2:
        raise SurfaceError("the amplitude matrix must be 2-D")
    a[0, 0] = 0.0
    n = a.shape[1]
    pos = np.arange(factor * n, dtype=np.float64) / factor
    lo = np.floor(pos).astype(np.intp)
    t = pos - lo
    hi = (lo + 1) % n
    return np.asarray(a[:, lo] * (1.0 - t) + a[:, hi % n] * t)


def _longer_half_amplitudes(z: FloatArray, factor: int, amplitude: str = DEFAULT_AMPLITUDE) -> FloatArray:
    """rfft2-layout amplitudes (unnormalised, for irfft2) of the longer surface, variance exact."""
    m, n = z.shape
    big_n = factor * n
    amp = amplitude_spectrum(z, amplitude)
    a1 = interpolate_amplitudes(amp, factor) * np.sqrt(m * big_n)  # (3.6): Z1* = √(ML)|Z1|
    half = a1[:, : big_n // 2 + 1].copy()
    half[0, 0] = 0.0
    # variance of irfft2(half·e^{iφ}) for the full point-symmetric matrix a1 (DC excluded)
    target_var = float(z.var())
    current_var = float(np.sum(a1**2)) / (m * big_n) ** 2
    if current_var > 0.0:
        half *= np.sqrt(target_var / current_var)
    return half


def phase_longer_heights(
    heights: npt.ArrayLike, factor: int, rng: np.random.Generator | SeedLike = None, *,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> FloatArray:
    """Heights of a random-phase surface ``factor`` times longer in y (eq. 3.4–3.6): for ``factor = 1``
    :func:`random_phase_heights`, else the interpolated amplitude matrix with the variance kept exactly."""
    factor = _check_factor(factor)
    z = checked_heights(heights)
    gen = as_generator(rng)
    if factor == 1:
        return random_phase_heights(z, gen, amplitude=amplitude)
    shape = (z.shape[0], factor * z.shape[1])
    half = _longer_half_amplitudes(z, factor, amplitude)
    return _phase_from_half_amplitudes(half, shape, float(z.mean()), gen)


def iaaft_longer_heights(
    heights: npt.ArrayLike, factor: int, rng: np.random.Generator | SeedLike = None, *, max_iter: int = 100,
    tol: float = 1e-4, amplitude: str = DEFAULT_AMPLITUDE,
) -> FloatArray:
    """Heights of an IAAFT surface ``factor`` times longer in y (:func:`iaaft_heights`)."""
    return iaaft_heights(heights, rng, factor=_check_factor(factor), max_iter=max_iter, tol=tol,
                         amplitude=amplitude).heights


def surrogate_surface(surface: Surface, heights: FloatArray, method: str, factor: int,
                      amplitude: str = DEFAULT_AMPLITUDE) -> Surface:
    """``heights`` — a surrogate of ``surface`` made by ``method``, ``factor`` times its length in y —
    as a :class:`Surface` of the same spacing (Δx, Δy) and size (ℓx, factor·ℓy)."""
    lx, ly = surface.physical_size_m
    return Surface(
        heights_m=heights,
        physical_size_m=(lx, factor * ly),
        source=f"{method} surrogate (length factor {factor}) of {surface.source}",
        n_undefined_filled=0,
        info={"surrogate": str(method), "length_factor": factor, "amplitude": str(amplitude),
              "original": surface.source},
    )


def longer_surface(
    surface: Surface,
    factor: int,
    rng: np.random.Generator | SeedLike = None,
    *,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> Surface:
    """A random-phase surface ``factor`` times longer in y, stochastically similar to ``surface``
    (eq. 3.6, the thesis's longer surfaces): the interpolated amplitude matrix of the estimate
    ``amplitude`` (:func:`amplitude_spectrum`) with random phases.  The spacing stays (Δx, Δy); the
    size becomes (ℓx, factor·ℓy).  Mean and variance equal the original's.  Other methods:
    :func:`stochfric.surface.surrogates.similar_surface`.
    """
    factor = _check_factor(factor)
    h = phase_longer_heights(surface.heights_m, factor, rng, amplitude=amplitude)
    return surrogate_surface(surface, h, PHASE_METHOD, factor, amplitude)


@dataclass(frozen=True, kw_only=True, eq=False)
class IaaftResult:
    """Result of :func:`iaaft_heights`: the map, its amplitude error ε, the iterations used."""

    heights: FloatArray
    amplitude_error: float
    iterations: int


def amplitude_error(heights: npt.ArrayLike, target_half_amplitude: npt.ArrayLike) -> float:
    """``ε = ‖|rfft2(z)| − A‖₂ / ‖A‖₂`` over the non-DC coefficients (rfft2 layout, unnormalised).

    The rfft2 half-plane counts every conjugate pair once (columns 0 and N/2 twice); the
    measure is only used relative to its own scale, so that weighting does not matter.
    """
    a = np.asarray(target_half_amplitude, dtype=np.float64)
    s = np.abs(np.fft.rfft2(np.asarray(heights, dtype=np.float64)))
    diff = s - a
    diff[0, 0] = 0.0
    ref = a.copy()
    ref[0, 0] = 0.0
    norm = float(np.linalg.norm(ref))
    return float(np.linalg.norm(diff)) / norm if norm > 0.0 else 0.0


def iaaft_heights(
    heights: npt.ArrayLike,
    rng: np.random.Generator | SeedLike = None,
    *,
    factor: int = 1,
    max_iter: int = 100,
    tol: float = 1e-4,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> IaaftResult:
    """IAAFT surrogate: measured height distribution exactly, amplitude spectrum approximately.

    Schreiber & Schmitz (1996), Phys. Rev. Lett. 77, 635.  Start: a random-phase surrogate
    (of the interpolated amplitude matrix for ``factor > 1``); iterate (1) impose the target
    amplitudes keeping the current phases, (2) replace the heights by the target heights in
    the rank order of (1).  The result is the output of step (2), so its sorted heights are
    the target heights exactly.  Stops when ε (:func:`amplitude_error`) changes by less than
    ``tol`` relative to ε, or after ``max_iter`` iterations.  The target amplitudes are the
    estimate ``amplitude`` of the map (:func:`amplitude_spectrum`).
    """
    z = checked_heights(heights)
    factor = _check_factor(factor)
    if max_iter < 1:
        raise SurfaceError(f"max_iter must be >= 1, got {max_iter}")
    gen = as_generator(rng)
    shape = (z.shape[0], factor * z.shape[1])
    mean = float(z.mean())
    if factor == 1:
        target = _half_amplitudes(z, amplitude)
    else:
        target = _longer_half_amplitudes(z, factor, amplitude)
        target[0, 0] = abs(mean) * shape[0] * shape[1]
    sorted_values = np.sort(np.repeat(z.ravel(), factor))
    ref = target.copy()
    ref[0, 0] = 0.0
    ref_norm = max(float(np.linalg.norm(ref)), np.finfo(float).tiny)
    current = _phase_from_half_amplitudes(target, shape, mean, gen)
    ranked = np.empty(sorted_values.size, dtype=np.float64)
    previous = np.inf
    iterations = 0
    for iterations in range(1, max_iter + 1):  # noqa: B007 - the count is returned
        # (2) rank-order remap onto the measured heights: the distribution is exact
        ranked[np.argsort(current, axis=None, kind="stable")] = sorted_values
        remapped = ranked.reshape(shape)
        spec = np.fft.rfft2(remapped)
        mag = np.abs(spec)
        diff = mag - target
        diff[0, 0] = 0.0
        err = float(np.linalg.norm(diff)) / ref_norm
        if abs(previous - err) <= tol * err:
            break
        previous = err
        # (1) impose the target amplitudes, keep the phases
        mag[mag == 0.0] = 1.0
        current = np.fft.irfft2(target * (spec / mag), s=shape)
    final = ranked.reshape(shape).copy()
    return IaaftResult(
        heights=np.asarray(final, dtype=np.float64),
        amplitude_error=amplitude_error(final, target),
        iterations=iterations,
    )


def iaaft_surface(
    surface: Surface,
    rng: np.random.Generator | SeedLike = None,
    *,
    max_iter: int = 100,
    tol: float = 1e-4,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> Surface:
    """:func:`iaaft_heights` of ``surface`` as a :class:`Surface` of the same size."""
    h = iaaft_longer_heights(surface.heights_m, 1, rng, max_iter=max_iter, tol=tol, amplitude=amplitude)
    return surrogate_surface(surface, h, IAAFT_METHOD, 1, amplitude)


def random_phase_surface(
    surface: Surface, rng: np.random.Generator | SeedLike = None, *, amplitude: str = DEFAULT_AMPLITUDE
) -> Surface:
    """:func:`random_phase_heights` of ``surface`` as a :class:`Surface` of the same size."""
    return longer_surface(surface, 1, rng, amplitude=amplitude)

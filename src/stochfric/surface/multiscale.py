"""Multi-scale marginal-matching surrogates: new maps with non-Gaussian local structure (issue 29).

Reference: D. J. Heeger & J. R. Bergen, "Pyramid-based texture analysis/synthesis", SIGGRAPH 1995,
229–238 — a texture is synthesised from noise by matching the histogram of every sub-band of a
pyramid to that of the example, and of the image itself, a few times over.  Here the same, adapted to
height maps and to what the contact analysis reads (summits, their radii and heights):

* **Bands** (:func:`band_masks`, :func:`decompose`).  ``J`` octave bands on the full grid (no
  down-sampling), built in the Fourier domain with smooth radial masks: with ``p = −log₂(2k)``
  (``k`` the radial wavenumber in cycles per grid step, so ``p = 0`` at a wavelength of 2 points),
  band ``j`` has the mask ``cos²(π/2 · (p − j))`` for ``|p − j| < 1``; band 0 also takes every
  wavenumber above 0.5 and band ``J − 1`` every one below its centre.  Neighbouring masks sum to 1,
  so the bands sum to the map less its mean exactly (an exactly invertible decomposition).  The
  masks are radial, but nothing is averaged over directions: the anisotropy of the map stays in its
  amplitude spectrum, which the synthesis re-imposes.  ``J = ⌊log₂(min(nx, ny)/4)⌋ + 1`` by default
  (:func:`band_count`): centre wavelengths 2, 4, …, up to a quarter of the shorter side (6 bands on
  200 points, 8 on 600).  The bands of the *measured* map are taken from its mirror extension
  (2nx × 2ny, even in both axes), so that the jump between opposite edges of a non-periodic map does
  not enter their histograms.
* **Synthesis** (:func:`multiscale_heights`).  Start from a random-phase surrogate
  (:func:`~stochfric.surface.synthesis.phase_longer_heights`: the measured amplitude spectrum of the
  estimate ``amplitude``, ``factor`` times longer in y where asked).  Then, ``iterations`` times
  (default :data:`DEFAULT_ITERATIONS` = 8): (1) decompose; rank-remap every band onto the sorted
  coefficients of the same band of the measured map and recombine — this turns Gaussian bands into
  the measured heavy-tailed, sparse ones (sharp asperities); (2) rank-remap the periodic 5-point
  Laplacian onto the measured map's (interior) Laplacian values and put the change back through the
  inverse Laplacian on the finest ``laplacian_bands`` octaves only (default
  :data:`LAPLACIAN_BANDS` = 3: the curvature the summits read lives there, and the inverse
  Laplacian would blow up at long wavelengths); (3) rank-remap the heights onto the measured heights
  (the height distribution is exact, as in IAAFT); (4) unless it was the last iteration, impose the
  target amplitude spectrum keeping the phases (as IAAFT does).  It stops early when an iteration
  changes the map by less than ``tol`` (relative RMS).  The result is the output of (3).  For
  ``factor > 1`` each measured sorted value (heights, bands) is repeated ``factor`` times, as IAAFT
  repeats the heights; the Laplacian values are resampled by their quantiles.  Deterministic given
  ``rng`` (only the starting phases are random).
* **Kept**: the height distribution exactly; the marginal distribution of every octave band and of
  the Laplacian approximately (to the last iteration's remaps); the amplitude spectrum
  approximately (:attr:`MultiscaleResult.amplitude_error`, a few per cent on the shared maps, up to
  ~15 % on maps whose Laplacian kurtosis is in the thousands); the mean.
* **Not kept**: the joint statistics across bands, orientations and positions — where a sharp
  asperity in one band sits relative to the others, the alignment of edges and ridges across scales
  (a lay's long grooves), the correlations of neighbouring coefficients.  This is marginal matching,
  not the full Portilla–Simoncelli model (which adds cross-scale and neighbourhood correlations).
  Nothing is copied from the map: only sorted values (marginals) and the amplitude spectrum are taken
  from the measurement, so the surrogate is a new map.

Measured (``benchmarks/eval_multiscale.py``, 8 surrogates, coarse prepared maps): the Laplacian kurtosis
of the map is reproduced everywhere (3 on a Gaussian field, 21 on a synthetic spiky one, 3.8 … 3230 on the
shared files, |z| < 3), and β̄ and σ_S come far closer than with random phases (β̄: z 143 → 4.7 on mnt-1,
158 → 23 on x3p-2, 801 → 29 on sur-2); the summit check passes on the synthetic maps, al3d-1 and plu-1.
The summit *count* is not a marginal: it stays off on x3p-2 (a lay, −17) and sur-2 (−26, worse than
random phases) and on mnt-1 and opd-1 (+9, +8) — there quilting passes and this method does not.  A map
whose height variance sits in a few outlier pixels (mnt-1, sur-2: ~100 points hold half of it) gets
surrogates with as few extreme pixels, which then dominate their cross-correlations.

Parameters: ``bands`` (default :func:`band_count`), ``iterations`` (8), ``laplacian_bands`` (3),
``tol`` (1e-3), ``amplitude`` (the estimate of the starting spectrum).  The registry entry is
:class:`MultiscaleSurrogate` (name ``"multiscale"``); :func:`register` adds it to
:data:`stochfric.surface.surrogates.SURROGATES` once (the package does not register it on import).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.random import SeedLike, as_generator
from stochfric.surface.io import SurfaceError
from stochfric.surface.synthesis import DEFAULT_AMPLITUDE, amplitude_error, checked_heights, phase_longer_heights

__all__ = [
    "DEFAULT_ITERATIONS",
    "DEFAULT_TOL",
    "LAPLACIAN_BANDS",
    "MULTISCALE_METHOD",
    "MultiscaleResult",
    "band_count",
    "band_masks",
    "decompose",
    "laplacian",
    "multiscale_heights",
    "resample_sorted",
]

#: The registry name of the method.
MULTISCALE_METHOD = "multiscale"
#: Iterations of the synthesis (band, Laplacian and height remaps, then the spectrum).
DEFAULT_ITERATIONS = 8
#: The finest octaves through which the Laplacian's remap is put back into the heights.
LAPLACIAN_BANDS = 3
#: Early stop: an iteration that changes the map by less than this (RMS, relative to the map's) ends it.
DEFAULT_TOL = 1e-3


def band_count(shape: tuple[int, int]) -> int:
    """Octave bands of a map of ``shape``: ``⌊log₂(min(nx, ny)/4)⌋ + 1`` (at least 1): centre
    wavelengths 2, 4, … points up to a quarter of the shorter side."""
    n = min(int(shape[0]), int(shape[1]))
    return max(1, math.floor(math.log2(n / 4.0)) + 1) if n >= 4 else 1


def check_bands(bands: int) -> int:
    if isinstance(bands, bool) or not isinstance(bands, int | np.integer) or bands < 1:
        raise SurfaceError(f"the number of bands must be an integer >= 1, got {bands!r}")
    return int(bands)


def _band_position(shape: tuple[int, int], bands: int) -> FloatArray:
    """``p = −log₂(2k)`` clipped to [0, bands − 1] on the rfft2 layout of ``shape`` (k in cycles per step);
    the DC element is set to ``bands − 1`` (its masks are zeroed where they are used)."""
    fx = np.fft.fftfreq(shape[0])[:, None]
    fy = np.fft.rfftfreq(shape[1])[None, :]
    k = np.hypot(fx, fy)
    k[0, 0] = 1.0  # placeholder; DC handled by the callers
    p = np.clip(-np.log2(2.0 * k), 0.0, float(bands - 1))
    p[0, 0] = float(bands - 1)
    return np.asarray(p, dtype=np.float64)


def _mask(position: FloatArray, j: int) -> FloatArray:
    """Band ``j`` of the cos² partition of unity at band positions ``position`` (DC excluded)."""
    d = position - float(j)
    m = np.where(np.abs(d) < 1.0, np.cos(0.5 * np.pi * d) ** 2, 0.0)
    m[0, 0] = 0.0
    return np.asarray(m, dtype=np.float64)


def band_masks(shape: tuple[int, int], bands: int | None = None) -> FloatArray:
    """The ``bands`` radial octave masks on the rfft2 layout of ``shape``: array ``(bands, nx, ny//2 + 1)``
    whose sum is 1 everywhere but at DC (0)."""
    j_count = band_count(shape) if bands is None else check_bands(bands)
    pos = _band_position((int(shape[0]), int(shape[1])), j_count)
    return np.stack([_mask(pos, j) for j in range(j_count)])


def decompose(heights: npt.ArrayLike, bands: int | None = None, *, mirror: bool = False) -> FloatArray:
    """The octave bands of a map, ``(bands, nx, ny)``; ``heights.mean() + bands.sum(0)`` is the map (to
    round-off).  ``mirror``: filter the even extension (2nx × 2ny) and crop, so that the edges of a
    non-periodic map add no jump (how the measured map is decomposed); else the map is periodic."""
    z = checked_heights(heights, "a band decomposition")
    j_count = band_count(z.shape) if bands is None else check_bands(bands)
    nx, ny = z.shape
    if mirror:
        ext = np.concatenate([z, z[::-1]], axis=0)
        ext = np.concatenate([ext, ext[:, ::-1]], axis=1)
    else:
        ext = z
    shape = (ext.shape[0], ext.shape[1])
    spec = np.fft.rfft2(ext - ext.mean())
    pos = _band_position(shape, j_count)
    out = np.empty((j_count, nx, ny), dtype=np.float64)
    for j in range(j_count):
        out[j] = np.fft.irfft2(spec * _mask(pos, j), s=shape)[:nx, :ny]
    return out  # with mirror: the crop of the extension's bands sums to z − ext.mean(), and ext.mean() = z.mean()


def laplacian(heights: npt.ArrayLike) -> FloatArray:
    """The 5-point Laplacian of the interior points (grid units; what the curvature test reads)."""
    h = np.asarray(heights, dtype=np.float64)
    return np.asarray(h[2:, 1:-1] + h[:-2, 1:-1] + h[1:-1, 2:] + h[1:-1, :-2] - 4.0 * h[1:-1, 1:-1])


def resample_sorted(values: npt.ArrayLike, n: int) -> FloatArray:
    """The sorted ``values`` resampled to ``n`` values: the same when ``n`` equals their number, each
    repeated ``n/size`` times when that is an integer (as IAAFT repeats the heights of a longer map),
    else the quantiles at ``(i + ½)/n`` by linear interpolation."""
    v = np.sort(np.asarray(values, dtype=np.float64).ravel())
    if v.size == 0:
        raise SurfaceError("no values to resample")
    return _expand(v, int(n))


def _expand(v: FloatArray, n: int) -> FloatArray:
    """:func:`resample_sorted` of values already sorted."""
    if n == v.size:
        return v
    if n % v.size == 0:
        return np.repeat(v, n // v.size)
    q = (np.arange(n, dtype=np.float64) + 0.5) * (v.size / n) - 0.5
    return np.asarray(np.interp(q, np.arange(v.size, dtype=np.float64), v))


def _remap(x: FloatArray, target_sorted: FloatArray) -> FloatArray:
    """``x`` with its values replaced, rank for rank, by ``target_sorted`` (same size)."""
    out = np.empty(x.size, dtype=np.float64)
    out[np.argsort(x, axis=None)] = target_sorted
    return out.reshape(x.shape)


@dataclass(frozen=True, kw_only=True, eq=False)
class MultiscaleResult:
    """Result of :func:`multiscale_heights`: the map, its amplitude error ε against the target spectrum
    (:func:`~stochfric.surface.synthesis.amplitude_error`), the iterations used and the bands."""

    heights: FloatArray
    amplitude_error: float
    iterations: int
    bands: int


class Synthesis:
    """The fixed parts of one synthesis: targets (sorted values, spectrum), band positions, operators."""

    def __init__(self, z: FloatArray, start: FloatArray, *, bands: int, laplacian_bands: int) -> None:
        shape = (int(start.shape[0]), int(start.shape[1]))
        n = start.size
        self.shape = shape
        self.bands = bands
        self.mean = float(z.mean())
        self.size = n
        # the measured sorted values at the measured map's size (expanded to the surrogate's when used,
        # so that a long map does not hold ``bands`` long arrays)
        self.heights_sorted = np.sort(z, axis=None)
        self.band_sorted = [np.sort(b, axis=None) for b in decompose(z, bands, mirror=True)]
        self.laplacian_sorted = np.sort(laplacian(z), axis=None) if min(z.shape) >= 3 else None
        self.position = _band_position(shape, bands)
        target = np.abs(np.fft.rfft2(start))
        target[0, 0] = abs(self.mean) * n
        self.target = target
        fx = np.fft.fftfreq(shape[0])[:, None]
        fy = np.fft.rfftfreq(shape[1])[None, :]
        lap = 2.0 * np.cos(2.0 * np.pi * fx) + 2.0 * np.cos(2.0 * np.pi * fy) - 4.0
        self.lap = np.asarray(lap, dtype=np.float64)
        # Σ of the masks of bands 0 … L−1: 1 up to p = L − 1, the cos² tail of band L − 1 above it
        tail = self.position - float(min(laplacian_bands, bands) - 1)
        high = np.where(tail <= 0.0, 1.0, np.where(tail < 1.0, np.cos(0.5 * np.pi * tail) ** 2, 0.0))
        high[0, 0] = 0.0
        with np.errstate(divide="ignore", invalid="ignore"):
            self.lap_inverse = np.where(high > 0.0, high / np.where(lap != 0.0, lap, 1.0), 0.0)
        self.lap_inverse[0, 0] = 0.0

    def remaps(self, x: FloatArray) -> FloatArray:
        """Steps (1)–(3): band marginals, Laplacian marginal, heights (exact)."""
        shape = self.shape
        spec = np.fft.rfft2(x)
        y = np.full(shape, self.mean)
        for j in range(self.bands):
            band = np.fft.irfft2(spec * _mask(self.position, j), s=shape)
            y += _remap(band, _expand(self.band_sorted[j], self.size))
        if self.laplacian_sorted is not None:
            lap = np.fft.irfft2(np.fft.rfft2(y) * self.lap, s=shape)
            change = _remap(lap, _expand(self.laplacian_sorted, self.size)) - lap
            y = y + np.fft.irfft2(np.fft.rfft2(change) * self.lap_inverse, s=shape)
        return _remap(y, _expand(self.heights_sorted, self.size))

    def spectrum(self, y: FloatArray) -> FloatArray:
        """Step (4): the target amplitudes with the phases of ``y``; the mean kept."""
        spec = np.fft.rfft2(y)
        mag = np.abs(spec)
        mag[mag == 0.0] = 1.0
        coef = self.target * (spec / mag)
        coef[0, 0] = self.mean * y.size
        return np.asarray(np.fft.irfft2(coef, s=self.shape))


def check_count(name: str, value: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
        raise SurfaceError(f"{name} must be an integer >= 1, got {value!r}")
    return int(value)


def multiscale_heights(
    heights: npt.ArrayLike,
    rng: np.random.Generator | SeedLike = None,
    *,
    factor: int = 1,
    bands: int | None = None,
    iterations: int = DEFAULT_ITERATIONS,
    laplacian_bands: int = LAPLACIAN_BANDS,
    tol: float = DEFAULT_TOL,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> MultiscaleResult:
    """A multi-scale marginal-matching surrogate of ``heights``, ``factor`` times longer in y (module doc).

    ``bands`` octave bands (default :func:`band_count` of the map), at most ``iterations`` rounds of
    band, Laplacian (through the finest ``laplacian_bands`` octaves) and height remaps with the
    amplitude spectrum (estimate ``amplitude``) re-imposed between them; stops early when a round
    changes the map by less than ``tol`` RMS relative to the map's RMS.  The heights' distribution is
    exact (each measured height ``factor`` times)."""
    z = checked_heights(heights)
    factor = check_count("the length factor", factor)
    iterations = check_count("iterations", iterations)
    laplacian_bands = check_count("laplacian_bands", laplacian_bands)
    j_count = band_count(z.shape) if bands is None else check_bands(bands)
    if not (math.isfinite(tol) and tol >= 0.0):
        raise SurfaceError(f"tol must be a finite number >= 0, got {tol!r}")
    gen = as_generator(rng)
    start = phase_longer_heights(z, factor, gen, amplitude=amplitude)
    synth = Synthesis(z, start, bands=j_count, laplacian_bands=laplacian_bands)
    scale = max(float(z.std()), np.finfo(float).tiny)
    x = start
    previous: FloatArray | None = None
    y = start
    used = 0
    for used in range(1, iterations + 1):
        y = synth.remaps(x)
        if previous is not None and float(np.sqrt(np.mean((y - previous) ** 2))) <= tol * scale:
            break
        previous = y
        if used < iterations:
            x = synth.spectrum(y)
    return MultiscaleResult(heights=np.asarray(y, dtype=np.float64), amplitude_error=amplitude_error(y, synth.target),
                            iterations=used, bands=j_count)

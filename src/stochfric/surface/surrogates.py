"""The surrogate methods by name: one registry of small strategy objects (method §3, thesis 3.1.2).

A surrogate method makes a stochastically similar height map of a measured one — of the same size, or
``factor`` times longer in y for μ along the path (§4c) — from a :class:`numpy.random.Generator`, and
says what it needs: whether it applies to a map at all (:meth:`SurrogateMethod.applicable`), what it
will cost before the work starts (:meth:`SurrogateMethod.cost_seconds`), and what the copy check
needs to see of one of its maps (:meth:`SurrogateMethod.copy_sample`: the map and, for a method made
of verbatim pieces of the measurement, the record of which piece came from where).

The registry :data:`SURROGATES` holds the package's three methods, in this order:

* ``phase`` (:class:`PhaseSurrogate`) — the thesis's random phases (eq. 3.4–3.6): a Gaussian field
  with the measured amplitude spectrum;
* ``iaaft`` (:class:`IaaftSurrogate`) — beyond the thesis: IAAFT, the measured height distribution
  exactly and the spectrum approximately (Schreiber & Schmitz 1996);
* ``quilt`` (:class:`QuiltSurrogate`) — beyond the thesis: pieces of the measurement with repaired
  seams (image quilting, :mod:`stochfric.surface.quilting`), keeping local non-Gaussian structure — a
  resampling of the map (docs/statistical_contact.md §0b);
* ``multiscale`` (:class:`MultiscaleSurrogate`) — beyond the thesis: new maps with the measured marginals
  of every octave band, of the Laplacian and of the heights (Heeger & Bergen 1995,
  :mod:`stochfric.surface.multiscale`).  Offered by name, not chosen by ``auto``.

A new method is one class (a subclass of :class:`SurrogateMethod` with ``name``, ``summary`` and
:meth:`~SurrogateMethod.heights`) and one :func:`register_surrogate` call; the analysis, its checks,
the figures and the command line's ``--surrogate`` take it from here.  ``"auto"`` is no method: the
analysis resolves it for a map (:meth:`stochfric.process.analysis_config.AnalysisConfig.surrogate_for`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any, ClassVar

import numpy as np

from stochfric.arrays import FloatArray
from stochfric.errors import InputError
from stochfric.random import SeedLike, as_generator
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.multiscale import (
    DEFAULT_ITERATIONS,
    DEFAULT_TOL,
    LAPLACIAN_BANDS,
    MULTISCALE_METHOD,
    Synthesis,
    band_count,
    check_bands,
    check_count,
    multiscale_heights,
)
from stochfric.surface.quilting import QUILT_METHOD, QuiltResult, quilt_applicable, quilt_heights
from stochfric.surface.synthesis import (
    AMPLITUDE_METHODS,
    DEFAULT_AMPLITUDE,
    IAAFT_METHOD,
    PHASE_METHOD,
    AmplitudeEstimate,
    checked_heights,
    gaussian_field_heights,
    iaaft_longer_heights,
    phase_longer_heights,
    surrogate_surface,
)

__all__ = [
    "AUTO_SURROGATE",
    "IAAFT_ESTIMATE_ITERATIONS",
    "SURROGATES",
    "IaaftSurrogate",
    "MultiscaleSurrogate",
    "PhaseSurrogate",
    "QuiltSurrogate",
    "SurrogateMethod",
    "SurrogateSettings",
    "register_surrogate",
    "similar_surface",
    "surrogate_method",
    "surrogate_names",
    "unregister_surrogate",
]

#: The surrogate setting that lets the analysis pick the method from the map (not a method).
AUTO_SURROGATE = "auto"

#: Iterations an IAAFT surrogate typically takes to settle at the default tolerance 1e-3 (measured on
#: al3d-1, x3p-2 and plu-1: 37–100, original size and 10× long); the cost estimate uses the cap, 100.
IAAFT_ESTIMATE_ITERATIONS = 100


@dataclass(frozen=True, kw_only=True)
class SurrogateSettings:
    """The settings a method may read: the amplitude estimate of the measured map
    (:class:`~stochfric.surface.synthesis.AmplitudeEstimate`), IAAFT's stopping tolerance and most
    iterations.  A method ignores the ones it does not use."""

    amplitude: str = DEFAULT_AMPLITUDE
    iaaft_tol: float = 1e-3
    max_iter: int = 100

    def __post_init__(self) -> None:
        if self.amplitude not in AMPLITUDE_METHODS:
            raise SurfaceError(f"unknown amplitude estimate {self.amplitude!r}; use one of "
                               f"{', '.join(AMPLITUDE_METHODS)}")
        object.__setattr__(self, "amplitude", AmplitudeEstimate(self.amplitude))


class SurrogateMethod:
    """A surrogate method: a name, one line of help, and how it makes a map (subclass and register it)."""

    #: The name on the command line and in every output.
    name: ClassVar[str] = ""
    #: One line for the help text and the docs.
    summary: ClassVar[str] = ""
    #: Whether its maps are made of verbatim pieces of the measurement (a resampling of it): the copy
    #: check then also measures the largest verbatim piece (:meth:`copy_sample` returns their sources).
    resamples: ClassVar[bool] = False
    #: Why it costs what :meth:`cost_seconds` says (the start of the note printed before the work).
    cost_reason: ClassVar[str] = ""

    def heights(self, heights: FloatArray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> FloatArray:
        """A surrogate of ``heights`` with ``factor`` times its length in y, from ``rng`` only."""
        raise NotImplementedError

    def predictive_heights(self, heights: FloatArray, rng: np.random.Generator, *,
                           settings: SurrogateSettings) -> FloatArray:
        """A map of the size of ``heights`` drawn from the method's model as a prediction of an
        *independent* sample of the surface (the held-out validation, :mod:`stochfric.process.holdout`).
        By default the method's own surrogate; a method whose surrogates are conditioned on a statistic of
        the map that an independent sample would not share overrides it (:class:`PhaseSurrogate`)."""
        return self.heights(heights, rng, factor=1, settings=settings)

    def applicable(self, heights: FloatArray, *, rule: str) -> tuple[bool, str]:
        """Can this map (summits by ``rule``) be made into surrogates by this method?  ``(yes, reason)``."""
        return True, f"{self.name} applies to any map"

    def cost_seconds(self, grid: tuple[int, int], maps: int) -> float | None:
        """Estimated time for ``maps`` surrogates of this grid [s], or None when not worth saying."""
        return None

    def copy_sample(self, heights: FloatArray, rng: np.random.Generator,
                    settings: SurrogateSettings) -> tuple[FloatArray, Any]:
        """One map of the original size for the copy check, and what it needs of its making (the
        verbatim-piece sources of a resampling method, else None)."""
        return self.heights(heights, rng, factor=1, settings=settings), None


class PhaseSurrogate(SurrogateMethod):
    """Random phases (thesis eq. 3.4–3.6, :func:`~stochfric.surface.synthesis.phase_longer_heights`)."""

    name = PHASE_METHOD
    summary = "random phases (thesis): a Gaussian field with the measured amplitude spectrum"

    def heights(self, heights: FloatArray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> FloatArray:
        return phase_longer_heights(heights, factor, rng, amplitude=settings.amplitude)

    def predictive_heights(self, heights: FloatArray, rng: np.random.Generator, *,
                           settings: SurrogateSettings) -> FloatArray:
        """The random-phase model as a prediction of a new sample: a Gaussian field with random amplitudes
        whose spectrum is the map's tapered periodogram in Welch's normalisation
        (:func:`~stochfric.surface.synthesis.gaussian_field_heights`), not the map's own amplitudes with
        random phases."""
        return gaussian_field_heights(heights, rng, amplitude=settings.amplitude)


class IaaftSurrogate(SurrogateMethod):
    """IAAFT (:func:`~stochfric.surface.synthesis.iaaft_heights`): Gaussian phases, measured heights."""

    name = IAAFT_METHOD
    summary = "IAAFT: the measured height distribution exactly, the amplitude spectrum approximately"
    cost_reason = "IAAFT surrogates iterate FFTs until the spectrum settles"

    def heights(self, heights: FloatArray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> FloatArray:
        return iaaft_longer_heights(heights, factor, rng, max_iter=settings.max_iter, tol=settings.iaaft_tol,
                                    amplitude=settings.amplitude)

    def cost_seconds(self, grid: tuple[int, int], maps: int) -> float:
        """One iteration (a real 2-D FFT pair and the rank remap, a sort) timed on a random field of the
        grid's size on this machine, scaled by ``maps`` (each counted in original sizes) and
        :data:`IAAFT_ESTIMATE_ITERATIONS`."""
        nx, ny = int(grid[0]), int(grid[1])
        z = np.random.default_rng(0).standard_normal((nx, ny))
        t0 = time.perf_counter()
        spec = np.fft.rfft2(z)
        back = np.fft.irfft2(spec, s=z.shape)
        np.argsort(back, axis=None)
        one = time.perf_counter() - t0
        return one * int(maps) * IAAFT_ESTIMATE_ITERATIONS


class QuiltSurrogate(SurrogateMethod):
    """Image quilting with gradient-domain seam repair (:func:`~stochfric.surface.quilting.quilt_heights`);
    its long wavelengths are a random-phase surrogate with the default amplitude estimate, so it ignores
    ``settings``."""

    name = QUILT_METHOD
    summary = ("quilt: pieces of the measurement with repaired seams (keeps local non-Gaussian structure; "
               "a resampling of the map)")
    resamples = True

    def heights(self, heights: FloatArray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> FloatArray:
        return quilt_heights(heights, rng, factor=factor, sources=False).heights

    def applicable(self, heights: FloatArray, *, rule: str) -> tuple[bool, str]:
        return quilt_applicable(heights, rule=rule)

    def copy_sample(self, heights: FloatArray, rng: np.random.Generator,
                    settings: SurrogateSettings) -> tuple[FloatArray, QuiltResult]:
        res = quilt_heights(heights, rng)
        return res.heights, res


class MultiscaleSurrogate(SurrogateMethod):
    """Multi-scale marginal matching (Heeger & Bergen 1995; :func:`multiscale_heights`): random phases,
    then the measured marginals of every octave band, of the Laplacian and of the heights, with the
    amplitude spectrum re-imposed between rounds.  Uses ``settings.amplitude``; IAAFT's ``max_iter``
    and ``iaaft_tol`` are not its settings (its own are the constructor's)."""

    name = MULTISCALE_METHOD
    summary = ("multiscale: new maps with the measured marginals of every octave band, of the Laplacian "
               "and of the heights (Heeger-Bergen marginal matching; cross-scale structure not kept)")
    cost_reason: ClassVar[str] = "multiscale surrogates remap every octave band a few times"

    def __init__(self, *, bands: int | None = None, iterations: int = DEFAULT_ITERATIONS,
                 laplacian_bands: int = LAPLACIAN_BANDS, tol: float = DEFAULT_TOL) -> None:
        self.bands = None if bands is None else check_bands(bands)
        self.iterations = check_count("iterations", iterations)
        self.laplacian_bands = check_count("laplacian_bands", laplacian_bands)
        self.tol = float(tol)

    def heights(self, heights: FloatArray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> FloatArray:
        return multiscale_heights(heights, rng, factor=factor, bands=self.bands, iterations=self.iterations,
                                  laplacian_bands=self.laplacian_bands, tol=self.tol,
                                  amplitude=settings.amplitude).heights

    def cost_seconds(self, grid: tuple[int, int], maps: int) -> float:
        """The set-up (the measured map's bands on its mirror extension) and one round (band, Laplacian
        and height remaps, the spectrum) timed on a random field of the grid's size on this machine;
        ``maps`` (each counted in original sizes) × (set-up + ``iterations`` rounds)."""
        nx, ny = int(grid[0]), int(grid[1])
        z = np.random.default_rng(0).standard_normal((nx, ny))
        j_count = band_count(z.shape) if self.bands is None else self.bands
        t0 = time.perf_counter()
        synth = Synthesis(z, z, bands=j_count, laplacian_bands=self.laplacian_bands)
        t1 = time.perf_counter()
        synth.spectrum(synth.remaps(z))
        t2 = time.perf_counter()
        return int(maps) * ((t1 - t0) + self.iterations * (t2 - t1))


#: name → method, in the order the help, the figures and the docs list them.
SURROGATES: dict[str, SurrogateMethod] = {}


def register_surrogate(method: SurrogateMethod) -> SurrogateMethod:
    """Add ``method`` under its ``name`` (a new name, not ``"auto"``); returns it."""
    name = method.name
    if not name or name == AUTO_SURROGATE or name in SURROGATES:
        raise InputError(f"a surrogate method needs a new name other than {AUTO_SURROGATE!r}; got {name!r} "
                         f"(registered: {', '.join(SURROGATES)})")
    SURROGATES[name] = method
    return method


def unregister_surrogate(name: str) -> None:
    """Remove the method ``name`` (tests, plug-ins); the package's own three cannot be removed."""
    if name in (PHASE_METHOD, IAAFT_METHOD, QUILT_METHOD, MULTISCALE_METHOD):
        raise InputError(f"{name!r} is one of the package's own surrogate methods")
    SURROGATES.pop(name, None)


def surrogate_names() -> tuple[str, ...]:
    """The registered method names, in registry order."""
    return tuple(SURROGATES)


def surrogate_method(name: str) -> SurrogateMethod:
    """The method registered as ``name`` (:class:`~stochfric.surface.io.SurfaceError` naming the
    known ones otherwise)."""
    try:
        return SURROGATES[str(name)]
    except KeyError:
        raise SurfaceError(f"unknown surrogate method {name!r}; use one of {', '.join(SURROGATES)}") from None


for _method in (PhaseSurrogate(), IaaftSurrogate(), QuiltSurrogate(), MultiscaleSurrogate()):
    register_surrogate(_method)


def similar_surface(
    surface: Surface,
    rng: np.random.Generator | SeedLike = None,
    *,
    method: str = PHASE_METHOD,
    factor: int = 1,
    max_iter: int = 100,
    tol: float = 1e-4,
    amplitude: str = DEFAULT_AMPLITUDE,
) -> Surface:
    """One stochastically similar surface of ``factor`` times the length of ``surface`` by the
    registered ``method`` (eq. 3.6 for random phases), as a :class:`Surface` of the same spacing."""
    m = surrogate_method(method)
    if isinstance(factor, bool) or not isinstance(factor, int | np.integer) or factor < 1:
        raise SurfaceError(f"the length factor must be an integer >= 1, got {factor!r}")
    if max_iter < 1:
        raise SurfaceError(f"max_iter must be >= 1, got {max_iter}")
    settings = SurrogateSettings(amplitude=amplitude, iaaft_tol=tol, max_iter=max_iter)
    z = checked_heights(surface.heights_m)
    h = m.heights(z, as_generator(rng), factor=int(factor), settings=settings)
    return surrogate_surface(surface, np.asarray(h, dtype=np.float64), m.name, int(factor), settings.amplitude)


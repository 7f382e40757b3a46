"""The choices of a simulation and the options of :func:`~stochfric.oscillator.integrate.simulate`.

Each choice is one :class:`~enum.StrEnum` (its values are the names in configs, on the command
line, in results; docs/glossary.md), defined once here and used by ``simulate``, the study configs
and the command line.  The options of ``simulate`` come in four small frozen groups:
:class:`NoiseOptions` (the random input), :class:`IntegrationOptions` (scheme, time grid,
tolerances), :class:`OutputOptions` (what is kept) and :class:`ExecutionOptions` (how it runs;
never changes a number).
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from enum import StrEnum

__all__ = [
    "ExecutionOptions",
    "IntegrationOptions",
    "Integrator",
    "Model",
    "NoiseOptions",
    "OutputOptions",
    "PathCoordinate",
    "WhiteIncrement",
    "WhiteIntensity",
    "WhiteStream",
    "default_integrator",
    "white_increment_of",
]


class Model(StrEnum):
    """The friction models of method §5, run side by side in the studies."""

    #: the friction law alone
    DETERMINISTIC = "deterministic"
    #: law + Gaussian white noise of intensity σ_ζ in the relative path (§5.1)
    WHITE = "white"
    #: law + a band-limited process μ̂ from a friction-process model (§5.2)
    CONTACT = "contact"


class Integrator(StrEnum):
    """Integration schemes: ``euler`` (thesis; Euler–Maruyama for white noise), ``milstein`` (white
    noise, strong order 1), ``accurate`` (adaptive DOP853 with event location; deterministic/contact)."""

    EULER = "euler"
    MILSTEIN = "milstein"
    ACCURATE = "accurate"


def default_integrator(model: Model | str, forced: bool) -> Integrator:
    """The converged integrator where Euler at the thesis's Δτ is known to be wrong, else Euler (issue 30,
    item 5): a forced deterministic or contact run takes ``accurate`` (Euler at Δτ = 0.005 settles into a
    spurious locked cycle on the forced brake at η = 1.2, docs/studies.md), the white-noise SDE and unforced
    runs Euler (the thesis's scheme, converged there: docs/oscillator.md).  ``euler`` stays the named
    reproduction mode."""
    return Integrator.ACCURATE if forced and Model(model) != Model.WHITE else Integrator.EULER


class PathCoordinate(StrEnum):
    """Where the contact process is read (method §7.7)."""

    #: the mass's own path |Δx1| in slip (thesis text §4.1.3)
    MASS = "mass"
    #: the relative sliding distance |γ0 − x2| Δτ
    RELATIVE = "relative"
    #: reproduction mode: μ̂ at the mass position x1 (eq. 4.36/4.38 as printed; ``euler`` only)
    POSITION = "position"


class WhiteIncrement(StrEnum):
    """White-noise increment rules (docs/oscillator.md, method §7 errata 4 and 10)."""

    #: the consistent Itô model: ΔW = R_k √Δτ, intensity σ_ζ per unit dimensionless relative path
    ITO = "ito"
    #: printed eq. (4.31) with the dimensional relative velocity: σ_ζ,eff = σ_ζ · L ω0 · Δτ, a
    #: reproduction mode whose intensity depends on the time step
    THESIS = "thesis"


class WhiteStream(StrEnum):
    """Random streams of the white-noise model (docs/performance.md); all exact N(0, 1), one per
    trajectory, different realisations of the same statistics."""

    #: R_k drawn inside the compiled kernel from the Philox4x32-10 stream keyed by the trajectory's
    #: spawned seed, turned into normals by a 1024-layer ziggurat (default)
    PHILOX_ZIGGURAT = "philox-ziggurat"
    #: the same Philox blocks through Box–Muller (:mod:`stochfric.random.philox`)
    PHILOX_BOXMULLER = "philox-boxmuller"
    #: numpy's ``Generator(PCG64(seed)).standard_normal`` per trajectory, drawn into a buffer
    PCG64 = "pcg64"


class WhiteIntensity(StrEnum):
    """σ_ζ rules of the white-noise model (docs/oscillator.md): the process model's σ_ζ rule
    (:class:`~stochfric.friction_process.model_base.SigmaZetaRule`) or the printed-(4.31) reproduction mode."""

    #: σ_ζ = σ_μ(p), the thesis's rule, consistent Itô model
    SIGMA_MU = "sigma_mu"
    #: σ_ζ = S0/2, the process's low-frequency spectral level
    SPECTRAL_LEVEL = "spectral_level"
    #: printed eq. (4.31): σ_ζ,eff = σ_μ(p)·Lω0·Δτ, a Δτ-dependent reproduction mode
    THESIS = "thesis"


def white_increment_of(model: Model | str, white_intensity: WhiteIntensity | str | None) -> WhiteIncrement:
    """The increment rule a simulation of ``model`` runs under the σ_ζ rule ``white_intensity``:
    ``thesis`` for the white-noise model under the ``thesis`` rule (printed eq. 4.31), else ``ito``."""
    thesis = model == Model.WHITE and white_intensity == WhiteIntensity.THESIS
    return WhiteIncrement.THESIS if thesis else WhiteIncrement.ITO


@dataclass(frozen=True, kw_only=True)
class NoiseOptions:
    """The random input of a simulation (method §5.1/§5.2, the seed rule of :mod:`.integrate`).

    ``sigma_zeta``: white-noise intensity σ_ζ (a number, or a function of the pressure p [Pa]); ``None``:
    the case's, else ``process.sigma_zeta(p)``.  ``white_increment``: ``None`` is the case's rule for
    the model (:func:`white_increment_of`), else ``ito``.  ``path_coordinate``: where the contact process
    is read.  ``common_random_numbers``: every parameter set draws from the first set's streams.
    ``stream_keys``: one tuple of ints in [0, 2³²) per parameter set (default ``(i,)``).
    """

    sigma_zeta: float | Callable[[float], float] | None = None
    white_increment: WhiteIncrement | None = None
    white_stream: WhiteStream = WhiteStream.PHILOX_ZIGGURAT
    path_coordinate: PathCoordinate = PathCoordinate.MASS
    common_random_numbers: bool = False
    stream_keys: Sequence[Sequence[int]] | None = None


@dataclass(frozen=True, kw_only=True)
class IntegrationOptions:
    """The scheme and its time grid (dimensionless τ = ω0 t).

    ``tau_end``, ``dt``: simulated time and step (``accurate``: initial step and sampling interval);
    ``None`` is the case's, else 50 and 0.005.  ``rtol``, ``atol``, ``max_step``: tolerances of the
    ``accurate`` integrator.
    """

    integrator: Integrator = Integrator.EULER
    tau_end: float | None = None
    dt: float | None = None
    rtol: float = 1e-11
    atol: float = 1e-13
    max_step: float = 0.1


@dataclass(frozen=True, kw_only=True)
class OutputOptions:
    """What a simulation keeps: every ``save_every``-th grid state (τ, x1, x2) when
    ``save_trajectory``; ``max_events`` X_gh per trajectory (``None``: 2 τ_end + 16)."""

    save_trajectory: bool = False
    save_every: int = 10
    max_events: int | None = None


@dataclass(frozen=True, kw_only=True)
class ExecutionOptions:
    """How a simulation runs; changes the speed, never a number.

    ``workers``: threads (``None``: all cores); ``batch_size``: the most trajectories per compiled call
    (fewer when needed to give every thread about four batches); ``progress(done, total)`` is called
    after every batch.
    """

    workers: int | None = None
    batch_size: int = 256
    progress: Callable[[int, int], None] | None = None

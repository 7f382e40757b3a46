"""``simulate``: ensembles of friction-oscillator trajectories (method §5, docs/method.md, thesis 4.1).

One call runs ``runs`` trajectories for each of many parameter sets (normal forces,
damping ratios, forcing frequencies …) in compiled kernels on all cores.  Trajectory
``(i, r)`` (parameter set ``i``, run ``r``) draws all its random numbers from its own
stream, the child with spawn key ``(*k_i, r)`` of the root seed
(:class:`numpy.random.SeedSequence`), where ``k_i`` is the set's *stream key*: ``(i,)`` by
default, or what the caller gives (the studies give a key made from the cell's own parameter
values, so a cell's numbers do not depend on its position in a grid:
:func:`stochfric.studies.tasks.cell_stream_key`); with ``common_random_numbers`` (:class:`~.options.NoiseOptions`)
every set uses ``k_0``, so run ``r`` sees the same noise at every parameter set.  The
numbers of a trajectory therefore do not depend on the number of threads, the batch
size or the order of execution.  White noise (:class:`~.options.WhiteStream`): the child's first
64 bits key the Philox stream drawn inside the compiled kernel, turned into normals by the ziggurat
(``philox-ziggurat``, default) or by Box–Muller (``philox-boxmuller``), or seed numpy's PCG64
(``pcg64``).  Contact process: a run's realisation is
an unbounded sequence of independent segments of the model's length ℓ (segment ``s`` of
trajectory ``(i, r)`` from the child ``(*k_i, r, s)``, which seeds numpy's PCG64 for the phases of
the spectral representation, computed in compiled code for the package's process models, bit
for bit); only the segments a run's path reaches are generated (:class:`_BatchRunner`), so the
process never repeats.

Models (method §5, :class:`~.options.Model`): ``deterministic`` (friction law only), ``white`` (law +
Gaussian white noise of intensity σ_ζ in the relative path, §5.1; integrators ``euler`` =
Euler–Maruyama, ``milstein``), ``contact`` (law + a band-limited process μ̂ generated
once per run from a friction-process model, §5.2; integrators ``euler``, ``accurate``).
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from enum import StrEnum
from typing import Any, Protocol, TypeVar

import numpy as np
import numpy.typing as npt

from ..friction_process.model import BandLimitedProcessModel, TabulatedProcessModel
from ..friction_process.spectral import generate_process_batch
from ..io_utils import package_versions
from ..random import SeedLike, as_seed_sequence, child_seed
from ..random import philox as _ph
from . import accurate as _acc
from . import kernels as _k
from . import options
from .case import Case
from .friction_laws import FrictionLaw, law_III
from .parameters import OscillatorParameters, ParameterError
from .result import SimulationResult, SimulationWarning

#: Kernel path mode of each path coordinate (:class:`~.options.PathCoordinate`).
_PATH_MODES = {options.PathCoordinate.MASS: _k.PATH_MASS, options.PathCoordinate.RELATIVE: _k.PATH_RELATIVE,
               options.PathCoordinate.POSITION: _k.PATH_POSITION}

#: Above this Δτ the Euler methods are refused: fewer than ~25 steps per natural period
#: 2π turn the solution's character (thesis Fig. 4.7/4.8 already shows it at 0.05/0.1).
DT_REFUSE = 0.25
#: Above these Δτ a warning is issued (thesis Fig. 4.8: forced, q = 0.5, η = 1.15, the
#: two-periodic solution is right up to Δτ = 0.01 and looks chaotic at 0.1; Fig. 4.7:
#: unforced, a deviation is visible at 0.05).
DT_WARN_FORCED = 0.01
DT_WARN_UNFORCED = 0.02


class ProcessModel(Protocol):
    """What :func:`simulate` needs from a friction-process model (§4e)."""

    @property
    def dx(self) -> float: ...

    @property
    def length(self) -> float: ...

    def generate(self, p: float, rng: np.random.Generator) -> npt.NDArray[np.float64]: ...

    def sigma_zeta(self, p: float) -> float: ...

    def to_dict(self) -> dict[str, Any]: ...


LawSpec = FrictionLaw | Callable[[OscillatorParameters], FrictionLaw]


@dataclass(frozen=True)
class _Plan:
    params: list[OscillatorParameters]
    laws: list[FrictionLaw]
    sigma: list[float]
    sigma_eff: list[float]
    pressures: list[float | None]
    x0: list[tuple[float, float]]
    nsteps: int


#: ``generate`` methods known to be ``generate_process(f, model.spectrum(f, p), dx, length, rng)``
#: with ``f = model.frequencies()`` (eq. 2.48), which :func:`simulate` evaluates for a whole
#: batch at once with the same numbers (:func:`_SpectralBatch`).
_SPECTRAL_GENERATE = (BandLimitedProcessModel.generate, TabulatedProcessModel.generate)


class _SpectralBatch:
    """Realisations of a spectral-representation process model for a batch of trajectories.

    Each trajectory's phases are ``Generator(PCG64(trajectory_seed)).uniform(0, 2π, K)``, as
    ``model.generate(p, rng)`` draws them, computed in compiled code
    (:func:`stochfric.random.philox.pcg64_uniform_for_children`); the realisations of all
    trajectories of one pressure are evaluated by one call of
    :func:`stochfric.friction_process.spectral.generate_process_batch`.  Bit for bit the numbers of
    ``model.generate`` per trajectory (tested), at ~1 µs instead of ~160 µs per trajectory.
    """

    def __init__(self, model: Any) -> None:
        self.model = model
        self.f = np.asarray(model.frequencies(), dtype=np.float64)
        self._psd: dict[float, npt.NDArray[np.float64]] = {}

    def psd(self, p: float) -> npt.NDArray[np.float64]:
        if p not in self._psd:
            self._psd[p] = np.asarray(self.model.spectrum(self.f, p), dtype=np.float64)
        return self._psd[p]

    def fill(self, out: npt.NDArray[np.float64], root: np.random.SeedSequence,
             tails: npt.NDArray[np.int64], pressures: list[float]) -> None:
        """``out[j]`` = realisation with spawn key ``(*root.spawn_key, *tails[j])`` at ``pressures[j]``."""
        phases = _ph.pcg64_uniform_for_children(root, tails, self.f.size, 2.0 * np.pi)
        pr = np.asarray(pressures, dtype=np.float64)
        for p in np.unique(pr):
            rows = np.flatnonzero(pr == p)
            out[rows] = generate_process_batch(self.f, self.psd(float(p)), self.model.dx,
                                               self.model.length, phases[rows])


def trajectory_seed(root: np.random.SeedSequence, stream_key: Sequence[int], run: int,
                    *segment: int) -> np.random.SeedSequence:
    """The seed sequence of run ``run`` of the parameter set with stream key ``stream_key``: spawn
    key ``(*stream_key, run)`` of ``root`` (contact process: ``(*stream_key, run, segment)``)
    (:func:`stochfric.random.child_seed`, the one place streams are derived)."""
    return child_seed(root, *stream_key, run, *segment)


def check_stream_keys(stream_keys: Any, npar: int) -> npt.NDArray[np.int64]:
    """The stream keys of ``npar`` parameter sets as an ``(npar, m)`` int64 array; default ``(i,)``.

    Every key is a tuple of ``m`` ints in ``[0, 2³²)`` (one 32-bit spawn-key word each), the same
    ``m`` for every set.
    """
    if stream_keys is None:
        return np.arange(npar, dtype=np.int64)[:, None]
    try:
        rows = [tuple(int(v) for v in k) for k in stream_keys]
    except (TypeError, ValueError):
        raise ParameterError("stream_keys must be one tuple of non-negative ints per parameter set") from None
    if len(rows) != npar:
        raise ParameterError(f"stream_keys has {len(rows)} entries for {npar} parameter sets")
    if len({len(r) for r in rows}) != 1 or not rows[0]:
        raise ParameterError("every stream key must have the same, non-zero number of entries")
    arr = np.array(rows, dtype=np.int64)
    if arr.min() < 0 or arr.max() >= 2**32:
        raise ParameterError("stream-key entries must lie in [0, 2**32)")
    return arr


def check_time_step(
    dt: float, tau_end: float, integrator: str, params: Sequence[OscillatorParameters]
) -> list[SimulationWarning]:
    """Refuse or warn about a Δτ that would change the solution's character.

    Euler-type schemes: refused above :data:`DT_REFUSE`; a warning above
    :data:`DT_WARN_FORCED` / ``max(1, η)`` for forced and above :data:`DT_WARN_UNFORCED`
    for unforced motion.  For ``accurate``, ``dt`` is only the initial step and the
    trajectory sampling interval.
    """
    if not (math.isfinite(dt) and dt > 0):
        raise ParameterError(f"time step dt must be a positive number, got {dt}")
    if not (math.isfinite(tau_end) and tau_end > 0):
        raise ParameterError(f"tau_end must be a positive number, got {tau_end}")
    if dt > tau_end:
        raise ParameterError(f"time step dt = {dt} exceeds tau_end = {tau_end}")
    out: list[SimulationWarning] = []
    if integrator == "accurate":
        return out
    eta_max = max(p.eta for p in params)
    forced = any(p.q > 0 and p.eta > 0 for p in params)
    fast = max(1.0, eta_max) if forced else 1.0
    if dt > DT_REFUSE / fast:
        raise ParameterError(
            f"dt = {dt} gives only {2 * math.pi / (dt * fast):.0f} steps per period "
            f"(2π/{fast:g}); the {integrator} scheme would change the solution's character. "
            f"Use dt <= {DT_WARN_FORCED if forced else DT_WARN_UNFORCED} "
            "(thesis Fig. 4.7/4.8) or the 'accurate' integrator"
        )
    limit = DT_WARN_FORCED / max(1.0, eta_max) if forced else DT_WARN_UNFORCED
    if dt > limit:
        what = (
            f"forced motion (η up to {eta_max:g}): the stick boundary moves in time, and the "
            "thesis (Fig. 4.8, q = 0.5, η = 1.15) shows Δτ > 0.01 turning a two-periodic "
            "solution into apparent chaos"
            if forced
            else "the thesis (Fig. 4.7) shows visible deviations of the stick-slip cycle at "
            "Δτ = 0.05"
        )
        out.append(SimulationWarning(
            "coarse-time-step",
            f"dt = {dt:g} is coarse for {what}; use dt <= {limit:g} or check convergence "
            "with the 'accurate' integrator",
        ))
    return out


def _resolve_law(law: LawSpec, p: OscillatorParameters) -> FrictionLaw:
    return law if isinstance(law, FrictionLaw) else law(p)


@dataclass(frozen=True)
class _System:
    """What :func:`simulate`'s first argument resolves to, with the law, process, σ_ζ, increment rule
    and time grid of its cases or of the options."""

    params: list[OscillatorParameters]
    laws: list[FrictionLaw] | LawSpec
    process: ProcessModel | None
    sigma_zeta: float | Callable[[float], float] | None
    white_increment: options.WhiteIncrement | str
    tau_end: float
    dt: float


def _same(a: Any, b: Any) -> bool:
    """``a is b`` or equal (models holding arrays compare unequal when ``==`` is ambiguous)."""
    if a is b:
        return True
    try:
        return bool(a == b)
    except (TypeError, ValueError):
        return False


def _system(
    system: Case | Sequence[Case] | OscillatorParameters | Sequence[OscillatorParameters],
    model: options.Model, law: LawSpec | None, process: ProcessModel | None, noise: options.NoiseOptions,
    integration: options.IntegrationOptions,
) -> _System:
    """The parameter sets and what they run with: from the :class:`Case` (or cases), else from ``law``,
    ``process`` and the options (defaults: law III, Itô increments, τ_end = 50, Δτ = 0.005)."""
    items = [system] if isinstance(system, Case | OscillatorParameters) else list(system)
    if not items:
        raise ParameterError("no parameter set given")
    cases = [c for c in items if isinstance(c, Case)]
    if not cases:
        return _System(
            params=list(items),  # type: ignore[arg-type]
            laws=law_III() if law is None else law, process=process, sigma_zeta=noise.sigma_zeta,
            white_increment=options.WhiteIncrement.ITO if noise.white_increment is None else noise.white_increment,
            tau_end=50.0 if integration.tau_end is None else integration.tau_end,
            dt=0.005 if integration.dt is None else integration.dt,
        )
    if len(cases) != len(items):
        raise ParameterError("give cases or parameter sets, not both")
    given = [name for name, value in (
        ("law", law), ("process", process), ("noise.sigma_zeta", noise.sigma_zeta),
        ("noise.white_increment", noise.white_increment), ("integration.tau_end", integration.tau_end),
        ("integration.dt", integration.dt)) if value is not None]
    if given:
        raise ParameterError(f"a Case fixes {', '.join(given)}; change the case instead "
                             "(dataclasses.replace(case, …))")
    first = cases[0]
    for c in cases[1:]:
        if not (_same(c.process, first.process) and (c.tau_end, c.dt, c.white_intensity, c.sigma_zeta)
                == (first.tau_end, first.dt, first.white_intensity, first.sigma_zeta)):
            raise ParameterError("the cases of one simulation must share the process model, tau_end, dt, "
                                 "white_intensity and sigma_zeta")
    return _System(params=[c.params for c in cases], laws=[c.law for c in cases], process=first.process,
                   sigma_zeta=first.sigma_zeta, white_increment=first.white_increment(model),
                   tau_end=first.tau_end, dt=first.dt)


def _plan(
    sysm: _System,
    model: options.Model,
    x0: tuple[float, float] | Sequence[tuple[float, float]] | None,
    white_increment: options.WhiteIncrement,
) -> _Plan:
    params, law, process, sigma_zeta, dt = sysm.params, sysm.laws, sysm.process, sysm.sigma_zeta, sysm.dt
    laws: list[FrictionLaw] = []
    sig: list[float] = []
    pressures: list[float | None] = []
    x0s: list[tuple[float, float]] = []
    per_set_x0 = x0 is not None and len(x0) > 0 and isinstance(x0[0], Sequence | np.ndarray)
    if per_set_x0 and len(x0) != len(params):  # type: ignore[arg-type]
        raise ParameterError("x0 per parameter set must have one entry per set")
    for i, p in enumerate(params):
        laws.append(law[i] if isinstance(law, list) else _resolve_law(law, p))
        pressures.append(p.pressure_pa)
        if model == options.Model.WHITE:
            if sigma_zeta is None and process is None:
                raise ParameterError(
                    "the white-noise model needs the intensity sigma_zeta or a friction-process "
                    "model (thesis rule: sigma_zeta = sigma_mu(p))"
                )
            if sigma_zeta is None:
                assert process is not None
                sig.append(process.sigma_zeta(_need_pressure(p, "white-noise intensity")))
            elif callable(sigma_zeta):
                sig.append(float(sigma_zeta(_need_pressure(p, "white-noise intensity"))))
            else:
                sig.append(float(sigma_zeta))
            if not (math.isfinite(sig[-1]) and sig[-1] >= 0):
                raise ParameterError(f"sigma_zeta must be finite and >= 0, got {sig[-1]}")
        else:
            sig.append(0.0)
        if model == options.Model.CONTACT:
            if process is None:
                raise ParameterError("the contact-analysis model needs a friction-process model")
            _need_pressure(p, "friction process")
        if x0 is None:
            x0s.append((0.0, p.gamma0))
        elif per_set_x0:
            xi: Any = x0[i]
            x0s.append((float(xi[0]), float(xi[1])))
        else:
            xx: Any = x0
            x0s.append((float(xx[0]), float(xx[1])))
        if not all(math.isfinite(v) for v in x0s[-1]):
            raise ParameterError(f"initial state x0 must be finite, got {x0s[-1]}")
    nsteps = round(sysm.tau_end / dt)
    eff = [thesis_sigma_zeta(s_, p, dt) if white_increment == options.WhiteIncrement.THESIS else s_
           for s_, p in zip(sig, params, strict=True)]
    return _Plan(list(params), laws, sig, eff, pressures, x0s, nsteps)


def thesis_sigma_zeta(sigma_zeta: float, params: OscillatorParameters, dt: float) -> float:
    """σ_ζ,eff = σ_ζ · L ω0 · Δτ: the intensity that printed eq. (4.31) effectively uses.

    (4.31) as printed multiplies the noise by ``Δτ R_k`` (not ``√Δτ R_k``, erratum 4) and,
    read with the dimensional relative velocity ``v_rel = L ω0 (γ0 − X2)`` [m/s] under the
    root (erratum 10), its noise term is
    ``n s √(σ_ζ L ω0 |γ0 − X2|) Δτ R_k = n s √(σ_ζ,eff |γ0 − X2|) √Δτ R_k``:
    the consistent Euler–Maruyama step with intensity ``σ_ζ,eff`` (L in m, ω0 in rad/s,
    taken as numbers; Δτ dimensionless).  It vanishes as Δτ → 0, so it is only a
    reproduction mode (docs/oscillator.md).
    """
    return float(sigma_zeta) * params.velocity_scale * float(dt)


def _need_pressure(p: OscillatorParameters, what: str) -> float:
    pr = p.pressure_pa
    if pr is None:
        raise ParameterError(
            f"the {what} depends on the contact pressure p = N/A; give the stiffness c and the "
            "contact area A (physical parameters or a preset)"
        )
    return pr


def pack_rows(
    params: Sequence[OscillatorParameters],
    laws: Sequence[FrictionLaw],
    sigma: Sequence[float],
    process_dx_m: float = 1.0,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int64]]:
    """The kernels' per-row inputs of parameter sets: ``(prm, lawp, shapes)``, row i from
    ``params[i]``, ``laws[i]`` and the noise intensity ``sigma[i]`` (the only place that knows the
    row layout ``kernels.P_*``; the kernels, ``accurate`` and the benchmarks read it).

    ``process_dx_m``: grid spacing of the contact process [m], stored per row in units of the
    set's length scale L.  ``lawp`` is padded with zeros to the longest law.
    """
    n = len(params)
    maxp = max(len(lw.params) for lw in laws)
    prm = np.zeros((n, _k.N_PRM))
    lawp = np.zeros((n, maxp))
    shapes = np.zeros(n, dtype=np.int64)
    for i, (p, lw) in enumerate(zip(params, laws, strict=True)):
        row = prm[i]
        row[_k.P_GAMMA0] = p.gamma0
        row[_k.P_N] = p.n
        row[_k.P_D] = p.damping_ratio
        row[_k.P_Q] = p.q
        row[_k.P_ETA] = p.eta
        row[_k.P_X30] = 0.0
        row[_k.P_VSCALE] = p.velocity_scale
        row[_k.P_MUS] = lw.static
        row[_k.P_SIGMA] = sigma[i]
        row[_k.P_PROC_DX] = process_dx_m / p.length_scale
        lawp[i, : len(lw.params)] = lw.params
        shapes[i] = lw.shape
    return prm, lawp, shapes


def simulate(
    system: Case | Sequence[Case] | OscillatorParameters | Sequence[OscillatorParameters],
    *,
    model: options.Model | str = options.Model.DETERMINISTIC,
    law: LawSpec | None = None,
    process: ProcessModel | None = None,
    x0: tuple[float, float] | Sequence[tuple[float, float]] | None = None,
    runs: int = 1,
    seed: SeedLike = None,
    noise: options.NoiseOptions | None = None,
    integration: options.IntegrationOptions | None = None,
    output: options.OutputOptions | None = None,
    execution: options.ExecutionOptions | None = None,
) -> SimulationResult:
    """Simulate the friction oscillator for every parameter set and run.

    Parameters
    ----------
    system:
        A :class:`~stochfric.oscillator.case.Case` (its parameters, law, process model, σ_ζ rule
        and time grid), several cases sharing process, time grid and σ_ζ rule, or one or several
        :class:`OscillatorParameters` (dimensionless, eq. 4.6/4.7) with ``law`` and ``process``.
    model:
        ``deterministic`` | ``white`` | ``contact`` (:class:`~.options.Model`; method §5, §5.1, §5.2).
    law:
        Without a case: a :class:`FrictionLaw` or a function of the parameter set returning one (e.g.
        the pressure law of eq. 4.13, whose ``μ_fit`` depends on ``p = N/A``).  Default: law III.
    process:
        Without a case: the friction-process model for ``contact`` (and the σ_ζ rule for ``white``).
    x0:
        Initial ``(x1, x2)``; default ``(0, γ0)`` (sticking at the origin).  One pair for
        all sets or one pair per set.
    runs, seed:
        Monte Carlo runs per set; the root seed (streams: see the module docstring).
    noise:
        :class:`~.options.NoiseOptions`: σ_ζ (a number, or a function of the pressure in Pa; default
        ``process.sigma_zeta(p)``, the thesis rule σ_ζ = σ_μ(p)); the increment rule ``ito`` (ΔW =
        R_k √Δτ, method §7 erratum 4) or ``thesis`` (printed eq. 4.31: σ_ζ,eff = σ_ζ · L ω0 · Δτ,
        :func:`thesis_sigma_zeta`, a Δτ-dependent reproduction mode, white model only); the white-noise
        stream (:class:`~.options.WhiteStream`; the three give different realisations of the same
        statistics, tests/statistical/test_white_stream.py); the path coordinate where the contact
        process is read (``mass``, thesis text §4.1.3; ``relative``, method §7.7; ``position``,
        reproduction mode, ``euler`` only, docs/friction_process.md); common random numbers and the
        stream keys (run ``r`` of set ``i`` draws from spawn key ``(*stream_keys[i], r)``).
    integration:
        :class:`~.options.IntegrationOptions`: ``euler`` (thesis; Euler–Maruyama for white noise),
        ``milstein`` (white noise, strong order 1), ``accurate`` (adaptive DOP853 with events;
        deterministic/contact); τ_end and Δτ (``accurate``: initial step and sampling); its tolerances.
    output:
        :class:`~.options.OutputOptions`: keep every ``save_every``-th grid state (τ, x1, x2); capacity
        for X_gh per trajectory (default ``2 τ_end + 16``).
    execution:
        :class:`~.options.ExecutionOptions`: threads, batch size, progress callback; they change the
        speed, never the numbers.
    """
    noise = noise or options.NoiseOptions()
    integration = integration or options.IntegrationOptions()
    output = output or options.OutputOptions()
    execution = execution or options.ExecutionOptions()
    model_ = _choice(options.Model, model, "model")
    sysm = _system(system, model_, law, process, noise, integration)
    plist, process, tau_end, dt = sysm.params, sysm.process, sysm.tau_end, sysm.dt
    integrator, white_increment, white_stream, path_coordinate = _check_options(
        model_, integration, noise, sysm.white_increment, runs, output)
    warn_list = check_time_step(dt, tau_end, integrator, plist)
    plan = _plan(sysm, model_, x0, white_increment)
    root = as_seed_sequence(seed)
    npar = len(plist)
    keys = check_stream_keys(noise.stream_keys, npar)
    save_every = output.save_every
    nev = int(output.max_events) if output.max_events is not None else int(2 * tau_end) + 16
    nsave = plan.nsteps // save_every + 1 if output.save_trajectory else 0
    out = _allocate_output(npar * runs, nev, nsave)
    ig = integration
    runner = _BatchRunner(
        plan=plan, model=model_, integrator=integrator, process=process, root=root, stream_keys=keys,
        runs=runs,
        common_random_numbers=noise.common_random_numbers, path_mode=_PATH_MODES[path_coordinate],
        white_stream=white_stream, dt=dt, save_every=save_every,
        accurate=_acc.AccurateSettings(float(tau_end), min(dt, ig.max_step), ig.max_step, ig.rtol, ig.atol,
                                       save_every * dt),
        out=out,
    )
    _run_batches(runner, npar * runs, execution.workers, execution.batch_size, execution.progress)
    return _result(runner, model_, integrator, white_increment, path_coordinate, tau_end=tau_end, integration=ig,
                   save_trajectory=output.save_trajectory, warnings=warn_list)


def _result(
    runner: _BatchRunner, model: options.Model, integrator: options.Integrator,
    white_increment: options.WhiteIncrement, path_coordinate: options.PathCoordinate, *, tau_end: float,
    integration: options.IntegrationOptions, save_trajectory: bool, warnings: list[SimulationWarning],
) -> SimulationResult:
    """The :class:`SimulationResult` of the trajectories ``runner`` has run: its outputs shaped per
    parameter set and run, the diagnostics, the warnings of the run (``warnings``, the time step's)
    and of its outcome (:func:`_post_warnings`), and the settings that fix its numbers."""
    plan, out, runs = runner.plan, runner.out, runner.runs
    npar, nev, nsave = len(plan.params), out.x_gh.shape[1], out.traj.shape[1]
    diagnostics = {k: out.diag[:, j].reshape(npar, runs).copy() for k, j in DIAGNOSTICS.items()}
    diagnostics["process_segments"] = runner.segments.reshape(npar, runs).astype(float)
    process = runner.process
    # returned in the result only (``result.warnings``, also in its JSON and NetCDF); callers show
    # them (the CLI prints each on stderr, the studies count them, the report explains them)
    warn_list = warnings + _post_warnings(out.counts, nev, out.diag, model, process, plan.params, runner.path_mode)
    ig = integration
    return SimulationResult(
        params=plan.params,
        x_gh=out.x_gh.reshape(npar, runs, nev),
        t_gh=out.t_gh.reshape(npar, runs, nev),
        stick_count=out.counts.reshape(npar, runs),
        diagnostics=diagnostics,
        trajectory=out.traj.reshape(npar, runs, nsave, 3) if save_trajectory else None,
        model=str(model),
        integrator=str(integrator),
        dt=runner.dt,
        tau_end=tau_end,
        runs=runs,
        seed_entropy=int(runner.root.entropy),  # type: ignore[arg-type]
        versions=package_versions(),
        path_coordinate=str(path_coordinate),
        x0=plan.x0,
        laws=[lw.to_dict() for lw in plan.laws],
        sigma_zeta=plan.sigma,
        process=process.to_dict() if (process is not None and model != options.Model.DETERMINISTIC) else None,
        warnings=warn_list,
        settings={
            "save_every": runner.save_every, "max_events": nev,
            "common_random_numbers": runner.common_random_numbers,
            "rtol": ig.rtol, "atol": ig.atol, "max_step": ig.max_step,
            "spawn_key_layout": "(*stream_key, run); contact process: (*stream_key, run, segment)",
            "stream_keys": runner.stream_keys.tolist(),
            "white_increment": str(white_increment),
            "white_stream": str(runner.white_stream),
            "sigma_zeta_effective": plan.sigma_eff,
        },
    )


#: Result diagnostics name → column of the kernels' diagnostics rows (``kernels.D_*``).
DIAGNOSTICS = {
    "path": _k.D_PATH, "min_slip_path": _k.D_MIN_SLIP_PATH,
    "n_short_slip_phases": _k.D_N_SHORT_SLIP, "n_belt_speed_without_stick": _k.D_N_NO_STICK,
    "x1_final": _k.D_X1, "x2_final": _k.D_X2, "stick_final": _k.D_STICK,
    "n_breakaway": _k.D_N_BREAKAWAY, "n_slip_phases": _k.D_N_SLIP_PHASES,
}


_E = TypeVar("_E", bound=StrEnum)


def _choice(kind: type[_E], value: Any, what: str) -> _E:
    """``value`` as a member of the choice ``kind``; ParameterError naming the choices otherwise."""
    try:
        return kind(value)
    except ValueError:
        raise ParameterError(f"unknown {what} {value!r}; choose one of {[str(v) for v in kind]}") from None


def _check_options(
    model: options.Model, integration: options.IntegrationOptions, noise: options.NoiseOptions,
    white_increment: options.WhiteIncrement | str, runs: Any, output: options.OutputOptions,
) -> tuple[options.Integrator, options.WhiteIncrement, options.WhiteStream, options.PathCoordinate]:
    """Refuse a combination of :func:`simulate` options that has no meaning, saying what to change;
    the choices as their enums."""
    integrator = _choice(options.Integrator, integration.integrator, "integrator")
    if model == options.Model.WHITE and integrator == options.Integrator.ACCURATE:
        raise ParameterError(
            "the white-noise model is an SDE: use integrator 'euler' (Euler–Maruyama) or "
            "'milstein', not 'accurate'"
        )
    if integrator == options.Integrator.MILSTEIN and model != options.Model.WHITE:
        raise ParameterError(
            "'milstein' is the strong order-1 scheme for the white-noise SDE; for the "
            f"{model} model use 'euler' or 'accurate'"
        )
    increment = _choice(options.WhiteIncrement, white_increment, "white-noise increment")
    if increment != options.WhiteIncrement.ITO and model != options.Model.WHITE:
        raise ParameterError(
            f"white_increment '{increment}' applies to the white-noise model only, not '{model}'"
        )
    stream = _choice(options.WhiteStream, noise.white_stream, "white-noise stream")
    path = _choice(options.PathCoordinate, noise.path_coordinate, "path coordinate")
    if path == options.PathCoordinate.POSITION and integrator == options.Integrator.ACCURATE:
        raise ParameterError(
            "path coordinate 'position' (a reproduction mode) is implemented for the fixed-step "
            "'euler' scheme only"
        )
    if isinstance(runs, bool) or not isinstance(runs, int | np.integer) or runs < 1:
        raise ParameterError(f"runs must be a positive integer, got {runs!r}")
    if output.save_every < 1:
        raise ParameterError(f"save_every must be >= 1, got {output.save_every}")
    return integrator, increment, stream, path


def _allocate_output(n_traj: int, capacity: int, nsave: int) -> _k.KernelOutput:
    """The outputs of ``n_traj`` trajectories: X_gh/τ_gh NaN beyond M, counts, saved states, diagnostics."""
    return _k.KernelOutput(
        x_gh=np.full((n_traj, capacity), np.nan), t_gh=np.full((n_traj, capacity), np.nan),
        counts=np.zeros(n_traj, dtype=np.int64), traj=np.zeros((n_traj, nsave, 3)),
        diag=np.zeros((n_traj, _k.N_DIAG)),
    )


#: Process segments a contact run starts with; ``None``: enough for a path of 0.7 γ0·τ_end (the paths of
#: the presets' runs stay below 0.65 γ0·τ_end: both presets, the forces and η of ``reproduce``), so a
#: run is rarely integrated twice and few unused segments are generated; a run that needs more is run
#: again with more.  The numbers do not depend on it (tests/unit/oscillator/test_simulate.py).
FIRST_SEGMENTS: int | None = None
#: The path per belt path γ0·τ_end that :data:`FIRST_SEGMENTS` provides for.
PATH_PER_BELT = 0.7


def first_segments(belt_segments: float) -> int:
    """Process segments a contact run starts with when the belt moves ``belt_segments`` = γ0·τ_end/ℓ
    process lengths during it (:data:`FIRST_SEGMENTS`, :data:`PATH_PER_BELT`); a run is run again with
    more when its path passes ``n − 0.1`` of them."""
    if FIRST_SEGMENTS is not None:
        return FIRST_SEGMENTS
    return max(1, math.ceil(PATH_PER_BELT * belt_segments + 0.1))


@dataclass
class _BatchRunner:
    """Runs trajectories ``lo … hi − 1`` (trajectory ``j`` = parameter set ``j // runs``, run
    ``j % runs``) through the compiled kernel: draws their random input from their own streams
    (:func:`trajectory_seed`), then writes rows ``lo … hi − 1`` of ``out``.

    Contact model: a run starts with one segment of the process (the model's n points); a run
    whose path reaches the end of what was generated is run again with more segments (at least
    twice as many), until its path stays inside.  The segments a run reads are the same however
    many were generated, so its numbers are those of an unbounded, never-repeating realisation
    (``segments`` records how many each run needed)."""

    plan: _Plan
    model: str
    integrator: str
    process: ProcessModel | None
    root: np.random.SeedSequence
    stream_keys: npt.NDArray[np.int64]
    runs: int
    common_random_numbers: bool
    path_mode: int
    white_stream: str
    dt: float
    save_every: int
    accurate: _acc.AccurateSettings
    out: _k.KernelOutput

    def __post_init__(self) -> None:
        noise: dict[str, int] = {options.Model.DETERMINISTIC: _k.NOISE_NONE, options.Model.WHITE: _k.NOISE_WHITE,
                                 options.Model.CONTACT: _k.NOISE_PROCESS}
        self.noise = noise[self.model]
        self.scheme = _k.SCHEME_MILSTEIN if self.integrator == "milstein" else _k.SCHEME_EULER
        contact = self.model == options.Model.CONTACT and self.process is not None
        self.n_proc = round(self.process.length / self.process.dx) if contact else 1  # type: ignore[union-attr]
        self.rows = pack_rows(self.plan.params, self.plan.laws, self.plan.sigma_eff,
                              self.process.dx if contact else 1.0)  # type: ignore[union-attr]
        self.x0 = np.array(self.plan.x0, dtype=np.float64).reshape(len(self.plan.params), 2)
        self.philox = self.noise == _k.NOISE_WHITE and self.white_stream != "pcg64"
        self.white_source = (_k.WHITE_ZIGGURAT if self.white_stream == "philox-ziggurat"
                             else _k.WHITE_PHILOX if self.philox else _k.WHITE_GIVEN)
        self.spectral = (_SpectralBatch(self.process) if self.noise == _k.NOISE_PROCESS
                         and getattr(type(self.process), "generate", None) in _SPECTRAL_GENERATE else None)
        # segments grow only where the path coordinate runs on ('position' reads at x1: periodic)
        self.extend = self.noise == _k.NOISE_PROCESS and self.path_mode != _k.PATH_POSITION
        self.segments = np.ones(self.out.counts.shape[0], dtype=np.int64)

    def _tails(self, sets: npt.NDArray[np.int64], rr: npt.NDArray[np.int64], *extra: npt.NDArray[np.int64]
               ) -> npt.NDArray[np.int64]:
        """Spawn-key tails ``(*stream key, run, *extra)`` of the trajectories ``(sets[j], rr[j])``."""
        keys = self.stream_keys[np.zeros_like(sets) if self.common_random_numbers else sets]
        return np.column_stack([keys, rr, *extra]).astype(np.int64)

    def _random_input(
        self, sets: npt.NDArray[np.int64], rr: npt.NDArray[np.int64], n_seg: int
    ) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.uint64]]:
        """The increments ``dw`` (white noise from a buffer), process realisations (``n_seg``
        segments each) and Philox keys of the trajectories ``(sets[j], rr[j])``."""
        b = sets.size
        nsteps = self.plan.nsteps
        buffer_white = self.noise == _k.NOISE_WHITE and not self.philox
        dw = np.empty((b, nsteps)) if buffer_white else np.zeros((b, 1))  # every row is filled below
        proc = np.zeros((b, n_seg * self.n_proc))
        # the key of trajectory (i, r): its spawned seed's first 64 bits (the same as
        # _ph.trajectory_key(trajectory_seed(root, k_i, r)), computed in compiled code)
        keys = (_ph.trajectory_keys(self.root, self._tails(sets, rr)) if self.philox
                else np.zeros(1, dtype=np.uint64))
        if self.spectral is not None:
            seg = np.tile(np.arange(n_seg), b)
            rows = np.repeat(np.arange(b), n_seg)
            prs = [self.plan.pressures[int(sets[j])] for j in rows]
            flat = np.empty((b * n_seg, self.n_proc))
            self.spectral.fill(flat, self.root, self._tails(sets[rows], rr[rows], seg),
                               [float(p_) for p_ in prs if p_ is not None])
            proc[:] = flat.reshape(b, n_seg * self.n_proc)
        elif self.noise != _k.NOISE_NONE and not self.philox:
            sq = math.sqrt(self.dt)
            tails = self._tails(sets, rr)
            for j in range(b):
                key, run = tuple(int(v) for v in tails[j, :-1]), int(tails[j, -1])
                if self.noise == _k.NOISE_WHITE:
                    rng = np.random.Generator(np.random.PCG64(trajectory_seed(self.root, key, run)))
                    rng.standard_normal(out=dw[j])
                    dw[j] *= sq
                    continue
                assert self.process is not None
                pr = self.plan.pressures[int(sets[j])]
                assert pr is not None
                for s_ in range(n_seg):
                    rng = np.random.Generator(np.random.PCG64(trajectory_seed(self.root, key, run, s_)))
                    vals = np.asarray(self.process.generate(pr, rng), dtype=np.float64)
                    if vals.shape != (self.n_proc,):
                        raise RuntimeError(
                            f"process realisation has shape {vals.shape}, expected ({self.n_proc},)"
                        )
                    proc[j, s_ * self.n_proc:(s_ + 1) * self.n_proc] = vals
        return dw, proc, keys

    def _run_rows(self, idx: npt.NDArray[np.int64], n_seg: int, out: _k.KernelOutput) -> None:
        """Trajectories ``idx`` with ``n_seg`` process segments, written to ``out`` (row j ↔ idx[j])."""
        sets = idx // self.runs
        rr = idx % self.runs
        dw, proc, keys = self._random_input(sets, rr, n_seg)
        prm, lawp, shapes = self.rows
        rows = _k.KernelRows(prm[sets], shapes[sets], lawp[sets], self.x0[sets], proc,
                             np.full(idx.size, n_seg * self.n_proc, dtype=np.int64))
        if self.integrator == "accurate":
            _acc.run_accurate_batch(rows, out, self.accurate, self.noise, self.path_mode)
        else:
            _k.run_fixed_step_batch(
                rows, out, _k.FixedStepGrid(self.plan.nsteps, self.dt, self.save_every), self.scheme,
                self.noise, self.path_mode,
                _k.WhiteInput(self.white_source, dw, keys),
            )

    def _exhausted(self, idx: npt.NDArray[np.int64], diag: npt.NDArray[np.float64], n_seg: int
                   ) -> npt.NDArray[np.bool_]:
        """Runs whose path came within a tenth of a segment of the end of ``n_seg`` segments
        (beyond the end the kernel would wrap round to the start; the spare tenth covers the
        trial stages of an adaptive step, which read ahead of the accepted path)."""
        pdx = self.rows[0][idx // self.runs, _k.P_PROC_DX]
        return diag[:, _k.D_PATH] >= (n_seg * self.n_proc - 1 - 0.1 * self.n_proc) * pdx

    def _first_segments(self, idx: npt.NDArray[np.int64]) -> int:
        """Segments the runs ``idx`` start with (:data:`FIRST_SEGMENTS`)."""
        if not self.extend:
            return 1
        if FIRST_SEGMENTS is not None:
            return FIRST_SEGMENTS
        prm = self.rows[0][idx // self.runs]
        belt = float(np.max(prm[:, _k.P_GAMMA0] / prm[:, _k.P_PROC_DX])) * self.plan.nsteps * self.dt
        return first_segments(belt / self.n_proc)

    def __call__(self, lo: int, hi: int) -> None:
        o = self.out
        idx = np.arange(lo, hi)
        n_seg = self._first_segments(idx)
        self._run_rows(idx, n_seg, _k.KernelOutput(o.x_gh[lo:hi], o.t_gh[lo:hi], o.counts[lo:hi],
                                                   o.traj[lo:hi], o.diag[lo:hi]))
        self.segments[lo:hi] = n_seg
        while self.extend:
            again = idx[self._exhausted(idx, o.diag[idx], n_seg)]
            if again.size == 0:
                break
            pdx = self.rows[0][again // self.runs, _k.P_PROC_DX]
            need = int(np.max(np.ceil(o.diag[again, _k.D_PATH] / (self.n_proc * pdx)))) + 2
            n_seg = max(2 * n_seg, need)
            tmp = _allocate_output(again.size, o.x_gh.shape[1], o.traj.shape[1])
            self._run_rows(again, n_seg, tmp)
            o.x_gh[again], o.t_gh[again], o.counts[again] = tmp.x_gh, tmp.t_gh, tmp.counts
            o.traj[again], o.diag[again] = tmp.traj, tmp.diag
            self.segments[again] = n_seg
            idx = again


def _run_batches(
    run_batch: Callable[[int, int], None], n_traj: int, workers: int | None, batch_size: int,
    progress: Callable[[int, int], None] | None,
) -> None:
    """Run ``run_batch(lo, hi)`` over ``0 … n_traj`` in batches on ``workers`` threads (default: all
    cores); ``progress(done, total)`` after every batch, in order.  The kernels release the GIL."""
    nworkers = workers if workers is not None else (os.cpu_count() or 1)
    if nworkers < 1:
        raise ParameterError(f"workers must be >= 1, got {workers}")
    if isinstance(batch_size, bool) or not isinstance(batch_size, int | np.integer) \
            or batch_size < 1:
        raise ParameterError(f"batch_size must be a positive integer, got {batch_size!r}")
    # at most batch_size per call, but at least ~4 batches per worker so that the threads
    # stay balanced on small ensembles (the numbers never depend on the batching)
    bsz = int(batch_size)
    if nworkers > 1:
        bsz = max(1, min(bsz, -(-n_traj // (4 * nworkers))))
    bounds = [(lo, min(lo + bsz, n_traj)) for lo in range(0, n_traj, bsz)]
    done = 0
    if nworkers == 1 or len(bounds) == 1:
        for lo, hi in bounds:
            run_batch(lo, hi)
            done += hi - lo
            if progress is not None:
                progress(done, n_traj)
        return
    with ThreadPoolExecutor(max_workers=nworkers) as pool:
        futures = [pool.submit(run_batch, lo, hi) for lo, hi in bounds]
        try:
            for f, (lo, hi) in zip(futures, bounds, strict=True):
                f.result()
                done += hi - lo
                if progress is not None:
                    progress(done, n_traj)
        except BaseException:
            for f in futures:
                f.cancel()
            raise


def _post_warnings(
    counts: npt.NDArray[np.int64],
    nev: int,
    diag: npt.NDArray[np.float64],
    model: str,
    process: ProcessModel | None,
    params: list[OscillatorParameters],
    path_mode: int = _k.PATH_MASS,
) -> list[SimulationWarning]:
    out: list[SimulationWarning] = []
    over = int(np.sum(counts > nev))
    if over:
        out.append(SimulationWarning(
            "event-buffer-full",
            f"{over} trajectories had more than max_events = {nev} slip->stick transitions; "
            "stick_count is exact but only the first X_gh were stored — raise max_events",
        ))
    stamp = tuple(getattr(process, "not_credible", ())) if process is not None else ()
    if stamp and model != options.Model.DETERMINISTIC:
        out.append(SimulationWarning(
            "process-not-credible",
            f"the friction-process model was written with --accept-not-credible: {'; '.join(stamp)}",
        ))
    if model == options.Model.CONTACT and process is not None:
        # 'position' (reproduction mode) reads the process at x1, periodically continued; in the
        # path coordinates the process never repeats (independent segments, _BatchRunner)
        if path_mode == _k.PATH_POSITION and not getattr(process, "grid_is_periodic", True):
            out.append(SimulationWarning(
                "process-grid-not-periodic",
                f"the process grid ({process.length:.4g} m / dx {process.dx:.4g} m) does not span "
                "exactly one period: its periodic continuation has a seam; choose dx = length/n",
            ))
        n_short = int(np.sum(diag[:, _k.D_N_SHORT_SLIP]))
        n_ph = int(np.sum(diag[:, _k.D_N_SLIP_PHASES]))
        if n_short:
            out.append(SimulationWarning(
                "slip-shorter-than-grid",
                f"{n_short} of {n_ph} slip phases ({100 * n_short / max(n_ph, 1):.1f} %) covered "
                f"less than one process grid spacing dx = {process.dx:.3g} m: there the friction "
                "process is only read between two grid points (thesis 4.1.3); use a finer "
                "process (smaller dx) for oscillations this small",
            ))
    return out

"""Side by side at equal settings: stochfric's ensemble kernels vs diffrax and plain compiled loops (issues 13, 32).

Usage::

    python benchmarks/bench_compare.py [--quick] [--json OUT]

Needs the optional extra ``bench`` (``pip install -e '.[bench]'``: jax, diffrax) for the
diffrax and jax rows; without it they are skipped with a note, and the other rows still run.

The problem is the brake preset of ``bench_oscillator.py`` (N = 5600 N, D = 5·10⁻⁶, pressure law
4.13, start sticking at x1 = 0), Δτ = 0.005.  The whole benchmark process is pinned to one core
(``sched_setaffinity``, set before JAX creates its thread pools, restored at the end).

**Equal settings.**  Every ensemble row integrates the SAME number of trajectories (``runs``:
1024 full, 256 ``--quick``) over the SAME number of steps (τ = 50: 10,000 steps full; τ = 20:
4,000 ``--quick``) of the same Δτ from the same initial state, and keeps only the final state:

* **stochfric** — :func:`stochfric.oscillator.integrate.simulate` with ``workers=1`` and its
  default output (``OutputOptions(save_trajectory=False)``): no trajectory is stored; it keeps the
  final state and counters (the diagnostics row, 9 numbers per trajectory) and, as part of its
  answer, the position and time of every slip→stick transition (X_gh, τ_gh: written at the events
  only, 7 per trajectory in the full run).  ``deterministic``/``contact``: the thesis's Euler method with the
  exact stick/slip switching; ``white``: Euler–Maruyama with the in-kernel Philox-ziggurat stream.
  End to end: the call includes deriving the per-trajectory Philox keys, generating the contact
  process realisations and building the result.
* **stochfric kernel** — the compiled batch call alone (``kernels.run_fixed_step_batch``) with the
  same rows and outputs ``simulate`` passes, preallocated; the contact model with the same one
  process period per trajectory that the other rows get (the kernel continues it periodically).
  Its final state equals ``simulate``'s bit for bit (the "check" column).
* **diffrax** (JAX on CPU, x64, ``vmap`` over the trajectories, ``jit``) — the closest it gets without
  stick events: the same equations with ``sign(v_rel)`` regularised to ``tanh(v_rel/ε)``,
  ``diffrax.Euler`` at the same fixed Δτ (with a ``ControlTerm`` and ``UnsafeBrownianPath``:
  Euler–Maruyama for the white model), ε = 4 n μ_s Δτ (the smallest ε at which explicit Euler is
  stable on the regularised stick branch, |∂f/∂x2| Δτ = n μ/ε Δτ < ½).  ``SaveAt(t1=True)``: the
  final state only.  The contact model carries the path as a third state and reads μ̂ by linear
  interpolation (periodic).
* **floors** — plain compiled loops of the same Euler recurrence, final state only, updated in
  place: the slip equation (4.7) with ``s = sign(γ0 − x2)`` (branch-free), no stick phase and no
  events (a cost floor, not a solver: near the belt speed it chatters instead of sticking), the
  constants as scalars.  ``numba loop``: ``@njit``, steps outer, the trajectories inner (so that
  LLVM vectorises across them); white noise from the package's own Philox-ziggurat generator
  (``ziggurat.fill_pair_ziggurat``, as the kernel draws it).  ``jax loop``: ``jax.lax.fori_loop``
  of one trajectory under ``vmap``/``jit``; white noise ``jax.random.normal(fold_in(key_r, k))``
  per trajectory and step.  ``jax loop (tanh)``: the same loop with diffrax's regularised sign, i.e.
  exactly diffrax's recurrence without diffrax (its final state is compared with diffrax's).  The
  contact floors add the path (``path += |x2| Δτ``) and μ̂(path) by linear interpolation with
  periodic continuation (a gather per step).

Compile/JIT time is excluded for all: every runner is called once before timing.  The timing runs
``rounds`` alternating rounds, one call of every runner per round, in one process, and keeps the
best of each (and the median, to show the scatter).  The measure is the CPU time of the process
(``time.process_time``; the process is pinned to one core, so JAX's threads are counted on that core
too): on a machine shared with other jobs it does not count the time the core ran someone else's
work, which wall time does; the wall time of the best round is printed beside it.

**solve_ivp** (:func:`scipy.integrate.solve_ivp` with terminal events for the slip→stick transitions
and a root search for breakaway; ``reference.simulate_solve_ivp`` for the deterministic model, the
same scheme with μ̂(path) for the contact model here) is the exception: one trajectory at a time,
``ivp_runs`` of them (its time is linear in the number of trajectories; at 1024 it would run for
hours), DOP853 at rtol 1e-12 (the package's reference setting) and RK45 at rtol 1e-6 (a user's
setting).  Not an SDE solver: no white-noise row.

Rates are trajectory-steps per second, a "step" being one Δτ of simulated time.  The ratios are
printed as "stochfric / TOOL" = rate of stochfric ÷ rate of TOOL (> 1: stochfric is faster) and, for
the floors, also as the time ratio stochfric ÷ floor, from the best rounds.  The targets (issue 32):
deterministic and contact at least 1.5× faster than diffrax and within 1.5× of the faster floor; white
at least 15× faster than diffrax; judged on the best rounds, with the median of the per-round ratios
beside them (two runs timed next to each other: steadier on a shared machine).  The "check" column
compares the first slip→stick position with stochfric's ``accurate`` integrator (DOP853 with events;
diffrax: x1 where x2 first returns to 0.95 γ0, from an untimed single trajectory saved every 10
steps), and final states between rows that integrate the same recurrence: stochfric's kernel and
``simulate`` bit for bit; diffrax and the tanh loop to rounding; the numba and jax floors to rounding
that the chattering sign amplifies over the run (6·10⁻¹⁶ relative at τ = 0.5, 10⁻¹¹ at τ = 20, up to
10⁻² for the contact model at τ = 50).
"""

from __future__ import annotations

import argparse
import functools
import importlib.util
import json
import math
import os
import statistics
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from scipy.integrate import solve_ivp

from stochfric import vector_width
from stochfric.oscillator import kernels as _k
from stochfric.oscillator import reference
from stochfric.oscillator.integrate import pack_rows, simulate, trajectory_seed
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, Integrator
from stochfric.random import philox as _ph
from stochfric.random.ziggurat import fill_pair_ziggurat, finish_pair_ziggurat

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_oscillator import DT, Case, brake_case, machine_info

SIZES: dict[str, dict[str, Any]] = {
    "full": dict(runs=1024, tau_end=50.0, rounds=7, ivp_runs=1, ivp_repeats=2, dense_check=True),
    "quick": dict(runs=256, tau_end=20.0, rounds=3, ivp_runs=1, ivp_repeats=1, dense_check=True),
    "smoke": dict(runs=4, tau_end=1.0, rounds=1, ivp_runs=1, ivp_repeats=1, dense_check=False),
}
MODELS = ("deterministic", "white", "contact")
#: issue 32: stochfric at least this many times faster than diffrax, per model
TARGET_SPEEDUP = {"deterministic": 1.5, "contact": 1.5, "white": 15.0}
#: issue 32: stochfric's time at most this multiple of the faster floor (deterministic, contact)
TARGET_FLOOR = 1.5
FLOOR_TOOLS = ("numba loop", "jax loop")

Floats = npt.NDArray[np.float64]


@dataclass
class Row:
    """One timed configuration: ``cpu_s`` the least CPU time of the process over the rounds (the rate's
    basis), ``wall_s`` the wall time of that round, ``rounds_s`` the CPU time of every round."""

    model: str
    tool: str
    setting: str
    runs: int
    steps: int
    wall_s: float
    cpu_s: float
    rate: float
    check: str = ""
    rounds_s: list[float] = field(default_factory=list)

    @property
    def ns(self) -> float:
        """ns of CPU time per trajectory-step (best round)."""
        return 1e9 / self.rate


@dataclass
class Comparison:
    """Rows, ratios, targets, checks, the machine and notes (skipped tools)."""

    size: str
    rows: list[Row] = field(default_factory=list)
    ratios: dict[str, float] = field(default_factory=dict)
    targets: dict[str, dict[str, Any]] = field(default_factory=dict)
    checks: dict[str, float] = field(default_factory=dict)
    machine: dict[str, Any] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {"size": self.size, "rows": [{**asdict(r), "ns_per_step": r.ns} for r in self.rows],
                "ratios": self.ratios, "targets": self.targets, "checks": self.checks,
                "machine": self.machine, "notes": self.notes}


@dataclass
class Runner:
    """One ensemble configuration: ``call`` runs it once (compiled), ``final`` reads the final x1 of
    every trajectory from what the last call returned."""

    model: str
    tool: str
    setting: str
    call: Callable[[], Any]
    final: Callable[[Any], Floats]
    last: Any = None


def _best(fn: Callable[[], Any], repeats: int) -> tuple[float, float, Any]:
    """(wall, CPU) of the call with the least CPU time of ``repeats``, and what the last call returned."""
    best = (math.inf, math.inf)
    res = None
    for _ in range(max(1, repeats)):
        c0, t0 = time.process_time(), time.perf_counter()
        res = fn()
        t1, c1 = time.perf_counter(), time.process_time()
        if c1 - c0 < best[1]:
            best = (t1 - t0, c1 - c0)
    return best[0], best[1], res


def _sigma(case: Case) -> float:
    assert case.process is not None and case.params.pressure_pa is not None
    return case.process.sigma_zeta(case.params.pressure_pa)


def _process_rows(case: Case, runs: int, seed: int = 1) -> Floats:
    """The process realisations ``simulate`` uses for runs ``0..runs-1`` (set 0, first segment)."""
    assert case.process is not None and case.params.pressure_pa is not None
    root = np.random.SeedSequence(seed)
    return np.stack([case.process.generate(
        case.params.pressure_pa, np.random.Generator(np.random.PCG64(trajectory_seed(root, (0,), r, 0))))
        for r in range(runs)])


def _white_keys(runs: int, seed: int = 1) -> npt.NDArray[np.uint64]:
    """The Philox keys ``simulate`` derives for runs ``0..runs-1`` of parameter set 0."""
    return _ph.trajectory_keys(np.random.SeedSequence(seed),
                               np.column_stack([np.zeros(runs, dtype=np.int64), np.arange(runs)]))


@dataclass(frozen=True)
class Recurrence:
    """The constants of the Euler recurrence of the brake case, as plain numbers (the floors)."""

    g0: float
    nn: float
    dd2: float
    vs: float
    p0: float
    p1: float
    p2: float
    p3: float
    eps: float  #: diffrax's regularisation width ε = 4 n μ_s Δτ
    sigma: float
    ito: float  #: Itô drift correction per s: −n² σ_ζ/4
    pdx: float  #: process grid spacing / L
    nsteps: int
    dt: float


def recurrence(case: Case, tau_end: float) -> Recurrence:
    p, law = case.params, case.law
    lp = law.param_array
    p0, p1, p2, p3 = (float(lp[0]), float(lp[1]), float(lp[2]), float(lp[3])) if lp.size == 4 \
        else (float(lp[0]), 0.0, 0.0, 0.0)
    sigma = _sigma(case)
    assert case.process is not None
    return Recurrence(g0=p.gamma0, nn=p.n, dd2=2.0 * p.damping_ratio, vs=p.velocity_scale, p0=p0, p1=p1,
                      p2=p2, p3=p3, eps=4.0 * p.n * law.static * DT, sigma=sigma, ito=-0.25 * p.n * p.n * sigma,
                      pdx=case.process.dx / p.length_scale, nsteps=round(tau_end / DT), dt=DT)


# --- the floors: plain compiled loops (numba) ---------------------------------------------------
# Steps outer, trajectories inner: the inner loop is branch-free and LLVM vectorises it across the
# trajectories (AVX2: 4 lanes, AVX-512: 8).  No stick phase, no events, final state only.

@numba.njit(error_model="numpy")
def floor_deterministic(x1: Floats, x2: Floats, nsteps: int, dt: float, g0: float, nn: float, dd2: float,
                        vs: float, p0: float, p1: float, p2: float, p3: float) -> None:  # pragma: no cover
    """``nsteps`` explicit Euler steps of the slip equation (4.7), ``s = sign(γ0 − x2)``, in place."""
    for _ in range(nsteps):
        for j in range(x1.shape[0]):
            a1 = x1[j]
            a2 = x2[j]
            vr = g0 - a2
            s = 1.0 if vr > 0.0 else -1.0
            v = vs * abs(vr)
            mu = p0 / (1.0 + p1 * v) + p2 + p3 * v * v
            x1[j] = a1 + a2 * dt
            x2[j] = a2 + (-a1 - dd2 * a2 + nn * mu * s) * dt


@numba.njit(error_model="numpy")
def floor_contact(x1: Floats, x2: Floats, path: Floats, proc: Floats, nsteps: int, dt: float, g0: float,
                  nn: float, dd2: float, vs: float, p0: float, p1: float, p2: float, p3: float,
                  pdx: float) -> None:  # pragma: no cover
    """As :func:`floor_deterministic` with μ = μ_k + μ̂(path), μ̂ read by linear interpolation of
    ``proc[j]`` (periodic continuation; a 32-bit index: with a 64-bit one the loop takes 1.7× as long
    on AVX2) and the mass path ``path += |x2| Δτ``."""
    nproc = np.int32(proc.shape[1])
    for _ in range(nsteps):
        for j in range(x1.shape[0]):
            a1 = x1[j]
            a2 = x2[j]
            u = path[j] / pdx
            fl = math.floor(u)
            i0 = np.int32(fl)
            i0 = i0 % nproc if i0 >= nproc else i0
            i1 = i0 + 1 if i0 + 1 < nproc else 0
            w = u - fl
            muhat = (1.0 - w) * proc[j, i0] + w * proc[j, i1]
            vr = g0 - a2
            s = 1.0 if vr > 0.0 else -1.0
            v = vs * abs(vr)
            mu = p0 / (1.0 + p1 * v) + p2 + p3 * v * v + muhat
            x1[j] = a1 + a2 * dt
            x2[j] = a2 + (-a1 - dd2 * a2 + nn * mu * s) * dt
            path[j] += abs(a2) * dt


@numba.njit(error_model="numpy")
def floor_white(x1: Floats, x2: Floats, keys: npt.NDArray[np.uint64], nsteps: int, dt: float, g0: float,
                nn: float, dd2: float, vs: float, p0: float, p1: float, p2: float, p3: float, sigma: float,
                ito: float) -> None:  # pragma: no cover
    """Euler–Maruyama of the white-noise model (method §5.1; Itô drift ``a + s·ito``, diffusion
    ``n s √(σ_ζ |γ0 − x2|)``), increments ``R_k √Δτ`` from the Philox-ziggurat stream of ``keys[j]``
    drawn for steps k and k + 1 at once, as the kernel draws them."""
    n = x1.shape[0]
    sqdt = math.sqrt(dt)
    wk = np.zeros(n)
    odd = np.zeros(n)
    miss = np.zeros((2, n), dtype=np.uint64)
    for k in range(nsteps):
        if k & 1:
            dw = odd
        else:
            if fill_pair_ziggurat(keys, np.uint64(k >> 1), sqdt, wk, odd, miss):
                finish_pair_ziggurat(keys, np.uint64(k >> 1), sqdt, wk, odd, miss)
            dw = wk
        for j in range(n):
            a1 = x1[j]
            a2 = x2[j]
            vr = g0 - a2
            s = 1.0 if vr > 0.0 else -1.0
            av = abs(vr)
            v = vs * av
            mu = p0 / (1.0 + p1 * v) + p2 + p3 * v * v
            drift = -a1 - dd2 * a2 + nn * mu * s
            x1[j] = a1 + a2 * dt
            x2[j] = a2 + (drift + s * ito) * dt + nn * s * math.sqrt(sigma * av) * dw[j]


def numba_floor(model: str, rc: Recurrence, runs: int, x0: tuple[float, float],
                proc: Floats | None) -> Runner:
    base = (rc.nsteps, rc.dt, rc.g0, rc.nn, rc.dd2, rc.vs, rc.p0, rc.p1, rc.p2, rc.p3)
    keys = _white_keys(runs)

    def call() -> Floats:
        x1 = np.full(runs, x0[0])
        x2 = np.full(runs, x0[1])
        if model == "deterministic":
            floor_deterministic(x1, x2, *base)
        elif model == "contact":
            assert proc is not None
            floor_contact(x1, x2, np.zeros(runs), proc, *base, rc.pdx)
        else:
            floor_white(x1, x2, keys, *base, rc.sigma, rc.ito)
        return x1

    return Runner(model, "numba loop", "@njit, steps × trajectories, sign(v_rel), no events", call,
                  lambda out: np.asarray(out))


# --- the floors in JAX, and diffrax ----------------------------------------------------------------

def have_jax() -> bool:
    return importlib.util.find_spec("jax") is not None


def have_diffrax() -> bool:
    return have_jax() and importlib.util.find_spec("diffrax") is not None


def _jax_inputs(model: str, rc: Recurrence, runs: int, x0: tuple[float, float],
                proc: Floats | None) -> tuple[Any, Any, Any]:
    """Per-trajectory initial states (the path as a third state for the contact model), keys and
    process rows, as JAX arrays (every one batched over the trajectories)."""
    import jax
    import jax.numpy as jnp

    y0s = np.zeros((runs, 3 if model == "contact" else 2))
    y0s[:, 0], y0s[:, 1] = x0
    keys = jax.random.split(jax.random.PRNGKey(1), runs)
    args = jnp.asarray(proc if proc is not None else np.zeros((runs, 1)))
    return jnp.asarray(y0s), keys, args


def _jax_mu(rc: Recurrence, x2: Any, path: Any, proc: Any, contact: bool) -> Any:
    """μ_k(|v_rel|) (+ μ̂(path), linear interpolation, periodic) in JAX."""
    import jax.numpy as jnp

    v = rc.vs * jnp.abs(rc.g0 - x2)
    mu = rc.p0 / (1.0 + rc.p1 * v) + rc.p2 + rc.p3 * v * v
    if contact:
        u = path / rc.pdx
        i = jnp.floor(u)
        w = u - i
        i0 = i.astype(jnp.int32)
        mu = mu + (1 - w) * jnp.take(proc, i0, mode="wrap") + w * jnp.take(proc, i0 + 1, mode="wrap")
    return mu


def jax_floor(model: str, rc: Recurrence, runs: int, x0: tuple[float, float], proc: Floats | None, *,
              regularised: bool = False) -> Runner:
    """``jax.lax.fori_loop`` of the Euler recurrence for one trajectory, under ``vmap`` and ``jit``."""
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    contact, white = model == "contact", model == "white"
    sqdt = math.sqrt(rc.dt)

    def one(key: Any, y0: Any, pr: Any) -> Any:
        def body(k: Any, y: Any) -> Any:
            x1, x2 = y[0], y[1]
            vr = rc.g0 - x2
            s = jnp.tanh(vr / rc.eps) if regularised else jnp.where(vr > 0.0, 1.0, -1.0)
            mu = _jax_mu(rc, x2, y[2] if contact else None, pr, contact)
            f = -x1 - rc.dd2 * x2 + rc.nn * mu * s
            if white:
                dw = jax.random.normal(jax.random.fold_in(key, k), dtype=jnp.float64) * sqdt
                x2n = x2 + (f + s * rc.ito) * rc.dt + rc.nn * s * jnp.sqrt(rc.sigma * jnp.abs(vr)) * dw
            else:
                x2n = x2 + f * rc.dt
            x1n = x1 + x2 * rc.dt
            if contact:
                return jnp.stack([x1n, x2n, y[2] + jnp.abs(x2) * rc.dt])
            return jnp.stack([x1n, x2n])

        return jax.lax.fori_loop(0, rc.nsteps, body, y0)

    y0, keys, args = _jax_inputs(model, rc, runs, x0, proc)
    fn = jax.jit(jax.vmap(one))

    def call() -> Any:
        return fn(keys, y0, args).block_until_ready()

    setting = ("fori_loop, vmap, tanh-regularised sign (diffrax's recurrence)" if regularised
               else "fori_loop, vmap, sign(v_rel), no events")
    return Runner(model, "jax loop (tanh)" if regularised else "jax loop", setting, call,
                  lambda out: np.asarray(out)[:, 0])


def diffrax_runner(model: str, rc: Recurrence, runs: int, x0: tuple[float, float], proc: Floats | None, *,
                   dense: bool = False) -> Runner:
    """A compiled ``vmap``-ped diffrax ensemble of ``runs`` trajectories; ``SaveAt(t1=True)`` (final
    state only), or with ``dense`` every 10th step (the untimed check)."""
    import diffrax
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    tau_end = rc.nsteps * rc.dt
    contact, white = model == "contact", model == "white"
    sigma = rc.sigma if white else 0.0

    def drift(t: Any, y: Any, args: Any) -> Any:
        vr = rc.g0 - y[1]
        s = jnp.tanh(vr / rc.eps)
        mu = _jax_mu(rc, y[1], y[2] if contact else None, args, contact)
        f = -y[0] - rc.dd2 * y[1] + rc.nn * mu * s + (s * rc.ito if white else 0.0)
        if contact:
            return jnp.stack([y[1], f, jnp.abs(y[1])])
        return jnp.stack([y[1], f])

    save = diffrax.SaveAt(ts=jnp.linspace(0.0, tau_end, rc.nsteps // 10 + 1)) if dense else diffrax.SaveAt(t1=True)

    def one(key: Any, y0: Any, args: Any) -> Any:
        if white:
            bm = diffrax.UnsafeBrownianPath(shape=(), key=key)

            def diffusion(t: Any, y: Any, args: Any) -> Any:
                vr = rc.g0 - y[1]
                return jnp.stack([0.0, rc.nn * jnp.tanh(vr / rc.eps) * jnp.sqrt(sigma * jnp.abs(vr))])

            terms: Any = diffrax.MultiTerm(diffrax.ODETerm(drift), diffrax.ControlTerm(diffusion, bm))
        else:
            terms = diffrax.ODETerm(drift)
        sol = diffrax.diffeqsolve(terms, diffrax.Euler(), 0.0, tau_end, rc.dt, y0, args=args,
                                  saveat=save, max_steps=rc.nsteps + 16,
                                  adjoint=diffrax.ForwardMode())  # no gradients needed
        return sol.ys

    y0, keys, args = _jax_inputs(model, rc, runs, x0, proc)
    fn = jax.jit(jax.vmap(one))

    def call() -> Any:
        return fn(keys, y0, args).block_until_ready()

    setting = "Euler" + ("–Maruyama" if white else "") + ", vmap, tanh-regularised sign, SaveAt(t1)"
    return Runner(model, "diffrax", setting, call, lambda out: np.asarray(out)[:, -1, 0])


def _first_return(ys: Floats, g0: float) -> float:
    """x1 where x2 first comes back within 5 % of γ0 after the first slip (x2 < γ0/2): the
    regularised model has no stick event, only a creep near γ0 (sampled every 10 steps)."""
    x1, x2 = ys[:, 0], ys[:, 1]
    left = np.flatnonzero(x2 < 0.5 * g0)
    if left.size == 0:
        return math.nan
    back = np.flatnonzero(x2[left[0]:] >= 0.95 * g0)
    return float(x1[left[0] + back[0]]) if back.size else math.nan


# --- stochfric ------------------------------------------------------------------------------------

def stochfric_runner(case: Case, model: str, runs: int, tau_end: float) -> Runner:
    """``simulate(workers=1)`` with its default output: final state, counters and X_gh only."""

    def call() -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return simulate(case.params, model=model, law=case.law, process=case.process, x0=case.x0, runs=runs,
                            seed=1, integration=IntegrationOptions(integrator=Integrator.EULER, tau_end=tau_end, dt=DT),
                            execution=ExecutionOptions(workers=1))

    setting = "simulate, euler" + (" (EM, Philox-ziggurat)" if model == "white" else ", exact stick events")
    return Runner(model, "stochfric", setting, call, lambda res: res.diagnostics["x1_final"][0])


def kernel_runner(case: Case, model: str, runs: int, tau_end: float, proc: Floats | None) -> Runner:
    """``kernels.run_fixed_step_batch`` alone with the rows and outputs ``simulate`` passes
    (preallocated; no trajectory rows), white noise drawn in the kernel from simulate's keys."""
    nsteps = round(tau_end / DT)
    sigma = _sigma(case) if model == "white" else 0.0
    pdx_m = case.process.dx if (model == "contact" and case.process is not None) else 1.0
    prm, lawp, shapes = pack_rows([case.params] * runs, [case.law] * runs, [sigma] * runs, pdx_m)
    x0 = np.tile(np.asarray(case.x0, dtype=np.float64), (runs, 1))
    nev = int(2 * tau_end) + 16
    pr = proc if proc is not None else np.zeros((runs, 1))
    rows = _k.KernelRows(prm, shapes, lawp, x0, pr, np.full(runs, pr.shape[1], dtype=np.int64))
    out = _k.KernelOutput(np.full((runs, nev), np.nan), np.full((runs, nev), np.nan), np.zeros(runs, dtype=np.int64),
                          np.zeros((runs, 0, 3)), np.zeros((runs, _k.N_DIAG)))
    grid = _k.FixedStepGrid(nsteps, DT, 10)
    white = (_k.WhiteInput(_k.WHITE_ZIGGURAT, np.zeros((runs, 1)), _white_keys(runs)) if model == "white"
             else _k.WhiteInput(_k.WHITE_GIVEN, np.zeros((runs, 1)), np.zeros(runs, dtype=np.uint64)))
    noise = {"deterministic": _k.NOISE_NONE, "white": _k.NOISE_WHITE, "contact": _k.NOISE_PROCESS}[model]

    def call() -> Floats:
        _k.run_fixed_step_batch(rows, out, grid, _k.SCHEME_EULER, noise, _k.PATH_MASS, white)
        return out.diag[:, _k.D_X1].copy()

    return Runner(model, "stochfric kernel", "run_fixed_step_batch alone, same rows", call,
                  lambda x: np.asarray(x))


# --- solve_ivp with events, contact model -------------------------------------------------------

def solve_ivp_contact(case: Case, proc: Floats, tau_end: float, *,
                      method: str = "DOP853", rtol: float = 1e-12, atol: float = 1e-14) -> list[float]:
    """Contact model (method §5.2, mass path) by ``solve_ivp`` with events, one trajectory.

    As ``reference.simulate_solve_ivp`` with μ = μ_k(|v|) + μ̂(path) in slip, the path
    (dimensionless, |dx1| accumulated) as a third state, μ̂ interpolated linearly and
    continued periodically (thesis 4.1.3); breakaway when |x1 + 2Dγ0| exceeds
    max(n μ_s, n (μ_k(0) + μ̂(path))) (the kernel's rule).  Returns X_gh.
    """
    p, law = case.params, case.law
    assert case.process is not None
    g0, n, d, vs = p.gamma0, p.n, p.damping_ratio, p.velocity_scale
    dx = case.process.dx / p.length_scale
    npts = proc.size
    lim = n * law.static
    mu0 = float(law.kinetic(0.0))

    def muhat(path: float) -> float:
        u = path / dx
        i = math.floor(u)
        w = u - i
        i0 = int(i) % npts
        return (1 - w) * proc[i0] + w * proc[(i0 + 1) % npts]

    xs: list[float] = []
    t, x1, x2, path = 0.0, float(case.x0[0]), float(case.x0[1]), 0.0
    stick = x2 == g0
    s = 1.0
    while t < tau_end:
        if stick:
            limb = max(lim, n * (mu0 + muhat(path)))
            # stick: x1 = x1s + γ0 (τ − τs); breakaway where |x1 + 2Dγ0| = limb (closed form)
            tb = t + max(0.0, ((limb - 2 * d * g0) - x1) / g0)
            if tb >= tau_end:
                break
            x1 += g0 * (tb - t)
            t = tb
            s = 1.0
            stick = False
            continue

        def rhs(tt: float, y: Floats, s: float = s) -> list[float]:
            vr = g0 - y[1]
            mu = float(law.kinetic(vs * abs(vr))) + muhat(y[2])
            return [y[1], -y[0] - 2 * d * y[1] + n * mu * s, abs(y[1])]

        def belt(tt: float, y: Floats, s: float = s) -> float:
            return s * (g0 - y[1])

        belt.terminal = True  # type: ignore[attr-defined]
        belt.direction = -1  # type: ignore[attr-defined]
        sol = solve_ivp(rhs, (t, tau_end), [x1, x2, path], method=method, rtol=rtol, atol=atol,
                        events=belt, first_step=1e-6)
        if sol.status != 1:
            break
        ye = sol.y_events[0][0]
        te = float(sol.t_events[0][0])
        if te - t < 1e-9:
            # the first slip runs against the unbalanced force (friction exceeds it): carried
            # on with the belt for one Δτ, then slip is tried again (the kernels' rule)
            x1, x2, t = x1 + g0 * DT, g0, t + DT
            continue
        t, x1, x2, path = te, float(ye[0]), g0, float(ye[2])
        if abs(x1 + 2 * d * g0) <= lim:
            xs.append(x1)
            stick = True
        else:
            s = -s
    return xs


# --- the comparison ---------------------------------------------------------------------------

def _rel(a: Floats, b: Floats) -> float:
    """max |a − b| / max |b|."""
    return float(np.max(np.abs(a - b)) / max(float(np.max(np.abs(b))), 1e-300))


def _time_rounds(runners: list[Runner], rounds: int,
                 say: Callable[[str], None]) -> dict[int, list[tuple[float, float]]]:
    """Every runner once per round, in turn, ``rounds`` times: (wall, CPU) per round."""
    times: dict[int, list[tuple[float, float]]] = {i: [] for i in range(len(runners))}
    for r in range(rounds):
        for i, rn in enumerate(runners):
            c0, t0 = time.process_time(), time.perf_counter()
            rn.last = rn.call()
            t1, c1 = time.perf_counter(), time.process_time()
            times[i].append((t1 - t0, c1 - c0))
        say(f"  round {r + 1}/{rounds} done")
    return times


def _ensemble_rows(out: Comparison, case: Case, cfg: dict[str, Any], say: Callable[[str], None]) -> None:
    """The ensemble rows at equal settings, timed in alternating rounds, with their checks."""
    runs, tau, rounds = int(cfg["runs"]), float(cfg["tau_end"]), int(cfg["rounds"])
    nst = round(tau / DT)
    rc = recurrence(case, tau)
    proc = _process_rows(case, runs)
    jax_ok, dfx_ok = have_jax(), have_diffrax()
    runners: list[Runner] = []
    for model in MODELS:
        pr = proc if model == "contact" else None
        runners += [stochfric_runner(case, model, runs, tau), kernel_runner(case, model, runs, tau, pr),
                    numba_floor(model, rc, runs, case.x0, pr)]
        if jax_ok:
            runners += [jax_floor(model, rc, runs, case.x0, pr),
                        jax_floor(model, rc, runs, case.x0, pr, regularised=True)]
        if dfx_ok:
            runners.append(diffrax_runner(model, rc, runs, case.x0, pr))
    if not jax_ok:
        out.notes.append("jax loop rows skipped: jax not installed (pip install -e '.[bench]')")
    if not dfx_ok:
        out.notes.append("diffrax rows skipped: jax/diffrax not installed (pip install -e '.[bench]')")
    say(f"  compiling / first calls of {len(runners)} runners ...")
    for rn in runners:
        rn.last = rn.call()  # compile / JIT, excluded from the timing
    times = _time_rounds(runners, rounds, say)

    # checks: untimed
    first_x = _accurate_first_x(case, tau)
    final = {(rn.model, rn.tool): rn.final(rn.last) for rn in runners}
    checks: dict[tuple[str, str], str] = {}
    for model in MODELS:
        fk, fs = final[(model, "stochfric kernel")], final[(model, "stochfric")]
        same = bool(np.array_equal(fk, fs))
        out.checks[f"{model}: stochfric kernel final x1 = simulate's (1 = bit for bit)"] = float(same)
        checks[(model, "stochfric kernel")] = "final x1 = simulate's, bit for bit" if same else \
            f"final x1 differs from simulate's: rel. {_rel(fk, fs):.1e}"
        if jax_ok and model != "white":
            d = _rel(final[(model, "numba loop")], final[(model, "jax loop")])
            out.checks[f"{model}: numba loop vs jax loop, final x1, max rel. diff"] = d
            checks[(model, "numba loop")] = f"final x1 vs jax loop: rel. diff {d:.1e}"
        if dfx_ok:
            d = _rel(final[(model, "diffrax")], final[(model, "jax loop (tanh)")])
            if model != "white":
                out.checks[f"{model}: diffrax vs jax loop (tanh), final x1, max rel. diff"] = d
            chk = f"final x1 vs jax loop (tanh): rel. diff {d:.1e}" if model != "white" else ""
            if model != "white" and cfg["dense_check"]:
                dense = diffrax_runner(model, rc, 1, case.x0, proc[:1] if model == "contact" else None, dense=True)
                xr = _first_return(np.asarray(dense.call())[0], case.params.gamma0)
                chk += f"; x1 at first return to 0.95 γ0 vs accurate X_gh: rel. diff {abs(xr / first_x[model] - 1):.1e}"
            checks[(model, "diffrax")] = (chk + "; " if chk else "") + f"ε = {rc.eps:.2g}"

    for i, rn in enumerate(runners):
        cpus = [c for _, c in times[i]]
        wall, cpu = times[i][int(np.argmin(cpus))]
        out.rows.append(Row(rn.model, rn.tool, rn.setting, runs, runs * nst, wall, cpu, runs * nst / cpu,
                            checks.get((rn.model, rn.tool), ""), cpus))


def _accurate_first_x(case: Case, tau: float) -> dict[str, float]:
    """The first X_gh of stochfric's ``accurate`` integrator (DOP853 with events), run 0, per model."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return {m: float(simulate(case.params, model=m, law=case.law, process=case.process, x0=case.x0, runs=1,
                                  seed=1, integration=IntegrationOptions(integrator=Integrator.ACCURATE, tau_end=tau,
                                                                         dt=DT),
                                  execution=ExecutionOptions(workers=1)).x_gh[0, 0, 0])
                for m in ("deterministic", "contact")}


def _ivp_runs(case: Case, proc: Floats | None, tau: float, n: int, method: str, rtol: float, atol: float
              ) -> list[float]:
    """``n`` solve_ivp trajectories (deterministic, or contact with ``proc``); the X_gh of the last."""
    xs: list[float] = []
    for _ in range(n):
        xs = (list(reference.simulate_solve_ivp(case.params, case.law, case.x0, tau, method=method, rtol=rtol,
                                                atol=atol)[0]) if proc is None
              else solve_ivp_contact(case, proc, tau, method=method, rtol=rtol, atol=atol))
    return xs


def _solve_ivp_rows(out: Comparison, case: Case, cfg: dict[str, Any], say: Callable[[str], None]) -> None:
    """solve_ivp with events, one trajectory at a time (its time is linear in the trajectories)."""
    tau, nivp, reps = float(cfg["tau_end"]), int(cfg["ivp_runs"]), int(cfg["ivp_repeats"])
    nst = round(tau / DT)
    proc1 = _process_rows(case, 1)[0]
    acc = _accurate_first_x(case, tau)
    for method, rtol, atol in (("DOP853", 1e-12, 1e-14), ("RK45", 1e-6, 1e-9)):
        setting = f"{method}, rtol {rtol:g}, events, one at a time"
        for model, proc in (("deterministic", None), ("contact", proc1)):
            wall, cpu, xg = _best(functools.partial(_ivp_runs, case, proc, tau, nivp, method, rtol, atol), reps)
            chk = f"first X_gh vs accurate: rel. diff {abs(xg[0] / acc[model] - 1):.1e}" if xg else ""
            out.rows.append(Row(model, "solve_ivp", setting, nivp, nivp * nst, wall, cpu, nivp * nst / cpu, chk,
                                [cpu]))
        say(f"  solve_ivp {method} done")
    out.notes.append("solve_ivp runs one trajectory at a time (ivp_runs of them; its time is linear in the "
                     "number of trajectories) and is an ODE solver: no white-noise (SDE) row")


def _ratios_and_targets(out: Comparison) -> None:
    """Ratios of the best rounds, and the targets (judged on them; with the median of the per-round ratios
    beside them, which pairs runs timed next to each other and so scatters less on a shared machine)."""
    rate = {(r.model, r.tool + (f" {r.setting.split(',')[0]}" if r.tool == "solve_ivp" else "")): r.rate
            for r in out.rows}
    rounds = {(r.model, r.tool): np.asarray(r.rounds_s) for r in out.rows if r.tool != "solve_ivp"}
    for model in MODELS:
        floor_tools = [t for t in FLOOR_TOOLS if (model, t) in rate]
        for mine in ("stochfric", "stochfric kernel"):
            if (model, mine) not in rate:
                continue
            for (m, tool), r in rate.items():
                if m != model or tool.startswith("stochfric"):
                    continue
                if mine == "stochfric kernel" and tool.startswith("solve_ivp"):
                    continue
                out.ratios[f"{model}: {mine} / {tool}"] = rate[(model, mine)] / r
            if (model, "diffrax") in rate:
                sp = rate[(model, mine)] / rate[(model, "diffrax")]
                per_round = rounds[(model, "diffrax")] / rounds[(model, mine)]
                out.targets[f"{model}: {mine} / diffrax ≥ {TARGET_SPEEDUP[model]:g}"] = dict(
                    value=sp, per_round_median=float(np.median(per_round)), target=TARGET_SPEEDUP[model],
                    met=bool(sp >= TARGET_SPEEDUP[model]))
            if floor_tools:
                fr = max(rate[(model, t)] for t in floor_tools) / rate[(model, mine)]
                out.ratios[f"{model}: time {mine} / time of the faster floor"] = fr
                if model != "white":
                    per_round = rounds[(model, mine)] / np.min([rounds[(model, t)] for t in floor_tools], axis=0)
                    out.targets[f"{model}: time {mine} / faster floor ≤ {TARGET_FLOOR:g}"] = dict(
                        value=fr, per_round_median=float(np.median(per_round)), target=TARGET_FLOOR,
                        met=bool(fr <= TARGET_FLOOR))
        if (model, "diffrax") in rate and (model, "jax loop (tanh)") in rate:
            out.ratios[f"{model}: time diffrax / time jax loop (tanh)"] = \
                rate[(model, "jax loop (tanh)")] / rate[(model, "diffrax")]


def run_comparison(size: str = "quick", *, log: Callable[[str], None] | None = None) -> Comparison:
    """Time every (model, tool) pair at ``size`` on one core and return the rows, ratios and targets."""
    cfg = SIZES[size]
    say = log or (lambda _m: None)
    case = brake_case()
    out = Comparison(size=size, machine=machine_info())
    # one core for everything, JAX included: XLA's CPU thread pools are created at first use and
    # inherit the affinity of the thread that creates them
    cpus = os.sched_getaffinity(0) if hasattr(os, "sched_getaffinity") else None
    if cpus:
        os.sched_setaffinity(0, {min(cpus)})
    try:
        _ensemble_rows(out, case, cfg, say)
        _solve_ivp_rows(out, case, cfg, say)
    finally:
        if cpus:
            os.sched_setaffinity(0, cpus)
    if hasattr(os, "getloadavg"):
        out.machine["loadavg_end"] = os.getloadavg()[0]
    if have_jax():
        import jax

        out.machine["jax"] = jax.__version__
    if have_diffrax():
        import diffrax

        out.machine["diffrax"] = diffrax.__version__
    _ratios_and_targets(out)
    return out


def format_comparison(c: Comparison) -> str:
    runs = max((r.runs for r in c.rows if r.tool != "solve_ivp"), default=0)
    nst = max((r.steps // r.runs for r in c.rows), default=0)
    head = (f"{'model':14s} {'tool':17s} {'setting':62s} {'runs':>5s} {'ns/step':>9s} {'median':>8s} "
            f"{'wall':>8s}  check")
    m = c.machine
    lines = [f"stochfric vs diffrax / plain loops / solve_ivp ({c.size}): brake, Δτ = {DT}, {nst} steps, "
             f"{runs} trajectories each (solve_ivp: fewer, one at a time), final state only, one core",
             f"machine: {m.get('cpu_model', '?')}, {m.get('cpu_count', '?')} cores, load avg "
             f"{m.get('loadavg_start', float('nan')):.2f} → {m.get('loadavg_end', float('nan')):.2f}; numba "
             f"{m.get('numba', '?')}, jax {m.get('jax', '-')}, diffrax {m.get('diffrax', '-')}",
             "", head, "-" * len(head)]
    for r in c.rows:
        med = 1e9 * statistics.median(r.rounds_s) / r.steps if r.rounds_s else math.nan
        lines.append(f"{r.model:14s} {r.tool:17s} {r.setting:62s} {r.runs:5d} {r.ns:9.2f} {med:8.2f} "
                     f"{1e9 * r.wall_s / r.steps:8.2f}  {r.check}")
    lines += ["", "ns/step: CPU time per trajectory-step, best of the rounds; median: of the rounds; wall: of the best "
              "round", "", "ratios (stochfric / TOOL: rate ratio, > 1 = stochfric faster; 'time …': time ratio)"]
    lines += [f"  {k:62s} {v:10.3g}" for k, v in c.ratios.items()]
    lines += ["", "targets (issue 32)"]
    lines += [f"  {k:62s} {t['value']:8.3g}  {'met' if t['met'] else 'NOT met':7s}  (median of the per-round ratios "
              f"{t['per_round_median']:.3g})" for k, t in c.targets.items()]
    lines += ["", "checks"]
    lines += [f"  {k:62s} {v:10.3g}" for k, v in c.checks.items()]
    lines += ["", *(f"note: {n}" for n in c.notes)]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    ap.add_argument("--quick", action="store_true", help="smaller sizes")
    ap.add_argument("--json", type=str, default=None, metavar="OUT", help="write JSON here")
    args = ap.parse_args(argv)
    vector_width.configure()  # as bench_oscillator.py: "auto" unless STOCHFRIC_VECTOR_WIDTH says otherwise
    t0 = time.perf_counter()
    c = run_comparison("quick" if args.quick else "full",
                       log=lambda m: print(m, file=sys.stderr, flush=True))
    print(format_comparison(c))
    print(f"\n(total {time.perf_counter() - t0:.1f} s)")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(c.to_dict(), fh, indent=2, default=float)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Performance suite of the friction oscillator (method §5, docs/method.md; not a pytest test).

Usage::

    python benchmarks/bench_oscillator.py [--quick] [--json OUT] [--before REV]

Everything is measured in one process and reported as *ratios* against baselines run in
that same process, so the figures compare like with like on whatever machine runs them:

* **rates** — trajectory-steps per second of :func:`stochfric.oscillator.integrate.simulate`
  on one core (``workers=1``) for every model/integrator: deterministic ``euler``, white
  ``euler`` (Euler–Maruyama), white ``milstein``, contact ``euler``, deterministic and contact
  ``accurate``; on the brake preset (N = 5600 N, pressure law 4.13, as the CLI builds it) and
  on the thesis's demonstration case (γ0 = 1, n = 10, D = 0, law III).  For ``accurate`` a
  "step" is one Δτ of the sampling grid (``τ_end/Δτ`` per run), so its rate is simulated time.
  The white-noise rates include drawing the Wiener increments (end-to-end: since issue 13
  inside the kernel, Philox4x32-10); the ``kernel only`` rows time the compiled Euler–Maruyama
  call with the same increments pre-drawn.  In the same run, the generation paths before
  issue 13: ``white euler, pcg64 buffer`` (numpy's normals drawn into a buffer,
  ``white_stream="pcg64"``) and ``contact euler, generate per run`` (``process.generate`` per
  trajectory instead of one batch evaluation).
* **before** (``--before REV``) — the rates of the issue-13 models with the package of git
  revision ``REV`` and with this one, each in a fresh subprocess running the same script, three
  rounds alternately, best of each (so both see the same load); ratios before/now per model.
* **baselines** — :func:`stochfric.oscillator.reference.euler_python` (the thesis's Euler
  method as a plain Python loop), :func:`em_python` below (the same loop with the
  Euler–Maruyama update, increments pre-drawn), and
  :func:`stochfric.oscillator.reference.simulate_solve_ivp` (scipy ``solve_ivp`` with
  events, DOP853, rtol 1e-12); ratios kernel/python-loop and accurate/solve_ivp.  Each
  baseline's X_gh is checked against the kernel's, so both do the same work.
* **generator** — ns per normal of the kernel's Philox4x32-10 blocks alone and with the
  Box–Muller transform (compiled loop over 32 lanes), and of numpy's PCG64 ``standard_normal``.
* **scaling** — Euler and Euler–Maruyama ensembles with ``workers=1`` vs ``workers=2``
  (repeats interleaved, best of each; CPU time / wall time shows whether two threads ran).
* **headline** — 10,000 white-noise runs of τ = 50 at Δτ = 0.005 (brake, N = 5600 N) on all
  cores (``--quick``: 1,000 runs, and the time scaled ×10).

Numba compilation is done (and excluded) before any timing; every figure is the best of
several repeats, which is the figure least disturbed by other load on the machine.
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import json
import math
import os
import platform
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from typing import Any

import numba
import numpy as np
import numpy.typing as npt
import scipy

from stochfric import vector_width
from stochfric.friction_process.model import BandLimitedProcessModel
from stochfric.oscillator import kernels as _k
from stochfric.oscillator import reference
from stochfric.oscillator.case import PhysicalInput, build_case
from stochfric.oscillator.friction_laws import FrictionLaw, law_III
from stochfric.oscillator.integrate import pack_rows, simulate
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, NoiseOptions
from stochfric.oscillator.parameters import OscillatorParameters
from stochfric.random import philox as _ph
from stochfric.random import ziggurat as _zig

#: Problem sizes per mode.  ``runs``: trajectories per rate measurement; ``tau_end``: τ per
#: run; ``repeats``: timing repeats (best taken); ``scale_runs``: ensemble of the scaling
#: test; ``headline_runs``: runs of the headline (scaled to 10,000 when fewer).
SIZES: dict[str, dict[str, Any]] = {
    "full": dict(runs=1024, tau_end=50.0, acc_runs=64, py_tau=50.0, ivp_tau=50.0, repeats=5,
                 scale_runs=2048, scale_repeats=7, headline_runs=10_000, headline_repeats=2),
    "quick": dict(runs=128, tau_end=50.0, acc_runs=16, py_tau=20.0, ivp_tau=20.0, repeats=3,
                  scale_runs=512, scale_repeats=5, headline_runs=1_000, headline_repeats=1),
    "smoke": dict(runs=2, tau_end=1.0, acc_runs=1, py_tau=1.0, ivp_tau=1.0, repeats=1,
                  scale_runs=4, scale_repeats=1, headline_runs=4, headline_repeats=1),
}

HEADLINE_RUNS = 10_000
HEADLINE_TARGET_S = 30.0
PYTHON_RATIO_TARGET = 100.0
SCALING_TARGET = 1.7
DT = 0.005
#: White-noise intensity σ_ζ of the demonstration case (it has no contact pressure, hence
#: no σ_μ(p)); a typical value of the presets' σ_μ.
DEMO_SIGMA_ZETA = 0.05


@dataclass
class Case:
    """One oscillator set-up of the suite."""

    name: str
    params: OscillatorParameters
    law: FrictionLaw
    process: BandLimitedProcessModel | Any | None
    sigma_zeta: float | None
    x0: tuple[float, float]


@dataclass
class Entry:
    """One timed configuration: ``rate`` trajectory-steps (or τ-steps) per second."""

    group: str
    case: str
    what: str
    runs: int
    steps: int
    wall_s: float
    cpu_s: float
    rate: float
    note: str = ""


@dataclass
class Report:
    """Everything the suite measured (see :func:`run_benchmarks`)."""

    size: str
    machine: dict[str, Any]
    entries: list[Entry] = field(default_factory=list)
    ratios: dict[str, float] = field(default_factory=dict)
    targets: dict[str, dict[str, Any]] = field(default_factory=dict)
    checks: dict[str, float] = field(default_factory=dict)

    def to_dict(self) -> dict[str, Any]:
        return {
            "size": self.size, "machine": self.machine,
            "entries": [asdict(e) for e in self.entries], "ratios": self.ratios,
            "targets": self.targets, "checks": self.checks,
        }


# --- cases ----------------------------------------------------------------------------------

def brake_case(normal_force: float = 5600.0) -> Case:
    """Brake preset as the CLI builds it (:func:`~stochfric.oscillator.case.build_case`: D = 5·10⁻⁶,
    pressure law 4.13)."""
    c = build_case("brake", physical=PhysicalInput(normal_force=normal_force))
    return Case("brake", c.params, c.law, c.process, None, (0.0, c.params.gamma0))


def demo_case() -> Case:
    """Thesis Fig. 4.4: D = 0, γ0 = 1, q = 0, n = 10, law III, start sticking at x1 = 0."""
    params = OscillatorParameters(gamma0=1.0, n=10.0)
    return Case("demo", params, law_III(), None, DEMO_SIGMA_ZETA, (0.0, 1.0))


def _sigma(case: Case) -> float:
    if case.sigma_zeta is not None:
        return case.sigma_zeta
    assert case.process is not None and case.params.pressure_pa is not None
    return case.process.sigma_zeta(case.params.pressure_pa)


# --- the pure-Python Euler–Maruyama baseline -------------------------------------------------

def em_python(
    params: OscillatorParameters, law: FrictionLaw, sigma: float, x0: tuple[float, float],
    tau_end: float, dt: float, dw: npt.NDArray[np.float64],
) -> list[float]:
    """The thesis's Euler–Maruyama method (4.30/4.31) as a plain Python loop (baseline).

    :func:`stochfric.oscillator.reference.euler_python` with the white-noise update of the
    compiled kernel (Itô drift ``a − s n² σ_ζ/4``, diffusion ``n s √(σ_ζ|γ0 − X2|)``,
    ``ΔW_k √(h/Δτ)`` on the remainder of a switched step); ``q = 0``.  ``dw`` holds the
    increments ``ΔW_k`` (``N(0, Δτ)``).  Returns the slip→stick positions X_gh.
    """
    g0, n, d = params.gamma0, params.n, params.damping_ratio
    vs = params.velocity_scale
    lim = n * law.static
    p = law.params
    rational = len(p) == 4
    ito = -0.25 * n * n * sigma

    def mu_k(v: float) -> float:
        if rational:
            return p[0] / (1.0 + p[1] * v) + p[2] + p[3] * v * v
        return p[0]

    x1, x2 = x0
    stick = x2 == g0 and abs(x1 + 2 * d * g0) <= lim
    s = 1.0
    out: list[float] = []
    for k in range(round(tau_end / dt)):
        h = dt
        dwk = float(dw[k])
        while h > 1e-12 * dt:
            if stick:
                f0 = x1 + 2 * d * g0
                x1n = x1 + g0 * h
                fn = x1n + 2 * d * g0
                if abs(fn) <= lim:
                    x1 = x1n
                    h = 0.0
                else:
                    bound = lim if fn > 0 else -lim
                    th = min(max((bound - f0) / (fn - f0), 0.0), 1.0)
                    x1 += g0 * th * h
                    h -= th * h
                    stick = False
                    s = 1.0 if fn > 0 else -1.0
            else:
                vr = g0 - x2
                if vr != 0.0:
                    s = 1.0 if vr > 0 else -1.0
                drift = -x1 - 2 * d * x2 + n * mu_k(vs * abs(vr)) * s + s * ito
                dwh = dwk if h == dt else dwk * math.sqrt(h / dt)
                x1n = x1 + x2 * h
                x2n = x2 + drift * h + n * s * math.sqrt(sigma * abs(vr)) * dwh
                vrn = g0 - x2n
                if vr == 0.0 and vrn * s <= 0.0:
                    x1 += g0 * h
                    x2 = g0
                    h = 0.0
                elif vr != 0.0 and vrn * s <= 0.0:
                    th = vr / (x2n - x2)
                    x1c = x1 + th * (x1n - x1)
                    if abs(x1c + 2 * d * g0) <= lim:
                        out.append(x1c)
                        x1, x2 = x1c, g0
                        h -= th * h
                        stick = True
                    else:
                        x1, x2 = x1n, x2n
                        h = 0.0
                else:
                    x1, x2 = x1n, x2n
                    h = 0.0
    return out


# --- timing helpers -------------------------------------------------------------------------

def _time(fn: Callable[[], object], repeats: int) -> tuple[float, float]:
    """Best wall time over ``repeats`` calls and the process CPU time of that call."""
    best = (math.inf, math.inf)
    for _ in range(max(1, repeats)):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        t1, c1 = time.perf_counter(), time.process_time()
        if t1 - t0 < best[0]:
            best = (t1 - t0, c1 - c0)
    return best


def _sim(case: Case, model: str, integrator: str, runs: int, tau_end: float,
         workers: int | None = 1, seed: int = 1, white_stream: str = "philox-ziggurat") -> Any:
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # e.g. "process exhausted" on long contact runs
        return simulate(case.params, model=model, law=case.law, process=case.process, x0=case.x0, runs=runs,
                        seed=seed, noise=NoiseOptions(sigma_zeta=case.sigma_zeta if model == "white" else None,
                                                      white_stream=white_stream),  # type: ignore[arg-type]
                        integration=IntegrationOptions(integrator=integrator, tau_end=tau_end, dt=DT),  # type: ignore[arg-type]
                        execution=ExecutionOptions(workers=workers))


class _PerTrajectory:
    """A process model that ``simulate`` does not recognise as a spectral representation, so
    it calls ``generate`` once per trajectory (the generation path before issue 13)."""

    def __init__(self, model: Any) -> None:
        self._m = model
        self.dx, self.length = model.dx, model.length
        self.grid_is_periodic = model.grid_is_periodic

    def generate(self, p: float, rng: np.random.Generator) -> npt.NDArray[np.float64]:
        return np.asarray(self._m.generate(p, rng))

    def sigma_zeta(self, p: float) -> float:
        return float(self._m.sigma_zeta(p))

    def to_dict(self) -> dict[str, Any]:
        return dict(self._m.to_dict())


#: (model, integrator) pairs of the rate table.
CONFIGS = (
    ("deterministic", "euler"),
    ("white", "euler"),
    ("white", "milstein"),
    ("contact", "euler"),
    ("deterministic", "accurate"),
    ("contact", "accurate"),
)


def _white_increments(case: Case, runs: int, tau_end: float, seed: int = 1
                      ) -> npt.NDArray[np.float64]:
    """The increments ``simulate`` draws for runs ``0..runs-1`` of parameter set 0 (its default
    stream, :func:`stochfric.random.ziggurat.step_normals`)."""
    nsteps = round(tau_end / DT)
    keys = _ph.trajectory_keys(np.random.SeedSequence(seed),
                               np.column_stack([np.zeros(runs, dtype=np.int64), np.arange(runs)]))
    return np.stack([_zig.step_normals(k, nsteps) for k in keys]).reshape(runs, nsteps) * math.sqrt(DT)


def _kernel_only(case: Case, dw: npt.NDArray[np.float64], noise: int) -> Callable[[], None]:
    """The compiled Euler (``NOISE_NONE``) or Euler–Maruyama (``NOISE_WHITE``, increments
    ``dw`` pre-drawn) batch call, with the arrays ``simulate`` would pass."""
    runs, nsteps = dw.shape
    tau_end = nsteps * DT
    # the rows simulate passes: one parameter set repeated (length scale L = 1 m, no process)
    prm, lawp, shapes = pack_rows([case.params] * runs, [case.law] * runs, [_sigma(case)] * runs,
                                  case.params.length_scale)
    x0 = np.tile(np.asarray(case.x0, dtype=np.float64), (runs, 1))
    nev = int(2 * tau_end) + 16
    proc = np.zeros((runs, 1))
    nproc = np.ones(runs, dtype=np.int64)
    xgh = np.full((runs, nev), np.nan)
    tgh = np.full((runs, nev), np.nan)
    counts = np.zeros(runs, dtype=np.int64)
    traj = np.zeros((runs, 0, 3))
    diag = np.zeros((runs, _k.N_DIAG))
    keys = np.zeros(runs, dtype=np.uint64)
    rows = _k.KernelRows(prm, shapes, lawp, x0, proc, nproc)
    out = _k.KernelOutput(xgh, tgh, counts, traj, diag)
    grid = _k.FixedStepGrid(nsteps, DT, 10)
    white = _k.WhiteInput(_k.WHITE_GIVEN, dw, keys)

    def call() -> None:
        _k.run_fixed_step_batch(rows, out, grid, _k.SCHEME_EULER, noise, _k.PATH_MASS, white)

    return call


# --- the normal generator alone -----------------------------------------------------------------

@numba.njit(error_model="numpy")
def _philox_words(keys: npt.NDArray[np.uint64], npairs: int, out: npt.NDArray[np.uint64]) -> None:
    """Philox4x32-10 blocks only (two 64-bit words per lane and pair), lanes as in the kernel."""
    zero = np.uint64(0)
    for p in range(npairs):
        c = np.uint64(p)
        for j in range(keys.shape[0]):
            out[0, j], out[1, j] = _ph.block_words(keys[j], c, zero, zero)


@numba.njit(error_model="numpy")
def _philox_normals(keys: npt.NDArray[np.uint64], npairs: int, out: npt.NDArray[np.float64]) -> None:
    """Philox4x32-10 + Box–Muller: the kernel's normals (two per lane and pair)."""
    for p in range(npairs):
        c = np.uint64(p)
        for j in range(keys.shape[0]):
            out[0, j], out[1, j] = _ph.pair_normals(keys[j], c)


@numba.njit(error_model="numpy")
def _ziggurat_normals(keys: npt.NDArray[np.uint64], npairs: int, out: npt.NDArray[np.float64],
                      miss: npt.NDArray[np.uint64]) -> None:
    """Philox4x32-10 + ziggurat: the default stream's normals, as the kernel draws them (the
    lane-parallel fast path, then the slow path for the lanes that need it)."""
    for p in range(npairs):
        c = np.uint64(p)
        if _zig.fill_pair_ziggurat(keys, c, 1.0, out[0], out[1], miss):
            _zig.finish_pair_ziggurat(keys, c, 1.0, out[0], out[1], miss)


def _generator_rates(rep: Report, cfg: dict[str, Any]) -> None:
    """ns per normal: Philox blocks alone, Philox + ziggurat and Philox + Box–Muller (32
    lock-step lanes, compiled loop), and numpy's ``Generator(PCG64).standard_normal`` into a
    buffer."""
    lanes = _k.LOCKSTEP
    npairs = max(1, int(cfg["runs"]) * round(float(cfg["tau_end"]) / DT) // (2 * lanes) // 8)
    keys = _ph.trajectory_keys(np.random.SeedSequence(1),
                               np.column_stack([np.zeros(lanes, dtype=np.int64), np.arange(lanes)]))
    words = np.zeros((2, lanes), dtype=np.uint64)
    normals = np.zeros((2, lanes))
    _philox_words(keys, 1, words)
    _philox_normals(keys, 1, normals)
    miss = np.zeros((2, lanes), dtype=np.uint64)
    _ziggurat_normals(keys, 1, normals, miss)
    n = 2 * lanes * npairs
    reps = int(cfg["repeats"])
    for what, fn in (("Philox4x32-10 words", lambda: _philox_words(keys, npairs, words)),
                     ("Philox4x32-10 + ziggurat", lambda: _ziggurat_normals(keys, npairs, normals, miss)),
                     ("Philox4x32-10 + Box–Muller", lambda: _philox_normals(keys, npairs, normals))):
        wall, cpu = _time(fn, reps)
        rep.entries.append(Entry("generator", "-", what, lanes, n, wall, cpu, n / wall,
                                 "per normal, 32 lanes, compiled loop"))
    buf = np.empty(n)
    rng = np.random.Generator(np.random.PCG64(1))
    wall, cpu = _time(lambda: rng.standard_normal(out=buf), reps)
    rep.entries.append(Entry("generator", "-", "numpy PCG64 standard_normal", 1, n, wall, cpu,
                             n / wall, "per normal, into a buffer"))


def _xgh_diff(a: npt.ArrayLike, b: npt.NDArray[np.float64]) -> float:
    """Largest |ΔX_gh| relative to max |X_gh| between a baseline and the kernel (inf: count)."""
    av = np.asarray(a, dtype=np.float64)
    bv = b[np.isfinite(b)]
    if av.shape != bv.shape:
        return math.inf
    if av.size == 0:
        return 0.0
    return float(np.max(np.abs(av - bv)) / max(float(np.max(np.abs(bv))), 1e-300))


# --- the suite ------------------------------------------------------------------------------

def _case_rates(rep: Report, case: Case, cfg: dict[str, Any]) -> None:
    """Rates of every configuration on ``case`` (one core), its baselines and their ratios."""
    reps = int(cfg["repeats"])
    for model, integ in CONFIGS:
        if model == "contact" and case.process is None:
            continue  # no contact pressure, no friction process for the demo case
        acc = integ == "accurate"
        runs = int(cfg["acc_runs"] if acc else cfg["runs"])
        tau = float(cfg["tau_end"])
        steps = runs * round(tau / DT)
        wall, cpu = _time(functools.partial(_sim, case, model, integ, runs, tau), reps)
        rep.entries.append(Entry("rate", case.name, f"{model} {integ}", runs, steps, wall, cpu,
                                 steps / wall, "Δτ-grid steps" if acc else ""))
    # the generation paths before issue 13, in the same run: numpy's PCG64 normals drawn into a
    # buffer (white_stream="pcg64", the same numbers as then) and the contact process generated
    # per trajectory by process.generate (a wrapper simulate does not recognise)
    runs, tau = int(cfg["runs"]), float(cfg["tau_end"])
    steps = runs * round(tau / DT)
    wall, cpu = _time(functools.partial(_sim, case, "white", "euler", runs, tau,
                                        white_stream="pcg64"), reps)
    rep.entries.append(Entry("rate", case.name, "white euler, pcg64 buffer", runs, steps, wall,
                             cpu, steps / wall, "numbers of versions before issue 13"))
    wall, cpu = _time(functools.partial(_sim, case, "white", "euler", runs, tau,
                                        white_stream="philox-boxmuller"), reps)
    rep.entries.append(Entry("rate", case.name, "white euler, Box–Muller", runs, steps, wall,
                             cpu, steps / wall, "the in-kernel stream before the ziggurat"))
    if case.process is not None:
        wall, cpu = _time(functools.partial(_sim, dataclasses.replace(
            case, process=_PerTrajectory(case.process)), "contact", "euler", runs, tau), reps)
        rep.entries.append(Entry("rate", case.name, "contact euler, generate per run", runs,
                                 steps, wall, cpu, steps / wall, "process.generate per trajectory"))
    # the compiled call alone (Wiener increments pre-drawn)
    runs, tau = int(cfg["runs"]), float(cfg["tau_end"])
    dw = _white_increments(case, runs, tau)
    for noise, what in ((_k.NOISE_NONE, "deterministic euler, kernel only"),
                        (_k.NOISE_WHITE, "white euler, kernel only")):
        call = _kernel_only(case, dw, noise)
        call()
        wall, cpu = _time(call, reps)
        rep.entries.append(Entry("rate", case.name, what, runs, dw.size, wall, cpu,
                                 dw.size / wall, "no simulate() around it"))
    # baselines: pure-Python loops and solve_ivp, one trajectory each
    pt = float(cfg["py_tau"])
    nst = round(pt / DT)
    dw1 = _white_increments(case, 1, pt)[0]
    sig = _sigma(case)
    p, lw, x0 = case.params, case.law, case.x0
    wall, cpu = _time(lambda: reference.euler_python(p, lw, x0, pt, DT), reps)
    rep.entries.append(Entry("baseline", case.name, "python loop, Euler", 1, nst, wall, cpu,
                             nst / wall, "reference.euler_python"))
    wall, cpu = _time(lambda: em_python(p, lw, sig, x0, pt, DT, dw1), reps)
    rep.entries.append(Entry("baseline", case.name, "python loop, Euler–Maruyama", 1, nst,
                             wall, cpu, nst / wall, "em_python, increments pre-drawn"))
    it = float(cfg["ivp_tau"])
    nst_ivp = round(it / DT)
    wall, cpu = _time(lambda: reference.simulate_solve_ivp(p, lw, x0, it), reps)
    rep.entries.append(Entry("baseline", case.name, "solve_ivp (DOP853, events)", 1, nst_ivp,
                             wall, cpu, nst_ivp / wall, "Δτ-grid steps"))
    # the baselines do the kernels' work: same X_gh
    rep.checks[f"{case.name}: euler_python vs kernel, max rel |ΔX_gh|"] = _xgh_diff(
        reference.euler_python(p, lw, x0, pt, DT),
        _sim(case, "deterministic", "euler", 1, pt).x_gh[0, 0])
    rep.checks[f"{case.name}: em_python vs kernel, max rel |ΔX_gh|"] = _xgh_diff(
        em_python(p, lw, sig, x0, pt, DT, dw1), _sim(case, "white", "euler", 1, pt).x_gh[0, 0])
    rep.checks[f"{case.name}: solve_ivp vs accurate, max rel |ΔX_gh|"] = _xgh_diff(
        reference.simulate_solve_ivp(p, lw, x0, it)[0],
        _sim(case, "deterministic", "accurate", 1, it).x_gh[0, 0])

    def rate(what: str, group: str = "rate") -> float:
        return next(e.rate for e in rep.entries
                    if e.case == case.name and e.what == what and e.group == group)

    py_e = rate("python loop, Euler", "baseline")
    py_em = rate("python loop, Euler–Maruyama", "baseline")
    c = case.name
    rep.ratios[f"{c}: Euler kernel / python Euler loop"] = rate("deterministic euler") / py_e
    rep.ratios[f"{c}: Euler–Maruyama / python Euler loop"] = rate("white euler") / py_e
    rep.ratios[f"{c}: Euler–Maruyama / python EM loop"] = rate("white euler") / py_em
    rep.ratios[f"{c}: Euler, kernel only / python Euler loop"] = (
        rate("deterministic euler, kernel only") / py_e)
    rep.ratios[f"{c}: EM, kernel only / python EM loop"] = (
        rate("white euler, kernel only") / py_em)
    rep.ratios[f"{c}: accurate / solve_ivp"] = (
        rate("deterministic accurate") / rate("solve_ivp (DOP853, events)", "baseline"))



#: Issue 13: end-to-end ns per trajectory-step on one core (brake, τ = 50, Δτ = 0.005).
WHITE_TARGET_NS = 4.0
CONTACT_TARGET_NS = 6.0

#: Run in a subprocess against the source tree of another revision (``--before REF``): the
#: rates of ``simulate`` for the models of issue 13, with that revision's package.  Uses only
#: API that exists in every revision since the presets (simulate, PhysicalParameters, brake), in
#: the form of that revision (presets in ``process`` or ``oscillator``; flat or grouped options).
_BEFORE_SNIPPET = r"""
import inspect, json, sys, time, warnings
warnings.simplefilter("ignore")
from stochfric import vector_width
if "choice" in inspect.signature(vector_width.configure).parameters:
    vector_width.configure()  # the same SIMD width as a revision that configured it at import
from stochfric.oscillator.friction_laws import pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.parameters import PhysicalParameters
try:
    from stochfric.oscillator.presets import brake
except ImportError:
    from stochfric.friction_process.presets import brake
runs, tau, reps, dt = int(sys.argv[1]), float(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
pre = brake()
p = PhysicalParameters(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                       normal_force=5600.0, damping_ratio=5e-6, contact_area=0.016).to_dimensionless()
law = pressure_law(pre.process.mean(5600.0 / 0.016))
grouped = "integration" in inspect.signature(simulate).parameters


def run(n, tau_end, model, integ):
    kw = dict(model=model, law=law, process=pre.process, x0=(0.0, p.gamma0), seed=1, runs=n)
    if not grouped:
        return simulate(p, dt=dt, tau_end=tau_end, integrator=integ, workers=1, **kw)
    from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions
    return simulate(p, integration=IntegrationOptions(integrator=integ, tau_end=tau_end, dt=dt),
                    execution=ExecutionOptions(workers=1), **kw)


out = {}
for model, integ, n in (("deterministic", "euler", runs), ("white", "euler", runs),
                        ("white", "milstein", runs), ("contact", "euler", runs),
                        ("deterministic", "accurate", max(1, runs // 16)),
                        ("contact", "accurate", max(1, runs // 16))):  # = BEFORE_CONFIGS
    run(1, 1.0, model, integ)
    best = float("inf")
    for _ in range(reps):
        t0 = time.perf_counter()
        run(n, tau, model, integ)
        best = min(best, time.perf_counter() - t0)
    out[f"{model} {integ}"] = best / (n * round(tau / dt))
print(json.dumps(out))
"""


#: (model, integrator) pairs of the before/after table.
BEFORE_CONFIGS = (("deterministic", "euler"), ("white", "euler"), ("white", "milstein"),
                  ("contact", "euler"), ("deterministic", "accurate"), ("contact", "accurate"))


def before_after(ref: str, cfg: dict[str, Any], rounds: int = 3,
                 log: Callable[[str], None] | None = None) -> tuple[dict[str, float], dict[str, float]]:
    """Seconds per trajectory-step of ``simulate`` (one core, brake) with the package of
    revision ``ref`` and with this one, ``rounds`` times alternately, best of each.

    Both sides run the same :data:`_BEFORE_SNIPPET` in a fresh subprocess: ``ref`` from a ``git archive``
    of its ``src`` in a temporary directory first on ``PYTHONPATH`` (its numba cache kept there across
    rounds), this one from the working tree.  Timing this revision inside the benchmark process instead
    read it up to 2x slower than the same code in a fresh process (a process that has compiled and run
    every other configuration first), which made a before/after ratio say more about the process than
    about the code.  Alternating the two keeps both under the same load of a shared machine.
    """
    import subprocess
    import tempfile

    say = log or (lambda _m: None)
    repo = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    runs, tau, reps = int(cfg["runs"]), float(cfg["tau_end"]), int(cfg["repeats"])
    before: dict[str, float] = {}
    after: dict[str, float] = {}

    def timed(env: dict[str, str]) -> dict[str, float]:
        res = subprocess.run([sys.executable, "-c", _BEFORE_SNIPPET, str(runs), str(tau), str(reps), str(DT)],
                             env=env, check=True, capture_output=True, text=True)
        return {k: float(v) for k, v in json.loads(res.stdout.strip().splitlines()[-1]).items()}

    with tempfile.TemporaryDirectory(prefix="stochfric-before-") as tmp:
        arch = subprocess.run(["git", "archive", ref, "src"], cwd=repo, check=True,
                              capture_output=True).stdout
        subprocess.run(["tar", "-x", "-C", tmp], input=arch, check=True)
        env_now = dict(os.environ, PYTHONPATH=os.path.join(repo, "src"))
        if vector_width.applied is not None and env_now.get("NUMBA_CPU_FEATURES") == vector_width.applied:
            # each revision as it runs: its own vector-width rule (none before it existed)
            del env_now["NUMBA_CPU_FEATURES"]
        env_ref = dict(env_now, PYTHONPATH=os.path.join(tmp, "src"), NUMBA_CACHE_DIR=os.path.join(tmp, "numba-cache"))
        for r in range(rounds):
            say(f"  before/after round {r + 1}/{rounds} (revision {ref} and this one, each in a subprocess) ...")
            for side, env in ((before, env_ref), (after, env_now)):
                for k, v in timed(env).items():
                    side[k] = min(side.get(k, math.inf), v)
    return before, after


def machine_info() -> dict[str, Any]:
    """The machine and the software versions the figures were taken with."""
    info: dict[str, Any] = {
        "cpu_count": os.cpu_count(),
        "platform": platform.platform(),
        "processor": platform.processor() or platform.machine(),
        "python": sys.version.split()[0],
        "numpy": np.__version__, "numba": numba.__version__, "scipy": scipy.__version__,
        "vector_width": "512 (stochfric.vector_width)" if vector_width.applied else "numba's default",
    }
    try:
        with open("/proc/cpuinfo") as fh:
            for line in fh:
                if line.startswith("model name"):
                    info["cpu_model"] = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    if hasattr(os, "getloadavg"):
        info["loadavg_start"] = os.getloadavg()[0]
    return info


def run_benchmarks(size: str = "quick", *, log: Callable[[str], None] | None = None,
                   before: str | None = None) -> Report:
    """Run the suite at ``size`` (``full`` | ``quick`` | ``smoke``) and return the report.

    ``before``: a git revision; its package's rates are measured first, in a subprocess on
    the same machine (:func:`before_after`), and reported as ``before``/``after`` entries and
    before/after ratios.
    """
    cfg = SIZES[size]
    say = log or (lambda _m: None)
    rep = Report(size=size, machine=machine_info())
    if before is not None:
        b_sec, a_sec = before_after(before, cfg, log=say)
        for what in b_sec:
            runs = max(1, int(cfg["runs"]) // 16) if "accurate" in what else int(cfg["runs"])
            steps = runs * round(float(cfg["tau_end"]) / DT)
            rep.entries.append(Entry("before", "brake", what, runs, steps, b_sec[what] * steps,
                                     math.nan, 1.0 / b_sec[what], f"revision {before}"))
            rep.entries.append(Entry("after", "brake", what, runs, steps, a_sec[what] * steps,
                                     math.nan, 1.0 / a_sec[what], "this revision, subprocess, alternated"))
    reps = int(cfg["repeats"])
    cases = [brake_case(), demo_case()]

    # warm-up: compile (or load from cache) every kernel outside the timings
    for case in cases:
        for model, integ in CONFIGS:
            if model == "contact" and case.process is None:
                continue
            _sim(case, model, integ, 1, 1.0)

    # 1. rates on one core, and the baselines
    for case in cases:
        _case_rates(rep, case, cfg)
    _generator_rates(rep, cfg)
    wall, cpu = _time(lambda: _sim(cases[0], "deterministic", "euler", 1, DT), reps)
    rep.entries.append(Entry("overhead", "brake", "simulate call, 1 run x 1 step", 1, 1, wall,
                             cpu, 1.0 / wall, "calls/s"))

    # 2. parallel scaling (repeats interleaved so that both see the same load)
    brk = cases[0]
    nsr = int(cfg["scale_runs"])
    for model in ("deterministic", "white"):
        best: dict[int, tuple[float, float]] = {1: (math.inf, 0.0), 2: (math.inf, 0.0)}
        for _ in range(int(cfg["scale_repeats"])):
            for w in (1, 2):
                wall, cpu = _time(functools.partial(_sim, brk, model, "euler", nsr,
                                                    float(cfg["tau_end"]), workers=w), 1)
                if wall < best[w][0]:
                    best[w] = (wall, cpu)
        steps = nsr * round(float(cfg["tau_end"]) / DT)
        for w in (1, 2):
            rep.entries.append(Entry("scaling", brk.name, f"{model} euler, workers={w}", nsr,
                                     steps, best[w][0], best[w][1], steps / best[w][0],
                                     f"CPU/wall {best[w][1] / best[w][0]:.2f}"))
        rep.ratios[f"brake: {model} euler, workers=2 / workers=1"] = best[1][0] / best[2][0]
        say(f"  scaling {model}: {best[1][0] / best[2][0]:.2f}x")

    # 3. headline: 10,000 white-noise runs, τ = 50, Δτ = 0.005, all cores
    hr = int(cfg["headline_runs"])
    htau = 50.0 if size != "smoke" else float(cfg["tau_end"])
    wall, cpu = _time(lambda: _sim(brk, "white", "euler", hr, htau, workers=None),
                      int(cfg["headline_repeats"]))
    steps = hr * round(htau / DT)
    rep.entries.append(Entry("headline", brk.name, "white euler, all cores", hr, steps, wall, cpu,
                             steps / wall, f"τ = {htau:g}, CPU/wall {cpu / wall:.2f}"))
    t10k = wall * HEADLINE_RUNS / hr * (50.0 / htau)
    rep.ratios["headline: time for 10,000 runs [s]"] = t10k

    # targets.  The issue asks for the *kernels* at >= 100x the pure-Python loop on one core:
    # Euler as run by simulate (no random numbers), Euler–Maruyama with the increments given to
    # both the kernel and the Python loop (like for like).  The end-to-end Euler–Maruyama ratio,
    # which adds numpy's normal generator (~9-10 ns per number, the same for any kernel), is
    # reported in the ratios above but is not a kernel figure.
    for c in ("brake", "demo"):
        for what in ("Euler kernel / python Euler loop", "EM, kernel only / python EM loop"):
            v = rep.ratios[f"{c}: {what}"]
            rep.targets[f"{c}: {what} >= {PYTHON_RATIO_TARGET:g}x"] = {
                "value": v, "met": v >= PYTHON_RATIO_TARGET}
    for model in ("deterministic", "white"):
        v = rep.ratios[f"brake: {model} euler, workers=2 / workers=1"]
        rep.targets[f"brake: {model} euler scaling 2 cores >= {SCALING_TARGET}x"] = {
            "value": v, "met": v >= SCALING_TARGET}
    rep.targets[f"10,000 white-noise runs < {HEADLINE_TARGET_S:g} s"] = {
        "value": t10k, "met": t10k < HEADLINE_TARGET_S,
        "measured_runs": hr}

    # issue 13: end to end on one core, and against the previous generation paths in this run
    def ns(what: str, group: str = "rate") -> float:
        return 1e9 / next(e.rate for e in rep.entries
                          if e.case == "brake" and e.what == what and e.group == group)

    for what, target in (("white euler", WHITE_TARGET_NS), ("contact euler", CONTACT_TARGET_NS)):
        v = ns(what)
        rep.targets[f"brake: {what} end to end <= {target:g} ns/step"] = {"value": v, "met": v <= target}
    rep.ratios["brake: white euler, pcg64 buffer / Philox in kernel (time)"] = (
        ns("white euler, pcg64 buffer") / ns("white euler"))
    rep.ratios["brake: white euler, Box–Muller / ziggurat (time)"] = (
        ns("white euler, Box–Muller") / ns("white euler"))
    rep.ratios["brake: contact euler, generate per run / per batch (time)"] = (
        ns("contact euler, generate per run") / ns("contact euler"))
    rep.ratios["brake: white euler / deterministic euler (time)"] = ns("white euler") / ns("deterministic euler")
    rep.ratios["brake: contact euler / deterministic euler (time)"] = ns("contact euler") / ns("deterministic euler")
    # issue 19: the converged integrator against Euler at Δτ = 0.005, ns per Δτ of simulated time
    for model in ("deterministic", "contact"):
        rep.ratios[f"brake: {model} accurate / euler (time per Δτ)"] = (
            ns(f"{model} accurate") / ns(f"{model} euler"))
        if before is not None:  # both revisions as measured side by side, in the same kind of process
            for group, label in (("before", before), ("after", "now")):
                rep.ratios[f"brake: {model} accurate / euler (time per Δτ), {label}, subprocess"] = (
                    ns(f"{model} accurate", group) / ns(f"{model} euler", group))
    if before is not None:
        for model, integ in BEFORE_CONFIGS:
            what = f"{model} {integ}"
            rep.ratios[f"brake: {what}, {before} / now (time)"] = ns(what, "before") / ns(what, "after")
    if hasattr(os, "getloadavg"):
        rep.machine["loadavg_end"] = os.getloadavg()[0]
    return rep


def format_report(rep: Report) -> str:
    """The report as plain-text tables."""
    lines = [f"stochfric oscillator benchmarks ({rep.size}); "
             f"{rep.machine.get('cpu_count')} cores, {rep.machine.get('cpu_model', '')}; "
             f"Python {rep.machine['python']}, numpy {rep.machine['numpy']}, "
             f"numba {rep.machine['numba']}; vector width {rep.machine.get('vector_width', '?')}; load avg "
             f"{rep.machine.get('loadavg_start', float('nan')):.2f} -> "
             f"{rep.machine.get('loadavg_end', float('nan')):.2f}", ""]
    head = (f"{'group':9s} {'case':6s} {'configuration':34s} {'runs':>6s} {'steps':>10s} "
            f"{'wall [s]':>9s} {'steps/s':>10s} {'ns/step':>8s}  note")
    lines += [head, "-" * len(head)]
    for e in rep.entries:
        lines.append(f"{e.group:9s} {e.case:6s} {e.what:34s} {e.runs:6d} {e.steps:10d} "
                     f"{e.wall_s:9.4f} {e.rate:10.3g} {1e9 / e.rate:8.1f}  {e.note}")
    lines += ["", "ratios"]
    for k, v in rep.ratios.items():
        lines.append(f"  {k:58s} {v:10.3g}")
    lines += ["", "baseline agreement (same X_gh as the kernels)"]
    for k, v in rep.checks.items():
        lines.append(f"  {k:58s} {v:10.2g}")
    lines += ["", "targets"]
    for k, t in rep.targets.items():
        lines.append(f"  {k:58s} {t['value']:10.3g}  {'met' if t['met'] else 'NOT MET'}")
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    ap.add_argument("--quick", action="store_true", help="smaller sizes (< 60 s)")
    ap.add_argument("--json", type=str, default=None, metavar="OUT", help="write JSON here")
    ap.add_argument("--before", type=str, default=None, metavar="REV",
                    help="also time the package of git revision REV (subprocess) for before/after")
    args = ap.parse_args(argv)
    size = "quick" if args.quick else "full"
    vector_width.configure()  # "auto" unless STOCHFRIC_VECTOR_WIDTH says otherwise: before numba compiles
    t0 = time.perf_counter()
    rep = run_benchmarks(size, log=lambda m: print(m, file=sys.stderr, flush=True),
                         before=args.before)
    print(format_report(rep))
    print(f"\n(total {time.perf_counter() - t0:.1f} s)")
    if args.json:
        with open(args.json, "w") as fh:
            json.dump(rep.to_dict(), fh, indent=2, default=float)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())

"""Side by side: stochfric's ensemble kernels vs what a user would reach for instead (issue 13).

Usage::

    python benchmarks/bench_compare.py [--quick] [--json OUT]

Needs the optional extra ``bench`` (``pip install -e '.[bench]'``: jax, diffrax) for the
diffrax rows; without it they are skipped with a note, and the ``solve_ivp`` rows still run.

The problem is the brake preset of ``bench_oscillator.py`` (N = 5600 N, D = 5·10⁻⁶, pressure law
4.13, start sticking at x1 = 0), τ = 50 at Δτ = 0.005 (10,000 steps per trajectory), on one
core.  Per model (method §5):

* **stochfric** — :func:`stochfric.oscillator.integrate.simulate` with ``workers=1``:
  ``deterministic``/``contact`` with the thesis's Euler method and exact stick events,
  ``white`` with Euler–Maruyama and the in-kernel Philox stream.
* **diffrax** (JAX on CPU, x64, pinned to one core with ``sched_setaffinity``, ``vmap`` over
  the trajectories, ``jit``-compiled, compile time excluded) — the closest it gets without stick
  events: the same equations with ``sign(v_rel)`` regularised to ``tanh(v_rel/ε)``,
  ``diffrax.Euler`` at the same fixed Δτ (with a ``ControlTerm`` and ``UnsafeBrownianPath`` it
  is Euler–Maruyama for the white model), ε = 4 n μ_s Δτ (the smallest ε at which explicit
  Euler is stable on the regularised stick branch, |∂f/∂x2| Δτ = n μ/ε Δτ < ½).  The contact
  model carries the path as a third state and reads μ̂ by linear interpolation (periodic).
* **solve_ivp** — :func:`scipy.integrate.solve_ivp` with terminal events for the slip→stick
  transitions and a root search for breakaway (``reference.simulate_solve_ivp`` for the
  deterministic model; the same scheme with μ̂(path) for the contact model, path as a third
  state, here), one trajectory at a time; DOP853 at rtol 1e-12 (the package's reference
  setting) and RK45 at rtol 1e-6 (a user's setting).  Not an SDE solver: no white-noise row.

Rates are trajectory-steps per second, a "step" being one Δτ of simulated time (adaptive
solvers take fewer or more internal steps).  The ratio is stochfric / other.  The "check"
column compares the first slip→stick position with stochfric's ``accurate`` integrator (DOP853
with events; diffrax: x1 where x2 first returns to γ0), to show that each solver integrates
the same motion (stochfric's Euler itself differs from ``accurate`` by its O(Δτ) error).
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import math
import os
import sys
import time
import warnings
from collections.abc import Callable
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.integrate import solve_ivp

from stochfric.oscillator import reference
from stochfric.oscillator.integrate import simulate, trajectory_seed
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions

sys.path.insert(0, str(Path(__file__).resolve().parent))
from bench_oscillator import DT, Case, brake_case

SIZES: dict[str, dict[str, Any]] = {
    "full": dict(runs=1024, jax_runs=256, tau_end=50.0, ivp_runs=2, repeats=3),
    "quick": dict(runs=256, jax_runs=64, tau_end=20.0, ivp_runs=1, repeats=2),
    "smoke": dict(runs=4, jax_runs=2, tau_end=1.0, ivp_runs=1, repeats=1),
}
MODELS = ("deterministic", "white", "contact")


@dataclass
class Row:
    """One timed configuration."""

    model: str
    tool: str
    setting: str
    runs: int
    steps: int
    wall_s: float
    cpu_s: float
    rate: float
    check: str = ""


@dataclass
class Comparison:
    """Rows, ratios stochfric/other per model, and notes (skipped tools)."""

    size: str
    rows: list[Row] = field(default_factory=list)
    ratios: dict[str, float] = field(default_factory=dict)
    notes: list[str] = field(default_factory=list)

    def to_dict(self) -> dict[str, Any]:
        return {"size": self.size, "rows": [asdict(r) for r in self.rows], "ratios": self.ratios,
                "notes": self.notes}


def _best(fn: Callable[[], object], repeats: int) -> tuple[float, float]:
    best = (math.inf, math.inf)
    for _ in range(max(1, repeats)):
        c0, t0 = time.process_time(), time.perf_counter()
        fn()
        t1, c1 = time.perf_counter(), time.process_time()
        if t1 - t0 < best[0]:
            best = (t1 - t0, c1 - c0)
    return best


def _sigma(case: Case) -> float:
    assert case.process is not None and case.params.pressure_pa is not None
    return case.process.sigma_zeta(case.params.pressure_pa)


def _process_rows(case: Case, runs: int, seed: int = 1) -> npt.NDArray[np.float64]:
    """The process realisations ``simulate`` uses for runs ``0..runs-1`` (set 0, first segment)."""
    assert case.process is not None and case.params.pressure_pa is not None
    root = np.random.SeedSequence(seed)
    return np.stack([case.process.generate(
        case.params.pressure_pa, np.random.Generator(np.random.PCG64(trajectory_seed(root, (0,), r, 0))))
        for r in range(runs)])


# --- solve_ivp with events, contact model -------------------------------------------------------

def solve_ivp_contact(case: Case, proc: npt.NDArray[np.float64], tau_end: float, *,
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

        def rhs(tt: float, y: npt.NDArray[np.float64], s: float = s) -> list[float]:
            vr = g0 - y[1]
            mu = float(law.kinetic(vs * abs(vr))) + muhat(y[2])
            return [y[1], -y[0] - 2 * d * y[1] + n * mu * s, abs(y[1])]

        def belt(tt: float, y: npt.NDArray[np.float64], s: float = s) -> float:
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


# --- diffrax ----------------------------------------------------------------------------------

def have_diffrax() -> bool:
    return importlib.util.find_spec("jax") is not None and importlib.util.find_spec("diffrax") is not None


def diffrax_runner(case: Case, model: str, runs: int, tau_end: float,
                   proc: npt.NDArray[np.float64] | None) -> tuple[Callable[[], Any], float]:
    """A compiled ``vmap``-ped diffrax ensemble of ``runs`` trajectories and its ε."""
    import diffrax
    import jax
    import jax.numpy as jnp

    jax.config.update("jax_enable_x64", True)
    p, law = case.params, case.law
    g0, n, d, vs = p.gamma0, p.n, p.damping_ratio, p.velocity_scale
    lp = law.param_array
    p0, p1, p2, p3 = (float(lp[0]), float(lp[1]), float(lp[2]), float(lp[3])) if lp.size == 4 \
        else (float(lp[0]), 0.0, 0.0, 0.0)
    eps = 4.0 * n * law.static * DT
    nsteps = round(tau_end / DT)
    sigma = _sigma(case) if model == "white" else 0.0
    dxp = case.process.dx / p.length_scale if (model == "contact" and case.process) else 1.0

    def mu(v: Any) -> Any:
        return p0 / (1.0 + p1 * v) + p2 + p3 * v * v

    def drift(t: Any, y: Any, args: Any) -> Any:
        vr = g0 - y[1]
        s = jnp.tanh(vr / eps)
        m = mu(vs * jnp.abs(vr))
        if model == "contact":
            u = y[2] / dxp
            i = jnp.floor(u)
            w = u - i
            i0 = i.astype(jnp.int32)
            m = m + (1 - w) * jnp.take(args, i0, mode="wrap") + w * jnp.take(args, i0 + 1, mode="wrap")
        f = -y[0] - 2 * d * y[1] + n * m * s - (0.25 * n * n * sigma * s if model == "white" else 0.0)
        if model == "contact":
            return jnp.stack([y[1], f, jnp.abs(y[1])])
        return jnp.stack([y[1], f])

    # one initial state per trajectory (x1 shifted by r·1e-12): without a batched input the
    # deterministic ensemble would not be batched at all (vmap keeps unbatched work unbatched)
    y0s = np.zeros((runs, 3 if model == "contact" else 2))
    y0s[:, 0] = case.x0[0] + 1e-12 * np.arange(runs)
    y0s[:, 1] = case.x0[1]
    save = diffrax.SaveAt(ts=jnp.linspace(0.0, tau_end, nsteps // 10 + 1))

    def one(key: Any, y0: Any, args: Any) -> Any:
        if model == "white":
            bm = diffrax.UnsafeBrownianPath(shape=(), key=key)

            def diffusion(t: Any, y: Any, args: Any) -> Any:
                vr = g0 - y[1]
                return jnp.stack([0.0, n * jnp.tanh(vr / eps) * jnp.sqrt(sigma * jnp.abs(vr))])

            terms: Any = diffrax.MultiTerm(diffrax.ODETerm(drift), diffrax.ControlTerm(diffusion, bm))
        else:
            terms = diffrax.ODETerm(drift)
        sol = diffrax.diffeqsolve(terms, diffrax.Euler(), 0.0, tau_end, DT, y0, args=args,
                                  saveat=save, max_steps=nsteps + 16,
                                  adjoint=diffrax.ForwardMode())  # no gradients needed
        return sol.ys

    keys = jax.random.split(jax.random.PRNGKey(1), runs)
    args = jnp.asarray(proc if proc is not None else np.zeros((runs, 1)))
    y0 = jnp.asarray(y0s)
    fn = jax.jit(jax.vmap(one))

    def call() -> Any:
        return fn(keys, y0, args).block_until_ready()

    return call, eps


def _first_return(ys: npt.NDArray[np.float64], g0: float) -> float:
    """x1 where x2 first comes back within 5 % of γ0 after the first slip (x2 < γ0/2): the
    regularised model has no stick event, only a creep near γ0 (sampled every 10 steps)."""
    x1, x2 = ys[:, 0], ys[:, 1]
    left = np.flatnonzero(x2 < 0.5 * g0)
    if left.size == 0:
        return math.nan
    back = np.flatnonzero(x2[left[0]:] >= 0.95 * g0)
    return float(x1[left[0] + back[0]]) if back.size else math.nan


# --- the comparison ---------------------------------------------------------------------------

def run_comparison(size: str = "quick", *, log: Callable[[str], None] | None = None) -> Comparison:
    """Time every (model, tool) pair at ``size`` and return the rows and ratios."""
    cfg = SIZES[size]
    say = log or (lambda _m: None)
    case = brake_case()
    tau = float(cfg["tau_end"])
    nst = round(tau / DT)
    reps = int(cfg["repeats"])
    out = Comparison(size=size)

    def sim(model: str, runs: int, integrator: str = "euler") -> Any:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return simulate(case.params, model=model, law=case.law, process=case.process, x0=case.x0, runs=runs,
                            seed=1, integration=IntegrationOptions(integrator=integrator, tau_end=tau, dt=DT),  # type: ignore[arg-type]
                            execution=ExecutionOptions(workers=1))

    rate: dict[tuple[str, str], float] = {}
    first_x: dict[str, float] = {}
    for model in MODELS:
        sim(model, 1)
        runs = int(cfg["runs"])
        wall, cpu = _best(lambda model=model, runs=runs: sim(model, runs), reps)
        out.rows.append(Row(model, "stochfric", "euler" + (" (EM, Philox)" if model == "white" else
                                                           ", exact stick events"),
                            runs, runs * nst, wall, cpu, runs * nst / wall))
        rate[(model, "stochfric")] = runs * nst / wall
        first_x[model] = float(sim(model, 1).x_gh[0, 0, 0])
        if model != "white":  # the accurate integrator (DOP853 with events) for the checks
            first_x[model + " accurate"] = float(sim(model, 1, integrator="accurate").x_gh[0, 0, 0])
        say(f"  stochfric {model}: {1e9 * wall / (runs * nst):.2f} ns/step")

    # solve_ivp with events, one trajectory at a time
    nivp = int(cfg["ivp_runs"])
    proc1 = _process_rows(case, 1)[0]
    for method, rtol, atol in (("DOP853", 1e-12, 1e-14), ("RK45", 1e-6, 1e-9)):
        setting = f"{method}, rtol {rtol:g}, events"
        wall, cpu = _best(lambda m=method, r=rtol, a=atol: [reference.simulate_solve_ivp(
            case.params, case.law, case.x0, tau, method=m, rtol=r, atol=a) for _ in range(nivp)], reps)
        xg = reference.simulate_solve_ivp(case.params, case.law, case.x0, tau, method=method,
                                          rtol=rtol, atol=atol)[0]
        chk = (f"first X_gh vs accurate: rel. diff {abs(xg[0] / first_x['deterministic accurate'] - 1):.1e}"
               if len(xg) else "")
        out.rows.append(Row("deterministic", "solve_ivp", setting, nivp, nivp * nst, wall, cpu,
                            nivp * nst / wall, chk))
        rate[("deterministic", f"solve_ivp {method}")] = nivp * nst / wall
        wall, cpu = _best(lambda m=method, r=rtol, a=atol: [solve_ivp_contact(
            case, proc1, tau, method=m, rtol=r, atol=a) for _ in range(nivp)], reps)
        xc = solve_ivp_contact(case, proc1, tau, method=method, rtol=rtol, atol=atol)
        chk = (f"first X_gh vs accurate: rel. diff {abs(xc[0] / first_x['contact accurate'] - 1):.1e}"
               if xc else "")
        out.rows.append(Row("contact", "solve_ivp", setting, nivp, nivp * nst, wall, cpu,
                            nivp * nst / wall, chk))
        rate[("contact", f"solve_ivp {method}")] = nivp * nst / wall
        say(f"  solve_ivp {method} done")
    out.notes.append("solve_ivp is an ODE solver: no white-noise (SDE) row")

    if have_diffrax():
        # one core for JAX too: XLA's CPU thread pools are created at first use and inherit the
        # affinity of the thread that creates them
        cpus = os.sched_getaffinity(0) if hasattr(os, "sched_getaffinity") else None
        if cpus:
            os.sched_setaffinity(0, {min(cpus)})
        jr = int(cfg["jax_runs"])
        for model in MODELS:
            proc = _process_rows(case, jr) if model == "contact" else None
            call, eps = diffrax_runner(case, model, jr, tau, proc)
            ys = np.asarray(call())  # compile
            wall, cpu = _best(call, reps)
            xr = _first_return(ys[0], case.params.gamma0)
            chk = (f"x1 at first return to 0.95 γ0 vs accurate X_gh: rel. diff "
                   f"{abs(xr / first_x[model + ' accurate'] - 1):.1e}; ε = {eps:.2g}"
                   if model != "white" else f"ε = {eps:.2g}")
            out.rows.append(Row(model, "diffrax", "Euler" + ("–Maruyama" if model == "white" else "")
                                + ", vmap, tanh-regularised sign", jr, jr * nst, wall, cpu,
                                jr * nst / wall, chk))
            rate[(model, "diffrax")] = jr * nst / wall
            say(f"  diffrax {model}: {1e9 * wall / (jr * nst):.1f} ns/step")
        if cpus:
            os.sched_setaffinity(0, cpus)
    else:
        out.notes.append("diffrax rows skipped: jax/diffrax not installed (pip install -e '.[bench]')")

    for (model, tool), r in rate.items():
        if tool != "stochfric":
            out.ratios[f"{model}: stochfric / {tool}"] = rate[(model, "stochfric")] / r
    return out


def format_comparison(c: Comparison) -> str:
    head = (f"{'model':14s} {'tool':10s} {'setting':44s} {'runs':>5s} {'wall [s]':>9s} "
            f"{'CPU/wall':>8s} {'ns/step':>9s}  check")
    lines = [f"stochfric vs diffrax / solve_ivp ({c.size}), brake, Δτ = {DT}, one core", "", head,
             "-" * len(head)]
    for r in c.rows:
        lines.append(f"{r.model:14s} {r.tool:10s} {r.setting:44s} {r.runs:5d} {r.wall_s:9.4f} "
                     f"{r.cpu_s / r.wall_s:8.2f} {1e9 / r.rate:9.1f}  {r.check}")
    lines += ["", "ratios (trajectory-steps per second)"]
    lines += [f"  {k:44s} {v:10.3g}" for k, v in c.ratios.items()]
    lines += ["", *(f"note: {n}" for n in c.notes)]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0] if __doc__ else None)
    ap.add_argument("--quick", action="store_true", help="smaller sizes")
    ap.add_argument("--json", type=str, default=None, metavar="OUT", help="write JSON here")
    args = ap.parse_args(argv)
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

"""Closed-form and independent reference solutions for the friction oscillator.

Used by the tests (reference tier) and the benchmarks; nobody here wrote the physics
they encode, so they check the integrators from outside:

* :func:`constant_friction_cycle` — the stick-slip limit cycle for a constant kinetic
  coefficient μ_k below the static μ_s (law II), undamped and damped: slip start and
  end positions, slip and stick durations, minimum velocity.
* :func:`hopf_damping` — the linear stability boundary of steady sliding,
  ``D_H = −n μ'(v_rel = v0) v0 / (2γ0)`` (linearisation of eq. 4.7 about
  ``x1s = n μ(v0)``, ``x2 = 0``; thesis eq. 4.39).
* :func:`simulate_solve_ivp` — the same stick/slip model integrated by
  :func:`scipy.integrate.solve_ivp` with terminal events (an independent solver).
* :func:`euler_python` — a plain pure-Python loop of the thesis's Euler method; the
  baseline of the benchmark suite.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy.optimize import brentq, minimize_scalar

from stochfric.errors import InputError

from .friction_laws import FrictionLaw
from .parameters import OscillatorParameters


@dataclass(frozen=True)
class StickSlipCycle:
    """The closed-form stick-slip cycle (all dimensionless)."""

    x_slip_start: float  # x_hg = n μ_s − 2Dγ0 (eq. 4.9, q = 0)
    x_slip_end: float  # X_gh
    slip_duration: float
    stick_duration: float
    min_velocity: float  # minimum of x2 during slip

    @property
    def period(self) -> float:
        return self.slip_duration + self.stick_duration


def constant_friction_cycle(
    *, n: float, gamma0: float, mu_static: float, mu_kinetic: float, damping_ratio: float = 0.0
) -> StickSlipCycle:
    """Stick-slip cycle for ``μ(v ≠ 0) = μ_k < μ_s = μ(0)``, ``q = 0`` (law II type).

    Slip starts at ``x_hg = n μ_s − 2Dγ0`` with ``x2 = γ0``; with ``ξ = x1 − n μ_k`` the
    slip phase is the free damped oscillator ``ξ'' + 2Dξ' + ξ = 0``::

        ξ(τ)  = e^{−Dτ} (ξ0 cos ω_d τ + (γ0 + Dξ0)/ω_d sin ω_d τ),  ω_d = √(1 − D²)
        x2(τ) = e^{−Dτ} (γ0 cos ω_d τ − (ξ0 + Dγ0)/ω_d sin ω_d τ)

    and it ends at the first ``τ > 0`` with ``x2 = γ0`` (the static condition then holds
    for the parameters used; checked).  Undamped: ``X_gh = n(2μ_k − μ_s)``, slip duration
    ``π + 2 atan(γ0/(nΔμ))``, minimum velocity ``−√((nΔμ)² + γ0²)``.  The stick phase
    moves at ``γ0`` from ``X_gh`` back to ``x_hg``.
    """
    if not 0 <= mu_kinetic < mu_static:
        raise InputError("need 0 <= mu_kinetic < mu_static")
    if not 0 <= damping_ratio < 1:
        raise InputError("need 0 <= damping_ratio < 1")
    d = damping_ratio
    x_hg = n * mu_static - 2 * d * gamma0
    xi0 = x_hg - n * mu_kinetic
    wd = math.sqrt(1 - d * d)

    def x2(t: float) -> float:
        return math.exp(-d * t) * (gamma0 * math.cos(wd * t) - (xi0 + d * gamma0) / wd * math.sin(wd * t))

    def xi(t: float) -> float:
        return math.exp(-d * t) * (xi0 * math.cos(wd * t) + (gamma0 + d * xi0) / wd * math.sin(wd * t))

    if d == 0:
        alpha = math.atan2(gamma0, xi0)
        t_slip = math.pi + 2 * alpha
        vmin = -math.hypot(xi0, gamma0)
    else:
        # bracket the first return of x2 to γ0 after it has dipped below
        grid = np.linspace(1e-9, 4 * math.pi, 40001)
        g = np.array([gamma0 - x2(t) for t in grid])
        idx = np.nonzero((g[:-1] > 0) & (g[1:] <= 0))[0]
        if idx.size == 0:
            raise InputError("the slip phase does not return to the belt speed: no stick-slip")
        i = int(idx[0])
        t_slip = brentq(lambda t: gamma0 - x2(t), grid[i], grid[i + 1], xtol=1e-15, rtol=1e-15)
        res = minimize_scalar(x2, bounds=(0.0, t_slip), method="bounded",
                              options={"xatol": 1e-12})
        vmin = float(res.fun)
    x_gh = xi(t_slip) + n * mu_kinetic
    if abs(x_gh + 2 * d * gamma0) > n * mu_static:
        raise InputError("static friction cannot hold at the end of the slip phase")
    return StickSlipCycle(
        x_slip_start=x_hg,
        x_slip_end=x_gh,
        slip_duration=float(t_slip),
        stick_duration=(x_hg - x_gh) / gamma0,
        min_velocity=float(vmin),
    )


def hopf_damping(params: OscillatorParameters, law: FrictionLaw) -> float:
    """Linear stability boundary of steady sliding ``D_H = −n μ'(v0) v0 / (2γ0)``.

    Linearising (4.7) about the rest position ``x1s = n μ(v0)`` (4.8) with
    ``v_rel = v0 − L ω0 x2`` gives ``x'' + (2D + n μ'(v0) L ω0) x' + x = 0``; steady
    sliding is stable for ``D > D_H``.  ``μ'`` is d μ / d|v| in s/m.  Negative for a
    rising law (then steady sliding is stable even undamped).
    """
    v0 = params.belt_speed
    return -params.n * law.derivative(v0) * v0 / (2 * params.gamma0)


def simulate_solve_ivp(
    params: OscillatorParameters,
    law: FrictionLaw,
    x0: tuple[float, float],
    tau_end: float,
    *,
    method: str = "DOP853",
    rtol: float = 1e-12,
    atol: float = 1e-14,
) -> tuple[np.ndarray, np.ndarray]:
    """Deterministic stick/slip by :func:`scipy.integrate.solve_ivp` with terminal events.

    Independent of the package's kernels (only the law's Python evaluation is shared).
    Slip: (4.7) with ``s = sign(γ0 − x2)`` fixed per segment; events ``x2 = γ0``.  Stick:
    closed form, end of stick from the static condition (4.2) by root finding.
    Returns ``(X_gh, τ_gh)``.
    """
    from scipy.integrate import solve_ivp  # the independent solver: imported where it is used (0.7 s)

    g0, n, d, q, eta = params.gamma0, params.n, params.damping_ratio, params.q, params.eta
    vs = params.velocity_scale
    lim = n * law.static
    xs: list[float] = []
    ts: list[float] = []

    def force(x1: float, t: float) -> float:
        return x1 + 2 * d * g0 - q * math.cos(eta * t)

    t = 0.0
    x1, x2 = float(x0[0]), float(x0[1])
    stick = x2 == g0 and abs(force(x1, t)) <= lim
    s = 1.0 if x2 <= g0 else -1.0
    while t < tau_end:
        if stick:
            x1s, ts0 = x1, t

            def h(tt: float, x1s: float = x1s, ts0: float = ts0) -> float:
                return abs(force(x1s + g0 * (tt - ts0), tt)) - lim

            step = 0.01 / max(1.0, eta)
            a = t
            tb = math.inf
            while a < tau_end:
                b = min(a + step, tau_end)
                if h(b) > 0:
                    tb = brentq(h, a, b, xtol=1e-15, rtol=4 * np.finfo(float).eps)
                    break
                a = b
            if not math.isfinite(tb):
                break
            x1 = x1s + g0 * (tb - ts0)
            t = tb
            s = 1.0 if force(x1, t) > 0 else -1.0
            stick = False
            continue

        def rhs(tt: float, y: np.ndarray, s: float = s) -> list[float]:
            vr = g0 - y[1]
            mu = float(law.kinetic(vs * abs(vr)))
            return [y[1], -y[0] - 2 * d * y[1] + n * mu * s + q * math.cos(eta * tt)]

        def belt(tt: float, y: np.ndarray, s: float = s) -> float:
            return s * (g0 - y[1])

        belt.terminal = True  # type: ignore[attr-defined]
        belt.direction = -1  # type: ignore[attr-defined]
        # step off the event surface by a tiny amount so the initial zero is not detected
        sol = solve_ivp(rhs, (t, tau_end), [x1, x2], method=method, rtol=rtol, atol=atol,
                        events=belt, first_step=1e-6)
        if sol.status != 1:
            break
        te = float(sol.t_events[0][0])
        ye = sol.y_events[0][0]
        t, x1, x2 = te, float(ye[0]), g0
        if abs(force(x1, t)) <= lim:
            xs.append(x1)
            ts.append(t)
            stick = True
        else:
            s = -s
    return np.asarray(xs), np.asarray(ts)


def euler_python(
    params: OscillatorParameters, law: FrictionLaw, x0: tuple[float, float], tau_end: float,
    dt: float,
) -> list[float]:
    """The thesis's Euler method (4.11/4.12) as a plain Python loop (benchmark baseline).

    Same switching rules as the compiled kernel, deterministic model, ``q = 0``.
    Returns the slip→stick positions X_gh.
    """
    g0, n, d = params.gamma0, params.n, params.damping_ratio
    vs = params.velocity_scale
    mus = law.static
    lim = n * mus
    p = law.params
    rational = len(p) == 4

    def mu_k(v: float) -> float:
        if rational:
            return p[0] / (1.0 + p[1] * v) + p[2] + p[3] * v * v
        return p[0]

    x1, x2 = x0
    stick = x2 == g0 and abs(x1 + 2 * d * g0) <= lim
    s = 1.0
    out: list[float] = []
    for _ in range(round(tau_end / dt)):
        h = dt
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
                acc = -x1 - 2 * d * x2 + n * mu_k(vs * abs(vr)) * s
                x1n = x1 + x2 * h
                x2n = x2 + acc * h
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

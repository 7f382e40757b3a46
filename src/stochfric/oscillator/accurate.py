"""The ``accurate`` integrator: adaptive Dormand–Prince 5(4) with event location.

For the deterministic and the contact-analysis models (no SDE).  Between events the
slip equations (4.7) / (4.36) are smooth, so the adaptive embedded Runge–Kutta pair
of Dormand and Prince (order 5, error estimate of order 4, Hairer's 4th-order dense
output; the method of MATLAB ``ode45`` that the thesis used as its reference) keeps
its order; every non-smooth point is an *event* at which the integration restarts:

* ``x2 = γ0`` (``v_rel = 0``): slip→stick if ``|x1 + 2Dγ0 − q cos x3| ≤ n μ_s``,
  otherwise the mass passes the belt speed and keeps slipping (thesis Fig. 4.15);
* ``x2 = 0`` when the path coordinate is the mass path (``|x2|`` has a kink there);
* the path coordinate crossing a grid point of the friction process (the linear
  interpolation of μ̂ has a kink at every grid point).

Events are located by bisection on the dense output to ``θ`` resolution 1e-15 and the
state at the event is recomputed by one Dormand–Prince step of exactly that length.  Within a
step the signs ``s = sign(γ0 − x2)`` and ``sign(x2)`` are held (the right-hand side is then
smooth across ``x2 = γ0`` and ``x2 = 0``; the step that contains one is not rejected by the
error control), and a step that would cross a grid point of the process is aimed at it
instead (cubic Hermite guess, then Newton on the step length: 1–2 extra steps per grid point
instead of a cascade of rejected steps across the kink).
The stick phase is solved in closed form (``x1 = x1s + γ0 (τ − τs)``); its end, the
first ``τ`` with ``|x1 + 2Dγ0 − q cos(x30 + ητ)| > n μ_s``, is found in closed form for
``q = 0`` and by a scan plus bisection otherwise (the scan jumps by the margin over the
Lipschitz bound γ0 + qη, steps of 0.02/max(1, η) only near the band).  At the belt speed with
``n μ_s < |F| ≤ n (μ_k(0) + μ̂)`` (contact model) no slip direction is consistent: the mass is
carried with the belt (:func:`carried_end`) until it sticks or breaks away, the Δτ → 0 limit of
the fixed-step scheme; after a passage of the belt speed without sticking the friction opposes
the unbalanced force (``s = sign F``).

With tolerances ``rtol = 1e-11``, ``atol = 1e-13`` the slip→stick positions are
independent of the initial step and of the tolerance to about 1e-9 (tests) and agree with
scipy's ``solve_ivp`` (DOP853, events, rtol 1e-12) to 1e-8 (tests/reference,
tests/regression/test_lyapunov_integrators.py).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
import numpy.typing as npt

from .friction_laws import mu_kinetic_row
from .kernels import (
    NOISE_PROCESS,
    P_D,
    P_ETA,
    P_GAMMA0,
    P_MUS,
    P_N,
    P_PROC_DX,
    P_Q,
    P_VSCALE,
    P_X30,
    PATH_MASS,
    KernelOutput,
    KernelRows,
    process_value_row,
    slip_drift,
    stick_force,
    store_diagnostics,
)

# Dormand–Prince 5(4) coefficients (Dormand & Prince 1980; Hairer, Nørsett & Wanner, Table II.5.2)
C2, C3, C4, C5 = 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0
A21 = 1.0 / 5.0
A31, A32 = 3.0 / 40.0, 9.0 / 40.0
A41, A42, A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
A51, A52, A53, A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
A61, A62, A63, A64, A65 = (
    9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0,
)
B1, B3, B4, B5, B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
E1, E3, E4, E5, E6, E7 = (
    71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0, -1.0 / 40.0,
)
# dense output (Hairer's contd5)
DD1, DD3, DD4, DD5, DD6, DD7 = (
    -12715105075.0 / 11282082432.0,
    87487479700.0 / 32700410799.0,
    -10690763975.0 / 1880347072.0,
    701980252875.0 / 199316789632.0,
    -1453857185.0 / 822651844.0,
    69997945.0 / 29380423.0,
)

class AccurateSettings(NamedTuple):
    """Settings of the adaptive integrator: ``τ_end``, initial step ``h0``, ``max_step``,
    tolerances ``rtol``/``atol`` and the sampling interval ``save_dt`` of the saved states."""

    tau_end: float
    h0: float
    max_step: float
    rtol: float
    atol: float
    save_dt: float


EV_NONE = 0
EV_BELT = 1
EV_ZERO_VELOCITY = 2
EV_NODE = 3


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _f(
    tau: float,
    y0: float,
    y1: float,
    y2: float,
    s: float,
    sz: float,
    prm: npt.NDArray[np.float64],
    shape: int,
    lawp: npt.NDArray[np.float64],
    r: int,
    noise: int,
    path_mode: int,
    proc: npt.NDArray[np.float64],
    n_proc: int,
    out: npt.NDArray[np.float64],
    j: int,
) -> None:  # pragma: no cover
    """Slip equations (4.7)/(4.36) with the path coordinate as third state, into ``out[j]``.

    The signs are those of the segment, held fixed within a step: ``s = sign(γ0 − x2)`` (so
    ``|γ0 − x2| = s(γ0 − x2)``) and, for the mass path, ``sz = sign(x2)`` (``|x2| = sz·x2``).  The
    right-hand side is then smooth across ``x2 = γ0`` and ``x2 = 0``, which are events where the
    integration restarts with the new sign, so the step that contains one is not rejected by the
    error control (a kink would cost a cascade of rejected steps).  ``lawp``/``proc`` are the rows'
    2-D arrays, ``r`` the row.
    """
    vr = prm[P_GAMMA0] - y1
    mu = mu_kinetic_row(shape, prm[P_VSCALE] * (s * vr), lawp, r)
    if noise == NOISE_PROCESS:
        mu += process_value_row(proc, r, n_proc, prm[P_PROC_DX], y2)
    out[j, 0] = y1
    acc = slip_drift(y0, y1, 2.0 * prm[P_D], prm[P_N], mu, s)
    if prm[P_Q] != 0.0:
        acc += prm[P_Q] * math.cos(prm[P_X30] + prm[P_ETA] * tau)
    out[j, 1] = acc
    out[j, 2] = sz * y1 if path_mode == PATH_MASS else s * vr


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _step(
    tau: float, y: npt.NDArray[np.float64], h: float, k: npt.NDArray[np.float64],
    s: float, sz: float, prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], r: int,
    noise: int, path_mode: int, proc: npt.NDArray[np.float64], n_proc: int,
    ynew: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """One Dormand–Prince step; ``k[0]`` must hold f(τ, y) on entry; fills k[1..6], ynew (FSAL)."""
    a0, a1, a2 = y[0], y[1], y[2]
    _f(tau + C2 * h, a0 + h * A21 * k[0, 0], a1 + h * A21 * k[0, 1], a2 + h * A21 * k[0, 2],
       s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 1)
    _f(tau + C3 * h,
       a0 + h * (A31 * k[0, 0] + A32 * k[1, 0]),
       a1 + h * (A31 * k[0, 1] + A32 * k[1, 1]),
       a2 + h * (A31 * k[0, 2] + A32 * k[1, 2]),
       s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 2)
    _f(tau + C4 * h,
       a0 + h * (A41 * k[0, 0] + A42 * k[1, 0] + A43 * k[2, 0]),
       a1 + h * (A41 * k[0, 1] + A42 * k[1, 1] + A43 * k[2, 1]),
       a2 + h * (A41 * k[0, 2] + A42 * k[1, 2] + A43 * k[2, 2]),
       s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 3)
    _f(tau + C5 * h,
       a0 + h * (A51 * k[0, 0] + A52 * k[1, 0] + A53 * k[2, 0] + A54 * k[3, 0]),
       a1 + h * (A51 * k[0, 1] + A52 * k[1, 1] + A53 * k[2, 1] + A54 * k[3, 1]),
       a2 + h * (A51 * k[0, 2] + A52 * k[1, 2] + A53 * k[2, 2] + A54 * k[3, 2]),
       s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 4)
    _f(tau + h,
       a0 + h * (A61 * k[0, 0] + A62 * k[1, 0] + A63 * k[2, 0] + A64 * k[3, 0] + A65 * k[4, 0]),
       a1 + h * (A61 * k[0, 1] + A62 * k[1, 1] + A63 * k[2, 1] + A64 * k[3, 1] + A65 * k[4, 1]),
       a2 + h * (A61 * k[0, 2] + A62 * k[1, 2] + A63 * k[2, 2] + A64 * k[3, 2] + A65 * k[4, 2]),
       s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 5)
    for i in range(3):
        ynew[i] = y[i] + h * (
            B1 * k[0, i] + B3 * k[2, i] + B4 * k[3, i] + B5 * k[4, i] + B6 * k[5, i]
        )
    _f(tau + h, ynew[0], ynew[1], ynew[2], s, sz, prm, shape, lawp, r, noise, path_mode, proc, n_proc, k, 6)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _err_norm(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64], h: float,
    rtol: float, atol: float,
) -> float:  # pragma: no cover
    """RMS of the embedded 4th-order error estimate, scaled by ``atol + rtol·max(|y|, |ynew|)``."""
    err = 0.0
    for i in range(3):
        sc = atol + rtol * max(abs(y[i]), abs(ynew[i]))
        e = h * (E1 * k[0, i] + E3 * k[2, i] + E4 * k[3, i] + E5 * k[4, i]
                 + E6 * k[5, i] + E7 * k[6, i]) / sc
        err += e * e
    return math.sqrt(err / 3.0)


@numba.njit(cache=True, nogil=True)
def _rhs(
    tau: float,
    y: npt.NDArray[np.float64],
    s: float,
    prm: npt.NDArray[np.float64],
    shape: int,
    lawp: npt.NDArray[np.float64],
    noise: int,
    path_mode: int,
    proc: npt.NDArray[np.float64],
    n_proc: int,
    out: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """:func:`_f` for one 1-D state, law and process (``sz = sign(x2)``); tests and benchmarks."""
    sz = 1.0 if y[1] >= 0.0 else -1.0
    k = np.empty((1, 3))
    _f(tau, y[0], y[1], y[2], s, sz, prm, shape, lawp.reshape((1, lawp.shape[0])), 0, noise, path_mode,
       proc.reshape((1, proc.shape[0])), n_proc, k, 0)
    out[0], out[1], out[2] = k[0, 0], k[0, 1], k[0, 2]


@numba.njit(cache=True, nogil=True)
def _dopri_step(
    tau: float, y: npt.NDArray[np.float64], h: float, k: npt.NDArray[np.float64],
    s: float, prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64],
    noise: int, path_mode: int, proc: npt.NDArray[np.float64], n_proc: int,
    ynew: npt.NDArray[np.float64], tmp: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """:func:`_step` for one 1-D law and process (``sz = sign(x2)`` at the start); tests.  ``tmp`` is
    unused (kept for the signature)."""
    sz = 1.0 if y[1] >= 0.0 else -1.0
    _step(tau, y, h, k, s, sz, prm, shape, lawp.reshape((1, lawp.shape[0])), 0, noise, path_mode,
          proc.reshape((1, proc.shape[0])), n_proc, ynew)


@numba.njit(cache=True, nogil=True)
def _dense(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64],
    h: float, theta: float, i: int,
) -> float:  # pragma: no cover
    """Component ``i`` of Hairer's 4th-order continuous extension at ``τ + θh``."""
    ydiff = ynew[i] - y[i]
    bspl = h * k[0, i] - ydiff
    r4 = ydiff - h * k[6, i] - bspl
    r5 = h * (
        DD1 * k[0, i] + DD3 * k[2, i] + DD4 * k[3, i] + DD5 * k[4, i] + DD6 * k[5, i]
        + DD7 * k[6, i]
    )
    t1 = 1.0 - theta
    return y[i] + theta * (ydiff + t1 * (bspl + theta * (r4 + t1 * r5)))


@numba.njit(cache=True, nogil=True)
def _root_theta(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64],
    h: float, comp: int, target: float, sgn: float,
) -> float:  # pragma: no cover
    """Smallest θ in (0, 1] with ``sgn·(target − y_comp(θ))`` reaching 0, by bisection."""
    lo = 0.0
    hi = 1.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        g = sgn * (target - _dense(y, ynew, k, h, mid, comp))
        if g > 0.0:
            lo = mid
        else:
            hi = mid
    return hi


@numba.njit(cache=True, nogil=True)
def breakaway_time(
    x1s: float, tau_s: float, tau_end: float, prm: npt.NDArray[np.float64], lim: float
) -> float:  # pragma: no cover
    """First ``τ > τs`` at which the stick condition (4.2) fails, or ``inf`` before ``τ_end``.

    ``F(τ) = x1s + γ0(τ − τs) + 2Dγ0 − q cos(x30 + ητ)``; stick holds while ``|F| ≤ lim``.
    """
    gamma0 = prm[P_GAMMA0]
    qq = prm[P_Q]
    eta = prm[P_ETA]
    f0 = stick_force(x1s, tau_s, prm)
    if qq == 0.0 or eta == 0.0:
        tb = tau_s + (lim - f0) / gamma0
        if tb < tau_s:
            tb = tau_s
        return tb if tb <= tau_end else np.inf
    delta = 0.02 / max(1.0, eta)
    # |F'| <= γ0 + q|η|: from a point with margin lim − |F| the band cannot be left within
    # margin/lip, so the scan jumps that far (never past a crossing) and steps by δ only near the band
    lip = gamma0 + abs(qq * eta)
    a = tau_s
    fa = f0
    while a < tau_end:
        b = min(a + max(delta, 0.999 * (lim - abs(fa)) / lip), tau_end)
        fb = stick_force(x1s + gamma0 * (b - tau_s), b, prm)
        if abs(fb) > lim:
            bound = lim if fb > 0.0 else -lim
            lo = a
            hi = b
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                fm = stick_force(x1s + gamma0 * (mid - tau_s), mid, prm)
                if (fm - bound) * (fb - bound) > 0.0 and abs(fm) > lim:
                    hi = mid
                else:
                    lo = mid
            return hi
        a = b
        fa = fb
    return np.inf


@numba.njit(cache=True, nogil=True)
def carried_end(
    x1s: float, tau_s: float, tau_end: float, prm: npt.NDArray[np.float64], lim: float, nn_k0: float,
    proc: npt.NDArray[np.float64], r: int, n_proc: int, path0: float, rate: float,
) -> tuple[float, bool]:  # pragma: no cover
    """End of a phase *carried with the belt* that starts at ``τs`` with ``lim < |F| ≤ lim_eff``.

    At the belt speed the static friction cannot hold (``|F| > n μ_s``) but the contact model's
    kinetic friction at ``v_rel → 0``, ``lim_eff = n (μ_k(0) + μ̂(path))`` (``nn_k0 = n μ_k(0)``),
    exceeds the force, so a slip in either direction would run against it: the mass moves with the
    belt (``x1 = x1s + γ0(τ − τs)``, the path grows at ``rate``: γ0 on the mass path, 0 on the
    relative one) until ``|F| ≤ lim`` (it sticks: ``True``) or ``|F| > lim_eff`` (it slips:
    ``False``) — the limit Δτ → 0 of the fixed-step scheme, which carries the mass with the belt
    step by step there.  Returns ``(τ, sticks)``, ``(inf, False)`` when it lasts past ``τ_end``.
    """
    gamma0 = prm[P_GAMMA0]
    pdx = prm[P_PROC_DX]
    eta = prm[P_ETA]
    f0 = stick_force(x1s, tau_s, prm)
    sg = 1.0 if f0 > 0.0 else -1.0  # |F| > lim > 0 throughout: F keeps its sign
    delta = min(0.02 / max(1.0, eta), 0.25 * pdx / max(rate, 1e-300))
    a = tau_s
    while a < tau_end:
        b = min(a + delta, tau_end)
        fb = sg * stick_force(x1s + gamma0 * (b - tau_s), b, prm)
        leb = nn_k0 + (prm[P_N] * process_value_row(proc, r, n_proc, pdx, path0 + rate * (b - tau_s)))
        if fb <= lim or fb > leb:
            inner = fb <= lim
            lo = a
            hi = b
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if mid <= lo or mid >= hi:
                    break
                fm = sg * stick_force(x1s + gamma0 * (mid - tau_s), mid, prm)
                if inner:
                    out = fm <= lim
                else:
                    out = fm > nn_k0 + prm[P_N] * process_value_row(proc, r, n_proc, pdx,
                                                                    path0 + rate * (mid - tau_s))
                if out:
                    hi = mid
                else:
                    lo = mid
            return hi, inner
        a = b
    return np.inf, False


#: A sample at τ = k·save_dt belongs to the step that ends there even when k·save_dt rounds a
#: hair above the step's end (3·0.1 = 0.30000000000000004 > 0.3): without this tolerance the last
#: row at τ_end stayed unwritten (0, 0, 0).  Relative to save_dt; the dense output is evaluated
#: at most 1e-9·save_dt past the step's end (an extrapolation of that size).
SAVE_TOL = 1e-9


@numba.njit(cache=True, nogil=True)
def _save_stick(
    traj: npt.NDArray[np.float64], isave: int, save_dt: float, x1s: float, tau_s: float,
    tau_e: float, gamma0: float,
) -> int:  # pragma: no cover
    while isave < traj.shape[0] and isave * save_dt <= tau_e + SAVE_TOL * save_dt:
        ts = isave * save_dt
        traj[isave, 0] = ts
        traj[isave, 1] = x1s + gamma0 * (ts - tau_s)
        traj[isave, 2] = gamma0
        isave += 1
    return isave


@numba.njit(cache=True, nogil=True)
def _save_dense(
    traj: npt.NDArray[np.float64], isave: int, save_dt: float, tau: float, tau_e: float,
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64], h: float,
) -> int:  # pragma: no cover
    """Rows ``τ = isave·save_dt ≤ τ_e`` of ``traj`` from the dense output of the step ``[τ, τ + h]``
    (slip); returns the next row index (the slip counterpart of :func:`_save_stick`)."""
    while isave < traj.shape[0] and isave * save_dt <= tau_e + SAVE_TOL * save_dt:
        tq = (isave * save_dt - tau) / h
        traj[isave, 0] = isave * save_dt
        traj[isave, 1] = _dense(y, ynew, k, h, tq, 0)
        traj[isave, 2] = _dense(y, ynew, k, h, tq, 1)
        isave += 1
    return isave


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _hermite_root(p0: float, p1: float, d0: float, d1: float, target: float) -> float:  # pragma: no cover
    """θ in (0, 1) where the cubic Hermite interpolant of a rising path (values ``p0``, ``p1``, slopes
    ``d0``, ``d1`` per unit θ) reaches ``target`` (``p0 < target < p1``); a few Newton steps from the
    linear guess, kept inside the bracket."""
    th = (target - p0) / (p1 - p0)
    dp = p1 - p0
    for _ in range(4):
        t2 = th * th
        t3 = t2 * th
        v = p0 + d0 * (t3 - 2.0 * t2 + th) + dp * (3.0 * t2 - 2.0 * t3) + d1 * (t3 - t2) - target
        dv = d0 * (3.0 * t2 - 4.0 * th + 1.0) + dp * (6.0 * th - 6.0 * t2) + d1 * (3.0 * t2 - 2.0 * th)
        if dv <= 0.0:
            break
        th2 = th - v / dv
        if not 0.0 < th2 < 1.0:
            break
        th = th2
    return th


#: Shortest step at the belt speed, and the time the mass is carried with the belt at least when no slip
#: direction leaves it (a sliding mode: the contact model's kinetic friction μ_k(0) + μ̂(path) grows
#: along the path faster than the force); the fixed-step scheme carries it for one Δτ.
CARRY_STEP = 1e-6

#: Newton iterations at most when a step is aimed at a grid point of the process (1–2 suffice).
NODE_ITER = 8


@numba.njit(cache=True, nogil=True)
def run_accurate(
    rows: KernelRows, out: KernelOutput, i: int, settings: AccurateSettings, noise: int, path_mode: int
) -> int:  # pragma: no cover
    """Integrate trajectory (row) ``i`` from ``τ = 0`` to ``τ_end``; returns ``M`` (see module doc).

    Reads row ``i`` of ``rows`` and writes row ``i`` of ``out`` except ``out.counts``; ``traj``
    rows (``τ, x1, x2``) are filled at ``τ = k·save_dt`` from the dense output.
    """
    prm = rows.prm[i]
    shape = rows.shapes[i]
    lawp = rows.lawp
    x10 = rows.x0[i, 0]
    x20 = rows.x0[i, 1]
    proc = rows.proc
    n_proc = rows.n_proc[i]
    xgh = out.x_gh[i]
    tgh = out.t_gh[i]
    traj = out.traj[i]
    diag = out.diag[i]
    tau_end, h0, max_step, rtol, atol, save_dt = settings
    gamma0 = prm[P_GAMMA0]
    nn = prm[P_N]
    lim = nn * prm[P_MUS]
    pdx = prm[P_PROC_DX]
    use_nodes = noise == NOISE_PROCESS
    mass_path = path_mode == PATH_MASS
    kinetic0 = mu_kinetic_row(shape, 0.0, lawp, i)

    y = np.empty(3)
    ynew = np.empty(3)
    k = np.empty((7, 3))
    y[0] = x10
    y[1] = x20
    y[2] = 0.0
    tau = 0.0
    m = 0
    max_ev = xgh.shape[0]
    n_short = 0
    n_no_stick = 0
    n_break = 0
    n_phases = 0
    min_slip = np.inf
    path_slip_start = 0.0
    isave = 0

    def _lim_eff(path: float) -> float:
        if use_nodes:
            return max(lim, nn * (kinetic0 + process_value_row(proc, i, n_proc, pdx, path)))
        return lim

    stick = x20 == gamma0 and abs(stick_force(x10, 0.0, prm)) <= _lim_eff(0.0)
    # off the belt speed the relative velocity decides; on it (and outside the static band) the
    # unbalanced force does: slip backwards (s = +1) when it exceeds +limit, forwards below −limit
    if x20 == gamma0:
        s = 1.0 if stick_force(x10, 0.0, prm) >= 0.0 else -1.0
    else:
        s = 1.0 if x20 < gamma0 else -1.0
    sz = 1.0
    h = min(h0, max_step)

    while tau < tau_end:
        if stick:
            tb = breakaway_time(y[0], tau, tau_end, prm, _lim_eff(y[2]))
            te = min(tb, tau_end)
            isave = _save_stick(traj, isave, save_dt, y[0], tau, te, gamma0)
            y[0] += gamma0 * (te - tau)
            if tb >= tau_end:
                tau = tau_end
                break
            tau = tb
            stick = False
            n_break += 1
            s = 1.0 if stick_force(y[0], tau, prm) > 0.0 else -1.0
            path_slip_start = y[2]
            h = min(h0, max_step)
            continue
        # a new slip segment (after a breakaway or an event): the signs s = sign(γ0 − x2) and
        # sz = sign(x2) are fixed until the next event
        if y[1] != gamma0:
            s = 1.0 if y[1] < gamma0 else -1.0
        _f(tau, y[0], y[1], y[2], s, 1.0, prm, shape, lawp, i, noise, path_mode, proc, n_proc, k, 0)
        if y[1] != 0.0:
            sz = 1.0 if y[1] > 0.0 else -1.0
        else:
            sz = 1.0 if k[0, 1] >= 0.0 else -1.0
        k[0, 2] = sz * y[1] if mass_path else s * (gamma0 - y[1])
        # the next grid point of the process ahead (the path never decreases within a segment)
        node = (math.floor(y[2] / pdx + 1e-9) + 1.0) * pdx if use_nodes else np.inf
        # integrate the slip segment until an event
        while True:
            if tau + h > tau_end:
                h = tau_end - tau
            _step(tau, y, h, k, s, sz, prm, shape, lawp, i, noise, path_mode, proc, n_proc, ynew)
            on_node = False
            h_try = h
            if ynew[2] > node and y[2] < node:
                # the step crosses a kink of the interpolated process: aim it at the grid point
                # instead (a step across the kink would fail the error test over and over).  First
                # guess from the cubic Hermite interpolant of the path (its rate |x2| or |γ0 − x2|
                # is continuous across the kink), then Newton on the step length with the path's
                # rate k[6, 2] at the step's end
                hn = _hermite_root(y[2], ynew[2], h * k[0, 2], h * k[6, 2], node) * h
                for _ in range(NODE_ITER):
                    _step(tau, y, hn, k, s, sz, prm, shape, lawp, i, noise, path_mode, proc, n_proc, ynew)
                    res = ynew[2] - node
                    if abs(res) <= 1e-13 * pdx or k[6, 2] <= 0.0:
                        break
                    hn2 = hn - res / k[6, 2]
                    if not 0.0 < hn2 <= h or hn2 == hn:
                        break
                    hn = hn2
                on_node = abs(ynew[2] - node) <= 1e-9 * pdx
                if not on_node:  # no convergence (not seen): halve the step and try again
                    h = 0.5 * h
                    continue
                h = hn
            at_belt = False
            if y[1] == gamma0 and s * (gamma0 - ynew[1]) < 0.0:
                # a segment that starts at the belt speed is back at (or on the wrong side of) it at
                # the step's end: a short excursion (|F| just above n μ_s) that the step jumped over,
                # or a slip against the unbalanced force (equal to it within rounding: no verdict, the step
                # stands).  Shorten the step until the excursion is
                # resolved; below CARRY_STEP it is a belt contact at once (stick, carried with the belt,
                # or, if neither, carried for that step as the fixed-step scheme does)
                if h > CARRY_STEP:
                    h *= 0.25
                    continue
                at_belt = True
            err = 0.0 if at_belt else _err_norm(y, ynew, k, h, rtol, atol)
            if err > 1.0:
                h *= max(0.2, 0.9 * err ** -0.2)
                continue
            # accepted: look for events in (τ, τ + h]
            ev = EV_NONE
            th = 2.0
            g_old = s * (gamma0 - y[1])
            g_new = s * (gamma0 - ynew[1])
            if g_old > 0.0 and g_new <= 0.0:
                t1 = _root_theta(y, ynew, k, h, 1, gamma0, s)
                if t1 < th:
                    th = t1
                    ev = EV_BELT
            if mass_path and sz * ynew[1] < 0.0 and sz * y[1] > 0.0:
                t2 = _root_theta(y, ynew, k, h, 1, 0.0, -sz)  # g = sz·x2 > 0 before the crossing
                if t2 < th:
                    th = t2
                    ev = EV_ZERO_VELOCITY
            if on_node and th > 1.0:
                th = 1.0
                ev = EV_NODE
            if at_belt:
                th = 0.0
                ev = EV_BELT
            h_next = min(h * min(5.0, max(0.2, 0.9 * max(err, 1e-10) ** -0.2)), max_step)
            if on_node:  # the step was cut short by the grid point, not by the error: keep the step
                h_next = min(max(h_next, h_try), max_step)
            if ev == EV_NONE:
                isave = _save_dense(traj, isave, save_dt, tau, tau + h, y, ynew, k, h)
                tau += h
                for c in range(3):
                    y[c] = ynew[c]
                    k[0, c] = k[6, c]
                h = h_next
                if tau >= tau_end:
                    break
                continue
            if ev == EV_NODE:  # the accepted step ends on the grid point
                isave = _save_dense(traj, isave, save_dt, tau, tau + h, y, ynew, k, h)
                tau += h
                for c in range(3):
                    y[c] = ynew[c]
                y[2] = node
                h = h_next
                break  # a new segment: the process's slope changes
            # event inside the step: recompute the state exactly at it
            if not at_belt:
                hev = th * h
                isave = _save_dense(traj, isave, save_dt, tau, tau + hev, y, ynew, k, h)
                _step(tau, y, hev, k, s, sz, prm, shape, lawp, i, noise, path_mode, proc, n_proc, ynew)
                tau += hev
                for c in range(3):
                    y[c] = ynew[c]
            h = max(h_next, 1e-6)
            if ev == EV_BELT:
                y[1] = gamma0
                fs = stick_force(y[0], tau, prm)
                sticks = abs(fs) <= lim
                if not sticks:
                    n_no_stick += 1
                    le = _lim_eff(y[2])
                    if abs(fs) <= le:
                        # carried with the belt until the force enters the static band or leaves
                        # the kinetic one (carried_end)
                        rate = gamma0 if mass_path else 0.0
                        tc, sticks = carried_end(y[0], tau, tau_end, prm, lim, nn * kinetic0, proc, i, n_proc,
                                                 y[2], rate)
                        te = min(tc, tau_end)
                        isave = _save_stick(traj, isave, save_dt, y[0], tau, te, gamma0)
                        y[0] += gamma0 * (te - tau)
                        y[2] += rate * (te - tau)
                        tau = te
                        if tc >= tau_end:
                            stick = True  # still moving with the belt at τ_end
                            break
                        fs = stick_force(y[0], tau, prm)
                if sticks:
                    if m < max_ev:
                        xgh[m] = y[0]
                        tgh[m] = tau
                    m += 1
                    sp = y[2] - path_slip_start
                    n_phases += 1
                    if sp < min_slip:
                        min_slip = sp
                    if sp < pdx:
                        n_short += 1
                    stick = True
                    break
                if at_belt and tau < tau_end:
                    # neither sticking nor carried, yet no slip direction leaves the belt speed:
                    # carried with the belt for one short step (progress guaranteed)
                    hc = min(CARRY_STEP, tau_end - tau)
                    isave = _save_stick(traj, isave, save_dt, y[0], tau, tau + hc, gamma0)
                    y[0] += gamma0 * hc
                    tau += hc
                    fs = stick_force(y[0], tau, prm)
                # the friction opposes the unbalanced force (as at a breakaway)
                s = 1.0 if fs > 0.0 else -1.0
                break
            y[1] = 0.0  # EV_ZERO_VELOCITY: a new segment with sz reversed
            break
    store_diagnostics(diag, y[2], min_slip, n_short, n_no_stick, y[0], y[1], stick, n_break, n_phases)
    return m


@numba.njit(cache=True, nogil=True)
def run_accurate_batch(
    rows: KernelRows, out: KernelOutput, settings: AccurateSettings, noise: int, path_mode: int
) -> None:  # pragma: no cover
    """:func:`run_accurate` over the rows of a batch (GIL released)."""
    for i in range(rows.prm.shape[0]):
        out.counts[i] = run_accurate(rows, out, i, settings, noise, path_mode)

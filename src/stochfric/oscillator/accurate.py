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
state at the event is recomputed by one Dormand–Prince step of exactly that length.
The stick phase is solved in closed form (``x1 = x1s + γ0 (τ − τs)``); its end, the
first ``τ`` with ``|x1 + 2Dγ0 − q cos(x30 + ητ)| > n μ_s``, is found in closed form for
``q = 0`` and by a fine scan plus bisection otherwise.

With tolerances ``rtol = 1e-11``, ``atol = 1e-13`` the slip→stick positions are
independent of the initial step and of the tolerance to about 1e-9 (tests).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
import numpy.typing as npt

from .friction_laws import mu_kinetic
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
    process_value,
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
    """Slip equations (4.7)/(4.36) with the path coordinate as third state."""
    gamma0 = prm[P_GAMMA0]
    x1 = y[0]
    x2 = y[1]
    vr = gamma0 - x2
    mu = mu_kinetic(shape, prm[P_VSCALE] * abs(vr), lawp)
    if noise == NOISE_PROCESS:
        mu += process_value(proc, n_proc, prm[P_PROC_DX], y[2])
    out[0] = x2
    out[1] = slip_drift(x1, x2, 2.0 * prm[P_D], prm[P_N], mu, s) + prm[P_Q] * math.cos(
        prm[P_X30] + prm[P_ETA] * tau)
    out[2] = abs(x2) if path_mode == PATH_MASS else abs(vr)


@numba.njit(cache=True, nogil=True)
def _dopri_step(
    tau: float, y: npt.NDArray[np.float64], h: float, k: npt.NDArray[np.float64],
    s: float, prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64],
    noise: int, path_mode: int, proc: npt.NDArray[np.float64], n_proc: int,
    ynew: npt.NDArray[np.float64], tmp: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """One Dormand–Prince step; ``k[0]`` must hold f(τ, y) on entry; fills k[1..6], ynew."""
    for i in range(3):
        tmp[i] = y[i] + h * A21 * k[0, i]
    _rhs(tau + C2 * h, tmp, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[1])
    for i in range(3):
        tmp[i] = y[i] + h * (A31 * k[0, i] + A32 * k[1, i])
    _rhs(tau + C3 * h, tmp, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[2])
    for i in range(3):
        tmp[i] = y[i] + h * (A41 * k[0, i] + A42 * k[1, i] + A43 * k[2, i])
    _rhs(tau + C4 * h, tmp, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[3])
    for i in range(3):
        tmp[i] = y[i] + h * (A51 * k[0, i] + A52 * k[1, i] + A53 * k[2, i] + A54 * k[3, i])
    _rhs(tau + C5 * h, tmp, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[4])
    for i in range(3):
        tmp[i] = y[i] + h * (
            A61 * k[0, i] + A62 * k[1, i] + A63 * k[2, i] + A64 * k[3, i] + A65 * k[4, i]
        )
    _rhs(tau + h, tmp, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[5])
    for i in range(3):
        ynew[i] = y[i] + h * (
            B1 * k[0, i] + B3 * k[2, i] + B4 * k[3, i] + B5 * k[4, i] + B6 * k[5, i]
        )
    _rhs(tau + h, ynew, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[6])


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
    a = tau_s
    while a < tau_end:
        b = min(a + delta, tau_end)
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
    return np.inf


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
    lawp = rows.lawp[i]
    x10 = rows.x0[i, 0]
    x20 = rows.x0[i, 1]
    proc = rows.proc[i]
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
    kinetic0 = mu_kinetic(shape, 0.0, lawp)

    y = np.empty(3)
    ynew = np.empty(3)
    tmp = np.empty(3)
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
            return max(lim, nn * (kinetic0 + process_value(proc, n_proc, pdx, path)))
        return lim

    stick = x20 == gamma0 and abs(stick_force(x10, 0.0, prm)) <= _lim_eff(0.0)
    # off the belt speed the relative velocity decides; on it (and outside the static band) the
    # unbalanced force does: slip backwards (s = +1) when it exceeds +limit, forwards below −limit
    if x20 == gamma0:
        s = 1.0 if stick_force(x10, 0.0, prm) >= 0.0 else -1.0
    else:
        s = 1.0 if x20 < gamma0 else -1.0
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
        if y[1] != gamma0:
            s = 1.0 if y[1] < gamma0 else -1.0
        _rhs(tau, y, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[0])
        # integrate the slip segment until an event
        while True:
            if tau + h > tau_end:
                h = tau_end - tau
            _dopri_step(tau, y, h, k, s, prm, shape, lawp, noise, path_mode, proc, n_proc,
                        ynew, tmp)
            err = 0.0
            for i in range(3):
                sc = atol + rtol * max(abs(y[i]), abs(ynew[i]))
                e = h * (E1 * k[0, i] + E3 * k[2, i] + E4 * k[3, i] + E5 * k[4, i]
                         + E6 * k[5, i] + E7 * k[6, i]) / sc
                err += e * e
            err = math.sqrt(err / 3.0)
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
            if use_nodes and path_mode == PATH_MASS and y[1] * ynew[1] < 0.0:
                sg = 1.0 if y[1] < 0.0 else -1.0  # g = sg·(0 − x2) > 0 before the crossing
                t2 = _root_theta(y, ynew, k, h, 1, 0.0, sg)
                if t2 < th:
                    th = t2
                    ev = EV_ZERO_VELOCITY
            if use_nodes:
                u = y[2] / pdx
                ju = math.floor(u + 1e-9)
                node = (ju + 1) * pdx
                if ynew[2] >= node:
                    t3 = _root_theta(y, ynew, k, h, 2, node, 1.0)
                    if t3 < th:
                        th = t3
                        ev = EV_NODE
            h_next = h * min(5.0, max(0.2, 0.9 * max(err, 1e-10) ** -0.2))
            if ev == EV_NONE:
                isave = _save_dense(traj, isave, save_dt, tau, tau + h, y, ynew, k, h)
                tau += h
                for i in range(3):
                    y[i] = ynew[i]
                    k[0, i] = k[6, i]
                h = min(h_next, max_step)
                if tau >= tau_end:
                    break
                continue
            # event inside the step: recompute the state exactly at it
            hev = th * h
            isave = _save_dense(traj, isave, save_dt, tau, tau + hev, y, ynew, k, h)
            _dopri_step(tau, y, hev, k, s, prm, shape, lawp, noise, path_mode, proc, n_proc,
                        ynew, tmp)
            tau += hev
            for i in range(3):
                y[i] = ynew[i]
            h = min(max(h, 1e-6), max_step)
            if ev == EV_BELT:
                y[1] = gamma0
                if abs(stick_force(y[0], tau, prm)) <= lim:
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
                n_no_stick += 1
                s = -s
                _rhs(tau, y, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[0])
            elif ev == EV_ZERO_VELOCITY:
                y[1] = 0.0
                _rhs(tau, y, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[0])
            else:
                y[2] = (math.floor(y[2] / pdx + 0.5)) * pdx
                _rhs(tau, y, s, prm, shape, lawp, noise, path_mode, proc, n_proc, k[0])
    store_diagnostics(diag, y[2], min_slip, n_short, n_no_stick, y[0], y[1], stick, n_break, n_phases)
    return m


@numba.njit(cache=True, nogil=True)
def run_accurate_batch(
    rows: KernelRows, out: KernelOutput, settings: AccurateSettings, noise: int, path_mode: int
) -> None:  # pragma: no cover
    """:func:`run_accurate` over the rows of a batch (GIL released)."""
    for i in range(rows.prm.shape[0]):
        out.counts[i] = run_accurate(rows, out, i, settings, noise, path_mode)

"""Compiled fixed-step kernels of the friction oscillator (METHOD.md §5, thesis 4.1).

Pure numerical code: arrays in, arrays out; no I/O, no global random state.  The
random input (Wiener increments ``ΔW_k`` or one friction-process realisation) is
drawn by the caller from the trajectory's own stream and passed in, so a trajectory's
numbers never depend on which thread or process ran it.

State and equations (dimensionless, eq. 4.6/4.7): ``x1 = y/L``, ``x2 = dx1/dτ``,
``x3 = x30 + ητ`` (carried analytically), and a path coordinate for the
contact-analysis process.

* Stick (4.6):  ``x1' = γ0``, ``x2 = γ0``, while ``|x1 + 2Dγ0 − q cos x3| ≤ n μ_s``.
* Slip (4.7):   ``x1' = x2``,
  ``x2' = −x1 − 2D x2 + n (μ_k(|v_rel|) + μ̂) s + q cos x3``,
  ``s = sign(v_rel) = sign(γ0 − x2)``, ``|v_rel| = L ω0 |γ0 − x2|`` in m/s.

Schemes (``scheme``):

* ``EULER`` — the thesis's explicit Euler (4.11/4.12, 4.37/4.38); with white noise
  (``noise == NOISE_WHITE``) the Euler–Maruyama scheme (4.30/4.31) on the Itô form
  of (4.23): drift ``a − s n² σ_ζ/4`` (METHOD §5.1, erratum 3), diffusion
  ``b = n s √(σ_ζ |γ0 − X2|)``, ``ΔW = R_k √Δτ`` (erratum 4).
* ``MILSTEIN`` — strong order 1 for the white-noise model: adds
  ``½ b b' (ΔW² − Δτ)`` with the analytic ``b b' = −s n² σ_ζ/2``.

Switching (thesis, below eq. 4.12): the grid ``τ_k = kΔτ`` is fixed.  When a step
crosses a switching condition, the switching point is found by *linear
interpolation inside the step* (stick→slip: of the force ``x1 + 2Dγ0 − q cos x3``
against ``±n μ_s``; slip→stick: of ``x2`` against ``γ0``), the state is set there,
and the rest of the step is integrated with the other equations, so the grid stays
``kΔτ``.  A slip step whose remainder follows a switch uses the scaled increment
``ΔW_k √(h/Δτ)`` (an exact ``N(0, h)`` variable, independent of everything used
before in that trajectory).  When ``x2`` reaches ``γ0`` but the static-friction
condition fails, the mass keeps slipping and the friction force changes sign
(thesis Fig. 4.15); these passages are counted.
"""

from __future__ import annotations

import math

import numba
import numpy as np
import numpy.typing as npt

from .friction_laws import mu_kinetic

# --- codes -------------------------------------------------------------------
SCHEME_EULER = 0
SCHEME_MILSTEIN = 1

NOISE_NONE = 0
NOISE_WHITE = 1
NOISE_PROCESS = 2

PATH_MASS = 0  # thesis: x_glob grows by |Δx1| in every slip step (4.1.3)
PATH_RELATIVE = 1  # relative sliding distance: grows by |γ0 − x2| Δτ

# --- layout of the per-trajectory parameter row --------------------------------
P_GAMMA0 = 0
P_N = 1
P_D = 2
P_Q = 3
P_ETA = 4
P_X30 = 5
P_VSCALE = 6
P_MUS = 7
P_SIGMA = 8
P_PROC_DX = 9
N_PRM = 10

# --- layout of the per-trajectory diagnostics row ------------------------------
D_PATH = 0  # total path coordinate travelled in slip (dimensionless, = metres for L = 1 m)
D_MIN_SLIP_PATH = 1  # shortest path of a completed slip phase (inf when none)
D_N_SHORT_SLIP = 2  # completed slip phases shorter than one process grid spacing
D_N_NO_STICK = 3  # belt speed reached while static friction could not hold (Fig. 4.15)
D_X1 = 4  # final state
D_X2 = 5
D_STICK = 6
D_N_BREAKAWAY = 7  # stick→slip transitions
D_N_SLIP_PHASES = 8  # completed slip phases (ended by sticking)
N_DIAG = 9


@numba.njit(cache=True, nogil=True, inline="always")
def process_value(proc: npt.NDArray[np.float64], n_proc: int, dx: float, path: float) -> float:  # pragma: no cover
    """μ̂ at path coordinate ``path``: linear interpolation between grid points
    ``j·dx`` and periodic continuation with period ``n_proc·dx`` (thesis 4.1.3)."""
    u = path / dx
    i = math.floor(u)
    w = u - i
    i0 = int(i)
    if i0 < 0 or i0 >= n_proc:  # integer division only beyond the first period
        i0 %= n_proc
    i1 = i0 + 1  # = (i0 + 1) mod n_proc
    if i1 == n_proc:
        i1 = 0
    return (1.0 - w) * proc[i0] + w * proc[i1]


@numba.njit(cache=True, nogil=True)
def em_step(x: float, drift: float, diffusion: float, dw: float, h: float) -> float:  # pragma: no cover
    """One Euler–Maruyama step ``x + a h + b ΔW`` (Itô)."""
    return x + drift * h + diffusion * dw


@numba.njit(cache=True, nogil=True)
def milstein_step(
    x: float, drift: float, diffusion: float, bbprime: float, dw: float, h: float
) -> float:  # pragma: no cover
    """One Milstein step ``x + a h + b ΔW + ½ b b' (ΔW² − h)`` (Itô, scalar noise)."""
    return x + drift * h + diffusion * dw + 0.5 * bbprime * (dw * dw - h)


@numba.njit(cache=True, nogil=True)
def _stick_force(x1: float, tau: float, prm: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """``x1 + 2Dγ0 − q cos(x30 + ητ)``: the force the static friction must hold (4.2/4.9)."""
    return x1 + 2.0 * prm[P_D] * prm[P_GAMMA0] - prm[P_Q] * math.cos(prm[P_X30] + prm[P_ETA] * tau)


@numba.njit(cache=True, nogil=True, inline="always")
def _stick_force_hoisted(
    x1: float, tau: float, c2: float, qq: float, x30: float, eta: float, forced: bool
) -> float:  # pragma: no cover
    """:func:`_stick_force` with the invariants hoisted: ``c2 = 2Dγ0``; the cosine is
    skipped when ``q = 0`` (``forced`` false), where ``q cos x3`` is ±0 and changes nothing."""
    f = x1 + c2
    if forced:
        f -= qq * math.cos(x30 + eta * tau)
    return f


@numba.njit(cache=True, nogil=True, inline="always")
def _breakaway_limit(
    lim: float, nn: float, mu_k0: float, noise: int, proc: npt.NDArray[np.float64], n_proc: int,
    dx: float, path: float,
) -> float:  # pragma: no cover
    """The force the static friction holds in a stick phase (constant during the phase).

    ``n μ_s``; for the contact model (``noise == NOISE_PROCESS``) breakaway also needs the
    unbalanced force to exceed the kinetic friction at ``v_rel → 0``,
    ``n (μ_k(0) + μ̂(path))``, else the first slip would run against it (see docs).
    """
    if noise == NOISE_PROCESS:
        return max(lim, nn * (mu_k0 + process_value(proc, n_proc, dx, path)))
    return lim


@numba.njit(cache=True, nogil=True)
def run_fixed_step(
    prm: npt.NDArray[np.float64],
    shape: int,
    lawp: npt.NDArray[np.float64],
    x10: float,
    x20: float,
    nsteps: int,
    dt: float,
    scheme: int,
    noise: int,
    path_mode: int,
    dw: npt.NDArray[np.float64],
    proc: npt.NDArray[np.float64],
    n_proc: int,
    xgh: npt.NDArray[np.float64],
    tgh: npt.NDArray[np.float64],
    traj: npt.NDArray[np.float64],
    decimate: int,
    diag: npt.NDArray[np.float64],
) -> int:  # pragma: no cover
    """Integrate one trajectory from ``τ = 0`` over ``nsteps`` steps of ``dt``.

    Returns the number of slip→stick transitions ``M``; their positions ``X_gh`` and
    times are written to ``xgh``/``tgh`` (as many as fit).  ``traj`` (``(k, 3)``,
    rows ``τ, x1, x2``) receives every ``decimate``-th grid state when ``k > 0``.
    ``dw`` holds the Wiener increments ``ΔW_k`` (``N(0, dt)``) for white noise,
    ``proc`` the process realisation on its grid for the contact model.
    """
    gamma0 = prm[P_GAMMA0]
    nn = prm[P_N]
    dd = prm[P_D]
    qq = prm[P_Q]
    eta = prm[P_ETA]
    x30 = prm[P_X30]
    vscale = prm[P_VSCALE]
    lim = nn * prm[P_MUS]
    sigma = prm[P_SIGMA]
    pdx = prm[P_PROC_DX]
    ito = -0.25 * nn * nn * sigma  # ½ b b' / s (METHOD §5.1)
    # loop invariants, hoisted with the same rounding as the expressions they replace
    dd2 = 2.0 * dd  # 2D
    c2 = dd2 * gamma0  # 2Dγ0 of the stick force (4.2/4.9)
    forced = qq != 0.0  # q = 0: q cos x3 is ±0, the cosine is not evaluated
    white = noise == NOISE_WHITE
    contact = noise == NOISE_PROCESS
    milstein = scheme == SCHEME_MILSTEIN
    mass_path = path_mode == PATH_MASS
    mu_k0 = mu_kinetic(shape, 0.0, lawp) if contact else 0.0

    x1 = x10
    x2 = x20
    tau = 0.0
    stick = (x2 == gamma0) and (abs(_stick_force(x1, tau, prm)) <= lim)
    s = 1.0
    if x2 > gamma0:
        s = -1.0
    path = 0.0
    # static limit of the current stick phase (path, hence μ̂, is fixed while sticking)
    lim_b = _breakaway_limit(lim, nn, mu_k0, noise, proc, n_proc, pdx, path)
    path_slip_start = 0.0
    min_slip = np.inf
    n_short = 0
    n_no_stick = 0
    n_break = 0
    n_phases = 0
    m = 0
    max_ev = xgh.shape[0]
    nsave = traj.shape[0]
    if nsave > 0:
        traj[0, 0] = tau
        traj[0, 1] = x1
        traj[0, 2] = x2
    isave = 1
    tiny = 1e-12 * dt

    for k in range(nsteps):
        h = dt
        dwk = 0.0
        if white:
            dwk = dw[k]
        t_end_step = (k + 1) * dt
        it = 0
        while h > tiny and it < 8:
            it += 1
            if stick:
                x1n = x1 + gamma0 * h
                fn = _stick_force_hoisted(x1n, tau + h, c2, qq, x30, eta, forced)
                if abs(fn) <= lim_b:
                    x1 = x1n
                    h = 0.0
                else:
                    f0 = _stick_force_hoisted(x1, tau, c2, qq, x30, eta, forced)
                    bound = lim_b if fn > 0.0 else -lim_b
                    den = fn - f0
                    th = (bound - f0) / den if den != 0.0 else 1.0
                    if th < 0.0:
                        th = 0.0
                    elif th > 1.0:
                        th = 1.0
                    x1 += gamma0 * th * h
                    tau += th * h
                    h -= th * h
                    stick = False
                    n_break += 1
                    # the unbalanced force decides the direction of the first slip:
                    # F > n μ_s → the spring pulls back, x2 falls below γ0, v_rel > 0
                    s = 1.0 if fn > 0.0 else -1.0
                    path_slip_start = path
            else:
                vr = gamma0 - x2
                if vr > 0.0:
                    s = 1.0
                elif vr < 0.0:
                    s = -1.0
                avr = abs(vr)
                mu = mu_kinetic(shape, vscale * avr, lawp)
                if contact:
                    mu += process_value(proc, n_proc, pdx, path)
                drift = -x1 - dd2 * x2 + nn * mu * s
                if forced:
                    drift += qq * math.cos(x30 + eta * tau)
                x1n = x1 + x2 * h
                if white:
                    dwh = dwk if h == dt else dwk * math.sqrt(h / dt)
                    b = nn * s * math.sqrt(sigma * avr)
                    if milstein:
                        x2n = milstein_step(x2, drift + s * ito, b, 2.0 * s * ito, dwh, h)
                    else:
                        x2n = em_step(x2, drift + s * ito, b, dwh, h)
                else:
                    x2n = x2 + drift * h
                if mass_path:
                    dpath = abs(x1n - x1)
                else:
                    dpath = avr * h
                vrn = gamma0 - x2n
                if vr == 0.0 and vrn * s <= 0.0:
                    # first slip step went against the unbalanced force (friction exceeded it):
                    # the mass is carried on with the belt for this step
                    x1 += gamma0 * h
                    x2 = gamma0
                    tau += h
                    h = 0.0
                elif vr != 0.0 and vrn * s <= 0.0:
                    th = vr / (x2n - x2)
                    x1c = x1 + th * (x1n - x1)
                    tc = tau + th * h
                    if abs(_stick_force_hoisted(x1c, tc, c2, qq, x30, eta, forced)) <= lim:
                        # slip → stick: X_gh
                        if m < max_ev:
                            xgh[m] = x1c
                            tgh[m] = tc
                        m += 1
                        path += th * dpath
                        sp = path - path_slip_start
                        n_phases += 1
                        if sp < min_slip:
                            min_slip = sp
                        if sp < pdx:
                            n_short += 1
                        x1 = x1c
                        x2 = gamma0
                        h -= th * h
                        tau = tc
                        stick = True
                        lim_b = _breakaway_limit(lim, nn, mu_k0, noise, proc, n_proc, pdx, path)
                    else:
                        # belt speed reached, static friction cannot hold: keep slipping
                        n_no_stick += 1
                        x1 = x1n
                        x2 = x2n
                        path += dpath
                        tau += h
                        h = 0.0
                else:
                    x1 = x1n
                    x2 = x2n
                    path += dpath
                    tau += h
                    h = 0.0
        if stick:
            x2 = gamma0
        tau = t_end_step
        if nsave > 0 and (k + 1) % decimate == 0 and isave < nsave:
            traj[isave, 0] = tau
            traj[isave, 1] = x1
            traj[isave, 2] = x2
            isave += 1
    diag[D_PATH] = path
    diag[D_MIN_SLIP_PATH] = min_slip
    diag[D_N_SHORT_SLIP] = n_short
    diag[D_N_NO_STICK] = n_no_stick
    diag[D_X1] = x1
    diag[D_X2] = x2
    diag[D_STICK] = 1.0 if stick else 0.0
    diag[D_N_BREAKAWAY] = n_break
    diag[D_N_SLIP_PHASES] = n_phases
    return m


@numba.njit(cache=True, nogil=True)
def run_fixed_step_batch(
    prm: npt.NDArray[np.float64],
    shapes: npt.NDArray[np.int64],
    lawp: npt.NDArray[np.float64],
    x0: npt.NDArray[np.float64],
    nsteps: int,
    dt: float,
    scheme: int,
    noise: int,
    path_mode: int,
    dw: npt.NDArray[np.float64],
    proc: npt.NDArray[np.float64],
    n_proc: npt.NDArray[np.int64],
    xgh: npt.NDArray[np.float64],
    tgh: npt.NDArray[np.float64],
    counts: npt.NDArray[np.int64],
    traj: npt.NDArray[np.float64],
    decimate: int,
    diag: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """:func:`run_fixed_step` over the rows of a batch (one row per trajectory).

    Releases the GIL, so batches run in parallel threads; row ``i`` only reads row
    ``i`` of every input, so results do not depend on how rows are batched.
    """
    for i in range(prm.shape[0]):
        counts[i] = run_fixed_step(
            prm[i], shapes[i], lawp[i], x0[i, 0], x0[i, 1], nsteps, dt, scheme, noise,
            path_mode, dw[i], proc[i], n_proc[i], xgh[i], tgh[i], traj[i], decimate, diag[i],
        )

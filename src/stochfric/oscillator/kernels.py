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

from .friction_laws import mu_kinetic_row

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


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def process_value_row(
    proc: npt.NDArray[np.float64], r: int | np.uint64, n_proc: int, dx: float, path: float
) -> float:  # pragma: no cover
    """μ̂ of realisation ``proc[r]`` at path coordinate ``path``: linear interpolation between
    grid points ``j·dx`` and periodic continuation with period ``n_proc·dx`` (thesis 4.1.3)."""
    u = path / dx
    i = math.floor(u)
    w = u - i
    i0 = int(i)
    if i0 < 0 or i0 >= n_proc:  # integer division only beyond the first period
        i0 %= n_proc
    i1 = i0 + 1  # = (i0 + 1) mod n_proc
    if i1 == n_proc:
        i1 = 0
    return (1.0 - w) * proc[r, i0] + w * proc[r, i1]


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def process_value(proc: npt.NDArray[np.float64], n_proc: int, dx: float, path: float) -> float:  # pragma: no cover
    """:func:`process_value_row` for a single realisation ``proc`` (1-D)."""
    return process_value_row(proc.reshape((1, proc.shape[0])), 0, n_proc, dx, path)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def em_step(x: float, drift: float, diffusion: float, dw: float, h: float) -> float:  # pragma: no cover
    """One Euler–Maruyama step ``x + a h + b ΔW`` (Itô)."""
    return x + drift * h + diffusion * dw


@numba.njit(cache=True, nogil=True, error_model="numpy")
def milstein_step(
    x: float, drift: float, diffusion: float, bbprime: float, dw: float, h: float
) -> float:  # pragma: no cover
    """One Milstein step ``x + a h + b ΔW + ½ b b' (ΔW² − h)`` (Itô, scalar noise)."""
    return x + drift * h + diffusion * dw + 0.5 * bbprime * (dw * dw - h)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _stick_force(x1: float, tau: float, prm: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """``x1 + 2Dγ0 − q cos(x30 + ητ)``: the force the static friction must hold (4.2/4.9)."""
    return x1 + 2.0 * prm[P_D] * prm[P_GAMMA0] - prm[P_Q] * math.cos(prm[P_X30] + prm[P_ETA] * tau)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _stick_force_hoisted(
    x1: float, tau: float, c2: float, qq: float, x30: float, eta: float, forced: bool
) -> float:  # pragma: no cover
    """:func:`_stick_force` with the invariants hoisted: ``c2 = 2Dγ0``; the cosine is
    skipped when ``q = 0`` (``forced`` false), where ``q cos x3`` is ±0 and changes nothing."""
    f = x1 + c2
    if forced:
        f -= qq * math.cos(x30 + eta * tau)
    return f


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _breakaway_limit(
    lim: float, nn: float, mu_k0: float, noise: int, proc: npt.NDArray[np.float64], r: int,
    n_proc: int, dx: float, path: float,
) -> float:  # pragma: no cover
    """The force the static friction holds in a stick phase (constant during the phase).

    ``n μ_s``; for the contact model (``noise == NOISE_PROCESS``) breakaway also needs the
    unbalanced force to exceed the kinetic friction at ``v_rel → 0``,
    ``n (μ_k(0) + μ̂(path))`` with μ̂ from realisation ``proc[r]``, else the first slip
    would run against it (see docs).
    """
    if noise == NOISE_PROCESS:
        return max(lim, nn * (mu_k0 + process_value_row(proc, r, n_proc, dx, path)))
    return lim


# --- per-trajectory state of the lock-step batch kernel ------------------------------
_F_X1 = 0
_F_X2 = 1
_F_TAU = 2
_F_S = 3
_F_PATH = 4
_F_LIMB = 5  # static limit of the current stick phase (path, hence μ̂, is fixed while sticking)
_F_PSS = 6  # path at the start of the current slip phase
_F_MINSLIP = 7
_NF = 8
_I_STICK = 0
_I_M = 1
_I_NSHORT = 2
_I_NNOSTICK = 3
_I_NBREAK = 4
_I_NPHASES = 5
_I_ISAVE = 6
_NI = 7
# per-trajectory constants, hoisted with the same rounding as the expressions they replace
_C_GAMMA0 = 0
_C_NN = 1
_C_DD2 = 2  # 2D
_C_C2 = 3  # 2Dγ0 of the stick force (4.2/4.9)
_C_QQ = 4
_C_X30 = 5
_C_ETA = 6
_C_VSCALE = 7
_C_LIM = 8  # n μ_s
_C_SIGMA = 9
_C_PDX = 10
_C_ITO = 11  # ½ b b' / s = −n² σ_ζ / 4 (METHOD §5.1)
_C_MUK0 = 12  # μ_k(0), contact model only
_C_FORCED = 13  # 1.0 when q ≠ 0 (q = 0: q cos x3 is ±0 and the cosine is skipped)
_NC = 14

#: Trajectories advanced in lock-step by :func:`run_fixed_step_batch`.  One Euler step is
#: a chain of dependent operations (x2 → v_rel → μ, with a division → x2) that leaves the
#: CPU idle; interleaving independent trajectories fills it (measured ~4× on Euler).
LOCKSTEP = 8


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _advance(
    jj: int, j: int, k: int, dt: float, fs: npt.NDArray[np.float64], ist: npt.NDArray[np.int64],
    cs: npt.NDArray[np.float64], shapes: npt.NDArray[np.int64], lawp: npt.NDArray[np.float64],
    white: bool, contact: bool, milstein: bool, mass_path: bool, noise: int,
    dw: npt.NDArray[np.float64], proc: npt.NDArray[np.float64], n_proc: npt.NDArray[np.int64],
    xgh: npt.NDArray[np.float64], tgh: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """Advance trajectory ``j`` (group slot ``jj``) over grid step ``k`` (see module doc)."""
    gamma0 = cs[jj, _C_GAMMA0]
    nn = cs[jj, _C_NN]
    dd2 = cs[jj, _C_DD2]
    c2 = cs[jj, _C_C2]
    qq = cs[jj, _C_QQ]
    x30 = cs[jj, _C_X30]
    eta = cs[jj, _C_ETA]
    vscale = cs[jj, _C_VSCALE]
    lim = cs[jj, _C_LIM]
    sigma = cs[jj, _C_SIGMA]
    pdx = cs[jj, _C_PDX]
    ito = cs[jj, _C_ITO]
    forced = cs[jj, _C_FORCED] != 0.0
    shape = shapes[j]
    x1 = fs[jj, _F_X1]
    x2 = fs[jj, _F_X2]
    tau = fs[jj, _F_TAU]
    s = fs[jj, _F_S]
    path = fs[jj, _F_PATH]
    lim_b = fs[jj, _F_LIMB]
    stick = ist[jj, _I_STICK] != 0
    h = dt
    dwk = 0.0
    if white:
        dwk = dw[j, k]
    tiny = 1e-12 * dt
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
                ist[jj, _I_NBREAK] += 1
                # the unbalanced force decides the direction of the first slip:
                # F > n μ_s → the spring pulls back, x2 falls below γ0, v_rel > 0
                s = 1.0 if fn > 0.0 else -1.0
                fs[jj, _F_PSS] = path
        else:
            vr = gamma0 - x2
            if vr > 0.0:
                s = 1.0
            elif vr < 0.0:
                s = -1.0
            avr = abs(vr)
            mu = mu_kinetic_row(shape, vscale * avr, lawp, j)
            if contact:
                mu += process_value_row(proc, j, n_proc[j], pdx, path)
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
                    m = ist[jj, _I_M]
                    if m < xgh.shape[1]:
                        xgh[j, m] = x1c
                        tgh[j, m] = tc
                    ist[jj, _I_M] = m + 1
                    path += th * dpath
                    sp = path - fs[jj, _F_PSS]
                    ist[jj, _I_NPHASES] += 1
                    if sp < fs[jj, _F_MINSLIP]:
                        fs[jj, _F_MINSLIP] = sp
                    if sp < pdx:
                        ist[jj, _I_NSHORT] += 1
                    x1 = x1c
                    x2 = gamma0
                    h -= th * h
                    tau = tc
                    stick = True
                    lim_b = _breakaway_limit(lim, nn, cs[jj, _C_MUK0], noise, proc, j, n_proc[j],
                                             pdx, path)
                else:
                    # belt speed reached, static friction cannot hold: keep slipping
                    ist[jj, _I_NNOSTICK] += 1
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
    fs[jj, _F_X1] = x1
    fs[jj, _F_X2] = x2
    fs[jj, _F_TAU] = (k + 1) * dt
    fs[jj, _F_S] = s
    fs[jj, _F_PATH] = path
    fs[jj, _F_LIMB] = lim_b
    ist[jj, _I_STICK] = 1 if stick else 0


@numba.njit(cache=True, nogil=True, error_model="numpy")
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
    """Integrate every row (one trajectory each) from ``τ = 0`` over ``nsteps`` steps of ``dt``.

    Row ``i`` reads only row ``i`` of every input and writes only row ``i`` of every output:
    ``counts[i]`` = number of slip→stick transitions ``M``, their positions ``X_gh`` and
    times in ``xgh[i]``/``tgh[i]`` (as many as fit), every ``decimate``-th grid state
    (``τ, x1, x2``) in ``traj[i]`` when it has rows, diagnostics in ``diag[i]``.  ``dw[i]``
    holds the Wiener increments ``ΔW_k`` (``N(0, dt)``) for white noise, ``proc[i]`` the
    process realisation (``n_proc[i]`` points) for the contact model.

    Trajectories are advanced in groups of :data:`LOCKSTEP`, step by step; their arithmetic
    is that of a single trajectory, so the numbers do not depend on the grouping or the
    batching.  Releases the GIL, so batches run in parallel threads.
    """
    white = noise == NOISE_WHITE
    contact = noise == NOISE_PROCESS
    milstein = scheme == SCHEME_MILSTEIN
    mass_path = path_mode == PATH_MASS
    nsave = traj.shape[1]
    ntraj = prm.shape[0]
    for g0 in range(0, ntraj, LOCKSTEP):
        g1 = min(ntraj, g0 + LOCKSTEP)
        ng = g1 - g0
        fs = np.empty((ng, _NF))
        ist = np.zeros((ng, _NI), dtype=np.int64)
        cs = np.empty((ng, _NC))
        for jj in range(ng):
            j = g0 + jj
            row = prm[j]
            gamma0 = row[P_GAMMA0]
            nn = row[P_N]
            dd2 = 2.0 * row[P_D]
            cs[jj, _C_GAMMA0] = gamma0
            cs[jj, _C_NN] = nn
            cs[jj, _C_DD2] = dd2
            cs[jj, _C_C2] = dd2 * gamma0
            cs[jj, _C_QQ] = row[P_Q]
            cs[jj, _C_X30] = row[P_X30]
            cs[jj, _C_ETA] = row[P_ETA]
            cs[jj, _C_VSCALE] = row[P_VSCALE]
            lim = nn * row[P_MUS]
            cs[jj, _C_LIM] = lim
            cs[jj, _C_SIGMA] = row[P_SIGMA]
            cs[jj, _C_PDX] = row[P_PROC_DX]
            cs[jj, _C_ITO] = -0.25 * nn * nn * row[P_SIGMA]
            mu_k0 = mu_kinetic_row(shapes[j], 0.0, lawp, j) if contact else 0.0
            cs[jj, _C_MUK0] = mu_k0
            cs[jj, _C_FORCED] = 1.0 if row[P_Q] != 0.0 else 0.0
            x1 = x0[j, 0]
            x2 = x0[j, 1]
            fs[jj, _F_X1] = x1
            fs[jj, _F_X2] = x2
            fs[jj, _F_TAU] = 0.0
            fs[jj, _F_S] = -1.0 if x2 > gamma0 else 1.0
            fs[jj, _F_PATH] = 0.0
            fs[jj, _F_LIMB] = _breakaway_limit(lim, nn, mu_k0, noise, proc, j, n_proc[j],
                                               row[P_PROC_DX], 0.0)
            fs[jj, _F_PSS] = 0.0
            fs[jj, _F_MINSLIP] = np.inf
            stick = (x2 == gamma0) and (abs(_stick_force(x1, 0.0, row)) <= lim)
            ist[jj, _I_STICK] = 1 if stick else 0
            ist[jj, _I_ISAVE] = 1
            if nsave > 0:
                traj[j, 0, 0] = 0.0
                traj[j, 0, 1] = x1
                traj[j, 0, 2] = x2
        for k in range(nsteps):
            save = nsave > 0 and (k + 1) % decimate == 0
            for jj0 in range(ng):
                uj = np.uint64(jj0)  # unsigned indices: no negative-index wrap-around code
                u = np.uint64(g0 + jj0)
                # fast paths: a plain stick or slip step that crosses no switching condition,
                # with the arithmetic of the first pass of _advance, committed only if no
                # event occurs in the step (otherwise _advance redoes it from the state)
                done = False
                if ist[uj, _I_STICK] != 0:
                    gamma0 = cs[uj, _C_GAMMA0]
                    x1n = fs[uj, _F_X1] + gamma0 * dt
                    fn = _stick_force_hoisted(x1n, fs[uj, _F_TAU] + dt, cs[uj, _C_C2],
                                              cs[uj, _C_QQ], cs[uj, _C_X30], cs[uj, _C_ETA],
                                              cs[uj, _C_FORCED] != 0.0)
                    if abs(fn) <= fs[uj, _F_LIMB]:
                        fs[uj, _F_X1] = x1n
                        fs[uj, _F_X2] = gamma0
                        fs[uj, _F_TAU] = (k + 1) * dt
                        done = True
                else:
                    gamma0 = cs[uj, _C_GAMMA0]
                    x1 = fs[uj, _F_X1]
                    x2 = fs[uj, _F_X2]
                    vr = gamma0 - x2
                    if vr != 0.0:
                        s = 1.0 if vr > 0.0 else -1.0
                        avr = abs(vr)
                        nn = cs[uj, _C_NN]
                        path = fs[uj, _F_PATH]
                        mu = mu_kinetic_row(shapes[u], cs[uj, _C_VSCALE] * avr, lawp, u)
                        if contact:
                            mu += process_value_row(proc, u, n_proc[u], cs[uj, _C_PDX], path)
                        drift = -x1 - cs[uj, _C_DD2] * x2 + nn * mu * s
                        if cs[uj, _C_FORCED] != 0.0:
                            drift += cs[uj, _C_QQ] * math.cos(cs[uj, _C_X30]
                                                             + cs[uj, _C_ETA] * fs[uj, _F_TAU])
                        x1n = x1 + x2 * dt
                        if white:
                            ito = cs[uj, _C_ITO]
                            b = nn * s * math.sqrt(cs[uj, _C_SIGMA] * avr)
                            if milstein:
                                x2n = milstein_step(x2, drift + s * ito, b, 2.0 * s * ito,
                                                    dw[u, k], dt)
                            else:
                                x2n = em_step(x2, drift + s * ito, b, dw[u, k], dt)
                        else:
                            x2n = x2 + drift * dt
                        if (gamma0 - x2n) * s > 0.0:
                            fs[uj, _F_X1] = x1n
                            fs[uj, _F_X2] = x2n
                            fs[uj, _F_PATH] = path + (abs(x1n - x1) if mass_path else avr * dt)
                            fs[uj, _F_TAU] = (k + 1) * dt
                            fs[uj, _F_S] = s
                            done = True
                if not done:
                    _advance(jj0, g0 + jj0, k, dt, fs, ist, cs, shapes, lawp, white, contact, milstein,
                             mass_path, noise, dw, proc, n_proc, xgh, tgh)
                if save:
                    isave = ist[uj, _I_ISAVE]
                    if isave < nsave:
                        traj[u, isave, 0] = fs[uj, _F_TAU]
                        traj[u, isave, 1] = fs[uj, _F_X1]
                        traj[u, isave, 2] = fs[uj, _F_X2]
                        ist[uj, _I_ISAVE] = isave + 1
        for jj in range(ng):
            j = g0 + jj
            counts[j] = ist[jj, _I_M]
            diag[j, D_PATH] = fs[jj, _F_PATH]
            diag[j, D_MIN_SLIP_PATH] = fs[jj, _F_MINSLIP]
            diag[j, D_N_SHORT_SLIP] = ist[jj, _I_NSHORT]
            diag[j, D_N_NO_STICK] = ist[jj, _I_NNOSTICK]
            diag[j, D_X1] = fs[jj, _F_X1]
            diag[j, D_X2] = fs[jj, _F_X2]
            diag[j, D_STICK] = 1.0 if ist[jj, _I_STICK] != 0 else 0.0
            diag[j, D_N_BREAKAWAY] = ist[jj, _I_NBREAK]
            diag[j, D_N_SLIP_PHASES] = ist[jj, _I_NPHASES]


@numba.njit(cache=True, nogil=True, error_model="numpy")
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
    """One trajectory through :func:`run_fixed_step_batch`; returns ``M``.

    Same meaning of the arguments, for a single row (``traj`` is ``(k, 3)``).
    """
    prm2 = prm.copy().reshape((1, prm.shape[0]))
    shapes = np.full(1, shape, dtype=np.int64)
    lawp2 = lawp.copy().reshape((1, lawp.shape[0]))
    x0 = np.empty((1, 2))
    x0[0, 0] = x10
    x0[0, 1] = x20
    dw2 = dw.copy().reshape((1, dw.shape[0]))
    proc2 = proc.copy().reshape((1, proc.shape[0]))
    nproc = np.full(1, n_proc, dtype=np.int64)
    xgh2 = np.full((1, xgh.shape[0]), np.nan)
    tgh2 = np.full((1, tgh.shape[0]), np.nan)
    counts = np.zeros(1, dtype=np.int64)
    traj2 = np.zeros((1, traj.shape[0], 3))
    diag2 = np.zeros((1, diag.shape[0]))
    run_fixed_step_batch(prm2, shapes, lawp2, x0, nsteps, dt, scheme, noise, path_mode, dw2,
                         proc2, nproc, xgh2, tgh2, counts, traj2, decimate, diag2)
    m = min(int(counts[0]), xgh.shape[0])
    xgh[:m] = xgh2[0, :m]
    tgh[:m] = tgh2[0, :m]
    traj[:, :] = traj2[0]
    diag[:] = diag2[0]
    return int(counts[0])

"""Compiled fixed-step kernels of the friction oscillator (method §5, docs/method.md, thesis 4.1).

Pure numerical code: arrays in, arrays out; no I/O, no global random state.  The
random input comes from the trajectory's own stream, so a trajectory's numbers never
depend on which thread or process ran it: one friction-process realisation, or the Wiener
increments ``ΔW_k``, is passed in by the caller, or (white noise, ``WHITE_ZIGGURAT`` and
``WHITE_PHILOX``) the increments are drawn inside the kernel from the counter-based
Philox4x32-10 stream keyed by the trajectory (:mod:`stochfric.oscillator.ziggurat`,
:mod:`stochfric.oscillator.philox`; counter = step, so no buffer and no sequential state).

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
  of (4.23): drift ``a − s n² σ_ζ/4`` (method §5.1, erratum 3), diffusion
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
from typing import NamedTuple

import numba
import numpy as np
import numpy.typing as npt

from .friction_laws import SHAPE_CONSTANT, SHAPE_RATIONAL, mu_kinetic_row, mu_rational
from .philox import pair_normals
from .ziggurat import fill_pair_ziggurat, finish_pair_ziggurat

# --- codes -------------------------------------------------------------------
SCHEME_EULER = 0
SCHEME_MILSTEIN = 1

NOISE_NONE = 0
NOISE_WHITE = 1
NOISE_PROCESS = 2

PATH_MASS = 0  # thesis: x_glob grows by |Δx1| in every slip step (4.1.3)
PATH_RELATIVE = 1  # relative sliding distance: grows by |γ0 − x2| Δτ
#: reproduction mode: μ̂ read at the mass position x1 itself, μ̂_SD(X_1, ξ) as printed in eq.
#: (4.36)/(4.38); the path diagnostics still accumulate |Δx1| (the mass path)
PATH_POSITION = 2

#: Where the white-noise increments come from: given by the caller (``dw``) or drawn inside the
#: kernel from the counter-based Philox4x32-10 stream of each trajectory's key (``keys``),
#: ``ΔW_k = R_k √Δτ``, with the normals R_k by the ziggurat (``WHITE_ZIGGURAT``, the default
#: stream, :mod:`stochfric.oscillator.ziggurat`) or by Box–Muller (``WHITE_PHILOX``, the stream of
#: versions before the ziggurat, :mod:`stochfric.oscillator.philox`).
WHITE_GIVEN = 0
WHITE_PHILOX = 1
WHITE_ZIGGURAT = 2

class KernelRows(NamedTuple):
    """Per-trajectory inputs of both integrators; row ``i`` belongs to trajectory ``i``
    (:func:`stochfric.oscillator.integrate.pack_rows` builds ``prm``, ``shapes``, ``lawp``)."""

    prm: npt.NDArray[np.float64]  #: (n, N_PRM) parameter rows in the ``P_*`` layout
    shapes: npt.NDArray[np.int64]  #: (n,) friction-law shape codes (``friction_laws.SHAPE_*``)
    lawp: npt.NDArray[np.float64]  #: (n, k) friction-law parameters, zero-padded
    x0: npt.NDArray[np.float64]  #: (n, 2) initial (x1, x2)
    proc: npt.NDArray[np.float64]  #: (n, n_max) contact-process realisations (contact model)
    n_proc: npt.NDArray[np.int64]  #: (n,) points of each realisation (one period)


class KernelOutput(NamedTuple):
    """Per-trajectory outputs of both integrators (row ``i`` = trajectory ``i``)."""

    x_gh: npt.NDArray[np.float64]  #: (n, capacity) slip→stick positions X_gh (NaN beyond M)
    t_gh: npt.NDArray[np.float64]  #: (n, capacity) their times τ
    counts: npt.NDArray[np.int64]  #: (n,) M, the number of slip→stick transitions
    traj: npt.NDArray[np.float64]  #: (n, n_save, 3) saved states (τ, x1, x2); n_save may be 0
    diag: npt.NDArray[np.float64]  #: (n, N_DIAG) diagnostics in the ``D_*`` layout


class FixedStepGrid(NamedTuple):
    """The fixed-step grid: ``nsteps`` steps of ``dt``; every ``decimate``-th state is saved."""

    nsteps: int
    dt: float
    decimate: int


class WhiteInput(NamedTuple):
    """Where the white-noise increments come from: ``source`` ``WHITE_GIVEN`` (``dw[i]``, the
    increments ΔW_k of row ``i``), ``WHITE_ZIGGURAT`` or ``WHITE_PHILOX`` (drawn in the kernel
    from ``keys[i]``)."""

    source: int
    dw: npt.NDArray[np.float64]
    keys: npt.NDArray[np.uint64]


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
def store_diagnostics(
    row: npt.NDArray[np.float64], path: float, min_slip_path: float, n_short: int, n_no_stick: int,
    x1: float, x2: float, stick: bool, n_breakaway: int, n_slip_phases: int,
) -> None:  # pragma: no cover
    """Write one trajectory's diagnostics row in the ``D_*`` layout (both integrators)."""
    row[D_PATH] = path
    row[D_MIN_SLIP_PATH] = min_slip_path
    row[D_N_SHORT_SLIP] = n_short
    row[D_N_NO_STICK] = n_no_stick
    row[D_X1] = x1
    row[D_X2] = x2
    row[D_STICK] = 1.0 if stick else 0.0
    row[D_N_BREAKAWAY] = n_breakaway
    row[D_N_SLIP_PHASES] = n_slip_phases


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def process_value_row(
    proc: npt.NDArray[np.float64], r: int | np.uint64, n_proc: int, dx: float, path: float
) -> float:  # pragma: no cover
    """μ̂ of realisation ``proc[r]`` at path coordinate ``path``: linear interpolation between
    grid points ``j·dx`` and periodic continuation with period ``n_proc·dx`` (thesis 4.1.3)."""
    u = path / dx
    i = math.floor(u)
    i0, i1 = _segment_ends(i, n_proc)
    return lerp(u - i, proc[r, i0], proc[r, i1])


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _segment_ends(i: float, n_proc: int) -> tuple[int, int]:  # pragma: no cover
    """Grid indices ``(i0, i1)`` of the ends of process segment ``i = floor(path/dx)`` under the
    periodic continuation with period ``n_proc`` points."""
    i0 = int(i)
    if i0 < 0 or i0 >= n_proc:  # integer division only beyond the first period
        i0 %= n_proc
    i1 = i0 + 1  # = (i0 + 1) mod n_proc
    if i1 == n_proc:
        i1 = 0
    return i0, i1


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def lerp(w: float, v0: float, v1: float) -> float:  # pragma: no cover
    """``(1 − w) v0 + w v1``: μ̂ between two grid values (the one interpolation of the process)."""
    return (1.0 - w) * v0 + w * v1


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def process_value(proc: npt.NDArray[np.float64], n_proc: int, dx: float, path: float) -> float:  # pragma: no cover
    """:func:`process_value_row` for a single realisation ``proc`` (1-D)."""
    return process_value_row(proc.reshape((1, proc.shape[0])), 0, n_proc, dx, path)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def em_step(x: float, drift: float, diffusion: float, dw: float, h: float) -> float:  # pragma: no cover
    """One Euler–Maruyama step ``x + a h + b ΔW`` (Itô)."""
    return x + drift * h + diffusion * dw


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def milstein_step(
    x: float, drift: float, diffusion: float, bbprime: float, dw: float, h: float
) -> float:  # pragma: no cover
    """One Milstein step ``x + a h + b ΔW + ½ b b' (ΔW² − h)`` (Itô, scalar noise)."""
    return x + drift * h + diffusion * dw + 0.5 * bbprime * (dw * dw - h)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def slip_drift(x1: float, x2: float, dd2: float, nn: float, mu: float, s: float) -> float:  # pragma: no cover
    """The unforced slip acceleration of (4.7)/(4.36), ``−x1 − 2D x2 + n μ s`` (``dd2 = 2D``,
    ``s = sign(γ0 − x2)``, μ = μ_k + μ̂); the caller adds ``q cos x3`` where the case is forced.
    Every integrator (fixed step, fast passes, DOPRI5) evaluates the slip equations through it."""
    return -x1 - dd2 * x2 + nn * mu * s


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def white_velocity_step(
    x2: float, drift: float, s: float, ito: float, nn: float, sigma: float, avr: float, dw: float,
    h: float, milstein: bool,
) -> float:  # pragma: no cover
    """``x2`` after one white-noise step of length ``h`` with increment ``dw`` (method §5.1):
    Itô drift ``a − s n² σ_ζ/4`` (``ito = −n² σ_ζ/4``, erratum 3), diffusion
    ``b = n s √(σ_ζ |γ0 − x2|)``; Euler–Maruyama, or Milstein with ``b b' = 2 s·ito``."""
    b = nn * s * math.sqrt(sigma * avr)
    if milstein:
        return milstein_step(x2, drift + s * ito, b, 2.0 * s * ito, dw, h)
    return em_step(x2, drift + s * ito, b, dw, h)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def stick_force(x1: float, tau: float, prm: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """``x1 + 2Dγ0 − q cos(x30 + ητ)``: the force the static friction must hold (4.2/4.9)."""
    return x1 + 2.0 * prm[P_D] * prm[P_GAMMA0] - prm[P_Q] * math.cos(prm[P_X30] + prm[P_ETA] * tau)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _stick_force_hoisted(
    x1: float, tau: float, c2: float, qq: float, x30: float, eta: float, forced: bool
) -> float:  # pragma: no cover
    """:func:`stick_force` with the invariants hoisted: ``c2 = 2Dγ0``; the cosine is
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


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _fill_pair(
    keys: npt.NDArray[np.uint64], pair: np.uint64, sqdt: float, wk: npt.NDArray[np.float64],
    zodd: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """``wk = R_{2p} √Δτ`` and ``zodd = R_{2p+1} √Δτ`` for every lane (``pair = p``): one
    Philox block and one Box–Muller pair per lane, branch-free.  A function of its own (not
    inlined) so that the compiler vectorises this loop across the lanes."""
    for jj in range(keys.shape[0]):
        z0, z1 = pair_normals(keys[jj], pair)
        wk[jj] = z0 * sqdt
        zodd[jj] = z1 * sqdt


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _lane_candidates(
    a1: float, a2: float, gam: float, c2: float, limb: float, vscale: float, p0: float,
    p1: float, p2: float, p3: float, dt: float, forced: bool, fq_next: float,
) -> tuple[float, bool, float, float, float, float]:  # pragma: no cover
    """Fast pass, one lane: the stick candidate ``x1s`` and whether it holds (4.2), and for the
    slip candidate ``v_rel``, ``s``, ``|v_rel|`` and μ_k in rational form (the arithmetic of
    :func:`_advance`); ``fq_next = q cos x3(τ_k + Δτ)`` where the lane is ``forced``."""
    x1s = a1 + gam * dt
    f = x1s + c2
    ok_stick = abs(f - fq_next if forced else f) <= limb
    vr = gam - a2
    s = 1.0 if vr > 0.0 else -1.0
    avr = abs(vr)
    mu = mu_rational(p0, p1, p2, p3, vscale * avr)
    return x1s, ok_stick, vr, s, avr, mu


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _lane_commit(
    jj: int, good: bool, is_st: bool, x1s: float, x1n: float, x2n: float, gam: float, a1: float,
    a2: float, dp: float, s: float, vx1: npt.NDArray[np.float64], vx2: npt.NDArray[np.float64],
    vpath: npt.NDArray[np.float64], vs: npt.NDArray[np.float64], vdone: npt.NDArray[np.float64],
) -> int:  # pragma: no cover
    """Fast pass, one lane: select the stick or slip candidate (or keep the state when the
    lane needs the full step) without branches; returns 1 when it needs the full step."""
    slip_ok = good & (not is_st)
    vx1[jj] = (x1s if is_st else x1n) if good else a1
    vx2[jj] = (gam if is_st else x2n) if good else a2
    vpath[jj] = vpath[jj] + dp if slip_ok else vpath[jj]
    vs[jj] = s if slip_ok else vs[jj]
    vdone[jj] = 1.0 if good else 0.0
    return 0 if good else 1


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _forcing_terms(
    k: int, dt: float, ng: int, cforced: npt.NDArray[np.float64], cqq: npt.NDArray[np.float64],
    cx30: npt.NDArray[np.float64], ceta: npt.NDArray[np.float64], fq_now: npt.NDArray[np.float64],
    fq_next: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """The forcing ``q cos(x30 + η τ)`` of every forced lane of a group at ``τ = kΔτ`` (slip step,
    4.7) and ``τ = kΔτ + Δτ`` (end of a stick step, 4.2): the same arguments and the same ``cos``
    as :func:`_advance`, so the numbers are those of the full step.  The cosine is evaluated once
    per distinct ``(q, x30, η)`` of neighbouring lanes (the runs of one parameter set), and the
    end-of-step value is carried to the next step where ``(k+1)Δτ`` and ``kΔτ + Δτ`` are the same
    float."""
    t0 = k * dt
    t1 = t0 + dt
    carry = k > 0 and t0 == (k - 1) * dt + dt
    for jj in range(ng):
        if cforced[jj] == 0.0:
            continue
        if jj > 0 and cforced[jj - 1] != 0.0 and cqq[jj] == cqq[jj - 1] and cx30[jj] == cx30[jj - 1] \
                and ceta[jj] == ceta[jj - 1]:
            fq_now[jj] = fq_now[jj - 1]
            fq_next[jj] = fq_next[jj - 1]
            continue
        fq_now[jj] = fq_next[jj] if carry else cqq[jj] * math.cos(cx30[jj] + ceta[jj] * t0)
        fq_next[jj] = cqq[jj] * math.cos(cx30[jj] + ceta[jj] * t1)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _fast_pass_contact(
    ng: int, dt: float, vx1: npt.NDArray[np.float64], vx2: npt.NDArray[np.float64],
    vstk: npt.NDArray[np.float64], vs: npt.NDArray[np.float64], vpath: npt.NDArray[np.float64],
    vlimb: npt.NDArray[np.float64], vdone: npt.NDArray[np.float64], cg: npt.NDArray[np.float64],
    cc2: npt.NDArray[np.float64], cvs: npt.NDArray[np.float64], cp0: npt.NDArray[np.float64],
    cp1: npt.NDArray[np.float64], cp2: npt.NDArray[np.float64], cp3: npt.NDArray[np.float64],
    cd2: npt.NDArray[np.float64], cn: npt.NDArray[np.float64], cpdx: npt.NDArray[np.float64],
    pseg: npt.NDArray[np.float64], pv0: npt.NDArray[np.float64], pv1: npt.NDArray[np.float64],
    position: bool, mass_path: bool, cforced: npt.NDArray[np.float64], fq_now: npt.NDArray[np.float64],
    fq_next: npt.NDArray[np.float64],
) -> int:  # pragma: no cover
    """Branch-free fast pass of :func:`run_fixed_step_batch` for a group with the contact
    process (no white noise): μ = μ_k + μ̂, μ̂ interpolated from the lane's cached segment
    ``[pseg, pseg + 1]`` with the arithmetic of :func:`process_value_row`.  Lanes that cannot
    complete the step (an event, or the reading coordinate left the segment) are marked in
    ``vdone``; returns their number.  A loop of its own so that the plain fast pass keeps its
    SIMD code."""
    nmiss = 0
    for jj in range(ng):
        a1 = vx1[jj]
        a2 = vx2[jj]
        gam = cg[jj]
        forced = cforced[jj] != 0.0
        x1s, ok_stick, vr, s, avr, mu = _lane_candidates(a1, a2, gam, cc2[jj], vlimb[jj], cvs[jj],
                                                         cp0[jj], cp1[jj], cp2[jj], cp3[jj], dt, forced,
                                                         fq_next[jj])
        path = vpath[jj]  # loaded unconditionally: a load inside the select below kept the
        u = (a1 if position else path) / cpdx[jj]  # loop from vectorising (4.6 vs 1.1 ns/step)
        fl = math.floor(u)
        w = u - fl
        hit = fl == pseg[jj]
        mu += lerp(w, pv0[jj], pv1[jj])
        drift = slip_drift(a1, a2, cd2[jj], cn[jj], mu, s)
        drift = drift + fq_now[jj] if forced else drift
        x1n = a1 + a2 * dt
        x2n = a2 + drift * dt
        ok_slip = (vr != 0.0) & ((gam - x2n) * s > 0.0)
        dp = abs(x1n - a1) if mass_path else avr * dt
        is_st = vstk[jj] != 0.0
        good = ok_stick if is_st else (ok_slip & hit)
        nmiss += _lane_commit(jj, good, is_st, x1s, x1n, x2n, gam, a1, a2, dp, s, vx1, vx2, vpath,
                              vs, vdone)
    return nmiss


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _load_segment(
    jj: int, r: int, coord: float, dx: float, proc: npt.NDArray[np.float64],
    n_proc: npt.NDArray[np.int64], pseg: npt.NDArray[np.float64], pv0: npt.NDArray[np.float64],
    pv1: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """Lane ``jj``: the process segment ``floor(coord/dx)`` of realisation ``proc[r]`` and its
    end values, as :func:`process_value_row` indexes them (periodic continuation)."""
    i = math.floor(coord / dx)
    i0, i1 = _segment_ends(i, n_proc[r])
    pseg[jj] = i
    pv0[jj] = proc[r, i0]
    pv1[jj] = proc[r, i1]


# --- per-trajectory state of the lock-step batch kernel ------------------------------
# Group arrays are stored field-major, ``fs[field, lane]``, so that every field of a group is
# one contiguous row that the compiler can process with SIMD instructions.
_F_X1 = 0
_F_X2 = 1
_F_STK = 2  # 1.0 while sticking
_F_S = 3
_F_PATH = 4
_F_LIMB = 5  # static limit of the current stick phase (path, hence μ̂, is fixed while sticking)
_F_PSS = 6  # path at the start of the current slip phase
_F_MINSLIP = 7
_F_DONE = 8  # 1.0 when the fast pass completed the current step
_NF = 9
_I_M = 0
_I_NSHORT = 1
_I_NNOSTICK = 2
_I_NBREAK = 3
_I_NPHASES = 4
_I_ISAVE = 5
_NI = 6
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
_C_ITO = 11  # ½ b b' / s = −n² σ_ζ / 4 (method §5.1)
_C_MUK0 = 12  # μ_k(0), contact model only
_C_FORCED = 13  # 1.0 when q ≠ 0 (q = 0: q cos x3 is ±0 and the cosine is skipped)
_C_P0 = 14  # law in rational form p0/(1 + p1 v) + p2 + p3 v² (constant law: p1 = p2 = p3 = 0)
_C_P1 = 15
_C_P2 = 16
_C_P3 = 17
_NC = 18

#: Trajectories advanced in lock-step by :func:`run_fixed_step_batch`.  One trajectory's Euler
#: step is a chain of dependent operations (x2 → v_rel → μ, with a division → x2) that leaves
#: the CPU idle; a group of independent trajectories in field-major arrays fills it, and the
#: branch-free fast pass over the group is compiled to SIMD instructions.
LOCKSTEP = 32


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _advance(
    jj: int, j: int, k: int, dt: float, fs: npt.NDArray[np.float64], ist: npt.NDArray[np.int64],
    cs: npt.NDArray[np.float64], shapes: npt.NDArray[np.int64], lawp: npt.NDArray[np.float64],
    white: bool, contact: bool, milstein: bool, mass_path: bool, position: bool, noise: int,
    dwk: float, proc: npt.NDArray[np.float64], n_proc: npt.NDArray[np.int64],
    xgh: npt.NDArray[np.float64], tgh: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """Advance trajectory ``j`` (group lane ``jj``) over grid step ``k`` (see module doc);
    ``dwk`` is its Wiener increment ``ΔW_k`` (white noise only).

    The full step with the thesis's switching logic; called when the fast pass of
    :func:`run_fixed_step_batch` found an event (or cannot handle the lane).
    """
    gamma0 = cs[_C_GAMMA0, jj]
    nn = cs[_C_NN, jj]
    dd2 = cs[_C_DD2, jj]
    c2 = cs[_C_C2, jj]
    qq = cs[_C_QQ, jj]
    x30 = cs[_C_X30, jj]
    eta = cs[_C_ETA, jj]
    vscale = cs[_C_VSCALE, jj]
    lim = cs[_C_LIM, jj]
    sigma = cs[_C_SIGMA, jj]
    pdx = cs[_C_PDX, jj]
    ito = cs[_C_ITO, jj]
    forced = cs[_C_FORCED, jj] != 0.0
    shape = shapes[j]
    x1 = fs[_F_X1, jj]
    x2 = fs[_F_X2, jj]
    tau = k * dt  # = the previous step's (k_prev + 1) * dt, bit for bit
    s = fs[_F_S, jj]
    path = fs[_F_PATH, jj]
    lim_b = fs[_F_LIMB, jj]
    stick = fs[_F_STK, jj] != 0.0
    h = dt
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
                ist[_I_NBREAK, jj] += 1
                # the unbalanced force decides the direction of the first slip:
                # F > n μ_s → the spring pulls back, x2 falls below γ0, v_rel > 0
                s = 1.0 if fn > 0.0 else -1.0
                fs[_F_PSS, jj] = path
        else:
            vr = gamma0 - x2
            if vr > 0.0:
                s = 1.0
            elif vr < 0.0:
                s = -1.0
            avr = abs(vr)
            mu = mu_kinetic_row(shape, vscale * avr, lawp, j)
            if contact:
                mu += process_value_row(proc, j, n_proc[j], pdx, x1 if position else path)
            drift = slip_drift(x1, x2, dd2, nn, mu, s)
            if forced:
                drift += qq * math.cos(x30 + eta * tau)
            x1n = x1 + x2 * h
            if white:
                dwh = dwk if h == dt else dwk * math.sqrt(h / dt)
                x2n = white_velocity_step(x2, drift, s, ito, nn, sigma, avr, dwh, h, milstein)
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
                    m = ist[_I_M, jj]
                    if m < xgh.shape[1]:
                        xgh[j, m] = x1c
                        tgh[j, m] = tc
                    ist[_I_M, jj] = m + 1
                    path += th * dpath
                    sp = path - fs[_F_PSS, jj]
                    ist[_I_NPHASES, jj] += 1
                    if sp < fs[_F_MINSLIP, jj]:
                        fs[_F_MINSLIP, jj] = sp
                    if sp < pdx:
                        ist[_I_NSHORT, jj] += 1
                    x1 = x1c
                    x2 = gamma0
                    h -= th * h
                    tau = tc
                    stick = True
                    lim_b = _breakaway_limit(lim, nn, cs[_C_MUK0, jj], noise, proc, j, n_proc[j],
                                             pdx, x1c if position else path)
                else:
                    # belt speed reached, static friction cannot hold: keep slipping
                    ist[_I_NNOSTICK, jj] += 1
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
    fs[_F_X1, jj] = x1
    fs[_F_X2, jj] = x2
    fs[_F_S, jj] = s
    fs[_F_PATH, jj] = path
    fs[_F_LIMB, jj] = lim_b
    fs[_F_STK, jj] = 1.0 if stick else 0.0


@numba.njit(cache=True, nogil=True, error_model="numpy")
def run_fixed_step_batch(
    rows: KernelRows, out: KernelOutput, grid: FixedStepGrid, scheme: int, noise: int, path_mode: int,
    white_input: WhiteInput,
) -> None:  # pragma: no cover
    """Integrate every row (one trajectory each) from ``τ = 0`` over ``grid.nsteps`` steps of
    ``grid.dt``.

    Row ``i`` reads only row ``i`` of every input and writes only row ``i`` of every output:
    ``counts[i]`` = number of slip→stick transitions ``M``, their positions ``X_gh`` and
    times in ``x_gh[i]``/``t_gh[i]`` (as many as fit), every ``decimate``-th grid state
    (``τ, x1, x2``) in ``traj[i]`` when it has rows, diagnostics in ``diag[i]``.  ``dw[i]``
    holds the Wiener increments ``ΔW_k`` (``N(0, dt)``) for white noise when
    ``white_source == WHITE_GIVEN``; with ``WHITE_ZIGGURAT`` (``WHITE_PHILOX``) they are drawn
    inside the kernel, ``ΔW_k = R_k √dt`` with ``R_k`` the step-``k`` normal of the
    Philox4x32-10 stream of ``keys[i]`` by the ziggurat (Box–Muller), so no increment buffer is
    written or read and the numbers are the same as giving
    ``dw[i] = ziggurat.step_normals(keys[i], nsteps[, box_muller=True]) · √dt``.
    ``proc[i]`` is the process realisation (``n_proc[i]`` points) for the contact model.

    Trajectories are advanced in groups of :data:`LOCKSTEP`, step by step.  Every step first
    runs a branch-free fast pass over the group — a stick step without breakaway, or a slip
    step that crosses no switching condition, with exactly the arithmetic of the full step —
    and then the full step :func:`_advance` for the lanes where an event happened.  With the
    contact process, each lane keeps the process values at the ends of its current grid
    segment, so the fast pass interpolates without gathers; a lane that enters another
    segment takes the full step, after which the segment is reloaded.  With forcing, the terms
    ``q cos x3`` at ``τ_k`` and ``τ_k + Δτ`` are computed before the pass, once per distinct
    ``(q, x30, η)`` of neighbouring lanes (:func:`_forcing_terms`: the cosine does not vectorise).
    Groups with a tabulated law take a scalar fast pass instead (its table look-ups do not
    vectorise).  The numbers of a trajectory do not depend on the grouping or the batching.
    Releases the GIL, so batches run in parallel threads.
    """
    prm, shapes, lawp, x0, proc, n_proc = rows
    xgh, tgh, counts, traj, diag = out
    nsteps, dt, decimate = grid
    white_source, dw, keys = white_input
    white = noise == NOISE_WHITE
    philox = white and white_source != WHITE_GIVEN
    ziggurat = white_source == WHITE_ZIGGURAT
    sqdt = math.sqrt(dt)
    contact = noise == NOISE_PROCESS
    milstein = scheme == SCHEME_MILSTEIN
    position = path_mode == PATH_POSITION
    mass_path = path_mode == PATH_MASS or position
    nsave = traj.shape[1]
    ntraj = prm.shape[0]
    for g0 in range(0, ntraj, LOCKSTEP):
        g1 = min(ntraj, g0 + LOCKSTEP)
        ng = g1 - g0
        fs = np.empty((_NF, ng))
        ist = np.zeros((_NI, ng), dtype=np.int64)
        cs = np.zeros((_NC, ng))
        vector = True  # every law of the group in rational form: the vectorised fast pass
        forcing = False  # a lane with q ≠ 0 in the group
        for jj in range(ng):
            j = g0 + jj
            row = prm[j]
            gamma0 = row[P_GAMMA0]
            nn = row[P_N]
            dd2 = 2.0 * row[P_D]
            cs[_C_GAMMA0, jj] = gamma0
            cs[_C_NN, jj] = nn
            cs[_C_DD2, jj] = dd2
            cs[_C_C2, jj] = dd2 * gamma0
            cs[_C_QQ, jj] = row[P_Q]
            cs[_C_X30, jj] = row[P_X30]
            cs[_C_ETA, jj] = row[P_ETA]
            cs[_C_VSCALE, jj] = row[P_VSCALE]
            lim = nn * row[P_MUS]
            cs[_C_LIM, jj] = lim
            cs[_C_SIGMA, jj] = row[P_SIGMA]
            cs[_C_PDX, jj] = row[P_PROC_DX]
            cs[_C_ITO, jj] = -0.25 * nn * nn * row[P_SIGMA]
            mu_k0 = mu_kinetic_row(shapes[j], 0.0, lawp, j) if contact else 0.0
            cs[_C_MUK0, jj] = mu_k0
            cs[_C_FORCED, jj] = 1.0 if row[P_Q] != 0.0 else 0.0
            if row[P_Q] != 0.0:
                forcing = True
            if shapes[j] == SHAPE_RATIONAL:
                cs[_C_P0, jj] = lawp[j, 0]
                cs[_C_P1, jj] = lawp[j, 1]
                cs[_C_P2, jj] = lawp[j, 2]
                cs[_C_P3, jj] = lawp[j, 3]
            elif shapes[j] == SHAPE_CONSTANT:
                # p0/(1 + 0·v) + 0 + 0·v² = p0 exactly: the rational form gives the same bits
                cs[_C_P0, jj] = lawp[j, 0]
            else:
                vector = False
            x1 = x0[j, 0]
            x2 = x0[j, 1]
            fs[_F_X1, jj] = x1
            fs[_F_X2, jj] = x2
            # on the belt speed the unbalanced force decides the direction of a first slip
            # (forwards, s = −1, when it is below the static band); off it the relative velocity
            if x2 == gamma0:
                fs[_F_S, jj] = 1.0 if stick_force(x1, 0.0, row) >= 0.0 else -1.0
            else:
                fs[_F_S, jj] = -1.0 if x2 > gamma0 else 1.0
            fs[_F_PATH, jj] = 0.0
            fs[_F_LIMB, jj] = _breakaway_limit(lim, nn, mu_k0, noise, proc, j, n_proc[j],
                                               row[P_PROC_DX], x1 if position else 0.0)
            fs[_F_PSS, jj] = 0.0
            fs[_F_MINSLIP, jj] = np.inf
            stick = (x2 == gamma0) and (abs(stick_force(x1, 0.0, row)) <= lim)
            fs[_F_STK, jj] = 1.0 if stick else 0.0
            ist[_I_ISAVE, jj] = 1
            if nsave > 0:
                traj[j, 0, 0] = 0.0
                traj[j, 0, 1] = x1
                traj[j, 0, 2] = x2
        # contiguous rows of the group (views, created once per group)
        vx1 = fs[_F_X1]
        vx2 = fs[_F_X2]
        vstk = fs[_F_STK]
        vs = fs[_F_S]
        vpath = fs[_F_PATH]
        vlimb = fs[_F_LIMB]
        vdone = fs[_F_DONE]
        cg = cs[_C_GAMMA0]
        cn = cs[_C_NN]
        cd2 = cs[_C_DD2]
        cc2 = cs[_C_C2]
        cvs = cs[_C_VSCALE]
        csig = cs[_C_SIGMA]
        cito = cs[_C_ITO]
        cp0 = cs[_C_P0]
        cp1 = cs[_C_P1]
        cp2 = cs[_C_P2]
        cp3 = cs[_C_P3]
        wk = np.zeros(ng)
        # contact process read without per-step gathers: each lane keeps the grid segment
        # floor(u) of its reading coordinate u = path/dx (or x1/dx) and the two process values
        # at its ends; the fast pass interpolates from them (the same arithmetic as
        # process_value_row) and leaves lanes that entered another segment to the full step,
        # after which the segment is reloaded.
        pseg = np.full(ng, np.nan)
        pv0 = np.zeros(ng)
        pv1 = np.zeros(ng)
        cpdx = cs[_C_PDX]
        if contact:
            for jj in range(ng):
                _load_segment(jj, g0 + jj, vx1[jj] if position else vpath[jj], cpdx[jj], proc,
                              n_proc, pseg, pv0, pv1)
        wodd = np.zeros(ng)  # ΔW_{k+1}, from the same Philox block as ΔW_k
        zmiss = np.zeros((2, ng), dtype=np.uint64)  # ziggurat draws left to the slow path
        # q cos x3 of the forced lanes at τ_k (slip) and τ_k + Δτ (stick), per step
        fq_now = np.zeros(ng)
        fq_next = np.zeros(ng)
        cfz = cs[_C_FORCED]
        cqq = cs[_C_QQ]
        cx30 = cs[_C_X30]
        ceta = cs[_C_ETA]
        gkeys = keys[g0:g1] if philox else keys[:0]
        for k in range(nsteps):
            if white:
                if not philox:
                    for jj in range(ng):
                        wk[jj] = dw[g0 + jj, k]
                elif k & 1:
                    for jj in range(ng):
                        wk[jj] = wodd[jj]
                else:
                    # one Philox block per lane gives ΔW_k and ΔW_{k+1}: branch-free, vectorised
                    if not ziggurat:
                        _fill_pair(gkeys, np.uint64(k >> 1), sqdt, wk, wodd)
                    elif fill_pair_ziggurat(gkeys, np.uint64(k >> 1), sqdt, wk, wodd, zmiss):
                        finish_pair_ziggurat(gkeys, np.uint64(k >> 1), sqdt, wk, wodd, zmiss)
            if forcing:
                _forcing_terms(k, dt, ng, cfz, cqq, cx30, ceta, fq_now, fq_next)
            nmiss = 0  # lanes the fast pass could not complete
            if vector and not contact:
                # fast pass, branch-free: both candidates, then a select per lane
                for jj in range(ng):
                    a1 = vx1[jj]
                    a2 = vx2[jj]
                    gam = cg[jj]
                    forced = cfz[jj] != 0.0
                    x1s, ok_stick, vr, s, avr, mu = _lane_candidates(
                        a1, a2, gam, cc2[jj], vlimb[jj], cvs[jj], cp0[jj], cp1[jj], cp2[jj],
                        cp3[jj], dt, forced, fq_next[jj])
                    drift = slip_drift(a1, a2, cd2[jj], cn[jj], mu, s)
                    drift = drift + fq_now[jj] if forced else drift
                    x1n = a1 + a2 * dt
                    if white:
                        x2n = white_velocity_step(a2, drift, s, cito[jj], cn[jj], csig[jj], avr, wk[jj], dt,
                                                  milstein)
                    else:
                        x2n = a2 + drift * dt
                    ok_slip = (vr != 0.0) & ((gam - x2n) * s > 0.0)
                    dp = abs(x1n - a1) if mass_path else avr * dt
                    is_st = vstk[jj] != 0.0
                    good = ok_stick if is_st else ok_slip
                    nmiss += _lane_commit(jj, good, is_st, x1s, x1n, x2n, gam, a1, a2, dp, s, vx1,
                                          vx2, vpath, vs, vdone)
            elif vector:
                # the same fast pass with the contact process, read from the lanes' segment
                # caches (the same interpolation as process_value_row); a lane whose reading
                # coordinate left its segment takes the full step
                nmiss += _fast_pass_contact(ng, dt, vx1, vx2, vstk, vs, vpath, vlimb, vdone, cg,
                                            cc2, cvs, cp0, cp1, cp2, cp3, cd2, cn, cpdx, pseg, pv0,
                                            pv1, position, mass_path, cfz, fq_now, fq_next)
            else:
                # scalar fast pass (a tabulated law in the group)
                for jj in range(ng):
                    j = g0 + jj
                    done = False
                    forced = cfz[jj] != 0.0
                    if vstk[jj] != 0.0:
                        gam = cg[jj]
                        x1n = vx1[jj] + gam * dt
                        fn = x1n + cc2[jj]
                        if forced:
                            fn -= fq_next[jj]
                        if abs(fn) <= vlimb[jj]:
                            vx1[jj] = x1n
                            vx2[jj] = gam
                            done = True
                    else:
                        gam = cg[jj]
                        a1 = vx1[jj]
                        a2 = vx2[jj]
                        vr = gam - a2
                        if vr != 0.0:
                            s = 1.0 if vr > 0.0 else -1.0
                            avr = abs(vr)
                            nn = cn[jj]
                            path = vpath[jj]
                            mu = mu_kinetic_row(shapes[j], cvs[jj] * avr, lawp, j)
                            if contact:
                                mu += process_value_row(proc, j, n_proc[j], cs[_C_PDX, jj],
                                                        a1 if position else path)
                            drift = slip_drift(a1, a2, cd2[jj], nn, mu, s)
                            if forced:
                                drift += fq_now[jj]
                            x1n = a1 + a2 * dt
                            if white:
                                x2n = white_velocity_step(a2, drift, s, cito[jj], nn, csig[jj], avr, wk[jj], dt,
                                                          milstein)
                            else:
                                x2n = a2 + drift * dt
                            if (gam - x2n) * s > 0.0:
                                vx1[jj] = x1n
                                vx2[jj] = x2n
                                vpath[jj] = path + (abs(x1n - a1) if mass_path else avr * dt)
                                vs[jj] = s
                                done = True
                    vdone[jj] = 1.0 if done else 0.0
                    nmiss += 0 if done else 1
            save = nsave > 0 and (k + 1) % decimate == 0
            if nmiss == 0 and not save:
                continue  # no lane needs the full step (most steps): skip the per-lane loop
            for jj in range(ng):
                j = g0 + jj
                if vdone[jj] == 0.0:
                    _advance(jj, j, k, dt, fs, ist, cs, shapes, lawp, white, contact, milstein,
                             mass_path, position, noise, wk[jj], proc, n_proc, xgh, tgh)
                    if contact and vector:
                        _load_segment(jj, j, vx1[jj] if position else vpath[jj], cpdx[jj], proc,
                                      n_proc, pseg, pv0, pv1)
                if save:
                    isave = ist[_I_ISAVE, jj]
                    if isave < nsave:
                        traj[j, isave, 0] = (k + 1) * dt
                        traj[j, isave, 1] = vx1[jj]
                        traj[j, isave, 2] = vx2[jj]
                        ist[_I_ISAVE, jj] = isave + 1
        for jj in range(ng):
            j = g0 + jj
            counts[j] = ist[_I_M, jj]
            store_diagnostics(diag[j], fs[_F_PATH, jj], fs[_F_MINSLIP, jj], ist[_I_NSHORT, jj],
                              ist[_I_NNOSTICK, jj], fs[_F_X1, jj], fs[_F_X2, jj], fs[_F_STK, jj] != 0.0,
                              ist[_I_NBREAK, jj], ist[_I_NPHASES, jj])

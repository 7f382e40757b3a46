"""Compiled fixed-step kernels of the friction oscillator (method §5, docs/method.md, thesis 4.1).

Pure numerical code: arrays in, arrays out; no I/O, no global random state.  The
random input comes from the trajectory's own stream, so a trajectory's numbers never
depend on which thread or process ran it: one friction-process realisation, or the Wiener
increments ``ΔW_k``, is passed in by the caller, or (white noise, ``WHITE_ZIGGURAT`` and
``WHITE_PHILOX``) the increments are drawn inside the kernel from the counter-based
Philox4x32-10 stream keyed by the trajectory (:mod:`stochfric.random.ziggurat`,
:mod:`stochfric.random.philox`; counter = step, so no buffer and no sequential state).

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

One step skeleton: :func:`_stick_candidate` (the stick update and its static test) and
:func:`_slip_candidate` (the slip update, the test whether ``v_rel`` reaches zero in the step and
the path increment) are the only places these are written.  The branch-free fast pass over a
lock-step group (:func:`_fast_lane`) and the full step with the switching logic
(:func:`_full_step`) both call them; the friction law is held per trajectory in the rational form
of :func:`~stochfric.oscillator.friction_laws.mu_rational`.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numba
import numpy as np
import numpy.typing as npt

from ..random.philox import pair_normals
from ..random.ziggurat import fill_pair_ziggurat, finish_pair_ziggurat
from .friction_laws import SHAPE_CONSTANT, mu_kinetic_row, mu_rational

# --- codes (each layout below is one tuple of names; its position is its code) -------------------
SCHEME_EULER, SCHEME_MILSTEIN = range(2)
NOISE_NONE, NOISE_WHITE, NOISE_PROCESS = range(3)
(
    PATH_MASS,  # thesis: x_glob grows by |Δx1| in every slip step (4.1.3)
    PATH_RELATIVE,  # relative sliding distance: grows by |γ0 − x2| Δτ
    PATH_POSITION,  # reproduction mode: μ̂ read at x1 itself, μ̂_SD(X_1, ξ) as printed in eq. (4.36)/(4.38);
    # the path diagnostics still accumulate |Δx1| (the mass path)
) = range(3)
#: Where the white-noise increments come from: given by the caller (``WHITE_GIVEN``, ``dw``) or drawn
#: inside the kernel from the counter-based Philox4x32-10 stream of each trajectory's key (``keys``),
#: ``ΔW_k = R_k √Δτ``, with the normals R_k by Box–Muller (``WHITE_PHILOX``, the stream of versions
#: before the ziggurat, :mod:`stochfric.random.philox`) or by the ziggurat (``WHITE_ZIGGURAT``, the
#: default stream, :mod:`stochfric.random.ziggurat`).
WHITE_GIVEN, WHITE_PHILOX, WHITE_ZIGGURAT = range(3)

# --- layout of the per-trajectory parameter row (the last name is the row length) --------------
(
    P_GAMMA0,  # γ0 = v0/(L ω0)
    P_N,  # n = N/(cL)
    P_D,  # damping ratio D
    P_Q,  # forcing amplitude q = Q/(cL)
    P_ETA,  # forcing frequency η = Ω/ω0
    P_X30,  # forcing phase x3(0)
    P_VSCALE,  # L ω0 [m/s]: |v_rel| = L ω0 |γ0 − x2|
    P_MUS,  # static coefficient μ_s
    P_SIGMA,  # white-noise intensity σ_ζ
    P_PROC_DX,  # process grid spacing / L
    N_PRM,
) = range(11)

# --- layout of the per-trajectory diagnostics row (the last name is the row length) ------------
(
    D_PATH,  # total path coordinate travelled in slip (dimensionless, = metres for L = 1 m)
    D_MIN_SLIP_PATH,  # shortest path of a completed slip phase (inf when none)
    D_N_SHORT_SLIP,  # completed slip phases shorter than one process grid spacing
    D_N_NO_STICK,  # belt speed reached while static friction could not hold (Fig. 4.15)
    D_X1,  # final state
    D_X2,
    D_STICK,
    D_N_BREAKAWAY,  # stick→slip transitions
    D_N_SLIP_PHASES,  # completed slip phases (ended by sticking)
    N_DIAG,
) = range(10)

#: Trajectories advanced in lock-step by :func:`run_fixed_step_batch`.  One trajectory's Euler
#: step is a chain of dependent operations (x2 → v_rel → μ, with a division → x2) that leaves
#: the CPU idle; a group of independent trajectories in field-major arrays fills it, and the
#: branch-free fast pass over the group is compiled to SIMD instructions.
LOCKSTEP = 32

Floats = npt.NDArray[np.float64]
Ints = npt.NDArray[np.int64]


class KernelRows(NamedTuple):
    """Per-trajectory inputs of both integrators; row ``i`` belongs to trajectory ``i``
    (:func:`stochfric.oscillator.integrate.pack_rows` builds ``prm``, ``shapes``, ``lawp``)."""

    prm: Floats  #: (n, N_PRM) parameter rows in the ``P_*`` layout
    shapes: Ints  #: (n,) friction-law shape codes (``friction_laws.SHAPE_*``)
    lawp: Floats  #: (n, k) friction-law parameters, zero-padded
    x0: Floats  #: (n, 2) initial (x1, x2)
    proc: Floats  #: (n, n_max) contact-process realisations (contact model)
    n_proc: Ints  #: (n,) points of each realisation (one period)


class KernelOutput(NamedTuple):
    """Per-trajectory outputs of both integrators (row ``i`` = trajectory ``i``)."""

    x_gh: Floats  #: (n, capacity) slip→stick positions X_gh (NaN beyond M)
    t_gh: Floats  #: (n, capacity) their times τ
    counts: Ints  #: (n,) M, the number of slip→stick transitions
    traj: Floats  #: (n, n_save, 3) saved states (τ, x1, x2); n_save may be 0
    diag: Floats  #: (n, N_DIAG) diagnostics in the ``D_*`` layout


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
    dw: Floats
    keys: npt.NDArray[np.uint64]


# --- the lock-step group ------------------------------------------------------------------------
# Field-major arrays ``a[field, lane]``, so that every field of a group is one contiguous row that the
# compiler processes with SIMD instructions; their rows are named by the layouts below.  (A NamedTuple
# of per-field arrays would name them as well, but numba counts references to every member each time
# the per-step code binds such a tuple, which costs more than the step itself.)

# per-lane constants, hoisted with the same rounding as the expressions they replace
(
    _C_GAMMA0, _C_NN,
    _C_DD2,  # 2D
    _C_C2,  # 2Dγ0 of the stick force (4.2/4.9)
    _C_QQ, _C_X30, _C_ETA, _C_VSCALE,
    _C_LIM,  # n μ_s
    _C_SIGMA, _C_PDX,
    _C_ITO,  # ½ b b' / s = −n² σ_ζ / 4 (method §5.1)
    _C_MUK0,  # μ_k(0), contact model only
    _C_FORCED,  # 1.0 when q ≠ 0 (q = 0: q cos x3 is ±0 and the cosine is skipped)
    _C_P0, _C_P1, _C_P2, _C_P3,  # law in rational form p0/(1 + p1 v) + p2 + p3 v² (constant: p1 = p2 = p3 = 0)
    _NC,
) = range(19)
# per-lane state between grid steps
(
    _F_X1, _F_X2,
    _F_STK,  # 1.0 while sticking
    _F_S,  # sign(v_rel) of the current (or last) slip
    _F_PATH,
    _F_LIMB,  # static limit of the current stick phase (path, hence μ̂, is fixed while sticking)
    _F_PSS,  # path at the start of the current slip phase
    _F_MINSLIP,
    _F_DONE,  # 1.0 when the fast pass completed the current step
    # the fast pass's new (x1, x2, s, path), copied into the fields above after the pass (see _fast_lane)
    _F_NEW_X1, _F_NEW_X2, _F_NEW_S, _F_NEW_PATH,
    _NF,
) = range(14)
# per-lane counters
(
    _I_M,  # slip→stick transitions M
    _I_NSHORT, _I_NNOSTICK, _I_NBREAK, _I_NPHASES,
    _I_ISAVE,  # next row of the saved trajectory
    _NI,
) = range(7)
# per-lane inputs of grid step k besides the state
(
    _W_DW,  # ΔW_k (white noise)
    _W_FQ_NOW,  # q cos x3 at τ_k (slip step, 4.7), forced lanes
    _W_FQ_NEXT,  # q cos x3 at τ_k + Δτ (end of a stick step, 4.2), forced lanes
    _NW,
) = range(4)
# per lane: the process grid segment floor(u) of its reading coordinate u (path/dx or x1/dx) and the
# process values at its ends, so that the fast pass interpolates without gathers
_S_INDEX, _S_V0, _S_V1, _NS = range(4)


class _Modes(NamedTuple):
    """The switches of a batch, the same for every lane."""

    white: bool  #: white noise (Euler–Maruyama or Milstein)
    milstein: bool
    contact: bool  #: μ̂ of the contact-analysis process added while slipping
    position: bool  #: μ̂ read at x1 (``PATH_POSITION``), else at the path coordinate
    mass_path: bool  #: the path grows by |Δx1| (``PATH_MASS``, ``PATH_POSITION``), else |γ0 − x2| Δτ


class _Lane(NamedTuple):
    """The constants of one lane as scalars (the ``_C_*`` rows at one lane)."""

    gamma0: float
    nn: float
    dd2: float
    c2: float
    qq: float
    x30: float
    eta: float
    vscale: float
    lim: float
    sigma: float
    pdx: float
    ito: float
    muk0: float
    forced: bool
    p0: float
    p1: float
    p2: float
    p3: float


class _Extern(NamedTuple):
    """What the full step reads and writes besides the group: the process realisations and the
    slip→stick events (only the arrays it needs: each array argument adds to the cost of a call)."""

    proc: Floats
    n_proc: Ints
    x_gh: Floats
    t_gh: Floats


class _Slip(NamedTuple):
    """A slip candidate over a step of length h (:func:`_slip_candidate`)."""

    vr: float  #: γ0 − x2 at the start
    s: float
    avr: float
    x1: float
    x2: float
    dpath: float
    crosses: bool  #: v_rel reaches zero (or changes sign) within the step


class _Sub(NamedTuple):
    """A lane inside one grid step of the full step: the state at τ, h of the step left."""

    x1: float
    x2: float
    tau: float
    h: float
    s: float
    path: float
    limb: float
    stick: bool


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def store_diagnostics(
    row: Floats, path: float, min_slip_path: float, n_short: int, n_no_stick: int,
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
    proc: Floats, r: int | np.uint64, n_proc: int, dx: float, path: float
) -> float:  # pragma: no cover
    """μ̂ of realisation ``proc[r]`` at path coordinate ``path``: linear interpolation between
    grid points ``j·dx`` and periodic continuation with period ``n_proc·dx`` (thesis 4.1.3)."""
    u = path / dx
    i = math.floor(u)
    i0, i1 = segment_ends(i, n_proc)
    return lerp(u - i, proc[r, i0], proc[r, i1])


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def segment_ends(i: float, n_proc: int) -> tuple[int, int]:  # pragma: no cover
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
def process_value(proc: Floats, n_proc: int, dx: float, path: float) -> float:  # pragma: no cover
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
    Every integrator (fixed step, DOP853) evaluates the slip equations through it."""
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
def stick_force(x1: float, tau: float, prm: Floats) -> float:  # pragma: no cover
    """``x1 + 2Dγ0 − q cos(x30 + ητ)``: the force the static friction must hold (4.2/4.9)."""
    return x1 + 2.0 * prm[P_D] * prm[P_GAMMA0] - prm[P_Q] * math.cos(prm[P_X30] + prm[P_ETA] * tau)


# --- the step skeleton ------------------------------------------------------------------------


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _lane(cs: Floats, jj: int) -> _Lane:  # pragma: no cover
    """The constants of lane ``jj``."""
    return _Lane(cs[_C_GAMMA0, jj], cs[_C_NN, jj], cs[_C_DD2, jj], cs[_C_C2, jj], cs[_C_QQ, jj], cs[_C_X30, jj],
                 cs[_C_ETA, jj], cs[_C_VSCALE, jj], cs[_C_LIM, jj], cs[_C_SIGMA, jj], cs[_C_PDX, jj],
                 cs[_C_ITO, jj], cs[_C_MUK0, jj], cs[_C_FORCED, jj] != 0.0, cs[_C_P0, jj], cs[_C_P1, jj],
                 cs[_C_P2, jj], cs[_C_P3, jj])


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _forcing(ln: _Lane, tau: float) -> float:  # pragma: no cover
    """``q cos(x30 + ητ)`` of a forced lane (0 for an unforced one, which never reads it)."""
    return ln.qq * math.cos(ln.x30 + ln.eta * tau) if ln.forced else 0.0


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _held_force(x1: float, ln: _Lane, fq: float) -> float:  # pragma: no cover
    """``x1 + 2Dγ0 − q cos x3`` (4.2/4.9) with ``fq = q cos x3``: :func:`stick_force` with the
    invariants hoisted; unforced lanes skip the term (``q cos x3`` is ±0 and changes nothing)."""
    f = x1 + ln.c2
    return f - fq if ln.forced else f


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _stick_candidate(
    x1: float, h: float, ln: _Lane, fq_end: float, limb: float
) -> tuple[float, float, bool]:  # pragma: no cover
    """Stick (4.6) over ``h``: ``x1 + γ0 h``, the force at the end of the step (``fq_end = q cos x3``
    there) and whether the static friction holds it, ``|F| ≤ limb`` (4.2)."""
    x1s = x1 + ln.gamma0 * h
    f = _held_force(x1s, ln, fq_end)
    return x1s, f, abs(f) <= limb


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _slip_candidate(
    x1: float, x2: float, s_prev: float, h: float, ln: _Lane, muhat: float, fq: float, dw: float,
    modes: _Modes,
) -> _Slip:  # pragma: no cover
    """Slip (4.7) over ``h`` from ``(x1, x2)``: the explicit Euler, Euler–Maruyama or Milstein step
    (increment ``dw``; ``fq = q cos x3`` at the start; μ = μ_k + μ̂ with ``muhat`` for the contact
    model), the path increment and whether ``v_rel`` reaches zero within the step.  At
    ``v_rel = 0`` the sign ``s_prev`` is kept (the unbalanced force chose it at breakaway)."""
    vr = ln.gamma0 - x2
    s = 1.0 if vr > 0.0 else (-1.0 if vr < 0.0 else s_prev)
    avr = abs(vr)
    mu = mu_rational(ln.p0, ln.p1, ln.p2, ln.p3, ln.vscale * avr)
    mu = mu + muhat if modes.contact else mu
    drift = slip_drift(x1, x2, ln.dd2, ln.nn, mu, s)
    drift = drift + fq if ln.forced else drift
    x1n = x1 + x2 * h
    if modes.white:
        x2n = white_velocity_step(x2, drift, s, ln.ito, ln.nn, ln.sigma, avr, dw, h, modes.milstein)
    else:
        x2n = x2 + drift * h
    dpath = abs(x1n - x1) if modes.mass_path else avr * h
    return _Slip(vr, s, avr, x1n, x2n, dpath, (ln.gamma0 - x2n) * s <= 0.0)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _breakaway_limit(ln: _Lane, contact: bool, muhat: float) -> float:  # pragma: no cover
    """The force the static friction holds in a stick phase (constant during the phase).

    ``n μ_s``; for the contact model breakaway also needs the unbalanced force to exceed the
    kinetic friction at ``v_rel → 0``, ``n (μ_k(0) + μ̂)`` with μ̂ = ``muhat`` where the phase
    started, else the first slip would run against it (see docs).
    """
    return max(ln.lim, ln.nn * (ln.muk0 + muhat)) if contact else ln.lim


# --- the fast pass: a step without an event, branch-free over the group --------------------------


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _fast_lane(
    jj: int, dt: float, cs: Floats, fs: Floats, stp: Floats, modes: _Modes, muhat: float, hit: bool
) -> int:  # pragma: no cover
    """Lane ``jj``: both candidates, then a select (no branch) of the stick step without breakaway
    or the slip step that crosses no switching condition; anything else — and a slip at ``v_rel = 0``
    or one whose process segment is not cached (``hit`` false) — is left to the full step.  Returns
    1 when the lane needs it.  The new (x1, x2, s, path) go to the ``_F_NEW_*`` fields (the old values
    where the step is not taken), which the caller copies into the state fields after the pass: stored
    into the field they were loaded from, the store of an old value is redundant, the compiler drops it
    and the loop's stores become masked stores, which AMD's Zen 2/3 execute as microcode.  For the same
    reason the new values are chosen by one two-way select each (stick, then slip) and stored after all
    selects: nested ternaries compiled to 4 masked stores and 4–7 masked loads per 4 lanes on AVX2 (Zen 3:
    0.68–0.75 of the time without them, the same bits; docs/performance.md, "Side by side")."""
    ln = _lane(cs, jj)
    a1 = fs[_F_X1, jj]
    a2 = fs[_F_X2, jj]
    x1s, _, ok_stick = _stick_candidate(a1, dt, ln, stp[_W_FQ_NEXT, jj], fs[_F_LIMB, jj])
    # s_prev = −1: a slip from v_rel = 0 is the full step's, so the fast pass never uses s there
    sl = _slip_candidate(a1, a2, -1.0, dt, ln, muhat, stp[_W_FQ_NOW, jj], stp[_W_DW, jj], modes)
    is_st = fs[_F_STK, jj] != 0.0
    stick_ok = is_st & ok_stick
    slip_ok = (not is_st) & (sl.vr != 0.0) & (not sl.crosses) & hit
    good = stick_ok | slip_ok
    path = fs[_F_PATH, jj]
    s_old = fs[_F_S, jj]
    # one two-way select per value (no nested ternaries): each folds into a select instruction, so
    # no store ends up in a conditional block (which the vectoriser turns into masked stores)
    nx1 = x1s if stick_ok else a1
    nx1 = sl.x1 if slip_ok else nx1
    nx2 = ln.gamma0 if stick_ok else a2
    nx2 = sl.x2 if slip_ok else nx2
    npath = path + sl.dpath if slip_ok else path
    ns = sl.s if slip_ok else s_old
    done = 1.0 if good else 0.0
    fs[_F_NEW_X1, jj] = nx1
    fs[_F_NEW_X2, jj] = nx2
    fs[_F_NEW_PATH, jj] = npath
    fs[_F_NEW_S, jj] = ns
    fs[_F_DONE, jj] = done
    return 0 if good else 1


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _cached_process(
    jj: int, fs: Floats, seg: Floats, pdx: float, position: bool
) -> tuple[float, bool]:  # pragma: no cover
    """μ̂ of lane ``jj`` from its cached segment (the arithmetic of :func:`process_value_row`) and
    whether its reading coordinate is still in that segment."""
    x1 = fs[_F_X1, jj]  # both loaded unconditionally: a load inside the select
    path = fs[_F_PATH, jj]  # kept the loop from vectorising
    u = (x1 if position else path) / pdx
    fl = math.floor(u)
    return lerp(u - fl, seg[_S_V0, jj], seg[_S_V1, jj]), fl == seg[_S_INDEX, jj]


# --- the full step: the thesis's switching logic inside the step ---------------------------------
# The substeps are scalar functions: the full step reads and writes the group's arrays itself (numba
# would count references to the arrays of an inlined function with branches in every substep).

#: what happened in a slip substep
_EV_NONE, _EV_STICK, _EV_NO_STICK = range(3)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _stick_substep(sub: _Sub, ln: _Lane) -> tuple[_Sub, bool]:  # pragma: no cover
    """Stick over the rest ``h`` of the step, or breakaway inside it (returned true): located by
    linear interpolation of the force against ``±limb``; the rest of the step then slips."""
    x1s, fn, holds = _stick_candidate(sub.x1, sub.h, ln, _forcing(ln, sub.tau + sub.h), sub.limb)
    if holds:
        return _Sub(x1s, sub.x2, sub.tau, 0.0, sub.s, sub.path, sub.limb, True), False
    f0 = _held_force(sub.x1, ln, _forcing(ln, sub.tau))
    bound = sub.limb if fn > 0.0 else -sub.limb
    den = fn - f0
    th = (bound - f0) / den if den != 0.0 else 1.0
    if th < 0.0:
        th = 0.0
    elif th > 1.0:
        th = 1.0
    # the unbalanced force decides the direction of the first slip:
    # F > n μ_s → the spring pulls back, x2 falls below γ0, v_rel > 0
    s = 1.0 if fn > 0.0 else -1.0
    return _Sub(sub.x1 + ln.gamma0 * th * sub.h, sub.x2, sub.tau + th * sub.h, sub.h - th * sub.h, s,
                sub.path, sub.limb, False), True


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _slip_substep(
    sub: _Sub, dt: float, dwk: float, ln: _Lane, muhat: float, modes: _Modes
) -> tuple[_Sub, int]:  # pragma: no cover
    """Slip over the rest ``h`` of the grid step (increment ``ΔW_k √(h/Δτ)``).  Where ``v_rel``
    reaches zero inside it, the crossing by linear interpolation of ``x2``: there the mass sticks
    (``_EV_STICK``, the state at the crossing; X_gh) if the static friction holds the force, else
    it keeps slipping through the belt speed (``_EV_NO_STICK``, Fig. 4.15)."""
    dwh = 0.0
    if modes.white:
        dwh = dwk if sub.h == dt else dwk * math.sqrt(sub.h / dt)
    sl = _slip_candidate(sub.x1, sub.x2, sub.s, sub.h, ln, muhat, _forcing(ln, sub.tau), dwh, modes)
    ends = _Sub(sl.x1, sl.x2, sub.tau + sub.h, 0.0, sl.s, sub.path + sl.dpath, sub.limb, False)
    if not sl.crosses:
        return ends, _EV_NONE
    if sl.vr == 0.0:
        # first slip step went against the unbalanced force (friction exceeded it): the mass is
        # carried on with the belt for this step
        return _Sub(sub.x1 + ln.gamma0 * sub.h, ln.gamma0, sub.tau + sub.h, 0.0, sl.s, sub.path, sub.limb,
                    False), _EV_NONE
    th = sl.vr / (sl.x2 - sub.x2)
    x1c = sub.x1 + th * (sl.x1 - sub.x1)
    tc = sub.tau + th * sub.h
    if not abs(_held_force(x1c, ln, _forcing(ln, tc))) <= ln.lim:
        return ends, _EV_NO_STICK
    return _Sub(x1c, ln.gamma0, tc, sub.h - th * sub.h, sl.s, sub.path + th * sl.dpath, sub.limb, True), _EV_STICK


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _full_step(
    jj: int, j: int, k: int, dt: float, dwk: float, cs: Floats, fs: Floats, ist: Ints, ext: _Extern, modes: _Modes,
) -> None:  # pragma: no cover
    """Advance trajectory ``j`` (group lane ``jj``) over grid step ``k`` with the switching logic
    (module doc); ``dwk`` is its Wiener increment ``ΔW_k`` (white noise only).  Called where the
    fast pass found an event."""
    ln = _lane(cs, jj)
    # τ = k·dt is the previous step's (k_prev + 1)·dt, bit for bit
    sub = _Sub(fs[_F_X1, jj], fs[_F_X2, jj], k * dt, dt, fs[_F_S, jj], fs[_F_PATH, jj], fs[_F_LIMB, jj],
               fs[_F_STK, jj] != 0.0)
    tiny = 1e-12 * dt
    it = 0
    while sub.h > tiny and it < 8:
        it += 1
        if sub.stick:
            sub, broke = _stick_substep(sub, ln)
            if broke:
                ist[_I_NBREAK, jj] += 1
                fs[_F_PSS, jj] = sub.path
            continue
        muhat = 0.0
        if modes.contact:
            muhat = process_value_row(ext.proc, j, ext.n_proc[j], ln.pdx, sub.x1 if modes.position else sub.path)
        sub, event = _slip_substep(sub, dt, dwk, ln, muhat, modes)
        if event == _EV_NO_STICK:
            ist[_I_NNOSTICK, jj] += 1
        elif event == _EV_STICK:  # slip → stick: X_gh
            m = ist[_I_M, jj]
            if m < ext.x_gh.shape[1]:
                ext.x_gh[j, m] = sub.x1
                ext.t_gh[j, m] = sub.tau
            ist[_I_M, jj] = m + 1
            sp = sub.path - fs[_F_PSS, jj]
            ist[_I_NPHASES, jj] += 1
            if sp < fs[_F_MINSLIP, jj]:
                fs[_F_MINSLIP, jj] = sp
            if sp < ln.pdx:
                ist[_I_NSHORT, jj] += 1
            # the static limit of the stick phase that starts here (μ̂ read where it starts)
            mu_start = 0.0
            if modes.contact:
                mu_start = process_value_row(ext.proc, j, ext.n_proc[j], ln.pdx, sub.x1 if modes.position else sub.path)
            limb = _breakaway_limit(ln, modes.contact, mu_start)
            sub = _Sub(sub.x1, sub.x2, sub.tau, sub.h, sub.s, sub.path, limb, True)
    fs[_F_X1, jj] = sub.x1
    fs[_F_X2, jj] = ln.gamma0 if sub.stick else sub.x2
    fs[_F_S, jj] = sub.s
    fs[_F_PATH, jj] = sub.path
    fs[_F_LIMB, jj] = sub.limb
    fs[_F_STK, jj] = 1.0 if sub.stick else 0.0


# --- one lock-step group -----------------------------------------------------------------------


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _forcing_terms(k: int, dt: float, cs: Floats, stp: Floats) -> None:  # pragma: no cover
    """The forcing ``q cos(x30 + η τ)`` of every forced lane of a group at ``τ = kΔτ`` (slip step,
    4.7) and ``τ = kΔτ + Δτ`` (end of a stick step, 4.2), into ``stp[_W_FQ_NOW]`` and
    ``stp[_W_FQ_NEXT]``: the same arguments and the same ``cos`` as the full step, so the numbers
    are those of the full step.  The cosine is evaluated once per distinct ``(q, x30, η)`` of
    neighbouring lanes (the runs of one parameter set), and the end-of-step value is carried to the
    next step where ``(k+1)Δτ`` and ``kΔτ + Δτ`` are the same float."""
    t0 = k * dt
    t1 = t0 + dt
    carry = k > 0 and t0 == (k - 1) * dt + dt
    forced, qq, x30, eta = cs[_C_FORCED], cs[_C_QQ], cs[_C_X30], cs[_C_ETA]
    fq_now, fq_next = stp[_W_FQ_NOW], stp[_W_FQ_NEXT]
    for jj in range(forced.shape[0]):
        if forced[jj] == 0.0:
            continue
        if jj > 0 and forced[jj - 1] != 0.0 and qq[jj] == qq[jj - 1] and x30[jj] == x30[jj - 1] \
                and eta[jj] == eta[jj - 1]:
            fq_now[jj] = fq_now[jj - 1]
            fq_next[jj] = fq_next[jj - 1]
            continue
        fq_now[jj] = fq_next[jj] if carry else qq[jj] * math.cos(x30[jj] + eta[jj] * t0)
        fq_next[jj] = qq[jj] * math.cos(x30[jj] + eta[jj] * t1)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _fill_pair(
    keys: npt.NDArray[np.uint64], pair: np.uint64, sqdt: float, wk: Floats, zodd: Floats,
) -> None:  # pragma: no cover
    """``wk = R_{2p} √Δτ`` and ``zodd = R_{2p+1} √Δτ`` for every lane (``pair = p``): one
    Philox block and one Box–Muller pair per lane, branch-free.  A function of its own (not
    inlined) so that the compiler vectorises this loop across the lanes."""
    for jj in range(keys.shape[0]):
        z0, z1 = pair_normals(keys[jj], pair)
        wk[jj] = z0 * sqdt
        zodd[jj] = z1 * sqdt


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _load_segment(
    jj: int, r: int, coord: float, dx: float, proc: Floats, n_proc: Ints, seg: Floats
) -> None:  # pragma: no cover
    """Lane ``jj``: the process segment ``floor(coord/dx)`` of realisation ``proc[r]`` and its
    end values, as :func:`process_value_row` indexes them (periodic continuation)."""
    i = math.floor(coord / dx)
    i0, i1 = segment_ends(i, n_proc[r])
    seg[_S_INDEX, jj] = i
    seg[_S_V0, jj] = proc[r, i0]
    seg[_S_V1, jj] = proc[r, i1]


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _init_lane(
    cs: Floats, fs: Floats, jj: int, rows: KernelRows, j: int, modes: _Modes
) -> None:  # pragma: no cover
    """Lane ``jj`` of a group: the constants of trajectory ``j`` and its state at ``τ = 0``."""
    row = rows.prm[j]
    gamma0 = row[P_GAMMA0]
    nn = row[P_N]
    cs[_C_GAMMA0, jj] = gamma0
    cs[_C_NN, jj] = nn
    cs[_C_DD2, jj] = 2.0 * row[P_D]
    cs[_C_C2, jj] = cs[_C_DD2, jj] * gamma0
    cs[_C_QQ, jj] = row[P_Q]
    cs[_C_X30, jj] = row[P_X30]
    cs[_C_ETA, jj] = row[P_ETA]
    cs[_C_VSCALE, jj] = row[P_VSCALE]
    cs[_C_LIM, jj] = nn * row[P_MUS]
    cs[_C_SIGMA, jj] = row[P_SIGMA]
    cs[_C_PDX, jj] = row[P_PROC_DX]
    cs[_C_ITO, jj] = -0.25 * nn * nn * row[P_SIGMA]
    cs[_C_MUK0, jj] = mu_kinetic_row(rows.shapes[j], 0.0, rows.lawp, j) if modes.contact else 0.0
    cs[_C_FORCED, jj] = 1.0 if row[P_Q] != 0.0 else 0.0
    cs[_C_P0, jj] = rows.lawp[j, 0]
    if rows.shapes[j] != SHAPE_CONSTANT:  # p0/(1 + 0·v) + 0 + 0·v² = p0: the same bits
        cs[_C_P1, jj] = rows.lawp[j, 1]
        cs[_C_P2, jj] = rows.lawp[j, 2]
        cs[_C_P3, jj] = rows.lawp[j, 3]
    x1 = rows.x0[j, 0]
    x2 = rows.x0[j, 1]
    fs[_F_X1, jj] = x1
    fs[_F_X2, jj] = x2
    # on the belt speed the unbalanced force decides the direction of a first slip
    # (forwards, s = −1, when it is below the static band); off it the relative velocity
    if x2 == gamma0:
        fs[_F_S, jj] = 1.0 if stick_force(x1, 0.0, row) >= 0.0 else -1.0
    else:
        fs[_F_S, jj] = -1.0 if x2 > gamma0 else 1.0
    muhat = process_value_row(rows.proc, j, rows.n_proc[j], row[P_PROC_DX], x1 if modes.position else 0.0) \
        if modes.contact else 0.0
    fs[_F_LIMB, jj] = _breakaway_limit(_lane(cs, jj), modes.contact, muhat)
    fs[_F_MINSLIP, jj] = np.inf
    fs[_F_STK, jj] = 1.0 if (x2 == gamma0) and (abs(stick_force(x1, 0.0, row)) <= cs[_C_LIM, jj]) else 0.0


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _run_group(
    g0: int, ng: int, rows: KernelRows, out: KernelOutput, grid: FixedStepGrid, white: WhiteInput, modes: _Modes,
) -> None:  # pragma: no cover
    """Integrate the group of trajectories ``g0 … g0 + ng − 1`` over every step of the grid: per step
    the white-noise increments, the forcing terms, the fast pass, and the full step where an event
    happened.  (The group's arrays are allocated here, where the compiler sees that they do not
    overlap; as arguments they would need run-time overlap checks in the SIMD loops.)"""
    nsteps, dt, decimate = grid
    proc, n_proc, traj = rows.proc, rows.n_proc, out.traj
    nsave = traj.shape[1]
    # LOCKSTEP columns also for a smaller last group: a row stride the compiler knows lets it prove that
    # the fast pass's _F_NEW_* rows do not overlap the rows it reads, so the pass stays a SIMD loop
    # (with a run-time stride: "unsafe dependent memory operations", a scalar loop)
    cs = np.zeros((_NC, LOCKSTEP))
    fs = np.zeros((_NF, LOCKSTEP))
    ist = np.zeros((_NI, LOCKSTEP), dtype=np.int64)
    for jj in range(ng):
        _init_lane(cs, fs, jj, rows, g0 + jj, modes)
        ist[_I_ISAVE, jj] = 1
        if nsave > 0:
            traj[g0 + jj, 0, 0] = 0.0
            traj[g0 + jj, 0, 1] = fs[_F_X1, jj]
            traj[g0 + jj, 0, 2] = fs[_F_X2, jj]
    ext = _Extern(proc, n_proc, out.x_gh, out.t_gh)
    stp = np.zeros((_NW, LOCKSTEP))
    seg = np.zeros((_NS, LOCKSTEP))
    seg[_S_INDEX] = np.nan
    if modes.contact:
        for jj in range(ng):
            _load_segment(jj, g0 + jj, fs[_F_X1, jj] if modes.position else fs[_F_PATH, jj], cs[_C_PDX, jj],
                          proc, n_proc, seg)
    in_kernel = modes.white and white.source != WHITE_GIVEN
    source, dw = white.source, white.dw
    keys = white.keys[g0:g0 + ng] if in_kernel else white.keys[:0]
    wk = stp[_W_DW]
    odd = np.zeros(ng)  # ΔW_{k+1}, from the same Philox block as ΔW_k
    miss = np.zeros((2, ng), dtype=np.uint64)  # ziggurat draws left to the slow path
    sqdt = math.sqrt(dt)
    forcing = False  # a lane with q ≠ 0 in the group
    for jj in range(ng):
        forcing = forcing or cs[_C_FORCED, jj] != 0.0
    # the switches of the fast pass as constants, per noise model: a switch read inside a SIMD loop
    # would make it compute both branches
    as_contact = _Modes(False, False, True, modes.position, modes.mass_path)
    as_white = _Modes(True, modes.milstein, False, modes.position, modes.mass_path)
    as_plain = _Modes(False, False, False, modes.position, modes.mass_path)
    # The draws and the loops over the lanes are written here rather than in inlined functions of
    # their own: an inlined function that takes arrays and holds a loop or a branch left numba's
    # reference counting of those arrays in every step (an atomic operation each, in all more than
    # the step).  The per-lane functions called inside the loops do not.
    for k in range(nsteps):
        if modes.white:  # ΔW_k: given, or drawn for steps k and k + 1 at once at even k
            if not in_kernel:
                for jj in range(ng):
                    wk[jj] = dw[g0 + jj, k]
            elif k & 1:
                for jj in range(ng):
                    wk[jj] = odd[jj]
            elif source == WHITE_PHILOX:
                _fill_pair(keys, np.uint64(k >> 1), sqdt, wk, odd)
            elif fill_pair_ziggurat(keys, np.uint64(k >> 1), sqdt, wk, odd, miss):
                finish_pair_ziggurat(keys, np.uint64(k >> 1), sqdt, wk, odd, miss)
        if forcing:
            _forcing_terms(k, dt, cs, stp)
        # the fast pass (:func:`_fast_lane`), one loop per noise model
        nmiss = 0
        if modes.contact:
            for jj in range(ng):
                muhat, hit = _cached_process(jj, fs, seg, cs[_C_PDX, jj], modes.position)
                nmiss += _fast_lane(jj, dt, cs, fs, stp, as_contact, muhat, hit)
        elif modes.white:
            for jj in range(ng):
                nmiss += _fast_lane(jj, dt, cs, fs, stp, as_white, 0.0, True)
        else:
            for jj in range(ng):
                nmiss += _fast_lane(jj, dt, cs, fs, stp, as_plain, 0.0, True)
        for jj in range(ng):  # unconditional stores (see _fast_lane)
            fs[_F_X1, jj] = fs[_F_NEW_X1, jj]
            fs[_F_X2, jj] = fs[_F_NEW_X2, jj]
            fs[_F_PATH, jj] = fs[_F_NEW_PATH, jj]
            fs[_F_S, jj] = fs[_F_NEW_S, jj]
        save = nsave > 0 and (k + 1) % decimate == 0
        if nmiss == 0 and not save:
            continue  # no lane needs the full step (most steps): skip the per-lane loop
        for jj in range(ng):
            j = g0 + jj
            if fs[_F_DONE, jj] == 0.0:
                _full_step(jj, j, k, dt, wk[jj], cs, fs, ist, ext, modes)
                if modes.contact:
                    _load_segment(jj, j, fs[_F_X1, jj] if modes.position else fs[_F_PATH, jj], cs[_C_PDX, jj],
                                  proc, n_proc, seg)
            isave = ist[_I_ISAVE, jj]
            if save and isave < nsave:
                traj[j, isave, 0] = (k + 1) * dt
                traj[j, isave, 1] = fs[_F_X1, jj]
                traj[j, isave, 2] = fs[_F_X2, jj]
                ist[_I_ISAVE, jj] = isave + 1
    for jj in range(ng):
        j = g0 + jj
        out.counts[j] = ist[_I_M, jj]
        store_diagnostics(out.diag[j], fs[_F_PATH, jj], fs[_F_MINSLIP, jj], ist[_I_NSHORT, jj], ist[_I_NNOSTICK, jj],
                          fs[_F_X1, jj], fs[_F_X2, jj], fs[_F_STK, jj] != 0.0, ist[_I_NBREAK, jj], ist[_I_NPHASES, jj])


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
    step that crosses no switching condition, with exactly the arithmetic of the full step (the
    same step skeleton) — and then the full step :func:`_full_step` for the lanes where an event
    happened.  With the contact process, each lane keeps the process values at the ends of its
    current grid segment, so the fast pass interpolates without gathers; a lane that enters
    another segment takes the full step, after which the segment is reloaded.  With forcing, the
    terms ``q cos x3`` at ``τ_k`` and ``τ_k + Δτ`` are computed before the pass, once per distinct
    ``(q, x30, η)`` of neighbouring lanes (:func:`_forcing_terms`: the cosine does not vectorise).
    The numbers of a trajectory do not depend on the grouping or the batching.  Releases the
    GIL, so batches run in parallel threads.
    """
    position = path_mode == PATH_POSITION
    modes = _Modes(noise == NOISE_WHITE, scheme == SCHEME_MILSTEIN, noise == NOISE_PROCESS, position,
                   path_mode == PATH_MASS or position)
    ntraj = rows.prm.shape[0]
    for g0 in range(0, ntraj, LOCKSTEP):
        _run_group(g0, min(ntraj, g0 + LOCKSTEP) - g0, rows, out, grid, white_input, modes)

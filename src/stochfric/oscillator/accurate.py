"""The ``accurate`` integrator: adaptive Dormand–Prince 8(5,3) (DOP853) with event location.

For the deterministic and the contact-analysis models (no SDE).  Between events the
slip equations (4.7) / (4.36) are smooth, so an adaptive high-order embedded Runge–Kutta pair keeps
its order: Hairer's DOP853 (order 8, error estimate from the embedded 5th- and 3rd-order solutions,
7th-order dense output; Hairer, Nørsett & Wanner, *Solving ODEs I*, §II.10; the coefficients are
scipy's ``solve_ivp(method="DOP853")``, in :mod:`~stochfric.oscillator.dop853_tableau`).  The thesis's
reference was MATLAB ``ode45`` (Dormand–Prince 5(4)); at the tolerances used here DOP853 takes about a
third of the steps for the same accuracy.  Every non-smooth point is an *event* at which the integration restarts:

* ``x2 = γ0`` (``v_rel = 0``): slip→stick if ``|x1 + 2Dγ0 − q cos x3| ≤ n μ_s``,
  otherwise the mass passes the belt speed and keeps slipping (thesis Fig. 4.15);
* ``x2 = 0`` when the path coordinate is the mass path (``|x2|`` has a kink there);
* the path coordinate crossing a grid point of the friction process (the linear
  interpolation of μ̂ has a kink at every grid point).

Within a slip segment the signs ``s = sign(γ0 − x2)`` and ``sign(x2)`` and, for the contact model,
the linear function of the process's current grid cell (extended past the cell's end) are held
(:class:`Segment`), so the right-hand side is smooth and no step straddling an event is rejected by the
error control.  After an accepted step the first event inside it is located on the dense output
(bisection to ``θ`` resolution 1e-15; grid points by Illinois regula falsi to 1e-12 Δx), and the state
there is the dense output's (7th order, so within the step's tolerance).  An event is looked for where
the signs at the step's ends differ, and also where ``x2`` has an extremum inside the step toward the
belt speed (toward 0 on the mass path) and ends near it (within ``h (|x2'(τ)| + |x2'(τ + h)|)``): the
minimum distance is then found on the dense output (golden section), so an excursion that touches the
belt speed and returns inside one step (a *graze*) is an event too.  A grid point passed before the
first belt/zero event of a step (the path turns there, so the step's end may lie before the grid
point again) is found the same way.
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

from .dop853_tableau import (
    A1_0,
    A2_0,
    A2_1,
    A3_0,
    A3_2,
    A4_0,
    A4_2,
    A4_3,
    A5_0,
    A5_3,
    A5_4,
    A6_0,
    A6_3,
    A6_4,
    A6_5,
    A7_0,
    A7_3,
    A7_4,
    A7_5,
    A7_6,
    A8_0,
    A8_3,
    A8_4,
    A8_5,
    A8_6,
    A8_7,
    A9_0,
    A9_3,
    A9_4,
    A9_5,
    A9_6,
    A9_7,
    A9_8,
    A10_0,
    A10_3,
    A10_4,
    A10_5,
    A10_6,
    A10_7,
    A10_8,
    A10_9,
    A11_0,
    A11_3,
    A11_4,
    A11_5,
    A11_6,
    A11_7,
    A11_8,
    A11_9,
    A11_10,
    A_EXTRA,
    B0,
    B5,
    B6,
    B7,
    B8,
    B9,
    B10,
    B11,
    C1,
    C2,
    C3,
    C4,
    C5,
    C6,
    C7,
    C8,
    C9,
    C10,
    C_EXTRA,
    D_DENSE,
    E3_0,
    E3_5,
    E3_6,
    E3_7,
    E3_8,
    E3_9,
    E3_10,
    E3_11,
    E5_0,
    E5_5,
    E5_6,
    E5_7,
    E5_8,
    E5_9,
    E5_10,
    E5_11,
)
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
    segment_ends,
    slip_drift,
    stick_force,
    store_diagnostics,
)

#: rows of the stage array: k[0..15] the stages (k[12] = f(τ + h, y_new), FSAL; k[13..15] the extra
#: stages of the dense output), k[16..22] its coefficients F0..F6
K_F = 16
K_ROWS = 23

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


class Segment(NamedTuple):
    """What stays fixed between two events of a slip phase; given it, the right-hand side is smooth.

    ``s = sign(γ0 − x2)`` (so ``|γ0 − x2| = s(γ0 − x2)``); the path's rate is
    ``rate_x2·x2 + rate_vr·(γ0 − x2)``: ``(sign(x2), 0)`` on the mass path, ``(0, s)`` on the relative
    one.  The process is the linear function of its current grid cell ``cell``
    (``μ̂ = (1 − w) p0 + w p1``, ``w = path/Δx − cell``, ``inv_dx = 1/Δx``; all 0 without a process),
    extended beyond the cell, so that a step that crosses the cell's end stays smooth (the crossing is
    an event).  Floats only: the compiled step keeps them in registers.
    """

    s: float
    rate_x2: float
    rate_vr: float
    cell: float
    p0: float
    p1: float
    inv_dx: float


class Run(NamedTuple):
    """What stays fixed over one trajectory: its row in the batch, its law's shape, whether it reads a
    contact process and the mass path, the static limit ``n μ_s`` and ``n μ_k(0)``."""

    row: int
    shape: int
    use_nodes: bool
    mass_path: bool
    lim: float
    nn_k0: float


class Rhs(NamedTuple):
    """The trajectory's constants of the slip equations: γ0, the velocity scale ``L ω0`` [m/s] of the
    friction law, ``2D`` and ``n``."""

    gamma0: float
    vscale: float
    dd2: float
    nn: float


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _rhs(prm: npt.NDArray[np.float64]) -> Rhs:  # pragma: no cover
    return Rhs(prm[P_GAMMA0], prm[P_VSCALE], 2.0 * prm[P_D], prm[P_N])


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _f(
    y0: float, y1: float, y2: float, force: float, c: Rhs, lawp: npt.NDArray[np.float64], seg: Segment,
    shape: int, row: int,
) -> tuple[float, float, float]:  # pragma: no cover
    """Slip equations (4.7)/(4.36) with the path coordinate as third state: ``(x1', x2', path')``;
    ``force`` is the forcing ``q cos(x30 + ητ)`` at the stage's time (branch-free, no stores: the
    compiled step keeps the stages in registers)."""
    s = seg.s
    vr = c.gamma0 - y1
    w = y2 * seg.inv_dx - seg.cell
    mu = mu_kinetic_row(shape, c.vscale * (s * vr), lawp, row) + ((1.0 - w) * seg.p0 + w * seg.p1)
    return y1, slip_drift(y0, y1, c.dd2, c.nn, mu, s) + force, seg.rate_x2 * y1 + seg.rate_vr * vr


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _forcing(prm: npt.NDArray[np.float64], tau: float) -> float:  # pragma: no cover
    """``q cos(x30 + ητ)`` (0 unforced)."""
    q = prm[P_Q]
    return q * math.cos(prm[P_X30] + prm[P_ETA] * tau) if q != 0.0 else 0.0


#: Offsets ``|η c h|`` up to which :func:`_shifted_cos` uses its series (error below 1e-18 there).
SERIES_MAX = 0.5


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _shifted_cos(c0: float, s0: float, phase: float, d: float) -> float:  # pragma: no cover
    """``cos(phase + d)`` from ``c0 = cos(phase)``, ``s0 = sin(phase)``: ``c0 cos d − s0 sin d`` with
    cos d and sin d from their Taylor series (to d¹⁶/16! and d¹⁵/15!) for ``|d| ≤`` :data:`SERIES_MAX`,
    else the library cosine.  The stages of one step share ``phase`` (two library calls per step
    instead of five)."""
    if abs(d) > SERIES_MAX:
        return math.cos(phase + d)
    d2 = d * d
    cd = 1.0 + d2 * (-1.0 / 2 + d2 * (1.0 / 24 + d2 * (-1.0 / 720 + d2 * (1.0 / 40320 + d2 * (
        -1.0 / 3628800 + d2 * (1.0 / 479001600 + d2 * (-1.0 / 87178291200 + d2 / 20922789888000)))))))
    sd = d * (1.0 + d2 * (-1.0 / 6 + d2 * (1.0 / 120 + d2 * (-1.0 / 5040 + d2 * (1.0 / 362880 + d2 * (
        -1.0 / 39916800 + d2 * (1.0 / 6227020800 + d2 * (-1.0 / 1307674368000))))))))
    return c0 * cd - s0 * sd


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _step(
    tau: float, y: npt.NDArray[np.float64], h: float, k: npt.NDArray[np.float64], prm: npt.NDArray[np.float64],
    lawp: npt.NDArray[np.float64], seg: Segment, shape: int, row: int, ynew: npt.NDArray[np.float64],
) -> None:  # pragma: no cover
    """One DOP853 step; ``k[0]`` must hold f(τ, y) on entry; fills k[5..12] (the stages the error
    estimate and the dense output use; k[12] = f(τ + h, ynew), FSAL) and ynew.  The stages are held in
    locals and stored once at the end."""
    q = prm[P_Q]

    g1 = g2 = g3 = g4 = g5 = g6 = g7 = g8 = g9 = g10 = g11 = 0.0
    if q != 0.0:
        phase = prm[P_X30] + prm[P_ETA] * tau
        eh = prm[P_ETA] * h
        c0 = math.cos(phase)
        s0 = math.sin(phase)
        g1 = q * _shifted_cos(c0, s0, phase, C1 * eh)
        g2 = q * _shifted_cos(c0, s0, phase, C2 * eh)
        g3 = q * _shifted_cos(c0, s0, phase, C3 * eh)
        g4 = q * _shifted_cos(c0, s0, phase, C4 * eh)
        g5 = q * _shifted_cos(c0, s0, phase, C5 * eh)
        g6 = q * _shifted_cos(c0, s0, phase, C6 * eh)
        g7 = q * _shifted_cos(c0, s0, phase, C7 * eh)
        g8 = q * _shifted_cos(c0, s0, phase, C8 * eh)
        g9 = q * _shifted_cos(c0, s0, phase, C9 * eh)
        g10 = q * _shifted_cos(c0, s0, phase, C10 * eh)
        g11 = q * _shifted_cos(c0, s0, phase, eh)
    c = _rhs(prm)
    a0, a1, a2 = y[0], y[1], y[2]
    k0_0, k0_1, k0_2 = k[0, 0], k[0, 1], k[0, 2]
    k1_0, k1_1, k1_2 = _f(a0 + h * (A1_0 * k0_0),
        a1 + h * (A1_0 * k0_1),
        a2 + h * (A1_0 * k0_2),
        g1, c, lawp, seg, shape, row)
    k2_0, k2_1, k2_2 = _f(a0 + h * (A2_0 * k0_0 + A2_1 * k1_0),
        a1 + h * (A2_0 * k0_1 + A2_1 * k1_1),
        a2 + h * (A2_0 * k0_2 + A2_1 * k1_2),
        g2, c, lawp, seg, shape, row)
    k3_0, k3_1, k3_2 = _f(a0 + h * (A3_0 * k0_0 + A3_2 * k2_0),
        a1 + h * (A3_0 * k0_1 + A3_2 * k2_1),
        a2 + h * (A3_0 * k0_2 + A3_2 * k2_2),
        g3, c, lawp, seg, shape, row)
    k4_0, k4_1, k4_2 = _f(a0 + h * (A4_0 * k0_0 + A4_2 * k2_0 + A4_3 * k3_0),
        a1 + h * (A4_0 * k0_1 + A4_2 * k2_1 + A4_3 * k3_1),
        a2 + h * (A4_0 * k0_2 + A4_2 * k2_2 + A4_3 * k3_2),
        g4, c, lawp, seg, shape, row)
    k5_0, k5_1, k5_2 = _f(a0 + h * (A5_0 * k0_0 + A5_3 * k3_0 + A5_4 * k4_0),
        a1 + h * (A5_0 * k0_1 + A5_3 * k3_1 + A5_4 * k4_1),
        a2 + h * (A5_0 * k0_2 + A5_3 * k3_2 + A5_4 * k4_2),
        g5, c, lawp, seg, shape, row)
    k6_0, k6_1, k6_2 = _f(a0 + h * (A6_0 * k0_0 + A6_3 * k3_0 + A6_4 * k4_0 + A6_5 * k5_0),
        a1 + h * (A6_0 * k0_1 + A6_3 * k3_1 + A6_4 * k4_1 + A6_5 * k5_1),
        a2 + h * (A6_0 * k0_2 + A6_3 * k3_2 + A6_4 * k4_2 + A6_5 * k5_2),
        g6, c, lawp, seg, shape, row)
    k7_0, k7_1, k7_2 = _f(a0 + h * (A7_0 * k0_0 + A7_3 * k3_0 + A7_4 * k4_0 + A7_5 * k5_0 + A7_6 * k6_0),
        a1 + h * (A7_0 * k0_1 + A7_3 * k3_1 + A7_4 * k4_1 + A7_5 * k5_1 + A7_6 * k6_1),
        a2 + h * (A7_0 * k0_2 + A7_3 * k3_2 + A7_4 * k4_2 + A7_5 * k5_2 + A7_6 * k6_2),
        g7, c, lawp, seg, shape, row)
    k8_0, k8_1, k8_2 = _f(a0 + h * (A8_0 * k0_0 + A8_3 * k3_0 + A8_4 * k4_0 + A8_5 * k5_0 + A8_6 * k6_0 + A8_7 * k7_0),
        a1 + h * (A8_0 * k0_1 + A8_3 * k3_1 + A8_4 * k4_1 + A8_5 * k5_1 + A8_6 * k6_1 + A8_7 * k7_1),
        a2 + h * (A8_0 * k0_2 + A8_3 * k3_2 + A8_4 * k4_2 + A8_5 * k5_2 + A8_6 * k6_2 + A8_7 * k7_2),
        g8, c, lawp, seg, shape, row)
    k9_0, k9_1, k9_2 = _f(a0 + h * (A9_0 * k0_0 + A9_3 * k3_0 + A9_4 * k4_0 + A9_5 * k5_0 + A9_6 * k6_0 +
            A9_7 * k7_0 + A9_8 * k8_0),
        a1 + h * (A9_0 * k0_1 + A9_3 * k3_1 + A9_4 * k4_1 + A9_5 * k5_1 + A9_6 * k6_1 + A9_7 * k7_1 + A9_8 * k8_1),
        a2 + h * (A9_0 * k0_2 + A9_3 * k3_2 + A9_4 * k4_2 + A9_5 * k5_2 + A9_6 * k6_2 + A9_7 * k7_2 + A9_8 * k8_2),
        g9, c, lawp, seg, shape, row)
    k10_0, k10_1, k10_2 = _f(a0 + h * (A10_0 * k0_0 + A10_3 * k3_0 + A10_4 * k4_0 + A10_5 * k5_0 + A10_6 * k6_0 +
            A10_7 * k7_0 + A10_8 * k8_0 + A10_9 * k9_0),
        a1 + h * (A10_0 * k0_1 + A10_3 * k3_1 + A10_4 * k4_1 + A10_5 * k5_1 + A10_6 * k6_1 + A10_7 * k7_1 +
                A10_8 * k8_1 + A10_9 * k9_1),
        a2 + h * (A10_0 * k0_2 + A10_3 * k3_2 + A10_4 * k4_2 + A10_5 * k5_2 + A10_6 * k6_2 + A10_7 * k7_2 +
                A10_8 * k8_2 + A10_9 * k9_2),
        g10, c, lawp, seg, shape, row)
    k11_0, k11_1, k11_2 = _f(a0 + h * (A11_0 * k0_0 + A11_3 * k3_0 + A11_4 * k4_0 + A11_5 * k5_0 + A11_6 * k6_0 +
            A11_7 * k7_0 + A11_8 * k8_0 + A11_9 * k9_0 + A11_10 * k10_0),
        a1 + h * (A11_0 * k0_1 + A11_3 * k3_1 + A11_4 * k4_1 + A11_5 * k5_1 + A11_6 * k6_1 + A11_7 * k7_1 +
                A11_8 * k8_1 + A11_9 * k9_1 + A11_10 * k10_1),
        a2 + h * (A11_0 * k0_2 + A11_3 * k3_2 + A11_4 * k4_2 + A11_5 * k5_2 + A11_6 * k6_2 + A11_7 * k7_2 +
                A11_8 * k8_2 + A11_9 * k9_2 + A11_10 * k10_2),
        g11, c, lawp, seg, shape, row)
    n0 = a0 + h * (B0 * k0_0 + B5 * k5_0 + B6 * k6_0 + B7 * k7_0 + B8 * k8_0 + B9 * k9_0 + B10 * k10_0 + B11 * k11_0)
    n1 = a1 + h * (B0 * k0_1 + B5 * k5_1 + B6 * k6_1 + B7 * k7_1 + B8 * k8_1 + B9 * k9_1 + B10 * k10_1 + B11 * k11_1)
    n2 = a2 + h * (B0 * k0_2 + B5 * k5_2 + B6 * k6_2 + B7 * k7_2 + B8 * k8_2 + B9 * k9_2 + B10 * k10_2 + B11 * k11_2)
    k12_0, k12_1, k12_2 = _f(n0, n1, n2, g11, c, lawp, seg, shape, row)
    ynew[0], ynew[1], ynew[2] = n0, n1, n2
    k[5, 0], k[5, 1], k[5, 2] = k5_0, k5_1, k5_2
    k[6, 0], k[6, 1], k[6, 2] = k6_0, k6_1, k6_2
    k[7, 0], k[7, 1], k[7, 2] = k7_0, k7_1, k7_2
    k[8, 0], k[8, 1], k[8, 2] = k8_0, k8_1, k8_2
    k[9, 0], k[9, 1], k[9, 2] = k9_0, k9_1, k9_2
    k[10, 0], k[10, 1], k[10, 2] = k10_0, k10_1, k10_2
    k[11, 0], k[11, 1], k[11, 2] = k11_0, k11_1, k11_2
    k[12, 0], k[12, 1], k[12, 2] = k12_0, k12_1, k12_2


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _err_norm(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64], h: float,
    rtol: float, atol: float,
) -> float:  # pragma: no cover
    """DOP853's error norm (Hairer; scipy ``DOP853._estimate_error_norm``): the 5th- and 3rd-order
    estimates ``e5``, ``e3`` scaled by ``atol + rtol·max(|y|, |ynew|)``,
    ``h·|e5|² / sqrt(3 (|e5|² + 0.01 |e3|²))``."""
    s5 = 0.0
    s3 = 0.0
    for i in range(3):
        sc = atol + rtol * max(abs(y[i]), abs(ynew[i]))
        e = (E5_0 * k[0, i] + E5_5 * k[5, i] + E5_6 * k[6, i] + E5_7 * k[7, i] + E5_8 * k[8, i] + E5_9 * k[9, i] +
                E5_10 * k[10, i] + E5_11 * k[11, i]) / sc
        f = (E3_0 * k[0, i] + E3_5 * k[5, i] + E3_6 * k[6, i] + E3_7 * k[7, i] + E3_8 * k[8, i] + E3_9 * k[9, i] +
                E3_10 * k[10, i] + E3_11 * k[11, i]) / sc
        s5 += e * e
        s3 += f * f
    if s5 == 0.0 and s3 == 0.0:
        return 0.0
    return abs(h) * s5 / math.sqrt(3.0 * (s5 + 0.01 * s3))


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _dense_prep(
    tau: float, y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64], h: float,
    prm: npt.NDArray[np.float64], lawp: npt.NDArray[np.float64], seg: Segment, shape: int, row: int,
) -> None:  # pragma: no cover
    """The 7th-order continuous extension of the accepted step ``[τ, τ + h]`` (scipy
    ``DOP853._dense_output_impl``): the three extra stages k[13..15] and the coefficients
    F0..F6 in k[16..22]; only for steps with an event or a save point."""
    c = _rhs(prm)
    for st in range(13, 16):  # the three extra stages, from the rows of A_EXTRA
        a = A_EXTRA[st - 13]
        z0 = a[0] * k[0, 0]
        z1 = a[0] * k[0, 1]
        z2 = a[0] * k[0, 2]
        for j in range(5, st):  # rows 1-4 of k are not stored (their stages stay in registers)
            z0 += a[j] * k[j, 0]
            z1 += a[j] * k[j, 1]
            z2 += a[j] * k[j, 2]
        k[st, 0], k[st, 1], k[st, 2] = _f(y[0] + h * z0, y[1] + h * z1, y[2] + h * z2,
                                          _forcing(prm, tau + C_EXTRA[st - 13] * h), c, lawp, seg, shape, row)
    for i in range(3):
        dy = ynew[i] - y[i]
        k[K_F, i] = dy
        k[K_F + 1, i] = h * k[0, i] - dy
        k[K_F + 2, i] = 2.0 * dy - h * (k[12, i] + k[0, i])
        for r in range(4):  # F3..F6 = h Σ_j D[r, j] k_j
            z = D_DENSE[r, 0] * k[0, i]
            for j in range(5, 16):
                z += D_DENSE[r, j] * k[j, i]
            k[K_F + 3 + r, i] = h * z

@numba.njit(cache=True, nogil=True, inline="always")
def _dense(y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], theta: float, i: int) -> float:  # pragma: no cover
    """Component ``i`` of DOP853's 7th-order continuous extension at ``τ + θh`` (after :func:`_dense_prep`)."""
    x = theta
    t1 = 1.0 - theta
    f = k[K_F:, i]
    return y[i] + x * (f[0] + t1 * (f[1] + x * (f[2] + t1 * (f[3] + x * (f[4] + t1 * (f[5] + x * f[6]))))))


@numba.njit(cache=True, nogil=True, inline="always")
def _root_theta(
    y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], comp: int, target: float, sgn: float, hi0: float,
) -> float:  # pragma: no cover
    """Smallest θ in (0, hi0] with ``sgn·(target − y_comp(θ))`` reaching 0 (≤ 0 at hi0), by bisection."""
    lo = 0.0
    hi = hi0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        g = sgn * (target - _dense(y, k, mid, comp))
        if g > 0.0:
            lo = mid
        else:
            hi = mid
    return hi


class BeltPhase(NamedTuple):
    """A mass moving with the belt from ``(τs, x1s)``, its force ``F`` seen with the sign ``sg``."""

    x1s: float
    tau_s: float
    sg: float


#: The process argument of :func:`_bisect_exit` for a limit without a process (static friction only).
_NO_PROCESS = np.zeros((1, 1))


@numba.njit(cache=True, nogil=True)
def _bisect_exit(
    phase: BeltPhase, prm: npt.NDArray[np.float64], a: float, b: float, lim: float, inner: bool, nn_k0: float,
    proc: npt.NDArray[np.float64], r: int, n_proc: int, path0: float, rate: float,
) -> float:  # pragma: no cover
    """Bisection in ``(a, b]`` (the force has left its band at ``b``, not at ``a``) for the first ``τ`` at
    which ``sg·F(τ) ≤ lim`` (``inner``: it enters the static band) or ``sg·F(τ)`` exceeds the limit above:
    ``lim`` without a process (``n_proc = 0``), else ``nn_k0 + n μ̂(path0 + rate (τ − τs))``; to the
    resolution of ``τ``."""
    x1s, tau_s, sg = phase
    gamma0 = prm[P_GAMMA0]
    lo = a
    hi = b
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid <= lo or mid >= hi:
            break
        fm = sg * stick_force(x1s + gamma0 * (mid - tau_s), mid, prm)
        if inner:
            out = fm <= lim
        elif n_proc == 0:
            out = fm > lim
        else:
            mu_hat = process_value_row(proc, r, n_proc, prm[P_PROC_DX], path0 + rate * (mid - tau_s))
            out = fm > nn_k0 + prm[P_N] * mu_hat
        if out:
            hi = mid
        else:
            lo = mid
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
            return _bisect_exit(BeltPhase(x1s, tau_s, 1.0 if fb > 0.0 else -1.0), prm, a, b, lim, False, 0.0,
                                _NO_PROCESS, 0, 0, 0.0, 0.0)
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
            return _bisect_exit(BeltPhase(x1s, tau_s, sg), prm, a, b, lim, inner, nn_k0, proc, r, n_proc, path0,
                                rate), inner
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


@numba.njit(cache=True, nogil=True, inline="always")
def _save_dense(
    traj: npt.NDArray[np.float64], isave: int, save_dt: float, tau: float, tau_e: float,
    y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], h: float,
) -> int:  # pragma: no cover
    """Rows ``τ = isave·save_dt ≤ τ_e`` of ``traj`` from the dense output of the step ``[τ, τ + h]``
    (slip; :func:`_dense_prep` done); returns the next row index."""
    while isave < traj.shape[0] and isave * save_dt <= tau_e + SAVE_TOL * save_dt:
        tq = (isave * save_dt - tau) / h
        traj[isave, 0] = isave * save_dt
        traj[isave, 1] = _dense(y, k, tq, 0)
        traj[isave, 2] = _dense(y, k, tq, 1)
        isave += 1
    return isave


@numba.njit(cache=True, nogil=True, inline="always")
def _graze_min(
    y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], comp: int, target: float, sgn: float,
) -> tuple[float, float]:  # pragma: no cover
    """(θ, g) at the minimum of ``g(θ) = sgn·(target − y_comp(θ))`` on [0, 1] (golden section on the
    dense output; stops as soon as g ≤ 0)."""
    a = 0.0
    b = 1.0
    r = 0.6180339887498949
    c = b - r * (b - a)
    d = a + r * (b - a)
    gc = sgn * (target - _dense(y, k, c, comp))
    gd = sgn * (target - _dense(y, k, d, comp))
    for _ in range(50):
        if gc <= 0.0 or gd <= 0.0 or b - a < 1e-9:
            break
        if gc < gd:
            b = d
            d = c
            gd = gc
            c = b - r * (b - a)
            gc = sgn * (target - _dense(y, k, c, comp))
        else:
            a = c
            c = d
            gc = gd
            d = a + r * (b - a)
            gd = sgn * (target - _dense(y, k, d, comp))
    if gc <= gd:
        return c, gc
    return d, gd


#: Shortest step at the belt speed, and the time the mass is carried with the belt at least when no slip
#: direction leaves it (a sliding mode: the contact model's kinetic friction μ_k(0) + μ̂(path) grows
#: along the path faster than the force); the fixed-step scheme carries it for one Δτ.  A regularisation
#: whose effect on X_gh is of its own size: with 1e-6, 5 of 16 sheet contact trajectories (1100 N, τ = 200)
#: moved by up to 1.1e-6 γ0 between rtol 1e-11 and 1e-13 (the carry decided at the level of rounding);
#: with 1e-8 all agree to ≤ 3.2e-8 γ0, the integrator's own level (test_stick_slip_cycle.py).
CARRY_STEP = 1e-8

#: A slip segment ends at a grid point of the process once the path is within this fraction of a grid
#: step of it (the state there is recomputed by one step of the located length).
NODE_TOL = 1e-12

#: Event codes of :func:`_slip_until_event` beyond ``EV_*``: the step that starts at the belt speed
#: shrank below :data:`CARRY_STEP` without leaving it (a belt contact at once).
EV_AT_BELT = 4

#: Slots of the per-trajectory counters (int array) of :func:`run_accurate`.
C_M, C_SHORT, C_NO_STICK, C_BREAK, C_PHASES = range(5)
#: Slots of its float scratch: the smallest slip path so far and the path at the start of the slip.
F_MIN_SLIP, F_SLIP_START = range(2)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _node_theta(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64],
    node: float, tol: float, b0: float, pb: float,
) -> float:  # pragma: no cover
    """θ in (0, 1] at which the dense output's path reaches ``node`` (``y[2] < node ≤ ynew[2]``), by
    the Illinois variant of regula falsi (superlinear; the path is monotone within a segment), to
    ``|path(θ) − node| ≤ tol``."""
    a = 0.0
    b = b0
    fa = y[2] - node
    fb = pb - node
    if fb <= tol:
        return b0
    side = 0
    c = b
    for _ in range(100):
        c = (a * fb - b * fa) / (fb - fa)
        if not a < c < b:
            c = 0.5 * (a + b)
        fc = _dense(y, k, c, 2) - node
        if abs(fc) <= tol or b - a <= 1e-15:
            break
        if fc > 0.0:
            b = c
            fb = fc
            if side == -1:
                fa *= 0.5
            side = -1
        else:
            a = c
            fa = fc
            if side == 1:
                fb *= 0.5
            side = 1
    return c


@numba.njit(cache=True, nogil=True)
def _new_segment(
    tau: float, y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], s: float, rows: KernelRows, run: Run,
) -> tuple[Segment, float]:  # pragma: no cover
    """The slip segment that starts at ``(τ, y)`` with friction direction ``s``: the sign of ``x2`` (of
    the acceleration where ``x2 = 0``) and the process cell; fills ``k[0] = f(τ, y)`` and returns the
    segment and the grid point ahead (``inf`` without a process)."""
    i = run.row
    prm = rows.prm[i]
    pdx = prm[P_PROC_DX]
    cell = 0.0
    p0 = 0.0
    p1 = 0.0
    inv_dx = 0.0
    node = np.inf
    if run.use_nodes:
        cell = math.floor(y[2] / pdx + 1e-9)
        j0, j1 = segment_ends(cell, rows.n_proc[i])
        p0 = rows.proc[i, j0]
        p1 = rows.proc[i, j1]
        inv_dx = 1.0 / pdx
        node = (cell + 1.0) * pdx
    rate_vr = 0.0 if run.mass_path else s
    seg = Segment(s, 1.0 if run.mass_path else 0.0, rate_vr, cell, p0, p1, inv_dx)
    k[0, 0], k[0, 1], k[0, 2] = _f(y[0], y[1], y[2], _forcing(prm, tau), _rhs(prm), rows.lawp, seg, run.shape, i)
    if run.mass_path:
        if y[1] != 0.0:
            sz = 1.0 if y[1] > 0.0 else -1.0
        else:
            sz = 1.0 if k[0, 1] >= 0.0 else -1.0
        seg = Segment(s, sz, rate_vr, cell, p0, p1, inv_dx)
        k[0, 2] = sz * y[1]
    return seg, node


@numba.njit(cache=True, nogil=True, inline="always")
def _event_candidates(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], seg: Segment, gamma0: float, node: float,
) -> tuple[bool, bool, bool]:  # pragma: no cover
    """Which events the accepted step ``[τ, τ + h]`` contains by the signs at its ends: the belt speed
    reached, ``x2 = 0`` on the mass path, the next grid point of the process."""
    belt = seg.s * (gamma0 - y[1]) > 0.0 and seg.s * (gamma0 - ynew[1]) <= 0.0
    sz = seg.rate_x2  # sign(x2) on the mass path, else 0 (no event)
    zero = sz != 0.0 and sz * ynew[1] < 0.0 and sz * y[1] > 0.0
    return belt, zero, ynew[2] >= node


@numba.njit(cache=True, nogil=True, inline="always")
def _first_event(
    y: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64], k: npt.NDArray[np.float64],
    seg: Segment, gamma0: float, node: float, node_tol: float, belt: bool, zero: bool, nd: bool,
    gb: bool, gz: bool,
) -> tuple[int, float]:  # pragma: no cover
    """The first event in the accepted step and its θ on the dense output (:func:`_dense_prep` done);
    ``gb``/``gz``: the belt speed / x2 = 0 may be touched inside the step without a sign change at its
    ends (an extremum of x2 in the step), found on the dense output.  A grid point passed before the
    path's turning point (the first belt/zero event) but not at the step's end is found as well."""
    ev = EV_NONE
    th = 2.0
    if belt:
        th = _root_theta(y, k, 1, gamma0, seg.s, 1.0)
        ev = EV_BELT
    elif gb:
        tm, gm = _graze_min(y, k, 1, gamma0, seg.s)
        if gm <= 0.0:
            th = _root_theta(y, k, 1, gamma0, seg.s, tm)
            ev = EV_BELT
    sz = seg.rate_x2
    if zero:
        t2 = _root_theta(y, k, 1, 0.0, -sz, 1.0)  # g = sz·x2 > 0 before the crossing
        if t2 < th:
            th = t2
            ev = EV_ZERO_VELOCITY
    elif gz:
        tm, gm = _graze_min(y, k, 1, 0.0, -sz)
        if gm <= 0.0:
            t2 = _root_theta(y, k, 1, 0.0, -sz, tm)
            if t2 < th:
                th = t2
                ev = EV_ZERO_VELOCITY
    if nd:
        t3 = _node_theta(y, ynew, k, node, node_tol, 1.0, ynew[2])
        if t3 < th:
            th = t3
            ev = EV_NODE
    elif ev != EV_NONE:
        pe = _dense(y, k, th, 2)
        if pe >= node:
            th = _node_theta(y, ynew, k, node, node_tol, th, pe)
            ev = EV_NODE
    return ev, th


@numba.njit(cache=True, nogil=True)
def _slip_until_event(
    tau: float, h: float, y: npt.NDArray[np.float64], k: npt.NDArray[np.float64], ynew: npt.NDArray[np.float64],
    rows: KernelRows, run: Run, seg: Segment, node: float, settings: AccurateSettings,
    traj: npt.NDArray[np.float64], isave: int,
) -> tuple[int, float, float, int]:  # pragma: no cover
    """Integrate the slip segment ``seg`` from ``(τ, y)`` (``k[0] = f(τ, y)``) with adaptive steps
    until its first event or ``τ_end``; returns ``(event, τ, next step, next save row)``, ``y`` at the event.

    The state at an event inside a step is the 7th-order dense output at the located ``θ``; the belt
    speed is then set exactly (``x2 = γ0``), as are ``x2 = 0`` and the grid point's path.
    """
    tau_end, _h0, max_step, rtol, atol, save_dt = settings
    prm = rows.prm[run.row]
    lawp = rows.lawp
    shape = run.shape
    row = run.row
    gamma0 = prm[P_GAMMA0]
    node_tol = NODE_TOL * prm[P_PROC_DX]
    while True:
        if tau + h > tau_end:
            h = tau_end - tau
        _step(tau, y, h, k, prm, lawp, seg, shape, row, ynew)
        at_belt = False
        if y[1] == gamma0 and seg.s * (gamma0 - ynew[1]) < 0.0:
            # a segment that starts at the belt speed is back at (or on the wrong side of) it at the
            # step's end: a short excursion (|F| just above n μ_s) that the step jumped over, or a slip
            # against the unbalanced force (equal to it within rounding).  Shorten the step until the
            # excursion is resolved; below CARRY_STEP it is a belt contact at once
            if h > CARRY_STEP:
                h *= 0.25
                continue
            at_belt = True
        err = 0.0 if at_belt else _err_norm(y, ynew, k, h, rtol, atol)
        fac = 0.9 * max(err, 1e-10) ** -0.125  # the controller's factor: err^(−1/8), 7 = the estimate's order
        if err > 1.0:
            h *= max(0.2, fac)
            continue
        h_next = min(h * min(5.0, max(0.2, fac)), max_step)
        if at_belt:
            return EV_AT_BELT, tau, max(h_next, 1e-6), isave
        belt, zero, nd = _event_candidates(y, ynew, seg, gamma0, node)
        # touches without a sign change at the step's ends: x2 has an extremum in the step toward the
        # belt speed (toward 0 on the mass path) and ends within a generous margin of it
        margin = h * (abs(k[0, 1]) + abs(k[12, 1]))
        ss = seg.s
        gb = (not belt and ss * (gamma0 - y[1]) > 0.0 and ss * (gamma0 - ynew[1]) > 0.0
              and ss * k[0, 1] > 0.0 and ss * k[12, 1] < 0.0
              and min(ss * (gamma0 - y[1]), ss * (gamma0 - ynew[1])) <= margin)
        sz = seg.rate_x2
        gz = (sz != 0.0 and not zero and sz * y[1] > 0.0 and sz * ynew[1] > 0.0
              and sz * k[0, 1] < 0.0 and sz * k[12, 1] > 0.0 and min(sz * y[1], sz * ynew[1]) <= margin)
        save = isave < traj.shape[0] and isave * save_dt <= tau + h + SAVE_TOL * save_dt
        ev, th = EV_NONE, 2.0
        if belt or zero or nd or gb or gz:
            _dense_prep(tau, y, ynew, k, h, prm, lawp, seg, shape, row)
            ev, th = _first_event(y, ynew, k, seg, gamma0, node, node_tol, belt, zero, nd, gb, gz)
        elif save:
            _dense_prep(tau, y, ynew, k, h, prm, lawp, seg, shape, row)
        if ev == EV_NONE:  # no event (a graze candidate may not touch): an ordinary step
            if save:
                isave = _save_dense(traj, isave, save_dt, tau, tau + h, y, k, h)
            tau += h
            for c in range(3):
                y[c] = ynew[c]
                k[0, c] = k[12, c]
            h = h_next
            if tau >= tau_end:
                return EV_NONE, tau, h, isave
            continue
        hev = th * h
        isave = _save_dense(traj, isave, save_dt, tau, tau + hev, y, k, h)
        # the state at the event from the 7th-order dense output (no recomputing step)
        d0 = _dense(y, k, th, 0)
        d1 = _dense(y, k, th, 1)
        d2 = _dense(y, k, th, 2)
        tau += hev
        y[0], y[1], y[2] = d0, d1, d2
        if ev == EV_NODE:
            y[2] = node
        elif ev == EV_BELT:
            y[1] = gamma0
        else:
            y[1] = 0.0
        return ev, tau, max(h_next, 1e-6), isave


@numba.njit(cache=True, nogil=True)
def _lim_eff(rows: KernelRows, run: Run, path: float) -> float:
    """The largest force the contact at the belt speed holds without slipping: ``n μ_s``, and for the
    contact model at least ``n (μ_k(0) + μ̂(path))`` (the kinetic friction as ``v_rel → 0``)."""
    if run.use_nodes:
        prm = rows.prm[run.row]
        mu_hat = process_value_row(rows.proc, run.row, rows.n_proc[run.row], prm[P_PROC_DX], path)
        return max(run.lim, run.nn_k0 + prm[P_N] * mu_hat)
    return run.lim


@numba.njit(cache=True, nogil=True)
def _belt_contact(
    tau: float, y: npt.NDArray[np.float64], s: float, rows: KernelRows, out: KernelOutput,
    settings: AccurateSettings, run: Run, isave: int, cnt: npt.NDArray[np.int64], fl: npt.NDArray[np.float64],
    at_belt: bool,
) -> tuple[float, int, bool, float]:  # pragma: no cover
    """The mass, slipping with friction direction ``s``, at the belt speed at ``τ``: it sticks (a
    slip→stick transition, recorded in ``out``), is carried with the belt (:func:`carried_end`), or
    slips on with the friction opposing the unbalanced force.  Returns ``(τ, next save row, stuck, s)``;
    ``stuck`` is also true when the mass is still carried with the belt at ``τ_end``."""
    i = run.row
    prm = rows.prm[i]
    gamma0 = prm[P_GAMMA0]
    lim = run.lim
    tau_end = settings.tau_end
    traj = out.traj[i]
    fs = stick_force(y[0], tau, prm)
    sticks = abs(fs) <= lim
    if not sticks:
        cnt[C_NO_STICK] += 1
        if abs(fs) <= _lim_eff(rows, run, y[2]):
            # carried with the belt until the force enters the static band or leaves the kinetic one
            rate = gamma0 if run.mass_path else 0.0
            tc, sticks = carried_end(y[0], tau, tau_end, prm, lim, run.nn_k0, rows.proc, i, rows.n_proc[i], y[2],
                                     rate)
            te = min(tc, tau_end)
            isave = _save_stick(traj, isave, settings.save_dt, y[0], tau, te, gamma0)
            y[0] += gamma0 * (te - tau)
            y[2] += rate * (te - tau)
            tau = te
            if tc >= tau_end:
                return tau, isave, True, s  # still moving with the belt at τ_end
            fs = stick_force(y[0], tau, prm)
    if sticks:
        m = cnt[C_M]
        if m < out.x_gh.shape[1]:
            out.x_gh[i, m] = y[0]
            out.t_gh[i, m] = tau
        cnt[C_M] += 1
        sp = y[2] - fl[F_SLIP_START]
        cnt[C_PHASES] += 1
        fl[F_MIN_SLIP] = min(fl[F_MIN_SLIP], sp)
        if sp < prm[P_PROC_DX]:
            cnt[C_SHORT] += 1
        return tau, isave, True, s
    if at_belt and tau < tau_end:
        # neither sticking nor carried, yet no slip direction leaves the belt speed: carried with the
        # belt for one short step (progress guaranteed)
        hc = min(CARRY_STEP, tau_end - tau)
        isave = _save_stick(traj, isave, settings.save_dt, y[0], tau, tau + hc, gamma0)
        y[0] += gamma0 * hc
        tau += hc
        fs = stick_force(y[0], tau, prm)
    return tau, isave, False, 1.0 if fs > 0.0 else -1.0  # the friction opposes the unbalanced force


@numba.njit(cache=True, nogil=True)
def run_accurate(
    rows: KernelRows, out: KernelOutput, i: int, settings: AccurateSettings, noise: int, path_mode: int
) -> int:  # pragma: no cover
    """Integrate trajectory (row) ``i`` from ``τ = 0`` to ``τ_end``; returns ``M`` (see module doc).

    Reads row ``i`` of ``rows`` and writes row ``i`` of ``out`` except ``out.counts``; ``traj``
    rows (``τ, x1, x2``) are filled at ``τ = k·save_dt`` from the dense output.
    """
    prm = rows.prm[i]
    tau_end = settings.tau_end
    gamma0 = prm[P_GAMMA0]
    run = Run(i, rows.shapes[i], noise == NOISE_PROCESS, path_mode == PATH_MASS, prm[P_N] * prm[P_MUS],
              prm[P_N] * mu_kinetic_row(rows.shapes[i], 0.0, rows.lawp, i))
    traj = out.traj[i]
    y = np.empty(3)
    ynew = np.empty(3)
    k = np.zeros((K_ROWS, 3))
    cnt = np.zeros(5, dtype=np.int64)
    fl = np.array([np.inf, 0.0])
    y[0] = rows.x0[i, 0]
    y[1] = rows.x0[i, 1]
    y[2] = 0.0
    tau = 0.0
    isave = 0
    f0 = stick_force(y[0], 0.0, prm)
    stick = y[1] == gamma0 and abs(f0) <= _lim_eff(rows, run, 0.0)
    # off the belt speed the relative velocity decides; on it (and outside the static band) the
    # unbalanced force does: slip backwards (s = +1) when it exceeds +limit, forwards below −limit
    if y[1] == gamma0:
        s = 1.0 if f0 >= 0.0 else -1.0
    else:
        s = 1.0 if y[1] < gamma0 else -1.0
    h = min(settings.h0, settings.max_step)
    while tau < tau_end:
        if stick:
            tb = breakaway_time(y[0], tau, tau_end, prm, _lim_eff(rows, run, y[2]))
            te = min(tb, tau_end)
            isave = _save_stick(traj, isave, settings.save_dt, y[0], tau, te, gamma0)
            y[0] += gamma0 * (te - tau)
            tau = te
            if tb >= tau_end:
                break
            stick = False
            cnt[C_BREAK] += 1
            s = 1.0 if stick_force(y[0], tau, prm) > 0.0 else -1.0
            fl[F_SLIP_START] = y[2]
            h = min(settings.h0, settings.max_step)
            continue
        # a new slip segment (after a breakaway or an event): the signs and the process cell are fixed
        # until the next event
        if y[1] != gamma0:
            s = 1.0 if y[1] < gamma0 else -1.0
        seg, node = _new_segment(tau, y, k, s, rows, run)
        ev, tau, h, isave = _slip_until_event(tau, h, y, k, ynew, rows, run, seg, node, settings, traj, isave)
        if ev == EV_BELT or ev == EV_AT_BELT:
            y[1] = gamma0
            tau, isave, stick, s = _belt_contact(tau, y, s, rows, out, settings, run, isave, cnt, fl,
                                                 ev == EV_AT_BELT)
    store_diagnostics(out.diag[i], y[2], fl[F_MIN_SLIP], cnt[C_SHORT], cnt[C_NO_STICK], y[0], y[1], stick,
                      cnt[C_BREAK], cnt[C_PHASES])
    return cnt[C_M]


@numba.njit(cache=True, nogil=True)
def run_accurate_batch(
    rows: KernelRows, out: KernelOutput, settings: AccurateSettings, noise: int, path_mode: int
) -> None:  # pragma: no cover
    """:func:`run_accurate` over the rows of a batch (GIL released)."""
    for i in range(rows.prm.shape[0]):
        out.counts[i] = run_accurate(rows, out, i, settings, noise, path_mode)

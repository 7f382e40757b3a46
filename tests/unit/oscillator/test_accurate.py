"""The ``accurate`` integrator (stochfric.oscillator.accurate) against closed forms.

With a constant kinetic coefficient (law II: μ_s = 0.4, μ_k = 0.25) and D = 0 every slip phase of
eq. (4.7) is a harmonic oscillation about x1 = s n μ_k, ``ξ = x1 − s n μ_k``:
``ξ(τ) = ξ0 cos τ + x2_0 sin τ``, ``x2(τ) = x2_0 cos τ − ξ0 sin τ``.  The switching times and positions
below follow from that by hand (they are not the law-II limit cycle of tests/reference, which starts
at the breakaway point): a start from rest, a passage of the belt speed without sticking (thesis
Fig. 4.15) and the sign rule after it, the stick phase's end (closed form and forced), the
DOP853 pair's order and its dense output.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
from scipy.optimize import brentq

from kernel_helpers import run_accurate  # tests/kernel_helpers.py (test helper)
from stochfric.oscillator import accurate as A
from stochfric.oscillator import kernels as K
from stochfric.oscillator.friction_laws import SHAPE_CONSTANT

N, MU_S, MU_K, G0 = 10.0, 0.4, 0.25, 1.0


def _prm(*, gamma0: float = G0, n: float = N, damping: float = 0.0, q: float = 0.0, eta: float = 0.0,
         x30: float = 0.0, proc_dx: float = 1.0) -> np.ndarray:
    prm = np.zeros(K.N_PRM)
    prm[K.P_GAMMA0] = gamma0
    prm[K.P_N] = n
    prm[K.P_D] = damping
    prm[K.P_Q] = q
    prm[K.P_ETA] = eta
    prm[K.P_X30] = x30
    prm[K.P_VSCALE] = 1.0
    prm[K.P_MUS] = MU_S
    prm[K.P_PROC_DX] = proc_dx
    return prm


def run(x0: tuple[float, float], tau_end: float, *, mu_k: float = MU_K, proc: np.ndarray | None = None,
        proc_dx: float = 1.0, save_dt: float = 0.1, **kw: float) -> dict[str, Any]:
    noise = K.NOISE_NONE if proc is None else K.NOISE_PROCESS
    one = run_accurate(_prm(proc_dx=proc_dx, **kw), SHAPE_CONSTANT, np.array([mu_k]), x0,
                       A.AccurateSettings(tau_end, 1e-3, 0.1, 1e-11, 1e-13, save_dt), noise, K.PATH_MASS, proc,
                       nsave=int(tau_end / save_dt) + 1)
    m, diag = one.m, one.diag
    return {"m": m, "xgh": one.x_gh[:m], "tgh": one.t_gh[:m], "traj": one.traj, "n_no_stick": diag[K.D_N_NO_STICK],
            "n_break": diag[K.D_N_BREAKAWAY], "stick": diag[K.D_STICK], "x1": diag[K.D_X1]}


def test_start_from_rest_sticks_where_the_harmonic_slip_reaches_the_belt_speed() -> None:
    """From (0, 0): s = +1, ξ = x1 − 2.5, x2 = 2.5 sin τ reaches γ0 = 1 at τ = asin(0.4) where
    x1 = 2.5 (1 − √0.84) = 0.20871…, inside n μ_s = 4: stick.  The stick lasts until x1 = 4, then
    the law-II cycle: X_gh = n(2μ_k − μ_s) = 1 after a slip of π + 2 atan(1/1.5)."""
    t0 = math.asin(0.4)
    x0 = 2.5 * (1.0 - math.sqrt(0.84))
    t1 = t0 + (4.0 - x0) / G0 + math.pi + 2.0 * math.atan(1.0 / 1.5)
    out = run((0.0, 0.0), 11.0)
    assert out["m"] == 2
    np.testing.assert_allclose(out["xgh"], [x0, 1.0], atol=1e-9)
    np.testing.assert_allclose(out["tgh"], [t0, t1], atol=1e-9)
    assert out["n_break"] == 1 and out["stick"] == 1.0
    assert out["x1"] == pytest.approx(1.0 + (11.0 - t1) * G0, abs=1e-9)  # sticking since t1
    # the sampled trajectory is the closed form: slip rows from the dense output, stick rows exact
    tr = out["traj"]
    slip = tr[1:5]  # τ = 0.1 … 0.4 < asin(0.4)
    np.testing.assert_allclose(slip[:, 1], 2.5 * (1 - np.cos(slip[:, 0])), atol=1e-9)
    np.testing.assert_allclose(slip[:, 2], 2.5 * np.sin(slip[:, 0]), atol=1e-9)
    stick = tr[(tr[:, 0] > t0) & (tr[:, 0] < t0 + 3.7)]
    np.testing.assert_allclose(stick[:, 1], x0 + (stick[:, 0] - t0) * G0, atol=1e-9)
    assert np.all(stick[:, 2] == G0)


def test_belt_speed_passed_without_sticking_reverses_the_friction_then_sticks() -> None:
    """Fig. 4.15 situation.  From (−4.5, 0.99): s = +1, ξ0 = −7, x2 = 0.99 cos τ + 7 sin τ reaches γ0
    after τa ≈ 0.00143 at x1a ≈ −4.4986, where |x1a| > 4: no stick, friction flips (s = −1,
    ξ = x1 + 2.5).  That slip returns to γ0 after 2 atan(−ξa/γ0) at ξ = −ξa, i.e. x1 = −x1a − 5 ≈ −0.5014:
    stick."""
    ta = brentq(lambda t: 0.99 * math.cos(t) + 7.0 * math.sin(t) - 1.0, 1e-9, 0.5, xtol=1e-16)
    x1a = 2.5 - 7.0 * math.cos(ta) + 0.99 * math.sin(ta)
    xia = x1a + 2.5
    out = run((-4.5, 0.99), 4.0)
    assert out["m"] == 1 and out["n_no_stick"] == 1
    assert out["xgh"][0] == pytest.approx(-xia - 2.5, abs=1e-9)  # −0.50142157…
    assert out["tgh"][0] == pytest.approx(ta + 2.0 * math.atan(-xia / G0), abs=1e-9)  # 2.21515…


def test_a_constant_process_shifts_the_kinetic_coefficient() -> None:
    """Contact model with μ̂ ≡ 0.1 on a fine grid (every grid point is a restart event): the slip
    obeys μ_k + μ̂ = 0.35, so from rest x2 = 3.5 sin τ meets γ0 at asin(1/3.5) and the cycle ends at
    n (2·0.35 − 0.4) = 3."""
    out = run((0.0, 0.0), 12.0, proc=np.full(50, 0.1), proc_dx=0.01)
    t0 = math.asin(1.0 / 3.5)
    assert out["m"] == 2
    np.testing.assert_allclose(out["xgh"], [3.5 * (1.0 - math.cos(t0)), 3.0], atol=1e-9)
    assert out["tgh"][0] == pytest.approx(t0, abs=1e-9)


def test_a_start_on_the_stick_line_below_the_static_band_slips_forward() -> None:
    """From (−5, γ0): the force 5 exceeds n μ_s = 4 pushing forwards, so s = −1, ξ = x1 + 2.5,
    ξ0 = −2.5: x2 = cos τ + 2.5 sin τ returns to γ0 at τ = 2 atan(2.5) = 2.38058 with ξ = +2.5,
    i.e. X_gh = 0 (solve_ivp of stochfric.oscillator.reference agrees: X_gh ≈ 0 at 2.38058)."""
    out = run((-5.0, 1.0), 4.0)
    assert out["m"] >= 1
    assert out["xgh"][0] == pytest.approx(0.0, abs=1e-9)
    assert out["tgh"][0] == pytest.approx(2.0 * math.atan(2.5), abs=1e-9)


# --- the end of a stick phase ------------------------------------------------------------------------


def test_breakaway_time_unforced_is_the_closed_form() -> None:
    """F(τ) = x1s + γ0 (τ − τs) + 2Dγ0 reaches lim at τs + (lim − F(τs))/γ0: 2 + (4 − 1.1)/0.5 = 7.8."""
    prm = _prm(gamma0=0.5, damping=0.1)
    assert A.breakaway_time(1.0, 2.0, 10.0, prm, 4.0) == pytest.approx(7.8, abs=1e-13)
    assert A.breakaway_time(1.0, 2.0, 7.0, prm, 4.0) == math.inf  # not before τ_end


@pytest.mark.parametrize("side", ["upper", "lower"])
def test_breakaway_time_forced_finds_the_first_crossing_of_either_bound(side: str) -> None:
    """q = 5 > lim = 4 with a slow belt (γ0 = 0.01): from τs = π/2 the force −5 cos τ rises to the upper
    bound +4; from τs = 3π/2 it falls to the lower bound −4.  Reference roots by brentq."""
    q, lim, g0 = 5.0, 4.0, 0.01
    ts = math.pi / 2 if side == "upper" else 1.5 * math.pi
    bound = lim if side == "upper" else -lim
    prm = _prm(gamma0=g0, q=q, eta=1.0)

    def force(t: float) -> float:
        return g0 * (t - ts) - q * math.cos(t)

    ref = brentq(lambda t: force(t) - bound, ts + 1e-6, ts + math.pi / 2, xtol=1e-15)
    tb = A.breakaway_time(0.0, ts, 20.0, prm, lim)
    assert tb == pytest.approx(ref, abs=1e-12)
    grid = np.linspace(ts, tb, 2001)[:-1]
    assert np.all(np.abs(g0 * (grid - ts) - q * np.cos(grid)) <= lim)  # no earlier crossing


# --- the Dormand–Prince 8(5,3) pair (DOP853) ------------------------------------------------------


def _dopri(h: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One step from (0.3, −0.5) of the law-I slip equation (x2' = −x1 + 2.5, s = +1)."""
    prm = _prm()
    lawp = np.array([MU_K])
    y = np.array([0.3, -0.5, 0.0])
    k = np.zeros((A.K_ROWS, 3))
    ynew = np.zeros(3)
    seg = A.Segment(s=1.0, rate_x2=-1.0, rate_vr=0.0, cell=0.0, p0=0.0, p1=0.0, inv_dx=0.0)  # mass path, x2 < 0
    k[0] = A._f(y[0], y[1], y[2], 0.0, A._rhs(prm), lawp.reshape(1, -1), seg, SHAPE_CONSTANT, 0)
    A._step(0.0, y, h, k, prm, lawp.reshape(1, -1), seg, SHAPE_CONSTANT, 0, ynew)
    A._dense_prep(0.0, y, ynew, k, h, prm, lawp.reshape(1, -1), seg, SHAPE_CONSTANT, 0)
    return y, ynew, k


def _exact(t: float | np.ndarray) -> tuple[Any, Any]:
    xi0, v0 = 0.3 - 2.5, -0.5
    return 2.5 + xi0 * np.cos(t) + v0 * np.sin(t), v0 * np.cos(t) - xi0 * np.sin(t)


def test_dop853_step_has_local_order_eight_and_dense_output_order_seven() -> None:
    """Local error of the 8th-order solution ∝ h⁹ (halving h divides it by ≈ 512) and of the 7th-order
    dense output at mid-step ∝ h⁸ (≈ 256); a wrong tableau entry drops these orders.  (At h = 0.1 the
    local error, 4e-16, is at rounding level, so the steps are 1.6 … 0.2.)"""
    errs, dens = [], []
    for h in (1.6, 0.8, 0.4, 0.2):
        y, ynew, k = _dopri(h)
        x1, x2 = _exact(h)
        errs.append(math.hypot(ynew[0] - x1, ynew[1] - x2))
        xm, vm = _exact(h / 2)
        dens.append(math.hypot(A._dense(y, k, 0.5, 0) - xm, A._dense(y, k, 0.5, 1) - vm))
        assert A._dense(y, k, 0.0, 0) == y[0] and A._dense(y, k, 1.0, 1) == ynew[1]
    r = np.array(errs[:-1]) / np.array(errs[1:])
    rd = np.array(dens[:-1]) / np.array(dens[1:])
    assert np.all((r > 400) & (r < 650)), r
    assert np.all((rd > 200) & (rd < 330)), rd
    # the third state is the mass path ∫|x2| dτ (here x2 < 0 throughout the step)
    y, ynew, _ = _dopri(0.1)
    ts = np.linspace(0, 0.1, 20001)
    path = float(np.sum(np.abs(_exact(ts)[1][:-1] + _exact(ts)[1][1:]) / 2) * (ts[1] - ts[0]))
    assert ynew[2] == pytest.approx(path, rel=1e-7)


def test_the_last_trajectory_sample_at_tau_end_is_written() -> None:
    """Sticking from (0, γ0) for the whole run: rows τ = 0, 0.1, 0.2, 0.3 with x1 = τ, x2 = 1.
    (simulate(..., integrator='accurate', tau_end=0.3, dt=0.1, save_every=1) allocates these 4 rows.)"""
    traj = run_accurate(_prm(), SHAPE_CONSTANT, np.array([MU_K]), (0.0, G0),
                        A.AccurateSettings(0.3, 1e-3, 0.1, 1e-11, 1e-13, 0.1), K.NOISE_NONE, K.PATH_MASS,
                        capacity=4, nsave=4).traj
    np.testing.assert_allclose(traj[:3], [[0.0, 0.0, 1.0], [0.1, 0.1, 1.0], [0.2, 0.2, 1.0]], atol=1e-15)
    np.testing.assert_allclose(traj[3], [0.3, 0.3, 1.0], atol=1e-12)


@pytest.mark.parametrize("eps", [1e-9, 1e-6])
def test_a_graze_of_the_belt_speed_inside_one_step_is_an_event(eps: float) -> None:
    """From (0, 0) the slip x2 = 2.5 sin τ peaks at 2.5; with γ0 = 2.5 − ε it exceeds the belt speed
    only for 2 acos(1 − ε/2.5) ≈ 5.7e-5 (ε = 1e-9), far inside one step (max_step 0.1), so the signs at
    the step's ends agree.  The graze search on the dense output finds the touch at τ* = asin(γ0/2.5),
    where x1 = 2.5 (1 − cos τ*) ≤ n μ_s = 4: the mass sticks there.  (Without it the mass slips past
    every peak and never sticks.)"""
    g0 = 2.5 - eps
    ts = math.asin(g0 / 2.5)
    out = run((0.0, 0.0), 3.0, gamma0=g0)
    assert out["m"] == 1
    assert out["tgh"][0] == pytest.approx(ts, abs=1e-9)
    assert out["xgh"][0] == pytest.approx(2.5 * (1.0 - math.cos(ts)), abs=1e-9)

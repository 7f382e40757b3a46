"""The compiled fixed-step kernel (stochfric.oscillator.kernels) against hand-computed steps.

Every expected value below is one or two explicit Euler steps of the equations of motion written
out here from docs/method.md §5 (thesis eq. 4.6/4.7, the switching rule below eq. 4.12):

* stick  (4.6): ``x1' = γ0``, ``x2 = γ0`` while ``|x1 + 2Dγ0 − q cos x3| ≤ n μ_s``;
* slip   (4.7): ``x1' = x2``, ``x2' = −x1 − 2D x2 + n μ_k(L ω0 |γ0 − x2|) s + q cos x3``,
  ``s = sign(γ0 − x2)``;
* a switching point inside a step is found by linear interpolation (force against ``±n μ_s`` for
  stick→slip, ``x2`` against ``γ0`` for slip→stick) and the rest of the step uses the other equations;
* white noise (§5.1): Itô drift ``− s n² σ_ζ/4``, diffusion ``b = n s √(σ_ζ |γ0 − x2|)``; Milstein adds
  ``½ b b' (ΔW² − Δτ)`` with ``b b' = −s n² σ_ζ/2`` (derived here from b, not read from the code).

The numbers are chosen so that each step can be checked with a pocket calculator (law II: μ_s = 0.4,
μ_k = 0.25; law III: Table 4.1).  The kernel is called directly, one parameter row per trajectory.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest

from kernel_helpers import run_fixed_step  # tests/kernel_helpers.py (test helper)
from stochfric.oscillator import kernels as K
from stochfric.oscillator.friction_laws import SHAPE_CONSTANT, SHAPE_RATIONAL

LAW_II = (SHAPE_CONSTANT, np.array([0.25, 0.0, 0.0, 0.0]), 0.4)  # μ_k = 0.25, μ_s = 0.4
LAW_III = (SHAPE_RATIONAL, np.array([0.3, 1.42, 0.1, 0.01]), 0.4)  # (μ0 − μ1, 1.42, μ1, 0.01)


def mu_III(v: float) -> float:
    """Table 4.1 law III, written from the thesis: (μ0 − μ1)/(1 + 1.42|v|) + μ1 + 0.01 v²."""
    return (0.4 - 0.1) / (1.0 + 1.42 * abs(v)) + 0.1 + 0.01 * v * v


#: The parameters ``run`` takes by name: their column of the parameter row and their default.
PRM = {"gamma0": (K.P_GAMMA0, 1.0), "n": (K.P_N, 10.0), "damping": (K.P_D, 0.0), "q": (K.P_Q, 0.0),
       "eta": (K.P_ETA, 0.0), "vscale": (K.P_VSCALE, 1.0), "sigma": (K.P_SIGMA, 0.0), "proc_dx": (K.P_PROC_DX, 1.0)}


def run(
    x0: list[tuple[float, float]] | tuple[float, float],
    nsteps: int,
    dt: float,
    *,
    law: tuple[int, np.ndarray, float] = LAW_II,
    noise: int = K.NOISE_NONE,
    scheme: int = K.SCHEME_EULER,
    path_mode: int = K.PATH_MASS,
    dw: np.ndarray | None = None,
    proc: np.ndarray | None = None,
    **prm: float,
) -> dict[str, Any]:
    """Run ``len(x0)`` trajectories with identical parameters (``prm``: the names of :data:`PRM`, else
    their defaults; x30 = 0, μ_s of the law) through ``run_fixed_step_batch``."""
    assert set(prm) <= set(PRM), set(prm) - set(PRM)
    starts = [x0] if isinstance(x0[0], float | int) else list(x0)  # type: ignore[list-item]
    nt = len(starts)
    row = np.zeros(K.N_PRM)
    for name, (col, default) in PRM.items():
        row[col] = prm.get(name, default)
    row[K.P_MUS] = law[2]
    shapes = np.full(nt, law[0], dtype=np.int64)
    lawp = np.tile(law[1], (nt, 1))
    x0a = np.array(starts, dtype=np.float64).reshape(nt, 2)
    dwa = np.zeros((nt, max(nsteps, 1))) if dw is None else np.tile(np.asarray(dw, float), (nt, 1))
    proca = np.tile(np.zeros(1) if proc is None else np.asarray(proc, float), (nt, 1))
    nproc = np.full(nt, proca.shape[1], dtype=np.int64)
    xgh = np.full((nt, 8), np.nan)
    tgh = np.full((nt, 8), np.nan)
    counts = np.zeros(nt, dtype=np.int64)
    traj = np.zeros((nt, nsteps + 1, 3))
    diag = np.zeros((nt, K.N_DIAG))
    K.run_fixed_step_batch(K.KernelRows(np.tile(row, (nt, 1)), shapes, lawp, x0a, proca, nproc),
                           K.KernelOutput(xgh, tgh, counts, traj, diag), K.FixedStepGrid(nsteps, dt, 1),
                           scheme, noise, path_mode,
                           K.WhiteInput(K.WHITE_GIVEN, dwa, np.zeros(1, dtype=np.uint64)))
    return {"x1": diag[:, K.D_X1], "x2": diag[:, K.D_X2], "stick": diag[:, K.D_STICK],
            "path": diag[:, K.D_PATH], "n_break": diag[:, K.D_N_BREAKAWAY],
            "n_no_stick": diag[:, K.D_N_NO_STICK], "n_phases": diag[:, K.D_N_SLIP_PHASES],
            "xgh": xgh, "tgh": tgh, "counts": counts, "traj": traj}


# --- slip: the explicit Euler step of eq. (4.7) ------------------------------------------------------


@pytest.mark.parametrize("forced", [False, True], ids=["unforced", "forced"])
def test_two_slip_steps_are_explicit_euler_steps_of_eq_4_7(forced: bool) -> None:
    """Law III with the velocity scale L ω0 = 2 m/s (μ reads the *dimensional* |v_rel|), damped,
    optionally forced (q cos ητ evaluated at the left end of each step)."""
    g0, n, d, vs, dt = 1.0, 10.0, 0.1, 2.0, 0.01
    q, eta = (0.5, 1.15) if forced else (0.0, 0.0)
    x1, x2 = 0.3, -0.5
    expected = []
    for k in range(2):
        vr = g0 - x2  # > 0: s = +1
        acc = -x1 - 2 * d * x2 + n * mu_III(vs * vr) * 1.0 + q * math.cos(eta * k * dt)
        x1, x2 = x1 + x2 * dt, x2 + acc * dt
        expected.append((x1, x2))
    # step 1 by hand for the unforced case: μ(3 m/s) = 0.3/5.26 + 0.1 + 0.09 = 0.2470342205…
    if not forced:
        assert expected[0][1] == pytest.approx(-0.5 + 0.01 * (-0.3 + 0.1 + 2.470342205323194), rel=1e-12)
    out = run((0.3, -0.5), 2, dt, law=LAW_III, gamma0=g0, n=n, damping=d, q=q, eta=eta, vscale=vs)
    np.testing.assert_allclose(out["traj"][0, 1:, 1:], np.array(expected), rtol=1e-14, atol=1e-15)
    assert out["stick"][0] == 0 and out["counts"][0] == 0 and out["n_break"][0] == 0
    # the mass path of the contact model grows by |Δx1| = |x2| Δτ per step (thesis 4.1.3)
    assert out["path"][0] == pytest.approx(0.5 * dt + abs(expected[0][1]) * dt, rel=1e-14)


def test_a_mass_faster_than_the_belt_feels_friction_backwards() -> None:
    """s = sign(γ0 − x2) = −1 for x2 > γ0: friction decelerates the mass."""
    out = run((0.0, 1.5), 1, 0.01)  # law II, n = 10, γ0 = 1
    assert out["x2"][0] == pytest.approx(1.5 + 0.01 * (-0.0 - 10 * 0.25), rel=1e-14)  # 1.475
    assert out["x1"][0] == pytest.approx(0.015, rel=1e-14)


# --- stick (4.6) and the two switching rules ---------------------------------------------------------


def test_stick_moves_with_the_belt_while_the_static_force_holds() -> None:
    out = run((0.5, 1.0), 100, 0.01, damping=0.1)  # |x1 + 2Dγ0| ≤ 0.5 + 1 + 0.2 < n μ_s = 4
    assert out["x1"][0] == pytest.approx(0.5 + 100 * 0.01 * 1.0, rel=1e-13)
    assert out["x2"][0] == 1.0 and out["stick"][0] == 1.0
    assert out["n_break"][0] == 0 and out["path"][0] == 0.0  # no path travelled in stick


def test_breakaway_is_located_inside_the_step_and_the_rest_of_the_step_slips() -> None:
    """n μ_s = 4, 2Dγ0 = 0.2: the force x1 + 0.2 reaches 4 at x1 = 3.8, 30 % into the step from
    x1 = 3.797 (Δτ = 0.01).  The first slip runs with s = +1 (the spring pulls back): over the
    remaining 0.007 the mass keeps x2 = γ0 in x1 and decelerates with
    x2' = −3.8 − 0.2·1 + 10·0.25 = −1.5."""
    out = run((3.797, 1.0), 1, 0.01, damping=0.1)
    assert out["n_break"][0] == 1 and out["stick"][0] == 0.0
    assert out["x1"][0] == pytest.approx(3.807, abs=1e-13)
    assert out["x2"][0] == pytest.approx(1.0 - 1.5 * 0.007, abs=1e-13)


def test_slip_to_stick_is_located_by_linear_interpolation_of_x2() -> None:
    """From (1.0, 0.99): x2' = −1 + 2.5 = 1.5, so x2 would reach 1.005 after Δτ = 0.01; it crosses
    γ0 = 1 at θ = 0.01/0.015 = 2/3 of the step, where x1 = 1 + (2/3)(0.99·0.01) = 1.0066.
    |1.0066| ≤ 4: the mass sticks there (X_gh) and moves with the belt for the last third."""
    out = run((1.0, 0.99), 1, 0.01)
    assert out["counts"][0] == 1 and out["n_phases"][0] == 1 and out["stick"][0] == 1.0
    assert out["xgh"][0, 0] == pytest.approx(1.0066, abs=1e-13)
    assert out["tgh"][0, 0] == pytest.approx(0.01 * 2 / 3, abs=1e-15)
    assert out["x1"][0] == pytest.approx(1.0066 + 0.01 / 3, abs=1e-13)
    assert out["x2"][0] == 1.0


def test_belt_speed_without_stick_keeps_slipping_and_reverses_the_friction() -> None:
    """Thesis Fig. 4.15: x2 reaches γ0 while |x1| > n μ_s.  From (−4.5, 0.99): x2' = 4.5 + 2.5 = 7,
    x2 passes γ0 at x1 ≈ −4.4986 where static friction (4) cannot hold the force 4.4986: the full
    Euler step is kept, (−4.4901, 1.06); the next step has s = −1: x2' = 4.4901 − 2.5."""
    out = run((-4.5, 0.99), 2, 0.01)
    assert out["counts"][0] == 0 and out["n_no_stick"][0] == 1
    np.testing.assert_allclose(out["traj"][0, 1, 1:], [-4.4901, 1.06], atol=1e-13)
    np.testing.assert_allclose(out["traj"][0, 2, 1:], [-4.4901 + 0.0106, 1.06 + 0.01 * (4.4901 - 2.5)],
                               atol=1e-13)


def test_lanes_of_one_lock_step_group_are_independent() -> None:
    """More trajectories than one lock-step group, mixed stick/slip/switching states: every lane
    gives its own hand-computed result (the group's fast pass and full step may not mix lanes)."""
    starts = [(1.0, 0.99), (0.5, 1.0), (3.997, 1.0), (0.0, 1.5)] * (K.LOCKSTEP // 4 + 2)
    out = run(starts, 1, 0.01)  # D = 0: breakaway at x1 = 4, 30 % into the step of lane 2
    x1 = {0: 1.0066 + 0.01 / 3, 1: 0.51, 2: 4.007, 3: 0.015}
    x2 = {0: 1.0, 1: 1.0, 2: 1.0 - 1.5 * 0.007, 3: 1.475}
    for j in range(len(starts)):
        assert out["x1"][j] == pytest.approx(x1[j % 4], abs=1e-13), j
        assert out["x2"][j] == pytest.approx(x2[j % 4], abs=1e-13), j
    assert out["counts"].tolist() == [1 if j % 4 == 0 else 0 for j in range(len(starts))]


def test_a_start_on_the_stick_line_below_the_static_band_slips_forward() -> None:
    """From (−5, γ0) the spring pushes with 5 > n μ_s = 4: the mass must leave the belt forwards
    (x2 > γ0, friction −n μ_k): one step gives x2 = 1 + 0.01·(5 − 2.5) = 1.025 (docs/oscillator.md:
    'the unbalanced force decides' the direction of the first slip)."""
    out = run((-5.0, 1.0), 1, 0.01)
    assert out["x2"][0] == pytest.approx(1.025, abs=1e-12)


def test_forced_breakaway_interpolates_the_moving_stick_bound() -> None:
    """Eq. (4.9): with forcing the force F = x1 + 2Dγ0 − q cos ητ moves in time.  q = 0.5, η = 1.15,
    D = 0, from (4.2, 1.0) stuck (F(0) = 3.7): after Δτ = 0.1, F = 4.3 − 0.5 cos 0.115 ≈ 3.80330 still
    holds; the next step ends with F ≈ 3.90988 — the bound 4 is crossed inside step 3, at
    θ = (4 − F(0.2))/(F(0.3) − F(0.2)) of it (linear interpolation of the force), then slip s = +1."""
    q, eta, dt = 0.5, 1.15, 0.1

    def force(x1: float, t: float) -> float:
        return x1 - q * math.cos(eta * t)

    f2, f3 = force(4.4, 0.2), force(4.5, 0.3)
    assert f2 < 4.0 < f3
    th = (4.0 - f2) / (f3 - f2)
    h = dt * (1 - th)
    x1b = 4.4 + th * dt
    x2 = 1.0 + h * (-x1b + 10 * 0.25 + q * math.cos(eta * (0.2 + th * dt)))
    out = run((4.2, 1.0), 3, dt, q=q, eta=eta)
    assert out["n_break"][0] == 1 and out["stick"][0] == 0.0
    np.testing.assert_allclose(out["traj"][0, 2, 1:], [4.4, 1.0], atol=1e-13)
    assert out["x1"][0] == pytest.approx(x1b + h, abs=1e-13)
    assert out["x2"][0] == pytest.approx(x2, abs=1e-13)


# --- white noise: Euler–Maruyama and Milstein steps with a given increment ---------------------------


@pytest.mark.parametrize("scheme", [K.SCHEME_EULER, K.SCHEME_MILSTEIN], ids=["euler-maruyama", "milstein"])
def test_white_noise_step_has_the_ito_drift_and_the_sqrt_diffusion(scheme: int) -> None:
    g0, n, sig, dt, dw = 1.0, 10.0, 0.01, 0.01, 0.07
    x1, x2 = 0.2, 0.5  # v_rel = 0.5 > 0, s = +1
    a = -x1 + n * 0.25  # law II, D = q = 0
    ito = -(n * n * sig) / 4  # ½ b ∂b/∂x2 with b = n s √(σ(γ0 − x2))
    b = n * math.sqrt(sig * (g0 - x2))  # = 10 √0.005
    bb = -(n * n * sig) / 2  # b ∂b/∂x2 = n √(σ u) · (−n σ /(2 √(σ u))), u = γ0 − x2
    x2n = x2 + (a + ito) * dt + b * dw
    if scheme == K.SCHEME_MILSTEIN:
        x2n += 0.5 * bb * (dw * dw - dt)
    out = run((x1, x2), 1, dt, sigma=sig, noise=K.NOISE_WHITE, scheme=scheme, dw=np.array([dw]))
    assert out["x2"][0] == pytest.approx(x2n, abs=1e-14)
    assert out["x1"][0] == pytest.approx(x1 + x2 * dt, abs=1e-15)
    # σ_ζ = 0 reduces both schemes to the deterministic Euler step, whatever ΔW
    det = run((x1, x2), 1, dt, sigma=0.0, noise=K.NOISE_WHITE, scheme=scheme, dw=np.array([dw]))
    assert det["x2"][0] == pytest.approx(x2 + a * dt, abs=1e-15)


def test_white_noise_leaves_the_stick_phase_deterministic() -> None:
    out = run((0.5, 1.0), 3, 0.01, sigma=0.5, noise=K.NOISE_WHITE, dw=np.array([0.3, -0.2, 0.1]))
    assert out["x1"][0] == pytest.approx(0.53, abs=1e-14) and out["x2"][0] == 1.0


# --- the contact-analysis process (§5.2) -------------------------------------------------------------


def test_process_value_interpolates_linearly_and_repeats_periodically() -> None:
    proc = np.array([0.0, 1.0, 4.0, 9.0])  # grid dx = 0.5, period 2
    pv = [K.process_value(proc, 4, 0.5, x) for x in (0.0, 0.25, 0.6, 1.75, 2.25, 4.6, 2.0)]
    np.testing.assert_allclose(pv, [0.0, 0.5, 1.6, 4.5, 0.5, 1.6, 0.0], atol=1e-14)


@pytest.mark.parametrize("path_mode", [K.PATH_MASS, K.PATH_RELATIVE, K.PATH_POSITION],
                         ids=["mass", "relative", "position"])
def test_contact_slip_steps_add_the_process_read_at_the_path(path_mode: int) -> None:
    """μ = μ_k + μ̂(path): μ̂ on the grid dx = 0.002 with values 0, 0.1, 0.2, …; the path starts at 0
    and grows by |Δx1| (mass, and position mode) or |γ0 − x2| Δτ (relative) per slip step; the
    position mode (eq. 4.36/4.38 as printed) reads μ̂ at x1 itself (x1 = 0.201 → grid point 100.5,
    i.e. 4.5 after the periodic continuation with 8 points)."""
    proc = 0.1 * np.arange(8)
    dx, dt, g0, n = 0.002, 0.01, 1.0, 10.0
    x1, x2, path = 0.201, -0.3, 0.0
    for _ in range(2):
        u = (x1 if path_mode == K.PATH_POSITION else path) / dx
        i = math.floor(u)
        mu_hat = proc[i % 8] + (u - i) * (proc[(i + 1) % 8] - proc[i % 8])
        acc = -x1 + n * (0.25 + mu_hat)
        dpath = abs(g0 - x2) * dt if path_mode == K.PATH_RELATIVE else abs(x2) * dt
        x1, x2, path = x1 + x2 * dt, x2 + acc * dt, path + dpath
    out = run((0.201, -0.3), 2, dt, noise=K.NOISE_PROCESS, path_mode=path_mode, proc=proc, proc_dx=dx)
    assert out["path"][0] == pytest.approx(path, abs=1e-15)
    assert out["x1"][0] == pytest.approx(x1, abs=1e-14) and out["x2"][0] == pytest.approx(x2, abs=1e-14)


def test_breakaway_with_the_process_also_needs_the_kinetic_friction_exceeded() -> None:
    """Documented choice (docs/oscillator.md): breakaway needs F > max(n μ_s, n (μ_k(0) + μ̂)).
    With μ̂ ≡ 0.25: n (0.25 + 0.25) = 5 > n μ_s = 4, so a stick from x1 = 3 lasts until x1 = 5
    (τ = 2), not until x1 = 4 (τ = 1)."""
    proc = np.full(8, 0.25)
    kw: dict[str, Any] = dict(noise=K.NOISE_PROCESS, proc=proc, proc_dx=0.01)
    at_15 = run((3.0, 1.0), 150, 0.01, **kw)
    assert at_15["stick"][0] == 1.0 and at_15["n_break"][0] == 0
    assert at_15["x1"][0] == pytest.approx(4.5, abs=1e-12)
    at_25 = run((3.0, 1.0), 250, 0.01, **kw)
    assert at_25["n_break"][0] == 1 and at_25["stick"][0] == 0.0
    # and without the process it breaks away at x1 = 4 (τ = 1)
    assert run((3.0, 1.0), 95, 0.01)["n_break"][0] == 0
    assert run((3.0, 1.0), 105, 0.01)["n_break"][0] == 1


def test_single_trajectory_wrapper_equals_the_batch_kernel() -> None:
    """``run_fixed_step`` (one row) is the batch kernel: same X_gh, same final state."""
    prm = np.zeros(K.N_PRM)
    prm[K.P_GAMMA0], prm[K.P_N], prm[K.P_VSCALE], prm[K.P_MUS], prm[K.P_PROC_DX] = 1.0, 10.0, 1.0, 0.4, 1.0
    one = run_fixed_step(prm, SHAPE_CONSTANT, np.array([0.25]), (0.0, 1.0), K.FixedStepGrid(2000, 0.01, 1),
                         K.SCHEME_EULER, K.NOISE_NONE, K.PATH_MASS, np.zeros(1))
    out = run((0.0, 1.0), 2000, 0.01)
    assert one.m == out["counts"][0] >= 2
    np.testing.assert_array_equal(one.x_gh, out["xgh"][0])
    assert one.diag[K.D_X1] == out["x1"][0] and one.diag[K.D_X2] == out["x2"][0]
    # law II cycle (undamped): X_gh → n(2μ_k − μ_s) = 1 with Euler's O(Δτ) error (−4.68 Δτ)
    assert one.x_gh[0] == pytest.approx(1.0, abs=0.1)


# --- the forcing terms of a lock-step group -----------------------------------------------------


def test_forcing_terms_are_q_cos_x3_at_both_ends_of_the_step() -> None:
    """``_forcing_terms``: q cos(x30 + η kΔτ) and q cos(x30 + η (kΔτ + Δτ)) for every forced lane,
    bit for bit the full step's values, whether computed, copied from an equal neighbour or carried
    from the previous step; unforced lanes untouched (zero)."""
    q = np.array([0.0, 2e-4, 2e-4, 5e-4, 0.0, 5e-4, 5e-4])
    x30 = np.array([0.0, 0.0, 0.0, 0.3, 0.0, 0.3, 0.0])
    eta = np.array([0.0, 1.3, 1.3, 0.7, 0.0, 0.7, 0.7])
    cs = np.zeros((K._NC, 7))
    cs[K._C_FORCED], cs[K._C_QQ], cs[K._C_X30], cs[K._C_ETA] = (q != 0.0), q, x30, eta
    stp = np.zeros((K._NW, 7))
    now, nxt = stp[K._W_FQ_NOW], stp[K._W_FQ_NEXT]
    dt = 0.005
    for k in range(0, 400):
        K._forcing_terms(k, dt, cs, stp)
        for j in range(7):
            if q[j] == 0.0:
                assert now[j] == 0.0 and nxt[j] == 0.0
            else:
                assert now[j] == q[j] * math.cos(x30[j] + eta[j] * (k * dt))
                assert nxt[j] == q[j] * math.cos(x30[j] + eta[j] * (k * dt + dt))

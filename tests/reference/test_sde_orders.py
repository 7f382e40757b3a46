"""Reference tier: measured strong orders of the SDE schemes (method §5.1).

1. Geometric Brownian motion dX = aX dτ + bX dW (closed-form solution) through the
   package's own step functions :func:`em_step` / :func:`milstein_step`.
2. The friction SDE (Itô form of eq. 4.23) in a slip phase, through the production kernel,
   against a fine-step Milstein reference on the same Brownian paths.

Strong error ε(Δτ) = E|X_Δτ(T) − X(T)|; order = slope of log ε over log Δτ.  Fixed
seeds, so the measured orders are deterministic numbers (friction SDE: EM 0.57,
Milstein 1.03); the bands are EM 0.5 ± 0.15 and Milstein 1 ± 0.2.
"""

from __future__ import annotations

import numpy as np
import pytest

from kernel_helpers import run_fixed_step  # tests/kernel_helpers.py (test helper)
from stochfric.oscillator import kernels as K
from stochfric.oscillator.friction_laws import law_III


def _brownian(rng: np.random.Generator, paths: int, n_fine: int, t_end: float) -> np.ndarray:
    return rng.standard_normal((paths, n_fine)) * np.sqrt(t_end / n_fine)


def _coarsen(dw: np.ndarray, factor: int) -> np.ndarray:
    return dw.reshape(dw.shape[0], -1, factor).sum(axis=2)


def _order(dts: np.ndarray, errs: np.ndarray) -> float:
    return float(np.polyfit(np.log(dts), np.log(errs), 1)[0])


def test_strong_orders_on_geometric_brownian_motion() -> None:
    a, b, x0, t_end = 1.5, 1.0, 1.0, 1.0
    rng = np.random.default_rng(20131106)
    n_fine = 2**12
    dw_fine = _brownian(rng, 400, n_fine, t_end)
    exact = x0 * np.exp((a - 0.5 * b * b) * t_end + b * dw_fine.sum(axis=1))
    dts, err_em, err_mil = [], [], []
    for k in (4, 5, 6, 7, 8):
        n = 2**k
        dw = _coarsen(dw_fine, n_fine // n)
        h = t_end / n
        xe = np.full(dw.shape[0], x0)
        xm = np.full(dw.shape[0], x0)
        for j in range(n):
            xe = np.array([K.em_step(x, a * x, b * x, w, h) for x, w in zip(xe, dw[:, j], strict=False)])
            xm = np.array([K.milstein_step(x, a * x, b * x, b * b * x, w, h)
                           for x, w in zip(xm, dw[:, j], strict=False)])
        dts.append(h)
        err_em.append(np.mean(np.abs(xe - exact)))
        err_mil.append(np.mean(np.abs(xm - exact)))
    assert 0.35 < _order(np.array(dts), np.array(err_em)) < 0.65
    assert 0.8 < _order(np.array(dts), np.array(err_mil)) < 1.2


def _friction_final_states(dw: np.ndarray, dt: float, scheme: int) -> tuple[np.ndarray, np.ndarray]:
    law = law_III()
    prm = np.zeros(K.N_PRM)
    prm[K.P_GAMMA0], prm[K.P_N], prm[K.P_VSCALE] = 50.0, 10.0, 0.01
    prm[K.P_MUS], prm[K.P_SIGMA], prm[K.P_PROC_DX] = law.static, 0.02, 1.0
    paths = dw.shape[0]
    out = np.zeros((paths, 2))
    ok = np.ones(paths, dtype=bool)
    for i in range(paths):
        one = run_fixed_step(prm, law.shape, law.param_array, (3.0, 0.0), K.FixedStepGrid(dw.shape[1], dt, 1),
                             scheme, K.NOISE_WHITE, K.PATH_RELATIVE, dw[i], capacity=4)
        diag = one.diag
        out[i] = diag[K.D_X1], diag[K.D_X2]
        ok[i] = one.m == 0 and diag[K.D_N_NO_STICK] == 0 and diag[K.D_N_BREAKAWAY] == 0
    return out, ok


def test_strong_orders_on_the_friction_sde_against_a_fine_reference() -> None:
    """Slip phase of the white-noise oscillator far below the belt speed (γ0 = 50, n = 10,
    L ω0 = 0.01 m/s, law III, σ_ζ = 0.02, x0 = (3, 0), τ = 1): b b' = −n² σ_ζ/2 = −1 makes
    the Milstein term matter, and no stick transition occurs, so the error is the scheme's."""
    t_end = 1.0
    rng = np.random.default_rng(42)
    n_fine = 2**14
    dw_fine = _brownian(rng, 200, n_fine, t_end)
    ref, ok_ref = _friction_final_states(dw_fine, t_end / n_fine, K.SCHEME_MILSTEIN)
    assert ok_ref.all()
    dts, err_em, err_mil = [], [], []
    for k in (6, 7, 8, 9, 10):
        n = 2**k
        dw = _coarsen(dw_fine, n_fine // n)
        xe, ok_e = _friction_final_states(dw, t_end / n, K.SCHEME_EULER)
        xm, ok_m = _friction_final_states(dw, t_end / n, K.SCHEME_MILSTEIN)
        assert ok_e.all() and ok_m.all()
        dts.append(t_end / n)
        err_em.append(np.mean(np.abs(xe[:, 1] - ref[:, 1])))
        err_mil.append(np.mean(np.abs(xm[:, 1] - ref[:, 1])))
    o_em = _order(np.array(dts), np.array(err_em))
    o_mil = _order(np.array(dts), np.array(err_mil))
    print(f"strong orders: EM {o_em:.3f}, Milstein {o_mil:.3f}")
    assert 0.35 < o_em < 0.65, (err_em, o_em)
    assert 0.8 < o_mil < 1.2, (err_mil, o_mil)
    assert err_mil[-1] < err_em[-1] / 3


@pytest.mark.parametrize("scheme", [K.SCHEME_EULER, K.SCHEME_MILSTEIN])
def test_zero_intensity_white_noise_equals_the_deterministic_euler(scheme: int) -> None:
    rng = np.random.default_rng(1)
    dw = _brownian(rng, 1, 400, 2.0)
    law = law_III()
    prm = np.zeros(K.N_PRM)
    prm[K.P_GAMMA0], prm[K.P_N], prm[K.P_VSCALE], prm[K.P_MUS] = 1.0, 10.0, 1.0, 0.4
    prm[K.P_PROC_DX] = 1.0
    grid = K.FixedStepGrid(400, 0.005, 1)
    d1 = run_fixed_step(prm, law.shape, law.param_array, (3.0, 0.0), grid, scheme, K.NOISE_WHITE, K.PATH_RELATIVE,
                        dw[0], capacity=4).diag
    d2 = run_fixed_step(prm, law.shape, law.param_array, (3.0, 0.0), grid, K.SCHEME_EULER, K.NOISE_NONE,
                        K.PATH_RELATIVE, dw[0], capacity=4).diag
    assert d1[K.D_X1] == d2[K.D_X1] and d1[K.D_X2] == d2[K.D_X2]

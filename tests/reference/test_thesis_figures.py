"""Reference tier: the thesis's integrator demonstrations (Fig. 4.6, 4.7, 4.8, 4.15).

Demo oscillator of method §5: ω0 = 1, γ0 = 1, n = 10, D = 0.
"""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.oscillator.friction_laws import law_II, law_III, pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions, OutputOptions
from stochfric.oscillator.parameters import OscillatorParameters, PhysicalParameters
from stochfric.oscillator.presets import brake

DEMO = OscillatorParameters(gamma0=1.0, n=10.0)


def test_fig_4_6_euler_inner_cycle_grows_without_damping() -> None:
    """Law II, x0 = (2, 0): the exact solution is the circle of radius 0.5 about n μ_k = 2.5
    that never reaches the stick line; Euler multiplies the radius by √(1 + Δτ²) per step."""
    dt, tau_end = 0.001, 50.0
    eu = simulate(DEMO, law=law_II(), x0=(2.0, 0.0), integration=IntegrationOptions(dt=dt, tau_end=tau_end),
                  output=OutputOptions(save_trajectory=True, save_every=1))
    ac = simulate(DEMO, law=law_II(), x0=(2.0, 0.0),
                  integration=IntegrationOptions(integrator="accurate", dt=dt, tau_end=tau_end),
                  output=OutputOptions(save_trajectory=True, save_every=10))
    assert eu.stick_count[0, 0] == ac.stick_count[0, 0] == 0
    r_eu = np.hypot(eu.trajectory[0, 0, :, 1] - 2.5, eu.trajectory[0, 0, :, 2])
    r_ac = np.hypot(ac.trajectory[0, 0, :, 1] - 2.5, ac.trajectory[0, 0, :, 2])
    np.testing.assert_allclose(r_ac, 0.5, atol=1e-8)
    k = np.arange(r_eu.size)
    np.testing.assert_allclose(r_eu, 0.5 * (1 + dt * dt) ** (k / 2), rtol=1e-9)
    assert r_eu[-1] > 0.5 * 1.02  # visibly outward spiral (2.5 % at τ = 50)


def test_fig_4_7_unforced_euler_keeps_the_character_at_coarse_steps() -> None:
    """Law III from (0, γ0): Δτ = 0.001 / 0.01 / 0.05 all give the period-1 cycle; the
    error in X_gh grows with Δτ (only 0.05 is visibly off in the thesis's plot)."""
    ref = simulate(DEMO, law=law_III(),
                   integration=IntegrationOptions(integrator="accurate", tau_end=50.0)).x_gh[0, 0, 0]
    errs = []
    for dt in (0.001, 0.01, 0.05):
        r = simulate(DEMO, law=law_III(), integration=IntegrationOptions(dt=dt, tau_end=50.0))
        assert bool(r.warnings) == (dt > 0.02)  # the coarse-step warning, in the result
        m = int(r.stick_count[0, 0])
        xg = r.x_gh[0, 0, :m]
        assert m >= 5
        assert np.ptp(xg[1:]) < 1e-3  # still one X_gh: the character is unchanged
        errs.append(abs(xg[-1] - ref))
    assert errs[0] < 0.005 < errs[2]
    assert errs[0] < errs[1] < errs[2]


def _period2_defect(xg: np.ndarray) -> float:
    tail = xg[len(xg) // 2:]
    return float(np.max(np.abs(tail[2:] - tail[:-2])))


def test_fig_4_8_forced_two_periodic_solution_and_dt_effects() -> None:
    """q = 0.5, η = 1.15, x0 = (3.2, γ0), law III: the exact solution is two-periodic; Euler
    keeps that up to Δτ = 0.01, and Δτ = 0.1 makes it look chaotic (with a warning)."""
    p = DEMO.replace(q=0.5, eta=1.15)
    ac = simulate(p, law=law_III(), x0=(3.2, 1.0),
                  integration=IntegrationOptions(integrator="accurate", tau_end=300.0))
    xa = ac.x_gh[0, 0, : int(ac.stick_count[0, 0])]
    assert _period2_defect(xa[-8:]) < 1e-7  # converged to the 2-cycle (transient decays slowly)
    assert abs(xa[-1] - xa[-2]) > 0.5  # two distinct stick positions
    e1 = simulate(p, law=law_III(), x0=(3.2, 1.0), integration=IntegrationOptions(dt=0.001, tau_end=300.0))
    x1 = e1.x_gh[0, 0, : int(e1.stick_count[0, 0])]
    assert _period2_defect(x1) < 1e-3
    assert sorted(x1[-2:]) == pytest.approx(sorted(xa[-2:]), abs=0.03)
    e3 = simulate(p, law=law_III(), x0=(3.2, 1.0), integration=IntegrationOptions(dt=0.1, tau_end=300.0))
    assert any("apparent chaos" in w.message for w in e3.warnings)
    x3 = e3.x_gh[0, 0, : int(e3.stick_count[0, 0])]
    assert _period2_defect(x3) > 0.3
    assert len(np.unique(np.round(x3[len(x3) // 2:], 2))) > 6


def test_fig_4_15_belt_speed_reached_without_sticking() -> None:
    """Brake, N = 720 N, undamped: x2 reaches γ0 while the static condition fails, the mass
    keeps slipping and sticks further right (thesis Fig. 4.15)."""
    pre = brake()
    p = PhysicalParameters(mass=pre.mass, stiffness=pre.stiffness, belt_speed=1.0,
                           normal_force=720.0, damping_ratio=5e-6,
                           contact_area=pre.contact_area).to_dimensionless()
    assert p.pressure_pa is not None
    law = pressure_law(pre.process.mean(p.pressure_pa))
    r = simulate(p, law=law, integration=IntegrationOptions(integrator="accurate", tau_end=50.0))
    m = int(r.stick_count[0, 0])
    assert m >= 5
    assert r.diagnostics["n_belt_speed_without_stick"][0, 0] == m
    lim = p.n * law.static
    # it sticks inside the static bounds, to the right of the left bound −n μ_s − 2Dγ0
    xg = r.x_gh[0, 0, :m]
    assert np.all(xg > -lim) and np.all(xg < lim)
    # and Euler converges to it with order one
    errs = [abs(simulate(p, law=law, integration=IntegrationOptions(dt=dt, tau_end=10.0)).x_gh[0, 0, 0] - xg[0])
            for dt in (1e-3, 1e-4)]
    assert errs[1] < errs[0] / 5

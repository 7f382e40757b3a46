"""Reference tier: linear stability boundary of steady sliding and the subcritical Hopf.

D_H = −n μ'(v0) v0 / (2γ0) (linearisation of eq. 4.7; thesis eq. 4.39) for the brake
preset at N = 5600 N with the pressure law (4.13).
"""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.oscillator.friction_laws import law_III, pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions, OutputOptions
from stochfric.oscillator.parameters import OscillatorParameters, PhysicalParameters
from stochfric.oscillator.presets import brake
from stochfric.oscillator.reference import hopf_damping


@pytest.fixture(scope="module")
def brake_case() -> tuple[OscillatorParameters, object]:
    pre = brake()
    p = PhysicalParameters(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                           normal_force=5600.0, contact_area=pre.contact_area).to_dimensionless()
    assert p.pressure_pa is not None
    return p, pressure_law(pre.process.mean(p.pressure_pa))


def test_hopf_boundary_equals_zero_trace_of_the_numerical_jacobian(brake_case) -> None:
    p, law = brake_case
    dh = hopf_damping(p, law)
    assert 0.09 < dh < 0.10  # ≈ 0.0946 for the Table 3.3 fit at p = 0.35 MPa
    # ∂(x2')/∂x2 at steady sliding from a central difference of the law (independent of
    # the analytic derivative): trace = −2D + n s ∂μ/∂x2 vanishes at D = D_H
    h = 1e-7
    vs = p.velocity_scale
    dmu_dx2 = (law(vs * (p.gamma0 - h)) - law(vs * (p.gamma0 + h))) / (2 * h)
    trace_at_dh = -2 * dh + p.n * float(dmu_dx2)
    assert abs(trace_at_dh) < 1e-6 * dh
    # law III demo: μ'(1 m/s) = −0.3·1.42/2.42² + 0.02
    demo = OscillatorParameters(gamma0=1.0, n=10.0)
    assert hopf_damping(demo, law_III()) == pytest.approx(
        -10 * (-0.3 * 1.42 / 2.42**2 + 0.02) / 2, rel=1e-12
    )


@pytest.mark.parametrize("offset", [-0.02, 0.02])
def test_small_oscillations_about_steady_sliding_grow_or_decay_at_the_linear_rate(
    brake_case, offset: float
) -> None:
    p, law = brake_case
    dh = hopf_damping(p, law)
    d = dh + offset
    q = p.replace(damping_ratio=d)
    xs = q.n * float(law.kinetic(q.belt_speed))  # rest position (4.8)
    eps = 1e-3 * q.gamma0
    res = simulate(q, law=law, x0=(xs + eps, 0.0),
                   integration=IntegrationOptions(integrator="accurate", tau_end=40.0, dt=0.01),
                   output=OutputOptions(save_trajectory=True, save_every=1))
    assert res.stick_count[0, 0] == 0
    tr = res.trajectory[0, 0]
    t, x = tr[:, 0], tr[:, 1] - xs
    # envelope: peaks of |x| per half period; slope of log amplitude = −(D − D_H)·ω-shift
    peaks = [i for i in range(1, len(x) - 1) if abs(x[i]) >= abs(x[i - 1]) and abs(x[i]) > abs(x[i + 1])]
    rate = np.polyfit(t[peaks], np.log(np.abs(x[peaks])), 1)[0]
    assert rate == pytest.approx(-offset, rel=0.02)


def test_stick_slip_survives_just_above_the_hopf_boundary(brake_case) -> None:
    """Subcritical Hopf: steady sliding is linearly stable for D > D_H, yet the stick-slip
    cycle reached from sticking at (0, γ0) persists; far above D_H it dies out."""
    p, law = brake_case
    dh = hopf_damping(p, law)
    above = simulate(p.replace(damping_ratio=dh + 0.01), law=law,
                     integration=IntegrationOptions(integrator="accurate", tau_end=100.0))
    m = int(above.stick_count[0, 0])
    assert m >= 10
    xg = above.x_gh[0, 0, :m]
    assert abs(xg[-1] - xg[-2]) < 1e-8  # a settled limit cycle
    far = simulate(p.replace(damping_ratio=dh + 0.1), law=law,
                   integration=IntegrationOptions(integrator="accurate", tau_end=100.0))
    assert far.stick_count[0, 0] == 0

"""Validation of the damping study against closed forms and the integrators (method §6.2).

* D_max^d(N) ≥ D_H(N) on the map: the Hopf bifurcation of steady sliding is subcritical,
  so a stick-slip cycle started from a large perturbation (sticking at the origin)
  survives above the linear stability boundary D_H = −n μ'(v0) v0/(2γ0).
* D_max^d does not depend on Δτ with the ``accurate`` integrator (Δτ is only its sampling
  step) and the thesis's Euler scheme agrees with it to one grid step.
* the stick probability is 1 well below D_max^d and 0 well above for every model.
"""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import damping_study

FORCES = (1800.0, 3000.0, 4400.0, 5600.0, 8000.0)


def _det(**kw: object) -> DampingConfig:
    base: dict[str, object] = {"models": ("deterministic",), "normal_forces": FORCES, "damping_ratios": "0.01:0.25:49",
                               "runs": 1, "seed": 0}
    base.update(kw)
    return DampingConfig(**base)  # type: ignore[arg-type]


def test_dmax_above_hopf_boundary_on_the_map() -> None:
    ds = damping_study(_det()).to_dataset()
    dmax = ds["d_max_sample_extreme"].sel(model="deterministic").values
    dh = ds["d_hopf"].values
    assert np.all(np.isfinite(dmax))
    assert np.all(dmax >= dh), (dmax, dh)
    # D_H grows ∝ n (the law's slope at v0 depends on p only through μ_fit): check the closed form
    assert np.all(np.diff(dh) > 0)
    # below D_H steady sliding is unstable: stick-slip at every grid D < D_H
    hc = ds["has_cycle"].sel(model="deterministic", run=0).values
    for i, d_h in enumerate(dh):
        below = ds["damping_ratio"].values < d_h
        assert np.all(hc[i, below] == 1)


def test_dmax_independent_of_dt_with_accurate() -> None:
    forces = (3000.0, 5600.0)
    a = damping_study(_det(normal_forces=forces, integrator="accurate", dt=0.005)).to_dataset()
    b = damping_study(_det(normal_forces=forces, integrator="accurate", dt=0.0025)).to_dataset()
    e = damping_study(_det(normal_forces=forces, integrator="euler", dt=0.005)).to_dataset()
    da = a["d_max_sample_extreme"].sel(model="deterministic").values
    np.testing.assert_array_equal(da, b["d_max_sample_extreme"].sel(model="deterministic").values)
    step = 0.005
    assert np.all(np.abs(e["d_max_sample_extreme"].sel(model="deterministic").values - da) <= step + 1e-12)


def test_probability_is_one_below_and_zero_far_above() -> None:
    cfg = DampingConfig(normal_forces=(5600.0,), damping_ratios=(0.06, 0.09, 0.3 * 0.99), runs=6, seed=3)
    ds = damping_study(cfg).to_dataset()
    p = ds["stick_probability"].sel(normal_force_n=5600.0)
    for m in cfg.models:
        assert p.sel(model=m).values[0] == 1.0
        assert p.sel(model=m).values[-1] == 0.0
    lo = ds["stick_probability_low"].sel(normal_force_n=5600.0, model="white").values
    hi = ds["stick_probability_high"].sel(normal_force_n=5600.0, model="white").values
    assert lo[0] == pytest.approx(0.025 ** (1 / 6))
    assert hi[-1] == pytest.approx(1 - 0.025 ** (1 / 6))

"""The `thesis` white-noise mode (printed eq. 4.31, method erratum 10) against the default Itô model.

Reading (docs/oscillator.md): ΔW = Δτ R_k with the dimensional relative velocity under the root
is Euler–Maruyama with σ_ζ,eff = σ_ζ · Lω0 · Δτ, so for small noise every X_gh deviation scales
with √(ω0Δτ): brake √(707.1 · 0.005) = 1.880, sheet √(316.2 · 0.005) = 1.257.

Observable: the *first* slip→stick position of each run (one independent value per run, the
same deterministic breakaway for every run, so the response to the noise is linear; the pooled
X_gh of a whole run are not, e.g. sheet 400 N: 1.16 ± 0.03).  Tolerance: 4 standard errors of
the ratio (delta method from bootstraps over runs, fixed seeds).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.oscillator.case import case_setup, law_for
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, NoiseOptions
from stochfric.studies.stats import RatioEstimate, std_ratio

RUNS = 1000
TAU_END = 12.0  # the first slip→stick transition lies near τ ≈ 6-9 for all six cases


def _first_x_gh(preset: str, forces: tuple[float, ...], mode: str, seed: int, dt: float) -> list[list[np.ndarray]]:
    st = case_setup(preset, white_intensity=mode, dt=dt)
    ps = [st.parameters(f, 5e-6) for f in forces]
    res = simulate(ps, model="white", law=lambda p: law_for(st.process, p), process=st.process, runs=RUNS,
                   seed=seed, noise=NoiseOptions(white_increment=st.white_increment),
                   integration=IntegrationOptions(tau_end=TAU_END, dt=dt), execution=ExecutionOptions(workers=2))
    assert np.all(np.isfinite(res.x_gh[:, :, 0])), "every run must reach its first stick phase"
    return [[res.x_gh[i, r, :1] for r in range(RUNS)] for i in range(len(forces))]


def _ratio(a: list[np.ndarray], b: list[np.ndarray]) -> RatioEstimate:
    return std_ratio(a, b, n_boot=300, rng=np.random.default_rng(5))


@pytest.mark.parametrize(("preset", "forces"), [("brake", (720.0, 2720.0, 8000.0)), ("sheet", (400.0, 880.0, 1750.0))])
def test_thesis_mode_scales_sigma_by_sqrt_omega0_dt(preset: str, forces: tuple[float, ...]) -> None:
    dt = 0.005
    ito = _first_x_gh(preset, forces, "sigma_mu", seed=11, dt=dt)
    thesis = _first_x_gh(preset, forces, "thesis", seed=12, dt=dt)
    k = math.sqrt(case_setup(preset).preset.omega0 * dt)
    for i, f in enumerate(forces):
        r = _ratio(thesis[i], ito[i])
        assert abs(r.value - k) < 4 * r.se_delta, (preset, f, r, k)
        # the test can fail: the ratio is many standard errors away from 1 (no scaling)
        assert abs(r.value - 1.0) > 4 * r.se_delta, (preset, f, r)


def test_thesis_mode_intensity_depends_on_dt_the_default_does_not() -> None:
    forces = (2720.0,)
    half = {m: _first_x_gh("brake", forces, m, seed=21, dt=0.0025)[0] for m in ("sigma_mu", "thesis")}
    full = {m: _first_x_gh("brake", forces, m, seed=22, dt=0.005)[0] for m in ("sigma_mu", "thesis")}
    r_ito = _ratio(full["sigma_mu"], half["sigma_mu"])
    r_thesis = _ratio(full["thesis"], half["thesis"])
    assert abs(r_ito.value - 1.0) < 4 * r_ito.se_delta, r_ito  # consistent SDE: no Δτ dependence
    assert abs(r_thesis.value - math.sqrt(2.0)) < 4 * r_thesis.se_delta, r_thesis  # σ ∝ √Δτ
    assert abs(r_thesis.value - 1.0) > 4 * r_thesis.se_delta, r_thesis

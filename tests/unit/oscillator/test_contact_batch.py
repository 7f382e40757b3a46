"""The contact model's process realisations, generated per batch (issue 13).

``simulate`` draws each trajectory's phases with compiled PCG64 and evaluates the spectral
representation (eq. 2.48) for the whole batch at once; the kernel reads μ̂ from per-lane
segment caches in its SIMD pass.  Both must give exactly the numbers of the per-trajectory
path (``process.generate(p, Generator(PCG64(trajectory_seed)))`` and the gathering scalar
pass).
"""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

from stochfric.friction_process.model import ModelFunction, TabulatedProcessModel
from stochfric.friction_process.spectral import generate_process, generate_process_batch
from stochfric.oscillator.friction_laws import pressure_law
from stochfric.oscillator.integrate import simulate, trajectory_seed
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, NoiseOptions, OutputOptions
from stochfric.oscillator.parameters import PhysicalParameters
from stochfric.oscillator.presets import brake, sheet
from stochfric.random import philox as P


class _PerTrajectory:
    """Wraps a process model so that ``simulate`` cannot recognise it and calls ``generate``
    per trajectory (the path of versions before issue 13)."""

    def __init__(self, model: Any) -> None:
        self._m = model
        self.dx, self.length = model.dx, model.length
        self.grid_is_periodic = model.grid_is_periodic

    def generate(self, p: float, rng: np.random.Generator) -> np.ndarray:
        return self._m.generate(p, rng)

    def sigma_zeta(self, p: float) -> float:
        return self._m.sigma_zeta(p)

    def to_dict(self) -> dict[str, Any]:
        return self._m.to_dict()


def _tabulated() -> TabulatedProcessModel:
    length, dx = 0.05, 0.0005
    f = np.arange(1, 50) / length
    table = np.stack([1e-5 * (1.0 - 0.5 * f / f[-1]), np.full(f.size, 4e-5)])
    return TabulatedProcessModel(name="tab", mu_mean=ModelFunction(a=2.0, b=-0.3, c=0.2),
                                 mu_std=ModelFunction(a=0.4, b=-0.17, c=0.0), dx=dx, length=length,
                                 pressures_pa=(1e5, 1e6), table_frequencies=tuple(f),
                                 table_psd=tuple(tuple(r) for r in table))


def test_batch_realisations_equal_generate_process_per_row() -> None:
    m = brake().process
    f = m.frequencies()
    s = m.spectrum(f, 3e5)
    root = np.random.SeedSequence(17)
    sets, runs = np.array([0, 0, 2, 5]), np.array([0, 3, 1, 2**31 + 1])
    phases = P.pcg64_uniform_for_children(root, np.column_stack([sets, runs]), f.size, 2 * np.pi)
    batch = generate_process_batch(f, s, m.dx, m.length, phases)
    for j in range(4):
        rng = np.random.Generator(np.random.PCG64(trajectory_seed(root, (int(sets[j]),), int(runs[j]))))
        np.testing.assert_array_equal(batch[j], generate_process(f, s, m.dx, m.length, rng))
    with pytest.raises(ValueError, match="phases must have shape"):
        generate_process_batch(f, s, m.dx, m.length, phases[:, :-1])


@pytest.mark.parametrize("path", ["mass", "relative", "position"])
@pytest.mark.parametrize(("preset", "tabulated"), [(brake, False), (sheet, False), (brake, True)])
def test_simulate_contact_equals_the_per_trajectory_path(path: str, preset: Any, tabulated: bool) -> None:
    pre = preset()
    process = _tabulated() if tabulated else pre.process
    base = PhysicalParameters(mass=pre.mass, stiffness=pre.stiffness, belt_speed=pre.belt_speed,
                              normal_force=2000.0, damping_ratio=5e-6,
                              contact_area=pre.contact_area).to_dimensionless()
    sets = [base, base.with_normal_force(4000.0), base.replace(q=1e-4, eta=1.3)]  # a forced set too

    def law(p: Any) -> Any:
        return pressure_law(pre.process.mean(p.pressure_pa))

    kw: dict[str, Any] = dict(model="contact", law=law, runs=5, seed=23, integration=IntegrationOptions(tau_end=25.0),
                              noise=NoiseOptions(path_coordinate=path), output=OutputOptions(save_trajectory=True))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        a = simulate(sets, process=process, **kw, execution=ExecutionOptions(workers=1))
        b = simulate(sets, process=_PerTrajectory(process), **kw, execution=ExecutionOptions(workers=1))
        c = simulate(sets, process=process, **kw, execution=ExecutionOptions(workers=2, batch_size=2))
    for r in (b, c):
        np.testing.assert_array_equal(a.x_gh, r.x_gh)
        np.testing.assert_array_equal(a.trajectory, r.trajectory)
        for k in a.diagnostics:
            np.testing.assert_array_equal(a.diagnostics[k], r.diagnostics[k])
    assert a.stick_count.sum() > 0

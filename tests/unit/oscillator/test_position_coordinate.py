"""`path_coordinate="position"`: the contact process read at the mass position x1 (eq. 4.36/4.38 as
printed, μ̂_SD(X_1, ξ)), a reproduction mode (docs/friction_process.md, issue 10)."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from stochfric.oscillator.case import case_setup, law_for
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions, NoiseOptions
from stochfric.oscillator.parameters import ParameterError


class FixedProcess:
    """A process model stub that returns one fixed realisation (brake grid)."""

    def __init__(self, base: Any, values: np.ndarray) -> None:
        self.base, self.values = base, values
        self.dx, self.length = base.dx, base.length

    def generate(self, p: float, rng: np.random.Generator) -> np.ndarray:
        return self.values.copy()

    def sigma_zeta(self, p: float) -> float:
        return 0.0

    def to_dict(self) -> dict[str, Any]:
        return {"kind": "fixed"}


def _run(values: np.ndarray, coordinate: str) -> np.ndarray:
    st = case_setup("brake")
    p = st.parameters(2720.0, 5e-6)
    res = simulate(p, model="contact", law=law_for(st.process, p), process=FixedProcess(st.process, values),
                   noise=NoiseOptions(path_coordinate=coordinate), integration=IntegrationOptions(tau_end=50.0))
    return res.x_gh[0, 0]


def test_position_mode_reads_only_where_the_mass_is() -> None:
    rng = np.random.default_rng(4)
    a = 0.07 * rng.standard_normal(79)
    b = a.copy()
    b[20:60] = 0.07 * rng.standard_normal(40)  # x1 ∈ [−1, 3]·1e-3 m never reaches 20·Δx = 12.7 mm
    pa, pb = _run(a, "position"), _run(b, "position")
    np.testing.assert_array_equal(pa, pb)
    ma, mb = _run(a, "mass"), _run(b, "mass")  # the accumulated path does reach them (≈ 30 mm by τ = 50)
    assert not np.array_equal(ma[np.isfinite(ma)], mb[np.isfinite(mb)])
    assert not np.array_equal(pa[np.isfinite(pa)], ma[np.isfinite(ma)])


def test_position_mode_refuses_the_accurate_integrator() -> None:
    st = case_setup("brake")
    p = st.parameters(2720.0, 5e-6)
    with pytest.raises(ParameterError, match="'position'"):
        simulate(p, model="contact", law=law_for(st.process, p), process=st.process,
                 noise=NoiseOptions(path_coordinate="position"),
                 integration=IntegrationOptions(integrator="accurate"))

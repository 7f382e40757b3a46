"""The friction oscillator (method §5, thesis 4.1): parameters, friction laws, integrators, results.

Physical → dimensionless parameters (:mod:`.parameters`, eq. 4.6/4.7), the friction-law registry
(:mod:`.friction_laws`, Table 4.1 and the pressure law 4.13), ensembles of trajectories with the
fixed-step kernels and the event-located DOPRI5 integrator (:mod:`.integrate`), labelled results
(:mod:`.result`) and closed-form references (:mod:`.reference`).  Importing compiles nothing:
the numba kernels compile (or load from their cache) on first use.
"""

from __future__ import annotations

from stochfric.oscillator.friction_laws import FrictionLaw, get_law, law_I, law_II, law_III, pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.parameters import OscillatorParameters, ParameterError, PhysicalParameters
from stochfric.oscillator.result import SimulationResult, SimulationWarning, load_result

__all__ = [
    "FrictionLaw",
    "OscillatorParameters",
    "ParameterError",
    "PhysicalParameters",
    "SimulationResult",
    "SimulationWarning",
    "get_law",
    "law_I",
    "law_II",
    "law_III",
    "load_result",
    "pressure_law",
    "simulate",
]

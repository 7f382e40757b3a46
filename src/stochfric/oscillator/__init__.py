"""The friction oscillator (method §5, thesis 4.1): parameters, friction laws, integrators, results.

Physical → dimensionless parameters (:mod:`.parameters`, eq. 4.6/4.7), the friction-law registry
(:mod:`.friction_laws`, Table 4.1 and the pressure law 4.13), the thesis's cases (:mod:`.presets`) and
one case built from any input (:mod:`.case`), the choices and option groups of a simulation
(:mod:`.options`), ensembles of trajectories with the fixed-step kernels and the event-located DOP853
integrator (:mod:`.integrate`), labelled results (:mod:`.result`) and closed-form references
(:mod:`.reference`).  Importing compiles nothing:
the numba kernels compile (or load from their cache) on first use.
"""

from __future__ import annotations

from stochfric.oscillator.case import (
    Case,
    CaseError,
    CaseSetup,
    DimensionlessInput,
    FrictionInput,
    PhysicalInput,
    build_case,
    case_setup,
)
from stochfric.oscillator.friction_laws import FrictionLaw, get_law, law_I, law_II, law_III, pressure_law
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import (
    ExecutionOptions,
    IntegrationOptions,
    Integrator,
    Model,
    NoiseOptions,
    OutputOptions,
    PathCoordinate,
    WhiteIncrement,
    WhiteIntensity,
    WhiteStream,
)
from stochfric.oscillator.parameters import OscillatorParameters, ParameterError, PhysicalParameters
from stochfric.oscillator.presets import Preset, PresetName, get_preset
from stochfric.oscillator.result import SimulationResult, SimulationWarning, load_result

__all__ = [
    "Case",
    "CaseError",
    "CaseSetup",
    "DimensionlessInput",
    "ExecutionOptions",
    "FrictionInput",
    "FrictionLaw",
    "IntegrationOptions",
    "Integrator",
    "Model",
    "NoiseOptions",
    "OscillatorParameters",
    "OutputOptions",
    "ParameterError",
    "PathCoordinate",
    "PhysicalInput",
    "PhysicalParameters",
    "Preset",
    "PresetName",
    "SimulationResult",
    "SimulationWarning",
    "WhiteIncrement",
    "WhiteIntensity",
    "WhiteStream",
    "build_case",
    "case_setup",
    "get_law",
    "get_preset",
    "law_I",
    "law_II",
    "law_III",
    "load_result",
    "pressure_law",
    "simulate",
]

"""stochfric — stochastic friction coefficients from measured surfaces and their effect on
friction-induced vibration (after N. Gaus, KIT 2013).

**Python API** (docs/api.md): the functions the command line calls, under one roof, each imported
from its home module on first use (``import stochfric`` itself stays light)::

    import stochfric as sf
    raw = sf.read_surface(sf.default_surface_path())          # a measured map (instrument file)
    fine, coarse, prep = sf.prepare_with_report(raw, sf.Preparation(detrend="auto", step=2))
    analysis = sf.analyse(coarse, sf.load_material("brake-pad"), approach_m, sf.AnalysisConfig(seed=1))
    case = sf.build_case("brake", physical=sf.PhysicalInput(normal_force=2720.0), model="contact")
    result = sf.simulate(case, model="contact", runs=100, seed=1,
                         integration=sf.IntegrationOptions(integrator=sf.Integrator.ACCURATE))
    study = sf.run_study(sf.DampingConfig(preset="brake", normal_forces=(5600.0,)))
    sf.write_report([study], "out")
    again = sf.load(result.to_netcdf("run/simulation.nc"))    # any saved result, typed again

Importing the package does no work — no compilation, no registration, no logging set-up, no
change to numba's settings.  The SIMD width numba compiles for on Intel Xeons with AVX-512 is an
explicit call, :func:`stochfric.vector_width.configure` (it changes speed, never a number); the
command line makes it when ``STOCHFRIC_VECTOR_WIDTH`` is set.
"""

from __future__ import annotations

import importlib
from typing import Any

__version__ = "0.1.0"

#: The curated API: name → home module (the object keeps its home name; one implementation).
API: dict[str, str] = {
    # surfaces (method §1)
    "read_surface": "stochfric.surface.io",
    "surface_from_array": "stochfric.surface.io",
    "default_surface_path": "stochfric.surface.io",
    "Surface": "stochfric.surface.io",
    "Preparation": "stochfric.surface.preprocess",
    "prepare_with_report": "stochfric.surface.preprocess",
    "summits_of": "stochfric.surface.summits",
    "load_scan": "stochfric.surface.scans",
    "pool_scans": "stochfric.surface.scans",
    "SurrogateMethod": "stochfric.surface.surrogates",
    "register_surrogate": "stochfric.surface.surrogates",
    # contact of one surface (§2)
    "load_material": "stochfric.contact.materials",
    "Material": "stochfric.contact.materials",
    "default_approach_m": "stochfric.contact.asperity",
    "asperity_contact": "stochfric.contact.asperity",
    # statistical contact analysis and the friction process (§3–§4)
    "AnalysisConfig": "stochfric.process.analysis_config",
    "analyse": "stochfric.process.statistics",
    "StatisticalContactAnalysis": "stochfric.process.analysis_result",
    "analyse_scans": "stochfric.process.pipeline",
    "ScanAnalysis": "stochfric.process.pipeline",
    "load_process_model": "stochfric.friction_process.model",
    # the friction oscillator (§5)
    "get_preset": "stochfric.oscillator.presets",
    "build_case": "stochfric.oscillator.case",
    "case_setup": "stochfric.oscillator.case",
    "Case": "stochfric.oscillator.case",
    "PhysicalInput": "stochfric.oscillator.case",
    "DimensionlessInput": "stochfric.oscillator.case",
    "FrictionInput": "stochfric.oscillator.case",
    "simulate": "stochfric.oscillator.integrate",
    "Model": "stochfric.oscillator.options",
    "Integrator": "stochfric.oscillator.options",
    "PathCoordinate": "stochfric.oscillator.options",
    "WhiteStream": "stochfric.oscillator.options",
    "WhiteIntensity": "stochfric.oscillator.options",
    "NoiseOptions": "stochfric.oscillator.options",
    "IntegrationOptions": "stochfric.oscillator.options",
    "OutputOptions": "stochfric.oscillator.options",
    "ExecutionOptions": "stochfric.oscillator.options",
    "SimulationResult": "stochfric.oscillator.result",
    "load_result": "stochfric.oscillator.result",
    # studies and the report (§6)
    "DampingConfig": "stochfric.studies.config",
    "ForcingConfig": "stochfric.studies.config",
    "LyapunovConfig": "stochfric.studies.config",
    "NormalForceConfig": "stochfric.studies.config",
    "run_study": "stochfric.studies.reproduce",
    "StudyResult": "stochfric.studies.base",
    "make_executor": "stochfric.studies.executors",
    "write_report": "stochfric.report.html",
    # saved results back as typed objects (any file the CLI or the library writes)
    "load": "stochfric.studies.loading",
}

__all__ = ["API", "__version__", *API]


def __getattr__(name: str) -> Any:
    """The API object ``name`` from its home module (PEP 562: imported on first use, then cached)."""
    home = API.get(name)
    if home is None:
        raise AttributeError(f"module 'stochfric' has no attribute {name!r}; the API is {sorted(API)}")
    value = getattr(importlib.import_module(home), name)
    globals()[name] = value
    return value


def __dir__() -> list[str]:
    return sorted(set(globals()) | set(API))

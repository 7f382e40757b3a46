"""μ as a stochastic process (method §3–§4, thesis 3.1.2–3.1.4, 3.2.3–3.2.5, 3.3.3–3.3.4).

The statistical contact analysis (:func:`analyse`, :mod:`.statistics`: contact of similar surfaces
in :mod:`.ensemble`, spectra in :mod:`.spectra`, fits in :mod:`.fit`, checks in :mod:`.checks` and
:mod:`.credibility`), the friction-process models (:mod:`.model`), the spectral representation
(:mod:`.spectral`) and the process models of the thesis's two cases (:mod:`.presets`).  Figures in
:mod:`.figures` (imported on demand: matplotlib).
"""

from __future__ import annotations

from stochfric.process.model import (
    BandLimitedProcessModel,
    FrictionProcessModel,
    ModelFunction,
    TabulatedProcessModel,
    load_process_model,
)
from stochfric.process.presets import brake_process, sheet_process
from stochfric.process.statistics import AnalysisConfig, StatisticalContactAnalysis, analyse

__all__ = [
    "AnalysisConfig",
    "BandLimitedProcessModel",
    "FrictionProcessModel",
    "ModelFunction",
    "StatisticalContactAnalysis",
    "TabulatedProcessModel",
    "analyse",
    "brake_process",
    "load_process_model",
    "sheet_process",
]

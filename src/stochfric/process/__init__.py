"""μ as a stochastic process (method §3–§4, thesis 3.1.2–3.1.4, 3.2.3–3.2.5, 3.3.3–3.3.4).

Contact of similar surfaces and sliding windows with their surrogate options (:mod:`.ensemble`),
spectra along the path (:mod:`.spectra`), estimators with standard errors (:mod:`.estimators`), the
fits of the model functions a p^b + c (:mod:`.fit`), the statistical analysis (:mod:`.statistics`,
:func:`analyse`) with its settings (:mod:`.analysis_config`), its result and files
(:mod:`.analysis_result`), its self-checks (:mod:`.checks`) and memory estimate (:mod:`.memory`);
the friction-process models (:mod:`.model`: the import point of :mod:`.model_function`,
:mod:`.model_base`, :mod:`.band_limited`, :mod:`.tabulated`), the spectral representation
(:mod:`.spectral`) and the thesis's presets (:mod:`.presets`).  Figures in :mod:`.figures`
(imported on demand: matplotlib).
"""

from __future__ import annotations

from stochfric.process.model import (
    BandLimitedProcessModel,
    FrictionProcessModel,
    ModelFunction,
    TabulatedProcessModel,
    load_process_model,
)
from stochfric.process.presets import Preset, brake, get_preset, sheet
from stochfric.process.statistics import AnalysisConfig, StatisticalContactAnalysis, analyse

__all__ = [
    "AnalysisConfig",
    "BandLimitedProcessModel",
    "FrictionProcessModel",
    "ModelFunction",
    "Preset",
    "StatisticalContactAnalysis",
    "TabulatedProcessModel",
    "analyse",
    "brake",
    "get_preset",
    "load_process_model",
    "sheet",
]

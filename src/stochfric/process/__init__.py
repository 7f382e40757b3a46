"""The statistical contact analysis that produces a friction-process model (method §3–§4, thesis
3.1.2–3.1.4, 3.2.3–3.2.5, 3.3.3–3.3.4).

:func:`analyse` (:mod:`.statistics`): contact of similar surfaces (:mod:`.ensemble`), fits
(:mod:`.fit`), checks and the gate (:mod:`.checks`, :mod:`.credibility`), the settings
(:mod:`.analysis_config`) and the result (:mod:`.analysis_result`); figures in :mod:`.figures`
(matplotlib).  The models it produces, and that the oscillator reads, live one floor down in
:mod:`stochfric.friction_process`.

Importing this package does no work: the names below are imported from their home modules on first
use (PEP 562), so ``import stochfric.process.checks`` does not load the whole analysis.
"""

from __future__ import annotations

from typing import Any

__all__ = ["AnalysisConfig", "StatisticalContactAnalysis", "analyse"]


def __getattr__(name: str) -> Any:
    if name == "AnalysisConfig":
        from stochfric.process.analysis_config import AnalysisConfig

        return AnalysisConfig
    if name == "StatisticalContactAnalysis":
        from stochfric.process.analysis_result import StatisticalContactAnalysis

        return StatisticalContactAnalysis
    if name == "analyse":
        from stochfric.process.statistics import analyse

        return analyse
    raise AttributeError(f"module 'stochfric.process' has no attribute {name!r}")

"""The study kinds (method §6): one :class:`StudyKind` per kind, in :data:`STUDY_KINDS`.

A kind names its config class (:mod:`~stochfric.studies.config`), its study function, its summary
class (:mod:`~stochfric.studies.summary`) and its title; the report keys its figures and readings
by the same names (the report is a higher layer).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from .base import StudyResult
from .config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig, StudyConfig
from .damping import DampingSummary, damping_study
from .errors import StudyError
from .forcing import ForcingSummary, forcing_study
from .lyapunov import LyapunovSummary, lyapunov_study
from .normal_force import NormalForceSummary, normal_force_study
from .summary import StudySummary


@dataclass(frozen=True)
class StudyKind:
    """One kind of study: ``name`` (``config.kind``, the file stem ``<name>.json``/``.nc``), its config
    class, its study function (``run(config, executor=…, checkpoint=…, progress=…)``), its summary class
    and a title (method section)."""

    name: str
    config: type[StudyConfig]
    run: Callable[..., StudyResult[Any]]
    summary: type[StudySummary]
    title: str


STUDY_KINDS: dict[str, StudyKind] = {k.name: k for k in (
    StudyKind("damping", DampingConfig, damping_study, DampingSummary,
              "Damping: P(stick-slip | D), D_max(α), D_max^d and the Hopf boundary (method §6.2)"),
    StudyKind("forcing", ForcingConfig, forcing_study, ForcingSummary,
              "Forcing: bifurcation diagrams over η (method §6.3)"),
    StudyKind("lyapunov", LyapunovConfig, lyapunov_study, LyapunovSummary,
              "Largest Lyapunov exponent (method §6.4)"),
    StudyKind("normal-force", NormalForceConfig, normal_force_study, NormalForceSummary,
              "Normal force: phase diagrams, PDFs, E[X_gh] ± σ, VarK (method §6.1)"),
)}


def study_kind(name: str) -> StudyKind:
    """The kind called ``name``; :class:`StudyError` naming the kinds for another."""
    try:
        return STUDY_KINDS[name]
    except KeyError:
        raise StudyError(f"unknown study kind {name!r}; one of {', '.join(STUDY_KINDS)}") from None

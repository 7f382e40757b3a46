"""Studies of the friction oscillator (method §6; thesis 4.2, 4.3).

Each study is a function taking a validated config and returning a
:class:`~stochfric.studies.base.StudyResult` (``to_dataset()``, its typed ``summary``,
``to_json_dict()``):
:func:`damping_study`, :func:`forcing_study`, :func:`lyapunov_study`,
:func:`normal_force_study`; :data:`STUDY_KINDS` names each kind's config, function and summary class.
Executors (serial, processes, Dask) and checkpoints never change the numbers.  Importing this package does no work;
:func:`reproduce` and :func:`run_study` (which reach the chapter-3 analysis, and with it the surface,
contact and process floors) are imported on first use, so a study worker that unpickles a task loads
the oscillator and the studies only.
"""

from typing import Any

from .base import StudyResult
from .config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from .damping import DampingSummary, damping_study
from .executors import DaskExecutor, ProcessExecutor, SerialExecutor, make_executor, run_tasks
from .forcing import ForcingSummary, forcing_study
from .kinds import STUDY_KINDS, StudyKind
from .lyapunov import LyapunovSummary, lyapunov_study
from .normal_force import NormalForceSummary, normal_force_study
from .store import CheckpointStore
from .summary import StudySummary

__all__ = [
    "STUDY_KINDS",
    "CheckpointStore",
    "DampingConfig",
    "DampingSummary",
    "DaskExecutor",
    "ForcingConfig",
    "ForcingSummary",
    "LyapunovConfig",
    "LyapunovSummary",
    "NormalForceConfig",
    "NormalForceSummary",
    "ProcessExecutor",
    "SerialExecutor",
    "StudyKind",
    "StudyResult",
    "StudySummary",
    "damping_study",
    "forcing_study",
    "lyapunov_study",
    "make_executor",
    "normal_force_study",
    "reproduce",
    "run_study",
    "run_tasks",
]


def __getattr__(name: str) -> Any:
    """:func:`reproduce` and :func:`run_study` on first use (PEP 562)."""
    if name == "reproduce":
        from .reproduce import reproduce

        return reproduce
    if name == "run_study":
        from .reproduce import run_study

        return run_study
    raise AttributeError(f"module 'stochfric.studies' has no attribute {name!r}")

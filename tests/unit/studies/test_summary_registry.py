""":meth:`StudyResult.load` finds a kind's summary class without importing the kinds' registry (which
imports the study modules, which import ``studies.base``: that was an import cycle).  Each study
module's summary class names its kind; the registry of the kinds agrees with them, and importing only
``stochfric.studies.base`` (in a fresh process) knows every kind: :mod:`stochfric.studies` imports the
study modules."""

from __future__ import annotations

import subprocess
import sys

import pytest

from stochfric.studies.errors import StudyError
from stochfric.studies.kinds import STUDY_KINDS
from stochfric.studies.summary import summary_class


def test_the_summary_classes_name_the_kinds_of_the_registry() -> None:
    for name, kind in STUDY_KINDS.items():
        assert summary_class(name) is kind.summary
    with pytest.raises(StudyError, match="unknown study kind 'sweep'; one of damping, forcing, lyapunov, normal-force"):
        summary_class("sweep")


def test_importing_the_study_base_alone_knows_every_kind() -> None:
    code = ("from stochfric.studies.base import StudyResult\nfrom stochfric.studies.summary import summary_class\n"
            "print(' '.join(summary_class(k).__name__ for k in ('damping', 'forcing', 'lyapunov', 'normal-force')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    assert done.stdout.split() == ["DampingSummary", "ForcingSummary", "LyapunovSummary", "NormalForceSummary"]

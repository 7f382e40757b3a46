"""The error of the studies layer."""

from __future__ import annotations

from ..errors import InputError

__all__ = ["StudyError"]


class StudyError(InputError):
    """A study is configured or run wrongly (its config, file, grid, executor or saved result); the
    message says what to change.  Errors of the case a study is built on are
    :class:`~stochfric.oscillator.case.CaseError`."""

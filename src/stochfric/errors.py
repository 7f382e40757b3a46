"""The package's own exceptions: one base for every error that bad input or an impossible request
raises, so that a caller (the command line, a script) catches :class:`StochfricError` once.

Each floor derives its error from :class:`StochfricError` *and* :class:`ValueError` (bad values are
value errors: code that caught ``ValueError`` keeps working): :class:`~stochfric.surface.io.SurfaceError`,
:class:`~stochfric.contact.asperity.ContactError`, :class:`~stochfric.contact.materials.MaterialError`,
:class:`ProcessModelError` (a friction-process model or its file), :class:`AnalysisError` (the
statistical contact analysis), :class:`~stochfric.oscillator.parameters.ParameterError` and
:class:`~stochfric.oscillator.case.CaseError`, :class:`~stochfric.studies.errors.StudyError`, and the
foundation's :class:`~stochfric.io_utils.OutputPathError` and
:class:`~stochfric.io_utils.MemoryRequestError`.  An argument of the wrong type is an
:class:`InputTypeError` (also a :class:`TypeError`).  A study config that pydantic refuses raises
:class:`~stochfric.studies.errors.StudyConfigError`.  Broken invariants stay ``AssertionError``.
"""

from __future__ import annotations

__all__ = ["AnalysisError", "InputError", "InputTypeError", "ProcessModelError", "StochfricError"]


class StochfricError(Exception):
    """Base of every error stochfric raises on purpose (bad input, an impossible request)."""


class InputError(StochfricError, ValueError):
    """A value, option or file the package cannot use; the message says what to change."""


class InputTypeError(StochfricError, TypeError):
    """An argument of the wrong type (a string where a number is meant, …); the message names it."""


class ProcessModelError(InputError):
    """A friction-process model that cannot be built or read (method §4e): a bad field or file."""


class AnalysisError(InputError):
    """The statistical contact analysis cannot run as asked (method §3–§4): settings, scans, approaches."""

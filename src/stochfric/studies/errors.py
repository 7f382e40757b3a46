"""The error of the studies layer."""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from pydantic import ValidationError

from ..errors import InputError

__all__ = ["StudyConfigError", "StudyError", "format_validation_errors"]


class StudyError(InputError):
    """A study is configured or run wrongly (its config, file, grid, executor or saved result); the
    message says what to change.  Errors of the case a study is built on are
    :class:`~stochfric.oscillator.case.CaseError`."""


class StudyConfigError(StudyError):
    """A study config that its validation refuses (pydantic's :class:`~pydantic.ValidationError`,
    kept as ``validation_error`` for callers that rename the fields, as the command line does with
    its flags); the message lists every problem on one line."""

    def __init__(self, validation_error: ValidationError) -> None:
        super().__init__(format_validation_errors(validation_error))
        self.validation_error = validation_error

    def __reduce__(self) -> tuple[Any, ...]:  # picklable (a Dask or process worker may raise it)
        return (StudyError, (str(self),))


def format_validation_errors(exc: ValidationError, names: Callable[[str], str] | None = None) -> str:
    """Every problem of ``exc`` on one line; ``names`` renames the field a location starts with
    (the command line shows its flag, e.g. ``--normal-force`` for ``normal_forces``)."""
    lines = []
    for e in exc.errors():
        loc = ""
        for i, part in enumerate(e["loc"]):
            if i == 0 and names is not None and isinstance(part, str):
                part = names(part)
            if isinstance(part, int):
                loc += f"[{part}]"
            elif part in ("damping", "forcing", "lyapunov", "normal-force") and loc.endswith("]"):
                continue  # the discriminator tag pydantic inserts
            else:
                loc += f".{part}" if loc else str(part)
        msg = str(e["msg"]).removeprefix("Value error, ")
        lines.append(f"{loc}: {msg}" if loc else msg)  # a whole-config rule names its own fields
    return "; ".join(lines)

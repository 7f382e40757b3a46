"""What the commands share: the choices offered on the command line, the flags of the library's
field names, and the one-line error exit.

Each fixed choice is one :class:`~enum.StrEnum` (typer shows its values and refuses others); a choice
whose names live in a registry of the library that Python code may extend is a :class:`RegistryChoice`,
which reads the registry when the command runs (the contact models of :mod:`stochfric.contact.models`:
``--method``).  The choices of a simulation and a study are the library's own
(:mod:`stochfric.oscillator.options`,
:class:`~stochfric.oscillator.presets.PresetName`, :class:`~stochfric.friction_process.presets.ProcessLevel`,
:class:`~stochfric.friction_process.model_base.SigmaZetaRule`); the ones below belong to the command line's
own steps.  Errors of the library name their inputs by field name in backquotes (```normal_force```);
:func:`in_flags` shows the flag instead (one table, :data:`FLAGS`).
"""

from __future__ import annotations

import functools
import inspect
import re
import typing
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass, field
from enum import StrEnum
from typing import Any, TypeVar

import typer

from ..oscillator.friction_laws import FRICTION_LAWS

F = TypeVar("F", bound=Callable[..., Any])

#: The one seed rule of the command line (issue 32 §4): what every ``--seed`` help says.
SEED_RULE = ("Root seed, recorded in every output (default 0 in every command; the reproduction commands use the seed "
             "of the tables they reproduce: reproduce 2013, study white-limit 19).")

#: Default of a command parameter that :func:`option_group` fills (never seen by typer).
GROUP: Any = None

__all__ = [
    "FLAGS", "GROUP", "SEED_RULE", "LawChoice", "RegistryChoice",
    "fail", "flag_of", "in_flags", "option_group",
]  # fmt: skip

# simulate (method §5): the named friction laws of oscillator.friction_laws
LawChoice = StrEnum("LawChoice", [(name, name) for name in FRICTION_LAWS])  # type: ignore[misc]


@dataclass(frozen=True)
class RegistryChoice:
    """A choice among the names of a library registry, read when the command runs (so a name
    registered from Python after the import is offered), given to ``typer.Option(parser=...)``.

    ``names`` returns the registry's current names; ``aliases`` maps accepted older spellings to
    them.  Called with the value on the command line it returns the registered name (an alias
    resolved); any other value is refused with the names (typer's usage error, exit status 2).
    """

    names: Callable[[], Iterable[str]]
    aliases: Mapping[str, str] = field(default_factory=dict)

    def choices(self) -> tuple[str, ...]:
        """The names accepted now: the registered ones, then the aliases."""
        return (*self.names(), *self.aliases)

    def listing(self) -> str:
        """``"a, b (aliases: old = a)"``: the names for a help or error text."""
        text = ", ".join(self.names())
        if self.aliases:
            text += " (aliases: " + ", ".join(f"{old} = {new}" for old, new in self.aliases.items()) + ")"
        return text

    def __call__(self, value: Any) -> str:
        name = self.aliases.get(str(value), str(value))
        if name in tuple(self.names()):
            return name
        raise typer.BadParameter(f"{str(value)!r} is not one of {self.listing()}")


#: The flag of each library field whose flag is not ``--`` + the field name with dashes (the case of
#: ``simulate``: :mod:`stochfric.oscillator.case`; the study configs: :mod:`stochfric.studies.config`).
FLAGS = {
    "process_file": "--process", "normal_forces": "--normal-force",
    "damping_ratios": "--damping-ratio", "phase_normal_force": "--phase-force",
    "phase_damping_ratios": "--phase-damping", "forcing_q": "--q",
}


def flag_of(field: str) -> str:
    """The command-line flag that fills the library field ``field``."""
    return FLAGS.get(field, "--" + field.replace("_", "-"))


def in_flags(message: str) -> str:
    """``message`` with every field name in backquotes (```normal_force```) shown as its flag."""
    return re.sub(r"`([A-Za-z_][A-Za-z0-9_]*)`", lambda m: flag_of(m.group(1)), message)


def write_failed(exc: OSError) -> typer.Exit:
    """:func:`fail` for an output that could not be written (disk full, no permission, a removed
    directory): what failed and where, and that the files written before are intact (every
    writer is atomic)."""
    where = f" ({exc.filename})" if getattr(exc, "filename", None) else ""
    return fail(f"could not write the results: {exc.strerror or exc}{where}; free some space or choose "
                "another output directory (files written before are intact)")


def fail(message: str) -> typer.Exit:
    """Print ``error: message`` on stderr and return the exit to raise (status 2)."""
    typer.echo(f"error: {message}", err=True)
    return typer.Exit(code=2)


def option_group(name: str, group: Callable[..., Any]) -> Callable[[F], F]:
    """Give a command the options of ``group`` in place of its parameter ``name``.

    ``group`` is a function whose parameters are typer options shared by several commands; the
    command's parameter ``name`` receives ``group(**values of those options)``.  The options
    appear in ``--help`` where ``name`` stands.  ``group`` must not raise (keep the raw values;
    validate in the command, where errors become a one-line message).
    """
    gsig = inspect.signature(group)
    ghints = typing.get_type_hints(group, include_extras=True)
    gparams = [p.replace(annotation=ghints[p.name], kind=inspect.Parameter.KEYWORD_ONLY)
               for p in gsig.parameters.values()]

    def decorate(command: F) -> F:
        hints = typing.get_type_hints(command, include_extras=True)
        params: list[inspect.Parameter] = []
        for p in inspect.signature(command).parameters.values():
            if p.name == name:
                params += gparams
            else:
                params.append(p.replace(annotation=hints.get(p.name, p.annotation),
                                        kind=inspect.Parameter.KEYWORD_ONLY))

        @functools.wraps(command)
        def wrapper(**kwargs: Any) -> Any:
            values = {k: kwargs.pop(k) for k in gsig.parameters}
            return command(**kwargs, **{name: group(**values)})

        wrapper.__signature__ = inspect.Signature(params, return_annotation=None)  # type: ignore[attr-defined]
        wrapper.__annotations__ = {p.name: p.annotation for p in params} | {"return": None}
        return typing.cast(F, wrapper)

    return decorate

"""The ``stochfric`` command-line application: one :class:`typer.Typer` with every command.

Commands live one per concern in this package (``simulate``, ``surface``/``contact``,
``friction-process``, ``study``/``run``/``reproduce``) and are added by their ``register``.
Every error the package raises on purpose derives from :class:`~stochfric.errors.StochfricError`;
one that a command lets through ends here, in :class:`StochfricGroup`, as one line ``error: …`` on
stderr and exit status 2 (:func:`~stochfric.cli.options.fail`), never a traceback.
"""

from __future__ import annotations

import sys
from typing import Annotated, Any

import typer
from typer.core import TyperGroup

from .. import __version__
from ..errors import StochfricError
from ..interrupts import command_ctrl_c_latch
from .assess import register as register_assess_command
from .contact_models import register as register_contact_models_command
from .help_panels import use_panels
from .options import fail, write_failed
from .process import register as register_process_commands
from .simulate import register as register_simulate_command
from .studies import register as register_study_commands
from .surface import register as register_surface_commands

__all__ = ["StochfricGroup", "app", "main"]


class StochfricGroup(TyperGroup):
    """The command group of :data:`app`: a :class:`~stochfric.errors.StochfricError` from any command ends
    with :func:`~stochfric.cli.options.fail` (``error: <message>`` on stderr, status 2), so that a command
    need not list the package's errors it may meet."""

    def invoke(self, ctx: Any) -> Any:  # a click Context (typer vendors click: no one import path for its type)
        # a Ctrl-C swallowed anywhere in the command still stops its sweeps
        with command_ctrl_c_latch():
            try:
                return super().invoke(ctx)
            except StochfricError as exc:
                raise fail(str(exc)) from None


app = typer.Typer(
    cls=StochfricGroup,
    name="stochfric",
    help="Stochastic friction from measured surfaces, and what it does to friction-induced "
    "vibration (after N. Gaus, KIT 2013).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
    # plain help text: rich markup would swallow units such as "[kg]" and turn "A:B:NUM" into an emoji
    rich_markup_mode=None,
)


def _version(value: bool) -> None:
    if value:
        typer.echo(f"stochfric {__version__}")
        raise typer.Exit()


@app.callback()
def _root(
    version: Annotated[
        bool, typer.Option("--version", callback=_version, is_eager=True, help="Show version.")
    ] = False,
) -> None:
    """stochfric command line."""


register_simulate_command(app)
register_surface_commands(app)
register_process_commands(app)
register_study_commands(app)
register_assess_command(app)
register_contact_models_command(app)
use_panels(app)  # --help in panels: Input, Physics, Numerics and execution, Output (issue 32)


def main() -> None:
    """Console-script entry point.  An output that cannot be written (disk full, no permission) ends
    with the one-line message of :func:`~stochfric.cli.options.write_failed` wherever it happens."""
    try:
        app()
    except KeyboardInterrupt:  # a Ctrl-C outside a command's own handler (startup, validation, shutdown)
        sys.stderr.write("interrupted; nothing more was run\n")
        raise SystemExit(130) from None
    except OSError as exc:
        try:
            raise write_failed(exc) from None
        except typer.Exit as done:
            raise SystemExit(done.exit_code) from None

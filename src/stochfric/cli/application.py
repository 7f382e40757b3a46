"""The ``stochfric`` command-line application: one :class:`typer.Typer` with every command.

Commands live one per concern in this package (``simulate``, ``surface``/``contact``,
``friction-process``, ``study``/``run``/``reproduce``) and are added by their ``register``.
"""

from __future__ import annotations

from typing import Annotated

import typer

from .. import __version__
from .options import write_failed
from .process import register as register_process_commands
from .simulate import register as register_simulate_command
from .studies import register as register_study_commands
from .surface import register as register_surface_commands

__all__ = ["app", "main"]

app = typer.Typer(
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


def main() -> None:
    """Console-script entry point.  An output that cannot be written (disk full, no permission) ends
    with the one-line message of :func:`~stochfric.cli.options.write_failed` wherever it happens."""
    try:
        app()
    except OSError as exc:
        try:
            raise write_failed(exc) from None
        except typer.Exit as done:
            raise SystemExit(done.exit_code) from None

"""cli.options.option_group: a group of shared typer options in place of one command parameter."""

from __future__ import annotations

from typing import Annotated, Any

import typer
from typer.testing import CliRunner

from stochfric.cli.options import GROUP, fail, option_group


def _group(alpha: Annotated[int, typer.Option("--alpha", help="A [-].")] = 1,
           beta: Annotated[str, typer.Option("--beta", help="B.")] = "b") -> dict[str, Any]:
    return {"alpha": alpha, "beta": beta}


def _app() -> typer.Typer:
    app = typer.Typer()

    @app.command()
    @option_group("shared", _group)
    def cmd(first: Annotated[str, typer.Option("--first")] = "f", shared: dict[str, Any] = GROUP,
            last: Annotated[bool, typer.Option("--last")] = False) -> None:
        if shared["alpha"] < 0:
            raise fail("alpha must be >= 0")
        typer.echo(f"{first} {shared['alpha']} {shared['beta']} {last}")

    @app.command()
    def other() -> None:  # a second command, so that typer keeps sub-commands
        pass

    return app


def test_group_options_reach_the_command_and_show_in_place() -> None:
    app, run = _app(), CliRunner()
    res = run.invoke(app, ["cmd", "--alpha", "3", "--last"])
    assert res.exit_code == 0 and res.output.strip() == "f 3 b True"
    assert run.invoke(app, ["cmd"]).output.strip() == "f 1 b False"
    help_text = run.invoke(app, ["cmd", "--help"]).output
    assert help_text.index("--first") < help_text.index("--alpha") < help_text.index("--beta") < help_text.index(
        "--last")
    bad = run.invoke(app, ["cmd", "--alpha", "-1"])
    assert bad.exit_code == 2 and "error: alpha must be >= 0" in bad.output


def test_the_real_commands_share_one_group() -> None:
    from stochfric.cli import app

    run = CliRunner()
    for path in (["surface"], ["contact"], ["friction-process"]):
        assert "--median-radius" in run.invoke(app, [*path, "--help"]).output
    for kind in ("damping", "forcing", "lyapunov", "normal-force"):
        out = run.invoke(app, ["study", kind, "--help"]).output
        assert "--white-intensity" in out and "--checkpoint" in out and "--preset" in out

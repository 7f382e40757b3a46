"""``--help`` of every command in panels (issue 32 §4): each option in Input, Physics, Numerics and
execution or Output, never in "Other options"; units and ranges printed as written; defaults shown."""

from __future__ import annotations

from typing import Any

import pytest
import typer.main
from typer.testing import CliRunner

from stochfric.cli.application import app
from stochfric.cli.help_panels import OTHER, PANEL_ORDER, panel_of

runner = CliRunner()


def _commands() -> list[tuple[str, Any]]:
    found: list[tuple[str, Any]] = []

    def walk(cmd: Any, path: str) -> None:
        if hasattr(cmd, "commands"):
            for name, sub in cmd.commands.items():
                walk(sub, f"{path} {name}".strip())
        else:
            found.append((path, cmd))

    walk(typer.main.get_command(app), "")
    return found


COMMANDS = _commands()


def test_every_command_is_covered() -> None:
    names = {n for n, _ in COMMANDS}
    assert {"simulate", "surface", "contact", "friction-process", "assess", "contact-models", "reproduce",
            "study damping", "study white-limit"} <= names


@pytest.mark.parametrize("name", [n for n, _ in COMMANDS])
def test_no_option_outside_the_four_panels(name: str) -> None:
    cmd = dict(COMMANDS)[name]
    stray = [p.opts[0] if p.opts else p.name for p in cmd.params if panel_of(p) == OTHER]
    assert not stray, f"{name}: add {stray} to stochfric.cli.help_panels.PANELS"


@pytest.mark.parametrize("name", ["simulate", "friction-process", "study damping", "contact"])
def test_help_shows_panels_in_order(name: str) -> None:
    res = runner.invoke(app, [*name.split(), "--help"], env={"COLUMNS": "120"})
    assert res.exit_code == 0, res.output
    shown = [p for p in PANEL_ORDER if f"─ {p} " in res.output]
    assert shown == sorted(shown, key=PANEL_ORDER.index) and len(shown) >= 3, shown
    assert OTHER not in shown
    assert "Traceback" not in res.output


def test_units_and_ranges_survive_and_defaults_show() -> None:
    res = runner.invoke(app, ["simulate", "--help"], env={"COLUMNS": "120"})
    text = " ".join(res.output.replace("│", " ").split())
    assert "[kg]" in text  # no rich markup: a unit in brackets prints as written
    assert "[default: 10; x>=1]" in text  # --save-every
    res = runner.invoke(app, ["study", "damping", "--help"], env={"COLUMNS": "120"})
    text = " ".join(res.output.replace("│", " ").split())
    assert "default: the thesis's, 10; normal-force 30" in text
    assert "START:STOP:NUM" in text

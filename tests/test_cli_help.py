"""Every command's --help shows its units and grid syntax verbatim (issue 11).

The commands are discovered from the click tree of the app, so a new command is checked
without touching this file.  Rich markup used to swallow ``[kg]``, ``[N]``, ``[m/s]`` … and
turn ``A:B:NUM`` into an emoji (``:b:``).
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import Any

import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli import app

_UNIT = re.compile(r"\[[^\]\n]{1,12}\]")  # "[kg]", "[N s/m]", "[m²]", "[-]"
_GRID = re.compile(r"\b[A-Z]+(?::[A-Z]+)+\b")  # "A:B:NUM", "START:STOP:NUM"


def _commands() -> Iterator[tuple[tuple[str, ...], Any]]:
    root = typer.main.get_command(app)

    def walk(path: tuple[str, ...], cmd: Any) -> Iterator[tuple[tuple[str, ...], Any]]:
        yield path, cmd
        for name, sub in sorted(getattr(cmd, "commands", {}).items()):  # a group (typer's own click)
            yield from walk((*path, name), sub)

    yield from walk((), root)


COMMANDS = list(_commands())


def _flat(text: str) -> str:
    return " ".join(text.split())


def test_the_tree_is_discovered() -> None:
    names = {" ".join(p) for p, _ in COMMANDS}
    assert {"simulate", "study", "study damping", "reproduce", "run"} <= names
    assert len(COMMANDS) >= 10


def _expected_tokens(cmd: Any) -> set[str]:
    texts = [cmd.help or ""] + [getattr(p, "help", None) or "" for p in cmd.params]
    out: set[str] = set()
    for t in texts:
        out.update(_UNIT.findall(t))
        out.update(_GRID.findall(t))
    return out


@pytest.mark.parametrize("path,cmd", COMMANDS, ids=[" ".join(p) or "stochfric" for p, _ in COMMANDS])
def test_help_shows_units_and_grid_syntax(path: tuple[str, ...], cmd: Any) -> None:
    res = CliRunner().invoke(app, [*path, "--help"], terminal_width=100)
    assert res.exit_code == 0, res.output
    shown = _flat(res.output)
    for token in _expected_tokens(cmd):
        assert _flat(token) in shown, f"{' '.join(path)} --help lost {token!r}"
    assert not re.search("[\U0001f000-\U0001faff]", res.output), "emoji in help (rich shortcode)"


def test_known_units_survive() -> None:
    """Anchors that do not depend on the token scan above (which would pass on an empty tree)."""
    runner = CliRunner()
    sim = _flat(runner.invoke(app, ["simulate", "--help"]).output)
    for needle in ("Mass m [kg]", "Belt speed v0 [m/s]", "[N s/m]", "[rad/s]", "[m²]"):
        assert needle in sim, needle
    dmp = _flat(runner.invoke(app, ["study", "damping", "--help"]).output)
    assert "A:B:NUM" in dmp and "START:STOP:NUM" in dmp and "N [N]" in dmp
    tokens = set().union(*(_expected_tokens(c) for _, c in COMMANDS))
    assert {"[kg]", "[m/s]", "A:B:NUM"} <= tokens

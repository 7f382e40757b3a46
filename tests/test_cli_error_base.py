"""The command line catches the package's error base once (issue 28): a
:class:`~stochfric.errors.StochfricError` that a command lets through ends in one line ``error: …`` on
stderr and exit status 2, never a traceback; bad input still does."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.cli import studies as cli_studies
from stochfric.cli.application import StochfricGroup
from stochfric.errors import ProcessModelError, StochfricError

runner = CliRunner()


def _one_error_line(result: Any, message: str) -> None:
    assert result.exit_code == 2, result.output
    assert result.stderr == f"error: {message}\n"
    assert result.stdout == "" and "Traceback" not in result.output


@pytest.mark.parametrize("error", [StochfricError("not a value error"), ProcessModelError("a bad model")])
def test_the_group_turns_a_package_error_into_one_line(error: Exception) -> None:
    local = typer.Typer(cls=StochfricGroup)

    @local.command()
    def first() -> None:
        raise error

    @local.command()
    def second() -> None:
        raise RuntimeError("a programming error is not caught")

    _one_error_line(runner.invoke(local, ["first"]), str(error))
    other = runner.invoke(local, ["second"])
    assert other.exit_code == 1 and isinstance(other.exception, RuntimeError)


def test_an_error_no_command_catches_ends_in_one_line(monkeypatch: pytest.MonkeyPatch) -> None:
    """The study command catches its ValueErrors; the base (no ValueError) reaches the application's group."""
    def run_study(*args: Any, **kwargs: Any) -> Any:
        raise StochfricError("the study cannot run")

    monkeypatch.setattr(cli_studies.reproduce_mod, "run_study", run_study)
    _one_error_line(runner.invoke(app, ["study", "forcing", "--runs", "2", "--json"]), "the study cannot run")


def test_a_bad_model_file_ends_in_one_line(tmp_path: Path) -> None:
    bad = tmp_path / "model.json"
    bad.write_text(json.dumps({"kind": "pink"}), encoding="utf-8")
    r = runner.invoke(app, ["simulate", "--preset", "brake", "--process", str(bad), "--runs", "1", "--tau-end", "1"])
    _one_error_line(r, f"{bad}: unknown process model kind 'pink'; known: ['band_limited', 'tabulated']")


def test_bad_input_ends_in_one_line_in_a_process_of_its_own() -> None:
    done = subprocess.run(
        [sys.executable, "-m", "stochfric.cli", "simulate", "--preset", "brake", "--normal-force", "1000", "--n", "1"],
        capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 2, done.stderr
    assert done.stdout == ""
    assert done.stderr.startswith("error: ") and len(done.stderr.splitlines()) == 1, done.stderr

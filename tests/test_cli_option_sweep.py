"""Every option of every command that takes a number, a text or a path, given a value that cannot be right,
ends in one clear line and exit status 2 — never a traceback, never silently accepted (issue 30, the
clean-error sweep).

Each command runs from a minimal valid invocation (:data:`BASE`) with one option replaced: floats get NaN, ∞
and −1, integers −5, texts the empty string, paths a file that can be neither read nor created.  A value
that is accepted starts real work; a SIGALRM stops it after :data:`ACCEPT_SECONDS` and the case fails as
"accepted".  About 390 invocations, 40 s on one core (every one
is refused before any work starts).  Found and fixed by it: ``simulate --process-length inf`` ended in a
traceback, ``simulate --sigma-zeta nan`` was ignored without a model that reads it, ``assess --tau-end nan``
and ``assess --contact-model ''`` started the analysis."""

from __future__ import annotations

import signal
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli.application import app

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"
RIG = Path(__file__).resolve().parents[1] / "docs" / "examples" / "strip-drawing-rig.toml"
BASE: dict[str, list[str]] = {
    "simulate": ["--preset", "brake"],
    "surface": [],
    "contact": ["--material", "brake-pad"],
    "friction-process": ["--material", "brake-pad"],
    "reproduce": ["--quick"],
    "assess": [str(SHARED / "x3p-2.x3p"), "--material", "dc04", "--machine", str(RIG), "--out", "aout"],
    "contact-models": ["--material", "brake-pad", "--pressures-mpa", "1:4:4", "--step", "3", "--out", "cm"],
    "study damping": ["--preset", "brake"],
    "study forcing": ["--preset", "brake"],
    "study lyapunov": ["--preset", "brake"],
    "study normal-force": ["--preset", "brake"],
    "study white-limit": ["--preset", "brake"],
}
#: Values that are right although they look wrong: an infinite time limit is the library's "none".
ALLOWED = {("contact-models", "--time-limit-s", "inf")}
BAD = {"int": ["-5"], "float": ["nan", "inf", "-1"], "str": [""], "path": ["/proc/nonexistent/x"]}
ACCEPT_SECONDS = 8


class _Accepted(BaseException):
    pass


def _alarm(signum: int, frame: Any) -> None:
    raise _Accepted


def _commands(group: Any, prefix: list[str]) -> Iterator[tuple[list[str], Any]]:
    for name, command in group.commands.items():
        if hasattr(command, "commands"):
            yield from _commands(command, [*prefix, name])
        else:
            yield [*prefix, name], command


def _cases() -> list[tuple[list[str], str, str]]:
    out = []
    for path, command in _commands(typer.main.get_command(app), []):
        for param in command.params:
            if getattr(param, "param_type_name", "") != "option" or param.hidden or param.is_flag:
                continue
            kind = str(param.bare_type()).lower()
            for value in BAD.get(kind, []):
                if (" ".join(path), param.opts[0], value) not in ALLOWED:
                    out.append((path, param.opts[0], value))
    return out


def test_the_sweep_covers_every_command() -> None:
    commands = {" ".join(path) for path, _ in _commands(typer.main.get_command(app), [])}
    assert commands - {"run"} <= set(BASE), commands - set(BASE)
    assert len(_cases()) > 250


@pytest.mark.parametrize(("path", "option", "value"), _cases(),
                         ids=lambda v: str(v) if isinstance(v, str) else "-".join(v))
def test_a_wrong_number_ends_in_one_line(path: list[str], option: str, value: str, tmp_path: Path,
                                        monkeypatch: pytest.MonkeyPatch) -> None:
    if "assess" in path and not (SHARED / "x3p-2.x3p").is_file():
        pytest.skip("the shared data (../shared) is not here")
    monkeypatch.chdir(tmp_path)
    base = list(BASE.get(" ".join(path), []))
    if option in base:
        i = base.index(option)
        del base[i:i + 2]
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(ACCEPT_SECONDS)
    try:
        result = CliRunner().invoke(app, [*path, *base, option, value])
    except _Accepted:
        pytest.fail(f"{' '.join(path)} {option} {value}: accepted (still running after {ACCEPT_SECONDS} s)")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, previous)
    assert result.exception is None or isinstance(result.exception, SystemExit), repr(result.exception)
    assert result.exit_code == 2, (result.exit_code, result.output[-300:])
    text = (result.stderr or result.output).strip()
    assert "Traceback" not in text
    last = text.splitlines()[-1]
    # ours: "error: <what to change>"; click's own range checks: "Invalid value for '--x': ..."
    assert last.startswith("error: ") or "Invalid value for" in last, last

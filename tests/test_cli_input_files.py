"""Every input file is checked before it is read (issue 32): a device or pipe (``/dev/zero`` never ends), a
directory and an oversized file end in one line, exit status 2 — never a hang or a traceback."""

from __future__ import annotations

from pathlib import Path

import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.io_utils import read_text_checked

runner = CliRunner()


@pytest.mark.parametrize(("args", "words"), [
    (["simulate", "--machine", "/dev/zero"], "cannot read machine file /dev/zero: not a regular file"),
    (["run", "/dev/zero"], "cannot read /dev/zero: not a regular file"),
    (["simulate", "--preset", "brake", "--model", "contact", "--process", "/dev/zero"],
     "cannot read friction-process model /dev/zero: not a regular file"),
    (["run", "{dir}"], "Is a directory"),
    (["simulate", "--machine", "{dir}"], "Is a directory"),
])
def test_special_files_end_in_one_line(args: list[str], words: str, tmp_path: Path) -> None:
    res = runner.invoke(app, [a.replace("{dir}", str(tmp_path)) for a in args])
    assert res.exit_code == 2, res.output
    assert words in res.stderr and res.stderr.count("\n") == 1 and "Traceback" not in res.output


def test_oversized_text_file_is_refused_before_reading(tmp_path: Path) -> None:
    big = tmp_path / "big.toml"
    big.write_text("#" * 2000)
    with pytest.raises(OSError, match="2000 bytes, more than the 1000"):
        read_text_checked(big, max_bytes=1000)
    assert read_text_checked(big, max_bytes=2000).startswith("#")

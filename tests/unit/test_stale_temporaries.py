"""Temporary files of an interrupted atomic write (writer killed: no cleanup ran) are removed by the
next write of the same file; those of a live writer are kept (issue 20 §2)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from stochfric.io_utils import write_text_atomic


def test_stale_temporary_of_a_dead_writer_is_removed_on_the_next_write(tmp_path: Path) -> None:
    target = tmp_path / "figure.png"
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], capture_output=True,
                          text=True, check=True)
    stale = tmp_path / f".figure.png.{int(dead.stdout)}-abc123.tmp"
    stale.write_bytes(b"half a png")
    live = tmp_path / f".figure.png.{os.getppid()}-def456.tmp"  # a live process (our parent)
    live.write_bytes(b"being written")
    other = tmp_path / ".other.png.1-xyz.tmp"
    other.write_bytes(b"not ours")
    write_text_atomic(target, "new")
    assert target.read_text() == "new"
    assert not stale.exists()
    assert live.exists() and other.exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted([target.name, live.name, other.name])

"""Ctrl-C prints the main process's one line and nothing else, whenever it arrives: while the
command is still importing, while spawned workers are importing, or while they compute (issue 20 §2).
The outcome does not depend on the timing, only which of the two messages appears."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.skipif(sys.platform == "win32", reason="process groups and SIGINT are POSIX")


@pytest.mark.parametrize("delay_s", [0.3, 4.5])
def test_ctrl_c_to_the_process_group_prints_no_traceback(tmp_path: Path, delay_s: float) -> None:
    cmd = [sys.executable, "-c", "from stochfric.cli import main; main()", "study", "damping", "--preset", "brake",
           "--runs", "400", "--tau-end", "400", "--executor", "processes", "--workers", "2",
           "--checkpoint", str(tmp_path / "ck"), "--out", str(tmp_path / "out")]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True)
    time.sleep(delay_s)
    os.killpg(proc.pid, signal.SIGINT)  # what a terminal's Ctrl-C does: the whole foreground group
    _, err = proc.communicate(timeout=120)
    assert proc.returncode == 130, (proc.returncode, err)
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("interrupted"), err

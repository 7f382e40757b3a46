"""A Ctrl-C is never lost (studies.executors._interrupt_latch): where its KeyboardInterrupt is swallowed — as
Python does inside a ctypes callback, which numba's compiler cache uses — the sweep still stops after the
running task with SweepInterrupted (exit 130 on the command line), instead of running on to exit 0."""

from __future__ import annotations

import os
import signal
from collections.abc import Iterator, Sequence
from types import SimpleNamespace
from typing import Any

import pytest

from stochfric.interrupts import CTRL_C
from stochfric.studies.executors import SerialExecutor, SweepInterrupted, run_tasks


class _SwallowingExecutor(SerialExecutor):
    """Runs tasks; during the first one a SIGINT arrives and its KeyboardInterrupt is swallowed."""

    def run(self, fn: Any, tasks: Sequence[Any]) -> Iterator[tuple[Any, Any]]:
        for k, t in enumerate(tasks):
            if k == 0:
                try:
                    os.kill(os.getpid(), signal.SIGINT)
                    for _ in range(1000):  # the handler runs at the next bytecode boundary
                        pass
                except KeyboardInterrupt:
                    pass  # what a ctypes callback does with it
            yield t, {"k": k}


def test_a_swallowed_ctrl_c_still_stops_the_sweep() -> None:
    previous = signal.signal(signal.SIGINT, signal.default_int_handler)  # as in a command-line process
    try:
        tasks = [SimpleNamespace(index=i) for i in range(5)]
        with pytest.raises(SweepInterrupted):
            run_tasks(tasks, executor=_SwallowingExecutor(), fn=lambda t, threads: {})  # type: ignore[arg-type]
        assert signal.getsignal(signal.SIGINT) is signal.default_int_handler  # the handler is restored
    finally:
        signal.signal(signal.SIGINT, previous)
    assert not CTRL_C.is_set()  # no stale Ctrl-C after the sweep


def test_without_ctrl_c_every_task_runs() -> None:
    tasks = [SimpleNamespace(index=i) for i in range(3)]
    results, stats = run_tasks(tasks, executor=SerialExecutor(), fn=lambda t, threads: {"i": t.index})  # type: ignore[arg-type]
    assert sorted(results) == [0, 1, 2] and stats.computed == 3


@pytest.mark.skipif(not hasattr(signal, "pthread_sigmask"), reason="no signal masks on this platform")
def test_a_ctrl_c_while_workers_start_is_answered_not_lost() -> None:
    """While worker processes start, SIGINT is blocked, not ignored: a child started then has it blocked (so
    it prints no traceback of its own), and the parent's Ctrl-C stays pending and arrives when the start is
    over (ignoring it lost it: a study under load then ran to its end and exited 0).  Run in a fresh,
    single-threaded interpreter: a SIGINT sent to the test runner's own process would reach its other
    threads (pytest-xdist's channel), which took the worker down once."""
    import subprocess
    import sys

    script = """
import os, signal, subprocess, sys
from stochfric.studies.executors import _workers_ignore_ctrl_c
signal.signal(signal.SIGINT, signal.default_int_handler)
child = "import signal; print(int(signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])))"
where = "lost"
try:
    with _workers_ignore_ctrl_c():
        blocked = subprocess.run([sys.executable, "-c", child], capture_output=True, text=True).stdout.strip()
        os.kill(os.getpid(), signal.SIGINT)
        for _ in range(100000):
            pass
        where = "pending"
    for _ in range(100000):
        pass
except KeyboardInterrupt:
    where = "answered after the start" if where == "pending" else "answered during the start"
print(blocked, where, int(signal.SIGINT in signal.pthread_sigmask(signal.SIG_BLOCK, [])))
"""
    out = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split("\n")[0] == "1 answered after the start 0", out.stdout + out.stderr

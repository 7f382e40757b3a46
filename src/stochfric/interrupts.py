"""A Ctrl-C is never lost (foundation layer: no stochfric imports).

Python delivers SIGINT as a KeyboardInterrupt at the next bytecode boundary of the main thread.  Raised inside
a ctypes callback — numba's compiler cache notifies through one — it is only printed ("Exception ignored on
calling ctypes callback function") and the program runs on: a study interrupted while compiling finished and
exited 0.  The latch's SIGINT handler also sets :data:`CTRL_C`; the sweep (:func:`stochfric.studies.executors.
run_tasks`) checks it before and after every task and stops as for any Ctrl-C.

The command line installs the latch for the whole command (:func:`command_ctrl_c_latch`), so a Ctrl-C swallowed
before the sweep starts is not lost either; a library caller gets it for the duration of each sweep
(:func:`ctrl_c_latch`).  Only the main thread, and only where SIGINT has Python's default handler (a worker
that ignores Ctrl-C keeps ignoring it).
"""

from __future__ import annotations

import contextlib
import signal
import threading
from collections.abc import Iterator
from typing import Any

__all__ = ["CTRL_C", "command_ctrl_c_latch", "ctrl_c_latch", "startup_ctrl_c_latch"]

#: Set by the latch's SIGINT handler; cleared when a latch starts.
CTRL_C = threading.Event()
_process_latch = False


def _on_sigint(signum: int, frame: Any) -> None:
    CTRL_C.set()
    raise KeyboardInterrupt


def _can_install() -> bool:
    return (threading.current_thread() is threading.main_thread()
            and signal.getsignal(signal.SIGINT) is signal.default_int_handler)


@contextlib.contextmanager
def command_ctrl_c_latch() -> Iterator[None]:
    """The latch for one command of the command line (installed at its start, removed at its end, so that an
    in-process caller such as a test runner gets its handler back and no stale Ctrl-C)."""
    global _process_latch
    if _process_latch or not _can_install():
        yield
        return
    CTRL_C.clear()
    previous = signal.signal(signal.SIGINT, _on_sigint)
    _process_latch = True
    try:
        yield
    finally:
        _process_latch = False
        CTRL_C.clear()
        signal.signal(signal.SIGINT, previous)


@contextlib.contextmanager
def startup_ctrl_c_latch() -> Iterator[threading.Event]:
    """The latch for a program's start (the console script's imports): yields an event that is set when a Ctrl-C
    came, even one whose KeyboardInterrupt was swallowed during the imports (in a ctypes callback, as numba's
    compiler uses), which would otherwise let the command run to its end.  The default handler is back
    afterwards, so that :func:`command_ctrl_c_latch` can take over."""
    if not _can_install():
        yield threading.Event()
        return
    CTRL_C.clear()
    previous = signal.signal(signal.SIGINT, _on_sigint)
    seen = threading.Event()
    try:
        yield seen
    finally:
        signal.signal(signal.SIGINT, previous)
        if CTRL_C.is_set():
            seen.set()
        CTRL_C.clear()


@contextlib.contextmanager
def ctrl_c_latch() -> Iterator[threading.Event]:
    """The latch for a block (a sweep): under a process latch, the process's event as it is (a Ctrl-C swallowed
    before the block counts); otherwise a fresh one, the previous handler restored afterwards."""
    if _process_latch and signal.getsignal(signal.SIGINT) is _on_sigint:
        yield CTRL_C
        return
    if not _can_install():
        yield threading.Event()  # never set: Ctrl-C is not ours to handle here
        return
    CTRL_C.clear()
    previous = signal.signal(signal.SIGINT, _on_sigint)
    try:
        yield CTRL_C
    finally:
        CTRL_C.clear()
        signal.signal(signal.SIGINT, previous)

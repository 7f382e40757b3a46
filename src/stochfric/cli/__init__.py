"""Command line: parse, call, print.  No physics here.

``stochfric`` with the commands ``simulate`` (method §5), ``surface`` and ``contact`` (§1–§2),
``friction-process`` (§3–§4), ``study``, ``run`` and ``reproduce`` (§6).  Input errors end with a
one-line message and exit status 2, never with a traceback.

This package module is light: the console script's :func:`main` imports the application
(:mod:`stochfric.cli.application`, seconds of imports) inside its own Ctrl-C guard, so an early Ctrl-C
prints one line instead of an import traceback.  ``app`` is imported on first use.
"""

from __future__ import annotations

import sys
from typing import Any

from ..interrupts import startup_ctrl_c_latch
from ..vector_width import configure

__all__ = ["app", "main"]


def main() -> None:
    """Console-script entry point (``stochfric``).  The command line is an application: it first applies the
    SIMD width of ``STOCHFRIC_VECTOR_WIDTH`` (default ``auto``: full width only on the CPUs where it was
    measured faster; :func:`stochfric.vector_width.configure`) to its own process; a bad value ends in one
    line, status 2.  Importing the library changes no setting."""
    with startup_ctrl_c_latch() as ctrl_c:  # a Ctrl-C swallowed during the imports is not lost
        try:
            configure()
            from .application import main as run
        except ValueError as exc:
            sys.stderr.write(f"error: {exc}\n")
            raise SystemExit(2) from None
        except KeyboardInterrupt:
            ctrl_c.set()
    if ctrl_c.is_set():
        sys.stderr.write("interrupted while starting; nothing was run\n")
        raise SystemExit(130)
    run()


def __getattr__(name: str) -> Any:
    if name == "app":
        from .application import app

        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

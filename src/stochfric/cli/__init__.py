"""Command line: parse, call, print.  No physics here.

``stochfric`` with the commands ``simulate`` (method §5), ``surface`` and ``contact`` (§1–§2),
``friction-process`` (§3–§4), ``study``, ``run`` and ``reproduce`` (§6).  Input errors end with a
one-line message and exit status 2, never with a traceback.

This package module is light: the console script's :func:`main` imports the application
(:mod:`stochfric.cli.application`, seconds of imports) inside its own Ctrl-C guard, so an early Ctrl-C
prints one line instead of an import traceback.  ``app`` is imported on first use.
"""

from __future__ import annotations

import os
import sys
from typing import Any

from ..vector_width import ENV, configure

__all__ = ["app", "main"]


def main() -> None:
    """Console-script entry point (``stochfric``).  With ``STOCHFRIC_VECTOR_WIDTH`` set it first applies
    that SIMD width (:func:`stochfric.vector_width.configure`); a bad value ends in one line, status 2."""
    if os.environ.get(ENV):
        try:
            configure()
        except ValueError as exc:
            sys.stderr.write(f"error: {exc}\n")
            raise SystemExit(2) from None
    try:
        from .application import main as run
    except KeyboardInterrupt:
        sys.stderr.write("interrupted while starting; nothing was run\n")
        raise SystemExit(130) from None
    run()


def __getattr__(name: str) -> Any:
    if name == "app":
        from .application import app

        return app
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

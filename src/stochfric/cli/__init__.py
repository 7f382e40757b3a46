"""Command line: parse, call, print.  No physics here.

``stochfric`` with the commands ``simulate`` (method §5), ``surface`` and ``contact`` (§1–§2),
``friction-process`` (§3–§4), ``study``, ``run`` and ``reproduce`` (§6).  Input errors end with a
one-line message and exit status 2, never with a traceback.
"""

from .app import app, main

__all__ = ["app", "main"]

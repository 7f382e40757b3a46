"""The SIMD width of the compiled kernels on Intel Xeon CPUs with AVX-512 (docs/performance.md).

LLVM (and therefore numba) compiles for 256-bit vectors on every Intel CPU with AVX-512, even where
the hardware runs 512-bit instructions at full clock (Xeon since Sapphire Rapids; LLVM issue
102047): the subtarget tuning ``prefer-256-bit``.  stochfric's lock-step kernels advance 32
trajectories per step in branch-free loops, and the white-noise generators
(:mod:`stochfric.random.philox`, :mod:`stochfric.random.ziggurat`) are pure arithmetic, so they
gain from the full width.

Nothing happens on import.  :func:`configure` removes the tuning flag, before numba compiles
anything, through numba's own setting ``NUMBA_CPU_FEATURES`` (the host's feature list plus
``-prefer-256-bit``).  It is called explicitly (``stochfric.vector_width.configure("auto")``), or
by the command line when ``STOCHFRIC_VECTOR_WIDTH`` is set.  The width changes no number: the
loops are element-wise across trajectories and are compiled without fast-math, so every lane
computes the same IEEE operations in the same order (tested: the same X_gh bit for bit).  Once
applied it affects every numba function compiled later in the process and, being an environment
variable, the processes it starts (the local process pool of the studies).

Choices (argument, or ``STOCHFRIC_VECTOR_WIDTH``): ``auto`` (full width on
:data:`FULL_WIDTH_CPUS`), ``512`` (on any x86 CPU with AVX-512, e.g. Ice Lake, whose 512-bit clock
penalty is small) or ``native`` (leave numba's choice).  A user's own
``NUMBA_CPU_NAME``/``NUMBA_CPU_FEATURES`` always win.
"""

from __future__ import annotations

import os
import platform
import sys

from stochfric.errors import InputError

#: LLVM CPU names of Intel Xeons with AVX-512 and no 512-bit frequency licence penalty.
FULL_WIDTH_CPUS = frozenset({"sapphirerapids", "emeraldrapids", "graniterapids", "graniterapids-d",
                             "diamondrapids"})
ENV = "STOCHFRIC_VECTOR_WIDTH"
CHOICES = ("auto", "512", "native")
#: The ``NUMBA_CPU_FEATURES`` string :func:`configure` set in this process (``None``: none), so that
#: tools starting other versions of the package in subprocesses can leave it out.
applied: str | None = None


def wide_features(choice: str, cpu_name: str, features: dict[str, bool], flat: str) -> str | None:
    """The ``NUMBA_CPU_FEATURES`` string for ``choice`` on a CPU with LLVM name ``cpu_name`` and
    feature map ``features`` (``flat``: their comma-separated form), or ``None`` to leave numba's."""
    if choice == "native" or not features.get("avx512f", False):
        return None
    if choice == "auto" and cpu_name not in FULL_WIDTH_CPUS:
        return None
    return flat + ",-prefer-256-bit"


def configure(choice: str | None = None) -> str | None:
    """Apply the vector width ``choice`` (``None``: ``STOCHFRIC_VECTOR_WIDTH``, else ``auto``) by the
    rule of the module docstring; returns the feature string set, or ``None`` when numba's default is
    kept.  Raises ``ValueError`` (a one-line message naming the choices) for an unknown choice."""
    given = os.environ.get(ENV, "auto") if choice is None else choice
    name = given.strip().lower()
    if name not in CHOICES:
        source = f"{ENV}={given!r}" if choice is None else f"vector width {given!r}"
        raise InputError(f"{source}: choose one of {', '.join(CHOICES)}")
    if os.environ.get("NUMBA_CPU_NAME") or os.environ.get("NUMBA_CPU_FEATURES"):
        return None  # the user's own numba target
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return None
    import llvmlite.binding as ll  # ~20 ms; numba's own dependency

    feats = ll.get_host_cpu_features()
    flat = wide_features(name, ll.get_host_cpu_name(), dict(feats), feats.flatten())
    if flat is None:
        return None
    global applied
    os.environ["NUMBA_CPU_FEATURES"] = applied = flat
    if "numba" in sys.modules:  # imported already: make numba re-read its environment
        from numba.core import config

        config.reload_config()
    return flat

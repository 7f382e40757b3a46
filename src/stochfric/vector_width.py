"""The SIMD width of the compiled kernels on Intel Xeon CPUs with AVX-512 (docs/performance.md).

LLVM (and therefore numba) compiles for 256-bit vectors on every Intel CPU with AVX-512, even where
the hardware runs 512-bit instructions at full clock (Xeon since Sapphire Rapids; LLVM issue
102047): the subtarget tuning ``prefer-256-bit``.  stochfric's lock-step kernels advance 32
trajectories per step in branch-free loops, and the white-noise generator (Philox4x32-10 +
Box–Muller, ``oscillator/philox.py``) is pure arithmetic, so they gain from the full width: on an
Intel Xeon (Emerald Rapids) the Philox + Box–Muller normal costs 3.4 instead of 4.8 ns and the
white-noise ensemble 6.2 instead of 7.8 ns per step (docs/performance.md).

:func:`configure` removes the tuning flag for the CPUs of :data:`FULL_WIDTH_CPUS` only, before
numba compiles anything, through numba's own setting ``NUMBA_CPU_FEATURES`` (the host's feature
list plus ``-prefer-256-bit``).  The width changes no number: the loops are element-wise across
trajectories and are compiled without fast-math, so every lane computes the same IEEE operations
in the same order (tested: the same X_gh bit for bit).  It is applied when ``stochfric`` is
imported and affects every numba function compiled later in the process, and, being an environment
variable, the processes it starts (the local process pool of the studies uses it that way).

``STOCHFRIC_VECTOR_WIDTH``: ``auto`` (default: full width on :data:`FULL_WIDTH_CPUS`), ``512`` (on
any x86 CPU with AVX-512, e.g. Ice Lake, whose 512-bit clock penalty is small) or ``native``
(leave numba's choice).  A user's own ``NUMBA_CPU_NAME``/``NUMBA_CPU_FEATURES`` always win.
"""

from __future__ import annotations

import os
import platform
import sys

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


def configure() -> str | None:
    """Apply the vector-width rule of the module docstring; returns the feature string set, or
    ``None`` when numba's default is kept.  Raises ``ValueError`` for an unknown
    ``STOCHFRIC_VECTOR_WIDTH``."""
    choice = os.environ.get(ENV, "auto").strip().lower()
    if choice not in CHOICES:
        raise ValueError(f"{ENV}={choice!r}: choose one of {', '.join(CHOICES)}")
    if os.environ.get("NUMBA_CPU_NAME") or os.environ.get("NUMBA_CPU_FEATURES"):
        return None  # the user's own numba target
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return None
    import llvmlite.binding as ll  # ~20 ms; numba's own dependency

    feats = ll.get_host_cpu_features()
    flat = wide_features(choice, ll.get_host_cpu_name(), dict(feats), feats.flatten())
    if flat is None:
        return None
    global applied
    os.environ["NUMBA_CPU_FEATURES"] = applied = flat
    if "numba" in sys.modules:  # imported before stochfric: make numba re-read its environment
        from numba.core import config

        config.reload_config()
    return flat

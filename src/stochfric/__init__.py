"""stochfric — stochastic friction coefficients from measured surfaces and their effect on
friction-induced vibration (after N. Gaus, KIT 2013).

Importing the package does no work — no compilation, no registration, no logging set-up — except
one setting: the SIMD width numba compiles for on Intel Xeons with AVX-512
(:mod:`stochfric.vector_width`; it changes speed, never a number; ``STOCHFRIC_VECTOR_WIDTH=native``
turns it off).
"""

from __future__ import annotations

from . import vector_width as _vector_width

__version__ = "0.1.0"
_vector_width.configure()

__all__ = ["__version__"]

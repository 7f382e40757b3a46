"""stochfric — stochastic friction coefficients from measured surfaces and their effect on
friction-induced vibration (after N. Gaus, KIT 2013).

Importing the package does no work: no compilation, no registration, no logging set-up.
"""

from __future__ import annotations

__version__ = "0.1.0"

__all__ = ["__version__"]

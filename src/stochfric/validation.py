"""Validators of scalar inputs shared by the parameter classes (SI values; messages say what to change).

Every validator returns the value as a ``float`` (:func:`count`: an ``int``; :func:`finite_tuple`: a tuple of floats) or
raises ``error`` (default :class:`ValueError`; callers pass their own subclass, e.g.
:class:`stochfric.oscillator.parameters.ParameterError`) with a message that names the quantity,
the allowed range with its unit, and the value given.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

__all__ = ["count", "finite", "finite_tuple", "non_negative", "positive"]


def finite(name: str, value: float, *, error: type[ValueError] = ValueError) -> float:
    """``value`` as a finite float, or ``error`` ("NAME must be a number / finite"); a boolean is no number."""
    if isinstance(value, bool):
        raise error(f"{name} must be a number, not the boolean {str(value).lower()}")
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise error(f"{name} must be a number, got {value!r}") from None
    if not math.isfinite(v):
        raise error(f"{name} must be finite, got {value!r}")
    return v


def positive(name: str, value: float, unit: str = "", *, error: type[ValueError] = ValueError) -> float:
    """``value`` > 0 as a float, or ``error`` ("NAME must be > 0 UNIT, got …")."""
    v = finite(name, value, error=error)
    if v <= 0.0:
        raise error(f"{name} must be > 0{(' ' + unit) if unit else ''}, got {value!r}")
    return v


def non_negative(name: str, value: float, unit: str = "", *, error: type[ValueError] = ValueError) -> float:
    """``value`` >= 0 as a float, or ``error`` ("NAME must be >= 0 UNIT, got …")."""
    v = finite(name, value, error=error)
    if v < 0.0:
        raise error(f"{name} must be >= 0{(' ' + unit) if unit else ''}, got {value!r}")
    return v


def finite_tuple(name: str, values: Any, *, error: type[ValueError] = ValueError) -> tuple[float, ...]:
    """A non-empty 1-D sequence of finite numbers as a tuple of floats, or ``error``."""
    try:
        arr = np.asarray(values, dtype=np.float64)
    except (TypeError, ValueError):
        raise error(f"{name} must be a sequence of numbers") from None
    if arr.ndim != 1 or arr.size == 0 or not np.all(np.isfinite(arr)):
        raise error(f"{name} must be a non-empty 1-D sequence of finite numbers")
    return tuple(float(v) for v in arr)


def count(name: str, value: Any, low: int = 1, *, error: type[ValueError] = ValueError) -> int:
    """An integer (Python or NumPy, not bool) >= ``low`` as an ``int``, or ``error``."""
    if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < low:
        raise error(f"{name} must be an integer >= {low}, got {value!r}")
    return int(value)

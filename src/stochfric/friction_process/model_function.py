"""The pressure model function f(p) = a p^b + c (thesis eq. 3.21 / 3.25), p in Pa.

The fitted form of E[μ](p), σ_μ(p) and the PSD level E[S](p) over the mean contact pressure
(:mod:`stochfric.process.fit` fits it, the friction-process models evaluate it).
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any, overload

import numpy as np
from numpy.typing import NDArray

from stochfric.errors import InputError, ProcessModelError
from stochfric.validation import finite

__all__ = ["ModelFunction", "checked_pressure"]


def checked_pressure(p_pa: float) -> float:
    """Pressure p [Pa] as a finite float > 0, or ValueError (the argument of every f(p) and model)."""
    p = finite("pressure p [Pa]", p_pa)
    if p <= 0.0:
        raise InputError(f"pressure p must be > 0 Pa, got {p_pa!r}")
    return p


@dataclass(frozen=True, kw_only=True)
class ModelFunction:
    """Pressure model function f(p) = a p^b + c (thesis eq. 3.21 / 3.25), p in Pa.

    The thesis fits it by nonlinear least squares to E[μ](p), σ_μ(p) and E[S](p)
    (Tables 3.3 and 3.6).  The result has the unit of the fitted quantity (μ and σ_μ
    are dimensionless).
    """

    a: float
    b: float
    c: float

    def __post_init__(self) -> None:
        for name in ("a", "b", "c"):
            value = finite(f"ModelFunction.{name}", getattr(self, name), error=ProcessModelError)
            object.__setattr__(self, name, value)

    @overload
    def __call__(self, p_pa: float) -> float: ...

    @overload
    def __call__(self, p_pa: NDArray[Any]) -> NDArray[np.float64]: ...

    def __call__(self, p_pa: float | NDArray[Any]) -> float | NDArray[np.float64]:
        """f(p) = a p^b + c for pressure(s) p [Pa] > 0 (eq. 3.21).

        A Python/NumPy scalar gives a ``float``, an array gives an array of its shape.
        Raises ValueError for p ≤ 0 or non-finite p (p^b is undefined or meaningless).
        """
        if np.ndim(p_pa) == 0 and not isinstance(p_pa, np.ndarray):
            p = checked_pressure(float(p_pa))
            return self.a * p**self.b + self.c
        arr = np.asarray(p_pa, dtype=np.float64)
        if not (np.all(np.isfinite(arr)) and np.all(arr > 0.0)):
            raise InputError("pressures p must be finite and > 0 Pa")
        result: NDArray[np.float64] = self.a * arr**self.b + self.c
        return result

    def to_dict(self) -> dict[str, float]:
        """``{"a": a, "b": b, "c": c}`` (p in Pa)."""
        return {"a": self.a, "b": self.b, "c": self.c}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> ModelFunction:
        """Inverse of :meth:`to_dict`."""
        return cls(a=data["a"], b=data["b"], c=data["c"])

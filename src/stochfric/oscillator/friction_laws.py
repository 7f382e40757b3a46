"""Velocity-dependent friction laws (method §5, thesis Table 4.1 and eq. 4.13/4.33).

A law is a :class:`FrictionLaw`: a *shape* (an integer code understood by the compiled
function :func:`mu_kinetic`), its parameter vector and the static coefficient ``μ(0)``.
Every shape is a rational form :func:`mu_rational` (the constant law is ``p0`` with
``p1 = p2 = p3 = 0``): the adaptive integrator calls :func:`mu_kinetic_row`, the fixed-step
kernels hold the four coefficients per trajectory.  So a new *named* law with an existing shape
is one factory function and one entry in :data:`FRICTION_LAWS`, and never a change to an
integrator; a shape that is not a rational form would be one more branch in
:func:`mu_kinetic_row` and :func:`dmu_kinetic`, a code in :data:`SHAPES`, and a law evaluation
of its own in the fixed-step kernels.

All laws take the magnitude of the *dimensional* relative velocity ``|v_rel|`` in m/s
(``v_rel = v0 − ẏ``, eq. 4.1); the sign of the friction force is applied by the
integrators (``sign(v_rel)``).  The kinetic value is the coefficient while slipping
(``v_rel ≠ 0``); ``static`` is the coefficient that bounds the sticking force (eq. 4.2).
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numba
import numpy as np
import numpy.typing as npt

from stochfric.errors import InputError

SHAPE_CONSTANT, SHAPE_RATIONAL = range(2)

#: Static coefficient μ0 of the pressure law (4.13), thesis value.
MU0 = 0.4

#: Codes of the compiled shapes understood by :func:`mu_kinetic`.
SHAPES: dict[str, int] = {
    "constant": SHAPE_CONSTANT,
    "rational": SHAPE_RATIONAL,
}

#: Number of parameters of each shape.
N_PARAMS = {SHAPE_CONSTANT: 1, SHAPE_RATIONAL: 4}


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def mu_rational(p0: float, p1: float, p2: float, p3: float, v_abs: float) -> float:  # pragma: no cover
    """The ``rational`` shape ``μ = p0/(1 + p1|v|) + p2 + p3 v²`` (law III, eq. 4.13), |v| in m/s.

    The one place this formula is written: :func:`mu_kinetic_row` and the fixed-step kernels (which
    hold p0..p3 per trajectory; the constant law is p0 with p1 = p2 = p3 = 0, the same bits for
    every finite |v|) both call it."""
    return p0 / (1.0 + p1 * v_abs) + p2 + p3 * v_abs * v_abs


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def mu_kinetic_row(
    shape: int, v_abs: float, p: npt.NDArray[np.float64], r: int | np.uint64
) -> float:  # pragma: no cover
    """Kinetic friction coefficient μ(|v_rel|) for ``|v_rel|`` in m/s, parameters ``p[r, :]``.

    * ``constant``: ``μ = p0`` (laws I and II).
    * ``rational``: ``μ = p0/(1 + p1|v|) + p2 + p3 v²`` (law III with
      ``p = (μ0 − μ1, 1.42, μ1, 0.01)``; eq. 4.13 with ``p = (μ_fit, 1.42, μ0 − μ_fit, 0.01)``).

    Row-indexed so that compiled batch kernels read a trajectory's law without creating
    an array view (and its reference-count traffic) in every step.
    """
    if shape == SHAPE_CONSTANT:
        return p[r, 0]
    return mu_rational(p[r, 0], p[r, 1], p[r, 2], p[r, 3], v_abs)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def mu_kinetic(shape: int, v_abs: float, p: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """:func:`mu_kinetic_row` for a 1-D parameter vector ``p``."""
    return mu_kinetic_row(shape, v_abs, p.reshape((1, p.shape[0])), 0)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def mu_kinetic_array(shape: int, v_abs: npt.NDArray[np.float64], p: npt.NDArray[np.float64]) -> npt.NDArray[
        np.float64]:  # pragma: no cover
    """:func:`mu_kinetic` at every element of the 1-D ``v_abs`` (the same scalar code, compiled loop)."""
    p2 = p.reshape((1, p.shape[0]))
    out = np.empty(v_abs.shape[0])
    for i in range(v_abs.shape[0]):
        out[i] = mu_kinetic_row(shape, v_abs[i], p2, 0)
    return out


@numba.njit(cache=True, nogil=True, error_model="numpy")
def dmu_kinetic(shape: int, v_abs: float, p: npt.NDArray[np.float64]) -> float:  # pragma: no cover
    """Derivative dμ/d|v| of :func:`mu_kinetic` [s/m]."""
    if shape == SHAPE_CONSTANT:
        return 0.0
    d = 1.0 + p[1] * v_abs
    return -p[0] * p[1] / (d * d) + 2.0 * p[3] * v_abs


@dataclass(frozen=True, kw_only=True)
class FrictionLaw:
    """A velocity-dependent friction law: compiled shape, parameters, static coefficient."""

    name: str
    shape: int
    params: tuple[float, ...]
    static: float
    description: str = ""

    def __post_init__(self) -> None:
        if self.shape not in N_PARAMS:
            raise InputError(f"unknown friction-law shape code {self.shape}")
        need = N_PARAMS[self.shape]
        if len(self.params) != need:
            raise InputError(f"law {self.name!r}: shape needs {need} parameters, got {self.params}")
        if not np.all(np.isfinite(self.params)) or not np.isfinite(self.static):
            raise InputError(f"law {self.name!r}: parameters must be finite")
        if self.static < 0:
            raise InputError(f"law {self.name!r}: static coefficient must be >= 0")
        vs = np.linspace(0.0, 20.0, 2001)
        if np.any(self.kinetic(vs) < 0):
            raise InputError(
                f"law {self.name!r} gives a negative kinetic coefficient for |v| <= 20 m/s; "
                "check its parameters (e.g. μ_fit(p) > μ0 in the pressure law)"
            )

    @property
    def param_array(self) -> npt.NDArray[np.float64]:
        return np.asarray(self.params, dtype=np.float64)

    def kinetic(self, v_abs: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """Kinetic coefficient at ``|v_rel|`` [m/s] (vectorised)."""
        v = np.abs(np.asarray(v_abs, dtype=np.float64))
        flat = mu_kinetic_array(self.shape, np.ascontiguousarray(v.ravel()), self.param_array)
        return flat.reshape(v.shape)

    def derivative(self, v_abs: float) -> float:
        """dμ/d|v| at ``|v_rel| = v_abs`` [s/m]."""
        return float(dmu_kinetic(self.shape, float(abs(v_abs)), self.param_array))

    def __call__(self, v_rel: npt.ArrayLike) -> npt.NDArray[np.float64]:
        """μ(v_rel) with the static value at ``v_rel = 0`` (Table 4.1)."""
        v = np.asarray(v_rel, dtype=np.float64)
        out = self.kinetic(v)
        return np.where(v == 0.0, self.static, out)

    def to_dict(self) -> dict[str, object]:
        return {
            "name": self.name,
            "shape": next(k for k, c in SHAPES.items() if c == self.shape),
            "params": list(self.params),
            "static": self.static,
            "description": self.description,
        }


def law_I(mu: float = 0.25) -> FrictionLaw:
    """Law I of Table 4.1: constant ``μ = 0.25`` (static = kinetic)."""
    return FrictionLaw(
        name="I", shape=SHAPE_CONSTANT, params=(mu,), static=mu,
        description=f"Table 4.1 law I: mu = {mu}",
    )


def law_II(mu_static: float = 0.4, mu_kinetic_value: float = 0.25) -> FrictionLaw:
    """Law II of Table 4.1: ``μ(0) = 0.4``, ``μ(v ≠ 0) = 0.25``."""
    return FrictionLaw(
        name="II", shape=SHAPE_CONSTANT, params=(mu_kinetic_value,), static=mu_static,
        description=f"Table 4.1 law II: mu(0) = {mu_static}, mu(v != 0) = {mu_kinetic_value}",
    )


def law_III(mu0: float = 0.4, mu1: float = 0.1, decay: float = 1.42, quad: float = 0.01) -> FrictionLaw:
    """Law III of Table 4.1: ``μ = (μ0 − μ1)/(1 + 1.42|v|) + μ1 + 0.01 v²`` (v in m/s)."""
    return FrictionLaw(
        name="III", shape=SHAPE_RATIONAL, params=(mu0 - mu1, decay, mu1, quad), static=mu0,
        description=f"Table 4.1 law III: (mu0-mu1)/(1+{decay}|v|) + mu1 + {quad} v^2, "
        f"mu0={mu0}, mu1={mu1}",
    )


def pressure_law(mu_fit: float, mu0: float = 0.4, decay: float = 1.42, quad: float = 0.01) -> FrictionLaw:
    """Pressure-dependent law μ_D of eq. (4.13)/(4.33).

    ``μ_D(v) = μ_fit(p)/(1 + 1.42|v|) + μ0 − μ_fit(p) + 0.01 v²`` with ``μ_fit(p) = E[μ](p)``
    from the contact analysis (model function 3.21) and ``μ0 = μ_D(0) = 0.4``.
    """
    if not np.isfinite(mu_fit) or mu_fit <= 0:
        raise InputError(f"mu_fit(p) must be a positive finite number, got {mu_fit}")
    if mu_fit > mu0:
        raise InputError(
            f"mu_fit(p) = {mu_fit:.4g} exceeds mu0 = {mu0}: eq. (4.13) would give a negative "
            "friction coefficient at high sliding speed; the pressure is outside the range the "
            "model function was fitted for"
        )
    return FrictionLaw(
        name="pressure", shape=SHAPE_RATIONAL, params=(mu_fit, decay, mu0 - mu_fit, quad),
        static=mu0,
        description=f"eq. (4.13): mu_fit/(1+{decay}|v|) + mu0 - mu_fit + {quad} v^2, "
        f"mu_fit={mu_fit:.6g}, mu0={mu0}",
    )


#: Named laws: name → factory.  The ``pressure`` law needs ``mu_fit``.
FRICTION_LAWS: dict[str, Callable[..., FrictionLaw]] = {
    "I": law_I,
    "II": law_II,
    "III": law_III,
    "pressure": pressure_law,
}


def get_law(name: str, **kwargs: float) -> FrictionLaw:
    """Build the registered law ``name`` (``I``, ``II``, ``III``, ``pressure``)."""
    try:
        factory = FRICTION_LAWS[name]
    except KeyError:
        raise InputError(
            f"unknown friction law {name!r}; choose one of {sorted(FRICTION_LAWS)}"
        ) from None
    return factory(**kwargs)

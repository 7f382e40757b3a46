"""Closed-form and quadrature reference solutions of contact mechanics (thesis 2.4.1–2.4.2), used by the tests.

Hertz contact of a sphere on a flat (eq. 2.72–2.77, 3.8–3.9) and the Greenwood–Williamson
expectation for summits of equal radius with Gaussian heights (eq. 2.83–2.90), its integrals
``F_n(h)`` in closed form for n = 0, 1, 2 and by adaptive quadrature for any other order, as the
thesis evaluates them ("numerisch ausgewertet").
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt
from scipy import integrate, special

from stochfric.arrays import FloatArray
from stochfric.errors import InputError

__all__ = [
    "GWContact",
    "HertzContact",
    "gw_contact",
    "gw_integral",
    "gw_integral_closed",
    "hertz_contact",
    "hertz_indentation_from_force",
]


@dataclass(frozen=True, kw_only=True)
class HertzContact:
    """Hertz contact of one sphere; SI units."""

    contact_radius_m: float
    contact_area_m2: float
    normal_force_n: float
    max_pressure_pa: float


def hertz_contact(*, radius_m: float, e_star_pa: float, indentation_m: float) -> HertzContact:
    """Hertz sphere of radius β [m] indented by δ [m] into a half-space of modulus E* [Pa].

    ``a = √(βδ)`` (2.74), ``A = πa²`` (2.77), ``N = (4/3)E*√β δ^{3/2}`` (3.9),
    ``p0 = 3N/(2πa²) = 2E* a/(πβ)`` (2.72, 2.75). ``δ <= 0`` gives no contact.
    """
    if not (radius_m > 0 and e_star_pa > 0):
        raise InputError("radius_m and e_star_pa must be > 0")
    d = max(float(indentation_m), 0.0)
    a = math.sqrt(radius_m * d)
    force = 4.0 / 3.0 * e_star_pa * math.sqrt(radius_m) * d**1.5
    p0 = 2.0 * e_star_pa * a / (math.pi * radius_m)
    return HertzContact(
        contact_radius_m=a,
        contact_area_m2=math.pi * a * a,
        normal_force_n=force,
        max_pressure_pa=p0,
    )


def hertz_indentation_from_force(*, radius_m: float, e_star_pa: float, force_n: float) -> float:
    """Indentation δ [m] for a load N [N]: ``a = (3Nβ/(4E*))^{1/3}`` (2.76), ``δ = a²/β``."""
    a = (3.0 * force_n * radius_m / (4.0 * e_star_pa)) ** (1.0 / 3.0)
    return a * a / radius_m


def gw_integral_closed(order: int, h: npt.ArrayLike) -> FloatArray:
    """``F_n(h)`` in closed form for n = 0, 1, 2 (standard normal heights).

    ``F₀ = Q(h)``, ``F₁ = φ(h) − h Q(h)``, ``F₂ = (1 + h²) Q(h) − h φ(h)`` with
    ``Q(h) = ½ erfc(h/√2)`` the upper tail and ``φ`` the standard normal density.
    """
    x = np.asarray(h, dtype=np.float64)
    q = 0.5 * special.erfc(x / math.sqrt(2.0))
    phi = np.exp(-0.5 * x * x) / math.sqrt(2.0 * math.pi)
    if order == 0:
        return np.asarray(q, dtype=np.float64)
    if order == 1:
        return np.asarray(phi - x * q, dtype=np.float64)
    if order == 2:
        return np.asarray((1.0 + x * x) * q - x * phi, dtype=np.float64)
    raise InputError(f"closed form only for orders 0, 1, 2; got {order}")


def gw_integral(order: float, h: npt.ArrayLike) -> FloatArray:
    """``F_n(h) = (1/√(2π)) ∫_h^∞ (s − h)^n e^{−s²/2} ds`` by adaptive quadrature (2.89/2.90).

    Substituting ``t = s − h`` keeps the integrand smooth at the lower limit.
    """
    hs = np.atleast_1d(np.asarray(h, dtype=np.float64))
    out = np.empty_like(hs)
    norm = 1.0 / math.sqrt(2.0 * math.pi)
    for idx, hv in enumerate(hs):

        def integrand(t: float, hv: float = float(hv)) -> float:
            return float(t**order * math.exp(-0.5 * (t + hv) ** 2))

        value, _ = integrate.quad(integrand, 0.0, math.inf, epsabs=0.0, epsrel=1e-12, limit=200)
        out[idx] = norm * value
    return out.reshape(np.shape(h))


@dataclass(frozen=True, kw_only=True)
class GWContact:
    """Expected GW contact quantities at the normalised separations ``h`` (arrays)."""

    separation: FloatArray
    n_contacts: FloatArray
    contact_area_m2: FloatArray
    normal_force_n: FloatArray


def gw_contact(
    *,
    n_summits: float,
    radius_m: float,
    sigma_m: float,
    e_star_pa: float,
    separation_m: npt.ArrayLike,
) -> GWContact:
    """GW expectation for ``K`` summits of radius β̄, Gaussian heights of std σ (2.83–2.90).

    ``separation_m`` is the distance ``d`` of the flat above the *mean* summit height [m], ``h = d/σ``:
    ``n = K F₀(h)``, ``A = π K β̄ σ F₁(h)`` (2.86, 2.89), ``N = (4/3) K E* √β̄ σ^{3/2} F_{3/2}(h)``
    (2.87, 2.90) with ``F_n`` of :func:`gw_integral` (standard normal density φ*, 2.88).
    """
    if not (n_summits > 0 and radius_m > 0 and sigma_m > 0 and e_star_pa > 0):
        raise InputError("n_summits, radius_m, sigma_m and e_star_pa must be > 0")
    d = np.asarray(separation_m, dtype=np.float64)
    h = d / sigma_m
    k = float(n_summits)
    return GWContact(
        separation=h,
        n_contacts=k * gw_integral_closed(0, h),
        contact_area_m2=math.pi * k * radius_m * sigma_m * gw_integral(1.0, h),
        normal_force_n=(4.0 / 3.0) * k * e_star_pa * math.sqrt(radius_m) * sigma_m**1.5 * gw_integral(1.5, h),
    )

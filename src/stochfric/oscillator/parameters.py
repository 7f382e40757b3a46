"""Parameters of the 1-DOF friction oscillator (method §5, thesis eq. 4.5-4.7).

Two equivalent descriptions are offered:

* :class:`PhysicalParameters` — mass ``m`` [kg], stiffness ``c`` [N/m], damper
  ``d_k`` [N s/m] *or* damping ratio ``D`` [-], belt speed ``v0`` [m/s], normal force
  ``N`` [N], forcing amplitude ``Q`` [N] and circular frequency ``Ω`` [rad/s], the
  nominal contact area ``A`` [m²] that turns ``N`` into a pressure, and the length
  scale ``L`` [m] (the thesis: ``L = 1 m``).
* :class:`OscillatorParameters` — the dimensionless form used by the integrators:
  ``ω0 = √(c/m)``, ``D = d_k / (2√(cm))``, ``η = Ω/ω0``, ``n = N/(cL)``,
  ``q = Q/(cL)``, ``γ0 = v0/(L ω0)`` (thesis, below eq. 4.7).  It keeps ``ω0`` and
  ``L`` because the friction laws of Table 4.1 take the *dimensional* relative
  velocity ``v_rel = L ω0 (γ0 − x2)`` in m/s, and optionally ``c`` and ``A`` so
  that the contact pressure ``p = N/A = n c L / A`` (eq. 4.13) is defined.

Both are frozen, keyword-only and validated at construction: a negative mass, a NaN
damping ratio or an impossible combination is refused with a message that says
what to change.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import asdict, dataclass, field
from functools import partial
from typing import Any

from stochfric.errors import InputError
from stochfric.validation import non_negative, positive


class ParameterError(InputError):
    """An oscillator parameter is invalid; the message says which one and why."""


_positive = partial(positive, error=ParameterError)
_non_negative = partial(non_negative, error=ParameterError)


@dataclass(frozen=True, kw_only=True)
class OscillatorParameters:
    """Dimensionless oscillator parameters (thesis eq. 4.6/4.7).

    Attributes
    ----------
    gamma0:
        ``γ0 = v0/(L ω0)``, dimensionless belt speed (> 0).
    n:
        ``n = N/(cL)``, dimensionless normal force (> 0).
    damping_ratio:
        ``D = d_k/(2√(cm))`` (>= 0, < 1: the closed forms and the Hopf boundary assume
        an underdamped oscillator; larger values are refused).
    q:
        ``q = Q/(cL)``, dimensionless forcing amplitude (>= 0).
    eta:
        ``η = Ω/ω0``, forcing frequency ratio (>= 0).
    omega0:
        ``ω0`` [rad/s]; with ``length_scale`` it fixes the velocity scale ``L ω0`` that
        converts ``γ0 − x2`` to the relative velocity in m/s used by the friction law.
    length_scale:
        ``L`` [m] (thesis: 1 m).
    stiffness:
        ``c`` [N/m], optional; needed for the normal force in newtons and the pressure.
    contact_area:
        Nominal contact area ``A`` [m²], optional; ``p = N/A`` (eq. 4.13).
    """

    gamma0: float
    n: float
    damping_ratio: float = 0.0
    q: float = 0.0
    eta: float = 0.0
    omega0: float = 1.0
    length_scale: float = 1.0
    stiffness: float | None = None
    contact_area: float | None = None

    def __post_init__(self) -> None:
        _positive("gamma0 (dimensionless belt speed γ0)", self.gamma0)
        _positive("n (dimensionless normal force N/(cL))", self.n)
        d = _non_negative("damping_ratio D", self.damping_ratio)
        if d >= 1.0:
            raise ParameterError(
                f"damping_ratio D must be < 1 (underdamped oscillator), got {d}; "
                "an overdamped friction oscillator has no stick-slip cycle to study"
            )
        _non_negative("q (dimensionless forcing amplitude Q/(cL))", self.q)
        _non_negative("eta (forcing frequency ratio Ω/ω0)", self.eta)
        _positive("omega0 [rad/s]", self.omega0, "rad/s")
        _positive("length_scale L [m]", self.length_scale, "m")
        if self.stiffness is not None:
            _positive("stiffness c [N/m]", self.stiffness, "N/m")
        if self.contact_area is not None:
            _positive("contact_area A [m²]", self.contact_area, "m²")

    # -- derived quantities -------------------------------------------------
    @property
    def velocity_scale(self) -> float:
        """``L ω0`` [m/s]: ``v_rel = L ω0 (γ0 − x2)`` (thesis eq. 4.16)."""
        return self.length_scale * self.omega0

    @property
    def belt_speed(self) -> float:
        """``v0 = γ0 L ω0`` [m/s]."""
        return self.gamma0 * self.velocity_scale

    @property
    def normal_force(self) -> float | None:
        """``N = n c L`` [N], or ``None`` when the stiffness is unknown."""
        if self.stiffness is None:
            return None
        return self.n * self.stiffness * self.length_scale

    @property
    def pressure_pa(self) -> float | None:
        """Nominal contact pressure ``p = N/A`` [Pa] (eq. 4.13), or ``None``."""
        nf = self.normal_force
        if nf is None or self.contact_area is None:
            return None
        return nf / self.contact_area

    def replace(self, **changes: Any) -> OscillatorParameters:
        """A copy with ``changes`` applied (validated again)."""
        d = asdict(self)
        d.update(changes)
        return OscillatorParameters(**d)

    def with_normal_force(self, normal_force: float) -> OscillatorParameters:
        """A copy at normal force ``normal_force`` [N]; needs ``stiffness``."""
        if self.stiffness is None:
            raise ParameterError(
                "a normal force in newtons needs the stiffness c; give physical parameters "
                "(mass, stiffness) or a preset, or set n directly"
            )
        nf = _positive("normal_force N [N]", normal_force, "N")
        return self.replace(n=nf / (self.stiffness * self.length_scale))

    def to_dict(self) -> dict[str, Any]:
        """All fields plus the derived physical values (None where undefined)."""
        d = asdict(self)
        d.update(
            belt_speed_m_s=self.belt_speed,
            normal_force_n=self.normal_force,
            pressure_pa=self.pressure_pa,
        )
        return d


@dataclass(frozen=True, kw_only=True)
class PhysicalParameters:
    """Physical oscillator parameters in SI units (thesis eq. 4.5).

    Exactly one of ``damping_coefficient`` (``d_k`` [N s/m]) and ``damping_ratio``
    (``D``) may be given; neither means undamped.
    """

    mass: float
    stiffness: float
    belt_speed: float
    normal_force: float
    damping_coefficient: float | None = None
    damping_ratio: float | None = None
    forcing_amplitude: float = 0.0
    forcing_frequency: float = 0.0
    contact_area: float | None = None
    length_scale: float = 1.0
    extra: dict[str, Any] = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        _positive("mass m [kg]", self.mass, "kg")
        _positive("stiffness c [N/m]", self.stiffness, "N/m")
        _positive("belt_speed v0 [m/s]", self.belt_speed, "m/s")
        _positive("normal_force N [N]", self.normal_force, "N")
        if self.damping_coefficient is not None and self.damping_ratio is not None:
            raise ParameterError(
                "give either damping_coefficient d_k [N s/m] or damping_ratio D, not both"
            )
        if self.damping_coefficient is not None:
            _non_negative("damping_coefficient d_k [N s/m]", self.damping_coefficient, "N s/m")
        if self.damping_ratio is not None:
            _non_negative("damping_ratio D", self.damping_ratio)
        _non_negative("forcing_amplitude Q [N]", self.forcing_amplitude, "N")
        _non_negative("forcing_frequency Ω [rad/s]", self.forcing_frequency, "rad/s")
        if self.contact_area is not None:
            _positive("contact_area A [m²]", self.contact_area, "m²")
        _positive("length_scale L [m]", self.length_scale, "m")

    @property
    def omega0(self) -> float:
        """``ω0 = √(c/m)`` [rad/s]."""
        return math.sqrt(self.stiffness / self.mass)

    def to_dimensionless(self) -> OscillatorParameters:
        """The dimensionless parameters of eq. (4.6/4.7)."""
        w0 = self.omega0
        if self.damping_coefficient is not None:
            d = self.damping_coefficient / (2.0 * math.sqrt(self.stiffness * self.mass))
        else:
            d = self.damping_ratio or 0.0
        cl = self.stiffness * self.length_scale
        return OscillatorParameters(
            gamma0=self.belt_speed / (self.length_scale * w0),
            n=self.normal_force / cl,
            damping_ratio=d,
            q=self.forcing_amplitude / cl,
            eta=self.forcing_frequency / w0,
            omega0=w0,
            length_scale=self.length_scale,
            stiffness=self.stiffness,
            contact_area=self.contact_area,
        )


def physical_parameters(
    mass: float, stiffness: float, belt_speed: float, normal_force: float, *,
    damping_ratio: float | None = None, damping_coefficient: float | None = None,
    forcing_amplitude: float = 0.0, eta: float = 0.0, contact_area: float | None = None,
) -> OscillatorParameters:
    """Dimensionless parameters (4.6/4.7) from SI input (kg, N/m, m/s, N, N s/m, N, m²); Ω = η ω0 and
    η kept exactly as given."""
    phys = PhysicalParameters(
        mass=mass, stiffness=stiffness, belt_speed=belt_speed, normal_force=normal_force,
        damping_coefficient=damping_coefficient, damping_ratio=damping_ratio,
        forcing_amplitude=forcing_amplitude, contact_area=contact_area,
    )
    phys = dataclasses.replace(phys, forcing_frequency=eta * phys.omega0)  # ω0 of the validated m, c
    # η exactly as given (Ω = η ω0 and back may differ in the last bit)
    return phys.to_dimensionless().replace(eta=float(eta))

"""The thesis's two application cases as oscillator presets: brake pad (§4.2) and DC04 steel sheet (§4.3).

A :class:`Preset` is the case data of method §6: the oscillator (m, c, v0), the nominal contact
area A that turns N into the pressure p = N/A (eq. 4.13), the stick-slip range of N, the thesis's
study settings, the time grid, and the friction-process model of the surface pairing
(:mod:`stochfric.friction_process.presets`: Tables 3.3/3.6).  SI units: kg, N/m, m/s, m², N.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from enum import StrEnum
from types import MappingProxyType
from typing import Any

from stochfric.errors import InputError, InputTypeError

from ..friction_process.model import BandLimitedProcessModel, ModelFunction
from ..friction_process.model_base import ProcessModelBase
from ..friction_process.presets import (
    BRAKE_PSD_LEVEL_FIT,
    SHEET_PSD_LEVEL_FIT,
    ProcessLevel,
    brake_process,
    process_with_level,
    sheet_process,
)

__all__ = ["PRESETS", "Preset", "PresetName", "StudyParameters", "brake", "get_preset", "sheet"]

#: Length scale L [m] of the dimensionless displacement x = y/L (thesis: L = 1 m).
_LENGTH_SCALE_M = 1.0


class PresetName(StrEnum):
    """The thesis's application cases."""

    BRAKE = "brake"
    SHEET = "sheet"


def _positive(name: str, value: Any, unit: str) -> float:
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise InputError(f"{name} must be a positive finite number {unit}, got {value!r}")
    return v


@dataclass(frozen=True, kw_only=True)
class StudyParameters:
    """The thesis's study settings of a preset (method §6): damping ratios D [-], forces N [N]."""

    #: D of the "undamped" runs (5·10⁻⁶)
    damping_undamped: float
    #: D of the damped runs
    damping_damped: float
    #: N of the damping study
    damping_study_force: float
    #: N of the forcing study
    forcing_study_force: float
    #: the N of the normal-force study (also the Lyapunov study's default)
    normal_force_study_forces: tuple[float, ...]

    def __post_init__(self) -> None:
        for attr in ("damping_undamped", "damping_damped"):
            d = float(getattr(self, attr))
            if not 0.0 <= d < 1.0:
                raise InputError(f"{attr} must lie in [0, 1), got {d!r}")
            object.__setattr__(self, attr, d)
        for attr in ("damping_study_force", "forcing_study_force"):
            object.__setattr__(self, attr, _positive(attr, getattr(self, attr), "[N]"))
        forces = tuple(_positive("normal_force_study_forces", f, "[N]") for f in self.normal_force_study_forces)
        if not forces:
            raise InputError("normal_force_study_forces must hold at least one force [N]")
        object.__setattr__(self, "normal_force_study_forces", forces)


@dataclass(frozen=True, kw_only=True)
class Preset:
    """One application case of the thesis (method §6), SI units.

    Attributes
    ----------
    name:
        ``"brake"`` or ``"sheet"``.
    mass, stiffness, belt_speed:
        m [kg], c [N/m], v0 [m/s].
    contact_area:
        Nominal contact area A [m²] of the pressure p = N/A (eq. 4.13).
    normal_force_range:
        (N_min, N_max) [N] of the stick-slip range studied in the thesis.
    default_normal_force:
        A representative normal force N [N] inside that range.
    process:
        The friction-process model (E[μ](p), σ_μ(p), band-limited spectrum, σ_ζ rule).
    tau_end, dt:
        Default dimensionless simulation end time τ_end and step Δτ (method §6).
    description:
        One-line provenance.
    study_parameters:
        The thesis's study settings (:class:`StudyParameters`).
    recorded_psd_level_fit:
        The thesis's E[S](p) fit (third row of Table 3.3/3.6), read only by the ``psd_level``
        reproduction mode (:meth:`process_with_level`): its PSD normalisation is unstated
        (method §7.8); the default process spectrum is scaled to σ_μ(p)².
    """

    name: str
    mass: float
    stiffness: float
    belt_speed: float
    contact_area: float
    normal_force_range: tuple[float, float]
    default_normal_force: float
    process: BandLimitedProcessModel | Any
    study_parameters: StudyParameters
    tau_end: float = 50.0
    dt: float = 0.005
    description: str = ""
    recorded_psd_level_fit: ModelFunction | None = None

    def __post_init__(self) -> None:
        for attr, unit in (
            ("mass", "[kg]"),
            ("stiffness", "[N/m]"),
            ("belt_speed", "[m/s]"),
            ("contact_area", "[m²]"),
            ("default_normal_force", "[N]"),
            ("tau_end", "(dimensionless)"),
            ("dt", "(dimensionless)"),
        ):
            object.__setattr__(self, attr, _positive(attr, getattr(self, attr), unit))
        lo, hi = (float(v) for v in self.normal_force_range)
        if not (0.0 < lo < hi and math.isfinite(hi)):
            raise InputError(
                f"normal_force_range must be (N_min, N_max) with 0 < N_min < N_max, got {self.normal_force_range!r}"
            )
        object.__setattr__(self, "normal_force_range", (lo, hi))
        if not lo <= self.default_normal_force <= hi:
            raise InputError(
                f"default_normal_force {self.default_normal_force!r} N lies outside "
                f"normal_force_range {self.normal_force_range!r}"
            )
        if not isinstance(self.process, ProcessModelBase):
            raise InputTypeError(f"process must be a friction-process model (band-limited or tabulated), "
                                 f"got {self.process!r}")
        if not isinstance(self.study_parameters, StudyParameters):
            raise InputTypeError(f"study_parameters must be StudyParameters, got {self.study_parameters!r}")

    @property
    def omega0(self) -> float:
        """Natural circular frequency ω0 = √(c/m) [rad/s] (below eq. 4.7)."""
        return math.sqrt(self.stiffness / self.mass)

    @property
    def gamma0(self) -> float:
        """Dimensionless belt speed γ0 = v0/(L ω0), L = 1 m (below eq. 4.7)."""
        return self.belt_speed / (_LENGTH_SCALE_M * self.omega0)

    def pressure(self, normal_force: float) -> float:
        """Nominal contact pressure p = N/A [Pa] for a normal force N [N] (eq. 4.13)."""
        n = float(normal_force)
        if not math.isfinite(n) or n <= 0.0:
            raise InputError(f"normal_force must be a positive finite number [N], got {n!r}")
        return n / self.contact_area

    @property
    def pressure_range_pa(self) -> tuple[float, float]:
        """(p_min, p_max) [Pa] of :attr:`normal_force_range`."""
        lo, hi = self.normal_force_range
        return lo / self.contact_area, hi / self.contact_area

    def process_with_level(self, level: ProcessLevel | str) -> Any:
        """The preset's process model under the process-level rule ``level``
        (:func:`stochfric.friction_process.presets.process_with_level`)."""
        return process_with_level(self.process, self.recorded_psd_level_fit, level)


def brake() -> Preset:
    """Brake pad on a disc (thesis §3.2, §4.2; method §4d table "brake", §6).

    m = 2 kg, c = 10⁶ N/m, v0 = 1 m/s → ω0 ≈ 707 rad/s, γ0 ≈ 1.414·10⁻³;
    A_pad = 0.016 m², stick-slip range N = 500 … 20000 N (p ≈ 0.031 … 1.25 MPa);
    process: :func:`stochfric.friction_process.presets.brake_process` (Table 3.3 fits).
    """
    return Preset(
        name="brake",
        mass=2.0,
        stiffness=1e6,
        belt_speed=1.0,
        contact_area=0.016,
        normal_force_range=(500.0, 20000.0),
        default_normal_force=5600.0,
        process=brake_process(),
        tau_end=50.0,
        dt=0.005,
        description="Brake pad on a rigid disc, Gaus (2013) §3.2 and §4.2, Table 3.3 fits",
        study_parameters=StudyParameters(
            damping_undamped=5e-6,
            damping_damped=0.15,
            damping_study_force=5600.0,
            forcing_study_force=4000.0,
            normal_force_study_forces=(720.0, 2720.0, 8000.0),
        ),
        recorded_psd_level_fit=BRAKE_PSD_LEVEL_FIT,
    )


def sheet() -> Preset:
    """DC04 steel sheet on DC04 (thesis §3.3, §4.3; method §4d table "sheet", §6).

    m = 1 kg, c = 10⁵ N/m, v0 = 1 m/s → ω0 ≈ 316 rad/s, γ0 ≈ 3.16·10⁻³;
    A = 10⁻³ m², stick-slip range N = 100 … 2000 N (p = 0.1 … 2 MPa);
    process: :func:`stochfric.friction_process.presets.sheet_process` (Table 3.6 fits).
    """
    return Preset(
        name="sheet",
        mass=1.0,
        stiffness=1e5,
        belt_speed=1.0,
        contact_area=1e-3,
        normal_force_range=(100.0, 2000.0),
        default_normal_force=1400.0,
        process=sheet_process(),
        tau_end=50.0,
        dt=0.005,
        description="DC04 steel sheet on DC04, Gaus (2013) §3.3 and §4.3, Table 3.6 fits",
        study_parameters=StudyParameters(
            damping_undamped=5e-6,
            damping_damped=0.17,
            damping_study_force=1400.0,
            forcing_study_force=1100.0,
            normal_force_study_forces=(400.0, 880.0, 1750.0),
        ),
        recorded_psd_level_fit=SHEET_PSD_LEVEL_FIT,
    )


#: Factories of the thesis's presets by name; call one to get a fresh :class:`Preset`.
PRESETS: Mapping[PresetName, Callable[[], Preset]] = MappingProxyType(
    {PresetName.BRAKE: brake, PresetName.SHEET: sheet})


def get_preset(name: PresetName | str) -> Preset:
    """The preset called ``name`` (``"brake"`` or ``"sheet"``); ValueError for others."""
    try:
        factory = PRESETS[PresetName(name)]
    except (ValueError, TypeError):
        raise InputError(f"unknown preset {name!r}; available presets: {sorted(str(p) for p in PresetName)}") from None
    return factory()

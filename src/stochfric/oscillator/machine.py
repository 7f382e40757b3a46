"""A machine description: the friction oscillator of one application, typed, validated, with units
(method §5–§6; docs/machines.md).

A :class:`Machine` is what stays fixed for one test rig or one brake: mass m [kg], stiffness c [N/m]
(or ω0 [rad/s]), belt speed v0 [m/s], nominal contact area A [m²] (p = N/A, eq. 4.13), the velocity
law μ_D(v) (Table 4.1 law III or the pressure law 4.13, with their coefficients), an optional
forcing Q cos(η τ), the operating envelope (normal-force range, damping range, a default N and D),
the time grid τ_end, Δτ and optionally the default settings of the thesis's studies.  The friction
*process* (E[μ](p), σ_μ(p), spectrum) is not part of a machine: it comes from a surface analysis or
from a preset, and :meth:`Machine.to_preset` joins the two.

A machine is a TOML file (the whole file, or a ``[machine]`` table of a larger file such as a
``study.toml``) or a Python object.  The TOML keys carry their unit as a suffix (``mass_kg``,
``stiffness_n_per_m``, ``normal_force_n = [500, 4000]``); dimensionless keys have none (``tau_end``,
``damping_ratio``, ``eta``).  Python code may use the field names without the suffix
(``Machine.model_validate({"mass": 2.0, ...})``).  The thesis's brake and sheet ship with the
package (``load_machine("brake")``); they reproduce :func:`~stochfric.oscillator.presets.brake` and
:func:`~stochfric.oscillator.presets.sheet` exactly.

Every refusal is a :class:`MachineError` (an :class:`~stochfric.errors.InputError`) on one line that
names the key, the value, the unit and the allowed range.
"""

from __future__ import annotations

import inspect
import json
import math
import tomllib
from collections.abc import Callable, Iterable, Mapping
from dataclasses import dataclass
from importlib import resources
from pathlib import Path
from typing import Annotated, Any, Literal

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, model_validator

from stochfric.io_utils import read_text_checked

from ..errors import InputError
from ..friction_process.model import BandLimitedProcessModel, ModelFunction
from .friction_laws import MU0, FrictionLaw, law_III, pressure_law
from .parameters import OscillatorParameters, physical_parameters
from .presets import _LENGTH_SCALE_M, Preset, StudyParameters

__all__ = [
    "Forcing",
    "FrictionLawSpec",
    "Machine",
    "MachineError",
    "StudyDefaults",
    "format_machine_errors",
    "load_machine",
    "machine_names",
    "parse_machine",
]

#: Law III's coefficients of Table 4.1 (the defaults of :func:`~.friction_laws.law_III`).
_LAW_III_DEFAULTS = {k: float(p.default) for k, p in inspect.signature(law_III).parameters.items()}
#: The thesis's D of the "undamped" runs (method §6.1).
_D_UNDAMPED = 5e-6
#: The package's folder of shipped machine files.
_SHIPPED = "machines"


class MachineError(InputError):
    """A machine description that cannot be used; the message (one line) names the key, the value, the
    unit and the allowed range.  ``validation_error``: pydantic's error behind it, if any."""

    def __init__(self, message: str, validation_error: ValidationError | None = None) -> None:
        super().__init__(message)
        self.validation_error = validation_error

    def __reduce__(self) -> tuple[Any, ...]:  # picklable (a process worker may raise it)
        return (MachineError, (str(self),))


# -- quantities: unit, allowed range, one-line messages ----------------------------------------------


@dataclass(frozen=True)
class _Spec:
    """A numeric key: what it is, its unit and its allowed range (``lo_open``/``hi_open``: excluded)."""

    what: str
    unit: str
    lo: float
    hi: float
    lo_open: bool = False
    hi_open: bool = False

    @property
    def range_text(self) -> str:
        lo, hi = ("(" if self.lo_open else "[") + f"{self.lo:g}", f"{self.hi:g}" + (")" if self.hi_open else "]")
        return f"{lo}, {hi}" + (f" {self.unit}" if self.unit else "")

    def value_text(self, value: Any) -> str:
        return f"{value!r}" + (f" {self.unit}" if self.unit else "")

    def inside(self, v: float) -> bool:
        return (self.lo < v if self.lo_open else self.lo <= v) and (v < self.hi if self.hi_open else v <= self.hi)

    def check(self, value: Any) -> float:
        """``value`` as a float, or ValueError: "WHAT = VALUE UNIT …; allowed RANGE"."""
        allowed = f"allowed {self.range_text}"
        if isinstance(value, bool) or not isinstance(value, int | float):
            raise ValueError(f"{self.what} must be a number, got {value!r}; {allowed}")
        try:
            v = float(value)
        except OverflowError:
            v = math.inf
        if not math.isfinite(v):
            raise ValueError(f"{self.what} must be finite, got {value!r}; {allowed}")
        if not self.inside(v):
            raise ValueError(f"{self.what} = {self.value_text(value)} is outside the allowed range {self.range_text}")
        return v


#: Every numeric key (TOML name) with its meaning, unit and range (docs/machines.md lists them).
SPECS: dict[str, _Spec] = {
    "mass_kg": _Spec("mass m", "kg", 1e-6, 1e5),
    "stiffness_n_per_m": _Spec("stiffness c", "N/m", 1.0, 1e12),
    "omega0_rad_s": _Spec("natural circular frequency ω0 = √(c/m)", "rad/s", 1e-3, 1e9),
    "belt_speed_m_s": _Spec("belt speed v0", "m/s", 1e-6, 1e3),
    "contact_area_m2": _Spec("nominal contact area A", "m²", 1e-12, 10.0),
    "normal_force_n": _Spec("normal force N", "N", 0.0, 1e9, lo_open=True),
    "default_normal_force_n": _Spec("default normal force N", "N", 0.0, 1e9, lo_open=True),
    "damping_ratio": _Spec("damping ratio D", "", 0.0, 1.0, hi_open=True),
    "damping_ratio_range": _Spec("damping ratio D", "", 0.0, 1.0, hi_open=True),
    "tau_end": _Spec("dimensionless end time τ_end", "", 0.0, 1e7, lo_open=True),
    "dt": _Spec("dimensionless time step Δτ", "", 0.0, 1.0, lo_open=True),
    "mu0": _Spec("static coefficient μ0 = μ_D(0)", "", 0.0, 10.0, lo_open=True),
    "mu1": _Spec("law III's high-speed level μ1", "", 0.0, 10.0),
    "decay_s_per_m": _Spec("decay rate of μ_D(v)", "s/m", 0.0, 1e3),
    "quad_s2_per_m2": _Spec("quadratic coefficient of μ_D(v)", "s²/m²", 0.0, 1e3),
    "amplitude_n": _Spec("forcing amplitude Q", "N", 0.0, 1e9),
    "eta": _Spec("forcing frequency ratio η = Ω/ω0", "", 0.0, 1e3),
    "damping_undamped": _Spec("D of the undamped runs", "", 0.0, 1.0, hi_open=True),
    "damping_damped": _Spec("D of the damped runs", "", 0.0, 1.0, hi_open=True),
    "damping_study_force_n": _Spec("N of the damping study", "N", 0.0, 1e9, lo_open=True),
    "forcing_study_force_n": _Spec("N of the forcing study", "N", 0.0, 1e9, lo_open=True),
    "normal_force_study_forces_n": _Spec("N of the normal-force study", "N", 0.0, 1e9, lo_open=True),
}


def _scalar(key: str) -> Callable[[Any], Any]:
    spec = SPECS[key]
    return lambda v: None if v is None else spec.check(v)


def _pair(key: str) -> Callable[[Any], Any]:
    """[low, high] with low < high, each in the key's range."""
    spec = SPECS[key]

    def check(v: Any) -> Any:
        if not isinstance(v, list | tuple) or len(v) != 2:
            raise ValueError(f"{spec.what} range must be [low, high] in {spec.range_text}, got {v!r}")
        lo, hi = (spec.check(x) for x in v)
        if not lo < hi:
            raise ValueError(f"{spec.what} range [{lo:g}, {hi:g}] must have low < high; allowed {spec.range_text}")
        return (lo, hi)
    return check


def _list(key: str) -> Callable[[Any], Any]:
    """A non-empty list of values in the key's range, none twice."""
    spec = SPECS[key]

    def check(v: Any) -> Any:
        if not isinstance(v, list | tuple) or not v:
            raise ValueError(f"{spec.what} must be a non-empty list of numbers in {spec.range_text}, got {v!r}")
        out = tuple(spec.check(x) for x in v)
        if len(set(out)) != len(out):
            raise ValueError(f"{spec.what}: a value is listed twice in {list(out)!r}")
        return out
    return check


def _q(key: str, kind: Callable[[str], Callable[[Any], Any]] = _scalar) -> Any:
    """The check of the TOML key ``key`` (:data:`SPECS`) by ``kind(key)``, run before pydantic's."""
    return BeforeValidator(kind(key))


def _text(max_len: int, single_line: bool) -> Callable[[Any], Any]:
    def check(v: Any) -> Any:
        if not isinstance(v, str):
            raise ValueError(f"must be a string, got {v!r}")
        if single_line and ("\n" in v or "\r" in v or not v.strip()):
            raise ValueError(f"must be a non-empty single line, got {v!r}")
        if len(v) > max_len:
            raise ValueError(f"must be at most {max_len} characters, got {len(v)}")
        return v
    return check


_CONFIG = ConfigDict(frozen=True, extra="forbid", populate_by_name=True)

# -- the model -------------------------------------------------------------------------------------


class FrictionLawSpec(BaseModel):
    """The velocity law μ_D(v) of the kinetic friction, v = |v_rel| in m/s (Table 4.1, eq. 4.13).

    ``III``: μ = (μ0 − μ1)/(1 + a|v|) + μ1 + b v²; ``pressure`` (4.13, the law of the thesis's studies):
    the same with μ1 = μ0 − E[μ](p) from the friction process at p = N/A.  a = ``decay_s_per_m``,
    b = ``quad_s2_per_m2``; the thesis's values are the defaults (μ0 = 0.4, μ1 = 0.1, a = 1.42, b = 0.01).
    """

    model_config = _CONFIG

    law: Literal["III", "pressure"] = "III"
    mu0: Annotated[float, _q("mu0")] = MU0
    mu1: Annotated[float, _q("mu1")] = Field(default=_LAW_III_DEFAULTS["mu1"])
    decay: Annotated[float, _q("decay_s_per_m")] = Field(default=_LAW_III_DEFAULTS["decay"], alias="decay_s_per_m")
    quad: Annotated[float, _q("quad_s2_per_m2")] = Field(default=_LAW_III_DEFAULTS["quad"], alias="quad_s2_per_m2")

    @model_validator(mode="after")
    def _mu1_is_law_iii(self) -> FrictionLawSpec:
        if self.law == "pressure" and "mu1" in self.model_fields_set:
            raise ValueError("mu1 is law III's: the pressure law takes μ1 = μ0 − E[μ](p) from the "
                             "friction process; remove mu1 or give law = \"III\"")
        return self

    def build(self, mu_fit: float | None = None) -> FrictionLaw:
        """The :class:`~.friction_laws.FrictionLaw`; the pressure law needs ``mu_fit`` = E[μ](p)."""
        if self.law == "III":
            return law_III(mu0=self.mu0, mu1=self.mu1, decay=self.decay, quad=self.quad)
        if mu_fit is None:
            raise MachineError("the pressure law (4.13) needs mu_fit = E[μ](p) from a friction-process model")
        return pressure_law(mu_fit, mu0=self.mu0, decay=self.decay, quad=self.quad)


class Forcing(BaseModel):
    """The external force Q cos(η τ) (thesis eq. 4.5–4.7): Q [N] and η = Ω/ω0; q = Q/(cL)."""

    model_config = _CONFIG

    amplitude: Annotated[float, _q("amplitude_n")] = Field(alias="amplitude_n")
    eta: Annotated[float, _q("eta")]


class StudyDefaults(BaseModel):
    """The default settings of the thesis's studies (method §6; :class:`~.presets.StudyParameters`)."""

    model_config = _CONFIG

    damping_undamped: Annotated[float, _q("damping_undamped")] = _D_UNDAMPED
    damping_damped: Annotated[float, _q("damping_damped")]
    damping_study_force: Annotated[float, _q("damping_study_force_n")] = Field(alias="damping_study_force_n")
    forcing_study_force: Annotated[float, _q("forcing_study_force_n")] = Field(alias="forcing_study_force_n")
    normal_force_study_forces: Annotated[tuple[float, ...], _q("normal_force_study_forces_n", _list)] = Field(
        alias="normal_force_study_forces_n")


class Machine(BaseModel):
    """One friction oscillator (method §5), SI units; see the module docstring and docs/machines.md.

    Give exactly one of ``stiffness`` (``stiffness_n_per_m``) and ``omega0`` (``omega0_rad_s``);
    the other is derived (c = m ω0², ω0 = √(c/m)) and both are attributes.  ``default_normal_force``
    defaults to the middle of ``normal_force_range``.  Build one with :meth:`model_validate` (a mapping
    with the TOML keys or the field names), :func:`load_machine` or :meth:`from_preset`.
    """

    model_config = _CONFIG

    name: Annotated[str, BeforeValidator(_text(80, True))]
    description: Annotated[str, BeforeValidator(_text(2000, False))] = ""
    mass: Annotated[float, _q("mass_kg")] = Field(alias="mass_kg")
    stiffness: Annotated[float | None, _q("stiffness_n_per_m")] = Field(default=None, alias="stiffness_n_per_m")
    omega0: Annotated[float | None, _q("omega0_rad_s")] = Field(default=None, alias="omega0_rad_s")
    belt_speed: Annotated[float, _q("belt_speed_m_s")] = Field(alias="belt_speed_m_s")
    contact_area: Annotated[float, _q("contact_area_m2")] = Field(alias="contact_area_m2")
    normal_force_range: Annotated[tuple[float, float], _q("normal_force_n", _pair)] = Field(alias="normal_force_n")
    default_normal_force: Annotated[float | None, _q("default_normal_force_n")] = Field(
        default=None, alias="default_normal_force_n")
    damping_ratio: Annotated[float, _q("damping_ratio")] = _D_UNDAMPED
    damping_ratio_range: Annotated[tuple[float, float], _q("damping_ratio_range", _pair)] = (0.0, 0.3)
    tau_end: Annotated[float, _q("tau_end")] = 50.0
    dt: Annotated[float, _q("dt")] = 0.005
    friction_law: FrictionLawSpec = Field(default_factory=FrictionLawSpec)
    forcing: Forcing | None = None
    study_defaults: StudyDefaults | None = None

    @model_validator(mode="after")
    def _consistent(self) -> Machine:
        self._derive_stiffness()
        lo, hi = self.normal_force_range
        if self.default_normal_force is None:
            object.__setattr__(self, "default_normal_force", 0.5 * (lo + hi))
        elif not lo <= self.default_normal_force <= hi:
            raise ValueError(f"default_normal_force_n = {self.default_normal_force!r} N lies outside normal_force_n "
                             f"[{lo:g}, {hi:g}] N")
        dlo, dhi = self.damping_ratio_range
        if not dlo <= self.damping_ratio <= dhi:
            raise ValueError(f"damping_ratio = {self.damping_ratio!r} lies outside damping_ratio_range "
                             f"[{dlo:g}, {dhi:g}]")
        if not self.dt < self.tau_end:
            raise ValueError(f"dt = {self.dt!r} must be smaller than tau_end = {self.tau_end!r}")
        if self.study_defaults is not None:
            self._check_study_defaults(self.study_defaults)
        return self

    def _derive_stiffness(self) -> None:
        given = {"stiffness", "omega0"} & self.model_fields_set
        given = {k for k in given if getattr(self, k) is not None}
        if len(given) != 1:
            raise ValueError("give exactly one of stiffness_n_per_m [N/m] and omega0_rad_s [rad/s] (the other "
                             f"follows from mass_kg: c = m ω0²), got {'both' if given else 'neither'}")
        if given == {"stiffness"}:  # (idempotent: pydantic may run this twice on one instance)
            assert self.stiffness is not None
            object.__setattr__(self, "omega0", math.sqrt(self.stiffness / self.mass))
            return
        assert self.omega0 is not None
        spec = SPECS["stiffness_n_per_m"]
        c = self.mass * self.omega0**2
        if not spec.inside(c):
            raise ValueError(f"omega0_rad_s = {self.omega0!r} rad/s with mass_kg = {self.mass!r} kg gives "
                             f"stiffness c = m ω0² = {c:g} N/m, outside the allowed range {spec.range_text}")
        object.__setattr__(self, "stiffness", c)

    def _check_study_defaults(self, s: StudyDefaults) -> None:
        lo, hi = self.normal_force_range
        forces = {"damping_study_force_n": (s.damping_study_force,), "forcing_study_force_n": (s.forcing_study_force,),
                  "normal_force_study_forces_n": s.normal_force_study_forces}
        for key, values in forces.items():
            bad = [f for f in values if not lo <= f <= hi]
            if bad:
                raise ValueError(f"study_defaults.{key} = {bad[0]!r} N lies outside normal_force_n [{lo:g}, {hi:g}] N")
        dlo, dhi = self.damping_ratio_range
        for key in ("damping_undamped", "damping_damped"):
            d = getattr(s, key)
            if not dlo <= d <= dhi:
                raise ValueError(f"study_defaults.{key} = {d!r} lies outside damping_ratio_range [{dlo:g}, {dhi:g}]")

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            raise MachineError(format_machine_errors(exc), exc) from None

    @classmethod
    def model_validate(cls, obj: Any, **kwargs: Any) -> Machine:
        """:meth:`pydantic.BaseModel.model_validate`, refusals as :class:`MachineError`.  A mapping is
        validated once, through ``__init__`` (pydantic would wrap the error of a custom ``__init__``)."""
        if isinstance(obj, Mapping) and not kwargs:
            bad = [k for k in obj if not isinstance(k, str)]
            if bad:
                raise MachineError(f"a machine's keys are strings, got {bad[0]!r}")
            return cls(**obj)
        try:
            return super().model_validate(obj, **kwargs)
        except ValidationError as exc:
            raise MachineError(format_machine_errors(exc), exc) from None

    # -- derived quantities -------------------------------------------------------------------------
    @property
    def gamma0(self) -> float:
        """Dimensionless belt speed γ0 = v0/(L ω0), L = 1 m (below eq. 4.7)."""
        assert self.omega0 is not None
        return self.belt_speed / (_LENGTH_SCALE_M * self.omega0)

    def pressure(self, normal_force: float) -> float:
        """Nominal contact pressure p = N/A [Pa] at the normal force N [N] (eq. 4.13)."""
        try:
            return SPECS["normal_force_n"].check(normal_force) / self.contact_area
        except ValueError as exc:
            raise MachineError(f"normal_force: {exc}") from None

    @property
    def pressure_range_pa(self) -> tuple[float, float]:
        """(p_min, p_max) [Pa] over the normal-force range."""
        lo, hi = self.normal_force_range
        return lo / self.contact_area, hi / self.contact_area

    @property
    def q(self) -> float:
        """Dimensionless forcing amplitude q = Q/(cL) (0 without forcing)."""
        assert self.stiffness is not None
        return 0.0 if self.forcing is None else self.forcing.amplitude / (self.stiffness * _LENGTH_SCALE_M)

    def check_envelope(self, normal_forces: Iterable[float] = (), damping_ratios: Iterable[float] = ()) -> None:
        """MachineError if a normal force [N] or a damping ratio lies outside the operating envelope."""
        lo, hi = self.normal_force_range
        bad = [float(n) for n in normal_forces if not lo <= float(n) <= hi]
        if bad:
            raise MachineError(f"normal force {bad[0]:g} N lies outside machine {self.name!r}'s normal_force_n "
                               f"[{lo:g}, {hi:g}] N")
        dlo, dhi = self.damping_ratio_range
        bad = [float(d) for d in damping_ratios if not dlo <= float(d) <= dhi]
        if bad:
            raise MachineError(f"damping ratio {bad[0]:g} lies outside machine {self.name!r}'s damping_ratio_range "
                               f"[{dlo:g}, {dhi:g}]")

    # -- bridges to the oscillator ------------------------------------------------------------------
    def oscillator_parameters(
        self, normal_force: float | None = None, damping_ratio: float | None = None, *,
        forcing_amplitude: float | None = None, eta: float | None = None,
    ) -> OscillatorParameters:
        """Dimensionless parameters (eq. 4.6/4.7) at N [N], D, Q [N], η; ``None``: the machine's default
        (N, D, its forcing or none).  The same numbers as :meth:`~.case.CaseSetup.parameters`."""
        assert self.stiffness is not None and self.default_normal_force is not None
        forcing = self.forcing
        return physical_parameters(
            self.mass, self.stiffness, self.belt_speed,
            self.default_normal_force if normal_force is None else normal_force,
            damping_ratio=self.damping_ratio if damping_ratio is None else damping_ratio,
            forcing_amplitude=(forcing.amplitude if forcing else 0.0) if forcing_amplitude is None else
            forcing_amplitude,
            eta=(forcing.eta if forcing else 0.0) if eta is None else eta,
            contact_area=self.contact_area,
        )

    def law(self, mu_fit: float | None = None) -> FrictionLaw:
        """The machine's velocity law as a :class:`~.friction_laws.FrictionLaw` (``mu_fit`` = E[μ](p) for
        the pressure law)."""
        return self.friction_law.build(mu_fit)

    def study_parameters(self) -> StudyParameters:
        """The study settings: ``study_defaults``, or without them D = 5·10⁻⁶ undamped, the machine's D
        damped, its default N for the damping and forcing studies, (N_min, N_default, N_max) for the
        normal-force study."""
        s = self.study_defaults
        if s is not None:
            return StudyParameters(
                damping_undamped=s.damping_undamped, damping_damped=s.damping_damped,
                damping_study_force=s.damping_study_force, forcing_study_force=s.forcing_study_force,
                normal_force_study_forces=s.normal_force_study_forces)
        assert self.default_normal_force is not None
        lo, hi = self.normal_force_range
        return StudyParameters(
            damping_undamped=_D_UNDAMPED, damping_damped=self.damping_ratio,
            damping_study_force=self.default_normal_force, forcing_study_force=self.default_normal_force,
            normal_force_study_forces=tuple(sorted({lo, self.default_normal_force, hi})))

    def to_preset(self, process: BandLimitedProcessModel | Any,
                  recorded_psd_level_fit: ModelFunction | None = None) -> Preset:
        """The :class:`~.presets.Preset` of this machine with the friction-process model ``process``
        (and, for the ``psd_level`` reproduction mode, the thesis's E[S](p) fit)."""
        assert self.stiffness is not None and self.default_normal_force is not None
        return Preset(
            name=self.name, mass=self.mass, stiffness=self.stiffness, belt_speed=self.belt_speed,
            contact_area=self.contact_area, normal_force_range=self.normal_force_range,
            default_normal_force=self.default_normal_force, process=process,
            study_parameters=self.study_parameters(), tau_end=self.tau_end, dt=self.dt,
            description=self.description, recorded_psd_level_fit=recorded_psd_level_fit)

    @classmethod
    def from_preset(cls, preset: Preset, **changes: Any) -> Machine:
        """The machine of a preset (its process left out): the pressure law with μ0 = 0.4, D = the
        undamped D, damping range [0, 0.3], the preset's study settings; ``changes`` (field names)
        override."""
        sp = preset.study_parameters
        data: dict[str, Any] = {
            "name": preset.name, "description": preset.description, "mass": preset.mass,
            "stiffness": preset.stiffness, "belt_speed": preset.belt_speed, "contact_area": preset.contact_area,
            "normal_force_range": preset.normal_force_range, "default_normal_force": preset.default_normal_force,
            "damping_ratio": sp.damping_undamped, "tau_end": preset.tau_end, "dt": preset.dt,
            "friction_law": {"law": "pressure", "mu0": MU0},
            "study_defaults": {
                "damping_undamped": sp.damping_undamped, "damping_damped": sp.damping_damped,
                "damping_study_force": sp.damping_study_force, "forcing_study_force": sp.forcing_study_force,
                "normal_force_study_forces": sp.normal_force_study_forces},
        }
        data.update(changes)
        return cls.model_validate(data)

    # -- output -------------------------------------------------------------------------------------
    def to_dict(self) -> dict[str, Any]:
        """The machine as its TOML keys (JSON-compatible; :meth:`model_validate` reads it back): of
        stiffness and ω0 only the one given."""
        derived = "stiffness" if "omega0" in self.model_fields_set else "omega0"
        out: dict[str, Any] = self.model_dump(mode="json", by_alias=True, exclude={derived}, exclude_none=True)
        if self.friction_law.law == "pressure":
            out["friction_law"].pop("mu1")  # the pressure law's μ1 = μ0 − E[μ](p) comes from the process
        return out

    def describe(self) -> dict[str, Any]:
        """:meth:`to_dict` plus the derived quantities (for provenance records)."""
        return {**self.to_dict(), "derived": {
            "stiffness_n_per_m": self.stiffness, "omega0_rad_s": self.omega0, "gamma0": self.gamma0,
            "pressure_range_pa": list(self.pressure_range_pa), "q": self.q}}

    def to_json(self, indent: int | None = 2) -> str:
        """:meth:`to_dict` as JSON."""
        return json.dumps(self.to_dict(), indent=indent, ensure_ascii=False)

    def to_toml(self, table: str | None = None) -> str:
        """The machine as TOML text (:func:`load_machine` reads it back); ``table``: under ``[table]``
        (e.g. ``"machine"`` for a study file)."""
        return _toml_document(self.to_dict(), table)


# -- errors ----------------------------------------------------------------------------------------


#: The keys that are a [low, high] range.
_PAIRS = ("normal_force_n", "damping_ratio_range")


def _allowed_keys(model: type[BaseModel]) -> str:
    return ", ".join(f.alias or name for name, f in model.model_fields.items())


def _model_at(loc: tuple[Any, ...]) -> type[BaseModel]:
    sub: dict[str, type[BaseModel]] = {"friction_law": FrictionLawSpec, "forcing": Forcing,
                                       "study_defaults": StudyDefaults}
    return sub.get(str(loc[0]), Machine) if loc else Machine


def format_machine_errors(exc: ValidationError, prefix: str = "") -> str:
    """Every problem of ``exc`` on one line: ``KEY: WHAT = VALUE UNIT …; allowed RANGE``; unknown keys
    with the keys allowed there.  ``prefix``: the place of the machine (``"machine."``)."""
    parts: list[str] = []
    unknown: dict[tuple[Any, ...], list[str]] = {}
    for e in exc.errors():
        loc = tuple(e["loc"])
        if e["type"] == "extra_forbidden":
            unknown.setdefault(loc[:-1], []).append(str(loc[-1]))
            continue
        place = prefix + ".".join(str(p) for p in loc if not isinstance(p, int))
        msg = str(e["msg"]).removeprefix("Value error, ")
        spec = SPECS.get(str(loc[-1])) if loc else None
        if e["type"] == "missing":
            shape = "[low, high] of the " if str(loc[-1]) in _PAIRS else ""
            msg = "missing" + (f": give {shape}{spec.what} in {spec.range_text}" if spec else "")
        elif e["type"] in ("model_type", "model_attributes_type", "dict_type"):
            msg = f"must be a table with the keys {_allowed_keys(_model_at(loc))}, got {e.get('input')!r}"
        elif e["type"] not in ("value_error", "assertion_error"):
            msg += f", got {e.get('input')!r}"
        parts.append(f"{place}: {msg}" if place else (f"{prefix.rstrip('.')}: {msg}" if prefix else msg))
    for loc, keys in unknown.items():
        where = (prefix + ".".join(str(p) for p in loc)).rstrip(".") or "the machine"
        parts.append(f"unknown key{'s' if len(keys) > 1 else ''} {', '.join(repr(k) for k in keys)} in {where}; "
                     f"allowed keys: {_allowed_keys(_model_at(loc))}")
    return "; ".join(parts)


# -- TOML writing (the flat / one-table-deep structure of a machine) ---------------------------------


def _toml_string(s: str) -> str:
    out = []
    for ch in s:
        if ch in '"\\':
            out.append("\\" + ch)
        elif ord(ch) < 0x20 or ord(ch) == 0x7F:
            out.append(f"\\u{ord(ch):04X}")
        else:
            out.append(ch)
    return '"' + "".join(out) + '"'


def _toml_value(v: Any) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, int | float):
        if not math.isfinite(v):
            raise MachineError(f"cannot write the non-finite number {v!r} to TOML")
        return repr(v)
    if isinstance(v, str):
        return _toml_string(v)
    if isinstance(v, list | tuple):
        return "[" + ", ".join(_toml_value(x) for x in v) + "]"
    raise MachineError(f"cannot write {v!r} to TOML")


def _toml_document(data: Mapping[str, Any], table: str | None) -> str:
    lines = ["# stochfric machine description (docs/machines.md): SI units, the key suffix names the unit"]
    if table:
        lines.append(f"[{table}]")
    tables = {k: v for k, v in data.items() if isinstance(v, Mapping)}
    lines += [f"{k} = {_toml_value(v)}" for k, v in data.items() if k not in tables]
    for key, sub in tables.items():
        lines += ["", f"[{table + '.' if table else ''}{key}]"]
        lines += [f"{k} = {_toml_value(v)}" for k, v in sub.items()]
    return "\n".join(lines) + "\n"


# -- loading ---------------------------------------------------------------------------------------


def machine_names() -> tuple[str, ...]:
    """The machines shipped with the package (``brake``, ``sheet``, …), by file name."""
    folder = resources.files("stochfric") / "data" / _SHIPPED
    return tuple(sorted(p.name[:-5] for p in folder.iterdir() if p.name.endswith(".toml")))


def _read_toml(text: str, source: str) -> dict[str, Any]:
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise MachineError(f"{source} is not valid TOML: {exc}") from None


def _shipped(name: str) -> Machine:
    key = name.strip().lower()
    if key not in machine_names():
        raise MachineError(f"unknown machine {name!r}: no such file, and not a shipped machine "
                           f"({', '.join(machine_names())})")
    res = resources.files("stochfric") / "data" / _SHIPPED / f"{key}.toml"
    return parse_machine(_read_toml(res.read_text(encoding="utf-8"), f"{key}.toml"), f"{key}.toml")


def parse_machine(data: Mapping[str, Any], source: str = "machine", base: Path | None = None, *,
                  follow: bool = True) -> Machine:
    """A machine from a loaded TOML mapping: its ``[machine]`` table if it has one (the rest of the file
    is not the machine's), else the whole mapping.  ``machine = "NAME_OR_PATH"`` refers to a shipped
    machine or a file (relative to ``base``) that is a machine itself (``follow``: not a reference again)."""
    prefix = ""
    if "machine" in data:
        table = data["machine"]
        if isinstance(table, str) and follow:
            ref = Path(table) if base is None or Path(table).is_absolute() else base / table
            return _load(ref if ref.is_file() else table, follow=False)
        if not isinstance(table, Mapping):
            raise MachineError(f"{source}: machine must be a table [machine] or the name or file of a machine "
                               f"(which is no reference itself), got {table!r}")
        data, prefix = table, "machine."
    try:
        return Machine.model_validate(dict(data))
    except MachineError as exc:
        assert exc.validation_error is not None
        msg = format_machine_errors(exc.validation_error, prefix)
        raise MachineError(f"{source}: {msg}", exc.validation_error) from None


def load_machine(source: str | Path | Machine) -> Machine:
    """A machine from a TOML file (the whole file, or its ``[machine]`` table) or a shipped name
    (``brake``, ``sheet``, …, any case; :func:`machine_names`); a :class:`Machine` is returned as is."""
    return _load(source, follow=True)


def _load(source: str | Path | Machine, follow: bool) -> Machine:
    if isinstance(source, Machine):
        return source
    if not isinstance(source, str | Path):
        raise MachineError(f"a machine is a file, a shipped name ({', '.join(machine_names())}) or a Machine, "
                           f"got {source!r}")
    path = Path(source)
    if isinstance(source, str) and not path.is_file() and path.suffix != ".toml" and len(path.parts) == 1:
        return _shipped(source)
    try:
        text = read_text_checked(path)
    except OSError as exc:
        raise MachineError(f"cannot read machine file {path}: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise MachineError(f"{path} is not UTF-8 text (byte {exc.start}: {exc.reason})") from None
    return parse_machine(_read_toml(text, str(path)), str(path), base=path.parent, follow=follow)

"""One oscillator case, built once (method §5–§6).

A *case* is everything one :func:`~stochfric.oscillator.integrate.simulate` call needs besides the
friction model, the number of runs and the seed: the dimensionless parameters (eq. 4.6/4.7), the
friction law, the friction-process model (preset or file, under the σ_ζ rule and the process-level
rule), and the time grid τ_end, Δτ.  It is built here, and only here, from

* a preset (``brake`` / ``sheet``, :mod:`.presets`: m, c, v0, A, process model, τ_end, Δτ; thesis
  Tables 3.3/3.6 and §4.2/§4.3) and/or physical parameters in SI units (:class:`PhysicalInput`), or
  dimensionless input γ0, n (:class:`DimensionlessInput`);
* the normal force N [N] (or n), the damping ratio D (or d_k [N s/m]), the forcing Q [N] (or q)
  and η = Ω/ω0;
* the friction law and process choices (:class:`FrictionInput`).

Two entries, one construction:

* :func:`build_case` — the single case of ``stochfric simulate`` and the benchmarks (every input
  form, the friction-law choice, μ0, the process length);
* :func:`case_setup` → :class:`CaseSetup` — what stays fixed over a study's grid (preset, process
  model under its rules, τ_end, Δτ); :meth:`CaseSetup.parameters` / :meth:`CaseSetup.case` add N, D,
  Q, η.

Both go through :func:`resolve_process` (the process model), :func:`physical_parameters` (SI →
dimensionless) and :func:`law_for` (the pressure law 4.13 with μ_fit = E[μ](p)).  Errors
(:class:`CaseError`) name the inputs by their field names in backquotes (```normal_force```); the
command line shows its flags instead.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..friction_process.model import FrictionProcessModel, SigmaZetaRule, load_process_model
from ..friction_process.model_base import check_pressure_range
from ..friction_process.presets import ProcessLevel
from .friction_laws import MU0, FrictionLaw, get_law, pressure_law
from .machine import Machine, MachineError, load_machine
from .options import Model, WhiteIncrement, WhiteIntensity, white_increment_of
from .parameters import OscillatorParameters, ParameterError, physical_parameters
from .presets import Preset, PresetName, get_preset

__all__ = [
    "MU0",
    "WHITE_MODEL_STANDING",
    "Case",
    "CaseError",
    "CaseSetup",
    "DimensionlessInput",
    "FrictionInput",
    "MachineLike",
    "PhysicalInput",
    "build_case",
    "case_setup",
    "law_for",
    "machine_preset",
    "physical_parameters",
    "pressure_check",
    "process_rule_of",
    "resolve_process",
    "with_white_intensity",
]

#: What the white-noise model is (docs/method.md §5.1a, ``stochfric study white-limit``), recorded with every
#: white-noise result: not the small-correlation-length limit of the measured contact process.
WHITE_MODEL_STANDING = ("phenomenological white noise in time: its intensity σ_ζ is fixed by no surface measurement, "
                        "and it is not the limit of the contact process (at a fixed spectral level σ(X_gh) grows as "
                        "ℓ^β, β ≈ −0.2 … −0.3, as the correlation length ℓ shrinks; method §5.1a)")



class CaseError(ParameterError):
    """A case (or a study built on it) is configured wrongly; the message says what to change,
    naming the inputs by their field names in backquotes."""


def process_rule_of(rule: WhiteIntensity | str) -> SigmaZetaRule:
    """The process model's σ_ζ rule behind a white-intensity rule (``thesis`` uses σ_ζ = σ_μ(p))."""
    return SigmaZetaRule.SIGMA_MU if rule == WhiteIntensity.THESIS else SigmaZetaRule(rule)


def with_white_intensity(process: FrictionProcessModel, rule: WhiteIntensity | str) -> FrictionProcessModel:
    """The process model with its σ_ζ rule set to ``rule`` (``"sigma_mu"`` | ``"spectral_level"``;
    ``"thesis"`` uses the process rule ``"sigma_mu"`` and scales it in :func:`simulate`).

    Only the white-noise model's intensity ``process.sigma_zeta(p)`` changes; the mean and the
    realisations of the contact-analysis process do not depend on the rule.
    """
    if rule not in tuple(WhiteIntensity):
        raise CaseError(f"`white_intensity` must be one of {[str(r) for r in WhiteIntensity]}, got {rule!r}")
    process_rule = process_rule_of(rule)
    if getattr(process, "sigma_zeta_rule", None) == process_rule:
        return process
    if not (dataclasses.is_dataclass(process) and any(f.name == "sigma_zeta_rule"
                                                      for f in dataclasses.fields(process))):
        raise CaseError(f"the friction-process model {type(process).__name__} has no sigma_zeta_rule; "
                        "use `white_intensity` sigma_mu")
    try:
        out: FrictionProcessModel = dataclasses.replace(process, sigma_zeta_rule=process_rule)
    except ValueError as exc:
        raise CaseError(f"`white_intensity` {process_rule}: {exc}") from None
    return out


def with_length(process: Any, length: float) -> Any:
    """The process model generated over ``length`` [m]; the grid keeps spanning whole periods:
    n = round(length/dx) points of dx = length/n (a ``psd_level`` model: its base model's grid)."""
    if hasattr(process, "base"):
        return dataclasses.replace(process, base=with_length(process.base, length))
    npts = max(2, round(length / process.dx))
    return dataclasses.replace(process, length=length, dx=length / npts)


def resolve_process(
    preset: Preset | None,
    process_file: str | Path | None = None,
    *,
    white_intensity: WhiteIntensity | str | None = WhiteIntensity.SIGMA_MU,
    process_level: ProcessLevel | str = ProcessLevel.SIGMA_MU,
    process_length: float | None = None,
) -> tuple[Any, str]:
    """The friction-process model of a case and its source (``"preset:brake"``, ``"file:…"``).

    A ``process_file`` replaces the preset's model; ``process_level`` ``"psd_level"`` (reproduction
    mode, presets only) replaces it by :class:`~stochfric.friction_process.presets.PsdLevelProcessModel`;
    ``white_intensity`` (``None``: keep the model's own rule) sets the σ_ζ rule; ``process_length``
    [m] regenerates over another length.  ``(None, "")`` without preset and file.
    """
    if process_level not in tuple(ProcessLevel):
        raise CaseError(f"`process_level` must be one of {[str(v) for v in ProcessLevel]}, got {process_level!r}")
    level = ProcessLevel(process_level)
    if level != ProcessLevel.SIGMA_MU and (process_file is not None or preset is None):
        raise CaseError("`process_level` psd_level rescales a preset's process; it cannot be combined with a "
                        "`process_file`: use a `preset`")
    if process_file is not None:
        process: Any = load_process_model(process_file)
        source = f"file:{process_file}"
    elif preset is not None:
        process = preset.process_with_level(level)
        source = f"preset:{preset.name}" + ("" if level == ProcessLevel.SIGMA_MU else f" ({level})")
    else:
        if white_intensity is not None:
            raise CaseError("`white_intensity` needs a friction-process model (a `preset` or a `process_file`)")
        return None, ""
    if white_intensity is not None:
        process = with_white_intensity(process, white_intensity)
    if process_length is not None:
        process = with_length(process, process_length)
    return process, source


def law_for(process: FrictionProcessModel, params: OscillatorParameters, mu0: float = MU0) -> FrictionLaw:
    """The pressure law (4.13/4.33) with μ_fit = E[μ](p) of the process model, p = N/A."""
    p = params.pressure_pa
    if p is None:
        raise CaseError("the pressure law needs p = N/A: parameters without stiffness or contact area")
    mu_fit = process.mean(p)
    if mu_fit > mu0:
        raise CaseError(
            f"the pressure law (4.13) needs E[μ](p) <= μ0, but the process model gives E[μ] = {mu_fit:.4g} "
            f"at p = {p / 1e6:.4g} MPa and μ0 = {mu0:g}: the kinetic friction would turn "
            f"negative at high sliding speed; give a larger static coefficient `mu0` ({mu_fit + 0.2:.2g} or "
            "more) or another `friction_law` (III)"
        )
    return pressure_law(mu_fit, mu0=mu0)


@dataclass(frozen=True)
class Case:
    """One oscillator case: parameters, friction law, process model and time grid.

    ``process`` is ``None`` for a case without a friction-process model (dimensionless input
    with a Table 4.1 law); ``sigma_zeta`` an explicit white-noise intensity (else the process's);
    ``white_intensity`` the σ_ζ rule the process model was set to (``None``: its own).
    """

    params: OscillatorParameters
    law: FrictionLaw
    process: Any = None
    tau_end: float = 50.0
    dt: float = 0.005
    preset: Preset | None = None
    process_source: str = ""
    white_intensity: WhiteIntensity | None = None
    sigma_zeta: float | None = None
    process_level: ProcessLevel = ProcessLevel.SIGMA_MU
    #: The stamp of a process model used outside its fitted pressures (allowed explicitly), else None.
    extrapolation: str | None = None

    def modes(self, model: Model | str) -> dict[str, str]:
        """The case's modelling modes as plain strings (recorded in every output): the σ_ζ rule of
        the white-noise model (``given`` for an explicit σ_ζ) and the contact process's level."""
        rule = ("given" if self.sigma_zeta is not None else self.white_intensity
                or str(getattr(self.process, "sigma_zeta_rule", SigmaZetaRule.SIGMA_MU)))
        out = {"white_intensity": str(rule) if model == Model.WHITE else "n/a",
               "process_level": str(self.process_level) if model == Model.CONTACT else "n/a"}
        if model == Model.WHITE:
            out["white_model"] = WHITE_MODEL_STANDING
        if self.extrapolation:
            out["extrapolation"] = self.extrapolation
        return out

    def white_increment(self, model: Model | str) -> WhiteIncrement:
        """The increment rule a simulation of ``model`` runs (:func:`~.options.white_increment_of`)."""
        return white_increment_of(model, self.white_intensity)


@dataclass(frozen=True)
class CaseSetup:
    """What a study keeps fixed over its grid: preset (m, c, v0, A), process model, time grid."""

    preset: Preset
    process: FrictionProcessModel
    process_source: str
    tau_end: float
    dt: float
    white_intensity: WhiteIntensity = WhiteIntensity.SIGMA_MU
    process_level: ProcessLevel = ProcessLevel.SIGMA_MU
    #: Use the process model outside its fitted pressures (stamped) instead of refusing (issue 30, item 3).
    allow_extrapolation: bool = False
    #: Static coefficient μ0 of the pressure law (4.13): the machine's ``[friction_law] mu0``, else the thesis's.
    mu0: float = MU0

    @property
    def white_increment(self) -> WhiteIncrement:
        """The increment rule of the setup's white-noise model (:func:`~.options.white_increment_of`)."""
        return white_increment_of(Model.WHITE, self.white_intensity)

    def parameters(
        self, normal_force: float, damping_ratio: float, forcing_amplitude: float = 0.0, eta: float = 0.0
    ) -> OscillatorParameters:
        """Dimensionless parameters (4.6/4.7) at N [N], D, Q [N] and η = Ω/ω0."""
        pre = self.preset
        return physical_parameters(pre.mass, pre.stiffness, pre.belt_speed, normal_force,
                                   damping_ratio=damping_ratio, forcing_amplitude=forcing_amplitude, eta=eta,
                                   contact_area=pre.contact_area)

    def case(
        self, normal_force: float, damping_ratio: float, forcing_amplitude: float = 0.0, eta: float = 0.0
    ) -> Case:
        """The :class:`Case` at N [N], D, Q [N], η: these parameters and the pressure law (4.13)."""
        return self.case_of(self.parameters(normal_force, damping_ratio, forcing_amplitude, eta))

    def case_of(self, params: OscillatorParameters) -> Case:
        """The :class:`Case` of parameters of this setup (:meth:`parameters`) with the pressure law (4.13)."""
        stamp = pressure_check(self.process, params, allow=self.allow_extrapolation)
        return Case(params=params, law=law_for(self.process, params, self.mu0), process=self.process,
                    tau_end=self.tau_end, dt=self.dt, preset=self.preset, process_source=self.process_source,
                    white_intensity=self.white_intensity, process_level=self.process_level, extrapolation=stamp)

    def extrapolation_stamps(self, normal_forces: Sequence[float]) -> list[str]:
        """The stamps of the forces [N] at which the process model is used outside its fitted pressures
        (empty: none; refused unless :attr:`allow_extrapolation`)."""
        stamps = [check_pressure_range(self.process, float(nf) / self.preset.contact_area, allow=True,
                                       context=f"N = {float(nf):g} N over A = {self.preset.contact_area:g} m²")
                  for nf in normal_forces]
        return [st for st in stamps if st]

    def check_forces(self, normal_forces: Sequence[float]) -> list[str]:
        """Refuse, before any work, forces [N] outside the model's fitted pressures (issue 30, item 3) unless
        :attr:`allow_extrapolation`; the stamps of the allowed ones."""
        forces = [float(nf) for nf in normal_forces]
        if forces and not self.allow_extrapolation:
            p = [nf / self.preset.contact_area for nf in forces]
            check_pressure_range(self.process, p, allow=False,
                                 context=f"N = {min(forces):g}–{max(forces):g} N over A = "
                                         f"{self.preset.contact_area:g} m²")
        return self.extrapolation_stamps(forces)

    def sigma_zeta(self, normal_force: float) -> float:
        """σ_ζ of the white-noise model at N [N] (p = N/A) under the setup's σ_ζ rule (for ``thesis``:
        the nominal σ_ζ = σ_μ(p); see :meth:`sigma_zeta_effective`)."""
        return float(self.process.sigma_zeta(float(normal_force) / self.preset.contact_area))

    def sigma_zeta_effective(self, normal_force: float) -> float:
        """The intensity the white-noise SDE actually uses: σ_ζ, or σ_ζ·Lω0·Δτ (L = 1 m) in ``thesis``
        mode (printed eq. 4.31, docs/oscillator.md)."""
        s = self.sigma_zeta(normal_force)
        return s * self.preset.omega0 * self.dt if self.white_increment == WhiteIncrement.THESIS else s

    def describe(self) -> dict[str, Any]:
        """JSON-compatible record of the case (for provenance); JSON has no unit attribute, so the
        keys carry the units."""
        pre = self.preset
        return {
            "preset": pre.name,
            "mass_kg": pre.mass,
            "stiffness_n_per_m": pre.stiffness,
            "belt_speed_m_s": pre.belt_speed,
            "contact_area_m2": pre.contact_area,
            "omega0_rad_s": pre.omega0,
            "gamma0": pre.gamma0,
            "process_source": self.process_source,
            "process": self.process.to_dict(),
            "tau_end": self.tau_end,
            "dt": self.dt,
            "white_intensity": str(self.white_intensity),
            "white_increment": str(self.white_increment),
            "process_level": str(self.process_level),
            "allow_extrapolation": self.allow_extrapolation,
        }


def pressure_check(process: Any, params: OscillatorParameters, *, allow: bool) -> str | None:
    """:func:`~stochfric.friction_process.model_base.check_pressure_range` at the case's p = N/A (None without
    a process model or a pressure)."""
    p = params.pressure_pa
    if process is None or p is None:
        return None
    nf = params.normal_force
    context = f"N = {nf:g} N over A = {params.contact_area:g} m²" if nf is not None and params.contact_area else ""
    return check_pressure_range(process, p, allow=allow, context=context)


def _preset(name: PresetName | str | Preset) -> Preset:
    if isinstance(name, Preset):
        return name
    try:
        return get_preset(name)
    except ValueError as exc:
        raise CaseError(str(exc)) from None


#: What a case's machine may be given as: a thesis preset name, a machine file or shipped name, or the object.
MachineLike = PresetName | str | Path | Preset | Machine


def machine_preset(machine: MachineLike, process_file: str | Path | None = None) -> Preset:
    """The :class:`Preset` (oscillator, contact area, envelope, study settings, process model) of a thesis
    preset name, a :class:`~.machine.Machine`, a machine TOML file or a shipped machine name (issue 30).

    The thesis's ``brake`` and ``sheet`` (names or their shipped machine files) keep their preset's process
    model (Tables 3.3/3.6) unless ``process_file`` replaces it; any other machine needs ``process_file`` (the
    friction-process model of the user's surface: ``stochfric friction-process`` or ``assess``)."""
    if isinstance(machine, Preset):
        return machine
    if isinstance(machine, str) and not isinstance(machine, Machine) and str(machine).lower() in tuple(PresetName):
        return _preset(str(machine).lower())
    try:
        m = load_machine(machine)
    except MachineError as exc:
        raise CaseError(f"{exc} (thesis presets: {', '.join(str(p) for p in PresetName)})") from None
    if process_file is not None:
        return m.to_preset(load_process_model(process_file))
    if m.name in tuple(PresetName):
        thesis = get_preset(m.name)
        return m.to_preset(thesis.process, thesis.recorded_psd_level_fit)
    raise CaseError(f"the machine {m.name!r} has no friction-process model of its own: give the model of its "
                    "surface (--process FILE from `stochfric friction-process`, or run `stochfric assess`)")


def case_setup(
    preset: MachineLike = PresetName.BRAKE,
    process_file: str | Path | None = None,
    tau_end: float | None = None,
    dt: float | None = None,
    white_intensity: WhiteIntensity | str = WhiteIntensity.SIGMA_MU,
    process_level: ProcessLevel | str = ProcessLevel.SIGMA_MU,
    *,
    allow_extrapolation: bool = False,
) -> CaseSetup:
    """Resolve a preset name and an optional friction-process model file; the σ_ζ rule
    ``white_intensity`` is applied to the process model (it overrides a file's own).
    ``process_level`` ``"psd_level"`` (reproduction mode, presets only) replaces the preset's
    process by :class:`~stochfric.friction_process.presets.PsdLevelProcessModel`."""
    pre = machine_preset(preset, process_file)
    process, source = resolve_process(pre, process_file, white_intensity=white_intensity,
                                      process_level=process_level)
    te = float(tau_end) if tau_end is not None else pre.tau_end
    step = float(dt) if dt is not None else pre.dt
    return CaseSetup(preset=pre, process=process, process_source=source, tau_end=te, dt=step,
                     white_intensity=WhiteIntensity(white_intensity), process_level=ProcessLevel(process_level),
                     allow_extrapolation=bool(allow_extrapolation), mu0=machine_mu0(preset))


def machine_mu0(machine: MachineLike) -> float:
    """μ0 of the pressure law: the machine's ``[friction_law] mu0``; the thesis's 0.4 for a preset."""
    if isinstance(machine, Preset) or (isinstance(machine, str) and str(machine).lower() in tuple(PresetName)):
        return MU0
    return float(load_machine(machine).friction_law.mu0)


@dataclass(frozen=True, kw_only=True)
class PhysicalInput:
    """Physical oscillator input in SI units (thesis eq. 4.5); ``None``: the preset's value, or not given.

    ``mass`` m [kg], ``stiffness`` c [N/m], ``belt_speed`` v0 [m/s], ``contact_area`` A [m²],
    ``normal_force`` N [N], ``damping_coefficient`` d_k [N s/m], ``forcing_amplitude`` Q [N].
    """

    mass: float | None = None
    stiffness: float | None = None
    belt_speed: float | None = None
    contact_area: float | None = None
    normal_force: float | None = None
    damping_coefficient: float | None = None
    forcing_amplitude: float | None = None


@dataclass(frozen=True, kw_only=True)
class DimensionlessInput:
    """Dimensionless oscillator input (eq. 4.6/4.7); ``None``: not given.

    ``n`` = N/(cL), ``q`` = Q/(cL), ``damping_ratio`` D and ``eta`` = Ω/ω0 go with a preset or physical
    input too; ``gamma0`` = v0/(Lω0) and ``omega0`` [rad/s] (default 1) only without them.
    """

    gamma0: float | None = None
    n: float | None = None
    damping_ratio: float | None = None
    q: float | None = None
    eta: float | None = None
    omega0: float | None = None


@dataclass(frozen=True, kw_only=True)
class FrictionInput:
    """The friction law and the friction-process model of a case.

    ``friction_law``: a Table 4.1 law (``I``, ``II``, ``III``) or ``pressure`` (4.13, with static
    coefficient ``mu0``); ``None``: ``pressure`` whenever a process model gives E[μ](p), else ``III``.
    ``process_file``: a friction-process model file replacing the preset's; ``process_length`` [m]:
    regenerate it over this length; ``process_level``, ``white_intensity``: its rules
    (``None``: ``sigma_mu``, and the model's own σ_ζ rule); ``sigma_zeta``: an explicit white-noise
    intensity instead of a rule.
    """

    friction_law: str | None = None
    mu0: float = MU0
    process_file: str | Path | None = None
    process_length: float | None = None
    process_level: ProcessLevel | None = None
    white_intensity: WhiteIntensity | None = None
    sigma_zeta: float | None = None
    #: Use the process model outside its fitted pressures (every output stamped) instead of refusing.
    allow_extrapolation: bool = False

    def __post_init__(self) -> None:
        # checked whether or not the model reads them: a value that cannot be right is refused, not ignored
        if self.process_length is not None and not (math.isfinite(self.process_length) and self.process_length > 0):
            raise CaseError(f"the process length ℓ must be a finite length > 0 [m], got {self.process_length!r}")
        if self.sigma_zeta is not None and not (math.isfinite(self.sigma_zeta) and self.sigma_zeta >= 0):
            raise CaseError(f"the white-noise intensity σ_ζ must be a finite number >= 0, got {self.sigma_zeta!r}")


def _parameters(pre: Preset | None, phys: PhysicalInput, dim: DimensionlessInput) -> OscillatorParameters:
    """The parameters of :func:`build_case` from a preset, SI input or dimensionless input."""
    if dim.q is not None and phys.forcing_amplitude is not None:
        raise CaseError("give the forcing as `forcing_amplitude` Q [N] or `q`, not both")
    if dim.damping_ratio is not None and phys.damping_coefficient is not None:
        raise CaseError("give the damping as `damping_ratio` D or `damping_coefficient` d_k [N s/m], not both")
    if phys.normal_force is not None and dim.n is not None:
        raise CaseError("give the normal force as `normal_force` N [N] or `n`, not both")
    if pre is not None or any(v is not None for v in (phys.mass, phys.stiffness, phys.belt_speed)):
        if dim.gamma0 is not None or dim.omega0 is not None:
            raise CaseError(
                "`gamma0`/`omega0` are for dimensionless input; with a preset or physical "
                "parameters give `belt_speed`, `mass`, `stiffness` instead"
            )
        m_ = phys.mass if phys.mass is not None else (pre.mass if pre else None)
        c_ = phys.stiffness if phys.stiffness is not None else (pre.stiffness if pre else None)
        v_ = phys.belt_speed if phys.belt_speed is not None else (pre.belt_speed if pre else None)
        a_ = phys.contact_area if phys.contact_area is not None else (pre.contact_area if pre else None)
        missing = [k for k, v in (("`mass`", m_), ("`stiffness`", c_), ("`belt_speed`", v_)) if v is None]
        if missing:
            raise CaseError(f"physical parameters need {', '.join(missing)} (or a `preset`)")
        assert m_ is not None and c_ is not None and v_ is not None
        if dim.n is not None:
            nf = dim.n * c_
        elif phys.normal_force is not None:
            nf = phys.normal_force
        elif pre is not None:
            nf = pre.default_normal_force
        else:
            raise CaseError("give the normal force `normal_force` N [N] or `n`")
        damping_ratio = dim.damping_ratio
        if damping_ratio is None and phys.damping_coefficient is None:
            damping_ratio = pre.study_parameters.damping_undamped if pre else 0.0
        forcing = dim.q * c_ if dim.q is not None else (phys.forcing_amplitude or 0.0)
        return physical_parameters(m_, c_, v_, nf, damping_ratio=damping_ratio,
                                   damping_coefficient=phys.damping_coefficient, forcing_amplitude=forcing,
                                   eta=dim.eta or 0.0, contact_area=a_)
    if phys.normal_force is not None or phys.forcing_amplitude is not None or phys.damping_coefficient is not None:
        raise CaseError(
            "`normal_force`, `forcing_amplitude` and `damping_coefficient` are in SI units and "
            "need `mass`, `stiffness`, `belt_speed` or a `preset`; for dimensionless input give "
            "`n`, `q`, `damping_ratio`"
        )
    if dim.gamma0 is None or dim.n is None:
        raise CaseError(
            "give either a `preset`, physical parameters (`mass`, `stiffness`, `belt_speed`, "
            "`normal_force`) or dimensionless `gamma0` and `n`"
        )
    return OscillatorParameters(
        gamma0=dim.gamma0, n=dim.n, damping_ratio=dim.damping_ratio or 0.0, q=dim.q or 0.0, eta=dim.eta or 0.0,
        omega0=dim.omega0 if dim.omega0 is not None else 1.0, contact_area=phys.contact_area,
    )


def build_case(
    preset: MachineLike | None = None,
    *,
    physical: PhysicalInput | None = None,
    dimensionless: DimensionlessInput | None = None,
    friction: FrictionInput | None = None,
    model: Model | str = Model.DETERMINISTIC,
    tau_end: float | None = None,
    dt: float | None = None,
) -> Case:
    """The one :class:`Case` of a simulation, from any input form (the options of ``stochfric simulate``).

    Parameters: a ``preset`` (its m, c, v0, A, default N and D = 5·10⁻⁶ unless given; m, c, v0, A
    may be overridden), ``physical`` SI input (:class:`PhysicalInput`), ``dimensionless`` input
    (:class:`DimensionlessInput`: n, q, D, η with either form; γ0, ω0 alone); ``None``: none given.
    The friction law and process (:class:`FrictionInput`) default to the pressure law (4.13) with μ0
    whenever a process model gives E[μ](p), else Table 4.1 law III.  ``model`` is only checked (white
    and contact need a process model, white may have ``sigma_zeta`` instead).  τ_end, Δτ default to
    the preset's (else 50, 0.005).  Raises :class:`CaseError` with a message that names the input to change.
    """
    fr = friction or FrictionInput()
    pre = machine_preset(preset, fr.process_file) if preset else None
    params = _parameters(pre, physical or PhysicalInput(), dimensionless or DimensionlessInput())
    if fr.white_intensity is not None and fr.sigma_zeta is not None:
        raise CaseError("give either `sigma_zeta` or `white_intensity`, not both")
    level = fr.process_level or ProcessLevel.SIGMA_MU
    process, source = resolve_process(pre, fr.process_file, white_intensity=fr.white_intensity,
                                      process_level=level, process_length=fr.process_length)
    stamp = pressure_check(process, params, allow=fr.allow_extrapolation)
    law_name = fr.friction_law or ("pressure" if process is not None and params.pressure_pa is not None else "III")
    if law_name == "pressure":
        if process is None or params.pressure_pa is None:
            raise CaseError(
                "the pressure law (4.13) needs E[μ](p) from a friction-process model and the "
                "pressure p = N/A: use a `preset`, or a `process_file` with physical parameters and "
                "`contact_area`"
            )
        law = law_for(process, params, fr.mu0)
    else:
        try:
            law = get_law(law_name)
        except ValueError as exc:
            raise CaseError(f"`friction_law`: {exc}") from None
    if model != Model.DETERMINISTIC and process is None and not (model == Model.WHITE and fr.sigma_zeta is not None):
        raise CaseError(
            f"the {model} model needs a friction-process model: give a `preset` or a `process_file`"
            + (" or `sigma_zeta`" if model == Model.WHITE else "")
        )
    return Case(
        params=params, law=law, process=process,
        tau_end=tau_end if tau_end is not None else (pre.tau_end if pre else 50.0),
        dt=dt if dt is not None else (pre.dt if pre else 0.005),
        preset=pre, process_source=source,
        white_intensity=WhiteIntensity(fr.white_intensity) if fr.white_intensity is not None else None,
        sigma_zeta=fr.sigma_zeta, process_level=ProcessLevel(level), extrapolation=stamp,
    )

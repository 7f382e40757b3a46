"""One oscillator case, built once (method §5–§6).

A *case* is everything one :func:`~stochfric.oscillator.integrate.simulate` call needs besides the
friction model, the number of runs and the seed: the dimensionless parameters (eq. 4.6/4.7), the
friction law, the friction-process model (preset or file, under the σ_ζ rule and the process-level
rule), and the time grid τ_end, Δτ.  It is built here, and only here, from

* a path preset (``brake`` / ``sheet``: m, c, v0, A, process model, τ_end, Δτ; thesis Tables
  3.3/3.6 and §4.2/§4.3) and/or physical parameters in SI units, or dimensionless input γ0, n;
* the normal force N [N] (or n), the damping ratio D (or d_k [N s/m]), the forcing Q [N] (or q)
  and η = Ω/ω0.

Two entries, one construction:

* :func:`build_case` — the single case of ``stochfric simulate`` and the benchmarks (every input
  form, the friction-law choice, μ0, ``--process-length``);
* :func:`case_setup` → :class:`CaseSetup` — what stays fixed over a study's grid (preset, process
  model under its rules, τ_end, Δτ); :meth:`CaseSetup.parameters` / :meth:`CaseSetup.case` add N, D,
  Q, η.  The studies use it through :func:`stochfric.studies.common.setup_for`.

Both go through :func:`resolve_process` (the process model), :func:`physical_parameters` (SI →
dimensionless) and :func:`law_for` (the pressure law 4.13 with μ_fit = E[μ](p)).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..process.model import FrictionProcessModel, load_process_model
from ..process.presets import PROCESS_LEVELS, Preset, get_preset, process_with_level
from .friction_laws import FrictionLaw, get_law, pressure_law
from .parameters import OscillatorParameters, ParameterError, PhysicalParameters

__all__ = [
    "MODELS",
    "PATH_COORDINATES",
    "WHITE_INTENSITY_RULES",
    "Case",
    "CaseError",
    "CaseSetup",
    "build_case",
    "case_setup",
    "law_for",
    "physical_parameters",
    "process_rule_of",
    "resolve_process",
    "white_increment_of",
    "with_white_intensity",
]

#: The three friction models of method §5, run side by side in the studies.
MODELS: tuple[str, ...] = ("deterministic", "white", "contact")
#: Where the contact process is read (method §7.7).
PATH_COORDINATES: tuple[str, ...] = ("mass", "relative", "position")
#: What the white-noise model is (docs/method.md §5.1a, ``stochfric study white-limit``), recorded with every
#: white-noise result: not the small-correlation-length limit of the measured contact process.
WHITE_MODEL_STANDING = ("phenomenological white noise in time: its intensity σ_ζ is fixed by no surface measurement, "
                        "and it is not the limit of the contact process (at a fixed spectral level σ(X_gh) grows as "
                        "ℓ^β, β ≈ −0.2 … −0.3, as the correlation length ℓ shrinks; method §5.1a)")

#: σ_ζ rules of the white-noise model (glossary: ``white_intensity``).
WHITE_INTENSITY_RULES: tuple[str, ...] = ("sigma_mu", "spectral_level", "thesis")
#: Static coefficient μ0 of the pressure law (4.13), thesis value.
MU0 = 0.4


class CaseError(ParameterError):
    """A case (or a study built on it) is configured wrongly; the message says what to change."""


def white_increment_of(rule: str) -> str:
    """The :func:`simulate` ``white_increment`` of a white-intensity rule: ``thesis`` → ``"thesis"``
    (printed eq. 4.31, σ_ζ,eff = σ_μ(p)·Lω0·Δτ), every other rule → ``"ito"``."""
    return "thesis" if rule == "thesis" else "ito"


def process_rule_of(rule: str) -> str:
    """The process model's σ_ζ rule behind a white-intensity rule (``thesis`` uses σ_ζ = σ_μ(p))."""
    return "sigma_mu" if rule == "thesis" else rule


def with_white_intensity(process: FrictionProcessModel, rule: str) -> FrictionProcessModel:
    """The process model with its σ_ζ rule set to ``rule`` (``"sigma_mu"`` | ``"spectral_level"``;
    ``"thesis"`` uses the process rule ``"sigma_mu"`` and scales it in :func:`simulate`).

    Only the white-noise model's intensity ``process.sigma_zeta(p)`` changes; the mean and the
    realisations of the contact-analysis process do not depend on the rule.
    """
    if rule not in WHITE_INTENSITY_RULES:
        raise CaseError(f"white-noise intensity rule must be one of {list(WHITE_INTENSITY_RULES)}, got {rule!r}")
    rule = process_rule_of(rule)
    if getattr(process, "sigma_zeta_rule", None) == rule:
        return process
    if not (dataclasses.is_dataclass(process) and any(f.name == "sigma_zeta_rule"
                                                      for f in dataclasses.fields(process))):
        raise CaseError(f"the friction-process model {type(process).__name__} has no sigma_zeta_rule; "
                        "use white_intensity = 'sigma_mu'")
    try:
        out: FrictionProcessModel = dataclasses.replace(process, sigma_zeta_rule=rule)
    except ValueError as exc:
        raise CaseError(f"white-noise intensity rule {rule!r}: {exc}") from None
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
    white_intensity: str | None = "sigma_mu",
    process_level: str = "sigma_mu",
    process_length: float | None = None,
) -> tuple[Any, str]:
    """The friction-process model of a case and its source (``"preset:brake"``, ``"file:…"``).

    A ``process_file`` replaces the preset's model; ``process_level`` ``"psd_level"`` (reproduction
    mode, presets only) replaces it by :class:`~stochfric.process.presets.PsdLevelProcessModel`;
    ``white_intensity`` (``None``: keep the model's own rule) sets the σ_ζ rule; ``process_length``
    regenerates over another length.  ``(None, "")`` without preset and file.
    """
    if process_level not in PROCESS_LEVELS:
        raise CaseError(f"process level must be one of {list(PROCESS_LEVELS)}, got {process_level!r}")
    if process_level != "sigma_mu" and (process_file is not None or preset is None):
        raise CaseError("process_level 'psd_level' rescales a preset's process; it cannot be combined with "
                        "a process file (process_file / --process): use a preset")
    if process_file is not None:
        process: Any = load_process_model(process_file)
        source = f"file:{process_file}"
    elif preset is not None:
        process = process_with_level(preset, process_level)
        source = f"preset:{preset.name}" + ("" if process_level == "sigma_mu" else f" ({process_level})")
    else:
        if white_intensity is not None:
            raise CaseError("--white-intensity needs a friction-process model (--preset or --process)")
        return None, ""
    if white_intensity is not None:
        process = with_white_intensity(process, white_intensity)
    if process_length is not None:
        process = with_length(process, process_length)
    return process, source


def physical_parameters(
    mass: float, stiffness: float, belt_speed: float, normal_force: float, *,
    damping_ratio: float | None = None, damping_coefficient: float | None = None,
    forcing_amplitude: float = 0.0, eta: float = 0.0, contact_area: float | None = None,
) -> OscillatorParameters:
    """Dimensionless parameters (4.6/4.7) from SI input; Ω = η ω0 and η kept exactly as given."""
    phys = PhysicalParameters(
        mass=mass, stiffness=stiffness, belt_speed=belt_speed, normal_force=normal_force,
        damping_coefficient=damping_coefficient, damping_ratio=damping_ratio,
        forcing_amplitude=forcing_amplitude, contact_area=contact_area,
    )
    phys = dataclasses.replace(phys, forcing_frequency=eta * phys.omega0)  # ω0 of the validated m, c
    # η exactly as given (Ω = η ω0 and back may differ in the last bit)
    return phys.to_dimensionless().replace(eta=float(eta))


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
            f"negative at high sliding speed; give a larger static coefficient (--mu0 {mu_fit + 0.2:.2g} or "
            "more) or another law (--friction-law III)"
        )
    return pressure_law(mu_fit, mu0=mu0)


@dataclass(frozen=True)
class Case:
    """One oscillator case: parameters, friction law, process model and time grid.

    ``process`` is ``None`` for a case without a friction-process model (dimensionless input
    with a Table 4.1 law); ``sigma_zeta`` an explicit white-noise intensity (else the process's).
    """

    params: OscillatorParameters
    law: FrictionLaw
    process: Any
    tau_end: float
    dt: float
    preset: Preset | None = None
    process_source: str = ""
    white_intensity: str | None = None
    sigma_zeta: float | None = None
    process_level: str = "sigma_mu"

    def modes(self, model: str) -> dict[str, str]:
        """The case's modelling modes as plain strings (recorded in every output): the σ_ζ rule of
        the white-noise model (``given`` for an explicit σ_ζ) and the contact process's level."""
        rule = ("given" if self.sigma_zeta is not None else self.white_intensity
                or str(getattr(self.process, "sigma_zeta_rule", "sigma_mu")))
        out = {"white_intensity": rule if model == "white" else "n/a",
               "process_level": self.process_level if model == "contact" else "n/a"}
        if model == "white":
            out["white_model"] = WHITE_MODEL_STANDING
        return out

    def white_increment(self, model: str) -> str:
        """``"thesis"`` for the white-noise model under the printed-(4.31) rule, else ``"ito"``."""
        return white_increment_of(self.white_intensity or "") if model == "white" else "ito"

    def simulate_kwargs(self, model: str) -> dict[str, Any]:
        """The case's keyword arguments of :func:`~stochfric.oscillator.integrate.simulate`."""
        return {"model": model, "law": self.law, "process": self.process, "sigma_zeta": self.sigma_zeta,
                "tau_end": self.tau_end, "dt": self.dt, "white_increment": self.white_increment(model)}


@dataclass(frozen=True)
class CaseSetup:
    """What a study keeps fixed over its grid: preset (m, c, v0, A), process model, time grid."""

    preset: Preset
    process: FrictionProcessModel
    process_source: str
    tau_end: float
    dt: float
    white_intensity: str = "sigma_mu"
    process_level: str = "sigma_mu"

    @property
    def white_increment(self) -> str:
        """``"thesis"`` for the printed-(4.31) reproduction mode, else ``"ito"``."""
        return white_increment_of(self.white_intensity)

    def parameters(
        self, normal_force: float, damping_ratio: float, forcing_amplitude: float = 0.0, eta: float = 0.0
    ) -> OscillatorParameters:
        """Dimensionless parameters (4.6/4.7) at N [N], D, Q [N] and η = Ω/ω0."""
        pre = self.preset
        return physical_parameters(pre.mass, pre.stiffness, pre.belt_speed, normal_force,
                                   damping_ratio=damping_ratio, forcing_amplitude=forcing_amplitude, eta=eta,
                                   contact_area=pre.contact_area_m2)

    def case(
        self, normal_force: float, damping_ratio: float, forcing_amplitude: float = 0.0, eta: float = 0.0
    ) -> Case:
        """The :class:`Case` at N [N], D, Q [N], η: these parameters and the pressure law (4.13)."""
        params = self.parameters(normal_force, damping_ratio, forcing_amplitude, eta)
        return Case(params=params, law=law_for(self.process, params), process=self.process,
                    tau_end=self.tau_end, dt=self.dt, preset=self.preset, process_source=self.process_source,
                    white_intensity=self.white_intensity)

    def sigma_zeta(self, normal_force: float) -> float:
        """σ_ζ of the white-noise model at N [N] (p = N/A) under the setup's σ_ζ rule (for ``thesis``:
        the nominal σ_ζ = σ_μ(p); see :meth:`sigma_zeta_effective`)."""
        return float(self.process.sigma_zeta(float(normal_force) / self.preset.contact_area_m2))

    def sigma_zeta_effective(self, normal_force: float) -> float:
        """The intensity the white-noise SDE actually uses: σ_ζ, or σ_ζ·Lω0·Δτ (L = 1 m) in ``thesis``
        mode (printed eq. 4.31, docs/oscillator.md)."""
        s = self.sigma_zeta(normal_force)
        return s * self.preset.omega0 * self.dt if self.white_increment == "thesis" else s

    def describe(self) -> dict[str, Any]:
        """JSON-compatible record of the case (for provenance)."""
        pre = self.preset
        return {
            "preset": pre.name,
            "mass_kg": pre.mass,
            "stiffness_n_per_m": pre.stiffness,
            "belt_speed_m_s": pre.belt_speed,
            "contact_area_m2": pre.contact_area_m2,
            "omega0_rad_s": pre.omega0,
            "gamma0": pre.gamma0,
            "process_source": self.process_source,
            "process": self.process.to_dict(),
            "tau_end": self.tau_end,
            "dt": self.dt,
            "white_intensity": self.white_intensity,
            "white_increment": self.white_increment,
            "process_level": self.process_level,
        }


def _preset(name: str) -> Preset:
    try:
        return get_preset(name)
    except ValueError as exc:
        raise CaseError(str(exc)) from None


def case_setup(
    preset: str = "brake",
    process_file: str | Path | None = None,
    tau_end: float | None = None,
    dt: float | None = None,
    white_intensity: str = "sigma_mu",
    process_level: str = "sigma_mu",
) -> CaseSetup:
    """Resolve a preset name and an optional friction-process model file (``--process FILE``);
    the σ_ζ rule ``white_intensity`` is applied to the process model (it overrides a file's own).
    ``process_level`` ``"psd_level"`` (reproduction mode, presets only) replaces the preset's
    process by :class:`~stochfric.process.presets.PsdLevelProcessModel`."""
    pre = _preset(preset)
    process, source = resolve_process(pre, process_file, white_intensity=white_intensity,
                                      process_level=process_level)
    te = float(tau_end) if tau_end is not None else pre.tau_end
    step = float(dt) if dt is not None else pre.dt
    return CaseSetup(preset=pre, process=process, process_source=source, tau_end=te, dt=step,
                     white_intensity=white_intensity, process_level=process_level)


def _parameters(
    pre: Preset | None, *, gamma0: float | None, n: float | None, normal_force: float | None,
    damping_ratio: float | None, damping_coefficient: float | None, q: float | None, eta: float | None,
    forcing_amplitude: float | None, mass: float | None, stiffness: float | None, belt_speed: float | None,
    contact_area: float | None, omega0: float | None,
) -> OscillatorParameters:
    """The parameters of :func:`build_case` from a preset, SI input or dimensionless input."""
    if q is not None and forcing_amplitude is not None:
        raise CaseError("give the forcing as --forcing-amplitude Q [N] or --q, not both")
    if damping_ratio is not None and damping_coefficient is not None:
        raise CaseError("give the damping as --damping D or --damping-coefficient, not both")
    if normal_force is not None and n is not None:
        raise CaseError("give the normal force as --normal-force [N] or --n, not both")
    if pre is not None or any(v is not None for v in (mass, stiffness, belt_speed)):
        if gamma0 is not None or omega0 is not None:
            raise CaseError(
                "--gamma0/--omega0 are for dimensionless input; with a preset or physical "
                "parameters set --belt-speed, --mass, --stiffness instead"
            )
        m_ = mass if mass is not None else (pre.mass if pre else None)
        c_ = stiffness if stiffness is not None else (pre.stiffness if pre else None)
        v_ = belt_speed if belt_speed is not None else (pre.belt_speed if pre else None)
        a_ = contact_area if contact_area is not None else (pre.contact_area_m2 if pre else None)
        missing = [k for k, v in (("--mass", m_), ("--stiffness", c_), ("--belt-speed", v_)) if v is None]
        if missing:
            raise CaseError(f"physical parameters need {', '.join(missing)} (or a --preset)")
        assert m_ is not None and c_ is not None and v_ is not None
        if n is not None:
            nf = n * c_
        elif normal_force is not None:
            nf = normal_force
        elif pre is not None:
            nf = pre.default_normal_force_n
        else:
            raise CaseError("give the normal force --normal-force N [newtons] or --n")
        if damping_ratio is None and damping_coefficient is None:
            damping_ratio = pre.study_parameters.get("damping_undamped", 0.0) if pre else 0.0
        return physical_parameters(m_, c_, v_, nf, damping_ratio=damping_ratio,
                                   damping_coefficient=damping_coefficient,
                                   forcing_amplitude=q * c_ if q is not None else (forcing_amplitude or 0.0),
                                   eta=eta or 0.0, contact_area=a_)
    if normal_force is not None or forcing_amplitude is not None or damping_coefficient is not None:
        raise CaseError(
            "--normal-force, --forcing-amplitude and --damping-coefficient are in SI units and "
            "need --mass/--stiffness/--belt-speed or a --preset; for dimensionless input use "
            "--n, --q, --damping"
        )
    if gamma0 is None or n is None:
        raise CaseError(
            "give either --preset {brake,sheet}, physical parameters (--mass --stiffness "
            "--belt-speed --normal-force), or dimensionless --gamma0 and --n"
        )
    return OscillatorParameters(
        gamma0=gamma0, n=n, damping_ratio=damping_ratio or 0.0, q=q or 0.0, eta=eta or 0.0,
        omega0=omega0 if omega0 is not None else 1.0, contact_area=contact_area,
    )


def build_case(
    preset: str | None = None,
    *,
    normal_force: float | None = None,
    n: float | None = None,
    damping_ratio: float | None = None,
    damping_coefficient: float | None = None,
    forcing_amplitude: float | None = None,
    q: float | None = None,
    eta: float | None = None,
    mass: float | None = None,
    stiffness: float | None = None,
    belt_speed: float | None = None,
    contact_area: float | None = None,
    gamma0: float | None = None,
    omega0: float | None = None,
    process_file: str | Path | None = None,
    process_length: float | None = None,
    white_intensity: str | None = None,
    process_level: str | None = None,
    friction_law: str | None = None,
    mu0: float = MU0,
    model: str = "deterministic",
    sigma_zeta: float | None = None,
    tau_end: float | None = None,
    dt: float | None = None,
) -> Case:
    """The one :class:`Case` of a simulation, from any input form (the options of ``stochfric simulate``).

    Parameters: a ``preset`` (its m, c, v0, A, default N and D = 5·10⁻⁶ unless given; m, c, v0, A
    may be overridden), physical SI input (``mass``, ``stiffness``, ``belt_speed``, ``normal_force``
    or ``n``, ``damping_ratio`` or ``damping_coefficient``, ``forcing_amplitude`` or ``q``,
    ``eta``, ``contact_area``), or dimensionless input (``gamma0``, ``n``, ``omega0``).  The
    friction law defaults to the pressure law (4.13) with ``mu0`` whenever a process model gives
    E[μ](p), else Table 4.1 law III.  ``model`` is only checked (white and contact need a process
    model, white may have ``sigma_zeta`` instead).  τ_end, Δτ default to the preset's (else 50,
    0.005).  Raises :class:`CaseError` with a message that names the option to change.
    """
    pre = _preset(preset) if preset else None
    params = _parameters(
        pre, gamma0=gamma0, n=n, normal_force=normal_force, damping_ratio=damping_ratio,
        damping_coefficient=damping_coefficient, q=q, eta=eta, forcing_amplitude=forcing_amplitude, mass=mass,
        stiffness=stiffness, belt_speed=belt_speed, contact_area=contact_area, omega0=omega0,
    )
    if white_intensity is not None and sigma_zeta is not None:
        raise CaseError("give either --sigma-zeta or --white-intensity, not both")
    process, source = resolve_process(pre, process_file, white_intensity=white_intensity,
                                      process_level=process_level or "sigma_mu", process_length=process_length)
    law_name = friction_law or ("pressure" if process is not None and params.pressure_pa is not None else "III")
    if law_name == "pressure":
        if process is None or params.pressure_pa is None:
            raise CaseError(
                "the pressure law (4.13) needs E[μ](p) from a friction-process model and the "
                "pressure p = N/A: use --preset, or --process FILE with physical parameters and "
                "--contact-area"
            )
        law = law_for(process, params, mu0)
    else:
        law = get_law(law_name)
    if model != "deterministic" and process is None and not (model == "white" and sigma_zeta is not None):
        raise CaseError(
            f"the {model} model needs a friction-process model: use --preset or --process FILE"
            + (" or --sigma-zeta" if model == "white" else "")
        )
    return Case(
        params=params, law=law, process=process,
        tau_end=tau_end if tau_end is not None else (pre.tau_end if pre else 50.0),
        dt=dt if dt is not None else (pre.dt if pre else 0.005),
        preset=pre, process_source=source, white_intensity=white_intensity, sigma_zeta=sigma_zeta,
        process_level=process_level or "sigma_mu",
    )

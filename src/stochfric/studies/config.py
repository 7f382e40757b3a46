"""Validated study configurations (pydantic; the boundary for the CLI and ``study.toml``).

Every study takes one of these frozen models.  Fields left ``None`` take the thesis's
values from the preset (method §6 table): the study forces, D = 5·10⁻⁶ undamped, τ_end = 50,
Δτ = 0.005.  Grids (plural names: ``normal_forces``, ``damping_ratios``; a thesis symbol keeps its
name: ``eta``, ``forcing_q``) accept ``"START:STOP:NUM"`` (inclusive), ``"a,b,c"`` or a list.
Forces are in newtons (docs/glossary.md: units).

The choices are the library's enums (:mod:`stochfric.oscillator.options`,
:class:`~stochfric.friction_process.presets.ProcessLevel`).  Two modelling choices of method §5 are fields of
every study: ``path_coordinate`` (where the contact-analysis process is read: ``"mass"`` = the
thesis's global coordinate of the mass, ``"relative"`` = the relative path) and ``white_intensity``
(the σ_ζ rule of the white-noise model: ``"sigma_mu"`` = the thesis's σ_ζ = σ_μ(p),
``"spectral_level"`` = white noise with the process's low-frequency spectral level, ``"thesis"`` =
the printed-(4.31) reproduction mode σ_ζ,eff = σ_μ(p)·Lω0·Δτ, whose intensity depends on Δτ;
docs/oscillator.md); the study applies the latter to its process model (preset or ``process_file``).

:meth:`StudyConfig.hash_config` is what the checkpoint hash covers: every field (they all
change the numbers) plus the content of a ``process_file``.
"""

from __future__ import annotations

import json
from collections.abc import Callable
from contextvars import ContextVar
from pathlib import Path
from typing import Annotated, Any, Literal, TypeVar

from pydantic import BaseModel, BeforeValidator, ConfigDict, Field, ValidationError, field_validator, model_validator

from stochfric.io_utils import read_text_checked

from ..errors import InputError
from ..friction_process.presets import ProcessLevel
from ..oscillator.machine import load_machine
from ..oscillator.options import Integrator, Model, PathCoordinate, WhiteIntensity
from ..oscillator.presets import PresetName
from .errors import StudyConfigError
from .grids import STICK_WINDOW, parse_grid

Grid = Annotated[tuple[float, ...], BeforeValidator(parse_grid)]

_T = TypeVar("_T")


def _distinct(values: tuple[_T, ...], what: str, example: str = "") -> tuple[_T, ...]:
    """``values`` when it holds at least one value and none twice; else the ``ValueError`` that
    names ``what`` one value is (``example``: how to give them)."""
    if not values:
        raise ValueError(f"give at least one {what}{example}")
    if len(set(values)) != len(values):
        raise ValueError(f"a {what} is listed twice: {', '.join(str(x) for x in values)}")
    return values


def _one_of(*allowed: Integrator) -> Callable[[Any], Any]:
    """A validator, run before the enum's own, that accepts only the integrators ``allowed`` (so that a
    wrong name is told the choices of this field, not every integrator of the package)."""
    def check(value: Any) -> Any:
        if not isinstance(value, str) or value not in {str(a) for a in allowed}:
            raise ValueError("Input should be " + " or ".join(f"'{a}'" for a in allowed))
        return value
    return check


#: The scheme of the deterministic and contact models, and of the white-noise SDE.
OdeIntegrator = Annotated[Integrator, BeforeValidator(_one_of(Integrator.EULER, Integrator.ACCURATE))]
SdeIntegrator = Annotated[Integrator, BeforeValidator(_one_of(Integrator.EULER, Integrator.MILSTEIN))]


def parse_risk_levels(spec: Any) -> Any:
    """Risk levels from ``"0.1,0.01"``, a number or a list (values checked by the config)."""
    if isinstance(spec, bool):
        raise ValueError("risk levels must be numbers, not a boolean")
    if isinstance(spec, int | float):
        return (float(spec),)
    if isinstance(spec, str):
        parts = [t.strip() for t in spec.split(",")]
        if not any(parts):
            raise ValueError("give at least one risk level, e.g. 0.1,0.01")
        try:
            return tuple(float(t) for t in parts if t)
        except ValueError:
            raise ValueError(f"{spec!r} is not a comma-separated list of numbers, e.g. 0.1,0.01") from None
    return spec


#: True while a larger model (a ``study.toml``) validates study configs: their errors stay pydantic's,
#: so that the file's error names the place (``study[0].field``).
NESTED_VALIDATION: ContextVar[bool] = ContextVar("NESTED_VALIDATION", default=False)


class StudyConfig(BaseModel):
    """Fields shared by all studies.  A value the validation refuses raises
    :class:`~stochfric.studies.errors.StudyConfigError` (every problem on one line)."""

    model_config = ConfigDict(frozen=True, extra="forbid")

    def __init__(self, **data: Any) -> None:
        try:
            super().__init__(**data)
        except ValidationError as exc:
            if NESTED_VALIDATION.get():  # inside a study.toml: pydantic collects the errors with their place
                raise
            raise StudyConfigError(exc) from None

    preset: PresetName = PresetName.BRAKE
    machine: str | None = Field(
        default=None, description="machine description (a TOML file, docs/machines.md, or a shipped name: brake, "
                                  "sheet, example-calliper) instead of the preset; a machine that is not a thesis "
                                  "preset needs a process_file")
    process_file: str | None = Field(
        default=None, description="friction-process model file (JSON) instead of the preset's"
    )
    allow_extrapolation: bool = Field(
        default=False, description="use the process model outside the pressures it was fitted on (every output is "
                                   "stamped) instead of refusing the study")
    models: tuple[Model, ...] = tuple(Model)
    runs: int = Field(default=10, ge=1, le=100_000)
    seed: int = Field(default=0, ge=0)
    tau_end: float | None = Field(default=None, gt=0)
    dt: float | None = Field(default=None, gt=0)
    integrator: OdeIntegrator = Integrator.EULER
    sde_integrator: SdeIntegrator = Integrator.EULER
    path_coordinate: PathCoordinate = Field(
        default=PathCoordinate.MASS,
        description="where the contact process is read: mass (thesis text) | relative | position (reproduction "
                    "mode: at x1, eq. 4.36/4.38 as printed; euler only)"
    )
    white_intensity: WhiteIntensity = Field(
        default=WhiteIntensity.SIGMA_MU,
        description="σ_ζ rule of the white-noise model: sigma_mu (thesis rule, consistent Itô model) | "
                    "spectral_level | thesis (printed eq. 4.31: σ_ζ,eff = σ_μ(p)·Lω0·Δτ, a Δτ-dependent "
                    "reproduction mode)",
    )
    process_level: ProcessLevel = Field(
        default=ProcessLevel.SIGMA_MU,
        description="variance of the contact process: sigma_mu (σ_μ(p)², method §4d) | psd_level (reproduction "
                    "mode: from the thesis's E[S](p) fit, normalised by its 0.08-at-0.5-MPa check)")
    stick_window: float = Field(default=STICK_WINDOW, ge=0.0, lt=1.0)
    x0: tuple[float, float] | None = None

    @model_validator(mode="before")
    @classmethod
    def _no_booleans_as_numbers(cls, data: Any) -> Any:
        """``seed = true`` is a slip, not seed 1: a boolean is refused wherever the field is not a switch."""
        if isinstance(data, dict):
            for key, value in data.items():
                field = cls.model_fields.get(key)
                if isinstance(value, bool) and field is not None and field.annotation is not bool:
                    raise ValueError(f"{key} must be a number, not the boolean {str(value).lower()}")
        return data

    @field_validator("models")
    @classmethod
    def _unique_models(cls, v: tuple[Model, ...]) -> tuple[Model, ...]:
        return _distinct(v, "model")

    @field_validator("machine")
    @classmethod
    def _machine_exists(cls, v: str | None) -> str | None:
        """A machine that cannot be read is refused with the config, before any work."""
        if v is not None:
            try:
                load_machine(v)
            except InputError as exc:
                raise ValueError(str(exc)) from None
        return v

    def hash_config(self) -> dict[str, Any]:
        """Everything that changes the numbers (for the checkpoint key)."""
        d = self.model_dump(mode="json")
        if self.process_file is not None:
            try:
                d["process_file_content"] = json.loads(read_text_checked(self.process_file))
            except (OSError, ValueError):
                d["process_file_content"] = None
        if self.machine is not None:  # the machine's content, not its path, changes the numbers
            try:
                d["machine_content"] = load_machine(self.machine).to_dict()
            except InputError:
                d["machine_content"] = None
        return d

    def case_label(self) -> str:
        """A short name of the case for labels and file names: the machine's file stem or name, else the preset."""
        return Path(self.machine).stem if self.machine is not None else str(self.preset)

    def case_source(self) -> str | PresetName:
        """What the case setup is built from: the machine when given, else the preset."""
        return self.machine if self.machine is not None else self.preset


class DampingConfig(StudyConfig):
    """Damping study (method §6.2, thesis 4.2.2/4.3.2): grid D × N."""

    kind: Literal["damping"] = "damping"
    normal_forces: Grid | None = Field(default=None, description="normal forces N [N] (default: the preset's "
                                                                   "damping-study force)")
    damping_ratios: Grid = Field(default_factory=lambda: parse_grid("0.05:0.25:41"), description="damping ratios D")
    common_random_numbers: bool = True
    confidence: float = Field(default=0.95, gt=0, lt=1)
    p_detect: float = Field(default=0.1, gt=0, lt=1)
    risk_levels: Annotated[tuple[float, ...], BeforeValidator(parse_risk_levels)] = Field(
        default=(0.1, 0.01),
        description="risk levels α of D_max(α), the largest D with P(stick-slip) >= α (each in (0, 1))")
    phase_normal_force: float | None = Field(
        default=None, gt=0,
        description="N [N] of the phase diagrams over D (default: the preset's damping-study force if it is "
                    "one of the normal forces, else the middle force)",
    )
    phase_damping_ratios: Grid | None = Field(
        default=None, description="D values of the phase diagrams (default: chosen from the results, see docs)"
    )
    phase_runs: int = Field(default=3, ge=0, le=1000, description="runs kept per D (stochastic models); 0: none")
    save_every: int = Field(default=10, ge=1, description="keep every k-th step of the phase trajectories")
    refine: bool = Field(
        default=False,
        description="close the D_max(α) interval adaptively: add runs at the grid D whose Clopper–Pearson band "
                    "still holds α between the interval's ends, until it is at most target_steps grid steps wide or "
                    "run_budget is spent (docs/studies.md, 'Closing the D_max(α) interval'); false: the thesis's "
                    "fixed runs")
    refine_risk_level: float | None = Field(
        default=None, gt=0, lt=1, allow_inf_nan=False,
        description="α whose D_max(α) interval the refinement closes (one of risk_levels; default: the first)")
    target_steps: int = Field(default=2, ge=0, le=1000,
                              description="width [grid steps] at which a D_max(α) interval counts as closed")
    max_runs_per_cell: int = Field(default=1000, ge=2, le=100_000,
                                   description="most runs of one grid cell under refinement")
    run_budget: int = Field(default=20_000, ge=1, le=100_000_000,
                            description="most runs the refinement adds in all (models, forces and D together)")

    @model_validator(mode="after")
    def _refinement(self) -> DampingConfig:
        """The refined α must be a risk level, and refinement must be able to add runs."""
        if self.refine_risk_level is not None and self.refine_risk_level not in self.risk_levels:
            raise ValueError(f"refine_risk_level (--refine-risk-level) {self.refine_risk_level:g} is not one of the "
                             f"risk levels ({', '.join(f'{a:g}' for a in self.risk_levels)})")
        if self.refine and self.max_runs_per_cell <= self.runs:
            raise ValueError(f"max_runs_per_cell (--max-runs-per-cell) {self.max_runs_per_cell} must exceed runs "
                             f"(--runs) {self.runs} to refine")
        return self

    @property
    def refined_risk_level(self) -> float:
        """The α the refinement closes: ``refine_risk_level``, else the first risk level."""
        return float(self.refine_risk_level if self.refine_risk_level is not None else self.risk_levels[0])

    @field_validator("damping_ratios")
    @classmethod
    def _damping_range(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        if any(not 0 <= d < 1 for d in v):
            raise ValueError("damping ratios must lie in [0, 1)")
        if list(v) != sorted(v):
            raise ValueError("the damping grid must be increasing")
        return v

    @field_validator("risk_levels")
    @classmethod
    def _risk_levels(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        bad = [a for a in v if not 0.0 < a < 1.0]
        if bad:
            raise ValueError(f"risk levels must lie in (0, 1) (a probability, 0.1 = 10 %), got {bad[0]:g}")
        return _distinct(v, "risk level", ", e.g. 0.1,0.01")

    def hash_config(self) -> dict[str, Any]:
        """As :meth:`StudyConfig.hash_config` without ``risk_levels``: they change the analysis only, so
        checkpoints of the same simulations resume under other risk levels.  With ``refine`` the refined α (the
        first risk level unless given) is in: it picks the refinement's runs."""
        d = super().hash_config()
        d.pop("risk_levels", None)
        if self.refine:
            d["refine_risk_level"] = self.refined_risk_level
        return d

    @field_validator("phase_damping_ratios")
    @classmethod
    def _phase_damping_range(cls, v: tuple[float, ...] | None) -> tuple[float, ...] | None:
        if v is None:
            return v
        if any(not 0 <= d < 1 for d in v):
            raise ValueError("phase-diagram damping ratios must lie in [0, 1)")
        return tuple(sorted(_distinct(v, "phase-diagram damping ratio")))


class _ForcedConfig(StudyConfig):
    """Fields of the studies of the forced oscillator: q = Q/(cL), η = Ω/ω0 (grids, >= 0), one D."""

    forcing_q: Grid = (5e-5, 5e-4)
    eta: Grid = Field(default_factory=lambda: parse_grid("0:3:61"))
    #: The forced studies run on the converged integrator by default: Euler at the thesis's
    #: Δτ = 0.005 locks spurious cycles at some η (brake 4000 N, q = 5e-4, η = 1.2: λ = -0.86 against
    #: +0.28 converged).  ``euler`` is their reproduction mode (recorded in the outputs).
    integrator: OdeIntegrator = Field(
        default=Integrator.ACCURATE,
        description="deterministic and contact models: accurate (adaptive DOP853 with events, default) | euler "
                    "(reproduction mode: the thesis's fixed Δτ)")
    damping_ratio: float | None = Field(default=None, ge=0, lt=1, description="damping ratio D")

    @model_validator(mode="before")
    @classmethod
    def _position_runs_on_euler(cls, data: Any) -> Any:
        """The reproduction mode ``path_coordinate = "position"`` exists for the fixed-step Euler scheme only:
        without an explicit integrator it runs on ``euler`` (recorded as a reproduction); an explicit
        ``accurate`` with it is refused, saying what to change."""
        if not isinstance(data, dict) or data.get("path_coordinate") != "position":
            return data
        if data.get("integrator") is None:
            return {**data, "integrator": "euler"}
        if data["integrator"] == "accurate":
            raise ValueError("path_coordinate 'position' (a reproduction mode) runs on the fixed-step Euler scheme "
                             "only: give integrator = 'euler' (--integrator euler) or another path coordinate")
        return data

    @field_validator("eta", "forcing_q")
    @classmethod
    def _non_negative(cls, v: tuple[float, ...]) -> tuple[float, ...]:
        if any(x < 0 for x in v):
            raise ValueError("values must be >= 0")
        return v


def integrator_record(config: StudyConfig) -> dict[str, str]:
    """The integrators a forced study ran with, for its JSON and dataset attributes: ``integrator``
    (deterministic, contact), ``sde_integrator`` (white noise) and ``integrator_mode``: ``converged``
    (``accurate``) or ``reproduction`` (``euler`` at a fixed Δτ, the thesis's scheme)."""
    mode = "converged" if config.integrator == "accurate" else "reproduction"
    return {"integrator": str(config.integrator), "sde_integrator": str(config.sde_integrator),
            "integrator_mode": mode}


class ForcingConfig(_ForcedConfig):
    """Forcing study (method §6.3, thesis 4.2.3/4.3.3): bifurcation data over η."""

    kind: Literal["forcing"] = "forcing"
    normal_force: float | None = Field(default=None, gt=0, description="normal force N [N] (default: the "
                                                                       "preset's forcing-study force)")


class LyapunovConfig(_ForcedConfig):
    """Largest Lyapunov exponent (method §6.4, eq. 4.43/4.44) over η and N."""

    kind: Literal["lyapunov"] = "lyapunov"
    normal_forces: Grid | None = Field(default=None, description="normal forces N [N] (default: the preset's "
                                                                   "normal-force-study forces)")
    eta: Grid = Field(default_factory=lambda: parse_grid("0.1:3:30"))
    perturbation: float = Field(default=1e-6, gt=0, description="shift of the initial x1 of the comparison run")
    linearity_tolerance: float = Field(
        default=0.1, gt=0, lt=1,
        description="a pair is linear when the twin run (2δ) separates by 2w within this relative tolerance")


class NormalForceConfig(StudyConfig):
    """Normal-force study (method §6.1, thesis 4.2.1/4.3.1)."""

    kind: Literal["normal-force"] = "normal-force"
    normal_forces: Grid | None = Field(default=None, description="normal forces N [N] (default: the preset's "
                                                                   "normal-force-study forces)")
    damping_ratios: Grid | None = Field(default=None, description="damping ratios D (default: the preset's "
                                                                    "undamped and damped D)")
    runs: int = Field(default=30, ge=1, le=100_000)
    phase_runs: int = Field(default=5, ge=0)
    save_every: int = Field(default=10, ge=1)


AnyStudyConfig = Annotated[
    DampingConfig | ForcingConfig | LyapunovConfig | NormalForceConfig, Field(discriminator="kind")
]

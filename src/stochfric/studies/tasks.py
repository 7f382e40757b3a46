"""Tasks of the studies (method §6): what one task is, where its random numbers come from,
and how it runs.

A study is a list of independent *tasks*; one task is one :func:`simulate` call that batches
many parameter sets (e.g. every damping ratio D of one normal force N and one friction model).
A task is described completely by a picklable, frozen :class:`TaskSpec`, so that it can run in
this process, in a local worker process or on a Dask worker and give the same numbers.

**Seeds by cell.**  Run ``r`` of a cell (one parameter set of a task: model, N, D, q, η and the
case) draws from spawn key ``(*cell key, r)`` of the study's root seed, where the cell key is a
hash of the model and the cell's own parameter values (:func:`cell_stream_key`), never of its
position in the grid, the task it is batched in, the executor or the order of execution: a cell
rerun alone, or inside a larger grid, gives the same numbers bit for bit.  Common random numbers
(the damping study's default) leave D out of the key, so every D of one (model, N) sees the same
noise; the Lyapunov study's reference, perturbed and twin runs have the same parameters and so
the same key.

A study's config becomes its case setup by :func:`setup_for` (preset, process model under its
rules, time grid: :func:`stochfric.oscillator.case.case_setup`), each cell a
:class:`~stochfric.oscillator.case.Case` of that setup; :func:`model_choices` records the modelling
choices with every result.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.case import WHITE_MODEL_STANDING, Case, CaseSetup, case_setup
from ..oscillator.integrate import simulate
from ..oscillator.options import ExecutionOptions, IntegrationOptions, Integrator, Model, NoiseOptions, OutputOptions
from ..oscillator.parameters import OscillatorParameters
from .config import StudyConfig
from .errors import StudyError

#: Version of the cell-key rule, the first word hashed (a new rule gives new streams).
CELL_KEY_RULE = "stochfric.cell/1"


def cell_stream_key(model: str, params: OscillatorParameters, shared: Sequence[str] = ()) -> tuple[int, int]:
    """The stream key of a study cell: two 32-bit words of a BLAKE2b hash of the model and every
    field of ``params`` (exact float values), with the fields named in ``shared`` left out (common
    random numbers over that axis).  Depends on nothing else (seed rule: module docstring)."""
    fields = {k: (None if k in shared or v is None else float(v).hex())
              for k, v in sorted(params.to_dict().items())}
    text = json.dumps([CELL_KEY_RULE, str(model), fields], sort_keys=True, separators=(",", ":"))
    word = int.from_bytes(hashlib.blake2b(text.encode("utf-8"), digest_size=8).digest(), "little")
    return word & 0xFFFFFFFF, word >> 32


@dataclass(frozen=True)
class TaskSpec:
    """One independent unit of a study: a single batched :func:`simulate` call.

    ``cases`` are the parameter sets of the call, each a :class:`~stochfric.oscillator.case.Case` of
    the study's setup (its law, process model, time grid and σ_ζ rule); ``x0`` one initial state per
    set (or ``None``: sticking at the origin, ``(0, γ0)``); ``noise`` carries the cells' stream keys and
    the path coordinate, ``integration`` the integrator.  ``keep_trajectory_runs`` > 0 keeps the
    decimated trajectories (every ``save_every``-th step) of that many runs (phase diagrams).
    """

    index: int
    label: str
    model: Model
    cases: tuple[Case, ...]
    runs: int
    seed: int
    x0: tuple[tuple[float, float], ...] | None = None
    noise: NoiseOptions = field(default_factory=NoiseOptions)
    integration: IntegrationOptions = field(default_factory=IntegrationOptions)
    keep_trajectory_runs: int = 0
    save_every: int = 10
    extra: dict[str, Any] = field(default_factory=dict, compare=False)

    @property
    def params(self) -> tuple[OscillatorParameters, ...]:
        """The parameter sets of the task."""
        return tuple(c.params for c in self.cases)


def task_for(
    config: StudyConfig,
    setup: CaseSetup,
    *,
    index: int,
    label: str,
    model: Model | str,
    params: Sequence[OscillatorParameters],
    runs: int | None = None,
    x0: tuple[tuple[float, float], ...] | str | None = "config",
    common_random_numbers: bool = False,
    keep_trajectory_runs: int = 0,
    save_every: int = 10,
) -> TaskSpec:
    """A :class:`TaskSpec` with the fields every study fills the same way from its config and setup.

    ``runs`` defaults to :func:`runs_for` ``(model, config.runs)``; ``x0="config"`` repeats
    ``config.x0`` for every parameter set (``None`` if the config has none); the integrator
    follows :func:`integrator_for`, the cases, time grid and σ_ζ rule the setup.
    ``common_random_numbers`` leaves D out of the cells' stream keys (:func:`cell_stream_key`).
    """
    ps = tuple(params)
    m = Model(model)
    shared = ("damping_ratio",) if common_random_numbers else ()
    start = (None if config.x0 is None else tuple(config.x0 for _ in ps)) if isinstance(x0, str) else x0
    return TaskSpec(
        index=index, label=label, model=m, cases=tuple(setup.case_of(p) for p in ps),
        runs=runs_for(m, config.runs) if runs is None else runs, seed=config.seed, x0=start,
        noise=NoiseOptions(stream_keys=tuple(cell_stream_key(m, p, shared) for p in ps),
                           path_coordinate=config.path_coordinate),
        integration=IntegrationOptions(integrator=integrator_for(m, config.integrator, config.sde_integrator)),
        keep_trajectory_runs=keep_trajectory_runs, save_every=save_every,
    )


def execute_task(spec: TaskSpec, threads: int | None = None) -> dict[str, npt.NDArray[Any]]:
    """Run one task; returns plain arrays (``x_gh``, ``t_gh`` trimmed to the longest run,
    ``stick_count``, ``n_belt_speed_without_stick``, optional ``trajectory``, ``warnings``).

    ``threads`` only changes the speed of :func:`simulate`, never the numbers.
    """
    keep = spec.keep_trajectory_runs > 0
    res = simulate(
        list(spec.cases), model=spec.model, x0=list(spec.x0) if spec.x0 is not None else None, runs=spec.runs,
        seed=int(spec.seed), noise=spec.noise, integration=spec.integration,
        output=OutputOptions(save_trajectory=keep, save_every=spec.save_every),
        execution=ExecutionOptions(workers=threads),
    )
    nev = int(max(1, np.max(np.sum(np.isfinite(res.x_gh), axis=2))))
    out: dict[str, npt.NDArray[Any]] = {
        "x_gh": res.x_gh[:, :, :nev].copy(),
        "t_gh": res.t_gh[:, :, :nev].copy(),
        "stick_count": res.stick_count.copy(),
        "n_belt_speed_without_stick": res.diagnostics["n_belt_speed_without_stick"].copy(),
        "sigma_zeta": np.asarray(res.sigma_zeta, dtype=float),
        "warnings": np.asarray(json.dumps([w.to_dict() for w in res.warnings])),
    }
    if keep and res.trajectory is not None:
        out["trajectory"] = res.trajectory[:, : spec.keep_trajectory_runs].copy()
    return out


def runs_for(model: Model | str, runs: int) -> int:
    """Monte Carlo runs of a model: one for the deterministic model (all runs would be equal)."""
    return 1 if model == Model.DETERMINISTIC else int(runs)


def integrator_for(model: Model | str, integrator: Integrator | str, sde_integrator: Integrator | str) -> Integrator:
    """``integrator`` for the deterministic and contact models, ``sde_integrator`` for white noise."""
    if model == Model.WHITE:
        if sde_integrator not in (Integrator.EULER, Integrator.MILSTEIN):
            raise StudyError(f"sde_integrator must be 'euler' or 'milstein', got {sde_integrator!r}")
        return Integrator(sde_integrator)
    if integrator not in (Integrator.EULER, Integrator.ACCURATE):
        raise StudyError(f"integrator must be 'euler' or 'accurate', got {integrator!r}")
    return Integrator(integrator)


def setup_for(config: StudyConfig, tau_end: float | None = None) -> CaseSetup:
    """The :class:`~stochfric.oscillator.case.CaseSetup` of a study config (``tau_end`` stands in for a
    missing ``config.tau_end``)."""
    te = config.tau_end if config.tau_end is not None else tau_end
    return case_setup(config.case_source(), config.process_file, te, config.dt, config.white_intensity,
                      config.process_level, allow_extrapolation=config.allow_extrapolation)


@dataclass(frozen=True)
class ModelChoices:
    """The modelling choices of a study, recorded with every result (its summary's fields of the same
    names): path coordinate, σ_ζ rule, white-noise increment, process level, σ_ζ per force [N] and the
    effective σ_ζ of the white-noise SDE (differs only in ``thesis`` mode); ``white_model``, the white
    model's standing, where the study runs it (else ``None``)."""

    path_coordinate: str
    white_intensity: str
    white_increment: str
    process_level: str
    sigma_zeta: list[float]
    sigma_zeta_effective: list[float]
    white_model: str | None = None


def model_choices(config: StudyConfig, setup: CaseSetup, forces: Sequence[float]) -> ModelChoices:
    """The :class:`ModelChoices` of ``config`` and its ``setup`` at the normal forces ``forces`` [N]."""
    return ModelChoices(
        path_coordinate=str(config.path_coordinate),
        white_intensity=str(config.white_intensity),
        white_increment=str(setup.white_increment),
        process_level=str(setup.process_level),
        sigma_zeta=[setup.sigma_zeta(nf) for nf in forces],
        sigma_zeta_effective=[setup.sigma_zeta_effective(nf) for nf in forces],
        white_model=WHITE_MODEL_STANDING if Model.WHITE in config.models else None,
    )


def warnings_of(arrays: dict[str, npt.NDArray[Any]]) -> list[dict[str, str]]:
    """Decode the simulation warnings stored by :func:`execute_task`."""
    w = arrays.get("warnings")
    if w is None:
        return []
    out: list[dict[str, str]] = json.loads(str(w))
    return out

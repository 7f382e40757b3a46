"""Shared pieces of the studies (method §6): grids, the stick window, task specs.

The case of a study (preset, process model, N, D → parameters and friction law) is built by
:mod:`stochfric.oscillator.case`; :func:`setup_for` takes it from a study config.

A study is a list of independent *tasks*; one task is one :func:`simulate` call that
batches many parameter sets (e.g. every damping ratio D of one normal force N and one
friction model).  A task is described completely by a picklable, frozen
:class:`TaskSpec`, so that it can run in this process, in a local worker process or on
a Dask worker and give the same numbers: its random numbers come from the seed sequence
with spawn key ``(task_index,)`` of the study's root seed (:func:`task_seed`), never from
the order of execution.

The three friction models of method §6 are run side by side: ``deterministic`` (the
pressure law 4.13 alone), ``white`` (plus white noise of intensity σ_ζ, §5.1: by default the
thesis's σ_ζ = σ_μ(p), or the process's low-frequency spectral level, or the printed-(4.31)
reproduction mode ``thesis`` with σ_ζ,eff = σ_μ(p)·Lω0·Δτ, ``white_intensity``)
and ``contact`` (plus a band-limited process from the friction-process model, §5.2).
"""

from __future__ import annotations

import json
import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.case import MODELS, CaseError, CaseSetup, case_setup, law_for
from ..oscillator.case import PATH_COORDINATES as PATH_COORDINATES
from ..oscillator.case import WHITE_INTENSITY_RULES as WHITE_INTENSITY_RULES
from ..oscillator.case import process_rule_of as process_rule_of
from ..oscillator.case import white_increment_of as white_increment_of
from ..oscillator.case import with_white_intensity as with_white_intensity
from ..oscillator.friction_laws import FrictionLaw
from ..oscillator.integrate import simulate
from ..oscillator.parameters import OscillatorParameters
from ..random import child_seed

#: The studies' names for the case of :mod:`stochfric.oscillator.case`: a study's configuration
#: errors are case errors, its setup is the case setup.
StudyError = CaseError
StudySetup = CaseSetup
make_setup = case_setup

#: Default stick window: a run "has a stick-slip cycle" when it has at least one slip→stick
#: transition with τ in (STICK_WINDOW · τ_end, τ_end] (after the transient, method §7.9).
STICK_WINDOW = 0.5


def parse_grid(spec: str | Sequence[float] | float) -> tuple[float, ...]:
    """A grid from ``"START:STOP:NUM"`` (inclusive linspace), ``"a,b,c"``, a number or a list.

    >>> parse_grid("0.05:0.25:5")
    (0.05, 0.1, 0.15, 0.2, 0.25)
    """
    if isinstance(spec, int | float) and not isinstance(spec, bool):
        vals: list[float] = [float(spec)]
    elif isinstance(spec, str):
        text = spec.strip()
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise StudyError(f"grid {spec!r}: use START:STOP:NUM, e.g. 0.05:0.25:41")
            try:
                a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
            except ValueError:
                raise StudyError(f"grid {spec!r}: START and STOP must be numbers, NUM an integer") from None
            if n < 1:
                raise StudyError(f"grid {spec!r}: NUM must be >= 1")
            vals = [float(v) for v in np.linspace(a, b, n)] if n > 1 else [a]
        else:
            try:
                vals = [float(v) for v in text.split(",") if v.strip()]
            except ValueError:
                raise StudyError(f"grid {spec!r}: use START:STOP:NUM or a comma-separated list") from None
    else:
        try:
            vals = [float(v) for v in spec]  # type: ignore[union-attr]
        except (TypeError, ValueError):
            raise StudyError(f"grid {spec!r}: expected numbers") from None
    if not vals:
        raise StudyError(f"grid {spec!r} is empty")
    if not all(math.isfinite(v) for v in vals):
        raise StudyError(f"grid {spec!r} contains a value that is not finite")
    # round away linspace noise (0.15000000000000002) so that labels and hashes are clean
    return tuple(float(f"{v:.12g}") for v in vals)


def setup_for(config: Any, tau_end: float | None = None) -> StudySetup:
    """:func:`make_setup` from a study config (``tau_end`` overrides a missing ``config.tau_end``)."""
    te = config.tau_end if config.tau_end is not None else tau_end
    return make_setup(config.preset, config.process_file, te, config.dt, config.white_intensity,
                      getattr(config, "process_level", "sigma_mu"))


def model_choices(config: Any, setup: StudySetup, forces: Sequence[float]) -> dict[str, Any]:
    """JSON record of the modelling choices: path coordinate, σ_ζ rule, σ_ζ per force and the
    effective σ_ζ of the white-noise SDE (differs only in ``thesis`` mode)."""
    return {
        "path_coordinate": config.path_coordinate,
        "white_intensity": config.white_intensity,
        "white_increment": setup.white_increment,
        "process_level": setup.process_level,
        "sigma_zeta": [setup.sigma_zeta(nf) for nf in forces],
        "sigma_zeta_effective": [setup.sigma_zeta_effective(nf) for nf in forces],
    }


def check_models(models: Sequence[str]) -> tuple[str, ...]:
    """Validate a list of model names (order kept, duplicates refused)."""
    out = tuple(str(m) for m in models)
    bad = [m for m in out if m not in MODELS]
    if bad:
        raise StudyError(f"unknown model(s) {bad}; choose from {list(MODELS)}")
    if len(set(out)) != len(out):
        raise StudyError(f"models listed twice: {list(out)}")
    if not out:
        raise StudyError("no model given")
    return out


def task_seed(root_entropy: int, task_index: int) -> np.random.SeedSequence:
    """Seed sequence of task ``task_index``: spawn key ``(task_index,)`` of the root seed.

    Depends only on the root seed and the task's position in the study grid, never on the
    executor, the number of workers or the order in which tasks finish.
    """
    return child_seed(int(root_entropy), int(task_index))


@dataclass(frozen=True)
class TaskSpec:
    """One independent unit of a study: a single batched :func:`simulate` call.

    ``params`` are the parameter sets of the call; ``x0`` one initial state per set (or
    ``None``: sticking at the origin, ``(0, γ0)``).  ``keep_trajectory_runs`` > 0 keeps the
    decimated trajectories of that many runs (phase diagrams).
    """

    index: int
    label: str
    model: str
    params: tuple[OscillatorParameters, ...]
    runs: int
    tau_end: float
    dt: float
    integrator: str
    root_entropy: int
    process: Any
    x0: tuple[tuple[float, float], ...] | None = None
    common_random_numbers: bool = False
    path_coordinate: str = "mass"
    keep_trajectory_runs: int = 0
    save_every: int = 10
    white_increment: str = "ito"
    extra: dict[str, Any] = field(default_factory=dict, compare=False)


def task_for(
    config: Any,
    setup: StudySetup,
    *,
    index: int,
    label: str,
    model: str,
    params: Sequence[OscillatorParameters],
    runs: int | None = None,
    x0: tuple[tuple[float, float], ...] | str | None = "config",
    **fields: Any,
) -> TaskSpec:
    """A :class:`TaskSpec` with the fields every study fills the same way from its config and setup.

    ``runs`` defaults to :func:`runs_for` ``(model, config.runs)``; ``x0="config"`` repeats
    ``config.x0`` for every parameter set (``None`` if the config has none); the integrator
    follows :func:`integrator_for`, the time grid, process and white-noise increment the setup.
    ``fields`` sets the remaining :class:`TaskSpec` fields (``common_random_numbers``,
    ``keep_trajectory_runs``, ``save_every``).
    """
    ps = tuple(params)
    start = (None if config.x0 is None else tuple(config.x0 for _ in ps)) if isinstance(x0, str) else x0
    return TaskSpec(
        index=index, label=label, model=model, params=ps,
        runs=runs_for(model, config.runs) if runs is None else runs,
        tau_end=setup.tau_end, dt=setup.dt,
        integrator=integrator_for(model, config.integrator, config.sde_integrator),
        root_entropy=config.seed, process=setup.process, x0=start,
        path_coordinate=config.path_coordinate, white_increment=setup.white_increment, **fields,
    )  # fmt: skip


def execute_task(spec: TaskSpec, threads: int | None = None) -> dict[str, npt.NDArray[Any]]:
    """Run one task; returns plain arrays (``x_gh``, ``t_gh`` trimmed to the longest run,
    ``stick_count``, ``n_belt_speed_without_stick``, optional ``trajectory``, ``warnings``).

    ``threads`` only changes the speed of :func:`simulate`, never the numbers.
    """
    process = spec.process

    def law(p: OscillatorParameters) -> FrictionLaw:
        return law_for(process, p)

    keep = spec.keep_trajectory_runs > 0
    res = simulate(
        list(spec.params), model=spec.model, law=law, process=process,
        x0=list(spec.x0) if spec.x0 is not None else None, tau_end=spec.tau_end, dt=spec.dt,
        integrator=spec.integrator, runs=spec.runs, seed=task_seed(spec.root_entropy, spec.index),
        path_coordinate=spec.path_coordinate, save_trajectory=keep, save_every=spec.save_every,
        workers=threads, common_random_numbers=spec.common_random_numbers,
        white_increment=spec.white_increment if spec.model == "white" else "ito",
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


def runs_for(model: str, runs: int) -> int:
    """Monte Carlo runs of a model: one for the deterministic model (all runs would be equal)."""
    return 1 if model == "deterministic" else int(runs)


def integrator_for(model: str, integrator: str, sde_integrator: str) -> str:
    """``integrator`` for the deterministic and contact models, ``sde_integrator`` for white noise."""
    if model == "white":
        if sde_integrator not in ("euler", "milstein"):
            raise StudyError(f"sde_integrator must be 'euler' or 'milstein', got {sde_integrator!r}")
        return sde_integrator
    if integrator not in ("euler", "accurate"):
        raise StudyError(f"integrator must be 'euler' or 'accurate', got {integrator!r}")
    return integrator


def window_mask(t_gh: npt.NDArray[np.float64], tau_end: float, window: float) -> npt.NDArray[np.bool_]:
    """Events in the stick window τ ∈ (window · τ_end, τ_end] (NaN padding is outside)."""
    if not 0.0 <= window < 1.0:
        raise StudyError(f"stick window fraction must be in [0, 1), got {window}")
    with np.errstate(invalid="ignore"):
        return np.isfinite(t_gh) & (t_gh > window * tau_end)


def warnings_of(arrays: dict[str, npt.NDArray[Any]]) -> list[dict[str, str]]:
    """Decode the simulation warnings stored by :func:`execute_task`."""
    w = arrays.get("warnings")
    if w is None:
        return []
    out: list[dict[str, str]] = json.loads(str(w))
    return out


def pad_events(arrs: Sequence[npt.NDArray[np.float64]]) -> list[npt.NDArray[np.float64]]:
    """NaN-pad arrays ``[..., event]`` to a common event length."""
    nev = max(a.shape[-1] for a in arrs)
    out = []
    for a in arrs:
        if a.shape[-1] < nev:
            pad = np.full((*a.shape[:-1], nev - a.shape[-1]), np.nan)
            a = np.concatenate([a, pad], axis=-1)
        out.append(a)
    return out

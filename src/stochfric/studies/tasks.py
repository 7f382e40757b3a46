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
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.case import CaseError as StudyError
from ..oscillator.case import CaseSetup as StudySetup
from ..oscillator.case import law_for
from ..oscillator.friction_laws import FrictionLaw
from ..oscillator.integrate import simulate
from ..oscillator.parameters import OscillatorParameters

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
    stream_keys: tuple[tuple[int, ...], ...] | None = None
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
    common_random_numbers: bool = False,
    **fields: Any,
) -> TaskSpec:
    """A :class:`TaskSpec` with the fields every study fills the same way from its config and setup.

    ``runs`` defaults to :func:`runs_for` ``(model, config.runs)``; ``x0="config"`` repeats
    ``config.x0`` for every parameter set (``None`` if the config has none); the integrator
    follows :func:`integrator_for`, the time grid, process and white-noise increment the setup.
    ``common_random_numbers`` leaves D out of the cells' stream keys (:func:`cell_stream_key`).
    ``fields`` sets the remaining :class:`TaskSpec` fields (``keep_trajectory_runs``, ``save_every``).
    """
    ps = tuple(params)
    shared = ("damping_ratio",) if common_random_numbers else ()
    start = (None if config.x0 is None else tuple(config.x0 for _ in ps)) if isinstance(x0, str) else x0
    return TaskSpec(
        index=index, label=label, model=model, params=ps,
        runs=runs_for(model, config.runs) if runs is None else runs,
        tau_end=setup.tau_end, dt=setup.dt,
        integrator=integrator_for(model, config.integrator, config.sde_integrator),
        root_entropy=config.seed, process=setup.process, x0=start,
        stream_keys=tuple(cell_stream_key(model, p, shared) for p in ps),
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
        integrator=spec.integrator, runs=spec.runs, seed=int(spec.root_entropy), stream_keys=spec.stream_keys,
        path_coordinate=spec.path_coordinate, save_trajectory=keep, save_every=spec.save_every,
        workers=threads,
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


def warnings_of(arrays: dict[str, npt.NDArray[Any]]) -> list[dict[str, str]]:
    """Decode the simulation warnings stored by :func:`execute_task`."""
    w = arrays.get("warnings")
    if w is None:
        return []
    out: list[dict[str, str]] = json.loads(str(w))
    return out

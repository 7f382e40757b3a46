"""The result object every study returns: an xarray Dataset plus a JSON summary."""

from __future__ import annotations

import json
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import xarray as xr

from ..io_utils import package_versions, write_netcdf_atomic, write_text_atomic
from .executors import Executor, SweepStats, run_tasks
from .store import CheckpointStore


def jsonable(obj: Any) -> Any:
    """Plain JSON values (NaN/inf → None, numpy → Python)."""
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, np.generic):
        return jsonable(obj.item())
    if isinstance(obj, float):
        return obj if np.isfinite(obj) else None
    return obj


@dataclass
class StudyResult:
    """A finished study: ``dataset`` (labelled arrays, units, provenance) and ``summary``."""

    kind: str
    dataset: xr.Dataset
    summary: dict[str, Any]
    stats: SweepStats = field(default_factory=SweepStats)

    def to_dataset(self) -> xr.Dataset:
        """The labelled arrays (dims named, units in attributes, config/seed/versions in attrs)."""
        return self.dataset

    def to_json_dict(self) -> dict[str, Any]:
        """The CLI's ``--json`` object."""
        out: dict[str, Any] = jsonable(self.summary)
        return out

    def to_netcdf(self, path: str | Path) -> Path:
        """Write the dataset to NetCDF (h5netcdf) atomically."""
        return write_netcdf_atomic(path, self.dataset)  # in memory first: a full disk is a clean OSError

    def save(self, directory: str | Path) -> list[Path]:
        """``<kind>.nc`` and ``<kind>.json`` in ``directory``."""
        d = Path(directory)
        d.mkdir(parents=True, exist_ok=True)
        nc = self.to_netcdf(d / f"{self.kind}.nc")
        js = write_text_atomic(d / f"{self.kind}.json", json.dumps(self.to_json_dict(), indent=1))
        return [nc, js]


def provenance_attrs(
    kind: str, config: Any, setup: Any, root_entropy: int, executor: Executor | None
) -> dict[str, str]:
    """Dataset attributes: config, case, seed, versions (JSON strings)."""
    return {
        "title": f"stochfric {kind} study",
        "study": kind,
        "config_json": json.dumps(jsonable(config.model_dump(mode="json"))),
        "setup_json": json.dumps(jsonable(setup.describe())),
        "seed_entropy": str(root_entropy),
        "seed_rule": "task k uses SeedSequence(seed, spawn_key=(k,)); trajectory (i, r) of a task spawn key (k, i, r)",
        "versions_json": json.dumps(package_versions()),
        "executor_json": json.dumps(executor.describe() if executor is not None else {"executor": "serial"}),
        "path_coordinate": str(getattr(config, "path_coordinate", "mass")),
        "white_intensity": str(getattr(config, "white_intensity", "sigma_mu")),
        "units_note": "x_gh, t_gh dimensionless (x = y/L, L = 1 m; tau = omega0 t); forces in N; damping ratio D [-]",
    }


def sweep(
    kind: str,
    config: Any,
    tasks: list[Any],
    executor: Executor | None,
    checkpoint: str | Path | None,
    progress: Callable[[int, int], None] | None,
) -> tuple[dict[int, dict[str, Any]], SweepStats, str | None]:
    """Run the tasks of a study with optional checkpointing; returns results, stats, hash."""
    store = CheckpointStore(checkpoint, config.hash_config(), kind=kind) if checkpoint is not None else None
    results, stats = run_tasks(tasks, executor=executor, store=store, progress=progress)
    return results, stats, (store.hash if store is not None else None)

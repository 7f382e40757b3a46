"""Checkpoints of a study: one file per finished task, keyed by a hash of the study config.

``CheckpointStore(root, config)`` keeps the tasks of one study configuration in
``root/<kind>-<hash>/``; the hash covers everything that changes the numbers (grid, runs,
seed, models, process model, τ_end, Δτ, integrators …) and nothing that does not (executor,
number of workers, output paths).  Every finished task is written atomically (temporary
file in the same directory, then :func:`os.replace`), so a crash or Ctrl-C loses at most
the tasks that were running; a rerun with the same configuration and directory loads the
finished tasks instead of recomputing them.
"""

from __future__ import annotations

import hashlib
import json
from collections.abc import Mapping
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from ..io_utils import atomic_path, write_text_atomic

#: Version of the checkpoint layout and of the stream rule; part of the hash, so checkpoints of
#: another version are never loaded (3: the config under the field names of docs/glossary.md).
SCHEMA = "stochfric.checkpoint/3"


def _canonical(obj: Any) -> Any:
    if isinstance(obj, Mapping):
        return {str(k): _canonical(v) for k, v in sorted(obj.items(), key=lambda kv: str(kv[0]))}
    if isinstance(obj, list | tuple):
        return [_canonical(v) for v in obj]
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    if isinstance(obj, Path):
        return str(obj)
    if isinstance(obj, float):
        return float(repr(obj)) if obj == obj else "nan"
    return obj


def config_hash(config: Mapping[str, Any]) -> str:
    """SHA-256 (hex, 16 characters) of the canonical JSON of ``config``."""
    text = json.dumps(_canonical(config), sort_keys=True, separators=(",", ":"), default=str)
    return hashlib.sha256(text.encode("utf-8")).hexdigest()[:16]


class CheckpointStore:
    """Finished tasks of one study configuration under ``root/<kind>-<hash>/``."""

    def __init__(self, root: str | Path, config: Mapping[str, Any], kind: str = "study") -> None:
        self.config = dict(config)
        self.hash = config_hash({**self.config, "checkpoint_schema": SCHEMA})
        self.directory = Path(root) / f"{kind}-{self.hash}"
        self.directory.mkdir(parents=True, exist_ok=True)
        cfg = self.directory / "config.json"
        if not cfg.exists():
            write_text_atomic(
                cfg, json.dumps({"schema": SCHEMA, "hash": self.hash, "config": _canonical(self.config)},
                                indent=1, default=str),
            )

    def path(self, index: int) -> Path:
        """File of task ``index``."""
        return self.directory / f"task-{int(index):06d}.npz"

    def has(self, index: int) -> bool:
        """Whether task ``index`` has finished (its file exists)."""
        return self.path(index).exists()

    def finished(self) -> set[int]:
        """Indices of all finished tasks."""
        out = set()
        for p in self.directory.glob("task-*.npz"):
            try:
                out.add(int(p.stem.split("-")[1]))
            except (IndexError, ValueError):  # pragma: no cover - foreign file
                continue
        return out

    def save(self, index: int, arrays: Mapping[str, npt.NDArray[Any]]) -> Path:
        """Write task ``index`` atomically (temporary file + ``os.replace``)."""
        target = self.path(index)
        with atomic_path(target) as tmp, open(tmp, "wb") as fh:
            payload: dict[str, Any] = {k: np.asarray(v) for k, v in arrays.items()}
            np.savez(fh, **payload)
        return target

    def load(self, index: int) -> dict[str, npt.NDArray[Any]]:
        """Read task ``index`` back."""
        with np.load(self.path(index), allow_pickle=False) as data:
            return {k: data[k] for k in data.files}

"""``stochfric run study.toml``: a validated TOML file with one or more studies.

Layout (every table optional except ``[[study]]``)::

    [defaults]            # fields applied to every study unless it sets them
    preset = "brake"
    seed = 1

    [execution]
    executor = "processes"   # serial | processes | dask
    workers = 2
    # scheduler = "tcp://127.0.0.1:8786"   (implies dask)
    checkpoint = "checkpoints"

    [output]
    dir = "results"
    report = true

    [[study]]
    kind = "damping"         # damping | forcing | lyapunov | normal-force
    normal_forces = [1800, 5600, 8000]
    damping_ratios = "0.05:0.25:41"

Errors name the place in the file (``study[0].damping_ratio: …``) and what is allowed.
"""

from __future__ import annotations

import tomllib
from pathlib import Path
from typing import Any

from pydantic import BaseModel, ConfigDict, Field, TypeAdapter, ValidationError

from stochfric.io_utils import read_text_checked

from .config import NESTED_VALIDATION, AnyStudyConfig
from .errors import StudyError, format_validation_errors
from .executors import ExecutorKind


class Execution(BaseModel):
    """Where the tasks run (never changes the numbers)."""

    model_config = ConfigDict(frozen=True, extra="forbid")
    executor: ExecutorKind = ExecutorKind.SERIAL
    workers: int | None = Field(default=None, ge=1)
    scheduler: str | None = None
    checkpoint: str | None = None


class Output(BaseModel):
    """Where results go."""

    model_config = ConfigDict(frozen=True, extra="forbid")
    dir: str = "results"
    report: bool = True


class RunFile(BaseModel):
    """A parsed, validated ``study.toml``."""

    model_config = ConfigDict(frozen=True, extra="forbid")
    defaults: dict[str, Any] = Field(default_factory=dict)
    execution: Execution = Field(default_factory=Execution)
    output: Output = Field(default_factory=Output)
    study: list[AnyStudyConfig] = Field(min_length=1)


def parse_run_file(data: dict[str, Any], source: str = "study.toml") -> RunFile:
    """Validate a loaded TOML mapping; StudyError with every problem on one line."""
    raw = dict(data)
    studies = raw.get("study")
    if studies is None:
        raise StudyError(f"{source}: no [[study]] table; add at least one, e.g. [[study]] kind = \"damping\"")
    if not isinstance(studies, list):
        raise StudyError(f"{source}: 'study' must be an array of tables ([[study]])")
    defaults = raw.get("defaults", {})
    if not isinstance(defaults, dict):
        raise StudyError(f"{source}: [defaults] must be a table")
    merged = []
    for i, s in enumerate(studies):
        if not isinstance(s, dict):
            raise StudyError(f"{source}: study[{i}] must be a table")
        if "kind" not in s:
            raise StudyError(f"{source}: study[{i}] needs kind = damping | forcing | lyapunov | normal-force")
        merged.append({**defaults, **s})
    raw["study"] = merged
    token = NESTED_VALIDATION.set(True)
    try:
        return TypeAdapter(RunFile).validate_python(raw)
    except ValidationError as exc:
        raise StudyError(f"{source}: {format_validation_errors(exc)}") from None
    finally:
        NESTED_VALIDATION.reset(token)


def load_run_file(path: str | Path) -> RunFile:
    """Read and validate ``path`` (TOML)."""
    p = Path(path)
    try:
        data = tomllib.loads(read_text_checked(p))
    except OSError as exc:
        raise StudyError(f"cannot read {p}: {exc.strerror or exc}") from None
    except UnicodeDecodeError as exc:
        raise StudyError(f"{p} is not UTF-8 text (byte {exc.start}: {exc.reason}); save it as UTF-8 TOML") from None
    except tomllib.TOMLDecodeError as exc:
        raise StudyError(f"{p} is not valid TOML: {exc}") from None
    return parse_run_file(data, str(p))

"""What every study shares: the :class:`Study` base (axes, tasks, assemble) and the
:class:`StudyResult` it returns (an xarray Dataset plus the study kind's typed summary,
:mod:`~stochfric.studies.summary`).

A study is a grid of independent tasks, one :func:`~stochfric.oscillator.integrate.simulate` call
each (:class:`~stochfric.studies.tasks.TaskSpec`).  A subclass of :class:`Study` names its task
axes (:meth:`Study.axes`: the friction model first, then the study's own), the parameter sets of
one grid point (:meth:`Study.task`) and how the results become a dataset and a summary
(:meth:`Study.assemble`); :meth:`Study.run` is the same for every study: build the tasks, run them
(:func:`sweep`: executor, checkpoints, progress), assemble.  Task ``k`` is the ``k``-th point of the
axes in C order; its cells draw their random numbers from keys made of their own parameter values
(:func:`~stochfric.studies.tasks.cell_stream_key`), so a cell's numbers do not depend on the grid.
"""

from __future__ import annotations

import itertools
import json
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Generic, TypeVar

import numpy as np
import numpy.typing as npt
import xarray as xr

from ..io_utils import package_versions, read_json_file, read_netcdf, write_netcdf_atomic, write_text_atomic
from ..oscillator.case import CaseSetup
from ..progress import Progress
from . import tasks as task_module
from .config import StudyConfig
from .errors import StudyError
from .executors import Executor, SweepStats, run_tasks
from .grids import pad_events
from .store import CheckpointStore
from .summary import StudySummary, WarningCount, summary_class, summary_kinds, to_json
from .tasks import TaskSpec, model_choices, setup_for, warnings_of

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

#: Version of a study's saved summary and dataset (2: seeds by cell, D_max(α), converged forced studies,
#: today's names); :meth:`StudyResult.load` refuses another.
STUDY_SCHEMA = "stochfric.study/2"

S = TypeVar("S", bound=StudySummary)
C = TypeVar("C", bound=StudyConfig)


@dataclass
class StudyResult(Generic[S]):
    """A finished study: ``dataset`` (labelled arrays, units, provenance) and its typed ``summary``
    (the study kind's summary class, :func:`~stochfric.studies.summary.summary_class`; the kinds'
    registry is :mod:`~stochfric.studies.kinds`)."""

    kind: str
    dataset: xr.Dataset
    summary: S
    stats: SweepStats = field(default_factory=SweepStats)

    def __repr__(self) -> str:
        s = self.summary
        dims = ", ".join(f"{k} {v}" for k, v in self.dataset.sizes.items())
        return (f"StudyResult({self.kind}, preset {s.preset}, models {s.models}, runs {s.runs}, seed {s.seed}; "
                f"dataset: {dims}; {self.stats.computed} task(s) computed, {self.stats.loaded} loaded; "
                f"summary: {type(s).__name__})")

    def to_dataset(self) -> xr.Dataset:
        """The labelled arrays (dims named, units in attributes, config/seed/versions in attrs)."""
        return self.dataset

    def to_json_dict(self) -> dict[str, Any]:
        """The CLI's ``--json`` object and the saved ``<kind>.json``: the summary as plain JSON values."""
        return self.summary.to_json()

    def plot(self, which: str | None = None, **kwargs: Any) -> Figure:
        """A figure of the study as a matplotlib figure (save it with ``fig.savefig(path)``): ``which`` names one
        of the kind's figures (:data:`~stochfric.studies.figures.STUDY_FIGURES`; the report draws them all);
        default: the kind's main figure — damping: P(stick-slip cycle) over D × N; forcing: the bifurcation
        diagram; lyapunov: λ over η; normal-force: the PDFs of X_gh (``damping_index=`` picks the D)."""
        from .figures import study_figure

        return study_figure(self.kind, self.dataset, which, **kwargs)

    @classmethod
    def load(cls, path: str | Path, kind: str | None = None) -> StudyResult[Any]:
        """The result :meth:`save` wrote (``<kind>.nc`` and ``<kind>.json``), its summary read into the kind's
        summary class.  ``path``: either file (the kind is its name) or their directory with ``kind`` (without
        it: the one study in the directory).  A result of another schema (:data:`STUDY_SCHEMA`: written by an
        older stochfric) is refused with one line saying to rerun; :class:`StudyError`.  A missing file is a
        :class:`FileNotFoundError`."""
        d, kind = _study_files(Path(path).expanduser(), kind)
        path = d / f"{kind}.json"
        what = f"{kind} study summary ({kind}.json of StudyResult.save or stochfric study {kind} --out)"
        data = read_json_file(path, what)
        found = data.get("schema") if isinstance(data, dict) else None
        if found != STUDY_SCHEMA:
            raise StudyError(f"{path} was written by another stochfric ({found or 'no schema'}; this "
                             f"one reads {STUDY_SCHEMA}): rerun the study (stochfric study {kind} …, or stochfric "
                             "reproduce)")
        try:
            summary = summary_class(kind).from_json(data)
        except (KeyError, TypeError, ValueError) as exc:
            raise StudyError(f"{path} is not a {kind} study summary of {STUDY_SCHEMA} ({exc!r}): rerun the "
                             "study") from None
        dataset = read_netcdf(d / f"{kind}.nc", f"{kind} study dataset ({kind}.nc beside {kind}.json)")
        return StudyResult(kind, dataset, summary)

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


def _study_files(path: Path, kind: str | None) -> tuple[Path, str]:
    """The directory and kind of a saved study from a file of it (``<kind>.nc`` / ``<kind>.json``) or its
    directory (and ``kind``, or the one study summary in it)."""
    if path.suffix in (".nc", ".json") and not path.is_dir():
        if kind is not None and kind != path.stem:
            raise StudyError(f"{path} is no file of a {kind} study (StudyResult.save writes {kind}.nc and "
                             f"{kind}.json)")
        if not _is_kind(path.stem):
            raise StudyError(f"{path} is no file of a study: StudyResult.save writes <kind>.nc and <kind>.json, the "
                             f"kind one of {', '.join(summary_kinds())}; stochfric.load reads any "
                             "saved result")
        return path.parent, path.stem
    if kind is not None:
        return path, kind
    if not path.is_dir():
        raise FileNotFoundError(f"no directory {path}: give the directory StudyResult.save wrote (or its "
                                "<kind>.json) and the study kind")
    kinds = sorted(q.stem for q in path.glob("*.json") if (path / f"{q.stem}.nc").is_file() and _is_kind(q.stem))
    if len(kinds) != 1:
        held = f"it holds the studies {', '.join(kinds)}" if kinds else "it holds no <kind>.json with its <kind>.nc"
        raise StudyError(f"{path}: {held}; give the file (e.g. {path / 'damping.json'}) or the kind")
    return path, kinds[0]


def _is_kind(name: str) -> bool:
    return name in summary_kinds()


def provenance_attrs(
    kind: str, config: StudyConfig, setup: CaseSetup, root_entropy: int, executor: Executor | None
) -> dict[str, str]:
    """Dataset attributes: config, case, seed, versions (JSON strings)."""
    return {
        "title": f"stochfric {kind} study",
        "study": kind,
        "config_json": json.dumps(to_json(config.model_dump(mode="json"))),
        "setup_json": json.dumps(to_json(setup.describe())),
        "seed_entropy": str(root_entropy),
        "seed_rule": ("run r of a cell uses SeedSequence(seed, spawn_key=(h0, h1, r)), (h0, h1) = BLAKE2b words of "
                      "the model and the cell's parameter values (studies.tasks.cell_stream_key; common random "
                      "numbers leave D out); contact process segment s: (h0, h1, r, s)"),
        "versions_json": json.dumps(package_versions()),
        "executor_json": json.dumps(executor.describe() if executor is not None else {"executor": "serial"}),
        # every modelling mode as a plain attribute (also in config_json / setup_json)
        "path_coordinate": str(getattr(config, "path_coordinate", "mass")),
        "white_intensity": str(getattr(config, "white_intensity", "sigma_mu")),
        "white_increment": str(getattr(setup, "white_increment", "ito")),
        "process_level": str(getattr(setup, "process_level", "sigma_mu")),
        "integrator": str(getattr(config, "integrator", "")),
        "sde_integrator": str(getattr(config, "sde_integrator", "")),
        "process_extension": "independent segments of the process length, generated as a run's path needs them",
        "units_note": "x_gh, t_gh dimensionless (x = y/L, L = 1 m; tau = omega0 t); forces in N; damping ratio D [-]",
    }


def sweep(
    kind: str,
    config: StudyConfig,
    tasks: list[Any],
    executor: Executor | None,
    checkpoint: str | Path | None,
    progress: Callable[[int, int], None] | None,
) -> tuple[dict[int, dict[str, Any]], SweepStats, str | None]:
    """Run the tasks of a study with optional checkpointing; returns results, stats, hash."""
    store = CheckpointStore(checkpoint, config.hash_config(), kind=kind) if checkpoint is not None else None
    results, stats = run_tasks(tasks, executor=executor, store=store, progress=progress)
    return results, stats, (store.hash if store is not None else None)


def warning_counts(warns: Sequence[dict[str, str]]) -> list[WarningCount]:
    """How often each simulation warning class occurred, sorted by code (the summaries' ``warnings``)."""
    codes = sorted({w["code"] for w in warns})
    return [WarningCount(c, sum(w["code"] == c for w in warns)) for c in codes]


class Study(Generic[C]):
    """Base of the four studies of method §6: axes, tasks, sweep, assemble (see the module docstring).

    ``self.config`` is the validated config (the kind's :class:`~stochfric.studies.config.StudyConfig`
    subclass ``C``), ``self.setup`` its case setup (preset, process model,
    τ_end, Δτ); ``default_tau_end`` replaces the preset's τ_end when the config sets none.
    """

    kind: ClassVar[str]
    default_tau_end: ClassVar[float | None] = None

    def __init__(self, config: C) -> None:
        self.config: C = config
        self.setup: CaseSetup = setup_for(config, tau_end=self.default_tau_end)

    # --- to be given by a study ---------------------------------------------------------

    def axes(self) -> dict[str, Sequence[Any]]:
        """The task axes, outermost first (``{"model": …, …}``): one task per point."""
        raise NotImplementedError

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        """The task at one point of :meth:`axes` (``point``: axis name → value)."""
        raise NotImplementedError

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 checkpoint_hash: str | None, executor: Executor | None) -> StudyResult[Any]:
        """The study's dataset and summary from the task results."""
        raise NotImplementedError

    # --- the same for every study ---------------------------------------------------------

    @property
    def shape(self) -> tuple[int, ...]:
        """Lengths of the task axes."""
        return tuple(len(v) for v in self.axes().values())

    def tasks(self) -> list[TaskSpec]:
        """One task per point of :meth:`axes` (C order), task index = position."""
        names = list(self.axes())
        return [self.task(k, dict(zip(names, values, strict=True)))
                for k, values in enumerate(itertools.product(*self.axes().values()))]

    def task_for(self, index: int, point: dict[str, Any], params: Sequence[Any], **fields: Any) -> TaskSpec:
        """:func:`~stochfric.studies.tasks.task_for` at ``point`` (label ``"model name=value …"``)."""
        label = " ".join([point["model"], *(f"{_LABELS.get(k, k)}={v:g}" for k, v in point.items() if k != "model")])
        return task_module.task_for(self.config, self.setup, index=index, label=label, model=point["model"],
                                    params=params, **fields)

    @classmethod
    def study(cls, config: C, *, executor: Executor | None = None, checkpoint: str | None = None,
              progress: Progress | None = None) -> StudyResult[Any]:
        """Run the study of ``config``: ``cls(config).run(…)`` (the functions ``damping_study`` etc.)."""
        return cls(config).run(executor=executor, checkpoint=checkpoint, progress=progress)

    def run(self, *, executor: Executor | None = None, checkpoint: str | None = None,
            progress: Progress | None = None) -> StudyResult[Any]:
        """Build the tasks, run them (checkpointed when ``checkpoint``), assemble the result.  A study
        with a second stage (the damping study's phase diagrams) overrides this."""
        tasks = self.tasks()
        results, stats, chash = sweep(self.kind, self.config, tasks, executor, checkpoint, progress)
        return self.assemble(tasks, results, stats, chash, executor)

    def stack(self, tasks: Sequence[TaskSpec], results: dict[int, dict[str, Any]], key: str
              ) -> npt.NDArray[np.float64]:
        """Per-run arrays of the tasks on the grid: ``[*axes, parameter set, run(, event)]``.

        Event arrays (``x_gh``, ``t_gh``) are NaN-padded to a common event length; runs a task did
        not do (the deterministic model does one) are NaN.
        """
        arrs = [np.asarray(results[t.index][key], dtype=float) for t in tasks]
        if key in ("x_gh", "t_gh"):
            arrs = pad_events(arrs)
        first = arrs[0]
        out = np.full((*self.shape, first.shape[0], self.config.runs, *first.shape[2:]), np.nan)
        for t, a in zip(tasks, arrs, strict=True):
            out[np.unravel_index(t.index, self.shape)][:, : t.runs] = a
        return out

    def event_variables(self, grid: dict[str, Any], x_gh: npt.NDArray[np.float64], t_gh: npt.NDArray[np.float64],
                        in_window: npt.NDArray[np.bool_]) -> tuple[dict[str, Any], dict[str, Any], tuple[str, ...]]:
        """Coordinates (model, ``grid``, run, event), the variables ``x_gh``, ``t_gh``, ``in_window``
        on them, and their dimension names."""
        coords: dict[str, Any] = {"model": list(self.config.models), **grid, "run": np.arange(self.config.runs),
                                  "event": np.arange(x_gh.shape[-1])}
        dims = tuple(coords)
        data: dict[str, Any] = {
            "x_gh": (dims, x_gh, {"units": "1", "long_name": "slip->stick position X_gh"}),
            "t_gh": (dims, t_gh, {"units": "1"}),
            "in_window": (dims, in_window.astype(np.int8), {"units": "1", "long_name": "event after the transient"}),
        }
        return coords, data, dims

    @staticmethod
    def warnings(tasks: Sequence[TaskSpec], results: dict[int, dict[str, Any]]) -> list[dict[str, str]]:
        """The simulation warnings of every task, in task order."""
        return [w for t in tasks for w in warnings_of(results[t.index])]

    def summary_head(self, forces: Sequence[float], warns: Sequence[dict[str, str]]) -> dict[str, Any]:
        """The :class:`~stochfric.studies.summary.StudySummary` fields of this study (case, seed, time
        grid, models, modelling choices, ``warns`` counted, versions) and σ_ζ, σ_ζ,eff at ``forces``
        (one per force), as keyword arguments of its summary class."""
        cfg, setup = self.config, self.setup
        choices = model_choices(cfg, setup, forces)
        return {"schema": STUDY_SCHEMA, "study": self.kind, "preset": setup.preset.name,
                "process_source": setup.process_source, "runs": cfg.runs, "seed": cfg.seed,
                "tau_end": setup.tau_end, "dt": setup.dt, "models": list(cfg.models),
                "path_coordinate": choices.path_coordinate, "white_intensity": choices.white_intensity,
                "white_increment": choices.white_increment, "process_level": choices.process_level,
                "white_model": choices.white_model, "sigma_zeta": choices.sigma_zeta,
                "sigma_zeta_effective": choices.sigma_zeta_effective, "warnings": warning_counts(warns),
                "extrapolation": setup.extrapolation_stamps(forces) or None, "versions": package_versions()}

    def dataset(self, data: dict[str, Any], coords: dict[str, Any], executor: Executor | None,
                checkpoint_hash: str | None, **attrs: Any) -> xr.Dataset:
        """The study's dataset with its provenance attributes (config, case, seed, versions, executor)."""
        ds = xr.Dataset(data, coords=coords)
        ds.attrs.update(provenance_attrs(self.kind, self.config, self.setup, self.config.seed, executor))
        ds.attrs["schema"] = STUDY_SCHEMA
        ds.attrs.update(attrs)
        ds.attrs["checkpoint_hash"] = checkpoint_hash or ""
        return ds


_LABELS = {"damping_ratio": "D", "normal_force_n": "N", "forcing_q": "q"}

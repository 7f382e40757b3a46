"""``stochfric reproduce``: every study of thesis chapter 4 for both presets, plus the report.

``quick=True`` uses coarse grids and few runs (measured times: README, "How long it takes");
the full plan uses the thesis's resolution (D 0.05 … 0.25 × 41, 7 forces, 10 runs; 30 runs for the normal-force
study; η 0 … 3 in steps of 0.05; Lyapunov τ = 200, 30 η, 3 forces, 10 runs).  ``runs`` replaces the runs of
every study (the thesis's fixed-runs mode at another R).  ``refine=True`` closes the damping studies'
D_max(10 %) intervals adaptively within ``run_budget`` added runs (docs/studies.md, "Closing the D_max(α)
interval"): only P(stick-slip | D) and D_max(α) take the added runs, every other number stays that of the fixed
runs.  The default is the thesis's fixed-runs mode.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

from ..oscillator.presets import PresetName
from ..progress import StagedProgress
from .base import StudyResult
from .chapter3 import chapter3_analysis
from .config import AnyStudyConfig, DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from .executors import Executor
from .grids import parse_grid
from .kinds import study_kind

_DAMPING_FORCES = {"brake": (1800.0, 2800.0, 3800.0, 4800.0, 5600.0, 6800.0, 8000.0),
                   "sheet": (400.0, 700.0, 1000.0, 1200.0, 1400.0, 1700.0, 2000.0)}
_LYAP_FORCES = {"brake": (2000.0, 4000.0, 8000.0), "sheet": (500.0, 1100.0, 1750.0)}


def run_study(config: AnyStudyConfig, **kwargs: Any) -> StudyResult[Any]:
    """Run the study of ``config`` (its kind's study function, :mod:`~stochfric.studies.kinds`)."""
    return study_kind(config.kind).run(config, **kwargs)


def configure(configs: list[Any], *, runs: int | None = None, refine: bool = False,
              run_budget: int | None = None) -> list[Any]:
    """``configs`` (of :func:`plan`) with ``runs`` runs per cell (``None``: theirs) and, for the damping studies,
    ``refine`` and ``run_budget`` (``None``: the default); a value the configs refuse raises
    :class:`~stochfric.studies.errors.StudyConfigError`."""
    fixed = {} if runs is None else {"runs": runs}
    closing = {"refine": refine, **({} if run_budget is None else {"run_budget": run_budget})} if refine else {}
    return [type(c)(**{**c.model_dump(exclude_unset=True), **fixed, **(closing if c.kind == "damping" else {})})
            if fixed or closing else c for c in configs]


def plan(quick: bool, seed: int = 2013) -> list[Any]:
    """The study configs of ``reproduce`` (both presets, the thesis's fixed runs)."""
    out: list[Any] = []
    g = parse_grid
    for pre in PresetName:
        forces = _DAMPING_FORCES[pre]
        if quick:
            out += [
                NormalForceConfig(preset=pre, runs=10, seed=seed, phase_runs=3),
                # the lowest, the thesis's phase-diagram force (brake 5600 N, sheet 1400 N) and the highest
                DampingConfig(preset=pre, normal_forces=(forces[0], forces[4], forces[-1]),
                              damping_ratios=g("0.05:0.25:21"), runs=5, seed=seed),
                ForcingConfig(preset=pre, eta=g("0:3:16"), runs=5, seed=seed),
                LyapunovConfig(preset=pre, normal_forces=_LYAP_FORCES[pre][1:2], eta=g("0.2:3:8"), runs=4, seed=seed),
            ]
        else:
            out += [
                NormalForceConfig(preset=pre, runs=30, seed=seed),
                DampingConfig(preset=pre, normal_forces=forces, damping_ratios=g("0.05:0.25:41"), runs=10, seed=seed),
                ForcingConfig(preset=pre, eta=g("0:3:61"), runs=10, seed=seed),
                LyapunovConfig(preset=pre, normal_forces=_LYAP_FORCES[pre], eta=g("0.1:3:30"), runs=10, seed=seed),
            ]
    return out


def reproduce(
    out: str | Path,
    *,
    quick: bool = False,
    seed: int = 2013,
    runs: int | None = None,
    refine: bool = False,
    run_budget: int | None = None,
    executor: Executor | None = None,
    checkpoint: str | Path | None = None,
    progress: StagedProgress | None = None,
    report: Callable[..., Any] | None = None,
    study_done: Callable[[StudyResult[Any]], None] | None = None,
) -> tuple[list[StudyResult[Any]], dict[str, float]]:
    """Run :func:`plan`, set by :func:`configure` to ``runs``, ``refine``, ``run_budget``, save every result under
    ``out/<preset>/`` and, with ``report``, write the report.

    ``report(results, out, title=…, chapter3=…)`` renders the results and the chapter-3 analysis of
    the shipped surface (:func:`~stochfric.studies.chapter3.chapter3_analysis` with ``seed``, handed over
    as a function that the report calls while it draws the study figures; the CLI passes
    :func:`stochfric.report.html.write_report`; the studies layer does not import the report).  The
    timings' ``report`` includes ``chapter3``, which runs inside it.

    ``progress(label, done, total)`` is called with the study's label (``"brake/damping"``) after
    every finished task, ``study_done(result)`` after every saved study.  Finished tasks are
    checkpointed (default ``out/checkpoints``), so an interrupted run resumes where it stopped.
    """
    base = Path(out)
    ck = str(checkpoint) if checkpoint is not None else str(base / "checkpoints")
    results: list[StudyResult[Any]] = []
    timings: dict[str, float] = {}
    t0 = time.perf_counter()
    for cfg in configure(plan(quick, seed), runs=runs, refine=refine, run_budget=run_budget):
        label = f"{cfg.preset}/{cfg.kind}"
        t = time.perf_counter()
        cb = (lambda d, n, label=label: progress(label, d, n)) if progress is not None else None
        res = run_study(cfg, executor=executor, checkpoint=ck, progress=cb)
        res.save(base / cfg.preset)
        timings[label] = time.perf_counter() - t
        results.append(res)
        if study_done is not None:
            study_done(res)
    timings["studies_total"] = time.perf_counter() - t0
    if report is not None:

        def chapter3() -> Any:
            t3 = time.perf_counter()
            ch3 = chapter3_analysis(base, quick=quick, seed=seed)
            timings["chapter3"] = time.perf_counter() - t3
            return ch3

        t = time.perf_counter()
        report(results, base, title="stochfric: reproduction of thesis chapter 4" + (" (quick)" if quick else ""),
               chapter3=chapter3)
        timings["report"] = time.perf_counter() - t
    timings["total"] = time.perf_counter() - t0
    return results, timings

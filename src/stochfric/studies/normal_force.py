"""Normal-force study (method §6.1; thesis 4.2.1 brake, 4.3.1 sheet; Fig. 4.12–4.21, 4.44–4.52).

Per model, damping ratio (undamped D = 5·10⁻⁶ and damped, brake 0.15 / sheet 0.17) and
normal force (brake 720 / 2720 / 8000 N, sheet 400 / 880 / 1750 N): R runs (thesis 30)
with τ_end = 50; phase-diagram trajectories of the first ``phase_runs`` runs; the X_gh
after the transient (stick window τ ∈ (w τ_end, τ_end]) pooled over the runs → PDF,
E[X_gh] ± σ (Tables 4.2/4.5) and VarK = |σ|/|E| (eq. 4.40, Tables 4.3/4.6) with standard
errors: closed forms for independent samples and a bootstrap over runs (the X_gh of one run
are correlated).  One task per (model, D): all forces in one simulate call.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.options import Model
from ..random import BOOTSTRAP_KEY, INTERVAL_KEY, child_generator
from .base import Study, StudyResult
from .config import NormalForceConfig
from .executors import Executor, SweepStats
from .grids import ordered, window_mask
from .stats import RatioEstimate, sample_summary, std_ratio
from .summary import OPTIONAL, StudySummary, Table
from .tasks import TaskSpec, runs_for

#: The normal-force study's per-model tables are indexed ``[normal_force_n][damping_ratio]``.
NORMAL_FORCE_LAYOUT = "model -> [normal_force_n][damping_ratio]"

_SE_FIELDS = ("mean", "std", "vark", "se_mean_iid", "se_std_iid", "se_vark_iid", "se_mean_boot", "se_std_boot",
              "se_vark_boot", "n", "n_runs")


@dataclass(frozen=True, kw_only=True)
class NormalForceSummary(StudySummary, kind="normal-force"):
    """The normal-force study's summary (module docstring).

    Grid: ``normal_force_n`` [N], ``damping_ratio`` [-]; σ_ζ, σ_ζ,eff [-] per force; ``stick_window``
    (τ from, τ to), dimensionless.  Per model, tables ``[normal_force_n][damping_ratio]`` (``layout``):
    E[X_gh], σ(X_gh) [-] and VarK = |σ|/|E| (eq. 4.40) [-] with bootstrap SEs (runs resampled) and
    closed-form SEs for independent samples (``_iid``), and the number of X_gh after the transient.
    With white and contact: σ contact/white per ``[N][D]`` with its 95 % bootstrap interval.
    """

    normal_force_n: list[float]
    damping_ratio: list[float]
    sigma_zeta: list[float]
    sigma_zeta_effective: list[float]
    stick_window: tuple[float, float]
    x_gh_mean: dict[str, Table]
    x_gh_std: dict[str, Table]
    vark: dict[str, Table] = field(metadata={"json_key": "varK"})
    x_gh_mean_se: dict[str, Table]
    x_gh_std_se: dict[str, Table]
    vark_se: dict[str, Table] = field(metadata={"json_key": "varK_se"})
    x_gh_mean_se_iid: dict[str, Table]
    x_gh_std_se_iid: dict[str, Table]
    vark_se_iid: dict[str, Table] = field(metadata={"json_key": "varK_se_iid"})
    n_events: dict[str, Table]
    layout: str = NORMAL_FORCE_LAYOUT
    sigma_ratio_contact_white: list[list[RatioEstimate]] | None = field(default=None, metadata=OPTIONAL)


class NormalForceStudy(Study[NormalForceConfig]):
    """One task per (model, D); all normal forces N in one simulate call."""

    kind = "normal-force"

    def __init__(self, config: NormalForceConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.forces = config.normal_forces or sp.normal_force_study_forces
        self.damping_ratio = config.damping_ratios or (sp.damping_undamped, sp.damping_damped)

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "damping_ratio": self.damping_ratio}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        runs = runs_for(point["model"], self.config.runs)
        return self.task_for(index, point, [self.setup.parameters(nf, point["damping_ratio"]) for nf in self.forces],
                             runs=runs, keep_trajectory_runs=min(self.config.phase_runs, runs),
                             save_every=self.config.save_every)

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 checkpoint_hash: str | None, executor: Executor | None) -> StudyResult[NormalForceSummary]:
        config = self.config
        x_gh = self.stack(tasks, results, "x_gh")
        t_gh = self.stack(tasks, results, "t_gh")
        sc = self.stack(tasks, results, "stick_count")
        traj = self.trajectories(tasks, results)
        inwin = window_mask(t_gh, self.setup.tau_end, config.stick_window)
        xw = np.where(inwin, x_gh, np.nan)
        table = self.table(xw)
        coords, data, d5 = self.event_variables({
            "damping_ratio": ("damping_ratio", np.asarray(self.damping_ratio), {"units": "1"}),
            "normal_force_n": ("normal_force_n", np.asarray(self.forces, float), {"units": "N"})}, x_gh, t_gh, inwin)
        data["stick_count"] = (d5[:4], sc, {"units": "1"})
        names = {"mean": "x_gh_mean", "std": "x_gh_std", "vark": "vark", "n": "n_events",
                 "n_runs": "n_runs_with_events"}
        for j, f in enumerate(_SE_FIELDS):
            name = names.get(f) or f.replace("se_mean", "x_gh_mean_se").replace("se_std", "x_gh_std_se").replace(
                "se_vark", "vark_se")
            data[name] = (d5[:3], table[..., j], {"units": "1"})
        if traj is not None:
            coords["phase_run"] = np.arange(max(1, config.phase_runs))
            coords["sample"] = np.arange(traj.shape[4])
            data["trajectory"] = ((*d5[:3], "phase_run", "sample", "component"), traj,
                                  {"units": "1", "long_name": "decimated (tau, x1, x2)"})
            coords["component"] = ["tau", "x1", "x2"]
        # tasks are per (model, D), all N in one call; the dataset and tables in the glossary's order (model, N, D)
        ds = ordered(self.dataset(data, coords, executor, checkpoint_hash, stick_window=config.stick_window))
        return StudyResult(self.kind, ds, self.summarise(table, xw, self.warnings(tasks, results)), stats)

    def trajectories(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]]
                     ) -> npt.NDArray[np.float64] | None:
        """The kept trajectories ``[model, D, N, phase run, sample, component]`` (``None``: none kept)."""
        nm, nd, nn = len(self.config.models), len(self.damping_ratio), len(self.forces)
        npr = max(1, self.config.phase_runs)
        traj = None
        for t in tasks:
            r = results[t.index]
            if "trajectory" in r:
                tr = r["trajectory"]
                if traj is None:
                    traj = np.full((nm, nd, nn, npr, tr.shape[2], 3), np.nan)
                traj[divmod(t.index, nd)][:, : tr.shape[1]] = tr
        return traj

    def table(self, xw: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """The X_gh statistics of :data:`_SE_FIELDS` per cell ``[model, D, N, field]``
        (:func:`~stochfric.studies.stats.sample_summary`, runs resampled with the cell's own seed)."""
        models = list(self.config.models)
        nm, nd, nn = xw.shape[:3]
        table = np.full((nm, nd, nn, len(_SE_FIELDS)), np.nan)
        for mi, di, ni in np.ndindex(nm, nd, nn):
            runs = 1 if models[mi] == Model.DETERMINISTIC else self.config.runs
            rng = child_generator(self.config.seed, BOOTSTRAP_KEY, mi, di, ni)
            s = sample_summary([xw[mi, di, ni, r] for r in range(runs)], rng=rng)
            table[mi, di, ni] = [float(getattr(s, f)) for f in _SE_FIELDS]
        return table

    def summarise(self, table: npt.NDArray[np.float64], xw: npt.NDArray[np.float64],
                  warns: list[dict[str, str]]) -> NormalForceSummary:
        """The :class:`NormalForceSummary`: the tables of ``table`` per model as ``[N][D]``."""
        config, models = self.config, list(self.config.models)

        def tab(field: str) -> dict[str, Table]:
            j = _SE_FIELDS.index(field)
            return {m: table[i, ..., j].T.tolist() for i, m in enumerate(models)}

        return NormalForceSummary(
            **self.summary_head(self.forces, warns),
            normal_force_n=list(self.forces), damping_ratio=list(self.damping_ratio),
            stick_window=(config.stick_window * self.setup.tau_end, self.setup.tau_end),
            x_gh_mean=tab("mean"), x_gh_std=tab("std"), vark=tab("vark"),
            x_gh_mean_se=tab("se_mean_boot"), x_gh_std_se=tab("se_std_boot"), vark_se=tab("se_vark_boot"),
            x_gh_mean_se_iid=tab("se_mean_iid"), x_gh_std_se_iid=tab("se_std_iid"), vark_se_iid=tab("se_vark_iid"),
            n_events=tab("n"),
            sigma_ratio_contact_white=_sigma_ratio(models, xw, config.runs, config.seed),
        )


#: Run the normal-force study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
normal_force_study = NormalForceStudy.study


def _sigma_ratio(models: Sequence[str], xw: Any, nr: int, seed: int) -> list[list[RatioEstimate]] | None:
    """σ(X_gh) contact / white per (D, N) with delta-method SE and 95 % bootstrap interval (runs
    resampled, fixed seed); ``None`` without both models.  Layout [normal_force][damping_ratio]."""
    if not (Model.WHITE in models and Model.CONTACT in models):
        return None
    ci, cw = models.index(Model.CONTACT), models.index(Model.WHITE)
    nd, nn = xw.shape[1:3]
    out = []
    for di in range(nd):
        row = []
        for ni in range(nn):
            g = child_generator(seed, INTERVAL_KEY, di, ni)
            row.append(std_ratio([xw[ci, di, ni, r] for r in range(nr)], [xw[cw, di, ni, r] for r in range(nr)],
                                 rng=g))
        out.append(row)
    return [list(col) for col in zip(*out, strict=True)]  # [N][D]

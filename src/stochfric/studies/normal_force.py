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
from typing import Any

import numpy as np

from ..io_utils import package_versions
from ..random import BOOTSTRAP_KEY, INTERVAL_KEY, child_generator
from .base import Study, StudyResult, warning_counts
from .config import NormalForceConfig
from .executors import Executor, SweepStats
from .grids import ordered, window_mask
from .stats import sample_summary, std_ratio
from .tasks import TaskSpec, runs_for

#: The normal-force study's per-model tables are indexed ``[normal_force_n][damping_ratio]``.
NORMAL_FORCE_LAYOUT = "model -> [normal_force_n][damping_ratio]"

_SE_FIELDS = ("mean", "std", "vark", "se_mean_iid", "se_std_iid", "se_vark_iid", "se_mean_boot", "se_std_boot",
              "se_vark_boot", "n", "n_runs")


class NormalForceStudy(Study):
    """One task per (model, D); all normal forces N in one simulate call."""

    kind = "normal-force"

    def __init__(self, config: NormalForceConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.forces = config.normal_force_n or tuple(float(v) for v in sp["normal_force_study_forces_n"])
        self.damping_ratio = config.damping_ratio or (float(sp["damping_undamped"]), float(sp["damping_damped"]))

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "damping_ratio": self.damping_ratio}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        runs = runs_for(point["model"], self.config.runs)
        return self.task_for(index, point, [self.setup.parameters(nf, point["damping_ratio"]) for nf in self.forces],
                             runs=runs, keep_trajectory_runs=min(self.config.phase_runs, runs),
                             save_every=self.config.save_every)

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 checkpoint_hash: str | None, executor: Executor | None) -> StudyResult:
        config, setup, forces, dampings = self.config, self.setup, self.forces, self.damping_ratio
        models = list(config.models)
        nm, nd, nn, nr = len(models), len(dampings), len(forces), config.runs
        x_gh = self.stack(tasks, results, "x_gh")
        t_gh = self.stack(tasks, results, "t_gh")
        sc = self.stack(tasks, results, "stick_count")
        npr = max(1, config.phase_runs)
        traj = None
        for t in tasks:
            r = results[t.index]
            if "trajectory" in r:
                tr = r["trajectory"]
                if traj is None:
                    traj = np.full((nm, nd, nn, npr, tr.shape[2], 3), np.nan)
                traj[divmod(t.index, nd)][:, : tr.shape[1]] = tr
        inwin = window_mask(t_gh, setup.tau_end, config.stick_window)
        xw = np.where(inwin, x_gh, np.nan)
        table = np.full((nm, nd, nn, len(_SE_FIELDS)), np.nan)
        for mi, di, ni in np.ndindex(nm, nd, nn):
            runs = 1 if models[mi] == "deterministic" else nr
            rng = child_generator(config.seed, BOOTSTRAP_KEY, mi, di, ni)
            s = sample_summary([xw[mi, di, ni, r] for r in range(runs)], rng=rng)
            table[mi, di, ni] = [float(getattr(s, f)) for f in _SE_FIELDS]
        coords, data, d5 = self.event_variables({
            "damping_ratio": ("damping_ratio", np.asarray(dampings), {"units": "1"}),
            "normal_force_n": ("normal_force_n", np.asarray(forces, float), {"units": "N"})}, x_gh, t_gh, inwin)
        data["stick_count"] = (d5[:4], sc, {"units": "1"})
        names = {"mean": "x_gh_mean", "std": "x_gh_std", "vark": "vark", "n": "n_events",
                 "n_runs": "n_runs_with_events"}
        for j, f in enumerate(_SE_FIELDS):
            name = names.get(f) or f.replace("se_mean", "x_gh_mean_se").replace("se_std", "x_gh_std_se").replace(
                "se_vark", "vark_se")
            data[name] = (d5[:3], table[..., j], {"units": "1"})
        if traj is not None:
            coords["phase_run"] = np.arange(npr)
            coords["sample"] = np.arange(traj.shape[4])
            data["trajectory"] = ((*d5[:3], "phase_run", "sample", "component"), traj,
                                  {"units": "1", "long_name": "decimated (tau, x1, x2)"})
            coords["component"] = ["tau", "x1", "x2"]
        # tasks are per (model, D), all N in one call; the dataset and tables in the glossary's order (model, N, D)
        ds = ordered(self.dataset(data, coords, executor, checkpoint_hash, stick_window=config.stick_window))

        def tab(field: str) -> dict[str, list[list[float]]]:
            j = _SE_FIELDS.index(field)
            return {m: table[i, ..., j].T.tolist() for i, m in enumerate(models)}

        summary: dict[str, Any] = {
            **self.summary_head(forces, {"normal_force_n": list(forces), "damping_ratio": list(dampings)}),
            "stick_window": [config.stick_window * setup.tau_end, setup.tau_end],
            "x_gh_mean": tab("mean"), "x_gh_std": tab("std"), "varK": tab("vark"),
            "x_gh_mean_se": tab("se_mean_boot"), "x_gh_std_se": tab("se_std_boot"), "varK_se": tab("se_vark_boot"),
            "x_gh_mean_se_iid": tab("se_mean_iid"), "x_gh_std_se_iid": tab("se_std_iid"),
            "varK_se_iid": tab("se_vark_iid"), "n_events": tab("n"),
            "layout": NORMAL_FORCE_LAYOUT,
            **_sigma_ratio(models, xw, nd, nn, nr, config.seed),
            "warnings": warning_counts(self.warnings(tasks, results)),
            "versions": package_versions(),
        }
        return StudyResult(self.kind, ds, summary, stats)


#: Run the normal-force study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
normal_force_study = NormalForceStudy.study


def _sigma_ratio(models: Sequence[str], xw: Any, nd: int, nn: int, nr: int, seed: int) -> dict[str, Any]:
    """σ(X_gh) contact / white per (D, N) with delta-method SE and 95 % bootstrap interval (runs
    resampled, fixed seed); empty without both models.  Layout [normal_force][damping_ratio]."""
    if not ("white" in models and "contact" in models):
        return {}
    ci, cw = models.index("contact"), models.index("white")
    out = []
    for di in range(nd):
        row = []
        for ni in range(nn):
            g = child_generator(seed, INTERVAL_KEY, di, ni)
            row.append(std_ratio([xw[ci, di, ni, r] for r in range(nr)], [xw[cw, di, ni, r] for r in range(nr)],
                                 rng=g).to_dict())
        out.append(row)
    return {"sigma_ratio_contact_white": [list(col) for col in zip(*out, strict=True)]}  # [N][D]

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

from collections.abc import Callable, Sequence
from typing import Any

import numpy as np
import xarray as xr

from ..io_utils import package_versions
from ..random import BOOTSTRAP_KEY, INTERVAL_KEY, child_generator
from .base import StudyResult, provenance_attrs, sweep
from .common import (
    TaskSpec,
    model_choices,
    pad_events,
    runs_for,
    setup_for,
    task_for,
    warnings_of,
    window_mask,
)
from .config import NormalForceConfig
from .executors import Executor
from .stats import sample_summary, std_ratio

_SE_FIELDS = ("mean", "std", "vark", "se_mean_iid", "se_std_iid", "se_vark_iid", "se_mean_boot", "se_std_boot",
              "se_vark_boot", "n", "n_runs")


def normal_force_tasks(config: NormalForceConfig) -> tuple[list[TaskSpec], dict[str, Any]]:
    """One task per (model, D)."""
    setup = setup_for(config)
    sp = setup.preset.study_parameters
    forces = config.normal_forces or tuple(float(v) for v in sp["normal_force_study_forces"])
    dampings = config.dampings or (float(sp["damping_undamped"]), float(sp["damping_damped"]))
    tasks = []
    idx = 0
    for model in config.models:
        for d in dampings:
            params = tuple(setup.parameters(nf, d) for nf in forces)
            runs = runs_for(model, config.runs)
            tasks.append(task_for(
                config, setup, index=idx, label=f"{model} D={d:g}", model=model, params=params, runs=runs,
                keep_trajectory_runs=min(config.phase_runs, runs), save_every=config.save_every,
            ))
            idx += 1
    return tasks, {"setup": setup, "forces": forces, "dampings": dampings}


def normal_force_study(
    config: NormalForceConfig,
    *,
    executor: Executor | None = None,
    checkpoint: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> StudyResult:
    """Run the normal-force study (see the module docstring)."""
    tasks, info = normal_force_tasks(config)
    setup, forces, dampings = info["setup"], info["forces"], info["dampings"]
    results, stats, chash = sweep("normal-force", config, tasks, executor, checkpoint, progress)
    models = list(config.models)
    nm, nd, nn, nr = len(models), len(dampings), len(forces), config.runs
    flat_x = pad_events([results[t.index]["x_gh"] for t in tasks])
    flat_t = pad_events([results[t.index]["t_gh"] for t in tasks])
    nev = flat_x[0].shape[-1]
    x_gh = np.full((nm, nd, nn, nr, nev), np.nan)
    t_gh = np.full((nm, nd, nn, nr, nev), np.nan)
    sc = np.full((nm, nd, nn, nr), np.nan)
    npr = max(1, config.phase_runs)
    traj = None
    warns: list[dict[str, str]] = []
    for t, a, b in zip(tasks, flat_x, flat_t, strict=True):
        mi, di = divmod(t.index, nd)
        r = results[t.index]
        x_gh[mi, di, :, : t.runs] = a
        t_gh[mi, di, :, : t.runs] = b
        sc[mi, di, :, : t.runs] = r["stick_count"]
        warns += warnings_of(r)
        if "trajectory" in r:
            tr = r["trajectory"]
            if traj is None:
                traj = np.full((nm, nd, nn, npr, tr.shape[2], 3), np.nan)
            traj[mi, di, :, : tr.shape[1]] = tr
    inwin = window_mask(t_gh, setup.tau_end, config.stick_window)
    xw = np.where(inwin, x_gh, np.nan)
    table = np.full((nm, nd, nn, len(_SE_FIELDS)), np.nan)
    for mi, di, ni in np.ndindex(nm, nd, nn):
        runs = 1 if models[mi] == "deterministic" else nr
        rng = child_generator(config.seed, BOOTSTRAP_KEY, mi, di, ni)
        s = sample_summary([xw[mi, di, ni, r] for r in range(runs)], rng=rng)
        table[mi, di, ni] = [float(getattr(s, f)) for f in _SE_FIELDS]
    coords: dict[str, Any] = {
        "model": models,
        "damping_ratio": ("damping_ratio", np.asarray(dampings), {"units": "1"}),
        "normal_force": ("normal_force", np.asarray(forces, float), {"units": "N"}),
        "run": np.arange(nr),
        "event": np.arange(nev),
    }
    d5 = ("model", "damping_ratio", "normal_force", "run", "event")
    data: dict[str, Any] = {
        "x_gh": (d5, x_gh, {"units": "1", "long_name": "slip->stick position X_gh"}),
        "t_gh": (d5, t_gh, {"units": "1"}),
        "in_window": (d5, inwin.astype(np.int8), {"units": "1"}),
        "stick_count": (d5[:4], sc, {"units": "1"}),
    }
    names = {"mean": "x_gh_mean", "std": "x_gh_std", "vark": "vark", "n": "n_events", "n_runs": "n_runs_with_events"}
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
    ds = xr.Dataset(data, coords=coords)
    ds.attrs.update(provenance_attrs("normal-force", config, setup, config.seed, executor))
    ds.attrs["stick_window"] = config.stick_window
    ds.attrs["checkpoint_hash"] = chash or ""

    def tab(field: str) -> dict[str, list[list[float]]]:
        j = _SE_FIELDS.index(field)
        return {m: table[i, ..., j].tolist() for i, m in enumerate(models)}

    codes = sorted({w["code"] for w in warns})
    summary: dict[str, Any] = {
        "study": "normal-force", "preset": setup.preset.name, "process_source": setup.process_source,
        "normal_force": list(forces), "damping": list(dampings), "runs": config.runs, "seed": config.seed,
        "tau_end": setup.tau_end, "dt": setup.dt, "models": models, **model_choices(config, setup, forces),
        "stick_window": [config.stick_window * setup.tau_end, setup.tau_end],
        "x_gh_mean": tab("mean"), "x_gh_std": tab("std"), "varK": tab("vark"),
        "x_gh_mean_se": tab("se_mean_boot"), "x_gh_std_se": tab("se_std_boot"), "varK_se": tab("se_vark_boot"),
        "x_gh_mean_se_iid": tab("se_mean_iid"), "x_gh_std_se_iid": tab("se_std_iid"),
        "varK_se_iid": tab("se_vark_iid"), "n_events": tab("n"),
        "layout": "model -> [damping][normal_force]",
        **_sigma_ratio(models, xw, nd, nn, nr, config.seed),
        "warnings": [{"code": c, "count": sum(w["code"] == c for w in warns)} for c in codes],
        "versions": package_versions(),
    }
    return StudyResult("normal-force", ds, summary, stats)


def _sigma_ratio(models: Sequence[str], xw: Any, nd: int, nn: int, nr: int, seed: int) -> dict[str, Any]:
    """σ(X_gh) contact / white per (D, N) with delta-method SE and 95 % bootstrap interval (runs
    resampled, fixed seed); empty without both models.  Layout [damping][normal_force]."""
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
    return {"sigma_ratio_contact_white": out}

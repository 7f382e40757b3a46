"""Largest Lyapunov exponent on the stick line (METHOD §6.4; thesis eq. 4.43/4.44, Fig. 4.41–4.43).

Poincaré section: the stick line x2 = γ0, crossed at the slip→stick transitions.  For each
(model, q, N, η) a reference run starts at ``x0`` (default: sticking at the origin,
(0, γ0)) and a comparison run at ``x0 + (δ, 0)``, δ = ``perturbation`` (default 10⁻⁶,
dimensionless, i.e. 1 µm for L = 1 m; the thesis gives no value — METHOD §7.9; the
sensitivity to δ is a table in ``docs/studies.md``).  Both runs use the same noise
realisation (two parameter sets with ``common_random_numbers=True``).

    w(i) = |X_gh,ref(i) − X_gh,pert(i)|,  λ = (1/K) Σ_{i=1}^{K} ln(w(i)/w(1))        (4.43)
    E[Λ] = (1/K) Σ_{i=1}^{K} ln(E[W(i)]/E[W(1)])   (mean over R run pairs)           (4.44)

K = the number of transitions both runs have (stochastic: the smallest over the runs).
If w(i) = 0 for some i ≤ K (the trajectories merged exactly, thesis: "liegen exakt
aufeinander") λ is undefined: status ``merged`` and λ = NaN, never an error.  Fewer than two
transitions: status ``too-few-transitions``.  Per-run λ (4.43) are stored too.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import numpy.typing as npt
import xarray as xr

from ..io_utils import package_versions
from .base import StudyResult, provenance_attrs, sweep
from .common import TaskSpec, integrator_for, model_choices, pad_events, runs_for, setup_for, warnings_of
from .config import LyapunovConfig
from .executors import Executor

STATUS = ("ok", "merged", "too-few-transitions")


def lyapunov_exponent(w: npt.ArrayLike) -> tuple[float, str, int]:
    """λ of eq. (4.43) from the distances w(1..K) (NaN entries end the sequence).

    Returns ``(λ, status, K)``; status ``merged`` (some w = 0) or ``too-few-transitions``
    (K < 2) gives λ = NaN.
    """
    arr = np.asarray(w, dtype=float)
    fin = np.isfinite(arr)
    k = int(np.argmin(fin)) if not fin.all() else arr.size
    arr = arr[:k]
    if k < 2:
        return math.nan, "too-few-transitions", k
    if np.any(arr == 0.0):
        return math.nan, "merged", k
    return float(np.mean(np.log(arr / arr[0]))), "ok", k


def lyapunov_tasks(config: LyapunovConfig) -> tuple[list[TaskSpec], dict[str, Any]]:
    """One task per (model, q, N): parameter sets (η0, η0, η1, η1, …) = (ref, pert) pairs."""
    setup = setup_for(config, tau_end=200.0)
    sp = setup.preset.study_parameters
    forces = config.normal_forces or tuple(float(v) for v in sp["normal_force_study_forces"])
    d = config.damping if config.damping is not None else float(sp["damping_undamped"])
    tasks = []
    idx = 0
    for model in config.models:
        for q in config.forcing_q:
            for nf in forces:
                params = []
                x0s = []
                for eta in config.eta:
                    p = setup.parameters(nf, d, q * setup.preset.stiffness, eta)
                    base = config.x0 if config.x0 is not None else (0.0, p.gamma0)
                    params += [p, p]
                    x0s += [(float(base[0]), float(base[1])), (float(base[0]) + config.perturbation, float(base[1]))]
                tasks.append(TaskSpec(
                    index=idx, label=f"{model} q={q:g} N={nf:g}", model=model, params=tuple(params),
                    runs=runs_for(model, config.runs), tau_end=setup.tau_end, dt=setup.dt,
                    integrator=integrator_for(model, config.integrator, config.sde_integrator),
                    root_entropy=config.seed, process=setup.process, x0=tuple(x0s),
                    common_random_numbers=True, path_coordinate=config.path_coordinate,
                    white_increment=setup.white_increment,
                ))
                idx += 1
    return tasks, {"setup": setup, "forces": forces, "damping": d}


def lyapunov_study(
    config: LyapunovConfig,
    *,
    executor: Executor | None = None,
    checkpoint: str | None = None,
    progress: Callable[[int, int], None] | None = None,
) -> StudyResult:
    """Run the Lyapunov study (see the module docstring)."""
    tasks, info = lyapunov_tasks(config)
    setup, forces = info["setup"], info["forces"]
    results, stats, chash = sweep("lyapunov", config, tasks, executor, checkpoint, progress)
    models, qs, etas = list(config.models), list(config.forcing_q), np.asarray(config.eta)
    nm, nq, nn, ne, nr = len(models), len(qs), len(forces), len(etas), config.runs
    flat = pad_events([results[t.index]["x_gh"] for t in tasks])
    nev = flat[0].shape[-1]
    w = np.full((nm, nq, nn, ne, nr, nev), np.nan)
    warns: list[dict[str, str]] = []
    for t, a in zip(tasks, flat, strict=True):
        mi, rest = divmod(t.index, nq * nn)
        qi, ni = divmod(rest, nn)
        ref, pert = a[0::2], a[1::2]  # [eta, run, event]
        w[mi, qi, ni, :, : t.runs] = np.abs(ref - pert)
        warns += warnings_of(results[t.index])
    lam = np.full((nm, nq, nn, ne), np.nan)
    status = np.full((nm, nq, nn, ne), "", dtype=object)
    kk = np.zeros((nm, nq, nn, ne), dtype=np.int64)
    lam_runs = np.full((nm, nq, nn, ne, nr), np.nan)
    status_runs = np.full((nm, nq, nn, ne, nr), "", dtype=object)
    for idx in np.ndindex(nm, nq, nn, ne):
        mi = idx[0]
        runs = 1 if models[mi] == "deterministic" else nr
        ww = w[idx][:runs]
        for r in range(runs):
            lam_runs[(*idx, r)], status_runs[(*idx, r)], _ = lyapunov_exponent(ww[r])
        # E[W(i)] over the runs, up to the smallest number of transitions
        counts = np.sum(np.isfinite(ww), axis=-1)
        kmin = int(counts.min()) if counts.size else 0
        ew = ww[:, :kmin].mean(axis=0) if kmin else np.zeros(0)
        lam[idx], status[idx], kk[idx] = lyapunov_exponent(ew)
    coords: dict[str, Any] = {
        "model": models,
        "forcing_q": ("forcing_q", np.asarray(qs), {"units": "1"}),
        "normal_force": ("normal_force", np.asarray(forces, float), {"units": "N"}),
        "eta": ("eta", etas, {"units": "1"}),
        "run": np.arange(nr),
        "event": np.arange(nev),
    }
    d4 = ("model", "forcing_q", "normal_force", "eta")
    ds = xr.Dataset({
        "w": ((*d4, "run", "event"), w, {"units": "1", "long_name": "w(i) = |X_gh,ref(i) - X_gh,pert(i)|"}),
        "lyapunov": (d4, lam, {"units": "1", "long_name": "lambda (4.43) / E[Lambda] (4.44), NaN unless ok"}),
        "status": (d4, status.astype(str), {"long_name": "ok | merged | too-few-transitions"}),
        "n_transitions": (d4, kk, {"units": "1", "long_name": "K used in (4.43)/(4.44)"}),
        "lyapunov_runs": ((*d4, "run"), lam_runs, {"units": "1", "long_name": "lambda of each run pair (4.43)"}),
        "status_runs": ((*d4, "run"), status_runs.astype(str), {}),
    }, coords=coords)
    ds.attrs.update(provenance_attrs("lyapunov", config, setup, config.seed, executor))
    ds.attrs["perturbation"] = config.perturbation
    ds.attrs["checkpoint_hash"] = chash or ""
    codes = sorted({x["code"] for x in warns})
    summary: dict[str, Any] = {
        "study": "lyapunov", "preset": setup.preset.name, "process_source": setup.process_source,
        "normal_force": list(forces), "forcing_q": qs, "eta": etas.tolist(), "damping": info["damping"],
        "runs": config.runs, "seed": config.seed, "tau_end": setup.tau_end, "dt": setup.dt,
        "perturbation": config.perturbation, "models": models, **model_choices(config, setup, forces),
        "lyapunov": {m: lam[i].tolist() for i, m in enumerate(models)},
        "status": {m: status[i].tolist() for i, m in enumerate(models)},
        "n_transitions": {m: kk[i].tolist() for i, m in enumerate(models)},
        "counts": {m: {s: int(np.sum(status[i] == s)) for s in STATUS} for i, m in enumerate(models)},
        "positive_fraction": {m: float(np.mean(lam[i][np.isfinite(lam[i])] > 0)) if np.isfinite(lam[i]).any()
                              else None for i, m in enumerate(models)},
        "warnings": [{"code": c, "count": sum(x["code"] == c for x in warns)} for c in codes],
        "versions": package_versions(),
    }
    return StudyResult("lyapunov", ds, summary, stats)

"""Forcing study (method §6.3; thesis 4.2.3 brake, 4.3.3 sheet; Fig. 4.30–4.37, 4.61–4.68).

D = 5·10⁻⁶, one normal force (brake 4000 N, sheet 1100 N), forcing q cos(ητ) with
q = Q/(cL) ∈ {5·10⁻⁵, 5·10⁻⁴}, η on a grid (thesis 0 … 3).  Bifurcation data: the X_gh of
the deterministic run and of R stochastic runs after the transient (stick window
τ ∈ (w τ_end, τ_end], default w = 0.5); E[X_gh] ± σ(X_gh) over η (pooled over runs) and
the ratio σ_contact/σ_white (thesis: ≈ 1.2 brake small q, ≈ 1.05 brake large q, ≈ 2.5
sheet).  One task per (model, q): all η in one simulate call.
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from typing import Any

import numpy as np

from ..io_utils import package_versions
from ..random import BOOTSTRAP_KEY, INTERVAL_KEY, child_generator
from .base import Study, StudyResult, warning_counts
from .config import ForcingConfig, integrator_record
from .executors import Executor, SweepStats
from .grids import window_mask
from .stats import sample_summary, std_ratio_over_cells
from .tasks import TaskSpec


class ForcingStudy(Study):
    """One task per (model, q); all η in one simulate call."""

    kind = "forcing"

    def __init__(self, config: ForcingConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.normal_force_n = config.normal_force_n if config.normal_force_n is not None else float(
            sp["forcing_study_force_n"])
        self.damping_ratio = config.damping_ratio if config.damping_ratio is not None else float(sp["damping_undamped"])

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "forcing_q": self.config.forcing_q}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        st, q = self.setup, point["forcing_q"]
        return self.task_for(index, point, [st.parameters(self.normal_force_n, self.damping_ratio,
                                                          q * st.preset.stiffness, eta) for eta in self.config.eta])

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 chash: str | None, executor: Executor | None) -> StudyResult:
        config, setup, nf = self.config, self.setup, self.normal_force_n
        models, qs, etas = list(config.models), list(config.forcing_q), np.asarray(config.eta)
        nm, nq, ne, nr = len(models), len(qs), len(etas), config.runs
        x_gh = self.stack(tasks, results, "x_gh")
        t_gh = self.stack(tasks, results, "t_gh")
        inwin = window_mask(t_gh, setup.tau_end, config.stick_window)
        xw = np.where(inwin, x_gh, np.nan)
        n_ev = inwin.sum(axis=(-2, -1))
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            mean = np.nanmean(xw, axis=(-2, -1))
            std = np.nanstd(xw, axis=(-2, -1), ddof=1)
        coords, data, dims5 = self.event_variables({
            "forcing_q": ("forcing_q", np.asarray(qs), {"units": "1", "long_name": "q = Q/(cL)"}),
            "eta": ("eta", etas, {"units": "1", "long_name": "eta = Omega/omega0"})}, x_gh, t_gh, inwin)
        data.update({
            "x_gh_mean": (dims5[:3], mean, {"units": "1", "long_name": "E[X_gh] after the transient"}),
            "x_gh_std": (dims5[:3], std, {"units": "1", "long_name": "sigma(X_gh) after the transient (ddof 1)"}),
            "n_events": (dims5[:3], n_ev, {"units": "1"}),
        })
        summary: dict[str, Any] = {
            **self.summary_head([nf], {
                "normal_force_n": nf, "damping_ratio": self.damping_ratio, "forcing_q": qs,
                "forcing_amplitude_n": [q * setup.preset.stiffness for q in qs], "eta": etas.tolist()},
            **integrator_record(config)),
            "x_gh_mean": {m: mean[i].tolist() for i, m in enumerate(models)},
            "x_gh_std": {m: std[i].tolist() for i, m in enumerate(models)},
        }
        summary["sigma_zeta"] = summary["sigma_zeta"][0]  # one normal force
        summary["sigma_zeta_effective"] = summary["sigma_zeta_effective"][0]
        # Monte Carlo uncertainty of E and σ per cell: bootstrap over runs (the run is the unit)
        se = np.full((nm, nq, ne, 2), np.nan)
        for mi, qi, ei in np.ndindex(nm, nq, ne):
            runs = 1 if models[mi] == "deterministic" else nr
            g = child_generator(config.seed, BOOTSTRAP_KEY, mi, qi, ei)
            sm = sample_summary([xw[mi, qi, ei, r] for r in range(runs)], n_boot=200, rng=g)
            se[mi, qi, ei] = [sm.se_mean_boot, sm.se_std_boot]
        data["x_gh_mean_se"] = (dims5[:3], se[..., 0], {"units": "1", "long_name": "bootstrap SE of E[X_gh]"})
        data["x_gh_std_se"] = (dims5[:3], se[..., 1], {"units": "1", "long_name": "bootstrap SE of sigma(X_gh)"})
        summary["x_gh_mean_se"] = {m: se[i, ..., 0].tolist() for i, m in enumerate(models)}
        summary["x_gh_std_se"] = {m: se[i, ..., 1].tolist() for i, m in enumerate(models)}
        if "white" in models and "contact" in models:
            with np.errstate(invalid="ignore", divide="ignore"):
                ratio = std[models.index("contact")] / std[models.index("white")]
            data["sigma_ratio"] = (("forcing_q", "eta"), ratio,
                                   {"units": "1", "long_name": "sigma_contact / sigma_white"})
            summary["sigma_ratio"] = {f"{q:g}": ratio[i].tolist() for i, q in enumerate(qs)}
            summary["sigma_ratio_median"] = {f"{q:g}": float(np.nanmedian(ratio[i])) if np.isfinite(ratio[i]).any()
                                             else None for i, q in enumerate(qs)}
            ci, cw = models.index("contact"), models.index("white")
            lo_hi = np.full((nq, ne, 2), np.nan)
            med_ci: dict[str, dict[str, Any]] = {}
            for qi, q in enumerate(qs):
                g = child_generator(config.seed, INTERVAL_KEY, qi)
                per, med = std_ratio_over_cells([[xw[ci, qi, e, r] for r in range(nr)] for e in range(ne)],
                                                [[xw[cw, qi, e, r] for r in range(nr)] for e in range(ne)], rng=g)
                lo_hi[qi] = [[p.low, p.high] for p in per]
                med_ci[f"{q:g}"] = med.to_dict()
            boot = {"units": "1", "long_name": "95 % bootstrap"}
            data["sigma_ratio_low"] = (("forcing_q", "eta"), lo_hi[..., 0], boot)
            data["sigma_ratio_high"] = (("forcing_q", "eta"), lo_hi[..., 1], dict(boot))
            summary["sigma_ratio_interval"] = {f"{q:g}": lo_hi[i].tolist() for i, q in enumerate(qs)}
            # the median over η with its bootstrap SE and 95 % interval (all η resampled together)
            summary["sigma_ratio_median_ci"] = med_ci
        ds = self.dataset(data, coords, executor, chash, stick_window=config.stick_window, **integrator_record(config))
        summary["warnings"] = warning_counts(self.warnings(tasks, results))
        summary["versions"] = package_versions()
        return StudyResult(self.kind, ds, summary, stats)


#: Run the forcing study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
forcing_study = ForcingStudy.study

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
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.options import Model
from ..random import BOOTSTRAP_KEY, INTERVAL_KEY, child_generator
from .base import Study, StudyResult
from .config import ForcingConfig, integrator_record
from .executors import Executor, SweepStats
from .grids import window_mask
from .stats import RatioEstimate, sample_summary, std_ratio_over_cells
from .summary import OPTIONAL, ForcedSummary, Table
from .tasks import TaskSpec


@dataclass(frozen=True, kw_only=True)
class ForcingSummary(ForcedSummary, kind="forcing"):
    """The forcing study's summary (module docstring).

    Case: ``normal_force_n`` [N], σ_ζ and σ_ζ,eff [-] at that force; the forcing amplitudes
    ``forcing_amplitude_n`` (Q [N]) of the grid ``forcing_q`` (:class:`ForcedSummary`).  Per model,
    tables ``[forcing_q][eta]`` [-]: E[X_gh] and σ(X_gh) after the transient with their bootstrap
    SEs.  With white and contact, per q (keyed ``f"{q:g}"``): σ_contact/σ_white per η with its 95 %
    bootstrap interval (``[eta][low, high]``), and its median over η with SE and interval.
    """

    normal_force_n: float
    forcing_amplitude_n: list[float]
    sigma_zeta: float
    sigma_zeta_effective: float
    x_gh_mean: dict[str, Table]
    x_gh_std: dict[str, Table]
    x_gh_mean_se: dict[str, Table]
    x_gh_std_se: dict[str, Table]
    sigma_ratio: dict[str, list[float]] | None = field(default=None, metadata=OPTIONAL)
    sigma_ratio_median: dict[str, float | None] | None = field(default=None, metadata=OPTIONAL)
    sigma_ratio_interval: dict[str, Table] | None = field(default=None, metadata=OPTIONAL)
    sigma_ratio_median_ci: dict[str, RatioEstimate] | None = field(default=None, metadata=OPTIONAL)


class ForcingStudy(Study[ForcingConfig]):
    """One task per (model, q); all η in one simulate call."""

    kind = "forcing"

    def __init__(self, config: ForcingConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.normal_force_n = config.normal_force if config.normal_force is not None else sp.forcing_study_force
        self.damping_ratio = config.damping_ratio if config.damping_ratio is not None else sp.damping_undamped

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "forcing_q": self.config.forcing_q}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        st, q = self.setup, point["forcing_q"]
        return self.task_for(index, point, [st.parameters(self.normal_force_n, self.damping_ratio,
                                                          q * st.preset.stiffness, eta) for eta in self.config.eta])

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 chash: str | None, executor: Executor | None) -> StudyResult[ForcingSummary]:
        config, qs = self.config, list(self.config.forcing_q)
        x_gh = self.stack(tasks, results, "x_gh")
        t_gh = self.stack(tasks, results, "t_gh")
        inwin = window_mask(t_gh, self.setup.tau_end, config.stick_window)
        xw = np.where(inwin, x_gh, np.nan)
        with np.errstate(invalid="ignore"), warnings.catch_warnings():
            warnings.simplefilter("ignore", RuntimeWarning)
            mean = np.nanmean(xw, axis=(-2, -1))
            std = np.nanstd(xw, axis=(-2, -1), ddof=1)
        coords, data, dims5 = self.event_variables({
            "forcing_q": ("forcing_q", np.asarray(qs), {"units": "1", "long_name": "q = Q/(cL)"}),
            "eta": ("eta", np.asarray(config.eta), {"units": "1", "long_name": "eta = Omega/omega0"})},
            x_gh, t_gh, inwin)
        se = self.bootstrap_se(xw)
        data.update({
            "x_gh_mean": (dims5[:3], mean, {"units": "1", "long_name": "E[X_gh] after the transient"}),
            "x_gh_std": (dims5[:3], std, {"units": "1", "long_name": "sigma(X_gh) after the transient (ddof 1)"}),
            "n_events": (dims5[:3], inwin.sum(axis=(-2, -1)), {"units": "1"}),
            "x_gh_mean_se": (dims5[:3], se[..., 0], {"units": "1", "long_name": "bootstrap SE of E[X_gh]"}),
            "x_gh_std_se": (dims5[:3], se[..., 1], {"units": "1", "long_name": "bootstrap SE of sigma(X_gh)"}),
        })
        ratio = self.sigma_ratio(xw, std)
        if ratio is not None:
            boot = {"units": "1", "long_name": "95 % bootstrap"}
            data["sigma_ratio"] = (("forcing_q", "eta"), ratio["value"],
                                   {"units": "1", "long_name": "sigma_contact / sigma_white"})
            data["sigma_ratio_low"] = (("forcing_q", "eta"), ratio["interval"][..., 0], boot)
            data["sigma_ratio_high"] = (("forcing_q", "eta"), ratio["interval"][..., 1], dict(boot))
        ds = self.dataset(data, coords, executor, chash, stick_window=config.stick_window, **integrator_record(config))
        summary = self.summarise(mean, std, se, ratio, self.warnings(tasks, results))
        return StudyResult(self.kind, ds, summary, stats)

    def bootstrap_se(self, xw: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
        """Monte Carlo uncertainty of E and σ per cell ``[model, q, η, (E, σ)]``: bootstrap over runs
        (the run is the unit; the deterministic model's one run)."""
        nm, nq, ne = xw.shape[:3]
        se = np.full((nm, nq, ne, 2), np.nan)
        for mi, qi, ei in np.ndindex(nm, nq, ne):
            runs = 1 if self.config.models[mi] == Model.DETERMINISTIC else self.config.runs
            g = child_generator(self.config.seed, BOOTSTRAP_KEY, mi, qi, ei)
            sm = sample_summary([xw[mi, qi, ei, r] for r in range(runs)], n_boot=200, rng=g)
            se[mi, qi, ei] = [sm.se_mean_boot, sm.se_std_boot]
        return se

    def sigma_ratio(self, xw: npt.NDArray[np.float64], std: npt.NDArray[np.float64]) -> dict[str, Any] | None:
        """σ_contact/σ_white per (q, η) (``value``), its 95 % bootstrap interval (``interval``,
        ``[q, η, (low, high)]``) and per q its median over η (``median``, all η resampled together);
        ``None`` without both models."""
        models, nr = list(self.config.models), self.config.runs
        if not (Model.WHITE in models and Model.CONTACT in models):
            return None
        ci, cw = models.index(Model.CONTACT), models.index(Model.WHITE)
        nq, ne = xw.shape[1:3]
        with np.errstate(invalid="ignore", divide="ignore"):
            value = std[ci] / std[cw]
        lo_hi = np.full((nq, ne, 2), np.nan)
        medians: list[RatioEstimate] = []
        for qi in range(nq):
            g = child_generator(self.config.seed, INTERVAL_KEY, qi)
            per, med = std_ratio_over_cells([[xw[ci, qi, e, r] for r in range(nr)] for e in range(ne)],
                                            [[xw[cw, qi, e, r] for r in range(nr)] for e in range(ne)], rng=g)
            lo_hi[qi] = [[p.low, p.high] for p in per]
            medians.append(med)
        return {"value": value, "interval": lo_hi, "median": medians}

    def summarise(self, mean: npt.NDArray[np.float64], std: npt.NDArray[np.float64], se: npt.NDArray[np.float64],
                  ratio: dict[str, Any] | None, warns: list[dict[str, str]]) -> ForcingSummary:
        """The :class:`ForcingSummary` of the study's statistics."""
        config, nf = self.config, self.normal_force_n
        models, qs = list(config.models), list(config.forcing_q)
        head, rec = self.summary_head([nf], warns), integrator_record(config)
        keys = [f"{q:g}" for q in qs]
        return ForcingSummary(
            **{**head, "sigma_zeta": head["sigma_zeta"][0],  # one normal force
               "sigma_zeta_effective": head["sigma_zeta_effective"][0]},
            normal_force_n=nf, damping_ratio=self.damping_ratio, forcing_q=qs,
            forcing_amplitude_n=[q * self.setup.preset.stiffness for q in qs], eta=list(config.eta),
            integrator=rec["integrator"], sde_integrator=rec["sde_integrator"],
            integrator_mode=rec["integrator_mode"],
            x_gh_mean={m: mean[i].tolist() for i, m in enumerate(models)},
            x_gh_std={m: std[i].tolist() for i, m in enumerate(models)},
            x_gh_mean_se={m: se[i, ..., 0].tolist() for i, m in enumerate(models)},
            x_gh_std_se={m: se[i, ..., 1].tolist() for i, m in enumerate(models)},
            sigma_ratio=None if ratio is None else {k: ratio["value"][i].tolist() for i, k in enumerate(keys)},
            sigma_ratio_median=None if ratio is None else {
                k: float(np.nanmedian(ratio["value"][i])) if np.isfinite(ratio["value"][i]).any() else None
                for i, k in enumerate(keys)},
            sigma_ratio_interval=None if ratio is None else {k: ratio["interval"][i].tolist()
                                                              for i, k in enumerate(keys)},
            sigma_ratio_median_ci=None if ratio is None else dict(zip(keys, ratio["median"], strict=True)),
        )


#: Run the forcing study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
forcing_study = ForcingStudy.study

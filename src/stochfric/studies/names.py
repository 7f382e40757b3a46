"""The names of the study results (docs/glossary.md) and how results saved under older names are read.

A study's summary (``<kind>.json``) and dataset (``<kind>.nc``) use the glossary's names:
``damping_ratio`` for D, ``normal_force_n`` for N [N], ``stick_count_mean`` for E[M],
``status_counts`` for the Lyapunov study's count of cells per status; their dimensions come in
:data:`DIMENSION_ORDER`.  Results written before the glossary used ``damping``,
``normal_force``, ``m_mean``, ``counts``, and the normal-force study ordered its dimensions
(model, damping_ratio, normal_force); :func:`current_summary` and :func:`current_dataset` bring
them to today's names and order (with a :class:`DeprecationWarning`), and
:func:`~stochfric.studies.base.StudyResult.load` and the report apply them, so saved results
still load and render.
"""

from __future__ import annotations

import warnings
from typing import Any

import xarray as xr

#: Summary keys before the glossary: old name → name now (every study; ``phase`` has its own).
SUMMARY_RENAMED: dict[str, str] = {
    "damping": "damping_ratio",
    "normal_force": "normal_force_n",
    "m_mean": "stick_count_mean",
    "m_mean_se": "stick_count_mean_se",
    "counts": "status_counts",
    # issue 19: the thesis's D_max^s is a sample extreme (grows with the number of runs), not a limit
    "d_max_stochastic": "d_max_sample_extreme",
}
#: Keys of the damping study's ``phase`` summary before the glossary.
PHASE_RENAMED: dict[str, str] = {"damping": "damping_ratio", "normal_force": "normal_force_n"}
#: Dataset variables and coordinates before the glossary.
DATASET_RENAMED: dict[str, str] = {
    "normal_force": "normal_force_n",
    "phase_normal_force": "phase_normal_force_n",
    "m_mean": "stick_count_mean",
    "m_mean_se": "stick_count_mean_se",
    "d_max": "d_max_sample_extreme",
    "d_max_low": "d_max_sample_extreme_low",
    "d_max_high": "d_max_sample_extreme_high",
}
#: The order of the grid dimensions in every study's dataset (those it has), before the
#: per-run and per-event ones (``run``, ``event``, …).
DIMENSION_ORDER = ("model", "stochastic_model", "forcing_q", "normal_force_n", "damping_ratio", "eta")

#: The normal-force study's per-model tables: ``[normal_force][damping_ratio]`` now,
#: ``[damping][normal_force]`` before the glossary.
NORMAL_FORCE_LAYOUT = "model -> [normal_force_n][damping_ratio]"
_OLD_NORMAL_FORCE_LAYOUT = "model -> [damping][normal_force]"
_NORMAL_FORCE_TABLES = ("x_gh_mean", "x_gh_std", "varK", "x_gh_mean_se", "x_gh_std_se", "varK_se",
                        "x_gh_mean_se_iid", "x_gh_std_se_iid", "varK_se_iid", "n_events")


class SummaryDict(dict[str, Any]):
    """A summary whose pre-glossary top-level keys still read (``s["damping"]`` is
    ``s["damping_ratio"]``), silently, for code written against the old names; JSON and
    iteration see today's keys only."""

    def __missing__(self, key: str) -> Any:
        new = SUMMARY_RENAMED.get(key)
        if new is None or new not in self:
            raise KeyError(key)
        return self[new]


def _deprecated(what: str, old: list[str]) -> None:
    warnings.warn(f"{what} uses names from before docs/glossary.md ({', '.join(old)}); read under today's names",
                  DeprecationWarning, stacklevel=3)


def _transpose(rows: Any) -> Any:
    return [list(r) for r in zip(*rows, strict=True)] if rows else rows


def current_summary(kind: str, summary: dict[str, Any]) -> dict[str, Any]:
    """``summary`` with today's keys and layout (a copy; a :class:`DeprecationWarning` when it had old ones).

    Giving both an old and its new key keeps the new one's value.
    """
    old = [k for k in SUMMARY_RENAMED if k in summary]
    phase = summary.get("phase")
    old_phase = [k for k in PHASE_RENAMED if isinstance(phase, dict) and k in phase]
    old_layout = kind == "normal-force" and summary.get("layout") == _OLD_NORMAL_FORCE_LAYOUT
    if not (old or old_phase or old_layout):
        return summary
    _deprecated(f"{kind} summary", old + [f"phase.{k}" for k in old_phase] + (["layout"] if old_layout else []))
    out = {SUMMARY_RENAMED.get(k, k): v for k, v in summary.items()
           if SUMMARY_RENAMED.get(k) not in summary}  # an old key beside its new one: the new one's value
    if old_phase:
        assert isinstance(phase, dict)
        out["phase"] = {PHASE_RENAMED.get(k, k): v for k, v in phase.items()}
    if old_layout:
        for key in _NORMAL_FORCE_TABLES:
            if key in out:
                out[key] = {m: _transpose(v) for m, v in out[key].items()}
        if out.get("sigma_ratio_contact_white"):
            out["sigma_ratio_contact_white"] = _transpose(out["sigma_ratio_contact_white"])
        out["layout"] = NORMAL_FORCE_LAYOUT
    return out


def ordered(ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with every variable's grid dimensions in :data:`DIMENSION_ORDER`, the others after."""
    return ds.transpose(*DIMENSION_ORDER, ..., missing_dims="ignore")


def current_dataset(kind: str, ds: xr.Dataset) -> xr.Dataset:
    """``ds`` with today's names and dimension order (a :class:`DeprecationWarning` when it had old names)."""
    old = {k: v for k, v in DATASET_RENAMED.items() if k in ds.variables and v not in ds.variables}
    if not old:
        return ds
    _deprecated(f"{kind} dataset", list(old))
    return ordered(ds.rename(old))

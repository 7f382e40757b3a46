"""Study results written before docs/glossary.md still load and render (stochfric.studies.names).

Old summaries (``damping``, ``normal_force``, ``m_mean``, ``m_mean_se``, ``counts``, the damping
study's ``phase.damping`` / ``phase.normal_force``, the normal-force study's
``[damping][normal_force]`` tables) and old datasets (``normal_force``, ``phase_normal_force``,
``m_mean``, the normal-force study's (model, damping_ratio, normal_force) order) are read under
today's names, with a DeprecationWarning.
"""

from __future__ import annotations

import json
import warnings
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

from stochfric.report.html import damping_reading, lyapunov_reading, normal_force_reading
from stochfric.studies.base import StudyResult, jsonable
from stochfric.studies.config import NormalForceConfig
from stochfric.studies.names import DIMENSION_ORDER, current_dataset, current_summary
from stochfric.studies.normal_force import normal_force_study

_TABLES = ("x_gh_mean", "x_gh_std", "varK", "x_gh_mean_se", "x_gh_std_se", "varK_se", "x_gh_mean_se_iid",
           "x_gh_std_se_iid", "varK_se_iid", "n_events")


def _as_before_the_glossary(res: StudyResult) -> tuple[dict[str, Any], xr.Dataset]:
    """The normal-force result as it was written before the glossary: old keys, old layout and order."""
    s = res.to_json_dict()
    old = {{"normal_force_n": "normal_force", "damping_ratio": "damping"}.get(k, k): v for k, v in s.items()}
    for key in _TABLES:
        old[key] = {m: [list(r) for r in zip(*v, strict=True)] for m, v in s[key].items()}
    old["sigma_ratio_contact_white"] = [list(r) for r in zip(*s["sigma_ratio_contact_white"], strict=True)]
    old["layout"] = "model -> [damping][normal_force]"
    ds = res.dataset.rename({"normal_force_n": "normal_force"}).transpose("model", "damping_ratio", "normal_force", ...)
    return old, ds


@pytest.fixture(scope="module")
def normal_force_result() -> StudyResult:
    return normal_force_study(NormalForceConfig(runs=3, seed=4, phase_runs=1, tau_end=20.0,
                                                normal_force_n=(720.0, 8000.0)))


def test_the_normal_force_study_is_in_the_glossary_order(normal_force_result: StudyResult) -> None:
    ds, s = normal_force_result.dataset, normal_force_result.to_json_dict()
    assert ds["x_gh"].dims == ("model", "normal_force_n", "damping_ratio", "run", "event")
    assert ds["trajectory"].dims[:3] == ("model", "normal_force_n", "damping_ratio")
    assert s["layout"] == "model -> [normal_force_n][damping_ratio]"
    # the summary's tables are the dataset's, [N][D]
    np.testing.assert_array_equal(np.array(s["n_events"]["white"], dtype=float),
                                  ds["n_events"].sel(model="white").values)
    assert len(s["sigma_ratio_contact_white"]) == 2 and len(s["sigma_ratio_contact_white"][0]) == 2
    for name, var in ds.data_vars.items():
        grid = [d for d in var.dims if d in DIMENSION_ORDER]
        assert grid == sorted(grid, key=DIMENSION_ORDER.index), name


def test_an_old_normal_force_result_loads_under_todays_names(normal_force_result: StudyResult,
                                                              tmp_path: Path) -> None:
    old_summary, old_ds = _as_before_the_glossary(normal_force_result)
    (tmp_path / "normal-force.json").write_text(json.dumps(old_summary), encoding="utf-8")
    old_ds.to_netcdf(tmp_path / "normal-force.nc", engine="h5netcdf")
    with pytest.warns(DeprecationWarning, match="before docs/glossary.md"):
        back = StudyResult.load(tmp_path, "normal-force")
    assert jsonable(back.summary) == jsonable(normal_force_result.summary)
    assert back.dataset["x_gh"].dims == normal_force_result.dataset["x_gh"].dims
    xr.testing.assert_identical(back.dataset, normal_force_result.dataset)
    assert normal_force_reading(back.summary) == normal_force_reading(normal_force_result.summary)
    # today's files load without a warning
    normal_force_result.save(tmp_path / "new")
    with warnings.catch_warnings():
        warnings.simplefilter("error", DeprecationWarning)
        again = StudyResult.load(tmp_path / "new", "normal-force")
    assert jsonable(again.summary) == jsonable(normal_force_result.summary)


def test_an_old_damping_summary_reads_under_todays_names() -> None:
    new = {"preset": "brake", "normal_force_n": [1000.0, 2000.0], "damping_ratio": [0.05, 0.1, 0.15],
           "d_hopf": [0.01, 0.02], "d_max_deterministic": [0.1, 0.15], "models": ["deterministic", "white"],
           "d_max_sample_extreme": {"white": [{"value": 0.1, "interval": [0.1, 0.15]},
                                              {"value": 0.15, "interval": [0.15, None]}]},
           "stick_count_mean": {"white": [[3.0, 1.0, 0.0], [4.0, 2.0, 1.0]]},
           "stick_count_mean_se": {"white": [[0.5, 0.5, 0.0], [0.5, 0.5, 0.5]]},
           "phase": {"normal_force_n": 2000.0, "damping_ratio": [0.05, 0.15], "damping_rule": "auto"}}
    old = {{"normal_force_n": "normal_force", "damping_ratio": "damping", "stick_count_mean": "m_mean",
            "stick_count_mean_se": "m_mean_se", "d_max_sample_extreme": "d_max_stochastic"}.get(k, k): v
           for k, v in new.items()}
    old["phase"] = {"normal_force": 2000.0, "damping": [0.05, 0.15], "damping_rule": "auto"}
    with pytest.warns(DeprecationWarning,
                      match=r"damping, normal_force, m_mean, m_mean_se, d_max_stochastic, phase.damping"):
        got = current_summary("damping", old)
    assert got == new
    assert damping_reading(got) == damping_reading(new)
    assert current_summary("damping", new) is new  # today's summary: as it is, no warning


def test_an_old_damping_dataset_reads_under_todays_names() -> None:
    old = xr.Dataset({"m_mean": (("model", "normal_force", "damping_ratio"), np.arange(6.0).reshape(1, 2, 3)),
                      "m_mean_se": (("model", "normal_force", "damping_ratio"), np.ones((1, 2, 3))),
                      "phase_normal_force": ((), 2000.0, {"units": "N"})},
                     coords={"model": ["white"], "normal_force": [1000.0, 2000.0], "damping_ratio": [0.1, 0.2, 0.3]})
    with pytest.warns(DeprecationWarning, match="damping dataset"):
        got = current_dataset("damping", old)
    assert set(got.data_vars) == {"stick_count_mean", "stick_count_mean_se", "phase_normal_force_n"}
    assert got["stick_count_mean"].dims == ("model", "normal_force_n", "damping_ratio")
    assert float(got["phase_normal_force_n"]) == 2000.0


def test_an_old_lyapunov_result_reads_and_the_old_keys_of_a_summary_still_resolve() -> None:
    counts = {"white": {"ok": 1, "merged": 0, "too-few-transitions": 0, "nonlinear": 1}}
    ds = xr.Dataset({"lyapunov": (("model", "forcing_q", "normal_force", "eta"), np.zeros((1, 1, 1, 2)))},
                    coords={"model": ["white"], "forcing_q": [5e-5], "normal_force": [4000.0], "eta": [1.0, 2.0]})
    old = StudyResult("lyapunov", ds, {"models": ["white"], "normal_force": [4000.0], "counts": counts,
                                       "perturbation": 1e-6, "tau_end": 100.0, "damping": 5e-6})
    with pytest.warns(DeprecationWarning):
        res = old.current()
    assert res.summary["status_counts"] == counts and res.summary["damping_ratio"] == 5e-6
    assert "counts" not in res.summary and res.dataset["lyapunov"].dims[2] == "normal_force_n"
    assert "<td>white</td><td>1</td><td>—</td><td>0</td><td>0</td><td>1</td>" in lyapunov_reading(res.summary)[0]
    # code written against the old keys still reads today's summary (silently): the CLI's table does
    s = res.to_json_dict()
    assert s["damping"] == s["damping_ratio"] and s["normal_force"] == [4000.0] and s["counts"] == counts
    assert "counts" not in json.loads(json.dumps(s))
    with pytest.raises(KeyError):
        s["no_such_key"]

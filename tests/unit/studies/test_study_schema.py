"""Saved study results are versioned (issue 21 §1): a result of another schema is refused with one line
saying to rerun; today's results round-trip; the datasets keep one dimension order."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

from stochfric.studies.base import STUDY_SCHEMA, StudyResult
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import DampingSummary, damping_study
from stochfric.studies.errors import StudyError
from stochfric.studies.grids import DIMENSION_ORDER
from stochfric.studies.kinds import STUDY_KINDS, study_kind
from stochfric.studies.reproduce import run_study


def test_a_saved_study_round_trips_and_another_schema_is_refused(tmp_path: Path) -> None:
    res = damping_study(DampingConfig(normal_forces=(5600.0,), damping_ratios=(0.1, 0.2), runs=2, seed=1,
                                      phase_runs=0, tau_end=20.0))
    assert res.summary.schema == STUDY_SCHEMA and res.dataset.attrs["schema"] == STUDY_SCHEMA
    res.save(tmp_path)
    again = StudyResult.load(tmp_path, "damping")
    assert isinstance(again.summary, DampingSummary)
    assert again.summary.d_max_deterministic == res.summary.d_max_deterministic
    assert again.to_json_dict() == res.to_json_dict()  # the typed summary reads back what was written
    dims = [d for d in again.dataset["x_gh"].dims if d in DIMENSION_ORDER]
    assert dims == [d for d in DIMENSION_ORDER if d in dims]
    path = tmp_path / "damping.json"
    old = json.loads(path.read_text(encoding="utf-8"))
    old.pop("schema")
    old["damping"] = old.pop("damping_ratio")  # a summary from before the glossary
    path.write_text(json.dumps(old), encoding="utf-8")
    with pytest.raises(StudyError, match=r"written by another stochfric \(no schema; this one reads "
                                         r"stochfric.study/2\): rerun the study"):
        StudyResult.load(tmp_path, "damping")


@pytest.mark.parametrize("config", [
    ForcingConfig(eta=(1.0,), forcing_q=(5e-4,), runs=2, tau_end=10.0, seed=3),
    LyapunovConfig(normal_forces=(4000.0,), forcing_q=(5e-4,), eta=(1.2,), runs=2, tau_end=20.0, seed=3),
    NormalForceConfig(runs=2, phase_runs=0, tau_end=10.0, seed=3),
], ids=lambda c: c.kind)
def test_every_kind_reads_back_its_typed_summary(tmp_path: Path, config: Any) -> None:
    """The summary is its kind's dataclass, written as JSON and read back into the same class."""
    kind = study_kind(config.kind)
    res = run_study(config)
    assert type(res.summary) is kind.summary and res.summary.study == config.kind
    res.save(tmp_path)
    again = StudyResult.load(tmp_path, config.kind)
    assert type(again.summary) is kind.summary
    assert again.to_json_dict() == json.loads(json.dumps(res.to_json_dict()))


def test_one_registry_entry_per_kind_and_the_report_shows_each() -> None:
    from stochfric.report.html import SECTIONS

    assert set(STUDY_KINDS) == set(SECTIONS) == {"damping", "forcing", "lyapunov", "normal-force"}
    for name, kind in STUDY_KINDS.items():
        assert kind.name == name and kind.config().kind == name and kind.title
    with pytest.raises(StudyError, match="unknown study kind 'sweep'; one of damping, forcing"):
        study_kind("sweep")


def test_a_summary_that_does_not_fit_its_class_is_refused(tmp_path: Path) -> None:
    res = run_study(ForcingConfig(eta=(1.0,), forcing_q=(5e-4,), runs=2, tau_end=10.0, seed=3))
    res.save(tmp_path)
    path = tmp_path / "forcing.json"
    data = json.loads(path.read_text(encoding="utf-8"))
    data.pop("x_gh_mean")
    path.write_text(json.dumps(data), encoding="utf-8")
    with pytest.raises(StudyError, match=r"is not a forcing study summary of stochfric.study/2 .*: rerun"):
        StudyResult.load(tmp_path, "forcing")

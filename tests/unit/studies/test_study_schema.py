"""Saved study results are versioned (issue 21 §1): a result of another schema is refused with one line
saying to rerun; today's results round-trip; the datasets keep one dimension order."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from stochfric.studies.base import STUDY_SCHEMA, StudyResult
from stochfric.studies.common import StudyError
from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.grids import DIMENSION_ORDER


def test_a_saved_study_round_trips_and_another_schema_is_refused(tmp_path: Path) -> None:
    res = damping_study(DampingConfig(normal_force_n=(5600.0,), damping_ratio=(0.1, 0.2), runs=2, seed=1,
                                      phase_runs=0, tau_end=20.0))
    assert res.summary["schema"] == STUDY_SCHEMA and res.dataset.attrs["schema"] == STUDY_SCHEMA
    res.save(tmp_path)
    again = StudyResult.load(tmp_path, "damping")
    assert again.summary["d_max_deterministic"] == res.to_json_dict()["d_max_deterministic"]
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

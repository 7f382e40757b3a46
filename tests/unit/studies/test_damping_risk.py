"""D_max(α) in the damping study (issue 19): dataset and JSON fields, and intervals that nest as runs grow."""

from __future__ import annotations

import json
import math
from typing import Any

import pytest

from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import damping_study


def _study(runs: int) -> dict[str, Any]:
    cfg = DampingConfig.model_validate({"normal_forces": (5600.0,), "damping_ratios": "0.1:0.3:41", "runs": runs,
                                        "seed": 0, "phase_runs": 0})
    return damping_study(cfg).to_json_dict()


@pytest.fixture(scope="module")
def studies() -> dict[int, dict[str, Any]]:
    return {r: _study(r) for r in (10, 40)}


def _overlap(a: list[Any], b: list[Any]) -> bool:
    lo = max(x for x in (a[0], b[0]) if x is not None) if a[0] is not None or b[0] is not None else -math.inf
    return a[1] is not None and b[1] is not None and lo <= min(a[1], b[1]) + 1e-12


def test_more_runs_give_intervals_inside_or_overlapping_those_of_fewer(studies: dict[int, dict[str, Any]]) -> None:
    few, many = studies[10], studies[40]
    for m in ("white", "contact"):
        for j, a in enumerate(few["risk_levels"]):
            e10, e40 = few["d_max_risk"][m][0][j], many["d_max_risk"][m][0][j]
            assert e10["risk_level"] == e40["risk_level"] == a
            assert _overlap(e10["interval"], e40["interval"]), (m, a, e10, e40)
            # 10 runs resolve neither 10 % nor 1 %: the upper end is the grid end, open, and says so
            assert e10["high_open"] and not e10["resolved"] and e10["interval"][1] == few["damping_ratio"][-1]
        # the sample extreme can only grow with the runs (the first 10 runs are the same runs)
        assert many["d_max_sample_extreme"][m][0]["value"] >= few["d_max_sample_extreme"][m][0]["value"]
    # 40 runs resolve 10 % (≥ 36 needed), not 1 %
    assert few["risk_levels_runs_to_resolve"] == [36, 368]
    assert [e["resolved"] for e in many["d_max_risk"]["contact"][0]] == [True, False]


def test_fields_units_and_labels() -> None:
    cfg = DampingConfig.model_validate({"normal_forces": (5600.0,), "damping_ratios": "0.12:0.2:5", "runs": 5,
                                        "seed": 0, "phase_runs": 0, "risk_levels": (0.2, 0.05, 0.01)})
    res = damping_study(cfg)
    ds = res.dataset
    assert list(ds["risk_level"].values) == [0.2, 0.05, 0.01] and ds["risk_level"].attrs["units"] == "1"
    for v in ("d_max_risk", "d_max_risk_low", "d_max_risk_high", "d_max_risk_high_open", "d_max_risk_resolved"):
        assert ds[v].dims == ("model", "normal_force_n", "risk_level"), v
        assert ds[v].attrs["units"] == "1" and ds[v].attrs["long_name"], v
    assert "grows with R" in ds["d_max_sample_extreme"].attrs["long_name"]
    assert "Clopper-Pearson" in ds["stick_probability_low"].attrs["long_name"]
    assert "d_max" not in ds and "d_safe" not in ds
    det = ds["d_max_risk"].sel(model="deterministic").values
    assert (det == ds["d_max_sample_extreme"].sel(model="deterministic").values[:, None]).all()
    s = json.loads(json.dumps(res.to_json_dict(), allow_nan=False))
    assert s["risk_levels"] == [0.2, 0.05, 0.01] and set(s["d_max_risk"]) == {"white", "contact"}
    e = s["d_max_risk"]["contact"][0][1]
    assert set(e) == {"risk_level", "value", "interval", "high_open", "resolved"} and e["risk_level"] == 0.05
    assert "d_safe" not in s and "d_max_stochastic" not in s and "d_max_sample_extreme" in s
    assert s["stick_probability_interval"] == "clopper-pearson"


def test_risk_levels_do_not_change_the_checkpoint_key() -> None:
    a = DampingConfig(runs=3)
    assert a.hash_config() == DampingConfig.model_validate({"runs": 3, "risk_levels": "0.2"}).hash_config()
    assert "risk_levels" not in a.hash_config()

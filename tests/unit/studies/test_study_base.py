"""The Study base and the study config fields."""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from stochfric.studies.base import Study, warning_counts
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import DampingStudy
from stochfric.studies.errors import StudyConfigError, StudyError
from stochfric.studies.forcing import ForcingStudy, forcing_study
from stochfric.studies.lyapunov import LyapunovStudy
from stochfric.studies.normal_force import NormalForceStudy
from stochfric.studies.store import config_hash
from stochfric.studies.summary import WarningCount
from stochfric.studies.tasks import TaskSpec


def test_tasks_enumerate_the_axes_in_c_order() -> None:
    cfg = LyapunovConfig(normal_forces=(2000.0, 4000.0), forcing_q=(5e-5, 5e-4), eta=(0.5, 1.0), runs=2)
    st = LyapunovStudy(cfg)
    tasks = st.tasks()
    assert st.shape == (3, 2, 2) and [t.index for t in tasks] == list(range(12))
    assert [t.label for t in tasks[:3]] == ["deterministic q=5e-05 N=2000", "deterministic q=5e-05 N=4000",
                                            "deterministic q=0.0005 N=2000"]
    assert tasks[4].model == "white" and len(tasks[4].params) == 3 * 2  # (ref, pert, twin) per eta
    assert [t.runs for t in tasks[::4]] == [1, 2, 2]  # the deterministic model runs once
    nf = NormalForceStudy(NormalForceConfig(runs=4, phase_runs=2))
    assert [t.keep_trajectory_runs for t in nf.tasks()] == [1, 1, 2, 2, 2, 2]
    assert DampingStudy(DampingConfig(normal_forces=(5600.0,), damping_ratios=(0.1, 0.2))).shape == (3, 1)


def test_stack_pads_events_and_leaves_missing_runs_nan() -> None:
    st = ForcingStudy(ForcingConfig(models=("deterministic", "white"), forcing_q=(5e-5,), eta=(1.0, 2.0), runs=3))
    tasks = st.tasks()
    results: dict[int, dict[str, Any]] = {
        0: {"x_gh": np.array([[[1.0]], [[2.0]]])},  # 1 run, 1 event
        1: {"x_gh": np.arange(12.0).reshape(2, 3, 2)},  # 3 runs, 2 events
    }
    x = st.stack(tasks, results, "x_gh")
    assert x.shape == (2, 1, 2, 3, 2)
    assert x[0, 0, 1, 0, 0] == 2.0 and np.isnan(x[0, 0, 1, 0, 1]) and np.isnan(x[0, 0, :, 1:]).all()
    np.testing.assert_array_equal(x[1, 0], np.arange(12.0).reshape(2, 3, 2))


def test_run_is_tasks_sweep_assemble_and_the_function_is_the_same() -> None:
    cfg = ForcingConfig(eta=(1.0,), forcing_q=(5e-4,), runs=2, tau_end=5.0, seed=4)
    a = forcing_study(cfg).to_json_dict()
    b = ForcingStudy(cfg).run().to_json_dict()
    a.pop("versions"), b.pop("versions")
    assert a == b and a["study"] == "forcing" and a["eta"] == [1.0]

    class Empty(Study):
        kind = "empty"

    with pytest.raises(NotImplementedError):
        Empty(cfg).tasks()


def test_warning_counts() -> None:
    w = [{"code": "b"}, {"code": "a"}, {"code": "b"}]
    assert warning_counts(w) == [WarningCount("a", 1), WarningCount("b", 2)]


@pytest.mark.parametrize(("cls", "old"), [
    (DampingConfig, {"damping_ratio": "0.1:0.2:3"}), (DampingConfig, {"normal_force_n": (4000.0,)}),
    (DampingConfig, {"phase_force_n": 4000.0}), (DampingConfig, {"phase_damping": (0.1,)}),
    (ForcingConfig, {"normal_force_n": 4000.0}), (ForcingConfig, {"damping": 0.1}),
    (LyapunovConfig, {"normal_force_n": (4000.0,)}), (NormalForceConfig, {"damping_ratio": (0.1,)}),
], ids=lambda v: getattr(v, "__name__", ""))
def test_config_names_not_in_the_glossary_are_unknown_fields(cls: Any, old: dict[str, Any]) -> None:
    """No compatibility layer (issue 21): another spelling is refused like any unknown field."""
    with pytest.raises(StudyConfigError, match=f"{next(iter(old))}: Extra inputs are not permitted"):
        cls(**old)


def test_the_checkpoint_key_is_the_config_under_its_own_names() -> None:
    cfg = DampingConfig(damping_ratios=(0.1, 0.2))
    d = cfg.model_dump(mode="json")
    d.pop("risk_levels")  # analysis only (issue 19): not in the checkpoint key
    assert cfg.hash_config() == d
    keys = [config_hash(c().hash_config()) for c in (DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig)]
    assert len(set(keys)) == 4


def test_study_error_and_case_error_are_value_errors() -> None:
    from stochfric.oscillator.case import CaseError

    assert issubclass(StudyError, ValueError) and issubclass(CaseError, ValueError)
    assert isinstance(ForcingStudy(ForcingConfig()).tasks()[0], TaskSpec)

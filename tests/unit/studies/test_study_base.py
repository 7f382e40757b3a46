"""The Study base (issue 12 item 4) and the renamed config fields (item 5)."""

from __future__ import annotations

import warnings
from typing import Any

import numpy as np
import pytest

from stochfric.studies.base import Study, warning_counts
from stochfric.studies.common import StudyError, TaskSpec
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import DampingStudy
from stochfric.studies.forcing import ForcingStudy, forcing_study
from stochfric.studies.lyapunov import LyapunovStudy
from stochfric.studies.normal_force import NormalForceStudy
from stochfric.studies.store import config_hash


def test_tasks_enumerate_the_axes_in_c_order() -> None:
    cfg = LyapunovConfig(normal_force_n=(2000.0, 4000.0), forcing_q=(5e-5, 5e-4), eta=(0.5, 1.0), runs=2)
    st = LyapunovStudy(cfg)
    tasks = st.tasks()
    assert st.shape == (3, 2, 2) and [t.index for t in tasks] == list(range(12))
    assert [t.label for t in tasks[:3]] == ["deterministic q=5e-05 N=2000", "deterministic q=5e-05 N=4000",
                                            "deterministic q=0.0005 N=2000"]
    assert tasks[4].model == "white" and len(tasks[4].params) == 3 * 2  # (ref, pert, twin) per eta
    assert [t.runs for t in tasks[::4]] == [1, 2, 2]  # the deterministic model runs once
    nf = NormalForceStudy(NormalForceConfig(runs=4, phase_runs=2))
    assert [t.keep_trajectory_runs for t in nf.tasks()] == [1, 1, 2, 2, 2, 2]
    assert DampingStudy(DampingConfig(normal_force_n=(5600.0,), damping_ratio=(0.1, 0.2))).shape == (3, 1)


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
    assert warning_counts(w) == [{"code": "a", "count": 1}, {"code": "b", "count": 2}]


def test_old_config_names_load_with_a_deprecation_warning() -> None:
    with pytest.warns(DeprecationWarning, match="'damping' is deprecated"):
        old = DampingConfig(damping="0.1:0.2:3")
    assert old == DampingConfig(damping_ratio="0.1:0.2:3") and old.damping == (0.1, 0.15, 0.2)
    with pytest.warns(DeprecationWarning, match="dampings"):
        assert NormalForceConfig(dampings="0.1,0.2").damping_ratio == (0.1, 0.2)
    with pytest.warns(DeprecationWarning):
        assert ForcingConfig(damping=0.1).damping_ratio == LyapunovConfig(damping=0.1).damping_ratio == 0.1
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match="damping_ratio only"):
            DampingConfig(damping="0.1:0.2:3", damping_ratio="0.1:0.2:3")
    # the checkpoint key keeps the old field name: checkpoints written before the rename resume
    cfg = DampingConfig(damping_ratio=(0.1, 0.2))
    assert "damping" in cfg.hash_config() and "damping_ratio" not in cfg.hash_config()
    d = cfg.model_dump(mode="json")
    for old, new in (("damping", "damping_ratio"), ("normal_forces", "normal_force_n"),
                     ("phase_force", "phase_force_n")):
        d[old] = d.pop(new)
    d.pop("risk_levels")  # analysis only (issue 19): not in the checkpoint key
    assert config_hash(cfg.hash_config()) == config_hash(d)


#: (config class, fields under the glossary's names, the same under the names before it, the checkpoint
#: key written before the rename, at 6f09680): a checkpoint written then must still resume.
_RENAMED_FORCES = [
    (DampingConfig, {"normal_force_n": (4000.0, 6000.0), "phase_force_n": 4000.0},
     {"normal_forces": (4000.0, 6000.0), "phase_force": 4000.0}, "33ca24bfa66fe10a"),
    # the forced studies' default integrator is accurate since issue 19 (other numbers, a new key); with
    # integrator = "euler" they keep the keys written at 6f09680 (447582a778574350, 56fdf99dc0d6f058)
    (ForcingConfig, {"normal_force_n": 4000.0}, {"normal_force": 4000.0}, "42562ff8babe3550"),
    (LyapunovConfig, {"normal_force_n": (4000.0,)}, {"normal_forces": (4000.0,)}, "b1f0fd40def5e6b3"),
    (NormalForceConfig, {"normal_force_n": (720.0, 8000.0)}, {"normal_forces": (720.0, 8000.0)}, "6ea32df5afdb1c2c"),
]


@pytest.mark.parametrize(("cls", "new", "old", "key"), _RENAMED_FORCES, ids=lambda v: getattr(v, "__name__", ""))
def test_renamed_force_fields_read_the_old_names_and_keep_the_checkpoint_key(
        cls: Any, new: dict[str, Any], old: dict[str, Any], key: str) -> None:
    cfg = cls(**new)
    with pytest.warns(DeprecationWarning, match=r"is deprecated: use '(normal|phase)_force_n'"):
        assert cls(**old) == cfg
    for name, value in old.items():  # read-only properties under the old names
        assert getattr(cfg, name) == value
        with pytest.raises(ValueError, match="frozen"):
            setattr(cfg, name, value)
    h = cfg.hash_config()
    assert set(old) <= set(h) and not set(new) & set(h)
    assert config_hash(h) == key
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        with pytest.raises(ValueError, match="give normal_force_n only"):
            cls(**old, normal_force_n=new["normal_force_n"])


def test_the_default_configs_keep_their_checkpoint_keys() -> None:
    keys = [config_hash(c().hash_config()) for c in (DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig)]
    # damping and normal force as at 6f09680; forcing and Lyapunov changed with their default integrator (issue 19).
    # The checkpoint directory adds the store's schema (stochfric.checkpoint/2: seeds by cell) to these keys.
    assert keys == ["f0b697b65c0e5c07", "e508e26bc15e0f7a", "0712e3b420dc3d00", "b1a3344e28a5337c"]


def test_study_error_is_the_case_error() -> None:
    from stochfric.oscillator.case import CaseError

    assert StudyError is CaseError and issubclass(StudyError, ValueError)
    assert isinstance(ForcingStudy(ForcingConfig()).tasks()[0], TaskSpec)

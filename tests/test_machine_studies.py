"""Every study takes a user's machine (issue 30, item 1): the forcing, Lyapunov, normal-force and damping
studies run on a machine that is no thesis case, with the friction-process model of its surface, and record it."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from stochfric.friction_process.model import ModelFunction
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.reproduce import run_study


def _model_file(tmp_path: Path) -> str:
    length, dx = 0.05, 0.0005
    f = np.arange(1, 50) / length
    table = np.stack([np.full(f.size, 1e-5), np.full(f.size, 2e-5)])
    m = TabulatedProcessModel(name="user surface", mu_mean=ModelFunction(a=0.0, b=1.0, c=0.3),
                              mu_std=ModelFunction(a=0.0, b=1.0, c=0.02), dx=dx, length=length,
                              pressures_pa=(0.1e6, 1.2e6), table_frequencies=tuple(f),
                              table_psd=tuple(tuple(r) for r in table))
    path = tmp_path / "model.json"
    path.write_text(json.dumps(m.to_dict()), encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("kind", ["forcing", "lyapunov", "normal-force", "damping"])
def test_every_study_runs_on_a_users_machine(tmp_path: Path, kind: str) -> None:
    common = dict(machine="example-calliper", process_file=_model_file(tmp_path), models=("deterministic",),
                  runs=2, tau_end=4.0, seed=3)
    config = {
        "forcing": lambda: ForcingConfig(**common, normal_force=2000.0, forcing_q=(5e-5,), eta=(0.5, 1.0)),
        "lyapunov": lambda: LyapunovConfig(**common, normal_forces=(2000.0,), forcing_q=(5e-5,), eta=(1.0,)),
        "normal-force": lambda: NormalForceConfig(**common, normal_forces=(600.0, 3000.0), damping_ratios=(0.05,),
                                                  phase_runs=0),
        "damping": lambda: DampingConfig(**common, normal_forces=(2000.0,), damping_ratios=(0.05, 0.1),
                                         phase_runs=0),
    }[kind]()
    res = run_study(config)
    s = res.summary
    assert s.preset == "example-calliper"
    assert "extrapolation" not in s.to_json()  # 0.15 … 0.75 MPa lie in the model's 0.1 … 1.2 MPa
    case = json.loads(res.dataset.attrs["setup_json"])
    assert case["preset"] == "example-calliper" and case["contact_area_m2"] == 4e-3 and case["mass_kg"] == 5.0
    assert json.loads(res.dataset.attrs["config_json"])["machine"] == "example-calliper"


@pytest.mark.parametrize("args, word", [
    (["simulate", "--machine", "nope"], "unknown machine 'nope'"),
    (["simulate", "--machine", "example-calliper"], "no friction-process model of its own"),
    (["simulate", "--machine", "brake", "--preset", "brake"], "not both"),
    (["study", "damping", "--machine", "missing.toml"], "machine"),
])
def test_machine_options_fail_in_one_line(args: list[str], word: str) -> None:
    from typer.testing import CliRunner

    from stochfric.cli import app

    r = CliRunner().invoke(app, args)
    assert r.exit_code == 2, r.output
    assert word in r.output and "Traceback" not in r.output


def test_a_bad_machine_file_fails_with_the_key(tmp_path: Path) -> None:
    from typer.testing import CliRunner

    from stochfric.cli import app

    bad = tmp_path / "rig.toml"
    bad.write_text('name = "rig"\nmass_kg = -5\nstiffness_n_per_m = 3e6\nbelt_speed_m_s = 0.3\n'
                   'contact_area_m2 = 4e-3\nnormal_force_n = [500, 4000]\n', encoding="utf-8")
    r = CliRunner().invoke(app, ["simulate", "--machine", str(bad), "--process", _model_file(tmp_path)])
    assert r.exit_code == 2 and "mass_kg" in r.output and "Traceback" not in r.output

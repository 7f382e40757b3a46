"""No silent extrapolation (issue 30, item 3): a process model records the pressures it was fitted on, and
simulate, every study and a machine refuse to use it outside them unless told to, then stamp every output."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.friction_process.model import ModelFunction
from stochfric.friction_process.model_base import ExtrapolationError, check_pressure_range, fitted_pressure_range
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.oscillator.case import FrictionInput, PhysicalInput, build_case, case_setup
from stochfric.oscillator.presets import brake
from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import DampingStudy
from stochfric.studies.errors import StudyConfigError


def _model(lo: float = 1.27e6, hi: float = 6.87e6, fitted: tuple[float, float] | None = None) -> TabulatedProcessModel:
    length, dx = 0.05, 0.0005
    f = np.arange(1, 50) / length
    table = np.stack([np.full(f.size, 1e-5), np.full(f.size, 2e-5)])
    return TabulatedProcessModel(name="user surface", mu_mean=ModelFunction(a=0.0, b=1.0, c=0.3),
                                 mu_std=ModelFunction(a=0.0, b=1.0, c=0.03), dx=dx, length=length,
                                 pressures_pa=(lo, hi), table_frequencies=tuple(f),
                                 table_psd=tuple(tuple(r) for r in table), fitted_range_pa=fitted)


def _write(tmp_path: Path, model: TabulatedProcessModel) -> Path:
    path = tmp_path / "model.json"
    path.write_text(json.dumps(model.to_dict()), encoding="utf-8")
    return path


def test_the_range_is_recorded_and_read_back(tmp_path: Path) -> None:
    m = _model(fitted=(1.5e6, 6e6))
    assert fitted_pressure_range(m) == (1.5e6, 6e6)
    assert fitted_pressure_range(_model()) == (1.27e6, 6.87e6)  # files without the field: the table's range
    back = TabulatedProcessModel.from_dict(json.loads(json.dumps(m.to_dict())))
    assert back.pressure_range_pa() == (1.5e6, 6e6)
    assert fitted_pressure_range(brake().process) is None  # the thesis's fits record no range


def test_inside_passes_outside_is_refused_or_stamped() -> None:
    m = _model()
    assert check_pressure_range(m, [1.27e6, 3e6, 6.87e6]) is None
    with pytest.raises(ExtrapolationError, match=r"fitted on p = 1\.27–6\.87 MPa.*p = 0\.03125 MPa"):
        check_pressure_range(m, 0.03125e6)
    stamp = check_pressure_range(m, [0.5e6, 8e6], allow=True)
    assert stamp is not None and stamp.startswith("EXTRAPOLATED") and "0.5–8 MPa" in stamp
    with pytest.raises(ValueError, match="fitted_range_pa"):
        _model(fitted=(2e6, 1e6))


def test_simulate_refuses_and_stamps(tmp_path: Path) -> None:
    path = _write(tmp_path, _model())
    # the README example's case: the brake at 500 N over 0.016 m² is 0.031 MPa
    fr = FrictionInput(process_file=path)
    with pytest.raises(ExtrapolationError, match=r"1\.27–6\.87 MPa.*N = 500 N over A = 0\.016"):
        build_case("brake", physical=PhysicalInput(normal_force=500.0), friction=fr, model="contact")
    case = build_case("brake", physical=PhysicalInput(normal_force=500.0), model="contact",
                      friction=FrictionInput(process_file=path, allow_extrapolation=True))
    assert case.extrapolation is not None and case.modes("contact")["extrapolation"] == case.extrapolation
    inside = build_case("brake", physical=PhysicalInput(normal_force=40000.0), model="contact", friction=fr)
    assert inside.extrapolation is None and "extrapolation" not in inside.modes("contact")


def test_the_cli_refuses_with_the_range_and_stamps_when_allowed(tmp_path: Path) -> None:
    path = _write(tmp_path, _model())
    runner = CliRunner()
    args = ["simulate", "--preset", "brake", "--process", str(path), "--normal-force", "500", "--tau-end", "2",
            "--model", "contact", "--json"]
    r = runner.invoke(app, args)
    assert r.exit_code == 2 and "1.27–6.87 MPa" in r.output and "Traceback" not in r.output
    r = runner.invoke(app, [*args, "--allow-extrapolation"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["extrapolation"].startswith("EXTRAPOLATED")


def test_a_study_is_refused_before_any_work_and_stamped_when_allowed(tmp_path: Path) -> None:
    path = str(_write(tmp_path, _model()))
    cfg = dict(machine="example-calliper", process_file=path, models=("deterministic",),
               normal_forces=(500.0, 4000.0), damping_ratios=(0.05, 0.1), tau_end=2.0, phase_runs=0)
    with pytest.raises(ExtrapolationError, match=r"N = 500 N over A = 0\.004"):
        DampingStudy(DampingConfig(**cfg)).tasks()
    study = DampingStudy(DampingConfig(**cfg, allow_extrapolation=True))
    assert study.setup.preset.name == "example-calliper" and study.setup.preset.contact_area == 4e-3
    stamps = study.setup.extrapolation_stamps([500.0, 4000.0])
    assert len(stamps) == 2 and all("A = 0.004" in s for s in stamps)


def test_a_machine_that_is_not_a_thesis_case_needs_a_process_model(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="has no friction-process model of its own"):
        case_setup("example-calliper")
    path = _write(tmp_path, _model(lo=0.1e6, hi=1.2e6))
    setup = case_setup("example-calliper", path)
    assert setup.check_forces([500.0, 4000.0]) == []  # 0.125 … 1 MPa lies inside 0.1 … 1.2 MPa
    with pytest.raises(StudyConfigError, match="machine"):
        DampingConfig(machine=str(tmp_path / "missing.toml"))

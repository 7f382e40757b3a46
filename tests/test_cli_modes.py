"""Every mode recorded (issue 19 §6): ``simulate``'s JSON and NetCDF and a study's NetCDF carry the
white-noise rule, the process level, the path coordinate, the increment and the stream as plain
fields, not only inside a JSON string."""

from __future__ import annotations

import json
from pathlib import Path

from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.oscillator.result import load_result
from stochfric.studies.base import StudyResult

runner = CliRunner()
MODES = ("white_intensity", "process_level", "path_coordinate", "white_increment", "white_stream", "integrator")


def test_simulate_records_every_mode_in_json_and_netcdf(tmp_path: Path) -> None:
    for model, extra, want in (
        ("white", ["--white-intensity", "spectral_level"], {"white_intensity": "spectral_level",
                                                            "process_level": "n/a"}),
        ("contact", ["--process-level", "psd_level", "--path-coordinate", "relative"],
         {"process_level": "psd_level", "path_coordinate": "relative", "white_intensity": "n/a"}),
    ):
        out = tmp_path / model
        res = runner.invoke(app, ["simulate", "--preset", "brake", "--model", model, "--runs", "2",
                                  "--tau-end", "5", "--json", "--out", str(out), *extra])
        assert res.exit_code == 0, res.output
        summary = json.loads(res.stdout)
        ds = load_result(out / "simulation.nc")
        for key in MODES:
            assert key in summary and key in ds.attrs, key
            assert str(summary[key]) == str(ds.attrs[key]), key
        for key, value in want.items():
            assert summary[key] == value, (key, summary[key])
        # the white model's standing is written with every white-noise result (method §5.1a)
        assert ("phenomenological" in summary.get("white_model", "")) == (model == "white")
        assert ("phenomenological" in ds.attrs.get("white_model", "")) == (model == "white")


def test_study_netcdf_records_every_mode(tmp_path: Path) -> None:
    res = runner.invoke(app, ["study", "forcing", "--preset", "sheet", "--runs", "2", "--eta", "1.0",
                              "--tau-end", "20", "--out", str(tmp_path), "--models", "white,contact"])
    assert res.exit_code == 0, res.output
    ds = StudyResult.load(tmp_path, "forcing").dataset
    for key in ("white_intensity", "process_level", "path_coordinate", "white_increment", "integrator",
                "sde_integrator", "seed_rule"):
        assert isinstance(ds.attrs.get(key), str) and ds.attrs[key], key
    assert ds.attrs["process_level"] == "sigma_mu"
    summary = StudyResult.load(tmp_path, "forcing").summary
    assert summary.white_model is not None and summary.white_model.startswith("phenomenological white noise in time")

"""CLI contract of ``stochfric study white-limit`` (issue 19): one-line errors, outputs."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from stochfric.cli import app

runner = CliRunner()


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--lengths", "abc"], "not a number"),
        (["--lengths", "1e-3"], "at least two"),
        (["--lengths", "1e-3,-1e-4"], "positive"),
        (["--lengths", "1e-3,nan"], "positive"),
        (["--lengths", "1e-3,1e-3"], "twice"),
        (["--lengths", "1,1e-3"], "0.1 m"),
        (["--runs", "1"], "runs"),
        (["--refine", "1"], "refine"),
        (["--steps-per-cell", "0"], "steps per grid cell"),
        (["--level-factor", "0"], "level_factor"),
        (["--dt-max", "-1"], "dt_max"),
        (["--normal-force", "-5"], "normal_force "),
        (["--process-length", "inf"], "process_length"),
        (["--plot"], "--out"),
        (["--workers", "0"], "--workers"),
        (["--lengths", "1e-3,1e-9"], "grid points"),
        (["--lengths", "1e-3,2e-7", "--runs", "3000"], "Euler steps"),
    ],
)
def test_bad_options_end_with_one_line(args: list[str], message: str) -> None:
    r = runner.invoke(app, ["study", "white-limit", *args])
    assert r.exit_code == 2, r.output
    assert "Traceback" not in r.output
    lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and lines[0].startswith("error: ") and message in lines[0], r.stderr


def test_unknown_preset_and_path_are_refused_by_the_parser() -> None:
    for args in (["--preset", "foo"], ["--path-coordinate", "position"]):
        r = runner.invoke(app, ["study", "white-limit", *args])
        assert r.exit_code == 2 and "Traceback" not in r.output


def test_an_output_that_is_a_file_is_refused(tmp_path: Path) -> None:
    f = tmp_path / "file"
    f.write_text("x")
    r = runner.invoke(app, ["study", "white-limit", "--out", str(f)])
    assert r.exit_code == 2 and r.stderr.startswith("error: ")


def test_small_run_writes_json_netcdf_and_figure(tmp_path: Path) -> None:
    r = runner.invoke(app, ["study", "white-limit", "--preset", "sheet", "--lengths", "1e-3,1e-4", "--runs", "8",
                            "--tau-end", "12", "--out", str(tmp_path), "--plot", "--json", "--workers", "1"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    assert d["preset"] == "sheet" and d["normal_force_n"] == 880.0
    for key in ("table", "fit", "verdict", "seed", "versions", "units", "low_frequency_psd_m"):
        assert key in d
    for kind in ("json", "netcdf", "figure"):
        assert Path(d["files"][kind]).is_file()
    saved = json.loads((tmp_path / "white_limit_sheet.json").read_text())
    assert saved["table"][0]["correlation_length_m"] == 1e-3
    import xarray as xr

    with xr.open_dataset(tmp_path / "white_limit_sheet.nc") as ds:
        assert ds["x_gh_std"].attrs["units"] == "1"
        assert ds["correlation_length"].attrs["units"] == "m"


def test_help_names_the_command() -> None:
    r = runner.invoke(app, ["study", "white-limit", "--help"])
    assert r.exit_code == 0 and "--lengths" in r.output and "--level-factor" in r.output

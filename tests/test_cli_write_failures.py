"""No traceback when an output cannot be written or an input file holds a wrong value (issue 20 §2):
disk full in the figure writers, a material file with a string or a boolean where a number belongs."""

from __future__ import annotations

import errno
import json
import sys
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

import stochfric.plotting
from stochfric.cli import app
from stochfric.cli.application import main

runner = CliRunner()


def _disk_full(path: Any, writer: Any) -> Path:
    raise OSError(errno.ENOSPC, "No space left on device", str(path))


def test_contact_plot_on_a_full_disk_is_one_line(monkeypatch: pytest.MonkeyPatch, tmp_path: Path) -> None:
    monkeypatch.setattr(stochfric.plotting, "write_atomic", _disk_full)
    res = runner.invoke(app, ["contact", "--material", "brake-pad", "--approach-um", "0.2:0.6:3",
                              "--plot", str(tmp_path / "figs")])
    assert res.exit_code == 2
    assert "could not write the results: No space left on device" in res.output
    assert "Traceback" not in res.output


def test_any_unwritable_output_ends_cleanly_through_main(monkeypatch: pytest.MonkeyPatch,
                                                         capsys: pytest.CaptureFixture[str]) -> None:
    """The console script's last resort: an OSError from any writer is the same one-line message."""
    app_module = sys.modules["stochfric.cli.application"]

    def boom() -> None:
        raise OSError(errno.ENOSPC, "No space left on device", "/somewhere/report.png")

    monkeypatch.setattr(app_module, "app", boom)
    monkeypatch.setattr(sys, "argv", ["stochfric", "reproduce"])
    with pytest.raises(SystemExit) as done:
        main()
    assert done.value.code == 2
    err = capsys.readouterr().err
    assert err.startswith("error: could not write the results: No space left on device (/somewhere/report.png)")


@pytest.mark.parametrize("value", ['"abc"', "true", "null", "[1]"])
def test_material_file_with_a_wrong_value_names_the_file_and_the_key(tmp_path: Path, value: str) -> None:
    fields = {"name": "x", "e2_pa": 2e11, "nu1": 0.3, "nu2": 0.3, "hardness_pa": 1e9, "shear_strength_pa": 1e8,
              "yield_strength_pa": 3e8}
    path = tmp_path / "mat.json"
    path.write_text(json.dumps(fields)[:-1] + f', "e1_pa": {value}}}', encoding="utf-8")
    res = runner.invoke(app, ["contact", "--material", str(path), "--approach-um", "0.2:0.6:3"])
    assert res.exit_code == 2, res.output
    assert f"material file {path}" in res.output and "e1_pa" in res.output
    assert "Traceback" not in res.output


@pytest.mark.parametrize(("key", "value", "says"), [
    ("dx", '"abc"', "dx must be a number"),
    ("length", "true", "length must be a number, not the boolean true"),
    ("falling_ratio", '"half"', "falling_ratio must be a number"),
    ("mu_mean", "null", "wrong type"),
])
def test_process_model_file_with_a_wrong_value_names_the_file(tmp_path: Path, key: str, value: str, says: str) -> None:
    from stochfric.oscillator.presets import brake

    good = tmp_path / "good.json"
    brake().process.save(good)
    data = json.loads(good.read_text(encoding="utf-8"))
    assert key in data
    data[key] = json.loads(value)
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data), encoding="utf-8")
    res = runner.invoke(app, ["simulate", "--preset", "brake", "--model", "contact", "--process", str(bad),
                              "--runs", "2", "--tau-end", "5"])
    assert res.exit_code == 2, res.output
    assert str(bad) in res.output and says in res.output, res.output
    assert "Traceback" not in res.output

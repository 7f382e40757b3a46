"""``stochfric contact-models`` and ``friction-process --contact-model`` (issue 31): the spread of the contact
models from the command line, and one clear line with exit 2 for bad input."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.friction_process.tabulated import TabulatedProcessModel

runner = CliRunner()
FAST = ["--realizations", "3", "--path-surfaces", "0", "--step", "2", "--seed", "1", "--workers", "1"]


def test_contact_models_json_and_files(tmp_path: Path) -> None:
    res = runner.invoke(app, ["contact-models", "--models", "gw,persson", "--pressures-mpa", "0.5:4:3", *FAST,
                              "--out", str(tmp_path / "cm"), "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["models"] == ["gw", "persson"] and len(d["pressure_pa"]) == 3
    assert d["pressure_pa"][0] == pytest.approx(0.5e6)
    assert set(d["per_model"]["gw"]["surrogates"]) >= {"mu_mean", "mu_std", "mu_mean_se"}
    assert d["uncertainty"]["model_half_width"] and d["recommended_models"]
    for key in ("contact_models_file", "contact_models_samples_file", "contact_models_figure"):
        assert Path(d["files"][key]).is_file()


def test_bem_area_is_corrected_unless_asked_for_pixels() -> None:
    """The boundary-element area is the perimeter-corrected one by default and the count with --bem-pixel-area;
    the JSON says which, and the corrected E[μ] is the lower (docs/bem_validation.md §4)."""
    pytest.importorskip("tamaas")
    mu = {}
    for flag in ([], ["--bem-pixel-area"]):
        res = runner.invoke(app, ["contact-models", "--models", "bem", "--pressures-mpa", "2,4", *FAST, *flag,
                                  "--json"])
        assert res.exit_code == 0, res.output
        d = json.loads(res.stdout)
        area = d["load_control"]["bem_area"]
        assert area == ("pixels" if flag else "corrected")
        mu[area] = d["per_model"]["bem"]["surrogates"]["mu_mean"]
    assert all(c < n for c, n in zip(mu["corrected"], mu["pixels"], strict=True))


def test_contact_models_text_table() -> None:
    res = runner.invoke(app, ["contact-models", "--models", "gw,persson", "--pressures-mpa", "1,2", *FAST])
    assert res.exit_code == 0, res.output
    assert "plasticity index" in res.stdout and "E[mu] persson" in res.stdout


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (["--pressures-mpa", "2:1:3"], "START <= STOP"),
        (["--pressures-mpa", "abc"], "START:STOP:NUM"),
        ([], "give the pressures"),
        (["--pressures-mpa", "1", "--machine", "brake"], "give the pressures"),
        (["--pressures-mpa", "1", "--models", "hertz"], "unknown contact model"),
        (["--pressures-mpa", "5000", "--models", "bem-plastic"], "hardness"),
        (["--pressures-mpa", "1", "--bem-solver", "abaqus"], "unknown boundary-element solver"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(args: list[str], message: str) -> None:
    res = runner.invoke(app, ["contact-models", *args, "--realizations", "2", "--path-surfaces", "0"])
    assert res.exit_code == 2, res.output
    lines = [ln for ln in res.stderr.splitlines() if ln.strip()]
    assert len(lines) == 1 and message in lines[0], res.stderr


def test_friction_process_takes_the_chosen_contact_model(tmp_path: Path) -> None:
    out = tmp_path / "fp"
    res = runner.invoke(app, ["friction-process", "--material", "brake-pad", "--realizations", "6", "--long-surfaces",
                              "3", "--length-factor", "3", "--seed", "2", "--contact-model", "persson",
                              "--accept-not-credible", "--out", str(out), "--step", "2"])
    assert res.exit_code in (0, 3), res.output
    assert "contact models" in res.stdout and "persson" in res.stdout
    assert "±grid" not in res.stdout  # no boundary-element model, no grid column
    model = TabulatedProcessModel.load(out / "friction_process.json")
    assert model.contact_model == "persson" and "[persson]" in model.name
    spread = json.loads((out / "contact_models.json").read_text())
    assert spread["models"] == ["gw", "persson"]


def test_friction_process_refuses_an_unknown_contact_model() -> None:
    res = runner.invoke(app, ["friction-process", "--material", "brake-pad", "--contact-model", "hertz"])
    assert res.exit_code == 2 and "unknown contact model" in res.stderr

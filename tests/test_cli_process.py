"""Command ``friction-process`` (built on a private Typer app through ``register``)."""

from __future__ import annotations

import json
import warnings
from pathlib import Path

import numpy as np
import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli.process import register
from stochfric.friction_process.model import TabulatedProcessModel, load_process_model
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions
from stochfric.oscillator.parameters import PhysicalParameters
from stochfric.process.ensemble import default_window_shift_points

#: Few realisations: the checks cannot pass on so few; the mechanics tests accept the result
#: (the gate itself: tests/test_cli_gate.py).
SMALL = ["--realizations", "8", "--long-surfaces", "3", "--length-factor", "4", "--accept-not-credible"]


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    a = typer.Typer()
    register(a)

    @a.command("noop")
    def _noop() -> None:  # a second command keeps Typer from collapsing the group
        pass

    return a


def test_json_outputs_files_and_figures(app: typer.Typer, tmp_path: Path) -> None:
    out = tmp_path / "fp"
    res = CliRunner().invoke(
        app,
        ["friction-process", "--material", "brake-pad", *SMALL, "--seed", "2", "--out", str(out), "--plot", "--json"],
    )
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    n_u = 12
    for key in ("pressure_pa", "mu_mean", "mu_std", "correlation_length_m"):
        assert len(data[key]) == n_u
    assert all(np.diff(data["pressure_pa"]) > 0)
    for name in ("mu_mean", "mu_std", "psd_level"):
        f = data["fit"][name]
        assert {"a", "b", "c", "a_se", "b_se", "c_se"} <= set(f)
    assert data["ergodicity"]["verdict"].endswith("ergodicity")
    assert len(data["sigma_zeta"]["spectral_level"]) == n_u
    model = load_process_model(out / "friction_process.json")
    assert isinstance(model, TabulatedProcessModel)
    assert model.grid_is_periodic and model.dx == pytest.approx(data["window_shift_m"])
    assert (out / "friction_process_statistics.nc").stat().st_size > 0
    assert len(data["figures"]) == 9 and all(Path(f).exists() for f in data["figures"])
    # the model file plugs into the oscillator (what `simulate --process FILE` does)
    params = PhysicalParameters(
        mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0, contact_area=0.016
    ).to_dimensionless()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # the 0.4 mm process is exhausted: expected for a 0.13 mm surface
        sim = simulate(params, model="contact", process=model, runs=1, seed=1,
                       integration=IntegrationOptions(tau_end=2.0))
    assert sim.process is not None and sim.process["kind"] == "tabulated"


def test_same_seed_same_result_and_text_output(app: typer.Typer) -> None:
    args = ["friction-process", "--material", "brake-pad", *SMALL, "--seed", "5", "--approach-um", "0.1:0.5:5"]
    a = CliRunner().invoke(app, [*args, "--json"])
    b = CliRunner().invoke(app, [*args, "--json"])
    assert a.exit_code == 0 and a.stdout == b.stdout
    text = CliRunner().invoke(app, [*args, "--window-shift-um", "20"])
    assert text.exit_code == 0, text.output
    assert "ergodicity" in text.stdout and "fit E[μ]" in text.stdout


def test_iaaft_surrogates(app: typer.Typer) -> None:
    # the held-out validation at its start size (IAAFT iterates FFTs: the default budget would make this the
    # slowest test of the suite)
    tiny = ["--realizations", "3", "--long-surfaces", "3", "--length-factor", "2", "--validation-budget", "4"]
    res = CliRunner().invoke(
        app, ["friction-process", "--material", "brake-pad", *tiny, "--surrogate", "iaaft", "--seed", "1",
              "--window-shift-um", "20", "--approach-um", "0.1:0.5:5", "--sigma-zeta-rule", "spectral_level", "--json",
              "--accept-not-credible"],  # the mechanics; IAAFT fails the held-out test on this non-Gaussian map
    )
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["config"]["surrogate"] == "iaaft"
    assert data["config"]["sigma_zeta_rule"] == data["model"]["sigma_zeta_rule"] == "spectral_level"


@pytest.mark.parametrize(
    ("extra", "message"),
    [
        (["--material", "rubber"], "unknown"),
        (["--material", "brake-pad", "--approach-um", "1:0"], "approach"),
        (["--material", "brake-pad", "--plot"], "--out"),
        (["--material", "brake-pad", "--realizations", "1"], "realizations"),
        (["--material", "brake-pad", "--window-shift-um", "1e5"], "window shift"),
        (["/nonexistent/file.x3p", "--material", "brake-pad"], "file.x3p"),
    ],
)
def test_bad_input_is_one_line_and_exit_2(app: typer.Typer, extra: list[str], message: str) -> None:
    res = CliRunner().invoke(app, ["friction-process", *extra])
    assert res.exit_code == 2, res.output
    assert message in res.output
    assert "Traceback" not in res.output


def test_default_window_shift() -> None:
    assert default_window_shift_points(296) == 16  # 7 µm on the shipped surface → 167 windows
    assert default_window_shift_points(5) == 1

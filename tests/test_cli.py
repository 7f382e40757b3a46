"""Command line: the simulate contract (issue 2) and clean errors."""

from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.oscillator.result import load_result

runner = CliRunner()


def _json(args: list[str]) -> dict:
    res = runner.invoke(app, args)
    assert res.exit_code == 0, res.output
    return json.loads(res.stdout)


def test_simulate_json_contract_brake_preset() -> None:
    d = _json(["simulate", "--preset", "brake", "--model", "white", "--runs", "3", "--seed", "5",
               "--tau-end", "20", "--json"])
    assert len(d["x_gh"]) == 3 and all(isinstance(v, float) for v in d["x_gh"][0])
    assert d["stick_count"] == [len(r) for r in d["x_gh"]]
    assert d["parameters"]["normal_force_n"] == pytest.approx(5600.0)
    assert d["parameters"]["gamma0"] == pytest.approx(1.41421e-3, rel=1e-5)
    assert d["warnings"] == []
    assert d["friction_law"]["name"] == "pressure"
    assert d["sigma_zeta"] == pytest.approx(0.0742, abs=5e-4)  # σ_μ(0.35 MPa), Table 3.3
    assert d["seed_entropy"] == "5" and d["model"] == "white"
    again = _json(["simulate", "--preset", "brake", "--model", "white", "--runs", "3", "--seed",
                   "5", "--tau-end", "20", "--json", "--workers", "1"])
    assert again["x_gh"] == d["x_gh"]


def test_simulate_dimensionless_thesis_demo_matches_closed_form() -> None:
    d = _json(["simulate", "--gamma0", "1", "--n", "10", "--friction-law", "II",
               "--integrator", "accurate", "--tau-end", "30", "--json"])
    assert d["x_gh"][0][0] == pytest.approx(1.0, abs=1e-8)  # n(2μ_k − μ_s)
    assert d["parameters"]["normal_force_n"] is None


def test_simulate_forced_with_coarse_step_warns_in_json() -> None:
    # Euler named: a forced run takes the converged integrator by default (issue 30, item 5)
    d = _json(["simulate", "--gamma0", "1", "--n", "10", "--q", "0.5", "--eta", "1.15", "--integrator", "euler",
               "--x0", "3.2", "1", "--dt", "0.1", "--tau-end", "20", "--json"])
    assert [w["code"] for w in d["warnings"]] == ["coarse-time-step"]
    assert d["x0"] == [3.2, 1.0]


def test_a_forced_run_takes_the_converged_integrator_by_default() -> None:
    forced = _json(["simulate", "--gamma0", "1", "--n", "10", "--q", "0.5", "--eta", "1.15", "--tau-end", "5",
                    "--json"])
    unforced = _json(["simulate", "--gamma0", "1", "--n", "10", "--tau-end", "5", "--json"])
    assert forced["integrator"] == "accurate" and unforced["integrator"] == "euler"


def test_simulate_writes_netcdf_and_plot(tmp_path) -> None:
    out = tmp_path / "run"
    plot = tmp_path / "phase.png"
    res = runner.invoke(app, ["simulate", "--preset", "sheet", "--model", "contact", "--runs", "2",
                              "--seed", "1", "--tau-end", "10", "--out", str(out), "--plot",
                              str(plot)])
    assert res.exit_code == 0, res.output
    assert "E[X_gh]" in res.stdout
    ds = load_result(out / "simulation.nc")
    assert ds.attrs["model"] == "contact"
    assert json.loads((out / "simulation.json").read_text())["preset"] == "sheet"
    assert plot.read_bytes()[:4] == b"\x89PNG"
    plot3 = tmp_path / "forced.png"
    res = runner.invoke(app, ["simulate", "--preset", "brake", "--forcing-amplitude", "500",
                              "--eta", "1.2", "--tau-end", "10", "--plot",
                              str(plot3)])
    assert res.exit_code == 0, res.output
    assert plot3.stat().st_size > 1000


@pytest.mark.parametrize(
    ("args", "fragment"),
    [
        (["--gamma0", "1"], "--gamma0 and --n"),
        (["--mass", "-2", "--stiffness", "1e6", "--belt-speed", "1", "--normal-force", "10"],
         "mass"),
        (["--gamma0", "1", "--n", "1", "--forcing-amplitude", "100"], "SI units"),
        (["--gamma0", "1", "--n", "10", "--model", "contact"], "friction-process model"),
        (["--gamma0", "1", "--n", "10", "--friction-law", "pressure"], "pressure law"),
        (["--preset", "brake", "--dt", "1"], "steps per period"),
        (["--preset", "brake", "--n", "0.1", "--normal-force", "5"], "not both"),
    ],
)
def test_simulate_errors_are_one_line_messages(args: list[str], fragment: str) -> None:
    res = runner.invoke(app, ["simulate", *args])
    assert res.exit_code == 2
    assert "Traceback" not in res.output
    assert fragment in res.output.replace("\n", " ")


def test_simulate_with_a_process_model_file(tmp_path) -> None:
    from stochfric.oscillator.presets import sheet

    path = sheet().process.save(tmp_path / "model.json")
    args = ["--mass", "1", "--stiffness", "1e5", "--belt-speed", "1", "--normal-force", "880",
            "--contact-area", "1e-3", "--model", "contact", "--runs", "2", "--seed", "4",
            "--tau-end", "10", "--json"]
    a = _json(["simulate", "--process", str(path), *args])
    b = _json(["simulate", "--preset", "sheet", "--normal-force", "880", "--damping-ratio", "0",
               "--model", "contact", "--runs", "2", "--seed", "4", "--tau-end", "10", "--json"])
    assert a["process"]["name"] == "sheet"
    assert a["x_gh"] == b["x_gh"]  # the same model from a file gives the same numbers
    # a longer process keeps whole periods on its grid
    c = _json(["simulate", "--preset", "brake", "--model", "contact", "--process-length", "0.2",
               "--runs", "1", "--seed", "1", "--tau-end", "5", "--json"])
    assert c["process"]["length"] == 0.2
    assert 0.2 / c["process"]["dx"] == pytest.approx(round(0.2 / c["process"]["dx"]), abs=1e-9)
    bad = tmp_path / "bad.json"
    bad.write_text("[1, 2]")
    res = runner.invoke(app, ["simulate", "--process", str(bad), *args])
    assert res.exit_code == 2 and "not a friction-process model" in res.output


def test_simulate_white_intensity_rules() -> None:
    base = ["simulate", "--preset", "brake", "--model", "white", "--runs", "2", "--seed", "1",
            "--tau-end", "10", "--json"]
    thesis = _json([*base, "--white-intensity", "sigma_mu"])
    level = _json([*base, "--white-intensity", "spectral_level"])
    default = _json(base)
    assert default["x_gh"] == thesis["x_gh"]  # the thesis's rule is the default
    assert thesis["sigma_zeta"] == pytest.approx(0.0742, abs=5e-4)  # σ_μ(0.35 MPa)
    # one-sided PSD level of the flat brake spectrum S0 = σ_μ²/(K Δf), σ_ζ = S0/2
    assert level["sigma_zeta"] == pytest.approx(0.0742037**2 / (39 * 20.0) / 2, rel=1e-4)
    assert level["process"]["sigma_zeta_rule"] == "spectral_level"
    res = runner.invoke(app, [*base, "--white-intensity", "spectral_level", "--sigma-zeta", "0.1"])
    assert res.exit_code == 2 and "not both" in res.output


def test_simulate_white_streams() -> None:
    """``--white-stream``: the default is the ziggurat stream; Box–Muller (the earlier default) and
    numpy's PCG64 give other realisations; the stream is recorded in the JSON."""
    base = ["simulate", "--preset", "brake", "--model", "white", "--runs", "3", "--seed", "1",
            "--tau-end", "10", "--json"]
    got = {s: _json([*base, "--white-stream", s]) for s in ("philox-ziggurat", "philox-boxmuller", "pcg64")}
    default = _json(base)
    assert default["x_gh"] == got["philox-ziggurat"]["x_gh"]
    assert len({json.dumps(d["x_gh"]) for d in got.values()}) == 3
    for name, d in got.items():
        assert d["white_stream"] == name
    assert runner.invoke(app, [*base, "--white-stream", "mt19937"]).exit_code == 2


def test_simulate_white_intensity_thesis_mode() -> None:
    base = ["simulate", "--preset", "brake", "--model", "white", "--runs", "2", "--seed", "1",
            "--tau-end", "10", "--json"]
    thesis = _json([*base, "--white-intensity", "thesis"])
    assert thesis["white_increment"] == "thesis"
    assert thesis["sigma_zeta"] == pytest.approx(0.0742, abs=5e-4)  # nominal σ_ζ = σ_μ(0.35 MPa)
    # printed (4.31): σ_ζ,eff = σ_ζ · Lω0 · Δτ (ω0 = √(1e6/2) rad/s, Δτ = 0.005)
    assert thesis["sigma_zeta_effective"] == pytest.approx(thesis["sigma_zeta"] * 707.1068 * 0.005, rel=1e-6)
    explicit = _json([*base, "--sigma-zeta", repr(thesis["sigma_zeta_effective"])])
    assert explicit["x_gh"] == thesis["x_gh"]  # the mode is exactly Itô EM with σ_ζ,eff
    default = _json(base)
    assert default["white_increment"] == "ito" and default["x_gh"] != thesis["x_gh"]


def test_simulate_process_level_psd_level() -> None:
    base = ["simulate", "--preset", "sheet", "--normal-force", "880", "--model", "contact", "--runs", "2",
            "--seed", "1", "--tau-end", "10", "--json"]
    d = _json([*base, "--process-level", "psd_level"])
    assert d["process"]["kind"] == "psd_level" and d["process"]["calibration"] == pytest.approx(0.06293, rel=1e-3)
    assert _json(base)["process"]["kind"] == "band_limited"
    res = runner.invoke(app, ["simulate", "--gamma0", "1", "--n", "10", "--process-level", "psd_level"])
    assert res.exit_code == 2 and "preset" in res.output


def test_case_errors_name_the_flags() -> None:
    """The case speaks in field names; the command line shows its flags (cli.options.FLAGS)."""
    res = runner.invoke(app, ["simulate", "--preset", "brake", "--normal-force", "1000", "--n", "0.001"])
    assert res.exit_code == 2
    assert "give the normal force as --normal-force N [N] or --n, not both" in res.stderr
    res = runner.invoke(app, ["simulate", "--gamma0", "1", "--n", "1", "--model", "contact"])
    assert res.exit_code == 2 and "give a --preset or a --process" in res.stderr

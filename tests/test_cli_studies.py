"""CLI contract of ``stochfric study …``, ``run`` and ``reproduce`` (JSON keys, errors)."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli.studies import register


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    a = typer.Typer()
    register(a)

    @a.callback()
    def _root() -> None:
        """test root"""

    return a


runner = CliRunner()


def _json(app: typer.Typer, args: list[str]) -> dict:
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_damping_json_contract(app: typer.Typer) -> None:
    d = _json(app, ["study", "damping", "--preset", "brake", "--normal-force", "5600",
                    "--damping-ratio", "0.05:0.25:41", "--runs", "10", "--json"])
    for key in ("normal_force_n", "damping_ratio", "d_max_deterministic", "d_max_sample_extreme", "d_hopf",
                "risk_levels", "d_max_risk", "stick_probability", "m_diff", "seed", "versions"):
        assert key in d, key
    assert "d_safe" not in d and "d_max_stochastic" not in d  # issue 19: no "safe" sample extreme
    assert d["normal_force_n"] == [5600.0] and len(d["damping_ratio"]) == 41
    assert d["d_max_deterministic"] == [0.14]
    assert d["d_hopf"][0] == pytest.approx(0.0946, abs=1e-4)
    for m in ("white", "contact"):
        e = d["d_max_sample_extreme"][m][0]
        assert set(e) == {"value", "interval"} and e["interval"][0] == e["value"]
        r = d["d_max_risk"][m][0]  # per risk level: 10 %, 1 % by default; 10 runs resolve neither
        assert [x["risk_level"] for x in r] == [0.1, 0.01] and all(x["high_open"] and not x["resolved"] for x in r)
    assert d["tasks"]["computed"] == 6  # 3 grid tasks + 3 phase-diagram tasks (one per model)
    # the thesis's modelling choices are the defaults and are recorded
    assert d["path_coordinate"] == "mass" and d["white_intensity"] == "sigma_mu"
    assert d["sigma_zeta"][0] == pytest.approx(0.0742, abs=5e-4)  # σ_μ(0.35 MPa)
    # phase diagrams over D at the preset's force (Fig. 4.22): auto D from the lowest grid D to above D_max
    ph = d["phase"]
    assert ph["normal_force_n"] == 5600.0 and ph["damping_rule"] == "auto"
    assert len(ph["damping_ratio"]) == 5 and ph["damping_ratio"][0] == 0.05
    assert ph["damping_ratio"][-1] > max(d["d_max_deterministic"][0],
                                           d["d_max_sample_extreme"]["contact"][0]["value"])
    assert ph["runs"] == {"deterministic": 1, "white": 3, "contact": 3}
    # docs/studies.md quotes this run (issue 32: quoted numbers are the numbers the example prints)
    docs = " ".join((Path(__file__).resolve().parents[1] / "docs" / "studies.md").read_text(encoding="utf-8").split())
    quoted = re.search(r"seed 0 \(D_max\^d / D_max\^s white / contact = ([\d.]+) / ([\d.]+) / ([\d.]+)\): D = "
                       r"([\d., ]+?) \(`tests/test_cli_studies.py`", docs)
    assert quoted is not None, "docs/studies.md no longer quotes the seed-0 damping example"
    printed = (d["d_max_deterministic"][0], d["d_max_sample_extreme"]["white"][0]["value"],
               d["d_max_sample_extreme"]["contact"][0]["value"])
    assert tuple(float(quoted.group(k)) for k in (1, 2, 3)) == printed
    assert [float(v) for v in quoted.group(4).split(",")] == ph["damping_ratio"]


def test_other_studies_json(app: typer.Typer, tmp_path: Path) -> None:
    f = _json(app, ["study", "forcing", "--eta", "0.5,1.5", "--runs", "3", "--json", "--out", str(tmp_path)])
    assert {"x_gh_mean", "x_gh_std", "sigma_ratio", "sigma_ratio_median"} <= set(f)
    assert (tmp_path / "forcing.nc").exists() and (tmp_path / "forcing.json").exists()
    ly = _json(app, ["study", "lyapunov", "--normal-force", "4000", "--q", "5e-4", "--eta", "1.2", "--runs", "2",
                     "--tau-end", "60", "--json"])
    assert {"lyapunov", "status", "n_transitions", "perturbation"} <= set(ly)
    assert ly["status"]["deterministic"][0][0][0] in ("ok", "merged", "too-few-transitions")
    nf = _json(app, ["study", "normal-force", "--preset", "sheet", "--runs", "3", "--phase-runs", "1", "--json"])
    assert {"x_gh_mean", "x_gh_std", "varK", "varK_se", "x_gh_mean_se"} <= set(nf)
    assert nf["normal_force_n"] == [400.0, 880.0, 1750.0] and nf["damping_ratio"] == [5e-6, 0.17]
    assert nf["layout"] == "model -> [normal_force_n][damping_ratio]" and len(nf["x_gh_mean"]["white"]) == 3


def test_human_output_and_report(app: typer.Typer, tmp_path: Path) -> None:
    r = runner.invoke(app, ["study", "damping", "--normal-force", "4000,6000", "--damping-ratio", "0.1:0.2:3",
                            "--runs", "2", "--report", str(tmp_path / "rep"), "--checkpoint", str(tmp_path / "ck")])
    assert r.exit_code == 0, r.output
    assert "D_max^d" in r.output and "D_H" in r.output
    assert (tmp_path / "rep" / "index.html").exists()
    r2 = runner.invoke(app, ["study", "damping", "--normal-force", "4000,6000", "--damping-ratio", "0.1:0.2:3",
                             "--runs", "2", "--checkpoint", str(tmp_path / "ck"), "--json"])
    assert json.loads(r2.stdout)["tasks"] == {"computed": 0, "loaded_from_checkpoint": 9}  # 6 grid + 3 phase


@pytest.mark.parametrize(
    ("args", "needle"),
    [
        (["study", "damping", "--damping-ratio", "0.3:0.1:x"], "START and STOP"),
        (["study", "damping", "--runs", "0"], "--runs"),
        (["study", "damping", "--models", "white,pink"], "--models"),
        (["study", "forcing", "--preset", "car"], "preset"),
        (["study", "damping", "--process", "/nonexistent/model.json"], "cannot read"),
        (["study", "damping", "--executor", "mpi"], "unknown executor"),
        (["study", "damping", "--white-intensity", "pink"], "--white-intensity"),
        (["study", "forcing", "--white-intensity", "sigma"], "'sigma_mu', 'spectral_level' or 'thesis'"),
        (["study", "lyapunov", "--path-coordinate", "global"], "--path-coordinate"),
        (["study", "normal-force", "--path-coordinate", "x"], "'mass', 'relative' or 'position'"),
        (["study", "damping", "--phase-damping", "0.1,1.5"], "--phase-damping"),
        (["study", "damping", "--phase-force", "-5"], "--phase-force:"),
        # issue 19: the risk levels of D_max(α)
        (["study", "damping", "--risk-levels", "1.5"], "--risk-levels: risk levels must lie in (0, 1)"),
        (["study", "damping", "--risk-levels", "0,0.1"], "--risk-levels: risk levels must lie in (0, 1)"),
        (["study", "damping", "--risk-levels", "-0.1"], "--risk-levels: risk levels must lie in (0, 1)"),
        (["study", "damping", "--risk-levels", "nan"], "--risk-levels: risk levels must lie in (0, 1)"),
        (["study", "damping", "--risk-levels", ""], "--risk-levels: give at least one risk level"),
        (["study", "damping", "--risk-levels", " , "], "--risk-levels: give at least one risk level"),
        (["study", "damping", "--risk-levels", "ten"], "--risk-levels: 'ten' is not a comma-separated"),
        (["study", "damping", "--risk-levels", "0.1,0.1"], "--risk-levels: a risk level is listed twice"),
    ],
)
def test_errors_exit_2(app: typer.Typer, args: list[str], needle: str) -> None:
    r = runner.invoke(app, args)
    assert r.exit_code == 2
    assert "error:" in r.output and needle in r.output
    assert "Traceback" not in r.output
    assert len(r.output.strip().splitlines()) == 1, r.output


def test_white_intensity_and_path_coordinate(app: typer.Typer, tmp_path: Path) -> None:
    base = ["study", "damping", "--normal-force", "5600", "--damping-ratio", "0.1:0.2:5", "--runs", "3", "--json"]
    thesis = _json(app, base)
    level = _json(app, [*base, "--white-intensity", "spectral_level", "--out", str(tmp_path)])
    assert thesis["white_intensity"] == "sigma_mu" and level["white_intensity"] == "spectral_level"
    assert thesis["sigma_zeta"][0] == pytest.approx(0.0742, abs=5e-4)
    # the flat brake spectrum: S0 = σ_μ²/(K Δf), σ_ζ = S0/2
    assert level["sigma_zeta"][0] == pytest.approx(0.0742037**2 / (39 * 20.0) / 2, rel=1e-3)
    for key in ("stick_probability", "stick_count_mean"):  # deterministic and contact results do not depend on the rule
        for m in ("deterministic", "contact"):
            assert thesis[key][m] == level[key][m], (key, m)
    import xarray as xr

    with xr.open_dataset(tmp_path / "damping.nc", engine="h5netcdf") as ds:
        assert ds.attrs["white_intensity"] == "spectral_level" and ds.attrs["path_coordinate"] == "mass"
        assert json.loads(ds.attrs["setup_json"])["process"]["sigma_zeta_rule"] == "spectral_level"
        assert float(ds["sigma_zeta"].sel(model="white").values[0]) == pytest.approx(level["sigma_zeta"][0])
    rel = _json(app, [*base, "--path-coordinate", "relative"])
    assert rel["path_coordinate"] == "relative"
    assert rel["stick_count_mean"]["deterministic"] == thesis["stick_count_mean"]["deterministic"]
    for kind, extra in (("forcing", ["--eta", "1.0"]), ("normal-force", ["--phase-runs", "0"]),
                        ("lyapunov", ["--normal-force", "4000", "--q", "5e-4", "--eta", "1.2", "--tau-end", "30"])):
        s = _json(app, ["study", kind, "--runs", "2", "--white-intensity", "spectral_level",
                        "--path-coordinate", "relative", *extra, "--json"])
        assert s["white_intensity"] == "spectral_level" and s["path_coordinate"] == "relative", kind
        sz = s["sigma_zeta"] if isinstance(s["sigma_zeta"], list) else [s["sigma_zeta"]]
        assert all(v < 1e-4 for v in sz), kind


def test_phase_options(app: typer.Typer) -> None:
    d = _json(app, ["study", "damping", "--preset", "sheet", "--normal-force", "1000,2000",
                    "--damping-ratio", "0.1:0.2:3", "--runs", "2", "--phase-damping", "0.12,0.05", "--phase-runs", "2",
                    "--json"])
    # the sheet's damping-study force 1400 N is not on the grid: the middle force is used
    assert d["phase"]["normal_force_n"] == 1000.0
    assert d["phase"]["damping_ratio"] == [0.05, 0.12] and d["phase"]["damping_rule"] == "given"
    assert d["phase"]["runs"] == {"deterministic": 1, "white": 2, "contact": 2}
    d = _json(app, ["study", "damping", "--normal-force", "5600", "--damping-ratio", "0.1,0.2", "--runs", "2",
                    "--phase-force", "3000", "--phase-runs", "0", "--json"])
    assert "phase" not in d and d["tasks"]["computed"] == 3


def test_process_file(app: typer.Typer, tmp_path: Path) -> None:
    from stochfric.oscillator.presets import get_preset

    path = tmp_path / "model.json"
    get_preset("brake").process.save(path)
    a = _json(app, ["study", "damping", "--damping-ratio", "0.1,0.15", "--runs", "2", "--json"])
    b = _json(app, ["study", "damping", "--damping-ratio", "0.1,0.15", "--runs", "2", "--process", str(path), "--json"])
    assert b["process_source"].startswith("file:")
    assert a["stick_probability"] == b["stick_probability"]


def test_run_toml(app: typer.Typer, tmp_path: Path) -> None:
    f = tmp_path / "study.toml"
    f.write_text(f"""
[defaults]
seed = 4
runs = 2
[execution]
executor = "serial"
checkpoint = "{(tmp_path / 'ck').as_posix()}"
[output]
dir = "{(tmp_path / 'out').as_posix()}"
report = true
[[study]]
kind = "damping"
normal_forces = [5600]
damping_ratios = "0.1:0.2:3"
white_intensity = "spectral_level"
path_coordinate = "relative"
phase_damping_ratios = [0.1, 0.2]
[[study]]
kind = "forcing"
eta = [1.0]
""")
    d = _json(app, ["run", str(f), "--json"])
    assert [s["study"] for s in d["studies"]] == ["damping", "forcing"]
    dmp, frc = d["studies"]
    assert dmp["white_intensity"] == "spectral_level" and dmp["path_coordinate"] == "relative"
    assert dmp["phase"]["damping_ratio"] == [0.1, 0.2]
    assert frc["white_intensity"] == "sigma_mu" and frc["path_coordinate"] == "mass"
    assert (tmp_path / "out" / "index.html").exists()
    assert (tmp_path / "out" / "00_damping_brake" / "damping.nc").exists()
    bad = tmp_path / "bad.toml"
    bad.write_text("[[study]]\nkind = 'damping'\nrunz = 3\n")
    r = runner.invoke(app, ["run", str(bad)])
    assert r.exit_code == 2 and "study[0].runz" in r.output


def test_reproduce_quick(app: typer.Typer, tmp_path: Path) -> None:
    d = _json(app, ["reproduce", "--quick", "--out", str(tmp_path), "--json"])
    # timings are reported, never asserted (a test must pass on a busy machine; targets live in benchmarks/)
    assert d["timings_s"]["total"] > 0
    assert (tmp_path / "index.html").exists()
    page = (tmp_path / "index.html").read_text(encoding="utf-8")
    for name in ("01_damping_brake_phase.png", "05_damping_sheet_phase.png"):  # Fig. 4.22 / 4.53 analogues
        assert (tmp_path / name).exists() and f'src="{name}"' in page, name
    assert "Phase curves at N = 5600 N" in page and "Phase curves at N = 1400 N" in page
    assert page.count("white-noise intensity rule: sigma_mu") == 8  # every study shows its choices


def test_position_reproduction_mode_runs_the_forced_studies_on_euler(app: typer.Typer) -> None:
    """The forced studies default to 'accurate' (issue 19 §3), but path_coordinate 'position' exists for Euler
    only: without an integrator it runs on euler (recorded as a reproduction); with 'accurate' it is refused."""
    from stochfric.studies.config import ForcingConfig, LyapunovConfig

    assert ForcingConfig().integrator == "accurate"
    assert ForcingConfig(path_coordinate="position").integrator == "euler"
    assert LyapunovConfig(path_coordinate="position").integrator == "euler"
    res = runner.invoke(app, ["study", "forcing", "--path-coordinate", "position", "--integrator", "accurate"])
    assert res.exit_code == 2
    assert res.output.startswith("error: path_coordinate 'position' (a reproduction mode) runs on the fixed-step")

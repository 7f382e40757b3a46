"""`stochfric assess` (issue 30, item 2): the user's surface on the user's machine.  Small settings: the
numbers are not the point here, the contract is (exit codes, refusals with reasons, the first screen, files)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.contact.materials import get_material
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.studies.assess import AssessSettings, PressureCoverageError, approach_for_pressures, assess
from stochfric.surface.io import default_surface_path
from stochfric.surface.scans import load_scan

RIG = """name = "test-rig"
mass_kg = 5.0
stiffness_n_per_m = 3.0e6
belt_speed_m_s = 0.3
contact_area_m2 = 4.0e-3
normal_force_n = [{lo}, {hi}]
damping_ratio = 0.05
damping_ratio_range = [0.0, 0.3]
[friction_law]
law = "pressure"
mu0 = {mu0}
"""
SMALL = AnalysisConfig(realizations=4, long_surfaces=3, holdout_realizations=4, holdout_max_realizations=4, seed=1)


def _rig(tmp_path: Path, lo: float = 2800.0, hi: float = 4000.0, mu0: float = 0.8) -> Path:
    path = tmp_path / "rig.toml"
    path.write_text(RIG.format(lo=lo, hi=hi, mu0=mu0), encoding="utf-8")
    return path


def test_pressures_the_measurement_cannot_carry_are_refused_with_the_reason() -> None:
    scan = load_scan(default_surface_path(), fill_undefined=True)
    mat = get_material("brake-pad")
    with pytest.raises(PressureCoverageError, match=r"only \d+ summits.*at least 20"):
        approach_for_pressures([scan.coarse], mat, (0.0125e6, 0.1e6), SMALL)
    with pytest.raises(PressureCoverageError, match="non-interaction range"):
        approach_for_pressures([scan.coarse], mat, (1e6, 500e6), SMALL)


def test_a_not_credible_analysis_exits_3_before_any_study(tmp_path: Path) -> None:
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["assess", str(default_surface_path()), "--material", "brake-pad", "--machine",
                                 str(_rig(tmp_path)), "--out", str(out), "--realizations", "4", "--fill-undefined",
                                 "--seed", "1"])
    assert r.exit_code == 3, r.output
    data = json.loads((out / "assess.json").read_text(encoding="utf-8"))
    # 4 realisations: the rank tests cannot decide a failure, so the gate says "undecided" (exit 3 all the same)
    assert data["status"] in ("not credible", "undecided") and data["reasons"] and data["forces"] == []
    assert not (out / "damping").exists()  # no study ran
    assert (out / "report.html").is_file() and f"status:     {data['status']}" in r.output


def test_forced_assessment_runs_the_studies_and_says_so_first(tmp_path: Path) -> None:
    settings = AssessSettings(runs=2, refine=False, forces=1, damping_points=2, tau_end=5.0, analysis=SMALL,
                              accept_not_credible=True, normal_force_study=False, workers=1)
    res = assess([default_surface_path()], "brake-pad", _rig(tmp_path), out=tmp_path / "o", settings=settings,
                 fill_undefined=True)
    assert res.exit_code == 0 and res.forced
    screen = res.first_screen()
    assert screen[0].startswith("WARNING: the surface analysis is NOT credible")
    assert any(line.startswith("machine:    test-rig") for line in screen)
    assert [f.normal_force_n for f in res.forces] == [3400.0]  # forces=1: the machine's default (midpoint)
    v = res.forces[0]
    assert v.risk in ("stick-slip", "no stick-slip", "undecided") and v.pressure_pa == v.normal_force_n / 4e-3
    assert (tmp_path / "o" / "damping" / "damping.json").is_file()
    lo, hi = res.analysis.analysis.model.pressure_range_pa()
    assert lo <= 2800.0 / 4e-3 and hi >= 4000.0 / 4e-3  # analysed at the machine's pressures


def test_a_static_coefficient_below_the_surface_mu_is_bad_input(tmp_path: Path) -> None:
    r = CliRunner().invoke(app, ["assess", str(default_surface_path()), "--material", "brake-pad", "--machine",
                                 str(_rig(tmp_path, mu0=0.3)), "--out", str(tmp_path / "o"), "--realizations", "4",
                                 "--fill-undefined", "--accept-not-credible", "--seed", "1"])
    assert r.exit_code == 2 and "mu0" in r.output and "Traceback" not in r.output


@pytest.mark.parametrize("args, word", [(["--runs", "0"], "runs"), (["--machine", "nope.toml"], "machine"),
                                        (["--material", "unobtainium"], "unobtainium")])
def test_bad_options_exit_2_in_one_line(tmp_path: Path, args: list[str], word: str) -> None:
    base = {"--material": "brake-pad", "--machine": "example-calliper", "--out": str(tmp_path / "o")}
    for k, v in zip(args[::2], args[1::2], strict=True):
        base[k] = v
    flat = [x for kv in base.items() for x in kv]
    r = CliRunner().invoke(app, ["assess", str(default_surface_path()), *flat])
    assert r.exit_code == 2 and word in r.output and "Traceback" not in r.output


def test_the_contact_model_is_named_and_its_spread_reported(tmp_path: Path) -> None:
    """Issue 31: --contact-model makes the first screen name the model the studies would read and put the
    model-choice part of "how sure" in numbers (here a not-credible run: the lines come before any study)."""
    out = tmp_path / "out"
    r = CliRunner().invoke(app, ["assess", str(default_surface_path()), "--material", "brake-pad", "--machine",
                                 str(_rig(tmp_path)), "--out", str(out), "--realizations", "4", "--fill-undefined",
                                 "--seed", "1", "--contact-model", "persson"])
    assert r.exit_code == 3, r.output
    screen = json.loads((out / "assess.json").read_text(encoding="utf-8"))["first_screen"]
    contact = next(line for line in screen if line.startswith("contact:"))
    assert "Persson's theory" in contact and "models gw, persson differ by up to" in contact
    assert any(line.startswith("model choice: E[μ] over gw, persson spans") for line in screen)
    assert (out / "friction_process" / "contact_models.json").is_file()


@pytest.mark.slow
def test_a_credible_surface_gives_a_verdict_without_forcing(tmp_path: Path) -> None:
    """The path a user wants: scans whose surface model is credible give exit 0 and a verdict per force, no
    --accept-not-credible.  No shared scan is credible (docs/statistical_contact.md §0d), so nine 512² crops of a
    synthetic Gaussian surface whose random-phase model is exact (docs/examples/gaussian_scans.py) on the
    calliper rig of docs/assess.md.  Slow tier: about 1 min on 2 cores."""
    import subprocess
    import sys

    root = Path(__file__).resolve().parents[1]
    subprocess.run([sys.executable, str(root / "docs/examples/gaussian_scans.py"), str(tmp_path / "scans")],
                   check=True, capture_output=True)
    scans = sorted((tmp_path / "scans").glob("*.npy"))
    settings = AssessSettings(runs=2, refine=False, forces=1, damping_points=3, tau_end=5.0, workers=2,
                              analysis=AnalysisConfig(realizations=40, long_surfaces=3, seed=1, surrogate="phase"),
                              normal_force_study=False)
    res = assess(scans, "brake-pad", root / "docs/examples/calliper-rig.toml", out=tmp_path / "o", settings=settings,
                 physical_size_m=(1596.24e-6, 1596.24e-6), height_unit="m")
    assert res.exit_code == 0 and res.status == "verdict" and not res.forced, res.reasons
    screen = res.first_screen()
    assert not screen[0].startswith("WARNING") and any("the surface model is credible" in line for line in screen)
    assert len(res.forces) == 1 and (tmp_path / "o" / "damping" / "damping.json").is_file()

"""Every saved result reads back as its typed object (issue 32, item 6): each type's ``load(path)`` and
``stochfric.load(path)``, which tells the kind from the file's stamped metadata; bad paths and files of
another kind end in one clear error naming the path.

Small results, built in seconds: a hand-made simulation, the smallest damping and white-limit studies, one
96 × 96 synthetic map analysed with 4 realisations (its statistics, model and GW contact-model spread), a
GW contact result and an assessment assembled from a shipped machine.
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Any

import numpy as np
import pytest
import xarray as xr

import stochfric as sf
from stochfric.contact.asperity import ContactResult, asperity_contact
from stochfric.contact.materials import get_material
from stochfric.io_utils import ResultFileError, write_netcdf_atomic
from stochfric.oscillator.friction_laws import law_III, pressure_law
from stochfric.oscillator.parameters import OscillatorParameters, PhysicalParameters
from stochfric.oscillator.result import SimulationResult, SimulationWarning, load_result
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.contact_models import ContactModelSpread, contact_model_spread
from stochfric.process.pipeline import STATISTICS_FILE, write_spread
from stochfric.process.saved import SavedAnalysis
from stochfric.studies.base import StudyResult
from stochfric.studies.damping import DampingSummary, damping_study
from stochfric.studies.errors import StudyError
from stochfric.studies.loading import KNOWN_RESULTS, SavedAssessment
from stochfric.studies.white_limit import WhiteLimitConfig, WhiteLimitResult, white_limit_study
from synthetic_maps import as_surface, gaussian_heights  # tests/synthetic_maps.py

PAD = get_material("brake-pad")


def _same(a: Any, b: Any) -> bool:
    """Equal as JSON (NaN equal to NaN, numpy values as Python's)."""
    def norm(x: Any) -> str:
        return json.dumps(x, sort_keys=True, default=lambda v: v.tolist() if hasattr(v, "tolist") else str(v))

    return norm(a) == norm(b)


# --- simulation ------------------------------------------------------------------------------------------


def _simulation() -> SimulationResult:
    brake = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0, damping_ratio=5e-6,
                               contact_area=0.016).to_dimensionless()
    bare = OscillatorParameters(gamma0=1.0, n=10.0, q=0.5, eta=1.15)
    x_gh = np.full((2, 2, 3), np.nan)
    x_gh[0, 0, :2] = [1.5e-3, 1.6e-3]
    x_gh[1, 0, :3] = [0.9, 1.1, 1.0]
    traj = np.zeros((2, 2, 4, 3))
    traj[..., 0] = [0.0, 0.05, 0.1, 0.15]
    traj[..., 1] = np.arange(16).reshape(2, 2, 4) * 1e-3
    traj[..., 2] = 1.0
    return SimulationResult(
        params=[brake, bare], x_gh=x_gh, t_gh=np.where(np.isfinite(x_gh), 10.0 * np.arange(3), np.nan),
        stick_count=np.array([[2, 0], [5, 0]], dtype=np.int64),
        diagnostics={"path": np.array([[0.01, 0.02], [3.0, 4.0]]), "n_breakaway": np.array([[2.0, 1.0], [5.0, 0.0]])},
        trajectory=traj, model="white", integrator="milstein", dt=0.005, tau_end=50.0, runs=2,
        seed_entropy=2**100 + 12345, path_coordinate="relative", x0=[(0.0, brake.gamma0), (3.2, 1.0)],
        laws=[pressure_law(0.28).to_dict(), law_III().to_dict()], sigma_zeta=[0.0742, 0.0],
        process={"kind": "band-limited", "dx_m": 6.3e-4},
        warnings=[SimulationWarning("event-buffer-full", "1 trajectories had more than max_events = 3")],
        settings={"max_events": 3, "rtol": 1e-11, "sigma_zeta_effective": [0.26, 0.0], "white_increment": "ito"},
        versions={"stochfric": "0.1.0", "numpy": np.__version__},
    )  # fmt: skip


def test_a_simulation_reads_back_as_the_typed_result(tmp_path: Path) -> None:
    res = _simulation()
    path = res.to_netcdf(tmp_path / "sim.nc")
    again = SimulationResult.load(path)
    assert type(again) is SimulationResult
    assert again.params == res.params and again.x0 == res.x0 and again.warnings == res.warnings
    for name in ("x_gh", "t_gh", "stick_count", "trajectory"):
        np.testing.assert_array_equal(getattr(again, name), getattr(res, name))  # NaN padding included
    assert again.stick_count.dtype == np.int64
    assert list(again.diagnostics) == ["path", "n_breakaway"]
    np.testing.assert_array_equal(again.diagnostics["path"], res.diagnostics["path"])
    assert again.seed_entropy == res.seed_entropy  # 128-bit entropy, exactly
    for name in ("model", "integrator", "dt", "tau_end", "runs", "path_coordinate", "laws", "sigma_zeta", "process",
                 "settings", "versions"):
        assert getattr(again, name) == getattr(res, name), name
    xr.testing.assert_identical(again.to_dataset(), load_result(path))  # saving it again writes the same file
    assert again.to_json_dict(1) == res.to_json_dict(1)
    assert type(sf.load(path)) is SimulationResult


def test_the_command_lines_attributes_are_kept(tmp_path: Path) -> None:
    """``stochfric simulate --out`` adds the case's modes as attributes: kept, and written again."""
    ds = _simulation().to_dataset()
    ds.attrs.update({"white_intensity": "sigma_mu", "process_level": "n/a", "white_model": "thesis"})
    path = write_netcdf_atomic(tmp_path / "out" / "simulation.nc", ds)
    again = sf.load(path)
    assert again.attrs == {"white_intensity": "sigma_mu", "process_level": "n/a", "white_model": "thesis"}
    xr.testing.assert_identical(again.to_dataset(), load_result(path))
    (tmp_path / "out" / "simulation.json").write_text(json.dumps(again.to_json_dict()), encoding="utf-8")
    from_json = sf.load(tmp_path / "out" / "simulation.json")  # the summary points to the record beside it
    np.testing.assert_array_equal(from_json.x_gh, again.x_gh)
    path.unlink()
    with pytest.raises(FileNotFoundError, match=r"simulation\.json is the JSON summary of a simulation.*"
                                                r"simulation\.nc beside it"):
        sf.load(tmp_path / "out" / "simulation.json")


# --- studies ---------------------------------------------------------------------------------------------


def test_a_study_reads_back_from_either_file_or_its_directory(tmp_path: Path) -> None:
    res = damping_study(sf.DampingConfig(normal_forces=(5600.0,), damping_ratios=(0.1, 0.2), runs=2, seed=1,
                                         phase_runs=0, tau_end=10.0))
    res.save(tmp_path)
    again = sf.load(tmp_path / "damping.nc")
    assert isinstance(again, StudyResult) and again.kind == "damping" and isinstance(again.summary, DampingSummary)
    assert _same(again.to_json_dict(), res.to_json_dict())
    xr.testing.assert_equal(again.dataset, res.dataset)
    assert again.dataset.attrs == res.dataset.attrs
    for other in (sf.load(tmp_path / "damping.json"), StudyResult.load(tmp_path)):  # the other file, the directory
        assert other.kind == "damping" and other.summary == again.summary
    with pytest.raises(StudyError, match=r"sim\.json is no file of a study: .*damping, forcing"):
        StudyResult.load(tmp_path / "sim.json")
    with pytest.raises(StudyError, match="no file of a forcing study"):
        StudyResult.load(tmp_path / "damping.nc", "forcing")
    (tmp_path / "damping.nc").unlink()
    with pytest.raises(FileNotFoundError, match=r"no file .*damping\.nc: give the path of a saved damping study"):
        StudyResult.load(tmp_path, "damping")


def test_a_white_limit_study_reads_back(tmp_path: Path) -> None:
    res = white_limit_study(WhiteLimitConfig(preset="brake", normal_force=2720.0, correlation_lengths=(1e-3, 1e-4),
                                             runs=4, tau_end=10.0, seed=5, workers=1))
    files = res.save(tmp_path)
    for path in (files["json"], files["netcdf"]):
        again = WhiteLimitResult.load(path)
        assert _same(again.summary.to_json(), res.summary.to_json())
        assert again.summary.config == res.summary.config  # the enum of the path coordinate included
        ds, want = again.dataset(), res.dataset()
        assert _same(json.loads(ds.attrs.pop("summary_json")), json.loads(want.attrs.pop("summary_json")))
        xr.testing.assert_identical(ds, want)  # the JSON file has its keys sorted; the same record
        assert again.x_gh == [] and type(sf.load(path)) is WhiteLimitResult


# --- surface, contact, the statistical analysis and its model -------------------------------------------


@pytest.fixture(scope="module")
def analysed(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Any]:
    surface = as_surface(gaussian_heights((96, 96), 2.0, 3))
    summits = sf.summits_of(surface)
    u = sf.default_approach_m(summits, num=6)
    cfg = AnalysisConfig(realizations=4, long_surfaces=3, length_factor=2, seed=1, surrogate="phase",
                         check_realizations=4, holdout_realizations=4, holdout_max_realizations=4)
    analysis = sf.analyse(surface, PAD, u, cfg)
    spread = contact_model_spread(surface, PAD, analysis.pressure_pa[:4], "gw", cfg, path_surfaces=2)
    return {"surface": surface, "summits": summits, "analysis": analysis, "spread": spread,
            "dir": tmp_path_factory.mktemp("analysed")}


def test_a_contact_result_reads_back(analysed: dict[str, Any], tmp_path: Path) -> None:
    res = asperity_contact(analysed["surface"], analysed["summits"], PAD, preparation={"file": "synthetic", "step": 1})
    path = res.to_netcdf(tmp_path / "contact.nc")
    again = ContactResult.load(path)
    assert again.to_dict() == res.to_dict() and again.n_contacts.dtype == np.int64
    assert type(sf.load(path)) is ContactResult


def test_the_saved_analysis_and_its_model_read_back(analysed: dict[str, Any]) -> None:
    a = analysed["analysis"]
    path = a.to_netcdf(analysed["dir"] / STATISTICS_FILE)
    saved = SavedAnalysis.load(path)
    assert saved.config == a.config and saved.seed_entropy == a.seed_entropy
    assert saved.credibility == a.credibility and saved.credible == a.credibility.credible
    assert saved.surrogate_choice == a.surrogate_choice and saved.material == a.material
    for name in ("approach_m", "pressure_pa", "mu_mean", "mu_std", "correlation_length_m", "psd_level"):
        want = a.ensemble.approach_m if name == "approach_m" else getattr(a, name)
        np.testing.assert_array_equal(getattr(saved, name), want, err_msg=name)
    assert _same(saved.fits, {k: f.to_dict() for k, f in a.fits.items()})
    for name in ("ergodicity", "surrogate_check", "window_check", "holdout", "measured_windows", "model_intervals"):
        record = getattr(a, name)
        assert record is not None and _same(getattr(saved, name), record.to_dict()), name
    assert saved.window_shift_m == a.path.window_shift_m
    assert saved.dataset["mu_mean"].attrs["units"] == "1" and saved.dataset["pressure_pa"].attrs["units"] == "Pa"
    xr.testing.assert_identical(saved.dataset, a.to_dataset())
    assert "SavedAnalysis(phase" in repr(saved) and type(sf.load(path)) is SavedAnalysis
    model_path = a.model.save(analysed["dir"] / "friction_process.json")
    assert sf.load(model_path) == a.model


def test_a_contact_model_spread_reads_back_from_either_file(analysed: dict[str, Any], tmp_path: Path) -> None:
    spread = analysed["spread"]
    files = write_spread(spread, tmp_path, figures=False)
    for path in (files["contact_models_file"], files["contact_models_samples_file"]):
        again = ContactModelSpread.load(path)
        assert _same(again.to_dict(), spread.to_dict())
        xr.testing.assert_identical(again.to_dataset(), spread.to_dataset())
        assert again.window_tiles == spread.window_tiles and again.control == spread.control
        np.testing.assert_array_equal(again.surrogates["gw"].seconds, spread.surrogates["gw"].seconds)
        np.testing.assert_array_equal(again.paths["gw"].mu, spread.paths["gw"].mu)
        assert type(sf.load(path)) is ContactModelSpread
    gw_path = spread.paths["gw"]  # the lowest, middle and highest pressure of the spread
    p = spread.pressure_pa
    np.testing.assert_allclose(gw_path.pressures_pa, [p[0], float(np.exp(np.mean(np.log(p)))), p[-1]])
    assert gw_path.mu.shape[0] == 2 and gw_path.mu.shape[2] == 3
    assert [q["pressure_pa"] for q in spread.to_dict()["path"]["gw"]["by_pressure"]] == gw_path.pressures_pa.tolist()
    one = tmp_path / "one"  # saved when the path had one pressure: (model, surface, window), "pressure_pa"
    ds1 = spread.to_dataset()
    ds1 = ds1.assign(path_mu=(("path_model", "long_surface", "path_window"), ds1["path_mu"].values[:, :, :, 1]))
    ds1 = ds1.drop_vars("path_pressure")
    ds1.attrs["paths_json"] = json.dumps({"gw": {"pressure_pa": gw_path.pressure_pa,
                                                 "window_shift_m": gw_path.window_shift_m,
                                                 "window_length_m": gw_path.window_length_m}})
    write_netcdf_atomic(one / "contact_models_samples.nc", ds1)
    (one / "contact_models.json").write_bytes(Path(files["contact_models_file"]).read_bytes())
    single = ContactModelSpread.load(one / "contact_models.json").paths["gw"]
    assert single.pressures_pa.tolist() == [gw_path.pressure_pa] and single.pressure_pa == gw_path.pressure_pa
    np.testing.assert_array_equal(single.mu[:, :, 0], gw_path.mu[:, :, 1])
    assert single.correlation_length() == gw_path.correlation_length()
    older = tmp_path / "old"  # before the wall times and paths were saved: NaN wall times, no paths
    ds = spread.to_dataset().drop_vars(["surrogate_seconds", "window_seconds", "path_mu", "path_model"])
    write_netcdf_atomic(older / "contact_models_samples.nc", ds)
    (older / "contact_models.json").write_bytes(Path(files["contact_models_file"]).read_bytes())
    old = ContactModelSpread.load(older / "contact_models.json")
    assert old.paths == {} and np.isnan(old.surrogates["gw"].seconds).all()
    np.testing.assert_array_equal(old.surrogates["gw"].mu, spread.surrogates["gw"].mu)
    (older / "contact_models_samples.nc").unlink()
    with pytest.raises(FileNotFoundError, match=r"contact_models_samples\.nc"):
        ContactModelSpread.load(older / "contact_models.json")


# --- the assessment --------------------------------------------------------------------------------------


def test_an_assessment_reads_back(tmp_path: Path) -> None:
    from stochfric.oscillator.machine import load_machine
    from stochfric.studies.assess import Assessment, ForceVerdict, _finish

    forces = [ForceVerdict(4000.0, 2.5e5, 5e-6, 0.8, (0.6, 0.9), 0.02, (0.015, 0.03), True, 0.01, "stick-slip", False),
              ForceVerdict(8000.0, 5e5, 5e-6, None, (None, None), None, (None, None), False, None, "undecided", None)]
    result = Assessment(status="verdict", reasons=[], machine=load_machine("brake"), material=PAD.to_dict(),
                        scans=["a.x3p"], approach_m=np.array([1e-6, 2e-6]), analysis=None, forces=forces,
                        risk_level=0.1, studies={"damping": "damping/damping.json"}, files={})
    _finish(result, tmp_path)
    saved = SavedAssessment.load(tmp_path / "assess.json")
    assert saved.forces == forces and saved.machine == result.machine and saved.exit_code == 0
    assert saved.first_screen == result.first_screen() and saved.status == "verdict"
    np.testing.assert_array_equal(saved.approach_m, [1e-6, 2e-6])
    assert type(sf.load(tmp_path / "assess.json")) is SavedAssessment


# --- bad input -------------------------------------------------------------------------------------------


def test_a_missing_path_a_directory_and_a_foreign_file_end_in_one_clear_error(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError, match=r"no file .*nothing\.nc \(the folder .* does not exist either\): "
                                                r"give the path of a saved stochfric result"):
        sf.load(tmp_path / "no" / "nothing.nc")
    path = _simulation().to_netcdf(tmp_path / "run" / "simulation.nc")
    with pytest.raises(ResultFileError, match=r"run is a directory, not a file: .*it holds simulation\.nc"):
        sf.load(tmp_path / "run")
    text = tmp_path / "notes.txt"
    text.write_text("not a result", encoding="utf-8")
    with pytest.raises(ValueError, match=r"notes\.txt is not a stochfric result .*not JSON"):
        sf.load(text)
    other = tmp_path / "other.json"
    other.write_text('{"a": 1}', encoding="utf-8")
    with pytest.raises(ValueError, match=r"other\.json: not a result stochfric knows.*" + KNOWN_RESULTS[0][:10]):
        sf.load(other)
    foreign = tmp_path / "foreign.nc"
    xr.Dataset({"a": ("x", [1.0])}, attrs={"title": "someone else's"}).to_netcdf(foreign, engine="h5netcdf")
    with pytest.raises(ValueError, match=r"foreign\.nc: not a result stochfric knows.*title \"someone else's\""):
        sf.load(foreign)
    for reader in (SimulationResult.load, load_result, ContactResult.load, SavedAnalysis.load):
        with pytest.raises(ValueError, match=r"foreign\.nc is not a"):
            reader(foreign)
        with pytest.raises(ValueError, match=r"notes\.txt is not a NetCDF-4 file"):
            reader(text)
    with pytest.raises(ValueError, match=r"simulation\.nc is not a contact result"):
        ContactResult.load(path)
    with pytest.raises(ValueError, match=r"simulation\.nc is not a white-limit study"):
        WhiteLimitResult.load(path)
    with pytest.raises(ValueError, match=r"other\.json is not an assessment"):
        SavedAssessment.load(other)
    assert not math.isnan(SimulationResult.load(path).dt)

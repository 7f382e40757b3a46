"""SimulationResult (stochfric.oscillator.result) built by hand: no simulation runs here.

A result with two parameter sets (the brake at N = 5600 N with its contact area, and a dimensionless
set without stiffness), two runs, NaN-padded events and a trajectory goes to NetCDF and back: the
arrays equal, NaN padding kept, units and long names on every variable, the derived physical
coordinates (N = n c L = 5600 N, p = N/A = 350 kPa, NaN where undefined), and the provenance
(schema, 128-bit seed entropy as an exact string, laws, σ_ζ, warnings, settings, versions).
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from stochfric.oscillator.friction_laws import law_III, pressure_law
from stochfric.oscillator.parameters import OscillatorParameters, PhysicalParameters
from stochfric.oscillator.result import SCHEMA, SimulationResult, SimulationWarning, load_result

SEED = 2**100 + 12345  # SeedSequence entropy can exceed 64 bits: it must survive as text


def _result(trajectory: bool = True) -> SimulationResult:
    brake = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0,
                               damping_ratio=5e-6, contact_area=0.016).to_dimensionless()
    bare = OscillatorParameters(gamma0=1.0, n=10.0, q=0.5, eta=1.15)
    x_gh = np.full((2, 2, 3), np.nan)
    x_gh[0, 0, :2] = [1.5e-3, 1.6e-3]
    x_gh[0, 1, :1] = [1.4e-3]
    x_gh[1, 0, :3] = [0.9, 1.1, 1.0]
    t_gh = np.where(np.isfinite(x_gh), 10.0 * np.arange(3), np.nan)
    stick_count = np.array([[2, 1], [5, 0]], dtype=np.int64)  # 5 > 3 stored: buffer overflow case
    traj = None
    if trajectory:
        tau = np.array([0.0, 0.05, 0.1, 0.15])
        traj = np.zeros((2, 2, 4, 3))
        traj[..., 0] = tau
        traj[..., 1] = np.arange(16).reshape(2, 2, 4) * 1e-3
        traj[..., 2] = 1.0
    return SimulationResult(
        params=[brake, bare], x_gh=x_gh, t_gh=t_gh, stick_count=stick_count,
        diagnostics={"path": np.array([[0.01, 0.02], [3.0, 4.0]]), "n_breakaway": np.array([[2.0, 1.0], [5.0, 0.0]])},
        trajectory=traj, model="white", integrator="milstein", dt=0.005, tau_end=50.0, runs=2,
        seed_entropy=SEED, path_coordinate="relative", x0=[(0.0, brake.gamma0), (3.2, 1.0)],
        laws=[pressure_law(0.28).to_dict(), law_III().to_dict()], sigma_zeta=[0.0742, 0.0],
        process={"kind": "band-limited", "dx_m": np.float64(6.3e-4)},
        warnings=[SimulationWarning("event-buffer-full", "1 trajectories had more than max_events = 3")],
        settings={"max_events": 3, "rtol": np.float64(1e-11), "sigma_zeta_effective": np.array([0.26, 0.0])},
        versions={"stochfric": "0.1.0", "numpy": np.__version__},
    )


def test_netcdf_round_trip_keeps_arrays_units_and_provenance(tmp_path: Path) -> None:
    res = _result()
    path = res.to_netcdf(tmp_path / "deep" / "dir" / "sim.nc")
    ds = load_result(path)
    np.testing.assert_array_equal(ds["x_gh"].values, res.x_gh)  # NaN padding included
    np.testing.assert_array_equal(ds["t_gh"].values, res.t_gh)
    np.testing.assert_array_equal(ds["stick_count"].values, [[2, 1], [5, 0]])
    assert np.issubdtype(ds["stick_count"].dtype, np.integer)
    np.testing.assert_array_equal(ds["path"].values, res.diagnostics["path"])
    assert ds["x_gh"].dims == ("param_set", "run", "event") and ds.sizes["event"] == 3
    # trajectory: time coordinate and the two state components
    assert res.trajectory is not None
    np.testing.assert_array_equal(ds["time"].values, [0.0, 0.05, 0.1, 0.15])
    np.testing.assert_array_equal(ds["x1"].values, res.trajectory[..., 1])
    np.testing.assert_array_equal(ds["x2"].values, res.trajectory[..., 2])
    # units on every variable (dimensionless: "1") and what each one is
    for name in ("x_gh", "t_gh", "stick_count", "path", "n_breakaway", "x1", "x2", "time"):
        assert ds[name].attrs["units"] == "1", name
    assert "X_gh" in ds["x_gh"].attrs["long_name"] and "omega0 t" in ds["t_gh"].attrs["long_name"]
    # derived physical coordinates per parameter set: N = n c L, p = N/A; NaN where undefined
    np.testing.assert_allclose(ds["normal_force_n"].values[0], 5600.0, rtol=1e-12)
    np.testing.assert_allclose(ds["pressure_pa"].values[0], 350_000.0, rtol=1e-12)
    assert math.isnan(ds["normal_force_n"].values[1]) and math.isnan(ds["pressure_pa"].values[1])
    np.testing.assert_allclose(ds["omega0_rad_s"].values, [math.sqrt(5e5), 1.0], rtol=1e-12)
    np.testing.assert_allclose(ds["gamma0"].values, [1 / math.sqrt(5e5), 1.0], rtol=1e-12)
    np.testing.assert_array_equal(ds["q"].values, [0.0, 0.5])
    np.testing.assert_array_equal(ds["sigma_zeta"].values, [0.0742, 0.0])
    # provenance attributes
    assert ds.attrs["model"] == "white" and ds.attrs["integrator"] == "milstein"
    assert ds.attrs["path_coordinate"] == "relative"
    assert ds.attrs["seed_entropy"] == str(SEED) and int(ds.attrs["seed_entropy"]) == SEED
    meta = json.loads(ds.attrs["metadata_json"])
    assert meta["schema"] == SCHEMA and meta["seed_entropy"] == str(SEED)
    assert meta["dt"] == 0.005 and meta["tau_end"] == 50.0 and meta["runs"] == 2
    assert meta["x0"] == [[0.0, 1 / math.sqrt(5e5)], [3.2, 1.0]]
    assert [lw["name"] for lw in meta["friction_law"]] == ["pressure", "III"]
    assert meta["parameters"][0]["normal_force_n"] == pytest.approx(5600.0)
    assert meta["parameters"][1]["normal_force_n"] is None
    assert meta["warnings"] == [{"code": "event-buffer-full", "message": "1 trajectories had more than max_events = 3"}]
    assert meta["settings"]["sigma_zeta_effective"] == [0.26, 0.0]  # numpy values made JSON
    assert meta["process"]["dx_m"] == 6.3e-4
    assert meta["versions"]["numpy"] == np.__version__


def test_without_trajectory_there_is_no_time_dimension(tmp_path: Path) -> None:
    ds = load_result(_result(trajectory=False).to_netcdf(tmp_path / "sim.nc"))
    assert "time" not in ds.dims and "x1" not in ds


def test_rewriting_replaces_the_file_and_leaves_no_temporary(tmp_path: Path) -> None:
    res = _result()
    path = res.to_netcdf(tmp_path / "sim.nc")
    res.x_gh[0, 0, 0] = 7.0
    res.to_netcdf(path)
    assert load_result(path)["x_gh"].values[0, 0, 0] == 7.0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["sim.nc"]


def test_load_result_refuses_a_file_of_another_schema(tmp_path: Path) -> None:
    other = tmp_path / "study.nc"
    ds = xr.Dataset({"a": ("x", [1.0])}, attrs={"metadata_json": json.dumps({"schema": "stochfric.study/1"})})
    ds.to_netcdf(other, engine="h5netcdf")
    with pytest.raises(ValueError, match=r"not a stochfric simulation result \(stochfric.simulation/1\)"):
        load_result(other)


def test_lists_and_json_drop_the_nan_padding() -> None:
    res = _result()
    assert res.n_param_sets == 2
    assert res.x_gh_list(0) == [[1.5e-3, 1.6e-3], [1.4e-3]]
    assert res.x_gh_list(1) == [[0.9, 1.1, 1.0], []]
    js = res.to_json_dict(param_set=1)
    assert js["x_gh"] == [[0.9, 1.1, 1.0], []] and js["t_gh"] == [[0.0, 10.0, 20.0], []]
    assert js["stick_count"] == [5, 0] and all(type(v) is int for v in js["stick_count"])
    assert js["x0"] == [3.2, 1.0] and js["friction_law"]["name"] == "III"
    assert js["sigma_zeta"] == 0.0 and js["sigma_zeta_effective"] == 0.0
    assert js["white_increment"] == "ito"  # default when the settings do not say
    assert js["diagnostics"]["path"] == [3.0, 4.0]
    assert js["parameters"]["q"] == 0.5 and js["parameters"]["pressure_pa"] is None
    json.dumps(js)  # plain JSON, no numpy scalars left
    js0 = res.to_json_dict(param_set=0)
    assert js0["sigma_zeta_effective"] == 0.26 and js0["parameters"]["pressure_pa"] == pytest.approx(350_000.0)

"""Damping study: phase diagrams over D at one force (Fig. 4.22/4.24/4.27, 4.53/4.55/4.58) and the
white-noise intensity rule / path coordinate of every study."""

from __future__ import annotations

import json
from pathlib import Path

import matplotlib.image as mpimg
import numpy as np
import pytest
import xarray as xr

from stochfric.oscillator.case import CaseError, case_setup, with_white_intensity
from stochfric.studies.config import DampingConfig, ForcingConfig
from stochfric.studies.damping import auto_phase_damping, damping_study, default_phase_force
from stochfric.studies.figures import damping_figures
from stochfric.studies.forcing import forcing_study

SMALL = DampingConfig(normal_forces=(4000.0, 5600.0), damping_ratios="0.05:0.25:9", runs=3, seed=3, tau_end=30.0)


@pytest.fixture(scope="module")
def small() -> xr.Dataset:
    return damping_study(SMALL).to_dataset()


def test_default_phase_force() -> None:
    assert default_phase_force(5600.0, (1800.0, 5600.0, 8000.0)) == 5600.0
    assert default_phase_force(1400.0, (400.0, 1000.0, 2000.0)) == 1000.0  # middle force
    assert default_phase_force(1400.0, (400.0, 1000.0)) == 400.0
    assert default_phase_force(1400.0, (700.0,)) == 700.0


def test_auto_phase_damping() -> None:
    grid = np.round(np.linspace(0.05, 0.25, 41), 12)
    # brake 5600 N: D_max 0.14 / 0.16 / 0.23 -> top = 0.235 (first grid D above the largest)
    assert auto_phase_damping(grid, [0.14, 0.16, 0.23]) == (0.05, 0.095, 0.145, 0.19, 0.235)
    # nothing above the largest D_max, or no cycle at all: up to the largest grid D
    assert auto_phase_damping(grid, [0.25, np.nan])[-1] == 0.25
    assert auto_phase_damping(grid, [np.nan, np.nan]) == (0.05, 0.1, 0.15, 0.2, 0.25)
    # a short grid: duplicates dropped
    assert auto_phase_damping([0.1, 0.2], [0.1]) == (0.1, 0.2)


def test_phase_trajectories_in_dataset(small: xr.Dataset, tmp_path: Path) -> None:
    ds = small
    tr = ds["phase_trajectory"]
    assert tr.dims == ("model", "phase_damping", "phase_run", "sample", "component")
    assert tr.attrs["units"] == "1"
    assert ds["phase_damping"].attrs["units"] == "1"
    assert ds["phase_normal_force_n"].attrs["units"] == "N"
    assert float(ds["phase_normal_force_n"]) == 5600.0  # the brake's damping-study force is on the grid
    assert ds["component"].values.tolist() == ["tau", "x1", "x2"]
    assert ds.attrs["phase_damping_rule"] == "auto"
    pd = ds["phase_damping"].values
    assert 2 <= pd.size <= 5 and pd[0] == 0.05
    assert set(pd) <= set(ds["damping_ratio"].values)
    assert tr.sizes["phase_run"] == 3
    # deterministic: one run kept; stochastic: all three; decimated every save_every steps
    assert np.isfinite(tr.sel(model="deterministic").values[:, 0]).all()
    assert np.isnan(tr.sel(model="deterministic").values[:, 1:]).all()
    assert np.isfinite(tr.sel(model="contact").values[..., 1]).all()
    tau = tr.sel(model="white", component="tau").values[0, 0]
    np.testing.assert_allclose(np.diff(tau), SMALL.save_every * 0.005, rtol=1e-9)
    assert tau[-1] == pytest.approx(30.0)
    # the deterministic phase run at a grid D repeats the grid result (no randomness)
    for k, d in enumerate(pd):
        assert ds["phase_has_cycle"].sel(model="deterministic").values[k, 0] == \
            ds["has_cycle"].sel(model="deterministic", normal_force_n=5600.0, damping_ratio=d).values[0]
    # NetCDF round trip keeps dims and units
    p = tmp_path / "d.nc"
    ds.to_netcdf(p, engine="h5netcdf")
    with xr.open_dataset(p, engine="h5netcdf") as back:
        assert back["phase_trajectory"].dims == tr.dims and back["phase_normal_force_n"].attrs["units"] == "N"


def test_phase_figure(small: xr.Dataset, tmp_path: Path) -> None:
    figs = damping_figures(small, tmp_path, prefix="x")
    names = [p.name for p, _ in figs]
    assert "x_phase.png" in names
    path, cap = figs[names.index("x_phase.png")]
    assert "4.22" in cap and "N = 5600 N" in cap
    img = mpimg.imread(path)
    assert img.shape[0] > 100 and img.shape[1] > 300
    # no phase runs: no phase variables, no phase figure
    ds0 = damping_study(SMALL.model_copy(update={"phase_runs": 0})).to_dataset()
    assert "phase_trajectory" not in ds0
    assert all(p.name != "y_phase.png" for p, _ in damping_figures(ds0, tmp_path, prefix="y"))


def test_phase_given_damping_and_force() -> None:
    cfg = DampingConfig(**{**SMALL.model_dump(), "phase_normal_force": 3000.0, "phase_damping_ratios": "0.2,0.07",
                           "phase_runs": 2})
    res = damping_study(cfg)
    ds = res.to_dataset()
    assert float(ds["phase_normal_force_n"]) == 3000.0
    assert ds["phase_damping"].values.tolist() == [0.07, 0.2]
    assert ds.attrs["phase_damping_rule"] == "given"
    assert res.to_json_dict()["phase"]["runs"]["white"] == 2


def test_white_intensity_rule_changes_sigma_zeta_only() -> None:
    base = DampingConfig(normal_forces=(5600.0,), damping_ratios="0.1:0.2:5", runs=3, seed=1, tau_end=30.0,
                         phase_runs=1)
    a = damping_study(base)
    b = damping_study(DampingConfig(**{**base.model_dump(), "white_intensity": "spectral_level"}))
    sa = float(a.dataset["sigma_zeta"].sel(model="white").values[0])
    sb = float(b.dataset["sigma_zeta"].sel(model="white").values[0])
    assert sa == pytest.approx(0.0742, abs=5e-4)  # σ_μ(0.35 MPa), thesis rule
    assert sb == pytest.approx(3.53e-6, rel=1e-2)  # low-frequency spectral level S0/2
    assert a.summary.sigma_zeta == [sa] and b.summary.sigma_zeta == [sb]
    assert a.dataset.attrs["white_intensity"] == "sigma_mu" and b.dataset.attrs["white_intensity"] == "spectral_level"
    assert json.loads(b.dataset.attrs["config_json"])["white_intensity"] == "spectral_level"
    for m in ("deterministic", "contact"):
        for v in ("x_gh", "stick_count", "phase_trajectory"):
            np.testing.assert_array_equal(a.dataset[v].sel(model=m).values, b.dataset[v].sel(model=m).values,
                                          err_msg=f"{m} {v}")
    assert not np.array_equal(a.dataset["x_gh"].sel(model="white").values,
                              b.dataset["x_gh"].sel(model="white").values, equal_nan=True)


def test_rule_applies_to_process_file_and_other_studies(tmp_path: Path) -> None:
    from stochfric.oscillator.presets import get_preset

    path = tmp_path / "model.json"
    get_preset("sheet").process.save(path)
    s = case_setup("sheet", path, white_intensity="spectral_level")
    assert s.process.sigma_zeta_rule == "spectral_level"
    assert s.process_source.startswith("file:")
    assert case_setup("sheet", path).process.sigma_zeta_rule == "sigma_mu"
    p = get_preset("brake").process
    assert with_white_intensity(p, "sigma_mu") is p
    with pytest.raises(CaseError, match="sigma_mu"):
        with_white_intensity(p, "pink")
    f = forcing_study(ForcingConfig(eta=(1.0,), runs=2, tau_end=20.0, white_intensity="spectral_level",
                                    path_coordinate="relative"))
    js = f.to_json_dict()
    assert js["white_intensity"] == "spectral_level" and js["path_coordinate"] == "relative"
    assert js["sigma_zeta"] < 1e-4
    assert f.dataset.attrs["path_coordinate"] == "relative"

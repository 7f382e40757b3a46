"""Seeds by cell (issue 19 §5): a cell's random streams depend on the seed and the cell's own
parameter values, so a cell run alone gives the numbers it has inside a larger grid, bit for bit,
whatever the grid's order, whatever task it is batched in."""

from __future__ import annotations

import numpy as np
import xarray as xr

from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import DampingStudy
from stochfric.studies.forcing import ForcingStudy
from stochfric.studies.lyapunov import LyapunovStudy
from stochfric.studies.normal_force import NormalForceStudy

COMMON = {"preset": "brake", "runs": 3, "seed": 11, "tau_end": 20.0}


def _tasks_by_cell(study: object) -> dict[tuple[str, float, float, float, float], dict[str, np.ndarray]]:
    """Per (model, N, D, q, η) cell: its runs' X_gh, τ_gh and stick counts (the task's arrays split by
    parameter set; the Lyapunov study's three twin sets stay together)."""
    from stochfric.studies.tasks import execute_task

    out: dict[tuple[str, float, float, float, float], dict[str, np.ndarray]] = {}
    for t in study.tasks():  # type: ignore[attr-defined]
        res = execute_task(t, threads=1)
        for i, p in enumerate(t.params):
            cell = (t.model, p.normal_force, p.damping_ratio, p.q, p.eta)
            nev = int(np.max(np.sum(np.isfinite(res["x_gh"][i]), axis=-1), initial=0))
            arrays = {"x_gh": res["x_gh"][i][:, :nev], "stick_count": res["stick_count"][i]}
            out.setdefault(cell, {})
            for k, v in arrays.items():
                out[cell].setdefault(k, []).append(v)  # type: ignore[attr-defined]
    return {c: {k: np.stack(v) if k == "stick_count" else v for k, v in a.items()} for c, a in out.items()}


def _same_cells(small: dict, big: dict) -> None:
    assert small and set(small) <= set(big)
    for cell, arrays in small.items():
        np.testing.assert_array_equal(arrays["stick_count"], big[cell]["stick_count"], err_msg=str(cell))
        for a, b in zip(arrays["x_gh"], big[cell]["x_gh"], strict=True):
            np.testing.assert_array_equal(a, b, err_msg=str(cell))


def test_damping_cell_alone_equals_cell_in_a_bigger_grid() -> None:
    alone = DampingStudy(DampingConfig(**COMMON, models=("contact",), normal_forces=(5600.0,),
                                       damping_ratios=(0.1,)))
    grid = DampingStudy(DampingConfig(**COMMON, models=("white", "contact"), normal_forces=(2800.0, 5600.0),
                                      damping_ratios=(0.05, 0.1, 0.15)))
    _same_cells(_tasks_by_cell(alone), _tasks_by_cell(grid))
    # without common random numbers too
    alone = DampingStudy(DampingConfig(**COMMON, models=("white",), normal_forces=(5600.0,),
                                       damping_ratios=(0.15,), common_random_numbers=False))
    grid = DampingStudy(DampingConfig(**COMMON, models=("white",), normal_forces=(5600.0,),
                                      damping_ratios=(0.05, 0.15), common_random_numbers=False))
    _same_cells(_tasks_by_cell(alone), _tasks_by_cell(grid))


def test_forcing_lyapunov_and_normal_force_cells_alone_equal_cells_in_bigger_grids() -> None:
    pairs = [
        (ForcingStudy(ForcingConfig(**COMMON, models=("contact",), forcing_q=(5e-4,), eta=(1.2,))),
         ForcingStudy(ForcingConfig(**COMMON, models=("white", "contact"), forcing_q=(5e-5, 5e-4),
                                    eta=(0.4, 1.2, 2.0)))),
        (LyapunovStudy(LyapunovConfig(**COMMON, models=("white",), forcing_q=(5e-4,), normal_forces=(4000.0,),
                                      eta=(1.2,))),
         LyapunovStudy(LyapunovConfig(**COMMON, models=("white",), forcing_q=(5e-4,),
                                      normal_forces=(2000.0, 4000.0), eta=(0.6, 1.2)))),
        (NormalForceStudy(NormalForceConfig(**COMMON, models=("contact",), normal_forces=(2720.0,),
                                            damping_ratios=(5e-6,), phase_runs=0)),
         NormalForceStudy(NormalForceConfig(**COMMON, models=("contact",), normal_forces=(720.0, 2720.0),
                                            damping_ratios=(5e-6, 0.15), phase_runs=0))),
    ]
    for alone, grid in pairs:
        _same_cells(_tasks_by_cell(alone), _tasks_by_cell(grid))


def test_a_finished_study_keeps_the_cell_numbers_of_a_smaller_one() -> None:
    """End to end through ``run`` and the dataset: the cell (contact, N = 5600 N, D = 0.1)."""
    small = DampingStudy(DampingConfig(**COMMON, models=("contact",), normal_forces=(5600.0,),
                                       damping_ratios=(0.1, 0.2), phase_damping_ratios=(0.1,))).run()
    big = DampingStudy(DampingConfig(**COMMON, models=("deterministic", "contact"), normal_forces=(1800.0, 5600.0),
                                     damping_ratios=(0.05, 0.1, 0.2), phase_damping_ratios=(0.1,))).run()
    sel = {"model": "contact", "normal_force_n": 5600.0, "damping_ratio": 0.1}
    a: xr.DataArray = small.dataset["x_gh"].sel(sel)
    b: xr.DataArray = big.dataset["x_gh"].sel(sel)
    n = min(a.sizes["event"], b.sizes["event"])
    np.testing.assert_array_equal(a.isel(event=slice(0, n)).values, b.isel(event=slice(0, n)).values)

"""Every real measured file through ``friction-process`` (issue: chapter 3 on any measurement).

Reduced realisation counts (CI); the full-size run is ``benchmarks/bench_process.py --files``.
Each file must finish with exit 0, produce finite statistics and a model file that loads, and
report the measured-vs-surrogate check and the ergodicity verdict.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

import pytest
import typer
from typer.testing import CliRunner

from stochfric.cli import app as main_app
from stochfric.process.model import load_process_model

#: The shared files (tests/conftest.py SHARED_FILES); names → has undefined points.
SHARED = {
    "al3d-1.al3d": False, "frt-1.frt": True, "mnt-1.mnt": False, "opd-1.opd": True,
    "plu-1.plu": False, "sur-2.sur": True, "x3p-2.x3p": False,
}  # fmt: skip

SMALL = ["--realizations", "6", "--long-surfaces", "3", "--length-factor", "3"]


@pytest.fixture(scope="module")
def app() -> typer.Typer:
    return main_app


@pytest.mark.parametrize("name", sorted(SHARED))
def test_friction_process_runs_on_every_shared_file(
    app: typer.Typer, name: str, tmp_path: Path, shared_file: Callable[[str], Path]
) -> None:
    path = shared_file(name)
    fill = ["--fill-undefined"] if SHARED[name] else []
    res = CliRunner().invoke(
        app,
        ["friction-process", str(path), "--material", "brake-pad", *fill, *SMALL, "--seed", "1",
         "--out", str(tmp_path / "fp"), "--json"],
    )  # fmt: skip
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert all(v is not None and math.isfinite(v) for v in data["mu_mean"])
    assert all(v is not None and v > 0 for v in data["pressure_pa"])
    check = data["surrogate_check"]
    assert set(check["z"]) == {"summit_count", "summit_radius_mean_m", "summit_height_std_m"}
    assert len(check["mu_z"]) == len(data["approach_m"])
    assert data["ergodicity"]["surfaces"] == 3 and data["ergodicity"]["windows_per_surface"] == 3
    model = load_process_model(data["model_file"])
    p = data["pressure_pa"][0]
    assert math.isfinite(model.mean(p))


def test_undefined_points_without_fill_are_refused(app: typer.Typer, shared_file: Callable[[str], Path]) -> None:
    path = shared_file("opd-1.opd")
    res = CliRunner().invoke(app, ["friction-process", str(path), "--material", "brake-pad", *SMALL])
    assert res.exit_code == 2
    assert "--fill-undefined" in res.output

"""``analyse_scans``: what ``friction-process`` does, as one library call with a typed result (issue 28)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

import stochfric as sf
from stochfric.cli import app
from stochfric.errors import AnalysisError, StochfricError
from stochfric.process.pipeline import MODEL_FILE, STATISTICS_FILE, window_shift_points
from stochfric.surface.io import surface_from_array

SMALL = dict(realizations=12, long_surfaces=3, length_factor=3, seed=3)
SMALL_ARGS = ["--realizations", "12", "--long-surfaces", "3", "--length-factor", "3", "--seed", "3"]


def test_the_library_call_gives_the_command_line_numbers(tmp_path: Path) -> None:
    run = sf.analyse_scans(None, "brake-pad", config=sf.AnalysisConfig(**SMALL), workers=1)
    assert isinstance(run, sf.ScanAnalysis) and run.approach_rule == "contacts"
    assert run.pooled.scans[0].default_surface and len(run.pooled.surfaces) == 1
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", *SMALL_ARGS, "--json",
                                   "--accept-not-credible", "--workers", "1"])
    assert res.exit_code == 0, res.output
    cli = json.loads(res.stdout)
    assert cli["mu_mean"] == pytest.approx([float(v) for v in run.analysis.mu_mean], rel=0, abs=0)
    assert cli["config"]["window_shift_points"] == run.analysis.config.window_shift_points
    ours = run.to_json_dict()
    assert ours["preparation"]["sha256"] == cli["preparation"]["sha256"] and ours["approach_rule"] == "contacts"
    written = run.write(tmp_path, model=True)
    assert Path(written["model_file"]).name == MODEL_FILE and Path(written["statistics_file"]).name == STATISTICS_FILE
    assert sf.load_process_model(written["model_file"]).to_dict() == run.analysis.model.to_dict()


def test_bad_input_raises_the_package_error_before_any_work(tmp_path: Path) -> None:
    afile = tmp_path / "afile"
    afile.write_text("x")
    with pytest.raises(StochfricError, match="existing file"):
        sf.analyse_scans(None, "brake-pad", out=afile)
    with pytest.raises(AnalysisError, match="workers"):
        sf.analyse_scans(None, "brake-pad", workers=0)
    with pytest.raises(StochfricError, match="unknown"):
        sf.analyse_scans(None, "no-such-material")


def test_window_shift_is_rounded_to_the_grid_and_must_leave_two_windows() -> None:
    s = surface_from_array(np.zeros((50, 100)), physical_size_m=(5e-5, 1e-4))  # Δy = 1 µm
    assert window_shift_points(s, 20.4e-6, 10) == 20
    assert window_shift_points(s, None, 10) == 5  # 0.0566 × 100 points
    with pytest.raises(AnalysisError, match="fewer than two windows"):
        window_shift_points(s, 1e-3, 2)
    with pytest.raises(AnalysisError, match="> 0"):
        window_shift_points(s, -1.0, 10)

"""Progress of studies (issue 11): the study is named, done/total is known, one line per study
when stderr is not a terminal; simulate's header has no ``preset=None``."""

from __future__ import annotations

import importlib
import re
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.cli.studies import _StudyProgress
from stochfric.studies.config import DampingConfig

reproduce_mod = importlib.import_module("stochfric.studies.reproduce")


def _tiny_plan(quick: bool, seed: int = 2013) -> list[Any]:
    return [DampingConfig(preset=p, normal_forces=(5600.0,) if p == "brake" else (1400.0,), damping_ratios=(0.1, 0.2),
                          runs=2, tau_end=10.0, phase_runs=0, models=("deterministic", "white"), seed=seed)
            for p in ("brake", "sheet")]


def test_reproduce_prints_one_line_per_finished_study(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import stochfric.report.html as report_html

    monkeypatch.setattr(reproduce_mod, "plan", _tiny_plan)
    monkeypatch.setattr(report_html, "write_report", lambda results, d, **k: Path(d) / "index.html")
    res = CliRunner().invoke(app, ["reproduce", "--out", str(tmp_path / "r")])
    assert res.exit_code == 0, res.output
    lines = re.findall(r"^\[(\d)/(\d)\] (\S+): (\d+) tasks \((\d+) computed, (\d+) from checkpoint\)", res.output,
                       re.MULTILINE)
    assert [(a, b, c) for a, b, c, *_ in lines] == [("1", "2", "brake/damping"), ("2", "2", "sheet/damping")]
    assert all(int(n) == int(c) + int(ld) and int(n) > 0 for *_, n, c, ld in lines)
    assert "None" not in res.output
    # a rerun loads everything from the checkpoints and says so
    again = CliRunner().invoke(app, ["reproduce", "--out", str(tmp_path / "r")])
    assert re.search(r"\[1/2\] brake/damping: (\d+) tasks \(0 computed, \1 from checkpoint\)", again.output), \
        again.output


def test_terminal_bar_names_the_study_with_done_and_total() -> None:
    prog = _StudyProgress(True, n_studies=3)
    prog.tty = True  # as on a terminal
    with prog:
        prog.start("brake/forcing")
        tasks = {t.description: t for t in prog._prog.tasks}
        assert tasks["brake/forcing"].fields["count"] == "counting tasks …"
        prog.tasks(4, 61)
        t = {t.description: t for t in prog._prog.tasks}["brake/forcing"]
        assert (t.completed, t.total, t.fields["count"]) == (4, 61, "4/61 tasks")
        prog.end(61, 0)
        overall = {t.description: t for t in prog._prog.tasks}["all studies"]
        assert overall.completed == 1 and overall.fields["count"] == "1/3 studies"


def test_simulate_header_names_a_preset_only_when_there_is_one() -> None:
    out = CliRunner().invoke(app, ["simulate", "--gamma0", "1", "--n", "10", "--tau-end", "5"]).output
    assert "preset=" not in out and "stochfric simulate" in out
    out = CliRunner().invoke(app, ["simulate", "--preset", "brake", "--tau-end", "5"]).output
    assert "preset=brake" in out


def test_reproduce_ctrl_c_says_what_is_saved(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    import stochfric.studies.executors as executors
    from stochfric.studies.tasks import execute_task

    class StopInSecondStudy(executors.Executor):
        def __init__(self) -> None:
            self.calls = 0

        def run(self, fn: Any, tasks: Any) -> Any:
            for t in tasks:
                self.calls += 1
                if self.calls > 3:  # the first tiny study has 2 tasks: stop after one of the second
                    raise KeyboardInterrupt
                yield t, execute_task(t, 1)

    monkeypatch.setattr(reproduce_mod, "plan", _tiny_plan)
    monkeypatch.setattr(executors, "make_executor", lambda *a, **k: StopInSecondStudy())
    res = CliRunner().invoke(app, ["reproduce", "--out", str(tmp_path / "r")])
    assert res.exit_code == 130, res.output
    assert re.search(r"\(1 of 2 studies finished and saved\), study sheet/damping after 1 of \d+ tasks", res.output)
    assert f"saved in {tmp_path / 'r' / 'checkpoints'}" in res.output and "Resume with:" in res.output
    assert (tmp_path / "r" / "brake" / "damping.nc").exists()

"""Executors (serial / processes / Dask) give identical numbers; checkpoints resume a sweep."""

from __future__ import annotations

from collections.abc import Iterator, Sequence
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from stochfric.studies.config import DampingConfig, LyapunovConfig
from stochfric.studies.damping import damping_study, damping_tasks
from stochfric.studies.executors import (
    DaskExecutor,
    Executor,
    ProcessExecutor,
    SerialExecutor,
    TaskFunction,
    TaskResult,
    make_executor,
    run_tasks,
)
from stochfric.studies.lyapunov import lyapunov_study
from stochfric.studies.store import CheckpointStore, config_hash
from stochfric.studies.tasks import TaskSpec

SMALL = DampingConfig(normal_forces=(4000.0, 6000.0), damping_ratios=(0.1, 0.14, 0.18), runs=3, seed=5, tau_end=12.0)


def _arrays(ds: xr.Dataset) -> dict[str, np.ndarray]:
    return {k: ds[k].values for k in ("x_gh", "t_gh", "stick_count", "stick_probability", "d_max_sample_extreme",
                                      "d_max_risk", "phase_damping", "phase_trajectory")}


def _assert_same(a: xr.Dataset, b: xr.Dataset) -> None:
    for k, v in _arrays(a).items():
        np.testing.assert_array_equal(v, _arrays(b)[k], err_msg=k)


class CountingExecutor(Executor):
    """Serial executor that counts computed tasks and can raise KeyboardInterrupt after k."""

    name = "counting"

    def __init__(self, interrupt_after: int | None = None) -> None:
        self.calls: list[int] = []
        self.interrupt_after = interrupt_after

    def run(self, fn: TaskFunction, tasks: Sequence[TaskSpec]) -> Iterator[tuple[TaskSpec, TaskResult]]:
        for t in tasks:
            if self.interrupt_after is not None and len(self.calls) >= self.interrupt_after:
                raise KeyboardInterrupt
            self.calls.append(t.index)
            yield t, fn(t, 1)


def test_serial_threads_and_processes_identical() -> None:
    ref = damping_study(SMALL).to_dataset()
    _assert_same(ref, damping_study(SMALL, executor=SerialExecutor(threads=1)).to_dataset())
    _assert_same(ref, damping_study(SMALL, executor=ProcessExecutor(workers=2)).to_dataset())


def test_dask_local_cluster_identical() -> None:
    distributed = pytest.importorskip("distributed")
    ref = damping_study(SMALL).to_dataset()
    with distributed.LocalCluster(n_workers=2, processes=True, threads_per_worker=1, dashboard_address=None) as cl, \
            distributed.Client(cl) as client:
        got = damping_study(SMALL, executor=DaskExecutor(client=client)).to_dataset()
        got2 = damping_study(SMALL, executor=DaskExecutor(address=cl.scheduler_address)).to_dataset()
    _assert_same(ref, got)
    _assert_same(ref, got2)


def test_seed_is_per_task_not_per_order() -> None:
    tasks, _ = damping_tasks(SMALL)
    forward, _ = run_tasks(tasks)
    backward, _ = run_tasks(list(reversed(tasks)))
    for t in tasks:
        np.testing.assert_array_equal(forward[t.index]["x_gh"], backward[t.index]["x_gh"])
    other = damping_study(SMALL.model_copy(update={"seed": 6})).to_dataset()
    assert not np.array_equal(other["x_gh"].sel(model="white").values,
                              damping_study(SMALL).to_dataset()["x_gh"].sel(model="white").values, equal_nan=True)


def test_resume_after_interrupt_and_deleted_files(tmp_path: Path) -> None:
    ref = damping_study(SMALL).to_dataset()
    n_tasks = len(damping_tasks(SMALL)[0])
    assert n_tasks == 6
    ex = CountingExecutor(interrupt_after=2)
    with pytest.raises(KeyboardInterrupt):
        damping_study(SMALL, executor=ex, checkpoint=str(tmp_path))
    store = CheckpointStore(tmp_path, SMALL.hash_config(), kind="damping")
    assert store.finished() == {0, 1}
    ex2 = CountingExecutor()
    res = damping_study(SMALL, executor=ex2, checkpoint=str(tmp_path))
    # finished tasks not recomputed; 6, 7, 8: the phase-diagram tasks (one per model)
    assert sorted(ex2.calls) == [2, 3, 4, 5, 6, 7, 8]
    assert res.stats.loaded == 2 and res.stats.computed == 7
    _assert_same(ref, res.to_dataset())
    # delete two task files: exactly those are recomputed
    store.path(1).unlink()
    store.path(4).unlink()
    store.path(7).unlink()
    ex3 = CountingExecutor()
    _assert_same(ref, damping_study(SMALL, executor=ex3, checkpoint=str(tmp_path)).to_dataset())
    assert sorted(ex3.calls) == [1, 4, 7]
    # a complete checkpoint computes nothing; no temporary files are left behind
    ex4 = CountingExecutor()
    damping_study(SMALL, executor=ex4, checkpoint=str(tmp_path))
    assert ex4.calls == []
    assert not list(store.directory.glob(".*.tmp"))


def test_checkpoint_key_changes_with_config(tmp_path: Path) -> None:
    a = CheckpointStore(tmp_path, SMALL.hash_config(), kind="damping")
    b = CheckpointStore(tmp_path, SMALL.model_copy(update={"runs": 4}).hash_config(), kind="damping")
    assert a.directory != b.directory
    assert config_hash({"x": 1.0, "y": [1, 2]}) == config_hash({"y": (1, 2), "x": 1.0})
    assert (a.directory / "config.json").exists()


def test_make_executor() -> None:
    assert isinstance(make_executor("serial"), SerialExecutor)
    assert isinstance(make_executor("processes", workers=2), ProcessExecutor)
    assert isinstance(make_executor("serial", scheduler="tcp://x:1"), DaskExecutor)
    with pytest.raises(ValueError):
        make_executor("mpi")
    with pytest.raises(ValueError):
        make_executor("dask")


def test_lyapunov_identical_across_executors() -> None:
    cfg = LyapunovConfig(normal_forces=(4000.0,), forcing_q=(5e-4,), eta=(1.2, 2.0), runs=2, tau_end=40.0, seed=1)
    a = lyapunov_study(cfg).to_dataset()
    b = lyapunov_study(cfg, executor=ProcessExecutor(workers=2)).to_dataset()
    np.testing.assert_array_equal(a["w"].values, b["w"].values)
    np.testing.assert_array_equal(a["lyapunov"].values, b["lyapunov"].values)


_SLEEPER = '''
import os, time

def sleep_task(task, threads):
    open(os.path.join(os.environ["PIDDIR"], str(os.getpid())), "w").close()
    time.sleep(60)
    return {}
'''

_PARENT = '''
import sys
sys.path.insert(0, sys.argv[1])
from sleeper import sleep_task
from stochfric.studies.executors import ProcessExecutor
for _ in ProcessExecutor(workers=2).run(sleep_task, [0, 1]):
    pass
'''


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/status", encoding="ascii") as fh:
            return not any(line.startswith("State:") and "Z" in line.split()[1] for line in fh)
    except FileNotFoundError:
        return False


_MIDDLE = '''
import subprocess, sys, time
subprocess.Popen([sys.executable, "-c", sys.argv[1], sys.argv[2]])
time.sleep(60)
'''
_WATCHED = '''
import os, sys, time
from stochfric.studies.executors import _exit_with_parent
_exit_with_parent(os.getppid(), poll_s=0.05)
open(os.path.join(sys.argv[1], str(os.getpid())), "w").close()
time.sleep(60)
'''


@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc (Linux)")
def test_parent_watchdog_ends_the_process_when_the_parent_is_killed(tmp_path: Path) -> None:
    """The worker initializer of ProcessExecutor, in a grandchild: kill -9 its parent, it exits."""
    import signal
    import subprocess
    import sys
    import time

    middle = subprocess.Popen([sys.executable, "-c", _MIDDLE, _WATCHED, str(tmp_path)])
    try:
        deadline = time.monotonic() + 30
        while not list(tmp_path.iterdir()) and time.monotonic() < deadline:
            time.sleep(0.05)
        (pidfile,) = tmp_path.iterdir()
        child = int(pidfile.name)
        assert _alive(child)
    finally:
        middle.send_signal(signal.SIGKILL)
        middle.wait()
    deadline = time.monotonic() + 3
    while _alive(child) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not _alive(child), "the watched process outlived its parent"


@pytest.mark.slow
@pytest.mark.skipif(not Path("/proc/self/status").exists(), reason="needs /proc (Linux)")
def test_workers_die_with_their_parent_after_kill_9(tmp_path: Path) -> None:
    import os
    import signal
    import subprocess
    import sys
    import time

    (tmp_path / "sleeper.py").write_text(_SLEEPER, encoding="utf-8")
    piddir = tmp_path / "pids"
    piddir.mkdir()
    parent = subprocess.Popen([sys.executable, "-c", _PARENT, str(tmp_path)], env={**os.environ, "PIDDIR": str(piddir)})
    try:
        deadline = time.monotonic() + 30
        while len(list(piddir.iterdir())) < 2 and time.monotonic() < deadline:
            time.sleep(0.1)
        workers = [int(p.name) for p in piddir.iterdir()]
        assert len(workers) == 2 and all(_alive(w) for w in workers)
    finally:
        parent.send_signal(signal.SIGKILL)
        parent.wait()
    deadline = time.monotonic() + 5
    while any(_alive(w) for w in workers) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert not any(_alive(w) for w in workers), "workers outlived their parent"


def test_ctrl_c_says_what_is_saved_and_how_to_resume(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from typer.testing import CliRunner

    import stochfric.studies.executors as executors
    from stochfric.cli import app

    args = ["study", "damping", "--normal-force", "4000,6000", "--damping-ratio", "0.1,0.14,0.18", "--runs", "3",
            "--seed", "5", "--tau-end", "12", "--checkpoint", str(tmp_path / "ck")]
    monkeypatch.setattr(executors, "make_executor", lambda *a, **k: CountingExecutor(interrupt_after=2))
    res = CliRunner().invoke(app, args)
    assert res.exit_code == 130, res.output
    assert "after 2 of 6 tasks" in res.output and "2 tasks of it are saved in" in res.output
    assert "Resume with:" in res.output and str(tmp_path / "ck") in res.output
    res = CliRunner().invoke(app, args[:-2])  # no checkpoint: nothing to resume, and it says so
    assert res.exit_code == 130 and "nothing was saved" in res.output


def test_run_json_reports_computed_and_loaded_tasks(tmp_path: Path) -> None:
    import json

    from typer.testing import CliRunner

    from stochfric.cli import app

    toml = tmp_path / "s.toml"
    toml.write_text(f'''[execution]
executor = "serial"
checkpoint = "{tmp_path / 'ck'}"
[output]
dir = "{tmp_path / 'out'}"
report = false
[[study]]
kind = "damping"
normal_forces = [4000, 6000]
damping_ratios = [0.1, 0.18]
runs = 2
tau_end = 10
phase_runs = 0
''', encoding="utf-8")
    first = json.loads(CliRunner().invoke(app, ["run", str(toml), "--json"]).output)
    n = first["tasks"]["computed"]
    assert n > 0 and first["tasks"]["loaded_from_checkpoint"] == 0
    assert first["studies"][0]["tasks"] == {"computed": n, "loaded_from_checkpoint": 0}
    again = json.loads(CliRunner().invoke(app, ["run", str(toml), "--json"]).output)
    assert again["tasks"] == {"computed": 0, "loaded_from_checkpoint": n}


def test_a_bad_scheduler_address_is_one_error_and_leaves_no_default_client() -> None:
    """``--scheduler ''`` (the option sweep) once left a broken global dask client behind, which then captured
    xarray's netCDF writes in every later test of the same process ("missing port number in address ''")."""
    pytest.importorskip("distributed")
    from distributed.client import _get_global_client

    from stochfric.studies.errors import StudyError

    with pytest.raises(StudyError, match=r"cannot use the Dask scheduler '' .*--scheduler tcp://HOST:PORT"):
        list(DaskExecutor(address="").run(lambda t, n: None, damping_tasks(SMALL)[:1]))  # type: ignore[arg-type]
    assert _get_global_client() is None

"""Errors before work, never after (issue 11): output paths, memory, full disk, file modes.

Every bad output path is refused with exit code 2 *before* anything is computed: the tests make
the computation itself fail loudly (monkeypatched), so a check that came too late would show.
"""

from __future__ import annotations

import errno
import importlib
import json
import os
import re
import resource
import signal
import stat
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest
from typer.testing import CliRunner

import stochfric.io_utils as io_utils
import stochfric.oscillator.integrate as integrate
from stochfric.cli import app
from stochfric.io_utils import OutputPathError, check_output_path, write_text_atomic

reproduce_mod = importlib.import_module("stochfric.studies.reproduce")  # the package re-exports a function
runner = CliRunner()
SIM = ["simulate", "--gamma0", "1", "--n", "10", "--tau-end", "5"]
STUDY = ["study", "damping", "--damping-ratio", "0.1:0.2:2", "--normal-force", "5600", "--runs", "2",
         "--models", "deterministic", "--tau-end", "10"]


@pytest.fixture
def no_work(monkeypatch: pytest.MonkeyPatch) -> None:
    """Any simulation or study that starts fails the test."""
    def boom(*_a: Any, **_k: Any) -> Any:
        raise AssertionError("work started before the output paths were checked")

    monkeypatch.setattr(integrate, "simulate", boom)
    monkeypatch.setattr(reproduce_mod, "run_study", boom)
    monkeypatch.setattr(reproduce_mod, "reproduce", boom)


def _bad(args: list[str], needle: str) -> None:
    res = runner.invoke(app, args)
    assert res.exit_code == 2, (res.output, res.exception)
    assert needle in res.output, res.output
    assert "Traceback" not in res.output


@pytest.mark.usefixtures("no_work")
@pytest.mark.parametrize("args,needle", [
    (["--out", "/proc/x"], "cannot create files in /proc"),
    (["--plot", "out.xyz"], "unknown file extension '.xyz'"),
    (["--plot", "{dir}"], "is a directory"),
    (["--out", "{file}"], "is an existing file, not a directory"),
    (["--plot", "{file}/p.png"], "is a file, so nothing can be created below it"),
    (["--plot", "/proc/p.png"], "cannot create files in /proc"),
])
def test_simulate_output_paths_checked_first(args: list[str], needle: str, tmp_path: Path) -> None:
    afile = tmp_path / "afile"
    afile.write_text("x")
    _bad(SIM + [a.format(dir=tmp_path, file=afile) for a in args], needle)


@pytest.mark.usefixtures("no_work")
def test_study_run_reproduce_output_paths_checked_first(tmp_path: Path) -> None:
    afile = tmp_path / "afile"
    afile.write_text("x")
    _bad([*STUDY, "--out", str(afile)], "--out")
    _bad([*STUDY, "--report", "/proc/r"], "--report /proc/r: cannot create files")
    _bad([*STUDY, "--checkpoint", str(afile / "ck")], "--checkpoint")
    _bad(["reproduce", "--out", "/proc/x"], "cannot create files in /proc")
    toml = tmp_path / "s.toml"
    toml.write_text(f'[output]\ndir = "{afile}"\n[[study]]\nkind = "damping"\nruns = 2\n', encoding="utf-8")
    _bad(["run", str(toml)], "is an existing file")


@pytest.mark.parametrize("args,needle", [
    (["friction-process", "--material", "brake-pad", "--out", "{file}"], "is an existing file"),
    (["surface", "--plot", "{file}"], "is an existing file"),
    (["contact", "--material", "brake-pad", "--output", "r.txt"], "unknown file extension '.txt'"),
    (["contact", "--material", "brake-pad", "--plot", "/proc/x"], "cannot create files in /proc"),
])
def test_surface_contact_process_output_paths_checked_first(
    args: list[str], needle: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    import stochfric.cli.surface as cli_surface

    def boom(*_a: Any, **_k: Any) -> Any:
        raise AssertionError("the surface was read before the output paths were checked")

    # all three commands read through SurfaceOptions.load -> cli.surface._load_and_prepare
    monkeypatch.setattr(cli_surface, "_load_and_prepare", boom)
    afile = tmp_path / "afile"
    afile.write_text("x")
    _bad([a.format(file=afile) for a in args], needle)


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_read_only_directory_refused(tmp_path: Path) -> None:
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o500)
    try:
        with pytest.raises(OutputPathError, match="cannot create files"):
            check_output_path(ro / "sub", option="--out")
    finally:
        ro.chmod(0o700)


def test_check_output_path_accepts_new_and_existing(tmp_path: Path) -> None:
    assert check_output_path(tmp_path / "a" / "b") == tmp_path / "a" / "b"
    assert not (tmp_path / "a").exists()  # nothing is created by the check
    assert check_output_path(tmp_path / "f.PNG", kind="file", suffixes=(".png",)) == tmp_path / "f.PNG"
    assert not list(tmp_path.iterdir())  # the write probe is removed


@pytest.mark.usefixtures("no_work")
@pytest.mark.parametrize("args", [["--runs", "1000000000"], ["--tau-end", "4e8"]])  # 8e10 steps: under the step limit
def test_simulate_refuses_requests_that_do_not_fit_in_memory(args: list[str]) -> None:
    res = runner.invoke(app, ["simulate", "--preset", "brake", "--model", "white", *args])
    assert res.exit_code == 2, res.output
    assert "of memory, but only" in res.output and "fewer --runs" in res.output
    assert re.search(r"needs about [\d.]+ [kMGTP]?B", res.output), res.output


def test_simulate_memory_estimate_scales_with_the_request() -> None:
    from stochfric.cli.simulate import _simulation_memory_bytes

    base = _simulation_memory_bytes(100, 50.0, 0.005, save_every=10, trajectories=False, model="deterministic",
                                    process_points=0, workers=1)
    assert base == pytest.approx(100 * 8 * (2 * 116 + 10))
    traj = _simulation_memory_bytes(100, 50.0, 0.005, save_every=10, trajectories=True, model="deterministic",
                                    process_points=0, workers=1)
    assert traj - base == pytest.approx(100 * 48 * 1001)
    # a contact run holds the process segments of its whole path (first_segments), a batch at a time
    contact = _simulation_memory_bytes(10, 50.0, 0.005, save_every=10, trajectories=False, model="contact",
                                       process_points=67 * 3, workers=2)
    assert contact - _simulation_memory_bytes(10, 50.0, 0.005, save_every=10, trajectories=False,
                                              model="deterministic", process_points=0, workers=2) \
        == pytest.approx(10 * 8 * 67 * 3)


@pytest.mark.usefixtures("no_work")
def test_a_contact_run_too_long_for_its_process_in_memory_is_refused_before_work() -> None:
    """Sheet, τ_end = 10⁸: the path needs about 1.1·10⁷ process segments per run (tens of GB for 64 runs)."""
    res = runner.invoke(app, ["simulate", "--preset", "sheet", "--model", "contact", "--tau-end", "1e8",
                                   "--dt", "1", "--runs", "64"])
    assert res.exit_code == 2, res.output
    assert "of memory, but only" in res.output


def test_disk_full_exits_2_and_keeps_the_previous_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    """A fake full disk (OSError ENOSPC from the byte writer): clean exit 2, old results intact."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "damping.nc").write_bytes(b"previous results")

    def full(self: Path, data: Any) -> int:
        raise OSError(errno.ENOSPC, "No space left on device")

    monkeypatch.setattr(Path, "write_bytes", full)
    res = runner.invoke(app, [*STUDY, "--out", str(out)])
    assert res.exit_code == 2, (res.output, res.exception)
    assert "No space left on device" in res.output
    assert (out / "damping.nc").read_bytes() == b"previous results"
    assert sorted(p.name for p in out.iterdir()) == ["damping.nc"]  # no temporary file left


def _small_file_limit() -> None:
    signal.signal(signal.SIGXFSZ, signal.SIG_IGN)  # EFBIG instead of a signal
    resource.setrlimit(resource.RLIMIT_FSIZE, (30_000, 30_000))


def test_real_write_failure_does_not_crash_the_interpreter(tmp_path: Path) -> None:
    """A real failing write below the C library (file-size limit → EFBIG): exit 2, no segfault (139)."""
    out = tmp_path / "o"
    out.mkdir()
    (out / "damping.nc").write_bytes(b"previous results")
    proc = subprocess.run([sys.executable, "-m", "stochfric.cli", *STUDY, "--out", str(out)],
                          capture_output=True, text=True, timeout=120, preexec_fn=_small_file_limit)
    assert proc.returncode == 2, (proc.returncode, proc.stderr[-2000:])
    assert "error:" in proc.stderr and "File too large" in proc.stderr
    assert (out / "damping.nc").read_bytes() == b"previous results"


def test_atomic_writes_respect_the_umask(tmp_path: Path) -> None:
    old = os.umask(0o022)
    try:
        write_text_atomic(tmp_path / "a.json", json.dumps({}))
        io_utils.write_bytes_atomic(tmp_path / "b.bin", b"x")
        os.umask(0o077)
        write_text_atomic(tmp_path / "c.json", "{}")
    finally:
        os.umask(old)
    assert stat.S_IMODE((tmp_path / "a.json").stat().st_mode) == 0o644
    assert stat.S_IMODE((tmp_path / "b.bin").stat().st_mode) == 0o644
    assert stat.S_IMODE((tmp_path / "c.json").stat().st_mode) == 0o600
    assert io_utils.current_umask() == old


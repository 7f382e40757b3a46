"""The SIMD-width setting (stochfric.vector_width): when it applies, and that it changes no number."""

from __future__ import annotations

import json
import os
import subprocess
import sys

import pytest

from stochfric import vector_width as vw

FLAT = "+avx2,+avx512f,+fma"


def test_auto_widens_only_listed_intel_xeons_with_avx512() -> None:
    assert vw.wide_features("auto", "emeraldrapids", {"avx512f": True}, FLAT) == FLAT + ",-prefer-256-bit"
    assert vw.wide_features("auto", "skylake-avx512", {"avx512f": True}, FLAT) is None  # clock penalty
    assert vw.wide_features("auto", "znver4", {"avx512f": True}, FLAT) is None  # LLVM's choice kept
    assert vw.wide_features("auto", "sapphirerapids", {"avx512f": False}, FLAT) is None


def test_512_on_any_avx512_cpu_and_native_never() -> None:
    assert vw.wide_features("512", "icelake-server", {"avx512f": True}, FLAT) == FLAT + ",-prefer-256-bit"
    assert vw.wide_features("512", "haswell", {"avx2": True}, FLAT) is None
    assert vw.wide_features("native", "emeraldrapids", {"avx512f": True}, FLAT) is None


def test_a_users_numba_target_wins(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("NUMBA_CPU_FEATURES", "+avx2")
    monkeypatch.setenv(vw.ENV, "512")
    assert vw.configure() is None
    assert os.environ["NUMBA_CPU_FEATURES"] == "+avx2"


def test_unknown_setting_is_refused(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv(vw.ENV, "1024")
    with pytest.raises(ValueError, match="STOCHFRIC_VECTOR_WIDTH='1024': choose one of auto, 512, native"):
        vw.configure()
    with pytest.raises(ValueError, match="vector width '256': choose one of auto, 512, native"):
        vw.configure("256")
    assert vw.configure("native") is None  # an explicit choice wins over the environment


def _python(code: str, width: str | None, *args: str) -> subprocess.CompletedProcess[str]:
    """``python -c code *args`` with numba's own target and ``STOCHFRIC_VECTOR_WIDTH = width``."""
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_FEATURES", "NUMBA_CPU_NAME", vw.ENV)}
    if width is not None:
        env[vw.ENV] = width
    return subprocess.run([sys.executable, "-c", code, *args], env=env, capture_output=True, text=True,
                          timeout=600)


@pytest.mark.parametrize("width", [None, "512", "1024"])
def test_importing_the_package_changes_no_numba_setting(width: str | None) -> None:
    """``import stochfric`` leaves numba's target alone, whatever ``STOCHFRIC_VECTOR_WIDTH`` says (even
    a bad value does not make the import fail): the width is an explicit call."""
    res = _python("import os, stochfric, stochfric.oscillator.kernels; print(os.environ.get('NUMBA_CPU_FEATURES'))",
                  width)
    assert res.returncode == 0, res.stderr
    assert res.stdout.strip() == "None"


def test_the_command_line_refuses_a_bad_width_in_one_line() -> None:
    res = _python("from stochfric.cli import main; main()", "1024", "--help")
    assert res.returncode == 2
    assert res.stderr == "error: STOCHFRIC_VECTOR_WIDTH='1024': choose one of auto, 512, native\n"
    assert res.stdout == ""


def test_the_command_line_applies_the_width_it_is_given() -> None:
    """The entry point applies ``STOCHFRIC_VECTOR_WIDTH`` (:func:`configure`) before the command runs;
    without it, ``auto`` (full width on the listed CPUs only)."""
    code = """
import os, platform, sys
from stochfric import cli
from stochfric.vector_width import wide_features
sys.argv = ["stochfric", "--version"]
try:
    cli.main()
except SystemExit as done:
    assert done.code == 0, done.code
import llvmlite.binding as ll
f = ll.get_host_cpu_features()
x86 = platform.machine().lower() in ("x86_64", "amd64")
choice = os.environ.get("STOCHFRIC_VECTOR_WIDTH", "auto")
expected = wide_features(choice, ll.get_host_cpu_name(), dict(f), f.flatten()) if x86 else None
print(os.environ.get("NUMBA_CPU_FEATURES") == expected)
"""
    assert _python(code, "512").stdout.split()[-1] == "True"
    assert _python(code, None).stdout.split()[-1] == "True"


_RUN = """
import json, os, stochfric
from stochfric import vector_width
vector_width.configure()
from stochfric.oscillator.case import case_setup
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import ExecutionOptions
c = case_setup("brake").case(5600.0, 5e-6)
out = {}
for model in ("deterministic", "white", "contact"):
    r = simulate(c, model=model, runs=40, seed=11, execution=ExecutionOptions(workers=1))
    out[model] = r.x_gh.tobytes().hex()
print(json.dumps({"features": os.environ.get("NUMBA_CPU_FEATURES"), "x_gh": out}))
"""


def _run(width: str) -> dict[str, object]:
    env = {k: v for k, v in os.environ.items() if k not in ("NUMBA_CPU_FEATURES", "NUMBA_CPU_NAME")}
    env[vw.ENV] = width
    res = subprocess.run([sys.executable, "-c", _RUN], env=env, capture_output=True, text=True, check=True,
                         timeout=600)
    return json.loads(res.stdout.strip().splitlines()[-1])  # type: ignore[no-any-return]


def test_the_width_changes_no_number() -> None:
    """X_gh of the three models, bit for bit, with numba's own width and with 512-bit vectors (on a
    CPU without AVX-512 both runs use numba's choice and the test holds trivially)."""
    native, wide = _run("native"), _run("512")
    assert native["features"] is None
    assert native["x_gh"] == wide["x_gh"]

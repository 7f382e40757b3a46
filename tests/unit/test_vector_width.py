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
    with pytest.raises(ValueError, match="auto, 512, native"):
        vw.configure()


_RUN = """
import json, os, stochfric
from stochfric.oscillator.case import case_setup
from stochfric.oscillator.integrate import simulate
c = case_setup("brake").case(5600.0, 5e-6)
out = {}
for model in ("deterministic", "white", "contact"):
    r = simulate(c.params, **c.simulate_kwargs(model), runs=40, seed=11, workers=1)
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

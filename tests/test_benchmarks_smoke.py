"""Smoke test of the oscillator performance suite (benchmarks/bench_oscillator.py).

Runs the suite's smallest configuration so that the script keeps working as the package
changes; it asserts nothing about speed (timings belong to the benchmark itself).
"""

from __future__ import annotations

import importlib.util
import math
import sys
from pathlib import Path
from types import ModuleType

BENCH = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_oscillator.py"


def _load() -> ModuleType:
    spec = importlib.util.spec_from_file_location("bench_oscillator", BENCH)
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod  # dataclasses resolve annotations through sys.modules
    spec.loader.exec_module(mod)
    return mod


def test_benchmark_suite_smallest_configuration_runs() -> None:
    bench = _load()
    rep = bench.run_benchmarks("smoke")
    whats = {(e.case, e.what) for e in rep.entries}
    for model, integ in bench.CONFIGS:
        assert ("brake", f"{model} {integ}") in whats
    assert ("brake", "python loop, Euler") in whats
    assert ("brake", "solve_ivp (DOP853, events)") in whats
    assert any(e.group == "scaling" for e in rep.entries)
    assert any(e.group == "headline" for e in rep.entries)
    for e in rep.entries:
        assert e.steps > 0 and e.wall_s > 0
        assert math.isfinite(e.rate) and e.rate > 0, e
    # the baselines integrate the same trajectories as the kernels
    for name, diff in rep.checks.items():
        assert diff <= 1e-6, name
    text = bench.format_report(rep)
    assert "targets" in text
    assert set(rep.to_dict()) == {"size", "machine", "entries", "ratios", "targets", "checks"}

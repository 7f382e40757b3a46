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
COMPARE = Path(__file__).resolve().parents[1] / "benchmarks" / "bench_compare.py"


def _load(path: Path = BENCH) -> ModuleType:
    spec = importlib.util.spec_from_file_location(path.stem, path)
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
    # the generation paths before issue 13, measured in the same run
    assert ("brake", "white euler, pcg64 buffer") in whats
    assert ("brake", "contact euler, generate per run") in whats
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


def test_comparison_suite_smallest_configuration_runs() -> None:
    """benchmarks/bench_compare.py: stochfric vs solve_ivp with events (and diffrax when the
    optional ``bench`` extra is installed; otherwise its rows are skipped with a note)."""
    _load(BENCH)  # bench_compare imports it by name
    cmp = _load(COMPARE)
    c = cmp.run_comparison("smoke")
    tools = {(r.model, r.tool) for r in c.rows}
    for model in cmp.MODELS:
        assert (model, "stochfric") in tools
    assert ("deterministic", "solve_ivp") in tools and ("contact", "solve_ivp") in tools
    if cmp.have_diffrax():
        assert all((m, "diffrax") in tools for m in cmp.MODELS)
    else:
        assert any("diffrax rows skipped" in n for n in c.notes)
    for r in c.rows:
        assert r.steps > 0 and math.isfinite(r.rate) and r.rate > 0, r
    assert "deterministic: stochfric / solve_ivp DOP853" in c.ratios
    assert "ratios" in cmp.format_comparison(c)

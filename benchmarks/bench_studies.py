"""Timing of the studies (a script, not a test): the thesis-resolution damping map and reproduce.

    python benchmarks/bench_studies.py            # damping map (thesis grid) serial and 2 processes
    python benchmarks/bench_studies.py --reproduce [--quick]

The damping map is D 0.05 … 0.25 × 41, N 1800 … 8000 × 7, three models, 10 runs,
τ_end = 50, Δτ = 0.005 (brake): 7 × 3 tasks, each one batched simulate call.
"""

from __future__ import annotations

import argparse
import json
import tempfile
import time

from stochfric.report.html import write_report
from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.executors import ProcessExecutor, SerialExecutor
from stochfric.studies.grids import parse_grid
from stochfric.studies.reproduce import reproduce

THESIS_MAP = DampingConfig(normal_forces=(1800.0, 2800.0, 3800.0, 4800.0, 5600.0, 6800.0, 8000.0),
                           damping_ratios=parse_grid("0.05:0.25:41"), runs=10, seed=1)


def bench_damping_map() -> dict[str, float]:
    """Wall time of the thesis damping map, serial (all threads) and with 2 processes."""
    out = {}
    warm = DampingConfig.model_validate({**THESIS_MAP.model_dump(), "normal_forces": (5600.0,), "runs": 2})
    damping_study(warm)  # compile/warm up
    for name, ex in (("serial", SerialExecutor()), ("processes_2", ProcessExecutor(workers=2))):
        t = time.perf_counter()
        damping_study(THESIS_MAP, executor=ex)
        out[f"damping_map_{name}_s"] = time.perf_counter() - t
    trajectories = 7 * 41 * (1 + 10 + 10)
    out["trajectories"] = trajectories
    out["steps_per_s_serial"] = trajectories * 10000 / out["damping_map_serial_s"]
    return out


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--reproduce", action="store_true")
    ap.add_argument("--quick", action="store_true")
    ap.add_argument("--json", default=None)
    a = ap.parse_args()
    res: dict[str, object] = bench_damping_map()
    if a.reproduce:
        with tempfile.TemporaryDirectory() as d:
            t = time.perf_counter()
            _, timings = reproduce(d, quick=a.quick, report=write_report)
            res["reproduce_s"] = time.perf_counter() - t
            res["reproduce_timings_s"] = timings
    print(json.dumps(res, indent=1))
    if a.json:
        with open(a.json, "w", encoding="utf-8") as fh:
            json.dump(res, fh, indent=1)


if __name__ == "__main__":
    main()

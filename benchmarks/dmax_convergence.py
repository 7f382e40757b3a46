"""Does D_max(α) converge with the number of runs R? (issue 19; docs/studies.md, damping section.)

The thesis's D_max^s — the largest D at which *any* run stuck — is a sample extreme: it grows with R.
D_max(α) = the largest grid D with P(stick-slip | D) ≥ α has a fixed target, and its interval
(per-D Clopper–Pearson bands, :func:`stochfric.studies.stats.risk_limit`) must shrink around it.

For brake N = 5600 N and sheet N = 1400 N (the thesis's damping-study forces), white and contact
models, D = 0.05:0.35:61 (the study's step 0.005, further up), seed 0, it runs the damping study at
each R and prints one Markdown table:
D_max(α) [low, high] per risk level, the sample extreme, and whether every interval overlaps those
of all smaller R (``consistent``).  ``≥ 0.35`` marks an open upper end (the grid end: P at the grid
end not excluded — always so when R runs cannot resolve α, marked ``*``).

    python benchmarks/dmax_convergence.py                       # R = 10, 30, 100, 300, 1000 (≈ 40 s, 2 cores)
    python benchmarks/dmax_convergence.py --runs 10,30 --json out.json

Each R is a separate study (same seed); not run in CI.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from typing import Any

from stochfric.studies.config import DampingConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.stats import runs_to_resolve

CASES = (("brake", 5600.0), ("sheet", 1400.0))
MODELS = ("white", "contact")


def _interval(e: dict[str, Any], grid_end: float) -> str:
    v, (lo, hi) = e["value"], e["interval"]
    lo_t = "< grid" if lo is None else f"{lo:.3g}"
    hi_t = "< grid" if hi is None else (f"≥ {grid_end:.3g}" if e["high_open"] else f"{hi:.3g}")
    star = "" if e["resolved"] else "*"
    return f"{'—' if v is None else f'{v:.3g}'} [{lo_t}, {hi_t}]{star}"


def _overlap(a: list[Any], b: list[Any], grid_start: float, grid_end: float) -> bool:
    """Do the intervals [low, high] overlap (None low = below the grid start, high None = below it too)?"""
    alo = grid_start - 1.0 if a[0] is None else a[0]
    blo = grid_start - 1.0 if b[0] is None else b[0]
    ahi = grid_start - 1.0 if a[1] is None else a[1]
    bhi = grid_start - 1.0 if b[1] is None else b[1]
    return max(alo, blo) <= min(ahi, bhi) + 1e-12


def run(runs: list[int], seed: int = 0, damping: str = "0.05:0.35:61",
        risk_levels: tuple[float, ...] = (0.1, 0.01)) -> list[dict[str, Any]]:
    """One row per (case, model, R) with the summary entries of D_max(α) and the sample extreme."""
    rows: list[dict[str, Any]] = []
    for preset, force in CASES:
        for r in runs:
            t0 = time.perf_counter()
            cfg = DampingConfig.model_validate({"preset": preset, "normal_forces": (force,), "damping_ratios": damping,
                                                "runs": r, "seed": seed, "models": MODELS, "phase_runs": 0,
                                                "risk_levels": risk_levels})
            s = damping_study(cfg).to_json_dict()
            wall = time.perf_counter() - t0
            for m in MODELS:
                rows.append({"preset": preset, "normal_force_n": force, "model": m, "runs": r, "wall_s": wall,
                             "d_max_risk": s["d_max_risk"][m][0],
                             "d_max_sample_extreme": s["d_max_sample_extreme"][m][0]["value"],
                             "grid": [s["damping_ratio"][0], s["damping_ratio"][-1]]})
    # consistency: each interval overlaps the intervals of every smaller R (same case, model, α)
    for row in rows:
        smaller = [o for o in rows if (o["preset"], o["model"]) == (row["preset"], row["model"])
                   and o["runs"] < row["runs"]]
        row["consistent"] = all(
            _overlap(e["interval"], o["d_max_risk"][j]["interval"], *row["grid"])
            for o in smaller for j, e in enumerate(row["d_max_risk"]))
    return rows


def table(rows: list[dict[str, Any]]) -> str:
    alphas = [e["risk_level"] for e in rows[0]["d_max_risk"]]
    head = ("| case | model | R | " + " | ".join(f"D_max({100 * a:g} %) [low, high]" for a in alphas)
            + " | sample extreme | consistent |")
    lines = [head, "|" + "---|" * (5 + len(alphas))]
    for row in rows:
        ext = row["d_max_sample_extreme"]
        lines.append(f"| {row['preset']} {row['normal_force_n']:g} N | {row['model']} | {row['runs']} | "
                     + " | ".join(_interval(e, row["grid"][1]) for e in row["d_max_risk"])
                     + f" | {'—' if ext is None else f'{ext:.3g}'} | {'yes' if row['consistent'] else 'NO'} |")
    res = ", ".join(f"α = {100 * a:g} %: R ≥ {runs_to_resolve(a)}" for a in alphas)
    lines.append(f"\n`*` R runs cannot resolve α (0 sticking runs of R do not exclude P ≥ α at 97.5 %; {res}).")
    return "\n".join(lines)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--runs", default="10,30,100,300,1000", help="comma-separated numbers of runs")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--damping", default="0.05:0.35:61",
                    help="D grid (the study's default 0.05:0.25:41 ends below brake contact D_max(1 %%))")
    ap.add_argument("--risk-levels", default="0.1,0.01")
    ap.add_argument("--json", default=None, help="also write the rows to this JSON file")
    a = ap.parse_args()
    runs = sorted(int(v) for v in a.runs.split(","))
    alphas = tuple(float(v) for v in a.risk_levels.split(","))
    t0 = time.perf_counter()
    rows = run(runs, a.seed, a.damping, alphas)
    print(table(rows))
    print(f"\n{len(rows)} rows in {time.perf_counter() - t0:.0f} s (seed {a.seed}, D = {a.damping}).")
    if a.json:
        with open(a.json, "w", encoding="utf-8") as f:
            json.dump(rows, f, indent=1, allow_nan=False)
    if not all(r["consistent"] for r in rows) or any(math.isnan(r["wall_s"]) for r in rows):
        raise SystemExit(1)


if __name__ == "__main__":
    main()

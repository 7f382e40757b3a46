"""The whole gate on scans whose random-phase model is exact (issue 29; docs/statistical_contact.md §0a).

Crops of the periodic 1700² Gaussian self-affine map of ``holdout_gaussian_maps.py`` (H = 0.8, Sq 0.5 µm,
3.1 µm spacing) are written as ``.npy`` scans and analysed as a user would (``analyse_scans``, brake-pad,
``--surrogate phase``, every default: R = 100, K = 10, the summit check's and the held-out test's budgets):

* ``one``  — one 512² crop;
* ``two``  — two disjoint 512² crops of one map, pooled (the scans-of-one-surface test applies);
* ``full`` — the whole 1700² map (minutes).

A sound gate must not refuse an exact model (family-wise false-alarm rate 5 % per check) and calls it credible
where the measurement has the power to see a factor 2 in σ_μ.  Prints one Markdown row per map and case:

    python benchmarks/gate_gaussian_scans.py [--cases one two] [--seeds 1 2 3 4 5 6] [--out DIR]

About 15-30 s per 512² analysis on 2 cores.  Not run in CI.
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

import numpy as np

from holdout_gaussian_maps import SPACING_M, gaussian_map
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.pipeline import analyse_scans

CROPS = {"one": [(0, 0)], "two": [(0, 0), (600, 600)]}


def run(case: str, seed: int, out: Path) -> str:
    whole = gaussian_map(1700, seed)
    n = 1700 if case == "full" else 512
    files = []
    for k, (i, j) in enumerate([(0, 0)] if case == "full" else CROPS[case]):
        path = out / f"gauss-{seed}-{case}-{k}.npy"
        np.save(path, whole[i:i + n, j:j + n])
        files.append(path)
    t0 = time.perf_counter()
    run = analyse_scans(files, "brake-pad", config=AnalysisConfig(seed=1, surrogate="phase"),
                        physical_size_m=(n * SPACING_M, n * SPACING_M), height_unit="m", workers=2)
    dt = time.perf_counter() - t0
    a = run.analysis
    sc, ho = a.surrogate_check, a.holdout
    r = int(a.ensemble.contact_area_m2.shape[0])
    codes = ", ".join(sorted(x.code for x in a.credibility.reasons)) or "–"
    summit = f"{sc.global_exceed}/{r}" if sc.global_exceed is not None else "–"
    held = (f"{ho.verdict}, max |z| {ho.max_abs_z:.2f} / {ho.threshold:.2f} at R = {ho.realizations}, detects "
            f"{ho.detectable_scatter_ratio:.2f}×"
            if ho is not None else "–")
    return f"| {case} | {seed} | {a.credibility.status} | {codes} | {summit} | {held} | {dt:.0f} |"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--cases", nargs="+", default=["one", "two"], choices=["one", "two", "full"])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1, 2, 3, 4, 5, 6])
    ap.add_argument("--out", type=Path, default=None, help="where the .npy scans go (default: a temporary folder)")
    args = ap.parse_args()
    print("| case | map seed | status | reasons | summit check K/R | held-out (verdict, max |z| / threshold, power) "
          "| s |")
    print("|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as tmp:
        out = args.out or Path(tmp)
        out.mkdir(parents=True, exist_ok=True)
        for case in args.cases:
            for seed in args.seeds:
                print(run(case, seed, out), flush=True)


if __name__ == "__main__":
    main()

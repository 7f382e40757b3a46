"""The held-out test's family-wise false-alarm rate, measured where the model is exact (issue 29; docs §0a).

Exact Gaussian self-affine maps (H = 0.8, roll-off below 1/50 px, Sq 0.5 µm: disjoint n × n crops of periodic
1700² maps, ``1700 // n`` squared crops per map) are given to the random-phase model, which is exact for them.
Each is validated on its held-out halves (:func:`stochfric.process.holdout.holdout_validation`) at a *fixed* R
(no growth, so no Monte Carlo margin enters; ``--sequential``: the gate's own rule, whose verdicts are counted,
``not credible`` being its false refusals): a false alarm is a map whose largest |z| exceeds the Student-t
Bonferroni threshold c.  A sound test has a rate ≤ α = 5 %; the Clopper–Pearson 95 % interval is printed, with
the mean and sd of z per statistic (1 and 0 for a calibrated one; a per-statistic excess names the culprit).

    python benchmarks/holdout_calibration.py [--size 256] [--maps 200] [--realizations 24] [--amplitude hann]

About 1 s per 256² map and 3 s per 512² map on one core.  Not run in CI.
"""

from __future__ import annotations

import argparse
import collections
import time

import numpy as np
from scipy import stats as sps

from holdout_gaussian_maps import SPACING_M, gaussian_map
from stochfric.contact.materials import get_material
from stochfric.process.ensemble import SurrogateOptions
from stochfric.process.holdout import HOLDOUT_MAX_REALIZATIONS, holdout_validation
from stochfric.surface.io import Surface
from stochfric.surface.summits import find_summits

BIG = 1700


def big_map(seed: int) -> np.ndarray:
    """A whole periodic 1700² Gaussian self-affine map, Sq 0.5 µm (``holdout_gaussian_maps.gaussian_map``)."""
    return gaussian_map(BIG, seed)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--size", type=int, default=256)
    ap.add_argument("--maps", type=int, default=200)
    ap.add_argument("--realizations", type=int, default=24)
    ap.add_argument("--sequential", action="store_true",
                    help="the gate's own procedure: 2-SE margin, R doubling to the default budget; counts verdicts")
    ap.add_argument("--amplitude", default="tukey", choices=["tukey", "hann"],
                    help="the taper of the predictive spectrum (the analysis's --amplitude; default tukey)")
    args = ap.parse_args()
    budget = HOLDOUT_MAX_REALIZATIONS if args.sequential else args.realizations
    verdicts: collections.Counter[str] = collections.Counter()
    n, per = args.size, BIG // args.size
    material = get_material("brake-pad")
    alarms, z_by = 0, collections.defaultdict(list)
    cache: dict[int, np.ndarray] = {}
    t0 = time.perf_counter()
    c = float("nan")
    for idx in range(args.maps):
        map_seed, crop = divmod(idx, per * per)
        if map_seed not in cache:
            cache.clear()
            cache[map_seed] = big_map(10_000 + map_seed)
        i, j = divmod(crop, per)
        z = np.ascontiguousarray(cache[map_seed][i * n:(i + 1) * n, j * n:(j + 1) * n])
        surface = Surface(heights_m=z, physical_size_m=(n * SPACING_M, n * SPACING_M), source=f"gaussian-{idx}")
        top = np.sort(find_summits(z, (SPACING_M, SPACING_M)).heights_m)[::-1]
        u = top[0] - top[[r for r in (20, 60, 150, 400) if r < top.size // 2]]
        options = SurrogateOptions(method="phase", amplitude=args.amplitude)
        v = holdout_validation([surface], material, u, options, seed=idx,
                               realizations=args.realizations, max_realizations=budget)
        verdicts[v.verdict] += 1
        c = v.threshold
        alarms += v.max_abs_z > c
        for t in v.tests:
            z_by[(t.statistic, t.quantity)].append(t.z)
        if args.sequential:
            print(f"map {idx}: {v.verdict} at R = {v.realizations}, max |z| {v.max_abs_z:.2f} (c {c:.2f})", flush=True)
        elif v.max_abs_z > c:
            print(f"map {idx}: max |z| {v.max_abs_z:.2f} > {c:.2f} ({v.worst})", flush=True)
    m = args.maps
    lo = sps.beta.ppf(0.025, alarms, m - alarms + 1) if alarms else 0.0
    hi = sps.beta.ppf(0.975, alarms + 1, m - alarms) if alarms < m else 1.0
    print(f"{n}² crops, R = {args.realizations}, threshold {c:.2f}: false alarms {alarms} of {m} = "
          f"{alarms / m:.3f} (95 % CI {lo:.3f}–{hi:.3f}); {time.perf_counter() - t0:.0f} s")
    if args.sequential:
        print("verdicts (2-SE margin, budget", budget, "per fold):", dict(verdicts))
    print("| statistic | quantity | mean z | sd z | beyond c |")
    print("|---|---|---|---|---|")
    for (stat, q), zs in sorted(z_by.items()):
        a = np.asarray(zs)
        print(f"| {stat} | {q} | {a.mean():+.2f} | {a.std(ddof=1):.2f} | {int(np.sum(np.abs(a) > c))} |")


if __name__ == "__main__":
    main()

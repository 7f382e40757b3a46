"""Speed of the boundary-element statistical analysis (issue 31, acceptance "speed").

Cases (each: ``contact_model_spread`` with ``--models``, R surrogates × P pressures, ``--workers`` processes):

* ``plu-1``: the shared Sensofar map coarsened as the thesis does (every 10th point: 77 × 58 points);
* ``1700``: a synthetic Gaussian self-affine 1700² map (H = 0.8, 1 µm pixels) coarsened by 10 (170²).

Prints wall time, CPU time and the peak resident memory of the parent and of the worker processes, next to a
baseline run of the GW model on the same samples in the same process (the ratio is what a target should be
stated in; absolute seconds depend on the machine).

Run: ``python benchmarks/bench_bem_analysis.py`` (both cases, 100 × 12, bem; about 5–10 min on 2 cores).
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

import numpy as np

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"


def _synthetic(n: int, hurst: float, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    q = np.hypot(*np.meshgrid(np.fft.fftfreq(n), np.fft.fftfreq(n), indexing="ij"))
    q[0, 0] = 1.0
    amp = q ** (-1.0 - hurst)
    amp[0, 0] = 0.0
    amp[q > 0.25] = 0.0
    h = np.real(np.fft.ifft2(amp * np.exp(2j * np.pi * rng.random((n, n)))))
    return np.asarray(1e-6 * h / h.std())


def _case(name: str):  # type: ignore[no-untyped-def]
    from stochfric.surface.io import Surface
    from stochfric.surface.preprocess import Preparation, coarsen
    from stochfric.surface.scans import load_scan

    if name == "plu-1":
        return load_scan(SHARED / "plu-1.plu", preparation=Preparation(step=10)).coarse
    h = _synthetic(1700, 0.8, 7)
    return coarsen(Surface(heights_m=h, physical_size_m=(1.7e-3, 1.7e-3), source="synthetic 1700²"), 10)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--cases", nargs="*", default=["plu-1", "1700"])
    ap.add_argument("--models", default="bem")
    ap.add_argument("--realizations", type=int, default=100)
    ap.add_argument("--pressures", type=int, default=12)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--material", default="brake-pad")
    args = ap.parse_args()

    from stochfric.contact.asperity import asperity_contact
    from stochfric.contact.materials import get_material
    from stochfric.process.analysis_config import AnalysisConfig
    from stochfric.process.contact_models import contact_model_spread
    from stochfric.process.pipeline import choose_approach
    from stochfric.surface.summits import summits_of

    mat = get_material(args.material)
    print("| case | grid | models | R × P | wall [s] | CPU parent + workers [s] | GW baseline wall [s] | ratio | "
          "peak RSS parent / worker [MiB] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for case in args.cases:
        surface = _case(case)
        u = choose_approach([surface], summit_rule="thesis")
        gw = asperity_contact(surface, summits_of(surface), mat, u)
        p = np.geomspace(float(gw.pressure_pa[0]), float(gw.pressure_pa[-1]), args.pressures)
        cfg = AnalysisConfig(realizations=args.realizations, seed=1, surrogate="phase")
        t0 = time.perf_counter()
        contact_model_spread(surface, mat, p, "gw", cfg, workers=args.workers)
        base = time.perf_counter() - t0
        c0 = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
        t0 = time.perf_counter()
        contact_model_spread(surface, mat, p, args.models, cfg, workers=args.workers)
        wall = time.perf_counter() - t0
        c1 = resource.getrusage(resource.RUSAGE_SELF), resource.getrusage(resource.RUSAGE_CHILDREN)
        cpu = sum(b.ru_utime + b.ru_stime - a.ru_utime - a.ru_stime for a, b in zip(c0, c1, strict=True))
        print(f"| {case} | {surface.nb_grid_pts[0]}×{surface.nb_grid_pts[1]} | {args.models} | "
              f"{args.realizations} × {args.pressures} | {wall:.1f} | {cpu:.1f} | {base:.1f} | {wall / base:.0f} | "
              f"{c1[0].ru_maxrss / 1024:.0f} / {c1[1].ru_maxrss / 1024:.0f} |", flush=True)


if __name__ == "__main__":
    main()

"""Benchmark: quilted surrogates (``similar_surface(method="quilt")``) against random-phase ones.

Two maps: a 1700 × 1700 synthetic non-Gaussian map (Gaussian-filtered white noise, correlation
length 2 points, plus 0.2 % deep pits — summit spacing ≈ 5 points like the real files, so the
patch rule gives the same patch sizes as there) and, when the shared file is there, the 768 × 576
plu-1 (read, prepared with the defaults).  Per map: seconds per realisation of ``"quilt"`` and of
``"phase"`` on the same map in the same process (one core; the ratio quilt/phase), the whole run of
``--realisations`` surrogates, a length-factor-10 quilt of plu-1, and the peak resident memory.

Target (issue): a 1700² map with 100 realisations in < 3 min and < 4 GiB on 2 cores, i.e.
≲ 1.5 s per realisation on one core; plu-1 well under 30 s for a whole run.

Run:  python benchmarks/bench_quilt.py [--realisations 10] [--size 1700]
"""

from __future__ import annotations

import argparse
import resource
import time
from pathlib import Path

import numpy as np
from scipy.ndimage import gaussian_filter

from stochfric.random import spawn_generators
from stochfric.surface.io import Surface, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.quilting import quilt_parameters
from stochfric.surface.surrogates import similar_surface

PLU = Path("/work/shared/data/topographies/plu-1.plu")


def synthetic(n: int, seed: int = 0) -> Surface:
    """A non-Gaussian n × n test map (smooth noise plus sparse deep pits)."""
    rng = np.random.default_rng(seed)
    z = gaussian_filter(rng.standard_normal((n, n)), 2.0, mode="wrap")
    pits = gaussian_filter((rng.random((n, n)) < 0.002).astype(float), 1.5, mode="wrap")
    z = z / z.std() - 40.0 * pits
    return Surface(heights_m=z * 1e-8, physical_size_m=(n * 1e-6, n * 1e-6), source="synthetic")


def per_realisation(surface: Surface, method: str, k: int, factor: int = 1) -> float:
    """Mean seconds of one realisation over ``k`` (after one warm-up call)."""
    similar_surface(surface, 99, method=method, factor=factor)
    t0 = time.perf_counter()
    for g in spawn_generators(1, k):
        similar_surface(surface, g, method=method, factor=factor)
    return (time.perf_counter() - t0) / k


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--realisations", type=int, default=10)
    ap.add_argument("--size", type=int, default=1700)
    args = ap.parse_args()
    maps = [("synthetic", synthetic(args.size))]
    if PLU.exists():
        maps.append(("plu-1", prepare(read_surface(PLU, fill_undefined=True))[0]))
    for name, surf in maps:
        par = quilt_parameters(surf.heights_m)
        q = per_realisation(surf, "quilt", args.realisations)
        p = per_realisation(surf, "phase", args.realisations)
        nx, ny = surf.heights_m.shape
        print(
            f"{name:10s} {nx}x{ny} patch {par.patch}: quilt {q:.3f} s/realisation, phase {p:.3f} s, "
            f"ratio quilt/phase {q / p:.1f}; 100 realisations on 1 core {100 * q:.0f} s"
        )
        if name == "plu-1":
            t0 = time.perf_counter()
            for g in spawn_generators(2, 30):
                similar_surface(surf, g, method="quilt")
            print(f"{name:10s} whole run of 30 quilted surrogates: {time.perf_counter() - t0:.1f} s")
            q10 = per_realisation(surf, "quilt", 2, factor=10)
            p10 = per_realisation(surf, "phase", 2, factor=10)
            print(f"{name:10s} length factor 10: quilt {q10:.2f} s, phase {p10:.2f} s, ratio {q10 / p10:.1f}")
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024**2
    print(f"peak resident memory {peak:.2f} GiB")


if __name__ == "__main__":
    main()

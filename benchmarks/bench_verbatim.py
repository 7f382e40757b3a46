"""Benchmark: the verbatim measure (``stochfric.process.verbatim.verbatim_fraction``) on plu-1.

plu-1 (768 × 576 points after the default preparation, block = one summit spacing = 5 points) when
``../shared/data/topographies/plu-1.plu`` is there, otherwise a synthetic 768 × 576 non-Gaussian map
(smooth noise with sparse bumps, the same block side).  Prints, on one core: the block side, the
time to build the map's matcher (window statistics) and its k-d index (used for the corner blocks),
then per surrogate (``phase`` and ``quilt``) the verbatim fraction (area), the random-block fraction,
the label and the seconds of one ``verbatim_fraction`` call with the matcher reused, and finally one
call from scratch (summits, matcher, index and the measure).

Target (issue 29): a 768 × 576 map with 64 blocks in a few seconds at most.

Run:  python benchmarks/bench_verbatim.py [--surrogates 4] [--blocks 64]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from scipy.ndimage import gaussian_filter

from stochfric.process.verbatim import BlockMatcher, default_block, verbatim_fraction
from stochfric.surface.io import read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.quilting import quilt_heights
from stochfric.surface.synthesis import random_phase_heights

PLU = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies" / "plu-1.plu"


def synthetic(shape: tuple[int, int] = (768, 576), seed: int = 0) -> np.ndarray:
    """A non-Gaussian test map of plu-1's size (smooth noise plus sparse sharp bumps)."""
    rng = np.random.default_rng(seed)
    z = gaussian_filter(rng.standard_normal(shape), 1.0, mode="wrap")
    bumps = np.zeros(shape)
    idx = rng.integers(0, min(shape), size=(shape[0] * shape[1] // 400, 2))
    bumps[idx[:, 0], idx[:, 1]] = 6.0 * z.std()
    z = z + gaussian_filter(bumps, 0.8, mode="wrap") * 4.0
    return np.asarray(1e-6 * z / z.std())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--surrogates", type=int, default=4)
    parser.add_argument("--blocks", type=int, default=64)
    args = parser.parse_args()
    if PLU.is_file():
        z = prepare(read_surface(PLU), Preparation())[1].heights_m
        name = "plu-1"
    else:
        z = synthetic()
        name = "synthetic 768 × 576 (plu-1 not found)"
    t0 = time.perf_counter()
    block = default_block(z)
    t1 = time.perf_counter()
    matcher = BlockMatcher(z, block)
    t2 = time.perf_counter()
    matcher.verbatim(np.zeros((0, block, block)))  # builds the k-d index of the corner search
    t3 = time.perf_counter()
    print(f"map {name}: {z.shape[0]} × {z.shape[1]} points, block {block} points ({matcher.method})")
    print(f"summit spacing {t1 - t0:.2f} s, matcher {t2 - t1:.2f} s, index {t3 - t2:.2f} s")
    print(f"{'method':>6} {'seed':>4} {'verbatim':>8} {'blocks':>6} {'label':>10} {'median NCC':>10} {'s':>6}")
    for method in ("phase", "quilt"):
        for seed in range(args.surrogates):
            h = random_phase_heights(z, seed) if method == "phase" else quilt_heights(z, seed).heights
            t = time.perf_counter()
            m = verbatim_fraction(h, z, matcher=matcher, blocks=args.blocks, rng=seed)
            dt = time.perf_counter() - t
            print(f"{method:>6} {seed:>4} {m.fraction:8.3f} {m.block_fraction:6.3f} {m.label:>10} "
                  f"{m.median_block_ncc:10.3f} {dt:6.2f}")  # fmt: skip
    h = random_phase_heights(z, 99)
    t = time.perf_counter()
    m = verbatim_fraction(h, z, blocks=args.blocks)
    print(f"from scratch (phase surrogate, {args.blocks} blocks): {time.perf_counter() - t:.2f} s, {m.summary()}")


if __name__ == "__main__":
    main()

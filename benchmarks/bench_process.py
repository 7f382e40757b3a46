"""Benchmark: μ along the path — 10 long surfaces × ~170 windows × 12 approaches (method §4c).

Shipped surface (200 × 296 points), long surfaces 10 × its length, windows of original size
shifted by a_y = 16 grid points (7 µm, the thesis's 0.3/5.3 of the window) → 167 windows per
surface, 12 approaches.  The fast path (:func:`stochfric.process.ensemble.window_contact`: summits
found once per long surface, windows as slices of the summits sorted by column, GW sums of the
summits that can touch in one compiled loop) is timed against the naive per-window loop (crop
the window, find its summits, GW sums), on the same long surfaces; synthesis of the long
surfaces is timed separately.  The whole command on real and thesis-size maps (time and peak
memory): ``benchmarks/bench_process_files.py``.

Run:  python benchmarks/bench_process.py [--surfaces K]
"""

from __future__ import annotations

import argparse
import time
from dataclasses import dataclass

import numpy as np

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.ensemble import naive_window_contact, window_contact
from stochfric.random import spawn_generators
from stochfric.surface.io import default_surface_path, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of
from stochfric.surface.synthesis import longer_surface

SHIFT_POINTS = 16
LENGTH_FACTOR = 10


@dataclass(frozen=True)
class BenchResult:
    """Timings [s] of the two window evaluations and of the synthesis."""

    surfaces: int
    windows: int
    approaches: int
    synthesis_s: float
    fast_s: float
    naive_s: float
    max_rel_diff: float

    @property
    def ratio(self) -> float:
        """naive / fast."""
        return self.naive_s / self.fast_s


def run(surfaces: int = 10, seed: int = 1) -> BenchResult:
    """Time both window evaluations over ``surfaces`` long surfaces; check they agree."""
    fine, _ = prepare(read_surface(default_surface_path()))
    mat = get_material("brake-pad")
    u = default_approach_m(summits_of(fine))
    t0 = time.perf_counter()
    longs = [longer_surface(fine, LENGTH_FACTOR, g) for g in spawn_generators(seed, surfaces)]
    synth = time.perf_counter() - t0
    ny = fine.nb_grid_pts[1]
    t0 = time.perf_counter()
    fast = [
        window_contact(s.heights_m, s.grid_spacing_m, mat, u, window_points=ny, shift_points=SHIFT_POINTS)
        for s in longs
    ]
    t_fast = time.perf_counter() - t0
    t0 = time.perf_counter()
    naive = [
        naive_window_contact(s.heights_m, s.grid_spacing_m, mat, u, window_points=ny, shift_points=SHIFT_POINTS)
        for s in longs
    ]
    t_naive = time.perf_counter() - t0
    diff = max(
        float(np.max(np.abs(f[1] - n[1]) / np.max(n[1]))) for f, n in zip(fast, naive, strict=True)
    )
    return BenchResult(
        surfaces=surfaces,
        windows=int(fast[0][0].shape[0]),
        approaches=int(u.size),
        synthesis_s=synth,
        fast_s=t_fast,
        naive_s=t_naive,
        max_rel_diff=diff,
    )


def main() -> None:
    """Print the timings."""
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--surfaces", type=int, default=10)
    args = parser.parse_args()
    r = run(args.surfaces)
    print(f"{r.surfaces} long surfaces x {r.windows} windows x {r.approaches} approaches")
    print(f"synthesis of the long surfaces : {1e3 * r.synthesis_s:8.1f} ms")
    print(f"fast window evaluation         : {1e3 * r.fast_s:8.1f} ms")
    print(f"naive per-window loop          : {1e3 * r.naive_s:8.1f} ms")
    print(f"speed-up naive / fast          : {r.ratio:8.2f}")
    print(f"max relative difference of N   : {r.max_rel_diff:.2e}")


if __name__ == "__main__":
    main()

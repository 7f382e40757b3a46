"""The random-phase model held out on Gaussian maps, where it is exact (issue 29; docs/statistical_contact.md §0a).

A synthetic Gaussian self-affine map (H = 0.8, roll-off below 1/50 px, random amplitudes and phases: the
map of ``bench_process_files.py thesis``) is cut to n × n points; the random-phase method is validated on
its held-out halves (:func:`stochfric.process.holdout.holdout_validation`, default budget 24 → 96, the GW
μ of brake-pad at the approaches of the 20th, 60th, 150th and 400th highest summit).  The model is exact
for this map, so a sound test must not refuse it.  Two predictive distributions are compared:

* ``conditional`` — the thesis's random-phase surrogates of the training half (its periodogram kept);
* ``predictive`` — :meth:`PhaseSurrogate.predictive_heights`, new Gaussian fields of the smoothed spectrum
  (what the held-out validation uses).

    python benchmarks/holdout_gaussian_maps.py [--sizes 850 1700] [--seeds 1700 1 2 3]

Prints one line per map and distribution (about 1 min per 1700² map on 2 cores).  Not run in CI.
"""

from __future__ import annotations

import argparse
import time

import numpy as np

from stochfric.contact.materials import get_material
from stochfric.process.ensemble import SurrogateOptions
from stochfric.process.holdout import holdout_validation
from stochfric.surface import surrogates
from stochfric.surface.io import Surface
from stochfric.surface.summits import find_summits

SPACING_M = 5.3e-3 / 1700


def gaussian_map(n: int, seed: int, hurst: float = 0.8, rolloff: float = 0.02) -> np.ndarray:
    """The periodic 1700² Gaussian map of ``bench_process_files.thesis_size_map`` (Sq 0.5 µm) cut to n × n."""
    rng = np.random.default_rng(seed)
    k = np.hypot(np.fft.fftfreq(1700)[:, None], np.fft.rfftfreq(1700)[None, :])
    k[0, 0] = 1.0
    psd = np.maximum(k, rolloff) ** (-2.0 * (1.0 + hurst))
    psd[0, 0] = 0.0
    coef = np.sqrt(psd) * (rng.standard_normal(psd.shape) + 1j * rng.standard_normal(psd.shape))
    z = np.fft.irfft2(coef, s=(1700, 1700))
    return np.asarray(z * (0.5e-6 / z.std()))[:n, :n]


def _conditional(self: surrogates.SurrogateMethod, heights: np.ndarray, rng: np.random.Generator, *,
                 settings: surrogates.SurrogateSettings) -> np.ndarray:
    return self.heights(heights, rng, factor=1, settings=settings)


def run(n: int, seed: int, mode: str) -> str:
    z = gaussian_map(n, seed)
    surface = Surface(heights_m=z, physical_size_m=(n * SPACING_M, n * SPACING_M), source=f"gaussian-{n}-{seed}")
    top = np.sort(find_summits(z, (SPACING_M, SPACING_M)).heights_m)[::-1]
    u = top[0] - top[[20, 60, 150, 400]]
    cls = surrogates.PhaseSurrogate
    saved = cls.predictive_heights
    if mode == "conditional":
        cls.predictive_heights = _conditional  # type: ignore[method-assign]
    try:
        t0 = time.perf_counter()
        v = holdout_validation([surface], get_material("brake-pad"), u, SurrogateOptions(method="phase"), seed=1)
        dt = time.perf_counter() - t0
    finally:
        cls.predictive_heights = saved  # type: ignore[method-assign]
    return (f"| {n} | {seed} | {mode} | {v.verdict} | {v.max_abs_z:.2f} | {v.threshold:.2f} | {v.realizations} | "
            f"{v.worst} | {dt:.0f} |")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--sizes", type=int, nargs="+", default=[850, 1700])
    ap.add_argument("--seeds", type=int, nargs="+", default=[1700, 1, 2, 3])
    args = ap.parse_args()
    print("| n | seed | draws | verdict | max abs z | threshold | R per fold | worst | s |")
    print("|---|---|---|---|---|---|---|---|---|")
    for n in args.sizes:
        for seed in args.seeds:
            for mode in ("conditional", "predictive"):
                print(run(n, seed, mode), flush=True)


if __name__ == "__main__":
    main()

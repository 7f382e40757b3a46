"""Benchmark: GW/Hertz contact of one 170 × 170 surface at 12 approaches.

The thesis's coarse brake-pad grid is 170 × 170 (1700 points, every 10th kept). Target:
the whole contact curve (summit search + radii + 12 approaches) in well under 10 ms.
The baseline, measured in the same process on the same summits, is the plain per-approach
Python loop over the summits that a direct transcription of (3.11)–(3.16) gives.

Run:  python benchmarks/bench_contact.py
"""

from __future__ import annotations

import math
import time
from collections.abc import Callable

import numpy as np
from scipy import ndimage

from stochfric.contact.asperity import asperity_sums, default_approach_m
from stochfric.contact.materials import get_material
from stochfric.surface.summits import find_summits

N = 170
DX = 31.2e-6  # m: 5.3 mm / 170 (thesis coarse brake grid)
REPEATS = 50


def synthetic_surface(seed: int = 1) -> np.ndarray:
    """Gaussian-correlated random heights (Sq ≈ 3 µm), fixed seed."""
    rng = np.random.default_rng(seed)
    z = ndimage.gaussian_filter(rng.normal(size=(N, N)), 0.8, mode="wrap")
    return np.asarray(z / z.std() * 3e-6)


def loop_baseline(z: np.ndarray, beta: np.ndarray, u: np.ndarray, e_star: float) -> np.ndarray:
    """Per-approach Python loop over summits: returns (A_c, N, n) for every u."""
    zmax = float(z.max())
    out = np.empty((u.size, 3))
    zl, bl = z.tolist(), beta.tolist()
    for k, uk in enumerate(u.tolist()):
        a = f = 0.0
        n = 0
        for zi, bi in zip(zl, bl, strict=True):
            d = zi - (zmax - uk)
            if d > 0.0:
                a += math.pi * bi * d
                f += 4.0 / 3.0 * e_star * math.sqrt(bi * d * d * d)
                n += 1
        out[k] = (a, f, n)
    return out


def loop_summits(z: np.ndarray, dx: float) -> tuple[np.ndarray, np.ndarray]:
    """Thesis summit rule and β = −1/κ by a plain double loop (baseline)."""
    zl = z.tolist()
    heights, radii = [], []
    for i in range(2, len(zl) - 2):
        for j in range(2, len(zl[0]) - 2):
            c = zl[i][j]
            if (c > zl[i - 1][j] and c > zl[i + 1][j] and c > zl[i - 2][j] and c > zl[i + 2][j]
                    and c > zl[i][j - 1] and c > zl[i][j + 1] and c > zl[i][j - 2]
                    and c > zl[i][j + 2]):  # fmt: skip
                kappa = 0.5 * (zl[i + 1][j] + zl[i - 1][j] + zl[i][j + 1] + zl[i][j - 1]
                               - 4.0 * c) / (dx * dx)  # fmt: skip
                heights.append(c)
                radii.append(-1.0 / kappa)
    return np.array(heights), np.array(radii)


def best_of(fn: Callable[[], object], repeats: int) -> float:
    best = math.inf
    for _ in range(repeats):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def main() -> None:
    z = synthetic_surface()
    e_star = get_material("brake-pad").e_star_pa
    s = find_summits(z, (DX, DX))
    u = default_approach_m(s)  # 12 approaches, σ_S/4 … 3σ_S

    def vectorised_sums() -> object:
        return asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=e_star)

    def full_curve() -> object:
        sm = find_summits(z, (DX, DX))
        return asperity_sums(sm.heights_m, sm.radius_m, u, e_star_pa=e_star)

    def baseline() -> object:
        return loop_baseline(s.heights_m, s.radius_m, u, e_star)

    def baseline_full() -> object:
        zs, bs = loop_summits(z, DX)
        return loop_baseline(zs, bs, u, e_star)

    # same numbers
    a, f, n = vectorised_sums()  # type: ignore[misc]
    ref = baseline()
    assert isinstance(ref, np.ndarray)
    np.testing.assert_allclose(a, ref[:, 0], rtol=1e-10)
    np.testing.assert_allclose(f, ref[:, 1], rtol=1e-10)
    np.testing.assert_array_equal(n, ref[:, 2])

    t_vec = best_of(vectorised_sums, REPEATS)
    t_full = best_of(full_curve, REPEATS)
    t_loop = best_of(baseline, 5)
    t_loop_full = best_of(baseline_full, 3)
    zs, _ = loop_summits(z, DX)
    assert zs.size == s.count
    print(f"surface {N}x{N}, {s.count} summits, {u.size} approaches, max contacts {int(n[-1])}")
    print("                                 vectorised      plain loop   ratio")
    print(f"contact sums (12 approaches)  : {t_vec * 1e3:8.3f} ms   {t_loop * 1e3:8.3f} ms   {t_loop / t_vec:5.0f}x")
    print(
        f"summits + radii + sums        : {t_full * 1e3:8.3f} ms   {t_loop_full * 1e3:8.3f} ms"
        f"   {t_loop_full / t_full:5.0f}x"
    )
    verdict = "OK" if t_full < 10e-3 else "SLOWER THAN TARGET"
    print(f"target < 10 ms for the whole curve: {verdict}")


if __name__ == "__main__":
    main()

"""Evaluation: does the measured map pass the summit check against its own surrogates?

For each rough shared topography (``/work/shared/data/topographies``, or ``--dir``): read with
undefined points filled, prepare with the default :class:`Preparation`, remove spikes (points
where ``|z − median3×3(z)| > 8 · 1.4826 · MAD`` are replaced by the 3×3 median; MAD over the
points whose residual is not exactly 0 — on quantised or smooth maps half the residuals are 0
and the plain MAD would flag a third of the map), then generate ``--n`` surrogates per method
and compute the summit check as in :func:`stochfric.process.checks.surrogate_check`:
``z = (measured − ensemble mean) / ensemble sd (ddof 1)`` for the summit count, the mean summit
radius β̄ and the summit-height sd σ_S (thesis summit rule); pass if all three |z| < 3.
Also printed: the Laplacian kurtosis of the map and the median over the surrogates, the copy
metrics of the quilted surrogates (largest normalised cross-correlation with the map and with the
next surrogate, largest verbatim piece / map area, maxima over the ensemble) and the seconds per
realisation.

Run:  python benchmarks/eval_surrogates.py [--n 30] [--methods quilt phase] [--files plu-1.plu ...]
Ablations of the fixed rule (not used for the verdict): ``--spacings``, ``--screening``,
``--candidates``.
"""

from __future__ import annotations

import argparse
import time
from dataclasses import replace
from pathlib import Path

import numpy as np
from scipy.ndimage import median_filter
from scipy.stats import kurtosis

from stochfric.process.ensemble import summit_statistics
from stochfric.random import spawn_generators
from stochfric.surface.io import Surface, read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.quilting import copy_metrics, quilt_heights, quilt_parameters
from stochfric.surface.summits import find_summits
from stochfric.surface.surrogates import similar_surface

DATA = Path("/work/shared/data/topographies")
ROUGH = ("al3d-1.al3d", "mnt-1.mnt", "opd-1.opd", "plu-1.plu", "sur-2.sur", "x3p-2.x3p")
NAMES = ("count", "beta", "sigma_s")


def despike(z: np.ndarray) -> np.ndarray:
    """Replace points farther than 8 robust sds from their 3×3 median by the median."""
    med = median_filter(z, 3, mode="nearest")
    r = z - med
    nz = r[r != 0.0]
    if nz.size == 0:
        return z
    mad = float(np.median(np.abs(nz - np.median(nz))))
    bad = np.abs(r) > 8.0 * 1.4826 * mad
    out = z.copy()
    out[bad] = med[bad]
    return out


def load(path: Path) -> Surface:
    """Read, prepare (defaults) and despike one map."""
    fine, _ = prepare(read_surface(path, fill_undefined=True), Preparation())
    return replace(fine, heights_m=despike(fine.heights_m))


def laplacian_kurtosis(z: np.ndarray) -> float:
    """Kurtosis (3 for a Gaussian) of the 5-point Laplacian."""
    lap = z[2:, 1:-1] + z[:-2, 1:-1] + z[1:-1, 2:] + z[1:-1, :-2] - 4.0 * z[1:-1, 1:-1]
    return float(kurtosis(lap.ravel(), fisher=False))


def stats_of(z: np.ndarray, spacing: tuple[float, float]) -> np.ndarray:
    s = find_summits(z, spacing, rule="thesis")
    return summit_statistics(s.heights_m, s.radius_m)


def evaluate(surface: Surface, method: str, n: int, seed: int, overrides: dict[str, float]) -> dict[str, object]:
    z = surface.heights_m
    spacing = surface.grid_spacing_m
    meas = stats_of(z, spacing)
    rows, kurt, ncc_map, ncc_pair, piece = [], [], [], [], []
    prev = None
    par = None
    if method == "quilt":
        par = quilt_parameters(z)
        if overrides.get("spacings"):
            par = quilt_parameters(z, patch_spacings=float(overrides["spacings"]))
        if overrides.get("screening") is not None:
            par = replace(par, screening_length=float(overrides["screening"]) * par.patch)
        if overrides.get("candidates"):
            par = replace(
                par, candidates=int(overrides["candidates"]), choose=min(par.choose, int(overrides["candidates"]))
            )
        if overrides.get("choose"):
            par = replace(par, choose=int(overrides["choose"]))
        if overrides.get("split") is not None:
            par = replace(par, split_wavelength=float(overrides["split"]) * par.patch)
    t0 = time.perf_counter()
    for k, g in enumerate(spawn_generators(seed, n)):
        if method == "quilt":
            res = quilt_heights(z, g, parameters=par)
            h = res.heights
            if k < overrides.get("copies", 5):
                cm = copy_metrics(h, z, source=res)
                ncc_map.append(cm.max_ncc)
                piece.append(cm.largest_piece_fraction)
                if prev is not None:
                    ncc_pair.append(copy_metrics(h, prev).max_ncc)
                prev = h
        else:
            h = similar_surface(surface, g, method=method).heights_m
        rows.append(stats_of(h, spacing))
        kurt.append(laplacian_kurtosis(h))
    seconds = (time.perf_counter() - t0) / n
    e = np.array(rows)
    zval = (meas - e.mean(axis=0)) / e.std(axis=0, ddof=1)
    return {
        "z": zval,
        "pass": bool(np.all(np.abs(zval) < 3.0)),
        "kurt": float(np.median(kurt)),
        "seconds": seconds,
        "ncc_map": max(ncc_map) if ncc_map else np.nan,
        "ncc_pair": max(ncc_pair) if ncc_pair else np.nan,
        "piece": max(piece) if piece else np.nan,
        "patch": par.patch if par else 0,
        "rel": e.mean(axis=0) / meas - 1.0,
    }


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=30)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--dir", type=Path, default=DATA)
    ap.add_argument("--files", nargs="*", default=list(ROUGH))
    ap.add_argument("--methods", nargs="*", default=["quilt", "phase"])
    ap.add_argument("--spacings", type=float, default=0.0, help="ablation: patch side in summit spacings")
    ap.add_argument("--screening", type=float, default=None, help="ablation: screening length in patches")
    ap.add_argument("--candidates", type=int, default=0, help="ablation: candidates per patch")
    ap.add_argument("--choose", type=int, default=0, help="ablation: choose among the k best candidates")
    ap.add_argument("--split", type=float, default=None, help="ablation: split wavelength in patches (0 = off)")
    ap.add_argument("--copies", type=int, default=5, help="surrogates whose copy metrics are computed")
    args = ap.parse_args()
    overrides = {
        "spacings": args.spacings,
        "screening": args.screening,
        "candidates": args.candidates,
        "copies": args.copies,
        "choose": args.choose,
        "split": args.split,
    }
    print(
        f"{'file':12s} {'grid':>9s} {'method':6s} {'patch':>5s} {'z_count':>8s} {'z_beta':>7s} {'z_sigS':>7s} "
        f"{'verdict':7s} {'kurt map':>9s} {'kurt sur':>9s} {'ncc map':>7s} {'ncc s-s':>7s} {'piece':>6s} "
        f"{'s/real':>7s}  rel.dev(count,beta,sigS)"
    )
    passed = dict.fromkeys(args.methods, 0)
    for name in args.files:
        surface = load(args.dir / name)
        z = surface.heights_m
        k_map = laplacian_kurtosis(z)
        for method in args.methods:
            r = evaluate(surface, method, args.n, args.seed, overrides)
            zc, zb, zs = np.asarray(r["z"], dtype=float).tolist()
            passed[method] += int(bool(r["pass"]))
            rel = ", ".join(f"{v:+.1%}" for v in r["rel"])  # type: ignore[attr-defined]
            print(
                f"{name:12s} {z.shape[0]:4d}x{z.shape[1]:<4d} {method:6s} {r['patch']:5d} {zc:8.2f} {zb:7.2f} "
                f"{zs:7.2f} {'pass' if r['pass'] else 'FAIL':7s} {k_map:9.1f} {r['kurt']:9.1f} "
                f"{r['ncc_map']:7.3f} {r['ncc_pair']:7.3f} {r['piece']:6.3f} {r['seconds']:7.3f}  {rel}",
                flush=True,
            )
    print("passed: " + ", ".join(f"{m} {c}/{len(args.files)}" for m, c in passed.items()))


if __name__ == "__main__":
    main()

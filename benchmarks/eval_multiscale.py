"""Evaluation: multi-scale marginal matching beside random phases and quilting (issue 29, item 4).

For every shared topography (``/work/shared/data/topographies``, or ``--dir``) and two synthetic maps of
known statistics (a Gaussian field, Laplacian kurtosis 3, and the same kind of field with sparse sharp
bumps, kurtosis ≈ 20): read with undefined points filled (:func:`stochfric.surface.io.read_surface`,
``fill_undefined=True``), prepare with the default :class:`Preparation` and take the coarse map
(files that fail to read or prepare are skipped with the reason).  For each method — ``phase``,
``quilt`` (only where :func:`~stochfric.surface.quilting.quilt_applicable` says the map can be quilted)
and ``multiscale`` (:mod:`stochfric.surface.multiscale`, registered for the run) — ``--n`` surrogates
(default 8, independent child streams of ``--seed``) and the z of the summit check,
``z = (map − ensemble mean)/ensemble sd`` (ddof 1), for the summit count, the mean summit radius β̄, the
summit-height sd σ_S (thesis rule, the map's spacing) and the kurtosis of the 5-point Laplacian; its mean
over the surrogates; the seconds per surrogate (this machine, wall clock); the largest normalised
cross-correlation of the first surrogate with the map (``ncc``; for random phases it is what an
independent field of the map's spectrum reaches, high on maps with few correlation areas); for
multiscale also its amplitude error ε (mean).

Run:  python benchmarks/eval_multiscale.py [--n 8] [--files plu-1.plu ...] [--methods phase multiscale]
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np
from scipy import ndimage
from scipy.stats import kurtosis

from stochfric.random import spawn_generators
from stochfric.surface.io import Surface, read_surface
from stochfric.surface.multiscale import laplacian, multiscale_heights, register
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.quilting import max_normalised_correlation, quilt_applicable
from stochfric.surface.summits import find_summits
from stochfric.surface.surrogates import SurrogateSettings, surrogate_method

DATA = Path("/work/shared/data/topographies")
METHODS = ("phase", "quilt", "multiscale")
SYNTHETIC = ("synthetic-gauss", "synthetic-spiky")


def synthetic(name: str, shape: tuple[int, int] = (320, 384), seed: int = 0) -> Surface:
    """A Gaussian field (corr. 1.5 points) or a field with sparse sharp bumps (spacing 1 µm)."""
    rng = np.random.default_rng(seed)
    if name == "synthetic-gauss":
        z = ndimage.gaussian_filter(rng.standard_normal(shape), 1.5, mode="wrap")
    else:
        z = ndimage.gaussian_filter(rng.standard_normal(shape), 1.0, mode="wrap")
        bumps = np.zeros(shape)
        idx = rng.integers(0, min(shape), size=(shape[0] * shape[1] // 400, 2))
        bumps[idx[:, 0], idx[:, 1]] = 6.0 * z.std()
        z = z + ndimage.gaussian_filter(bumps, 0.8, mode="wrap") * 4.0
    return Surface(heights_m=1e-6 * z / z.std(), physical_size_m=(shape[0] * 1e-6, shape[1] * 1e-6), source=name)


def load(path: Path) -> Surface:
    """Read (undefined points filled) and prepare (defaults) one file; the coarse map."""
    return prepare(read_surface(path, fill_undefined=True), Preparation())[1]


def laplacian_kurtosis(z: np.ndarray) -> float:
    """Kurtosis (3 for a Gaussian field) of the 5-point Laplacian of the interior points."""
    return float(kurtosis(laplacian(z).ravel(), fisher=False))


def stats_of(z: np.ndarray, spacing: tuple[float, float]) -> np.ndarray:
    """(summit count, β̄ [m], σ_S [m], Laplacian kurtosis)."""
    s = find_summits(z, spacing)
    n = s.count
    return np.array([float(n), float(s.radius_m.mean()) if n else np.nan, float(s.heights_m.std()) if n > 1 else np.nan,
                     laplacian_kurtosis(z)])


def evaluate(surface: Surface, method: str, n: int, seed: int) -> dict[str, object]:
    z = surface.heights_m
    spacing = surface.grid_spacing_m
    measured = stats_of(z, spacing)
    settings = SurrogateSettings()
    m = surrogate_method(method)
    rows, eps = [], []
    ncc = float("nan")
    seconds = 0.0
    for k, g in enumerate(spawn_generators(seed, n)):
        t0 = time.perf_counter()
        if method == "multiscale":
            res = multiscale_heights(z, g, amplitude=settings.amplitude)
            h = res.heights
            eps.append(res.amplitude_error)
        else:
            h = m.heights(z, g, factor=1, settings=settings)
        seconds += time.perf_counter() - t0
        rows.append(stats_of(h, spacing))
        if k == 0:
            ncc = max_normalised_correlation(h, z)
    e = np.array(rows)
    with np.errstate(divide="ignore", invalid="ignore"):
        zval = (measured - e.mean(axis=0)) / e.std(axis=0, ddof=1)
    return {"z": zval, "measured": measured, "mean": e.mean(axis=0), "seconds": seconds / n,
            "eps": float(np.mean(eps)) if eps else float("nan"), "ncc": ncc,
            "pass": bool(np.all(np.abs(zval[:3]) < 3.0))}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--n", type=int, default=8)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--dir", type=Path, default=DATA)
    ap.add_argument("--files", nargs="*", default=None, help="file names under --dir (default: all) or "
                    f"{', '.join(SYNTHETIC)}")
    ap.add_argument("--methods", nargs="*", default=list(METHODS))
    args = ap.parse_args()
    register()
    names = args.files
    if names is None:
        names = [*SYNTHETIC, *sorted(p.name for p in args.dir.iterdir() if p.is_file() and p.suffix != ".md")]
    print(f"{'map':16s} {'grid':>9s} {'method':10s} {'z_count':>8s} {'z_beta':>8s} {'z_sigS':>8s} {'z_kurt':>9s} "
          f"{'check':5s} {'kurt map':>9s} {'kurt sur':>9s} {'s/surr':>7s} {'eps':>6s} {'ncc':>5s}")
    for name in names:
        try:
            surface = synthetic(name) if name in SYNTHETIC else load(args.dir / name)
        except Exception as exc:  # report and go on: a file that cannot be read or prepared is skipped
            print(f"{name:16s} skipped: {type(exc).__name__}: {exc}", flush=True)
            continue
        z = surface.heights_m
        for method in args.methods:
            if method == "quilt":
                ok, why = quilt_applicable(z)
                if not ok:
                    print(f"{name:16s} {z.shape[0]:4d}x{z.shape[1]:<4d} {method:10s} not applicable: {why}", flush=True)
                    continue
            r = evaluate(surface, method, args.n, args.seed)
            zc, zb, zs, zk = np.asarray(r["z"], dtype=float).tolist()
            km = float(np.asarray(r["measured"])[3])
            ks = float(np.asarray(r["mean"])[3])
            print(f"{name:16s} {z.shape[0]:4d}x{z.shape[1]:<4d} {method:10s} {zc:8.1f} {zb:8.1f} {zs:8.1f} {zk:9.1f} "
                  f"{'pass' if r['pass'] else 'FAIL':5s} {km:9.1f} {ks:9.1f} {r['seconds']:7.2f} {r['eps']:6.3f} "
                  f"{r['ncc']:5.2f}", flush=True)


if __name__ == "__main__":
    main()

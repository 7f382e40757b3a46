"""GW/Hertz vs elastic half-space (boundary elements) at equal load, with grid convergence.

Issue 9 §5: μ = A_c τ_max / N compares the two models only at the same normal force. For one
measured file this script computes the GW contact over u = (u_lo … u_hi) σ_S, prescribes each
GW force to the half-space (ContactMechanics, border frame of the summit rule lowered out of
reach), and prints A_c(BEM)/A_c(GW) = μ(BEM)/μ(GW) per load for

* grid refinements of the half-space (``--refine 1 2 3``: cubic-spline interpolation of the
  analysed surface onto a k× finer grid; GW stays on the analysed grid), and
* coarsenings of the data (``--step 1 2 3``: every k-th point; GW and BEM both on it).

The numbers in docs/surface_contact.md come from

    python benchmarks/bem_equal_load.py --step 1 --refine 1 2 3 --sigma 0.5 1 1.5 2 2.5 3
    python benchmarks/bem_equal_load.py --step 1 2 3 --refine 1 --sigma 0.5 1 2 3 4 5 6 7

(the default shipped surface, brake-pad pairing; the ratio does not depend on E* at equal
N/E*). ``--json FILE`` writes all numbers.  Slow: a ×3 refinement of the 200 × 296 surface
takes about 5 min on one core.
"""

from __future__ import annotations

import argparse
import json
import time
from pathlib import Path

import numpy as np

from stochfric.contact.halfspace import _framed_and_refined, compare_equal_load
from stochfric.contact.materials import get_material
from stochfric.surface.io import Surface, default_surface_path, read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("file", nargs="?", default=None, help="height map (default: the shipped surface)")
    ap.add_argument("--material", default="brake-pad")
    ap.add_argument("--step", type=int, nargs="+", default=[1])
    ap.add_argument("--refine", type=int, nargs="+", default=[1])
    ap.add_argument("--sigma", type=float, nargs="+", default=[0.5, 1, 1.5, 2, 2.5, 3], help="u in units of σ_S")
    ap.add_argument("--json", type=Path, default=None)
    ap.add_argument(
        "--gw-on-refined",
        action="store_true",
        help="also compare GW on the spline-refined surface (summits and radii on the fine grid) "
        "with the half-space on the same grid: separates interaction from the curvature estimate",
    )
    args = ap.parse_args()
    path = Path(args.file) if args.file else default_surface_path()
    raw = read_surface(path, fill_undefined=True)
    mat = get_material(args.material)
    out: dict[str, object] = {"file": path.name, "material": args.material, "runs": []}
    for step in args.step:
        _fine, coarse = prepare(raw, Preparation(detrend="plane", median_radius=0, step=step))
        summits = summits_of(coarse)
        sigma = float(np.std(summits.heights_m))
        u = np.asarray(args.sigma) * sigma
        t0 = time.perf_counter()
        cmp = compare_equal_load(coarse, summits, mat, u, refine=args.refine)
        dt = time.perf_counter() - t0
        gw = cmp.asperity
        print(f"\n{path.name} step {step}: grid {coarse.nb_grid_pts}, {summits.count} summits, "
              f"sigma_S = {sigma * 1e6:.4g} um, {dt:.1f} s")  # fmt: skip
        head = f"{'u/sS':>5} {'A/Anom GW':>10} {'n GW':>5} {'mu GW':>7}"
        for k in args.refine:
            head += f" | x{k}: {'A/Anom':>8} {'patch':>5} {'mu':>6} {'ratio':>6} {'u/uGW':>6}"
        print(head)
        for i in range(u.size):
            line = f"{args.sigma[i]:5.2f} {gw.area_fraction[i]:10.4g} {int(gw.n_contacts[i]):5d} {gw.mu[i]:7.4f}"
            for k in args.refine:
                b = cmp.halfspace[k]
                line += (f" |     {b.area_fraction[i]:8.4g} {int(b.n_contacts[i]):5d} {b.mu[i]:6.4f} "
                         f"{cmp.area_ratio(k)[i]:6.3f} {b.approach_m[i] / gw.approach_m[i]:6.2f}")  # fmt: skip
            print(line)
        run = cmp.to_dict()
        run.update({"step": step, "grid": list(coarse.nb_grid_pts), "n_summits": summits.count,
                    "sigma_s_m": sigma, "u_over_sigma_s": list(args.sigma), "seconds": dt})  # fmt: skip
        out["runs"].append(run)  # type: ignore[attr-defined]
        if args.gw_on_refined:
            for k in args.refine:
                fine_surface = Surface(
                    heights_m=_framed_and_refined(np.asarray(coarse.heights_m), 0, k),
                    physical_size_m=coarse.physical_size_m,
                )
                fs = summits_of(fine_surface)
                # the same u / sigma_S points on the refined surface's own summits
                uf = np.asarray(args.sigma) * float(np.std(fs.heights_m))
                t0 = time.perf_counter()
                c2 = compare_equal_load(fine_surface, fs, mat, uf, refine=(1,))
                g2 = c2.asperity
                print(f"  GW and BEM both on the x{k} grid ({fs.count} summits, {time.perf_counter() - t0:.1f} s):")
                for i in range(uf.size):
                    print(f"  {args.sigma[i]:5.2f} A/Anom GW {g2.area_fraction[i]:10.4g} "
                          f"n {int(g2.n_contacts[i]):5d} mu GW {g2.mu[i]:.4f} BEM {c2.halfspace[1].mu[i]:.4f} "
                          f"ratio {c2.area_ratio(1)[i]:6.3f}")  # fmt: skip
                r2 = c2.to_dict()
                r2.update({"step": step, "gw_on_refined": k, "n_summits": fs.count})
                out["runs"].append(r2)  # type: ignore[attr-defined]
    if args.json is not None:
        args.json.write_text(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()

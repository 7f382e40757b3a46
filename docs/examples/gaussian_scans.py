"""Write nine 512² scans of one synthetic Gaussian surface whose random-phase model is exact (docs/assess.md).

Crops of the periodic 1700² Gaussian self-affine map of ``benchmarks/holdout_gaussian_maps.py`` (H = 0.8,
roll-off at 50 points, spacing 5.3 mm / 1700 = 3.118 µm), scaled to Sq 1.25 µm (2.5 × the benchmark's, so that
brake-pad gives E[μ] of a brake, 0.4–0.5), at the corners of a 3 × 3 grid 594 points apart (nine disjoint
scans), as ``.npy`` height matrices in metres (give ``--size-um 1596.24:1596.24 --height-unit m``).  No shared
scan gives a credible surface model (docs/statistical_contact.md §0d); these show what a credible case looks
like, on data whose truth is known:

    python docs/examples/gaussian_scans.py OUTDIR [--seed 1]
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from holdout_gaussian_maps import SPACING_M, gaussian_map

N, SIDE, SQ_M = 512, 1700, 1.25e-6
CORNERS = tuple((i, j) for i in (0, 594, 1188) for j in (0, 594, 1188))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out", type=Path)
    ap.add_argument("--seed", type=int, default=1)
    args = ap.parse_args()
    args.out.mkdir(parents=True, exist_ok=True)
    whole = gaussian_map(SIDE, args.seed) * (SQ_M / 0.5e-6)
    for k, (i, j) in enumerate(CORNERS):
        path = args.out / f"gaussian-{args.seed}-{k}.npy"
        np.save(path, whole[i:i + N, j:j + N])
        print(path)
    print(f"--size-um {N * SPACING_M * 1e6:.2f}:{N * SPACING_M * 1e6:.2f} --height-unit m")


if __name__ == "__main__":
    main()

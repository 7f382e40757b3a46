"""The contact-model table of docs/contact_models.md (issue 31): on every shared rough file, E[μ] and σ_μ at
three pressures for gw, bem, bem-plastic and persson on the same surrogates and measured windows, the GW/BEM
ratio and the plasticity index, for an elastic pairing (brake-pad) and a metal one (steel-s235).

Rules, the same for every file (no per-file tuning):

* the map is prepared with the defaults and coarsened by the smallest step that leaves at most ``--max-side``
  points on its longer side (the thesis coarsens by 10; the boundary-element cost grows with the grid);
* the three pressures are those GW gives on the prepared map at the 4th, 8th and 12th of the 12 approaches of
  the default approach rule (``contacts``: from 20 touching summits to A_c/A_nom = 0.1), so each file is
  compared over its own GW range (the lowest approaches touch too few pixels for a boundary-element solution
  of the coarse map);
* a file whose solve fails (an under-resolved contact) is printed with the reason, not dropped silently;
* ``--realizations`` surrogates of the analysis's default method (``auto``), seed ``--seed``;
* the boundary-element resolution on the measured (coarsened) map itself at the three pressures, elastic, its
  summit frame lowered as in the analysis: *px/patch*, the mean contact pixels per patch, and *A'/A*, the
  perimeter-corrected area (the models' default, docs/bem_validation.md §4) over the pixel count — where the
  contacts are one or two pixels the two areas differ by up to 2×, and neither is validated there.

Run: ``python benchmarks/contact_model_table.py --realizations 20`` (about 10–20 min on 2 cores);
``--files al3d-1.al3d`` for one file; ``--json PATH`` writes every number.
"""

from __future__ import annotations

import argparse
import json
import math
import time
from pathlib import Path

import numpy as np

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"
FILES = ("al3d-1.al3d", "mnt-1.mnt", "opd-1.opd", "plu-1.plu", "sur-2.sur", "x3p-2.x3p")  # frt-1: not a rough map
MATERIALS = ("brake-pad", "steel-s235")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--files", nargs="*", default=list(FILES))
    ap.add_argument("--materials", nargs="*", default=list(MATERIALS))
    ap.add_argument("--realizations", type=int, default=20)
    ap.add_argument("--max-side", type=int, default=192)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()

    from stochfric.contact.asperity import asperity_contact
    from stochfric.contact.bem import BemSettings, bem_contact
    from stochfric.contact.materials import get_material
    from stochfric.errors import AnalysisError
    from stochfric.process.analysis_config import AnalysisConfig
    from stochfric.process.contact_models import contact_model_spread
    from stochfric.process.pipeline import choose_approach
    from stochfric.surface.preprocess import Preparation
    from stochfric.surface.scans import load_scan
    from stochfric.surface.summits import SUMMIT_RULES

    rows = []
    print("| file | grid (step) | material | γ | p [MPa] | gw | bem | bem-plastic | persson | gw/bem | σ_μ gw / bem |"
          " ±sampling / ±model | px/patch | A'/A | s |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name in args.files:
        path = SHARED / name
        raw = load_scan(path, fill_undefined=True)
        step = max(1, math.ceil(max(raw.fine.nb_grid_pts) / args.max_side))
        scan = load_scan(path, fill_undefined=True, preparation=Preparation(step=step)) if step > 1 else raw
        surface = scan.coarse
        for mat_name in args.materials:
            mat = get_material(mat_name)
            u = choose_approach([surface], summit_rule="thesis")
            gw = asperity_contact(surface, scan.coarse_summits, mat, u)
            p = np.asarray(gw.pressure_pa)[[3, 7, 11]]
            cfg = AnalysisConfig(realizations=args.realizations, seed=args.seed)
            t0 = time.perf_counter()
            try:
                spread = contact_model_spread(surface, mat, p, "all", cfg, workers=args.workers)
            except AnalysisError as exc:
                print(f"| {name} | {surface.nb_grid_pts[0]}×{surface.nb_grid_pts[1]} ({step}) | {mat_name} | | "
                      f"{p[0] / 1e6:.3g}–{p[-1] / 1e6:.3g} | failed: {exc} |", flush=True)
                rows.append({"file": name, "material": mat_name, "error": str(exc)})
                continue
            seconds = time.perf_counter() - t0
            sol = bem_contact(surface.heights_m, surface.physical_size_m, mat.e_star_pa, p,
                              settings=BemSettings(frame_points=SUMMIT_RULES["thesis"].margin))
            per_patch = sol.contact_area_m2 / sol.nominal_area_m2 * np.prod(surface.nb_grid_pts) / sol.n_patches
            kept = sol.corrected_area_m2 / sol.contact_area_m2
            stats = {m: spread.surrogate_statistics(m) for m in spread.models}
            split = spread.uncertainty_split()
            ratio = spread.ratio("gw", "bem")
            assert ratio is not None
            for k, pk in enumerate(spread.pressure_pa):
                cells = " | ".join(f"{stats[m]['mu_mean'][k]:.3f}" for m in spread.models)
                print(f"| {name} | {surface.nb_grid_pts[0]}×{surface.nb_grid_pts[1]} ({step}) | {mat_name} | "
                      f"{spread.plasticity_index:.3g} | {pk / 1e6:.3g} | {cells} | {ratio[k]:.2f} | "
                      f"{stats['gw']['mu_std'][k]:.3f} / {stats['bem']['mu_std'][k]:.3f} | "
                      f"{split['sampling_half_width'][k]:.3f} / {split['model_half_width'][k]:.3f} | "
                      f"{per_patch[k]:.1f} | {kept[k]:.2f} | {seconds:.0f} |", flush=True)
            rows.append({"file": name, "step": step, "grid": list(surface.nb_grid_pts), "material": mat_name,
                         "seconds": seconds, "pixels_per_patch": per_patch.tolist(),
                         "corrected_over_pixel_area": kept.tolist(), "spread": spread.to_dict()})
    if args.json is not None:
        args.json.write_text(json.dumps(rows, indent=1, default=str))


if __name__ == "__main__":
    main()

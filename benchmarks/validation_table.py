"""The surrogate methods validated out of sample on every shared rough file (issue 29; docs/statistical_contact.md §5).

For each file (prepared with the defaults, undefined points filled) and each surrogate method that applies:
the held-out verdict (:func:`stochfric.process.holdout.holdout_validation`, default budget) with its power,
and the verbatim fraction of 4 surrogates (:func:`stochfric.process.verbatim.verbatim_fraction`); per file the
measured-window statistics (:func:`stochfric.process.holdout.measured_windows`), which rest on the
measurement alone.  Material: the pairing whose μ is physical on the file (docs/statistical_contact.md §5):
brake-pad on al3d-1, dc04 on the nanometre-rough maps.

    python benchmarks/validation_table.py [--seed 1] [--files al3d-1.al3d x3p-2.x3p ...] [--methods phase quilt]

Prints a markdown table.  Not run in CI (minutes).
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from stochfric.contact.materials import load_material
from stochfric.errors import StochfricError
from stochfric.process.ensemble import SurrogateOptions
from stochfric.process.holdout import holdout_validation, measured_windows
from stochfric.process.pipeline import choose_approach
from stochfric.process.verbatim import BlockMatcher, default_block, pool_verbatim, verbatim_fraction
from stochfric.random import spawn_generators
from stochfric.surface.io import read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.surrogates import SURROGATES, SurrogateSettings

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"
FILES = ["al3d-1.al3d", "mnt-1.mnt", "opd-1.opd", "plu-1.plu", "sur-2.sur", "x3p-2.x3p", "frt-1.frt"]


def _row(name: str, seed: int, methods: list[str]) -> list[str]:
    try:
        raw = read_surface(SHARED / name, fill_undefined=True)
        _fine, coarse = prepare(raw, Preparation())
    except StochfricError as exc:
        return [f"| {name} | refused by the preparation: {str(exc)[:120]} | | | | |"]
    mat = load_material("brake-pad" if name.startswith("al3d") else "dc04")
    u_full = choose_approach([coarse], summit_rule="thesis")  # the default range, capped on the windows
    u = np.linspace(u_full[0], u_full[-1], 6)
    mw = measured_windows([coarse], mat, u, rule="thesis")
    if mw is None:
        measured = "too few summits for 2 × 2 windows"
    else:
        k = [0, u.size - 1]
        measured = (f"{mw.windows} windows: E[μ] " + ", ".join(
            f"{mw.mu_mean[i]:.3g} [{mw.mu_mean_ci95[i, 0]:.3g}, {mw.mu_mean_ci95[i, 1]:.3g}]" for i in k)
            + "; σ_μ " + ", ".join(f"{mw.mu_std[i]:.3g} [{mw.mu_std_ci95[i, 0]:.2g}, {mw.mu_std_ci95[i, 1]:.2g}]"
                                  for i in k)
            + f"; n_eff {np.min(mw.effective_windows):.3g}–{np.max(mw.effective_windows):.3g}")
    rows = []
    h = coarse.heights_m
    matcher = BlockMatcher(h, default_block(h, "thesis"))
    for method in (SURROGATES[m] for m in methods):
        ok, why = method.applicable(h, rule="thesis")
        if not ok:
            rows.append(f"| {name} | {method.name} | not applicable: {why[:80]} | | | |")
            continue
        t0 = time.perf_counter()
        try:
            v = holdout_validation([coarse], mat, u, SurrogateOptions(method=method.name), seed=seed)
            verdict = f"{v.verdict} (max \\|z\\| {v.max_abs_z:.2f} / {v.threshold:.2f}, R = {v.realizations})"
            power = f"{v.detectable_scatter_ratio:.2g}× / {v.detectable_mean_shift_sd:.2g} sd"
        except StochfricError as exc:
            verdict, power = f"not testable: {str(exc)[:90]}", ""
        gens = spawn_generators(seed, 4)
        settings = SurrogateSettings()
        vm = pool_verbatim([verbatim_fraction(method.heights(h, g, factor=1, settings=settings), h, matcher=matcher,
                                              rng=k) for k, g in enumerate(gens)])
        rows.append(f"| {name} | {method.name} | {verdict} | {power} | {100 * vm.fraction:.0f} % ({vm.label}) | "
                    f"{time.perf_counter() - t0:.0f} s |")
    return [f"| {name} | measured | {measured} | | | |", *rows]


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--files", nargs="*", default=FILES)
    ap.add_argument("--methods", nargs="*", default=list(SURROGATES), help="surrogate methods (default: all)")
    args = ap.parse_args()
    print("| file | method | held-out verdict (max \\|z\\| / Student-t threshold, surrogates per fold) "
          "| detects (scatter ratio / mean shift) | verbatim | time |")
    print("|---|---|---|---|---|---|")
    for name in args.files:
        for line in _row(name, args.seed, args.methods):
            print(line, flush=True)


if __name__ == "__main__":
    main()

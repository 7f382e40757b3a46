"""Lyapunov study against the perturbation δ, and its η dependence (issue 10, method §6.4).

Brake, N = 4000 N, q = 5·10⁻⁵ and 5·10⁻⁴, η = 0.1 … 3 (30 values), R = 10, τ_end = 200.  For each δ:
the count of defined exponents (status ok) and of undefined ones by reason, the median of the
defined exponents per transition, and — for comparison — the median of the printed (4.43)/(4.44)
``separation_index_443`` over all cells (defined or not), which is what used to be reported.

    python examples/lyapunov_delta.py
"""

from __future__ import annotations

import warnings

import numpy as np

from stochfric.studies.config import LyapunovConfig
from stochfric.studies.lyapunov import lyapunov_study

DELTAS = (1e-8, 1e-7, 1e-6, 1e-5, 1e-4)


def main() -> None:
    warnings.simplefilter("ignore")
    out = {}
    print("| δ | model | ok / diverging / nonlinear / merged / too few | median λ (ok, diverging cells) | "
          "cells λ > 2SE / λ < −2SE | median (4.43) as printed, all cells |")
    print("|---|---|---|---|---|---|")
    for d in DELTAS:
        cfg = LyapunovConfig.model_validate({"normal_forces": (4000.0,), "eta": "0.1:3:30", "runs": 10, "seed": 1,
                                             "perturbation": d})
        s = lyapunov_study(cfg).to_json_dict()
        out[d] = s
        for m in s["models"]:
            lam = np.array(s["lyapunov"][m], dtype=float)
            sep = np.array(s["separation_index_443"][m], dtype=float)
            c = s["status_counts"][m]
            sig = s["significance"][m]
            med = f"{np.nanmedian(lam):+.3f}" if np.isfinite(lam).any() else "—"
            print(f"| {d:g} | {m} | {c['ok']} / {c['diverging']} / {c['nonlinear']} / {c['merged']} / "
                  f"{c['too-few-transitions']} | "
                  f"{med} | {sig['positive']} / {sig['negative']} | {np.nanmedian(sep):+.2f} |", flush=True)
    s = out[1e-8]
    eta = np.array(s["eta"])
    print("\nη dependence at δ = 1e-8 (sign of λ per η: + / − beyond 2 SE, 0 within, . undefined):")
    for m in s["models"]:
        lam = np.array(s["lyapunov"][m], dtype=float)[:, 0]  # [q, eta]
        se = np.nan_to_num(np.array(s["lyapunov_se"][m], dtype=float)[:, 0])
        rows = []
        for qi, q in enumerate(s["forcing_q"]):
            sym = ["." if not np.isfinite(v) else ("+" if v - 2 * e > 0 else ("−" if v + 2 * e < 0 else "0"))
                   for v, e in zip(lam[qi], se[qi], strict=True)]
            rows.append(sym)
            print(f"  {m:13s} q = {q:g}: {''.join(sym)}")
        both = [(a, b) for a, b in zip(rows[0], rows[1], strict=True) if a in "+−" and b in "+−"]
        same = sum(a == b for a, b in both)
        print(f"  {m:13s} same significant sign at both q: {same} of {len(both)} η")
    print("  η:", " ".join(f"{v:.1f}" for v in eta))


if __name__ == "__main__":
    main()

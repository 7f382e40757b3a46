"""σ(X_gh) of the white-noise model against the time step Δτ, default vs ``thesis`` mode (issue 10).

The default (Itô, ΔW = R_k √Δτ, σ_ζ = σ_μ(p)) converges as Δτ → 0; the reproduction mode
``--white-intensity thesis`` (printed eq. 4.31: σ_ζ,eff = σ_μ(p)·Lω0·Δτ) loses its noise as
Δτ → 0, σ(X_gh) ∝ √Δτ.  Six thesis cases, D = 5·10⁻⁶, τ_end = 50, window τ > 25, bootstrap SEs.

    python examples/white_intensity_dt.py --runs 300
"""

from __future__ import annotations

import argparse
import functools
import warnings

import numpy as np

from stochfric.oscillator.case import case_setup, law_for
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import ExecutionOptions, IntegrationOptions, NoiseOptions
from stochfric.studies.grids import window_mask
from stochfric.studies.stats import sample_summary

CASES = {"brake": (720.0, 2720.0, 8000.0), "sheet": (400.0, 880.0, 1750.0)}
DTS = (0.01, 0.005, 0.0025, 0.00125)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=300)
    ap.add_argument("--seed", type=int, default=2013)
    a = ap.parse_args()
    warnings.simplefilter("ignore")
    print("| preset | N [N] | mode | " + " | ".join(f"Δτ = {d:g}" for d in DTS) + " |")
    print("|---|---|---|" + "---|" * len(DTS))
    for preset, forces in CASES.items():
        for mode in ("sigma_mu", "thesis"):
            cells: dict[float, list[str]] = {f: [] for f in forces}
            for dt in DTS:
                st = case_setup(preset, white_intensity=mode, dt=dt)
                ps = [st.parameters(f, 5e-6) for f in forces]
                r = simulate(ps, model="white", law=functools.partial(law_for, st.process), process=st.process,
                             runs=a.runs, seed=a.seed, noise=NoiseOptions(white_increment=st.white_increment),
                             integration=IntegrationOptions(dt=dt), execution=ExecutionOptions(workers=2))
                for i, f in enumerate(forces):
                    mk = window_mask(r.t_gh[i], 50.0, 0.5)
                    s = sample_summary([r.x_gh[i, j][mk[j]] for j in range(a.runs)], n_boot=200,
                                       rng=np.random.default_rng(0))
                    cells[f].append(f"{s.std * 1e4:.3f} ± {s.se_std_boot * 1e4:.3f}")
            for f in forces:
                print(f"| {preset} | {f:g} | {mode} | " + " | ".join(cells[f]) + " |", flush=True)


if __name__ == "__main__":
    main()

"""Which contact-analysis process did the thesis use?  Candidate readings side by side (issue 10).

Runs the six normal-force cases of method §6.1 (brake 720/2720/8000 N, sheet 400/880/1750 N,
D = 5·10⁻⁶, τ_end = 50, Δτ = 0.005, stick window τ > 25) with the contact-analysis model under
several readings of chapter 3.3 / 4.1.3 and prints E[X_gh] and σ(X_gh) with bootstrap standard
errors (over runs), and the ratio σ/σ(default) with its delta-method standard error.

All readings run through :func:`stochfric.oscillator.integrate.simulate`.  Eq. (4.36)/(4.38) as
printed read the process at the mass *position* X_1 (μ̂_SD(X_1, ξ)), while the text of §4.1.3
describes the accumulated path x_glob: that reading is the kernel's ``path_coordinate="position"``.

    python examples/contact_process_candidates.py --runs 300
"""

from __future__ import annotations

import argparse
import dataclasses
import functools
import math
import warnings
from collections.abc import Callable, Iterator
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.oscillator.case import CaseSetup, case_setup, law_for
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import ExecutionOptions, NoiseOptions
from stochfric.oscillator.presets import Preset
from stochfric.studies.grids import window_mask
from stochfric.studies.stats import sample_summary

CASES = {"brake": (720.0, 2720.0, 8000.0), "sheet": (400.0, 880.0, 1750.0)}


class ScaledProcess:
    """A process model whose realisations are multiplied by ``gain(p)`` (variance readings)."""

    def __init__(self, base: Any, gain: Callable[[float], float]) -> None:
        self.base = base
        self.gain = gain

    def __getattr__(self, name: str) -> Any:
        return getattr(self.base, name)

    def generate(self, p: float, rng: np.random.Generator) -> npt.NDArray[np.float64]:
        return np.asarray(self.base.generate(p, rng)) * self.gain(p)


def psd_level_fit(pre: Preset, p: float) -> float:
    """The thesis's E[S](p) model function (third row of Table 3.3 / 3.6), unstated units."""
    f = pre.recorded_psd_level_fit
    assert f is not None
    return max(f.a * p**f.b + f.c, 0.0)


def readings(setup: CaseSetup) -> Iterator[tuple[str, Any, str]]:
    """(name, process model, path coordinate) of every candidate run through the kernel."""
    base: Any = setup.process  # the presets' BandLimitedProcessModel (a dataclass)
    pre = setup.preset
    k_harm = len(base.frequencies())
    df = 1.0 / base.length
    yield "default: var σ_μ(p)², mass path", base, "mass"
    yield "relative path (method §7.7)", base, "relative"
    yield "printed Δx, non-periodic grid", dataclasses.replace(
        base, dx=6.3e-4 if pre.name == "brake" else 3e-4), "mass"
    yield "E[S](p) as one-sided PSD, f in 1/m", ScaledProcess(
        base, lambda p: math.sqrt(psd_level_fit(pre, p) * k_harm * df) / base.std(p)), "mass"
    yield "E[S](p) as one-sided PSD, f in 1/mm", ScaledProcess(
        base, lambda p: math.sqrt(psd_level_fit(pre, p) * k_harm * df * 1e-3) / base.std(p)), "mass"
    yield "E[S] two-sided (variance σ_μ²/2)", ScaledProcess(base, lambda p: 1 / math.sqrt(2.0)), "mass"
    other = "falling" if pre.name == "brake" else "flat"
    yield f"spectrum {other}", dataclasses.replace(base, spectrum_shape=other, falling_ratio=0.5), "mass"
    yield "position X_1 (eq. 4.36/4.38 as printed)", base, "position"
    yield "position X_1 and variance σ_μ²/2", ScaledProcess(base, lambda p: 1 / math.sqrt(2.0)), \
        "position"
    yield "psd_level: E[S](p), thesis check 0.08 (mass path)", pre.process_with_level("psd_level"), "mass"
    yield "psd_level and position X_1", pre.process_with_level("psd_level"), "position"
    yield "psd_level and relative path", pre.process_with_level("psd_level"), "relative"


def _row(x_gh: npt.NDArray[np.float64], t_gh: npt.NDArray[np.float64]) -> tuple[float, float, float, float]:
    mk = window_mask(t_gh, 50.0, 0.5)
    s = sample_summary([x_gh[r][mk[r]] for r in range(x_gh.shape[0])], n_boot=300,
                       rng=np.random.default_rng(0))
    return s.mean, s.se_mean_boot, s.std, s.se_std_boot


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=300)
    ap.add_argument("--seed", type=int, default=2013)
    a = ap.parse_args()
    warnings.simplefilter("ignore")
    print("| preset | reading | low N | middle N | high N |")
    print("|---|---|---|---|---|")
    print("cells: E[X_gh] ± SE, σ(X_gh) ± SE (units 1e-4), σ/σ_default ± SE; brake 720/2720/8000 N, "
          "sheet 400/880/1750 N")
    for preset, forces in CASES.items():
        setup = case_setup(preset)
        ps = [setup.parameters(f, 5e-6) for f in forces]
        ref: list[tuple[float, float]] = []
        results: list[tuple[str, list[tuple[float, float, float, float]]]] = []
        for name, proc, pc in readings(setup):
            r = simulate(ps, model="contact", law=functools.partial(law_for, setup.process), process=proc,
                         runs=a.runs, seed=a.seed, noise=NoiseOptions(path_coordinate=pc),
                         execution=ExecutionOptions(workers=2))
            results.append((name, [_row(r.x_gh[i], r.t_gh[i]) for i in range(len(forces))]))
        ref = [(v[2], v[3]) for v in results[0][1]]
        for name, rows in results:
            cells = []
            for (mean, sem, sd, ses), (s0, se0) in zip(rows, ref, strict=True):
                ratio = sd / s0
                se_r = ratio * math.sqrt((ses / sd) ** 2 + (se0 / s0) ** 2) if name != results[0][0] else 0.0
                cells.append(f"{mean * 1e4:+.3f} ± {sem * 1e4:.3f}, {sd * 1e4:.3f} ± {ses * 1e4:.3f}, "
                             f"{ratio:.2f} ± {se_r:.2f}")
            print(f"| {preset} | {name} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()

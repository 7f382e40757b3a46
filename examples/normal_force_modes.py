"""Normal-force study (method §6.1) in every reproduction mode, both presets (issue 10).

Equivalent to ``stochfric study normal-force --preset brake|sheet --runs 300`` with
``--white-intensity {sigma_mu,thesis}``, ``--path-coordinate {mass,relative,position}`` and
``--process-level {sigma_mu,psd_level}``:

* ``default``      — white: σ_ζ = σ_μ(p), Itô (ΔW = R_k √Δτ); contact: mass path (thesis text);
* ``thesis``       — white: printed eq. (4.31), σ_ζ,eff = σ_μ(p)·Lω0·Δτ; contact: process read at
  the mass position x1 (eq. 4.36/4.38 as printed);
* ``thesis-rel``   — white as ``thesis``; contact: relative path (method §7.7);
* ``thesis-psd``   — as ``thesis`` with ``--process-level psd_level`` (process variance from the
  thesis's E[S](p) fit, normalised by its check σ = 0.08 at 0.5 MPa);
* ``thesis-psd-mass`` — as ``thesis-psd`` but the process read along the mass path.

Prints, per preset, force and mode, E[X_gh] and σ(X_gh) with bootstrap standard errors (runs
resampled) and σ contact/white with its 95 % bootstrap interval; with ``--figure FILE`` draws
σ(X_gh) ± SE per case and mode.  Also the forcing-study ratio σ contact/white (median over η
with 95 % interval) per mode with ``--forcing``, and D_max^d / D_max^s per mode with ``--damping``.

    python examples/normal_force_modes.py --runs 300 --forcing --damping \
        --figure docs/figures/normal_force_modes.png
"""

from __future__ import annotations

import argparse
import warnings
from typing import Any

from stochfric.studies.config import DampingConfig, ForcingConfig, NormalForceConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.forcing import forcing_study
from stochfric.studies.normal_force import normal_force_study

MODES: dict[str, dict[str, str]] = {
    "default": {"white_intensity": "sigma_mu", "path_coordinate": "mass"},
    "thesis": {"white_intensity": "thesis", "path_coordinate": "position"},
    "thesis-rel": {"white_intensity": "thesis", "path_coordinate": "relative"},
    "thesis-psd": {"white_intensity": "thesis", "path_coordinate": "position", "process_level": "psd_level"},
    "thesis-psd-mass": {"white_intensity": "thesis", "path_coordinate": "mass", "process_level": "psd_level"},
}


def run_normal_force(preset: str, runs: int, seed: int) -> dict[str, dict[str, Any]]:
    out = {}
    for name, mode in MODES.items():
        cfg = NormalForceConfig(preset=preset, runs=runs, seed=seed, phase_runs=0, **mode)  # type: ignore[arg-type]
        out[name] = normal_force_study(cfg).to_json_dict()
    return out


def table(preset: str, res: dict[str, dict[str, Any]]) -> list[str]:
    lines = []
    for name, s in res.items():
        for ni, nf in enumerate(s["normal_force_n"]):
            cells = []
            for m in ("deterministic", "white", "contact"):
                e, se = s["x_gh_mean"][m][ni][0], s["x_gh_mean_se"][m][ni][0]
                sd, ses = s["x_gh_std"][m][ni][0], s["x_gh_std_se"][m][ni][0]
                if m == "deterministic":
                    cells.append(f"{e * 1e4:+.3f}")
                else:
                    cells.append(f"{e * 1e4:+.3f} ± {(se or 0) * 1e4:.3f} | {sd * 1e4:.3f} ± {(ses or 0) * 1e4:.3f}")
            r = s["sigma_ratio_contact_white"][ni][0]
            cells.append(f"{r['value']:.2f} [{r['low']:.2f}, {r['high']:.2f}]")
            lines.append(f"| {preset} | {nf:g} | {name} | " + " | ".join(cells) + " |")
    return lines


def figure(all_res: dict[str, dict[str, dict[str, Any]]], path: str) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.2))
    for ax, (preset, res) in zip(axes, all_res.items(), strict=True):
        width = 0.08
        k = 0
        for name, s in res.items():
            for m, mk in (("white", "o"), ("contact", "s")):
                xs = [i + (k - 4.5) * width for i in range(len(s["normal_force_n"]))]
                ys = [row[0] * 1e4 for row in s["x_gh_std"][m]]
                es = [(row[0] or 0) * 1e4 for row in s["x_gh_std_se"][m]]
                ax.errorbar(xs, ys, yerr=es, fmt=mk, ms=4, capsize=2, label=f"{m}, {name}")
                k += 1
        ax.set_xticks(range(len(res["default"]["normal_force_n"])))
        ax.set_xticklabels([f"{v:g} N" for v in res["default"]["normal_force_n"]])
        ax.set_ylabel("σ(X_gh) · 10⁴")
        ax.set_title(f"{preset}, D = 5·10⁻⁶, τ_end = 50, Δτ = 0.005, window τ > 25", fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def forcing(preset: str, runs: int, seed: int) -> list[str]:
    lines = []
    for name, mode in MODES.items():
        s = forcing_study(ForcingConfig(preset=preset, runs=runs, seed=seed, **mode)).to_json_dict()  # type: ignore[arg-type]
        for q, ci in s["sigma_ratio_median_ci"].items():
            lines.append(f"| {preset} | {q} | {name} | {ci['value']:.2f} ± {ci['se_delta']:.2f} "
                         f"[{ci['low']:.2f}, {ci['high']:.2f}] |")
    return lines


#: the damping-study force per preset (the thesis's phase-diagram forces)
DAMPING_FORCE = {"brake": 5600.0, "sheet": 1400.0}


def _dmax(cell: Any) -> str:
    """'value [value, next grid point]' of a D_max^s entry, with '> grid' where it has no end."""
    value, (low, high) = cell["value"], cell["interval"]
    if value is None:
        return "—"
    return f"{value:g} [{low:g}, {'> grid' if high is None else f'{high:g}'}]"


def damping(preset: str, runs: int, seed: int) -> list[str]:
    """D_max^d and D_max^s per mode at one force, D = 0.05 … 0.25 × 41 (as `study damping`)."""
    lines = []
    for name, mode in MODES.items():
        cfg = DampingConfig(preset=preset, normal_forces=(DAMPING_FORCE[preset],), runs=runs, seed=seed,
                            **mode)  # type: ignore[arg-type]
        s = damping_study(cfg).to_json_dict()
        det = s["d_max_deterministic"][0]
        lines.append(f"| {preset} | {name} | {det:g} | {_dmax(s['d_max_sample_extreme']['white'][0])} | "
                     f"{_dmax(s['d_max_sample_extreme']['contact'][0])} |")
    return lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--runs", type=int, default=300)
    ap.add_argument("--seed", type=int, default=2013)
    ap.add_argument("--figure", default=None)
    ap.add_argument("--forcing", action="store_true", help="also the forcing-study σ ratio (10 runs, η = 0:3:61)")
    ap.add_argument("--damping", action="store_true",
                    help="also D_max^d, D_max^s per mode (10 runs, seed 0, D = 0.05:0.25:41, N = 5600 / 1400 N)")
    a = ap.parse_args()
    warnings.simplefilter("ignore")
    all_res = {}
    print("| preset | N [N] | mode | det. E (1e-4) | white E ± SE | white σ ± SE | contact E ± SE | "
          "contact σ ± SE | σ contact/white [95 %] |")
    print("|---|---|---|---|---|---|---|---|---|")
    for preset in ("brake", "sheet"):
        all_res[preset] = run_normal_force(preset, a.runs, a.seed)
        print("\n".join(table(preset, all_res[preset])), flush=True)
    if a.figure:
        figure(all_res, a.figure)
    if a.forcing:
        print("\n| preset | q | mode | median over η of σ contact/white ± SE [95 %] |")
        print("|---|---|---|---|")
        for preset in ("brake", "sheet"):
            print("\n".join(forcing(preset, 10, a.seed)), flush=True)
    if a.damping:
        print("\n| preset | mode | D_max^d | D_max^s white | D_max^s contact |")
        print("|---|---|---|---|---|")
        for preset in ("brake", "sheet"):
            print("\n".join(damping(preset, 10, 0)), flush=True)


if __name__ == "__main__":
    main()

"""Sensitivity of the open choices of method §7.9 (tables for ``docs/studies.md``).

* damping study: the stick window w, τ_end, the initial state (sticking at the origin vs a
  small perturbation of steady sliding), Δτ / integrator, common random numbers over D;
* Lyapunov study: the perturbation δ of the comparison run.

``python examples/sensitivity.py [--preset brake]`` prints Markdown tables (an example script: the library
holds no command-line scripts; the studies it calls are the library's).
"""

from __future__ import annotations

import argparse
import math
from typing import Any

from stochfric.oscillator.case import case_setup
from stochfric.studies.config import DampingConfig, LyapunovConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.lyapunov import lyapunov_study


def _fmt(v: Any) -> str:
    if v is None or (isinstance(v, float) and not math.isfinite(v)):
        return "—"
    return f"{v:.3g}"


def damping_sensitivity(preset: str = "brake", normal_force: float | None = None, seed: int = 2013,
                        runs: int = 10) -> list[dict[str, Any]]:
    """D_max^d and the sample extreme D_max^s (white, contact) for variants of the open choices."""
    setup = case_setup(preset)
    nf = normal_force if normal_force is not None else float(setup.preset.study_parameters.damping_study_force)
    case = setup.case(nf, 0.0)
    p, law = case.params, case.law
    x1s = p.n * float(law.kinetic(p.belt_speed))  # static rest position (4.8): n μ(v0)
    base: dict[str, Any] = {"preset": preset, "normal_forces": (nf,), "runs": runs, "seed": seed}
    variants: list[tuple[str, dict[str, Any]]] = [
        ("default: w = 0.5, τ_end = 50, Δτ = 0.005, euler, x0 = (0, γ0), CRN", {}),
        ("stick window w = 0.25", {"stick_window": 0.25}),
        ("stick window w = 0.75", {"stick_window": 0.75}),
        ("stick window w = 0.9", {"stick_window": 0.9}),
        ("τ_end = 100 (w = 0.5)", {"tau_end": 100.0}),
        ("τ_end = 200 (w = 0.5)", {"tau_end": 200.0}),
        ("Δτ = 0.0025", {"dt": 0.0025}),
        ("Δτ = 0.001", {"dt": 0.001}),
        ("integrator accurate (det., contact)", {"integrator": "accurate"}),
        ("independent noise over D (no CRN)", {"common_random_numbers": False}),
        ("other seed", {"seed": seed + 1}),
        ("x0 = steady sliding + 1e-5 (small start)", {"x0": (x1s + 1e-5, 0.0)}),
        ("x0 = steady sliding + 1e-4", {"x0": (x1s + 1e-4, 0.0)}),
    ]
    rows = []
    for label, change in variants:
        s = damping_study(DampingConfig.model_validate({**base, **change})).to_json_dict()
        rows.append({
            "variant": label,
            "d_hopf": s["d_hopf"][0],
            "d_max_deterministic": s["d_max_deterministic"][0],
            "d_max_white": s["d_max_sample_extreme"]["white"][0]["value"],
            "d_hi_white": s["d_max_sample_extreme"]["white"][0]["interval"][1],
            "d_max_contact": s["d_max_sample_extreme"]["contact"][0]["value"],
            "d_hi_contact": s["d_max_sample_extreme"]["contact"][0]["interval"][1],
        })
    return rows


def lyapunov_sensitivity(preset: str = "brake", seed: int = 2013, runs: int = 10) -> list[dict[str, Any]]:
    """Per δ = 1e-7 … 1e-5: the share of defined cells with λ > 2 SE and the undefined/merged counts."""
    setup = case_setup(preset)
    nf = float(setup.preset.study_parameters.forcing_study_force)
    rows = []
    for delta in (1e-7, 1e-6, 1e-5):
        cfg = LyapunovConfig.model_validate({"preset": preset, "normal_forces": (nf,), "eta": "0.1:3:30",
                                             "runs": runs, "seed": seed, "perturbation": delta})
        s = lyapunov_study(cfg).to_json_dict()
        row: dict[str, Any] = {"perturbation": delta}
        for m in s["models"]:
            row[f"positive_{m}"] = s["positive_fraction"][m]
            row[f"merged_{m}"] = s["status_counts"][m]["merged"]
            row[f"undefined_{m}"] = sum(v for k, v in s["status_counts"][m].items() if k != "ok")
        rows.append(row)
    return rows


def main() -> None:  # pragma: no cover - documentation helper
    ap = argparse.ArgumentParser(description=__doc__)
    ap.add_argument("--preset", default="brake")
    a = ap.parse_args()
    rows = damping_sensitivity(a.preset)
    print("| variant | D_H | D_max^d | D_max^s white (sample extreme) [.., D_hi] | "
          "D_max^s contact (sample extreme) [.., D_hi] |")
    print("|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['variant']} | {_fmt(r['d_hopf'])} | {_fmt(r['d_max_deterministic'])} | "
              f"{_fmt(r['d_max_white'])} [.., {_fmt(r['d_hi_white'])}] | "
              f"{_fmt(r['d_max_contact'])} [.., {_fmt(r['d_hi_contact'])}] |")
    print()
    ly = lyapunov_sensitivity(a.preset)
    print("| δ | λ > 2 SE det. | white | contact (fraction of defined cells) | "
          "undefined det. / white / contact |")
    print("|---|---|---|---|---|")
    for r in ly:
        print(f"| {r['perturbation']:g} | {_fmt(r['positive_deterministic'])} | {_fmt(r['positive_white'])} | "
              f"{_fmt(r['positive_contact'])} | {r['undefined_deterministic']} / {r['undefined_white']} / "
              f"{r['undefined_contact']} |")


if __name__ == "__main__":  # pragma: no cover
    main()

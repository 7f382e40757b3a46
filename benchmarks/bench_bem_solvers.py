"""Speed of the BEM solvers of stochfric.contact.bem: Tamaas vs ContactMechanics (periodic, free).

For each grid (64², 128², 200²) one self-affine periodic map (H = 0.8, roll-off at L/2, short
cutoff 4 pixels, 1 µm rms on 100 µm; validate_bem_kappa.self_affine_map) is solved over a sweep
of 12 nominal pressures, geometric from 0.25 % to 10 % of E*ḡ/2 (A/A_nom ≈ 0.5 … 20 %), in one
:func:`~stochfric.contact.bem.bem_contact` call (ascending, warm-started), at tolerance 1e-8 and
1e-6, elastic and with a hardness H = 0.2 E*ḡ (the top pressure is 0.25 H).  Printed per
configuration: the sweep's wall time, the mean and the first (cold) solve's time, the mean
iterations, and max |ΔA_c|/A_c between the two tolerances.  A sweep that runs past
``--limit`` seconds is cut by the solver's own time limit and shown as "> limit".

    python benchmarks/bench_bem_solvers.py            # about 10 min on 2 cores
    python benchmarks/bench_bem_solvers.py --quick    # 64² only, < 1 min
    python benchmarks/bench_bem_solvers.py --json out.json

The table in docs/bem_validation.md comes from the full run.
"""

from __future__ import annotations

import argparse
import importlib.util
import json
import platform
import sys
import time
from dataclasses import asdict, dataclass
from pathlib import Path
from types import ModuleType

import numpy as np

from stochfric.contact.bem import BemError, BemSettings, bem_available, bem_contact

HERE = Path(__file__).resolve().parent
N_PRESSURES = 12


def _kappa_module() -> ModuleType:
    spec = importlib.util.spec_from_file_location("validate_bem_kappa", HERE / "validate_bem_kappa.py")
    assert spec is not None and spec.loader is not None
    mod = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = mod
    spec.loader.exec_module(mod)
    return mod


@dataclass(frozen=True)
class Row:
    """One configuration: solver, boundary, elastic/plastic, grid, tolerance and its timings."""

    solver: str
    periodic: bool
    plastic: bool
    grid: int
    tolerance: float
    sweep_s: float | None  # None: cut by the time limit
    mean_solve_s: float | None
    first_solve_s: float | None
    mean_iterations: float | None
    area_fraction: list[float] | None
    note: str = ""


def machine() -> str:
    """CPU model and the cores this process may use."""
    model = platform.processor() or "unknown CPU"
    info: dict[str, str] = {}
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            key, _, value = line.partition(":")
            info.setdefault(key.strip(), value.strip())
    except OSError:
        pass
    if "model name" in info:
        # AMD family 25 (0x19) model 0/1 is Zen 3 (Milan)
        model = f"{info['model name']} (family {info.get('cpu family', '?')} model {info.get('model', '?')})"
    import os

    cores = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") else os.cpu_count()
    return f"{model}, {cores} cores, Python {platform.python_version()}"


def run(grids: tuple[int, ...], limit_s: float, configs: list[tuple[str, bool, bool]]) -> list[Row]:
    """Every (solver, periodic, plastic) configuration on every grid at both tolerances."""
    ks = _kappa_module()
    size, e_star = 1e-4, 1e9
    rows: list[Row] = []
    for n in grids:
        h = ks.self_affine_map(n, hurst=0.8, size_m=size, short_wavelength_m=4 * size / n, seed=0)
        g = ks.rms_gradient(h, (size, size))
        p = np.geomspace(0.0025, 0.1, N_PRESSURES) * e_star * g / 2
        hardness = 0.2 * e_star * g
        for solver, periodic, plastic in configs:
            if not bem_available(solver):
                continue
            for tol in (1e-8, 1e-6):
                settings = BemSettings(
                    solver=solver, periodic=periodic, tolerance=tol, time_limit_s=limit_s,
                    hardness_pa=hardness if plastic else None, max_iterations=20_000,
                )  # fmt: skip
                t0 = time.perf_counter()
                try:
                    sol = bem_contact(h, (size, size), e_star, p, settings=settings)
                except BemError as err:
                    rows.append(Row(solver, periodic, plastic, n, tol, None, None, None, None, None, str(err)[:80]))
                    print(_line(rows[-1]), flush=True)
                    continue
                wall = time.perf_counter() - t0
                rows.append(
                    Row(
                        solver, periodic, plastic, n, tol, wall, float(sol.seconds.mean()), float(sol.seconds[0]),
                        float(sol.iterations.mean()), [float(v) for v in sol.area_fraction],
                    )
                )  # fmt: skip
                print(_line(rows[-1], rows), flush=True)
    return rows


def _area_change(row: Row, rows: list[Row]) -> float | None:
    """max |A(1e-6) − A(1e-8)| / A(1e-8) over the sweep, for a 1e-6 row."""
    if row.tolerance != 1e-6 or row.area_fraction is None:
        return None
    for r in rows:
        same = (r.solver, r.periodic, r.plastic, r.grid) == (row.solver, row.periodic, row.plastic, row.grid)
        if same and r.tolerance == 1e-8 and r.area_fraction is not None:
            a, b = np.asarray(row.area_fraction), np.asarray(r.area_fraction)
            return float(np.max(np.abs(a - b) / b))
    return None


def _fmt(v: float | None, spec: str) -> str:
    return "—" if v is None else format(v, spec)


def _line(r: Row, rows: list[Row] | None = None) -> str:
    boundary = "periodic" if r.periodic else "free"
    kind = "plastic" if r.plastic else "elastic"
    change = _area_change(r, rows or [])
    if "time limit" in r.note:
        sweep, note = "> " + r.note.split("time limit of ")[1].split(" s")[0], ""
    else:
        sweep, note = _fmt(r.sweep_s, ".2f"), ("" if r.sweep_s is not None else " " + r.note)
    cells = [
        f"{r.solver:16s}", f"{boundary:8s}", f"{kind:7s}", f"{r.grid:4d}²", f"{r.tolerance:.0e}", f"{sweep:>8s}",
        f"{_fmt(r.mean_solve_s, '.4f'):>8s}", f"{_fmt(r.first_solve_s, '.4f'):>8s}",
        f"{_fmt(r.mean_iterations, '.0f'):>6s}", f"{'' if change is None else f'{change:.1e}':>8s}",
    ]  # fmt: skip
    return "| " + " | ".join(cells) + " |" + note


HEADER = (
    "| solver           | boundary | kind    | grid  | tol   | sweep s  | solve s  | first s  | iters  | ΔA/A     |\n"
    "|------------------|----------|---------|-------|-------|----------|----------|----------|--------|----------|"
)

CONFIGS = [
    ("tamaas", True, False),
    ("contactmechanics", True, False),
    ("contactmechanics", False, False),
    ("tamaas", True, True),
    ("contactmechanics", True, True),
]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="64² only")
    ap.add_argument("--grids", type=int, nargs="+", default=[64, 128, 200])
    ap.add_argument("--limit", type=float, default=60.0, help="time limit of one sweep [s]")
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()
    grids = (64,) if args.quick else tuple(args.grids)
    print(f"machine: {machine()}")
    print(f"{N_PRESSURES} pressures per sweep (warm-started); ΔA/A: max change of A_c from tol 1e-8 to 1e-6\n")
    print(HEADER)
    t0 = time.perf_counter()
    rows = run(grids, args.limit, CONFIGS)
    print(f"\ntotal {time.perf_counter() - t0:.0f} s")
    if args.json:
        args.json.write_text(json.dumps({"machine": machine(), "rows": [asdict(r) for r in rows]}, indent=1))


if __name__ == "__main__":
    main()

"""``stochfric contact-models SCAN... --material M (--pressures-mpa SPEC | --machine FILE) --out DIR``: μ of the user's
surface by every contact model at the pressures asked for, with the model spread (issue 31; library:
:func:`stochfric.process.contact_models.contact_model_spread`).  Parse, call, print; no physics.

Exit 0 with the table; 2 for bad input (one line ``error: …``).
"""

from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer

from stochfric.cli.options import GROUP, SEED_RULE, fail, option_group, write_failed
from stochfric.cli.surface import SurfaceOptions, surface_options
from stochfric.contact.materials import load_material, material_names
from stochfric.errors import AnalysisError, StochfricError
from stochfric.io_utils import check_output_path, json_ready
from stochfric.process.contact_models import ALL_MODELS, STATISTICAL_CONTACT_MODELS
from stochfric.surface.surrogates import AUTO_SURROGATE
from stochfric.units import MEGAPASCAL

__all__ = ["contact_models_command", "parse_pressures_mpa", "register"]

#: Most pressures of one run (each costs one boundary-element solve per sample and model).
MAX_PRESSURES = 40


def parse_pressures_mpa(spec: str) -> np.ndarray:
    """``"START:STOP:NUM"`` (log-spaced) or ``"P1,P2,..."`` in MPa → pressures in Pa."""
    what = f"--pressures-mpa must be START:STOP:NUM (log-spaced) or P1,P2,... in MPa, got {spec!r}"
    try:
        parts = spec.split(":")
        if len(parts) == 3:
            start, stop, num = float(parts[0]), float(parts[1]), int(parts[2])
        elif len(parts) == 1:
            listed = [float(v) for v in spec.split(",") if v.strip()]
        else:
            raise AnalysisError(what)
    except ValueError:
        raise AnalysisError(what) from None
    if len(parts) == 3:
        if not (math.isfinite(start) and math.isfinite(stop)) or start <= 0 or stop < start or num < 1:
            raise AnalysisError(f"--pressures-mpa needs 0 < START <= STOP and NUM >= 1, got {spec!r}")
        values = np.geomspace(start, stop, num)
    else:
        values = np.array(listed)
    if values.size == 0 or not np.all(np.isfinite(values)) or np.any(values <= 0):
        raise AnalysisError(f"--pressures-mpa needs pressures > 0 MPa, got {spec!r}")
    if values.size > MAX_PRESSURES:
        raise AnalysisError(f"--pressures-mpa asks for {values.size} pressures; at most {MAX_PRESSURES}")
    return np.unique(values) * MEGAPASCAL


@option_group("surf", surface_options)
def contact_models_command(
    files: Annotated[list[Path] | None, typer.Argument(
        help="Height map(s) of one surface (several: pooled scans). Default: the shipped surface.",
        show_default=False)] = None,
    material: Annotated[str, typer.Option("--material", help=f"Pairing: {', '.join(material_names())} or a JSON "
                                                             "file (SI units).")] = "brake-pad",
    pressures_mpa: Annotated[str | None, typer.Option(
        "--pressures-mpa", help="Nominal pressures: START:STOP:NUM (log-spaced) or P1,P2,... in MPa.")] = None,
    machine: Annotated[str | None, typer.Option(
        "--machine", help="Instead of --pressures-mpa: the pressures N/A_nom over this machine's normal-force "
                          "range (a TOML file or a shipped name, docs/machines.md).")] = None,
    pressure_points: Annotated[int, typer.Option("--pressure-points", min=2, max=MAX_PRESSURES,
                                                 help="Pressures over the machine's range (with --machine).")] = 6,
    models: Annotated[str, typer.Option(
        "--models", help=f"{ALL_MODELS} or a comma-separated list of {', '.join(STATISTICAL_CONTACT_MODELS)}.")
    ] = ALL_MODELS,
    realizations: Annotated[int, typer.Option("--realizations", min=2, help="Surrogates of original size (the "
                                                                            "analysis's first R).")] = 40,
    surrogate: Annotated[str, typer.Option("--surrogate", help="auto or a surrogate method (friction-process "
                                                               "--help).")] = AUTO_SURROGATE,
    path_surfaces: Annotated[int, typer.Option(
        "--path-surfaces", min=0, help="Long surfaces for the path spectrum per model at the lowest, middle and "
                                       "highest pressure (0: none; each costs a solve per window).")] = 2,
    bem_solver: Annotated[str, typer.Option("--bem-solver", help="auto (Tamaas elastic, ContactMechanics with the "
                                                                 "cap: the faster each), tamaas or "
                                                                 "contactmechanics.")] = "auto",
    tolerance: Annotated[float, typer.Option("--tolerance", help="Relative tolerance of every boundary-element "
                                                                 "solve.")] = 1e-8,
    max_iterations: Annotated[int, typer.Option("--max-iterations", min=1, help="Iteration limit of one "
                                                                                "boundary-element solve.")] = 5000,
    time_limit_s: Annotated[float, typer.Option("--time-limit-s", help="Time limit of one sample's solves [s].")
                            ] = 600.0,
    persson_corrected: Annotated[bool, typer.Option(
        "--persson-corrected", help="Persson with the small-load slope κ = 2 of exact solutions instead of "
                                    "√(8/π) (docs/persson.md).")] = False,
    bem_pixel_area: Annotated[bool, typer.Option(
        "--bem-pixel-area", help="Boundary-element area as the count of contact pixels, without the perimeter "
                                 "correction of Yastrebov et al. 2017 (docs/bem_validation.md §4).")] = False,
    seed: Annotated[int, typer.Option("--seed", min=0, help=SEED_RULE)] = 0,
    workers: Annotated[int | None, typer.Option("--workers", min=1, help="Processes (default: all cores); the "
                                                                         "numbers do not depend on it.")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Directory for contact_models.json, the per-sample "
                                                           "NetCDF and contact_models.png.")] = None,
    surf: SurfaceOptions = GROUP,
    as_json: Annotated[bool, typer.Option("--json", help="Print the summary as JSON.")] = False,
) -> None:
    """Which contact model, and how much it matters: μ = τ_max A_c/N of the measured windows and the surrogates
    by GW, the elastic and elastic-plastic boundary-element solution and Persson's theory at the given
    pressures (load control), with the envelope and the split of the uncertainty (docs/contact_models.md)."""
    from stochfric.process.analysis_config import AnalysisConfig
    from stochfric.process.contact_models import LoadControl, contact_model_spread
    from stochfric.process.pipeline import write_spread
    from stochfric.surface.scans import load_scan, pool_scans

    try:
        if (pressures_mpa is None) == (machine is None):
            raise AnalysisError("give the pressures: --pressures-mpa START:STOP:NUM or --machine FILE (one of them)")
        if out is not None:
            check_output_path(out, option="--out")
        mat = load_material(material)
        if machine is not None:
            from stochfric.oscillator.machine import load_machine

            lo, hi = load_machine(machine).pressure_range_pa
            pressures = np.geomspace(lo, hi, pressure_points)
        else:
            assert pressures_mpa is not None
            pressures = parse_pressures_mpa(pressures_mpa)
        control = LoadControl(bem_solver=bem_solver, tolerance=tolerance, max_iterations=max_iterations,
                              time_limit_s=time_limit_s, persson_corrected=persson_corrected,
                              bem_area="pixels" if bem_pixel_area else "corrected")
        cfg = AnalysisConfig(realizations=realizations, surrogate=surrogate, summit_rule=surf.summit_rule, seed=seed)
        paths: list[Path | None] = list(files) if files else [None]
        pooled = pool_scans([load_scan(p, preparation=surf.preparation(), summit_rule=cfg.summit_rule,
                                       physical_size_m=surf.physical_size_m(), height_unit=surf.height_unit,
                                       fill_undefined=surf.fill_undefined) for p in paths])
        with _progress(show=not as_json) as progress:
            spread = contact_model_spread(list(pooled.surfaces), mat, pressures, models, cfg, control=control,
                                          path_surfaces=path_surfaces, workers=workers, progress=progress)
        payload = spread.to_dict()
        payload["preparation"] = pooled.record()
        if out is not None:
            payload["files"] = write_spread(spread, out)
    except (StochfricError, ValueError) as exc:
        raise fail(str(exc)) from None
    except OSError as exc:
        raise write_failed(exc) from None
    if as_json:
        typer.echo(json.dumps(json_ready(payload), indent=2))
        return
    _print(payload)


def _progress(*, show: bool) -> Any:
    from stochfric.cli.process import _progress as bars

    return bars(show=show)


def _print(d: dict[str, Any]) -> None:
    """The table: E[μ] per model and pressure, the ratio GW/BEM, the uncertainty split, the recommendation."""
    models = d["models"]
    p = d["pressure_pa"]
    typer.echo(f"surface: {d['surface']['source']} ({d['surface']['grid'][0]}×{d['surface']['grid'][1]} points), "
               f"material {d['material'].get('name', '?')}, {d['realizations']} surrogates ({d['surrogate_method']})"
               + (f", {d['measured_windows']['windows']} measured windows" if d["measured_windows"] else ""))
    typer.echo(f"plasticity index {_f(d['plasticity_index'], '.3g')}: {d['recommendation']}")
    head = f"{'p [MPa]':>9} " + " ".join(f"{'E[mu] ' + m:>17}" for m in models)
    extra = "  gw/bem" if d["ratio_gw_to_bem"] is not None else ""
    typer.echo(head + extra + "  +-sampling  +-model")
    unc = d["uncertainty"]
    for k, pk in enumerate(p):
        row = f"{pk / MEGAPASCAL:9.4g} "
        for m in models:
            s = d["per_model"][m]["surrogates"]
            row += f" {_f(s['mu_mean'][k], '.3f')} ± {_f(1.96 * (s['mu_mean_se'][k] or math.nan), '.3f'):>5}    "
        if d["ratio_gw_to_bem"] is not None:
            row += f"  {_f(d['ratio_gw_to_bem'][k], '.3f')}"
        row += f"  {_f(unc['sampling_half_width'][k], '.3f'):>9}  {_f(unc['model_half_width'][k], '.3f'):>7}"
        typer.echo(row)
    typer.echo(f"sampling: {unc['sampling_source']}; model: half the range of E[mu] over {', '.join(models)}")
    disc = unc.get("discretisation_half_width")
    if disc:
        cells = ", ".join(_f(v, ".3g") for v in disc)
        typer.echo(f"grid: half the difference of the boundary-element E[mu] between the perimeter-corrected area "
                   f"and the pixel count, per pressure: {cells} (docs/bem_validation.md §4)")
    for m in models:
        solver = d["per_model"][m]["solver"]
        if m.startswith("bem"):
            typer.echo(f"{m}: {' / '.join(solver['used'])}, at most {solver['max_iterations_used']} iterations "
                       f"(limit {d['load_control']['max_iterations']}), {solver['seconds_total']:.1f} s in all, "
                       f"slowest sample {solver['seconds_per_sample_max']:.2f} s (limit "
                       f"{d['load_control']['time_limit_s']:g} s)")
        for w in solver["warnings"]:
            typer.echo(f"warning ({m}): {w}", err=True)
    for m, path in d.get("path", {}).items():
        per = path.get("by_pressure") or [path]
        cells = ", ".join(f"{_f(None if q['correlation_length_m'] is None else q['correlation_length_m'] * 1e6, '.3g')}"
                          f" µm at {q['pressure_pa'] / MEGAPASCAL:.3g} MPa" for q in per)
        typer.echo(f"path ({m}, {path['long_surfaces']} long surfaces): integral correlation length {cells}")
    for n in d["notes"]:
        typer.echo(f"note: {n}", err=True)
    for key, value in d.get("files", {}).items():
        typer.echo(f"{key}: {value}")


def _f(v: Any, fmt: str) -> str:
    return "n/a" if v is None or not math.isfinite(float(v)) else format(float(v), fmt)


def register(app: typer.Typer) -> None:
    """Add ``contact-models`` to ``app``."""
    app.command("contact-models")(contact_models_command)

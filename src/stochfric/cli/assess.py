"""``stochfric assess SCAN... --material M --machine FILE --out DIR``: the user's surface on the user's machine
(issue 30, item 2; library: :func:`stochfric.studies.assess.assess`).  Parse, call, print; no physics.

Exit 0 with a verdict; 3 when the surface analysis is not credible or does not cover the machine's pressures
(no study runs unless ``--accept-not-credible``); 2 for bad input.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Annotated

import typer
from rich.console import Console
from rich.markup import escape

from stochfric.cli.options import GROUP, SEED_RULE, fail, option_group, write_failed
from stochfric.cli.surface import SurfaceOptions, surface_options
from stochfric.contact.materials import material_names
from stochfric.errors import StochfricError
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.credibility import NOT_CREDIBLE_EXIT


@option_group("surf", surface_options)
def assess_command(
    files: Annotated[list[Path], typer.Argument(help="Height map(s) of the user's surface (several: scans of one "
                                                     "surface, pooled).", show_default=False)],
    material: Annotated[str, typer.Option("--material", help=f"Pairing: {', '.join(material_names())} or a JSON "
                                                             "file (SI units).")],
    machine: Annotated[str, typer.Option("--machine", help="Machine description: a TOML file (docs/machines.md) "
                                                           "or a shipped name (brake, sheet, example-calliper).")],
    out: Annotated[Path, typer.Option("--out", help="Output directory: assess.json, report.html, the analysis "
                                                    "and the studies.")],
    runs: Annotated[int, typer.Option("--runs", min=1, help="Monte Carlo runs per grid cell before refinement.")] = 10,
    run_budget: Annotated[int, typer.Option("--run-budget", min=1, help="Most runs the adaptive refinement of "
                                                                        "D_max(α) adds in all.")] = 20_000,
    no_refine: Annotated[bool, typer.Option("--no-refine", help="Fixed runs (the thesis's mode): D_max(α) "
                                                                "intervals may stay open.")] = False,
    risk_level: Annotated[float, typer.Option("--risk-level", help="α of D_max(α) and of the verdict.")] = 0.1,
    forces: Annotated[int, typer.Option("--forces", min=1, help="Normal forces over the machine's range "
                                                                "(log-spaced, plus its default force).")] = 5,
    damping_points: Annotated[int, typer.Option("--damping-points", min=2, help="D grid over the machine's "
                                                                                "damping range.")] = 21,
    realizations: Annotated[int, typer.Option("--realizations", min=4, help="Surrogates of the analysis.")] = 100,
    tau_end: Annotated[float | None, typer.Option("--tau-end", help="Simulated time τ_end (default: the "
                                                                    "machine's).")] = None,
    seed: Annotated[int, typer.Option("--seed", min=0, help=SEED_RULE)] = 0,
    workers: Annotated[int | None, typer.Option("--workers", min=1, help="Processes (default: all cores).")] = None,
    accept_not_credible: Annotated[bool, typer.Option(
        "--accept-not-credible", help="Run the studies on a surface model that is not credible (every output "
                                      "then says so).")] = False,
    allow_extrapolation: Annotated[bool, typer.Option(
        "--allow-extrapolation", help="Use the model outside its fitted pressures (stamped).")] = False,
    no_normal_force_study: Annotated[bool, typer.Option("--no-normal-force-study",
                                                        help="Skip the normal-force study.")] = False,
    contact_model: Annotated[str, typer.Option(
        "--contact-model", help="The contact model whose E[μ](p), σ_μ(p) the studies read: gw (the thesis), bem, "
                                "bem-plastic, persson; or all (GW, with every model's spread reported; "
                                "docs/contact_models.md).")] = "gw",
    surf: SurfaceOptions = GROUP,
    as_json: Annotated[bool, typer.Option("--json", help="Print assess.json instead of the first screen.")] = False,
) -> None:
    """Will this machine stick-slip with this surface? Surface analysis at the machine's pressures, the
    friction-process model, the damping and normal-force studies, one verdict per force (docs/assess.md)."""
    from stochfric.studies.assess import AssessSettings, assess

    err = Console(stderr=True)
    try:
        settings = AssessSettings(
            runs=runs, refine=not no_refine, run_budget=run_budget, risk_level=risk_level, seed=seed,
            forces=forces, damping_points=damping_points, tau_end=tau_end, workers=workers,
            analysis=AnalysisConfig(realizations=realizations, seed=seed, summit_rule=surf.summit_rule),
            accept_not_credible=accept_not_credible, allow_extrapolation=allow_extrapolation,
            contact_model=contact_model,
            normal_force_study=not no_normal_force_study)
        result = assess(files, material, machine, out=out, settings=settings,
                        progress=None if as_json else (lambda s: err.print(f"[dim]{escape(s)}[/]")),
                        preparation=surf.preparation(), physical_size_m=surf.physical_size_m(),
                        height_unit=surf.height_unit, fill_undefined=surf.fill_undefined)
    except (StochfricError, ValueError) as exc:
        raise fail(str(exc)) from None
    except OSError as exc:
        raise write_failed(exc) from None
    if as_json:
        typer.echo(json.dumps(result.to_json_dict(), default=str))
    else:
        for line in result.first_screen():
            typer.echo(line)
        typer.echo(f"wrote {result.files['report']} and {result.files['json']}")
    if result.exit_code:
        raise typer.Exit(NOT_CREDIBLE_EXIT)


def register(app: typer.Typer) -> None:
    """Add the ``assess`` command to ``app``."""
    app.command("assess")(assess_command)

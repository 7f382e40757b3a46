"""``stochfric study white-limit``: σ(X_gh) of the contact model as the process's correlation length
ℓ → 0 at a fixed low-frequency level (:mod:`stochfric.studies.white_limit`).  Parse, call,
print; no physics.  Input errors end with a one-line message and exit code 2.
"""

from __future__ import annotations

import json
import math
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer

from ..io_utils import OutputPathError, check_output_path
from ..oscillator.options import PathCoordinate
from ..oscillator.presets import PresetName
from ..studies.white_limit import (
    PATH_COORDINATES,
    WhiteLimitConfig,
    WhiteLimitSummary,
    white_limit_figure,
    white_limit_study,
)
from .options import SEED_RULE, fail

__all__ = ["white_limit_command"]

#: The study's path coordinates (:data:`~stochfric.studies.white_limit.PATH_COORDINATES`) as a typer choice.
WhitePathChoice = StrEnum("WhitePathChoice", [(p.name, p.value) for p in PATH_COORDINATES])  # type: ignore[misc]
#: The config's default path coordinate as that choice.
DEFAULT_PATH = WhitePathChoice(WhiteLimitConfig.path_coordinate)


def _lengths(spec: str) -> tuple[float, ...]:
    out = []
    for part in spec.split(","):
        text = part.strip()
        if not text:
            continue
        try:
            value = float(text)
        except ValueError:
            raise fail(f"--lengths: {text!r} is not a number; give correlation lengths in m, e.g. "
                       "1e-3,1e-4,1e-5,1e-6") from None
        if not (math.isfinite(value) and value > 0.0):
            raise fail(f"--lengths: correlation lengths must be positive numbers [m], got {text!r}")
        out.append(value)
    if len(out) < 2:
        raise fail("--lengths: give at least two correlation lengths [m], e.g. 1e-3,1e-4,1e-5,1e-6")
    return tuple(out)


def white_limit_command(
    preset: Annotated[PresetName, typer.Option("--preset", help="Thesis case: brake | sheet.")] = PresetName.BRAKE,
    normal_force: Annotated[float | None, typer.Option(
        "--normal-force", help="N [N] (default: the preset's middle normal-force study force, brake 2720, sheet 880).")
    ] = None,
    lengths: Annotated[str, typer.Option(
        "--lengths", help="Correlation lengths ℓ [m], comma-separated (integral scale S0/(4σ²)).")
    ] = "1e-3,1e-4,1e-5,1e-6",
    runs: Annotated[int, typer.Option("--runs", help="Monte Carlo runs per ℓ and time step.")] = 300,
    seed: Annotated[int, typer.Option("--seed", min=0, help=SEED_RULE)] = 19,
    damping_ratio: Annotated[float, typer.Option("--damping-ratio", help="D (default 5e-6).")] = 5e-6,
    path_coordinate: Annotated[WhitePathChoice, typer.Option(
        "--path-coordinate", help="Where the process is read: relative (sliding distance, as the white model) "
                                  "| mass (the thesis's |Δx1|).")] = DEFAULT_PATH,
    tau_end: Annotated[float | None, typer.Option("--tau-end", help="τ_end (default: preset, 50).")] = None,
    process_length: Annotated[float | None, typer.Option(
        "--process-length", help="Least process length [m] (default 2 γ0 τ_end; doubled if a run's path exceeds it).")
    ] = None,
    steps_per_cell: Annotated[float, typer.Option(
        "--steps-per-cell", help="Δτ = min(dt-max, Δx/(k·2γ0)): at least k steps per grid spacing.")] = 4.0,
    dt_max: Annotated[float, typer.Option("--dt-max", help="Largest Δτ.")] = 0.001,
    refine: Annotated[int, typer.Option("--refine", help="Also run at Δτ/refine (same realisations).")] = 4,
    level_factor: Annotated[float, typer.Option(
        "--level-factor", help="S0 = factor × the preset's low-frequency PSD level (default 1).")] = 1.0,
    fit_min_length: Annotated[float | None, typer.Option(
        "--fit-min-length", help="Fit σ(X_gh) ∝ ℓ^β over ℓ >= this [m] only (default: all ℓ).")] = None,
    workers: Annotated[int | None, typer.Option("--workers", help="Threads (default: all cores).")] = None,
    out: Annotated[Path | None, typer.Option("--out", help="Write white_limit_<preset>.json/.nc here.")] = None,
    plot: Annotated[bool, typer.Option("--plot", help="Also write white_limit_<preset>.png into --out.")] = False,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
) -> None:
    """σ(X_gh), E[X_gh] of the contact model over the correlation length ℓ at fixed S0 (is white noise its limit?)."""
    ells = _lengths(lengths)
    if plot and out is None:
        raise fail("--plot writes the figure into --out DIR: give --out")
    if out is not None:
        try:
            check_output_path(out, option="--out")
        except OutputPathError as exc:
            raise fail(str(exc)) from None
    if workers is not None and workers < 1:
        raise fail(f"--workers must be >= 1, got {workers}")
    try:
        cfg = WhiteLimitConfig(
            preset=preset.value, normal_force=normal_force, correlation_lengths=ells, runs=runs, seed=seed,
            damping_ratio=damping_ratio, tau_end=tau_end, path_coordinate=PathCoordinate(path_coordinate),
            process_length=process_length, steps_per_cell=steps_per_cell, dt_max=dt_max, refine=refine,
            level_factor=level_factor, fit_min_length=fit_min_length, workers=workers,
        )
        progress = None if json_out else (lambda msg: typer.echo(msg, err=True))
        result = white_limit_study(cfg, progress=progress)
        files: dict[str, Any] = {}
        if out is not None:
            files = {k: str(v) for k, v in result.save(out).items()}
            if plot:
                files["figure"] = str(white_limit_figure([result], out / f"white_limit_{cfg.preset}.png"))
    except ValueError as exc:  # CaseError / ParameterError are ValueErrors
        raise fail(str(exc)) from None
    s = result.summary
    if json_out:
        typer.echo(json.dumps({**s.to_json(), "files": files}, allow_nan=True))
        return
    _print(s)
    for kind, path in files.items():
        typer.echo(f"wrote     {path} ({kind})")


def _print(s: WhiteLimitSummary) -> None:
    typer.echo(f"white-limit {s.preset} N = {s.normal_force_n:g} N, D = {s.damping_ratio:g}, "
               f"S0 = {s.low_frequency_psd_m:.3g} m (one-sided), path {s.config.path_coordinate}, "
               f"{s.config.runs} runs, seed {s.seed}; preset ℓ0 = {s.preset_correlation_length_m:.3g} m")
    r = s.config.refine
    typer.echo(f"{'ℓ [m]':>8} {'σ_μ':>6} {'Δτ':>8} {'E[X_gh]':>18} {'σ(X_gh) at Δτ':>18} "
               f"{f'σ(X_gh) at Δτ/{r}':>18} {'Δσ/SE':>6} {'events':>6} {'no-stick':>8}")
    for row in s.table:
        c, f = row.coarse, row.fine
        typer.echo(
            f"{row.correlation_length_m:8.2g} {row.sigma_mu:6.3g} {c.dt:8.2g} "
            f"{f.x_gh_mean:9.3e} ± {f.x_gh_mean_se:6.1e} {c.x_gh_std:9.3e} ± {c.x_gh_std_se:6.1e} "
            f"{f.x_gh_std:9.3e} ± {f.x_gh_std_se:6.1e} {row.std_difference_over_se:6.2f} {f.n_events:6d} "
            f"{f.passes_without_stick_per_run:8.3g}"
        )
    fit = s.fit
    if fit.beta is not None and fit.local_slopes is not None:
        typer.echo(f"fit σ(X_gh) ∝ ℓ^β over ℓ = {min(fit.lengths_m):.2g} … {max(fit.lengths_m):.2g} m: "
                   f"β = {fit.beta:.3f} ± {fit.beta_se_reported:.3f} "
                   f"(χ²/dof = {fit.chi2:.1f}/{fit.dof}); local slopes "
                   + ", ".join(f"{v.slope:.2f}±{v.slope_se:.2f}" for v in fit.local_slopes))
    typer.echo(f"verdict   {s.verdict}")
    typer.echo(f"time      {s.elapsed_s:.1f} s")

"""Command ``simulate``: the friction oscillator (method §5).  Parse, call, print; no physics here.

Errors in the input end with a one-line message and exit code 2, never with a traceback.
"""

from __future__ import annotations

import json
import math
import os
import sys
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn
from rich.table import Table

from ..friction_process.presets import ProcessLevel
from ..io_utils import check_output_path, require_memory, write_netcdf_atomic, write_text_atomic
from ..oscillator import (
    Case,
    CaseError,
    DimensionlessInput,
    ExecutionOptions,
    FrictionInput,
    IntegrationOptions,
    Integrator,
    Model,
    NoiseOptions,
    OutputOptions,
    ParameterError,
    PathCoordinate,
    PhysicalInput,
    PresetName,
    SimulationResult,
    WhiteIntensity,
    WhiteStream,
    build_case,
    integrate,
)
from ..oscillator.figures import plot_phase_portrait
from ..oscillator.options import default_integrator
from .options import GROUP, SEED_RULE, LawChoice, fail, in_flags, option_group, write_failed

err_console = Console(stderr=True)


PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def _simulation_memory_bytes(runs: int, tau_end: float, dt: float, *, save_every: int, trajectories: bool,
                             model: str, process_points: int, workers: int | None) -> float:
    """Bytes that ``simulate`` allocates for one parameter set: X_gh/t_gh (2·(2τ_end + 16) per run),
    the stored trajectories (3 components every ``save_every`` steps, doubled for the NetCDF copy), and
    per worker a batch of 256 white-noise increments or process realisations (``process_points`` per run:
    the segments a contact run starts with)."""
    nsteps = math.ceil(tau_end / dt)
    events = int(2 * tau_end) + 16
    per_run = 8 * (2 * events + 1 + 9) + (2 * 24 * (nsteps // save_every + 1) if trajectories else 0)
    batch = min(runs, 256 * (workers or os.cpu_count() or 1)) * 8 * (
        (nsteps if model == Model.WHITE else 0) + (process_points if model == Model.CONTACT else 0))
    return float(runs) * per_run + batch


#: Most time steps of one run (τ_end/Δτ): 10¹¹ steps take about 10 minutes per run at the measured
#: 5 ns per step (docs/performance.md); more is a typing slip, not a study.
MAX_STEPS_PER_RUN = 1e11
#: Measured cost of one Euler step of one run [s] (white noise, one core; docs/performance.md).
SECONDS_PER_STEP = 5e-9


def _check_step_count(tau_end: float, dt: float, runs: int) -> None:
    """Refuse, before any work, a non-finite τ_end or Δτ and a step count no run could finish."""
    for flag, v in (("--tau-end", tau_end), ("--dt", dt)):
        if not (math.isfinite(v) and v > 0):
            raise ParameterError(f"{flag} must be a finite number > 0, got {v!r}")
    steps = tau_end / dt
    if not steps <= MAX_STEPS_PER_RUN:
        hours = steps * max(runs, 1) * SECONDS_PER_STEP / 3600.0
        raise ParameterError(
            f"--tau-end {tau_end:g} / --dt {dt:g} = {steps:.3g} steps per run (limit {MAX_STEPS_PER_RUN:.0e}); "
            f"{runs} run(s) would take about {hours:.3g} h at {SECONDS_PER_STEP * 1e9:g} ns per step: use a larger "
            "--dt or a shorter --tau-end"
        )


def _progress_bar(enabled: bool) -> Progress | None:
    """A progress bar of the runs on stderr (removed when done), or ``None`` when not ``enabled``."""
    if not enabled:
        return None
    prog = Progress(
        TextColumn("[progress.description]{task.description}"), BarColumn(),
        TextColumn("{task.completed}/{task.total}"), TimeRemainingColumn(),
        console=err_console, transient=True,
    )
    return prog


def physical_options(
    normal_force: Annotated[
        float | None, typer.Option(help="Normal force N [newtons] (needs stiffness).")
    ] = None,
    damping_coefficient: Annotated[
        float | None, typer.Option(help="Damper constant d_k [N s/m].")
    ] = None,
    forcing_amplitude: Annotated[
        float | None, typer.Option(help="Forcing amplitude Q [newtons].")
    ] = None,
    mass: Annotated[float | None, typer.Option(help="Mass m [kg].")] = None,
    stiffness: Annotated[float | None, typer.Option(help="Stiffness c [N/m].")] = None,
    belt_speed: Annotated[float | None, typer.Option(help="Belt speed v0 [m/s].")] = None,
    contact_area: Annotated[
        float | None, typer.Option(help="Nominal contact area A [m²] for p = N/A.")
    ] = None,
) -> PhysicalInput:
    """The SI options of ``simulate`` (thesis eq. 4.5), as given (``None``: the preset's or not given)."""
    return PhysicalInput(mass=mass, stiffness=stiffness, belt_speed=belt_speed, contact_area=contact_area,
                         normal_force=normal_force, damping_coefficient=damping_coefficient,
                         forcing_amplitude=forcing_amplitude)


def dimensionless_options(
    damping_ratio: Annotated[float | None, typer.Option(help="Damping ratio D [-].")] = None,
    gamma0: Annotated[float | None, typer.Option(help="Dimensionless belt speed γ0.")] = None,
    n: Annotated[float | None, typer.Option("--n", help="Dimensionless normal force N/(cL).")] = None,
    q: Annotated[float | None, typer.Option("--q", help="Dimensionless forcing Q/(cL).")] = None,
    eta: Annotated[float | None, typer.Option(help="Forcing frequency ratio η = Ω/ω0 [-].")] = None,
    omega0: Annotated[
        float | None, typer.Option(help="ω0 [rad/s] for dimensionless input (default 1).")
    ] = None,
) -> DimensionlessInput:
    """The dimensionless options of ``simulate`` (eq. 4.6/4.7), as given (``None``: not given)."""
    return DimensionlessInput(gamma0=gamma0, n=n, damping_ratio=damping_ratio, q=q, eta=eta, omega0=omega0)


@option_group("dimensionless", dimensionless_options)
@option_group("physical", physical_options)
def simulate(
    preset: Annotated[
        PresetName | None,
        typer.Option(help="Thesis case: oscillator, contact area, friction-process model."),
    ] = None,
    machine: Annotated[
        str | None,
        typer.Option(help="Machine description instead of --preset: a TOML file (docs/machines.md) or a shipped "
                          "name (brake, sheet, example-calliper); one that is not a thesis case needs --process."),
    ] = None,
    allow_extrapolation: Annotated[
        bool,
        typer.Option(help="Use the process model outside the pressures it was fitted on (the output is stamped) "
                          "instead of refusing."),
    ] = False,
    model: Annotated[Model, typer.Option(
        help="Friction model (method §5): deterministic = the friction law alone; white = phenomenological "
             "white noise in time, σ_ζ a free intensity that no surface measurement fixes (not the small-ℓ "
             "limit of the contact process, method §5.1a); contact = the measured surface's friction process.")] = (
        Model.DETERMINISTIC
    ),
    friction_law: Annotated[
        LawChoice | None,
        typer.Option(help="Table 4.1 law or the pressure law (4.13); default: pressure with a "
                     "preset or process model, III otherwise."),
    ] = None,
    mu0: Annotated[
        float,
        typer.Option("--mu0", help="Static coefficient μ0 of the pressure law (4.13) [-]; thesis 0.4. It must "
                     "exceed E[μ](p) of the process model (the drop to the kinetic value)."),
    ] = 0.4,
    physical: PhysicalInput = GROUP,
    dimensionless: DimensionlessInput = GROUP,
    x0: Annotated[
        tuple[float, float] | None,
        typer.Option(help="Initial state X1 X2 (default: sticking at (0, γ0))."),
    ] = None,
    tau_end: Annotated[float | None, typer.Option(help="End time τ_end (default 50).")] = None,
    dt: Annotated[float | None, typer.Option(help="Time step Δτ (default 0.005).")] = None,
    integrator: Annotated[Integrator | None, typer.Option(
        help="Integrator (default: accurate for a forced deterministic or contact run, where Euler at the "
             "thesis's Δτ locks into spurious cycles; euler otherwise, and for the white-noise SDE). euler is the "
             "thesis's reproduction mode.", show_default="auto")] = None,
    runs: Annotated[int, typer.Option(min=1, help="Monte Carlo runs.")] = 1,
    seed: Annotated[int, typer.Option(min=0, help=SEED_RULE)] = 0,
    sigma_zeta: Annotated[
        float | None, typer.Option(help="White-noise intensity σ_ζ (default: from the rule below).")
    ] = None,
    white_intensity: Annotated[
        WhiteIntensity | None,
        typer.Option(help="Rule for σ_ζ from the process model: sigma_mu (thesis, σ_ζ = σ_μ(p)) or "
                     "spectral_level (matches the process's low-frequency PSD level) or thesis (reproduction "
                     "mode: printed eq. 4.31, σ_ζ,eff = σ_μ(p)·Lω0·Δτ, depends on Δτ)."),
    ] = None,
    path_coordinate: Annotated[
        PathCoordinate, typer.Option(help="Where the contact process is read (method §7.7).")
    ] = PathCoordinate.MASS,
    white_stream: Annotated[
        WhiteStream,
        typer.Option(help="Normals of the white-noise model: philox-ziggurat (default, in the kernel), "
                     "philox-boxmuller (the same Philox stream by Box–Muller) or pcg64 (numpy's stream, "
                     "drawn into a buffer); same statistics, different realisations."),
    ] = WhiteStream.PHILOX_ZIGGURAT,
    process_level: Annotated[
        ProcessLevel | None,
        typer.Option(help="Variance of the contact process: sigma_mu (σ_μ(p)², default) or psd_level "
                     "(reproduction mode: from the thesis's E[S](p) fit; presets only)."),
    ] = None,
    process_file: Annotated[
        Path | None,
        typer.Option("--process", help="Friction-process model file (JSON, `stochfric "
                     "friction-process`); replaces the preset's model."),
    ] = None,
    process_length: Annotated[
        float | None, typer.Option(help="Length ℓ of one generated process segment [m] (a band-limited "
                                         "model's band starts at 1/ℓ); a run that slides further reads further, "
                                         "independent segments: the process never repeats.")
    ] = None,
    save_every: Annotated[int, typer.Option(min=1, help="Trajectory decimation.")] = 10,
    workers: Annotated[int | None, typer.Option(min=1, help="Threads (default: all).")] = None,
    out: Annotated[
        Path | None, typer.Option(help="Directory for simulation.nc (+ JSON summary).")
    ] = None,
    plot: Annotated[Path | None, typer.Option(help="Phase portrait file (.png/.pdf/.svg).")] = None,
    json_out: Annotated[bool, typer.Option("--json", help="Print one JSON object.")] = False,
) -> None:
    """Run the friction oscillator (deterministic, white-noise or contact-process friction)."""
    save_traj = plot is not None or out is not None
    try:
        _check_outputs(out, plot)
        if machine is not None and preset is not None:
            raise fail("give --preset or --machine, not both")
        case = build_case(
            machine if machine is not None else preset, model=model, tau_end=tau_end, dt=dt, physical=physical,
            dimensionless=dimensionless,
            friction=FrictionInput(friction_law=friction_law.value if friction_law else None, mu0=mu0,
                                   process_file=process_file, process_length=process_length,
                                   process_level=process_level, white_intensity=white_intensity,
                                   sigma_zeta=sigma_zeta, allow_extrapolation=allow_extrapolation),
        )
        if integrator is None:
            integrator = default_integrator(model, forced=case.params.q > 0.0)
        _check_resources(case, model, runs, save_every=save_every, trajectories=save_traj, workers=workers)
        result = _run_with_progress(
            case, model=model, x0=(float(x0[0]), float(x0[1])) if x0 else None, runs=runs, seed=seed,
            noise=NoiseOptions(path_coordinate=path_coordinate, white_stream=white_stream),
            integration=IntegrationOptions(integrator=integrator),
            output=OutputOptions(save_trajectory=save_traj, save_every=save_every),
            workers=workers, show_progress=not json_out)
    except CaseError as exc:
        raise fail(in_flags(str(exc))) from None
    except ValueError as exc:  # the package's input errors (stochfric.errors.InputError) are ValueErrors
        raise fail(str(exc)) from None
    summary = _write_outputs(result, case, model, out, plot)
    if json_out:
        typer.echo(json.dumps(summary))
        return
    _print_summary(result, summary, out, plot)


def _check_outputs(out: Path | None, plot: Path | None) -> None:
    """Refuse, before any work, an ``--out`` directory or ``--plot`` file that could not be written."""
    if out is not None:
        check_output_path(out, option="--out")
    if plot is not None:
        check_output_path(plot, option="--plot", kind="file", suffixes=PLOT_SUFFIXES)


def _check_resources(case: Case, model: Model, runs: int, *, save_every: int, trajectories: bool,
                     workers: int | None) -> None:
    """Refuse, before any work, a step count no run could finish (:func:`_check_step_count`) and a
    simulation that would not fit in memory (:func:`_simulation_memory_bytes`)."""
    te, step, process = case.tau_end, case.dt, case.process
    _check_step_count(te, step, runs)
    # a contact run holds the process for its whole path: first_segments of the model's length
    points = 0
    if process is not None:
        belt = case.params.gamma0 * te * case.params.length_scale / process.length
        points = round(process.length / process.dx) * integrate.first_segments(belt)
    need = _simulation_memory_bytes(
        runs, te, step, save_every=save_every, trajectories=trajectories, model=model,
        process_points=points, workers=workers)
    require_memory(need, what=f"simulate with --runs {runs} --tau-end {te:g} --dt {step:g}", advice=(
        "use fewer --runs or a shorter --tau-end (run several smaller jobs with different --seed)"
        + (", or a larger --save-every, or drop --out/--plot (no trajectories are kept without them)"
           if trajectories else "")))


def _run_with_progress(case: Case, *, model: Model, x0: tuple[float, float] | None, runs: int, seed: int | None,
                       noise: NoiseOptions, integration: IntegrationOptions, output: OutputOptions,
                       workers: int | None, show_progress: bool) -> SimulationResult:
    """:func:`stochfric.oscillator.integrate.simulate` of ``case``, with a progress bar on a terminal's
    stderr for 200 runs or more (``show_progress``)."""
    prog = _progress_bar(show_progress and runs >= 200 and sys.stderr.isatty())
    cb = None
    if prog is not None:
        prog.start()
        task = prog.add_task("trajectories", total=runs)

        def cb(done: int, total: int) -> None:
            prog.update(task, completed=done)

    try:
        return integrate.simulate(case, model=model, x0=x0, runs=runs, seed=seed, noise=noise,
                                  integration=integration, output=output,
                                  execution=ExecutionOptions(workers=workers, progress=cb))
    finally:
        if prog is not None:
            prog.stop()


def _write_outputs(result: SimulationResult, case: Case, model: Model, out: Path | None,
                   plot: Path | None) -> dict[str, Any]:
    """The JSON summary of ``result`` (with the preset and the case's modes), written with the NetCDF
    record into ``out`` and the phase portrait into ``plot`` where given."""
    summary = result.to_json_dict()
    summary["preset"] = case.preset.name if case.preset else None
    modes = case.modes(model)
    summary.update(modes)
    try:
        if out is not None:
            ds = result.to_dataset()
            ds.attrs.update(modes)
            write_netcdf_atomic(out / "simulation.nc", ds)
            write_text_atomic(out / "simulation.json", json.dumps(summary, indent=1))
        if plot is not None:
            plot_phase_portrait(result, plot)
    except OSError as exc:  # disk full, place removed meanwhile: the previous files stay intact
        raise write_failed(exc) from None
    return summary


def _print_summary(result: Any, summary: dict[str, Any], out: Path | None, plot: Path | None) -> None:
    con = Console()
    p = result.params[0]
    con.print(
        f"[bold]stochfric simulate[/] model={result.model} integrator={result.integrator} "
        f"law={summary['friction_law']['name']}"
        + (f" preset={summary['preset']}" if summary["preset"] else "")
    )
    line = f"γ0={p.gamma0:.5g} n={p.n:.5g} D={p.damping_ratio:.3g} q={p.q:.3g} η={p.eta:.3g}"
    if p.normal_force is not None:
        line += f"  N={p.normal_force:.6g} N"
    if p.pressure_pa is not None:
        line += f"  p={p.pressure_pa / 1e6:.4g} MPa"
    if result.model != Model.DETERMINISTIC:
        line += f"  σ_ζ={result.sigma_zeta[0]:.4g}" if result.model == Model.WHITE else ""
        if result.settings.get("white_increment") == "thesis":
            line += f" (thesis mode: σ_ζ,eff={result.settings['sigma_zeta_effective'][0]:.4g})"
    con.print(line + f"  τ_end={result.tau_end:g} Δτ={result.dt:g} runs={result.runs} "
              f"seed={result.seed_entropy}")
    xs = [v for row in summary["x_gh"] for v in row]
    table = Table(title="slip→stick transitions X_gh (dimensionless, x = y/L)")
    for col in ("runs", "M mean", "M min", "M max", "E[X_gh]", "σ(X_gh)", "VarK = |σ|/|E|"):
        table.add_column(col, justify="right")
    m = np.asarray(summary["stick_count"])
    if xs:
        mean = float(np.mean(xs))
        sd = float(np.std(xs, ddof=1)) if len(xs) > 1 else 0.0
        vk = f"{abs(sd) / abs(mean):.3g}" if mean != 0 else "—"
        table.add_row(str(result.runs), f"{m.mean():.3g}", str(m.min()), str(m.max()),
                      f"{mean:.6g}", f"{sd:.3g}", vk)
    else:
        table.add_row(str(result.runs), f"{m.mean():.3g}", str(m.min()), str(m.max()), "—", "—",
                      "—")
    con.print(table)
    for w in result.warnings:
        con.print(f"[yellow]warning[/] ({w.code}): {w.message}")
    if summary.get("extrapolation"):
        con.print(f"[bold red]{escape(summary['extrapolation'])}[/] (--allow-extrapolation)")
    if out is not None:
        con.print(f"wrote {out / 'simulation.nc'} and {out / 'simulation.json'}")
    if plot is not None:
        con.print(f"wrote {plot}")


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``."""
    app.command("simulate")(simulate)

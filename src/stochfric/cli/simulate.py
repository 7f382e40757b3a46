"""Command ``simulate``: the friction oscillator (method §5).  Parse, call, print; no physics here.

Errors in the input end with a one-line message and exit code 2, never with a traceback.
"""

from __future__ import annotations

import json
import math
import os
import sys
import warnings
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn
from rich.table import Table

err_console = Console(stderr=True)


class ModelChoice(StrEnum):
    deterministic = "deterministic"
    white = "white"
    contact = "contact"


class LawChoice(StrEnum):
    I = "I"
    II = "II"
    III = "III"
    pressure = "pressure"


class IntegratorChoice(StrEnum):
    euler = "euler"
    accurate = "accurate"
    milstein = "milstein"


class PresetChoice(StrEnum):
    brake = "brake"
    sheet = "sheet"


class WhiteIntensityChoice(StrEnum):
    sigma_mu = "sigma_mu"
    spectral_level = "spectral_level"
    thesis = "thesis"


class ProcessLevelChoice(StrEnum):
    sigma_mu = "sigma_mu"
    psd_level = "psd_level"


class PathChoice(StrEnum):
    mass = "mass"
    relative = "relative"
    position = "position"


def fail(message: str) -> typer.Exit:
    """Print ``message`` as a one-line error and return the exit to raise (code 2)."""
    err_console.print(f"[bold red]error:[/] {escape(message)}", soft_wrap=True, highlight=False)
    return typer.Exit(code=2)


def _build_parameters(
    preset: str | None,
    gamma0: float | None,
    n: float | None,
    normal_force: float | None,
    damping: float | None,
    q: float | None,
    eta: float | None,
    forcing_amplitude: float | None,
    mass: float | None,
    stiffness: float | None,
    belt_speed: float | None,
    damping_coefficient: float | None,
    contact_area: float | None,
    omega0: float | None,
) -> tuple[Any, Any]:
    """Turn the CLI options into OscillatorParameters (and the preset, if any)."""
    from dataclasses import replace

    from ..oscillator.parameters import OscillatorParameters, ParameterError, PhysicalParameters
    from ..process.presets import get_preset

    if q is not None and forcing_amplitude is not None:
        raise ParameterError("give the forcing as --forcing-amplitude Q [N] or --q, not both")
    if damping is not None and damping_coefficient is not None:
        raise ParameterError("give the damping as --damping D or --damping-coefficient, not both")
    if normal_force is not None and n is not None:
        raise ParameterError("give the normal force as --normal-force [N] or --n, not both")
    pre = get_preset(preset) if preset else None
    physical = pre is not None or any(v is not None for v in (mass, stiffness, belt_speed))
    if physical:
        if gamma0 is not None or omega0 is not None:
            raise ParameterError(
                "--gamma0/--omega0 are for dimensionless input; with a preset or physical "
                "parameters set --belt-speed, --mass, --stiffness instead"
            )
        m_ = mass if mass is not None else (pre.mass if pre else None)
        c_ = stiffness if stiffness is not None else (pre.stiffness if pre else None)
        v_ = belt_speed if belt_speed is not None else (pre.belt_speed if pre else None)
        a_ = contact_area if contact_area is not None else (pre.contact_area if pre else None)
        missing = [k for k, v in (("--mass", m_), ("--stiffness", c_), ("--belt-speed", v_))
                   if v is None]
        if missing:
            raise ParameterError(f"physical parameters need {', '.join(missing)} (or a --preset)")
        assert m_ is not None and c_ is not None and v_ is not None
        if n is not None:
            nf = n * c_
        elif normal_force is not None:
            nf = normal_force
        elif pre is not None:
            nf = pre.default_normal_force
        else:
            raise ParameterError("give the normal force --normal-force N [newtons] or --n")
        phys = PhysicalParameters(
            mass=m_, stiffness=c_, belt_speed=v_, normal_force=nf,
            damping_coefficient=damping_coefficient,
            damping_ratio=damping if damping is not None else (
                None if damping_coefficient is not None else (
                    pre.study_parameters.get("damping_undamped", 0.0) if pre else 0.0)),
            forcing_amplitude=(q * c_ if q is not None else (forcing_amplitude or 0.0)),
            contact_area=a_,
        )
        # η is a ratio: Ω = η ω0, with ω0 from the validated mass and stiffness
        phys = replace(phys, forcing_frequency=(eta or 0.0) * phys.omega0)
        return phys.to_dimensionless(), pre
    if normal_force is not None or forcing_amplitude is not None or damping_coefficient is not None:
        raise ParameterError(
            "--normal-force, --forcing-amplitude and --damping-coefficient are in SI units and "
            "need --mass/--stiffness/--belt-speed or a --preset; for dimensionless input use "
            "--n, --q, --damping"
        )
    if gamma0 is None or n is None:
        raise ParameterError(
            "give either --preset {brake,sheet}, physical parameters (--mass --stiffness "
            "--belt-speed --normal-force), or dimensionless --gamma0 and --n"
        )
    return OscillatorParameters(
        gamma0=gamma0, n=n, damping_ratio=damping or 0.0, q=q or 0.0, eta=eta or 0.0,
        omega0=omega0 if omega0 is not None else 1.0, contact_area=contact_area,
    ), None


PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def _simulation_memory_bytes(runs: int, tau_end: float, dt: float, *, save_every: int, trajectories: bool,
                             model: str, process_points: int, workers: int | None) -> float:
    """Bytes that ``simulate`` allocates for one parameter set: X_gh/t_gh (2·(2τ_end + 16) per run),
    the stored trajectories (3 components every ``save_every`` steps, doubled for the NetCDF copy), and
    per worker a batch of 256 white-noise increments or process realisations."""
    nsteps = math.ceil(tau_end / dt)
    events = int(2 * tau_end) + 16
    per_run = 8 * (2 * events + 1 + 9) + (2 * 24 * (nsteps // save_every + 1) if trajectories else 0)
    batch = 256 * (workers or os.cpu_count() or 1) * 8 * (
        (nsteps if model == "white" else 0) + (process_points if model == "contact" else 0))
    return float(runs) * per_run + batch


def _progress_bar(enabled: bool) -> tuple[Progress | None, Any]:
    if not enabled:
        return None, None
    prog = Progress(
        TextColumn("[progress.description]{task.description}"), BarColumn(),
        TextColumn("{task.completed}/{task.total}"), TimeRemainingColumn(),
        console=err_console, transient=True,
    )
    return prog, None


def simulate(
    preset: Annotated[
        PresetChoice | None,
        typer.Option(help="Thesis case: oscillator, contact area, friction-process model."),
    ] = None,
    model: Annotated[ModelChoice, typer.Option(help="Friction model (method §5).")] = (
        ModelChoice.deterministic
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
    normal_force: Annotated[
        float | None, typer.Option(help="Normal force N [newtons] (needs stiffness).")
    ] = None,
    damping: Annotated[float | None, typer.Option(help="Damping ratio D [-].")] = None,
    damping_coefficient: Annotated[
        float | None, typer.Option(help="Damper constant d_k [N s/m].")
    ] = None,
    forcing_amplitude: Annotated[
        float | None, typer.Option(help="Forcing amplitude Q [newtons].")
    ] = None,
    forcing_frequency: Annotated[
        float | None, typer.Option(help="Forcing frequency ratio η = Ω/ω0 [-].")
    ] = None,
    gamma0: Annotated[float | None, typer.Option(help="Dimensionless belt speed γ0.")] = None,
    n: Annotated[float | None, typer.Option("--n", help="Dimensionless normal force N/(cL).")] = None,
    q: Annotated[float | None, typer.Option("--q", help="Dimensionless forcing Q/(cL).")] = None,
    eta: Annotated[float | None, typer.Option(help="Forcing frequency ratio η (alias).")] = None,
    omega0: Annotated[
        float | None, typer.Option(help="ω0 [rad/s] for dimensionless input (default 1).")
    ] = None,
    mass: Annotated[float | None, typer.Option(help="Mass m [kg].")] = None,
    stiffness: Annotated[float | None, typer.Option(help="Stiffness c [N/m].")] = None,
    belt_speed: Annotated[float | None, typer.Option(help="Belt speed v0 [m/s].")] = None,
    contact_area: Annotated[
        float | None, typer.Option(help="Nominal contact area A [m²] for p = N/A.")
    ] = None,
    x0: Annotated[
        tuple[float, float] | None,
        typer.Option(help="Initial state X1 X2 (default: sticking at (0, γ0))."),
    ] = None,
    tau_end: Annotated[float | None, typer.Option(help="End time τ_end (default 50).")] = None,
    dt: Annotated[float | None, typer.Option(help="Time step Δτ (default 0.005).")] = None,
    integrator: Annotated[IntegratorChoice, typer.Option(help="Integrator.")] = (
        IntegratorChoice.euler
    ),
    runs: Annotated[int, typer.Option(min=1, help="Monte Carlo runs.")] = 1,
    seed: Annotated[int | None, typer.Option(min=0, help="Root seed (recorded).")] = None,
    sigma_zeta: Annotated[
        float | None, typer.Option(help="White-noise intensity σ_ζ (default: from the rule below).")
    ] = None,
    white_intensity: Annotated[
        WhiteIntensityChoice | None,
        typer.Option(help="Rule for σ_ζ from the process model: sigma_mu (thesis, σ_ζ = σ_μ(p)) or "
                     "spectral_level (matches the process's low-frequency PSD level) or thesis (reproduction "
                     "mode: printed eq. 4.31, σ_ζ,eff = σ_μ(p)·Lω0·Δτ, depends on Δτ)."),
    ] = None,
    path_coordinate: Annotated[
        PathChoice, typer.Option(help="Where the contact process is read (method §7.7).")
    ] = PathChoice.mass,
    process_level: Annotated[
        ProcessLevelChoice | None,
        typer.Option(help="Variance of the contact process: sigma_mu (σ_μ(p)², default) or psd_level "
                     "(reproduction mode: from the thesis's E[S](p) fit; presets only)."),
    ] = None,
    process_file: Annotated[
        Path | None,
        typer.Option("--process", help="Friction-process model file (JSON, `stochfric "
                     "friction-process`); replaces the preset's model."),
    ] = None,
    process_length: Annotated[
        float | None, typer.Option(help="Length of the generated process [m].")
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
    from dataclasses import replace

    from ..oscillator.friction_laws import get_law, pressure_law
    from ..oscillator.integrate import SimulationWarningCategory
    from ..oscillator.integrate import simulate as run_sim
    from ..oscillator.parameters import ParameterError

    try:
        from ..io_utils import check_output_path

        if out is not None:
            check_output_path(out, option="--out")
        if plot is not None:
            check_output_path(plot, option="--plot", kind="file", suffixes=PLOT_SUFFIXES)
        params, pre = _build_parameters(
            preset.value if preset else None, gamma0, n, normal_force, damping, q,
            forcing_frequency if forcing_frequency is not None else eta, forcing_amplitude,
            mass, stiffness, belt_speed, damping_coefficient, contact_area, omega0,
        )
        if forcing_frequency is not None and eta is not None and forcing_frequency != eta:
            raise ParameterError("--forcing-frequency and --eta are the same η; give one")
        process: Any = pre.process if pre is not None else None
        if process_file is not None:
            from ..process.model import load_process_model

            process = load_process_model(process_file)
        if white_intensity is not None:
            if process is None:
                raise ParameterError("--white-intensity needs a friction-process model (--preset or --process)")
            if sigma_zeta is not None:
                raise ParameterError("give either --sigma-zeta or --white-intensity, not both")
            rule = "sigma_mu" if white_intensity is WhiteIntensityChoice.thesis else white_intensity.value
            process = replace(process, sigma_zeta_rule=rule)
        if process is not None and process_length is not None:
            # keep the grid spanning whole periods: n = round(length/dx) points of dx = length/n
            npts = max(2, round(process_length / process.dx))
            process = replace(process, length=process_length, dx=process_length / npts)
        if process_level is ProcessLevelChoice.psd_level:
            if pre is None or process_file is not None:
                raise ParameterError("--process-level psd_level rescales a preset's process: use --preset, "
                                     "not --process")
            from ..process.presets import psd_level_process

            process = replace(psd_level_process(pre), base=process, sigma_zeta_rule=process.sigma_zeta_rule)
        # default: the pressure law (4.13) whenever a process model gives E[μ](p)
        law_name = friction_law.value if friction_law else (
            "pressure" if process is not None and params.pressure is not None else "III")
        if law_name == "pressure":
            if process is None or params.pressure is None:
                raise ParameterError(
                    "the pressure law (4.13) needs E[μ](p) from a friction-process model and the "
                    "pressure p = N/A: use --preset, or --process FILE with physical parameters and "
                    "--contact-area"
                )
            mu_fit = process.mean(params.pressure)
            if mu_fit > mu0:
                raise ParameterError(
                    f"the pressure law (4.13) needs E[μ](p) <= μ0, but the process model gives E[μ] = {mu_fit:.4g} "
                    f"at p = {params.pressure / 1e6:.4g} MPa and μ0 = {mu0:g}: the kinetic friction would turn "
                    f"negative at high sliding speed; give a larger static coefficient (--mu0 {mu_fit + 0.2:.2g} or "
                    "more) or another law (--friction-law III)"
                )
            law = pressure_law(mu_fit, mu0=mu0)
        else:
            law = get_law(law_name)
        if model is not ModelChoice.deterministic and process is None and not (
            model is ModelChoice.white and sigma_zeta is not None
        ):
            raise ParameterError(
                f"the {model.value} model needs a friction-process model: use --preset or --process FILE"
                + (" or --sigma-zeta" if model is ModelChoice.white else "")
            )
        te = tau_end if tau_end is not None else (pre.tau_end if pre else 50.0)
        step = dt if dt is not None else (pre.dt if pre else 0.005)
        if te > 0 and step > 0:
            from ..io_utils import require_memory

            save_traj = plot is not None or out is not None
            need = _simulation_memory_bytes(
                runs, te, step, save_every=save_every, trajectories=save_traj, model=model.value,
                process_points=round(process.length / process.dx) if process is not None else 0, workers=workers)
            require_memory(need, what=f"simulate with --runs {runs} --tau-end {te:g} --dt {step:g}", advice=(
                "use fewer --runs or a shorter --tau-end (run several smaller jobs with different --seed)"
                + (", or a larger --save-every, or drop --out/--plot (no trajectories are kept without them)"
                   if save_traj else "")))
        prog, _ = _progress_bar(not json_out and runs >= 200 and sys.stderr.isatty())
        task = None
        cb = None
        if prog is not None:
            prog.start()
            task = prog.add_task("trajectories", total=runs)

            def cb(done: int, total: int) -> None:
                prog.update(task, completed=done)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore", SimulationWarningCategory)
            try:
                result = run_sim(
                    params, model=model.value, law=law, process=process,
                    sigma_zeta=sigma_zeta, x0=(float(x0[0]), float(x0[1])) if x0 else None, tau_end=te, dt=step,
                    integrator=integrator.value, runs=runs, seed=seed,
                    path_coordinate=path_coordinate.value,
                    save_trajectory=plot is not None or out is not None, save_every=save_every,
                    workers=workers, progress=cb,
                    white_increment="thesis" if (white_intensity is WhiteIntensityChoice.thesis
                                                 and model is ModelChoice.white) else "ito",
                )
            finally:
                if prog is not None:
                    prog.stop()
    except (ParameterError, ValueError) as exc:
        raise fail(str(exc)) from None

    summary = result.to_json_dict()
    summary["preset"] = pre.name if pre else None
    try:
        if out is not None:
            from ..io_utils import write_netcdf_atomic, write_text_atomic

            write_netcdf_atomic(out / "simulation.nc", result.to_dataset())
            write_text_atomic(out / "simulation.json", json.dumps(summary, indent=1))
        if plot is not None:
            from ..report.figures import plot_phase_portrait

            plot_phase_portrait(result, plot)
    except OSError as exc:  # disk full, place removed meanwhile: the previous files stay intact
        raise fail(f"could not write the results: {exc}") from None
    if json_out:
        typer.echo(json.dumps(summary))
        return
    _print_summary(result, summary, out, plot)


def _print_summary(result: Any, summary: dict[str, Any], out: Path | None, plot: Path | None) -> None:
    import numpy as np

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
    if p.pressure is not None:
        line += f"  p={p.pressure / 1e6:.4g} MPa"
    if result.model != "deterministic":
        line += f"  σ_ζ={result.sigma_zeta[0]:.4g}" if result.model == "white" else ""
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
    if out is not None:
        con.print(f"wrote {out / 'simulation.nc'} and {out / 'simulation.json'}")
    if plot is not None:
        con.print(f"wrote {plot}")


def register(app: typer.Typer) -> None:
    """Add the ``simulate`` command to ``app``."""
    app.command("simulate")(simulate)

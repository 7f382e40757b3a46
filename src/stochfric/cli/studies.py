"""Command line for the studies: ``stochfric study {normal-force,damping,forcing,lyapunov}``,
``stochfric run study.toml`` and ``stochfric reproduce``.  Parse, call, print; no physics.

Input errors end with a one-line message and exit code 2.  ``--json`` prints one JSON
object (no progress bar); otherwise a rich progress bar with the time remaining runs on
stderr and a short table is printed.
"""

from __future__ import annotations

import importlib
import json
import shlex
import sys
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import typer
from rich.console import Console
from rich.markup import escape
from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn
from rich.table import Table

from ..io_utils import OutputPathError, check_output_path
from ..report import html as report_html
from ..studies import executors, run_config
from ..studies.base import StudyResult
from ..studies.damping import DampingSummary
from ..studies.errors import StudyConfigError, StudyError, format_validation_errors
from ..studies.executors import ExecutorKind, SweepInterrupted
from ..studies.kinds import study_kind
from ..studies.refine import width_text
from .options import GROUP, SEED_RULE, fail, flag_of, option_group
from .white_limit import white_limit_command

#: the module (``stochfric.studies`` re-exports its function ``reproduce`` under the same name);
#: called through the module so that tests can replace ``plan`` / ``run_study`` / ``reproduce``
reproduce_mod = importlib.import_module("..studies.reproduce", __package__)

ForcedDampingOpt = Annotated[float | None, typer.Option("--damping-ratio", help="D (default 5e-6).")]
ModelsOpt = Annotated[str | None, typer.Option("--models", help="Comma-separated: deterministic,white,contact.")]
PresetOpt = Annotated[str, typer.Option("--preset", help="Thesis case: brake | sheet.")]
MachineOpt = Annotated[str | None, typer.Option(
    "--machine", help="Machine description instead of --preset: a TOML file (docs/machines.md) or a shipped name "
                      "(brake, sheet, example-calliper); a machine that is not a thesis case needs --process.")]
ExtrapOpt = Annotated[bool, typer.Option(
    "--allow-extrapolation", help="Use the process model outside the pressures it was fitted on (every output is "
                                  "stamped) instead of refusing.")]
ProcessOpt = Annotated[Path | None, typer.Option("--process", help="Friction-process model file (JSON).")]
RunsOpt = Annotated[int | None, typer.Option(
    "--runs", help="Monte Carlo runs per cell (default: the thesis's, 10; normal-force 30).")]
SeedOpt = Annotated[int, typer.Option("--seed", min=0, help=SEED_RULE)]
TauOpt = Annotated[float | None, typer.Option("--tau-end", help="Simulated time τ_end (default: preset).")]
DtOpt = Annotated[float | None, typer.Option("--dt", help="Time step Δτ (default: preset).")]
IntOpt = Annotated[str | None, typer.Option(
    "--integrator", help="euler | accurate (deterministic, contact; default: accurate for the forcing and Lyapunov "
                         "studies, euler otherwise; euler at the thesis's Δτ is their reproduction mode).")]
WinOpt = Annotated[float, typer.Option("--stick-window", help="Stick window: τ > w·τ_end counts (default 0.5).")]
ForceListOpt = Annotated[str | None, typer.Option("--normal-force", help="N [N] list (default: preset).")]
ForcingQOpt = Annotated[str | None, typer.Option(
    "--q", help="Forcing amplitudes q = Q/(cL), list (default 5e-5,5e-4).")]
EtaOpt = Annotated[str | None, typer.Option(
    "--eta", help="η = Ω/ω0 grid START:STOP:NUM or list (default: forcing 0:3:61, lyapunov 0.1:3:30).")]
PhaseRunsOpt = Annotated[int, typer.Option("--phase-runs", min=0, help="Runs kept for the phase diagrams (0: none).")]
# issue 30: closing the D_max(α) interval (numbers as text: the config validates them, one line on error)
BudgetOpt = Annotated[str | None, typer.Option(
    "--run-budget", metavar="<int>", help="Most runs the refinement adds, all models, forces and D together "
                                            "(default 20000).")]
ExecOpt = Annotated[str, typer.Option(
    "--executor", help=f"{ExecutorKind.SERIAL} | {ExecutorKind.PROCESSES} (local) ; see --scheduler.")]
WorkersOpt = Annotated[int | None, typer.Option("--workers", help="Processes (or threads for serial).")]
SchedOpt = Annotated[str | None, typer.Option("--scheduler", help="Dask scheduler address (uses Dask).")]
CkptOpt = Annotated[Path | None, typer.Option("--checkpoint", help="Checkpoint directory (resume).")]
OutOpt = Annotated[Path | None, typer.Option("--out", help="Write <study>.nc and <study>.json here.")]
ReportOpt = Annotated[Path | None, typer.Option("--report", help="Write an HTML report into this directory.")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object.")]
PathOpt = Annotated[str, typer.Option(
    "--path-coordinate", help="Where the contact process is read: mass (thesis text, path of the mass) | relative | "
                              "position (reproduction mode: at x1, eq. 4.36/4.38 as printed; euler only).")]
LevelOpt = Annotated[str, typer.Option(
    "--process-level", help="Variance of the contact process: sigma_mu (σ_μ(p)², default) | psd_level "
                            "(reproduction mode: from the thesis's E[S](p) fit, normalised by its 0.08-at-0.5-MPa "
                            "check; presets only).")]
WhiteOpt = Annotated[str, typer.Option(
    "--white-intensity", help="σ_ζ of the white-noise model: sigma_mu (thesis, σ_ζ = σ_μ(p)) | spectral_level "
                              "(the process's low-frequency spectral level) | thesis (reproduction mode: printed "
                              "eq. 4.31, σ_ζ,eff = σ_μ(p)·Lω0·Δτ, depends on Δτ).")]


class _StudyProgress:
    """Progress of one or more studies on stderr.

    On a terminal: a rich bar naming the running study with done/total tasks and the time
    remaining (and, for several studies, a second bar over the studies).  Otherwise (a log
    file, a pipe): one line per finished study.  ``enabled=False`` (``--json``): silent.
    """

    def __init__(self, enabled: bool, n_studies: int = 1) -> None:
        self.enabled = enabled
        self.n_studies = n_studies
        self.tty = enabled and sys.stderr.isatty()
        self.finished = 0
        self.label = ""
        self.done = 0
        self.total: int | None = None
        self._prog: Any = None
        self._study_task: Any = None
        self._all_task: Any = None
        self._t0 = time.perf_counter()

    def __enter__(self) -> _StudyProgress:
        if self.tty:
            self._prog = Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.fields[count]}"),
                                  TimeElapsedColumn(), TextColumn("ETA"), TimeRemainingColumn(),
                                  console=Console(stderr=True), transient=True)
            self._prog.start()
            if self.n_studies > 1:
                self._all_task = self._prog.add_task("all studies", total=self.n_studies,
                                                     count=f"0/{self.n_studies} studies")
        return self

    def __exit__(self, *exc: object) -> None:
        if self._prog is not None:
            self._prog.stop()

    def start(self, label: str) -> None:
        """A study begins: name it on the bar."""
        self.label, self.done, self.total = label, 0, None
        self._t0 = time.perf_counter()
        if self._prog is not None:
            if self._study_task is not None:
                self._prog.remove_task(self._study_task)
            self._study_task = self._prog.add_task(label, total=None, count="counting tasks …")

    def tasks(self, done: int, total: int) -> None:
        """``progress(done, total)`` callback of a study."""
        self.done, self.total = done, total
        if self._prog is not None and self._study_task is not None:
            self._prog.update(self._study_task, completed=done, total=total, count=f"{done}/{total} tasks")

    def end(self, computed: int, loaded: int) -> None:
        """The running study has finished: advance the bar, or print its line."""
        self.finished += 1
        if self._prog is not None and self._all_task is not None:
            self._prog.update(self._all_task, completed=self.finished,
                              count=f"{self.finished}/{self.n_studies} studies")
        if self.enabled and not self.tty:
            print(f"[{self.finished}/{self.n_studies}] {self.label}: {computed + loaded} tasks ({computed} computed, "
                  f"{loaded} from checkpoint) in {time.perf_counter() - self._t0:.1f} s", file=sys.stderr, flush=True)


def _interrupted(exc: KeyboardInterrupt, what: str, checkpoint: Path | None) -> typer.Exit:
    """Ctrl-C: say how many tasks are saved and how to resume; exit code 130."""
    done = total = None
    if isinstance(exc, SweepInterrupted):
        done, total = exc.stats.loaded + exc.stats.computed, exc.total
    head = f"interrupted in {what}" + (f" after {done} of {total} tasks" if done is not None else "")
    if checkpoint is None:
        msg = (f"{head}; nothing was saved (no --checkpoint). Run with --checkpoint DIR to be able to resume "
               "an interrupted study.")
    else:
        argv = sys.argv[1:] if Path(sys.argv[0]).name == "stochfric" else None
        cmd = shlex.join(["stochfric", *argv]) if argv is not None else "the same command"
        msg = (f"{head}; {done if done is not None else 'all finished'} tasks of it are saved in {checkpoint}. "
               f"Resume with: {cmd}  (finished tasks are loaded, not recomputed)")
    typer.echo(msg, err=True)
    return typer.Exit(code=130)


def _check_dirs(**dirs: Path | str | None) -> None:
    """Check every output directory before any work (``StudyError`` with the option name)."""
    for name, d in dirs.items():
        if d is not None:
            try:
                check_output_path(d, option="--" + name.replace("_", "-"))
            except OutputPathError as exc:
                raise StudyError(str(exc)) from None


def _whole(value: str | None, flag: str) -> int | None:
    """A whole-number option given as text (``None``: not given); one line naming ``flag`` otherwise."""
    if value is None:
        return None
    try:
        return int(value.strip())
    except ValueError:
        raise fail(f"{flag}: {value!r} is not a whole number") from None


def _models(spec: str | None) -> dict[str, Any]:
    if spec is None:
        return {}
    return {"models": tuple(m.strip() for m in spec.split(",") if m.strip())}


def study_options(
    preset: PresetOpt = "brake", runs: RunsOpt = None, seed: SeedOpt = 0, models: ModelsOpt = None,
    process: ProcessOpt = None, tau_end: TauOpt = None, dt: DtOpt = None, integrator: IntOpt = None,
    path_coordinate: PathOpt = "mass", white_intensity: WhiteOpt = "sigma_mu", process_level: LevelOpt = "sigma_mu",
    machine: MachineOpt = None, allow_extrapolation: ExtrapOpt = False,
) -> dict[str, Any]:
    """The config fields every study command shares (case, Monte Carlo, modelling choices); options
    left out take the config's defaults (:func:`~stochfric.cli.options.option_group`)."""
    d: dict[str, Any] = {"preset": preset, "seed": seed, "path_coordinate": path_coordinate,
                         "white_intensity": white_intensity, "process_level": process_level, **_models(models)}
    if integrator is not None:
        d["integrator"] = integrator
    if machine is not None:
        d["machine"] = machine
    if allow_extrapolation:
        d["allow_extrapolation"] = True
    if process is not None:
        d["process_file"] = str(process)
    if runs is not None:
        d["runs"] = runs
    if tau_end is not None:
        d["tau_end"] = tau_end
    if dt is not None:
        d["dt"] = dt
    return d


def forced_options(q: ForcingQOpt = None, eta: EtaOpt = None, damping_ratio: ForcedDampingOpt = None) -> dict[str, Any]:
    """The forcing grid of the forced-oscillator studies (forcing, Lyapunov); options left out take the
    study config's defaults."""
    return {"forcing_q": q, "eta": eta, "damping_ratio": damping_ratio}


@dataclass(frozen=True)
class ExecutionOptions:
    """Where a study command runs and what it writes (never changes the numbers)."""

    executor: str  # an ExecutorKind's name as given (make_executor refuses another with one line)
    workers: int | None
    scheduler: str | None
    checkpoint: Path | None
    out: Path | None
    report: Path | None
    json_out: bool


def execution_options(
    executor: ExecOpt = ExecutorKind.SERIAL, workers: WorkersOpt = None, scheduler: SchedOpt = None,
    checkpoint: CkptOpt = None, out: OutOpt = None, report: ReportOpt = None, json_out: JsonOpt = False,
) -> ExecutionOptions:
    """The execution and output options of a study command."""
    return ExecutionOptions(executor, workers, scheduler, checkpoint, out, report, json_out)


def _validate(kind: str, fields: dict[str, Any]) -> Any:
    try:
        return study_kind(kind).config(**{k: v for k, v in fields.items() if v is not None})
    except StudyConfigError as exc:
        raise StudyError(format_validation_errors(exc.validation_error, flag_of)) from None


def _execute(kind: str, fields: dict[str, Any], run: ExecutionOptions) -> None:
    """Validate a study command's options (``fields``: :func:`study_options` and the study's own) into
    its config, run it and print or write the results."""
    executor, workers, scheduler, checkpoint = run.executor, run.workers, run.scheduler, run.checkpoint
    out, report, json_out = run.out, run.report, run.json_out
    try:
        cfg = _validate(kind, fields)
    except StudyError as exc:
        raise fail(str(exc)) from None
    try:
        _check_dirs(out=out, report=report, checkpoint=checkpoint)
        ex = executors.make_executor(executor, workers=workers, scheduler=scheduler)
        t0 = time.perf_counter()
        with _StudyProgress(not json_out) as prog:
            prog.start(f"{cfg.kind} ({cfg.case_label()})")
            res = reproduce_mod.run_study(cfg, executor=ex, checkpoint=str(checkpoint) if checkpoint else None,
                            progress=prog.tasks)
            prog.end(res.stats.computed, res.stats.loaded)
        wall = time.perf_counter() - t0
        files: list[str] = []
        if out is not None:
            files += [str(p) for p in res.save(out)]
        if report is not None:
            files.append(str(report_html.write_report([res], report)))
    except (ValueError, OSError) as exc:  # StudyError and the package's other input errors are ValueErrors
        raise fail(str(exc)) from None
    except KeyboardInterrupt as exc:
        raise _interrupted(exc, f"{cfg.kind} ({cfg.case_label()})", checkpoint) from None
    payload = res.to_json_dict()
    payload["wall_time_s"] = wall
    payload["tasks"] = {"computed": res.stats.computed, "loaded_from_checkpoint": res.stats.loaded}
    payload["files"] = files
    if json_out:
        typer.echo(json.dumps(payload, allow_nan=False))
        return
    _print_summary(res, wall, files)


def _closure_lines(s: DampingSummary) -> list[str]:
    """Per stochastic model and force how far the D_max(α) interval of the refined α (else the first) is closed,
    and how to close the open ones (docs/studies.md, "Closing the D_max(α) interval")."""
    alpha = s.refinement.risk_level if s.refinement is not None else s.risk_levels[0]
    j = s.risk_levels.index(alpha)
    lines = [f"D_max({100 * alpha:g} %) {m}, N = {nf:g} N: {width_text(s.d_max_risk_width[m][i][j])}"
             for m in s.d_max_risk_width for i, nf in enumerate(s.normal_force_n)]
    if s.refinement is not None:
        r = s.refinement
        lines.append(f"refinement: {r.runs_added} runs added in {r.rounds} rounds (budget {r.run_budget}, at most "
                     f"{r.max_runs_per_cell} runs per cell); stopped: {r.stop}")
    elif any(not w[j].closed and w[j].status == "open" for per in s.d_max_risk_width.values() for w in per):
        lines.append("to close the open intervals: --refine (adds runs where the band still holds α; "
                     "--run-budget N, default 20000)")
    return lines


def _closure_brief(s: DampingSummary) -> str:
    """One line: how many D_max(α) intervals (stochastic models × forces, α refined or the first) are closed, and
    how to close the open ones."""
    alpha = s.refinement.risk_level if s.refinement is not None else s.risk_levels[0]
    j = s.risk_levels.index(alpha)
    ws = [w[j] for per in s.d_max_risk_width.values() for w in per]
    count = {st: sum(w.status == st for w in ws) for st in ("closed", "open", "beyond-grid", "below-grid")}
    text = (f"D_max({100 * alpha:g} %) intervals: {count['closed']} of {len(ws)} closed (at most "
            f"{ws[0].target_steps if ws else 2} grid steps)" + "".join(
                f", {count[st]} {st}" for st in ("open", "beyond-grid", "below-grid") if count[st]))
    if count["open"]:
        text += ("; the refinement's budget is spent" if s.refinement is not None and s.refinement.stop == "budget"
                 else "") + " — close them with --refine (--run-budget N, default 20000)"
    return text


def _damping_table(s: DampingSummary) -> Table:
    """The damping study's limits per force: D_H, D_max^d, D_max(α) per model and α, sample extremes."""
    t = Table(title=escape("largest damping with P(stick-slip) ≥ α [interval]; sample extreme = largest D at "
                           "which any run stuck (thesis D_max^s, grows with the runs)"))
    risk, grid, det = s.d_max_risk, s.damping_ratio, s.d_max_deterministic
    for col in ["N [N]", "D_H", "D_max^d", *[f"D_max({100 * a:g} %) {m}" for m in risk for a in s.risk_levels],
                *[f"sample extreme {m}" for m in s.d_max_sample_extreme]]:
        t.add_column(col, justify="right")
    for i, nf in enumerate(s.normal_force_n):
        row = [f"{nf:g}", f"{s.d_hopf[i]:.4g}", report_html.dmax_text(det[i], grid) if det else "—"]
        row += [report_html.risk_text(risk[m][i][j], grid, s.runs, compact=True)
                for m in risk for j in range(len(s.risk_levels))]
        row += [report_html.dmax_text(e[i].value, grid) for e in s.d_max_sample_extreme.values()]
        t.add_row(*(escape(c) for c in row))
    return t


def _print_summary(res: StudyResult[Any], wall: float, files: list[str]) -> None:
    s = res.summary
    con = Console()
    con.print(f"[bold]stochfric study {res.kind}[/] preset={s.preset} runs={s.runs} seed={s.seed} "
              f"({wall:.1f} s; tasks computed {res.stats.computed}, from checkpoint {res.stats.loaded})")
    if isinstance(s, DampingSummary):
        con.print(_damping_table(s))
        for line in _closure_lines(s):
            con.print(escape(line))
    _, reading = report_html.SECTIONS[res.kind].reading(s)
    con.print(escape(reading))
    con.print(report_html.model_choices_text(s))
    for w in s.warnings:
        con.print(f"[yellow]warning[/] {w.code} ×{w.count}")
    for f in files:
        con.print(f"wrote {f}")


@option_group("common", study_options)
@option_group("run", execution_options)
def damping_command(
    common: dict[str, Any] = GROUP,
    normal_force: Annotated[str | None, typer.Option("--normal-force", help="N [N]: value, list or A:B:NUM.")] = None,
    damping_ratio: Annotated[
        str, typer.Option("--damping-ratio", help="D grid START:STOP:NUM or list.")
    ] = "0.05:0.25:41",
    stick_window: WinOpt = 0.5,
    confidence: Annotated[float, typer.Option("--confidence", help="Clopper–Pearson level.")] = 0.95,
    p_detect: Annotated[float, typer.Option(
        "--p-detect", help="Stick probability below which D_hi of the sample extreme is read.")] = 0.1,
    risk_levels: Annotated[str | None, typer.Option(
        "--risk-levels", help="Risk levels α of D_max(α), the largest D with P(stick-slip) ≥ α: comma-separated "
                              "probabilities in (0, 1) (default 0.1,0.01).")] = None,
    x0: Annotated[tuple[float, float] | None, typer.Option("--x0", help="Initial X1 X2 (default (0, γ0)).")] = None,
    phase_force: Annotated[float | None, typer.Option(
        "--phase-force", help="N [N] of the phase diagrams over D (default: the preset's damping-study force if "
                              "it is on the --normal-force grid, else the middle force).")] = None,
    phase_damping: Annotated[str | None, typer.Option(
        "--phase-damping", help="D values of the phase diagrams, list or A:B:NUM (default: 5 grid values from the "
                                "lowest D to the first grid D above the largest D_max at the phase force).")] = None,
    phase_runs: PhaseRunsOpt = 3,
    refine: Annotated[bool, typer.Option(
        "--refine", help="Close the D_max(α) interval adaptively: add runs at the D whose Clopper–Pearson band still "
                         "holds α between its ends, until it is at most --target-steps grid steps wide or --run-budget "
                         "runs are added (docs/studies.md).")] = False,
    run_budget: BudgetOpt = None,
    max_runs_per_cell: Annotated[str | None, typer.Option(
        "--max-runs-per-cell", metavar="<int>", help="Most runs of one (N, D) cell under --refine (default 1000).")
    ] = None,
    target_steps: Annotated[str | None, typer.Option(
        "--target-steps", metavar="<int>", help="Width in grid steps at which a D_max(α) interval counts as closed "
                                                  "(default 2).")] = None,
    refine_risk_level: Annotated[str | None, typer.Option(
        "--refine-risk-level", metavar="<float>", help="α whose interval --refine closes, one of --risk-levels "
                                                     "(default: the first).")] = None,
    run: ExecutionOptions = GROUP,
) -> None:
    """Damping study: P(stick-slip | D), D_max(α) with interval, D_max^d, D_H, M_diff, M_quot, phase diagrams
    over D (method §6.2); --refine closes the D_max(α) interval adaptively."""
    lone = [f for f, v in (("--run-budget", run_budget), ("--max-runs-per-cell", max_runs_per_cell),
                           ("--refine-risk-level", refine_risk_level)) if v is not None and not refine]
    if lone:
        raise fail(f"{lone[0]}: it sets the refinement; give --refine with it")
    _execute("damping", {**common, "stick_window": stick_window,
                         "normal_forces": normal_force, "damping_ratios": damping_ratio, "confidence": confidence,
                         "p_detect": p_detect, "risk_levels": risk_levels, "x0": x0, "phase_normal_force": phase_force,
                         "phase_damping_ratios": phase_damping, "phase_runs": phase_runs, "refine": refine or None,
                         "run_budget": run_budget, "max_runs_per_cell": max_runs_per_cell,
                         "target_steps": target_steps, "refine_risk_level": refine_risk_level}, run)


@option_group("common", study_options)
@option_group("forced", forced_options)
@option_group("run", execution_options)
def forcing_command(
    common: dict[str, Any] = GROUP,
    normal_force: Annotated[float | None, typer.Option("--normal-force", help="N [N] (default: preset).")] = None,
    forced: dict[str, Any] = GROUP,
    stick_window: WinOpt = 0.5,
    run: ExecutionOptions = GROUP,
) -> None:
    """Forcing study: bifurcation data, E[X_gh] ± σ over η, σ_contact/σ_white (method §6.3)."""
    _execute("forcing", {**common, **forced, "stick_window": stick_window, "normal_force": normal_force}, run)


@option_group("common", study_options)
@option_group("forced", forced_options)
@option_group("run", execution_options)
def lyapunov_command(
    common: dict[str, Any] = GROUP,
    normal_force: ForceListOpt = None,
    forced: dict[str, Any] = GROUP,
    perturbation: Annotated[float, typer.Option("--perturbation", help="δ added to x1(0) of the comparison run.")
                            ] = 1e-6,
    run: ExecutionOptions = GROUP,
) -> None:
    """Largest Lyapunov exponent λ (4.43) / E[Λ] (4.44) over η and N (method §6.4)."""
    _execute("lyapunov", {**common, **forced, "normal_forces": normal_force, "perturbation": perturbation}, run)


@option_group("common", study_options)
@option_group("run", execution_options)
def normal_force_command(
    common: dict[str, Any] = GROUP,
    normal_force: ForceListOpt = None,
    damping_ratio: Annotated[
        str | None, typer.Option("--damping-ratio", help="D list (default 5e-6 and the damped D).")
    ] = None,
    phase_runs: PhaseRunsOpt = 5,
    stick_window: WinOpt = 0.5,
    run: ExecutionOptions = GROUP,
) -> None:
    """Normal-force study: phase diagrams, PDFs, E[X_gh] ± σ, VarK with SEs (method §6.1)."""
    _execute("normal-force", {**common, "stick_window": stick_window,
                              "normal_forces": normal_force, "damping_ratios": damping_ratio,
                              "phase_runs": phase_runs}, run)


def run_command(
    file: Annotated[Path, typer.Argument(help="Study file (TOML), see examples/study.toml.")],
    json_out: JsonOpt = False,
) -> None:
    """Run the studies of a TOML file (validated; results, checkpoints and report as configured)."""
    what = str(file)
    ckpt: Path | None = None
    try:
        rf = run_config.load_run_file(file)
        ckpt = Path(rf.execution.checkpoint) if rf.execution.checkpoint else None
        _check_dirs(out=rf.output.dir, checkpoint=ckpt)
        ex = executors.make_executor(rf.execution.executor if rf.execution.scheduler is None else ExecutorKind.DASK,
                           workers=rf.execution.workers, scheduler=rf.execution.scheduler)
        results = []
        out = Path(rf.output.dir)
        with _StudyProgress(not json_out, len(rf.study)) as prog:
            for i, cfg in enumerate(rf.study):
                what = f"study[{i}] {cfg.kind} ({cfg.case_label()})"
                prog.start(what)
                res = reproduce_mod.run_study(cfg, executor=ex, checkpoint=rf.execution.checkpoint,
                                              progress=prog.tasks)
                res.save(out / f"{i:02d}_{cfg.kind}_{cfg.case_label()}")
                prog.end(res.stats.computed, res.stats.loaded)
                results.append(res)
        index = report_html.write_report(results, out) if rf.output.report else None
    except (ValueError, OSError) as exc:  # StudyError and the package's other input errors are ValueErrors
        raise fail(str(exc)) from None
    except KeyboardInterrupt as exc:
        raise _interrupted(exc, what, ckpt) from None
    tasks = [{"computed": r.stats.computed, "loaded_from_checkpoint": r.stats.loaded} for r in results]
    payload = {"studies": [{**r.to_json_dict(), "tasks": t} for r, t in zip(results, tasks, strict=True)],
               "tasks": {k: sum(t[k] for t in tasks) for k in ("computed", "loaded_from_checkpoint")},
               "out": str(out), "report": str(index) if index else None}
    if json_out:
        typer.echo(json.dumps(payload, allow_nan=False))
        return
    for r in results:
        typer.echo(f"{r.kind} ({r.summary.preset}): {report_html.SECTIONS[r.kind].reading(r.summary)[1]}")
    typer.echo(f"results in {out}" + (f", report {index}" if index else ""))


def reproduce_command(
    quick: Annotated[bool, typer.Option("--quick", help="Coarse grids and few runs (the studies in a "
                                                        "fifth of the time; the report takes as long; measured times "
                                                        "in the README).")] = False,
    out: Annotated[Path, typer.Option("--out", help="Output directory.")] = Path("reproduce"),
    seed: SeedOpt = 2013,
    runs: Annotated[str | None, typer.Option(
        "--runs", metavar="<int>", help="Monte Carlo runs per cell of every study (default: the thesis's, 10; 30 for "
                                          "the normal-force study).")] = None,
    refine: Annotated[bool, typer.Option(
        "--refine", help="Damping studies: close the D_max(10 %) interval adaptively within --run-budget added runs "
                         "(only P(stick-slip | D) and D_max(α) take them; default: the thesis's fixed runs).")] = False,
    run_budget: BudgetOpt = None,
    executor: ExecOpt = ExecutorKind.SERIAL, workers: WorkersOpt = None, scheduler: SchedOpt = None,
    json_out: JsonOpt = False,
) -> None:
    """All studies of thesis chapter 4 for brake and sheet, results and DIR/index.html."""
    what = "reproduce"
    n_runs, budget = _whole(runs, "--runs"), _whole(run_budget, "--run-budget")
    if budget is not None and not refine:
        raise fail("--run-budget: it bounds the refinement; give --refine with it")
    try:  # every config before any work: a bad --runs or --run-budget ends with one line naming the flag
        plan = reproduce_mod.configure(reproduce_mod.plan(quick, seed), runs=n_runs, refine=refine, run_budget=budget)
    except StudyConfigError as exc:
        raise fail(format_validation_errors(exc.validation_error, flag_of)) from None
    try:
        _check_dirs(out=out)
        ex = executors.make_executor(executor, workers=workers, scheduler=scheduler)
        with _StudyProgress(not json_out, len(plan)) as prog:
            def on_tasks(label: str, d: int, n: int) -> None:
                nonlocal what
                if label != prog.label:
                    what = f"reproduce ({prog.finished} of {prog.n_studies} studies finished and saved), study {label}"
                    prog.start(label)
                prog.tasks(d, n)

            results, timings = reproduce_mod.reproduce(out, quick=quick, seed=seed, runs=n_runs, refine=refine,
                                                       run_budget=budget, executor=ex, progress=on_tasks,
                                         study_done=lambda res: prog.end(res.stats.computed, res.stats.loaded),
                                         report=report_html.write_report)
    except (ValueError, OSError) as exc:  # StudyError and the package's other input errors are ValueErrors
        raise fail(str(exc)) from None
    except KeyboardInterrupt as exc:
        raise _interrupted(exc, what, out / "checkpoints") from None
    payload = {"out": str(out), "report": str(out / "index.html"), "timings_s": timings,
               "studies": [{"study": r.kind, "preset": r.summary.preset,
                            "tasks": {"computed": r.stats.computed, "loaded_from_checkpoint": r.stats.loaded}}
                           for r in results]}
    if json_out:
        typer.echo(json.dumps(payload))
        return
    for r in results:
        typer.echo(f"{r.kind} ({r.summary.preset}): {report_html.SECTIONS[r.kind].reading(r.summary)[1]}")
        if isinstance(r.summary, DampingSummary):
            typer.echo(f"  {_closure_brief(r.summary)}")
    split = ", ".join(f"{k} {v:.1f} s" + (" (while the report draws)" if k == "chapter3" else "")
                      for k, v in timings.items() if k not in ("studies_total", "total"))
    typer.echo(f"time per step: {split}")
    typer.echo(f"report {out / 'index.html'}; total {timings['total']:.1f} s")


def register(app: typer.Typer) -> None:
    """Add ``study {normal-force,damping,forcing,lyapunov,white-limit}``, ``run`` and ``reproduce`` to ``app``."""
    study = typer.Typer(help="Studies of thesis chapter 4 (method §6): three friction models side by side.",
                        no_args_is_help=True)
    study.command("damping")(damping_command)
    study.command("forcing")(forcing_command)
    study.command("lyapunov")(lyapunov_command)
    study.command("normal-force")(normal_force_command)
    study.command("white-limit")(white_limit_command)
    app.add_typer(study, name="study")
    app.command("run")(run_command)
    app.command("reproduce")(reproduce_command)

"""Command ``friction-process``: statistical contact analysis → friction-process model.

Parse, call, print (no physics): the work is :func:`stochfric.process.statistics.analyse`.
``register(app)`` adds the command to a :class:`typer.Typer` application.  Lengths on the
command line are in µm; everything inside and in the JSON is SI.  Bad input ends with one line
``error: …`` on stderr and exit status 2.
"""

from __future__ import annotations

import contextlib
import json
import math
from collections.abc import Callable, Iterator
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import typer
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

from stochfric.cli.options import (
    GROUP,
    SEED_RULE,
    RegistryChoice,
    fail,
    option_group,
    write_failed,
)
from stochfric.cli.surface import (
    SurfaceOptions,
    _echo_warnings,
    parse_approach_um,
    surface_options,
)
from stochfric.contact.materials import load_material, material_names
from stochfric.errors import AnalysisError, StochfricError
from stochfric.friction_process.model_base import SigmaZetaRule
from stochfric.friction_process.tabulated import PressureRule, VarianceRule
from stochfric.io_utils import check_output_path, json_ready
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.analysis_result import StatisticalContactAnalysis
from stochfric.process.checks import WINDOW_MIN_SUMMITS, WINDOW_TILES
from stochfric.process.credibility import NOT_CREDIBLE_EXIT
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION
from stochfric.process.holdout import HOLDOUT_MAX_REALIZATIONS, HOLDOUT_REALIZATIONS
from stochfric.process.pipeline import MODEL_FILE, STATISTICS_FILE, ApproachRule, ScanAnalysis, analyse_scans
from stochfric.surface.quilting import MAX_PATCH_FRACTION, MIN_PATCH_SUMMIT_SPACINGS
from stochfric.surface.surrogates import AUTO_SURROGATE, SURROGATES, surrogate_names
from stochfric.surface.synthesis import AmplitudeEstimate
from stochfric.units import MICROMETRE

__all__ = ["register"]

#: ``--surrogate``: ``auto`` or a method of the registry (read when the command runs).
SURROGATE_CHOICE = RegistryChoice(names=lambda: (AUTO_SURROGATE, *surrogate_names()))
_SURROGATE_HELP = (
    "auto: random phases where the map's curvature is Gaussian (Laplacian kurtosis within 3·√(24/n_s) of 3), "
    f"else quilt where patches of {MIN_PATCH_SUMMIT_SPACINGS:g} summit spacings fit {1 / MAX_PATCH_FRACTION:.0f} "
    "times along the shorter side, else phase; or a method: "
    + "; ".join(f"{name} ({m.summary})" for name, m in SURROGATES.items()) + "."
)



ValidationBudgetOpt = Annotated[
    int | None, typer.Option(
        "--validation-budget", help="Most surrogates per fold of the held-out validation: it starts with "
        f"min({HOLDOUT_REALIZATIONS}, --realizations) and doubles while a statistic lies within 2 Monte Carlo SE "
        "of the threshold; undecided after the budget. Default: 8 × the "
        f"start, at most {HOLDOUT_MAX_REALIZATIONS}.")
]
SummitBudgetOpt = Annotated[
    int | None, typer.Option(
        "--summit-budget", min=2, help="Most realisations the summit check may grow the ensemble to: it doubles "
        "--realizations while the Monte Carlo p-value of its rank test is within its binomial error of 5 %; "
        "undecided after the budget. Default: by the map, a bounded amount of work — 32 × --realizations on "
        "maps up to 512 × 512 points, down to 4 × on a 1700 × 1700 map (docs/statistical_contact.md §0e).")
]

FilesArg = Annotated[
    list[Path] | None,
    typer.Argument(
        help="Height map(s): instrument files SurfaceTopography reads (x3p, sur, opd, datx, plu, mnt, al3d, frt, "
        "…) or .npy/.txt/.csv matrices (then --size-um and --height-unit are required). Several files are "
        "several scans of one surface, pooled into one ensemble (same pixel size, or --resample). Default: "
        "the measured surface shipped with the package.",
        show_default=False,
    ),
]


@option_group("surf", surface_options)
def friction_process_command(
    material: Annotated[str, typer.Option("--material", help=f"Pairing: {', '.join(material_names())} or a JSON "
                                                             "file (SI units).")],
    files: FilesArg = None,
    realizations: Annotated[int, typer.Option("--realizations", help="Similar surfaces of original size (§4a).")] = 100,
    long_surfaces: Annotated[int, typer.Option("--long-surfaces", help="Long surfaces for μ along the path (§4c).")
                             ] = 10,
    length_factor: Annotated[
        int, typer.Option("--length-factor", help="Length of a long surface in original lengths (thesis 10).")
    ] = 10,
    window_shift_um: Annotated[
        float | None,
        typer.Option("--window-shift-um", help="Window shift a_y [µm], rounded to whole grid points; "
                     "default 0.0566 × the window length (thesis 0.3 of 5.3 mm)."),
    ] = None,
    approach_um: Annotated[
        str | None,
        typer.Option("--approach-um", help="START:STOP:NUM in µm; default: 12 approaches by --approach-rule."),
    ] = None,
    approach_rule: Annotated[
        ApproachRule,
        typer.Option("--approach-rule", help="Default approach range: contacts (from 20 touching summits to "
                     "A_c/A_nom = --max-area-fraction or half the summits touching) or sigma (σ_S/4 … 3σ_S, "
                     "stretched to the highest summit; used by reproduce)."),
    ] = ApproachRule.CONTACTS,
    surrogate: Annotated[
        str,
        typer.Option("--surrogate", parser=SURROGATE_CHOICE, metavar="METHOD", help=_SURROGATE_HELP),
    ] = AUTO_SURROGATE,
    validation_budget: ValidationBudgetOpt = None,
    summit_budget: SummitBudgetOpt = None,
    window_tiles: Annotated[
        int, typer.Option("--window-tiles", help="Measured-window check: at most N × N disjoint windows per scan "
                          f"(fewer when a window would hold < {WINDOW_MIN_SUMMITS} summits).")
    ] = WINDOW_TILES,
    resample: Annotated[
        bool, typer.Option("--resample", help="Pooled scans with different pixel sizes: resample them (linear "
                           "interpolation) to the coarsest pixel size instead of refusing.")
    ] = False,
    workers: Annotated[
        int | None, typer.Option("--workers", help="Processes for the realisations (default: all cores); the "
                                 "numbers do not depend on it.")
    ] = None,
    accept_not_credible: Annotated[
        bool, typer.Option("--accept-not-credible", help="Write the model file even when the analysis is not "
                           "credible (exit status 3 otherwise); the model is stamped and every reader warns.")
    ] = False,
    amplitude: Annotated[
        AmplitudeEstimate,
        typer.Option("--amplitude", help="Amplitude estimate of the measured map: tukey (default) or hann "
                     "(edge jump removed, variance restored) or raw (the thesis's DFT of the non-periodic map)."),
    ] = AmplitudeEstimate.TUKEY,
    max_area_fraction: Annotated[
        float,
        typer.Option("--max-area-fraction", help="Fits use points with mean A_c/A_nom up to this (default: the end "
                     "of the GW/boundary-element plateau at equal load, docs/surface_contact.md)."),
    ] = DEFAULT_MAX_AREA_FRACTION,
    pressure_rule: Annotated[
        PressureRule, typer.Option("--pressure-rule", help="nearest (thesis) or interpolate (log-log in p).")
    ] = PressureRule.NEAREST,
    variance_rule: Annotated[
        VarianceRule, typer.Option("--variance-rule", help="sigma_mu (scale to the σ_μ fit) or tabulated.")
    ] = VarianceRule.SIGMA_MU,
    sigma_zeta_rule: Annotated[
        SigmaZetaRule, typer.Option("--sigma-zeta-rule", help="sigma_mu (thesis) or spectral_level (S0/2).")
    ] = SigmaZetaRule.SIGMA_MU,
    seed: Annotated[int, typer.Option("--seed", min=0, help=SEED_RULE)] = 0,
    contact_model: Annotated[str, typer.Option("--contact-model", help="gw (thesis), bem, bem-plastic, persson, a list "
                             "or all: also solve the surrogates and windows by them at the fitted pressures and report "
                             "the spread; one non-GW model sets the model's E[μ](p), σ_μ(p) (docs/contact_models.md).")
                             ] = "gw",
    out: Annotated[
        Path | None,
        typer.Option("--out", help=f"Directory for {MODEL_FILE} (the model) and {STATISTICS_FILE}."),
    ] = None,
    plot: Annotated[
        bool, typer.Option("--plot", help="Also write the figures into DIR/figures (needs --out).")
    ] = False,
    surf: SurfaceOptions = GROUP,
    as_json: Annotated[bool, typer.Option("--json", help="Print the result as JSON.")] = False,
) -> None:
    """Statistical contact analysis of similar surfaces → friction-process model (method §3–§4)."""
    try:
        if plot and out is None:
            raise AnalysisError("--plot writes into the output directory: give --out DIR")
        if out is not None:
            check_output_path(out, option="--out")
        mat = load_material(material)
        approach = parse_approach_um(approach_um) if approach_um is not None else None
        cfg = AnalysisConfig(
            realizations=realizations, long_surfaces=long_surfaces, length_factor=length_factor,
            surrogate=surrogate, amplitude=amplitude, summit_rule=surf.summit_rule,
            max_area_fraction=max_area_fraction, pressure_rule=pressure_rule, variance_rule=variance_rule,
            sigma_zeta_rule=sigma_zeta_rule, window_tiles=window_tiles, seed=seed,
            holdout_realizations=None if validation_budget is None else min(
                HOLDOUT_REALIZATIONS, max(4, realizations), validation_budget),
            holdout_max_realizations=validation_budget, summit_max_realizations=summit_budget,
        )  # fmt: skip
        with _progress(show=not as_json) as progress:
            run = analyse_scans(
                files, mat, config=cfg, preparation=surf.preparation(), physical_size_m=surf.physical_size_m(),
                height_unit=surf.height_unit, fill_undefined=surf.fill_undefined, resample=resample,
                approach_m=approach, approach_rule=approach_rule.value, window_shift_m=_window_shift_m(window_shift_um),
                workers=workers, progress=progress, notify=None if as_json else _note,
                contact_model=contact_model,
            )  # fmt: skip
        payload = run.to_json_dict()
        if out is not None:
            payload.update(run.write(out, model=run.credible or accept_not_credible, figures=plot))
    except (StochfricError, ValueError) as exc:  # ValueError: e.g. a fit without enough points
        raise fail(str(exc)) from None
    except OSError as exc:  # disk full while writing: the previous files stay intact
        raise write_failed(exc) from None
    _show(run, payload, as_json=as_json, accept_not_credible=accept_not_credible)


def _show(run: ScanAnalysis, payload: dict[str, Any], *, as_json: bool, accept_not_credible: bool) -> None:
    """Warnings and checks on stderr, the result as JSON or text, then the gate (exit 3 when not credible)."""
    _echo_warnings(payload["warnings"])
    _echo_checks(run.analysis)
    if as_json:
        typer.echo(json.dumps(json_ready(payload), indent=1, allow_nan=False))
    else:
        _print(run, payload)
    _gate(run.analysis, accept_not_credible=accept_not_credible)


def _note(text: str) -> None:
    typer.echo(f"note: {text}", err=True)


def _window_shift_m(window_shift_um: float | None) -> float | None:
    """``--window-shift-um`` in metres (checked here, at the edge, in the unit the user typed)."""
    if window_shift_um is None:
        return None
    if not (math.isfinite(window_shift_um) and window_shift_um > 0):
        raise AnalysisError(f"--window-shift-um must be > 0, got {window_shift_um!r}")
    return window_shift_um * MICROMETRE


def _gate(analysis: StatisticalContactAnalysis, *, accept_not_credible: bool) -> None:
    """A not-credible analysis: a warning when it was accepted, else one line and exit status 3."""
    if analysis.credibility.credible:
        return
    if accept_not_credible:
        typer.echo("warning: [not-credible-accepted] the model was written with --accept-not-credible and is "
                   "stamped so; simulate and the studies warn when they read it", err=True)
        return
    typer.echo(
        f"error: {analysis.credibility.status} ({', '.join(analysis.credibility.codes())}): no model file written; "
        "fix the cause named above, or give --accept-not-credible to write a stamped model", err=True)
    raise typer.Exit(code=NOT_CREDIBLE_EXIT)


def _summit_verdict(analysis: StatisticalContactAnalysis) -> tuple[str, str]:
    """The summit check as the gate reads it (decided against its Monte Carlo error, docs §0a):
    ('pass' | 'FAIL' | 'undecided', 'credible' | 'NOT credible' | 'undecided')."""
    cfg = analysis.config
    realizations = int(analysis.ensemble.contact_area_m2.shape[0])
    failed, near = analysis.surrogate_check.decided(realizations, looks=cfg.summit_looks)
    if failed:
        return "FAIL", "NOT credible"
    return ("undecided", "undecided (p-value within its Monte Carlo error of 5 %)") if near else ("pass", "credible")


def _echo_checks(analysis: StatisticalContactAnalysis) -> None:
    """The two checks of the surrogates against the measurement, one line each on stderr (also with --json)."""
    sc, wc = analysis.surrogate_check, analysis.window_check
    z = sc.z
    typer.echo(
        f"check: summits ({sc.surrogate}) z count {z['summit_count']:+.1f}, β̄ {z['summit_radius_mean_m']:+.1f}, "
        f"σ_S {z['summit_height_std_m']:+.1f}, max |z| of μ(u) {_num(sc.max_abs_mu_z, '.1f')} (limit "
        f"{sc.limit:.2f}" + (f"; rank test: {sc.global_exceed} of {analysis.ensemble.contact_area_m2.shape[0]} "
                             "realisations as extreme as the map" if sc.global_exceed is not None else "")
        + f") → {_summit_verdict(analysis)[0]}", err=True)
    if wc is None:
        typer.echo("check: measured windows not checked (too few summits for 2 x 2 windows)", err=True)
    else:
        typer.echo(f"check: measured windows, in sample ({wc.measured_windows}) max |z| {wc.max_abs_z:.2f} (threshold "
                   f"{wc.threshold:.2f}) → {'pass' if wc.consistent else 'FAIL'} (information; the gate uses the "
                   "held-out test)", err=True)
    ho = analysis.holdout
    if ho is not None:
        typer.echo(f"check: held out ({ho.method}, {ho.realizations} surrogates per fold) max |z| "
                   f"{_num(ho.max_abs_z, '.2f')} (threshold {_num(ho.threshold, '.2f')}; detects a scatter ratio ≥ "
                   f"{_num(ho.detectable_scatter_ratio, '.2g')}) → {ho.verdict}", err=True)


@contextlib.contextmanager
def _progress(*, show: bool) -> Iterator[Callable[[str, int, int], None] | None]:
    """A rich progress display on stderr (one bar per stage) and its callback; None without ``show``."""
    if not show:
        yield None
        return
    with Progress(
        TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
        TimeRemainingColumn(), console=Console(stderr=True), transient=True,
    ) as prog:  # fmt: skip
        tasks: dict[str, Any] = {}

        def report(stage: str, done: int, total: int) -> None:
            if stage not in tasks:
                tasks[stage] = prog.add_task(stage, total=total)
            prog.update(tasks[stage], completed=done)

        yield report


def _num(v: Any, fmt: str) -> str:
    return "n/a" if v is None or not math.isfinite(float(v)) else format(float(v), fmt)


def _print(run: ScanAnalysis, written: dict[str, Any]) -> None:
    """The analysis as text (stdout), from the result objects; ``written``: the files, as in the JSON."""
    um = MICROMETRE
    analysis = run.analysis
    cfg = analysis.config
    files = [str(s.path) for s in run.pooled.scans]
    typer.echo(f"surface   {' + '.join(files)}  seed={analysis.seed_entropy}")
    typer.echo(f"surrogate {analysis.surrogate_choice}")
    typer.echo(
        f"ensemble  {cfg.realizations} realisations; path: {cfg.long_surfaces} long surfaces × "
        f"{analysis.path.samples.mu.shape[1]} windows, a_y = {analysis.path.window_shift_m / um:.4g} µm"
    )
    used = analysis.fits["mu_mean"].used
    typer.echo(f"{'u [µm]':>8} {'p [MPa]':>9} {'Ac/Anom':>9} {'E[μ]':>7} {'σ_μ':>7} {'ℓ_corr ± SE [µm]':>18} "
               f"{'E[S] [m]':>10} {'fit':>4}")
    u = analysis.ensemble.approach_m
    for k in range(len(analysis.pressure_pa)):
        typer.echo(
            f"{u[k] / um:8.4g} {analysis.pressure_pa[k] / 1e6:9.4g} "
            f"{analysis.area_fraction[k]:9.3g} {analysis.mu_mean[k]:7.4f} {analysis.mu_std[k]:7.4f} "
            f"{_num(analysis.correlation_length_m[k] / um, '.4g'):>9} ± "
            f"{_num(analysis.correlation_length_se_m[k] / um, '<6.2g')} {analysis.psd_level[k]:10.3g} "
            f"{'yes' if used[k] else 'no':>4}"
        )
    ci = np.asarray(analysis.correlation_length_ci95_m)
    typer.echo(f"ℓ_corr    95 % interval over {analysis.path.samples.mu.shape[0]} long surfaces [µm]: "
               + " ".join(f"[{_num(lo / um, '.3g')}, {_num(hi / um, '.3g')}]" for lo, hi in ci))
    for key, label in (("mu_mean", "E[μ]"), ("mu_std", "σ_μ"), ("psd_level", "E[S]")):
        f = analysis.fits[key]
        typer.echo(
            f"fit {label:<5} a = {f.a:.5g} ± {_num(f.a_se, '.2g')}, b = {f.b:.4g} ± "
            f"{_num(f.b_se, '.2g')}, c = {f.c:.5g} ± {_num(f.c_se, '.2g')} ({f.n_points} points)"
        )
    _print_checks(analysis)
    _print_contact_models(run)
    for key in ("model_file", "statistics_file", "contact_models_file"):
        if key in written:
            typer.echo(f"wrote     {written[key]}")
    for f in written.get("figures", []):
        typer.echo(f"figure    {f}")
    for n in analysis.notes:
        typer.echo(f"note      {n}")
    cr = analysis.credibility
    typer.echo("verdict   " + ("credible" if cr.credible else f"{cr.status.upper()}: " + ", ".join(cr.codes())))


def _print_contact_models(run: ScanAnalysis) -> None:
    """E[μ] of every contact model at the fitted pressures, the GW/BEM ratio, the uncertainty split and the
    model the written file takes (nothing with GW alone)."""
    spread = run.contact_models
    if spread is None:
        return
    stats = {m: spread.surrogate_statistics(m)["mu_mean"] for m in spread.models}
    split = spread.uncertainty_split()
    ratio = spread.ratio("gw", "bem")
    grid = split["discretisation_half_width"]
    typer.echo(f"contact models ({spread.realizations} surrogates, load control): "
               + "   ".join(f"{m}" for m in spread.models)
               + ("   gw/bem" if ratio is not None else "") + "   ±sampling ±model"
               + ("" if grid is None else " ±grid (BEM: corrected area vs pixel count)"))
    for k, p in enumerate(spread.pressure_pa):
        typer.echo(f"  p = {p / 1e6:8.4g} MPa  " + "  ".join(f"{stats[m][k]:.4f}" for m in spread.models)
                   + (f"  {ratio[k]:.3f}" if ratio is not None else "")
                   + f"  {split['sampling_half_width'][k]:.3f} {split['model_half_width'][k]:.3f}"
                   + ("" if grid is None else f" {grid[k]:.3f}"))
    typer.echo(f"contact   plasticity index {_num(spread.plasticity_index, '.3g')}: {spread.recommendation}")
    typer.echo(f"contact   the model file's E[μ](p), σ_μ(p): {run.model.contact_model}"
               + (" (spectrum shape from GW, level scaled)" if run.model.contact_model != "gw" else ""))


def _print_checks(analysis: StatisticalContactAnalysis) -> None:
    """The checks as text: surrogates against the map, measured windows, copies, scans, ergodicity,
    σ_ζ by both rules and the process check."""
    um = MICROMETRE
    sc = analysis.surrogate_check
    zs, me, em, es = sc.z, sc.measured, sc.ensemble_mean, sc.ensemble_std
    typer.echo(
        f"surrogates vs measured map ({sc.surrogate}, amplitude {sc.amplitude}): summits "
        f"{me['summit_count']:.0f} vs {em['summit_count']:.0f} ± {es['summit_count']:.0f} "
        f"(z {zs['summit_count']:+.1f}), "
        f"β̄ {me['summit_radius_mean_m'] / um:.3g} vs {em['summit_radius_mean_m'] / um:.3g} ± "
        f"{es['summit_radius_mean_m'] / um:.2g} µm (z {zs['summit_radius_mean_m']:+.1f}), σ_S "
        f"{me['summit_height_std_m'] / um:.4g} vs {em['summit_height_std_m'] / um:.4g} ± "
        f"{es['summit_height_std_m'] / um:.2g} µm (z {zs['summit_height_std_m']:+.1f}), max |z| of μ(u) "
        f"{_num(sc.max_abs_mu_z, '.1f')} → {_summit_verdict(analysis)[1]}"
    )
    wc = analysis.window_check
    if wc is None:
        typer.echo("measured windows: not checked (too few summits for 2 × 2 windows)")
    else:
        k = int(np.argmax(np.abs(wc.z)))
        typer.echo(
            f"measured windows ({wc.measured_windows} of {wc.window_size_m[0] / um:.4g} × "
            f"{wc.window_size_m[1] / um:.4g} µm vs {wc.surrogate_windows} surrogate windows): sd of μ at "
            f"u_{k} {wc.measured_std[k]:.3g} [{wc.measured_std_ci95[k][0]:.3g}, "
            f"{wc.measured_std_ci95[k][1]:.3g}] "
            f"vs {wc.surrogate_std[k]:.3g}; max |z| {wc.max_abs_z:.2f} (threshold {wc.threshold:.2f}) → "
            f"{wc.verdict}"
        )
    cc = analysis.copy_check
    if cc is not None:
        piece = cc.largest_piece_fraction
        typer.echo(
            f"new surfaces? {cc.surrogates} surrogates: largest NCC with the map {_num(cc.max_ncc_with_map, '.2f')}, "
            f"between surrogates {_num(cc.max_ncc_between_surrogates, '.2f')} (limit {cc.ncc_limit:g})"
            + (f", largest verbatim piece {100 * piece:.2g} % of the map (limit {100 * cc.piece_limit:g} %)"
               if piece else "")
            + f" → {'COPY' if cc.is_copy else 'new'}"
        )
        if cc.verbatim is not None:
            typer.echo(f"verbatim  {cc.verbatim.summary()}")
    _print_evidence(analysis)
    bs = analysis.between_scans
    if bs is not None:
        typer.echo(f"one surface? {analysis.scan_scatter.scans} scans, random-effects test of μ over their windows: "
                   f"{bs.verdict}")
    ss = analysis.scan_scatter
    if ss.scans > 1:
        typer.echo(f"scans     {ss.scans} pooled; sd of μ(u): between scans "
                   + " ".join(_num(v, ".3g") for v in ss.between_scan_std)
                   + "; within a scan (windows) " + " ".join(_num(v, ".3g") for v in ss.within_scan_window_std))
    erg = analysis.ergodicity
    typer.echo(
        f"ergodicity ({erg.surfaces} long surfaces × {erg.windows_per_surface} windows): max |z| = "
        f"{erg.max_abs_z:.2f} (threshold {erg.threshold:.2f}) → {erg.verdict}"
    )
    sz = analysis.sigma_zeta_table()
    typer.echo("σ_ζ       p [MPa]: " + " ".join(f"{p / 1e6:.3g}" for p in sz["pressure_pa"]))
    typer.echo("  sigma_mu       : " + " ".join(_num(v, ".3g") for v in sz["sigma_mu"]))
    typer.echo("  spectral_level : " + " ".join(_num(v, ".3g") for v in sz["spectral_level"]))
    typer.echo(f"process check: generated σ within {analysis.process_check.max_std_z():.2f} standard errors of "
               "the target")


def _print_evidence(analysis: StatisticalContactAnalysis) -> None:
    """What rests on the measurement: μ over its disjoint windows with intervals, and the surrogate model
    tested on held-out halves with the test's power."""
    um = MICROMETRE
    mw = analysis.measured_windows
    if mw is None:
        typer.echo("measured  too few summits for 2 × 2 windows: no number rests on the measurement's windows")
    else:
        typer.echo(
            f"measured  {mw.windows} windows of {mw.window_size_m[0] / um:.4g} × {mw.window_size_m[1] / um:.4g} µm "
            f"(measurement only; effective windows {_num(float(np.min(mw.effective_windows)), '.3g')}–"
            f"{_num(float(np.max(mw.effective_windows)), '.3g')}): E[μ] "
            + " ".join(f"{m:.3g} [{lo:.3g}, {hi:.3g}]" for m, (lo, hi) in zip(mw.mu_mean, mw.mu_mean_ci95, strict=True))
        )
        typer.echo("          σ_μ over those windows " + " ".join(
            f"{s:.3g} [{lo:.3g}, {hi:.3g}]" for s, (lo, hi) in zip(mw.mu_std, mw.mu_std_ci95, strict=True)))
    mi = analysis.model_intervals
    if mi is not None:
        what = " and surface sampling)" if mi.includes_sampling else " only: no measured windows)"
        typer.echo(f"model     E[μ] (95 % interval: Monte Carlo{what} " + " ".join(
            f"{m:.3g} [{lo:.3g}, {hi:.3g}]" for m, (lo, hi) in zip(mi.mu_mean, mi.mu_mean_ci95, strict=True)))
        typer.echo("          σ_μ " + " ".join(
            f"{s:.3g} [{lo:.3g}, {hi:.3g}]" for s, (lo, hi) in zip(mi.mu_std, mi.mu_std_ci95, strict=True)))
    ho = analysis.holdout
    if ho is not None:
        typer.echo(f"held out  {ho.method} surrogates from one half of the map tested on the other (2 folds, "
                   f"{ho.held_out_windows} windows per fold, {ho.realizations} surrogates per fold): {ho.verdict} — "
                   f"{ho.reason}")
        if ho.tests:
            typer.echo(f"          power: detects a scatter ratio of μ ≥ {_num(ho.detectable_scatter_ratio, '.2g')} "
                       f"and a mean shift ≥ {_num(ho.detectable_mean_shift_sd, '.2g')} sd of the window mean with "
                       f"80 % probability (family-wise false alarms {ho.alpha:.0%})")


def register(app: typer.Typer) -> None:
    """Add the ``friction-process`` command to ``app``."""
    app.command("friction-process")(friction_process_command)

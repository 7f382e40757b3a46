"""Command ``friction-process``: statistical contact analysis → friction-process model.

Parse, call, print (no physics): the work is :func:`stochfric.process.statistics.analyse`.
``register(app)`` adds the command to a :class:`typer.Typer` application.  Lengths on the
command line are in µm; everything inside and in the JSON is SI.  Bad input ends with one line
``error: …`` on stderr and exit status 2.
"""

from __future__ import annotations

import json
import math
from enum import StrEnum
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import numpy.typing as npt
import typer
from rich.console import Console
from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn

from stochfric.cli.options import (
    GROUP,
    AmplitudeChoice,
    SurrogateChoice,
    fail,
    option_group,
    write_failed,
)
from stochfric.cli.surface import (
    SurfaceOptions,
    _echo_warnings,
    _surface_warnings,
    parse_approach_um,
    surface_options,
)
from stochfric.contact.asperity import ContactError, default_approach_m
from stochfric.contact.materials import MaterialError, load_material, material_names
from stochfric.friction_process.model_base import SigmaZetaRule
from stochfric.friction_process.tabulated import PressureRule, VarianceRule
from stochfric.io_utils import check_output_path
from stochfric.process.checks import WINDOW_TILES
from stochfric.process.credibility import NOT_CREDIBLE_EXIT
from stochfric.process.ensemble import default_window_shift_points
from stochfric.process.figures import plot_surrogates, write_process_figures
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION
from stochfric.process.memory import iaaft_cost_seconds
from stochfric.process.statistics import AnalysisConfig, StatisticalContactAnalysis, analyse
from stochfric.surface.grid import crop_surface, resample_surface
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.quilting import quilt_applicable, quilt_heights
from stochfric.surface.summits import summits_of
from stochfric.surface.synthesis import iaaft_heights, random_phase_heights
from stochfric.units import MICROMETRE

__all__ = ["register"]

_INPUT_ERRORS = (SurfaceError, ContactError, MaterialError)


ApproachRuleChoice = StrEnum("ApproachRuleChoice", "contacts sigma")  # contact.asperity.APPROACH_RULES

MODEL_FILE = "friction_process.json"
STATISTICS_FILE = "friction_process_statistics.nc"


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
    material: Annotated[
        str,
        typer.Option("--material", help=f"Pairing: {', '.join(material_names())} or a JSON file (SI units)."),
    ],
    files: FilesArg = None,
    realizations: Annotated[int, typer.Option("--realizations", help="Similar surfaces of original size (§4a).")] = 100,
    long_surfaces: Annotated[
        int, typer.Option("--long-surfaces", help="Long surfaces for μ along the path (§4c).")
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
        ApproachRuleChoice,
        typer.Option("--approach-rule", help="Default approach range: contacts (from 20 touching summits to "
                     "A_c/A_nom = --max-area-fraction or half the summits touching) or sigma (σ_S/4 … 3σ_S, "
                     "stretched to the highest summit; used by reproduce)."),
    ] = ApproachRuleChoice.contacts,
    surrogate: Annotated[
        SurrogateChoice,
        typer.Option("--surrogate", help="auto (quilt where the map holds enough summits for patches of 16 summit "
                     "spacings, 3 along the shorter side; phase otherwise), phase (thesis, Gaussian field), iaaft "
                     "(Gaussian phases, measured heights) or quilt (pieces of the measurement with repaired seams: "
                     "keeps local non-Gaussian structure)."),
    ] = SurrogateChoice.auto,
    window_tiles: Annotated[
        int, typer.Option("--window-tiles", help="Measured-window check: at most N × N disjoint windows per scan "
                          "(fewer when a window would hold < 40 summits).")
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
        AmplitudeChoice,
        typer.Option("--amplitude", help="Amplitude estimate of the measured map: tukey (default) or hann "
                     "(edge jump removed, variance restored) or raw (the thesis's DFT of the non-periodic map)."),
    ] = AmplitudeChoice.tukey,
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
    seed: Annotated[int | None, typer.Option("--seed", min=0, help="Root seed (recorded).")] = None,
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
        _check_out(out, plot=plot)
        mat = load_material(material)
        approach = parse_approach_um(approach_um) if approach_um is not None else None
        scans, records, warnings = _load_scans(files, surf, resample=resample)
        u = _approach(scans, surf.summit_rule, approach, approach_rule, max_area_fraction)
        cfg = AnalysisConfig(
            realizations=realizations, long_surfaces=long_surfaces, length_factor=length_factor,
            window_shift_points=_window_shift_points(scans[0], window_shift_um, length_factor),
            surrogate=surrogate.value, amplitude=amplitude.value, summit_rule=surf.summit_rule,
            max_area_fraction=max_area_fraction, pressure_rule=pressure_rule, variance_rule=variance_rule,
            sigma_zeta_rule=sigma_zeta_rule, window_tiles=window_tiles, seed=seed,
        )  # fmt: skip
        if not as_json:
            _announce_cost(scans[0], cfg)
        if workers is not None and workers < 1:
            raise ContactError(f"--workers must be >= 1, got {workers}")
        name = "+".join(Path(r["file"]).stem for r in records)
        analysis = _run(scans, mat, u, cfg, name, show_progress=not as_json, workers=workers)
        payload = _payload(analysis, warnings, records, approach_rule.value if approach is None else "explicit")
        payload.update(_write(analysis, out, plot=plot, model=analysis.credibility.credible or accept_not_credible,
                              heights=scans[0].heights_m, seed=seed))
    except (*_INPUT_ERRORS, ValueError) as exc:  # ValueError: e.g. a fit without enough points
        raise fail(str(exc)) from None
    except OSError as exc:  # disk full while writing: the previous files stay intact
        raise write_failed(exc) from None
    _echo_warnings(payload["warnings"])
    _echo_checks(payload)
    if as_json:
        typer.echo(json.dumps(_clean(payload), indent=1, allow_nan=False))
    else:
        _print(payload, analysis)
    _gate(analysis, accept_not_credible=accept_not_credible)


def _payload(
    analysis: StatisticalContactAnalysis, warnings: list[dict[str, Any]], records: list[dict[str, Any]],
    approach_rule: str,
) -> dict[str, Any]:
    """The JSON summary: the analysis's, with the reading's and the gate's warnings, the preparation
    record(s) and the approach rule."""
    payload = analysis.to_json_dict()
    payload["warnings"] = warnings + payload["warnings"] + [r.to_dict() for r in analysis.credibility.reasons]
    payload["preparation"] = records[0] if len(records) == 1 else {"scans": records}
    payload["approach_rule"] = approach_rule
    return payload


def _approach(
    scans: list[Surface], rule: str, approach: npt.NDArray[np.float64] | None, approach_rule: ApproachRuleChoice,
    max_area_fraction: float,
) -> npt.NDArray[np.float64]:
    """The approaches u [m]: ``approach`` or the default range by ``approach_rule`` on the scan with
    the fewest summits (at least 2 needed)."""
    summit_sets = [summits_of(s, rule=rule) for s in scans]
    fewest = min(summit_sets, key=lambda x: x.count)
    if fewest.count < 2:
        raise ContactError(f"the prepared surface has {fewest.count} summit(s); at least 2 are needed")
    if approach is not None:
        return approach
    return default_approach_m(fewest, rule=approach_rule.value, max_area_fraction=max_area_fraction)


def _window_shift_points(surface: Surface, window_shift_um: float | None, length_factor: int) -> int:
    """a_y in grid points of y (default: the thesis's 0.3 of 5.3 mm of the window length); at least
    two windows must fit on a long surface."""
    ny = surface.nb_grid_pts[1]
    if window_shift_um is None:
        shift = default_window_shift_points(ny)
    else:
        if not (math.isfinite(window_shift_um) and window_shift_um > 0):
            raise ContactError(f"--window-shift-um must be > 0, got {window_shift_um!r}")
        shift = max(1, round(window_shift_um * MICROMETRE / surface.grid_spacing_m[1]))
    if shift >= ny * length_factor - ny:
        raise ContactError(
            f"the window shift ({shift} points) leaves fewer than two windows on a long surface of "
            f"{length_factor} × {ny} points; use a smaller --window-shift-um or a larger --length-factor"
        )
    return shift


def _check_out(out: Path | None, *, plot: bool) -> None:
    """Before any work: ``--plot`` needs ``--out``; a file or an unwritable place ends the command now."""
    if plot and out is None:
        raise ContactError("--plot writes into the output directory: give --out DIR")
    if out is not None:
        check_output_path(out, option="--out")


def _write(
    analysis: StatisticalContactAnalysis, out: Path | None, *, plot: bool, model: bool,
    heights: npt.NDArray[np.float64], seed: int | None,
) -> dict[str, Any]:
    """Write the model file (when ``model``), the statistics NetCDF and with ``plot`` the figures into
    ``out`` (nothing without ``out``); their paths, keyed as in the JSON."""
    written: dict[str, Any] = {}
    if out is None:
        return written
    if model:
        written["model_file"] = str(analysis.model.save(_mkdir(out) / MODEL_FILE))
    written["statistics_file"] = str(analysis.to_netcdf(_mkdir(out) / STATISTICS_FILE))
    if plot:
        written["figures"] = [str(p) for p in _figures(analysis, heights, out / "figures", seed)]
    return written


def _gate(analysis: StatisticalContactAnalysis, *, accept_not_credible: bool) -> None:
    """A not-credible analysis: a warning when it was accepted, else one line and exit status 3."""
    if analysis.credibility.credible:
        return
    if accept_not_credible:
        typer.echo("warning: [not-credible-accepted] the model was written with --accept-not-credible and is "
                   "stamped so; simulate and the studies warn when they read it", err=True)
        return
    typer.echo(
        f"error: not credible ({', '.join(analysis.credibility.codes())}): no model file written; fix the "
        "cause named above, or give --accept-not-credible to write a stamped model", err=True)
    raise typer.Exit(code=NOT_CREDIBLE_EXIT)


def _echo_checks(payload: dict[str, Any]) -> None:
    """The two checks of the surrogates against the measurement, one line each on stderr (also with --json)."""
    sc, wc = payload["surrogate_check"], payload["window_check"]
    z = sc["z"]
    typer.echo(
        f"check: summits ({sc['surrogate']}) z count {z['summit_count']:+.1f}, β̄ {z['summit_radius_mean_m']:+.1f}, "
        f"σ_S {z['summit_height_std_m']:+.1f}, max |z| of μ(u) {_num(sc['max_abs_mu_z'], '.1f')} (limit "
        f"{sc['limit']:g}) → {'pass' if sc['credible'] else 'FAIL'}", err=True)
    if wc is None:
        typer.echo("check: measured windows not checked (too few summits for 2 x 2 windows)", err=True)
    else:
        typer.echo(f"check: measured windows ({wc['measured_windows']}) max |z| {wc['max_abs_z']:.2f} (threshold "
                   f"{wc['threshold']:.2f}) → {'pass' if wc['consistent'] else 'FAIL'}", err=True)


def _load_scans(
    files: list[Path] | None, surf: SurfaceOptions, *, resample: bool
) -> tuple[list[Surface], list[dict[str, Any]], list[dict[str, Any]]]:
    """Read and prepare every scan; one grid for all (resampled to the coarsest pixel size with
    ``resample``, then cropped to the common size, both reported); the warnings of all scans."""
    paths: list[Path | None] = list(files) if files else [None]
    scans, records, warnings = [], [], []
    for path in paths:
        raw, _fine, coarse, _fs, _cs, record = surf.load(path)
        scans.append(coarse)
        records.append(record)
        seen = set()
        for w in _surface_warnings(raw) + [dict(x) for x in coarse.info.get("warnings", [])]:
            if w["message"] not in seen:
                seen.add(w["message"])
                warnings.append(w)
    if len(scans) == 1:
        return scans, records, warnings
    spacings = [s.grid_spacing_m for s in scans]
    if any(not np.allclose(sp, spacings[0], rtol=1e-6, atol=0.0) for sp in spacings):
        if not resample:
            listing = ", ".join(f"{Path(r['file']).name}: {sp[0] * 1e6:.4g}×{sp[1] * 1e6:.4g} µm"
                                for r, sp in zip(records, spacings, strict=True))
            raise SurfaceError(f"pooled scans need one pixel size ({listing}); give --resample to resample them "
                               "to the coarsest, or prepare them with --step so that they match")
        target = (max(sp[0] for sp in spacings), max(sp[1] for sp in spacings))
        scans = [resample_surface(s, target) for s in scans]
        for r in records:
            r["resampled_to_m"] = list(target)
    shape = (min(s.nb_grid_pts[0] for s in scans), min(s.nb_grid_pts[1] for s in scans))
    if any(s.nb_grid_pts != shape for s in scans):
        scans = [crop_surface(s, shape) for s in scans]
        for r in records:
            r["cropped_to"] = list(shape)
    return scans, records, warnings


def _announce_cost(surface: Surface, cfg: AnalysisConfig) -> None:
    """Say before the work what an expensive surrogate method will cost (stderr)."""
    if cfg.surrogate != "iaaft":
        return
    seconds = iaaft_cost_seconds(surface.nb_grid_pts, cfg.realizations, cfg.long_surfaces, cfg.length_factor)
    typer.echo(f"note: IAAFT surrogates iterate FFTs until the spectrum settles: about {seconds:.0f} s for "
               f"{cfg.realizations} maps and {cfg.long_surfaces} long surfaces of this grid (estimate)", err=True)


def _mkdir(path: Path) -> Path:
    path.mkdir(parents=True, exist_ok=True)
    return path


def _run(scans: Any, mat: Any, u: Any, cfg: Any, name: str, *, show_progress: bool, workers: int | None) -> Any:
    if not show_progress:
        return analyse(scans, mat, u, cfg, name=name, workers=workers)
    with Progress(
        TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
        TimeRemainingColumn(), console=Console(stderr=True), transient=True,
    ) as prog:  # fmt: skip
        tasks: dict[str, Any] = {}

        def report(stage: str, done: int, total: int) -> None:
            if stage not in tasks:
                tasks[stage] = prog.add_task(stage, total=total)
            prog.update(tasks[stage], completed=done)

        return analyse(scans, mat, u, cfg, name=name, progress=report, workers=workers)


def _figures(analysis: Any, heights: Any, directory: Path, seed: int | None) -> list[Path]:
    paths = write_process_figures(analysis, directory)
    amp = analysis.config.amplitude
    sur = {
        "phase": random_phase_heights(heights, seed, amplitude=amp),
        "iaaft": iaaft_heights(heights, seed, tol=1e-3, amplitude=amp).heights,
    }
    if quilt_applicable(heights, rule=analysis.config.summit_rule)[0]:
        sur["quilt"] = quilt_heights(heights, seed).heights
    paths.append(plot_surrogates(heights, sur, directory / "surrogates.png"))
    return paths


def _clean(obj: Any) -> Any:
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_clean(v) for v in obj]
    if isinstance(obj, float | np.floating):
        return float(obj) if math.isfinite(float(obj)) else None
    if isinstance(obj, np.integer):
        return int(obj)
    return obj


def _num(v: Any, fmt: str) -> str:
    return "n/a" if v is None or not math.isfinite(float(v)) else format(float(v), fmt)


def _print(payload: dict[str, Any], analysis: Any) -> None:
    um = MICROMETRE
    cfg = analysis.config
    files = [payload["preparation"]["file"]] if "file" in payload["preparation"] else [
        r["file"] for r in payload["preparation"]["scans"]]
    typer.echo(f"surface   {' + '.join(files)}  seed={payload['seed_entropy']}")
    typer.echo(f"surrogate {analysis.surrogate_choice}")
    typer.echo(
        f"ensemble  {cfg.realizations} realisations; path: {cfg.long_surfaces} long surfaces × "
        f"{analysis.path.samples.mu.shape[1]} windows, a_y = {analysis.path.window_shift_m / um:.4g} µm"
    )
    used = analysis.fits["mu_mean"].used
    typer.echo(f"{'u [µm]':>8} {'p [MPa]':>9} {'Ac/Anom':>9} {'E[μ]':>7} {'σ_μ':>7} {'ℓ_corr ± SE [µm]':>18} "
               f"{'E[S] [m]':>10} {'fit':>4}")
    for k in range(len(payload["pressure_pa"])):
        typer.echo(
            f"{payload['approach_m'][k] / um:8.4g} {payload['pressure_pa'][k] / 1e6:9.4g} "
            f"{payload['area_fraction'][k]:9.3g} {payload['mu_mean'][k]:7.4f} {payload['mu_std'][k]:7.4f} "
            f"{_num(analysis.correlation_length_m[k] / um, '.4g'):>9} ± "
            f"{_num(analysis.correlation_length_se_m[k] / um, '<6.2g')} {payload['psd_level_m'][k]:10.3g} "
            f"{'yes' if used[k] else 'no':>4}"
        )
    ci = payload.get("correlation_length_ci95_m") or []
    typer.echo(f"ℓ_corr    95 % interval over {payload.get('correlation_length_surfaces', '?')} long surfaces [µm]: "
               + " ".join(f"[{_num(lo / um if lo is not None else None, '.3g')}, "
                          f"{_num(hi / um if hi is not None else None, '.3g')}]" for lo, hi in ci))
    for key, label in (("mu_mean", "E[μ]"), ("mu_std", "σ_μ"), ("psd_level", "E[S]")):
        f = payload["fit"][key]
        typer.echo(
            f"fit {label:<5} a = {f['a']:.5g} ± {_num(f['a_se'], '.2g')}, b = {f['b']:.4g} ± "
            f"{_num(f['b_se'], '.2g')}, c = {f['c']:.5g} ± {_num(f['c_se'], '.2g')} ({f['n_points']} points)"
        )
    _print_checks(payload)
    for key in ("model_file", "statistics_file"):
        if key in payload:
            typer.echo(f"wrote     {payload[key]}")
    for f in payload.get("figures", []):
        typer.echo(f"figure    {f}")
    for n in payload.get("notes", []):
        typer.echo(f"note      {n}")
    cr = payload["credibility"]
    typer.echo("verdict   " + ("credible" if cr["credible"] else
                               "NOT credible: " + ", ".join(r["code"] for r in cr["reasons"])))


def _print_checks(payload: dict[str, Any]) -> None:
    """The checks of the summary as text: surrogates against the map, measured windows, copies, scans,
    ergodicity, σ_ζ by both rules and the process check."""
    um = MICROMETRE
    sc = payload["surrogate_check"]
    zs = sc["z"]
    me, em, es = sc["measured"], sc["ensemble_mean"], sc["ensemble_std"]
    typer.echo(
        f"surrogates vs measured map ({sc['surrogate']}, amplitude {sc['amplitude']}): summits "
        f"{me['summit_count']:.0f} vs {em['summit_count']:.0f} ± {es['summit_count']:.0f} "
        f"(z {zs['summit_count']:+.1f}), "
        f"β̄ {me['summit_radius_mean_m'] / um:.3g} vs {em['summit_radius_mean_m'] / um:.3g} ± "
        f"{es['summit_radius_mean_m'] / um:.2g} µm (z {zs['summit_radius_mean_m']:+.1f}), σ_S "
        f"{me['summit_height_std_m'] / um:.4g} vs {em['summit_height_std_m'] / um:.4g} ± "
        f"{es['summit_height_std_m'] / um:.2g} µm (z {zs['summit_height_std_m']:+.1f}), max |z| of μ(u) "
        f"{_num(sc['max_abs_mu_z'], '.1f')} → {'credible' if sc['credible'] else 'NOT credible'}"
    )
    wc = payload.get("window_check")
    if wc is None:
        typer.echo("measured windows: not checked (too few summits for 2 × 2 windows)")
    else:
        k = int(np.argmax(np.abs(wc["z"])))
        typer.echo(
            f"measured windows ({wc['measured_windows']} of {wc['window_size_m'][0] / um:.4g} × "
            f"{wc['window_size_m'][1] / um:.4g} µm vs {wc['surrogate_windows']} surrogate windows): sd of μ at "
            f"u_{k} {wc['measured_std'][k]:.3g} [{wc['measured_std_ci95'][k][0]:.3g}, "
            f"{wc['measured_std_ci95'][k][1]:.3g}] "
            f"vs {wc['surrogate_std'][k]:.3g}; max |z| {wc['max_abs_z']:.2f} (threshold {wc['threshold']:.2f}) → "
            f"{wc['verdict']}"
        )
    cc = payload["copy_check"]
    if cc:
        piece = cc["largest_piece_fraction"]
        typer.echo(
            f"new surfaces? {cc['surrogates']} surrogates: largest NCC with the map {cc['max_ncc_with_map']:.2f}, "
            f"between surrogates {_num(cc['max_ncc_between_surrogates'], '.2f')} (limit {cc['ncc_limit']:g})"
            + (f", largest verbatim piece {100 * piece:.2g} % of the map (limit {100 * cc['piece_limit']:g} %)"
               if piece else "")
            + f" → {'COPY' if cc['is_copy'] else 'new'}"
        )
    ss = payload["scan_scatter"]
    if ss["scans"] > 1:
        typer.echo(f"scans     {ss['scans']} pooled; sd of μ(u): between scans "
                   + " ".join(_num(v, ".3g") for v in ss["between_scan_std"])
                   + "; within a scan (windows) " + " ".join(_num(v, ".3g") for v in ss["within_scan_window_std"]))
    erg = payload["ergodicity"]
    typer.echo(
        f"ergodicity ({erg['surfaces']} long surfaces × {erg['windows_per_surface']} windows): max |z| = "
        f"{erg['max_abs_z']:.2f} (threshold {erg['threshold']:.2f}) → {erg['verdict']}"
    )
    sz = payload["sigma_zeta"]
    typer.echo("σ_ζ       p [MPa]: " + " ".join(f"{p / 1e6:.3g}" for p in sz["pressure_pa"]))
    typer.echo("  sigma_mu       : " + " ".join(_num(v, ".3g") for v in sz["sigma_mu"]))
    typer.echo("  spectral_level : " + " ".join(_num(v, ".3g") for v in sz["spectral_level"]))
    pc = payload["process_check"]
    typer.echo(f"process check: generated σ within {pc['max_std_z']:.2f} standard errors of the target")


def register(app: typer.Typer) -> None:
    """Add the ``friction-process`` command to ``app``."""
    app.command("friction-process")(friction_process_command)

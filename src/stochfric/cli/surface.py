"""Command-line commands ``surface`` and ``contact`` (parse, call, print; no physics).

``register(app)`` adds both commands to a :class:`typer.Typer` application.  Units are
converted here, at the edge: lengths on the command line are in µm, everything inside is SI.
Bad input ends with one line ``error: …`` on stderr and exit status 2, never a traceback.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass
from pathlib import Path
from typing import Annotated, Any

import numpy as np
import numpy.typing as npt
import typer

from stochfric.cli.options import GROUP, RegistryChoice, fail, option_group, write_failed
from stochfric.contact.asperity import ContactError, ContactResult
from stochfric.contact.figures import write_contact_figures
from stochfric.contact.materials import Material, load_material, material_names
from stochfric.contact.models import ALIASES, CONTACT_MODELS, ContactProblem, contact_model, contact_model_names
from stochfric.contact.validity import plasticity_validity, result_validity
from stochfric.errors import StochfricError
from stochfric.io_utils import OutputPathError, check_output_path, json_ready, write_json_atomic
from stochfric.surface.figures import write_surface_figures
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.prepare_checks import MAX_UNDEFINED_DEFAULT, OUTLIER_K, OUTLIER_SQ
from stochfric.surface.preprocess import Preparation
from stochfric.surface.scans import PreparedScan, load_scan
from stochfric.surface.statistics import (
    height_moments,
    plasticity_index,
    plasticity_verdict,
    surface_statistics,
)
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, SUMMIT_RULES, Summits
from stochfric.units import MICROMETRE

__all__ = ["parse_approach_um", "parse_size_um", "register"]

#: ``--method``: the contact models of :mod:`stochfric.contact.models`, read when the command runs.
CONTACT_METHOD = RegistryChoice(contact_model_names, ALIASES)


# ------------------------------------------------------------------ parsing helpers


#: Most approaches a command accepts (each costs a pass over the summits and a column in every result).
MAX_APPROACHES = 10_000


def parse_approach_um(spec: str) -> npt.NDArray[np.float64]:
    """``"START:STOP:NUM"`` in µm → ``linspace(START, STOP, NUM)`` in metres."""
    parts = spec.split(":")
    if len(parts) != 3:
        raise ContactError(f"--approach-um must be START:STOP:NUM in µm, got {spec!r}")
    try:
        start, stop = float(parts[0]), float(parts[1])
        num = int(parts[2])
    except ValueError:
        raise ContactError(f"--approach-um must be START:STOP:NUM in µm, got {spec!r}") from None
    if not (math.isfinite(start) and math.isfinite(stop)) or start <= 0 or stop < start:
        raise ContactError(f"--approach-um needs 0 < START <= STOP, got {spec!r}")
    if num < 1:
        raise ContactError(f"--approach-um needs NUM >= 1, got {spec!r}")
    if num > MAX_APPROACHES:
        raise ContactError(f"--approach-um asks for {num} approaches; a μ(u) curve needs tens (the default is 12), "
                           f"at most {MAX_APPROACHES}")
    return np.linspace(start, stop, num) * MICROMETRE


def parse_size_um(spec: str) -> tuple[float, float]:
    """``"LX:LY"`` (or one value for a square) in µm → ``(ℓx, ℓy)`` in metres."""
    parts = spec.split(":")
    try:
        values = [float(p) for p in parts]
    except ValueError:
        raise SurfaceError(f"--size-um must be LX:LY in µm, got {spec!r}") from None
    if len(values) == 1:
        values = values * 2
    if len(values) != 2 or not all(math.isfinite(v) and v > 0 for v in values):
        raise SurfaceError(f"--size-um must be two positive lengths LX:LY in µm, got {spec!r}")
    return values[0] * MICROMETRE, values[1] * MICROMETRE


# ------------------------------------------------------------------ shared pipeline


@dataclass(frozen=True)
class SurfaceOptions:
    """How a height map is read and prepared: the options shared by ``surface``, ``contact`` and
    ``friction-process`` (:func:`surface_options`), validated when the map is loaded."""

    median_radius: int
    step: int
    detrend: str
    fill_undefined: bool
    summit_rule: str
    size_um: str | None
    height_unit: str | None
    cutoff_um: float | None = None
    outliers: bool = True
    outlier_k: float = OUTLIER_K
    outlier_sq: float = OUTLIER_SQ
    quantised: str = "warn"
    max_undefined: float = MAX_UNDEFINED_DEFAULT
    rough_check: bool = True

    def physical_size_m(self) -> tuple[float, float] | None:
        """``--size-um`` in metres (None when not given)."""
        return parse_size_um(self.size_um) if self.size_um is not None else None

    def preparation(self) -> Preparation:
        """Every preparation step (docs/surface_contact.md, "Preparation"); SurfaceError for invalid
        values."""
        cutoff = None if self.cutoff_um is None else float(self.cutoff_um) * MICROMETRE
        return Preparation(detrend=self.detrend, median_radius=self.median_radius, step=self.step, cutoff_m=cutoff,
                           outliers=self.outliers, outlier_k=self.outlier_k, outlier_sq=self.outlier_sq,
                           quantised=self.quantised, max_undefined=self.max_undefined,
                           rough_check=self.rough_check)  # fmt: skip

    def load(self, file: Path | None) -> PreparedScan:
        """Read ``file`` (default: the shipped surface), prepare it and find the summits
        (:func:`stochfric.surface.scans.load_scan`)."""
        return _load_and_prepare(file, size_um=self.size_um, height_unit=self.height_unit,
                                 fill_undefined=self.fill_undefined, preparation=self.preparation(),
                                 summit_rule=self.summit_rule)


def _load_and_prepare(
    file: Path | None,
    *,
    size_um: str | None,
    height_unit: str | None,
    fill_undefined: bool,
    preparation: Preparation,
    summit_rule: str,
) -> PreparedScan:
    size = parse_size_um(size_um) if size_um is not None else None
    return load_scan(file, preparation=preparation, summit_rule=summit_rule, physical_size_m=size,
                     height_unit=height_unit, fill_undefined=fill_undefined)


def _gamma(material: Material, stats: dict[str, Any]) -> float | None:
    sigma, beta = stats["summit_height_std_m"], stats["summit_radius_mean_m"]
    if sigma is None or beta is None:
        return None
    return plasticity_index(
        e_star_pa=material.e_star_pa,
        hardness_pa=material.hardness,
        sigma_s_m=sigma,
        beta_mean_m=beta,
    )


def _echo_result(payload: dict[str, Any], as_json: bool) -> bool:
    """The warnings on stderr, then with ``as_json`` the payload as JSON; True when that was all."""
    _echo_warnings(payload["warnings"])
    if as_json:
        typer.echo(json.dumps(payload, indent=2, allow_nan=False))
    return as_json


def _surface_warnings(raw: Surface) -> list[dict[str, Any]]:
    return [dict(w) for w in raw.info.get("warnings", [])]


def _echo_warnings(items: list[dict[str, Any]]) -> None:
    """One line ``warning: [code] message`` per warning on stderr."""
    for w in items:
        typer.echo(f"warning: [{w['code']}] {w['message']}", err=True)


def _summit_gamma(material: Material, summits: Summits) -> float | None:
    if summits.count < 2:
        return None
    beta = float(np.mean(summits.radius_m))
    sigma = float(np.std(summits.heights_m))
    if not (sigma > 0.0 and beta > 0.0):
        return None
    return plasticity_index(
        e_star_pa=material.e_star_pa, hardness_pa=material.hardness, sigma_s_m=sigma, beta_mean_m=beta
    )


# ------------------------------------------------------------------ options

FileArg = Annotated[
    Path | None,
    typer.Argument(
        help="Height map: an instrument file SurfaceTopography reads (x3p, sur, opd, datx, "
        "plu, mnt, al3d, frt, …) or a .npy/.txt/.csv matrix (then --size-um and "
        "--height-unit are required). Default: the measured surface shipped with the package.",
        show_default=False,
    ),
]
MedianOpt = Annotated[int, typer.Option("--median-radius", help="Median filter radius r, window (2r+1)²; 0 = off.")]
StepOpt = Annotated[int, typer.Option("--step", help="Coarsening: keep every k-th point; 1 = off.")]
DetrendOpt = Annotated[
    str,
    typer.Option(
        "--detrend",
        help="Form removal: auto (default: plane, raised to quadratic, poly3 while the next degree removes "
        "more than 25 % of the remaining variance) | none | mean | plane | quadratic | poly3 | gaussian | "
        "robust-gaussian (ISO 16610-61 / -71 L-filter, needs --cutoff-um).",
    ),
]
CutoffOpt = Annotated[
    float | None,
    typer.Option("--cutoff-um", help="Nesting index λc [µm] of the Gaussian L-filter (--detrend gaussian or "
                 "robust-gaussian); between 5 grid spacings and the larger map side."),
]  # fmt: skip
OutliersOpt = Annotated[
    bool,
    typer.Option("--outliers/--no-outliers", help="Replace isolated spikes/pits (|z - 5x5 median| > max(k·σ_r, "
                 "m·S)) by harmonic interpolation; count and positions are reported."),
]  # fmt: skip
OutlierKOpt = Annotated[
    float, typer.Option("--outlier-k", help="Outlier rule: multiple k of the robust residual scale σ_r (>= 3).")
]
OutlierSqOpt = Annotated[
    float, typer.Option("--outlier-sq", help="Outlier rule: multiple m of the robust height scale S (>= 2).")
]
QuantisedOpt = Annotated[
    str,
    typer.Option("--quantised", help="Quantised heights (more than 2 % tied neighbour pairs): warn (default) | "
                 "dither (add uniform noise of one height quantum)."),
]  # fmt: skip
MaxUndefinedOpt = Annotated[
    float,
    typer.Option("--max-undefined", help="Largest fraction of undefined points filled (0 < F <= 1; default 0.05)."),
]
RoughCheckOpt = Annotated[
    bool,
    typer.Option("--rough-check/--no-rough-check", help="Refuse maps that are no rough surface (a step or "
                 "two-level map, a part outline)."),
]  # fmt: skip
FillOpt = Annotated[
    bool,
    typer.Option("--fill-undefined", help="Fill undefined points by harmonic interpolation (else refuse)."),
]
#: ``--summit-rule``: a rule of the registry (read when the command runs).
SUMMIT_RULE_CHOICE = RegistryChoice(names=lambda: tuple(SUMMIT_RULES))
RuleOpt = Annotated[
    str,
    typer.Option("--summit-rule", parser=SUMMIT_RULE_CHOICE, metavar="RULE",
                 help="; ".join(f"{r.name} ({r.summary})" for r in SUMMIT_RULES.values()) + "."),
]
SizeOpt = Annotated[
    str | None,
    typer.Option("--size-um", help="Physical size LX:LY [µm] for files that do not store it."),
]
UnitOpt = Annotated[
    str | None,
    typer.Option("--height-unit", help="Height unit (m, mm, um, nm) for files without one, optionally with a "
                                       "conversion factor FACTOR*UNIT (2.5e-3*um: each stored value × 2.5e-3 is "
                                       "a height in µm)."),
]


def surface_options(
    median_radius: MedianOpt = 0,
    step: StepOpt = 1,
    detrend: DetrendOpt = "auto",
    fill_undefined: FillOpt = False,
    summit_rule: RuleOpt = DEFAULT_SUMMIT_RULE,
    size_um: SizeOpt = None,
    height_unit: UnitOpt = None,
    cutoff_um: CutoffOpt = None,
    outliers: OutliersOpt = True,
    outlier_k: OutlierKOpt = OUTLIER_K,
    outlier_sq: OutlierSqOpt = OUTLIER_SQ,
    quantised: QuantisedOpt = "warn",
    max_undefined: MaxUndefinedOpt = MAX_UNDEFINED_DEFAULT,
    rough_check: RoughCheckOpt = True,
) -> SurfaceOptions:
    """The reading and preparation options of a command (:func:`~stochfric.cli.options.option_group`)."""
    return SurfaceOptions(median_radius=median_radius, step=step, detrend=detrend, fill_undefined=fill_undefined,
                          summit_rule=summit_rule, size_um=size_um, height_unit=height_unit,
                          cutoff_um=cutoff_um, outliers=outliers, outlier_k=outlier_k, outlier_sq=outlier_sq,
                          quantised=quantised, max_undefined=max_undefined, rough_check=rough_check)


PlotOpt = Annotated[Path | None, typer.Option("--plot", help="Write PNG figures into this directory.")]
#: Files of ``surface --out DIR`` and ``contact --out DIR``.
SURFACE_JSON, CONTACT_JSON, CONTACT_NC = "surface.json", "contact.json", "contact.nc"
OutDirOpt = Annotated[Path | None, typer.Option(
    "--out", help="Output directory: the result (JSON; contact: also NetCDF) and, without --plot, the figures.")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print the result as JSON.")]


_METHOD_HELP = (
    "Contact model: " + "; ".join(f"{m.name} ({m.summary})" for m in CONTACT_MODELS.values())
    + ". The earlier names " + " and ".join(f"{old} (= {new})" for old, new in ALIASES.items())
    + " are accepted; a model registered in stochfric.contact.models is offered too."
)

# ------------------------------------------------------------------ commands


@option_group("surf", surface_options)
def surface_command(
    file: FileArg = None,
    surf: SurfaceOptions = GROUP,
    material: Annotated[
        str | None,
        typer.Option(
            "--material",
            help=f"Pairing for the plasticity index (3.7): {', '.join(material_names())} or a JSON file.",
        ),
    ] = None,
    out: OutDirOpt = None,
    plot: PlotOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """Surface analysis: statistics of the fine and the coarse surface, summits, radii,
    plasticity index (method §1)."""
    try:  # output paths first: an unwritable place ends the command before any work
        if out is not None:
            check_output_path(out, option="--out")
        if plot is not None:
            check_output_path(plot, option="--plot")
    except OutputPathError as exc:
        raise fail(str(exc)) from None
    plot = plot if plot is not None else out
    try:
        prep = surf.preparation()
        mat = load_material(material) if material is not None else None
        scan = surf.load(file)
        raw, fine, coarse, fs, cs, record = (scan.raw, scan.fine, scan.coarse, scan.fine_summits,
                                             scan.coarse_summits, scan.record())
        if cs.count == 0:
            raise SurfaceError(
                f"no summit found on the {coarse.nb_grid_pts[0]}×{coarse.nb_grid_pts[1]} "
                f"prepared surface (rule {surf.summit_rule!r}); use a smaller step or "
                "median radius"
            )
        fine_stats = surface_statistics(fine, fs).to_dict()
        coarse_stats = surface_statistics(coarse, cs).to_dict()
        payload: dict[str, Any] = {
            "file": record["file"],
            "preparation": record,
            **coarse_stats,
            "raw_sq_m": height_moments(raw.heights_m)[0],
            "fine": fine_stats,
            "coarse": coarse_stats,
        }
        warn = _surface_warnings(fine)
        if mat is not None:
            g_coarse = _gamma(mat, coarse_stats)
            g_fine = _gamma(mat, fine_stats)
            payload["material"] = mat.to_dict()
            payload["plasticity_index"] = g_coarse
            payload["plasticity_verdict"] = plasticity_verdict(g_coarse) if g_coarse is not None else None
            payload["plasticity_index_fine"] = g_fine
            if g_coarse is not None:
                warn += [w.to_dict() for w in plasticity_validity(g_coarse, name=Path(record["file"]).name)]
        payload["warnings"] = warn
        figures: list[str] = []
        if plot is not None:
            figures = [
                str(p)
                for p in write_surface_figures(
                    plot, fine=fine, coarse=coarse, fine_summits=fs, coarse_summits=cs, step=surf.step
                )
            ]
            payload["figures"] = figures
        if out is not None:
            payload["output"] = str(out / SURFACE_JSON)
            write_json_atomic(out / SURFACE_JSON, json_ready(payload))
    except StochfricError as exc:
        raise fail(str(exc)) from None
    except OSError as exc:  # disk full while writing a figure or the NetCDF: the previous files stay
        raise write_failed(exc) from None
    if _echo_result(payload, as_json):
        return
    um = MICROMETRE
    typer.echo(f"surface   {record['file']}")
    typer.echo(
        f"prepared  detrend={record['detrend']} median_radius={prep.median_radius} step={prep.step} "
        f"summit_rule={surf.summit_rule} filled={raw.n_undefined_filled}"
    )
    rep = scan.report
    sq_deg = ", ".join(f"{v / um:.4g}" for v in rep.form["sq_by_degree_m"])
    typer.echo(
        f"form      {rep.form['requested']} -> {rep.form['applied']} (Sq after degree 1, 2, 3: {sq_deg} µm); "
        f"outliers replaced {rep.outliers['count']}; tied pairs {100 * rep.quantisation['tie_fraction']:.3g} %; "
        f"undefined {100 * rep.undefined['fraction']:.3g} %"
    )
    for label, st in (("fine", fine_stats), ("coarse", coarse_stats)):
        typer.echo(
            f"{label:<7}   grid {st['grid'][0]}x{st['grid'][1]}, "
            f"size {st['physical_size_m'][0] / um:.4g} x {st['physical_size_m'][1] / um:.4g} µm, "
            f"Sq {st['sq_m'] / um:.4g} µm, summits {st['n_summits']}, "
            f"σ_S {_fmt(st['summit_height_std_m'], um)} µm, "
            f"β̄ {_fmt(st['summit_radius_mean_m'], um)} µm"
        )
    if mat is not None:
        typer.echo(
            f"plasticity index ({mat.name}): γ = {_fmt(payload['plasticity_index'], 1.0)} "
            f"(coarse, {payload['plasticity_verdict']}), "
            f"{_fmt(payload['plasticity_index_fine'], 1.0)} (fine)"
        )
    if "output" in payload:
        typer.echo(f"output    {payload['output']}")
    for f in figures:
        typer.echo(f"figure    {f}")


@option_group("surf", surface_options)
def contact_command(
    material: Annotated[
        str,
        typer.Option(
            "--material",
            help=f"Pairing: {', '.join(material_names())} or a JSON file with the fields of "
            "stochfric.contact.Material (SI units).",
        ),
    ],
    file: FileArg = None,
    approach_um: Annotated[
        str | None,
        typer.Option(
            "--approach-um",
            help="START:STOP:NUM in µm (linspace); default: from 20 touching summits to A_c/A_nom = 0.1 (or half the "
            "summits touching), 12 steps.",
        ),
    ] = None,
    method: Annotated[
        str,
        typer.Option("--method", parser=CONTACT_METHOD, metavar="MODEL", help=_METHOD_HELP),
    ] = "gw",
    bem_refine: Annotated[
        int,
        typer.Option(
            "--bem-refine",
            help="bem: solve on a K-times finer grid (cubic-spline interpolation); 1 = the analysed grid.",
            min=1,
            max=4,
        ),
    ] = 1,
    bem_frame: Annotated[
        int | None,
        typer.Option(
            "--bem-frame",
            help="bem: border frame [points] lowered out of reach; default the summit rule's "
            "margin (2 thesis, 1 8-neighbour).",
            min=0,
        ),
    ] = None,
    surf: SurfaceOptions = GROUP,
    out: OutDirOpt = None,
    output: Annotated[Path | None, typer.Option(
        "--output", hidden=True, help="Deprecated: the NetCDF file (use --out DIR).")] = None,
    plot: PlotOpt = None,
    as_json: JsonOpt = False,
) -> None:
    """Contact analysis over the approach u: A_c, p, contacts, μ (method §2)."""
    try:  # output paths first: an unwritable place ends the command before any work
        if out is not None and output is not None:
            raise fail("give --out DIR (contact.nc and contact.json) or the deprecated --output FILE, not both")
        if output is not None:
            typer.echo("warning [deprecated-option]: --output FILE is deprecated; use --out DIR "
                       f"(writes DIR/{CONTACT_NC} and DIR/{CONTACT_JSON})", err=True)
            check_output_path(output, option="--output", kind="file", suffixes=(".nc",))
        if out is not None:
            check_output_path(out, option="--out")
            output = out / CONTACT_NC
        if plot is not None:
            check_output_path(plot, option="--plot")
    except OutputPathError as exc:
        raise fail(str(exc)) from None
    try:
        mat = load_material(material)
        approach = parse_approach_um(approach_um) if approach_um is not None else None
        scan = surf.load(file)
        fine, coarse, cs, record = scan.fine, scan.coarse, scan.coarse_summits, scan.record()
        record["approach"] = ("given" if approach is not None
                              else "default: contacts rule (20 summits .. A_c/A_nom = 0.1)")
        model = contact_model(method).configured(frame_points=bem_frame, refine=bem_refine)
        problem = ContactProblem(surface=coarse, summits=cs, material=mat, approach_m=approach, preparation=record)
        main = model.contact(problem)
        gw = problem.asperity  # the GW result: the validity checks, and the loads of a load-controlled model
        equal_load = model.control == "load"
        results: list[ContactResult] = [gw] if main is gw else [gw, main]
        payload = main.to_dict()
        if equal_load:
            payload["asperity"] = _equal_load_record(gw, main)
        gamma = _summit_gamma(mat, cs)
        payload["plasticity_index"] = gamma
        payload["warnings"] = _surface_warnings(fine) + [
            w.to_dict() for w in result_validity(gw, plasticity_index=gamma, name=Path(record["file"]).name)
        ]
        if output is not None:
            payload["output"] = str(main.to_netcdf(output))
        plot = plot if plot is not None else out
        if plot is not None:
            payload["figures"] = [str(p) for p in write_contact_figures(plot, results)]
        if out is not None:
            write_json_atomic(out / CONTACT_JSON, json_ready(payload))
    except StochfricError as exc:
        raise fail(str(exc)) from None
    except OSError as exc:  # disk full while writing a figure or the NetCDF: the previous files stay
        raise write_failed(exc) from None
    if _echo_result(payload, as_json):
        return
    typer.echo(f"surface   {record['file']}  ({coarse.nb_grid_pts[0]}x{coarse.nb_grid_pts[1]})")
    _print_contact(payload, mat, gw, main, equal_load=equal_load)


def _equal_load_record(gw: ContactResult, main: ContactResult) -> dict[str, Any]:
    """The GW result beside the half-space at the GW normal forces, and the ratios half-space / GW."""
    gw_dict = gw.to_dict()
    return {
        "comparison": "equal load: the half-space carries the GW normal force",
        "approach_m": gw_dict["approach_m"],
        "contact_area_m2": gw_dict["contact_area_m2"],
        "area_fraction": gw_dict["area_fraction"],
        "pressure_pa": gw_dict["pressure_pa"],
        "n_contacts": [int(v) for v in gw.n_contacts],
        "mu": gw_dict["mu"],
        "area_ratio_halfspace_to_asperity": _ratio(main.contact_area_m2, gw.contact_area_m2),
        "mu_ratio_halfspace_to_asperity": _ratio(main.mu, gw.mu),
        "approach_ratio_halfspace_to_asperity": _ratio(main.approach_m, gw.approach_m),
    }


def _print_contact(
    payload: dict[str, Any], mat: Material, gw: ContactResult, main: ContactResult, *, equal_load: bool
) -> None:
    """The contact result as text (lengths in µm, pressures in MPa): material, one row per approach,
    the equal-load ratios of a load-controlled model (the half-space), the files written."""
    um = MICROMETRE
    typer.echo(
        f"material  {mat.name}: E* = {mat.e_star_pa / 1e9:.4g} GPa, "
        f"τ_max = {mat.shear_strength_pa / 1e6:.4g} MPa; method {main.method}"
        + (" (equal load: u is the half-space's approach at the GW force)" if equal_load else "")
    )
    typer.echo(f"{'u [µm]':>9} {'A_c [m²]':>11} {'A_c/A_nom':>10} {'p [MPa]':>10} {'contacts':>9} {'μ':>7}")
    for k in range(main.approach_m.size):
        typer.echo(
            f"{main.approach_m[k] / um:9.4g} {main.contact_area_m2[k]:11.4g} "
            f"{main.area_fraction[k]:10.4g} {main.pressure_pa[k] / 1e6:10.4g} "
            f"{int(main.n_contacts[k]):9d} {main.mu[k]:7.4g}"
        )
    if equal_load:
        ratio = payload["asperity"]["area_ratio_halfspace_to_asperity"]
        typer.echo("equal load: A_c(BEM)/A_c(GW) = mu(BEM)/mu(GW): " + " ".join(_fmt(r, 1.0) for r in ratio))
        typer.echo("GW mu:  " + " ".join(f"{v:.4g}" for v in gw.mu))
    for key in ("output",):
        if key in payload:
            typer.echo(f"{key:<9} {payload[key]}")
    for f in payload.get("figures", []):
        typer.echo(f"figure    {f}")


def _ratio(a: npt.NDArray[np.float64], b: npt.NDArray[np.float64]) -> list[float | None]:
    with np.errstate(divide="ignore", invalid="ignore"):
        r = a / b
    return [float(v) if math.isfinite(v) else None for v in r]


def _fmt(value: float | None, scale: float) -> str:
    return "n/a" if value is None else f"{value / scale:.4g}"


def register(app: typer.Typer) -> None:
    """Add the ``surface`` and ``contact`` commands to ``app``."""
    app.command("surface")(surface_command)
    app.command("contact")(contact_command)

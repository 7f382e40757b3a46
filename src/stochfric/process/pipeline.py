"""The friction-process pipeline as one library call: scans → prepared, pooled maps → approaches →
statistical contact analysis → model (method §1, §3–§4).

:func:`analyse_scans` is what ``stochfric friction-process FILE...`` does, step by step: read and
prepare every scan (:func:`~stochfric.surface.scans.load_scan`), pool them onto one grid
(:func:`~stochfric.surface.scans.pool_scans`), choose the approaches (:func:`choose_approach`) and the
window shift of μ along the path (:func:`window_shift_points`), run
:func:`~stochfric.process.statistics.analyse`.  It returns a :class:`ScanAnalysis`: the typed result,
its JSON summary (:meth:`ScanAnalysis.to_json_dict`) and its files (:meth:`ScanAnalysis.write`).  The
command line parses, calls this and prints; a Python user calls the same::

    import stochfric as sf
    run = sf.analyse_scans(["spot1.x3p", "spot2.x3p"], "dc04", config=sf.AnalysisConfig(seed=1))
    run.analysis.credibility.credible, run.analysis.model
    run.write("fp", model=run.credible)
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, replace
from pathlib import Path
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import ApproachRule, default_approach_m
from stochfric.contact.materials import Material, get_material, load_material
from stochfric.errors import AnalysisError
from stochfric.friction_process.tabulated import TabulatedProcessModel
from stochfric.io_utils import check_output_path
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.analysis_result import StatisticalContactAnalysis
from stochfric.process.checks import WINDOW_TILES, window_tiles
from stochfric.process.contact_models import (
    ContactModelSpread,
    LoadControl,
    contact_model_spread,
    parse_contact_models,
    process_model_for,
)
from stochfric.process.ensemble import default_window_shift_points, tile_contact
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION
from stochfric.process.pooling import require_summits_for_pooling
from stochfric.process.statistics import analyse
from stochfric.random import as_generator
from stochfric.surface.io import Surface
from stochfric.surface.preprocess import Preparation
from stochfric.surface.scans import PooledScans, load_scan, pool_scans
from stochfric.surface.summits import summits_of
from stochfric.surface.surrogates import SURROGATES, SurrogateSettings

__all__ = [
    "MODEL_FILE",
    "SPREAD_FILE",
    "STATISTICS_FILE",
    "ApproachRule",
    "ScanAnalysis",
    "analyse_scans",
    "cap_on_windows",
    "choose_approach",
    "window_shift_points",
    "write_spread",
]

#: File names of :meth:`ScanAnalysis.write`.
MODEL_FILE = "friction_process.json"
STATISTICS_FILE = "friction_process_statistics.nc"


#: The ``approach_rule`` recorded when the approaches were given explicitly.
EXPLICIT_APPROACH = "explicit"


def choose_approach(
    surfaces: Sequence[Surface], *, summit_rule: str, approach_m: npt.ArrayLike | None = None,
    rule: ApproachRule | str = ApproachRule.CONTACTS, max_area_fraction: float = DEFAULT_MAX_AREA_FRACTION,
    window_tiles_max: int = WINDOW_TILES,
) -> FloatArray:
    """The approaches u [m]: ``approach_m`` when given, else the default range by ``rule`` on the scan
    with the fewest summits (at least 2 are needed on every scan), capped on the analysis's own windows
    (:func:`cap_on_windows`)."""
    summit_sets = [summits_of(s, rule=summit_rule) for s in surfaces]
    fewest = min(summit_sets, key=lambda x: x.count)
    if fewest.count < 2:
        raise AnalysisError(f"the prepared surface has {fewest.count} summit(s); at least 2 are needed")
    if approach_m is not None:
        return np.asarray(approach_m, dtype=np.float64)
    u = default_approach_m(fewest, rule=ApproachRule(rule).value, max_area_fraction=max_area_fraction)
    tiles = window_tiles(fewest.count, window_tiles_max) or 1
    # the contacts rule promises the non-interaction range; the thesis's sigma rule only full contact
    limit = max_area_fraction if ApproachRule(rule) == ApproachRule.CONTACTS else None
    return cap_on_windows(surfaces, u, summit_rule=summit_rule, tiles=tiles, mean_area_fraction=limit)


#: Approaches tried between 0 and the default u_hi when the range is capped on the windows.
CAP_GRID = 256


def cap_on_windows(
    surfaces: Sequence[Surface], u: FloatArray, *, summit_rule: str, tiles: int, mean_area_fraction: float | None,
) -> FloatArray:
    """Cap a default approach range on the windows the analysis evaluates (issue 29, item 7).

    The default rules read the range from the whole map with the flat at its highest summit.  The analysis
    also evaluates the map's disjoint ``tiles × tiles`` windows (measured windows, held-out test), each
    referenced to its *own* highest summit, so at the same u a window is pressed further than the map: on
    the shared files up to A_c/A_nom = 1.6 in one window at the rule's u_hi.  The largest approach kept is
    the largest u at which (a) no such window's GW contact area exceeds its nominal area (A_c/A_nom ≤ 1:
    beyond it the model has no meaning) and (b) the mean A_c/A_nom of the whole scans (the model's
    windows) stays within ``mean_area_fraction`` (the contacts rule's non-interaction limit, which the rule
    already meets on the scan it reads; None: only (a)).  A capped range keeps its number of points: from
    the rule's u_lo to the cap, or from cap/num when the cap lies below u_lo.  An uncapped range is returned
    unchanged."""
    u = np.asarray(u, dtype=np.float64)
    probe = np.linspace(0.0, float(u[-1]), CAP_GRID + 1)[1:]
    mat = get_material("dc04")  # A_c of GW does not depend on E*: any material gives the same areas
    ok = np.ones(probe.size, dtype=bool)
    whole = []
    for s in surfaces:
        z = np.asarray(s.heights_m)
        for t in {tiles, 1}:
            area, _force, _n = tile_contact(z, s.grid_spacing_m, mat, probe, tiles=t, rule=summit_rule)
            frac = np.asarray(area) / (s.physical_size_m[0] * s.physical_size_m[1] / (t * t))
            ok &= frac.max(axis=0) <= 1.0
            if t == 1:
                whole.append(frac[0])
    if mean_area_fraction is not None:
        ok &= np.mean(np.stack(whole), axis=0) <= mean_area_fraction * (1.0 + 1e-9)
    if ok.all():
        return u
    first_bad = int(np.argmin(ok))
    cap = float(probe[first_bad - 1]) if first_bad > 0 else float(probe[0])
    n = u.size
    return np.linspace(float(u[0]), cap, n) if cap > u[0] else np.linspace(cap / n, cap, n)


def window_shift_points(surface: Surface, window_shift_m: float | None, length_factor: int) -> int:
    """a_y in grid points of y: ``window_shift_m`` rounded to whole points, default the thesis's 0.3 of
    5.3 mm of the window length (:func:`~stochfric.process.ensemble.default_window_shift_points`); at
    least two windows must fit on a long surface of ``length_factor`` lengths."""
    ny = surface.nb_grid_pts[1]
    if window_shift_m is None:
        shift = default_window_shift_points(ny)
    else:
        if not (isinstance(window_shift_m, int | float) and math.isfinite(window_shift_m) and window_shift_m > 0):
            raise AnalysisError(f"the window shift must be > 0, got {window_shift_m!r} m")
        shift = max(1, round(window_shift_m / surface.grid_spacing_m[1]))
    if shift >= ny * length_factor - ny:
        raise AnalysisError(
            f"the window shift ({shift} points) leaves fewer than two windows on a long surface of "
            f"{length_factor} × {ny} points; use a smaller --window-shift-um or a larger --length-factor"
        )
    return shift


def notify_cost(surface: Surface, cfg: AnalysisConfig, notify: Callable[[str], None]) -> None:
    """Say before the work what the surrogates of ``cfg`` will cost on this grid, when their method
    estimates it (``"auto"`` resolves to methods that do not), and what they cost if the summit check grows the
    ensemble to its budget (``cfg`` with the budget resolved, :func:`analyse_scans`)."""
    method = SURROGATES.get(cfg.surrogate)
    long_maps = cfg.long_surfaces * cfg.length_factor
    seconds = None if method is None else method.cost_seconds(surface.nb_grid_pts, cfg.realizations + long_maps)
    if method is not None and seconds is not None:
        budget = int(cfg.summit_max_realizations or cfg.realizations)
        grown = method.cost_seconds(surface.nb_grid_pts, budget + long_maps) if budget > cfg.realizations else None
        notify(f"{method.cost_reason}: about {seconds:.0f} s for {cfg.realizations} maps and "
               f"{cfg.long_surfaces} long surfaces of this grid (estimate)"
               + (f"; up to about {grown:.0f} s if the summit check grows the ensemble to its budget of {budget}"
                  if grown is not None else ""))


@dataclass(frozen=True, kw_only=True, eq=False)
class ScanAnalysis:
    """The result of :func:`analyse_scans`: the pooled scans, the analysis, how the approaches were
    chosen, and the warnings of reading and preparing the scans."""

    pooled: PooledScans
    analysis: StatisticalContactAnalysis
    #: ``"contacts"``, ``"sigma"`` or ``"explicit"``.
    approach_rule: str
    #: The reading's and the preparation's coded warnings (``{"code", "message"}``).
    scan_warnings: list[dict[str, Any]]
    #: The contact models solved on the same windows and surrogates at the analysis's pressures
    #: (``contact_model`` other than ``gw``; :mod:`~stochfric.process.contact_models`), else None.
    contact_models: ContactModelSpread | None = None
    #: The model written: the analysis's (GW), or with E[μ], σ_μ from the chosen contact model.
    process_model: TabulatedProcessModel | None = None
    #: How :attr:`process_model` was made from the spread (:func:`~stochfric.process.contact_models.process_model_for`).
    contact_model_record: dict[str, Any] | None = None

    @property
    def model(self) -> TabulatedProcessModel:
        """The friction-process model this run writes (the chosen contact model's; GW by default)."""
        return self.process_model if self.process_model is not None else self.analysis.model

    @property
    def credible(self) -> bool:
        """The gate's verdict (:mod:`stochfric.process.credibility`)."""
        return self.analysis.credibility.credible

    def warnings(self) -> list[dict[str, Any]]:
        """Every warning in order: reading and preparation, the analysis's validity warnings, the gate's reasons."""
        a = self.analysis
        return (list(self.scan_warnings) + [w.to_dict() for w in a.warnings]
                + [r.to_dict() for r in a.credibility.reasons])

    def to_json_dict(self) -> dict[str, Any]:
        """The JSON summary of ``friction-process --json``: the analysis's, with every warning, the
        preparation record(s) and the approach rule (SI units)."""
        payload = self.analysis.to_json_dict()
        payload["warnings"] = self.warnings()
        payload["preparation"] = self.pooled.record()
        payload["approach_rule"] = self.approach_rule
        payload["contact_model"] = self.model.contact_model
        if self.contact_models is not None:
            payload["contact_models"] = self.contact_models.to_dict()
            payload["contact_model_record"] = self.contact_model_record
            payload["model"] = self.model.to_dict()
        return payload

    def write(self, out: str | os.PathLike[str], *, model: bool | None = None, figures: bool = False) -> dict[str, Any]:
        """Write into ``out``: the model file :data:`MODEL_FILE` (when ``model``; default: when credible),
        the statistics :data:`STATISTICS_FILE` and with ``figures`` the figures into ``out/figures``.
        Every file is written atomically.  Returns their paths, keyed as in the JSON summary
        (``model_file``, ``statistics_file``, ``figures``)."""
        directory = Path(out)
        directory.mkdir(parents=True, exist_ok=True)
        written: dict[str, Any] = {}
        if self.credible if model is None else model:
            written["model_file"] = str(self.model.save(directory / MODEL_FILE))
        written["statistics_file"] = str(self.analysis.to_netcdf(directory / STATISTICS_FILE))
        if self.contact_models is not None:
            written.update(write_spread(self.contact_models, directory, figures=figures))
        if figures:
            written["figures"] = [str(p) for p in self.write_figures(directory / "figures")]
        return written

    def write_figures(self, directory: Path) -> list[Path]:
        """The analysis's figures (:func:`~stochfric.process.figures.write_process_figures`) and one
        surrogate of the first scan by every registered method that applies to it, beside the map."""
        from stochfric.process.figures import plot_surrogates, write_process_figures  # matplotlib

        a = self.analysis
        paths = write_process_figures(a, directory)
        heights = self.pooled.surfaces[0].heights_m
        settings = SurrogateSettings(amplitude=a.config.amplitude)
        maps = {name: m.heights(heights, as_generator(a.config.seed), factor=1, settings=settings)
                for name, m in SURROGATES.items() if m.applicable(heights, rule=a.config.summit_rule)[0]}
        paths.append(plot_surrogates(heights, maps, directory / "surrogates.png"))
        return paths


def analyse_scans(
    files: Sequence[str | os.PathLike[str] | None] | None,
    material: Material | str,
    *,
    config: AnalysisConfig | None = None,
    preparation: Preparation | None = None,
    physical_size_m: tuple[float, float] | None = None,
    height_unit: str | None = None,
    fill_undefined: bool = False,
    resample: bool = False,
    approach_m: npt.ArrayLike | None = None,
    approach_rule: ApproachRule | str = ApproachRule.CONTACTS,
    window_shift_m: float | None = None,
    workers: int | None = None,
    progress: Callable[[str, int, int], None] | None = None,
    notify: Callable[[str], None] | None = None,
    out: str | os.PathLike[str] | None = None,
    contact_model: str = "gw",
    load_control: LoadControl | None = None,
    path_surfaces: int = 3,
) -> ScanAnalysis:
    """Scans → friction-process model: what ``stochfric friction-process FILE...`` does (module docstring).

    ``files``: instrument files of one surface (``None`` or empty: the shipped surface); several are
    pooled into one ensemble (one pixel size, or ``resample``).  ``material``: a name or a
    :class:`~stochfric.contact.materials.Material`.  ``config``: the analysis settings (its
    ``summit_rule`` also finds the summits of the prepared scans); its ``window_shift_points`` is
    replaced by ``window_shift_m`` [m] rounded to the grid, by default the thesis's proportion of the
    window (:func:`window_shift_points`).  ``approach_m`` [m], or the default range by ``approach_rule``
    (:func:`choose_approach`).  ``progress(stage, done, total)`` is called as the work advances;
    ``notify(text)`` once before it with the cost estimate of an expensive surrogate method
    (:meth:`~stochfric.surface.surrogates.SurrogateMethod.cost_seconds`).  ``out``: an output
    directory checked *before* any work (nothing is written; call :meth:`ScanAnalysis.write`).
    Raises a :class:`~stochfric.errors.StochfricError` subclass for bad input; the gate's verdict is
    in the result, not an exception.

    ``contact_model`` (issue 31): ``gw`` (the thesis, default) or ``bem``, ``bem-plastic``, ``persson``, a
    comma-separated list or ``all``.  Anything but ``gw`` alone also solves the analysis's surrogates and
    measured windows with GW and those models at the pressures the GW fits used (load control,
    :func:`~stochfric.process.contact_models.contact_model_spread`, ``load_control`` its solver limits,
    ``path_surfaces`` long surfaces for the path spectrum per model); with one model other than GW the
    written model takes its E[μ](p) and σ_μ(p) from it (:func:`~stochfric.process.contact_models.process_model_for`).
    """
    cfg = config if config is not None else AnalysisConfig()
    models = parse_contact_models(contact_model)
    if out is not None:
        check_output_path(Path(out), option="--out")
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise AnalysisError(f"--workers must be >= 1, got {workers}")
    mat = load_material(material) if isinstance(material, str) else material
    paths: list[str | os.PathLike[str] | None] = list(files) if files else [None]
    pooled = pool_scans([load_scan(p, preparation=preparation, summit_rule=cfg.summit_rule,
                                   physical_size_m=physical_size_m, height_unit=height_unit,
                                   fill_undefined=fill_undefined) for p in paths], resample=resample)
    surfaces = list(pooled.surfaces)
    if pooled.resampled_to_m is not None:  # never reduce scans to a handful of summits to make them poolable
        require_summits_for_pooling([summits_of(s, rule=cfg.summit_rule).count for s in surfaces],
                                    names=[s.path.name for s in pooled.scans], resampled_to_m=pooled.resampled_to_m)
    u = choose_approach(surfaces, summit_rule=cfg.summit_rule, approach_m=approach_m, rule=approach_rule,
                        max_area_fraction=cfg.max_area_fraction, window_tiles_max=cfg.window_tiles)
    cfg = replace(cfg, window_shift_points=window_shift_points(surfaces[0], window_shift_m, cfg.length_factor))
    cfg = cfg.with_summit_budget(sum(int(s.heights_m.size) for s in surfaces))  # before the cost is said
    if notify is not None:
        notify_cost(surfaces[0], cfg, notify)
    analysis = analyse(surfaces, mat, u, cfg, name=pooled.name, progress=progress, workers=workers)
    rule = EXPLICIT_APPROACH if approach_m is not None else ApproachRule(approach_rule).value
    if models == ("gw",):
        return ScanAnalysis(pooled=pooled, analysis=analysis, approach_rule=rule, scan_warnings=pooled.warnings)
    fit = analysis.fits["mu_mean"]
    used_p = np.asarray(fit.pressure_pa, dtype=np.float64)[np.asarray(fit.used, dtype=bool)]
    spread = contact_model_spread(surfaces, mat, used_p, ("gw", *models), cfg, control=load_control,
                                  path_surfaces=min(path_surfaces, cfg.long_surfaces), workers=workers,
                                  progress=progress)
    single = [m for m in models if m != "gw"]
    chosen = single[0] if len(models) == 1 else "gw"
    model, record = process_model_for(analysis.model, spread, chosen)
    return ScanAnalysis(pooled=pooled, analysis=analysis, approach_rule=rule, scan_warnings=pooled.warnings,
                        contact_models=spread, process_model=model, contact_model_record=record)


#: File names of the contact-model spread (:func:`write_spread`).
SPREAD_FILE = "contact_models.json"
SPREAD_SAMPLES_FILE = "contact_models_samples.nc"


def write_spread(spread: ContactModelSpread, out: str | os.PathLike[str], *, figures: bool = True) -> dict[str, Any]:
    """Write the spread into ``out`` atomically: :data:`SPREAD_FILE` (summary), :data:`SPREAD_SAMPLES_FILE`
    (per-sample arrays) and with ``figures`` the envelope figure ``contact_models.png``; their paths."""
    import json

    from stochfric.io_utils import json_ready, write_netcdf_atomic, write_text_atomic

    directory = Path(out)
    directory.mkdir(parents=True, exist_ok=True)
    written: dict[str, Any] = {}
    text = json.dumps(json_ready(spread.to_dict()), indent=2)
    written["contact_models_file"] = str(write_text_atomic(directory / SPREAD_FILE, text))
    written["contact_models_samples_file"] = str(write_netcdf_atomic(directory / SPREAD_SAMPLES_FILE,
                                                                     spread.to_dataset()))
    if figures:
        from stochfric.process.figures import plot_contact_model_spread

        written["contact_models_figure"] = str(plot_contact_model_spread(spread, directory / "contact_models.png"))
    return written

"""The chapter-3 analysis of the shipped measured surface, computed for the report (method §1–§4).

``stochfric reproduce`` runs :func:`chapter3_analysis` once and hands the :class:`Chapter3` result
to the report, which only renders it: surface statistics and summits (method §1), the GW/Hertz
contact over the default approach range (§2), and the statistical contact analysis with its
friction-process model (§3–§4).  The model file and the NetCDF of all statistics are written
under ``directory/friction_process``.

Settings (recorded in the result): the shipped surface al3d-1, plane detrend, no filter, no
coarsening, thesis summit rule, brake-pad material (Tables 3.1/3.2), random-phase surrogates, the
approach range σ_S/4 … 3σ_S (``default_approach_m(rule="sigma")``, the thesis's ratio),
a_y = 0.0566 × the window length; ``quick``: 30 realisations and 4 long surfaces instead of 100
and 10.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..contact.asperity import ApproachRule, ContactResult, asperity_contact, default_approach_m
from ..contact.materials import Material, load_material
from ..process.ensemble import default_window_shift_points
from ..process.statistics import AnalysisConfig, StatisticalContactAnalysis, analyse
from ..surface.io import Surface, default_surface_path, read_surface
from ..surface.preprocess import Preparation, prepare
from ..surface.statistics import SurfaceStatistics, surface_statistics
from ..surface.summits import DEFAULT_SUMMIT_RULE, Summits, summits_of
from ..surface.synthesis import PHASE_METHOD

__all__ = ["CHAPTER3_SEED", "Chapter3", "chapter3_analysis"]

#: Default seed of the chapter-3 analysis in the report (recorded on the page).
CHAPTER3_SEED = 2013


@dataclass(frozen=True, kw_only=True, eq=False)
class Chapter3:
    """Everything the report shows of chapter 3 (SI units; files relative to nothing: absolute)."""

    surface_path: Path
    fine: Surface
    coarse: Surface
    fine_summits: Summits
    coarse_summits: Summits
    preparation: Preparation
    surface_stats: SurfaceStatistics
    material: Material
    contact: ContactResult
    analysis: StatisticalContactAnalysis
    model_path: Path
    statistics_path: Path
    seed: int
    quick: bool
    info: dict[str, Any] = field(default_factory=dict)


def chapter3_analysis(directory: str | Path, *, quick: bool = False, seed: int = CHAPTER3_SEED) -> Chapter3:
    """Run method §1–§4 on the shipped surface; write the model file and the statistics NetCDF."""
    path = default_surface_path()
    prep = Preparation(detrend="plane", median_radius=0, step=1)
    fine, coarse = prepare(read_surface(path), prep)
    fs = summits_of(fine, rule=DEFAULT_SUMMIT_RULE)
    cs = fs if coarse is fine else summits_of(coarse, rule=DEFAULT_SUMMIT_RULE)
    material = load_material("brake-pad")
    u = default_approach_m(cs, rule=ApproachRule.SIGMA)  # the thesis's ratio 1:12 in σ_S (reproduction mode)
    contact = asperity_contact(coarse, cs, material, u, preparation=prep.to_dict())
    cfg = AnalysisConfig(
        realizations=30 if quick else 100, long_surfaces=4 if quick else 10,
        summit_max_realizations=30 if quick else 100,  # the thesis's fixed ensemble (reproduction mode)
        window_shift_points=default_window_shift_points(coarse.nb_grid_pts[1]), surrogate=PHASE_METHOD, seed=seed,
    )  # fmt: skip
    analysis = analyse(coarse, material, u, cfg, name="shipped surface (al3d-1)")
    out = Path(directory) / "friction_process"
    out.mkdir(parents=True, exist_ok=True)
    return Chapter3(
        surface_path=Path(path),
        fine=fine,
        coarse=coarse,
        fine_summits=fs,
        coarse_summits=cs,
        preparation=prep,
        surface_stats=surface_statistics(coarse, cs),
        material=material,
        contact=contact,
        analysis=analysis,
        model_path=analysis.model.save(out / "friction_process.json"),
        statistics_path=analysis.to_netcdf(out / "statistics.nc"),
        seed=seed,
        quick=quick,
    )

"""Every figure of the package, drawn from small inputs at the size and dpi it is saved with (issue 32, item 5):

no overlapping tick labels on any axis (x, y, z separately), a label with a unit on every axis that has
ticks (``[unit]`` or "dimensionless", "count", "probability"), no empty panel, no text of one panel on
top of another's, no label twice side by side, nothing cut off at the figure's edge
(:func:`stochfric.plotting.layout_problems`).  Also: the ``plot()`` helpers of the result classes return
matplotlib figures (item 6), :func:`~stochfric.plotting.save_figure` thins crowded ticks, and a standard
error above 100 % is printed "undefined" in the report's table.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import replace
from functools import cached_property
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from matplotlib.figure import Figure

from stochfric.contact.asperity import ContactResult, asperity_contact
from stochfric.contact.figures import figure_contact
from stochfric.contact.materials import get_material
from stochfric.oscillator.figures import figure_phase_portrait
from stochfric.oscillator.integrate import simulate
from stochfric.oscillator.options import IntegrationOptions, NoiseOptions, OutputOptions
from stochfric.oscillator.parameters import PhysicalParameters
from stochfric.oscillator.result import SimulationResult
from stochfric.plotting import layout_problems, new_figure, save_figure, tick_label_overlaps
from stochfric.process import figures as pfig
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.analysis_result import StatisticalContactAnalysis
from stochfric.process.contact_models import contact_model_spread
from stochfric.process.statistics import analyse
from stochfric.report.html import UNDEFINED, normal_force_reading, se_percent
from stochfric.studies import figures as sfig
from stochfric.studies.base import STUDY_SCHEMA, StudyResult
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.forcing import forcing_study
from stochfric.studies.lyapunov import lyapunov_study
from stochfric.studies.normal_force import NormalForceSummary, normal_force_study
from stochfric.surface.figures import figure_fine_vs_coarse, figure_pdfs, figure_surface
from stochfric.surface.io import Surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of
from synthetic_maps import as_surface, gaussian_heights  # tests/synthetic_maps.py

#: dpi the figures are saved with: the simulation's phase portrait 130, everything else 110
PHASE_DPI, DPI = 130, 110


class Inputs:
    """Small results, each built once on first use (a few seconds in all)."""

    @cached_property
    def studies(self) -> dict[str, StudyResult[Any]]:
        return {
            "normal-force": normal_force_study(NormalForceConfig(runs=2, phase_runs=2, seed=1, tau_end=30.0)),
            "damping": damping_study(DampingConfig(normal_forces=(4000.0, 5600.0), damping_ratios="0.05:0.25:5",
                                                   runs=3, seed=3, tau_end=30.0)),
            "forcing": forcing_study(ForcingConfig(eta="0.5:2:3", runs=2, seed=1, tau_end=30.0)),
            "lyapunov": lyapunov_study(LyapunovConfig(normal_forces=(4000.0,), eta=(1.2, 2.0), runs=2,
                                                      tau_end=60.0, seed=1)),
        }

    def simulation(self, forced: bool) -> SimulationResult:
        p = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0, contact_area=0.016,
                               damping_ratio=0.05).to_dimensionless()
        return simulate(replace(p, q=2e-4, eta=1.2) if forced else p, model="white", runs=3, seed=1,
                        noise=NoiseOptions(sigma_zeta=0.05), integration=IntegrationOptions(tau_end=40.0),
                        output=OutputOptions(save_trajectory=True))

    @cached_property
    def surfaces(self) -> tuple[Surface, Surface, Any, Any]:
        z = np.random.default_rng(2).normal(size=(60, 50)) * 1e-6
        fine, coarse = prepare(Surface(heights_m=z, physical_size_m=(6e-4, 5e-4)), Preparation(median_radius=1,
                                                                                                  step=2))
        return fine, coarse, summits_of(fine), summits_of(coarse)

    @cached_property
    def contact(self) -> ContactResult:
        _, coarse, _, cs = self.surfaces
        return asperity_contact(coarse, cs, get_material("brake-pad"))

    @cached_property
    def map(self) -> Surface:
        return as_surface(gaussian_heights((48, 48), 2.0, 3))

    @cached_property
    def analysis(self) -> StatisticalContactAnalysis:
        return analyse(self.map, get_material("brake-pad"), np.linspace(0.2e-6, 2.0e-6, 6),
                       AnalysisConfig(realizations=6, long_surfaces=3, length_factor=3, seed=3, surrogate="phase"))

    def spread(self, pressures: int, path: bool = False) -> Any:
        """GW and Persson at ``pressures`` pressures (a short log range), with the path spectra if ``path``."""
        p = self.analysis.pressure_pa
        cfg = AnalysisConfig(realizations=3, seed=1, surrogate="phase", long_surfaces=3, length_factor=3)
        return contact_model_spread(self.map, get_material("brake-pad"), np.geomspace(p[1], p[-1], pressures),
                                    models="gw,persson", config=cfg, path_surfaces=2 if path else 0,
                                    path_pressure_pa=float(p[3]) if path else None)


@pytest.fixture(scope="module")
def inputs() -> Inputs:
    return Inputs()


def _study(kind: str, builder: Callable[..., Figure | None], **kw: Any) -> Callable[[Inputs], Figure | None]:
    return lambda i: builder(i.studies[kind].dataset, **kw)


#: name → (builder from the inputs, the dpi it is saved with)
FIGURES: dict[str, tuple[Callable[[Inputs], Figure | None], int]] = {
    "phase_portrait": (lambda i: figure_phase_portrait(i.simulation(False)), PHASE_DPI),
    "phase_portrait_forced_3d": (lambda i: figure_phase_portrait(i.simulation(True)), PHASE_DPI),
    "surface": (lambda i: figure_surface(i.surfaces[0]), DPI),
    "fine_vs_coarse": (lambda i: figure_fine_vs_coarse(i.surfaces[0], i.surfaces[1], step=2), DPI),
    "surface_pdfs": (lambda i: figure_pdfs([("fine", i.surfaces[0], i.surfaces[2]),
                                            ("coarse", i.surfaces[1], i.surfaces[3])]), DPI),
    "contact": (lambda i: figure_contact([i.contact]), DPI),
    **{f"process_{name}": ((lambda i, name=name: pfig.analysis_figure(i.analysis, name)), DPI)
       for name in pfig.ANALYSIS_FIGURES},
    "process_surrogates": (lambda i: pfig.figure_surrogates(i.map.heights_m, {"phase": i.map.heights_m[::-1]}), DPI),
    "process_contact_models": (lambda i: pfig.figure_contact_model_spread(i.spread(4)), DPI),
    "process_contact_models_with_path": (lambda i: pfig.figure_contact_model_spread(i.spread(12, path=True)), DPI),
    **{f"{kind}_{name}": (_study(kind, builder), DPI)
       for kind, builders in sfig.STUDY_FIGURES.items() for name, builder in builders.items()},
    "normal-force_pdf_D1": (_study("normal-force", sfig.figure_normal_force_pdf, damping_index=1), DPI),
}


@pytest.mark.parametrize("name", sorted(FIGURES))
def test_figure_layout(inputs: Inputs, name: str) -> None:
    build, dpi = FIGURES[name]
    fig = build(inputs)
    assert isinstance(fig, Figure), f"{name}: the small input holds the data of this figure"
    assert layout_problems(fig, dpi=dpi) == []


def test_the_checker_finds_what_it_looks_for() -> None:
    """Crowded tick labels, an axis without a unit, an empty panel, a label twice: all reported."""
    fig = new_figure(2.0, 2.0)
    ax, empty = fig.subplots(1, 2)
    ax.plot([0.0, 1.0], [0.0, 1.0])
    ax.set_xticks(np.linspace(0, 1, 30))
    ax.set_xlabel("x")
    ax.set_ylabel("v [m/s]")
    empty.set_ylabel("v [m/s]")
    empty.set_xlabel("t [s]")
    found = "\n".join(layout_problems(fig, dpi=DPI))
    assert "x tick labels" in found and "overlap" in found
    assert "the x label 'x' has no unit" in found
    assert "an empty panel" in found


def test_save_figure_thins_crowded_ticks(tmp_path: Path) -> None:
    """A data range no builder foresaw: save_figure gives the crowded axis fewer ticks before it is written."""
    from matplotlib.ticker import MaxNLocator

    fig = new_figure(3.0, 2.0)
    ax = fig.subplots()
    ax.plot([1.0e-3, 1.234567e-3], [0.0, 1.0])
    ax.xaxis.set_major_locator(MaxNLocator(nbins=25))
    ax.ticklabel_format(axis="x", useOffset=False)
    out = save_figure(fig, tmp_path / "crowded.png")
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert tick_label_overlaps(fig) == []


# --- result.plot() (issue 32, item 6) -----------------------------------------------------------------------


def test_simulation_result_plot(inputs: Inputs) -> None:
    fig = inputs.simulation(False).plot()
    assert isinstance(fig, Figure) and len(fig.axes) == 1 and fig.axes[0].lines


def test_study_result_plot_draws_each_kinds_main_figure(inputs: Inputs) -> None:
    titles = {"damping": "P(stick-slip cycle)", "forcing": "deterministic (black)", "lyapunov": "q = ",
              "normal-force": "N = "}
    for kind, res in inputs.studies.items():
        fig = res.plot()
        assert isinstance(fig, Figure)
        assert titles[kind] in fig.axes[0].get_title(), kind
    assert isinstance(inputs.studies["normal-force"].plot("phase", damping_index=1), Figure)
    with pytest.raises(ValueError, match="known: probability, maps"):
        inputs.studies["damping"].plot("nope")


def test_analysis_and_contact_result_plot(inputs: Inputs) -> None:
    fig = inputs.analysis.plot()
    assert isinstance(fig, Figure) and [ax.get_xlabel() for ax in fig.axes] == ["p [MPa]"] * 3
    assert isinstance(inputs.analysis.plot("ergodicity"), Figure)
    with pytest.raises(ValueError, match="model_functions"):
        inputs.analysis.plot("nope")
    fig = inputs.contact.plot(inputs.contact)
    assert isinstance(fig, Figure) and len(fig.axes) == 4 and len(fig.axes[0].lines) == 2


# --- the report's SE % cell ---------------------------------------------------------------------------------


def test_a_standard_error_above_100_percent_is_undefined() -> None:
    assert se_percent(0.0125) == pytest.approx(1.25)
    assert se_percent(1.0) == pytest.approx(100.0)
    assert se_percent(260.0) == UNDEFINED == "undefined"
    assert se_percent(None) is None and math.isnan(se_percent(float("nan")))  # type: ignore[arg-type]
    t = [[0.5, 0.5]]  # tables [normal_force_n][damping_ratio]
    summary = NormalForceSummary(
        schema=STUDY_SCHEMA, study="normal-force", preset="brake", process_source="preset", runs=2, seed=1,
        tau_end=50.0, dt=0.005, models=["white"], path_coordinate="mass", white_intensity="sigma_mu",
        white_increment="ito", process_level="sigma_mu", normal_force_n=[4000.0], damping_ratio=[5e-6, 0.1],
        sigma_zeta=[0.07], sigma_zeta_effective=[0.07], stick_window=(25.0, 50.0),
        x_gh_mean={"white": [[1e-6, 2e-4]]}, x_gh_std={"white": t}, vark={"white": [[3.0, 0.2]]},
        x_gh_mean_se={"white": t}, x_gh_std_se={"white": t}, vark_se={"white": [[260.0, 0.02]]},
        x_gh_mean_se_iid={}, x_gh_std_se_iid={}, vark_se_iid={}, n_events={"white": [[40.0, 40.0]]})
    table, txt = normal_force_reading(summary)
    assert "<td>undefined</td>" in table and "26000" not in table and "<td>2</td>" in table
    assert "“undefined”" in txt

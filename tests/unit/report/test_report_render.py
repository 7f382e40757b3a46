"""The report renders hand-built results (stochfric.report): no study and no simulation runs here.

tests/test_report_html.py renders the output of real (small) studies; this file feeds the report
results written by hand, with the integrators switched off, so that every number on the page is one
this test put in: the Lyapunov section's table and headline, the warnings explained, the provenance,
HTML escaping, the damping verdict (is P(stick-slip) ≥ α above the deterministic limit?) and the phase portrait of a
hand-built simulation result.
"""

from __future__ import annotations

import json
import re
from pathlib import Path
from types import SimpleNamespace
from typing import Any, NoReturn

import matplotlib.image as mpimg
import numpy as np
import pytest
import xarray as xr

from stochfric.oscillator import accurate, integrate, kernels
from stochfric.oscillator.friction_laws import law_II
from stochfric.oscillator.parameters import OscillatorParameters
from stochfric.oscillator.result import SimulationResult
from stochfric.report import plot_phase_portrait, write_report
from stochfric.report.html import (
    WARNING_HELP,
    damping_headline,
    damping_reading,
    dmax_text,
    forcing_reading,
    model_choices_text,
    normal_force_headline,
    reading_html,
    rich_text,
)
from stochfric.studies.base import STUDY_SCHEMA, StudyResult
from stochfric.studies.damping import DampingSummary, DMaxRisk, PhaseSummary, SampleExtreme
from stochfric.studies.forcing import ForcingSummary
from stochfric.studies.lyapunov import LyapunovSummary, Significance
from stochfric.studies.normal_force import NormalForceSummary
from stochfric.studies.stats import RatioEstimate
from stochfric.studies.summary import WarningCount

PNG = b"\x89PNG\r\n\x1a\n"


def _head(study: str, models: list[str], **over: Any) -> dict[str, Any]:
    """The common summary fields of a hand-built study summary."""
    return {"schema": STUDY_SCHEMA, "study": study, "preset": "brake", "process_source": "preset", "runs": 2,
            "seed": 1, "tau_end": 50.0, "dt": 0.005, "models": models, "path_coordinate": "mass",
            "white_intensity": "sigma_mu", "white_increment": "ito", "process_level": "sigma_mu", **over}


def _lyapunov_result() -> StudyResult:
    models = ["deterministic", "white"]
    eta = np.array([1.0, 1.5, 2.0])
    forces = np.array([4000.0, 8000.0])
    lam = np.array([[[[0.10, -0.20, 0.05], [np.nan, 0.30, -0.10]]],
                    [[[0.02, np.nan, -0.01], [0.04, 0.01, -0.30]]]])  # model, q, N, η
    status = np.where(np.isfinite(lam), "ok", "merged")
    status[0, 0, 1, 0] = "nonlinear"
    ds = xr.Dataset(
        {"lyapunov": (("model", "forcing_q", "normal_force_n", "eta"), lam, {"units": "1"}),
         "status": (("model", "forcing_q", "normal_force_n", "eta"), status)},
        coords={"model": models, "forcing_q": [5e-5], "normal_force_n": forces, "eta": eta},
        attrs={"config_json": json.dumps({"runs": 2, "eta": [1.0, 1.5, 2.0]}),
               "setup_json": json.dumps({"gamma0": 1.41e-3, "process": {"secret": "not shown"}}),
               "seed_entropy": "20131234", "seed_rule": "task k uses SeedSequence(seed, spawn_key=(k,))",
               "versions_json": json.dumps({"stochfric": "0.1.0"})},
    )
    counts = {"deterministic": {"ok": 4, "merged": 1, "too-few-transitions": 0, "nonlinear": 1},
              "white": {"ok": 5, "merged": 1, "too-few-transitions": 0, "nonlinear": 0}}
    summary = LyapunovSummary(
        **_head("lyapunov", models, tau_end=200.0,
                warnings=[WarningCount("slip-shorter-than-grid", 3), WarningCount("no-such-code", 1)]),
        normal_force_n=forces.tolist(), forcing_q=[5e-5], eta=eta.tolist(), damping_ratio=5e-6,
        sigma_zeta=[0.07, 0.08], sigma_zeta_effective=[0.07, 0.08], perturbation=1e-6, linearity_tolerance=0.1,
        integrator="accurate", sde_integrator="euler-maruyama", integrator_mode="converged",
        lyapunov={m: lam[i].tolist() for i, m in enumerate(models)},
        lyapunov_se={m: np.zeros_like(lam[i]).tolist() for i, m in enumerate(models)},
        status={m: status[i].tolist() for i, m in enumerate(models)},
        lyapunov_is_lower_bound={m: np.zeros(lam[i].shape, bool).tolist() for i, m in enumerate(models)},
        diverging_growth=100.0, n_transitions={m: np.zeros(lam[i].shape, int).tolist() for i, m in enumerate(models)},
        status_counts=counts,
        significance={"deterministic": Significance(defined=4, positive=2, negative=0),
                      "white": Significance(defined=5, positive=1, negative=1)},
        positive_fraction={"deterministic": 0.5, "white": 0.2},
        separation_index_443={m: lam[i].tolist() for i, m in enumerate(models)},
        separation_index_status={m: status[i].tolist() for i, m in enumerate(models)},
    )
    return StudyResult(kind="lyapunov", dataset=ds, summary=summary)


def _refuse(*args: Any, **kwargs: Any) -> NoReturn:
    raise AssertionError("the report must render results, not simulate")


@pytest.fixture(scope="module")
def page(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, str]:
    d = tmp_path_factory.mktemp("report")
    with pytest.MonkeyPatch.context() as mp:
        for mod, name in ((integrate, "simulate"), (kernels, "run_fixed_step_batch"),
                          (accurate, "run_accurate_batch")):
            mp.setattr(mod, name, _refuse)
        index = write_report([_lyapunov_result()], d, title="run <7> & co")
    return index, index.read_text(encoding="utf-8")


def test_the_page_is_written_with_its_figure(page: tuple[Path, str]) -> None:
    index, text = page
    assert index.name == "index.html" and text.startswith("<!DOCTYPE html>")
    srcs = re.findall(r'<img src="([^"]+)"', text)
    assert srcs == ["00_lyapunov_brake.png"]
    png = index.parent / srcs[0]
    assert png.read_bytes()[:8] == PNG and mpimg.imread(png).shape[0] > 100
    assert "<h1>run &lt;7&gt; &amp; co</h1>" in text and "<title>run &lt;7&gt; &amp; co</title>" in text
    assert "Chapter 3" not in text  # no chapter-3 analysis given: no such section


def test_the_lyapunov_table_and_headline_show_the_given_numbers(page: tuple[Path, str]) -> None:
    _, text = page
    rows = re.findall(r"<tr>(<td>.*?)</tr>", text)
    assert "<td>deterministic</td><td>4</td><td>—</td><td>1</td><td>0</td><td>1</td><td>2</td><td>0</td>" in rows
    assert "<td>white</td><td>5</td><td>—</td><td>1</td><td>0</td><td>0</td><td>1</td><td>1</td>" in rows
    reading = text[text.index("<h2>Reading</h2>"):text.index("<h2 id='s0'>")]
    assert ("brake, Lyapunov exponent on the stick line: cells with λ &gt; 0 by more than 2 SE: "
            "deterministic 2 (white noise: not defined as Δτ → 0).") in reading
    assert "White noise: no sign is read" in text and "white q = " not in text
    assert "perturbation δ = 1e-06, τ<sub>end</sub> = 200" in text
    assert "<a href='#s0'>lyapunov</a>" in reading


def test_every_warning_is_counted_and_explained(page: tuple[Path, str]) -> None:
    _, text = page
    assert "<dt>slip-shorter-than-grid: lyapunov (brake) ×3</dt>" in text
    what, todo = WARNING_HELP["slip-shorter-than-grid"]
    assert rich_text(what) in text and rich_text(todo) in text
    assert "<dt>no-such-code: lyapunov (brake) ×1</dt>" in text  # an unknown code still appears
    assert "See the warning messages of the simulations." in text
    assert "Simulation warnings: slip-shorter-than-grid ×3, no-such-code ×1" in text


def test_provenance_is_shown_without_the_process_internals(page: tuple[Path, str]) -> None:
    _, text = page
    assert "seed entropy: 20131234; task k uses SeedSequence(seed, spawn_key=(k,))" in text
    assert "&quot;gamma0&quot;: 0.00141" in text and "not shown" not in text
    assert "<summary>config</summary>" in text and "<summary>versions</summary>" in text
    assert "<h2>Versions</h2>" in text


# --- the readings, from hand-built summaries ---------------------------------------------------------


def _damping_summary(det: list[float | None], white: list[tuple[float | None, float | None, float | None]],
                     resolved: bool = True) -> DampingSummary:
    """Three forces; ``white``: D_max(10 %) per force as (value, low, high)."""
    grid = [0.05, 0.1, 0.15, 0.2, 0.25]
    return DampingSummary(
        **_head("damping", ["deterministic", "white"], runs=100),
        normal_force_n=[1000.0, 2000.0, 3000.0], damping_ratio=grid, d_hopf=[0.02, 0.04, 0.06],
        sigma_zeta=[0.07] * 3, sigma_zeta_effective=[0.07] * 3, stick_window=(25.0, 50.0), confidence=0.95,
        p_detect=0.1, risk_levels=[0.1], risk_levels_runs_to_resolve=[36], stick_probability_interval="clopper-pearson",
        d_max_deterministic=det,
        phase=PhaseSummary(normal_force_n=2000.0, damping_ratio=[0.05, 0.15], damping_rule="auto",
                           runs={"white": 2}, save_every=10, has_cycle_fraction={"white": [1.0, 0.0]}),
        d_max_risk={"white": [[DMaxRisk(risk_level=0.1, value=v, interval=(lo, hi), resolved=resolved,
                                        high_open=hi is not None and hi >= 0.25)] for v, lo, hi in white]},
        d_max_sample_extreme={"white": [SampleExtreme(value=hi, interval=(hi, None)) for _, _, hi in white]},
        stick_probability={}, stick_count_mean={}, stick_count_mean_se={}, x_gh_mean_se={}, x_gh_std_se={})


def test_damping_headline_says_where_the_deterministic_limit_is_exceeded_at_the_risk_level() -> None:
    line = damping_headline(_damping_summary([0.1, 0.15, 0.2], [(0.1, 0.1, 0.1), (0.2, 0.2, 0.2), (0.2, 0.15, 0.2)]))
    assert line == ("brake, N = 2000 N: stick-slip up to D = 0.15 deterministically, P(stick-slip) ≥ 10 % up to "
                    "D = 0.2 [0.2, 0.2] with white noise — the deterministic limit is exceeded at 10 % risk (white: "
                    "P(stick-slip) ≥ 10 % above D_max^d). Forces where P(stick-slip) ≥ 10 % above D_max^d "
                    "(3 forces): white: 2000 N.")
    assert "safe" not in line


def test_damping_headline_holds_unresolved_and_at_the_grid_edges() -> None:
    holds = damping_headline(_damping_summary([0.1, 0.15, 0.2], [(0.1, 0.1, 0.1), (0.15, 0.1, 0.15), (None,) * 3]))
    assert "— the deterministic limit holds at 10 % risk (P(stick-slip) < 10 % above it)" in holds
    assert "white: none" in holds and "safe" not in holds
    open_ = damping_headline(_damping_summary([0.1, 0.15, 0.2], [(0.1, 0.1, 0.1), (0.15, 0.1, 0.25)] * 2,
                                              resolved=False))
    assert "0.15 [0.1, ≥ 0.25*]" in open_ and "neither confirmed nor exceeded" in open_
    assert open_.endswith("(*100 runs cannot resolve 10 %).")
    edge = damping_headline(_damping_summary([0.1, 0.25, 0.2], [(0.1, 0.1, 0.1), (0.25, 0.25, 0.25), (0.2,) * 3]))
    assert "stick-slip up to D = 0.25 or beyond (the grid end) deterministically" in edge
    assert "— the limits reach the grid end: extend the D grid to compare them" in edge
    none = damping_headline(_damping_summary([0.1, None, 0.2], [(0.1, 0.1, 0.1), (None,) * 3, (0.2,) * 3]))
    assert "no stick-slip even at D = 0.05 (the grid start) deterministically" in none


def test_damping_reading_is_short_bullets_and_names_the_sample_extreme() -> None:
    table, reading = damping_reading(_damping_summary([0.1, 0.15, 0.2], [(0.1, 0.1, 0.1), (0.15, 0.1, 0.25),
                                                                        (0.2, 0.15, 0.2)], resolved=False))
    lines = reading.split("\n")
    assert all(x.startswith("• ") for x in lines) and all(len(x) < 260 for x in lines)
    assert "safe" not in reading and "safe" not in table
    assert any("Sample extreme (thesis D_max^s" in x and "not a limit" in x for x in lines)
    assert any(x.startswith("• *: open upper end — 100 runs cannot resolve 10 % (≥ 36 runs needed)") for x in lines)
    assert "D<sub>max</sub>(10 %) white [low, high]" in table and "0.15 [0.1, ≥ 0.25*]" in table
    html = reading_html(reading)
    assert html.startswith("<ul class='reading'><li>") and html.count("<li>") == len(lines)


def test_dmax_text_and_rich_text() -> None:
    grid = [0.05, 0.1, 0.15]
    assert dmax_text(0.1, grid) == "0.1"
    assert dmax_text(0.15, grid) == "≥ 0.15 (> grid)"
    assert dmax_text(None, grid) == dmax_text(float("nan"), grid) == "< grid start (0.05)"
    assert rich_text("D_max^d < X_gh & stick_window") == (
        "D<sub>max</sub><sup>d</sup> &lt; X<sub>gh</sub> &amp; stick_window")


def test_forcing_reading_pairs_each_q_with_its_median_and_interval() -> None:
    summary = ForcingSummary(
        **_head("forcing", ["white", "contact"]), normal_force_n=4000.0, damping_ratio=5e-6, forcing_q=[5e-5, 5e-4],
        forcing_amplitude_n=[50.0, 500.0], eta=[1.0], integrator="accurate", sde_integrator="euler-maruyama",
        integrator_mode="converged", sigma_zeta=0.07, sigma_zeta_effective=0.07, x_gh_mean={}, x_gh_std={},
        x_gh_mean_se={}, x_gh_std_se={}, sigma_ratio_median={"5e-05": 1.2, "0.0005": 1.05},
        sigma_ratio_median_ci={"5e-05": RatioEstimate(value=1.2, se_delta=0.05, low=1.1, high=1.3, confidence=0.95)})
    table, txt = forcing_reading(summary)
    assert "<tr><td>5e-05</td><td>1.2</td><td>1.1 … 1.3</td></tr>" in table
    assert "<tr><td>0.0005</td><td>1.05</td><td>—</td></tr>" in table
    assert txt.startswith("q = 5e-05: median σ_contact/σ_white over η = 1.2 (95 % bootstrap interval 1.1 … 1.3); "
                          "q = 0.0005: median σ_contact/σ_white over η = 1.05 (95 % bootstrap interval —)")


def test_normal_force_headline_names_the_forces_with_stick_slip() -> None:
    summary = NormalForceSummary(
        **_head("normal-force", ["deterministic", "contact"], preset="sheet"), normal_force_n=[400.0, 880.0],
        damping_ratio=[5e-6, 0.17], sigma_zeta=[0.07, 0.08], sigma_zeta_effective=[0.07, 0.08],
        stick_window=(25.0, 50.0), x_gh_mean={}, x_gh_std={}, vark={}, x_gh_mean_se={}, x_gh_std_se={}, vark_se={},
        x_gh_mean_se_iid={}, x_gh_std_se_iid={}, vark_se_iid={},
        # tables [normal_force_n][damping_ratio]
        n_events={"deterministic": [[12.0, 0.0], [9.0, 3.0]], "contact": [[10.0, float("nan")], [8.0, 0.0]]})
    assert normal_force_headline(summary) == (
        "sheet, N = 400, 880 N: at D = 5e-06 stick-slip at every force in every model; at D = 0.17 stick-slip "
        "deterministic 880 N; contact nowhere.")


def test_reproduction_modes_are_labelled_as_such() -> None:
    """docs/oscillator.md: the printed-(4.31) intensity and the position read mode are reproduction modes
    only, and must say so wherever they are used."""
    default = model_choices_text(SimpleNamespace(
        path_coordinate="mass", white_intensity="sigma_mu", white_increment="ito", process_level="sigma_mu",
        white_model=None, sigma_zeta=[0.0742, 0.08], sigma_zeta_effective=[0.0742, 0.08],
        normal_force_n=[5600.0, 8000.0]))
    assert "REPRODUCTION MODE" not in default
    assert "σ_ζ of the white model = 0.0742 (N = 5600 N), 0.08 (N = 8000 N)." in default
    repro = model_choices_text(SimpleNamespace(
        path_coordinate="position", white_intensity="thesis", white_increment="thesis", sigma_zeta=0.0742,
        sigma_zeta_effective=[0.2624], process_level="psd_level", white_model=None, normal_force_n=4000.0))
    assert repro.count("REPRODUCTION MODE") == 3
    assert "effective σ_ζ,eff = 0.2624" in repro


# --- the phase portrait of one simulation result -----------------------------------------------------


def _simulation(forced: bool, trajectory: bool = True) -> SimulationResult:
    p = OscillatorParameters(gamma0=1.0, n=10.0, q=0.5 if forced else 0.0, eta=1.15 if forced else 0.0)
    tau = np.linspace(0.0, 10.0, 201)
    traj = np.stack([np.broadcast_to(tau, (2, 201)), np.stack([np.cos(tau), 0.9 * np.cos(tau)]),
                     np.stack([-np.sin(tau), -0.9 * np.sin(tau)])], axis=-1)[None]
    x_gh = np.array([[[1.0, np.nan], [0.9, 0.95]]])
    return SimulationResult(
        params=[p], x_gh=x_gh, t_gh=x_gh * 0 + 5.0, stick_count=np.array([[1, 2]]), diagnostics={},
        trajectory=traj if trajectory else None, model="deterministic", integrator="accurate", dt=0.05,
        tau_end=10.0, runs=2, seed_entropy=1, path_coordinate="mass", x0=[(0.0, 1.0)],
        laws=[law_II().to_dict()], sigma_zeta=[0.0], process=None)


@pytest.mark.parametrize("forced", [False, True], ids=["2-D", "3-D forced"])
def test_phase_portrait_of_a_hand_built_result(tmp_path: Path, forced: bool) -> None:
    out = plot_phase_portrait(_simulation(forced), tmp_path / "sub" / "phase.png")
    assert out.read_bytes()[:8] == PNG and mpimg.imread(out).shape[:2] == (676, 910)  # 7 × 5.2 in at 130 dpi
    svg = plot_phase_portrait(_simulation(forced), tmp_path / "phase.svg")
    assert "<svg" in svg.read_text(encoding="utf-8")[:500]


def test_phase_portrait_needs_a_trajectory(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="save_trajectory=True"):
        plot_phase_portrait(_simulation(False, trajectory=False), tmp_path / "x.png")
    assert not (tmp_path / "x.png").exists()

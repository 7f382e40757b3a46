"""The report's one-look verdict (issue 20 §5): per preset and normal force, D_max^d, D_max(α) with its
interval for each stochastic model, and whether the deterministic limit holds at that risk."""

from __future__ import annotations

from types import SimpleNamespace

from stochfric.report.html import verdict_section
from stochfric.studies.base import STUDY_SCHEMA
from stochfric.studies.damping import DampingSummary, DMaxRisk


def _entry(value: float | None, lo: float | None, hi: float | None, *, high_open: bool = False,
           resolved: bool = True) -> list[DMaxRisk]:
    return [DMaxRisk(risk_level=0.1, value=value, interval=(lo, hi), high_open=high_open, resolved=resolved)]


def test_verdict_table_says_holds_not_safe_and_not_resolved() -> None:
    summary = DampingSummary(
        schema=STUDY_SCHEMA, study="damping", preset="brake", process_source="preset:brake", runs=100, seed=1,
        tau_end=50.0, dt=0.005, models=["deterministic", "white", "contact"], path_coordinate="mass",
        white_intensity="sigma_mu", white_increment="ito", process_level="sigma_mu",
        normal_force_n=[1800.0, 5600.0, 8000.0], damping_ratio=[0.05, 0.1, 0.15, 0.2, 0.25],
        d_max_deterministic=[0.1, 0.15, 0.2], d_hopf=[0.03, 0.09, 0.13], sigma_zeta=[0.07] * 3,
        sigma_zeta_effective=[0.07] * 3, stick_window=(25.0, 50.0), confidence=0.95, p_detect=0.1,
        risk_levels=[0.1], risk_levels_runs_to_resolve=[36], stick_probability_interval="clopper-pearson",
        d_max_risk={
            "white": [_entry(0.1, 0.05, 0.1), _entry(0.15, 0.15, 0.15), _entry(0.2, 0.2, 0.25)],
            "contact": [_entry(0.1, 0.1, 0.1), _entry(0.2, 0.2, 0.25), _entry(0.2, 0.2, 0.2)],
        },
        d_max_sample_extreme={}, stick_probability={}, stick_count_mean={}, stick_count_mean_se={},
        x_gh_mean_se={}, x_gh_std_se={},
    )
    html = verdict_section([SimpleNamespace(kind="damping", summary=summary)])
    assert html.startswith("<h2>Verdict</h2>") and "<h3>brake</h3>" in html
    # the page says whose friction model the verdict is about (issue 30, item 7)
    assert "Whose friction model" in html and "thesis&#x27;s friction-process model of that preset" in html
    rows = html.split("<tr>")[2:]
    assert len(rows) == 3
    assert rows[0].endswith("<td>holds</td></tr>")                        # every interval at or below D_max^d
    assert "<b>not safe</b>: contact stick-slips above it" in rows[1]     # contact [0.2, 0.25] > 0.15
    assert "not resolved (white: more runs)" in rows[2]                   # white [0.2, 0.25] reaches above 0.2
    assert "0.2 [0.2, 0.25]" in rows[1]


def test_no_verdict_without_a_damping_study() -> None:
    assert verdict_section([SimpleNamespace(kind="forcing", summary={"preset": "brake"})]) == ""

"""Regression tier: numbers the project itself produced with fixed seeds (numpy 2.4, numba 0.68).

The simulations are deterministic given the seed (per-task and per-trajectory streams), so
grid-valued results (D_max) are pinned exactly and real numbers to a relative 1e-6 (room
for compiler/libm differences only).  If an intended change of the numerics moves them,
re-pin and say why in the commit.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest

from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.forcing import forcing_study
from stochfric.studies.lyapunov import lyapunov_study
from stochfric.studies.normal_force import normal_force_study

RTOL = 1e-6


def test_damping_brake_5600() -> None:
    s = damping_study(DampingConfig(normal_forces=(5600.0,), runs=10, seed=0)).to_json_dict()
    assert s["d_hopf"][0] == pytest.approx(0.09461801564752419, rel=1e-9)
    assert s["d_max_deterministic"] == [PIN["damping"]["det"]]
    assert s["d_max_sample_extreme"]["white"][0] == PIN["damping"]["white"]
    assert s["d_max_sample_extreme"]["contact"][0] == PIN["damping"]["contact"]
    assert np.sum(s["stick_count_mean"]["white"][0]) == pytest.approx(PIN["damping"]["sum_m_white"], rel=RTOL)
    assert s["d_max_risk"]["white"][0][0] == PIN["damping"]["risk_white"]
    assert s["d_max_risk"]["contact"][0][0] == PIN["damping"]["risk_contact"]


def _first_damping(table: list[list[float]]) -> list[float]:
    """The normal-force study's table [normal_force_n][damping_ratio] at the first D, over N."""
    return [row[0] for row in table]


def test_normal_force_brake() -> None:
    s = normal_force_study(NormalForceConfig(runs=8, seed=1, phase_runs=0)).to_json_dict()
    for m in ("deterministic", "white", "contact"):
        got = np.array(_first_damping(s["x_gh_mean"][m]), dtype=float)
        np.testing.assert_allclose(got, PIN["normal_force"][m], rtol=RTOL)
    np.testing.assert_allclose(np.array(_first_damping(s["x_gh_std"]["contact"]), dtype=float),
                               PIN["normal_force"]["std_contact"], rtol=RTOL)


def test_forcing_and_lyapunov_brake() -> None:
    f = forcing_study(ForcingConfig(eta="0.5:2.5:5", runs=4, seed=2)).to_json_dict()
    np.testing.assert_allclose([f["sigma_ratio_median"]["5e-05"], f["sigma_ratio_median"]["0.0005"]],
                               PIN["forcing"], rtol=RTOL)
    ly = lyapunov_study(LyapunovConfig(normal_forces=(4000.0,), eta=(1.2, 2.0), runs=3, seed=2, tau_end=100.0))
    s = ly.to_json_dict()
    # issue 10: the numbers of (4.43)/(4.44) as printed are unchanged; since then they are kept under
    # `separation_index_443` (with a status: "nonlinear" where the twin check finds w not ∝ δ, here
    # white, q = 5e-5), and `lyapunov` is the δ-independent exponent per transition.
    got = np.array(s["separation_index_443"]["deterministic"], dtype=float).ravel()
    np.testing.assert_allclose(got, PIN["lyapunov_det"], rtol=RTOL)
    got = np.array(s["separation_index_443"]["white"], dtype=float).ravel()
    np.testing.assert_allclose(got, PIN["lyapunov_white"], rtol=RTOL)
    assert list(np.array(s["separation_index_status"]["white"]).ravel()) == ["nonlinear", "nonlinear", "ok", "ok"]
    for m in ("deterministic", "white", "contact"):
        lam = np.array(s["lyapunov"][m], dtype=float).ravel()
        np.testing.assert_array_equal(np.isnan(lam), np.array(s["status"][m]).ravel() != "ok")


@pytest.mark.parametrize(("preset", "path"), [("brake", "position"), ("sheet", "mass")])
def test_reproduction_modes(preset: str, path: str) -> None:
    """Issue 10: the recommended thesis reproductions (thesis white, psd_level, position / mass path)."""
    s = normal_force_study(NormalForceConfig(preset=preset, runs=8, seed=5, phase_runs=0, white_intensity="thesis",
                                             process_level="psd_level", path_coordinate=path)).to_json_dict()
    assert s["white_increment"] == "thesis" and s["process_level"] == "psd_level" and s["path_coordinate"] == path
    pin = PIN_MODES[preset]
    np.testing.assert_allclose(_first_damping(s["x_gh_std"]["white"]), pin["white"], rtol=RTOL)
    np.testing.assert_allclose(_first_damping(s["x_gh_std"]["contact"]), pin["contact"], rtol=RTOL)
    np.testing.assert_allclose(s["sigma_zeta_effective"], pin["sigma_zeta_effective"], rtol=1e-12)


#: issue 10, generated with the call above (seeded).  Re-pinned for issue 19: streams keyed by the cell's
#: parameter values (studies.tasks.cell_stream_key) and a contact process that never repeats (independent
#: segments) — both change every stochastic number by design; the deterministic entries did not move.
PIN_MODES: dict[str, dict[str, list[float]]] = {
    "brake": {"white": [5.8053676624080666e-05, 0.00012527227847765722, 0.000242686123055399],
              "contact": [0.00013287863596350225, 0.00010740433462216355, 0.0004506023336558945],
              "sigma_zeta_effective": [0.3000429846205081, 0.27214971166199203, 0.2584938819092959]},
    "sheet": {"white": [0.00018184415660183194, 0.00042113256534908456, 0.000643622834585861],
              "contact": [0.0004957928734838899, 0.000991339726030591, 0.0012466094969900586],
              "sigma_zeta_effective": [0.12631611612913693, 0.1084441895613858, 0.09272322369419539]},
}


#: generated with the calls above (seeded), numpy 2.4.6, numba 0.68.1, Python 3.11.7.  Re-pinned for
#: issue 19 (see PIN_MODES): seeds by cell and the never-repeating contact process moved the stochastic
#: entries; the Lyapunov study's default integrator became ``accurate`` (converged; Euler at the thesis's
#: Δτ is the reproduction mode), which moved its deterministic entries.  The deterministic normal-force
#: and damping entries are unchanged since they were first pinned.
PIN: dict[str, Any] = {
    "damping": {"det": 0.14, "white": {"value": 0.15, "interval": [0.15, 0.165]},
                "contact": {"value": 0.2, "interval": [0.2, 0.215]}, "sum_m_white": 127.9,
                "risk_white": {"risk_level": 0.1, "value": 0.15, "interval": [0.14, 0.25],
                               "high_open": True, "resolved": False},
                "risk_contact": {"risk_level": 0.1, "value": 0.2, "interval": [0.18, 0.25],
                                 "high_open": True, "resolved": False}},
    "normal_force": {
        "deterministic": [-2.0643135547601296e-05, -0.0005630499940741167, -5.490876691743714e-05],
        "white": [-1.5754582498388397e-05, -0.0005608523820198771, -4.4083895621551346e-05],
        "contact": [-2.211791499082217e-05, -0.0005906932188857842, -6.409854142417375e-05],
        "std_contact": [0.0001280247120473844, 0.00029814185334739777, 0.0004665773487976754],
    },
    "forcing": [3.7772164261663637, 1.4349337230189585],
    "lyapunov_det": [-0.581617020540744, -0.3332387199950408, 0.6990328466577442, 0.05891975476539867],
    "lyapunov_white": [-0.09214744427296191, -0.4587969638082913, -1.777536674851295, 0.03849742468260434],
}

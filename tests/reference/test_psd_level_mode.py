"""Reproduction mode ``process_level = "psd_level"`` (issue 10): the process variance from the
thesis's E[S](p) fits, normalised by the thesis's own check σ_μ̂SD = 0.08 at 0.5 MPa (§3.2.5)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.friction_process.presets import BRAKE_PSD_LEVEL_FIT, brake_process, process_with_level, psd_level_process
from stochfric.oscillator.case import CaseError, case_setup
from stochfric.oscillator.presets import get_preset


def test_calibration_reproduces_the_thesis_check_and_scales_with_es() -> None:
    b = get_preset("brake")
    m = psd_level_process(brake_process(), BRAKE_PSD_LEVEL_FIT)
    assert b.process_with_level("psd_level") == m
    assert m.std(5e5) == pytest.approx(0.08, rel=1e-12)  # the thesis's Fig. 3.23 check
    fit = b.recorded_psd_level_fit
    assert fit is not None
    for p in (4.5e4, 1.7e5, 5e5):  # 720 / 2720 / 8000 N
        assert m.std(p) / m.std(5e5) == pytest.approx(math.sqrt(fit(p) / fit(5e5)), rel=1e-12)
    # documented ratios to σ_μ(p): brake 1.31 / 1.20 / 1.09, sheet 2.26 / 2.26 / 2.29
    got = [m.std(b.pressure(f)) / b.process.std(b.pressure(f)) for f in (720.0, 2720.0, 8000.0)]
    np.testing.assert_allclose(got, [1.309, 1.199, 1.094], atol=1e-3)
    s = get_preset("sheet")
    ms = s.process_with_level("psd_level")
    got = [ms.std(s.pressure(f)) / s.process.std(s.pressure(f)) for f in (400.0, 880.0, 1750.0)]
    np.testing.assert_allclose(got, [2.255, 2.255, 2.289], atol=1e-3)
    assert ms.calibration == m.calibration  # one normalisation for both surfaces


def test_realisations_spectrum_and_white_intensity() -> None:
    s = get_preset("sheet")
    m = s.process_with_level("psd_level")
    p = s.pressure(880.0)
    x = m.generate(p, np.random.default_rng(1))
    assert np.var(x) == pytest.approx(m.std(p) ** 2, rel=1e-10)  # periodic grid: exact grid variance
    assert m.variance(p) == pytest.approx(m.std(p) ** 2, rel=1e-12)
    base = s.process.generate(p, np.random.default_rng(1))
    np.testing.assert_allclose(x, base * m.std(p) / s.process.std(p), rtol=1e-12)  # same phases
    assert m.sigma_zeta(p) == s.process.sigma_zeta(p)  # white noise unchanged (Table 4.4 ≈ σ_μ)
    assert m.mean(p) == s.process.mean(p)
    assert m.to_dict()["kind"] == "psd_level"


def test_setup_and_errors(tmp_path) -> None:  # type: ignore[no-untyped-def]
    st = case_setup("brake", process_level="psd_level")
    assert st.process_level == "psd_level" and st.process.std(5e5) == pytest.approx(0.08)
    assert "psd_level" in st.process_source and st.describe()["process_level"] == "psd_level"
    assert process_with_level(brake_process(), None, "sigma_mu") == get_preset("brake").process
    with pytest.raises(ValueError, match="no E\\[S\\]\\(p\\) fit"):
        process_with_level(brake_process(), None, "psd_level")
    with pytest.raises(CaseError, match="process_level"):
        case_setup("brake", process_level="loud")
    f = tmp_path / "m.json"
    get_preset("brake").process.save(f)
    with pytest.raises(CaseError, match="cannot be combined"):
        case_setup("brake", process_file=f, process_level="psd_level")

"""Height moments, PDFs, summit statistics and the plasticity index."""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.statistics import (
    height_moments,
    pdf,
    plasticity_index,
    plasticity_verdict,
    surface_statistics,
)
from stochfric.surface.summits import summits_of


def test_height_moments_exact_two_point() -> None:
    sq, skew, kurt = height_moments(np.array([[1.0, -1.0], [3.0, 1.0]]) - 1.0)
    assert sq == pytest.approx(math.sqrt(2.0))
    assert skew == pytest.approx(0.0)
    assert kurt == pytest.approx(2.0)  # m4 = 8, m2² = 4
    assert math.isnan(height_moments(np.ones((3, 3)))[1])


def test_height_moments_gaussian_within_standard_error() -> None:
    n = 200_000
    z = np.random.default_rng(11).normal(0.0, 2.0, size=n)
    sq, skew, kurt = height_moments(z)
    # standard errors of the sample moments of a Gaussian: σ/√(2n), √(6/n), √(24/n)
    assert abs(sq - 2.0) < 4 * 2.0 / math.sqrt(2 * n)
    assert abs(skew) < 4 * math.sqrt(6 / n)
    assert abs(kurt - 3.0) < 4 * math.sqrt(24 / n)


def test_pdf_is_normalised() -> None:
    v = np.random.default_rng(0).exponential(size=5000)
    x, d = pdf(v, 30)
    width = (v.max() - v.min()) / 30
    assert np.sum(d) * width == pytest.approx(1.0)
    assert x.size == 30
    with pytest.raises(SurfaceError):
        pdf([], 10)
    with pytest.raises(SurfaceError):
        pdf([1.0, np.nan], 10)


def test_surface_statistics_consistent_with_summits() -> None:
    z = np.random.default_rng(5).normal(size=(50, 40)) * 1e-6
    s = Surface(heights_m=z, physical_size_m=(5e-4, 4e-4))
    sm = summits_of(s)
    st = surface_statistics(s, sm)
    assert st.grid == (50, 40)
    assert st.n_summits == sm.count > 0
    assert st.summit_height_std_m == pytest.approx(np.std(sm.heights_m))
    assert st.summit_radius_mean_m == pytest.approx(np.mean(sm.radius_m))
    assert st.summit_density_per_m2 == pytest.approx(sm.count / 2e-7)
    assert st.sq_m == pytest.approx(np.std(z))
    d = st.to_dict()
    assert d["grid"] == [50, 40]


def test_plasticity_index_formula_and_verdict() -> None:
    # γ = (E*/H) √(σ_S/β̄)
    g = plasticity_index(e_star_pa=1.1e9, hardness_pa=1.708e9, sigma_s_m=1e-6, beta_mean_m=25e-6)
    assert g == pytest.approx(1.1 / 1.708 * 0.2)
    assert plasticity_verdict(0.35) == "elastic"
    assert plasticity_verdict(0.8) == "elastic-plastic"
    assert plasticity_verdict(5.8) == "plastic"
    assert plasticity_verdict(0.6) == "elastic-plastic"
    assert plasticity_verdict(1.0) == "elastic-plastic"
    with pytest.raises(SurfaceError):
        plasticity_index(e_star_pa=1e9, hardness_pa=0.0, sigma_s_m=1e-6, beta_mean_m=1e-5)
    with pytest.raises(SurfaceError):
        plasticity_index(e_star_pa=1e9, hardness_pa=1e9, sigma_s_m=math.nan, beta_mean_m=1e-5)

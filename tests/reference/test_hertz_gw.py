"""Reference tests of the GW/Hertz contact sums (thesis 2.4.1–2.4.2, 3.1.3).

1. A single Hertz asperity, exactly.
2. Discrete sums over a large synthetic set of Gaussian summit heights against the GW
   integrals (2.89)/(2.90) evaluated numerically, within 4 Monte Carlo standard errors
   (the standard error of a sum of K i.i.d. terms is √K · std(term), the term's variance
   taken from the same closed forms / quadrature).
3. Linear growth of the contact area with the load once many summits touch (GW), against
   A ∝ N^{2/3} for one asperity (Hertz).
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from stochfric.contact.asperity import asperity_sums
from stochfric.contact.reference import (
    gw_contact,
    gw_integral,
    gw_integral_closed,
    hertz_contact,
    hertz_indentation_from_force,
)

E_STAR = 1.1e9  # Pa
BETA = 20e-6  # m
SIGMA = 1e-6  # m
K = 200_000
SEED = 20130101


@pytest.mark.parametrize("delta", [1e-9, 0.3e-6, 2e-6])
def test_single_hertz_asperity_exact(delta: float) -> None:
    a, f, n = asperity_sums([0.0], [BETA], [delta], e_star_pa=E_STAR)
    hz = hertz_contact(radius_m=BETA, e_star_pa=E_STAR, indentation_m=delta)
    assert n[0] == 1
    assert a[0] == pytest.approx(math.pi * BETA * delta, rel=1e-13)  # (3.8), a² = βδ (2.74)
    assert f[0] == pytest.approx(4 / 3 * E_STAR * math.sqrt(BETA * delta**3), rel=1e-13)  # (3.9)
    assert a[0] == pytest.approx(hz.contact_area_m2, rel=1e-13)
    assert f[0] == pytest.approx(hz.normal_force_n, rel=1e-13)
    # (2.75)/(2.76): N = (2/3) p0 π a², a = (3Nβ/(4E*))^{1/3}
    assert hz.normal_force_n == pytest.approx(2 / 3 * hz.max_pressure_pa * math.pi * delta * BETA)
    assert hertz_indentation_from_force(radius_m=BETA, e_star_pa=E_STAR, force_n=hz.normal_force_n) == pytest.approx(
        delta, rel=1e-12
    )
    # single-asperity μ = A τ / N = 3π τ √β / (4 E* √δ)
    tau = 35e6
    assert a[0] * tau / f[0] == pytest.approx(
        3 * math.pi * tau * math.sqrt(BETA) / (4 * E_STAR * math.sqrt(delta)), rel=1e-12
    )


def test_gw_integrals_quadrature_against_closed_forms() -> None:
    h = np.linspace(-2.0, 4.0, 13)
    for order in (0, 1, 2):
        np.testing.assert_allclose(gw_integral(float(order), h), gw_integral_closed(order, h), rtol=1e-10, atol=1e-300)
    # F_{3/2} lies between F_1 and F_2 in the log-convex sense: F_{3/2}² <= F_1 F_2
    f1, f15, f2 = gw_integral(1.0, h), gw_integral(1.5, h), gw_integral(2.0, h)
    assert np.all(f15**2 <= f1 * f2 * (1 + 1e-12))
    # F_{3/2}(0) = 2^{1/4} Γ(5/4) / √(2π)
    expected = 2**0.25 * math.gamma(1.25) / math.sqrt(2 * math.pi)
    assert float(gw_integral(1.5, 0.0)) == pytest.approx(expected, rel=1e-10)


@pytest.fixture(scope="module")
def gaussian_summits() -> np.ndarray:
    return np.random.default_rng(SEED).normal(0.0, SIGMA, K)


@pytest.mark.parametrize("h", [0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
def test_discrete_sums_match_gw_integrals(gaussian_summits: np.ndarray, h: float) -> None:
    z = gaussian_summits
    d = h * SIGMA  # flat at d above the mean summit height (the distribution's mean, 0)
    u = z.max() - d  # approach from the highest summit, (3.11)
    a, f, n = asperity_sums(z, np.full(K, BETA), [u], e_star_pa=E_STAR)
    gw = gw_contact(n_summits=K, radius_m=BETA, sigma_m=SIGMA, e_star_pa=E_STAR, separation_m=d)

    # expectation and Monte Carlo standard error of each sum
    p0 = float(gw_integral_closed(0, h))
    se_n = math.sqrt(K * p0 * (1 - p0))
    f1, f2 = float(gw_integral(1.0, h)), float(gw_integral(2.0, h))
    se_a = math.pi * BETA * SIGMA * math.sqrt(K * (f2 - f1**2))
    f15, f3 = float(gw_integral(1.5, h)), float(gw_integral(3.0, h))
    scale_n = 4 / 3 * E_STAR * math.sqrt(BETA) * SIGMA**1.5
    se_f = scale_n * math.sqrt(K * (f3 - f15**2))

    assert abs(n[0] - gw.n_contacts) < 4 * se_n
    assert abs(a[0] - gw.contact_area_m2) < 4 * se_a
    assert abs(f[0] - gw.normal_force_n) < 4 * se_f
    # where thousands touch the tolerance is tight: a wrong factor or exponent fails
    if h <= 2.0:
        assert 4 * se_a < 0.1 * gw.contact_area_m2
        assert 4 * se_f < 0.1 * gw.normal_force_n


def test_area_grows_linearly_with_load_once_many_touch(gaussian_summits: np.ndarray) -> None:
    z = gaussian_summits
    hs = np.linspace(3.0, 1.5, 7)  # from ~270 to ~13 400 contacts
    u = z.max() - hs * SIGMA
    a, f, n = asperity_sums(z, np.full(K, BETA), u, e_star_pa=E_STAR)
    assert n.min() > 200
    slope = np.diff(np.log(a)) / np.diff(np.log(f))
    # GW: d ln A / d ln N between 0.93 and 0.97 in this range; Hertz would give 2/3
    assert np.all(slope > 0.9)
    assert np.all(slope < 1.0)
    # the load grows ~100-fold; A/N changes by ~1.26 where Hertz (A/N ∝ N^{-1/3}) gives ~4.7
    load_factor = f[-1] / f[0]
    assert load_factor > 50
    ratio = a / f
    assert ratio.max() / ratio.min() < 1.3
    assert ratio.max() / ratio.min() < 0.3 * load_factor ** (1 / 3)
    # the GW integrals give the same slopes
    gw = gw_contact(n_summits=K, radius_m=BETA, sigma_m=SIGMA, e_star_pa=E_STAR,
                    separation_m=hs * SIGMA)  # fmt: skip
    gw_slope = np.diff(np.log(gw.contact_area_m2)) / np.diff(np.log(gw.normal_force_n))
    np.testing.assert_allclose(slope, gw_slope, atol=0.03)
    # one asperity: A ∝ N^{2/3}
    a1, f1, _ = asperity_sums([0.0], [BETA], [1e-7, 1e-6], e_star_pa=E_STAR)
    assert np.log(a1[1] / a1[0]) / np.log(f1[1] / f1[0]) == pytest.approx(2 / 3, rel=1e-12)

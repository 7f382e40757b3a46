"""Multi-scale marginal-matching surrogates (:mod:`stochfric.surface.multiscale`, issue 29 item 4).

Fixed seeds; the tolerances are the estimators' standard errors (the Laplacian kurtosis: √(24/n_s) with
n_s the summit count, as the curvature test of ``auto``; the summit statistics: the ensemble's own sd,
z = (map − ensemble mean)/ensemble sd over 8 surrogates).  No timing is asserted.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest
from scipy.stats import kurtosis

from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.multiscale import (
    MULTISCALE_METHOD,
    band_count,
    band_masks,
    decompose,
    laplacian,
    multiscale_heights,
    resample_sorted,
)
from stochfric.surface.quilting import max_normalised_correlation
from stochfric.surface.summits import find_summits
from stochfric.surface.surrogates import SURROGATES, MultiscaleSurrogate, similar_surface
from stochfric.surface.synthesis import phase_longer_heights
from synthetic_maps import gaussian_heights, spiky_heights  # tests/synthetic_maps.py

SPACING = (1e-6, 1e-6)
ENSEMBLE = 8


_field = gaussian_heights


_spiky = spiky_heights


def _kurt(z: np.ndarray) -> float:
    return float(kurtosis(laplacian(z).ravel(), fisher=False))


def _stats(z: np.ndarray) -> np.ndarray:
    """(summit count, β̄, σ_S, Laplacian kurtosis)."""
    s = find_summits(z, SPACING)
    return np.array([s.count, s.radius_m.mean(), s.heights_m.std(), _kurt(z)])


def _z(measured: np.ndarray, ensemble: list[np.ndarray]) -> np.ndarray:
    e = np.array(ensemble)
    return np.asarray((measured - e.mean(0)) / e.std(0, ddof=1))


def test_bands_are_an_exact_partition_periodic_and_mirrored() -> None:
    z = np.random.default_rng(1).standard_normal((50, 37)).cumsum(0)
    masks = band_masks((50, 37))
    total = masks.sum(0)
    assert masks.shape == (band_count((50, 37)), 50, 37 // 2 + 1)
    assert total[0, 0] == 0.0 and np.allclose(np.delete(total.ravel(), 0), 1.0, atol=1e-12)
    assert masks.min() >= 0.0
    for mirror in (False, True):
        b = decompose(z, mirror=mirror)
        assert np.allclose(b.sum(0) + z.mean(), z, atol=1e-12 * np.abs(z).max())
    assert [band_count(s) for s in [(200, 296), (600, 960), (3, 3), (8, 100)]] == [6, 8, 1, 2]


def test_resample_sorted_repeats_or_interpolates_quantiles() -> None:
    v = np.array([3.0, 1.0, 2.0])
    assert np.array_equal(resample_sorted(v, 3), [1.0, 2.0, 3.0])
    assert np.array_equal(resample_sorted(v, 6), [1.0, 1.0, 2.0, 2.0, 3.0, 3.0])
    r = resample_sorted(np.arange(100.0), 250)
    assert r.size == 250 and np.all(np.diff(r) >= 0) and r[0] == 0.0 and r[-1] == 99.0
    assert r.mean() == pytest.approx(49.5, abs=0.05)


def test_gaussian_map_stays_gaussian_with_its_spectrum_and_variance() -> None:
    g = _field((160, 192), 1.5, seed=11)
    n_s = find_summits(g, SPACING).count
    se = np.sqrt(24.0 / n_s)  # the SE of the curvature test of ``auto``
    for seed in range(3):
        r = multiscale_heights(g, seed)
        assert abs(_kurt(r.heights) - 3.0) < 3.0 * se
        assert r.amplitude_error < 0.03  # IAAFT after one remap: 3.4 % on the shipped map
        assert np.array_equal(np.sort(r.heights, axis=None), np.sort(g, axis=None))  # heights exact
        phase = phase_longer_heights(g, 1, seed)
        ratios = [a.var() / b.var() for a, b in zip(decompose(r.heights), decompose(phase), strict=True)]
        # every octave's power within 10 % of the spectrum's, but the finest one: the band of a smooth
        # field (corr 1.5 points) at a 2-point wavelength holds ~e⁻¹¹ of the variance, there the edges of
        # the measured map (mirror kinks) dominate its histogram
        assert all(abs(x - 1.0) < 0.1 for x in ratios[1:]), ratios


def test_non_gaussian_map_summits_and_curvature_are_much_closer_than_random_phases() -> None:
    z = _spiky((160, 192))
    measured = _stats(z)
    assert measured[3] > 15.0  # far from Gaussian curvature
    phase = [_stats(phase_longer_heights(z, 1, seed)) for seed in range(100, 100 + ENSEMBLE)]
    multi = [_stats(multiscale_heights(z, seed).heights) for seed in range(100, 100 + ENSEMBLE)]
    z_phase, z_multi = np.abs(_z(measured, phase)), np.abs(_z(measured, multi))
    # random phases fail the summit check (β̄, σ_S) and the curvature by far; the multiscale ones pass
    assert z_phase[1:3].min() > 5.0 and z_phase[3] > 100.0, z_phase
    assert z_multi[:3].max() < 3.0 and z_multi[3] < 5.0, z_multi
    assert np.all(z_multi < 0.5 * z_phase), (z_multi, z_phase)
    kurt_multi = np.mean([s[3] for s in multi])
    assert kurt_multi == pytest.approx(measured[3], rel=0.5)


def test_a_surrogate_is_a_new_map_not_a_copy() -> None:
    z = _spiky((160, 192))
    a = multiscale_heights(z, 1).heights
    b = multiscale_heights(z, 2).heights
    assert max_normalised_correlation(a, z) < 0.5
    assert max_normalised_correlation(b, z) < 0.5
    assert not np.array_equal(a, b) and max_normalised_correlation(a, b) < 0.5


def test_a_longer_map_has_the_same_marginals() -> None:
    z = _spiky((160, 192))
    r = multiscale_heights(z, 7, factor=3)
    assert r.heights.shape == (160, 3 * 192)
    assert np.array_equal(np.sort(r.heights, axis=None), np.repeat(np.sort(z, axis=None), 3))
    se = np.sqrt(24.0 / find_summits(z, SPACING).count)
    assert abs(_kurt(r.heights) - 3.0) > 10 * se  # non-Gaussian curvature
    assert _kurt(r.heights) == pytest.approx(_kurt(z), rel=0.5)
    q = [0.01, 0.5, 0.99]
    assert np.allclose(np.quantile(laplacian(r.heights), q), np.quantile(laplacian(z), q), rtol=0.15)
    measured, long = decompose(z, mirror=True), decompose(r.heights)
    for j in range(1, measured.shape[0]):  # every band's spread; the finest one reads the map's edges
        assert long[j].std() == pytest.approx(measured[j].std(), rel=0.1), j
    assert r.amplitude_error < 0.1


def test_deterministic_by_seed() -> None:
    z = _spiky((96, 80), seed=3)
    a = multiscale_heights(z, np.random.default_rng(5))
    b = multiscale_heights(z, np.random.default_rng(5))
    assert np.array_equal(a.heights, b.heights) and a.iterations == b.iterations
    m = MultiscaleSurrogate(iterations=3)
    from stochfric.surface.surrogates import SurrogateSettings

    s = SurrogateSettings()
    assert np.array_equal(m.heights(z, np.random.default_rng(9), factor=2, settings=s),
                          m.heights(z, np.random.default_rng(9), factor=2, settings=s))


def test_bad_arguments_are_refused() -> None:
    z = _field((40, 40), 1.0, seed=2)
    for kw in ({"factor": 0}, {"iterations": 0}, {"bands": 0}, {"laplacian_bands": 0}, {"tol": -1.0}):
        with pytest.raises(SurfaceError):
            multiscale_heights(z, 0, **kw)


@pytest.fixture
def registered() -> Iterator[MultiscaleSurrogate]:
    """``register()`` for the test; the registry is as it was afterwards."""
    before = dict(SURROGATES)
    method = SURROGATES[MULTISCALE_METHOD]  # registered by the package (offered by name, not by auto)
    assert isinstance(method, MultiscaleSurrogate)
    yield method
    assert dict(SURROGATES) == before


def test_register_once_then_similar_surface(registered: MultiscaleSurrogate) -> None:
    assert SURROGATES[MULTISCALE_METHOD] is registered
    z = _spiky((96, 112), seed=4)
    surface = Surface(heights_m=z, physical_size_m=(96e-6, 112e-6))
    s = similar_surface(surface, np.random.default_rng(0), method=MULTISCALE_METHOD)
    assert s.heights_m.shape == z.shape and s.info["surrogate"] == MULTISCALE_METHOD
    longer = similar_surface(surface, 1, method=MULTISCALE_METHOD, factor=2)
    assert longer.heights_m.shape == (96, 224) and longer.physical_size_m == pytest.approx((96e-6, 224e-6))
    cost = registered.cost_seconds((96, 112), 4)
    assert np.isfinite(cost) and cost > 0.0

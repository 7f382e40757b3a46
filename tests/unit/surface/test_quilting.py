"""Quilted surrogates (stochfric.surface.quilting)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.ndimage import gaussian_filter

from stochfric.process.ensemble import summit_statistics
from stochfric.random import spawn_generators
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.quilting import (
    QuiltParameters,
    copy_metrics,
    largest_verbatim_piece,
    low_band,
    max_patch,
    quilt_heights,
    quilt_parameters,
    screened_poisson,
    source_gradients,
)
from stochfric.surface.summits import find_summits
from stochfric.surface.surrogates import SURROGATES as SURROGATE_METHODS
from stochfric.surface.surrogates import similar_surface


def _field(n: int = 160, m: int = 192, corr: float = 2.0, seed: int = 0) -> np.ndarray:
    """A smooth stationary Gaussian field (Gaussian-filtered white noise, unit variance)."""
    z = gaussian_filter(np.random.default_rng(seed).standard_normal((n, m)), corr, mode="wrap")
    return np.asarray(z / z.std())


def test_registered() -> None:
    assert "quilt" in SURROGATE_METHODS


def test_screened_poisson_identity() -> None:
    z = _field(40, 50)
    i, j = np.indices(z.shape)
    gx, gy = source_gradients(z, i, j, np.zeros(z.shape, dtype=np.int8))
    np.testing.assert_allclose(screened_poisson(z, gx, gy, 7.0), z, atol=1e-10)


def test_one_patch_returns_the_map() -> None:
    z = _field(48, 48)
    par = QuiltParameters(patch=48, overlap=1, candidates=1, rotate=False, screening_length=12.0)
    res = quilt_heights(z, 3, parameters=par)
    np.testing.assert_allclose(res.heights, z, atol=1e-10)
    assert largest_verbatim_piece(res.source_i, res.source_j, res.rotated) == z.size


def test_rotated_source_gradients_keep_the_map() -> None:
    z = _field(30, 40)
    i, j = np.indices(z.shape)
    zr = z[::-1, ::-1]  # the map rotated by 180°, taken from the source with rotated = 1
    gx, gy = source_gradients(z, z.shape[0] - 1 - i, z.shape[1] - 1 - j, np.ones(z.shape, dtype=np.int8))
    np.testing.assert_allclose(screened_poisson(zr, gx, gy, 5.0), zr, atol=1e-10)


def test_deterministic_given_the_seed() -> None:
    z = _field()
    a = quilt_heights(z, np.random.default_rng(5)).heights
    b = quilt_heights(z, np.random.default_rng(5)).heights
    c = quilt_heights(z, np.random.default_rng(6)).heights
    np.testing.assert_array_equal(a, b)
    assert not np.allclose(a, c)


def test_shape_and_factor() -> None:
    z = _field()
    assert quilt_heights(z, 1, factor=3).heights.shape == (z.shape[0], 3 * z.shape[1])
    s = Surface(heights_m=z * 1e-7, physical_size_m=(1e-4, 1.2e-4))
    long = similar_surface(s, 2, method="quilt", factor=2)
    assert long.heights_m.shape == (z.shape[0], 2 * z.shape[1])
    assert long.physical_size_m == pytest.approx((1e-4, 2.4e-4))
    assert long.info["surrogate"] == "quilt"


def test_copy_check_flags_a_copy_and_passes_a_surrogate() -> None:
    z = _field()
    shifted = z[13:, 21:]  # a shifted crop of the map is a copy
    assert copy_metrics(shifted, z).is_copy
    rolled = np.roll(z, (40, 55), axis=(0, 1))  # a periodic shift covers the map in 4 verbatim pieces
    assert copy_metrics(rolled, z).max_ncc > 0.99
    res = quilt_heights(z, 11)
    m = copy_metrics(res.heights, z, source=res)
    assert not m.is_copy
    assert m.largest_piece_fraction < 0.1
    assert m.max_ncc < 0.9
    # a source map that is one constant offset is one verbatim piece: the whole map
    i, j = np.indices(z.shape)
    assert largest_verbatim_piece(i, j, np.zeros(z.shape, dtype=np.int8)) == z.size


def test_seams_keep_summit_density_and_height_sd() -> None:
    """On a stationary Gaussian field the quilt's summit count and σ_S match the map within the
    spread of an ensemble of independent maps of the same field (|z| < 4)."""
    n_real = 8
    maps = [_field(seed=s) for s in range(1, n_real + 1)]
    ref = np.array([summit_statistics(*_hr(m)) for m in maps])  # independent maps: the natural spread
    z = _field(seed=0)
    quilts = np.array([summit_statistics(*_hr(quilt_heights(z, g).heights)) for g in spawn_generators(2, n_real)])
    meas = np.array(summit_statistics(*_hr(z)))
    sd = np.hypot(ref.std(axis=0, ddof=1), quilts.std(axis=0, ddof=1))
    zscore = (quilts.mean(axis=0) - meas) / sd
    assert abs(zscore[0]) < 4.0, zscore  # summit count
    assert abs(zscore[2]) < 4.0, zscore  # σ_S


def _hr(z: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    s = find_summits(z, (1.0, 1.0), rule="thesis")
    return s.heights_m, s.radius_m


def test_bad_sizes() -> None:
    with pytest.raises(SurfaceError):
        QuiltParameters(patch=2, overlap=1)
    with pytest.raises(SurfaceError):
        QuiltParameters(patch=20, overlap=11)
    with pytest.raises(SurfaceError):
        QuiltParameters(patch=20, overlap=5, candidates=2, choose=3)
    with pytest.raises(SurfaceError):
        quilt_parameters(np.zeros((20, 20)))  # too small to quilt
    with pytest.raises(SurfaceError):
        quilt_heights(_field(30, 30), 1, parameters=QuiltParameters(patch=40, overlap=10))
    with pytest.raises(SurfaceError):
        quilt_heights(_field(), 1, factor=0)
    with pytest.raises(SurfaceError):
        quilt_heights(np.full((50, 50), np.nan), 1)


def test_low_band_has_the_maps_low_pass_power() -> None:
    """Random-sign DCT low band: the map's low-pass variance exactly (factor 1), the mean kept,
    about the same variance on a longer grid, deterministic given the generator."""
    z = _field(120, 150, corr=6.0) + 3.0
    lam = 40.0
    from scipy import fft as sfft

    from stochfric.surface.quilting import _dct_wavenumbers, _split_gain

    coef = sfft.dctn(z - z.mean(), norm="ortho") * _split_gain(_dct_wavenumbers(*z.shape), lam)
    target = float(np.sum(coef**2)) / z.size
    a = low_band(z, lam, 5)
    assert a.shape == z.shape
    assert a.mean() == pytest.approx(z.mean(), abs=1e-12)
    assert a.var() == pytest.approx(target, rel=1e-6)
    assert not np.allclose(a, low_band(z, lam, 6))
    np.testing.assert_array_equal(a, low_band(z, lam, 5))
    long = low_band(z, lam, 7, factor=3)
    assert long.shape == (120, 450)
    assert long.var() == pytest.approx(target, rel=0.02)


def test_max_patch_keeps_a_piece_below_the_copy_limit() -> None:
    assert max_patch(650, 650) == 205  # 1/3 would be 216: 216² > 10 % of the map
    assert max_patch(960, 600) == 200
    for nx, ny in ((100, 100), (768, 576), (1700, 1700), (300, 900)):
        p = max_patch(nx, ny)
        assert p * p < 0.1 * nx * ny and p <= min(nx, ny) / 3


def test_fused_seam_repair_equals_the_two_step_form_bit_for_bit() -> None:
    """quilt_heights builds κ² hard − div g point by point (no gradient arrays, for memory); it must equal
    source_gradients + screened_poisson exactly."""
    from stochfric.surface.quilting import _seam_rhs, _solve_screened, screened_poisson, source_gradients

    rng = np.random.default_rng(8)
    z = rng.standard_normal((40, 50))
    hard = rng.standard_normal((33, 70))
    si = rng.integers(0, 40, size=hard.shape).astype(np.int32)
    sj = rng.integers(0, 50, size=hard.shape).astype(np.int32)
    rot = rng.integers(0, 2, size=hard.shape).astype(np.int8)
    gx, gy = source_gradients(z, si, sj, rot)
    two_step = screened_poisson(hard, gx, gy, 7.0)
    kappa2 = 1.0 / 49.0
    fused = _solve_screened(_seam_rhs(z, si, sj, rot, hard, kappa2), kappa2)
    assert np.array_equal(two_step, fused)

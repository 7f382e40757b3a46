"""Detrend, median filter, coarsening and the Preparation record."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.preprocess import Preparation, coarsen, detrend, median_filter, prepare


def _rough(nx: int = 40, ny: int = 30, seed: int = 0) -> np.ndarray:
    return np.random.default_rng(seed).normal(size=(nx, ny))


def test_detrend_plane_removes_tilt_exactly() -> None:
    r = _rough()
    r = detrend(r, "plane")  # a residual is orthogonal to every plane
    i, j = np.meshgrid(np.arange(40.0), np.arange(30.0), indexing="ij")
    tilted = r + 3.0 + 0.2 * i - 0.7 * j
    np.testing.assert_allclose(detrend(tilted, "plane"), r, atol=1e-10)
    np.testing.assert_allclose(detrend(tilted, "height"), r, atol=1e-10)  # alias
    # the plane fit does not remove curvature
    bowl = r + 0.01 * (i - 20.0) ** 2
    assert np.std(detrend(bowl, "plane") - r) > 0.1
    np.testing.assert_allclose(detrend(bowl, "quadratic"), detrend(r, "quadratic"), atol=1e-9)


def test_detrend_matches_surfacetopography() -> None:
    from SurfaceTopography import Topography

    i, j = np.meshgrid(np.arange(40.0), np.arange(30.0), indexing="ij")
    h = _rough() + 0.3 * i + 0.1 * j + 0.002 * i * j
    topo = Topography(h, (4.0, 3.0), periodic=False)
    np.testing.assert_allclose(detrend(h, "plane"), topo.detrend("height").heights(), atol=1e-10)
    np.testing.assert_allclose(detrend(h, "quadratic"), topo.detrend("curvature").heights(), atol=1e-9)


def test_detrend_mean_and_none() -> None:
    h = _rough() + 5.0
    assert detrend(h, "mean").mean() == pytest.approx(0.0, abs=1e-12)
    np.testing.assert_array_equal(detrend(h, "none"), h)
    with pytest.raises(SurfaceError, match="unknown detrend mode"):
        detrend(h, "cubic")


@pytest.mark.parametrize("radius", [1, 2, 3])
def test_median_window_is_2r_plus_1(radius: int) -> None:
    h = _rough(25, 25, seed=radius)
    out = median_filter(h, radius)
    w = 2 * radius + 1
    for i, j in [(10, 10), (radius, 12), (20, 7)]:
        window = h[i - radius : i + radius + 1, j - radius : j + radius + 1]
        assert window.shape == (w, w)
        assert out[i, j] == pytest.approx(np.median(window))


def test_median_removes_impulse_noise_and_zero_is_identity() -> None:
    h = np.zeros((15, 15))
    h[7, 7] = 100.0
    h[3, 4] = -50.0
    assert np.abs(median_filter(h, 1)).max() == 0.0
    np.testing.assert_array_equal(median_filter(h, 0), h)


def test_coarsen_keeps_every_kth_point() -> None:
    h = _rough(53, 50)
    s = Surface(heights_m=h, physical_size_m=(53e-6, 50e-6))
    c = coarsen(s, 10)
    np.testing.assert_array_equal(c.heights_m, h[::10, ::10])
    assert c.nb_grid_pts == (6, 5)
    assert c.grid_spacing_m == pytest.approx((10e-6, 10e-6))
    assert c.physical_size_m == pytest.approx((60e-6, 50e-6))
    assert coarsen(s, 1) is s
    with pytest.raises(SurfaceError, match=r"step 13 leaves 5×4 points of the 53×50 grid.*step <= 10"):
        coarsen(s, 13)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"median_radius": -1}, "median_radius must be >= 0"),
        ({"step": 0}, "step must be >= 1"),
        ({"step": True}, "step must be an integer"),
        ({"step": 2.5}, "step must be an integer"),
        ({"detrend": "spline"}, "unknown detrend mode"),
    ],
)
def test_preparation_validation(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(SurfaceError, match=match):
        Preparation(**kwargs)  # type: ignore[arg-type]


def test_preparation_record_normalises_aliases() -> None:
    p = Preparation(detrend="height", median_radius=5, step=10)
    assert p.to_dict() == {"detrend": "plane", "median_radius": 5, "step": 10}


def test_prepare_order_detrend_median_coarsen() -> None:
    i, _ = np.meshgrid(np.arange(60.0), np.arange(50.0), indexing="ij")
    h = _rough(60, 50) + 0.5 * i
    s = Surface(heights_m=h, physical_size_m=(60e-6, 50e-6))
    fine, coarse = prepare(s, Preparation(detrend="plane", median_radius=2, step=4))
    expected = median_filter(detrend(h, "plane"), 2)
    np.testing.assert_allclose(fine.heights_m, expected)
    np.testing.assert_allclose(coarse.heights_m, expected[::4, ::4])
    assert fine.physical_size_m == s.physical_size_m
    f2, c2 = prepare(s)
    assert c2 is f2  # step 1: one surface


def test_prepare_refuses_tiny_surface() -> None:
    s = Surface(heights_m=np.zeros((4, 10)), physical_size_m=(1.0, 1.0))
    with pytest.raises(SurfaceError, match="only 4×10 points"):
        prepare(s)

"""Synthetic height maps of known statistics for the tests (heights in m, 1 µm RMS, 1 µm pixels)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.surface.io import Surface

Array = npt.NDArray[np.float64]


def gaussian_heights(shape: tuple[int, int], corr: float, seed: int = 0) -> Array:
    """A stationary Gaussian field: Gaussian-filtered white noise (periodic), unit RMS in µm."""
    z = ndimage.gaussian_filter(np.random.default_rng(seed).standard_normal(shape), corr, mode="wrap")
    return np.asarray(1e-6 * z / z.std())


def spiky_heights(shape: tuple[int, int], seed: int = 0) -> Array:
    """A Gaussian field with sparse sharp bumps: strongly non-Gaussian curvature, big enough to quilt."""
    rng = np.random.default_rng(seed)
    z = ndimage.gaussian_filter(rng.standard_normal(shape), 1.0, mode="wrap")
    bumps = np.zeros(shape)
    idx = rng.integers(0, min(shape), size=(shape[0] * shape[1] // 400, 2))
    bumps[idx[:, 0], idx[:, 1]] = 6.0 * z.std()
    z = z + ndimage.gaussian_filter(bumps, 0.8, mode="wrap") * 4.0
    return np.asarray(1e-6 * z / z.std())


def as_surface(heights: Array) -> Surface:
    """``heights`` on 1 µm pixels."""
    return Surface(heights_m=heights, physical_size_m=(heights.shape[0] * 1e-6, heights.shape[1] * 1e-6))

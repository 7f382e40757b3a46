"""Bringing scans of one surface onto one grid (pooled analysis of several measurements).

* :func:`resample_surface` — linear interpolation onto a coarser pixel size (the physical size
  is kept up to a fraction of the new pixel; a finer pixel size is refused: interpolation does
  not add detail).
* :func:`crop_surface` — the centred sub-grid of a given shape (the nominal area follows).
"""

from __future__ import annotations

import numpy as np
from scipy.interpolate import RegularGridInterpolator

from stochfric.surface.io import MIN_GRID_POINTS, Surface, SurfaceError

__all__ = ["crop_surface", "resample_surface"]


def resample_surface(surface: Surface, spacing_m: tuple[float, float]) -> Surface:
    """``surface`` linearly interpolated onto pixels of ``spacing_m = (Δx, Δy)`` [m] (≥ its own)."""
    dx, dy = surface.grid_spacing_m
    tx, ty = float(spacing_m[0]), float(spacing_m[1])
    if not (tx > 0 and ty > 0) or tx < dx * (1 - 1e-9) or ty < dy * (1 - 1e-9):
        raise SurfaceError(f"resampling {surface.source} to {tx:.4g}×{ty:.4g} m pixels: the target must be at least "
                           f"its own {dx:.4g}×{dy:.4g} m")
    nx, ny = surface.nb_grid_pts
    lx, ly = surface.physical_size_m
    mx, my = int(np.floor(lx / tx + 1e-9)), int(np.floor(ly / ty + 1e-9))
    if min(mx, my) < MIN_GRID_POINTS:
        raise SurfaceError(f"resampling {surface.source} to {tx:.4g}×{ty:.4g} m pixels leaves {mx}×{my} points")
    interp = RegularGridInterpolator((np.arange(nx) * dx, np.arange(ny) * dy), surface.heights_m,
                                     bounds_error=False, fill_value=None)
    xx, yy = np.meshgrid(np.arange(mx) * tx, np.arange(my) * ty, indexing="ij")
    pts = np.stack([np.minimum(xx, (nx - 1) * dx).ravel(), np.minimum(yy, (ny - 1) * dy).ravel()], axis=1)
    heights = interp(pts).reshape(mx, my)
    return Surface(heights_m=np.ascontiguousarray(heights), physical_size_m=(mx * tx, my * ty), source=surface.source,
                   n_undefined_filled=surface.n_undefined_filled,
                   info={**surface.info, "resampled_from": list(surface.grid_spacing_m)})


def crop_surface(surface: Surface, shape: tuple[int, int]) -> Surface:
    """The centred ``shape`` sub-grid of ``surface`` (same pixel size; nominal area follows)."""
    nx, ny = surface.nb_grid_pts
    mx, my = int(shape[0]), int(shape[1])
    if not (MIN_GRID_POINTS <= mx <= nx and MIN_GRID_POINTS <= my <= ny):
        raise SurfaceError(f"cannot crop the {nx}×{ny} grid of {surface.source} to {mx}×{my}")
    i0, j0 = (nx - mx) // 2, (ny - my) // 2
    dx, dy = surface.grid_spacing_m
    heights = np.array(surface.heights_m[i0 : i0 + mx, j0 : j0 + my])
    return Surface(heights_m=heights, physical_size_m=(mx * dx, my * dy), source=surface.source,
                   n_undefined_filled=surface.n_undefined_filled,
                   info={**surface.info, "cropped_from": [nx, ny]})

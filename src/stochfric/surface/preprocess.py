"""Preparing a measured surface for the contact analysis (method §1.1–1.2, thesis 3.2.1).

Steps, each optional and recorded in :class:`Preparation` (and from there in every result):

1. **detrend** — remove a least-squares polynomial: ``"none"``, ``"mean"`` (the mean height),
   ``"plane"`` (best-fit plane; SurfaceTopography calls it ``"height"``) or ``"quadratic"``
   (full second-order polynomial in x and y; SurfaceTopography's ``"curvature"``).
   Measured data nearly always carry a tilt (``al3d-1``: Sq 7.7 µm raw, 0.29 µm without the
   plane), so ``"plane"`` is the default.
2. **median filter** of radius ``r``: window of ``(2r+1) × (2r+1)`` points (the thesis uses
   Matlab ``median2`` with r = 5 for the brake pad, r = 6 for the sheet); at the edges the data
   are mirrored (``scipy.ndimage.median_filter(mode="reflect")``), so no artificial zeros
   enter. ``r = 0`` switches it off.
3. **coarse discretisation** — keep every k-th point in both directions (thesis k = 10): the
   finest asperities are flattened plastically at first contact, the next scale deforms
   elastically.  The kept point ``i·k`` stands for a cell of ``k`` fine points, so the coarse
   spacing is exactly ``kΔ`` and the coarse physical size ``⌈n/k⌉·kΔ`` (equal to the measured
   size when ``k`` divides ``n``, at most ``(k−1)Δ`` larger otherwise).

The order is always detrend → median filter → coarsen.  The *fine* surface of the thesis's
figures is the filtered one (after steps 1–2), the *coarse* one the result of step 3.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass
from typing import Any, Literal

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.surface.io import MIN_GRID_POINTS, Surface, SurfaceError

__all__ = [
    "DETREND_MODES",
    "DetrendMode",
    "Preparation",
    "coarsen",
    "detrend",
    "median_filter",
    "prepare",
]

DetrendMode = Literal["none", "mean", "plane", "quadratic"]
DETREND_MODES: tuple[str, ...] = ("none", "mean", "plane", "quadratic")
#: SurfaceTopography's names for the same modes.
_ALIASES = {"center": "mean", "height": "plane", "curvature": "quadratic"}

FloatArray = npt.NDArray[np.float64]


def _normalise_mode(mode: str) -> str:
    m = _ALIASES.get(mode, mode)
    if m not in DETREND_MODES:
        raise SurfaceError(
            f"unknown detrend mode {mode!r}; use one of {', '.join(DETREND_MODES)} "
            f"(or SurfaceTopography's {', '.join(_ALIASES)})"
        )
    return m


@dataclass(frozen=True, kw_only=True)
class Preparation:
    """How a surface was prepared; recorded with every result.

    Attributes
    ----------
    detrend:
        ``"none"``, ``"mean"``, ``"plane"`` (default) or ``"quadratic"``
        (aliases ``"center"``, ``"height"``, ``"curvature"`` are accepted and normalised).
    median_radius:
        Median filter radius r >= 0 [grid points]; window (2r+1)×(2r+1); 0 = off.
    step:
        Coarsening step k >= 1: keep every k-th point; 1 = off.
    """

    detrend: str = "plane"
    median_radius: int = 0
    step: int = 1

    def __post_init__(self) -> None:
        object.__setattr__(self, "detrend", _normalise_mode(str(self.detrend)))
        for name, value, low in (("median_radius", self.median_radius, 0), ("step", self.step, 1)):
            if isinstance(value, bool) or not isinstance(value, int | np.integer):
                raise SurfaceError(f"{name} must be an integer, got {value!r}")
            if value < low:
                raise SurfaceError(f"{name} must be >= {low}, got {value}")
            object.__setattr__(self, name, int(value))

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary (JSON / netCDF attributes)."""
        return asdict(self)


def detrend(heights: npt.ArrayLike, mode: str = "plane") -> FloatArray:
    """Subtract the least-squares polynomial of ``mode`` from ``heights`` (same units).

    The fit uses the grid indices as coordinates; for a uniform grid this gives the same
    residual as a fit over physical positions (the polynomial spaces are the same).
    """
    h = np.asarray(heights, dtype=np.float64)
    m = _normalise_mode(mode)
    if m == "none":
        return h.copy()
    if m == "mean":
        return h - h.mean()
    nx, ny = h.shape
    # centred, scaled coordinates keep the least-squares system well conditioned
    x = (np.arange(nx, dtype=np.float64) - (nx - 1) / 2) / max(nx, 1)
    y = (np.arange(ny, dtype=np.float64) - (ny - 1) / 2) / max(ny, 1)
    xx, yy = np.meshgrid(x, y, indexing="ij")
    columns = [np.ones_like(xx), xx, yy]
    if m == "quadratic":
        columns += [xx * xx, xx * yy, yy * yy]
    design = np.stack([c.ravel() for c in columns], axis=1)
    coef, *_ = np.linalg.lstsq(design, h.ravel(), rcond=None)
    return h - (design @ coef).reshape(h.shape)


def median_filter(heights: npt.ArrayLike, radius: int) -> FloatArray:
    """2-D median filter over a (2r+1)×(2r+1) window, edges mirrored (method §1.1)."""
    h = np.asarray(heights, dtype=np.float64)
    if radius < 0:
        raise SurfaceError(f"median radius must be >= 0, got {radius}")
    if radius == 0:
        return h.copy()
    return np.asarray(ndimage.median_filter(h, size=2 * radius + 1, mode="reflect"))


def coarsen(surface: Surface, step: int) -> Surface:
    """Keep every ``step``-th point in x and y (method §1.2); spacing becomes ``step·Δ``.

    Raises :class:`SurfaceError` if fewer than ``MIN_GRID_POINTS`` points would remain in a
    direction (the summit rule needs two neighbours on each side).
    """
    if step < 1:
        raise SurfaceError(f"step must be >= 1, got {step}")
    if step == 1:
        return surface
    h = surface.heights_m[::step, ::step]
    nx, ny = h.shape
    if min(nx, ny) < MIN_GRID_POINTS:
        raise SurfaceError(
            f"step {step} leaves {nx}×{ny} points of the {surface.nb_grid_pts[0]}×"
            f"{surface.nb_grid_pts[1]} grid; at least {MIN_GRID_POINTS} per direction are "
            f"needed, use a step <= {min(surface.nb_grid_pts) // MIN_GRID_POINTS}"
        )
    dx, dy = surface.grid_spacing_m
    return Surface(
        heights_m=np.array(h),
        physical_size_m=(nx * step * dx, ny * step * dy),
        source=surface.source,
        n_undefined_filled=surface.n_undefined_filled,
        info={**surface.info, "coarsened_from": list(surface.nb_grid_pts)},
    )


def prepare(surface: Surface, preparation: Preparation | None = None) -> tuple[Surface, Surface]:
    """Apply ``preparation`` to ``surface``; return ``(fine, coarse)``.

    ``fine`` is detrended and median filtered, ``coarse`` additionally coarsened (the two
    are the same object for ``step = 1``). The contact analysis uses ``coarse``.
    """
    prep = preparation if preparation is not None else Preparation()
    nx, ny = surface.nb_grid_pts
    if min(nx, ny) < MIN_GRID_POINTS:
        raise SurfaceError(
            f"the surface has only {nx}×{ny} points; at least {MIN_GRID_POINTS} per direction are needed"
        )
    h = detrend(surface.heights_m, prep.detrend)
    h = median_filter(h, prep.median_radius)
    fine = Surface(
        heights_m=h,
        physical_size_m=surface.physical_size_m,
        source=surface.source,
        n_undefined_filled=surface.n_undefined_filled,
        info=dict(surface.info),
    )
    return fine, coarsen(fine, prep.step)

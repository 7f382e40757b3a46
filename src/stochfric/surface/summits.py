"""Summits (asperity tips) and their radii (method §1.3–1.4, thesis 3.1.1, eq. 3.1).

Rules (strict inequalities, interior points only): ``"thesis"`` (default) — ``z(i,j)`` higher than
the two points on each side along x and along y (8 comparisons); ``"8-neighbour"`` — higher than
all 8 nearest neighbours.  Radius (3.1, sign misprint fixed): ``β = −1/κ`` with
``κ = ½(∂²z/∂x² + ∂²z/∂y²)`` by central differences; a candidate with ``κ ≥ 0`` is excluded and
counted, and plateau tops (equal maxima) are counted (docs/surface_contact.md, "Summits and radii").
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.surface.io import Surface, SurfaceError

__all__ = ["DEFAULT_SUMMIT_RULE", "SUMMIT_RULES", "SummitRule", "Summits", "find_summits", "summit_rule",
           "summits_of"]


@dataclass(frozen=True)
class SummitRule:
    """A summit rule: a grid point is a summit when it is strictly higher than the neighbours at
    ``offsets`` (grid steps (di, dj)); ``margin`` is the distance from the border it needs."""

    name: str
    summary: str
    offsets: tuple[tuple[int, int], ...]

    @property
    def margin(self) -> int:
        """Grid points a summit lies at least inside the border (the farthest compared neighbour)."""
        return max(max(abs(di), abs(dj)) for di, dj in self.offsets)


#: name → rule (registry order: the default first).
SUMMIT_RULES: dict[str, SummitRule] = {
    r.name: r
    for r in (
        SummitRule("thesis", "higher than the two points on each side along x and along y (thesis 3.1.1)",
                   ((-2, 0), (-1, 0), (1, 0), (2, 0), (0, -2), (0, -1), (0, 1), (0, 2))),
        SummitRule("8-neighbour", "higher than all 8 nearest neighbours",
                   tuple((di, dj) for di in (-1, 0, 1) for dj in (-1, 0, 1) if (di, dj) != (0, 0))),
    )
}
DEFAULT_SUMMIT_RULE = "thesis"


def summit_rule(name: str) -> SummitRule:
    """The rule registered as ``name`` (:class:`~stochfric.surface.io.SurfaceError` naming the known ones)."""
    try:
        return SUMMIT_RULES[str(name)]
    except KeyError:
        raise SurfaceError(f"unknown summit rule {name!r}; use one of {', '.join(SUMMIT_RULES)}") from None

IntArray = npt.NDArray[np.intp]


@dataclass(frozen=True, kw_only=True, eq=False)
class Summits:
    """Summits of one surface.

    Attributes
    ----------
    heights_m:
        Summit heights ``z_s`` [m] (in the surface's height datum).
    radius_m:
        Summit radii ``β = −1/κ`` [m] (3.1), all > 0.
    i, j:
        Grid indices of the summits (x, y).
    rule:
        The summit rule used.
    n_excluded_flat:
        Candidates excluded because ``κ >= 0`` (flat / saddle); 0 for the strict rules.
    n_plateau:
        Plateau tops: candidates not lower than any compared neighbour, tied with at least
        one and higher than at least one; not counted as summits.
    area_m2:
        Nominal area of the surface they were found on [m²] (for the summit density).
    """

    heights_m: FloatArray
    radius_m: FloatArray
    i: IntArray
    j: IntArray
    rule: str
    n_excluded_flat: int
    n_plateau: int
    area_m2: float

    @property
    def count(self) -> int:
        """Number of summits."""
        return int(self.heights_m.size)

    @property
    def density_per_m2(self) -> float:
        """Summit density [1/m²]: count / nominal area."""
        return self.count / self.area_m2


def find_summits(
    heights_m: npt.ArrayLike,
    grid_spacing_m: tuple[float, float],
    *,
    rule: str = DEFAULT_SUMMIT_RULE,
    area_m2: float | None = None,
) -> Summits:
    """Find summits and their radii on a uniform grid (thesis 3.1.1, eq. 3.1).

    Parameters
    ----------
    heights_m:
        ``z[i, j]`` [m], shape ``(nx, ny)``.
    grid_spacing_m:
        ``(Δx, Δy)`` [m].
    rule:
        ``"thesis"`` or ``"8-neighbour"`` (see the module docstring).
    area_m2:
        Nominal area [m²] for the density; default ``nx Δx · ny Δy``.
    """
    z = np.asarray(heights_m, dtype=np.float64)
    if z.ndim != 2:
        raise SurfaceError(f"summits need a 2-D height map, got {z.ndim} dimension(s)")
    spec = summit_rule(rule)
    offsets, m = spec.offsets, spec.margin
    nx, ny = z.shape
    dx, dy = float(grid_spacing_m[0]), float(grid_spacing_m[1])
    if not (dx > 0 and dy > 0):
        raise SurfaceError(f"grid spacing must be > 0, got {grid_spacing_m!r}")
    area = float(area_m2) if area_m2 is not None else nx * dx * ny * dy
    empty_f = np.empty(0, dtype=np.float64)
    empty_i = np.empty(0, dtype=np.intp)
    if nx <= 2 * m or ny <= 2 * m:
        return Summits(
            heights_m=empty_f, radius_m=empty_f, i=empty_i, j=empty_i, rule=rule,
            n_excluded_flat=0, n_plateau=0, area_m2=area,
        )  # fmt: skip
    centre = z[m : nx - m, m : ny - m]
    strict = np.ones(centre.shape, dtype=bool)
    weak = np.ones(centre.shape, dtype=bool)
    above_some = np.zeros(centre.shape, dtype=bool)
    for di, dj in offsets:
        other = z[m + di : nx - m + di, m + dj : ny - m + dj]
        gt = centre > other
        strict &= gt
        above_some |= gt
        weak &= centre >= other
    # plateau tops: not lower than any neighbour, tied with one, higher than another
    # (points inside a perfectly flat region are not tops)
    n_plateau = int(np.count_nonzero(weak & above_some & ~strict))
    ci, cj = np.nonzero(strict)
    i = (ci + m).astype(np.intp)
    j = (cj + m).astype(np.intp)
    zc = z[i, j]
    d2x = (z[i + 1, j] - 2.0 * zc + z[i - 1, j]) / (dx * dx)
    d2y = (z[i, j + 1] - 2.0 * zc + z[i, j - 1]) / (dy * dy)
    kappa = 0.5 * (d2x + d2y)  # (3.1)
    ok = kappa < 0.0
    n_excluded = int(np.count_nonzero(~ok))
    beta = -1.0 / kappa[ok]  # β = −1/κ (method erratum 1)
    return Summits(
        heights_m=zc[ok],
        radius_m=beta,
        i=i[ok],
        j=j[ok],
        rule=rule,
        n_excluded_flat=n_excluded,
        n_plateau=n_plateau,
        area_m2=area,
    )


def summits_of(surface: Surface, *, rule: str = DEFAULT_SUMMIT_RULE) -> Summits:
    """:func:`find_summits` on a :class:`~stochfric.surface.io.Surface`."""
    return find_summits(surface.heights_m, surface.grid_spacing_m, rule=rule, area_m2=surface.nominal_area_m2)

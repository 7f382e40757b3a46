"""Surface statistics, PDFs and the plasticity index (method §1.5–1.6, thesis 3.1.3).

* Sq: root-mean-square height about the mean [m]; skewness; kurtosis (not the excess: 3 for a Gaussian).
* σ_S: standard deviation of the summit heights (population, ``ddof = 0``) [m]; β̄: mean summit
  radius [m]; summit density: summits per nominal area [1/m²].
* PDFs: normalised histograms (integral 1), as in thesis Fig. 3.10 / 3.27.
* Plasticity index (3.7): ``γ = (E*/H) √(σ_S/β̄)``; < 0.6 mostly elastic, > 1 mostly plastic.
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.summits import Summits

__all__ = [
    "ELASTIC_LIMIT",
    "GAUSSIAN_CURVATURE_Z",
    "PLASTIC_LIMIT",
    "CurvatureGaussianity",
    "SurfaceStatistics",
    "curvature_gaussianity",
    "height_moments",
    "pdf",
    "plasticity_index",
    "plasticity_verdict",
    "surface_statistics",
]

#: γ below this: mostly elastic (thesis 3.1.3).
ELASTIC_LIMIT = 0.6
#: γ above this: mostly plastic (thesis 3.1.3).
PLASTIC_LIMIT = 1.0


@dataclass(frozen=True, kw_only=True)
class SurfaceStatistics:
    """Statistics of one (fine or coarse) surface and its summits; SI units."""

    grid: tuple[int, int]
    physical_size_m: tuple[float, float]
    grid_spacing_m: tuple[float, float]
    sq_m: float
    skewness: float
    kurtosis: float
    n_summits: int
    summit_density_per_m2: float
    summit_height_mean_m: float
    summit_height_std_m: float
    summit_height_max_m: float
    summit_radius_mean_m: float
    summit_radius_median_m: float
    n_excluded_flat: int
    n_plateau: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (tuples become lists, NaN becomes None)."""
        out: dict[str, Any] = {}
        for key, value in asdict(self).items():
            if isinstance(value, tuple):
                out[key] = list(value)
            elif isinstance(value, float) and not math.isfinite(value):
                out[key] = None
            else:
                out[key] = value
        return out


def height_moments(heights: npt.ArrayLike) -> tuple[float, float, float]:
    """``(Sq, skewness, kurtosis)`` of all heights (kurtosis not in excess; 3 = Gaussian)."""
    z = np.asarray(heights, dtype=np.float64).ravel()
    dev = z - z.mean()
    sq = float(np.sqrt(np.mean(dev * dev)))
    if sq == 0.0:
        return 0.0, math.nan, math.nan
    return sq, float(np.mean(dev**3) / sq**3), float(np.mean(dev**4) / sq**4)


def surface_statistics(surface: Surface, summits: Summits) -> SurfaceStatistics:
    """Sq, skewness, kurtosis, σ_S, β̄, summit density of ``surface`` (method §1.5)."""
    sq, skew, kurt = height_moments(surface.heights_m)
    n = summits.count
    if n:
        zs = summits.heights_m
        mean_h, std_h, max_h = float(zs.mean()), float(zs.std()), float(zs.max())
        beta_mean = float(summits.radius_m.mean())
        beta_median = float(np.median(summits.radius_m))
    else:
        mean_h = std_h = max_h = beta_mean = beta_median = math.nan
    return SurfaceStatistics(
        grid=surface.nb_grid_pts,
        physical_size_m=surface.physical_size_m,
        grid_spacing_m=surface.grid_spacing_m,
        sq_m=sq,
        skewness=skew,
        kurtosis=kurt,
        n_summits=n,
        summit_density_per_m2=summits.density_per_m2,
        summit_height_mean_m=mean_h,
        summit_height_std_m=std_h,
        summit_height_max_m=max_h,
        summit_radius_mean_m=beta_mean,
        summit_radius_median_m=beta_median,
        n_excluded_flat=summits.n_excluded_flat,
        n_plateau=summits.n_plateau,
    )


def pdf(values: npt.ArrayLike, bins: int | npt.ArrayLike = 50) -> tuple[FloatArray, FloatArray]:
    """Normalised histogram: ``(bin centres, density)`` with ``Σ density·width = 1``.

    Thesis Fig. 3.10 / 3.27 (PDFs of z, z_s and β). Non-finite values are refused.
    """
    v = np.asarray(values, dtype=np.float64).ravel()
    if v.size == 0:
        raise SurfaceError("cannot estimate a PDF from no values")
    if not np.all(np.isfinite(v)):
        raise SurfaceError("cannot estimate a PDF from NaN or infinite values")
    density, edges = np.histogram(v, bins=bins, density=True)
    return 0.5 * (edges[:-1] + edges[1:]), density.astype(np.float64)


def plasticity_index(*, e_star_pa: float, hardness_pa: float, sigma_s_m: float, beta_mean_m: float) -> float:
    """Plasticity index (3.7): ``γ = (E*/H) √(σ_S/β̄)`` [-].

    ``E*`` [Pa] from (3.10), ``H = 5.6 R_p`` [Pa] (or a tabulated hardness), ``σ_S`` the
    standard deviation of the summit heights [m], ``β̄`` the mean summit radius [m].
    """
    for name, v in (
        ("e_star_pa", e_star_pa),
        ("hardness_pa", hardness_pa),
        ("sigma_s_m", sigma_s_m),
        ("beta_mean_m", beta_mean_m),
    ):
        if not (math.isfinite(v) and v >= 0.0):
            raise SurfaceError(f"plasticity index: {name} must be finite and >= 0, got {v!r}")
    if hardness_pa == 0.0 or beta_mean_m == 0.0:
        raise SurfaceError("plasticity index: hardness and mean summit radius must be > 0")
    return (e_star_pa / hardness_pa) * math.sqrt(sigma_s_m / beta_mean_m)


def plasticity_verdict(gamma: float) -> str:
    """``"elastic"`` (γ < 0.6), ``"plastic"`` (γ > 1) or ``"elastic-plastic"`` (thesis 3.1.3)."""
    if not math.isfinite(gamma):
        raise SurfaceError(f"plasticity index must be finite, got {gamma!r}")
    if gamma < ELASTIC_LIMIT:
        return "elastic"
    if gamma > PLASTIC_LIMIT:
        return "plastic"
    return "elastic-plastic"


#: A map's curvature counts as Gaussian when its Laplacian kurtosis lies within this many
#: √(24/n_s) of 3 (:func:`curvature_gaussianity`).
GAUSSIAN_CURVATURE_Z = 3.0


@dataclass(frozen=True, kw_only=True)
class CurvatureGaussianity:
    """The result of :func:`curvature_gaussianity`: the Laplacian's kurtosis κ, z = (κ − 3)/√(24/n_s),
    the verdict and its limit on |z|."""

    laplacian_kurtosis: float
    z: float
    gaussian: bool
    limit: float = GAUSSIAN_CURVATURE_Z

    def to_dict(self) -> dict[str, Any]:
        """The fields by name (JSON)."""
        return asdict(self)


def curvature_gaussianity(heights: npt.ArrayLike, summit_count: int) -> CurvatureGaussianity:
    """Is the map's curvature field that of a Gaussian field?  (The rule of ``--surrogate auto``.)

    κ = kurtosis of the 5-point Laplacian (interior points; 3 for any Gaussian field), z = (κ − 3) /
    √(24/n_s) with the summit count n_s standing for the number of independent curvature values.
    That SE is conservative: on 24 Gaussian fields of 200²…800² points and correlation lengths
    0.7…5 points |z| ≤ 0.51 (sd 0.24); the shared real maps give z = 7 (al3d-1) … 3·10⁴ (mnt-1).
    ``gaussian`` when |z| ≤ :data:`GAUSSIAN_CURVATURE_Z`: there random-phase surrogates are exact.
    """
    h = np.asarray(heights, dtype=np.float64)
    lap = (h[2:, 1:-1] + h[:-2, 1:-1] + h[1:-1, 2:] + h[1:-1, :-2] - 4.0 * h[1:-1, 1:-1]).ravel()
    c = lap - lap.mean()
    m2 = float(np.mean(c * c))
    kappa = float(np.mean(c**4) / (m2 * m2)) if m2 > 0.0 else math.nan
    z = (kappa - 3.0) / math.sqrt(24.0 / max(int(summit_count), 1)) if math.isfinite(kappa) else math.inf
    return CurvatureGaussianity(laplacian_kurtosis=kappa, z=z, gaussian=bool(abs(z) <= GAUSSIAN_CURVATURE_Z))

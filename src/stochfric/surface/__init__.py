"""Surface analysis of measured topographies (method §1, thesis 3.1.1, 3.2.1, 3.3.1).

Reading (:mod:`.io`), preparation (:mod:`.preprocess`), summits and radii (:mod:`.summits`),
statistics and the plasticity index (:mod:`.statistics`); figures in :mod:`.figures`
(imported on demand: it needs matplotlib).
"""

from __future__ import annotations

from stochfric.surface.io import (
    Surface,
    SurfaceError,
    default_surface_path,
    read_surface,
    surface_from_array,
)
from stochfric.surface.preprocess import Preparation, coarsen, detrend, median_filter, prepare
from stochfric.surface.statistics import (
    SurfaceStatistics,
    height_moments,
    pdf,
    plasticity_index,
    plasticity_verdict,
    surface_statistics,
)
from stochfric.surface.summits import Summits, find_summits, summits_of

__all__ = [
    "Preparation",
    "Summits",
    "Surface",
    "SurfaceError",
    "SurfaceStatistics",
    "coarsen",
    "default_surface_path",
    "detrend",
    "find_summits",
    "height_moments",
    "median_filter",
    "pdf",
    "plasticity_index",
    "plasticity_verdict",
    "prepare",
    "read_surface",
    "summits_of",
    "surface_from_array",
    "surface_statistics",
]

"""Memory needed by the statistical contact analysis, estimated before any work (method §4c).

The long surfaces of the path analysis dominate: one surface of M × (F·N) points is held at a
time (its heights, the FFT of the synthesis, the summit search).  :func:`check_memory` refuses a
request that does not fit, with the figures and what to change.
"""

from __future__ import annotations

from stochfric.errors import AnalysisError
from stochfric.io_utils import available_memory_bytes, format_bytes

__all__ = [
    "MEMORY_FIXED_BYTES",
    "MEMORY_PER_POINT_BYTES",
    "check_memory",
    "estimate_peak_memory_bytes",
    "sample_arrays_bytes",
    "workers_that_fit",
]

#: Peak memory of :func:`analyse` per grid point of one long surface [bytes] and its fixed part
#: (interpreter, numpy, numba), measured with ``benchmarks/bench_process_files.py``: 1700 × 17000
#: points (the thesis's 1700² map, length factor 10) peaked at 1118 MiB with random phases, i.e.
#: ≈ 33 B per point above ≈ 220 MiB, and at 2278 MiB over two workers with quilts (≈ 1140 MiB
#: each, ≈ 32 B per point); the estimate uses 48 B per point and 256 MiB for a margin.
MEMORY_PER_POINT_BYTES = 48
MEMORY_FIXED_BYTES = 256 * 2**20


def estimate_peak_memory_bytes(grid: tuple[int, int], length_factor: int) -> int:
    """Estimated peak memory of :func:`analyse` [bytes]: one long surface of M × (F·N) points at a time."""
    return MEMORY_FIXED_BYTES + MEMORY_PER_POINT_BYTES * int(grid[0]) * int(grid[1]) * int(length_factor)


def workers_that_fit(
    grid: tuple[int, int], length_factor: int, workers: int, available: int | None = None
) -> int:
    """How many of ``workers`` processes may build long surfaces at once: each holds one long
    surface (:data:`MEMORY_PER_POINT_BYTES` per point, measured for random-phase and quilted ones:
    about 33 B), the parent its fixed part; at least 1 (:func:`check_memory` refuses what does not
    fit with one)."""
    have = available_memory_bytes() if available is None else available
    if have is None:
        return max(1, int(workers))
    per = MEMORY_PER_POINT_BYTES * int(grid[0]) * int(grid[1]) * int(length_factor)
    return max(1, min(int(workers), int((have - MEMORY_FIXED_BYTES) // max(per, 1))))


def sample_arrays_bytes(realizations: int, long_surfaces: int, windows: int, approaches: int, tiles: int) -> int:
    """Memory of the per-sample results [bytes]: A_c, N (float64) and contact counts (int64) over the
    approaches for every realisation and its tiles², and for every window of every long surface
    (shifted windows and non-overlapping blocks), plus the seed streams (≈ 1 KiB each)."""
    per = 3 * 8 * int(approaches)
    return (int(realizations) * (per * (1 + int(tiles) ** 2) + 1024)
            + int(long_surfaces) * (per * 2 * int(windows) + 1024))


def check_memory(
    grid: tuple[int, int], length_factor: int, available: int | None = None, *, samples_bytes: int = 0
) -> int:
    """Refuse, before any work, an analysis whose long surfaces do not fit in memory.

    Returns the estimate [bytes]; raises :class:`AnalysisError` with the figures and what to change
    when it exceeds the available memory (``available``; default
    :func:`stochfric.io_utils.available_memory_bytes`).
    """
    need = estimate_peak_memory_bytes(grid, length_factor) + int(samples_bytes)
    have = available_memory_bytes() if available is None else available
    if have is not None and samples_bytes > have // 2:
        raise AnalysisError(
            f"the results of so many realisations / long surfaces need about {format_bytes(samples_bytes)} but "
            f"{format_bytes(have)} are available; use fewer --realizations or --long-surfaces (100 and 10 are the "
            "thesis's numbers; the statistics converge as 1/sqrt(R))"
        )
    if have is not None and need > have:
        raise AnalysisError(
            f"the analysis needs about {format_bytes(need)} (long surfaces of {grid[0]} × {length_factor * grid[1]} "
            f"points) but {format_bytes(have)} are available; use a smaller --length-factor, coarsen the map "
            "(--step 2 or more), or crop it (--size-um with a cropped file)"
        )
    return need

"""How much of a surrogate is verbatim pieces of the measured map?  (issue 29, item 3)

A measure that does not ask the generator how it made the surrogate.  It compares the **curvature
field** (the 5-point Laplacian, :func:`laplacian`: the field the summits and their radii read) of
the surrogate with the measured map's, block by block:

* ``blocks`` points are drawn uniformly over the surrogate; the ``block × block`` block centred on each
  is compared with every ``block × block`` window of the map's Laplacian that lies wholly inside the
  map, as it is and rotated by 180° (the block matches the rotated map where the rotated block matches
  the map), by the normalised cross-correlation (NCC: the Pearson correlation of the two blocks).  A
  block is **verbatim** when its best NCC reaches :data:`VERBATIM_NCC`.
* A block across a seam between two verbatim pieces is not verbatim, so for each point whose centred
  block is not, the four blocks that have the point at a corner are tried too.  A point is verbatim
  when one of its five blocks is: ``fraction`` is the **verbatim area fraction** (up to the two
  Laplacian rows at a seam, which belong to neither piece), ``block_fraction`` the fraction of the
  randomly placed blocks alone (the review's measure; lower by the blocks that straddle seams).
* Each verbatim point's best match gives the piece of the map it comes from (shift and orientation);
  ``largest_piece_share`` is the largest share of the sampled points from one piece.

Block side (default): one mean summit spacing of the measured map, ``√(area / n_summits)`` in grid
points (:func:`summit_spacing_points`), at least :data:`MIN_BLOCK` points: about one summit and its
flanks, the scale at which a surrogate is supposed to be new.

**Threshold** ``VERBATIM_NCC = 0.98``.  A verbatim piece has NCC 1 up to round-off, also after a quilt
adds its long-wavelength field and its seam repair (their Laplacian is small against the roughness's
on the block scale): the median block NCC of quilted surrogates of every shared map is 1.000.  A block
of a surrogate that is no piece of the map only reaches the largest of many chance correlations with
the ~10⁵–10⁶ windows of the map: measured over 4 random-phase surrogates × 64 random blocks each
(median / 99th percentile / largest best NCC), shared maps prepared with the defaults: al3d-1 (block
16) 0.48 / 0.66 / 0.69, plu-1 (5) 0.82 / 0.89 / 0.90, mnt-1 (5) 0.82 / 0.92 / 0.95, x3p-2 (13) 0.59 /
0.76 / 0.77, opd-1 (5) 0.81 / 0.87 / 0.88, sur-2 (5) 0.77 / 0.86 / 0.88; Gaussian fields (the hardest
case: a smooth Laplacian has few independent values per block) 320² correlation length 1 point (5)
0.89 / 0.94 / 0.95, 768 × 576 (5) 0.91 / 0.95 / 0.96, 1700² correlation length 2 (9) 0.92 / 0.96 /
0.96.  No block of a random-phase surrogate reached the threshold, with the corner blocks included
(fraction 0 on every map above).  The chance maximum grows slowly with the number of windows: on maps
much larger than 1700², check a random-phase control (``benchmarks/bench_verbatim.py``).

**Labels** (:func:`verbatim_label`): ``"copy"`` when one piece of the map covers at least
:data:`COPY_PIECE_SHARE` of the sampled points (the map itself, shifted, cropped or rotated);
``"resampling"`` when at least :data:`RESAMPLING_FRACTION` of the points are verbatim — the surrogate
is mostly pieces of the measurement, a block bootstrap, not a new surface, and the scatter between
such surrogates rests on at most ``measured_pieces`` = (map points) / block² independent pieces of
the measurement (:func:`independent_pieces`); ``"new"`` otherwise.  The label reads the point
estimate of the fraction; its 95 % Clopper–Pearson interval is reported beside it.  Measured (4
surrogates each, 64 points): quilts of the shared maps 95–100 % verbatim (random blocks 77–95 %) →
resampling; the maps cut into 4 × 4 windows and reshuffled 92–97 % → resampling; the maps rotated by
180° → copy; random phases 0 % → new.

**Cost.**  The map's window sums (cumulative sums) once per map (:class:`BlockMatcher`, reusable
for all surrogates of one map); the centred blocks against all windows by a float32 matrix product
(``method="direct"``, block ≤ :data:`DIRECT_MAX_BLOCK`) or by FFT (one forward and two inverse FFTs
of the map's size per block, ``scipy.fft`` with ``next_fast_len``); the corner blocks through a k-d
tree of the map's windows projected on 8 principal directions, which is exact (a projection cannot
separate two unit vectors with NCC ≥ t by more than √(2 − 2t)) and needs only the few candidates in
that ball (where a block's projection says little about it — more than 2 % of the windows in the
ball, as for large blocks of a noise-like curvature field — that block is matched against all windows).
plu-1 (768 × 576, block 5, 64 points): about 1 s per surrogate on one busy core, 1.7 s from scratch
(``benchmarks/bench_verbatim.py``); a 1700² map (block 9) about 7 s per surrogate.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any, NamedTuple

import numpy as np
import numpy.typing as npt
from numpy.lib.stride_tricks import sliding_window_view
from scipy import fft as sfft
from scipy.spatial import cKDTree
from scipy.stats import beta as beta_dist

from stochfric.arrays import FloatArray
from stochfric.errors import AnalysisError
from stochfric.random import SeedLike, as_generator
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, find_summits

__all__ = [
    "COPY_PIECE_SHARE",
    "DEFAULT_BLOCKS",
    "DIRECT_MAX_BLOCK",
    "MATCH_METHODS",
    "MIN_BLOCK",
    "RESAMPLING_FRACTION",
    "VERBATIM_CONFIDENCE",
    "VERBATIM_LABELS",
    "VERBATIM_NCC",
    "BlockMatcher",
    "Matches",
    "VerbatimMeasure",
    "clopper_pearson_interval",
    "default_block",
    "independent_pieces",
    "laplacian",
    "pool_verbatim",
    "summit_spacing_points",
    "verbatim_fraction",
    "verbatim_label",
]

#: A block is verbatim when its best normalised cross-correlation with the map's Laplacian reaches this.
VERBATIM_NCC = 0.98
#: A surrogate at least this fraction of whose points are verbatim is a resampling (block bootstrap).
RESAMPLING_FRACTION = 0.5
#: A surrogate whose verbatim points are one piece of the map (one shift and orientation) at least at
#: this fraction of its sampled points is a copy of the map.
COPY_PIECE_SHARE = 0.5
#: Smallest block side [points].
MIN_BLOCK = 5
#: Points (blocks) drawn per surrogate by default.
DEFAULT_BLOCKS = 64
#: Confidence of the interval of the verbatim fraction.
VERBATIM_CONFIDENCE = 0.95
#: The labels, from most to least verbatim.
VERBATIM_LABELS = ("copy", "resampling", "new")
#: Blocks (and windows of the map) whose Laplacian variance is below this fraction of the map
#: Laplacian's variance are flat: no correlation is defined there.
FLAT_VARIANCE = 1e-10
#: Ways to match the blocks (:class:`BlockMatcher`).
MATCH_METHODS = ("auto", "fft", "direct")
#: Largest block side matched directly under ``method="auto"`` (above it the FFT is cheaper).
DIRECT_MAX_BLOCK = 20
#: Candidate points drawn per requested point before giving up on flat surrogates.
_MAX_DRAWS_PER_BLOCK = 8
#: Blocks transformed together by the FFT method (memory: this many spectra of the map's size).
_BATCH = 8
#: Principal directions of the map's windows that index them for :meth:`BlockMatcher.verbatim`.
_TREE_DIMENSIONS = 8
#: Below this threshold the corner blocks are matched against every window instead (the index's
#: candidate sets grow with the radius √(2 − 2t)).
_TREE_MIN_THRESHOLD = 0.95
#: A block with more candidates than this fraction of the map's windows (and than ``_TREE_MIN_CAP``)
#: is matched against all of them.
_TREE_MAX_CANDIDATES = 0.02
_TREE_MIN_CAP = 1000
#: Windows sampled to find those directions.
_PCA_WINDOWS = 2000
#: Entries of the window matrix or of its product per chunk of the direct method (float32: 8 MiB).
_DIRECT_CHUNK = 1 << 21

IntArray = npt.NDArray[np.int64]


def _map(heights: npt.ArrayLike, what: str) -> FloatArray:
    z = np.asarray(heights, dtype=np.float64)
    if z.ndim != 2 or min(z.shape) < 3:
        raise AnalysisError(f"{what} must be a 2-D height map of at least 3 × 3 points, got shape {z.shape}")
    if not np.all(np.isfinite(z)):
        raise AnalysisError(f"{what} has non-finite heights")
    return z


def laplacian(heights: npt.ArrayLike) -> FloatArray:
    """The 5-point Laplacian of the interior points, shape ``(nx − 2, ny − 2)``, in units of height per
    grid step² (the stencil of :func:`stochfric.surface.statistics.curvature_gaussianity`)."""
    h = _map(heights, "the map")
    return np.asarray(h[2:, 1:-1] + h[:-2, 1:-1] + h[1:-1, 2:] + h[1:-1, :-2] - 4.0 * h[1:-1, 1:-1])


def summit_spacing_points(heights: npt.ArrayLike, rule: str = DEFAULT_SUMMIT_RULE) -> float:
    """Mean summit spacing ``√(nx·ny / n_summits)`` in grid points (summits by ``rule`` on a unit grid,
    :func:`stochfric.surface.summits.find_summits`); ``inf`` when the map has no summit."""
    z = _map(heights, "the map")
    n = find_summits(z, (1.0, 1.0), rule=rule).count
    return math.sqrt(z.size / n) if n else math.inf


def default_block(heights: npt.ArrayLike, rule: str = DEFAULT_SUMMIT_RULE) -> int:
    """One mean summit spacing (rounded), at least :data:`MIN_BLOCK` and at most the Laplacian's shorter
    side."""
    z = _map(heights, "the map")
    spacing = summit_spacing_points(z, rule)
    upper = min(z.shape) - 2
    side = upper if not math.isfinite(spacing) else round(spacing)
    return int(min(max(side, MIN_BLOCK), upper))


def independent_pieces(measured_points: int, block: int) -> int:
    """Disjoint ``block × block`` pieces of a map of ``measured_points`` points (at least 1): the most
    independent samples of the measurement that the scatter of a resampling of it can rest on."""
    if isinstance(block, bool) or not isinstance(block, int | np.integer) or block < 1:
        raise AnalysisError(f"the block side must be an integer >= 1 point, got {block!r}")
    return max(1, int(measured_points) // (int(block) * int(block)))


def clopper_pearson_interval(k: int, n: int, confidence: float = VERBATIM_CONFIDENCE) -> tuple[float, float]:
    """Exact (Clopper–Pearson) two-sided interval of a binomial probability from ``k`` of ``n``;
    ``(0, 1)`` for ``n = 0``."""
    if n <= 0:
        return (0.0, 1.0)
    a = 1.0 - confidence
    lo = float(beta_dist.ppf(a / 2, k, n - k + 1)) if k > 0 else 0.0
    hi = float(beta_dist.ppf(1 - a / 2, k + 1, n - k)) if k < n else 1.0
    return (lo, hi)


def verbatim_label(fraction: float, largest_piece_share: float) -> str:
    """``"copy"`` (one piece of the map covers at least :data:`COPY_PIECE_SHARE` of the sampled
    points), ``"resampling"`` (at least :data:`RESAMPLING_FRACTION` of them are verbatim) or ``"new"``."""
    if largest_piece_share >= COPY_PIECE_SHARE:
        return "copy"
    if fraction >= RESAMPLING_FRACTION:
        return "resampling"
    return "new"


_DESCRIPTIONS = {
    "copy": "a copy of the measurement (one piece of the map)",
    "resampling": "a resampling of the measurement (block bootstrap), not a new surface",
    "new": "a new surface (few verbatim pieces of the measurement)",
}


@dataclass(frozen=True, kw_only=True)
class VerbatimMeasure:
    """Verbatim content of a surrogate (or of several, :func:`pool_verbatim`) at the block scale.

    Attributes
    ----------
    fraction:
        Fraction of the sampled points that lie in a verbatim block (the block centred on the point
        or, with ``corners``, one of the four blocks with the point at a corner): the verbatim area
        fraction; the label reads it.
    ci95:
        Its Clopper–Pearson interval (:data:`VERBATIM_CONFIDENCE`) from ``verbatim_blocks`` of ``blocks``.
    block_fraction:
        Fraction of the centred blocks alone that are verbatim (randomly placed blocks, the review's
        measure; a block across a seam between two verbatim pieces is not verbatim).
    largest_piece_share:
        Largest fraction of the sampled points whose verbatim block matches the map at one and the
        same shift and orientation (one piece of the map; 1 for the map itself, shifted or rotated);
        the largest over the surrogates when pooled.
    median_best_ncc, median_block_ncc:
        Medians over the points of ``best_ncc`` and of ``block_ncc``.
    block:
        Block side [grid points].
    blocks, verbatim_blocks, skipped_flat:
        Points sampled (one centred block each), of them verbatim, and draws skipped because the
        centred block was flat.
    threshold:
        NCC at which a block counts as verbatim.
    measured_pieces:
        Disjoint blocks of the measured map (:func:`independent_pieces`).
    surrogates:
        Surrogates measured (1 unless pooled).
    label:
        ``"copy"``, ``"resampling"`` or ``"new"`` (:func:`verbatim_label`).
    best_ncc, block_ncc:
        Per point: the best NCC found (its centred block's, or that of a verbatim corner block), and
        its centred block's best NCC (not in :meth:`to_dict`; their quartiles are).
    """

    fraction: float
    ci95: tuple[float, float]
    block_fraction: float
    largest_piece_share: float
    median_best_ncc: float
    median_block_ncc: float
    block: int
    blocks: int
    verbatim_blocks: int
    skipped_flat: int
    threshold: float
    measured_pieces: int
    surrogates: int
    label: str
    best_ncc: tuple[float, ...] = ()
    block_ncc: tuple[float, ...] = ()

    @property
    def is_copy(self) -> bool:
        """The label is ``"copy"``."""
        return self.label == "copy"

    @property
    def is_resampling(self) -> bool:
        """The label is ``"copy"`` or ``"resampling"``: the surrogate is (mostly) the measurement again."""
        return self.label in ("copy", "resampling")

    @property
    def description(self) -> str:
        """What the label means, in words."""
        return _DESCRIPTIONS[self.label]

    def summary(self) -> str:
        """One line for the output: the fraction, its interval, the label in words and, for a
        resampling, the number of independent pieces its scatter rests on."""
        lo, hi = self.ci95
        text = (
            f"{100 * self.fraction:.0f} % verbatim at {self.block} × {self.block} points (95 % CI "
            f"{100 * lo:.0f}–{100 * hi:.0f} %, {self.blocks} points; random blocks "
            f"{100 * self.block_fraction:.0f} %, median block NCC {self.median_block_ncc:.3f}, limit "
            f"{self.threshold:g}): {self.description}"
        )
        if self.is_resampling:
            text += f"; its scatter rests on ≈ {self.measured_pieces} independent pieces of the measurement"
        return text

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (the per-point NCCs as quartiles)."""

        def quartiles(v: tuple[float, ...]) -> list[float]:
            return [float(x) for x in np.quantile(v, [0.25, 0.5, 0.75])] if v else [math.nan] * 3

        return {
            "fraction": self.fraction,
            "ci95": list(self.ci95),
            "block_fraction": self.block_fraction,
            "largest_piece_share": self.largest_piece_share,
            "median_best_ncc": self.median_best_ncc,
            "median_block_ncc": self.median_block_ncc,
            "best_ncc_quartiles": quartiles(self.best_ncc),
            "block_ncc_quartiles": quartiles(self.block_ncc),
            "block_points": self.block,
            "blocks": self.blocks,
            "verbatim_blocks": self.verbatim_blocks,
            "skipped_flat": self.skipped_flat,
            "threshold": self.threshold,
            "measured_pieces": self.measured_pieces,
            "surrogates": self.surrogates,
            "label": self.label,
            "description": self.description,
        }


def _window_sums(a: FloatArray, block: int) -> tuple[FloatArray, FloatArray]:
    """Sums of ``a`` and of ``a²`` over every ``block × block`` window wholly inside ``a``."""

    def box(v: FloatArray) -> FloatArray:
        c = np.zeros((v.shape[0] + 1, v.shape[1] + 1))
        np.cumsum(np.cumsum(v, axis=0), axis=1, out=c[1:, 1:])
        return np.asarray(c[block:, block:] - c[:-block, block:] - c[block:, :-block] + c[:-block, :-block])

    return box(a), box(a * a)


class Matches(NamedTuple):
    """Best match of each block: NCC (NaN for a flat block), the top-left corner ``(i, j)`` of the
    map window and whether the block matched rotated by 180°."""

    ncc: FloatArray
    i: IntArray
    j: IntArray
    rotated: npt.NDArray[np.bool_]


class BlockMatcher:
    """Best NCC of ``block × block`` pieces against every window of a map's Laplacian, as it is and
    rotated by 180°; the map's window statistics (and, for the FFT, its spectrum) are computed once —
    reuse it for many surrogates of one map.

    ``method``: ``"fft"`` — one forward and two inverse FFTs of the map's size per block (float64,
    cost independent of the block side); ``"direct"`` — the map's window matrix times the blocks
    (float32 BLAS in row chunks; its round-off is relative to each window's own norm, so quiet
    windows are safe); ``"auto"`` (default) — direct up to :data:`DIRECT_MAX_BLOCK` points, FFT
    above.  Both agree to ~1e-6 (tested).
    """

    def __init__(self, measured: npt.ArrayLike, block: int, *, method: str = "auto", workers: int = 1) -> None:
        lap = laplacian(measured)
        self.shape: tuple[int, int] = (int(lap.shape[0]), int(lap.shape[1]))
        if isinstance(block, bool) or not isinstance(block, int | np.integer) or not 2 <= block <= min(lap.shape):
            raise AnalysisError(
                f"the block side must be an integer between 2 and the map's Laplacian side {min(lap.shape)}, "
                f"got {block!r}"
            )
        if method not in MATCH_METHODS:
            raise AnalysisError(f"unknown matching method {method!r}; use one of {', '.join(MATCH_METHODS)}")
        self.block = int(block)
        self.workers = int(workers)
        self.method = ("direct" if self.block <= DIRECT_MAX_BLOCK else "fft") if method == "auto" else method
        scale = float(lap.std())
        if not scale > 0.0:
            raise AnalysisError("the map's Laplacian is zero: a plane has no curvature to match")
        self.scale = scale
        lap = lap / scale
        self.lap = lap
        self._tree: tuple[cKDTree, FloatArray, IntArray] | None = None
        n = float(self.block * self.block)
        s1, s2 = _window_sums(lap, self.block)
        var = s2 - s1 * s1 / n  # n · variance of each window
        flat = var <= FLAT_VARIANCE * n
        self.inv_norm = np.where(flat, 0.0, 1.0 / np.sqrt(np.where(flat, 1.0, var)))
        self.windows: tuple[int, int] = (int(self.inv_norm.shape[0]), int(self.inv_norm.shape[1]))
        self.lap32 = lap.astype(np.float32)
        self.inv_norm32 = self.inv_norm.astype(np.float32)
        if self.method == "fft":
            self.fshape = tuple(sfft.next_fast_len(int(s), real=True) for s in lap.shape)
            self.spectrum = sfft.rfft2(lap, s=self.fshape, workers=self.workers)

    def match(self, pieces: npt.ArrayLike) -> Matches:
        """Best match of each block in ``pieces`` (``k × block × block`` Laplacian values) with the map,
        plain or rotated by 180°."""
        b = self.block
        p = np.asarray(pieces, dtype=np.float64) / self.scale
        if p.ndim != 3 or p.shape[1:] != (b, b):
            raise AnalysisError(f"pieces must have shape (k, {b}, {b}), got {p.shape}")
        k = p.shape[0]
        ncc = np.full(k, np.nan)
        pos = np.zeros(k, dtype=np.int64)
        rot = np.zeros(k, dtype=bool)
        p = p - p.mean(axis=(1, 2), keepdims=True)
        norm = np.sqrt(np.sum(p * p, axis=(1, 2)))
        idx = np.flatnonzero(norm > math.sqrt(FLAT_VARIANCE * b * b))
        if idx.size:
            q = p[idx] / norm[idx, None, None]
            best, where, rotated = self._fft(q) if self.method == "fft" else self._direct(q)
            ncc[idx] = np.minimum(best, 1.0)
            pos[idx] = where
            rot[idx] = rotated
        return Matches(ncc=ncc, i=pos // self.windows[1], j=pos % self.windows[1], rotated=rot)

    def best(self, pieces: npt.ArrayLike) -> FloatArray:
        """Best NCC of each block in ``pieces`` with the map, plain or rotated; NaN for a flat block."""
        return self.match(pieces).ncc

    def verbatim(self, pieces: npt.ArrayLike, threshold: float = VERBATIM_NCC) -> Matches:
        """The best match of each block in ``pieces`` among the map windows (plain or rotated) whose NCC
        with it reaches ``threshold``; NCC ``-inf`` where there is none (NaN for a flat block).

        Exact, and cheap for thresholds near 1: two unit vectors with NCC ≥ t lie within
        ``r = √(2 − 2t)`` of each other, and so do their projections on any orthonormal directions.  The
        map's normalised windows are projected once on their :data:`_TREE_DIMENSIONS` leading principal
        directions and put in a k-d tree; a block's candidates are the windows within ``r`` of its
        projection (as it is and rotated), and only those are correlated exactly.  A block with more
        than :data:`_TREE_MAX_CANDIDATES` of the windows as candidates (the projection says little
        about it) is matched against every window instead (:meth:`match`)."""
        b = self.block
        raw = np.asarray(pieces, dtype=np.float64)
        if raw.ndim != 3 or raw.shape[1:] != (b, b):
            raise AnalysisError(f"pieces must have shape (k, {b}, {b}), got {raw.shape}")
        tree, directions, live_windows = self._index()
        k = raw.shape[0]
        ncc = np.full(k, np.nan)
        pos = np.zeros(k, dtype=np.int64)
        rot = np.zeros(k, dtype=bool)
        p = raw / self.scale
        p = p - p.mean(axis=(1, 2), keepdims=True)
        norm = np.sqrt(np.sum(p * p, axis=(1, 2)))
        idx = np.flatnonzero(norm > math.sqrt(FLAT_VARIANCE * b * b))
        n = idx.size
        if n == 0:
            return Matches(ncc=ncc, i=pos, j=pos.copy(), rotated=rot)
        ncc[idx] = -np.inf
        q = (p[idx] / norm[idx, None, None]).reshape(n, b * b)
        vecs = np.concatenate([q, q[:, ::-1]])  # the blocks, then rotated by 180°
        points = vecs @ directions.T
        radius = math.sqrt(max(2.0 - 2.0 * threshold, 0.0)) + 1e-6
        counts = np.asarray(tree.query_ball_point(points, radius, return_length=True), dtype=np.int64)
        cap = max(_TREE_MIN_CAP, int(_TREE_MAX_CANDIDATES * live_windows.size))
        heavy = (counts[:n] > cap) | (counts[n:] > cap)
        best = np.full(2 * n, -np.inf)
        where = np.zeros(2 * n, dtype=np.int64)
        queries = np.flatnonzero(~np.concatenate([heavy, heavy]) & (counts > 0))
        my = self.windows[1]
        offs = np.arange(b)
        per_chunk = max(1, _DIRECT_CHUNK // (b * b))
        start = 0
        while start < queries.size:  # chunks of at most per_chunk candidates (or one query)
            stop = start + max(1, int(np.searchsorted(np.cumsum(counts[queries[start:]]), per_chunk, side="right")))
            sel = queries[start:stop]
            start = stop
            found = tree.query_ball_point(points[sel], radius, return_sorted=False)
            owner = np.repeat(sel, [len(c) for c in found])
            cand = live_windows[np.concatenate([np.asarray(c, dtype=np.int64) for c in found])]
            ci, cj = cand // my, cand % my
            w = self.lap[(ci[:, None] + offs)[:, :, None], (cj[:, None] + offs)[:, None, :]].reshape(cand.size, -1)
            vals = np.einsum("ij,ij->i", w, vecs[owner]) * self.inv_norm[ci, cj]
            order = np.lexsort((vals, owner))  # per owner ascending: its best is the last
            last = order[np.r_[owner[order][1:] != owner[order][:-1], True]]
            best[owner[last]] = vals[last]
            where[owner[last]] = cand[last]
        use_rot = best[n:] > best[:n]
        top = np.where(use_rot, best[n:], best[:n])
        at = np.where(use_rot, where[n:], where[:n])
        if heavy.any():
            full = self.match(raw[idx[heavy]])
            top[heavy] = full.ncc
            at[heavy] = full.i * my + full.j
            use_rot[heavy] = full.rotated
        hit = top >= threshold
        ncc[idx[hit]] = np.minimum(top[hit], 1.0)
        pos[idx[hit]] = at[hit]
        rot[idx[hit]] = use_rot[hit]
        return Matches(ncc=ncc, i=pos // my, j=pos % my, rotated=rot)

    def _index(self) -> tuple[cKDTree, FloatArray, IntArray]:
        """The k-d tree of the non-flat normalised windows' projections, the directions (rows) and the
        windows' flat indices, built once."""
        if self._tree is None:
            b = self.block
            mx, my = self.windows
            live = np.flatnonzero(self.inv_norm.ravel() > 0.0)
            gen = np.random.default_rng(0)  # fixed: the index is a function of the map
            pick = np.sort(gen.choice(live, size=min(live.size, _PCA_WINDOWS), replace=False)) if live.size else live
            offs = np.arange(b)
            pi, pj = pick // my, pick % my
            x = self.lap[(pi[:, None] + offs)[:, :, None], (pj[:, None] + offs)[:, None, :]].reshape(pick.size, -1)
            x = (x - x.mean(axis=1, keepdims=True)) * self.inv_norm[pi, pj][:, None]
            dims = min(_TREE_DIMENSIONS, b * b - 1)
            if pick.size:  # the leading eigenvectors of the windows' second-moment matrix
                vecs = np.linalg.eigh(x.T @ x)[1]
                directions = np.ascontiguousarray(vecs[:, ::-1][:, :dims].T)
            else:
                directions = np.zeros((dims, b * b))
            # projections of every window: (window · direction) / ‖window − mean‖ (directions sum to zero)
            proj = np.empty((mx * my, dims))
            d32 = directions.T.astype(np.float32)
            rows = max(1, _DIRECT_CHUNK // (b * b * my))
            for i in range(0, mx, rows):
                w = sliding_window_view(self.lap32[i : i + rows + b - 1], (b, b)).reshape(-1, b * b)
                proj[i * my : i * my + w.shape[0]] = (w @ d32) * self.inv_norm32[i : i + rows].reshape(-1, 1)
            tree = cKDTree(proj[live], balanced_tree=False, compact_nodes=False)
            self._tree = (tree, directions, live)
        return self._tree

    @staticmethod
    def _pick(plain: FloatArray, rotated: FloatArray) -> tuple[FloatArray, IntArray, npt.NDArray[np.bool_]]:
        """Per row of the ``k × windows`` NCCs: the larger maximum, where, and whether it is the rotated one."""
        ap, ar = plain.argmax(axis=1), rotated.argmax(axis=1)
        rows = np.arange(plain.shape[0])
        vp, vr = plain[rows, ap], rotated[rows, ar]
        use_rot = vr > vp
        return np.where(use_rot, vr, vp).astype(np.float64), np.where(use_rot, ar, ap), use_rot

    def _fft(self, q: FloatArray) -> tuple[FloatArray, IntArray, npt.NDArray[np.bool_]]:
        b = self.block
        mx, my = self.windows
        parts = []
        for start in range(0, q.shape[0], _BATCH):
            fq = sfft.rfft2(q[start : start + _BATCH], s=self.fshape, axes=(1, 2), workers=self.workers)
            plain = sfft.irfft2(self.spectrum * np.conj(fq), s=self.fshape, axes=(1, 2), workers=self.workers)
            plain = (plain[:, :mx, :my] * self.inv_norm).reshape(fq.shape[0], -1)
            # correlation with the block rotated by 180° = the convolution, read off shifted by block − 1
            conv = sfft.irfft2(self.spectrum * fq, s=self.fshape, axes=(1, 2), workers=self.workers)
            conv = (conv[:, b - 1 : b - 1 + mx, b - 1 : b - 1 + my] * self.inv_norm).reshape(fq.shape[0], -1)
            parts.append(self._pick(plain, conv))
        return (
            np.concatenate([x[0] for x in parts]),
            np.concatenate([x[1] for x in parts]),
            np.concatenate([x[2] for x in parts]),
        )

    def _direct(self, q: FloatArray) -> tuple[FloatArray, IntArray, npt.NDArray[np.bool_]]:
        b = self.block
        k = q.shape[0]
        flat = q.reshape(k, b * b)
        rows_q = np.concatenate([flat, flat[:, ::-1]]).astype(np.float32)  # the blocks, then rotated by 180°
        mx, my = self.windows
        rows = max(1, _DIRECT_CHUNK // (max(b * b, 2 * k) * my))
        best = np.full(2 * k, -np.inf, dtype=np.float32)
        where = np.zeros(2 * k, dtype=np.int64)
        every = np.arange(2 * k)
        for i in range(0, mx, rows):
            w = sliding_window_view(self.lap32[i : i + rows + b - 1], (b, b)).reshape(-1, b * b)
            c = rows_q @ w.T  # (2k, windows): each block's correlations contiguous
            c *= self.inv_norm32[i : i + rows].reshape(1, -1)
            am = c.argmax(axis=1)
            val = c[every, am]
            better = val > best
            best[better] = val[better]
            where[better] = i * my + am[better]
        use_rot = best[k:] > best[:k]
        ncc = np.where(use_rot, best[k:], best[:k]).astype(np.float64)
        return ncc, np.where(use_rot, where[k:], where[:k]), use_rot


def _blocks_at(lap: FloatArray, ti: IntArray, tj: IntArray, b: int) -> FloatArray:
    """The ``b × b`` blocks of ``lap`` with top-left corners ``(ti, tj)``, shape ``(k, b, b)``."""
    offs = np.arange(b)
    return np.asarray(lap[(ti[:, None] + offs)[:, :, None], (tj[:, None] + offs)[:, None, :]])


def _piece_keys(m: Matches, ti: IntArray, tj: IntArray, b: int) -> IntArray:
    """One key per block for the piece of the map it belongs to: the shift (map − surrogate) of an
    unrotated match, the sum (map + surrogate + block − 1) of a rotated one, and the orientation."""
    sign = np.where(m.rotated, 1, -1)
    off = np.where(m.rotated, b - 1, 0)
    return np.stack([m.i + sign * ti + off, m.j + sign * tj + off, m.rotated.astype(np.int64)], axis=1)


def _largest_share(keys: IntArray, n: int) -> float:
    if n == 0 or keys.shape[0] == 0:
        return 0.0
    _, counts = np.unique(keys, axis=0, return_counts=True)
    return float(counts.max()) / n


def verbatim_fraction(
    surrogate: npt.ArrayLike,
    measured: npt.ArrayLike,
    *,
    block: int | None = None,
    blocks: int = DEFAULT_BLOCKS,
    rng: np.random.Generator | SeedLike = 0,
    threshold: float = VERBATIM_NCC,
    corners: bool = True,
    rule: str = DEFAULT_SUMMIT_RULE,
    matcher: BlockMatcher | None = None,
    method: str = "auto",
) -> VerbatimMeasure:
    """Verbatim content of ``surrogate`` with respect to the ``measured`` map (module docstring).

    ``block`` defaults to one mean summit spacing of ``measured`` (:func:`default_block`, summits by
    ``rule``).  ``blocks`` points are drawn uniformly over the surrogate's Laplacian from ``rng`` (a
    generator or a seed; default seed 0, so the measure is a function of its inputs); the block
    centred on each point (moved inside at the border) is matched first — a draw whose centred block
    is flat is skipped and replaced, at most 8 × ``blocks`` draws — and with ``corners`` the four
    blocks that have the point at a corner are matched for every point whose centred block is not
    verbatim.  The surrogate may be larger than the map (a long surface).  Pass a
    :class:`BlockMatcher` of ``measured`` to measure many surrogates of one map without redoing its
    window statistics; ``method`` chooses how a new one matches (:class:`BlockMatcher`).
    """
    z = _map(measured, "the measured map")
    s = _map(surrogate, "the surrogate")
    if isinstance(blocks, bool) or not isinstance(blocks, int | np.integer) or blocks < 1:
        raise AnalysisError(f"blocks must be an integer >= 1, got {blocks!r}")
    if not 0.0 < threshold <= 1.0:
        raise AnalysisError(f"the NCC threshold must lie in (0, 1], got {threshold!r}")
    if matcher is None:
        matcher = BlockMatcher(z, default_block(z, rule) if block is None else block, method=method)
    elif block is not None and block != matcher.block:
        raise AnalysisError(f"block {block} differs from the matcher's block {matcher.block}")
    if matcher.shape != (z.shape[0] - 2, z.shape[1] - 2):
        raise AnalysisError("the matcher was built for a map of another shape")
    b = matcher.block
    lap = laplacian(s)
    lx, ly = lap.shape
    if b > min(lx, ly):
        raise AnalysisError(f"the block side {b} exceeds the surrogate's Laplacian ({lx}×{ly})")
    gen = as_generator(rng)
    got: list[tuple[IntArray, IntArray, FloatArray, IntArray]] = []
    have, skipped, draws = 0, 0, 0
    while have < blocks and draws < _MAX_DRAWS_PER_BLOCK * blocks:
        k = int(blocks) - have
        pi = gen.integers(0, lx, size=k)
        pj = gen.integers(0, ly, size=k)
        draws += k
        ti = np.clip(pi - b // 2, 0, lx - b)
        tj = np.clip(pj - b // 2, 0, ly - b)
        m = matcher.match(_blocks_at(lap, ti, tj, b))
        live = np.isfinite(m.ncc)
        skipped += int(np.count_nonzero(~live))
        got.append((pi[live], pj[live], m.ncc[live], _piece_keys(m, ti, tj, b)[live]))
        have += int(np.count_nonzero(live))
    if have == 0:
        raise AnalysisError(f"the surrogate has no curvature: every one of {draws} sampled blocks is flat")
    pi = np.concatenate([g[0] for g in got])
    pj = np.concatenate([g[1] for g in got])
    block_ncc = np.concatenate([g[2] for g in got])
    keys = np.concatenate([g[3] for g in got])
    best = block_ncc.copy()
    todo = np.flatnonzero(best < threshold) if corners else np.empty(0, dtype=np.int64)
    if todo.size:
        ci = np.concatenate([np.clip(pi[todo] - di, 0, lx - b) for di in (0, b - 1) for _ in (0, 1)])
        cj = np.concatenate([np.clip(pj[todo] - dj, 0, ly - b) for _ in (0, 1) for dj in (0, b - 1)])
        corner_blocks = _blocks_at(lap, ci, cj, b)
        if threshold >= _TREE_MIN_THRESHOLD:
            m = matcher.verbatim(corner_blocks, threshold)
        else:  # the index's candidate balls grow with 1 − threshold: search everything
            m = matcher.match(corner_blocks)
        vals = np.where(np.isfinite(m.ncc), m.ncc, -np.inf).reshape(4, todo.size)
        ck = _piece_keys(m, ci, cj, b).reshape(4, todo.size, 3)
        pick = vals.argmax(axis=0)
        cols = np.arange(todo.size)
        better = vals[pick, cols] >= threshold  # the centred blocks of these points are below it
        best[todo[better]] = vals[pick, cols][better]
        keys[todo[better]] = ck[pick, cols][better]
    n = int(best.size)
    verbatim = best >= threshold
    return _measure(
        best=best, block_ncc=block_ncc, share=_largest_share(keys[verbatim], n), block=b, skipped=skipped,
        threshold=float(threshold), measured_pieces=independent_pieces(z.size, b), surrogates=1,
    )  # fmt: skip


def _measure(
    *, best: FloatArray, block_ncc: FloatArray, share: float, block: int, skipped: int, threshold: float,
    measured_pieces: int, surrogates: int,
) -> VerbatimMeasure:  # fmt: skip
    n = int(best.size)
    k = int(np.count_nonzero(best >= threshold))
    frac = k / n if n else math.nan
    return VerbatimMeasure(
        fraction=frac,
        ci95=clopper_pearson_interval(k, n),
        block_fraction=float(np.count_nonzero(block_ncc >= threshold) / n) if n else math.nan,
        largest_piece_share=share,
        median_best_ncc=float(np.median(best)) if n else math.nan,
        median_block_ncc=float(np.median(block_ncc)) if n else math.nan,
        block=block,
        blocks=n,
        verbatim_blocks=k,
        skipped_flat=skipped,
        threshold=threshold,
        measured_pieces=measured_pieces,
        surrogates=surrogates,
        label=verbatim_label(frac if n else 0.0, share),
        best_ncc=tuple(float(v) for v in best),
        block_ncc=tuple(float(v) for v in block_ncc),
    )


def pool_verbatim(measures: Sequence[VerbatimMeasure]) -> VerbatimMeasure:
    """The measures of several surrogates of one map (same block and threshold) pooled: all sampled
    points counted together, the largest piece share of any one surrogate (a copy among them makes
    the pool a copy), the label of the pooled fraction."""
    if not measures:
        raise AnalysisError("nothing to pool: no verbatim measure given")
    first = measures[0]
    if any(m.block != first.block or m.threshold != first.threshold for m in measures):
        raise AnalysisError("verbatim measures pooled must share the block side and the threshold")
    return _measure(
        best=np.array([v for m in measures for v in m.best_ncc]),
        block_ncc=np.array([v for m in measures for v in m.block_ncc]),
        share=max(m.largest_piece_share for m in measures),
        block=first.block,
        skipped=sum(m.skipped_flat for m in measures),
        threshold=first.threshold,
        measured_pieces=first.measured_pieces,
        surrogates=sum(m.surrogates for m in measures),
    )

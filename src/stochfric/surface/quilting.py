"""Non-Gaussian surrogates: image quilting with gradient-domain seam repair (method §3, beyond the thesis).

Surrogates made of pieces of the measured map keep the local, non-Gaussian structure (summits, their
curvature) that the Greenwood–Williamson contact reads: the map's high-pass part is quilted (Efros &
Freeman 2001) from randomly placed square patches, the seams are repaired by a screened Poisson
equation on the source gradients, and the map's own DCT low-pass with random signs gives the long
wavelengths (:func:`low_band`).  The patch rules are fixed constants; :func:`copy_metrics` says how
much of the map a surrogate copies (docs/statistical_contact.md, "Non-Gaussian surrogates: quilting").
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any, NamedTuple

import numba
import numpy as np
import numpy.typing as npt
from scipy import fft as sfft
from scipy.sparse import coo_matrix
from scipy.sparse.csgraph import connected_components

from stochfric.arrays import FloatArray
from stochfric.random import SeedLike, as_generator
from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, find_summits
from stochfric.surface.synthesis import checked_heights

__all__ = [
    "CANDIDATES",
    "CHOOSE",
    "COPY_NCC_LIMIT",
    "COPY_PIECE_LIMIT",
    "MAX_PATCH_FRACTION",
    "MIN_PATCH",
    "MIN_PATCH_SUMMIT_SPACINGS",
    "OVERLAP_FRACTION",
    "PATCH_SUMMIT_SPACINGS",
    "QUILT_METHOD",
    "SCREENING_PATCHES",
    "SPLIT_ORDER",
    "SPLIT_PATCHES",
    "CopyMetrics",
    "QuiltParameters",
    "QuiltResult",
    "copy_metrics",
    "largest_verbatim_piece",
    "low_band",
    "max_normalised_correlation",
    "max_patch",
    "quilt_applicable",
    "quilt_heights",
    "quilt_parameters",
    "quilt_surface",
    "screened_poisson",
    "source_gradients",
    "split_heights",
]

IntArray = npt.NDArray[np.int32]

#: Patch side in mean summit spacings (capped by :func:`max_patch`).
PATCH_SUMMIT_SPACINGS = 24.0
#: A map is quilted only if a patch of this many summit spacings fits under the cap.
MIN_PATCH_SUMMIT_SPACINGS = 16.0
#: Smallest patch side [points].
MIN_PATCH = 12
#: Largest patch side as a fraction of the shorter map side (several patches per map).
MAX_PATCH_FRACTION = 1.0 / 3.0
#: Overlap of neighbouring patches as a fraction of the patch side.
OVERLAP_FRACTION = 0.25
#: Random candidate source positions drawn per patch.
CANDIDATES = 4
#: The patch is drawn uniformly among the ``CHOOSE`` best (least overlap error) admissible candidates.
CHOOSE = 4
#: Screening length 1/κ of the seam repair in patch sides.
SCREENING_PATCHES = 1.0
#: Split wavelength between random-phase long and quilted short wavelengths, in patch sides (0 = off).
SPLIT_PATCHES = 1.5
#: The registry name of quilted surrogates (:mod:`stochfric.surface.surrogates`).
QUILT_METHOD = "quilt"
#: Order of the Butterworth split between the random-phase long and the quilted short wavelengths.
SPLIT_ORDER = 8
#: A surrogate whose largest verbatim piece exceeds this fraction of the map's area is a copy.
COPY_PIECE_LIMIT = 0.1
#: A surrogate whose largest normalised cross-correlation with the map exceeds this is a copy.
COPY_NCC_LIMIT = 0.9


@dataclass(frozen=True, kw_only=True)
class QuiltParameters:
    """Patch side, overlap [points], candidates per patch, 180° rotation, screening length [points]."""

    patch: int
    overlap: int
    candidates: int = CANDIDATES
    rotate: bool = True
    screening_length: float = 0.0
    split_wavelength: float = 0.0
    choose: int = 1

    def __post_init__(self) -> None:
        if self.patch < 4:
            raise SurfaceError(f"the patch side must be >= 4 points, got {self.patch}")
        if not 1 <= self.overlap <= self.patch // 2:
            raise SurfaceError(f"the overlap must be between 1 and patch/2 = {self.patch // 2}, got {self.overlap}")
        if self.candidates < 1:
            raise SurfaceError(f"candidates must be >= 1, got {self.candidates}")
        if not 1 <= self.choose <= self.candidates:
            raise SurfaceError(f"choose must be between 1 and candidates = {self.candidates}, got {self.choose}")
        if not self.split_wavelength >= 0.0:
            raise SurfaceError(f"the split wavelength must be >= 0, got {self.split_wavelength}")
        if not self.screening_length >= 0.0:
            raise SurfaceError(f"the screening length must be >= 0, got {self.screening_length}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return asdict(self)


@dataclass(frozen=True, kw_only=True, eq=False)
class QuiltResult:
    """A quilted map: repaired heights, each point's source point and orientation, the parameters."""

    heights: FloatArray
    source_i: IntArray
    source_j: IntArray
    rotated: npt.NDArray[np.int8]
    parameters: QuiltParameters


def _heights(z: npt.ArrayLike) -> FloatArray:
    return checked_heights(z, "quilting")


def max_patch(nx: int, ny: int) -> int:
    """Largest patch side for an ``nx × ny`` map: at most ``min(nx, ny) · MAX_PATCH_FRACTION`` and
    with ``patch² < COPY_PIECE_LIMIT · nx · ny`` (a verbatim piece is at most one patch: below the
    copy limit by construction)."""
    upper = int(min(nx, ny) * MAX_PATCH_FRACTION)
    while upper > 0 and upper * upper >= COPY_PIECE_LIMIT * nx * ny:
        upper -= 1
    return upper


def quilt_parameters(
    heights: npt.ArrayLike,
    *,
    rule: str = DEFAULT_SUMMIT_RULE,
    patch_spacings: float = PATCH_SUMMIT_SPACINGS,
    candidates: int = CANDIDATES,
    choose: int = CHOOSE,
    rotate: bool = True,
) -> QuiltParameters:
    """The fixed rules applied to a map (summits by ``rule``): ``patch = clip(round(patch_spacings · d_s),
    MIN_PATCH, max_patch(nx, ny))`` with ``d_s = √(nx·ny / n_summits)`` the mean summit spacing in points,
    ``overlap = round(patch · OVERLAP_FRACTION)``, screening length ``SCREENING_PATCHES · patch`` and split
    wavelength ``SPLIT_PATCHES · patch`` [points]."""
    z = _heights(heights)
    nx, ny = z.shape
    upper = max_patch(nx, ny)
    if upper < MIN_PATCH:
        raise SurfaceError(
            f"a {nx}×{ny} map is too small to quilt: patches of at least {MIN_PATCH} points must fit "
            f"{1 / MAX_PATCH_FRACTION:.0f} times along the shorter side and cover less than "
            f"{COPY_PIECE_LIMIT:.0%} of the map"
        )
    n = find_summits(z, (1.0, 1.0), rule=rule).count
    spacing = math.sqrt(z.size / n) if n else float(upper)
    patch = int(min(max(round(patch_spacings * spacing), MIN_PATCH), upper))
    overlap = max(1, round(patch * OVERLAP_FRACTION))
    return QuiltParameters(
        patch=patch,
        overlap=overlap,
        candidates=candidates,
        choose=min(choose, candidates),
        rotate=rotate,
        screening_length=SCREENING_PATCHES * patch,
        split_wavelength=SPLIT_PATCHES * patch,
    )


def quilt_applicable(heights: npt.ArrayLike, *, rule: str = DEFAULT_SUMMIT_RULE) -> tuple[bool, str]:
    """Can this map be quilted by the fixed rules (:func:`quilt_parameters`)?  ``(yes, reason)``.

    A quilt needs patches of at least ``MIN_PATCH_SUMMIT_SPACINGS`` summit spacings (so that
    seams touch few summits) under the cap :func:`max_patch` (at least ``1/MAX_PATCH_FRACTION``
    along the shorter side, one patch below ``COPY_PIECE_LIMIT`` of the area, so that the
    surrogate is not one piece of the map): ``round(16 d_s) <= max_patch(nx, ny)``.  The patch
    used is then ``min(round(24 d_s), max_patch)`` (:func:`quilt_parameters`).  A map with too
    few summits for that is left to random phases (``surrogate = "auto"``).
    """
    z = _heights(heights)
    nx, ny = z.shape
    upper = max_patch(nx, ny)
    n = find_summits(z, (1.0, 1.0), rule=rule).count
    if n == 0:
        return False, "the map has no summit"
    spacing = math.sqrt(z.size / n)
    need = round(MIN_PATCH_SUMMIT_SPACINGS * spacing)
    if need > upper:
        return False, (f"{n} summits, mean spacing {spacing:.3g} points: a patch of {MIN_PATCH_SUMMIT_SPACINGS:g} "
                       f"spacings ({need} points) does not fit {1 / MAX_PATCH_FRACTION:.0f} times along the "
                       f"shorter side ({min(nx, ny)} points) with less than {COPY_PIECE_LIMIT:.0%} of the map")
    patch = min(max(round(PATCH_SUMMIT_SPACINGS * spacing), MIN_PATCH), upper)
    return True, (f"{n} summits, mean spacing {spacing:.3g} points: patches of {patch} points, "
                  f"{min(nx, ny) / patch:.1f} along the shorter side")


@numba.njit(cache=True, nogil=True)
def _cut_path(err: FloatArray) -> npt.NDArray[np.int64]:
    """Minimum-cost path from the first to the last row of ``err`` (moves −1, 0, +1): column per row."""
    rows, cols = err.shape
    cost = err.copy()
    for u in range(1, rows):
        for v in range(cols):
            best = cost[u - 1, v]
            if v > 0 and cost[u - 1, v - 1] < best:
                best = cost[u - 1, v - 1]
            if v < cols - 1 and cost[u - 1, v + 1] < best:
                best = cost[u - 1, v + 1]
            cost[u, v] += best
    path = np.empty(rows, dtype=np.int64)
    v = 0
    for w in range(1, cols):
        if cost[rows - 1, w] < cost[rows - 1, v]:
            v = w
    path[rows - 1] = v
    for u in range(rows - 2, -1, -1):
        best_v = v
        if v > 0 and cost[u, v - 1] < cost[u, best_v]:
            best_v = v - 1
        if v < cols - 1 and cost[u, v + 1] < cost[u, best_v]:
            best_v = v + 1
        v = best_v
        path[u] = v
    return path


class _Source(NamedTuple):
    """A candidate source patch: its first point ``(i, j)``, ``rotated`` (1: turned by 180°) and
    ``last`` = patch − 1 (point ``(u, v)`` of a rotated patch is ``(i + last − u, j + last − v)``)."""

    i: int
    j: int
    rotated: int
    last: int


@numba.njit(cache=True, nogil=True)
def _block_error(
    z: FloatArray, out: FloatArray, src: _Source, x0: int, y0: int, rows: int, v_start: int, v_stop: int, e: float,
    best_err: float,
) -> float:  # pragma: no cover - compiled
    """``e`` plus the squared difference between the output placed at ``(x0, y0)`` and the candidate
    source patch ``src`` over rows ``0..rows`` and columns ``v_start..v_stop`` of the patch; stops
    early once it reaches ``best_err``."""
    ci, cj, r, b1 = src
    for u in range(rows):
        for v in range(v_start, v_stop):
            h = z[ci + u, cj + v] if r == 0 else z[ci + b1 - u, cj + b1 - v]
            d = out[x0 + u, y0 + v] - h
            e += d * d
        if e >= best_err:
            break
    return e


@numba.njit(cache=True, nogil=True)
def _overlap_errors(
    z: FloatArray, out: FloatArray, src: _Source, x0: int, y0: int, err: FloatArray, top: bool
) -> None:  # pragma: no cover - compiled
    """Squared differences between the output placed at ``(x0, y0)`` and the source patch ``src``
    over the left overlap (``err[u, v]``, row u, column v) or, with ``top``, the top overlap
    (``err[v, u]``): the seam runs along the first axis of ``err``."""
    ci, cj, r, b1 = src
    for s in range(err.shape[0]):
        for t in range(err.shape[1]):
            u, v = (t, s) if top else (s, t)
            h = z[ci + u, cj + v] if r == 0 else z[ci + b1 - u, cj + b1 - v]
            d = out[x0 + u, y0 + v] - h
            err[s, t] = d * d


@numba.njit(cache=True, nogil=True)
def _quilt_kernel(
    z: FloatArray,
    n_px: int,
    n_py: int,
    patch: int,
    overlap: int,
    cand: npt.NDArray[np.int64],
    exclusion: int,
    pick: npt.NDArray[np.int64],
    choose: int,
) -> tuple[FloatArray, IntArray, IntArray, npt.NDArray[np.int8]]:
    """Raster-order quilt of ``n_px × n_py`` patches; ``cand[k, c] = (i, j, rotated)``.

    A candidate whose source offset lies within ``exclusion`` of an already placed neighbour's with
    the same orientation is excluded (the trivial continuation, which would copy the map); the
    patch is the ``pick[k] mod n``-th of the ``n`` admissible candidates ordered by overlap error,
    cut into the placed ones along the minimum-error boundaries (one vertical, one horizontal cut)."""
    step = patch - overlap
    px = n_px * step + overlap
    py = n_py * step + overlap
    out = np.zeros((px, py))
    si = np.zeros((px, py), dtype=np.int32)
    sj = np.zeros((px, py), dtype=np.int32)
    rot = np.zeros((px, py), dtype=np.int8)
    # per placed patch: orientation and source offset (constant along a verbatim piece)
    p_rot = np.zeros((n_px, n_py), dtype=np.int64)
    p_di = np.zeros((n_px, n_py), dtype=np.int64)
    p_dj = np.zeros((n_px, n_py), dtype=np.int64)
    n_cand = cand.shape[1]
    err_v = np.empty((patch, overlap))
    err_h = np.empty((patch, overlap))
    b1 = patch - 1
    for a in range(n_px):
        for b in range(n_py):
            k = a * n_py + b
            x0 = a * step
            y0 = b * step
            errs = np.full(n_cand, np.inf)
            best_err = np.inf
            n_ok = 0
            for c in range(n_cand):
                ci = cand[k, c, 0]
                cj = cand[k, c, 1]
                r = cand[k, c, 2]
                if r == 0:
                    di = ci - x0
                    dj = cj - y0
                else:
                    di = ci + b1 + x0
                    dj = cj + b1 + y0
                excluded = False
                for na, nb in ((a, b - 1), (a - 1, b), (a - 1, b - 1), (a - 1, b + 1)):
                    if na < 0 or nb < 0 or nb >= n_py:
                        continue
                    if p_rot[na, nb] == r and abs(p_di[na, nb] - di) < exclusion and abs(p_dj[na, nb] - dj) < exclusion:
                        excluded = True
                if excluded:
                    continue
                n_ok += 1
                e = 0.0
                # left overlap: all rows, first `overlap` columns; top overlap: first `overlap` rows,
                # columns not counted already
                src = _Source(ci, cj, r, b1)
                if b > 0:
                    e = _block_error(z, out, src, x0, y0, patch, 0, overlap, e, best_err)
                if a > 0 and e < best_err:
                    e = _block_error(z, out, src, x0, y0, overlap, overlap if b > 0 else 0, patch, e, best_err)
                errs[c] = e
                if choose == 1 and e < best_err:
                    best_err = e
            if n_ok == 0:  # every candidate excluded: take the first
                best = 0
            else:
                order = np.argsort(errs, kind="mergesort")
                pick_k = pick[k] % n_ok
                best = order[pick_k]
            ci = cand[k, best, 0]
            cj = cand[k, best, 1]
            r = cand[k, best, 2]
            p_rot[a, b] = r
            if r == 0:
                p_di[a, b] = ci - x0
                p_dj[a, b] = cj - y0
            else:
                p_di[a, b] = ci + b1 + x0
                p_dj[a, b] = cj + b1 + y0
            # minimum-error boundary cuts
            cut_v = np.zeros(patch, dtype=np.int64)
            cut_h = np.zeros(patch, dtype=np.int64)
            if b > 0:
                _overlap_errors(z, out, _Source(ci, cj, r, b1), x0, y0, err_v, False)
                cut_v = _cut_path(err_v)
            if a > 0:
                _overlap_errors(z, out, _Source(ci, cj, r, b1), x0, y0, err_h, True)
                cut_h = _cut_path(err_h)
            for u in range(patch):
                for v in range(patch):
                    if b > 0 and v < overlap and v < cut_v[u]:
                        continue
                    if a > 0 and u < overlap and u < cut_h[v]:
                        continue
                    if r == 0:
                        s_i = ci + u
                        s_j = cj + v
                    else:
                        s_i = ci + b1 - u
                        s_j = cj + b1 - v
                    out[x0 + u, y0 + v] = z[s_i, s_j]
                    si[x0 + u, y0 + v] = s_i
                    sj[x0 + u, y0 + v] = s_j
                    rot[x0 + u, y0 + v] = r
    return out, si, sj, rot


def source_gradients(
    heights: npt.ArrayLike, source_i: npt.ArrayLike, source_j: npt.ArrayLike, rotated: npt.ArrayLike
) -> tuple[FloatArray, FloatArray]:
    """Target forward differences ``(g_x, g_y)`` of an output map from its source points.

    ``g_x(p) = z(s + e_x) − z(s)`` for a point taken as it is, ``z(s − e_x) − z(s)`` for a
    180°-rotated one (the forward step in the output is the backward step in the source), the
    source's nearest difference where the source point is on the map's border; the last row of
    ``g_x`` and the last column of ``g_y`` are 0 (Neumann boundary).
    """
    z = _heights(heights)
    i = np.asarray(source_i, dtype=np.intp)
    j = np.asarray(source_j, dtype=np.intp)
    r = np.asarray(rotated, dtype=bool)
    fx = np.empty_like(z)
    fx[:-1] = z[1:] - z[:-1]
    fx[-1] = fx[-2]
    fy = np.empty_like(z)
    fy[:, :-1] = z[:, 1:] - z[:, :-1]
    fy[:, -1] = fy[:, -2]
    gx = np.where(r, -fx[np.maximum(i - 1, 0), j], fx[i, j])
    gy = np.where(r, -fy[i, np.maximum(j - 1, 0)], fy[i, j])
    gx[-1, :] = 0.0
    gy[:, -1] = 0.0
    return np.asarray(gx), np.asarray(gy)


def screened_poisson(hard: npt.ArrayLike, gx: npt.ArrayLike, gy: npt.ArrayLike, screening_length: float) -> FloatArray:
    """Solve ``(κ² − ∇²) z = κ² hard − div g``, κ = 1/``screening_length``, Neumann boundaries.

    ``g`` are forward differences (last row of ``gx``, last column of ``gy`` zero), ``div`` the
    matching backward difference, ``∇²`` the 5-point Neumann Laplacian, diagonalised by the
    orthonormal DCT-II.  ``screening_length = 0`` returns ``hard``.  If ``g`` are the forward
    differences of ``hard`` the result is ``hard`` (to round-off).
    """
    h = np.asarray(hard, dtype=np.float64)
    if screening_length <= 0.0:
        return h.copy()
    gxa = np.asarray(gx, dtype=np.float64)
    gya = np.asarray(gy, dtype=np.float64)
    kappa2 = 1.0 / (screening_length * screening_length)
    div = gxa.copy()
    div[1:] -= gxa[:-1]
    div += gya
    div[:, 1:] -= gya[:, :-1]
    rhs = kappa2 * h - div
    del div
    return _solve_screened(rhs, kappa2)


def _solve_screened(rhs: FloatArray, kappa2: float) -> FloatArray:
    """``(κ² − ∇²)⁻¹ rhs`` with Neumann boundaries by the orthonormal DCT-II (``rhs`` is overwritten)."""
    m, n = rhs.shape
    lam_x = 4.0 * np.sin(np.pi * np.arange(m) / (2 * m)) ** 2
    lam_y = 4.0 * np.sin(np.pi * np.arange(n) / (2 * n)) ** 2
    coef = sfft.dctn(rhs, type=2, norm="ortho", overwrite_x=True, workers=1)
    del rhs
    coef /= kappa2 + lam_x[:, None] + lam_y[None, :]
    return np.asarray(sfft.idctn(coef, type=2, norm="ortho", overwrite_x=True, workers=1))


@numba.njit(cache=True, nogil=True)
def _source_step(z: FloatArray, i: int, j: int, r: int, axis: int) -> float:  # pragma: no cover - compiled
    """The target forward difference of :func:`source_gradients` at one output point."""
    m, n = z.shape
    if axis == 0:
        a = max(i - 1, 0) if r else i
        a = min(a, m - 2)
        d = z[a + 1, j] - z[a, j]
    else:
        b = max(j - 1, 0) if r else j
        b = min(b, n - 2)
        d = z[i, b + 1] - z[i, b]
    return -d if r else d


@numba.njit(cache=True, nogil=True)
def _seam_rhs(
    z: FloatArray, si: IntArray, sj: IntArray, rot: npt.NDArray[np.int8], hard: FloatArray, kappa2: float
) -> FloatArray:  # pragma: no cover - compiled
    """``κ² hard − div g`` of :func:`screened_poisson` with ``g`` from :func:`source_gradients`, point by
    point without storing ``g`` (the same floating-point operations in the same order)."""
    px, py = hard.shape
    rhs = np.empty((px, py))
    for x in range(px):
        for y in range(py):
            gx = 0.0 if x == px - 1 else _source_step(z, si[x, y], sj[x, y], rot[x, y], 0)
            d = gx
            if x >= 1:
                d = d - _source_step(z, si[x - 1, y], sj[x - 1, y], rot[x - 1, y], 0)
            gy = 0.0 if y == py - 1 else _source_step(z, si[x, y], sj[x, y], rot[x, y], 1)
            d = d + gy
            if y >= 1:
                d = d - (0.0 if y - 1 == py - 1 else _source_step(z, si[x, y - 1], sj[x, y - 1], rot[x, y - 1], 1))
            rhs[x, y] = kappa2 * hard[x, y] - d
    return rhs


def _split_gain(k: FloatArray, split_wavelength: float) -> FloatArray:
    """Power-complementary low-pass gain ``L(k) = (1 + (k/k_c)^(2p))^(−1/2)``, k_c = 2π/λ_c (L² + H² = 1).

    Butterworth of order p = :data:`SPLIT_ORDER`.
    """
    kc = 2.0 * np.pi / split_wavelength
    return np.asarray(1.0 / np.sqrt(1.0 + (k / kc) ** (2 * SPLIT_ORDER)))


def _dct_wavenumbers(m: int, n: int) -> FloatArray:
    """|k| [rad/point] of the DCT-II modes of an ``m × n`` map."""
    kx = np.pi * np.arange(m) / m
    ky = np.pi * np.arange(n) / n
    return np.asarray(np.sqrt(kx[:, None] ** 2 + ky[None, :] ** 2))


def _high_gain(k: FloatArray, split_wavelength: float) -> FloatArray:
    low = _split_gain(k, split_wavelength)
    return np.asarray(np.sqrt(np.maximum(1.0 - low * low, 0.0)))


def split_heights(heights: npt.ArrayLike, split_wavelength: float) -> FloatArray:
    """High-pass part ``H(k)·z`` of a (non-periodic) map, filtered in the DCT-II domain (no edge jump)."""
    z = _heights(heights)
    coef = sfft.dctn(z, type=2, norm="ortho", workers=1)
    coef *= _high_gain(_dct_wavenumbers(*z.shape), split_wavelength)
    return np.asarray(sfft.idctn(coef, type=2, norm="ortho", workers=1))


def low_band(
    heights: npt.ArrayLike, split_wavelength: float, rng: np.random.Generator | SeedLike = None, *, factor: int = 1
) -> FloatArray:
    """Random-sign DCT surrogate of the low-pass part ``L(k)·z`` of a map, ``(nx, factor·ny)`` points.

    The map's own DCT-II coefficients (mean removed) times ``L(k)``, each with a random sign, and
    the mean added back: for ``factor = 1`` the low band has exactly the power spectrum (DCT) —
    hence the variance and the slopes — of the map's own low-pass part.  For ``factor > 1``
    mode ``q'`` along y takes the map's mode ``q = round(q'/factor)`` (the same wavelength), its
    power shared among the ``count(q)`` long modes that take it (amplitude ``·√(factor/count)``),
    so the variance is the map's low-band variance again.  Only modes with ``L(k) ≥ 10⁻⁶``
    (``k ≤ 5.62 k_c``) are kept; their signs are drawn from ``rng`` in C order.
    """
    z = _heights(heights)
    gen = as_generator(rng)
    m, n = z.shape
    f = int(factor)
    n2 = f * n
    mean = float(z.mean())
    coef = sfft.dctn(z - mean, type=2, norm="ortho", workers=1)
    kmax = 2.0 * np.pi / split_wavelength * 10.0 ** (12.0 / (4 * SPLIT_ORDER))  # L(kmax) = 1e-6
    p_box = min(m, math.ceil(kmax * m / np.pi) + 1)
    q_box = min(n2, math.ceil(kmax * n2 / np.pi) + 1)
    q_map = np.minimum((2 * np.arange(n2) + f) // (2 * f), n - 1)  # round(q'/f), half up
    count = np.bincount(q_map, minlength=n).astype(np.float64)
    q_src = q_map[:q_box]
    amp = coef[:p_box][:, q_src] * np.sqrt(f / count[q_src])[None, :]
    kx = np.pi * np.arange(p_box) / m
    ky = np.pi * np.arange(q_box) / n2
    amp *= _split_gain(np.sqrt(kx[:, None] ** 2 + ky[None, :] ** 2), split_wavelength)
    amp *= np.where(gen.random((p_box, q_box)) < 0.5, -1.0, 1.0)
    full = np.zeros((m, n2))
    full[:p_box, :q_box] = amp
    low = np.asarray(sfft.idctn(full, type=2, norm="ortho", overwrite_x=True, workers=1))
    low += mean  # in place: a long surface's band is as large as the surface
    return low


def quilt_heights(
    heights: npt.ArrayLike,
    rng: np.random.Generator | SeedLike = None,
    *,
    factor: int = 1,
    parameters: QuiltParameters | None = None,
    sources: bool = True,
) -> QuiltResult:
    """A quilted surrogate of ``heights`` (module docstring), ``(nx, factor·ny)`` points.

    Deterministic given ``rng``: all random numbers are drawn from it in a fixed order.  With
    ``sources=False`` the source maps are freed before the long wavelengths are added (a third
    less peak memory for a long surface) and the result holds empty ones (``copy_metrics`` then
    measures the correlation only).
    """
    z = _heights(heights)
    gen = as_generator(rng)
    nx, ny = z.shape
    if isinstance(factor, bool) or not isinstance(factor, int | np.integer) or factor < 1:
        raise SurfaceError(f"the length factor must be an integer >= 1, got {factor!r}")
    px, py = nx, int(factor) * ny
    par = parameters if parameters is not None else quilt_parameters(z)
    b, ov = par.patch, par.overlap
    if b > min(nx, ny):
        raise SurfaceError(f"the patch side {b} exceeds the map ({nx}×{ny} points)")
    split = par.split_wavelength > 0.0
    src = split_heights(z, par.split_wavelength) if split else z
    step = b - ov
    n_px = max(1, math.ceil((px - ov) / step))
    n_py = max(1, math.ceil((py - ov) / step))
    n_patch = n_px * n_py
    cand = np.empty((n_patch, par.candidates, 3), dtype=np.int64)
    cand[:, :, 0] = gen.integers(0, nx - b + 1, size=(n_patch, par.candidates))
    cand[:, :, 1] = gen.integers(0, ny - b + 1, size=(n_patch, par.candidates))
    if par.rotate:
        cand[:, :, 2] = gen.integers(0, 2, size=(n_patch, par.candidates))
    else:
        cand[:, :, 2] = 0
    pick = gen.integers(0, par.choose, size=n_patch) if par.choose > 1 else np.zeros(n_patch, dtype=np.int64)
    out, si, sj, rot = _quilt_kernel(src, n_px, n_py, b, ov, cand, max(1, b // 2), pick.astype(np.int64), par.choose)
    del cand
    hard = out[:px, :py]
    si = si[:px, :py]
    sj = sj[:px, :py]
    rot = rot[:px, :py]
    kappa2 = 1.0 / (par.screening_length * par.screening_length) if par.screening_length > 0.0 else 0.0
    rhs = _seam_rhs(src, si, sj, rot, hard, kappa2) if kappa2 > 0.0 else np.array(hard)
    del out, hard  # the hard quilt is in rhs now; free it before the solve (memory of long surfaces)
    if not sources:
        si = sj = np.empty((0, 0), dtype=np.int32)
        rot = np.empty((0, 0), dtype=np.int8)
    repaired = _solve_screened(rhs, kappa2) if kappa2 > 0.0 else rhs
    del rhs
    if split:
        repaired += low_band(z, par.split_wavelength, gen, factor=int(factor))
    return QuiltResult(heights=repaired, source_i=si, source_j=sj, rotated=rot, parameters=par)


def quilt_surface(
    surface: Surface,
    rng: np.random.Generator | SeedLike = None,
    *,
    factor: int = 1,
    parameters: QuiltParameters | None = None,
) -> Surface:
    """:func:`quilt_heights` of ``surface``, ``factor`` times longer along y (axis 1), as a Surface."""
    res = quilt_heights(surface.heights_m, rng, factor=factor, parameters=parameters)
    lx, ly = surface.physical_size_m
    return Surface(
        heights_m=res.heights,
        physical_size_m=(lx, int(factor) * ly),
        source=f"quilt surrogate (length factor {factor}) of {surface.source}",
        n_undefined_filled=0,
        info={
            "surrogate": QUILT_METHOD,
            "length_factor": int(factor),
            "original": surface.source,
            "quilt": res.parameters.to_dict(),
        },
    )


def largest_verbatim_piece(source_i: npt.ArrayLike, source_j: npt.ArrayLike, rotated: npt.ArrayLike) -> int:
    """Points in the largest 4-connected region of constant source offset and orientation.

    Such a region is a verbatim copy of a piece of the map (for a rotated region, rotated).
    """
    i = np.asarray(source_i, dtype=np.int64)
    j = np.asarray(source_j, dtype=np.int64)
    r = np.asarray(rotated, dtype=np.int64)
    m, n = i.shape
    gi, gj = np.indices((m, n), dtype=np.int64)
    sign = 1 - 2 * r  # offset s − p, or s + p for a rotated point
    key_i = i - sign * gi
    key_j = j - sign * gj
    idx = np.arange(m * n).reshape(m, n)
    same_x = (key_i[1:] == key_i[:-1]) & (key_j[1:] == key_j[:-1]) & (r[1:] == r[:-1])
    same_y = (key_i[:, 1:] == key_i[:, :-1]) & (key_j[:, 1:] == key_j[:, :-1]) & (r[:, 1:] == r[:, :-1])
    rows = np.concatenate([idx[:-1][same_x], idx[:, :-1][same_y]])
    cols = np.concatenate([idx[1:][same_x], idx[:, 1:][same_y]])
    graph = coo_matrix((np.ones(rows.size, dtype=np.int8), (rows, cols)), shape=(m * n, m * n))
    _, labels = connected_components(graph, directed=False)
    return int(np.bincount(labels).max())


def max_normalised_correlation(a: npt.ArrayLike, b: npt.ArrayLike, *, min_overlap: float = 0.25) -> float:
    """Largest normalised cross-correlation of ``a`` and ``b`` over all shifts (FFT).

    At each relative shift the overlapping parts are compared with their own means and standard
    deviations (Pearson correlation of the overlap); only shifts where the overlap covers at
    least ``min_overlap`` of the smaller map's points count.  A shifted or cropped copy gives
    1; independent fields give a few times 1/√(overlap points / correlation area).
    """
    x = _heights(a)
    y = _heights(b)
    shape = (x.shape[0] + y.shape[0] - 1, x.shape[1] + y.shape[1] - 1)
    fshape = tuple(sfft.next_fast_len(s, real=True) for s in shape)

    def spec(v: FloatArray) -> Any:
        return sfft.rfft2(v, s=fshape)

    def corr(fa: Any, fb: Any) -> FloatArray:
        return np.asarray(sfft.irfft2(fa * np.conj(fb), s=fshape))

    x0 = x - x.mean()
    y0 = y - y.mean()
    scale = max(float(np.abs(x0).max()), float(np.abs(y0).max()), np.finfo(float).tiny)
    x0 /= scale
    y0 /= scale
    fx, fy = spec(x0), spec(y0)
    fx2, fy2 = spec(x0 * x0), spec(y0 * y0)
    fox, foy = spec(np.ones_like(x0)), spec(np.ones_like(y0))
    count = np.rint(corr(fox, foy))
    sxy = corr(fx, fy)
    sx = corr(fx, foy)
    sy = corr(fox, fy)
    sxx = corr(fx2, foy)
    syy = corr(fox, fy2)
    need = min_overlap * min(x.size, y.size)
    ok = count >= max(need, 2.0)
    cnt = np.where(ok, count, 1.0)
    cov = sxy - sx * sy / cnt
    vx = sxx - sx * sx / cnt
    vy = syy - sy * sy / cnt
    floor = 1e-12 * cnt
    ok &= (vx > floor) & (vy > floor)
    with np.errstate(invalid="ignore", divide="ignore"):
        r = np.where(ok, cov / np.sqrt(np.where(ok, vx * vy, 1.0)), -np.inf)
    return float(np.max(r))


@dataclass(frozen=True, kw_only=True)
class CopyMetrics:
    """How much of a map a surrogate reproduces (:func:`copy_metrics`)."""

    max_ncc: float
    largest_piece_fraction: float
    ncc_limit: float
    piece_limit: float

    @property
    def is_copy(self) -> bool:
        """True if the largest verbatim piece or the largest correlation exceeds its limit."""
        return self.largest_piece_fraction > self.piece_limit or self.max_ncc > self.ncc_limit


def copy_metrics(
    surrogate: npt.ArrayLike,
    original: npt.ArrayLike,
    *,
    source: QuiltResult | None = None,
    ncc_limit: float = COPY_NCC_LIMIT,
    piece_limit: float = COPY_PIECE_LIMIT,
) -> CopyMetrics:
    """Overlap of ``surrogate`` with ``original`` (the map, or another surrogate).

    ``max_ncc``: :func:`max_normalised_correlation`.  ``largest_piece_fraction``: the largest
    verbatim piece (:func:`largest_verbatim_piece`, from ``source``'s source map) over the
    area of ``original``; without ``source`` only the correlation is measured (piece 0).
    """
    ncc = max_normalised_correlation(surrogate, original)
    piece = 0.0
    if source is not None:
        piece = largest_verbatim_piece(source.source_i, source.source_j, source.rotated) / np.asarray(original).size
    return CopyMetrics(max_ncc=ncc, largest_piece_fraction=float(piece), ncc_limit=ncc_limit, piece_limit=piece_limit)

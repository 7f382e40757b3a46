"""Contact analysis of many similar surfaces and of sliding windows (method §4a–c, thesis 3.1.4, 3.2.4, 3.2.5).

GW/Hertz + Bowden–Tabor contact as arrays over (sample, approach): :func:`ensemble_contact` of R
surrogates of original size (§4a), :func:`window_contact` of windows along a long surface, each
referenced to its own highest summit (§4b–c), :func:`path_contact` of K long surfaces (§4c and the
ergodicity check).  Realisation / long surface k uses the k-th child seed stream, so the numbers do
not depend on how the work is split (docs/statistical_contact.md §2).
"""

from __future__ import annotations

import functools
import math
from collections.abc import Sequence
from dataclasses import dataclass, field, replace
from typing import Any, TypedDict, Unpack

import numba
import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import BowdenTabor, IntArray, asperity_sums
from stochfric.contact.materials import Material
from stochfric.errors import AnalysisError
from stochfric.process.parallel import map_indexed
from stochfric.progress import Progress
from stochfric.random import SeedLike, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, SUMMIT_RULES, find_summits
from stochfric.surface.surrogates import SURROGATES, SurrogateMethod, SurrogateSettings, similar_surface
from stochfric.surface.synthesis import AMPLITUDE_METHODS, DEFAULT_AMPLITUDE, PHASE_METHOD, AmplitudeEstimate
from stochfric.validation import count

__all__ = [
    "DEFAULT_SHIFT_FRACTION",
    "ContactSamples",
    "PathContact",
    "SurrogateKeywords",
    "SurrogateOptions",
    "default_window_shift_points",
    "ensemble_contact",
    "naive_window_contact",
    "path_contact",
    "summit_statistics",
    "tile_contact",
    "tile_grid",
    "window_contact",
    "window_starts",
]


#: The thesis's window shift relative to the window length: a_y = 0.3 mm of ℓ_Fl = 5.3 mm (§3.2.4).
DEFAULT_SHIFT_FRACTION = 0.3 / 5.3



@dataclass(frozen=True, kw_only=True)
class SurrogateOptions:
    """How the similar surfaces are made and their summits found (method §3, §4a–c).

    One home for the options shared by :func:`ensemble_contact`, :func:`path_contact` and the
    analysis settings (:class:`~stochfric.process.analysis_config.AnalysisConfig`).

    ``method``: a registered surrogate method (:data:`~stochfric.surface.surrogates.SURROGATES`:
    ``"phase"``, ``"iaaft"``, ``"quilt"``, …); ``amplitude``: the amplitude estimate of the measured
    map (:class:`~stochfric.surface.synthesis.AmplitudeEstimate`); ``iaaft_tol``: the IAAFT stopping
    tolerance; ``rule``: the summit rule (:data:`~stochfric.surface.summits.SUMMIT_RULES`).
    """

    method: str = PHASE_METHOD
    amplitude: str = DEFAULT_AMPLITUDE
    iaaft_tol: float = 1e-3
    rule: str = DEFAULT_SUMMIT_RULE

    def __post_init__(self) -> None:
        if self.method not in SURROGATES:
            raise AnalysisError(f"unknown surrogate method {self.method!r}; use one of {', '.join(SURROGATES)}")
        if self.amplitude not in AMPLITUDE_METHODS:
            raise AnalysisError(f"amplitude must be one of {AMPLITUDE_METHODS}, got {self.amplitude!r}")
        object.__setattr__(self, "amplitude", AmplitudeEstimate(self.amplitude))

    @property
    def surrogate(self) -> SurrogateMethod:
        """The registered method ``method``."""
        return SURROGATES[self.method]

    @property
    def settings(self) -> SurrogateSettings:
        """The settings the method reads (amplitude estimate, IAAFT tolerance)."""
        return SurrogateSettings(amplitude=self.amplitude, iaaft_tol=self.iaaft_tol)

    @classmethod
    def of(cls, options: SurrogateOptions | None = None, **keywords: Unpack[SurrogateKeywords]) -> SurrogateOptions:
        """``options`` (default: the defaults) with the given keyword options replaced."""
        base = options if options is not None else cls()
        return replace(base, **keywords) if keywords else base

    def similar(self, surface: Surface, rng: np.random.Generator, factor: int = 1) -> Surface:
        """One similar surface of ``factor`` × the length of ``surface`` with these options."""
        return similar_surface(surface, rng, method=self.method, factor=factor, tol=self.iaaft_tol,
                               amplitude=self.amplitude)


class SurrogateKeywords(TypedDict, total=False):
    """The fields of :class:`SurrogateOptions` as keyword arguments (the public functions take both)."""

    method: str
    amplitude: str
    iaaft_tol: float
    rule: str

@dataclass(frozen=True, kw_only=True, eq=False)
class ContactSamples(BowdenTabor):
    """GW/Hertz contact of many samples (realisations or windows) over the approach.

    Arrays have shape ``(..., U)``: leading axes index the samples, the last the approach.
    SI units; every sample has the nominal area ``nominal_area_m2``.  p, A_c/A_nom and μ
    (3.14–3.16) come from :class:`~stochfric.contact.asperity.BowdenTabor`.
    """

    info: dict[str, Any] = field(default_factory=dict)
    #: Per sample (leading axes): summit count, mean summit radius β̄ [m], summit-height
    #: standard deviation σ_S [m] — shape (..., 3); recorded by :func:`ensemble_contact`.
    summit_stats: FloatArray | None = None
    #: GW sums of each sample's disjoint tiles (samples, tiles², U), for the measured-window check.
    tile_samples: ContactSamples | None = None

    @classmethod
    def of(cls, surface: Surface, material: Material, approach_m: FloatArray, area_m2: FloatArray,
           force_n: FloatArray, n_contacts: IntArray, **extra: Any) -> ContactSamples:
        """Samples of ``surface``'s size in the pairing ``material`` (nominal area and τ_max from them)."""
        return cls(approach_m=approach_m, contact_area_m2=area_m2, normal_force_n=force_n, n_contacts=n_contacts,
                   nominal_area_m2=surface.nominal_area_m2, shear_strength_pa=material.shear_strength_pa, **extra)



def _margin(rule: str) -> int:
    """Points a summit of ``rule`` lies at least inside the grid border (AnalysisError for an unknown rule)."""
    if rule not in SUMMIT_RULES:
        raise AnalysisError(f"unknown summit rule {rule!r}; use one of {', '.join(SUMMIT_RULES)}")
    return SUMMIT_RULES[rule].margin


def _check_count(name: str, value: int, low: int = 1) -> int:
    return count(name, value, low, error=AnalysisError)


def _approach(approach_m: npt.ArrayLike) -> FloatArray:
    u = np.atleast_1d(np.asarray(approach_m, dtype=np.float64))
    if u.ndim != 1 or u.size == 0 or not np.all(np.isfinite(u)) or np.any(u <= 0.0):
        raise AnalysisError("approaches must be a non-empty 1-D sequence of finite values > 0 m")
    return u


def _one_surface(
    heights: FloatArray, spacing: tuple[float, float], material: Material, u: FloatArray, rule: str
) -> tuple[FloatArray, FloatArray, IntArray]:
    area, force, count, _stats = _one_surface_with_stats(heights, spacing, material, u, rule)
    return area, force, count


def summit_statistics(heights: FloatArray, radius: FloatArray) -> FloatArray:
    """(count, mean summit radius β̄ [m], summit-height standard deviation σ_S [m]) (method §1.5)."""
    n = heights.size
    return np.array([float(n), float(radius.mean()) if n else np.nan, float(heights.std()) if n > 1 else np.nan])


def tile_grid(shape: tuple[int, int], tiles: int) -> list[tuple[int, int, int, int]]:
    """Disjoint ``tiles × tiles`` windows of a grid: ``(i0, i1, j0, j1)`` each, row-major.

    Each side is split into ``tiles`` equal parts of ``⌊n/tiles⌋`` points (a remainder at the
    far edge is left out), so every tile has the same size and nominal area.
    """
    nx, ny = shape
    t = _check_count("tiles", tiles)
    wx, wy = nx // t, ny // t
    if min(wx, wy) < 5:
        raise AnalysisError(f"{t} × {t} tiles of a {nx}×{ny} grid leave {wx}×{wy} points; use fewer tiles")
    return [(a * wx, (a + 1) * wx, b * wy, (b + 1) * wy) for a in range(t) for b in range(t)]


def tile_contact(
    heights_m: FloatArray, spacing: tuple[float, float], material: Material, u: FloatArray, *, tiles: int,
    rule: str,
) -> tuple[FloatArray, FloatArray, IntArray]:
    """GW sums of the disjoint ``tiles × tiles`` windows of one map, each window referenced to its
    own highest summit (as if cut out and analysed on its own): ``(A_c, N, n_contacts)``, shape
    (tiles², U).

    The summits are found once on the whole map; a window analysed on its own finds exactly the
    summits at least the rule's margin inside it, with the same radii (as in :func:`window_contact`).
    A window without a summit gives zeros (μ undefined there).
    """
    m = _margin(rule)
    s = find_summits(heights_m, spacing, rule=rule)
    boxes = tile_grid(heights_m.shape, tiles)
    area = np.zeros((len(boxes), u.size))
    force = np.zeros((len(boxes), u.size))
    count = np.zeros((len(boxes), u.size), dtype=np.int64)
    for t, (i0, i1, j0, j1) in enumerate(boxes):
        inside = (s.i >= i0 + m) & (s.i < i1 - m) & (s.j >= j0 + m) & (s.j < j1 - m)
        if np.any(inside):
            area[t], force[t], count[t] = asperity_sums(
                s.heights_m[inside], s.radius_m[inside], u, e_star_pa=material.e_star_pa
            )
    return area, force, count


def _one_surface_with_stats(
    heights: FloatArray, spacing: tuple[float, float], material: Material, u: FloatArray, rule: str
) -> tuple[FloatArray, FloatArray, IntArray, FloatArray]:
    s = find_summits(heights, spacing, rule=rule)
    if s.count == 0:
        raise AnalysisError(f"a {heights.shape[0]}×{heights.shape[1]} sample has no summit (rule {rule!r})")
    area, force, count = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=material.e_star_pa)
    return area, force, count, summit_statistics(s.heights_m, s.radius_m)


def _scans(surface: Surface | Sequence[Surface]) -> list[Surface]:
    scans = [surface] if isinstance(surface, Surface) else list(surface)
    if not scans:
        raise AnalysisError("no surface given")
    shape = scans[0].nb_grid_pts
    spacing = scans[0].grid_spacing_m
    for s in scans[1:]:
        if s.nb_grid_pts != shape or not np.allclose(s.grid_spacing_m, spacing, rtol=1e-9, atol=0.0):
            raise AnalysisError(
                f"pooled scans must share the grid: {s.source} has {s.nb_grid_pts} points at "
                f"{s.grid_spacing_m} m, {scans[0].source} {shape} at {spacing} m"
            )
    return scans


def ensemble_contact(
    surface: Surface | Sequence[Surface],
    material: Material,
    approach_m: npt.ArrayLike,
    *,
    realizations: int,
    seed: SeedLike = None,
    progress: Progress | None = None,
    options: SurrogateOptions | None = None,
    tiles: int | None = None,
    workers: int | None = 1,
    extend: ContactSamples | None = None,
    **surrogate: Unpack[SurrogateKeywords],
) -> ContactSamples:
    """Contact of R similar surfaces of original size over ``approach_m`` (method §4a).

    Realisation r is :func:`~stochfric.surface.surrogates.similar_surface` of scan ``r mod S``
    (``surface`` may be one map or S scans of one surface on the same grid) with the r-th child
    stream of ``seed`` and the surrogate ``options`` (:class:`SurrogateOptions`; its fields
    ``method``, ``amplitude``, ``iaaft_tol``, ``rule`` may also be given as keywords); each is
    referenced to its own highest summit.  Shape (R, U); ``summit_stats`` (R, 3) holds every
    realisation's summit count, β̄ and σ_S for the measured-vs-surrogate check, ``info["scan"]``
    the scan of each realisation.  With ``tiles``, ``tile_samples`` holds the GW sums of every
    realisation's disjoint ``tiles × tiles`` windows (R, tiles², U) for the measured-window check.
    ``workers`` processes share the realisations (:func:`~stochfric.process.parallel.map_indexed`;
    the numbers do not depend on it; ``None``: all cores).  ``extend``: an ensemble this call made with fewer
    realisations (same surfaces, seed, options and tiles); its realisations are kept and only the new ones
    computed — realisation r depends on the seed and r only, so the result equals a fresh call.
    """
    scans = _scans(surface)
    r_count = _check_count("realizations", realizations)
    first = 0 if extend is None else int(extend.contact_area_m2.shape[0])
    if extend is not None and not 0 < first <= r_count:
        raise AnalysisError(f"an ensemble of {first} realisations cannot be extended to {r_count}")
    opts = SurrogateOptions.of(options, **surrogate)
    u = _approach(approach_m)
    area = np.empty((r_count, u.size))
    force = np.empty((r_count, u.size))
    count = np.empty((r_count, u.size), dtype=np.int64)
    stats = np.empty((r_count, 3))
    n_tiles = 0 if tiles is None else len(tile_grid(scans[0].nb_grid_pts, tiles))
    t_area = np.empty((r_count, n_tiles, u.size))
    t_force = np.empty((r_count, n_tiles, u.size))
    t_count = np.empty((r_count, n_tiles, u.size), dtype=np.int64)
    scan_of = [r % len(scans) for r in range(r_count)]
    seeds = spawn_seed_sequences(seed, r_count)

    def one(r: int) -> tuple[FloatArray, FloatArray, IntArray, FloatArray, tuple[FloatArray, FloatArray, IntArray]]:
        sim = opts.similar(scans[scan_of[r]], np.random.Generator(np.random.PCG64(seeds[r])))
        a, f, c, st = _one_surface_with_stats(sim.heights_m, sim.grid_spacing_m, material, u, opts.rule)
        t = (tile_contact(sim.heights_m, sim.grid_spacing_m, material, u, tiles=tiles, rule=opts.rule)
             if tiles is not None else (np.empty((0, u.size)), np.empty((0, u.size)), np.empty((0, u.size), np.int64)))
        return a, f, c, st, t

    if extend is not None:  # the realisations already made: realisation r depends on the seed and r only
        area[:first], force[:first], count[:first] = (extend.contact_area_m2, extend.normal_force_n,
                                                      extend.n_contacts)
        stats[:first] = extend.summit_stats if extend.summit_stats is not None else np.nan
        if tiles is not None and extend.tile_samples is not None:
            old = extend.tile_samples
            t_area[:first], t_force[:first], t_count[:first] = (old.contact_area_m2, old.normal_force_n,
                                                                old.n_contacts)
    done = None if progress is None else (lambda k: progress(first + k, r_count))
    rows = map_indexed(lambda k: one(first + k), r_count - first, workers=workers, done=done)
    for r, (a, f, c, st, t) in enumerate(rows, start=first):
        area[r], force[r], count[r], stats[r] = a, f, c, st
        if tiles is not None:
            t_area[r], t_force[r], t_count[r] = t
    info = {"kind": "ensemble", "surrogate": opts.method, "amplitude": opts.amplitude, "realizations": r_count,
            "summit_rule": opts.rule, "scans": len(scans), "scan": scan_of}
    tile_samples = None
    if tiles is not None:
        (i0, i1, j0, j1) = tile_grid(scans[0].nb_grid_pts, tiles)[0]
        dx, dy = scans[0].grid_spacing_m
        tile_samples = ContactSamples(
            approach_m=u, contact_area_m2=t_area, normal_force_n=t_force, n_contacts=t_count,
            nominal_area_m2=(i1 - i0) * dx * (j1 - j0) * dy, shear_strength_pa=material.shear_strength_pa,
            info={"kind": "tiles", "tiles": tiles},
        )  # fmt: skip
    return ContactSamples.of(
        scans[0], material, u, area, force, count, summit_stats=stats, tile_samples=tile_samples, info=info,
    )


def default_window_shift_points(window_points: int) -> int:
    """a_y in grid points: ⌊0.0566 · window length⌋ (the thesis's 0.3 mm of 5.3 mm), at least 1."""
    return max(1, math.floor(DEFAULT_SHIFT_FRACTION * window_points))


def window_starts(total_points: int, window_points: int, shift_points: int) -> IntArray:
    """First column of every window: 0, shift, 2·shift, … while the window fits."""
    total = _check_count("total_points", total_points)
    win = _check_count("window_points", window_points)
    shift = _check_count("shift_points", shift_points)
    if win > total:
        raise AnalysisError(f"the window ({win} points) is longer than the surface ({total} points)")
    return np.arange(0, total - win + 1, shift, dtype=np.int64)


@numba.njit(cache=True, nogil=True)
def _window_sums(
    heights: FloatArray,
    radius: FloatArray,
    lo: IntArray,
    hi: IntArray,
    u: FloatArray,
    area: FloatArray,
    force: FloatArray,
    count: IntArray,
) -> None:  # pragma: no cover - compiled
    """GW sums (3.11–3.13) of every window w over the summits ``lo[w]:hi[w]`` (column-sorted).

    Each window is referenced to its own highest summit; only summits above ``ref − max(u)``
    can touch, so the approach loop runs over those alone.  ``force`` is Σ √β d^{3/2}
    (the factor (4/3)E* is applied by the caller).  Memory: O(1) beyond the outputs.
    """
    n_u = u.size
    u_max = u.max()
    for w in range(lo.size):
        a = lo[w]
        b = hi[w]
        ref = -np.inf
        for i in range(a, b):
            if heights[i] > ref:
                ref = heights[i]
        for k in range(n_u):
            area[w, k] = 0.0
            force[w, k] = 0.0
            count[w, k] = 0
        floor = ref - u_max
        for i in range(a, b):
            zi = heights[i]
            if zi <= floor:
                continue
            bi = radius[i]
            sb = np.sqrt(bi)
            for k in range(n_u):
                d = zi - (ref - u[k])
                if d > 0.0:
                    area[w, k] += np.pi * bi * d
                    force[w, k] += sb * d * np.sqrt(d)
                    count[w, k] += 1


def window_contact(
    heights_m: npt.ArrayLike,
    grid_spacing_m: tuple[float, float],
    material: Material,
    approach_m: npt.ArrayLike,
    *,
    window_points: int,
    shift_points: int,
    rule: str = DEFAULT_SUMMIT_RULE,
    crop: bool = False,
) -> tuple[FloatArray, FloatArray, IntArray]:
    """GW contact of every window of a long surface (windows along y, axis 1), fast path.

    Windows cover columns ``[s, s + window_points)`` for ``s`` in :func:`window_starts`; each is
    referenced to its own highest summit.  Returns ``(A_c, N, n_contacts)`` of shape (W, U).
    The summits of the long surface are found once: a window analysed on its own finds exactly
    those whose column lies at least the rule's margin
    (:attr:`~stochfric.surface.summits.SummitRule.margin`) inside it, with the same radii, so every
    window is a contiguous slice of the column-sorted summits.
    ``crop=True`` is the reference (:func:`naive_window_contact`): crop each window and analyse it
    on its own; the fast path equals it to round-off.
    """
    z = np.asarray(heights_m, dtype=np.float64)
    u = _approach(approach_m)
    margin = _margin(rule)
    starts = window_starts(z.shape[1], window_points, shift_points)
    area = np.empty((starts.size, u.size))
    force = np.empty((starts.size, u.size))
    count = np.empty((starts.size, u.size), dtype=np.int64)
    if crop:
        for w, s in enumerate(starts):
            area[w], force[w], count[w] = _one_surface(
                np.ascontiguousarray(z[:, s : s + window_points]), grid_spacing_m, material, u, rule
            )
        return area, force, count
    summits = find_summits(z, grid_spacing_m, rule=rule)
    order = np.argsort(summits.j, kind="stable")
    col = summits.j[order]
    zs = summits.heights_m[order]
    beta = summits.radius_m[order]
    lo = np.searchsorted(col, starts + margin, side="left")
    hi = np.searchsorted(col, starts + window_points - margin, side="left")
    n_in = hi - lo
    if np.any(n_in == 0):
        bad = int(np.argmin(n_in))
        raise AnalysisError(f"window {bad} (columns {int(starts[bad])}…) has no summit; use larger windows")
    _window_sums(zs, beta, lo.astype(np.int64), hi.astype(np.int64), u, area, force, count)
    force *= (4.0 / 3.0) * material.e_star_pa
    return area, force, count


#: Reference for :func:`window_contact`: crop each window and analyse it on its own.
naive_window_contact = functools.partial(window_contact, crop=True)


@dataclass(frozen=True, kw_only=True, eq=False)
class PathContact:
    """μ along the path (method §4c): K long surfaces × W windows × U approaches.

    ``samples`` holds A_c, N, counts of the windows shifted by ``window_shift_m`` = a_y, shape
    (K, W, U).  ``blocks`` holds the **non-overlapping** windows of the same long surfaces
    (shift = window length), shape (K, J, U): the populations of the ergodicity check
    (:func:`stochfric.process.checks.ergodicity_check`).
    """

    samples: ContactSamples
    blocks: ContactSamples
    window_shift_m: float
    window_shift_points: int
    window_length_m: float
    surface_length_m: float

    @property
    def positions_m(self) -> FloatArray:
        """Window positions y_w = w a_y [m] (start of each window)."""
        return np.arange(self.samples.mu.shape[1], dtype=np.float64) * self.window_shift_m


def _long_windows(
    scans: list[Surface],
    material: Material,
    u: FloatArray,
    *,
    surfaces: int,
    factor: int,
    shifts: tuple[int, ...],
    opts: SurrogateOptions,
    seed: SeedLike,
    progress: Progress | None,
    workers: int | None,
) -> list[tuple[FloatArray, FloatArray, IntArray]]:
    """GW sums of the windows of K long surfaces, one (K, W_s, U) triple per window shift."""
    seeds = spawn_seed_sequences(seed, surfaces)
    ny = scans[0].nb_grid_pts[1]

    def one(k: int) -> list[tuple[FloatArray, FloatArray, IntArray]]:
        long = opts.similar(scans[k % len(scans)], np.random.Generator(np.random.PCG64(seeds[k])), factor)
        return [
            window_contact(long.heights_m, long.grid_spacing_m, material, u, window_points=ny, shift_points=shift,
                           rule=opts.rule)
            for shift in shifts
        ]

    done = None if progress is None else (lambda k: progress(k, surfaces))
    per_surface = map_indexed(one, surfaces, workers=workers, done=done)
    out = [[per_surface[k][s_idx] for k in range(surfaces)] for s_idx in range(len(shifts))]
    return [
        (np.stack([o[0] for o in per]), np.stack([o[1] for o in per]), np.stack([o[2] for o in per]))
        for per in out
    ]


def path_contact(
    surface: Surface | Sequence[Surface],
    material: Material,
    approach_m: npt.ArrayLike,
    *,
    long_surfaces: int = 10,
    length_factor: int = 10,
    shift_points: int,
    seed: SeedLike = None,
    progress: Progress | None = None,
    options: SurrogateOptions | None = None,
    workers: int | None = 1,
    **surrogate: Unpack[SurrogateKeywords],
) -> PathContact:
    """μ(y) over K long surfaces of ``length_factor`` × the original length (method §4c).

    Windows of the original size are shifted by ``shift_points`` grid points (a_y) along y;
    long surface k uses the k-th child stream of ``seed`` and the surrogate ``options``
    (:class:`SurrogateOptions`, or its fields as keywords), made from scan ``k mod S`` when
    ``surface`` is a list of S scans on one grid.  The same long surfaces are also cut into
    ``length_factor`` non-overlapping windows (``blocks``) for the ergodicity check.
    """
    scans = _scans(surface)
    surface = scans[0]
    k_count = _check_count("long_surfaces", long_surfaces)
    factor = _check_count("length_factor", length_factor, 2)
    shift = _check_count("shift_points", shift_points)
    opts = SurrogateOptions.of(options, **surrogate)
    u = _approach(approach_m)
    ny = surface.nb_grid_pts[1]
    (area, force, count), (b_area, b_force, b_count) = _long_windows(
        scans, material, u, surfaces=k_count, factor=factor, shifts=(shift, ny), opts=opts, seed=seed,
        progress=progress, workers=workers,
    )
    dy = surface.grid_spacing_m[1]
    info = {"surrogate": opts.method, "amplitude": opts.amplitude, "long_surfaces": k_count, "length_factor": factor}

    def samples(a: FloatArray, n: FloatArray, c: IntArray, kind: str) -> ContactSamples:
        return ContactSamples.of(surface, material, u, a, n, c, info={"kind": kind, **info})

    return PathContact(
        samples=samples(area, force, count, "path"),
        blocks=samples(b_area, b_force, b_count, "blocks"),
        window_shift_m=shift * dy,
        window_shift_points=shift,
        window_length_m=surface.physical_size_m[1],
        surface_length_m=factor * surface.physical_size_m[1],
    )

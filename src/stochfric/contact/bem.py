"""Boundary-element (BEM) contact at load control: elastic and elastic–perfectly-plastic.

A rigid rough surface of heights ``h(x, y)`` [m] is pressed onto a flat elastic half-space of
contact modulus E* [Pa] (E* = combined modulus, Johnson's 1/E* = (1−ν₁²)/E₁ + (1−ν₂²)/E₂) at
prescribed *nominal* pressures p [Pa]; the contact pressure field is found on the map's grid by
an FFT-accelerated Green's-function method (the surface is a collocation grid, one unknown
pressure per pixel) with the constrained conjugate-gradient algorithm of Polonsky & Keer
(Wear 231 (1999) 206).  Two independent maintained implementations are wrapped:

* ``"tamaas"`` — Tamaas (Frérot, Anciaux, Rey, Pham-Ba & Molinari, JOSS 5 (2020) 2121):
  ``PolonskyKeerRey`` for elastic contact, ``KatoSaturated`` (Kato's projection method,
  Stanley & Kato, J. Tribol. 119 (1997) 481) for the pressure cap; periodic only.  The
  installed wheel is built with the sequential ``cpp`` backend (``tm.TamaasInfo.backend``; no
  OpenMP, FFTW without threads): a solve runs on one core whatever ``OMP_NUM_THREADS`` says,
  and it holds the GIL, so a caller parallelises over surfaces with processes, not threads.
  Tamaas logs through Python's ``sys.stdout``/``sys.stderr``: each solve runs at log level
  "info" with both streams redirected into a buffer (under a module lock, the level restored
  afterwards), which silences it and gives the iteration count; nothing is printed.
* ``"contactmechanics"`` — ContactMechanics (Pastewka group, contactengineering.net):
  ``constrained_conjugate_gradients`` (Polonsky & Keer) on a ``PeriodicFFTElasticHalfSpace``
  or, with ``periodic=False``, a ``FreeFFTElasticHalfSpace`` (zero-padded 2n × 2n grid); the
  cap is its ``hardness`` argument (pixel force ≤ H × pixel area), the same call that
  ``PlasticNonSmoothContactSystem`` with a ``PlasticTopography`` makes, but without the
  plastic displacement that system accumulates from one load to the next.

Assumptions: frictionless normal contact, small slopes (half-space Green's function), linear
elasticity; with ``hardness_pa`` the contact pressure is capped at the hardness H (the
"pressure-cap" elastic–perfectly-plastic model of Stanley & Kato 1997 and Almqvist et al.,
Tribol. Int. 40 (2007) 574).  Every pressure is solved from the *unworn* surface: the
permanent flattening of earlier, lower loads is not carried over (no loading history), which
is what Tamaas' cap means and what makes the result depend on p only.  Both solvers use the
same collocation kernel (periodic: û = 2 p̂ / (E* |q|)) and agree to the pixel
(docs/bem_validation.md).

The pressures are solved in ascending order, each from the previous solution where that helps:
Tamaas keeps its pressure field; ContactMechanics gets the previous displacements when elastic
and starts cold with the cap (a warm start took more iterations there).  The results come back
in the order given.  See docs/bem_validation.md for the validation (Hertz, solver agreement,
plastic limit, the area slope κ) and the speed measurements.
"""

from __future__ import annotations

import contextlib
import dataclasses
import io
import math
import re
import threading
import time
import warnings
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.contact.asperity import ContactError
from stochfric.contact.halfspace import framed_and_refined

__all__ = [
    "BEM_SOLVERS",
    "COARSE_PATCH_PIXELS",
    "MIN_GRID_POINTS",
    "PERIMETER_CORRECTION",
    "UNDER_RESOLVED_PIXELS",
    "BemError",
    "BemSettings",
    "BemSolution",
    "bem_available",
    "bem_contact",
    "check_nominal_pressures",
    "contact_edges",
]

#: The wrapped solvers (see the module docstring).
BEM_SOLVERS = ("tamaas", "contactmechanics")
#: Fewest grid points a side the BEM accepts.
MIN_GRID_POINTS = 16
#: Fewer pixels in contact than this at some pressure → an "under-resolved" warning in the solution.
UNDER_RESOLVED_PIXELS = 10
#: Fewer contact pixels per patch than this on average at some pressure → a "coarse contacts" warning: the
#: pixel count and the perimeter-corrected area then differ by more than about 20 % (a 2 × 2 patch keeps
#: 1 − 8 × 0.118 / 4 = 76 % of its count, a single pixel 53 %), and κ was validated on larger contacts.
COARSE_PATCH_PIXELS = 4.0
#: Relative deviation of the carried force from p·A_nom above which the solution carries a warning.
FORCE_CHECK_RTOL = 1e-6
#: A pixel is at the cap (plastic) when its pressure is >= H × (1 − this).
PLASTIC_RTOL = 1e-9
#: Area removed per contact/non-contact pixel edge, in pixel areas: (π − 1 + ln 2)/24 (Yastrebov,
#: Anciaux & Molinari, Tribol. Int. 114 (2017) 161; the value Tamaas' ``Statistics2D.contact``
#: applies, checked in tests/unit/contact/test_bem.py).
PERIMETER_CORRECTION = (math.pi - 1.0 + math.log(2.0)) / 24.0

_FloatArray = npt.NDArray[np.float64]
_MODULES = {"tamaas": "tamaas", "contactmechanics": "ContactMechanics"}
_INSTALL = {"tamaas": "pip install tamaas", "contactmechanics": "pip install 'stochfric[halfspace]'"}


class BemError(ContactError):
    """A boundary-element contact that cannot be solved as asked (input, convergence, time limit)."""


def bem_available(solver: str) -> bool:
    """Whether the BEM ``solver`` (one of :data:`BEM_SOLVERS`) can be imported here."""
    if solver not in _MODULES:
        raise BemError(f"unknown BEM solver {solver!r}; choose one of {', '.join(BEM_SOLVERS)}")
    try:
        if solver == "tamaas":
            import tamaas  # noqa: F401
        else:
            import ContactMechanics  # noqa: F401
    except ImportError:
        return False
    return True


def _is_int(v: Any) -> bool:
    return isinstance(v, int | np.integer) and not isinstance(v, bool)


def _is_real(v: Any, *, inf: bool = False) -> bool:
    if isinstance(v, bool) or not isinstance(v, int | float | np.integer | np.floating):
        return False
    return not math.isnan(v) and (inf or math.isfinite(v))


@dataclass(frozen=True, kw_only=True)
class BemSettings:
    """Settings of :func:`bem_contact`.

    Attributes
    ----------
    solver:
        ``"tamaas"``, ``"contactmechanics"`` or ``"auto"`` (default), which the constructor
        replaces by the faster one measured (docs/bem_validation.md, AMD EPYC Zen 3): Tamaas
        for elastic periodic contact (1.3–9× faster than ContactMechanics at 200²–64²),
        ContactMechanics with a hardness (Tamaas' ``KatoSaturated`` needs 10³–10⁴ iterations:
        2.6× slower at 128², over 60 s a 12-pressure sweep at 200²) or with ``periodic=False``.
        An instance always holds one of :data:`BEM_SOLVERS`.
    periodic:
        Periodic half-space (the map repeats); Tamaas supports only ``True``.  ContactMechanics
        with ``False`` solves the free (non-periodic) half-space on a zero-padded 2n × 2n grid.
    frame_points:
        Width [points] of a border frame lowered to the map's minimum (out of reach), as
        :mod:`stochfric.contact.halfspace` does; 0: none.
    tolerance:
        Relative convergence tolerance.  Tamaas: its own error, the pressure-weighted mean gap
        Σ p·g / Σ p in units of the rms height of the map, < ``tolerance`` (checked with
        ``computeError()`` after the solve).  ContactMechanics: rms and max penetration
        < ``tolerance × Sq`` (Sq the rms height of the solved map), tensile pixel force
        < ``tolerance × p × pixel area`` and relative change of the force and the rigid-body
        position per iteration < ``tolerance``.  At 1e-6 instead of 1e-8 the contact areas of
        the benchmark maps did not change (elastic, both solvers) and the sweeps ran 15–30 %
        faster.
    max_iterations:
        Iteration limit of one solve (one pressure); reaching it raises :class:`BemError`.
    time_limit_s:
        Wall-clock limit [s] of one :func:`bem_contact` call (all pressures; ``math.inf``: none).
        Checked before every Tamaas solve (a Tamaas solve cannot be interrupted;
        ``max_iterations`` bounds it) and at every ContactMechanics iteration.
    hardness_pa:
        Hardness H [Pa]: ``None`` elastic; else the contact pressure is capped at H.
    """

    solver: str = "auto"
    periodic: bool = True
    frame_points: int = 0
    tolerance: float = 1e-8
    max_iterations: int = 5000
    time_limit_s: float = 120.0
    hardness_pa: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.periodic, bool):
            raise BemError(f"periodic must be True or False, got {self.periodic!r}")
        if self.solver == "auto":
            fast = "tamaas" if self.hardness_pa is None and self.periodic else "contactmechanics"
            object.__setattr__(self, "solver", fast)
        if self.solver not in BEM_SOLVERS:
            raise BemError(f"unknown BEM solver {self.solver!r}; choose one of {', '.join(BEM_SOLVERS)} or 'auto'")
        if self.solver == "tamaas" and not self.periodic:
            raise BemError("Tamaas solves only the periodic half-space: use periodic=True or solver='contactmechanics'")
        if not _is_int(self.frame_points) or self.frame_points < 0:
            raise BemError(f"frame_points must be an integer >= 0, got {self.frame_points!r}")
        if not _is_real(self.tolerance) or not 0.0 < self.tolerance < 1.0:
            raise BemError(f"tolerance must lie in (0, 1), got {self.tolerance!r}")
        if not _is_int(self.max_iterations) or self.max_iterations < 1:
            raise BemError(f"max_iterations must be an integer >= 1, got {self.max_iterations!r}")
        if not _is_real(self.time_limit_s, inf=True) or self.time_limit_s <= 0.0:
            raise BemError(f"time_limit_s must be > 0 s (math.inf for none), got {self.time_limit_s!r}")
        h = self.hardness_pa
        if h is not None and not (_is_real(h) and h > 0.0):
            raise BemError(f"hardness_pa must be None (elastic) or a finite value > 0 Pa, got {h!r}")

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (``time_limit_s`` = ``None`` when infinite)."""
        out = asdict(self)
        if not math.isfinite(self.time_limit_s):
            out["time_limit_s"] = None
        return out


@dataclass(frozen=True, kw_only=True, eq=False)
class BemSolution:
    """Result of :func:`bem_contact`, one value per prescribed pressure in the order given
    (``eq=False``: the arrays make field-wise equality ambiguous; compare fields instead).

    Attributes
    ----------
    pressure_pa:
        Nominal pressures p [Pa] as given.
    normal_force_n:
        Total force carried [N] (Σ pixel pressures × pixel area); equals p·A_nom within the
        tolerance (a larger deviation adds a warning).
    contact_area_m2:
        Real contact area A_c [m²]: pixels with positive pressure × pixel area.
    area_fraction:
        A_c / A_nom.
    corrected_area_m2:
        A_c with the perimeter correction of Yastrebov, Anciaux & Molinari (Tribol. Int. 114
        (2017) 161) [m²]: A_c − :data:`PERIMETER_CORRECTION` × (elastic contact edges) × pixel
        area.  Counting pixels overestimates the area of a contact whose pressure falls to zero
        like √(distance) at its edge (elastic) by a fraction of a pixel per edge; the correction
        is their geometric average over edge orientations.  Only edges of pixels below the cap
        count: a pixel at the hardness has no elastic edge, so the fully plastic limit
        A_c = N/H stays exact.  docs/bem_validation.md §4 measures κ with both areas.
    contact_edges:
        Elastic contact/non-contact pixel edges (4-neighbourhood; across the periodic wrap when
        periodic) per pressure; see ``corrected_area_m2``.
    plastic_area_m2:
        Pixels at the cap (pressure ≥ H(1 − :data:`PLASTIC_RTOL`)) × pixel area [m²]; 0 when elastic.
    n_patches:
        4-connected contact patches (the periodic wrap is ignored: a patch cut by the map's
        edge counts twice).
    approach_m:
        Rigid-body approach [m]: highest height of the solved map minus the position of the
        flat — the mean plane of the deformed elastic surface (periodic) or its undeformed
        far-field plane (free half-space); 0 at first touch.
    iterations:
        Solver iterations per pressure.
    seconds:
        Wall-clock time per pressure [s].
    nominal_area_m2:
        A_nom = Lx·Ly [m²].
    solver:
        The solver used.
    settings:
        :meth:`BemSettings.to_dict` plus the grid and the solver's detail.
    warnings:
        Human-readable warnings (under-resolution, force check).
    """

    pressure_pa: _FloatArray
    normal_force_n: _FloatArray
    contact_area_m2: _FloatArray
    area_fraction: _FloatArray
    plastic_area_m2: _FloatArray
    n_patches: npt.NDArray[np.int64]
    approach_m: _FloatArray
    iterations: npt.NDArray[np.int64]
    seconds: _FloatArray
    nominal_area_m2: float
    solver: str
    corrected_area_m2: _FloatArray
    contact_edges: npt.NDArray[np.int64]
    settings: dict[str, Any] = field(default_factory=dict)
    warnings: tuple[str, ...] = ()

    @property
    def corrected_area_fraction(self) -> _FloatArray:
        """corrected_area_m2 / A_nom."""
        return np.asarray(self.corrected_area_m2 / self.nominal_area_m2, dtype=np.float64)

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (SI units in the keys; NaN → ``None``)."""

        def floats(a: npt.NDArray[Any]) -> list[float | None]:
            return [float(v) if math.isfinite(v) else None for v in np.asarray(a, dtype=np.float64)]

        return {
            "solver": self.solver,
            "nominal_area_m2": float(self.nominal_area_m2),
            "pressure_pa": floats(self.pressure_pa),
            "normal_force_n": floats(self.normal_force_n),
            "contact_area_m2": floats(self.contact_area_m2),
            "area_fraction": floats(self.area_fraction),
            "plastic_area_m2": floats(self.plastic_area_m2),
            "corrected_area_m2": floats(self.corrected_area_m2),
            "contact_edges": [int(v) for v in self.contact_edges],
            "n_patches": [int(v) for v in self.n_patches],
            "approach_m": floats(self.approach_m),
            "iterations": [int(v) for v in self.iterations],
            "seconds": floats(self.seconds),
            "settings": dict(self.settings),
            "warnings": list(self.warnings),
        }


@dataclass(frozen=True)
class _Grid:
    """The solved map: heights [m] (mean removed, frame applied), physical size [m], pixel area [m²]."""

    heights: _FloatArray
    size: tuple[float, float]
    pixel_area: float

    @property
    def shape(self) -> tuple[int, int]:
        return (int(self.heights.shape[0]), int(self.heights.shape[1]))


@dataclass
class _Field:
    """One converged solve: pixel pressures [Pa], approach [m], iterations."""

    pressure: _FloatArray
    approach: float
    iterations: int
    #: A remark on how the solve was accepted (empty: by the solver's own convergence test).
    note: str = ""


class _Clock:
    """The time limit of one :func:`bem_contact` call."""

    def __init__(self, limit_s: float) -> None:
        self.start = time.perf_counter()
        self.limit = limit_s
        self.reached: float | None = None  # the last pressure solved [Pa]

    def over(self) -> bool:
        return time.perf_counter() - self.start > self.limit

    def error(self, p: float) -> BemError:
        done = "no pressure solved yet" if self.reached is None else f"solved up to p = {_mpa(self.reached)}"
        return BemError(
            f"BEM time limit of {self.limit:g} s exceeded at p = {_mpa(p)} ({done}): raise time_limit_s, "
            "use a coarser map or fewer pressures"
        )


class _NotConverged(BemError):
    """A solver stopped at its iteration limit without meeting its convergence test."""


class _SingleNode(BemError):
    """Tamaas could not compute its error: a contact of a single node (NaN in the complementarity error)."""


class _TimeUp(BemError):
    """Raised from the ContactMechanics callback when the time limit is reached (turned into the clock's
    :class:`BemError` naming the pressure reached)."""


def bem_contact(
    heights_m: npt.ArrayLike,
    physical_size_m: tuple[float, float],
    e_star_pa: float,
    pressures_pa: npt.ArrayLike,
    *,
    settings: BemSettings = BemSettings(),
) -> BemSolution:
    """Load-controlled BEM contact of a rigid rough surface on an elastic half-space.

    Parameters
    ----------
    heights_m:
        Heights [m] of the rigid rough surface, 2-D ``(nx, ny)``, at least
        :data:`MIN_GRID_POINTS` a side; grid spacing ``physical_size_m / (nx, ny)``.  Higher
        values touch first; the mean is irrelevant.
    physical_size_m:
        ``(Lx, Ly)`` [m].
    e_star_pa:
        Contact modulus E* [Pa] of the half-space (already the combined modulus).
    pressures_pa:
        Nominal pressures p = N / A_nom [Pa], each > 0 (and < H with a hardness).
    settings:
        :class:`BemSettings`.

    Returns
    -------
    BemSolution
        One entry per pressure, in the order given.

    Raises
    ------
    BemError
        Bad input, a missing solver, non-convergence within ``max_iterations``, or the time limit.
    """
    notes: list[str] = []
    try:
        grid, p, fields, seconds = _solve(heights_m, physical_size_m, e_star_pa, pressures_pa, settings)
    except (_SingleNode, _NotConverged) as exc:
        # the same discretisation by the other solver (they agree pixel for pixel, docs/bem_validation.md §2):
        # Tamaas cannot compute its error on a one-node contact; either solver may stall where the other
        # does not (ContactMechanics' capped solver on some maps, Tamaas' on large grids)
        other = "contactmechanics" if settings.solver == "tamaas" else "tamaas"
        if not bem_available(other) or (other == "tamaas" and not settings.periodic):
            raise
        try:
            grid, p, fields, seconds = _solve(heights_m, physical_size_m, e_star_pa, pressures_pa,
                                              dataclasses.replace(settings, solver=other))
        except BemError:
            raise exc from None
        settings = dataclasses.replace(settings, solver=other)
        why = "a contact of a single node" if isinstance(exc, _SingleNode) else "it did not converge"
        notes.append(f"{exc.args[0].split(':')[0]} ({why}); solved by {other} instead")
    nb = len(p)
    force, area, plastic = np.empty(nb), np.empty(nb), np.zeros(nb)
    approach = np.empty(nb)
    patches, iterations = np.empty(nb, dtype=np.int64), np.empty(nb, dtype=np.int64)
    edges = np.empty(nb, dtype=np.int64)
    for k in np.argsort(p, kind="stable"):
        sol = fields[k]
        if sol.note:
            notes.append(sol.note)
        in_contact = sol.pressure > 0.0
        n_contact = int(np.count_nonzero(in_contact))
        force[k] = float(sol.pressure.sum()) * grid.pixel_area
        area[k] = n_contact * grid.pixel_area
        at_cap = None
        if settings.hardness_pa is not None:
            at_cap = sol.pressure >= settings.hardness_pa * (1.0 - PLASTIC_RTOL)
            plastic[k] = float(np.count_nonzero(at_cap)) * grid.pixel_area
        edges[k] = contact_edges(in_contact, periodic=settings.periodic, exclude=at_cap)
        patches[k] = int(ndimage.label(in_contact)[1])
        approach[k] = sol.approach
        iterations[k] = sol.iterations
        if n_contact < UNDER_RESOLVED_PIXELS:
            notes.append(
                f"under-resolved: {n_contact} pixels in contact at p = {_mpa(float(p[k]))} "
                f"(fewer than {UNDER_RESOLVED_PIXELS}): refine the map or raise the pressure"
            )
        elif patches[k] > 0 and n_contact < COARSE_PATCH_PIXELS * patches[k]:
            notes.append(
                f"coarse contacts: fewer than {COARSE_PATCH_PIXELS:g} pixels per contact patch on average at "
                f"p = {_mpa(float(p[k]))}: the pixel count and the perimeter-corrected area differ by 20-50 % "
                "there; refine the map (a smaller coarsening step) for a resolved area"
            )
        target = float(p[k]) * grid.size[0] * grid.size[1]
        dev = abs(force[k] - target) / target
        if dev > max(FORCE_CHECK_RTOL, 10.0 * settings.tolerance):
            notes.append(f"force check: the carried force deviates by {dev:.2e} (relative) at p = {_mpa(float(p[k]))}")
    nominal = grid.size[0] * grid.size[1]
    detail = dict(settings.to_dict())
    detail["grid"] = list(grid.shape)
    detail["physical_size_m"] = list(grid.size)
    detail["e_star_pa"] = float(e_star_pa)
    detail["method"] = (
        "Tamaas PolonskyKeerRey" if settings.hardness_pa is None else "Tamaas KatoSaturated"
    ) if settings.solver == "tamaas" else (
        "ContactMechanics constrained CG (Polonsky-Keer)"
        + ("" if settings.hardness_pa is None else " with hardness")
        + (", periodic" if settings.periodic else ", free (zero-padded)")
    )  # fmt: skip
    return BemSolution(
        pressure_pa=p.copy(), normal_force_n=force, contact_area_m2=area, area_fraction=area / nominal,
        plastic_area_m2=plastic, n_patches=patches, approach_m=approach, iterations=iterations, seconds=seconds,
        nominal_area_m2=nominal, solver=settings.solver, settings=detail, warnings=tuple(notes),
        corrected_area_m2=area - PERIMETER_CORRECTION * edges * grid.pixel_area, contact_edges=edges,
    )  # fmt: skip


def contact_edges(
    in_contact: npt.NDArray[np.bool_], *, periodic: bool = True, exclude: npt.NDArray[np.bool_] | None = None
) -> int:
    """Edges between a contact and a non-contact pixel (4-neighbourhood) of a 2-D mask, across
    the wrap when ``periodic``; edges whose contact pixel is in ``exclude`` (e.g. at the hardness)
    do not count.  The perimeter, in pixel edges, of Yastrebov et al. (2017)'s area correction."""
    mask = np.asarray(in_contact, dtype=bool)
    if mask.ndim != 2:
        raise BemError(f"in_contact must be 2-D, got shape {mask.shape}")
    counted = mask if exclude is None else mask & ~np.asarray(exclude, dtype=bool)
    total = 0
    for axis in (0, 1):
        if periodic:
            for shift in (1, -1):
                total += int(np.count_nonzero(counted & ~np.roll(mask, shift, axis=axis)))
        else:
            lo = [slice(None)] * 2
            hi = [slice(None)] * 2
            lo[axis], hi[axis] = slice(None, -1), slice(1, None)
            a, b = mask[tuple(lo)], mask[tuple(hi)]
            ca, cb = counted[tuple(lo)], counted[tuple(hi)]
            total += int(np.count_nonzero(ca & ~b)) + int(np.count_nonzero(cb & ~a))
    return total


def _solve(
    heights_m: npt.ArrayLike,
    physical_size_m: tuple[float, float],
    e_star_pa: float,
    pressures_pa: npt.ArrayLike,
    settings: BemSettings,
) -> tuple[_Grid, _FloatArray, list[_Field], _FloatArray]:
    """Check the input and solve every pressure in ascending order: the solved grid, the
    pressures as given, the converged fields and the seconds per pressure (both in that order)."""
    if not isinstance(settings, BemSettings):
        raise BemError(f"settings must be a BemSettings, got {type(settings).__name__}")
    grid = _grid(heights_m, physical_size_m, settings.frame_points)
    e_star = _positive(e_star_pa, "e_star_pa", "Pa")
    p = check_nominal_pressures(pressures_pa, settings.hardness_pa)
    if not bem_available(settings.solver):
        raise BemError(f"the BEM solver {settings.solver!r} is not installed: {_INSTALL[settings.solver]}")
    clock = _Clock(settings.time_limit_s)
    runner: _Tamaas | _ContactMechanics
    runner = (_Tamaas if settings.solver == "tamaas" else _ContactMechanics)(grid, e_star, settings, clock)
    fields: list[_Field | None] = [None] * len(p)
    seconds = np.empty(len(p))
    for k in np.argsort(p, kind="stable"):
        if clock.over():
            raise clock.error(float(p[k]))
        t0 = time.perf_counter()
        fields[k] = runner.solve(float(p[k]))
        seconds[k] = time.perf_counter() - t0
        clock.reached = float(p[k])
    return grid, p, [f for f in fields if f is not None], seconds


# --------------------------------------------------------------------------------------- input


def _mpa(p: float) -> str:
    return f"{p / 1e6:.4g} MPa"


def _positive(v: Any, name: str, unit: str) -> float:
    try:
        x = float(v)
    except (TypeError, ValueError):
        raise BemError(f"{name} must be a number [{unit}], got {v!r}") from None
    if not (math.isfinite(x) and x > 0.0):
        raise BemError(f"{name} must be finite and > 0 {unit}, got {v!r}")
    return x


def _grid(heights_m: npt.ArrayLike, physical_size_m: tuple[float, float], frame: int) -> _Grid:
    h = np.array(heights_m, dtype=np.float64)
    if h.ndim != 2:
        raise BemError(f"heights_m must be a 2-D map, got {h.ndim} dimension(s)")
    nx, ny = h.shape
    if min(nx, ny) < MIN_GRID_POINTS:
        raise BemError(
            f"map too coarse for the BEM ({nx}×{ny} points; need >= {MIN_GRID_POINTS} a side): "
            "use a smaller coarsening step"
        )
    if not np.all(np.isfinite(h)):
        bad = int(np.count_nonzero(~np.isfinite(h)))
        raise BemError(f"heights_m has {bad} non-finite value(s) (NaN/inf): fill or crop undefined points first")
    try:
        lx, ly = (float(v) for v in physical_size_m)
    except (TypeError, ValueError):
        raise BemError(f"physical_size_m must be two lengths (Lx, Ly) [m], got {physical_size_m!r}") from None
    if not all(math.isfinite(v) and v > 0.0 for v in (lx, ly)):
        raise BemError(f"physical_size_m must be two finite lengths > 0 m, got {physical_size_m!r}")
    if 2 * frame >= min(nx, ny) - 1:
        raise BemError(f"frame_points = {frame} leaves no interior on a {nx}×{ny} map")
    h = framed_and_refined(h, frame, 1)
    h -= float(h.mean())
    if not float(np.abs(h).max()) > 0.0:
        raise BemError("the map is flat (all heights equal): the BEM contact of a flat is not defined")
    return _Grid(heights=np.ascontiguousarray(h), size=(lx, ly), pixel_area=lx * ly / (nx * ny))


def check_nominal_pressures(pressures_pa: npt.ArrayLike, hardness: float | None) -> _FloatArray:
    """The nominal pressures [Pa] as a 1-D array, checked: finite, > 0 and, with a hardness H, below H (a
    contact at p >= H would be fully plastic); :class:`BemError` with one line otherwise."""
    try:
        p = np.atleast_1d(np.asarray(pressures_pa, dtype=np.float64))
    except (TypeError, ValueError):
        raise BemError(f"pressures_pa must be numbers [Pa], got {pressures_pa!r}") from None
    if p.ndim != 1 or p.size == 0:
        raise BemError("pressures_pa must be a non-empty 1-D sequence of nominal pressures [Pa]")
    if not np.all(np.isfinite(p)) or np.any(p <= 0.0):
        raise BemError("nominal pressures must be finite and > 0 Pa")
    if hardness is not None:
        # the highest pressure decides; ``p >= H`` also covers a hardness below the lowest pressure
        top = float(p.max())
        if top >= hardness:
            raise BemError(
                f"p = {_mpa(top)} is at or above the hardness H = {_mpa(hardness)}: the contact would be "
                "fully plastic; lower the pressures or check the material's hardness"
            )
    return p


# -------------------------------------------------------------------------------------- Tamaas

_TAMAAS_ITER = re.compile(r"^\s*(\d+)\s+(\S+)\s+(\S+)\s*$")
#: Serialises the redirection of sys.stdout/sys.stderr around Tamaas solves (threads would
#: otherwise restore each other's buffers).
_TAMAAS_LOG_LOCK = threading.Lock()


class _Tamaas:
    """One Tamaas model for all pressures: every solve starts from the last pressure field.

    Tamaas works in reduced units here — lengths in units of Lx, pressures in units of E* (the
    contact problem is invariant under this scaling): its ``KatoSaturated`` stalls in SI units
    (measured: a 64² map with heights ~1 µm on 100 µm stayed at error 5·10⁻⁵ after 500
    iterations where the reduced problem converges to 10⁻⁸ in 160)."""

    def __init__(self, grid: _Grid, e_star: float, settings: BemSettings, clock: _Clock) -> None:
        import tamaas as tm  # type: ignore[import-untyped,unused-ignore]

        self.tm, self.grid, self.settings = tm, grid, settings
        self.length, self.e_star = grid.size[0], e_star
        nx, ny = grid.shape
        size = [1.0, grid.size[1] / self.length]
        self.model = tm.ModelFactory.createModel(tm.model_type.basic_2d, size, [nx, ny])
        self.model.E = 1.0  # with nu = 0, E_star = E / (1 − nu²) = E: the contact modulus (unit)
        self.model.nu = 0.0
        self.surface = np.ascontiguousarray(grid.heights / self.length)  # kept alive: the solver refers to it
        if settings.hardness_pa is None:
            self.solver = tm.PolonskyKeerRey(self.model, self.surface, settings.tolerance)
        else:
            self.solver = tm.KatoSaturated(self.model, self.surface, settings.tolerance, settings.hardness_pa / e_star)
        self.solver.max_iter = int(settings.max_iterations)
        # Tamaas logs the iterations through Python's sys.stderr at level "info": log only the first
        # and the last one and read the count from the captured last line
        self.solver.dump_freq = int(settings.max_iterations) + 10
        self.top = float(grid.heights.max())

    def solve(self, p: float) -> _Field:
        tm, tol = self.tm, self.settings.tolerance
        buf = io.StringIO()
        with _TAMAAS_LOG_LOCK:
            level = tm.get_log_level()
            try:
                tm.set_log_level(tm.LogLevel.info)
                with contextlib.redirect_stderr(buf), contextlib.redirect_stdout(buf):
                    self.solver.solve(p / self.e_star)
            except FloatingPointError as exc:  # Tamaas: NaN in the error, e.g. a contact of a single node
                raise _SingleNode(
                    f"Tamaas failed at p = {_mpa(p)} ({str(exc).split(': ')[-1].strip()}): the contact is "
                    "under-resolved; use a finer map (a smaller coarsening step) or higher pressures"
                ) from None
            finally:
                tm.set_log_level(level)
        # the convergence test is the solver's own: the error of its last iteration, read from the
        # log (KatoSaturated.solve returns 0 whatever the error; computeError() after the solve
        # can differ from it by ~10 %, measured at 256²); computeError() only without a log line
        iterations, error = _tamaas_log(buf.getvalue())
        if not math.isfinite(error):
            error = float(self.solver.computeError())
        if not error <= tol:
            raise _NotConverged(
                f"Tamaas did not converge at p = {_mpa(p)}: error {error:.3g} > tolerance {tol:.3g} after "
                f"{iterations} iterations (max_iterations = {self.settings.max_iterations}); raise max_iterations "
                "or the tolerance, or coarsen the map"
            )
        reduced = np.array(self.model.traction, dtype=np.float64).reshape(self.grid.shape)
        if self.settings.hardness_pa is None:
            # in contact the displacement equals the heights (gap 0): the flat's mean plane is mean(u)
            u = np.asarray(self.model.displacement, dtype=np.float64)
            position = float(u.mean()) * self.length
        else:
            # KatoSaturated's displacement includes the plastic flow (gap 0 on every contact pixel):
            # place the flat from the elastic response to the pressures instead
            position = self._elastic_position(reduced) * self.length
        return _Field(reduced * self.e_star, self.top - position, iterations)

    def _elastic_position(self, reduced: _FloatArray) -> float:
        """Mean plane c of the elastic surface (reduced units) under the pressures ``reduced``
        (units of E*) with the pressure cap: its displacement is c + u_el, u_el = 2 p̂ / (E* |q|)
        (the periodic Boussinesq kernel Tamaas uses, zero mean); on the elastic contact pixels
        (0 < p < H) the gap c + u_el − h is 0, so c is the median of h − u_el there.  Without
        elastic pixels c is the middle of the range the gap signs allow (≥ 0 out of contact,
        ≤ 0 on the plastic pixels)."""
        nx, ny = self.grid.shape
        qx = 2 * np.pi * np.fft.fftfreq(nx, d=1.0 / nx)
        qy = 2 * np.pi * np.fft.fftfreq(ny, d=(self.grid.size[1] / self.length) / ny)
        q = np.hypot(qx[:, None], qy[None, :])
        q[0, 0] = np.inf
        u_el = np.fft.ifft2(np.fft.fft2(reduced) * (2.0 / q)).real
        rest = self.surface - u_el
        cap = float(self.settings.hardness_pa or math.inf) / self.e_star * (1.0 - 1e-9)
        elastic = (reduced > 0.0) & (reduced < cap)
        if np.any(elastic):
            return float(np.median(rest[elastic]))
        free, plastic = reduced <= 0.0, reduced >= cap
        low = float(rest[free].max()) if np.any(free) else float(rest[plastic].min())
        high = float(rest[plastic].min()) if np.any(plastic) else low
        return 0.5 * (low + high)


def _tamaas_log(log: str) -> tuple[int, float]:
    """Iterations and final error of one Tamaas solve from its log.  Iterations: the last
    iteration number of every block (a block starts with the "Iter" header; ``KatoSaturated``
    runs two loops), summed; −1 if none.  Error: the last error logged; NaN if none."""
    total, last, found, error = 0, 0, False, math.nan
    for line in log.splitlines():
        if line.strip().startswith("Iter"):
            total, last = total + last, 0
            continue
        m = _TAMAAS_ITER.match(line)
        if m:
            last, found = int(m.group(1)), True
            try:
                error = float(m.group(3))
            except ValueError:
                error = math.nan
    return (total + last if found else -1), error


# --------------------------------------------------------------------------- ContactMechanics


def _feasible(result: Any, cv: dict[str, Any], kwargs: dict[str, Any], nb: tuple[int, int]) -> bool:
    """Whether a ContactMechanics result that reports no success still meets the contact conditions: penetration
    and tensile pixel force within their tolerances and the total force within 10⁻⁶ of the target."""
    pen, pres = cv.get("max_pen", math.inf), cv.get("max_pres", math.inf)
    target = float(kwargs["external_force"])
    carried = float(np.asarray(result.jac, dtype=np.float64)[: nb[0], : nb[1]].sum())
    return bool(pen <= kwargs["pentol"] and pres <= kwargs["forcetol"] and abs(carried - target) <= 1e-6 * target)


class _ContactMechanics:
    """One substrate for all pressures: every solve starts from the previous displacements."""

    def __init__(self, grid: _Grid, e_star: float, settings: BemSettings, clock: _Clock) -> None:
        from ContactMechanics import FreeFFTElasticHalfSpace, PeriodicFFTElasticHalfSpace
        from SurfaceTopography import Topography

        self.grid, self.settings, self.clock = grid, settings, clock
        nb = grid.shape
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            self.topography = Topography(grid.heights, grid.size, unit="m", periodic=settings.periodic)
            if settings.periodic:
                self.substrate: Any = PeriodicFFTElasticHalfSpace(nb, e_star, grid.size)
            else:
                self.substrate = FreeFFTElasticHalfSpace(nb, e_star, grid.size)
        self.sq = float(np.sqrt(np.mean(grid.heights**2)))
        self.top = float(grid.heights.max())
        self.previous: Any = None

    def solve(self, p: float) -> _Field:
        from ContactMechanics.Optimization import constrained_conjugate_gradients

        grid, settings, clock = self.grid, self.settings, self.clock
        tol, nb = settings.tolerance, grid.shape

        def stop(*_: Any) -> None:
            if clock.over():
                raise _TimeUp

        kwargs: dict[str, Any] = {
            "external_force": p * grid.size[0] * grid.size[1],
            "pentol": tol * self.sq,
            "forcetol": tol * p * grid.pixel_area,
            "thermotol": tol,
            "maxiter": int(settings.max_iterations),
            "callback": stop,
        }
        if settings.hardness_pa is not None:
            # the solver works with pixel forces: cap = H × pixel area; every pressure is solved
            # from the unworn surface (no plastic displacement carried over)
            kwargs["hardness"] = settings.hardness_pa * grid.pixel_area
        if self.previous is not None and settings.hardness_pa is None:
            # warm start (elastic only: with the cap, starting from the previous displacements took
            # more iterations than a cold start — 5318 vs 3889 at p = 0.95 H on a 64² map)
            kwargs["initial_displacements"] = self.previous
        try:
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                result = constrained_conjugate_gradients(self.substrate, self.topography, **kwargs)
        except _TimeUp:
            raise clock.error(p) from None
        cv = getattr(result, "maxcv", None) or {}
        note = ""
        if not result.success and _feasible(result, cv, kwargs, nb):
            # the contact conditions hold and the force is carried; only the relative change per iteration
            # (thermotol) stalled, as the capped solver's mixing fallback does near full plasticity
            note = (f"ContactMechanics at p = {_mpa(p)}: penetration and tensile force within tolerance and the "
                    f"force carried after {int(result.nit)} iterations; its relative-change test did not settle "
                    "(accepted)")
        elif not result.success:
            raise _NotConverged(
                f"ContactMechanics did not converge at p = {_mpa(p)} after {int(result.nit)} iterations (max "
                f"penetration {cv.get('max_pen', math.nan):.3g} m vs {tol * self.sq:.3g} m, tensile pixel force "
                f"{cv.get('max_pres', math.nan):.3g} N vs {tol * p * grid.pixel_area:.3g} N); raise max_iterations "
                "or the tolerance, or coarsen the map"
            )
        self.previous = result.x
        forces = np.asarray(result.jac, dtype=np.float64)[: nb[0], : nb[1]]
        u = np.asarray(result.x, dtype=np.float64)
        # rigid surface at h + offset, elastic surface at u (gap = u − h − offset); the flat's
        # position: the deformed mean plane (periodic) or the undeformed far field, 0 (free)
        flat = float(u[: nb[0], : nb[1]].mean()) if settings.periodic else 0.0
        return _Field(forces / grid.pixel_area, self.top + float(result.offset) - flat, int(result.nit), note)

"""Elastic half-space boundary-element reference for the GW contact (method §2 "Validation", thesis Fig. 3.12–3.14).

The prepared surface solved as a full elastic half-space contact (rigid rough surface against an
elastic flat of modulus E*, 3.10) by ContactMechanics' FFT Green's-function solver, the optional
dependency ``stochfric[halfspace]``, on the GW model's approach axis; compared with the GW sums at
equal load, with a border frame and optional spline refinement (docs/surface_contact.md, "Elastic
half-space reference").
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import ContactError, ContactResult, _as_approach, asperity_contact
from stochfric.contact.materials import Material
from stochfric.surface.io import Surface
from stochfric.surface.summits import Summits

__all__ = [
    "EqualLoadComparison",
    "compare_equal_load",
    "default_frame_points",
    "framed_and_refined",
    "halfspace_available",
    "halfspace_contact",
]


def halfspace_available() -> bool:
    """Whether ContactMechanics (``pip install 'stochfric[halfspace]'``) can be imported."""
    try:
        import ContactMechanics  # noqa: F401
    except ImportError:
        return False
    return True


def halfspace_contact(
    surface: Surface,
    material: Material,
    approach_m: npt.ArrayLike | None = None,
    *,
    normal_force_n: npt.ArrayLike | None = None,
    reference_m: float | None = None,
    summits: Summits | None = None,
    frame_points: int | None = None,
    refine: int = 1,
    preparation: dict[str, Any] | None = None,
    pentol_m: float | None = None,
    maxiter: int = 10_000,
) -> ContactResult:
    """Boundary-element contact of ``surface`` against a rigid flat at ``z_ref − u``.

    Give either ``approach_m`` (displacement control) or ``normal_force_n`` (load control:
    the total force is prescribed and the approach ``u`` is read from the solution).

    Parameters
    ----------
    surface:
        The prepared (coarse) surface; heights [m].
    material:
        Pairing; its E* (3.10) is the half-space's contact modulus, τ_max gives μ (3.16).
    approach_m:
        Approaches u [m] (> 0); solved in ascending order, each warm-started from the last.
    normal_force_n:
        Normal forces N [N] (> 0), instead of ``approach_m``.
    reference_m:
        ``z_ref`` [m]; default the highest summit of ``summits`` (as the GW model), or the
        highest grid point if no summits are given.
    frame_points:
        Width of the border frame lowered to the map's minimum, out of reach, so that both
        models see the same asperities (the summit rule cannot see those cut by the edge);
        default the summit rule's margin (0 without ``summits``).
    refine:
        Solve on a ``refine`` × finer grid (cubic-spline interpolation, same physical size).
    pentol_m:
        Penetration tolerance [m]; default ``1e-6 × Sq`` of the surface (scales with it).
    maxiter:
        Iteration limit per solve; non-convergence raises :class:`ContactError`.

    Returns
    -------
    ContactResult
        ``method = "halfspace"``; ``n_contacts`` counts 4-connected contact patches; the
        contact area is (pixels with positive pressure) × pixel area.
    """
    if not halfspace_available():
        raise ContactError("the half-space reference needs ContactMechanics: pip install 'stochfric[halfspace]'")
    target, load_control = _targets(approach_m, normal_force_n)
    if int(refine) != refine or refine < 1:
        raise ContactError(f"refine must be an integer >= 1, got {refine!r}")
    z_ref, ref_name = _reference(surface, summits, reference_m)
    frame = default_frame_points(summits) if frame_points is None else int(frame_points)
    if frame < 0 or 2 * frame >= min(surface.nb_grid_pts):
        raise ContactError(f"frame_points must be >= 0 and leave an interior, got {frame}")
    h0 = np.array(surface.heights_m, dtype=np.float64)
    tol = pentol_m if pentol_m is not None else max(float(h0.std()), 1e-300) * 1e-6
    h = framed_and_refined(h0, frame, int(refine))
    solver = _Solver(pentol_m=tol, maxiter=maxiter, reference_m=z_ref, load_control=load_control)
    approach, area, force, patches = _solve(h, surface, material, target, solver)
    prep = dict(preparation or {})
    prep.setdefault("reference", ref_name)
    prep["reference_m"] = z_ref
    prep["halfspace"] = {
        "solver": "ContactMechanics constrained CG (Polonsky-Keer)",
        "substrate": "free (non-periodic)",
        "pentol_m": tol,
        "control": "load" if load_control else "approach",
        "frame_points": frame,
        "refine": int(refine),
        "grid": [int(h.shape[0]), int(h.shape[1])],
    }
    return ContactResult.of("halfspace", surface, material, approach, area, force, patches, prep)


def _targets(approach_m: npt.ArrayLike | None, normal_force_n: npt.ArrayLike | None) -> tuple[FloatArray, bool]:
    """The prescribed approaches u [m] or normal forces N [N], and whether they are forces (load control)."""
    if (approach_m is None) == (normal_force_n is None):
        raise ContactError("give either approach_m or normal_force_n")
    if normal_force_n is not None:
        return _as_load(normal_force_n), True
    assert approach_m is not None
    return _as_approach(approach_m), False


def _reference(surface: Surface, summits: Summits | None, reference_m: float | None) -> tuple[float, str]:
    """``z_ref`` [m] and its name: given, the highest summit (as the GW model) or the highest point."""
    if reference_m is not None:
        return float(reference_m), "given"
    if summits is not None and summits.count:
        return float(summits.heights_m.max()), "highest summit"
    return float(surface.heights_m.max()), "highest point"


@dataclass(frozen=True, kw_only=True)
class _Solver:
    """Settings of the solves: penetration tolerance [m], iteration limit, ``z_ref`` [m] and whether
    the targets are forces (load control) or approaches."""

    pentol_m: float
    maxiter: int
    reference_m: float
    load_control: bool


def _solve(
    h: FloatArray, surface: Surface, material: Material, target: FloatArray, solver: _Solver
) -> tuple[FloatArray, FloatArray, FloatArray, npt.NDArray[np.int64]]:
    """Solve the half-space contact of the heights ``h`` (on ``surface``'s physical size) at every
    target, in ascending order, each warm-started from the last; approach u [m], contact area
    [m²], normal force [N] and the number of 4-connected contact patches per target."""
    from ContactMechanics import FreeFFTElasticHalfSpace
    from ContactMechanics.Systems import NonSmoothContactSystem
    from SurfaceTopography import Topography

    nb = (int(h.shape[0]), int(h.shape[1]))
    pixel_area = surface.nominal_area_m2 / (nb[0] * nb[1])
    z_ref, load_control = solver.reference_m, solver.load_control
    approach, area, force = np.empty_like(target), np.empty_like(target), np.empty_like(target)
    patches = np.empty(target.shape, dtype=np.int64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        topo = Topography(h, surface.physical_size_m, unit="m", periodic=False)
        substrate = FreeFFTElasticHalfSpace(nb, material.e_star_pa, surface.physical_size_m)
        system = NonSmoothContactSystem(substrate=substrate, surface=topo)
        previous: Any = None
        for idx in np.argsort(target, kind="stable"):
            # rigid rough surface at heights + offset, elastic flat at 0: contact where
            # h + offset > 0, i.e. h > z_ref − u  =>  offset = u − z_ref
            kwargs: dict[str, Any] = {"pentol": solver.pentol_m, "maxiter": solver.maxiter}
            if load_control:
                kwargs["external_force"] = float(target[idx])
            else:
                kwargs["offset"] = float(target[idx] - z_ref)
            if previous is not None:
                kwargs["initial_displacements"] = previous
            result = system.minimize_proxy(**kwargs)
            if not result.success:
                what = f"N = {target[idx]:.4g} N" if load_control else f"u = {target[idx]:.4g} m"
                raise ContactError(
                    f"half-space solver did not converge at {what} ({result.message}); raise maxiter "
                    "or coarsen the surface"
                )
            previous = result.x
            f = np.asarray(result.jac)[: nb[0], : nb[1]]
            in_contact = f > 0.0
            force[idx] = float(f.sum())
            offset = float(getattr(result, "offset", target[idx] - z_ref))
            approach[idx] = float(target[idx]) if not load_control else offset + z_ref
            area[idx] = float(np.count_nonzero(in_contact)) * pixel_area
            patches[idx] = int(ndimage.label(in_contact)[1])
    return approach, area, force, patches


def default_frame_points(summits: Summits | None) -> int:
    """Border frame of the summit rule: 2 (thesis rule), 1 (8-neighbour), 0 without summits."""
    if summits is None:
        return 0
    return 1 if summits.rule == "8-neighbour" else 2


def _as_load(normal_force_n: npt.ArrayLike) -> npt.NDArray[np.float64]:
    n = np.atleast_1d(np.asarray(normal_force_n, dtype=np.float64))
    if n.ndim != 1 or n.size == 0 or not np.all(np.isfinite(n)) or np.any(n <= 0.0):
        raise ContactError("normal forces must be a non-empty 1-D sequence of finite values > 0 N")
    return n


def framed_and_refined(h: npt.NDArray[np.float64], frame: int, refine: int) -> npt.NDArray[np.float64]:
    """Lower a border frame of ``frame`` points to the minimum; spline-refine by ``refine``."""
    out = h.copy()
    if frame > 0:
        low = float(out.min())
        out[:frame, :] = low
        out[-frame:, :] = low
        out[:, :frame] = low
        out[:, -frame:] = low
    if refine > 1:
        nx, ny = out.shape
        # cell-centred mapping: fine point k sits at coarse coordinate (k + 1/2)/refine − 1/2
        xi = (np.arange(nx * refine) + 0.5) / refine - 0.5
        yi = (np.arange(ny * refine) + 0.5) / refine - 0.5
        gx, gy = np.meshgrid(xi, yi, indexing="ij")
        out = ndimage.map_coordinates(out, [gx, gy], order=3, mode="nearest")
    return out


@dataclass(frozen=True, kw_only=True, eq=False)
class EqualLoadComparison:
    """GW and boundary-element contact at the same normal forces (μ = A_c τ_max / N, 3.16).

    ``asperity`` is the GW result; ``halfspace`` maps each refinement factor to the BEM result
    at the GW forces.  Ratios are BEM / GW; at equal N the μ ratio equals the area ratio.
    """

    asperity: ContactResult
    halfspace: dict[int, ContactResult]

    def area_ratio(self, refine: int) -> npt.NDArray[np.float64]:
        """A_c(BEM) / A_c(GW) at equal load, one value per load."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return self.halfspace[refine].contact_area_m2 / self.asperity.contact_area_m2

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (SI units)."""
        gw = self.asperity
        out: dict[str, Any] = {
            "comparison": "equal load",
            "normal_force_n": _listify(gw.normal_force_n),
            "pressure_pa": _listify(gw.pressure_pa),
            "approach_gw_m": _listify(gw.approach_m),
            "area_fraction_gw": _listify(gw.area_fraction),
            "n_contacts_gw": [int(v) for v in gw.n_contacts],
            "mu_gw": _listify(gw.mu),
            "halfspace": {},
        }
        for k, res in sorted(self.halfspace.items()):
            out["halfspace"][str(k)] = {
                "refine": k,
                "grid": res.preparation.get("halfspace", {}).get("grid"),
                "frame_points": res.preparation.get("halfspace", {}).get("frame_points"),
                "approach_m": _listify(res.approach_m),
                "area_fraction": _listify(res.area_fraction),
                "n_patches": [int(v) for v in res.n_contacts],
                "mu": _listify(res.mu),
                "area_ratio_halfspace_to_asperity": _listify(self.area_ratio(k)),
            }
        return out


def _listify(a: npt.NDArray[np.float64]) -> list[float | None]:
    return [float(v) if np.isfinite(v) else None for v in np.asarray(a, dtype=np.float64)]


def compare_equal_load(
    surface: Surface,
    summits: Summits,
    material: Material,
    approach_m: npt.ArrayLike | None = None,
    *,
    refine: Sequence[int] = (1,),
    frame_points: int | None = None,
    preparation: dict[str, Any] | None = None,
    maxiter: int = 10_000,
) -> EqualLoadComparison:
    """GW/Hertz contact over ``approach_m`` and the half-space at the same normal forces.

    ``approach_m`` defaults to :func:`stochfric.contact.asperity.default_approach_m`; the
    half-space is solved once per refinement factor in ``refine`` (grid convergence), with
    the border frame of :func:`halfspace_contact`.  Approaches where GW carries no load are
    refused (the half-space needs a force > 0).
    """
    gw = asperity_contact(surface, summits, material, approach_m, preparation=preparation)
    if np.any(gw.normal_force_n <= 0.0):
        raise ContactError("the GW force is 0 at some approach; give approaches > 0")
    bem = {
        int(k): halfspace_contact(
            surface, material, normal_force_n=gw.normal_force_n, summits=summits,
            frame_points=frame_points, refine=int(k), preparation=dict(gw.preparation), maxiter=maxiter,
        )
        for k in refine
    }  # fmt: skip
    return EqualLoadComparison(asperity=gw, halfspace=bem)

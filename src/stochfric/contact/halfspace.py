"""Elastic half-space boundary-element reference (method §2 "Validation", thesis Fig. 3.12–3.14).

The thesis validated its GW/Hertz sums with an ABAQUS FEM model of the coarse surface; here
the same prepared surface is solved as a full elastic half-space contact with the
boundary-element (FFT Green's function) solver of ContactMechanics (Polonsky–Keer
constrained conjugate gradients, non-periodic ``FreeFFTElasticHalfSpace``), the optional
dependency ``stochfric[halfspace]``.

Set-up, matched to :func:`stochfric.contact.asperity.asperity_contact`:

* **equal load or equal approach.**  μ = A_c τ_max / N (3.16) compares the two models only at
  the same normal force N, so :func:`compare_equal_load` (and ``contact --method halfspace``)
  prescribes the GW force as the half-space's total force (``external_force`` of the
  Polonsky–Keer solver) and reads the approach from the solution.  At equal *approach* the
  half-space's settlement is mixed into the comparison (on the shipped surface the flat must
  move 1.1–1.6 × further than the GW u for the same load over the default range, 3.7 × at
  A_c/A_nom = 0.45).  ``halfspace_contact`` offers both;
* the flat is at ``z_ref − u`` with the same reference ``z_ref`` (the highest summit), so both
  methods share the approach axis;
* **border frame.**  The summit rule cannot see asperities cut by the edge of the map (the
  thesis rule needs two neighbours on each side), but the half-space can: on the default surface
  16 border points lie above the highest summit and touch first.  ``frame_points`` (default:
  the summit rule's margin, 2 for the thesis rule, 1 for 8-neighbour, 0 without summits)
  lowers the outermost rows and columns to the map's minimum, so that both models see the same
  asperities;
* **refinement.**  ``refine = k`` interpolates the heights by cubic splines onto a k × finer
  grid of the same size before solving (a grid-convergence check: a Hertz spot a few pixels
  wide is over-counted on the measurement grid);
* the elastic rough surface against a rigid flat is solved in the equivalent form of a rigid
  rough surface against an elastic flat with modulus E* (3.10) (small slopes, linear
  elasticity; the two are the same problem for the gap);
* the heights are the grid values, each grid point a pixel of area ``Δx Δy``; the contact area
  is (number of pixels with positive pressure) × ``Δx Δy`` and the number of contacts the
  number of 4-connected contact patches;
* every asperity interacts with every other through the half-space (the GW model ignores
  this), and the contact is not restricted to summits.

The function is slow compared with the GW sums (one iterative solve per approach) and meant
as a check on modest grids (the thesis's 170 × 170 coarse grid takes seconds).
"""

from __future__ import annotations

import warnings
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.contact.asperity import ContactError, ContactResult, _as_approach, asperity_contact
from stochfric.contact.materials import Material
from stochfric.surface.io import Surface
from stochfric.surface.summits import Summits

__all__ = [
    "EqualLoadComparison",
    "compare_equal_load",
    "default_frame_points",
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
        Width of the border frame lowered out of reach (module doc); default the summit
        rule's margin (0 without ``summits``).
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
    try:
        from ContactMechanics import FreeFFTElasticHalfSpace
        from ContactMechanics.Systems import NonSmoothContactSystem
        from SurfaceTopography import Topography
    except ImportError:
        raise ContactError(
            "the half-space reference needs ContactMechanics: pip install 'stochfric[halfspace]'"
        ) from None
    if (approach_m is None) == (normal_force_n is None):
        raise ContactError("give either approach_m or normal_force_n")
    load_control = normal_force_n is not None
    if normal_force_n is not None:
        target = _as_load(normal_force_n)
    else:
        assert approach_m is not None
        target = _as_approach(approach_m)
    if int(refine) != refine or refine < 1:
        raise ContactError(f"refine must be an integer >= 1, got {refine!r}")
    if reference_m is not None:
        z_ref = float(reference_m)
        ref_name = "given"
    elif summits is not None and summits.count:
        z_ref = float(summits.heights_m.max())
        ref_name = "highest summit"
    else:
        z_ref = float(surface.heights_m.max())
        ref_name = "highest point"
    frame = default_frame_points(summits) if frame_points is None else int(frame_points)
    if frame < 0 or 2 * frame >= min(surface.nb_grid_pts):
        raise ContactError(f"frame_points must be >= 0 and leave an interior, got {frame}")
    h0 = np.array(surface.heights_m, dtype=np.float64)
    sq = float(h0.std())
    tol = pentol_m if pentol_m is not None else max(sq, 1e-300) * 1e-6
    h = _framed_and_refined(h0, frame, int(refine))
    nb = (int(h.shape[0]), int(h.shape[1]))
    pixel_area = surface.nominal_area_m2 / (nb[0] * nb[1])

    order = np.argsort(target, kind="stable")
    approach = np.empty_like(target)
    area = np.empty_like(target)
    force = np.empty_like(target)
    patches = np.empty(target.shape, dtype=np.int64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        topo = Topography(h, surface.physical_size_m, unit="m", periodic=False)
        substrate = FreeFFTElasticHalfSpace(nb, material.e_star_pa, surface.physical_size_m)
        system = NonSmoothContactSystem(substrate=substrate, surface=topo)
        previous: Any = None
        for idx in order:
            # rigid rough surface at heights + offset, elastic flat at 0: contact where
            # h + offset > 0, i.e. h > z_ref − u  =>  offset = u − z_ref
            kwargs: dict[str, Any] = {"pentol": tol, "maxiter": maxiter}
            if load_control:
                kwargs["external_force"] = float(target[idx])
            else:
                kwargs["offset"] = float(target[idx] - z_ref)
            if previous is not None:
                kwargs["initial_displacements"] = previous
            result = system.minimize_proxy(**kwargs)
            what = f"N = {target[idx]:.4g} N" if load_control else f"u = {target[idx]:.4g} m"
            if not result.success:
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
        "grid": list(nb),
    }
    return ContactResult.of("halfspace", surface, material, approach, area, force, patches, prep)


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


def _framed_and_refined(h: npt.NDArray[np.float64], frame: int, refine: int) -> npt.NDArray[np.float64]:
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

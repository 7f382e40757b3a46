"""Elastic half-space boundary-element reference (METHOD.md §2 "Validation", thesis Fig. 3.12–3.14).

The thesis validated its GW/Hertz sums with an ABAQUS FEM model of the coarse surface; here
the same prepared surface is solved as a full elastic half-space contact with the
boundary-element (FFT Green's function) solver of ContactMechanics (Polonsky–Keer
constrained conjugate gradients, non-periodic ``FreeFFTElasticHalfSpace``), the optional
dependency ``stochfric[halfspace]``.

Set-up, matched to :func:`stochfric.contact.asperity.asperity_contact`:

* the flat is at ``z_ref − u`` with the same reference ``z_ref`` (the highest summit), so both
  methods share the approach axis; grid points higher than the highest summit (possible near
  the border, where the summit rule has no candidates) touch already at small u;
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
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.contact.asperity import ContactError, ContactResult, _as_approach
from stochfric.contact.materials import Material
from stochfric.surface.io import Surface
from stochfric.surface.summits import Summits

__all__ = ["halfspace_available", "halfspace_contact"]


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
    approach_m: npt.ArrayLike,
    *,
    reference_m: float | None = None,
    summits: Summits | None = None,
    preparation: dict[str, Any] | None = None,
    pentol_m: float | None = None,
    maxiter: int = 10_000,
) -> ContactResult:
    """Boundary-element contact of ``surface`` against a rigid flat at ``z_ref − u``.

    Parameters
    ----------
    surface:
        The prepared (coarse) surface; heights [m].
    material:
        Pairing; its E* (3.10) is the half-space's contact modulus, τ_max gives μ (3.16).
    approach_m:
        Approaches u [m] (> 0); solved in ascending order, each warm-started from the last.
    reference_m:
        ``z_ref`` [m]; default the highest summit of ``summits`` (as the GW model), or the
        highest grid point if no summits are given.
    pentol_m:
        Penetration tolerance [m]; default ``1e-6 × Sq`` of the surface (scales with it).
    maxiter:
        Iteration limit per approach; non-convergence raises :class:`ContactError`.

    Returns
    -------
    ContactResult
        ``method = "halfspace"``; ``n_contacts`` counts contact patches.
    """
    try:
        from ContactMechanics import FreeFFTElasticHalfSpace
        from ContactMechanics.Systems import NonSmoothContactSystem
        from SurfaceTopography import Topography
    except ImportError:
        raise ContactError(
            "the half-space reference needs ContactMechanics: pip install 'stochfric[halfspace]'"
        ) from None
    u = _as_approach(approach_m)
    if reference_m is not None:
        z_ref = float(reference_m)
        ref_name = "given"
    elif summits is not None and summits.count:
        z_ref = float(summits.heights_m.max())
        ref_name = "highest summit"
    else:
        z_ref = float(surface.heights_m.max())
        ref_name = "highest point"
    h = np.array(surface.heights_m, dtype=np.float64)
    sq = float(h.std())
    tol = pentol_m if pentol_m is not None else max(sq, 1e-300) * 1e-6
    dx, dy = surface.grid_spacing_m
    pixel_area = dx * dy

    order = np.argsort(u, kind="stable")
    area = np.empty_like(u)
    force = np.empty_like(u)
    patches = np.empty(u.shape, dtype=np.int64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        topo = Topography(h, surface.physical_size_m, unit="m", periodic=False)
        substrate = FreeFFTElasticHalfSpace(surface.nb_grid_pts, material.e_star_pa, surface.physical_size_m)
        system = NonSmoothContactSystem(substrate=substrate, surface=topo)
        previous: Any = None
        for idx in order:
            # rigid rough surface at heights + offset, elastic flat at 0: contact where
            # h + offset > 0, i.e. h > z_ref − u  =>  offset = u − z_ref
            kwargs: dict[str, Any] = {"offset": float(u[idx] - z_ref), "pentol": tol}
            if previous is not None:
                kwargs["initial_displacements"] = previous
            result = system.minimize_proxy(maxiter=maxiter, **kwargs)
            if not result.success:
                raise ContactError(
                    f"half-space solver did not converge at u = {u[idx]:.4g} m "
                    f"({result.message}); raise maxiter or coarsen the surface"
                )
            previous = result.x
            f = np.asarray(result.jac)[: h.shape[0], : h.shape[1]]
            in_contact = f > 0.0
            force[idx] = float(f.sum())
            area[idx] = float(np.count_nonzero(in_contact)) * pixel_area
            patches[idx] = int(ndimage.label(in_contact)[1])
    prep = dict(preparation or {})
    prep.setdefault("reference", ref_name)
    prep["reference_m"] = z_ref
    prep["halfspace"] = {"solver": "ContactMechanics constrained CG (Polonsky-Keer)",
                         "substrate": "free (non-periodic)", "pentol_m": tol}  # fmt: skip
    return ContactResult(
        method="halfspace",
        approach_m=u,
        contact_area_m2=area,
        normal_force_n=force,
        n_contacts=patches,
        nominal_area_m2=surface.nominal_area_m2,
        shear_strength_pa=material.shear_strength_pa,
        e_star_pa=material.e_star_pa,
        material=material.to_dict(),
        preparation=prep,
    )

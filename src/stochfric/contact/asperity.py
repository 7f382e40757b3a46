"""Greenwood–Williamson / Hertz contact with Bowden–Tabor friction (method §2, thesis 3.1.3, eq. 3.8–3.16).

The summits of an elastic rough surface, Hertzian spheres of radius β_i that do not interact, are
pressed by a smooth rigid flat at the approach u > 0 measured from the highest summit: contact area
(3.12), normal force (3.13), pressure (3.14) and μ = A_c τ_max / N (3.16) over u, vectorised over
the approaches (docs/surface_contact.md, "Contact analysis").
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from enum import StrEnum
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.contact.materials import Material
from stochfric.contact.validity import MIN_CONTACTS, NON_INTERACTION_AREA_FRACTION
from stochfric.errors import InputError
from stochfric.io_utils import ResultFileError, read_netcdf, write_netcdf_atomic
from stochfric.surface.io import Surface
from stochfric.surface.summits import Summits

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = [
    "APPROACH_RULES",
    "ApproachRule",
    "BowdenTabor",
    "ContactError",
    "ContactResult",
    "asperity_contact",
    "asperity_sums",
    "bowden_tabor_mu",
    "default_approach_m",
    "read_contact_result",
]

IntArray = npt.NDArray[np.int64]

#: Approach range of the ``"sigma"`` rule in units of σ_S: ``linspace(σ_S/4, 3σ_S, 12)`` (ratio 1:12 as
#: the thesis's brake range 1…12 µm), stretched when the highest summit stands far above the rest
#: (see :func:`default_approach_m`; the default rule is ``"contacts"``).
DEFAULT_APPROACH_SIGMA = (0.25, 3.0)
DEFAULT_APPROACH_NUM = 12
#: Relative margin by which the ``"contacts"`` range ends inside its area limit (rounding only).
AREA_TARGET_MARGIN = 1e-9

#: Block size (elements of the u × summits broadcast) that bounds the memory of the force sum.
_BLOCK_ELEMENTS = 1 << 22

_VARIABLES: dict[str, tuple[str, str]] = {
    "contact_area_m2": ("m2", "real contact area A_c (3.12)"),
    "normal_force_n": ("N", "normal force N (3.13)"),
    "pressure_pa": ("Pa", "nominal pressure p = N / A_nom (3.14)"),
    "n_contacts": ("1", "number of contacts (summits with d > 0, or grid points in contact)"),
    "area_fraction": ("1", "A_c / A_nom"),
    "friction_force_n": ("N", "Bowden-Tabor friction force R = A_c tau_max (3.15)"),
    "mu": ("1", "friction coefficient mu = A_c tau_max / N (3.16)"),
}


class ContactError(InputError):
    """Invalid contact-analysis input (no summit, bad approach range, missing solver)."""


def _as_approach(approach_m: npt.ArrayLike) -> FloatArray:
    u = np.atleast_1d(np.asarray(approach_m, dtype=np.float64))
    if u.ndim != 1 or u.size == 0:
        raise ContactError("approach_m must be a non-empty 1-D sequence of approaches [m]")
    if not np.all(np.isfinite(u)) or np.any(u <= 0.0):
        raise ContactError(
            "approaches must be finite and > 0 m (u is measured from the highest summit; at "
            "u = 0 nothing carries load and mu is undefined)"
        )
    return u


class ApproachRule(StrEnum):
    """How :func:`default_approach_m` chooses the default approach range: ``contacts`` (from 20
    touching summits to A_c/A_nom = max_area_fraction or half the summits touching) or ``sigma``
    (σ_S/4 … 3σ_S, stretched to the highest summit; the thesis's proportion)."""

    CONTACTS = "contacts"
    SIGMA = "sigma"


APPROACH_RULES: tuple[str, ...] = tuple(ApproachRule)


def default_approach_m(
    summits: Summits,
    num: int = DEFAULT_APPROACH_NUM,
    *,
    rule: str = ApproachRule.CONTACTS,
    max_area_fraction: float = NON_INTERACTION_AREA_FRACTION,
) -> FloatArray:
    """Default approaches [m] from the surface's own summits, ``num`` points, by ``rule``.

    ``"contacts"`` (default): the range of contact *states* the GW model is valid for, read from
    the measured summits with the flat referenced to the highest summit (3.11):

    * ``u_lo`` — the approach at which ``2 × MIN_CONTACTS`` (20) summits touch, so that μ is a
      statistic of many asperities from the first point on;
    * ``u_hi`` — the approach at which the GW contact area reaches ``max_area_fraction`` of the
      nominal area (the end of the non-interaction range, 0.1), or at which half of the summits
      touch (the flat at the median summit height), whichever comes first;
    * ``linspace(u_lo, u_hi, num)``; when the map is too small for that (``u_hi <= u_lo``),
      ``linspace(u_hi/num, u_hi, num)``.

    Spikes shift the whole range by their excess (the flat has to pass them, since the highest
    summit is the reference) but never set its width, and the range never reaches A_c > A_nom.

    ``"sigma"``: ``linspace(u_hi/12, u_hi, num)`` with ``u_hi = max(3 σ_S, z_s,max − z̄_s)`` (the
    thesis's ratio 1:12 in units of the summit-height sd; used by ``reproduce`` for the shipped
    surface).  On a map with spikes its width is set by the spike.
    """
    if rule not in APPROACH_RULES:
        raise ContactError(f"unknown approach rule {rule!r}; use one of {', '.join(APPROACH_RULES)}")
    if summits.count < 2:
        raise ContactError(
            f"{summits.count} summit(s) found: the default approach range needs at least 2 summits; "
            "give an explicit range"
        )
    z = np.asarray(summits.heights_m, dtype=np.float64)
    sigma = float(np.std(z))
    if not sigma > 0.0:
        raise ContactError("all summits have the same height (σ_S = 0); give an explicit range")
    n = int(num)
    if rule == ApproachRule.SIGMA:
        lo, hi = DEFAULT_APPROACH_SIGMA
        u_top = max(hi * sigma, float(z.max() - z.mean()))
        return np.linspace(u_top * lo / hi, u_top, n)
    if not 0.0 < max_area_fraction <= 1.0:
        raise ContactError(f"max_area_fraction must lie in (0, 1], got {max_area_fraction!r}")
    order = np.argsort(z)[::-1]
    zs = z[order]
    beta = np.asarray(summits.radius_m, dtype=np.float64)[order]
    depth = zs[0] - zs  # approach at which summit k starts to touch (0 for the highest)
    u_half = float(depth[(zs.size - 1) // 2 + 1]) if zs.size > 2 else float(depth[-1])
    # A(u) = Σ_{depth_k < u} π β_k (u − depth_k), linear between consecutive depths
    c_beta = np.cumsum(np.pi * beta)
    c_beta_depth = np.cumsum(np.pi * beta * depth)
    area_at_depth = c_beta * depth - c_beta_depth  # A at u = depth[k] from summits 0..k
    # a hair inside the limit, so that rounding in the contact sums never puts the last approach past
    # the limit the validity check (contact.validity, ``beyond-non-interaction``) tests
    target = max_area_fraction * summits.area_m2 * (1.0 - AREA_TARGET_MARGIN)
    k = int(np.searchsorted(area_at_depth, target, side="right"))
    if k >= zs.size:  # every summit touches before the area target: extrapolate linearly
        u_area = float(depth[-1] + (target - area_at_depth[-1]) / c_beta[-1])
    else:  # between depth[k-1] and depth[k] the summits 0..k-1 touch
        u_area = float(depth[k - 1] + (target - area_at_depth[k - 1]) / c_beta[k - 1])
    u_hi = min(u_area, u_half)
    k_lo = 2 * MIN_CONTACTS
    u_lo = float(depth[k_lo]) if zs.size > k_lo else u_hi
    if not u_hi > u_lo:
        return np.linspace(u_hi / n, u_hi, n)
    return np.linspace(u_lo, u_hi, n)


def asperity_sums(
    summit_heights_m: npt.ArrayLike,
    radius_m: npt.ArrayLike,
    approach_m: npt.ArrayLike,
    *,
    e_star_pa: float,
    reference_m: float | None = None,
) -> tuple[FloatArray, FloatArray, IntArray]:
    """GW/Hertz sums over summits for every approach: ``(A_c [m²], N [N], n_contacts)``.

    Eq. (3.11)–(3.13): ``d_i = z_i − (z_ref − u)``; summits with ``d_i > 0`` touch;
    ``A_c = Σ π β_i d_i``, ``N = Σ (4/3) E* √β_i d_i^{3/2}``.  ``z_ref`` defaults to the
    highest summit (the thesis's choice); a lower reference is allowed.

    Parameters
    ----------
    summit_heights_m, radius_m:
        Summit heights ``z_i`` [m] and radii ``β_i`` [m] (> 0), same length.
    approach_m:
        Approaches ``u`` [m], any order, > 0.
    e_star_pa:
        Contact modulus E* [Pa] (3.10).
    reference_m:
        ``z_ref`` [m]; default ``max(z_i)``.
    """
    z = np.asarray(summit_heights_m, dtype=np.float64).ravel()
    beta = np.asarray(radius_m, dtype=np.float64).ravel()
    u = _as_approach(approach_m)
    if z.shape != beta.shape:
        raise ContactError(f"{z.size} summit heights but {beta.size} radii")
    if z.size == 0:
        raise ContactError("no summit: the surface has no asperity that could touch the flat")
    if not (np.all(np.isfinite(z)) and np.all(np.isfinite(beta)) and np.all(beta > 0.0)):
        raise ContactError("summit heights must be finite and radii finite and > 0")
    if not (math.isfinite(e_star_pa) and e_star_pa > 0.0):
        raise ContactError(f"E* must be finite and > 0 Pa, got {e_star_pa!r}")
    z_ref = float(z.max()) if reference_m is None else float(reference_m)

    # sort once: depth below the reference, ascending
    order = np.argsort(z_ref - z, kind="stable")
    delta = (z_ref - z)[order]  # >= 0 for the default reference
    beta_s = beta[order]
    # number touching at each u: d = u − δ > 0  <=>  δ < u
    k = np.searchsorted(delta, u, side="left").astype(np.int64)
    # area by cumulative sums: Σ_{i<k} π β_i (u − δ_i) = π (u S_β(k) − S_βδ(k))
    s_beta = np.concatenate(([0.0], np.cumsum(beta_s)))
    s_beta_delta = np.concatenate(([0.0], np.cumsum(beta_s * delta)))
    area = np.pi * (u * s_beta[k] - s_beta_delta[k])
    area = np.maximum(area, 0.0)  # guard against round-off for tiny d
    # force by broadcasting over the summits that touch at the largest u, in blocks
    k_max = int(k.max())
    sqrt_beta = np.sqrt(beta_s[:k_max])
    delta_t = delta[:k_max]
    force = np.empty_like(u)
    rows = max(1, _BLOCK_ELEMENTS // max(k_max, 1))
    for start in range(0, u.size, rows):
        ub = u[start : start + rows, None]
        d = np.clip(ub - delta_t[None, :], 0.0, None)
        force[start : start + rows] = (d * np.sqrt(d)) @ sqrt_beta
    force *= (4.0 / 3.0) * e_star_pa
    return area, force, k


def bowden_tabor_mu(area_m2: npt.ArrayLike, force_n: npt.ArrayLike, shear_strength_pa: float) -> FloatArray:
    """``μ = A_c τ_max / N`` (3.15–3.16) elementwise; NaN where N = 0 (nothing carries load)."""
    a = np.asarray(area_m2, dtype=np.float64)
    n = np.asarray(force_n, dtype=np.float64)
    with np.errstate(divide="ignore", invalid="ignore"):
        out = a * shear_strength_pa / n
    return np.asarray(np.where(n > 0.0, out, np.nan))


@dataclass(frozen=True, kw_only=True, eq=False)
class BowdenTabor:
    """Contact sums over the approach u and the quantities derived from them by eq. (3.14)–(3.16).

    The base of every container of contact sums (:class:`ContactResult` over the approach,
    :class:`stochfric.process.ensemble.ContactSamples` over samples × approach): the approach
    ``approach_m`` [m] (last axis), ``contact_area_m2`` A_c [m²], ``normal_force_n`` N [N] and
    ``n_contacts`` of any array shape, the nominal area ``nominal_area_m2`` [m²] and the shear
    strength ``shear_strength_pa`` τ_max [Pa].
    """

    approach_m: FloatArray
    contact_area_m2: FloatArray
    normal_force_n: FloatArray
    n_contacts: IntArray
    nominal_area_m2: float
    shear_strength_pa: float

    @property
    def pressure_pa(self) -> FloatArray:
        """Nominal pressure ``p = N / A_nom`` [Pa] (3.14)."""
        return self.normal_force_n / self.nominal_area_m2

    @property
    def area_fraction(self) -> FloatArray:
        """``A_c / A_nom`` [-]."""
        return self.contact_area_m2 / self.nominal_area_m2

    @property
    def friction_force_n(self) -> FloatArray:
        """Bowden–Tabor friction force ``R = A_c τ_max`` [N] (3.15)."""
        return self.contact_area_m2 * self.shear_strength_pa

    @property
    def mu(self) -> FloatArray:
        """Friction coefficient ``μ = A_c τ_max / N`` (3.16); NaN where N = 0."""
        return bowden_tabor_mu(self.contact_area_m2, self.normal_force_n, self.shear_strength_pa)


@dataclass(frozen=True, kw_only=True, eq=False)
class ContactResult(BowdenTabor):
    """Contact quantities over the approach ``u``; SI units, one value per approach.

    ``preparation`` records how the surface was prepared and analysed (detrend, median
    radius, step, summit rule, file, sha256, …); ``material`` the pairing used.
    """

    method: str
    e_star_pa: float
    material: dict[str, Any] = field(default_factory=dict)
    preparation: dict[str, Any] = field(default_factory=dict)

    @classmethod
    def of(cls, method: str, surface: Surface, material: Material, approach_m: FloatArray, area_m2: FloatArray,
           force_n: FloatArray, n_contacts: IntArray, preparation: dict[str, Any]) -> ContactResult:
        """The result of ``method`` on ``surface`` in the pairing ``material`` (nominal area, E*, τ_max
        and the material record taken from them) from its A_c, N and contact counts over the approach."""
        return cls(method=method, approach_m=approach_m, contact_area_m2=area_m2, normal_force_n=force_n,
                   n_contacts=n_contacts, nominal_area_m2=surface.nominal_area_m2,
                   shear_strength_pa=material.shear_strength_pa, e_star_pa=material.e_star_pa,
                   material=material.to_dict(), preparation=preparation)

    def plot(self, *others: ContactResult) -> Figure:
        """A_c, p, the number of contacts and μ over the approach u as a matplotlib figure (thesis Fig. 3.11;
        :func:`~stochfric.contact.figures.figure_contact`), with ``others`` (e.g. the half-space result of the
        same surface, Fig. 3.14) drawn alongside.  Save it with ``fig.savefig(path)``."""
        from stochfric.contact.figures import figure_contact

        return figure_contact([self, *others])

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: arrays as lists (NaN as ``None``), SI units in the keys."""

        def listify(a: npt.NDArray[Any]) -> list[Any]:
            return [None if isinstance(v, float) and not math.isfinite(v) else v for v in a.tolist()]

        return {
            "method": self.method,
            "approach_m": listify(self.approach_m),
            "contact_area_m2": listify(self.contact_area_m2),
            "normal_force_n": listify(self.normal_force_n),
            "pressure_pa": listify(self.pressure_pa),
            "n_contacts": [int(v) for v in self.n_contacts],
            "area_fraction": listify(self.area_fraction),
            "friction_force_n": listify(self.friction_force_n),
            "mu": listify(self.mu),
            "nominal_area_m2": self.nominal_area_m2,
            "e_star_pa": self.e_star_pa,
            "shear_strength_pa": self.shear_strength_pa,
            "material": self.material,
            "preparation": self.preparation,
        }

    def to_dataset(self) -> Any:
        """An :class:`xarray.Dataset` over the dimension ``approach`` with units in ``attrs``.

        Dictionaries (material, preparation) are stored as JSON strings so that the dataset
        round-trips through netCDF (:func:`read_contact_result`).
        """
        import xarray as xr

        from stochfric import __version__

        values = {
            "contact_area_m2": self.contact_area_m2,
            "normal_force_n": self.normal_force_n,
            "pressure_pa": self.pressure_pa,
            "n_contacts": self.n_contacts.astype(np.int64),
            "area_fraction": self.area_fraction,
            "friction_force_n": self.friction_force_n,
            "mu": self.mu,
        }
        data_vars = {
            name: (
                ("approach",),
                np.asarray(arr),
                {"units": _VARIABLES[name][0], "long_name": _VARIABLES[name][1]},
            )
            for name, arr in values.items()
        }
        return xr.Dataset(
            data_vars=data_vars,
            coords={
                "approach_m": (
                    ("approach",),
                    self.approach_m,
                    {"units": "m", "long_name": "approach u of the rigid flat (3.11)"},
                )
            },
            attrs={
                "title": CONTACT_TITLE,
                "method": self.method,
                "nominal_area_m2": self.nominal_area_m2,
                "e_star_pa": self.e_star_pa,
                "shear_strength_pa": self.shear_strength_pa,
                "material": json.dumps(self.material, sort_keys=True),
                "preparation": json.dumps(self.preparation, sort_keys=True),
                "stochfric_version": __version__,
            },
        )

    @classmethod
    def from_dataset(cls, ds: Any) -> Self:
        """Rebuild from :meth:`to_dataset` output (also after a netCDF round trip)."""
        attrs = ds.attrs
        return cls(
            method=str(attrs["method"]),
            approach_m=np.asarray(ds["approach_m"].values, dtype=np.float64),
            contact_area_m2=np.asarray(ds["contact_area_m2"].values, dtype=np.float64),
            normal_force_n=np.asarray(ds["normal_force_n"].values, dtype=np.float64),
            n_contacts=np.asarray(ds["n_contacts"].values, dtype=np.int64),
            nominal_area_m2=float(attrs["nominal_area_m2"]),
            shear_strength_pa=float(attrs["shear_strength_pa"]),
            e_star_pa=float(attrs["e_star_pa"]),
            material=json.loads(attrs.get("material", "{}")),
            preparation=json.loads(attrs.get("preparation", "{}")),
        )

    def to_netcdf(self, path: str | Path) -> Path:
        """Write :meth:`to_dataset` to ``path`` atomically (temp file in the same folder,
        then :func:`os.replace`); returns the path."""
        ds = self.to_dataset()
        return write_netcdf_atomic(path, ds)

    @classmethod
    def load(cls, path: str | Path) -> Self:
        """The result saved in ``path`` (:meth:`to_netcdf`, ``stochfric contact --output FILE.nc``).  A missing
        file is a :class:`FileNotFoundError`; a file of another kind an :class:`~stochfric.errors.InputError`."""
        what = "contact result (stochfric contact --output FILE.nc)"
        ds = read_netcdf(path, what)
        if ds.attrs.get("title") != CONTACT_TITLE or "method" not in ds.attrs:
            raise ResultFileError(f"{path} is not a {what}; stochfric.load reads any saved result")
        return cls.from_dataset(ds)


#: The ``title`` attribute of a saved contact result (:meth:`ContactResult.to_dataset`).
CONTACT_TITLE = "stochfric contact analysis"


def read_contact_result(path: str | Path) -> ContactResult:
    """Load a :class:`ContactResult` written by :meth:`ContactResult.to_netcdf` (:meth:`ContactResult.load`)."""
    return ContactResult.load(path)


def asperity_contact(
    surface: Surface,
    summits: Summits,
    material: Material,
    approach_m: npt.ArrayLike | None = None,
    *,
    preparation: dict[str, Any] | None = None,
) -> ContactResult:
    """GW/Hertz + Bowden–Tabor contact of ``surface`` over ``approach_m`` (3.8–3.16).

    ``summits`` must have been found on ``surface`` (its nominal area gives ``p``);
    ``approach_m`` defaults to :func:`default_approach_m`.
    """
    if summits.count == 0:
        raise ContactError(
            f"no summit found on the {surface.nb_grid_pts[0]}×{surface.nb_grid_pts[1]} surface "
            f"(rule {summits.rule!r}); use a smaller step or a larger surface"
        )
    u = default_approach_m(summits) if approach_m is None else _as_approach(approach_m)
    area, force, k = asperity_sums(summits.heights_m, summits.radius_m, u, e_star_pa=material.e_star_pa)
    prep = dict(preparation or {})
    prep.setdefault("summit_rule", summits.rule)
    prep.setdefault("n_summits", summits.count)
    prep.setdefault("reference", "highest summit")
    return ContactResult.of("asperity", surface, material, u, area, force, k, prep)

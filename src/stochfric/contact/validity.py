"""Is a contact result inside the validity of the GW/Hertz + Bowden–Tabor model (method §2, eq. 3.7–3.16)?

Each violated assumption of the model — μ > 1, A_c/A_nom > 1 or beyond the non-interaction range,
too few contacts, a plastic or elastic-plastic plasticity index — becomes a :class:`ValidityWarning`
with a stable ``code`` and a message that says what to change (the table of docs/surface_contact.md,
"Validity warnings"): :func:`contact_validity` on plain arrays over the approach,
:func:`result_validity` on a :class:`~stochfric.contact.asperity.ContactResult`.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.errors import InputError
from stochfric.surface.statistics import ELASTIC_LIMIT, PLASTIC_LIMIT

__all__ = [
    "MIN_CONTACTS",
    "NON_INTERACTION_AREA_FRACTION",
    "ValidityWarning",
    "contact_validity",
    "plasticity_validity",
    "result_validity",
]

#: Fewer contacts than this and μ is not a statistic of the surface.
MIN_CONTACTS = 10

#: Upper end of the non-interaction range of A_c/A_nom: up to 0.1 the half-space/GW area ratio
#: at equal load stays within about 10 % of its plateau on every surface and grid tested
#: (al3d-1, x3p-2, plu-1; benchmarks/bem_equal_load.py); it leaves it beyond 0.13–0.16 on the
#: grooved x3p-2 and plu-1 (0.45–0.53 on al3d-1).  Also the default of the fits' rule.
NON_INTERACTION_AREA_FRACTION = 0.1


@dataclass(frozen=True)
class ValidityWarning:
    """One violated assumption: ``code`` (stable identifier), ``message`` (what and what to
    change) and the indices of the approaches it concerns (empty: the whole result)."""

    code: str
    message: str
    indices: tuple[int, ...] = field(default=())

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"code": self.code, "message": self.message, "indices": list(self.indices)}

    def __str__(self) -> str:
        return f"{self.code}: {self.message}"


def _where(values: npt.NDArray[np.float64], mask: npt.NDArray[np.bool_]) -> tuple[int, ...]:
    return tuple(int(i) for i in np.flatnonzero(mask & np.isfinite(values)))


def _u_text(approach_m: npt.NDArray[np.float64] | None, idx: Sequence[int]) -> str:
    if approach_m is None or not idx:
        return f"at {len(idx)} point(s)"
    lo, hi = approach_m[idx[0]] * 1e6, approach_m[idx[-1]] * 1e6
    return f"at {len(idx)} approach(es), u = {lo:.4g}" + (f" … {hi:.4g} µm" if len(idx) > 1 else " µm")


def contact_validity(
    *,
    mu: npt.ArrayLike,
    area_fraction: npt.ArrayLike,
    n_contacts: npt.ArrayLike,
    approach_m: npt.ArrayLike | None = None,
    plasticity_index: float | None = None,
    max_area_fraction: float | None = None,
    min_contacts: int = MIN_CONTACTS,
    name: str = "",
) -> list[ValidityWarning]:
    """Validity checks of a contact result given as arrays over the approach (module docstring).

    Parameters
    ----------
    mu:
        Friction coefficient μ (3.16) per approach [-]; NaN entries are skipped.
    area_fraction:
        A_c/A_nom per approach [-].
    n_contacts:
        Number of contacts per approach (may be a mean over an ensemble).
    approach_m:
        Approaches u [m] (only to name them in the messages).
    plasticity_index:
        γ (3.7) of the analysed surface with this material, or None (not checked).
    max_area_fraction:
        Upper end of the non-interaction range of A_c/A_nom; default
        :data:`NON_INTERACTION_AREA_FRACTION`.
    min_contacts:
        Fewest contacts for a statistic (default :data:`MIN_CONTACTS`).
    name:
        Prefix for the messages (e.g. the file name).

    Returns
    -------
    list of ValidityWarning
        Empty when every check passes.
    """
    if max_area_fraction is None:
        max_area_fraction = NON_INTERACTION_AREA_FRACTION
    m = np.atleast_1d(np.asarray(mu, dtype=np.float64))
    frac = np.atleast_1d(np.asarray(area_fraction, dtype=np.float64))
    nc = np.atleast_1d(np.asarray(n_contacts, dtype=np.float64))
    if not (m.shape == frac.shape == nc.shape) or m.ndim != 1:
        raise InputError("mu, area_fraction and n_contacts must be 1-D of the same length")
    u = None if approach_m is None else np.atleast_1d(np.asarray(approach_m, dtype=np.float64))
    if u is not None and u.shape != m.shape:
        raise InputError("approach_m must have one value per point")
    pre = f"{name}: " if name else ""
    out: list[ValidityWarning] = []

    checks: list[tuple[str, npt.NDArray[np.float64], npt.NDArray[np.bool_], Callable[[tuple[int, ...]], str]]] = [
        ("mu-above-one", m, m > 1.0, lambda idx: (
            f"{pre}mu > 1 {_u_text(u, idx)} (max {float(np.nanmax(m[list(idx)])):.3g}): the mean contact "
            "pressure N/A_c is below the shear strength tau_max, i.e. the asperities are too blunt or "
            "E* too low for this pairing (Hertz: N/A_c = 4E*/(3 pi) sqrt(d/beta)); use a material that "
            "belongs to this surface (E*, tau_max) or larger approaches - Bowden-Tabor is not meant here")),
        ("area-fraction-above-one", frac, frac > 1.0, lambda idx: (
            f"{pre}A_c/A_nom > 1 {_u_text(u, idx)} (max {float(np.nanmax(frac[list(idx)])):.3g}): more "
            "contact than nominal area is impossible; the approach exceeds the surface's height range - "
            "use smaller approaches (the default range ends at A_c/A_nom = 0.1)")),
        ("beyond-non-interaction", frac, (frac > max_area_fraction) & (frac <= 1.0), lambda idx: (
            f"{pre}A_c/A_nom > {max_area_fraction:g} {_u_text(u, idx)}: beyond the non-interaction range "
            "the asperities interact and the GW area departs from the elastic half-space solution "
            "(docs/surface_contact.md); use smaller approaches, or check with --method halfspace")),
        ("few-contacts", nc, nc < min_contacts, lambda idx: (
            f"{pre}fewer than {min_contacts} contacts {_u_text(u, idx)} (min {float(np.nanmin(nc[list(idx)])):.3g}): "
            "mu there belongs to one or a few asperities, not to the surface; use larger approaches or a "
            "larger measured area")),
    ]  # fmt: skip
    for code, values, mask, message in checks:
        idx = _where(values, mask)
        if idx:
            out.append(ValidityWarning(code, message(idx), idx))
    if plasticity_index is not None:
        out.extend(plasticity_validity(plasticity_index, name=name))
    return out


def plasticity_validity(plasticity_index: float, *, name: str = "") -> list[ValidityWarning]:
    """Warnings for a plasticity index γ (3.7): ``plastic`` (γ > 1), ``elastic-plastic``
    (0.6 ≤ γ ≤ 1); empty for γ < 0.6 or a non-finite γ."""
    g = float(plasticity_index)
    pre = f"{name}: " if name else ""
    if not math.isfinite(g) or g < ELASTIC_LIMIT:
        return []
    if g > PLASTIC_LIMIT:
        return [ValidityWarning(
            "plastic",
            f"{pre}plasticity index gamma = {g:.3g} > {PLASTIC_LIMIT:g}: the contact is mostly plastic "
            "and the elastic Hertz/GW model does not apply; use a plastic or elastic-plastic contact "
            "model, or check the material's E* and hardness",
        )]  # fmt: skip
    return [ValidityWarning(
        "elastic-plastic",
        f"{pre}plasticity index gamma = {g:.3g} in [{ELASTIC_LIMIT:g}, {PLASTIC_LIMIT:g}]: part of "
        "the contacts yield, so the elastic model is questionable; treat mu as an estimate or use "
        "an elastic-plastic model",
    )]  # fmt: skip


def result_validity(
    result: Any,
    *,
    plasticity_index: float | None = None,
    max_area_fraction: float | None = None,
    min_contacts: int = MIN_CONTACTS,
    name: str = "",
) -> list[ValidityWarning]:
    """:func:`contact_validity` of a :class:`~stochfric.contact.asperity.ContactResult`."""
    return contact_validity(
        mu=result.mu,
        area_fraction=result.area_fraction,
        n_contacts=result.n_contacts,
        approach_m=result.approach_m,
        plasticity_index=plasticity_index,
        max_area_fraction=max_area_fraction,
        min_contacts=min_contacts,
        name=name,
    )

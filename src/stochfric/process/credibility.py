"""Is a statistical contact analysis credible enough to write a friction-process model? (method §3–§4)

The gate of ``stochfric friction-process``: each reason why an analysis is *not credible* (the summit
check failed, the surrogate model failed on held-out data or could not be decided, surrogates that copy
the map, E[μ] outside the physical range, a contact area above the nominal one, too few points for the
fits, a fit whose standard error exceeds its coefficient) is a coded
:class:`~stochfric.contact.validity.ValidityWarning`; the command then exits with status 3 and
writes no model file unless the user accepts it (docs/statistical_contact.md §0).  The verdict is one
of three (:attr:`Credibility.status`): ``credible``, ``not credible``, or ``undecided`` when the only
reason is an out-of-sample test that more surrogates (or more measured area) would decide.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.contact.validity import ValidityWarning
from stochfric.process.checks import CopyCheck
from stochfric.process.holdout import HoldoutValidation
from stochfric.process.pooling import BetweenScanTest

__all__ = ["MIN_FIT_POINTS", "MU_PHYSICAL_RANGE", "NOT_CREDIBLE_EXIT", "UNDECIDED_CODE", "Credibility",
           "assess_credibility"]

#: Range of a physical mean friction coefficient of a dry contact: boundary-lubricated (0.03) to clean-metal
#: adhesion (1.5), spanning dry metal, polymer and brake-pad pairings; outside it Bowden–Tabor with this
#: pairing does not describe the surface.
MU_PHYSICAL_RANGE = (0.03, 1.5)
#: Fewest points inside the non-interaction range for a fit of a p^b + c.
MIN_FIT_POINTS = 4
#: Exit status of ``friction-process`` for a result that is not credible (2 is bad input).
NOT_CREDIBLE_EXIT = 3
#: The reason codes of a test that more realisations or more measured area would decide.
UNDECIDED_CODE = "holdout-undecided"
UNDECIDED_SUMMIT_CODE = "summit-check-undecided"
UNDECIDED_CODES = frozenset({UNDECIDED_CODE, UNDECIDED_SUMMIT_CODE})


@dataclass(frozen=True)
class Credibility:
    """The verdict of :func:`assess_credibility`: the reasons against (empty: credible)."""

    reasons: tuple[ValidityWarning, ...]

    @property
    def credible(self) -> bool:
        """True when nothing speaks against the analysis."""
        return not self.reasons

    @property
    def status(self) -> str:
        """``credible``, ``undecided`` (the only reason: an out-of-sample test not yet decided) or ``not credible``."""
        if not self.reasons:
            return "credible"
        return "undecided" if set(self.codes()) <= UNDECIDED_CODES else "not credible"

    def codes(self) -> list[str]:
        """The reasons' codes."""
        return [r.code for r in self.reasons]

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {"credible": self.credible, "status": self.status, "reasons": [r.to_dict() for r in self.reasons]}

    @classmethod
    def from_dict(cls, d: dict[str, Any]) -> Credibility:
        """The inverse of :meth:`to_dict` (``credible`` and ``status`` follow from the reasons)."""
        return cls(tuple(ValidityWarning(r["code"], r["message"], tuple(r.get("indices", ()))) for r in d["reasons"]))


def _where(u: npt.NDArray[np.float64], mask: npt.NDArray[np.bool_]) -> str:
    idx = np.flatnonzero(mask)
    return f"u = {u[idx[0]] * 1e6:.4g} … {u[idx[-1]] * 1e6:.4g} µm" if idx.size > 1 else f"u = {u[idx[0]] * 1e6:.4g} µm"


def assess_credibility(
    *,
    name: str,
    approach_m: npt.ArrayLike,
    surrogate_ok: bool,
    surrogate_failures: list[str],
    surrogate_undecided: list[str] | None = None,
    realizations: int | None = None,
    realizations_to_decide: int | None = None,
    window_ok: bool | None,
    window_max_z: float | None,
    copies: CopyCheck | None = None,
    holdout: HoldoutValidation | None = None,
    between_scans: BetweenScanTest | None = None,
    uncertain_fits: list[str] | None = None,
    mu_means: list[npt.ArrayLike],
    area_fractions: list[npt.ArrayLike],
    fit_mask: npt.ArrayLike,
    valid_fit_points: int,
) -> Credibility:
    """Collect the reasons of the module docstring.  ``window_ok = None``: the window check could not be
    made (too few summits for 2 × 2 windows); that is reported by the analysis, not a reason here.
    ``mu_means`` and ``area_fractions``: E[μ](u) and mean A_c/A_nom(u) of the path and the ensemble;
    μ is checked at the approaches of ``fit_mask``, the area at every approach."""
    u = np.asarray(approach_m, dtype=np.float64)
    used = np.asarray(fit_mask, dtype=bool)
    out: list[ValidityWarning] = []
    if not surrogate_ok:
        out.append(ValidityWarning(
            "surrogate-check-failed",
            f"{name}: the measured map lies outside its surrogate ensemble (Monte Carlo rank test, 5 % "
            f"family-wise, decided; furthest out: {', '.join(surrogate_failures)}): the "
            "surrogates do not resemble this surface; try another "
            "--surrogate (quilt keeps local non-Gaussian structure) or check the preparation",
        ))  # fmt: skip
    if surrogate_ok and surrogate_undecided:
        out.append(ValidityWarning(
            UNDECIDED_SUMMIT_CODE,
            f"{name}: the summit check's Monte Carlo p-value (the map furthest out at "
            f"{', '.join(surrogate_undecided)}) lies within its binomial error of 5 % with {realizations} "
            "realisations: another seed could decide either way; "
            + (f"about {realizations_to_decide} realisations would decide it (--summit-budget lets the check grow "
               "the ensemble to decide)" if realizations_to_decide else
               "the map sits on the limit itself: no affordable number of realisations decides it"),
        ))  # fmt: skip
    if window_ok is False and holdout is None:  # the in-sample check gates only where no held-out test ran
        out.append(ValidityWarning(
            "window-check-failed",
            f"{name}: mu scatters across disjoint windows of the measurement unlike the same windows of the "
            f"surrogates (max |z| {window_max_z:.2f}); the surrogates do not carry the measured scatter",
        ))  # fmt: skip
    if holdout is not None and holdout.verdict == "not credible":
        out.append(ValidityWarning(
            "holdout-failed",
            f"{name}: the {holdout.method} surrogates, made from one half of the map, do not describe the other "
            f"half: {holdout.reason}",
        ))  # fmt: skip
    elif holdout is not None and holdout.verdict == "undecided":
        out.append(ValidityWarning(
            UNDECIDED_CODE,
            f"{name}: the {holdout.method} surrogate model is not validated on held-out data: {holdout.reason}",
        ))  # fmt: skip
    if between_scans is not None and not between_scans.one_surface:
        out.append(ValidityWarning(
            "scans-not-one-surface",
            f"{name}: the pooled scans are not of one surface: μ of their windows differs between scans more than "
            f"within a scan ({between_scans.verdict}); analyse them separately",
        ))  # fmt: skip
    for fit in uncertain_fits or []:
        out.append(ValidityWarning(
            "fit-uncertain",
            f"{name}: {fit}: a model function whose standard error reaches its value says nothing; use more "
            "realisations / long surfaces or a wider approach range",
        ))  # fmt: skip
    if copies is not None and copies.is_copy:
        out.append(ValidityWarning(
            "surrogate-copies-map",
            f"{name}: a surrogate reproduces the map (largest NCC with it {copies.max_ncc_with_map:.3g}, limit "
            f"{copies.ncc_limit:g}; largest verbatim piece {copies.largest_piece_fraction:.3g} of the map, limit "
            f"{copies.piece_limit:g}): the ensemble is not one of new surfaces",
        ))  # fmt: skip
    lo, hi = MU_PHYSICAL_RANGE
    for label, mu in zip(("path", "ensemble"), mu_means, strict=False):
        m = np.asarray(mu, dtype=np.float64)
        bad = used & (~np.isfinite(m) | (m < lo) | (m > hi))
        if np.any(bad):
            out.append(ValidityWarning(
                "mu-out-of-range",
                f"{name}: E[mu] of the {label} statistics is {np.nanmin(m[bad]):.3g} … {np.nanmax(m[bad]):.3g} at "
                f"{_where(u, bad)}, outside the physical range {lo:g} … {hi:g}: this pairing (E*, tau_max) does not "
                "belong to this surface, or the preparation left artefacts",
                tuple(int(i) for i in np.flatnonzero(bad)),
            ))  # fmt: skip
            break
    for label, frac in zip(("path", "ensemble"), area_fractions, strict=False):
        f = np.asarray(frac, dtype=np.float64)
        bad = f > 1.0
        if np.any(bad):
            out.append(ValidityWarning(
                "area-above-nominal",
                f"{name}: the mean contact area of the {label} statistics exceeds the nominal area (max "
                f"{np.nanmax(f):.3g}) at {_where(u, bad)}; use smaller approaches",
                tuple(int(i) for i in np.flatnonzero(bad)),
            ))  # fmt: skip
            break
    if valid_fit_points < MIN_FIT_POINTS:
        out.append(ValidityWarning(
            "fit-too-few-points",
            f"{name}: only {valid_fit_points} approach(es) lie inside the non-interaction range; the fits a p^b + c "
            f"need at least {MIN_FIT_POINTS}: choose approaches with A_c/A_nom <= the --max-area-fraction",
        ))  # fmt: skip
    return Credibility(tuple(out))

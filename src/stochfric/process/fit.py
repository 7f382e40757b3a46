"""Model functions f(p) = a p^b + c fitted by nonlinear least squares (eq. 3.21, method §4d).

:func:`fit_model_function` fits E[μ], σ_μ or the PSD level over the mean pressure, with parameter
standard errors; :func:`fit_mask` leaves out the high-pressure points beyond the non-interaction
range of GW, as the thesis does (§3.2.5).  The fit, its uncertainties and the exclusion rule with
its evidence: docs/statistical_contact.md §3.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.optimize import OptimizeWarning, curve_fit

from stochfric.arrays import FloatArray
from stochfric.contact.validity import NON_INTERACTION_AREA_FRACTION
from stochfric.errors import InputError
from stochfric.friction_process.model_function import ModelFunction

__all__ = [
    "DEFAULT_MAX_AREA_FRACTION",
    "ModelFit",
    "fit_mask",
    "fit_model_function",
]


#: Largest mean contact-area fraction A_c/A_nom of a point used in the fits: the end of the
#: non-interaction range measured against the half-space at equal load (docs/surface_contact.md).
DEFAULT_MAX_AREA_FRACTION = NON_INTERACTION_AREA_FRACTION

_B_GRID = np.concatenate((np.linspace(-3.0, -0.02, 150), np.linspace(0.02, 3.0, 150)))


@dataclass(frozen=True, kw_only=True)
class ModelFit:
    """A fitted model function f(p) = a p^b + c (p in Pa) with standard errors.

    ``used`` marks the points that entered the fit (the others are the excluded
    high-pressure points); ``chi2_reduced`` is χ²/dof with the given ``sigma`` (or the residual
    variance with unit weights); ``note`` explains any fallback.
    """

    a: float
    b: float
    c: float
    a_se: float
    b_se: float
    c_se: float
    covariance: tuple[tuple[float, ...], ...]
    pressure_pa: tuple[float, ...]
    values: tuple[float, ...]
    used: tuple[bool, ...]
    chi2_reduced: float
    note: str = ""
    rule: dict[str, Any] = field(default_factory=dict)

    def model_function(self) -> ModelFunction:
        """The fit as a :class:`~stochfric.friction_process.model_function.ModelFunction`."""
        return ModelFunction(a=self.a, b=self.b, c=self.c)

    def __call__(self, p_pa: npt.ArrayLike) -> FloatArray:
        """f(p) at pressures p [Pa] > 0."""
        return np.asarray(self.a * np.asarray(p_pa, dtype=np.float64) ** self.b + self.c)

    @property
    def n_points(self) -> int:
        """Points the fit uses."""
        return int(sum(self.used))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (p in Pa)."""

        def num(v: float) -> float | None:
            return v if math.isfinite(v) else None

        return {
            "a": self.a,
            "b": self.b,
            "c": self.c,
            "a_se": num(self.a_se),
            "b_se": num(self.b_se),
            "c_se": num(self.c_se),
            "n_points": self.n_points,
            "used": [bool(u) for u in self.used],
            "n_excluded": int(len(self.used) - sum(self.used)),
            "chi2_reduced": num(self.chi2_reduced),
            "note": self.note,
            "rule": self.rule,
            "pressure_unit": "Pa",
        }


def fit_mask(
    area_fraction: npt.ArrayLike,
    pressure_pa: npt.ArrayLike,
    *,
    max_area_fraction: float = DEFAULT_MAX_AREA_FRACTION,
    min_points: int = 4,
) -> tuple[npt.NDArray[np.bool_], str]:
    """Points to use in the fits: mean A_c/A_nom ≤ ``max_area_fraction`` (the non-interaction range).

    Parameters
    ----------
    area_fraction:
        Mean A_c/A_nom per pressure point [-].
    pressure_pa:
        Mean pressure p per point [Pa]; non-finite or p ≤ 0 points are never used.
    max_area_fraction:
        Upper end of the non-interaction range (default 0.1, measured against the
        boundary-element solution at equal load).
    min_points:
        Fewest points a fit needs; if fewer pass, the ``min_points`` lowest pressures are used.

    Returns ``(mask, note)``; ``note`` is non-empty when the ``min_points`` lowest pressures had
    to be used instead.
    """
    frac = np.asarray(area_fraction, dtype=np.float64)
    p = np.asarray(pressure_pa, dtype=np.float64)
    if frac.shape != p.shape or frac.ndim != 1:
        raise InputError("area_fraction and pressure_pa must be 1-D of the same length")
    finite = np.isfinite(frac) & np.isfinite(p) & (p > 0.0)
    mask = finite & (frac <= max_area_fraction)
    if int(mask.sum()) >= min_points:
        return mask, ""
    order = np.argsort(np.where(finite, p, np.inf))[:min_points]
    mask = np.zeros_like(finite)
    mask[order] = True
    mask &= finite
    return mask, (
        f"only {int((finite & (frac <= max_area_fraction)).sum())} point(s) with A_c/A_nom <= "
        f"{max_area_fraction:g}; the {int(mask.sum())} lowest pressures were used"
    )


def _linear_ac(x: FloatArray, y: FloatArray, w: FloatArray, b: float) -> tuple[float, float, float]:
    design = np.stack([x**b, np.ones_like(x)], axis=1) * w[:, None]
    coef, *_ = np.linalg.lstsq(design, y * w, rcond=None)
    resid = design @ coef - y * w
    return float(coef[0]), float(coef[1]), float(resid @ resid)


def fit_model_function(
    pressure_pa: npt.ArrayLike,
    values: npt.ArrayLike,
    sigma: npt.ArrayLike | None = None,
    *,
    mask: npt.ArrayLike | None = None,
    note: str = "",
    rule: dict[str, Any] | None = None,
) -> ModelFit:
    """Fit f(p) = a p^b + c (eq. 3.21) by nonlinear least squares.

    Trust-region reflective fit of the scaled form A (p/p_ref)^b + c (p_ref the geometric mean of
    the used pressures), started from the best of a grid over b with (A, c) solved linearly, and
    transformed back to a = A p_ref^(−b) with the covariance through the Jacobian.  With ``sigma``
    the covariance is that of absolute weights times max(1, χ²/dof) (never shrunk below the data's
    own errors); without it, unit weights and the usual χ²/dof scaling.

    Parameters
    ----------
    pressure_pa:
        Pressures p [Pa] > 0.
    values:
        The quantity at p (E[μ], σ_μ or the PSD level).
    sigma:
        Standard errors of ``values`` (> 0) or None (unit weights).
    mask:
        Points to use (default: all finite ones); at least 4 are needed.
    """
    p = np.asarray(pressure_pa, dtype=np.float64)
    y = np.asarray(values, dtype=np.float64)
    if p.shape != y.shape or p.ndim != 1:
        raise InputError("pressure_pa and values must be 1-D of the same length")
    use = np.isfinite(p) & np.isfinite(y) & (p > 0.0)
    if mask is not None:
        use &= np.asarray(mask, dtype=bool)
    s_all = None if sigma is None else np.asarray(sigma, dtype=np.float64)
    if s_all is not None:
        if s_all.shape != p.shape:
            raise InputError("sigma must have one value per point")
        use &= np.isfinite(s_all) & (s_all > 0.0)
    n = int(use.sum())
    if n < 4:
        raise InputError(f"a fit of a p^b + c needs at least 4 usable points, got {n}")
    pu, yu = p[use], y[use]
    su = s_all[use] if s_all is not None else np.ones(n)
    p_ref = float(np.exp(np.mean(np.log(pu))))
    x = pu / p_ref
    w = 1.0 / su
    best = min(((*_linear_ac(x, yu, w, float(b)), float(b)) for b in _B_GRID), key=lambda t: t[2])
    p0 = (best[0], best[3], best[1])

    def model(xx: FloatArray, a_: float, b_: float, c_: float) -> FloatArray:
        return np.asarray(a_ * xx**b_ + c_)

    fit_note = note
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", OptimizeWarning)
            popt, pcov = curve_fit(
                model, x, yu, p0=p0, sigma=su, absolute_sigma=True, method="trf", maxfev=20000
            )
    except (RuntimeError, ValueError) as exc:
        popt, pcov = np.asarray(p0), np.full((3, 3), np.inf)
        fit_note = (fit_note + "; " if fit_note else "") + f"least squares did not converge ({exc})"
    resid = (model(x, *popt) - yu) / su
    dof = n - 3
    chi2_red = float(resid @ resid) / dof if dof > 0 else math.nan
    if sigma is None:
        scale = chi2_red if math.isfinite(chi2_red) else math.inf
    else:
        scale = max(1.0, chi2_red) if math.isfinite(chi2_red) else 1.0
    pcov = np.asarray(pcov) * scale
    big_a, b, c = (float(v) for v in popt)
    a = big_a * p_ref ** (-b)
    jac = np.array(
        [[p_ref ** (-b), -big_a * p_ref ** (-b) * math.log(p_ref), 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]]
    )
    with np.errstate(invalid="ignore"):
        cov = jac @ pcov @ jac.T
    se = np.sqrt(np.where(np.diag(cov) >= 0.0, np.diag(cov), np.nan))
    return ModelFit(
        a=a,
        b=b,
        c=c,
        a_se=float(se[0]),
        b_se=float(se[1]),
        c_se=float(se[2]),
        covariance=tuple(tuple(float(v) for v in row) for row in cov),
        pressure_pa=tuple(float(v) for v in p),
        values=tuple(float(v) for v in y),
        used=tuple(bool(v) for v in use),
        chi2_reduced=chi2_red,
        note=fit_note,
        rule=dict(rule or {}),
    )

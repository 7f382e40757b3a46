"""Estimators with their standard errors used by the statistical contact analysis (method §4).

* :func:`mean_and_std_errors` — mean and standard deviation over independent samples with the
  standard errors SE(mean) = s/√n and SE(s) = √((m4 − s⁴)/n)/(2s) (delta method with the sample
  fourth central moment m4; no Gaussian assumption);
* :func:`linear_fit` — least-squares line with standard errors (A_c/A_nom over p, Fig. 3.17);
* :func:`mu_pdfs` — PDFs of μ over the ensemble, one histogram per approach (Fig. 3.18a).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray
from stochfric.errors import InputError

__all__ = ["linear_fit", "mean_and_std_errors", "mu_pdfs"]


def mean_and_std_errors(samples: npt.ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray]:
    """Mean, standard deviation (ddof = 1) and their standard errors over axis 0.

    SE(mean) = s/√n; SE(s) = √((m4 − s⁴)/n) / (2s) (delta method, m4 the fourth central moment).
    """
    x = np.asarray(samples, dtype=np.float64)
    n = x.shape[0]
    if n < 2:
        raise InputError("need at least two samples")
    mean = x.mean(axis=0)
    sd = x.std(axis=0, ddof=1)
    m4 = np.mean((x - mean) ** 4, axis=0)
    with np.errstate(invalid="ignore", divide="ignore"):
        se_sd = np.sqrt(np.maximum(m4 - sd**4, 0.0) / n) / (2.0 * sd)
    return mean, sd, sd / math.sqrt(n), np.where(sd > 0.0, se_sd, 0.0)


def linear_fit(x: npt.ArrayLike, y: npt.ArrayLike) -> dict[str, float]:
    """Least-squares line y = slope·x + intercept with standard errors (Fig. 3.17)."""
    xa = np.asarray(x, dtype=np.float64)
    ya = np.asarray(y, dtype=np.float64)
    coef, cov = np.polyfit(xa, ya, 1, cov=True) if xa.size > 3 else (np.polyfit(xa, ya, 1), np.full((2, 2), np.nan))
    pred = np.polyval(coef, xa)
    ss_res = float(np.sum((ya - pred) ** 2))
    ss_tot = float(np.sum((ya - ya.mean()) ** 2))
    return {
        "slope": float(coef[0]),
        "intercept": float(coef[1]),
        "slope_se": float(np.sqrt(cov[0, 0])),
        "intercept_se": float(np.sqrt(cov[1, 1])),
        "r_squared": 1.0 - ss_res / ss_tot if ss_tot > 0 else math.nan,
    }


def mu_pdfs(mu: FloatArray, bins: int) -> tuple[FloatArray, FloatArray]:
    """Histogram densities of μ per approach: ``(edges (U, bins+1), density (U, bins))`` over samples (axis 0)."""
    n_u = mu.shape[1]
    edges = np.empty((n_u, bins + 1))
    dens = np.empty((n_u, bins))
    for k in range(n_u):
        col = mu[:, k][np.isfinite(mu[:, k])]
        lo, hi = (float(col.min()), float(col.max())) if col.size else (0.0, 1.0)
        if hi <= lo:
            hi = lo + 1e-12
        dens[k], edges[k] = np.histogram(col, bins=bins, range=(lo, hi), density=True)
    return edges, dens

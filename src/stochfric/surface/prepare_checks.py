"""Metrological preparation steps and checks (ISO 25178-2 / ISO 16610 vocabulary; method §1.1).

The building blocks of :func:`stochfric.surface.preprocess.prepare` — the undefined-point limit,
outlier removal, form removal (polynomial, the ``auto`` rule, the Gaussian L-filters of ISO
16610-61/-71), the quantisation check and dither, the rough-surface verdict (step, part outline) —
each returning what it did so that the preparation record can say it.  The rules' numbers are the
constants below (docs/surface_contact.md, "Preparation").
"""

from __future__ import annotations

import math
import warnings
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.arrays import FloatArray

__all__ = [
    "AUTO_VARIANCE_GAIN",
    "MAX_UNDEFINED_DEFAULT",
    "OUTLIER_K",
    "OUTLIER_POSITIONS_CAP",
    "OUTLIER_SQ",
    "OUTLIER_WINDOW",
    "OUTLINE_BORDER_FRACTION",
    "STEP_MIN_CLASS",
    "STEP_SEPARATION",
    "TIE_WARN",
    "auto_degree",
    "dither",
    "gaussian_lfilter",
    "otsu_split",
    "outlier_mask",
    "polynomial_residual",
    "rough_surface_verdict",
    "sarle_bimodality",
    "tie_statistics",
]


#: Largest fraction of undefined points filled: the harmonic fill has no interior maximum (maximum
#: principle), so a filled area carries no summit and biases the summit density by its fraction.
MAX_UNDEFINED_DEFAULT = 0.05
#: Side of the median window of the outlier test: its breakdown is 12 of 25 points, so clusters of up
#: to 12 points are seen as isolated; larger features are resolved by the instrument and kept.
OUTLIER_WINDOW = 5
#: k of ``k σ_r``: beyond the map's own local residuals (a Gaussian residual exceeds 6 σ once in 5·10⁸).
OUTLIER_K = 6.0
#: m of ``m S``: 5 Sq from its own neighbourhood, which no Gaussian height field of 10⁶ points reaches
#: (P(|z| > 5 Sq) = 5.7·10⁻⁷), while the heavy-tailed pixel-scale curvature of real maps stays below it.
OUTLIER_SQ = 5.0
#: Most outlier positions recorded.
OUTLIER_POSITIONS_CAP = 100
#: The ``auto`` form rule raises the degree while its extra terms remove more than this share of the
#: remaining variance (each degree judged on its own, so an odd cubic form without quadratic part is
#: found): a rough field of N correlation areas loses about p/N to p extra smooth terms.
AUTO_VARIANCE_GAIN = 0.25
#: Tie fraction of neighbouring height pairs above which heights are quantised: the thesis's summit
#: rule makes 8 strict comparisons, so about 1 − (1 − p)⁸ ≈ 15 % of the candidates meet a tie.
TIE_WARN = 0.02
#: Otsu separation |μ₂ − μ₁| / σ_within above which a map is a step (unimodal distributions give ≤ 4.2,
#: two levels of Gaussian roughness ≈ step/sd) ...
STEP_SEPARATION = 5.0
#: ... when both classes hold at least this fraction (smaller ones are features: pores, scratches).
STEP_MIN_CLASS = 0.05
#: Fraction of the map in undefined points connected to its border above which the map is a part
#: outline (the measuring field extends past the part).
OUTLINE_BORDER_FRACTION = 0.05
#: ISO 16610-61 Gaussian weighting function s(x) = exp(−π (x/(α λc))²)/(α λc), α = √(ln 2/π).
GAUSS_ALPHA = math.sqrt(math.log(2.0) / math.pi)
#: ISO 16610-71 biweight constant: c = 4.4478 · median |r| (= 3 σ for Gaussian residuals).
ROBUST_C = 4.4478
ROBUST_ITERATIONS = 5


def _mad_scale(v: FloatArray) -> float:
    """1.4826 · median |v − median v| (the sd for Gaussian data)."""
    return float(1.4826 * np.median(np.abs(v - np.median(v))))


# ----------------------------------------------------------------------------- form


def polynomial_residual(heights: npt.ArrayLike, degree: int) -> FloatArray:
    """``heights`` minus its least-squares polynomial of total degree ``degree`` in x and y (0…3).

    Centred, scaled grid-index coordinates; columns in the order 1, x, y, x², xy, y², x³, x²y,
    xy², y³ (the residual does not depend on the order).
    """
    h = np.asarray(heights, dtype=np.float64)
    if degree == 0:
        return h - h.mean()
    nx, ny = h.shape
    x = (np.arange(nx, dtype=np.float64) - (nx - 1) / 2) / max(nx, 1)
    y = (np.arange(ny, dtype=np.float64) - (ny - 1) / 2) / max(ny, 1)
    xx, yy = np.meshgrid(x, y, indexing="ij")
    columns = [np.ones_like(xx)]
    for total in range(1, degree + 1):
        columns += [xx ** (total - b) * yy**b for b in range(total + 1)]
    design = np.stack([c.ravel() for c in columns], axis=1)
    coef, *_ = np.linalg.lstsq(design, h.ravel(), rcond=None)
    return np.asarray(h - (design @ coef).reshape(h.shape), dtype=np.float64)


def auto_degree(heights: npt.ArrayLike, *, gain: float = AUTO_VARIANCE_GAIN) -> tuple[int, list[float]]:
    """The ``auto`` form rule: the highest degree d ≤ 3 (at least 1) whose extra terms remove more
    than ``gain`` of the variance left by degree d − 1.  Returns the degree and Sq [input units] after degrees
    1, 2, 3."""
    sq = [float(np.sqrt(np.mean(polynomial_residual(heights, d) ** 2))) for d in (1, 2, 3)]
    degree = 1
    for d in (2, 3):
        if sq[d - 1] ** 2 < (1.0 - gain) * sq[d - 2] ** 2:
            degree = d
    return degree, sq


def gaussian_lfilter(
    heights: npt.ArrayLike,
    spacing_m: tuple[float, float],
    cutoff_m: float,
    *,
    robust: bool = False,
) -> tuple[FloatArray, dict[str, Any]]:
    """Remove the Gaussian mean surface of nesting index ``cutoff_m`` (λc) from ``heights``.

    ISO 16610-61 areal Gaussian filter: weighting function with standard deviation
    ``α λc / √(2π)`` (α = √(ln 2/π)), 50 % transmission at λc.  Edges by normalised convolution
    (the weights are renormalised over the part of the kernel inside the map), so no padding
    value enters.  ``robust``: ISO 16610-71 style reweighting — Tukey biweights
    ``(1 − (r/c)²)²`` with ``c = 4.4478·median|r|``, ``ROBUST_ITERATIONS`` passes.  The input
    should be levelled (a plane removed) first.  Returns the roughness (S-L surface) and a
    record.
    """
    h = np.asarray(heights, dtype=np.float64)
    sigma_m = GAUSS_ALPHA * cutoff_m / math.sqrt(2.0 * math.pi)
    sig = (sigma_m / spacing_m[0], sigma_m / spacing_m[1])

    def smooth(v: FloatArray) -> FloatArray:
        return np.asarray(ndimage.gaussian_filter(v, sig, mode="constant", cval=0.0), dtype=np.float64)

    norm = smooth(np.ones_like(h))
    mean = smooth(h) / norm
    iterations = 0
    if robust:
        for _ in range(ROBUST_ITERATIONS):
            r = h - mean
            c = ROBUST_C * float(np.median(np.abs(r)))
            if not c > 0.0:
                break
            w = np.where(np.abs(r) < c, (1.0 - (r / c) ** 2) ** 2, 0.0)
            den = smooth(w)
            mean = np.where(den > 1e-12 * norm, smooth(w * h) / np.maximum(den, 1e-300), mean)
            iterations += 1
    return h - mean, {"sigma_points": [float(sig[0]), float(sig[1])], "robust_iterations": iterations}


# ----------------------------------------------------------------------------- outliers


def outlier_mask(
    heights: npt.ArrayLike, *, k: float = OUTLIER_K, m_sq: float = OUTLIER_SQ, window: int = OUTLIER_WINDOW
) -> tuple[npt.NDArray[np.bool_], dict[str, float]]:
    """Isolated spikes and pits: ``|z − median_window(z)| > max(k σ_r, m_sq S)`` with the robust
    scales σ_r = 1.4826·MAD of the residual and S = 1.4826·MAD of the plane-levelled map."""
    z = np.asarray(heights, dtype=np.float64)
    r = z - ndimage.median_filter(z, size=window, mode="reflect")
    sigma_r = _mad_scale(r)
    s_rob = _mad_scale(polynomial_residual(z, 1))
    threshold = max(k * sigma_r, m_sq * s_rob)
    if not threshold > 0.0:  # a flat map: nothing stands out
        return np.zeros(z.shape, dtype=bool), {"sigma_r": sigma_r, "s_robust": s_rob, "threshold": threshold}
    return np.abs(r) > threshold, {"sigma_r": sigma_r, "s_robust": s_rob, "threshold": threshold}


# ----------------------------------------------------------------------------- quantisation


def tie_statistics(heights: npt.ArrayLike) -> dict[str, Any]:
    """Fractions of tied (identical) x- and y-neighbour pairs, both together, and the height
    quantum (smallest positive neighbour step, in the input's units; None without one)."""
    z = np.asarray(heights, dtype=np.float64)
    dx = np.abs(np.diff(z, axis=0))
    dy = np.abs(np.diff(z, axis=1))
    tx, ty = int(np.count_nonzero(dx == 0)), int(np.count_nonzero(dy == 0))
    positive = np.concatenate([dx[dx > 0], dy[dy > 0]])
    quantum = float(positive.min()) if positive.size else None
    return {
        "tie_fraction": (tx + ty) / max(dx.size + dy.size, 1),
        "tie_fraction_x": tx / max(dx.size, 1),
        "tie_fraction_y": ty / max(dy.size, 1),
        "quantum": quantum,
    }


def dither(heights: npt.ArrayLike, quantum: float, seed: int = 0) -> FloatArray:
    """``heights`` plus uniform noise in ``[−q/2, q/2)`` (seeded: the same map gives the same
    result)."""
    z = np.asarray(heights, dtype=np.float64)
    rng = np.random.default_rng(seed)
    return np.asarray(z + (rng.random(z.shape) - 0.5) * quantum, dtype=np.float64)


# ----------------------------------------------------------------------------- rough surface


def otsu_split(heights: npt.ArrayLike, candidates: int = 2048) -> dict[str, float]:
    """Otsu's two-class split (maximum between-class variance) over the sorted heights.

    Returns the threshold, the smaller class's fraction and the separation
    ``|μ₂ − μ₁| / σ_within`` (σ_within² = w₁σ₁² + w₂σ₂²).
    """
    z = np.sort(np.asarray(heights, dtype=np.float64).ravel())
    offset = float(z.mean())
    n = z.size
    z = z - offset
    cs, cs2 = np.cumsum(z), np.cumsum(z * z)
    idx = np.unique(np.linspace(1, n - 1, min(candidates, n - 1)).astype(np.int64))
    n1 = idx.astype(np.float64)
    n2 = n - n1
    m1 = cs[idx - 1] / n1
    m2 = (cs[-1] - cs[idx - 1]) / n2
    b = int(np.argmax(n1 * n2 * (m1 - m2) ** 2))
    i = int(idx[b])
    w1 = n1[b] / n
    v1 = max(cs2[i - 1] / n1[b] - m1[b] ** 2, 0.0)
    v2 = max((cs2[-1] - cs2[i - 1]) / n2[b] - m2[b] ** 2, 0.0)
    within = math.sqrt(w1 * v1 + (1.0 - w1) * v2)
    sep = float((m2[b] - m1[b]) / within) if within > 0 else math.inf
    return {"threshold": float(z[i] + offset), "minor_class_fraction": float(min(w1, 1.0 - w1)), "separation": sep}


def sarle_bimodality(heights: npt.ArrayLike) -> float | None:
    """Sarle's bimodality coefficient (g² + 1)/κ (κ not in excess); reported, not used to refuse
    (skewed unimodal maps reach the classical 5/9 too)."""
    z = np.asarray(heights, dtype=np.float64).ravel()
    s = float(z.std())
    if not s > 0:
        return None
    u = (z - z.mean()) / s
    return float((np.mean(u**3) ** 2 + 1.0) / np.mean(u**4))


def _robust_plane_residual(z: FloatArray, plane: FloatArray, iterations: int = 8) -> FloatArray:
    """``z`` minus a plane fitted by iteratively reweighted least squares (Tukey biweight,
    c = 4.685 × the MAD scale): it follows the majority of the points, so a raised or lowered
    region (a step at the edge) stays out of the fit instead of tilting it."""
    w = np.ones(z.size)
    r = z.ravel()
    for _ in range(iterations):
        sw = np.sqrt(w)
        coef, *_ = np.linalg.lstsq(plane * sw[:, None], z.ravel() * sw, rcond=None)
        r = z.ravel() - plane @ coef
        scale = 1.4826 * float(np.median(np.abs(r - np.median(r))))
        if not scale > 0:
            break
        u = r / (4.685 * scale)
        w = np.where(np.abs(u) < 1.0, (1.0 - u * u) ** 2, 0.0)
        if not np.any(w > 0):
            break
    return r.reshape(z.shape)


def _levelled_two_class_split(z: FloatArray, iterations: int = 3) -> tuple[dict[str, float], float]:
    """Otsu split of ``z`` after levelling it with a plane fitted *together with* a step between the
    two classes (as a step height is evaluated, ISO 5436-1): a least-squares plane alone tilts to
    absorb a step and hides it.  Two starts — the map as given and the residual of a robust plane
    (which ignores a minority region) — the split with the larger separation is kept.  Returns
    the split of the levelled map and the fitted step height."""
    nx, ny = z.shape
    x = (np.arange(nx, dtype=np.float64) - (nx - 1) / 2) / nx
    y = (np.arange(ny, dtype=np.float64) - (ny - 1) / 2) / ny
    xx, yy = np.meshgrid(x, y, indexing="ij")
    plane = np.stack([np.ones(z.size), xx.ravel(), yy.ravel()], axis=1)
    best: tuple[dict[str, float], float] | None = None
    for start in (z, _robust_plane_residual(z, plane)):
        levelled = start
        step = 0.0
        for _ in range(iterations):
            t = otsu_split(levelled)["threshold"]
            upper = (levelled > t).ravel().astype(np.float64)
            if upper.min() == upper.max():
                break
            coef, *_ = np.linalg.lstsq(np.column_stack([plane, upper]), z.ravel(), rcond=None)
            levelled = z - (plane @ coef[:3]).reshape(z.shape)
            step = float(abs(coef[3]))
        split = otsu_split(levelled)
        if best is None or split["separation"] > best[0]["separation"]:
            best = (split, step)
    assert best is not None
    return best


def rough_surface_verdict(form_removed: npt.ArrayLike, *, undefined_border_fraction: float = 0.0) -> dict[str, Any]:
    """Is the form-removed map a rough surface?  ``{"rough": bool, "reason": str | None, …}``."""
    z = np.asarray(form_removed, dtype=np.float64)
    otsu, step_height = _levelled_two_class_split(z)
    step = otsu["separation"] > STEP_SEPARATION and otsu["minor_class_fraction"] >= STEP_MIN_CLASS
    outline = undefined_border_fraction > OUTLINE_BORDER_FRACTION
    reason = None
    if outline:
        reason = (f"part outline: {100 * undefined_border_fraction:.3g} % of the map is an undefined "
                  f"surround connected to its border (limit {100 * OUTLINE_BORDER_FRACTION:g} %), the "
                  "measuring field extends past the part")  # fmt: skip
    elif step:
        reason = (
            f"step or two-level map: the heights split into two classes "
            f"({100 * otsu['minor_class_fraction']:.3g} % / {100 * (1 - otsu['minor_class_fraction']):.3g} %) "
            f"whose means are {otsu['separation']:.3g} within-class sd apart (limit {STEP_SEPARATION:g})"
        )
    return {
        "rough": reason is None,
        "reason": reason,
        "otsu_separation": otsu["separation"] if math.isfinite(otsu["separation"]) else None,
        "otsu_minor_class_fraction": otsu["minor_class_fraction"],
        "step_height_m": step_height,
        "sarle_bimodality": sarle_bimodality(z),
        "undefined_border_fraction": float(undefined_border_fraction),
        "limits": {"step_separation": STEP_SEPARATION, "step_min_class": STEP_MIN_CLASS,
                   "outline_border_fraction": OUTLINE_BORDER_FRACTION},
    }  # fmt: skip


def undefined_border_fraction(mask: npt.NDArray[np.bool_]) -> float:
    """Fraction of the map covered by undefined regions (4-connected) that touch the border."""
    if not mask.any():
        return 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        labels, n = ndimage.label(mask)
    if n == 0:
        return 0.0
    border = np.unique(np.concatenate([labels[0, :], labels[-1, :], labels[:, 0], labels[:, -1]]))
    border = border[border > 0]
    return float(np.isin(labels, border).sum() / mask.size)

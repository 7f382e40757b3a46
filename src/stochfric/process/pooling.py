"""Pooling several scans of one surface: are they one surface, how many are needed, may they be pooled.

A 256² map is a normal measurement; the σ_μ a friction-process model needs rests on several of them.
This module states the rules for pooling scans as one ensemble (issue 29, item 5):

* :func:`between_scan_test` — a **random-effects test** on μ of the disjoint windows of every scan
  (the windows of the measured-window check, :func:`measured_window_mu`): per approach a one-way
  ANOVA of the window means between scans (F = between-scan / within-scan mean square, the
  between-scan variance component σ_b² and the intraclass correlation) and a Brown–Forsythe test of
  the within-scan scatter (scans of one surface also scatter alike); Holm's step-down procedure over
  all 2U hypotheses at family-wise ``alpha``.  Scans it refuses are not of one surface
  (:class:`BetweenScanTest`, ``one_surface``).  It also reports the smallest between-scan standard
  deviation it would detect with 80 % power at these numbers of scans and windows.
* :func:`scans_needed` / :func:`sigma_mu_relative_se` — how many scans of a given size give σ_μ to a
  stated relative precision.
* :func:`pixel_sizes_agree` with :data:`POOL_PIXEL_RTOL` — scans whose pixel sizes agree within an
  instrument's lateral calibration are one pixel size (no resampling).
* :data:`MIN_SUMMITS_PER_SCAN`, :func:`require_summits_for_pooling`,
  :func:`check_resampling_keeps_summits` — a scan is never reduced to a handful of summits to make it
  poolable.

SI units throughout; μ is dimensionless.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import optimize
from scipy import stats as sps

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import bowden_tabor_mu
from stochfric.contact.materials import Material
from stochfric.errors import AnalysisError
from stochfric.process.checks import WINDOW_MIN_SUMMITS, window_tiles
from stochfric.process.ensemble import tile_contact
from stochfric.surface.grid import resample_surface
from stochfric.surface.io import Surface
from stochfric.surface.scans import PIXEL_RTOL, pixel_size_spread, pixel_sizes_agree, relabel_to_mean_pixel_size
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, find_summits

__all__ = [
    "BETWEEN_SCAN_ALPHA",
    "BETWEEN_SCAN_POWER",
    "MIN_SUMMITS_PER_SCAN",
    "MIN_WINDOWS_PER_SCAN",
    "POOL_PIXEL_RTOL",
    "BetweenScanTest",
    "ScansNeeded",
    "between_scan_test",
    "check_resampling_keeps_summits",
    "detectable_between_scan_sd",
    "measured_window_mu",
    "on_common_pixel_size",
    "pixel_size_spread",
    "pixel_sizes_agree",
    "require_summits_for_pooling",
    "scans_needed",
    "sigma_mu_relative_se",
]

#: Family-wise false-alarm probability of the between-scan test (Holm over 2 tests × U approaches).
BETWEEN_SCAN_ALPHA = 0.05

#: Power at which the smallest detectable between-scan standard deviation is reported.
BETWEEN_SCAN_POWER = 0.8

#: Relative tolerance within which the pixel sizes of scans to be pooled count as one pixel size.
#: The lateral calibration of a profilometer or AFM (scanner linearity, objective magnification) is
#: uncertain to about 0.5 % to 1 %, so two files whose pixel sizes differ by less than that — e.g. one
#: measurement stored in two formats, 0.1 % apart from rounding the scan size — cannot be told apart
#: by their pixel size and are pooled as they are, without interpolation.  Beyond it the scans are
#: different pixel sizes: resample them (``--resample``) or measure them alike.
POOL_PIXEL_RTOL = PIXEL_RTOL  # stochfric.surface.scans: pool_scans uses the same

#: Windows per scan the between-scan test needs: 3 × 3 disjoint windows.  With 2 × 2 windows each scan
#: gives 3 degrees of freedom to the within-scan variance, the Brown–Forsythe test compares spreads of
#: 4 values, and two such scans detect (80 % power, U = 12) only scan means about 4.5 within-scan sd
#: apart; with 3 × 3 windows 2.2 sd, with 4 × 4 (the window check's default) 1.5 sd
#: (:func:`detectable_between_scan_sd`, fixed effects, level α/24).
MIN_WINDOWS_PER_SCAN = 9

#: Summits a scan must keep to be pooled: :data:`MIN_WINDOWS_PER_SCAN` windows of
#: :data:`~stochfric.process.checks.WINDOW_MIN_SUMMITS` (20) summits each, the least at which μ of a
#: window is a statistic of many asperities (the measured-window check's rule) — 180.  A scan with fewer
#: summits (e.g. an AFM scan resampled to 51 × 51 points, 21–41 summits) cannot be tested against the
#: others, so it cannot be pooled.
MIN_SUMMITS_PER_SCAN = MIN_WINDOWS_PER_SCAN * WINDOW_MIN_SUMMITS

_RULE = (
    "one surface unless Holm's step-down procedure over the 2U hypotheses at the U approaches - no more "
    "between-scan variance of the window mu than sigma_b^2/sigma_w^2 = the null ratio (0 unless given; "
    "one-way random-effects ANOVA, F = between-scan / within-scan mean square) and equal within-scan "
    "scatter (Brown-Forsythe) - rejects any at family-wise alpha = {alpha:g} "
    "(the first step, smallest p <= alpha/(2U), is Bonferroni's); windows with undefined mu are dropped; "
    "assumes disjoint windows several correlation lengths wide, so that the windows of one scan are "
    "independent given the scan"
)


_ARRAY_FIELDS = (
    "null_variance_ratio", "f_statistic", "df_between", "df_within", "p_value", "sigma_b2", "sigma_w2", "icc",
    "scatter_statistic", "scatter_p_value", "detectable_sigma_b", "detectable_mean_sd", "neighbour_correlation",
)  # fmt: skip


def _finite_list(a: npt.ArrayLike) -> list[float | None]:
    return [float(v) if math.isfinite(float(v)) else None for v in np.asarray(a, dtype=np.float64).ravel()]


# --------------------------------------------------------------------------------------------------
# μ of the disjoint windows of each scan
# --------------------------------------------------------------------------------------------------


def measured_window_mu(
    surfaces: Sequence[Surface],
    material: Material,
    approach_m: npt.ArrayLike,
    *,
    tiles: int | None = None,
    rule: str = DEFAULT_SUMMIT_RULE,
) -> list[FloatArray]:
    """μ of the disjoint ``tiles × tiles`` windows of every scan, one array (tiles², U) per scan.

    Each window is analysed on its own, referenced to its own highest summit
    (:func:`~stochfric.process.ensemble.tile_contact`, as the measured-window check does); μ =
    A_c τ_max / N (:func:`~stochfric.contact.asperity.bowden_tabor_mu`), NaN where a window carries
    no load.  ``tiles`` None: the window check's rule on the scan with the fewest summits
    (:func:`~stochfric.process.checks.window_tiles`); :class:`AnalysisError` if even 2 × 2 windows
    would hold fewer than 20 summits each.
    """
    if not surfaces:
        raise AnalysisError("no scan given")
    u = np.atleast_1d(np.asarray(approach_m, dtype=np.float64))
    if tiles is None:
        fewest = min(find_summits(s.heights_m, s.grid_spacing_m, rule=rule).count for s in surfaces)
        chosen = window_tiles(fewest)
        if chosen is None:
            raise AnalysisError(
                f"a scan has {fewest} summits: 2 x 2 windows of {WINDOW_MIN_SUMMITS} summits each do not fit, "
                "so its windows cannot be compared with the other scans'"
            )
        tiles = chosen
    out = []
    for s in surfaces:
        area, force, _count = tile_contact(s.heights_m, s.grid_spacing_m, material, u, tiles=tiles, rule=rule)
        out.append(bowden_tabor_mu(area, force, material.shear_strength_pa))
    return out


# --------------------------------------------------------------------------------------------------
# The between-scan test
# --------------------------------------------------------------------------------------------------


def _anova(groups: list[FloatArray], null_ratio: float = 0.0) -> tuple[float, float, float, float, float, float, float]:
    """One-way ANOVA of ``groups`` (each ≥ 2 values): (F, df1, df2, p, MSB, MSW, n0); p of H0 σ_b²/σ_w² ≤
    ``null_ratio`` (F/(1 + n₀·ratio) against F(df1, df2))."""
    n = np.array([g.size for g in groups], dtype=np.float64)
    k, total = len(groups), float(n.sum())
    means = np.array([g.mean() for g in groups])
    grand = float(np.concatenate(groups).mean())
    ssb = float(np.sum(n * (means - grand) ** 2))
    ssw = float(sum(np.sum((g - g.mean()) ** 2) for g in groups))
    df1, df2 = k - 1.0, total - k
    msb, msw = ssb / df1, ssw / df2
    n0 = (total - float(np.sum(n**2)) / total) / df1
    if msw > 0:
        f = msb / msw
        p = float(sps.f.sf(f / (1.0 + n0 * null_ratio), df1, df2))
    elif msb > 0:
        f, p = math.inf, 0.0
    else:
        f, p = math.nan, math.nan
    return f, df1, df2, p, msb, msw, n0


def _brown_forsythe(groups: list[FloatArray]) -> tuple[float, float]:
    """Brown–Forsythe (Levene about the median) statistic and p-value; NaN when every deviation is 0."""
    with np.errstate(divide="ignore", invalid="ignore"):
        dev = [np.abs(g - np.median(g)) for g in groups]
        if not any(np.any(d > 0) for d in dev):
            return math.nan, math.nan
        res = sps.levene(*groups, center="median")
    stat, p = float(res.statistic), float(res.pvalue)
    return (stat, p) if math.isfinite(stat) else (math.nan, math.nan)


def detectable_between_scan_sd(
    n_windows: Sequence[int], *, level: float, power: float = BETWEEN_SCAN_POWER, null_ratio: float = 0.0
) -> tuple[float, float]:
    """The smallest spread of the scans' true mean μ that the ANOVA at significance ``level`` detects with
    probability ``power``, in units of the within-scan sd σ_w, for scans with ``n_windows`` windows each:
    ``(random_effects, fixed_effects)``.

    * random effects — scans drawn from surfaces whose means scatter with sd σ_b: then MSB/MSW is
      (1 + n₀σ_b²/σ_w²) times a central F(k−1, N−k) (exact for equal window counts and normal μ; n₀ the
      ANOVA's effective window count per scan otherwise), so σ_b/σ_w = √((c·F_crit/F_{1−power} − 1)/n₀),
      c = 1 + n₀·``null_ratio`` (the threshold of the test of H0 σ_b²/σ_w² ≤ ``null_ratio``);
    * fixed effects — these particular scans' true means have sd s (ddof 1): F is noncentral with
      λ = n₀(k−1)s²/σ_w², solved for ``power`` at the threshold c·F_crit (two scans: means |Δ| = √2·s
      apart; with ``null_ratio`` > 0 an approximation).

    With two scans the random-effects number is large (one between-scan degree of freedom: a random pair
    of surfaces can have nearly equal means by chance); the fixed-effects number says how far apart the
    means of the scans at hand must be.
    """
    n = np.asarray([int(v) for v in n_windows], dtype=np.float64)
    if n.size < 2 or np.any(n < 2):
        return math.nan, math.nan
    k, total = float(n.size), float(n.sum())
    df1, df2 = k - 1.0, total - k
    n0 = (total - float(np.sum(n**2)) / total) / df1
    f_crit = float(sps.f.isf(level, df1, df2)) * (1.0 + n0 * float(null_ratio))
    random_effects = math.sqrt(max(f_crit / float(sps.f.ppf(1.0 - power, df1, df2)) - 1.0, 0.0) / n0)

    def miss(lam: float) -> float:
        return float(sps.ncf.sf(f_crit, df1, df2, lam)) - power

    hi = 1.0
    while miss(hi) < 0:
        hi *= 2.0
    lam = float(optimize.brentq(miss, 0.0, hi, xtol=1e-10, rtol=1e-10))
    fixed_effects = math.sqrt(lam / (n0 * df1))
    return random_effects, fixed_effects


def _holm(p_values: FloatArray, alpha: float) -> npt.NDArray[np.bool_]:
    """Holm's step-down rejections of the finite ``p_values`` at family-wise ``alpha`` (NaN: not tested)."""
    reject = np.zeros(p_values.shape, dtype=bool)
    flat = p_values.ravel()
    tested = np.flatnonzero(np.isfinite(flat))
    m = tested.size
    order = tested[np.argsort(flat[tested], kind="stable")]
    out = reject.ravel()
    for rank, idx in enumerate(order):
        if flat[idx] <= alpha / (m - rank):
            out[idx] = True
        else:
            break
    return out.reshape(p_values.shape)


def _neighbour_correlation(resid: list[FloatArray]) -> float:
    """Correlation of the within-scan residuals of horizontally and vertically adjacent windows, the
    windows of each scan a row-major t × t grid (:func:`~stochfric.process.ensemble.tile_grid`); NaN
    when a scan's window count is not a square or fewer than 3 pairs are defined."""
    a_all: list[float] = []
    b_all: list[float] = []
    for r in resid:
        t = math.isqrt(r.size)
        if t * t != r.size or t < 2:
            return math.nan
        grid = r.reshape(t, t)
        for a, b in ((grid[:-1, :], grid[1:, :]), (grid[:, :-1], grid[:, 1:])):
            ok = np.isfinite(a) & np.isfinite(b)
            a_all.extend(a[ok].tolist())
            b_all.extend(b[ok].tolist())
    if len(a_all) < 3:
        return math.nan
    x, y = np.asarray(a_all), np.asarray(b_all)
    if x.std() == 0 or y.std() == 0:
        return math.nan
    return float(np.corrcoef(x, y)[0, 1])


@dataclass(frozen=True, kw_only=True)
class BetweenScanTest:
    """The random-effects test of several scans being of one surface (per approach; arrays of length U).

    Per approach, on μ of the disjoint windows of each scan (windows with undefined μ dropped; a scan with
    fewer than 2 defined windows left out at that approach):

    * ``f_statistic``, ``df_between``, ``df_within``, ``p_value`` — one-way ANOVA of the window means
      between scans, F = MSB/MSW (unequal window counts allowed); p of H0 σ_b²/σ_w² ≤
      ``null_variance_ratio`` λ₀ (F/(1 + n₀λ₀) against F(k−1, N−k); λ₀ = 0 the classical test);
    * ``sigma_b2`` — the between-scan variance component, method of moments (MSB − MSW)/n₀ truncated at
      0; ``sigma_w2`` = MSW, the within-scan (window-to-window) variance; ``icc`` = σ_b²/(σ_b² + σ_w²);
    * ``scatter_statistic``, ``scatter_p_value`` — Brown–Forsythe test of equal within-scan scatter;
    * ``detectable_sigma_b`` — the smallest between-scan sd σ_b (random effects: scans of surfaces whose
      mean μ scatters with sd σ_b) the ANOVA detects with ``power`` at the Bonferroni level α/(2U);
      ``detectable_mean_sd`` — the same for the true means of these scans (fixed effects, noncentral
      F); both in μ, i.e. the ratios of :func:`detectable_between_scan_sd` times √MSW;
    * ``neighbour_correlation`` — correlation of the residuals of adjacent windows (diagnostic of the
      independence assumption; about −1/(n−1) when it holds, n the windows per scan);
    * ``mean_rejected``, ``scatter_rejected`` — Holm's rejections over the 2U hypotheses.

    ``one_surface`` is False when any hypothesis is rejected; ``failing_approaches`` are the indices
    of the approaches with a rejection (``failing_means``, ``failing_scatter`` by test).
    """

    scans: int
    windows: tuple[int, ...]
    alpha: float
    power: float
    approach_m: FloatArray | None
    null_variance_ratio: FloatArray
    f_statistic: FloatArray
    df_between: FloatArray
    df_within: FloatArray
    p_value: FloatArray
    sigma_b2: FloatArray
    sigma_w2: FloatArray
    icc: FloatArray
    scatter_statistic: FloatArray
    scatter_p_value: FloatArray
    detectable_sigma_b: FloatArray
    detectable_mean_sd: FloatArray
    neighbour_correlation: FloatArray
    mean_rejected: npt.NDArray[np.bool_]
    scatter_rejected: npt.NDArray[np.bool_]
    one_surface: bool
    failing_approaches: tuple[int, ...]
    failing_means: tuple[int, ...]
    failing_scatter: tuple[int, ...]
    rule: str
    notes: tuple[str, ...] = field(default_factory=tuple)

    @property
    def verdict(self) -> str:
        """``"one surface"`` or ``"NOT one surface …"`` with the failing approaches."""
        if self.one_surface:
            return "one surface"
        parts = []
        if self.failing_means:
            parts.append("window means differ at approach(es) " + ", ".join(str(i) for i in self.failing_means))
        if self.failing_scatter:
            parts.append("window scatter differs at approach(es) " + ", ".join(str(i) for i in self.failing_scatter))
        return "NOT one surface: " + "; ".join(parts)

    @property
    def variance_ratio(self) -> FloatArray:
        """σ_b²/σ_w² per approach, the estimated between-scan variance in units of the within-scan variance
        (NaN where σ_w² is 0 or undefined)."""
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.where(self.sigma_w2 > 0, self.sigma_b2 / self.sigma_w2, np.nan)

    @property
    def min_p_value(self) -> float:
        """The smallest p-value over both tests and all approaches (NaN if none was tested)."""
        p = np.concatenate([self.p_value, self.scatter_p_value])
        return float(np.nanmin(p)) if np.any(np.isfinite(p)) else math.nan

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: every field (NaN and ±inf as None), the verdict and the rule."""
        out: dict[str, Any] = {
            "scans": self.scans, "windows": list(self.windows), "alpha": self.alpha, "power": self.power,
            "approach_m": None if self.approach_m is None else _finite_list(self.approach_m),
        }  # fmt: skip
        for name in _ARRAY_FIELDS:
            out[name] = _finite_list(getattr(self, name))
        out["mean_rejected"] = [bool(v) for v in self.mean_rejected]
        out["scatter_rejected"] = [bool(v) for v in self.scatter_rejected]
        out.update(one_surface=self.one_surface, failing_approaches=list(self.failing_approaches),
                   failing_means=list(self.failing_means), failing_scatter=list(self.failing_scatter),
                   verdict=self.verdict, rule=self.rule, notes=list(self.notes))  # fmt: skip
        return out


def between_scan_test(
    window_mu: Sequence[npt.ArrayLike],
    *,
    alpha: float = BETWEEN_SCAN_ALPHA,
    power: float = BETWEEN_SCAN_POWER,
    approach_m: npt.ArrayLike | None = None,
    null_variance_ratio: npt.ArrayLike = 0.0,
) -> BetweenScanTest:
    """Are these scans of one surface?  A random-effects test on μ of the disjoint windows of each scan.

    ``window_mu``: one array (windows_s, U) per scan — μ of its disjoint windows at the U approaches
    (:func:`measured_window_mu`; windows in the row-major order of
    :func:`~stochfric.process.ensemble.tile_grid` for the neighbour diagnostic).  Per approach a one-way
    ANOVA of the window means between scans and a Brown–Forsythe test of the within-scan scatter; the
    family of 2U hypotheses is decided by Holm's step-down procedure at family-wise ``alpha`` (any
    rejection: not one surface — the same decision as Bonferroni's α/(2U), Holm only names more of the
    failing approaches).  See :class:`BetweenScanTest` for what is returned.

    **Assumption.** The windows of one scan are independent given the scan: they are disjoint, and each is
    several correlation lengths of the surface wide, so that μ of neighbouring windows (each referenced to
    its own highest summit) share no summits and hardly any long wavelengths.  Correlated windows make the
    scan means scatter more than MSW/n says and the test refuses too often; ``neighbour_correlation``
    shows it.  μ need not be normal: the F test of the means is robust to moderate non-normality with
    similar window counts, and the scatter test is Brown–Forsythe's (about the median).

    **The null hypothesis** is σ_b²/σ_w² ≤ ``null_variance_ratio`` λ₀ (per approach; default 0: the scans
    are windows of one stationary surface).  Long wavelengths do not break it: independent random-phase
    self-affine maps of one generator (256², H = 0.5 and 0.8, no roll-off, 4 × 4 windows, heights in one
    fixed unit) are refused in 3 of 180 pairs.  Maps rescaled each to its own RMS height are different
    surfaces (their short-wavelength roughness differs by a random factor) and are refused.  A positive λ₀
    accepts a stated amount of between-scan variance as part of the surface (e.g. a known heterogeneity);
    :attr:`BetweenScanTest.variance_ratio` is the estimate from a set of scans.

    :class:`AnalysisError` for fewer than two scans, arrays of different U, or when no approach has two
    scans with at least two defined windows each.
    """
    if not (0.0 < float(alpha) < 1.0):
        raise AnalysisError(f"alpha must lie in (0, 1), got {alpha!r}")
    if not (0.0 < float(power) < 1.0):
        raise AnalysisError(f"power must lie in (0, 1), got {power!r}")
    arrays = [np.asarray(m, dtype=np.float64) for m in window_mu]
    arrays = [a[:, None] if a.ndim == 1 else a for a in arrays]
    if len(arrays) < 2:
        raise AnalysisError(f"the between-scan test needs at least two scans, got {len(arrays)}")
    if any(a.ndim != 2 for a in arrays) or len({a.shape[1] for a in arrays}) != 1:
        raise AnalysisError(
            "the window mu of every scan must be an array (windows, U) with the same U: "
            + ", ".join(str(a.shape) for a in arrays)
        )
    n_u = arrays[0].shape[1]
    u = None if approach_m is None else np.atleast_1d(np.asarray(approach_m, dtype=np.float64))
    if u is not None and u.size != n_u:
        raise AnalysisError(f"{u.size} approaches given for window mu at {n_u}")
    null = np.broadcast_to(np.asarray(null_variance_ratio, dtype=np.float64), (n_u,)).copy()
    if not np.all(np.isfinite(null) & (null >= 0)):
        raise AnalysisError(f"the null variance ratio must be finite and >= 0, got {null.tolist()}")

    nan = np.full(n_u, np.nan)
    f_stat, df1, df2, p_val = nan.copy(), nan.copy(), nan.copy(), nan.copy()
    sb2, sw2, icc = nan.copy(), nan.copy(), nan.copy()
    bf_stat, bf_p = nan.copy(), nan.copy()
    neighbour = nan.copy()
    counts: list[list[int]] = []
    notes: list[str] = []
    for j in range(n_u):
        cols = [a[:, j] for a in arrays]
        groups = [c[np.isfinite(c)] for c in cols]
        kept = [g for g in groups if g.size >= 2]
        if len(kept) < len(groups):
            notes.append(f"approach {j}: {len(groups) - len(kept)} scan(s) with fewer than 2 defined windows left out")
        if len(kept) < 2:
            counts.append([])
            continue
        counts.append([g.size for g in kept])
        f, d1, d2, p, msb, msw, n0 = _anova(kept, float(null[j]))
        f_stat[j], df1[j], df2[j], p_val[j] = f, d1, d2, p
        sw2[j] = msw
        sb2[j] = max((msb - msw) / n0, 0.0)
        total = sb2[j] + sw2[j]
        icc[j] = sb2[j] / total if total > 0 else math.nan
        bf_stat[j], bf_p[j] = _brown_forsythe(kept)
        neighbour[j] = _neighbour_correlation([c - np.nanmean(c) if np.any(np.isfinite(c)) else c for c in cols])
    tested = np.isfinite(p_val) | np.isfinite(bf_p)
    if not np.any(tested):
        raise AnalysisError(
            "the between-scan test found no approach at which two scans have at least two windows with defined mu each"
        )
    m = int(np.sum(np.isfinite(p_val)) + np.sum(np.isfinite(bf_p)))
    level = alpha / m
    det_b, det_m = nan.copy(), nan.copy()
    cache: dict[tuple[tuple[int, ...], float], tuple[float, float]] = {}
    for j in range(n_u):
        if counts[j] and math.isfinite(float(sw2[j])):
            key = (tuple(counts[j]), float(null[j]))
            if key not in cache:
                cache[key] = detectable_between_scan_sd(key[0], level=level, power=power, null_ratio=key[1])
            ratio_b, ratio_m = cache[key]
            det_b[j], det_m[j] = ratio_b * math.sqrt(sw2[j]), ratio_m * math.sqrt(sw2[j])
    reject = _holm(np.stack([p_val, bf_p]), alpha)
    mean_rej, scatter_rej = reject[0], reject[1]
    failing = tuple(int(i) for i in np.flatnonzero(mean_rej | scatter_rej))
    return BetweenScanTest(
        scans=len(arrays), windows=tuple(int(a.shape[0]) for a in arrays), alpha=float(alpha), power=float(power),
        approach_m=u, null_variance_ratio=null, f_statistic=f_stat, df_between=df1, df_within=df2, p_value=p_val,
        sigma_b2=sb2, sigma_w2=sw2, icc=icc, scatter_statistic=bf_stat, scatter_p_value=bf_p, detectable_sigma_b=det_b,
        detectable_mean_sd=det_m, neighbour_correlation=neighbour, mean_rejected=mean_rej,
        scatter_rejected=scatter_rej, one_surface=not failing, failing_approaches=failing,
        failing_means=tuple(int(i) for i in np.flatnonzero(mean_rej)),
        failing_scatter=tuple(int(i) for i in np.flatnonzero(scatter_rej)),
        rule=_RULE.format(alpha=float(alpha)), notes=tuple(notes),
    )  # fmt: skip


# --------------------------------------------------------------------------------------------------
# How many scans
# --------------------------------------------------------------------------------------------------


def sigma_mu_relative_se(n_windows: int, kurtosis: float = 3.0) -> float:
    """Relative standard error of a sample standard deviation of μ over ``n_windows`` independent windows,
    μ of kurtosis κ (3 for normal μ): √((κ − (n−3)/(n−1))/(4n)), from Var(s²) = σ⁴(κ − (n−3)/(n−1))/n by
    the delta method.  For κ = 3 it is exactly 1/√(2(n−1)); for large n ≈ √((κ−1)/(4n))."""
    n = int(n_windows)
    if n < 2:
        raise AnalysisError(f"a standard deviation needs at least 2 windows, got {n_windows!r}")
    k = float(kurtosis)
    if not (math.isfinite(k) and k >= 1.0):
        raise AnalysisError(f"the kurtosis of mu must be a finite number >= 1, got {kurtosis!r}")
    return math.sqrt(max(k - (n - 3) / (n - 1), 0.0) / (4.0 * n))


@dataclass(frozen=True, kw_only=True)
class ScansNeeded:
    """How many scans of one size give σ_μ to a relative precision (:func:`scans_needed`)."""

    scans: int
    windows: int
    windows_per_scan: int
    rel_precision: float
    relative_se: float
    kurtosis: float
    sigma_mu: float | None
    sigma_mu_se: float | None
    assumption: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary of the fields."""
        return {k: getattr(self, k) for k in self.__dataclass_fields__}


def scans_needed(
    sigma_mu: float | None,
    rel_precision: float,
    *,
    windows_per_scan: int,
    kurtosis: float = 3.0,
    max_scans: int = 100_000,
) -> ScansNeeded:
    """The number of scans of one size for σ_μ to a relative standard error ≤ ``rel_precision``.

    σ_μ is the standard deviation of μ over windows of one size (``windows_per_scan`` of them per scan:
    1 when σ_μ is meant at the scan's own size — the model's window —, tiles² when it is meant at the size
    of the disjoint tiles of the window check).  The smallest number n of windows with
    :func:`sigma_mu_relative_se` (n, κ) ≤ ``rel_precision`` is found, and scans = ⌈n / windows_per_scan⌉.
    ``sigma_mu`` (optional, e.g. from a pilot scan) only turns the precision into an absolute standard
    error ``sigma_mu_se``.  ``kurtosis``: of μ over such windows (3 for normal μ; μ at small approaches,
    resting on a few summits, is heavy-tailed: estimate it from the windows of a pilot scan, e.g.
    ``scipy.stats.kurtosis(mu, fisher=False)``).

    **Assumption:** the windows are independent — disjoint, several correlation lengths wide, and the scans
    are of one surface (:func:`between_scan_test`); correlated windows carry less information and need more
    scans.
    """
    r = float(rel_precision)
    if not (0.0 < r < 1.0):
        raise AnalysisError(f"the relative precision must lie in (0, 1), got {rel_precision!r}")
    w = int(windows_per_scan)
    if w < 1:
        raise AnalysisError(f"windows per scan must be >= 1, got {windows_per_scan!r}")
    if sigma_mu is not None and not (math.isfinite(float(sigma_mu)) and float(sigma_mu) >= 0):
        raise AnalysisError(f"sigma_mu must be a finite number >= 0, got {sigma_mu!r}")
    sigma_mu_relative_se(2, kurtosis)  # validates the kurtosis
    lo, hi = 2, 2
    while sigma_mu_relative_se(hi, kurtosis) > r:
        lo, hi = hi, hi * 2
        if hi > max_scans * w:
            raise AnalysisError(
                f"a relative precision of {r:g} of sigma_mu needs more than {max_scans} scans "
                f"of {w} window(s) each (kurtosis {kurtosis:g})"
            )
    while lo < hi:  # smallest n with se(n) <= r (se decreasing in n)
        mid = (lo + hi) // 2
        if sigma_mu_relative_se(mid, kurtosis) <= r:
            hi = mid
        else:
            lo = mid + 1
    n = hi
    scans = max(-(-n // w), 1)
    if scans * w < 2:
        scans = 2
    achieved = sigma_mu_relative_se(scans * w, kurtosis)
    assumption = (
        f"{scans * w} independent windows ({w} per scan: disjoint, several correlation lengths wide) of one "
        f"surface; relative SE of sigma_mu = sqrt((kappa - (n-3)/(n-1))/(4n)) with kappa = {float(kurtosis):g}"
    )
    s = None if sigma_mu is None else float(sigma_mu)
    return ScansNeeded(scans=scans, windows=scans * w, windows_per_scan=w, rel_precision=r, relative_se=achieved,
                       kurtosis=float(kurtosis), sigma_mu=s, sigma_mu_se=None if s is None else achieved * s,
                       assumption=assumption)  # fmt: skip


# --------------------------------------------------------------------------------------------------
# Pixel sizes and summits
# --------------------------------------------------------------------------------------------------


def on_common_pixel_size(surfaces: Sequence[Surface], rtol: float = POOL_PIXEL_RTOL) -> list[Surface]:
    """The scans with one pixel size, without interpolation
    (:func:`stochfric.surface.scans.relabel_to_mean_pixel_size`, as ``pool_scans`` does);
    :class:`AnalysisError` when their pixel sizes do not agree within ``rtol``."""
    spacings = [s.grid_spacing_m for s in surfaces]
    if not pixel_sizes_agree(spacings, rtol):
        sx, sy = pixel_size_spread(spacings)
        raise AnalysisError(
            f"the scans' pixel sizes differ by {sx:.3%} (x) and {sy:.3%} (y), more than {rtol:.3%}: resample "
            "them to one pixel size or measure them alike"
        )
    return relabel_to_mean_pixel_size(surfaces)


def require_summits_for_pooling(
    summit_counts: Sequence[int],
    *,
    names: Sequence[str] | None = None,
    resampled_to_m: tuple[float, float] | None = None,
    min_summits: int = MIN_SUMMITS_PER_SCAN,
) -> None:
    """Refuse (:class:`AnalysisError`) scans with fewer than ``min_summits`` summits (after resampling to
    ``resampled_to_m`` where given): they cannot be tested against the other scans, so they cannot be
    pooled.  The message says what to do instead."""
    counts = [int(c) for c in summit_counts]
    labels = list(names) if names is not None else [f"scan {i + 1}" for i in range(len(counts))]
    if len(labels) != len(counts):
        raise AnalysisError(f"{len(labels)} names for {len(counts)} summit counts")
    poor = [(n, c) for n, c in zip(labels, counts, strict=True) if c < min_summits]
    if not poor:
        return
    listing = ", ".join(f"{n}: {c}" for n, c in poor)
    where = (
        f" after resampling to {resampled_to_m[0] * 1e6:.4g} x {resampled_to_m[1] * 1e6:.4g} um pixels"
        if resampled_to_m is not None
        else ""
    )
    raise AnalysisError(
        f"pooling needs at least {min_summits} summits per scan ({MIN_WINDOWS_PER_SCAN} windows of "
        f"{WINDOW_MIN_SUMMITS} summits, so that the scans can be tested for being one surface); {listing}"
        f"{where}. Scans are never reduced to a handful of summits to make them poolable: pool scans of one "
        f"pixel size (within {POOL_PIXEL_RTOL:.1%}) without resampling, measure the scans alike (same pixel "
        "size, larger scan areas), or analyse each scan on its own"
    )


def check_resampling_keeps_summits(
    surfaces: Sequence[Surface],
    spacing_m: tuple[float, float],
    *,
    names: Sequence[str] | None = None,
    rule: str = DEFAULT_SUMMIT_RULE,
    min_summits: int = MIN_SUMMITS_PER_SCAN,
) -> list[int]:
    """The summit counts of ``surfaces`` resampled to pixels of ``spacing_m`` (as ``pool_scans(...,
    resample=True)`` would, :func:`~stochfric.surface.grid.resample_surface`); refuses
    (:func:`require_summits_for_pooling`) when one keeps fewer than ``min_summits``."""
    counts = []
    for s in surfaces:
        r = s if np.allclose(s.grid_spacing_m, spacing_m, rtol=1e-9, atol=0.0) else resample_surface(s, spacing_m)
        counts.append(find_summits(r.heights_m, r.grid_spacing_m, rule=rule).count)
    require_summits_for_pooling(counts, names=names if names is not None else [str(s.source) for s in surfaces],
                                resampled_to_m=(float(spacing_m[0]), float(spacing_m[1])),
                                min_summits=min_summits)  # fmt: skip
    return counts

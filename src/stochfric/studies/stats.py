"""Estimators with uncertainty for the studies (method §6: "give their uncertainty").

* :func:`clopper_pearson` — exact binomial interval for a probability (stick-slip
  probability at a damping ratio, §6.2), from the beta distribution; :func:`wilson` — the
  Wilson score interval (reference only: it can undercover at small n·p).
* :func:`risk_limit` — D_max(α), the largest grid D at which P(stick-slip) ≥ α, with the
  interval read off the per-D Clopper–Pearson bands.
* :func:`sample_summary` — E[X_gh], σ(X_gh) and VarK = |σ|/|E| (eq. 4.40) with standard
  errors, both the closed forms for independent samples and a bootstrap over *runs*
  (the X_gh of one run are correlated, so the run is the independent unit).
"""

from __future__ import annotations

import math
import warnings
from dataclasses import asdict, dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.stats import beta, norm

from stochfric.errors import InputError


def clopper_pearson(k: npt.ArrayLike, n: npt.ArrayLike, confidence: float = 0.95) -> tuple[
        npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Two-sided Clopper–Pearson interval for a binomial probability (k successes in n).

    lower = B(α/2; k, n − k + 1) (0 for k = 0), upper = B(1 − α/2; k + 1, n − k) (1 for
    k = n), α = 1 − confidence.  Closed forms: k = 0 → upper = 1 − (α/2)^{1/n}.
    """
    if not 0.0 < confidence < 1.0:
        raise InputError(f"confidence must be in (0, 1), got {confidence}")
    kk = np.asarray(k, dtype=float)
    nn = np.asarray(n, dtype=float)
    a = 1.0 - confidence
    with np.errstate(invalid="ignore", divide="ignore"):
        lo = np.where(kk > 0, beta.ppf(a / 2, np.maximum(kk, 1e-300), nn - kk + 1), 0.0)
        hi = np.where(kk < nn, beta.ppf(1 - a / 2, kk + 1, np.maximum(nn - kk, 1e-300)), 1.0)
    bad = ~(nn > 0)
    lo = np.where(bad, np.nan, lo)
    hi = np.where(bad, np.nan, hi)
    return np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)


def wilson(k: npt.ArrayLike, n: npt.ArrayLike, confidence: float = 0.95) -> tuple[
        npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Wilson score interval: (p̂ + z²/2n ± z √(p̂(1 − p̂)/n + z²/4n²)) / (1 + z²/n), z = Φ⁻¹((1 + c)/2)."""
    if not 0.0 < confidence < 1.0:
        raise InputError(f"confidence must be in (0, 1), got {confidence}")
    kk = np.asarray(k, dtype=float)
    nn = np.asarray(n, dtype=float)
    z = float(norm.ppf(0.5 + confidence / 2))
    with np.errstate(invalid="ignore", divide="ignore"):
        p = kk / nn
        centre = (p + z * z / (2 * nn)) / (1 + z * z / nn)
        half = z * np.sqrt(p * (1 - p) / nn + z * z / (4 * nn * nn)) / (1 + z * z / nn)
    bad = ~(nn > 0)
    lo = np.where(bad, np.nan, np.clip(centre - half, 0.0, 1.0))
    hi = np.where(bad, np.nan, np.clip(centre + half, 0.0, 1.0))
    return np.asarray(lo, dtype=float), np.asarray(hi, dtype=float)


def zero_count_upper_bound(n: int, confidence: float = 0.95) -> float:
    """One-sided upper bound on p after 0 successes in n trials: 1 − (1 − confidence)^{1/n}."""
    if n <= 0:
        return 1.0
    return 1.0 - (1.0 - confidence) ** (1.0 / n)


class _JsonRecord:
    """``to_dict`` of the result records below: their fields, NaN/inf as ``None``."""

    def to_dict(self) -> dict[str, Any]:
        return {k: (None if isinstance(v, float) and not math.isfinite(v) else v)
                for k, v in asdict(self).items()}  # type: ignore[call-overload]


@dataclass(frozen=True)
class SampleSummary(_JsonRecord):
    """E, σ (ddof 1), VarK = |σ|/|E| with standard errors; NaN where undefined."""

    n: int
    n_runs: int
    mean: float
    std: float
    vark: float
    se_mean_iid: float
    se_std_iid: float
    se_vark_iid: float
    se_mean_boot: float
    se_std_boot: float
    se_vark_boot: float


def _stats(x: npt.NDArray[np.float64]) -> tuple[float, float, float]:
    if x.size == 0:
        return math.nan, math.nan, math.nan
    m = float(np.mean(x))
    s = float(np.std(x, ddof=1)) if x.size > 1 else math.nan
    v = abs(s) / abs(m) if m != 0 and math.isfinite(s) else math.nan
    return m, s, v


def sample_summary(
    per_run: list[npt.NDArray[np.float64]], *, n_boot: int = 400, rng: np.random.Generator | None = None
) -> SampleSummary:
    """Pool the samples of all runs; SEs in closed form (iid) and by resampling runs.

    Closed forms for n independent samples: SE(E) = σ/√n, SE(σ) ≈ σ/√(2(n − 1)),
    SE(VarK) ≈ VarK √(1/(2(n − 1)) + VarK²/n) (delta method, normal data).
    """
    runs = [np.asarray(r, dtype=float)[np.isfinite(r)] for r in per_run]
    pooled = np.concatenate(runs) if runs else np.zeros(0)
    n = int(pooled.size)
    m, s, v = _stats(pooled)
    se_m = s / math.sqrt(n) if n > 1 else math.nan
    se_s = s / math.sqrt(2 * (n - 1)) if n > 1 else math.nan
    se_v = v * math.sqrt(1 / (2 * (n - 1)) + v * v / n) if n > 1 and math.isfinite(v) else math.nan
    bm = bs = bv = math.nan
    nonempty = [r for r in runs if r.size]
    if len(nonempty) > 1 and n_boot > 1:
        g = rng if rng is not None else np.random.default_rng(0)
        # replicate b picks runs idx[b] (the same draws, in the same order, as one `integers`
        # call per replicate); pooled moments from per-run sums, vectorised over replicates
        k = len(nonempty)
        idx = g.integers(0, k, size=(n_boot, k))
        s0 = np.array([r.size for r in nonempty], dtype=float)[idx].sum(axis=1)
        s1 = np.array([r.sum() for r in nonempty])[idx].sum(axis=1)
        shift = m  # moments about the pooled mean: no cancellation in the variance
        s2 = np.array([((r - shift) ** 2).sum() for r in nonempty])[idx].sum(axis=1)
        d1 = s1 / s0 - shift
        with np.errstate(invalid="ignore", divide="ignore"):
            ms = s1 / s0
            var = (s2 - s0 * d1 * d1) / (s0 - 1)
            ss = np.where(s0 > 1, np.sqrt(np.maximum(var, 0.0)), np.nan)
            vs = np.where(ms != 0, np.abs(ss) / np.abs(ms), np.nan)
        bm = float(np.nanstd(ms, ddof=1))
        bs = float(np.nanstd(ss, ddof=1))
        bv = float(np.nanstd(vs, ddof=1)) if np.sum(np.isfinite(vs)) > 1 else math.nan
    return SampleSummary(n=n, n_runs=len(nonempty), mean=m, std=s, vark=v, se_mean_iid=se_m, se_std_iid=se_s,
                         se_vark_iid=se_v, se_mean_boot=bm, se_std_boot=bs, se_vark_boot=bv)


@dataclass(frozen=True)
class RatioEstimate(_JsonRecord):
    """A ratio of two independent Monte Carlo estimates with its uncertainty.

    ``se_delta`` is the delta-method standard error r·√((SE_a/a)² + (SE_b/b)²) from the
    bootstrap-over-runs SEs of numerator and denominator; ``low``/``high`` the interval
    r·exp(±z·SE(log r*)) of :func:`ratio_interval`, SE from the bootstrap replicates of the ratio
    (numerator and denominator resampled independently, by runs, fixed seed).
    """

    value: float
    se_delta: float
    low: float
    high: float
    confidence: float


def ratio_interval(
    replicates: npt.ArrayLike, estimate: float, confidence: float = 0.95
) -> tuple[float, float]:
    """Interval of a positive ratio from its bootstrap replicates: r·exp(±z·SE(log r*)).

    Why not the percentile interval of the replicates: a σ resampled over few runs is biased
    low — a resample of n runs holds duplicates and keeps only about (n − 1)/n of the
    between-run variance — and more so for the contact model, whose X_gh scatter is mostly
    between runs (one process realisation per run), than for white noise.  So the replicates of
    σ contact/white sit below the estimate, and a percentile interval (worse still, of the
    median over many cells, whose replicates scatter little) can exclude its own estimate: with
    10 runs the forcing study printed 1.16 [0.97, 1.13].  The bootstrap is used here only for the
    *spread* (the standard deviation of log r*), and the interval is centred on the estimate on
    the log scale (a ratio is skewed).  Reference: coverage ≥ 0.85 for 20 iid runs, and the
    estimate inside its interval by construction (tests/statistical/test_studies_estimators.py).
    """
    b = np.asarray(replicates, dtype=float)
    b = b[np.isfinite(b) & (b > 0)]
    if b.size < 2 or not (math.isfinite(estimate) and estimate > 0):
        return math.nan, math.nan
    se_log = float(np.std(np.log(b), ddof=1))
    z = float(norm.ppf(0.5 + confidence / 2))
    return estimate * math.exp(-z * se_log), estimate * math.exp(z * se_log)


def _boot_std(runs: list[npt.NDArray[np.float64]], n_boot: int, g: np.random.Generator) -> npt.NDArray[np.float64]:
    """σ (ddof 1) of the pooled values of ``len(runs)`` runs drawn with replacement, per replicate.

    The same run draws, in the same order, as one ``integers`` call per replicate; moments from
    per-run sums about the pooled mean (vectorised over the replicates)."""
    out = np.full(n_boot, math.nan)
    if len(runs) < 2:
        return out
    k = len(runs)
    idx = g.integers(0, k, size=(n_boot, k))
    pooled = np.concatenate(runs)
    shift = float(pooled.mean()) if pooled.size else 0.0
    s0 = np.array([r.size for r in runs], dtype=float)[idx].sum(axis=1)
    s1 = np.array([(r - shift).sum() for r in runs])[idx].sum(axis=1)
    s2 = np.array([((r - shift) ** 2).sum() for r in runs])[idx].sum(axis=1)
    with np.errstate(invalid="ignore", divide="ignore"):
        var = (s2 - s1 * s1 / s0) / (s0 - 1)
    ok = s0 > 1
    out[ok] = np.sqrt(np.maximum(var[ok], 0.0))
    return out


def std_ratio(
    per_run_a: list[npt.NDArray[np.float64]],
    per_run_b: list[npt.NDArray[np.float64]],
    *,
    n_boot: int = 400,
    confidence: float = 0.95,
    rng: np.random.Generator | None = None,
) -> RatioEstimate:
    """σ_a/σ_b of two pooled samples (e.g. σ(X_gh) contact / white) with a bootstrap interval.

    The run is the independent unit (the X_gh of one run are correlated), so both samples are
    resampled by runs; NaN where a sample has fewer than two values.
    """
    ra = [np.asarray(r, dtype=float)[np.isfinite(r)] for r in per_run_a]
    rb = [np.asarray(r, dtype=float)[np.isfinite(r)] for r in per_run_b]
    ra = [r for r in ra if r.size]
    rb = [r for r in rb if r.size]
    xa = np.concatenate(ra) if ra else np.zeros(0)
    xb = np.concatenate(rb) if rb else np.zeros(0)
    if xa.size < 2 or xb.size < 2:
        return RatioEstimate(math.nan, math.nan, math.nan, math.nan, confidence)
    sa, sb = float(np.std(xa, ddof=1)), float(np.std(xb, ddof=1))
    r = sa / sb if sb > 0 else math.nan
    g = rng if rng is not None else np.random.default_rng(0)
    ba, bb = _boot_std(ra, n_boot, g), _boot_std(rb, n_boot, g)
    with np.errstate(invalid="ignore", divide="ignore"):
        br = ba / bb
    ok = np.isfinite(br)
    if np.sum(ok) < 2 or not math.isfinite(r):
        return RatioEstimate(r, math.nan, math.nan, math.nan, confidence)
    rel = math.sqrt((float(np.nanstd(ba, ddof=1)) / sa) ** 2 + (float(np.nanstd(bb, ddof=1)) / sb) ** 2)
    lo, hi = ratio_interval(br[ok], r, confidence)
    return RatioEstimate(r, r * rel, lo, hi, confidence)


def std_ratio_over_cells(
    cells_a: list[list[npt.NDArray[np.float64]]],
    cells_b: list[list[npt.NDArray[np.float64]]],
    *,
    n_boot: int = 200,
    confidence: float = 0.95,
    rng: np.random.Generator | None = None,
) -> tuple[list[RatioEstimate], RatioEstimate]:
    """σ_a/σ_b per cell (e.g. per η of the forcing study) and their median over the cells.

    ``cells_a[e]`` / ``cells_b[e]`` are the per-run samples of cell e.  Every cell is resampled by
    runs, independently for a and b; the median's interval comes from the same replicates (the
    median of the per-cell bootstrap ratios of each replicate), so it carries the uncertainty of
    every cell.  Cells with fewer than two values on either side are NaN and left out of the median.
    """
    g = rng if rng is not None else np.random.default_rng(0)
    per: list[RatioEstimate] = []
    reps = np.full((n_boot, len(cells_a)), math.nan)
    for e, (ca, cb) in enumerate(zip(cells_a, cells_b, strict=True)):
        ra = [r for r in (np.asarray(x, dtype=float)[np.isfinite(x)] for x in ca) if r.size]
        rb = [r for r in (np.asarray(x, dtype=float)[np.isfinite(x)] for x in cb) if r.size]
        xa = np.concatenate(ra) if ra else np.zeros(0)
        xb = np.concatenate(rb) if rb else np.zeros(0)
        if xa.size < 2 or xb.size < 2 or not np.std(xb) > 0:
            per.append(RatioEstimate(math.nan, math.nan, math.nan, math.nan, confidence))
            continue
        sa, sb = float(np.std(xa, ddof=1)), float(np.std(xb, ddof=1))
        ba, bb = _boot_std(ra, n_boot, g), _boot_std(rb, n_boot, g)
        with np.errstate(invalid="ignore", divide="ignore"):
            reps[:, e] = ba / bb
        ok = np.isfinite(reps[:, e])
        if np.sum(ok) < 2:
            per.append(RatioEstimate(sa / sb, math.nan, math.nan, math.nan, confidence))
            continue
        rel = math.sqrt((float(np.nanstd(ba, ddof=1)) / sa) ** 2 + (float(np.nanstd(bb, ddof=1)) / sb) ** 2)
        lo, hi = ratio_interval(reps[ok, e], sa / sb, confidence)
        per.append(RatioEstimate(sa / sb, sa / sb * rel, lo, hi, confidence))
    vals = np.array([p.value for p in per])
    if not np.isfinite(vals).any():
        return per, RatioEstimate(math.nan, math.nan, math.nan, math.nan, confidence)
    med = float(np.nanmedian(vals))
    use = np.isfinite(vals)
    with np.errstate(invalid="ignore"), warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)  # a replicate with no finite cell: NaN, dropped below
        bmed = np.nanmedian(np.where(np.isfinite(reps[:, use]), reps[:, use], np.nan), axis=1)
    bmed = bmed[np.isfinite(bmed)]
    if bmed.size < 2:
        return per, RatioEstimate(med, math.nan, math.nan, math.nan, confidence)
    lo, hi = ratio_interval(bmed, med, confidence)
    return per, RatioEstimate(med, float(np.std(bmed, ddof=1)), lo, hi, confidence)


def pooled_bootstrap_se(
    x: npt.NDArray[np.float64], *, n_boot: int = 200, rng: np.random.Generator | None = None
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:
    """Bootstrap-over-runs SEs of the pooled mean and σ (ddof 1), vectorised over leading axes.

    ``x[..., run, event]`` with NaN padding (as in the study arrays).  One set of run indices is
    drawn per replicate and shared by all cells (each cell's SE is still a plain bootstrap over
    its runs).  NaN where a cell has fewer than two runs with values or fewer than three values.
    """
    g = rng if rng is not None else np.random.default_rng(0)
    fin = np.isfinite(x)
    xs = np.where(fin, x, 0.0)
    s1 = xs.sum(axis=-1)
    s2 = (xs * xs).sum(axis=-1)
    cnt = fin.sum(axis=-1).astype(float)
    nr = x.shape[-2]
    idx = g.integers(0, nr, size=(n_boot, nr))
    b1 = s1[..., idx].sum(axis=-1)  # [..., boot]
    b2 = s2[..., idx].sum(axis=-1)
    bn = cnt[..., idx].sum(axis=-1)
    with np.errstate(invalid="ignore", divide="ignore"):
        mean = b1 / bn
        var = (b2 - bn * mean * mean) / (bn - 1)
        sd = np.sqrt(np.where(var > 0, var, 0.0))
        mean = np.where(bn > 0, mean, np.nan)
        sd = np.where(bn > 1, sd, np.nan)
    ok_cell = (np.sum(cnt > 0, axis=-1) >= 2) & (cnt.sum(axis=-1) >= 3)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        se_m = np.nanstd(mean, axis=-1, ddof=1)
        se_s = np.nanstd(sd, axis=-1, ddof=1)
    return np.where(ok_cell, se_m, np.nan), np.where(ok_cell, se_s, np.nan)


@dataclass(frozen=True)
class RiskLimit(_JsonRecord):
    """D_max(α) on a D grid with its interval (:func:`risk_limit`); NaN = below the grid start.

    ``value``: the largest grid D with k/n ≥ α.  ``low``: the largest grid D whose Clopper–Pearson
    lower bound is ≥ α (P ≥ α there, with confidence; NaN: no grid D is confidently at risk α).
    ``high``: the largest grid D whose upper bound is ≥ α (every grid D above it has P < α, with
    confidence).  ``high_open``: ``high`` is the grid end, so D_max(α) may lie at or beyond it.
    ``resolved``: n runs can resolve α at all — the upper bound after 0 of n, 1 − ((1 − c)/2)^{1/n},
    is below α; if not, ``high`` is the grid end at every D with k = 0 (the runs cannot exclude P ≥ α).
    n is the fewest runs of a grid D above ``low`` (the D that decide ``high``; all D when ``low`` is NaN),
    which matters where the runs differ between grid D (adaptive refinement, :mod:`~stochfric.studies.refine`);
    ``low`` at the grid end leaves no D above it and is resolved (P ≥ α there with confidence: the grid, not
    the runs, keeps the upper end open).  ``n_runs``: the fewest runs of any grid D.
    """

    risk_level: float
    value: float
    low: float
    high: float
    high_open: bool
    resolved: bool
    n_runs: int
    confidence: float


def risk_limit(damping: npt.ArrayLike, k: npt.ArrayLike, n: npt.ArrayLike, risk_level: float,
               confidence: float = 0.95) -> RiskLimit:
    """D_max(α) = the largest grid D with P(stick-slip | D) ≥ α, and an interval for it.

    ``k[j]`` of ``n`` (or ``n[j]``) runs stick at ``damping[j]`` (increasing).  Per D the two-sided
    Clopper–Pearson interval at ``confidence`` (:func:`clopper_pearson`), each end a one-sided
    bound at (1 + c)/2.  The true D_max(α) (on the grid) lies in [``low``, ``high``]:

    * ``high`` is wrong only if the upper bound at the true D_max(α) itself falls below α — one grid
      point, probability ≤ (1 − c)/2;
    * ``low`` is wrong only if the lower bound is ≥ α at some grid D above the true D_max(α), where
      P < α — each such D with probability ≤ (1 − c)/2, in practice only the one or two D just above,
      where P is close to α (joint coverage measured in tests/statistical/test_risk_limit_coverage.py).

    No assumption on the shape of P(D) and none on independence across D (the damping study uses the
    same noise at every D): only the runs at one D must be independent.
    """
    if not 0.0 < risk_level < 1.0:
        raise InputError(f"risk level must be in (0, 1), got {risk_level}")
    d = np.asarray(damping, dtype=float)
    kk = np.asarray(k, dtype=float)
    nn = np.broadcast_to(np.asarray(n, dtype=float), kk.shape)
    ok = nn > 0
    lo, hi = clopper_pearson(kk, np.where(ok, nn, 1.0), confidence)
    lo, hi = np.where(ok, lo, np.nan), np.where(ok, hi, np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        p = np.where(ok, kk / np.where(ok, nn, 1.0), np.nan)

    def largest(mask: npt.NDArray[np.bool_]) -> float:
        return float(d[mask].max()) if mask.any() else math.nan

    n_min = int(nn[ok].min()) if ok.any() else 0
    low = largest(lo >= risk_level)
    above = ok & (d > low + 1e-12) if math.isfinite(low) else ok
    if math.isfinite(low) and not above.any():  # low is the grid end: P ≥ α there with confidence, nothing above
        resolved = True
    else:  # the cells that decide the upper end
        n_ref = int(nn[above].min()) if above.any() else n_min
        resolved = n_ref > 0 and 1.0 - ((1.0 - confidence) / 2) ** (1.0 / n_ref) < risk_level
    high = largest(hi >= risk_level)
    return RiskLimit(risk_level=float(risk_level), value=largest(p >= risk_level), low=low,
                     high=high, high_open=bool(math.isfinite(high) and d.size > 0 and high >= d.max() - 1e-12),
                     resolved=bool(resolved), n_runs=n_min, confidence=float(confidence))


def runs_to_resolve(risk_level: float, confidence: float = 0.95) -> int:
    """The fewest runs n at which 0 sticking runs exclude P ≥ α: 1 − ((1 − c)/2)^{1/n} < α."""
    return math.floor(math.log((1.0 - confidence) / 2) / math.log(1.0 - risk_level)) + 1

"""How far a Monte Carlo estimate must stay from a limit before a check decides (issue 29 item 6).

A check compares estimates z₁ … z_m, each with a Monte Carlo standard error SE_i, against a limit, and may
look again after adding realisations (L looks at most).  A decision must not be one a different seed would
undo, so it is taken only when every estimate is k·SE_i away from the limit on its side:

    k = Φ⁻¹(1 − α / (m · L)),

a Bonferroni bound over the m quantities and L looks: for a quantity whose true value lies exactly on the
limit the chance that some look decides it on the wrong side is at most α/(m·L), and at most α for the whole
check (family-wise), :data:`FLIP_ALPHA` = 5 %.  The in-sample summit check uses it (before: k = 2), because
its bootstrap SE understates the seed-to-seed spread of its z (1.3× on al3d-1 at R = 640 over 10 seeds); the
held-out test keeps k = 2, where a reversal needs a 4-SE swing (docs/statistical_contact.md §0a).
"""

from __future__ import annotations

import math

import numpy as np
import numpy.typing as npt
from scipy import stats as sps

from stochfric.errors import AnalysisError

__all__ = [
    "FLIP_ALPHA",
    "SUMMIT_ALPHA",
    "critical_value",
    "decision_margin",
    "looks_within",
    "monte_carlo_draws_to_decide",
    "monte_carlo_rank_decision",
]

#: The largest probability that a decided verdict is one another seed would reverse (all quantities and
#: looks of one check together).
FLIP_ALPHA = 0.05


def decision_margin(quantities: int, looks: int = 1, alpha: float = FLIP_ALPHA) -> float:
    """k = Φ⁻¹(1 − α/(m·L)) [Monte Carlo standard errors] for ``quantities`` = m estimates and ``looks`` = L
    (module docstring).  m = 16, L = 1: 2.73; m = 16, L = 3: 3.08; m = 60, L = 3: 3.45."""
    m, n = int(quantities), int(looks)
    if m < 1 or n < 1 or not 0.0 < alpha < 1.0:
        raise AnalysisError(f"a decision margin needs >= 1 quantity and look and 0 < alpha < 1, got m = {quantities}, "
                            f"L = {looks}, alpha = {alpha}")
    return float(sps.norm.isf(alpha / (m * n)))


def looks_within(start: int, budget: int) -> int:
    """How many looks a check that doubles its realisations from ``start`` takes at most within ``budget``
    (1 when it cannot grow)."""
    s, b = int(start), int(budget)
    if s < 1:
        raise AnalysisError(f"a check needs at least 1 realisation to start with, got {start}")
    return 1 + max(0, math.floor(math.log2(max(b, s) / s) + 1e-12))


#: The family-wise false-alarm probability of the summit check's Monte Carlo test (all quantities and scans
#: together): a map that *is* a member of its surrogate ensemble is called not credible with probability ≤ 5 %.
SUMMIT_ALPHA = 0.05


def monte_carlo_rank_decision(exceed: int, realizations: int, alpha: float, looks: int = 1,
                              flip_alpha: float = FLIP_ALPHA) -> str:
    """The sequential decision of a Monte Carlo rank test (Barnard 1963; Besag & Clifford 1991).

    ``exceed`` = K of ``realizations`` = R null draws have a statistic at least as extreme as the data's.  The
    exact Monte Carlo p-value is (1 + K)/(R + 1); the p-value of infinitely many draws, p*, is estimated by
    K/R with a binomial error.  Decided ``"fail"`` when the one-sided Clopper–Pearson upper bound of p* at
    confidence 1 − ε lies below ``alpha`` (and (1 + K)/(R + 1) ≤ alpha, the exact test rejects), ``"pass"``
    when the lower bound lies above it, else ``"undecided"`` (more draws decide it).  ε = ``flip_alpha`` /
    ``looks``: over all looks the chance that a map whose p* lies exactly at ``alpha`` is decided on either
    side is at most ``flip_alpha`` — one statistic, so no Bonferroni factor over quantities."""
    k, r, n = int(exceed), int(realizations), int(looks)
    if r < 1 or not 0 <= k <= r or n < 1 or not 0.0 < alpha < 1.0:
        raise AnalysisError(f"a Monte Carlo decision needs 0 <= K <= R, R >= 1, looks >= 1 and 0 < alpha < 1, got "
                            f"K = {exceed}, R = {realizations}, looks = {looks}, alpha = {alpha}")
    eps = float(flip_alpha) / n
    upper = 1.0 if k >= r else float(sps.beta.ppf(1.0 - eps, k + 1, r - k))
    lower = 0.0 if k <= 0 else float(sps.beta.ppf(eps, k, r - k + 1))
    if upper < alpha and (1.0 + k) / (r + 1.0) <= alpha:
        return "fail"
    if lower > alpha:
        return "pass"
    return "undecided"


def monte_carlo_draws_to_decide(exceed: int, realizations: int, alpha: float, looks: int = 1,
                                flip_alpha: float = FLIP_ALPHA) -> int | None:
    """About how many draws decide an undecided :func:`monte_carlo_rank_decision`: with p̂ = K/R the binomial
    bound is decided once z_ε √(p̂(1 − p̂)/R') < |p̂ − alpha|, R' = z_ε² p̂(1 − p̂)/(p̂ − alpha)² (at least the
    draws an exact test needs to reject at all, 1/alpha − 1), rounded up to R·2^j; None when p̂ is within
    0.1 alpha of alpha (on the limit: no affordable number decides it) or the decision is made."""
    k, r = int(exceed), int(realizations)
    if monte_carlo_rank_decision(k, r, alpha, looks, flip_alpha) != "undecided":
        return None
    p = max(k, 0.5) / r  # K = 0: half a count, so that the estimate is finite
    gap = abs(p - alpha)
    if gap < 0.1 * alpha:
        return None
    z = float(sps.norm.isf(float(flip_alpha) / int(looks)))
    need = max(z * z * p * (1.0 - p) / (gap * gap), 1.0 / alpha)
    return int(r * 2 ** max(1, math.ceil(math.log2(need / r)))) if need > r else 2 * r


def critical_value(t_null: npt.ArrayLike, alpha: float) -> float:
    """The largest-|z| critical value of the exact Monte Carlo test at ``alpha``: it rejects when (1 + K)/(R + 1)
    ≤ alpha, K = #(T_j ≥ T_map), i.e. when T_map exceeds the (k* + 1)-th largest T_j, k* = ⌊alpha (R + 1)⌋ − 1.
    With too few realisations to reject at all (alpha (R + 1) < 1) the largest T_j (the envelope)."""
    t = np.sort(np.asarray(t_null, dtype=np.float64))[::-1]
    k = math.floor(alpha * (t.size + 1) + 1e-9) - 1
    return float(t[max(k, 0)]) if t.size else math.inf

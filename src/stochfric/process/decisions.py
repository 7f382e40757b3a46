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

from scipy import stats as sps

from stochfric.errors import AnalysisError

__all__ = ["FLIP_ALPHA", "decision_margin", "looks_within"]

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

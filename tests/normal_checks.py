"""Shared statistical checks of a stream of standard normals (test helper).

Every bound is 4 standard errors of its estimator or a KS critical value at α = 1e-4, so with
fixed keys the checks are deterministic.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats


def assert_standard_normal(z: np.ndarray) -> None:
    """Mean, variance, skewness, kurtosis, the two-sided tail fractions beyond 1, 2 and 3, the
    sign balance and KS of ``z`` against N(0, 1); mean, variance and KS also for the even and
    odd entries separately (the two words of one Philox block)."""
    n = z.size
    assert abs(z.mean()) < 4 / math.sqrt(n)
    assert abs(z.var() - 1.0) < 4 * math.sqrt(2 / n)
    assert abs(stats.skew(z)) < 4 * math.sqrt(6 / n)
    assert abs(stats.kurtosis(z)) < 4 * math.sqrt(24 / n)
    assert abs(np.mean(z > 0) - 0.5) < 4 * 0.5 / math.sqrt(n)
    for c in (1.0, 2.0, 3.0):
        p = 2 * stats.norm.sf(c)
        frac = np.mean(np.abs(z) > c)
        assert abs(frac - p) < 4 * math.sqrt(p * (1 - p) / n), (c, frac, p)
    assert stats.kstest(z, "norm").statistic < stats.kstwo.ppf(1 - 1e-4, n)
    for part in (z[0::2], z[1::2]):
        assert abs(part.mean()) < 4 / math.sqrt(part.size)
        assert abs(part.var() - 1.0) < 4 * math.sqrt(2 / part.size)
        assert stats.kstest(part, "norm").statistic < stats.kstwo.ppf(1 - 1e-4, part.size)

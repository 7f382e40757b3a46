"""Statistical tier: the normals R_k of the in-kernel Box–Muller white-noise stream
(``white_stream="philox-boxmuller"``: Philox4x32-10 + Box–Muller, stochfric.random.philox)
at fixed keys.  The default stream's ziggurat normals: test_ziggurat_normals.py.

Every bound is a multiple of the estimator's own standard error (4 SE, or the KS critical
value at α = 1e-4), so with the fixed keys the tests are deterministic and a wrong
transform (a lost quadrant, a biased radius, correlated lanes) fails them.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from normal_checks import assert_standard_normal  # tests/normal_checks.py (test helper)
from stochfric.random import philox as P
from stochfric.random import ziggurat as Z

N = 400_000
KEY = np.uint64(0x5EED5EED12345678)


def _z() -> np.ndarray:
    return Z.step_normals(KEY, N, True)


def test_moments_tails_and_ks_of_one_stream() -> None:
    assert_standard_normal(_z())


def test_box_muller_angle_and_radius() -> None:
    z = _z()
    # the quadrant and octant structure of the angle: the angle 2π U2 of each pair is uniform
    ang = np.arctan2(z[1::2], z[0::2])
    u = (ang + np.pi) / (2 * np.pi)
    assert stats.kstest(u, "uniform").statistic < stats.kstwo.ppf(1 - 1e-4, u.size)
    # the radius² = −2 ln U1 is exponential with mean 2 (chi-square, 2 degrees of freedom)
    r2 = z[0::2] ** 2 + z[1::2] ** 2
    assert stats.kstest(r2, "chi2", args=(2,)).statistic < stats.kstwo.ppf(1 - 1e-4, r2.size)


def test_independence_between_steps() -> None:
    z = _z()
    n = z.size
    se = 1 / math.sqrt(n)
    for lag in (1, 2, 3, 64):
        rho = np.corrcoef(z[:-lag], z[lag:])[0, 1]
        assert abs(rho) < 4 * se, (lag, rho)
        # dependence that a linear correlation misses (e.g. between the two normals of a pair)
        rho2 = np.corrcoef(z[:-lag] ** 2, z[lag:] ** 2)[0, 1]
        assert abs(rho2) < 4 * se, (lag, rho2)


def test_independence_between_trajectories() -> None:
    """Lanes keyed by neighbouring spawn keys (runs r, r+1 of one root) and neighbouring raw
    keys: no correlation at the same step."""
    root = np.random.SeedSequence(2013)
    keys = P.trajectory_keys(root, np.column_stack([np.zeros(64, dtype=np.int64), np.arange(64)]))
    assert np.unique(keys).size == keys.size
    m = 4000
    zs = np.stack([Z.step_normals(k, m, True) for k in keys])
    c = np.corrcoef(zs)
    off = c[~np.eye(64, dtype=bool)]
    # 2016 pairs of independent series of length m: each ρ ~ N(0, 1/m); the largest |ρ| of
    # 2016 exceeds 5 SE with probability ≈ 1e-3, and their mean is ~ N(0, 1/(m · 2016))
    assert np.max(np.abs(off)) < 5 / math.sqrt(m)
    assert abs(off.mean()) < 4 / math.sqrt(m * off.size / 2)
    z2 = np.stack([Z.step_normals(np.uint64(k), m, True) for k in (1, 2, 3, 2**32, 2**32 + 1)])
    c2 = np.corrcoef(z2)[~np.eye(5, dtype=bool)]
    assert np.max(np.abs(c2)) < 5 / math.sqrt(m)

"""Statistical tier: the normals R_k of the default white-noise stream (Philox4x32-10 words
through the 1024-layer ziggurat, stochfric.random.ziggurat) at fixed keys.

Every bound is a multiple of the estimator's own standard error (4 SE) or a critical value at
α = 1e-4, so with the fixed keys the tests are deterministic.  The layer test is the one a
wrong table or a wrong slow path cannot pass: the counts of |R| in every layer's band
``[x_{i+1}, x_i)``, split at the band's middle so that the wedge part is checked on its own,
against the exact normal probabilities (2048 cells), plus the tail beyond ``r`` that only the
tail algorithm produces and the top band that only the wedge test produces.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats

from normal_checks import assert_standard_normal  # tests/normal_checks.py (test helper)
from stochfric.random import ziggurat as Z

N = 2_000_000
KEY = np.uint64(0x5EED5EED12345678)
X = np.array(Z._X_TABLE)


def _z() -> np.ndarray:
    return Z.step_normals(KEY, N)


def test_moments_tails_and_ks_of_one_stream() -> None:
    assert_standard_normal(_z())


def test_every_layer_band_and_its_wedge_half_have_the_normal_probability() -> None:
    z = np.abs(_z())
    n = z.size
    r = Z.ZIGGURAT_R
    # cells: [0, x_1023), then for i = 1022 … 1 the band [x_{i+1}, x_i) halved, then [r, ∞)
    inner = X[1:-1][::-1]  # x_1023 … x_1 = r, increasing
    mids = 0.5 * (inner[:-1] + inner[1:])
    edges = np.sort(np.concatenate([[0.0], inner, mids, [np.inf]]))
    counts = np.histogram(z, bins=edges)[0]
    p = 2.0 * np.diff(stats.norm.cdf(edges))
    p[-1] = 2.0 * stats.norm.sf(r)
    expected = n * p
    chi2 = float(np.sum((counts - expected) ** 2 / expected))
    assert chi2 < stats.chi2.ppf(1 - 1e-4, counts.size - 1), chi2
    # the tail beyond r (only the tail algorithm gives these) and the top band (only the wedge)
    for c, pc in ((counts[-1], p[-1]), (counts[0], p[0])):
        assert abs(c - n * pc) < 4 * math.sqrt(n * pc * (1 - pc)), (c, n * pc)
    # the shape of the tail: R − r given |R| > r against the normal tail
    t = z[z > r]
    u = stats.norm.sf(t) / stats.norm.sf(r)  # uniform on (0, 1) if the tail is right
    assert stats.kstest(u, "uniform").statistic < stats.kstwo.ppf(1 - 1e-4, t.size)


def test_independence_between_steps_and_keys() -> None:
    z = _z()
    n = z.size
    se = 1 / math.sqrt(n)
    for lag in (1, 2, 3, 64):
        assert abs(np.corrcoef(z[:-lag], z[lag:])[0, 1]) < 4 * se
    # |R| of the two words of one block (a slow draw of one continues on its own counters)
    a, b = np.abs(z[0::2]), np.abs(z[1::2])
    assert abs(np.corrcoef(a, b)[0, 1]) < 4 / math.sqrt(a.size)
    m = 200_000
    keys = [np.uint64(k) for k in (1, 2, 3, 2**32, 2**32 + 1, int(KEY) + 1)]
    zs = np.stack([Z.step_normals(k, m) for k in keys])
    c = np.corrcoef(zs)
    off = c[~np.eye(len(keys), dtype=bool)]
    assert np.abs(off).max() < 4 / math.sqrt(m)


def test_the_tail_algorithm_gives_the_normal_tail() -> None:
    """A first draw in layer 0 beyond ``r`` (``u ≥ k_0``) goes to the tail algorithm, whose output
    must be distributed as R given |R| > r: 20,000 such draws (random keys and pairs) against
    the normal tail by KS, and their sign is the draw's sign bit."""
    rng = np.random.default_rng(20261124)
    m = 20_000
    k0 = int(Z._KI[0])
    u = rng.integers(k0, 2**53, m, dtype=np.uint64)
    neg = rng.integers(0, 2, m, dtype=np.uint64)
    words = (u << np.uint64(11)) | (neg << np.uint64(10))  # layer 0
    keys = rng.integers(0, 2**64, m, dtype=np.uint64, endpoint=False)
    pairs = rng.integers(0, 2**40, m, dtype=np.uint64)
    t = np.array([Z.ziggurat_slow(keys[j], pairs[j], np.uint64(j & 1), words[j]) for j in range(m)])
    assert np.array_equal(t < 0, neg == 1)
    a = np.abs(t)
    assert (a > Z.ZIGGURAT_R).all()
    uu = stats.norm.sf(a) / stats.norm.sf(Z.ZIGGURAT_R)
    assert stats.kstest(uu, "uniform").statistic < stats.kstwo.ppf(1 - 1e-4, m)

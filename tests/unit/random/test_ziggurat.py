"""The ziggurat normals of the default white-noise stream (stochfric.random.ziggurat).

Tables: the committed file is exactly :func:`compute_tables`' output; the 256-layer root equals
the published value (Marsaglia & Tsang 2000, numpy's ``ziggurat_nor_r``); every layer has the
area ``v``, and ``v`` is the base strip plus the normal tail computed independently with scipy's
``erfc``.  Draws: the fast path is the textbook ``±u x_i 2⁻⁵³`` with acceptance exactly
``x < x_{i+1}``; the slow path returns tail values beyond ``r`` from layer 0 and values below the
layer's abscissa elsewhere; the lane-parallel fill equals the scalar pair for every lane.
Distribution tests are in tests/statistical/test_ziggurat_normals.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import special

from stochfric.random import philox as P
from stochfric.random import ziggurat as Z

X = np.array(Z._X_TABLE)
F = np.array(Z._F_TABLE)
N = Z.ZIGGURAT_LAYERS


def test_committed_tables_are_the_generators_output() -> None:
    r, v, x, fx = Z.compute_tables()
    assert r == Z.ZIGGURAT_R and v == Z.ZIGGURAT_V
    assert x == list(Z._X_TABLE) and fx == list(Z._F_TABLE)


def test_256_layer_root_is_the_published_value() -> None:
    r, _, x, _ = Z.compute_tables(256)
    assert r == pytest.approx(Z.PUBLISHED_R_256, abs=4.5e-16)  # 1 ulp of 3.65
    assert len(x) == 257 and x[1] == r and x[-1] == 0.0


def test_layers_have_equal_area_and_the_base_holds_the_tail() -> None:
    r, v = Z.ZIGGURAT_R, Z.ZIGGURAT_V
    assert len(X) == N + 1 and X[1] == r and X[-1] == 0.0 and F[-1] == 1.0
    # f(x_i) of the decimal x_i vs exp of the rounded x_i: relative error ≲ (1 + x_i²) ulp
    np.testing.assert_allclose(F, np.exp(-0.5 * X * X), rtol=1e-14, atol=0)
    # layers 1 … N−1: x_i (f(x_{i+1}) − f(x_i)) = v; the top layer closes at f = 1
    np.testing.assert_allclose(X[1:N] * (F[2:] - F[1:N]), v, rtol=2e-12)
    # base: r f(r) + ∫_r^∞ f = v = x_0 f(r), the tail from scipy (independent of the decimal code)
    tail = math.sqrt(math.pi / 2) * special.erfc(r / math.sqrt(2))
    assert r * math.exp(-0.5 * r * r) + tail == pytest.approx(v, rel=1e-14)
    assert X[0] * F[1] == pytest.approx(v, rel=1e-15)
    # N layers of area v cover the half-normal area √(π/2) and a little more (0.2 % overhead)
    assert 1.0 < N * v / math.sqrt(math.pi / 2) < 1.0025


def test_fast_path_threshold_is_exact() -> None:
    """k_i is the least integer with float(k_i)·w_i ≥ x_{i+1}: accepting u < k_i is accepting
    exactly the products below the next layer's abscissa."""
    wi, ki = Z._WI, Z._KI
    np.testing.assert_array_equal(wi, X[:N] * 2.0**-53)
    for i in range(N):
        k = int(ki[i])
        assert float(k) * wi[i] >= X[i + 1]
        assert k == 0 or float(k - 1) * wi[i] < X[i + 1]
    assert ki[N - 1] == 0  # the top layer always takes the wedge test


def _fast(words: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    idx = (words & np.uint64(N - 1)).astype(np.int64)
    neg = ((words >> np.uint64(10)) & np.uint64(1)).astype(bool)
    u = (words >> np.uint64(11)).astype(np.float64)
    x = u * Z._WI[idx]
    return np.where(neg, -x, x), x < X[idx + 1]


def test_pairs_follow_the_textbook_fast_path_and_the_slow_path_stays_in_its_region() -> None:
    key = np.uint64(0xC0FFEE1234567890)
    npairs = 60_000
    z = Z.step_normals(key, 2 * npairs)
    words = np.empty(2 * npairs, dtype=np.uint64)
    k0, k1 = int(key) & 0xFFFFFFFF, int(key) >> 32
    for p in range(npairs):
        o = P.philox4x32_10_array(np.array([p, 0, 0, 0], dtype=np.uint64), np.array([k0, k1], dtype=np.uint64))
        words[2 * p] = (int(o[1]) << 32) | int(o[0])
        words[2 * p + 1] = (int(o[3]) << 32) | int(o[2])
    zf, ok = _fast(words)
    np.testing.assert_array_equal(z[ok], zf[ok])
    frac_slow = 1.0 - ok.mean()
    expected = 1.0 - float(np.mean(Z._KI.astype(np.float64) * 2.0**-53))  # 0.43 %
    assert abs(frac_slow - expected) < 4 * math.sqrt(expected / ok.size)
    slow = ~ok
    assert np.isfinite(z[slow]).all()
    idx = (words & np.uint64(N - 1)).astype(np.int64)
    tail_words = slow & (idx == 0)
    assert tail_words.sum() > 0
    # layer 0 rejected ⇒ u x_0 2⁻⁵³ ≥ r ⇒ the tail algorithm: |z| > r, same sign as the word
    assert (np.abs(z[tail_words]) > Z.ZIGGURAT_R).all()
    assert np.array_equal(np.signbit(z[tail_words]), np.signbit(zf[tail_words]))


def test_lane_parallel_fill_equals_the_scalar_pairs() -> None:
    keys = np.concatenate([np.arange(64, dtype=np.uint64) * np.uint64(0x9E3779B97F4A7C15),
                           np.array([0, 2**64 - 1], dtype=np.uint64)])
    n = keys.size
    wk, zo = np.empty(n), np.empty(n)
    miss = np.zeros((2, n), dtype=np.uint64)
    sq = 0.07
    nslow = 0
    for p in range(3000):
        pair = np.uint64(p)
        m = Z.fill_pair_ziggurat(keys, pair, sq, wk, zo, miss)
        nslow += m
        assert m == int(np.count_nonzero(miss))
        if m:
            Z.finish_pair_ziggurat(keys, pair, sq, wk, zo, miss)
        for j in (0, 1, 17, 63, 64, 65):
            a, b = Z.pair_normals_ziggurat(keys[j], pair)
            assert wk[j] == a * sq and zo[j] == b * sq
        if m:
            for j in np.nonzero(miss.any(axis=0))[0]:
                a, b = Z.pair_normals_ziggurat(keys[j], pair)
                assert wk[j] == a * sq and zo[j] == b * sq
    assert nslow > 1000  # the slow path was exercised (0.43 % of 396,000 draws)


def test_step_normals_are_a_prefix_stream() -> None:
    key = np.uint64(0x0123456789ABCDEF)
    z = Z.step_normals(key, 7)
    np.testing.assert_array_equal(Z.step_normals(key, 5000)[:7], z)
    a, _ = Z.pair_normals_ziggurat(key, np.uint64(3))
    assert z[6] == a  # step 6 is the first normal of pair 3

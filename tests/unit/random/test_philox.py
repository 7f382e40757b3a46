"""The counter-based generator of the white-noise kernels (stochfric.random.philox).

Philox4x32-10 (the kernels') and Philox4x64-10 against the known-answer vectors of their
published specification (Random123, ``tests/kat_vectors``), the 4x64 variant also bit for bit
against numpy's independent ``Philox``; the branch-free elementary functions against the C library; the
Box–Muller transform against its textbook formula; the compiled SeedSequence hash against
numpy's; and the kernel's in-place draws against the same numbers given as increments.
Moments, KS and independence of the normals are in tests/statistical/test_philox_normals.py.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from philox64 import philox4x64_10_array  # tests/unit/random/philox64.py (test helper)

from kernel_helpers import run_fixed_step  # tests/kernel_helpers.py (test helper)
from stochfric.oscillator import kernels as K
from stochfric.oscillator.friction_laws import law_III
from stochfric.oscillator.integrate import simulate, trajectory_seed
from stochfric.oscillator.options import IntegrationOptions, NoiseOptions, OutputOptions
from stochfric.oscillator.parameters import OscillatorParameters, ParameterError
from stochfric.random import philox as P
from stochfric.random import ziggurat as Z

#: Random123 tests/kat_vectors, the three "philox4x32 10" lines: counter[4], key[2], result[4].
KAT_PHILOX4X32_10 = [
    ((0x00000000, 0x00000000, 0x00000000, 0x00000000), (0x00000000, 0x00000000),
     (0x6627E8D5, 0xE169C58D, 0xBC57AC4C, 0x9B00DBD8)),
    ((0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF, 0xFFFFFFFF), (0xFFFFFFFF, 0xFFFFFFFF),
     (0x408F276D, 0x41C83B0E, 0xA20BC7C6, 0x6D5451FD)),
    ((0x243F6A88, 0x85A308D3, 0x13198A2E, 0x03707344), (0xA4093822, 0x299F31D0),
     (0xD16CFE09, 0x94FDCCEB, 0x5001E420, 0x24126EA1)),
]


@pytest.mark.parametrize(("ctr", "key", "expected"), KAT_PHILOX4X32_10)
def test_philox4x32_10_known_answers(ctr: tuple[int, ...], key: tuple[int, ...],
                                     expected: tuple[int, ...]) -> None:
    out = P.philox4x32_10_array(np.array(ctr, dtype=np.uint64), np.array(key, dtype=np.uint64))
    assert [int(v) for v in out] == list(expected)


#: Random123 tests/kat_vectors, the three "philox4x64 10" lines.
KAT_PHILOX4X64_10 = [
    ((0, 0, 0, 0), (0, 0),
     (0x16554D9ECA36314C, 0xDB20FE9D672D0FDC, 0xD7E772CEE186176B, 0x7E68B68AEC7BA23B)),
    ((2**64 - 1,) * 4, (2**64 - 1,) * 2,
     (0x87B092C3013FE90B, 0x438C3C67BE8D0224, 0x9CC7D7C69CD777B6, 0xA09CAEBF594F0BA0)),
    ((0x243F6A8885A308D3, 0x13198A2E03707344, 0xA4093822299F31D0, 0x082EFA98EC4E6C89),
     (0x452821E638D01377, 0xBE5466CF34E90C6C),
     (0xA528F45403E61D95, 0x38C72DBD566E9788, 0xA5A1610E72FD18B5, 0x57BD43B5E52B7FE6)),
]


@pytest.mark.parametrize(("ctr", "key", "expected"), KAT_PHILOX4X64_10)
def test_philox4x64_10_known_answers(ctr: tuple[int, ...], key: tuple[int, ...],
                                     expected: tuple[int, ...]) -> None:
    out = philox4x64_10_array(np.array(ctr, dtype=np.uint64), np.array(key, dtype=np.uint64))
    assert [int(v) for v in out] == list(expected)


def test_philox4x64_10_equals_numpys_independent_implementation() -> None:
    """numpy's ``Philox`` (4x64-10) increments its 256-bit counter, then encrypts: its n-th block
    is philox(counter + n).  The round structure shared with the kernels' 4x32 variant is thereby
    checked against an implementation that is not ours."""
    rng = np.random.default_rng(11)
    for _ in range(20):
        c = rng.integers(0, 2**64, 4, dtype=np.uint64, endpoint=False)
        k = rng.integers(0, 2**64, 2, dtype=np.uint64, endpoint=False)
        c[0] = np.uint64(2**64 - 3)  # the increment carries into word 1 after three blocks
        raw = np.random.Philox(counter=c, key=k).random_raw(20)
        for n in range(1, 6):
            total = sum(int(w) << (64 * i) for i, w in enumerate(c)) + n
            cn = np.array([(total >> (64 * i)) & (2**64 - 1) for i in range(4)], dtype=np.uint64)
            np.testing.assert_array_equal(raw[4 * (n - 1): 4 * n], philox4x64_10_array(cn, k))


def _ulps(got: np.ndarray, ref: np.ndarray) -> np.ndarray:
    return np.abs(got - ref) / np.spacing(np.abs(ref))


def test_elementary_functions_agree_with_the_c_library_to_one_ulp() -> None:
    rng = np.random.default_rng(5)
    # log on (0, 1]: uniform and log-uniform down to 2^-53 (the smallest U1 of Box–Muller)
    u = np.concatenate([rng.uniform(0.0, 1.0, 200_000), np.exp2(-rng.uniform(0, 53, 200_000)),
                        [2.0**-53, 0.5, math.sqrt(0.5), 1.0 - 2.0**-53]])
    ref = np.log(u)
    got = P.elementary_array(u, 0)
    assert got[-1] != 0.0 and P.elementary_array(np.array([1.0]), 0)[0] == 0.0
    assert _ulps(got, ref).max() <= 1.0
    x = np.concatenate([rng.uniform(-math.pi / 4, math.pi / 4, 200_000), [0.0, math.pi / 4, -math.pi / 4]])
    for which, fn in ((1, np.sin), (2, np.cos)):
        ref = fn(x)
        got = P.elementary_array(x, which)
        nz = ref != 0.0
        assert _ulps(got[nz], ref[nz]).max() <= 1.0
        assert np.all(got[~nz] == 0.0)


def test_box_muller_is_the_textbook_transform_in_every_quadrant() -> None:
    rng = np.random.default_rng(6)
    w0 = rng.integers(0, 2**64, 100_000, dtype=np.uint64, endpoint=False)
    w1 = rng.integers(0, 2**64, 100_000, dtype=np.uint64, endpoint=False)
    # angles at and next to the quarter-turn boundaries of the exact integer reduction
    edges = np.array([(q << 62) + d for q in range(4) for d in (-(1 << 11), 0, 1 << 11)
                      if 0 <= (q << 62) + d < 2**64], dtype=np.uint64)
    w1 = np.concatenate([w1, edges, np.array([2**64 - 1], dtype=np.uint64)])
    w0 = np.concatenate([w0, np.full(edges.size + 1, 2**63, dtype=np.uint64)])
    z0, z1 = P.box_muller_array(w0, w1)
    u1 = ((w0 >> np.uint64(11)).astype(np.float64) + 1.0) * 2.0**-53
    u2 = (w1 >> np.uint64(11)).astype(np.float64) * 2.0**-53
    r = np.sqrt(-2.0 * np.log(u1))
    np.testing.assert_allclose(z0, r * np.cos(2 * np.pi * u2), rtol=0, atol=1e-14 * (1 + r.max()))
    np.testing.assert_allclose(z1, r * np.sin(2 * np.pi * u2), rtol=0, atol=1e-14 * (1 + r.max()))
    # extremes: U1 = 2^-53 gives the largest radius √(106 ln 2), U1 = 1 gives 0
    zmax, _ = P.box_muller_array(np.zeros(1, dtype=np.uint64), np.zeros(1, dtype=np.uint64))
    assert zmax[0] == pytest.approx(math.sqrt(106 * math.log(2)), rel=1e-15)
    zmin, _ = P.box_muller_array(np.full(1, 2**64 - 1, dtype=np.uint64), np.zeros(1, dtype=np.uint64))
    assert zmin[0] == 0.0


def test_step_normals_are_philox_blocks_through_box_muller() -> None:
    key = np.uint64(0x0123456789ABCDEF)
    z = Z.step_normals(key, 7, True)
    for p in range(4):
        o = P.philox4x32_10_array(np.array([p, 0, 0, 0], dtype=np.uint64),
                                  np.array([int(key) & 0xFFFFFFFF, int(key) >> 32], dtype=np.uint64))
        w0 = np.array([(int(o[1]) << 32) | int(o[0])], dtype=np.uint64)
        w1 = np.array([(int(o[3]) << 32) | int(o[2])], dtype=np.uint64)
        a, b = P.box_muller_array(w0, w1)
        assert z[2 * p] == a[0]
        if 2 * p + 1 < 7:
            assert z[2 * p + 1] == b[0]
    # a prefix of a longer stream: the numbers of step k do not depend on how many are drawn
    np.testing.assert_array_equal(Z.step_normals(key, 1000, True)[:7], z)


@pytest.mark.parametrize("root", [
    np.random.SeedSequence(1), np.random.SeedSequence(0), np.random.SeedSequence(2**100 + 7),
    np.random.SeedSequence(5, spawn_key=(3, 2**40)), np.random.SeedSequence(9, pool_size=8),
    np.random.SeedSequence([1, 2, 3]), np.random.SeedSequence(),
])
def test_compiled_seed_sequence_equals_numpy(root: np.random.SeedSequence) -> None:
    sets = np.array([0, 0, 1, 2, 7, 100_000, 0, 2**32 - 1])
    runs = np.array([0, 1, 0, 5, 3, 2, 2**31 + 5, 1])
    got = P.trajectory_keys(root, np.column_stack([sets, runs]))
    ref = [P.trajectory_key(trajectory_seed(root, (int(s),), int(r))) for s, r in zip(sets, runs, strict=True)]
    assert got.dtype == np.uint64
    assert [int(v) for v in got] == [int(v) for v in ref]
    # indices beyond 32 bits take numpy's own path
    big = P.trajectory_keys(root, [[2**33, 1]])
    assert int(big[0]) == int(P.trajectory_key(trajectory_seed(root, (2**33,), 1)))
    with pytest.raises(ValueError, match="non-negative"):
        P.trajectory_keys(root, [[-1, 0]])
    # longer tails (a study cell's two key words, the run, a process segment) hash like numpy too
    tails = np.array([[5, 2**32 - 1, 0, 0], [7, 3, 2, 9]])
    got4 = P.child_states(root, tails, 8)
    for row, want in zip(tails, got4, strict=True):
        assert want.tolist() == trajectory_seed(root, tuple(int(v) for v in row[:2]), int(row[2]), int(row[3])
                                                ).generate_state(8).tolist()


def _prm(sigma: float) -> np.ndarray:
    prm = np.zeros((1, K.N_PRM))
    prm[0, K.P_GAMMA0], prm[0, K.P_N], prm[0, K.P_VSCALE] = 1.0, 10.0, 1.0
    prm[0, K.P_MUS], prm[0, K.P_SIGMA], prm[0, K.P_PROC_DX] = 0.4, sigma, 1.0
    return prm


@pytest.mark.parametrize("source", ["ziggurat", "boxmuller"])
@pytest.mark.parametrize("scheme", [K.SCHEME_EULER, K.SCHEME_MILSTEIN])
def test_kernel_draws_equal_the_same_numbers_given_as_increments(scheme: int, source: str) -> None:
    """``WHITE_ZIGGURAT`` / ``WHITE_PHILOX`` draw R_k inside the kernel; giving ΔW_k = R_k √Δτ
    from :func:`ziggurat.step_normals` (``box_muller`` false / true) to the ``WHITE_GIVEN`` path must
    reproduce it bit for bit (odd and even step counts, so both halves of a Philox block are
    used at the end; 40 lanes, so two lock-step groups, and with the ziggurat ≈ 1000 draws that
    take its slow path in the middle of a group)."""
    law = law_III()
    dt = 0.005
    kernel_source, draw = ((K.WHITE_ZIGGURAT, Z.step_normals) if source == "ziggurat"
                           else (K.WHITE_PHILOX, lambda k, n: Z.step_normals(k, n, True)))
    for nsteps in (3001, 3000):
        keys = np.concatenate([np.array([0xDEADBEEF12345678, 7, 2**63 + 11], dtype=np.uint64),
                               np.arange(37, dtype=np.uint64) * np.uint64(0x9E3779B97F4A7C15)])
        n = keys.size
        prm = np.repeat(_prm(0.05), n, axis=0)
        shapes = np.full(n, law.shape, dtype=np.int64)
        lawp = np.tile(law.param_array, (n, 1))
        x0 = np.tile([0.0, 1.0], (n, 1))
        outs = []
        for src in (kernel_source, K.WHITE_GIVEN):
            if src == K.WHITE_GIVEN:
                dw = np.stack([draw(k, nsteps) for k in keys]) * math.sqrt(dt)
            else:
                dw = np.zeros((n, 1))
            xgh = np.full((n, 64), np.nan)
            traj = np.zeros((n, nsteps // 10 + 1, 3))
            diag = np.zeros((n, K.N_DIAG))
            counts = np.zeros(n, dtype=np.int64)
            K.run_fixed_step_batch(
                K.KernelRows(prm, shapes, lawp, x0, np.zeros((n, 1)), np.ones(n, dtype=np.int64)),
                K.KernelOutput(xgh, np.full((n, 64), np.nan), counts, traj, diag),
                K.FixedStepGrid(nsteps, dt, 10), scheme, K.NOISE_WHITE, K.PATH_MASS, K.WhiteInput(src, dw, keys))
            outs.append((xgh, traj, diag, counts))
        for a, b in zip(*outs, strict=True):
            np.testing.assert_array_equal(a, b)
        counts = outs[0][3]
        assert (counts > 0).mean() > 0.5, counts  # stick-slip cycles happened


def test_simulate_white_streams() -> None:
    """Default ``philox-ziggurat``: key of trajectory (i, r) = its spawned seed, normals by the
    ziggurat; ``philox-boxmuller`` the same blocks by Box–Muller; ``pcg64`` numpy's normals of the
    same seed, given as increments.  Any other name (``philox`` alone, which names no transform) is
    refused with the three choices."""
    p = OscillatorParameters(gamma0=1.0, n=10.0)
    kw = dict(model="white", law=law_III(), runs=3, seed=4, integration=IntegrationOptions(tau_end=5.0),
              output=OutputOptions(save_trajectory=True, save_every=1))
    res = {name: simulate(p, **kw, noise=NoiseOptions(sigma_zeta=0.05, white_stream=name))
           for name in ("philox-boxmuller", "pcg64")}
    res["philox-ziggurat"] = simulate(p, **kw, noise=NoiseOptions(sigma_zeta=0.05))
    for name, r in res.items():
        assert r.settings["white_stream"] == name
    assert not np.array_equal(res["philox-ziggurat"].trajectory, res["philox-boxmuller"].trajectory)
    with pytest.raises(ParameterError, match="unknown white-noise stream 'philox'; choose one of "
                       r"\['philox-ziggurat', 'philox-boxmuller', 'pcg64'\]"):
        simulate(p, **kw, noise=NoiseOptions(sigma_zeta=0.05, white_stream="philox"))
    dt, nsteps = 0.005, 1000
    root = np.random.SeedSequence(4)

    def key(r: int) -> np.uint64:
        return P.trajectory_key(trajectory_seed(root, (0,), r))

    draws = {
        "philox-ziggurat": lambda r: Z.step_normals(key(r), nsteps),
        "philox-boxmuller": lambda r: Z.step_normals(key(r), nsteps, True),
        "pcg64": lambda r: np.random.Generator(np.random.PCG64(trajectory_seed(root, (0,), r))).standard_normal(nsteps),
    }
    for name, draw in draws.items():
        for r in range(3):
            dw = draw(r) * math.sqrt(dt)
            one = run_fixed_step(_prm(0.05)[0], law_III().shape, law_III().param_array, (0.0, 1.0),
                                 K.FixedStepGrid(nsteps, dt, 1), K.SCHEME_EULER, K.NOISE_WHITE, K.PATH_MASS, dw,
                                 capacity=32, nsave=nsteps + 1)
            np.testing.assert_array_equal(res[name].trajectory[0, r], one.traj)
    with pytest.raises(Exception, match="white-noise stream"):
        simulate(p, **kw, noise=NoiseOptions(sigma_zeta=0.05, white_stream="mt19937"))

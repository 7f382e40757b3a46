"""Random numbers inside the compiled kernels: Philox4x32-10, normal deviates, and numpy's
SeedSequence and PCG64 in compiled code.

Philox4x32-10 (Salmon, Moraes, Dror & Shaw, "Parallel random numbers: as easy as 1, 2, 3",
SC'11; the Random123 library) maps a 128-bit *counter* ``(c0, c1, c2, c3)`` and a 64-bit
*key* ``(k0, k1)`` (32-bit words) through ten rounds of

    (c0, c1, c2, c3) ← (hi(M1·c2) ⊕ c1 ⊕ k0,  lo(M1·c2),  hi(M0·c0) ⊕ c3 ⊕ k1,  lo(M0·c0)),
    (k0, k1) ← (k0 + W0, k1 + W1) mod 2³² between rounds,

``M0 = 0xD2511F53``, ``M1 = 0xCD9E8D57``, ``W0 = 0x9E3779B9``, ``W1 = 0xBB67AE85``, to four
32-bit output words.  For a fixed key the map is a bijection of the counter space, so distinct
counters give distinct, statistically independent blocks: a trajectory's stream is addressed
by ``(key, counter)`` and needs no state, no buffer and no sequential draw — the numbers of
step ``k`` of trajectory ``j`` are the same whichever thread, batch or machine computes them
(the scheme of JAX's ``threefry``/``philox`` keys and of GPU SDE solvers).

Stream layout used by the oscillator kernels (method §5.1, docs/performance.md):

* key: the 64 bits ``SeedSequence.generate_state(1, uint64)`` of the trajectory's own spawned
  seed sequence (spawn key ``(*stream key, run)``), split into ``k0`` (low) and ``k1`` (high)
  (:func:`trajectory_keys` computes the same hash in compiled code);
* grid steps ``2p`` and ``2p + 1`` share the block ``philox(ctr = (p mod 2³², p div 2³², 0, 0))``:
  its words ``w0 = c1·2³² + c0`` and ``w1 = c3·2³² + c2`` give the pair ``(R_{2p}, R_{2p+1})``
  by the Box–Muller transform (:func:`box_muller`; ``white_stream="philox-boxmuller"``) or,
  in the default stream, by the ziggurat (:mod:`stochfric.random.ziggurat`), whose rare
  slow-path draws use the counters ``(p mod 2³², p div 2³², a, 1 + h)``, ``a ≥ 1``.  Counter
  word 3 values ≥ 3 are free for further streams of the same trajectory.

Normal deviates: Box–Muller on 53-bit uniforms, exact in distribution up to that resolution
and to the < 1-ulp errors of its logarithm, sine and cosine, which are written here as
branch-free polynomials (fdlibm's) so that one pass computes a Philox block and a normal pair
for all lock-step lanes with SIMD instructions (numba has no vector math library on this
machine; the C library's ``log``/``sin``/``cos`` would keep the loop scalar).  Measured costs
are in docs/performance.md.

Seeding: :func:`child_states` is numpy's :class:`~numpy.random.SeedSequence` hash of a child
``(*root.spawn_key, *tail)`` and :func:`pcg64_uniform_for_children` numpy's
``Generator(PCG64(child)).uniform``, both in compiled code and bit for bit numpy's (tested):
per trajectory they cost ~0.1 µs instead of ~10 µs of Python, which matters when a trajectory
is only ~10 µs of integration.
"""

from __future__ import annotations

import math
from typing import Any

import numba
import numpy as np
import numpy.typing as npt
from llvmlite import ir
from numba.core import types
from numba.core.extending import intrinsic

from stochfric.errors import InputError

__all__ = [
    "PHILOX_M0",
    "PHILOX_M1",
    "PHILOX_W0",
    "PHILOX_W1",
    "block_words",
    "box_muller",
    "child_states",
    "open_unit",
    "pair_normals",
    "pcg64_uniform_for_children",
    "philox4x32_10",
    "trajectory_key",
    "trajectory_keys",
]

PHILOX_M0 = np.uint64(0xD2511F53)
PHILOX_M1 = np.uint64(0xCD9E8D57)
PHILOX_W0 = np.uint64(0x9E3779B9)
PHILOX_W1 = np.uint64(0xBB67AE85)
_MASK32 = np.uint64(0xFFFFFFFF)
_S32 = np.uint64(32)

@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def philox4x32_10(
    c0: np.uint64, c1: np.uint64, c2: np.uint64, c3: np.uint64, k0: np.uint64, k1: np.uint64
) -> tuple[np.uint64, np.uint64, np.uint64, np.uint64]:  # pragma: no cover
    """Philox4x32-10 of counter ``(c0, c1, c2, c3)`` under key ``(k0, k1)`` (32-bit values held
    in uint64).  Returns the four 32-bit output words (Random123 ``philox4x32(ctr, key)``)."""
    for _ in range(10):
        p0 = PHILOX_M0 * c0
        p1 = PHILOX_M1 * c2
        n0 = (p1 >> _S32) ^ c1 ^ k0
        n2 = (p0 >> _S32) ^ c3 ^ k1
        c1 = p1 & _MASK32
        c3 = p0 & _MASK32
        c0 = n0
        c2 = n2
        k0 = (k0 + PHILOX_W0) & _MASK32
        k1 = (k1 + PHILOX_W1) & _MASK32
    return c0, c1, c2, c3


@numba.njit(cache=True, nogil=True, error_model="numpy")
def philox4x32_10_array(
    ctr: npt.NDArray[np.uint64], key: npt.NDArray[np.uint64]
) -> npt.NDArray[np.uint64]:  # pragma: no cover
    """:func:`philox4x32_10` of one counter (4 words) and key (2 words), as an array (tests)."""
    out = np.empty(4, dtype=np.uint64)
    out[0], out[1], out[2], out[3] = philox4x32_10(ctr[0], ctr[1], ctr[2], ctr[3], key[0], key[1])
    return out


# --- bit casts (compiled to a plain register move, so loops using them still vectorise) ---------

def _bitcast(source: Any, target: Any, llvm_type: Any) -> Any:
    """A compiled-only function reinterpreting the 64 bits of a ``source`` value as ``target``
    (no conversion: one LLVM ``bitcast``)."""

    @intrinsic
    def cast(typingctx, value):  # type: ignore[no-untyped-def]  # pragma: no cover
        if value != source:
            return None

        def codegen(context, builder, signature, args):  # type: ignore[no-untyped-def]
            return builder.bitcast(args[0], llvm_type)

        return target(source), codegen

    return cast


#: uint64 bits → float64, and back
_as_float = _bitcast(types.uint64, types.float64, ir.DoubleType())
_as_bits = _bitcast(types.float64, types.uint64, ir.IntType(64))


# --- branch-free elementary functions for the Box–Muller transform ------------------------------
# Polynomials of fdlibm (Sun Microsystems, 1993: e_log.c, k_sin.c, k_cos.c), accurate to < 1 ulp
# on their reduced ranges; written without branches or table look-ups so that the compiler
# vectorises them across the lock-step lanes (numba has no vector libm here).  Tests compare them
# with the C library over their whole input range.
_LN2_HI = 6.93147180369123816490e-01
_LN2_LO = 1.90821492927058770002e-10
#: e_log.c Lg1 … Lg7
_LG = (6.666666666666735130e-01, 3.999999999940941908e-01, 2.857142874366239149e-01, 2.222219843214978396e-01,
       1.818357216161805012e-01, 1.531383769920937332e-01, 1.479819860511658591e-01)
#: k_sin.c S1 … S6
_S = (-1.66666666666666324348e-01, 8.33333333332248946124e-03, -1.98412698298579493134e-04,
      2.75573137070700676789e-06, -2.50507602534068634195e-08, 1.58969099521155010221e-10)
#: k_cos.c C1 … C6
_C = (4.16666666666666019037e-02, -1.38888888888741095749e-03, 2.48015872894767294178e-05,
      -2.75573143513906633035e-07, 2.08757232129817482790e-09, -1.13596475577881948265e-11)
_MANT = np.uint64(0x000FFFFFFFFFFFFF)
_ONE_BITS = np.uint64(0x3FF0000000000000)
_SQRT2 = 1.4142135623730951


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def log_positive(u: float) -> float:  # pragma: no cover
    """ln u for a normal, finite u > 0 (branch-free fdlibm ``__ieee754_log``; < 1 ulp)."""
    bits: np.uint64 = _as_bits(u)
    e = np.int64(bits >> np.uint64(52)) - 1023
    m = _as_float((bits & _MANT) | _ONE_BITS)  # u = 2^e m, m in [1, 2)
    big = m > _SQRT2
    m = 0.5 * m if big else m  # m in [√2/2, √2)
    e = e + 1 if big else e
    lg1, lg2, lg3, lg4, lg5, lg6, lg7 = _LG
    f = m - 1.0
    s = f / (2.0 + f)
    z = s * s
    w = z * z
    t1 = w * (lg2 + w * (lg4 + w * lg6))
    t2 = z * (lg1 + w * (lg3 + w * (lg5 + w * lg7)))
    r = t2 + t1
    hfsq = 0.5 * f * f
    dk = float(e)
    return dk * _LN2_HI - ((hfsq - (s * (hfsq + r) + dk * _LN2_LO)) - f)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def sin_kernel(x: float) -> float:  # pragma: no cover
    """sin x for |x| ≤ π/4 (fdlibm ``__kernel_sin`` with zero tail; < 1 ulp)."""
    s1, s2, s3, s4, s5, s6 = _S
    z = x * x
    v = z * x
    r = s2 + z * (s3 + z * (s4 + z * (s5 + z * s6)))
    return x + v * (s1 + z * r)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def cos_kernel(x: float) -> float:  # pragma: no cover
    """cos x for |x| ≤ π/4 (fdlibm ``__kernel_cos`` with zero tail; < 1 ulp)."""
    c1, c2, c3, c4, c5, c6 = _C
    z = x * x
    r = z * (c1 + z * (c2 + z * (c3 + z * (c4 + z * (c5 + z * c6)))))
    hz = 0.5 * z
    w = 1.0 - hz
    return w + (((1.0 - w) - hz) + z * r)


_TWO_M53 = 1.0 / 9007199254740992.0  # 2^-53
_HALF_PI_2M51 = 0.5 * math.pi / 2.0**51  # (π/2) 2^-51


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def block_words(
    key: np.uint64, pair: np.uint64, c2: np.uint64, c3: np.uint64
) -> tuple[np.uint64, np.uint64]:  # pragma: no cover
    """The two 64-bit words ``w0 = c1·2³² + c0``, ``w1 = c3·2³² + c2`` of the Philox4x32-10 block
    of counter ``(pair mod 2³², pair div 2³², c2, c3)`` under ``key`` (the stream layout above)."""
    o0, o1, o2, o3 = philox4x32_10(pair & _MASK32, pair >> _S32, c2, c3, key & _MASK32, key >> _S32)
    return (o1 << _S32) | o0, (o3 << _S32) | o2


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def open_unit(w: np.uint64) -> float:  # pragma: no cover
    """``(⌊w/2¹¹⌋ + 1) 2⁻⁵³ ∈ (0, 1]``: a 53-bit uniform that is never 0 (a logarithm follows)."""
    return float(np.int64((w >> np.uint64(11)) + np.uint64(1))) * _TWO_M53


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def box_muller(w0: np.uint64, w1: np.uint64) -> tuple[float, float]:  # pragma: no cover
    """Two independent standard normals from two 64-bit words (Box & Muller 1958).

    ``U1 = (⌊w0/2¹¹⌋ + 1) 2⁻⁵³ ∈ (0, 1]`` (53 bits, never 0), ``U2 = ⌊w1/2¹¹⌋ 2⁻⁵³ ∈ [0, 1)``;
    ``R = √(−2 ln U1)``, ``φ = 2π U2``; returns ``(R cos φ, R sin φ)``.  The angle is reduced
    exactly in integers: ``φ = (π/2)(q + ρ)`` with ``q`` the nearest quarter turn and
    ``|ρ| ≤ ½``, so the sine and cosine polynomials only see ``|x| ≤ π/4``.  Exact in
    distribution up to the 53-bit resolution of the uniforms (largest |z| = √(106 ln 2) ≈ 8.57)
    and the < 1-ulp errors of the elementary functions.  Branch-free: vectorises.
    """
    r = math.sqrt(-2.0 * log_positive(open_unit(w0)))
    a = np.int64(w1 >> np.uint64(11))  # U2 = a 2^-53; 4 U2 = a 2^-51 quarter turns
    q = (a + np.int64(1 << 50)) >> np.int64(51)  # nearest quarter turn, 0..4
    rho = float(a - (q << np.int64(51))) * _HALF_PI_2M51  # in [-π/4, π/4)
    c = cos_kernel(rho)
    s = sin_kernel(rho)
    # (cos, sin) of q·π/2 + x for q mod 4 = 0, 1, 2, 3: (c, s), (−s, c), (−c, −s), (s, −c);
    # as selects, not a branch chain, so that the loop stays vectorised
    swap = (q & np.int64(1)) != 0
    cz = s if swap else c
    sz = c if swap else s
    cz = -cz if ((q + np.int64(1)) & np.int64(2)) != 0 else cz
    sz = -sz if (q & np.int64(2)) != 0 else sz
    return r * cz, r * sz


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def pair_normals(key: np.uint64, pair: np.uint64) -> tuple[float, float]:  # pragma: no cover
    """The normals ``(R_{2p}, R_{2p+1})`` of steps ``2p`` and ``2p + 1`` of the trajectory with
    ``key``: Box–Muller on the two 64-bit words of the block ``philox(ctr = (p, 0, 0, 0))``."""
    zero = np.uint64(0)
    w0, w1 = block_words(key, pair, zero, zero)
    return box_muller(w0, w1)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def box_muller_array(
    w0: npt.NDArray[np.uint64], w1: npt.NDArray[np.uint64]
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64]]:  # pragma: no cover
    """:func:`box_muller` elementwise (tests)."""
    n = w0.shape[0]
    z0 = np.empty(n)
    z1 = np.empty(n)
    for i in range(n):
        z0[i], z1[i] = box_muller(w0[i], w1[i])
    return z0, z1


@numba.njit(cache=True, nogil=True, error_model="numpy")
def elementary_array(x: npt.NDArray[np.float64], which: int) -> npt.NDArray[np.float64]:  # pragma: no cover
    """``log_positive`` (0), ``sin_kernel`` (1) or ``cos_kernel`` (2) elementwise (tests)."""
    out = np.empty_like(x)
    for i in range(x.shape[0]):
        if which == 0:
            out[i] = log_positive(x[i])
        elif which == 1:
            out[i] = sin_kernel(x[i])
        else:
            out[i] = cos_kernel(x[i])
    return out

def trajectory_key(seed: np.random.SeedSequence) -> np.uint64:
    """The 64-bit Philox key of a trajectory: ``seed.generate_state(1, uint64)[0]`` of its own
    spawned :class:`numpy.random.SeedSequence` (method §0: one child stream per trajectory)."""
    return np.uint64(seed.generate_state(1, np.uint64)[0])


# --- SeedSequence in compiled code ----------------------------------------------------------------
# numpy's SeedSequence (M. E. O'Neill's seed_seq_fe hash; numpy/random/bit_generator.pyx) costs
# ~8 µs per child in Python, as much as 1 ns per step of a τ = 50 trajectory.  The same hash in
# compiled code gives the same keys (tested against numpy bit for bit) in ~0.1 µs.
_INIT_A = np.uint64(0x43B0D7E5)
_MULT_A = np.uint64(0x931E8875)
_INIT_B = np.uint64(0x8B51F9DD)
_MULT_B = np.uint64(0x58F38DED)
_MIX_MULT_L = np.uint64(0xCA01F9DD)
_MIX_MULT_R = np.uint64(0x4973F715)
_XSHIFT = np.uint64(16)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def _child_states(
    prefix: npt.NDArray[np.uint64], tails: npt.NDArray[np.uint64], pool_size: int, n_words: int,
) -> npt.NDArray[np.uint64]:  # pragma: no cover
    """``SeedSequence(entropy, spawn_key=(*root_key, *tails[i])).generate_state(n_words, uint32)``
    for every row ``i`` of ``tails`` (32-bit words held in uint64, shape ``(len(tails), n_words)``);
    ``prefix`` holds the 32-bit words of the assembled entropy before the tail (run entropy
    padded to the pool size, then the root's spawn key); every tail entry is < 2³²."""
    n, m = tails.shape
    npre = prefix.shape[0]
    ne = npre + m
    ent = np.empty(ne, dtype=np.uint64)
    ent[:npre] = prefix
    mixer = np.empty(pool_size, dtype=np.uint64)
    out = np.empty((n, n_words), dtype=np.uint64)
    for t in range(n):
        for c in range(m):
            ent[npre + c] = tails[t, c]
        hc = _INIT_A
        for i in range(pool_size):
            v = ent[i] if i < ne else np.uint64(0)
            v = (v ^ hc) & _MASK32
            hc = (hc * _MULT_A) & _MASK32
            v = (v * hc) & _MASK32
            mixer[i] = v ^ (v >> _XSHIFT)
        for i_src in range(pool_size):
            for i_dst in range(pool_size):
                if i_src != i_dst:
                    v = (mixer[i_src] ^ hc) & _MASK32
                    hc = (hc * _MULT_A) & _MASK32
                    v = (v * hc) & _MASK32
                    v ^= v >> _XSHIFT
                    r = (_MIX_MULT_L * mixer[i_dst] - _MIX_MULT_R * v) & _MASK32
                    mixer[i_dst] = r ^ (r >> _XSHIFT)
        for i_src in range(pool_size, ne):
            for i_dst in range(pool_size):
                v = (ent[i_src] ^ hc) & _MASK32
                hc = (hc * _MULT_A) & _MASK32
                v = (v * hc) & _MASK32
                v ^= v >> _XSHIFT
                r = (_MIX_MULT_L * mixer[i_dst] - _MIX_MULT_R * v) & _MASK32
                mixer[i_dst] = r ^ (r >> _XSHIFT)
        hb = _INIT_B
        for i_dst in range(n_words):
            v = (mixer[i_dst % pool_size] ^ hb) & _MASK32
            hb = (hb * _MULT_B) & _MASK32
            v = (v * hb) & _MASK32
            out[t, i_dst] = v ^ (v >> _XSHIFT)
    return out


def _uint32_words(value: int) -> list[int]:
    """Little-endian 32-bit words of a non-negative int (numpy's ``_int_to_uint32_array``)."""
    if value < 0:
        raise InputError("seed entropy and spawn keys must be non-negative")
    words = [value & 0xFFFFFFFF]
    value >>= 32
    while value:
        words.append(value & 0xFFFFFFFF)
        value >>= 32
    return words


def spawn_tails(keys: npt.ArrayLike) -> npt.NDArray[np.int64]:
    """``keys`` as a 2-D int64 array of spawn-key tails, one row per child (a 1-D array is one
    column); refuses negative entries."""
    arr = np.asarray(keys, dtype=np.int64)
    if arr.ndim == 1:
        arr = arr[:, None]
    if arr.ndim != 2:
        raise InputError(f"spawn-key tails must be a 2-D array (children × entries), got shape {arr.shape}")
    if arr.size and arr.min() < 0:
        raise InputError("spawn-key entries must be non-negative")
    return arr


def child_states(root: np.random.SeedSequence, keys: npt.ArrayLike, n_words: int) -> npt.NDArray[np.uint32]:
    """``generate_state(n_words, uint32)`` of the children of ``root`` with spawn keys
    ``(*root.spawn_key, *keys[i])`` (``keys``: one row of spawn-key entries per child, e.g.
    ``(*cell key, run)``: :func:`stochfric.oscillator.integrate.trajectory_seed`), computed in
    compiled code; shape ``(len(keys), n_words)``.

    Equal, bit for bit, to numpy's :class:`~numpy.random.SeedSequence` (falls back to it where
    an entry is ≥ 2³² or the root's entropy is not an integer).
    """
    tails = spawn_tails(keys)
    entropy = root.entropy
    if tails.size and (int(tails.max()) >= 2**32 or entropy is None
                       or not isinstance(entropy, int | np.integer)):
        return np.array([np.random.SeedSequence(
            entropy, spawn_key=(*root.spawn_key, *(int(v) for v in row)), pool_size=root.pool_size
        ).generate_state(n_words, np.uint32) for row in tails], dtype=np.uint32).reshape(len(tails), n_words)
    run_entropy = _uint32_words(int(entropy))  # type: ignore[arg-type]
    run_entropy += [0] * max(0, root.pool_size - len(run_entropy))  # spawn key always present
    prefix = run_entropy + [w for k in root.spawn_key for w in _uint32_words(int(k))]
    return _child_states(np.array(prefix, dtype=np.uint64), tails.astype(np.uint64),
                         int(root.pool_size), int(n_words)).astype(np.uint32)


def trajectory_keys(root: np.random.SeedSequence, keys: npt.ArrayLike) -> npt.NDArray[np.uint64]:
    """:func:`trajectory_key` of the children with spawn keys ``(*root.spawn_key, *keys[i])`` of
    ``root``, computed in compiled code (:func:`child_states`; bit for bit numpy's)."""
    w = child_states(root, keys, 2).astype(np.uint64)
    return np.ascontiguousarray(w[:, 0] | (w[:, 1] << np.uint64(32)))


# --- numpy's PCG64 in compiled code ---------------------------------------------------------------
# The contact model draws each trajectory's K phases with numpy's Generator(PCG64(seed)).uniform
# (method §0); creating that generator costs ~10 µs per trajectory in Python.  The same 128-bit
# LCG with the XSL-RR output (O'Neill 2014; numpy's pcg64.h), seeded the way numpy seeds it from
# SeedSequence.generate_state(4, uint64), gives the same numbers (tested bit for bit).
_PCG_MULT_HI = np.uint64(0x2360ED051FC65DA4)
_PCG_MULT_LO = np.uint64(0x4385DF649FCCF645)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _mulhi64(a: np.uint64, b: np.uint64) -> np.uint64:  # pragma: no cover
    """High 64 bits of the 128-bit product ``a·b``."""
    a0 = a & _MASK32
    a1 = a >> _S32
    b0 = b & _MASK32
    b1 = b >> _S32
    p00 = a0 * b0
    p01 = a0 * b1
    p10 = a1 * b0
    mid = (p00 >> _S32) + (p01 & _MASK32) + (p10 & _MASK32)
    return a1 * b1 + (p01 >> _S32) + (p10 >> _S32) + (mid >> _S32)


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def _pcg_step(
    sh: np.uint64, sl: np.uint64, ih: np.uint64, il: np.uint64
) -> tuple[np.uint64, np.uint64]:  # pragma: no cover
    """state ← state · M + inc (mod 2¹²⁸), as (high, low) 64-bit halves."""
    lo = sl * _PCG_MULT_LO
    hi = _mulhi64(sl, _PCG_MULT_LO) + sh * _PCG_MULT_LO + sl * _PCG_MULT_HI
    lo2 = lo + il
    carry = np.uint64(1) if lo2 < lo else np.uint64(0)
    return hi + ih + carry, lo2


@numba.njit(cache=True, nogil=True, error_model="numpy")
def pcg64_uniform(
    seeds: npt.NDArray[np.uint64], count: int, scale: float
) -> npt.NDArray[np.float64]:  # pragma: no cover
    """``Generator(PCG64(s)).uniform(0, scale, count)`` for every row ``s`` of ``seeds``, where
    row ``i`` holds ``SeedSequence.generate_state(4, uint64)`` of generator ``i``."""
    n = seeds.shape[0]
    out = np.empty((n, count))
    one = np.uint64(1)
    zero = np.uint64(0)
    for t in range(n):
        # pcg64_set_seed: initstate = (s0, s1), initseq = (s2, s3) (high, low)
        ih = (seeds[t, 2] << one) | (seeds[t, 3] >> np.uint64(63))
        il = (seeds[t, 3] << one) | one
        sh, sl = _pcg_step(zero, zero, ih, il)
        lo = sl + seeds[t, 1]
        carry = one if lo < sl else zero
        sh, sl = _pcg_step(sh + seeds[t, 0] + carry, lo, ih, il)
        for i in range(count):
            sh, sl = _pcg_step(sh, sl, ih, il)
            x = sh ^ sl
            rot = sh >> np.uint64(58)
            w = (x >> rot) | (x << ((np.uint64(64) - rot) & np.uint64(63)))
            out[t, i] = 0.0 + scale * (float(w >> np.uint64(11)) * (1.0 / 9007199254740992.0))
    return out


def pcg64_uniform_for_children(
    root: np.random.SeedSequence, keys: npt.ArrayLike, count: int, high: float
) -> npt.NDArray[np.float64]:
    """Row ``i``: ``Generator(PCG64(child)).uniform(0, high, count)`` for the child of ``root``
    with spawn key ``(*root.spawn_key, *keys[i])``, computed in compiled code."""
    w = child_states(root, keys, 8).astype(np.uint64)
    seeds = np.ascontiguousarray(w[:, 0::2] | (w[:, 1::2] << np.uint64(32)))
    return pcg64_uniform(seeds, int(count), float(high) - 0.0)

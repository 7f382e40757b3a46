"""Standard normals from Philox words by the ziggurat method: the default white-noise stream.

The ziggurat (Marsaglia & Tsang, "The ziggurat method for generating random variables",
J. Stat. Softw. 5(8), 2000) covers the half-normal density ``f(x) = exp(−x²/2)`` with
``N = 1024`` layers of equal area ``v``: layer ``i ≥ 1`` is the rectangle
``[0, x_i] × [f(x_i), f(x_{i+1})]`` and layer 0 is ``[0, r] × [0, f(r)]`` plus the tail
``x > r``, written as a rectangle of virtual width ``x_0 = v / f(r)``.  The abscissae are
``x_1 = r``, ``x_{i+1} = f⁻¹(f(x_i) + v/x_i)``, ``x_N = 0``; ``r`` is the root of "the last layer
closes", ``v = r f(r) + ∫_r^∞ f``.  One draw takes one 64-bit word ``w``:

* layer ``i = w mod 2¹⁰``, sign = bit 10, ``u = ⌊w / 2¹¹⌋`` (53 bits), ``x = u · x_i 2⁻⁵³``;
* **fast path**: ``u < k_i`` (``k_i`` the least integer with ``k_i · x_i 2⁻⁵³ ≥ x_{i+1}``, i.e.
  ``x < x_{i+1}``): the point lies under the curve, return ``±x`` — 99.57 % of draws, one
  multiplication, two table look-ups and a compare, branch-free over the lock-step lanes
  (1024 layers rather than the usual 128 or 256 because the slow path, a scalar pass with its
  own Philox blocks and a logarithm, costs ~75 ns: 256 layers leave 1.5 % of draws to it);
* otherwise (:func:`ziggurat_slow`, a scalar pass over the few lanes that need it):
  layer 0 → the tail by Marsaglia's method (``a = −ln U₁ / r``, ``b = −ln U₂`` until
  ``2b > a²``; return ``±(r + a)``); layer ``i ≥ 1`` → the wedge test
  ``f(x_i) + U (f(x_{i+1}) − f(x_i)) < f(x)``, taken as ``ln y < −x²/2`` with the package's own
  logarithm (:func:`~stochfric.random.philox.log_positive`), else a fresh draw.

The method is exact in distribution up to the 53-bit resolution of ``u`` and the < 1-ulp
error of that logarithm (it moves a wedge decision only when ``y`` is within one ulp of
``f(x)``).  Its slow path uses only IEEE arithmetic, ``sqrt`` and the package's polynomial
logarithm, and the tables are decimal-exact values (below), so the numbers are the same on
every machine — no C-library ``exp``/``log`` is involved.

Stream layout (docs/performance.md, "White noise"): grid steps ``2p`` and ``2p + 1`` of the
trajectory with ``key`` take the words ``w0 = c1·2³² + c0`` and ``w1 = c3·2³² + c2`` of the
Philox4x32-10 block of counter ``(p mod 2³², p div 2³², 0, 0)`` — the block the Box–Muller
stream (:func:`~stochfric.random.philox.pair_normals`) reads.  A draw that leaves the fast
path continues with the blocks of counters ``(p mod 2³², p div 2³², a, 1 + h)``,
``a = 1, 2, …``, ``h`` = 0 for the even step and 1 for the odd one; each block gives two more
words (``U₁, U₂`` of a tail try, or the wedge ``U`` and the next draw).  So every normal is a
function of ``(key, step)`` alone: independent of threads, batches and which other lanes took
the slow path.

Tables: ``stochfric/data/ziggurat_1024.json`` holds ``r``, ``v``, ``x_i`` and ``f(x_i)`` rounded once from
50-digit :mod:`decimal` arithmetic (correctly rounded ``exp``, ``ln``, ``sqrt``; the tail
integral by Laplace's continued fraction); :func:`compute_tables` regenerates them and a test
checks that the file is its output.  For 1024 layers ``r = 4.038849846109504``,
``v = 0.001226324646353088``.  The same code for 256 layers gives ``r = 3.654152885361008771…``,
the published value 3.6541528853610088 (Marsaglia & Tsang 2000; numpy's ``ziggurat_nor_r``) to
2.5e-17 (tested).  Run ``python -m stochfric.random.ziggurat`` to rewrite the file.
"""

from __future__ import annotations

import decimal
import json
import math
import sys
from importlib import resources
from pathlib import Path

import numba
import numpy as np
import numpy.typing as npt

from .philox import _TWO_M53, block_words, log_positive, open_unit, pair_normals

__all__ = [
    "ZIGGURAT_LAYERS",
    "ZIGGURAT_R",
    "ZIGGURAT_V",
    "compute_tables",
    "pair_normals_ziggurat",
    "step_normals",
    "ziggurat_fast",
    "ziggurat_slow",
]

ZIGGURAT_LAYERS = 1024
_LAYER_MASK = np.uint64(ZIGGURAT_LAYERS - 1)
#: the tables' file in the package data (:func:`write_tables`)
TABLES_FILE = "ziggurat_1024.json"


def _read_tables() -> tuple[float, float, tuple[float, ...], tuple[float, ...]]:
    """``(r, v, x_0 … x_N, f(x_0) … f(x_N))`` from the package data (floats written with
    ``repr``, so they read back bit for bit)."""
    data = json.loads((resources.files("stochfric") / "data" / TABLES_FILE).read_text(encoding="utf-8"))
    if data["layers"] != ZIGGURAT_LAYERS or len(data["x"]) != ZIGGURAT_LAYERS + 1:
        raise RuntimeError(f"{TABLES_FILE} holds {data['layers']} layers, the code needs {ZIGGURAT_LAYERS}")
    return float(data["r"]), float(data["v"]), tuple(data["x"]), tuple(data["f"])


ZIGGURAT_R, ZIGGURAT_V, _X_TABLE, _F_TABLE = _read_tables()


def _fast_tables() -> tuple[npt.NDArray[np.float64], npt.NDArray[np.int64], npt.NDArray[np.float64]]:
    """``w_i = x_i 2⁻⁵³``, ``k_i`` = least integer with ``float(k_i)·w_i ≥ x_{i+1}`` (the exact
    float comparison the fast path makes), ``f_i = f(x_i)`` (``f_N = 1``)."""
    x = np.array(_X_TABLE, dtype=np.float64)
    wi = x[:ZIGGURAT_LAYERS] * _TWO_M53  # a power-of-two scaling: exact
    ki = np.empty(ZIGGURAT_LAYERS, dtype=np.int64)
    for i in range(ZIGGURAT_LAYERS):
        w, top = float(wi[i]), float(x[i + 1])
        k = math.ceil(top / w)
        while k > 0 and float(k - 1) * w >= top:
            k -= 1
        while float(k) * w < top:
            k += 1
        ki[i] = k
    return wi, ki, np.array(_F_TABLE, dtype=np.float64)


_WI, _KI, _FI = _fast_tables()


@numba.njit(cache=True, nogil=True, error_model="numpy", inline="always")
def ziggurat_fast(w: np.uint64) -> tuple[float, bool]:  # pragma: no cover
    """The fast path of one draw from word ``w``: ``(±x, accepted)``; ``x`` is meaningful only
    where ``accepted`` (branch-free: a gather, a multiplication and a compare)."""
    idx = np.int64(w & _LAYER_MASK)
    u = np.int64(w >> np.uint64(11))
    x = float(u) * _WI[idx]
    z = -x if (w >> np.uint64(10)) & np.uint64(1) else x
    return z, u < _KI[idx]


@numba.njit(cache=True, nogil=True, error_model="numpy")
def ziggurat_slow(key: np.uint64, pair: np.uint64, half: np.uint64, w: np.uint64) -> float:  # pragma: no cover
    """The normal of step ``2·pair + half`` whose first word ``w`` may have left the fast path:
    tail and wedge tests and fresh draws from the blocks ``(pair, a, 1 + half)``, ``a = 1, 2, …``
    (module docstring)."""
    c3 = np.uint64(1) + half
    a = np.uint64(0)
    while True:
        idx = np.int64(w & _LAYER_MASK)
        neg = (w >> np.uint64(10)) & np.uint64(1)
        u = np.int64(w >> np.uint64(11))
        x = float(u) * _WI[idx]
        if u < _KI[idx]:
            return -x if neg else x
        a += np.uint64(1)
        u0, u1 = block_words(key, pair, a, c3)
        if idx == 0:
            # the tail x > r (Marsaglia 1964): one block per try
            while True:
                ta = -log_positive(open_unit(u0)) / ZIGGURAT_R
                tb = -log_positive(open_unit(u1))
                if tb + tb > ta * ta:
                    z = ZIGGURAT_R + ta
                    return -z if neg else z
                a += np.uint64(1)
                u0, u1 = block_words(key, pair, a, c3)
        # wedge of layer idx: y uniform on [f(x_idx), f(x_idx+1)), accept if y < f(x)
        y = _FI[idx] + float(np.int64(u0 >> np.uint64(11))) * _TWO_M53 * (_FI[idx + 1] - _FI[idx])
        if log_positive(y) < -0.5 * x * x:
            return -x if neg else x
        w = u1  # a fresh draw


@numba.njit(cache=True, nogil=True, error_model="numpy")
def pair_normals_ziggurat(key: np.uint64, pair: np.uint64) -> tuple[float, float]:  # pragma: no cover
    """The normals ``(R_{2p}, R_{2p+1})`` of steps ``2p`` and ``2p + 1`` (``pair = p``) of the
    trajectory with ``key`` (scalar; the kernels compute the same numbers lane-parallel)."""
    w0, w1 = block_words(key, pair, np.uint64(0), np.uint64(0))
    z0, ok0 = ziggurat_fast(w0)
    z1, ok1 = ziggurat_fast(w1)
    if not ok0:
        z0 = ziggurat_slow(key, pair, np.uint64(0), w0)
    if not ok1:
        z1 = ziggurat_slow(key, pair, np.uint64(1), w1)
    return z0, z1


@numba.njit(cache=True, nogil=True, error_model="numpy")
def step_normals(key: np.uint64, nsteps: int, box_muller: bool = False) -> npt.NDArray[np.float64]:  # pragma: no cover
    """The normals ``R_0 … R_{nsteps−1}`` the kernels draw for the trajectory with ``key``: the
    default stream (ziggurat), or with ``box_muller`` the ``philox-boxmuller`` stream
    (:func:`~stochfric.random.philox.pair_normals`).  The same numbers; for tests and for
    giving the increments explicitly, ``ΔW_k = R_k √Δτ``."""
    out = np.empty(nsteps + 1)
    for p in range((nsteps + 1) // 2):
        pair = np.uint64(p)
        if box_muller:
            out[2 * p], out[2 * p + 1] = pair_normals(key, pair)
        else:
            out[2 * p], out[2 * p + 1] = pair_normals_ziggurat(key, pair)
    return out[:nsteps]


@numba.njit(cache=True, nogil=True, error_model="numpy")
def fill_pair_ziggurat(
    keys: npt.NDArray[np.uint64], pair: np.uint64, sqdt: float, wk: npt.NDArray[np.float64],
    zodd: npt.NDArray[np.float64], miss: npt.NDArray[np.uint64],
) -> int:  # pragma: no cover
    """Fast path for every lane (``pair = p``), in one branch-free loop that the compiler
    vectorises: ``wk = R_{2p} √Δτ``, ``zodd = R_{2p+1} √Δτ`` where the draw was accepted.  Returns
    how many draws were not; then :func:`finish_pair_ziggurat` must run.  ``miss`` (shape
    ``(2, lanes)``, scratch) receives the words of the rejected draws and 0 elsewhere (a word of
    0 is layer 0, ``u = 0``: always accepted)."""
    nmiss = 0
    zero = np.uint64(0)
    for jj in range(keys.shape[0]):
        w0, w1 = block_words(keys[jj], pair, zero, zero)
        z0, ok0 = ziggurat_fast(w0)
        z1, ok1 = ziggurat_fast(w1)
        wk[jj] = z0 * sqdt
        zodd[jj] = z1 * sqdt
        miss[0, jj] = zero if ok0 else w0
        miss[1, jj] = zero if ok1 else w1
        nmiss += (0 if ok0 else 1) + (0 if ok1 else 1)
    return nmiss


@numba.njit(cache=True, nogil=True, error_model="numpy")
def finish_pair_ziggurat(
    keys: npt.NDArray[np.uint64], pair: np.uint64, sqdt: float, wk: npt.NDArray[np.float64],
    zodd: npt.NDArray[np.float64], miss: npt.NDArray[np.uint64],
) -> None:  # pragma: no cover
    """The slow path (:func:`ziggurat_slow`) for the draws :func:`fill_pair_ziggurat` left in
    ``miss`` (0.43 % of draws)."""
    zero = np.uint64(0)
    for jj in range(keys.shape[0]):
        if miss[0, jj] != zero:
            wk[jj] = ziggurat_slow(keys[jj], pair, zero, miss[0, jj]) * sqdt
        if miss[1, jj] != zero:
            zodd[jj] = ziggurat_slow(keys[jj], pair, np.uint64(1), miss[1, jj]) * sqdt


# --- the tables, in decimal arithmetic ------------------------------------------------------------

#: the published 256-layer r (Marsaglia & Tsang 2000; numpy's ``ziggurat_nor_r``), with which a
#: test compares ``compute_tables(256)``
PUBLISHED_R_256 = 3.6541528853610088


def _float_root(layers: int) -> float:
    """``r`` of a ``layers``-layer ziggurat in float64 (bisection of the closure), the start of
    the decimal root search."""

    def closure(r: float) -> float:
        v = r * math.exp(-0.5 * r * r) + math.sqrt(0.5 * math.pi) * math.erfc(r / math.sqrt(2.0))
        x = r
        for _ in range(1, layers - 1):
            a = v / x + math.exp(-0.5 * x * x)
            if a >= 1.0:
                return 1.0  # r too small: the layers reach the top early
            x = math.sqrt(-2.0 * math.log(a))
        return v / x + math.exp(-0.5 * x * x) - 1.0

    lo, hi = 1.0, 8.0
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if closure(mid) > 0.0:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def compute_tables(
    layers: int = ZIGGURAT_LAYERS, digits: int = 50
) -> tuple[float, float, list[float], list[float]]:
    """``(r, v, x_0 … x_N, f(x_0) … f(x_N))`` of the ``N = layers`` normal ziggurat, computed
    with ``digits``-digit :mod:`decimal` arithmetic and rounded once to float64.

    ``r`` is the root of ``v/x_{N−1} + f(x_{N−1}) = 1`` (the top layer closes), found by the
    secant method from a float64 bisection; ``v = r f(r) + f(r) M(r)`` with Mills' ratio
    ``M(r) = 1/(r + 1/(r + 2/(r + 3/(r + …))))`` (Laplace's continued fraction, 4000 terms).
    """
    ctx = decimal.Context(prec=digits)
    half = decimal.Decimal("0.5")

    def f(x: decimal.Decimal) -> decimal.Decimal:
        return ctx.exp(ctx.minus(ctx.multiply(ctx.multiply(x, x), half)))

    def v_of(r: decimal.Decimal) -> decimal.Decimal:
        acc = r
        for k in range(4000, 0, -1):
            acc = ctx.add(r, ctx.divide(decimal.Decimal(k), acc))
        return ctx.multiply(f(r), ctx.add(r, ctx.divide(1, acc)))

    def build(r: decimal.Decimal) -> tuple[decimal.Decimal, list[decimal.Decimal]]:
        v = v_of(r)
        x = [ctx.divide(v, f(r)), r]
        for _ in range(1, layers - 1):
            x.append(ctx.sqrt(ctx.multiply(-2, ctx.ln(ctx.add(ctx.divide(v, x[-1]), f(x[-1]))))))
        return v, x

    def closure(r: decimal.Decimal) -> decimal.Decimal:
        v, x = build(r)
        return ctx.subtract(ctx.add(ctx.divide(v, x[-1]), f(x[-1])), 1)

    a = decimal.Decimal(repr(_float_root(layers)))
    b = ctx.add(a, decimal.Decimal("1e-12"))
    ga, gb = closure(a), closure(b)
    tol = decimal.Decimal(10) ** (-(digits - 12))
    for _ in range(30):
        if gb == ga or abs(gb) < tol:
            break
        c = ctx.subtract(b, ctx.divide(ctx.multiply(gb, ctx.subtract(b, a)), ctx.subtract(gb, ga)))
        a, ga = b, gb
        b, gb = c, closure(c)
    if abs(gb) >= tol:
        raise ArithmeticError(f"ziggurat root search did not converge (closure {gb})")
    v, x = build(b)
    x.append(decimal.Decimal(0))
    fx = [f(xi) for xi in x]
    fx[-1] = decimal.Decimal(1)
    return float(b), float(v), [float(xi) for xi in x], [float(fi) for fi in fx]


def write_tables(path: Path | None = None) -> Path:
    """Write :func:`compute_tables` to the package data (or ``path``) as JSON; returns the path."""
    r, v, x, fx = compute_tables()
    target = path or Path(__file__).parent.parent / "data" / TABLES_FILE
    data = {"generator": "python -m stochfric.random.ziggurat (compute_tables: 50-digit decimal, "
                         "rounded once to float64)",
            "layers": ZIGGURAT_LAYERS, "r": r, "v": v, "x": x, "f": fx}
    target.write_text(json.dumps(data, indent=0) + "\n", encoding="utf-8")
    return target


if __name__ == "__main__":  # pragma: no cover
    sys.stdout.write(f"wrote {write_tables()}\n")

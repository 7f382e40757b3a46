"""Philox4x64-10, a test helper: the 64-bit member of the Philox family with the round structure
of :func:`stochfric.random.philox.philox4x32_10` (which the kernels use).  numpy ships no
Philox4x32, but its ``Philox`` is 4x64-10, so this lets ``test_philox.py`` compare the round
structure bit for bit with an independent implementation.  Not part of the package: the kernels
never call it."""

from __future__ import annotations

import numba
import numpy as np
import numpy.typing as npt

from stochfric.random.philox import _mulhi64

_M0_64 = np.uint64(0xD2E7470EE14C6C93)
_M1_64 = np.uint64(0xCA5A826395121157)
_W0_64 = np.uint64(0x9E3779B97F4A7C15)
_W1_64 = np.uint64(0xBB67AE8584CAA73B)


@numba.njit(cache=True, nogil=True, error_model="numpy")
def philox4x64_10_array(
    ctr: npt.NDArray[np.uint64], key: npt.NDArray[np.uint64]
) -> npt.NDArray[np.uint64]:  # pragma: no cover
    """Philox4x64-10 of one counter (4 64-bit words) and key (2 words): the 64-bit member of
    the family, with the same round structure as :func:`philox4x32_10` (multipliers
    ``0xD2E7470EE14C6C93``, ``0xCA5A826395121157``, Weyl increments ``0x9E3779B97F4A7C15``,
    ``0xBB67AE8584CAA73B``)."""
    c0, c1, c2, c3 = ctr[0], ctr[1], ctr[2], ctr[3]
    k0, k1 = key[0], key[1]
    for _ in range(10):
        hi0 = _mulhi64(_M0_64, c0)
        lo0 = _M0_64 * c0
        hi1 = _mulhi64(_M1_64, c2)
        lo1 = _M1_64 * c2
        c0, c1, c2, c3 = hi1 ^ c1 ^ k0, lo1, hi0 ^ c3 ^ k1, lo0
        k0 = k0 + _W0_64
        k1 = k1 + _W1_64
    out = np.empty(4, dtype=np.uint64)
    out[0], out[1], out[2], out[3] = c0, c1, c2, c3
    return out



"""Test helpers: one trajectory through the batch kernels (tests only; the package calls
:func:`stochfric.oscillator.kernels.run_fixed_step_batch` through ``simulate``)."""

from __future__ import annotations

from typing import NamedTuple

import numpy as np
import numpy.typing as npt

from stochfric.oscillator import accurate as A
from stochfric.oscillator import kernels as K


class OneRun(NamedTuple):
    """The outputs of one trajectory: ``M`` and its rows of :class:`~stochfric.oscillator.kernels.KernelOutput`
    (``x_gh``/``t_gh`` NaN beyond ``M``, unsaved ``traj`` rows NaN)."""

    m: int
    x_gh: npt.NDArray[np.float64]
    t_gh: npt.NDArray[np.float64]
    traj: npt.NDArray[np.float64]
    diag: npt.NDArray[np.float64]


def _rows(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x0: tuple[float, float],
    proc: npt.NDArray[np.float64] | None,
) -> K.KernelRows:
    """The one-row :class:`~stochfric.oscillator.kernels.KernelRows` of a single trajectory (``proc``:
    its process realisation, one period; ``None``: no process)."""
    procv = np.zeros(1) if proc is None else np.ascontiguousarray(proc, dtype=np.float64)
    return K.KernelRows(
        np.ascontiguousarray(prm, dtype=np.float64).reshape(1, -1), np.full(1, shape, dtype=np.int64),
        np.ascontiguousarray(lawp, dtype=np.float64).reshape(1, -1), np.array([x0], dtype=np.float64),
        procv.reshape(1, -1), np.full(1, procv.size, dtype=np.int64),
    )


def _output(capacity: int, nsave: int) -> K.KernelOutput:
    return K.KernelOutput(np.full((1, capacity), np.nan), np.full((1, capacity), np.nan), np.zeros(1, dtype=np.int64),
                          np.full((1, nsave, 3), np.nan), np.zeros((1, K.N_DIAG)))


def _one(m: int, out: K.KernelOutput) -> OneRun:
    return OneRun(m, out.x_gh[0], out.t_gh[0], out.traj[0], out.diag[0])


def run_fixed_step(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x0: tuple[float, float],
    grid: K.FixedStepGrid, scheme: int, noise: int, path_mode: int, dw: npt.NDArray[np.float64],
    proc: npt.NDArray[np.float64] | None = None, capacity: int = 8, nsave: int = 0,
) -> OneRun:
    """:func:`~stochfric.oscillator.kernels.run_fixed_step_batch` for a single row with the
    increments ``dw`` given (``WHITE_GIVEN``); room for ``capacity`` events and ``nsave`` states."""
    out = _output(capacity, nsave)
    K.run_fixed_step_batch(
        _rows(prm, shape, lawp, x0, proc), out, grid, int(scheme), int(noise), int(path_mode),
        K.WhiteInput(K.WHITE_GIVEN, np.ascontiguousarray(dw, dtype=np.float64).reshape(1, -1),
                     np.zeros(1, dtype=np.uint64)),
    )
    return _one(int(out.counts[0]), out)


def run_accurate(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x0: tuple[float, float],
    settings: A.AccurateSettings, noise: int, path_mode: int, proc: npt.NDArray[np.float64] | None = None,
    capacity: int = 16, nsave: int = 0,
) -> OneRun:
    """:func:`~stochfric.oscillator.accurate.run_accurate` for one trajectory, with room for
    ``capacity`` events and ``nsave`` states."""
    out = _output(capacity, nsave)
    return _one(int(A.run_accurate(_rows(prm, shape, lawp, x0, proc), out, 0, settings, noise, path_mode)), out)

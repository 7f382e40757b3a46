"""Test helpers: one trajectory through the batch kernels (tests only; the package calls
:func:`stochfric.oscillator.kernels.run_fixed_step_batch` through ``simulate``)."""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from stochfric.oscillator import accurate as A
from stochfric.oscillator import kernels as K


def _rows(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x10: float, x20: float,
    proc: npt.NDArray[np.float64], n_proc: int,
) -> K.KernelRows:
    """The one-row :class:`~stochfric.oscillator.kernels.KernelRows` of a single trajectory."""
    return K.KernelRows(
        np.ascontiguousarray(prm, dtype=np.float64).reshape(1, -1), np.full(1, shape, dtype=np.int64),
        np.ascontiguousarray(lawp, dtype=np.float64).reshape(1, -1), np.array([[x10, x20]], dtype=np.float64),
        np.ascontiguousarray(proc, dtype=np.float64).reshape(1, -1), np.full(1, n_proc, dtype=np.int64),
    )


def run_fixed_step(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x10: float, x20: float,
    nsteps: int, dt: float, scheme: int, noise: int, path_mode: int, dw: npt.NDArray[np.float64],
    proc: npt.NDArray[np.float64], n_proc: int, xgh: npt.NDArray[np.float64], tgh: npt.NDArray[np.float64],
    traj: npt.NDArray[np.float64], decimate: int, diag: npt.NDArray[np.float64],
) -> int:
    """:func:`~stochfric.oscillator.kernels.run_fixed_step_batch` for a single row with the
    increments ``dw`` given (``WHITE_GIVEN``); fills ``xgh``/``tgh`` (as many as fit), ``traj``
    (``(k, 3)``) and ``diag`` and returns ``M``."""
    xgh2 = np.full((1, xgh.shape[0]), np.nan)
    tgh2 = np.full((1, tgh.shape[0]), np.nan)
    counts = np.zeros(1, dtype=np.int64)
    traj2 = np.zeros((1, traj.shape[0], 3))
    diag2 = np.zeros((1, diag.shape[0]))
    K.run_fixed_step_batch(
        _rows(prm, shape, lawp, x10, x20, proc, n_proc), K.KernelOutput(xgh2, tgh2, counts, traj2, diag2),
        K.FixedStepGrid(int(nsteps), float(dt), int(decimate)), int(scheme), int(noise), int(path_mode),
        K.WhiteInput(K.WHITE_GIVEN, np.ascontiguousarray(dw, dtype=np.float64).reshape(1, -1),
                     np.zeros(1, dtype=np.uint64)),
    )
    m = min(int(counts[0]), xgh.shape[0])
    xgh[:m] = xgh2[0, :m]
    tgh[:m] = tgh2[0, :m]
    traj[:, :] = traj2[0]
    diag[:] = diag2[0]
    return int(counts[0])


def run_accurate(
    prm: npt.NDArray[np.float64], shape: int, lawp: npt.NDArray[np.float64], x10: float, x20: float,
    tau_end: float, h0: float, max_step: float, rtol: float, atol: float, noise: int, path_mode: int,
    proc: npt.NDArray[np.float64], n_proc: int, xgh: npt.NDArray[np.float64], tgh: npt.NDArray[np.float64],
    traj: npt.NDArray[np.float64], save_dt: float, diag: npt.NDArray[np.float64],
) -> int:
    """:func:`~stochfric.oscillator.accurate.run_accurate` for one trajectory, writing into the
    given 1-D ``xgh``/``tgh``/``diag`` and 2-D ``traj`` (views of one-row outputs); returns ``M``."""
    out = K.KernelOutput(xgh.reshape(1, -1), tgh.reshape(1, -1), np.zeros(1, dtype=np.int64),
                         traj.reshape(1, *traj.shape), diag.reshape(1, -1))
    return int(A.run_accurate(_rows(prm, shape, lawp, x10, x20, proc, n_proc), out, 0,
                              A.AccurateSettings(tau_end, h0, max_step, rtol, atol, save_dt), noise, path_mode))

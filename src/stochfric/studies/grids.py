"""Grids and the event window of the studies (method §6): parameter grids from
``START:STOP:NUM`` / lists, the stick window after the transient, padding of event arrays."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import numpy.typing as npt

from .errors import StudyError

#: Default stick window: a run "has a stick-slip cycle" when it has at least one slip→stick
#: transition with τ in (STICK_WINDOW · τ_end, τ_end] (after the transient, method §7.9).
STICK_WINDOW = 0.5

#: Most values one grid axis may hold: every value is a cell of runs (the thesis's densest axis has
#: 41); more is a typing slip that would allocate and run for hours before saying anything.
MAX_GRID_POINTS = 10_000


def parse_grid(spec: str | Sequence[float] | float) -> tuple[float, ...]:
    """A grid from ``"START:STOP:NUM"`` (inclusive linspace), ``"a,b,c"``, a number or a list.

    >>> parse_grid("0.05:0.25:5")
    (0.05, 0.1, 0.15, 0.2, 0.25)
    """
    if isinstance(spec, int | float) and not isinstance(spec, bool):
        vals: list[float] = [float(spec)]
    elif isinstance(spec, str):
        text = spec.strip()
        if ":" in text:
            parts = text.split(":")
            if len(parts) != 3:
                raise StudyError(f"grid {spec!r}: use START:STOP:NUM, e.g. 0.05:0.25:41")
            try:
                a, b, n = float(parts[0]), float(parts[1]), int(parts[2])
            except ValueError:
                raise StudyError(f"grid {spec!r}: START and STOP must be numbers, NUM an integer") from None
            if n < 1:
                raise StudyError(f"grid {spec!r}: NUM must be >= 1")
            if n > MAX_GRID_POINTS:
                raise StudyError(f"grid {spec!r}: {n} values; at most {MAX_GRID_POINTS} per axis (every value is a "
                                 "cell of runs; the thesis's densest axis has 41)")
            vals = [float(v) for v in np.linspace(a, b, n)] if n > 1 else [a]
        else:
            try:
                vals = [float(v) for v in text.split(",") if v.strip()]
            except ValueError:
                raise StudyError(f"grid {spec!r}: use START:STOP:NUM or a comma-separated list") from None
    else:
        try:
            vals = [float(v) for v in spec]  # type: ignore[union-attr]
        except (TypeError, ValueError):
            raise StudyError(f"grid {spec!r}: expected numbers") from None
    if not vals:
        raise StudyError(f"grid {spec!r} is empty")
    if len(vals) > MAX_GRID_POINTS:
        raise StudyError(f"grid {spec!r}: {len(vals)} values; at most {MAX_GRID_POINTS} per axis")
    if not all(math.isfinite(v) for v in vals):
        raise StudyError(f"grid {spec!r} contains a value that is not finite")
    # round away linspace noise (0.15000000000000002) so that labels and hashes are clean
    return tuple(float(f"{v:.12g}") for v in vals)


def window_mask(t_gh: npt.NDArray[np.float64], tau_end: float, window: float) -> npt.NDArray[np.bool_]:
    """Events in the stick window τ ∈ (window · τ_end, τ_end] (NaN padding is outside)."""
    if not 0.0 <= window < 1.0:
        raise StudyError(f"stick window fraction must be in [0, 1), got {window}")
    with np.errstate(invalid="ignore"):
        return np.isfinite(t_gh) & (t_gh > window * tau_end)


def pad_events(arrs: Sequence[npt.NDArray[np.float64]]) -> list[npt.NDArray[np.float64]]:
    """NaN-pad arrays ``[..., event]`` to a common event length."""
    nev = max(a.shape[-1] for a in arrs)
    out = []
    for a in arrs:
        if a.shape[-1] < nev:
            pad = np.full((*a.shape[:-1], nev - a.shape[-1]), np.nan)
            a = np.concatenate([a, pad], axis=-1)
        out.append(a)
    return out


#: The order of the grid dimensions in every study's dataset (those it has), before the
#: per-run and per-event ones (``run``, ``event``, …).
DIMENSION_ORDER = ("model", "stochastic_model", "forcing_q", "normal_force_n", "damping_ratio", "eta")


def ordered(ds: Any) -> Any:
    """The dataset ``ds`` with every variable's grid dimensions in :data:`DIMENSION_ORDER`, the others after."""
    return ds.transpose(*DIMENSION_ORDER, ..., missing_dims="ignore")

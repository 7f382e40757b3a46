"""Figures of a simulation (matplotlib object API on an Agg canvas; files only, no windows, no pyplot).

:func:`figure_phase_portrait` builds the figure (``SimulationResult.plot``), :func:`plot_phase_portrait`
writes it.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from stochfric.errors import InputError

from ..plotting import X1_LABEL, X2_LABEL, new_figure, save_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

#: Read by its attributes only: not imported, so that ``SimulationResult.plot()`` makes no import cycle
#: (``tests/unit/test_layers.py``).
SimulationResult = Any  # stochfric.oscillator.result.SimulationResult

__all__ = ["figure_phase_portrait", "plot_phase_portrait"]

_SUPERSCRIPT = str.maketrans("-0123456789", "⁻⁰¹²³⁴⁵⁶⁷⁸⁹")


def _power_of_ten(*arrays: np.ndarray) -> int:
    """The exponent k (a multiple of 3) that brings the largest finite magnitude of ``arrays`` to 1…1000:
    axis values in units of 10^k, so the tick labels of a 3-D axis stay short."""
    finite = [np.abs(a[np.isfinite(a)]) for a in arrays]
    top = max((float(a.max()) for a in finite if a.size), default=0.0)
    if top <= 0.0 or not math.isfinite(top):
        return 0
    k = 3 * math.floor(math.log10(top) / 3)
    return k if k < 0 else 0


def _scaled(label: str, k: int) -> str:
    """``label`` with its values given in units of 10^k."""
    unit = f"(dimensionless, ×10{str(k).translate(_SUPERSCRIPT)})"
    return label if k == 0 else label.replace("(dimensionless)", unit)


def figure_phase_portrait(result: SimulationResult, param_set: int = 0) -> Figure:
    """Phase portrait x2 over x1 (thesis Fig. 4.4, 4.12–4.14), 3-D (x1, x2, x3) for forced motion.

    The stick line ``x2 = γ0`` is drawn dashed, the static-friction bounds of the stick
    line (eq. 4.9/4.10, unforced) are marked, and every slip→stick position ``X_gh`` is a
    dot.  Several runs are overlaid in grey with run 0 in black.  A 7 × 5.2 in figure.
    """
    from matplotlib.ticker import MaxNLocator

    if result.trajectory is None:
        raise InputError("the result holds no trajectory; simulate with save_trajectory=True")
    p = result.params[param_set]
    traj = result.trajectory[param_set]
    forced = p.q > 0 and p.eta > 0
    fig = new_figure(7.0, 5.2, layout=None)
    title = (
        f"{result.model}, {result.integrator}, n = {p.n:.4g}, D = {p.damping_ratio:.3g}"
        + (f", q = {p.q:.3g}, η = {p.eta:.3g}" if forced else "")
        + (f", N = {p.normal_force:.0f} N" if p.normal_force is not None else "")
    )
    law = result.laws[param_set]
    mus = float(law["static"])
    if forced:
        ax3 = fig.add_subplot(111, projection="3d")
        tt = np.linspace(0, 2 * np.pi, 200)
        xb = p.n * mus - 2 * p.damping_ratio * p.gamma0 + p.q * np.cos(tt)
        k1 = _power_of_ten(traj[:, :, 1], xb)
        k2 = _power_of_ten(traj[:, :, 2], np.array([p.gamma0]))
        s1, s2 = 10.0 ** -k1, 10.0 ** -k2
        for r in range(traj.shape[0] - 1, -1, -1):
            col = "k" if r == 0 else "0.6"
            tau = traj[r, :, 0]
            ax3.plot(traj[r, :, 1] * s1, traj[r, :, 2] * s2, np.mod(p.eta * tau, 2 * np.pi), color=col,
                     lw=0.6)
        ax3.plot(xb * s1, np.full_like(tt, p.gamma0 * s2), tt, "r--", lw=1, label="stick boundary (4.9)")
        for axis in (ax3.xaxis, ax3.yaxis, ax3.zaxis):
            axis.set_major_locator(MaxNLocator(nbins=4))
        ax3.tick_params(labelsize=8)
        ax3.set_box_aspect(None, zoom=0.8)  # room for the axis labels inside the figure
        ax3.set_xlabel(_scaled(X1_LABEL, k1), fontsize=8, labelpad=8)
        ax3.set_ylabel(_scaled(X2_LABEL, k2), fontsize=8, labelpad=8)
        ax3.set_zlabel("x3 = ητ mod 2π (dimensionless)", fontsize=8, labelpad=6)
        ax3.legend(loc="upper left", fontsize=8)
        ax3.set_title(title, fontsize=9)
    else:
        ax = fig.add_subplot(111)
        for r in range(traj.shape[0] - 1, -1, -1):
            col = "k" if r == 0 else "0.6"
            ax.plot(traj[r, :, 1], traj[r, :, 2], color=col, lw=0.6)
            xg = result.x_gh[param_set, r]
            xg = xg[np.isfinite(xg)]
            ax.plot(xg, np.full_like(xg, p.gamma0), "o", color="tab:red" if r == 0 else "0.4",
                    ms=3)
        ax.axhline(p.gamma0, color="tab:blue", ls="--", lw=0.8, label="stick line x2 = γ0")
        bound = p.n * mus
        ax.plot([bound - 2 * p.damping_ratio * p.gamma0, -bound - 2 * p.damping_ratio * p.gamma0],
                [p.gamma0, p.gamma0], "|", color="tab:blue", ms=12,
                label="static-friction bounds (4.9/4.10)")
        ax.set_xlabel(X1_LABEL)
        ax.set_ylabel(X2_LABEL)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=6))
        ax.legend(loc="lower right", fontsize=8)
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    return fig


def plot_phase_portrait(result: SimulationResult, path: str | Path, param_set: int = 0) -> Path:
    """:func:`figure_phase_portrait` written to ``path`` (format from the extension, 130 dpi); returns the path."""
    return save_figure(figure_phase_portrait(result, param_set), path, dpi=130)

"""Figures of a simulation (matplotlib object API on an Agg canvas; files only, no windows, no pyplot)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stochfric.errors import InputError

from ..io_utils import write_atomic
from ..oscillator.result import SimulationResult
from ..plotting import new_figure


def plot_phase_portrait(result: SimulationResult, path: str | Path, param_set: int = 0) -> Path:
    """Phase portrait x2 over x1 (thesis Fig. 4.4, 4.12–4.14), 3-D (x1, x2, x3) for forced motion.

    The stick line ``x2 = γ0`` is drawn dashed, the static-friction bounds of the stick
    line (eq. 4.9/4.10, unforced) are marked, and every slip→stick position ``X_gh`` is a
    dot.  Several runs are overlaid in grey with run 0 in black.
    """
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
        for r in range(traj.shape[0] - 1, -1, -1):
            col = "k" if r == 0 else "0.6"
            tau = traj[r, :, 0]
            ax3.plot(traj[r, :, 1], traj[r, :, 2], np.mod(p.eta * tau, 2 * np.pi), color=col,
                     lw=0.6)
        tt = np.linspace(0, 2 * np.pi, 200)
        xb = p.n * mus - 2 * p.damping_ratio * p.gamma0 + p.q * np.cos(tt)
        ax3.plot(xb, np.full_like(tt, p.gamma0), tt, "r--", lw=1, label="stick boundary (4.9)")
        ax3.set_xlabel("x1")
        ax3.set_ylabel("x2")
        ax3.set_zlabel("x3 = ητ mod 2π")
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
        ax.set_xlabel("x1 = y/L")
        ax.set_ylabel("x2 = dx1/dτ")
        ax.legend(loc="lower right", fontsize=8)
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=0.3)
    fig.tight_layout()
    target = Path(path)
    suffix = target.suffix.lstrip(".") or "png"
    write_atomic(target, lambda tmp: fig.savefig(tmp, dpi=130, format=suffix))
    return target

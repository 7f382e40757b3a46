"""Figures of the surface analysis, after thesis Fig. 3.7–3.10 (contact figures: :mod:`stochfric.contact.figures`).

Matplotlib's object API with the Agg canvas (no pyplot, no global state, no display): every
function builds a :class:`matplotlib.figure.Figure`, writes it to ``path`` and returns the
path.  Lengths are shown in µm, pressures in MPa (conversion only here, at the edge).
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from stochfric.plotting import new_figure, save_figure
from stochfric.surface.io import Surface
from stochfric.surface.statistics import pdf
from stochfric.surface.summits import Summits
from stochfric.units import MICROMETRE

if TYPE_CHECKING:
    from matplotlib.axes import Axes

__all__ = [
    "plot_fine_vs_coarse",
    "plot_pdfs",
    "plot_surface",
    "write_surface_figures",
]


def _image(ax: Axes, surface: Surface, title: str) -> None:
    lx, ly = (v / MICROMETRE for v in surface.physical_size_m)
    im = ax.imshow(
        surface.heights_m.T / MICROMETRE,
        origin="lower",
        extent=(0.0, lx, 0.0, ly),
        cmap="viridis",
        interpolation="nearest",
    )
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("y [µm]")
    ax.set_title(title)
    ax.figure.colorbar(im, ax=ax, label="z [µm]", shrink=0.8)


def plot_surface(surface: Surface, path: str | Path, *, title: str = "filtered surface") -> Path:
    """The (filtered) height map, as thesis Fig. 3.7 / 3.24."""
    fig = new_figure(6.0, 5.0)
    _image(fig.add_subplot(1, 1, 1), surface, title)
    return save_figure(fig, path)


def plot_fine_vs_coarse(fine: Surface, coarse: Surface, path: str | Path, *, step: int, row: int = 1) -> Path:
    """Fine vs coarse: both maps and one profile along x at ``y = row·Δy_coarse``
    (thesis Fig. 3.8 / 3.9 / 3.25 / 3.26)."""
    fig = new_figure(13.0, 4.2)
    _image(fig.add_subplot(1, 3, 1), fine, f"fine {fine.nb_grid_pts[0]}×{fine.nb_grid_pts[1]}")
    _image(
        fig.add_subplot(1, 3, 2),
        coarse,
        f"coarse (k = {step}) {coarse.nb_grid_pts[0]}×{coarse.nb_grid_pts[1]}",
    )
    ax = fig.add_subplot(1, 3, 3)
    j_c = min(max(row, 0), coarse.nb_grid_pts[1] - 1)
    j_f = min(j_c * step, fine.nb_grid_pts[1] - 1)
    dxf = fine.grid_spacing_m[0]
    dxc = coarse.grid_spacing_m[0]
    ax.plot(
        np.arange(fine.nb_grid_pts[0]) * dxf / MICROMETRE,
        fine.heights_m[:, j_f] / MICROMETRE,
        lw=0.8,
        label="fine",
    )
    ax.plot(
        np.arange(coarse.nb_grid_pts[0]) * dxc / MICROMETRE,
        coarse.heights_m[:, j_c] / MICROMETRE,
        "o-",
        ms=3,
        lw=1.0,
        label="coarse",
    )
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("z [µm]")
    ax.set_title(f"profile at y = {j_c}·Δy (coarse)")
    ax.legend()
    return save_figure(fig, path)


def plot_pdfs(surfaces: Sequence[tuple[str, Surface, Summits]], path: str | Path, *, bins: int = 40) -> Path:
    """PDFs of all heights z, summit heights z_s and radii β for each labelled surface
    (thesis Fig. 3.10 / 3.27).  Summit PDFs use ``clip(√n, 5, bins)`` bins for n summits."""
    fig = new_figure(13.0, 4.0)
    axes = [fig.add_subplot(1, 3, k + 1) for k in range(3)]
    for label, surface, summits in surfaces:
        x, d = pdf(surface.heights_m / MICROMETRE, bins)
        axes[0].plot(x, d, label=label)
        if summits.count >= 2:
            nb = int(np.clip(np.sqrt(summits.count), 5, bins))
            x, d = pdf(summits.heights_m / MICROMETRE, nb)
            axes[1].plot(x, d, label=f"{label} ({summits.count})")
            x, d = pdf(summits.radius_m / MICROMETRE, nb)
            axes[2].plot(x, d, label=label)
    for ax, xlabel, title in zip(
        axes,
        ("z [µm]", "z_s [µm]", "β [µm]"),
        ("all heights", "summit heights", "summit radii"),
        strict=True,
    ):
        ax.set_xlabel(xlabel)
        ax.set_ylabel("probability density [1/µm]")
        ax.set_title(title)
        ax.legend()
    return save_figure(fig, path)


def write_surface_figures(
    directory: str | Path,
    *,
    fine: Surface,
    coarse: Surface,
    fine_summits: Summits,
    coarse_summits: Summits,
    step: int,
) -> list[Path]:
    """All surface figures into ``directory``: ``surface.png``, ``fine_vs_coarse.png``,
    ``pdfs.png``."""
    d = Path(directory)
    return [
        plot_surface(fine, d / "surface.png"),
        plot_fine_vs_coarse(fine, coarse, d / "fine_vs_coarse.png", step=step),
        plot_pdfs([("fine", fine, fine_summits), ("coarse", coarse, coarse_summits)], d / "pdfs.png"),
    ]

"""Figures of the surface analysis, after thesis Fig. 3.7–3.10 (contact figures: :mod:`stochfric.contact.figures`).

Matplotlib's object API with the Agg canvas (no pyplot, no global state, no display): every
``figure_*`` function builds a :class:`matplotlib.figure.Figure` and returns it; the ``plot_*``
function of the same name writes it to ``path`` and returns the path.  Lengths are shown in µm,
pressures in MPa (conversion only here, at the edge).
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
    from matplotlib.figure import Figure
    from matplotlib.image import AxesImage

__all__ = [
    "figure_fine_vs_coarse",
    "figure_pdfs",
    "figure_surface",
    "plot_fine_vs_coarse",
    "plot_pdfs",
    "plot_surface",
    "write_surface_figures",
]


HEIGHT_LABEL = "height z [µm]"


def _image(ax: Axes, surface: Surface, title: str, *, colourbar: bool = True,
           limits: tuple[float, float] | None = None) -> AxesImage:
    lx, ly = (v / MICROMETRE for v in surface.physical_size_m)
    vmin, vmax = limits if limits is not None else (None, None)
    im = ax.imshow(
        surface.heights_m.T / MICROMETRE,
        origin="lower",
        extent=(0.0, lx, 0.0, ly),
        cmap="viridis",
        interpolation="nearest",
        vmin=vmin,
        vmax=vmax,
    )
    ax.set_xlabel("x [µm]")
    ax.set_ylabel("y [µm]")
    ax.set_title(title)
    if colourbar:
        ax.figure.colorbar(im, ax=ax, label=HEIGHT_LABEL, shrink=0.8)
    return im


def figure_surface(surface: Surface, *, title: str = "filtered surface") -> Figure:
    """The (filtered) height map, as thesis Fig. 3.7 / 3.24."""
    fig = new_figure(6.0, 5.0)
    _image(fig.add_subplot(1, 1, 1), surface, title)
    return fig


def plot_surface(surface: Surface, path: str | Path, *, title: str = "filtered surface") -> Path:
    """:func:`figure_surface` written to ``path``."""
    return save_figure(figure_surface(surface, title=title), path)


def figure_fine_vs_coarse(fine: Surface, coarse: Surface, *, step: int, row: int = 1) -> Figure:
    """Fine vs coarse: both maps (one colour scale, one colour bar under them) and one profile along x at
    ``y = row·Δy_coarse`` (thesis Fig. 3.8 / 3.9 / 3.25 / 3.26)."""
    fig = new_figure(13.0, 4.6)
    axes = [fig.add_subplot(1, 3, k + 1) for k in range(3)]
    z = np.concatenate([fine.heights_m.ravel(), coarse.heights_m.ravel()]) / MICROMETRE
    limits = (float(np.nanmin(z)), float(np.nanmax(z)))
    im = _image(axes[0], fine, f"fine {fine.nb_grid_pts[0]}×{fine.nb_grid_pts[1]}", colourbar=False, limits=limits)
    _image(axes[1], coarse, f"coarse (k = {step}) {coarse.nb_grid_pts[0]}×{coarse.nb_grid_pts[1]}",
           colourbar=False, limits=limits)
    fig.colorbar(im, ax=axes[:2], label=HEIGHT_LABEL, orientation="horizontal", shrink=0.6, aspect=40)
    ax = axes[2]
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
    ax.set_ylabel(HEIGHT_LABEL)
    ax.set_title(f"profile at y = {j_c}·Δy (coarse)")
    ax.legend()
    return fig


def plot_fine_vs_coarse(fine: Surface, coarse: Surface, path: str | Path, *, step: int, row: int = 1) -> Path:
    """:func:`figure_fine_vs_coarse` written to ``path``."""
    return save_figure(figure_fine_vs_coarse(fine, coarse, step=step, row=row), path)


def figure_pdfs(surfaces: Sequence[tuple[str, Surface, Summits]], *, bins: int = 40) -> Figure:
    """PDFs of all heights z, summit heights z_s and radii β for each labelled surface
    (thesis Fig. 3.10 / 3.27).  Summit PDFs use ``clip(√n, 5, bins)`` bins for n summits; a panel
    without summits (fewer than two on every surface) says so."""
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
        ax.set_title(title)
        if not ax.lines:
            ax.set_xticks([])
            ax.set_yticks([])
            ax.text(0.5, 0.5, "fewer than two summits", ha="center", va="center", transform=ax.transAxes)
            continue
        ax.set_xlabel(xlabel)
        ax.set_ylabel("probability density [1/µm]")
        ax.legend()
    return fig


def plot_pdfs(surfaces: Sequence[tuple[str, Surface, Summits]], path: str | Path, *, bins: int = 40) -> Path:
    """:func:`figure_pdfs` written to ``path``."""
    return save_figure(figure_pdfs(surfaces, bins=bins), path)


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

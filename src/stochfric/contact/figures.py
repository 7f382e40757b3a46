"""Figures of the contact analysis, after thesis Fig. 3.11 / 3.28 (and 3.14 for the half-space).

Matplotlib's object API on an Agg canvas (:mod:`stochfric.plotting`); lengths in µm, pressures in
MPa (conversion only here, at the edge).  :func:`figure_contact` builds the figure
(``ContactResult.plot``), :func:`plot_contact` writes it.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from stochfric.plotting import MU_LABEL, new_figure, save_figure
from stochfric.units import MEGAPASCAL, MICROMETRE

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

#: Read by its attributes only: not imported, so that ``ContactResult.plot()`` makes no import cycle
#: (``tests/unit/test_layers.py``).
ContactResult = Any  # stochfric.contact.asperity.ContactResult

__all__ = ["figure_contact", "plot_contact", "write_contact_figures"]


def figure_contact(results: Sequence[ContactResult]) -> Figure:
    """A_c, p, number of contacts and μ over u (thesis Fig. 3.11 / 3.28); several results
    (e.g. GW and half-space, Fig. 3.14) are drawn side by side."""
    fig = new_figure(11.0, 8.0)
    axes = [fig.add_subplot(2, 2, k + 1) for k in range(4)]
    for res in results:
        u = res.approach_m / MICROMETRE
        label = res.method
        axes[0].plot(u, res.contact_area_m2 / MICROMETRE**2, "o-", ms=3, label=label)
        axes[1].plot(u, res.pressure_pa / MEGAPASCAL, "o-", ms=3, label=label)
        axes[2].plot(u, res.n_contacts, "o-", ms=3, label=label)
        axes[3].plot(u, res.mu, "o-", ms=3, label=label)
    for ax, ylabel, title in zip(
        axes,
        ("A_c [µm²]", "p [MPa]", "number of contacts (count)", MU_LABEL),
        ("contact area", "nominal pressure", "contacts", "friction coefficient (Bowden–Tabor)"),
        strict=True,
    ):
        ax.set_xlabel("approach u [µm]")
        ax.set_ylabel(ylabel)
        ax.set_title(title)
        ax.legend()
    return fig


def plot_contact(results: Sequence[ContactResult], path: str | Path) -> Path:
    """:func:`figure_contact` written to ``path``."""
    return save_figure(figure_contact(results), path)


def write_contact_figures(directory: str | Path, results: Sequence[ContactResult]) -> list[Path]:
    """``contact.png`` (A_c, p, contacts, μ over u) into ``directory``."""
    return [plot_contact(results, Path(directory) / "contact.png")]

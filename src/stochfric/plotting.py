"""Figures without pyplot: a matplotlib :class:`~matplotlib.figure.Figure` on an Agg canvas, saved atomically.

Every figure module of the package builds its figures with :func:`new_figure` and writes them with
:func:`save_figure`; nothing switches the global matplotlib backend or touches pyplot's state, so
importing the package has no side effect on a user's plotting session.
"""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from stochfric.io_utils import write_atomic

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

__all__ = ["new_figure", "new_subplots", "save_figure"]


def new_figure(
    width: float, height: float, *, layout: Literal["constrained", "compressed", "tight"] | None = "constrained"
) -> Figure:
    """A figure of ``width`` × ``height`` inches on its own Agg canvas (constrained layout by default)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(width, height), layout=layout)
    FigureCanvasAgg(fig)
    return fig


def new_subplots(nrows: int = 1, ncols: int = 1, *, figsize: tuple[float, float], **kwargs: Any) -> tuple[Figure, Any]:
    """``pyplot.subplots`` without pyplot: a figure on its own Agg canvas and its axes (``Figure.subplots``)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig_keys = ("layout", "dpi", "constrained_layout", "tight_layout")
    fig = Figure(figsize=figsize, **{k: kwargs.pop(k) for k in fig_keys if k in kwargs})
    FigureCanvasAgg(fig)
    return fig, fig.subplots(nrows, ncols, **kwargs)


def save_figure(fig: Figure, path: str | Path, *, dpi: int = 110) -> Path:
    """Write ``fig`` to ``path`` atomically (format from the extension, default PNG); returns the path."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fmt = p.suffix.lstrip(".").lower() or "png"
    return write_atomic(p, lambda tmp: fig.savefig(tmp, format=fmt, dpi=dpi))

"""Figures without pyplot: a matplotlib :class:`~matplotlib.figure.Figure` on an Agg canvas, saved atomically.

Every figure module of the package builds its figures with :func:`new_figure` (or :func:`new_subplots`)
in a ``figure_*`` function that returns the :class:`~matplotlib.figure.Figure`, and writes them with
:func:`save_figure`; nothing switches the global matplotlib backend or touches pyplot's state, so
importing the package has no side effect on a user's plotting session, and a returned figure is
collected like any object once it is no longer referenced.

Every axis carries a unit: ``[unit]`` after the quantity, or ``(dimensionless…)`` for the oscillator's
dimensionless variables (the labels below).  :func:`save_figure` checks the tick labels of the drawn
figure and thins the ticks of an axis whose labels overlap (:func:`tick_label_overlaps`,
:func:`thin_ticks`), so a data range no test foresaw still gives readable axes.
"""

from __future__ import annotations

import itertools
import math
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

from stochfric.io_utils import write_atomic

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.axis import Axis
    from matplotlib.figure import Figure
    from matplotlib.text import Text
    from matplotlib.transforms import Bbox

__all__ = [
    "DAMPING_LABEL",
    "ETA_LABEL",
    "MU_LABEL",
    "X1_LABEL",
    "X2_LABEL",
    "X_GH_LABEL",
    "layout_problems",
    "log_ticks",
    "new_figure",
    "new_subplots",
    "save_figure",
    "thin_ticks",
    "tick_label_overlaps",
]

#: Axis labels of the oscillator's dimensionless variables (method §5: x = y/L, τ = ω0 t).
X_GH_LABEL = "X_gh (dimensionless, x = y/L)"
X1_LABEL = "x1 = y/L (dimensionless)"
X2_LABEL = "x2 = dx1/dτ (dimensionless)"
DAMPING_LABEL = "damping ratio D (dimensionless)"
ETA_LABEL = "η = Ω/ω0 (dimensionless)"
MU_LABEL = "μ (dimensionless)"


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
    """Write ``fig`` to ``path`` atomically (format from the extension, default PNG); returns the path.

    A figure without a layout engine gets ``tight_layout`` first.  After the write the drawn tick labels
    are checked: an axis whose labels overlap gets fewer ticks (:func:`thin_ticks`) and the figure is
    written again (at most three times); the common case costs no extra drawing."""
    p = Path(path)
    p.parent.mkdir(parents=True, exist_ok=True)
    fmt = p.suffix.lstrip(".").lower() or "png"
    fig.set_dpi(dpi)  # drawn at the dpi it is saved with: the check below sees the saved layout
    if fig.get_layout_engine() is None:
        fig.tight_layout()
    for _ in range(3):
        write_atomic(p, lambda tmp: fig.savefig(tmp, format=fmt, dpi=dpi))
        crowded = {id(axis): axis for axis, _ in tick_label_overlaps(fig)}
        if not crowded or not any([thin_ticks(axis) for axis in crowded.values()]):
            break
        if fig.get_layout_engine() is None:
            fig.tight_layout()
    return p


def log_ticks(ax: Axes, which: Literal["x", "y"] = "x") -> None:
    """Readable ticks on a logarithmic axis: no labels on minor ticks (a short log range labels them all and
    they overlap); a range of less than 1.5 decades gets 1-2-5 major ticks in plain numbers instead."""
    from matplotlib.ticker import FuncFormatter, LogLocator, NullFormatter

    axis = ax.xaxis if which == "x" else ax.yaxis
    axis.set_minor_formatter(NullFormatter())
    lo, hi = sorted(ax.get_xlim() if which == "x" else ax.get_ylim())
    if lo > 0 and hi > 0 and math.log10(hi / lo) < 1.5:
        axis.set_major_locator(LogLocator(base=10.0, subs=(1.0, 2.0, 5.0)))
        axis.set_major_formatter(FuncFormatter(lambda v, _pos: f"{v:g}"))


def _drawn_tick_labels(axis: Axis, which: Literal["major", "both"] = "both") -> list[Text]:
    """The non-empty tick labels ``axis`` drew in the last draw (inside the view interval, visible)."""
    if not axis.get_visible() or not _axes_on(axis.axes):
        return []
    lo, hi = sorted(float(v) for v in axis.get_view_interval())
    eps = 1e-9 * (hi - lo if hi > lo else max(abs(hi), 1.0))
    out: list[Text] = []
    groups = [axis.get_major_ticks(len(axis.get_majorticklocs()))]
    if which == "both":
        groups.append(axis.get_minor_ticks(len(axis.get_minorticklocs())))
    for ticks in groups:
        for tick in ticks:
            loc = tick.get_loc()
            if loc is None or not (lo - eps <= float(loc) <= hi + eps) or not tick.get_visible():
                continue
            out += [t for t in (tick.label1, tick.label2) if t.get_visible() and t.get_text().strip()]
    return out


def _axes_on(ax: Axes) -> bool:
    """Does ``ax`` draw its axes (a 3-D axes keeps this in ``_axis3don``)?"""
    return bool(getattr(ax, "_axis3don", ax.axison))


def _square(t: Text) -> bool:
    """Is ``t`` drawn at a right angle (its bounding box then is its outline; a 3-D axis label at 30° is not)?"""
    return float(t.get_rotation()) % 90.0 == 0.0


def _overlap(a: Bbox, b: Bbox) -> bool:
    """Boxes sharing an area (touching edges do not count)."""
    return min(a.x1, b.x1) - max(a.x0, b.x0) > 0 and min(a.y1, b.y1) - max(a.y0, b.y0) > 0


def _axes_axes(ax: Axes) -> list[tuple[str, Axis]]:
    names = ("x", "y", "z") if hasattr(ax, "zaxis") else ("x", "y")
    return [(n, getattr(ax, f"{n}axis")) for n in names]


def tick_label_overlaps(fig: Figure) -> list[tuple[Axis, str]]:
    """(axis, description) for every pair of overlapping tick labels of one axis in the figure's last draw
    (x, y and z separately; visible, non-empty labels only).  Draw the figure first (``savefig`` or
    ``fig.canvas.draw()``)."""
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    out = []
    for ax in fig.axes:
        for name, axis in _axes_axes(ax):
            labels = _drawn_tick_labels(axis)
            boxes = [(t.get_text(), t.get_window_extent(renderer)) for t in labels]
            for (ta, a), (tb, b) in itertools.combinations(boxes, 2):
                if _overlap(a, b):
                    out.append((axis, f"{_axes_name(ax)}: {name} tick labels {ta!r} and {tb!r} overlap"))
    return out


def thin_ticks(axis: Axis) -> bool:
    """Fewer ticks on an axis with overlapping labels: no minor labels, then about half the major ticks
    (a fixed set of ticks, e.g. named categories, is rotated first); False when nothing is left to change."""
    from matplotlib.ticker import (
        FixedLocator,
        LogLocator,
        MaxNLocator,
        NullFormatter,
        NullLocator,
        SymmetricalLogLocator,
    )

    n = max(1, len(_drawn_tick_labels(axis, "major")))
    if not isinstance(axis.get_minor_locator(), NullLocator) and not isinstance(axis.get_minor_formatter(),
                                                                                NullFormatter):
        axis.set_minor_formatter(NullFormatter())
        return True
    loc = axis.get_major_locator()
    if isinstance(loc, FixedLocator):
        labels = _drawn_tick_labels(axis, "major")
        if axis is axis.axes.xaxis and labels and labels[0].get_rotation() == 0:
            axis.set_tick_params(labelrotation=30)
            for t in axis.get_majorticklabels():
                t.set_horizontalalignment("right")
            return True
        locs = [float(v) for v in loc.tick_values(0.0, 1.0)]
        if len(locs) <= 2:
            return False
        axis.set_major_locator(FixedLocator(locs[::2]))
        return True
    if isinstance(loc, SymmetricalLogLocator):
        return False
    if isinstance(loc, LogLocator):
        if n <= 2:
            return False
        axis.set_major_locator(LogLocator(base=10.0, numticks=max(2, n // 2 + 1)))
        return True
    if n <= 2:
        return False
    axis.set_major_locator(MaxNLocator(nbins=max(2, n // 2)))
    return True


def _axes_name(ax: Axes) -> str:
    title = ax.get_title() or ax.get_title("left") or ax.get_label()
    return repr(title) if title else f"axes at {tuple(round(v, 2) for v in ax.get_position().bounds)}"


#: Words that give an axis label its unit when no ``[unit]`` does.
UNIT_WORDS = ("dimensionless", "count", "probability")


def _has_data(ax: Axes) -> bool:
    import numpy as np

    for line in ax.lines:
        x, y = (np.asarray(v, dtype=float) for v in line.get_data())
        if x.size and np.isfinite(x).any() and np.isfinite(y).any():
            return True
    for c in ax.collections:
        offsets = np.asarray(getattr(c, "get_offsets", list)())
        if offsets.size or len(c.get_paths()):
            return True
    return bool(ax.images or ax.patches or ax.containers)


def layout_problems(fig: Figure, *, dpi: float | None = None, draw: bool = True) -> list[str]:
    """What is wrong with the figure's layout, as it is drawn at ``dpi`` (default: the figure's):

    overlapping tick labels of one axis; an axis with tick labels but no label, or a label without a
    unit (``[…]`` or one of :data:`UNIT_WORDS`); a panel without data (lines, collections, images or
    patches; a panel with no ticks and a text note counts as a note); titles, axis labels and tick labels
    of different axes on top of each other; the same label twice side by side (two neighbouring
    panels' identical y labels); text cut off at the figure's edge.  Empty list: none of these."""
    if dpi is not None:
        fig.set_dpi(dpi)
    if draw:
        fig.draw_without_rendering()  # the layout and every text's place, without rasterising
    renderer = fig.canvas.get_renderer()  # type: ignore[attr-defined]
    problems = [why for _, why in tick_label_overlaps(fig)]
    texts: list[tuple[int, str, str, Text]] = []  # (axes, role, description, text)
    for k, ax in enumerate(fig.axes):
        if not ax.get_visible():
            continue
        name = _axes_name(ax)
        colourbar = hasattr(ax, "_colorbar")
        for axis_name, axis in _axes_axes(ax):
            ticks = _drawn_tick_labels(axis)
            label = axis.get_label_text().strip() if axis.label.get_visible() else ""
            if ticks and not label:
                problems.append(f"{name}: the {axis_name} axis has tick labels but no label")
            elif ticks and "[" not in label and not any(w in label for w in UNIT_WORDS):
                problems.append(f"{name}: the {axis_name} label {label!r} has no unit")
            texts += [(k, f"{axis_name} tick", f"{axis_name} tick label {t.get_text()!r}", t) for t in ticks]
            if label:
                texts.append((k, f"{axis_name} label", f"{axis_name} label {label!r}", axis.label))
            offset = axis.get_offset_text()
            if ticks and offset.get_visible() and offset.get_text().strip():
                texts.append((k, f"{axis_name} offset", f"{axis_name} offset {offset.get_text()!r}", offset))
        for title in (ax.title, ax._left_title, ax._right_title):  # type: ignore[attr-defined]
            if title.get_visible() and title.get_text().strip():
                texts.append((k, "title", f"title {title.get_text()!r}", title))
        if colourbar or not _axes_on(ax):
            if not colourbar and not (ax.images or ax.collections):
                problems.append(f"{name}: a panel without axes shows nothing")
            continue
        has_ticks = any(_drawn_tick_labels(axis) for _, axis in _axes_axes(ax))
        if not _has_data(ax) and (has_ticks or not ax.texts):
            problems.append(f"{name}: an empty panel (no data drawn)")
    if fig._suptitle is not None and fig._suptitle.get_text().strip():  # type: ignore[attr-defined]
        suptitle = fig._suptitle  # type: ignore[attr-defined]
        texts.append((-1, "suptitle", f"suptitle {suptitle.get_text()!r}", suptitle))
    boxes = [(k, role, what, t, t.get_window_extent(renderer)) for k, role, what, t in texts]
    width, height = fig.bbox.width, fig.bbox.height
    problems += [f"{what} (axes {k}) is cut off at the figure's edge" for k, _, what, _, b in boxes
                 if b.x0 < -1 or b.y0 < -1 or b.x1 > width + 1 or b.y1 > height + 1]
    # one axis's own tick labels: tick_label_overlaps above; every other pair here
    for (ka, ra, wa, ta, a), (kb, rb, wb, tb, b) in itertools.combinations(boxes, 2):
        if (ka != kb or ra != rb) and _square(ta) and _square(tb) and _overlap(a, b):
            problems.append(f"{wa} (axes {ka}) overlaps {wb} (axes {kb})")
        elif (ka != kb and ta.get_text() == tb.get_text() and ra.endswith(" label") and rb.endswith(" label")
              and ta.get_rotation() == tb.get_rotation() == 90
              and min(abs(a.x0 - b.x1), abs(b.x0 - a.x1)) < 40 and min(a.y1, b.y1) > max(a.y0, b.y0)):
            problems.append(f"{wa} twice side by side (axes {ka} and {kb})")
    return problems

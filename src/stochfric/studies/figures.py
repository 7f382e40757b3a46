"""Figures of the studies (matplotlib Agg; PNG files only).

Each ``figure_*(ds)`` builds one :class:`~matplotlib.figure.Figure` from a study's dataset (``None``
where the dataset lacks what it shows); each ``*_figures(ds, directory)`` draws a kind's figures with
them, writes them and returns ``[(path, caption), …]``; captions name the thesis figure the plot
corresponds to.  :func:`study_figure` picks a kind's figure by name (``StudyResult.plot``).
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import TYPE_CHECKING, Any

import matplotlib
import numpy as np
import xarray as xr
from matplotlib.ticker import MaxNLocator

from ..oscillator.options import Model
from ..plotting import DAMPING_LABEL, ETA_LABEL, X1_LABEL, X2_LABEL, X_GH_LABEL, new_subplots, save_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure as MplFigure

#: A written figure: its path and caption.
Figure = tuple[Path, str]
_COLORS: dict[str, str] = {Model.DETERMINISTIC: "k", Model.WHITE: "tab:blue", Model.CONTACT: "tab:red"}
#: diverging colour map of the M_diff panels; its low end is red, so M_diff < 0 (more stick-slip than the
#: deterministic run) is red
MDIFF_CMAP = "RdBu"


def colour_name(rgba: tuple[float, ...]) -> str:
    """"red", "blue" or "white/grey" for an RGBA colour (the dominant channel)."""
    r, _g, b = rgba[:3]
    if abs(r - b) < 0.15:
        return "white/grey"
    return "red" if r > b else "blue"


def mdiff_colours() -> tuple[str, str]:
    """(colour of negative, colour of positive) M_diff in :data:`MDIFF_CMAP`."""
    cmap = matplotlib.colormaps.get_cmap(MDIFF_CMAP)
    return colour_name(cmap(0.0)), colour_name(cmap(1.0))


def tidy_x_ticks(ax: Any, nbins: int = 4) -> None:
    """At most ``nbins`` x ticks, long numbers as a common ×10^k offset: no overlapping labels."""
    ax.xaxis.set_major_locator(MaxNLocator(nbins=nbins))
    ax.ticklabel_format(axis="x", style="sci", scilimits=(-3, 4), useOffset=True)


def no_data(ax: Any, text: str) -> None:
    """Replace an empty panel's blank 0–1 axes by a centred note (e.g. "no stick")."""
    ax.set_xticks([])
    ax.set_yticks([])
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, fontsize=10, color="0.35")


def grid_edges(dd: Any, d_max: Any) -> tuple[Any, Any]:
    """Masks of D_max values at the grid's end (the true limit is beyond the grid) and missing ones
    (no stick-slip even at the grid's first D: the limit lies below the grid start)."""
    v = np.asarray(d_max, dtype=float)
    at_end = np.isfinite(v) & (v >= float(np.max(dd)) - 1e-12)
    below = ~np.isfinite(v)
    return at_end, below


def _legend(ax: Any, size: int) -> None:
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=size)


def _save(fig: Any, path: Path) -> Path:
    """Write a study figure (PNG, 110 dpi; overlapping tick labels thinned: :func:`~stochfric.plotting.save_figure`)."""
    return save_figure(fig, path, dpi=110)


def _mesh_limits(ax: Any, dd: Any, nn: Any) -> None:
    """Axis limits of a ``pcolormesh(dd, nn, …, shading="nearest")``: the cells' outer edges, so that lines
    drawn beyond the grid (D_H below the first D) leave no empty strip next to the map."""
    def edges(v: Any) -> tuple[float, float]:
        v = np.sort(np.asarray(v, dtype=float))
        if v.size < 2:
            half = 0.5 * abs(float(v[0])) if v.size and v[0] != 0 else 0.5
            return float(v[0]) - half, float(v[0]) + half
        return float(v[0] - 0.5 * (v[1] - v[0])), float(v[-1] + 0.5 * (v[-1] - v[-2]))

    ax.set_xlim(*edges(dd))
    ax.set_ylim(*edges(nn))


def _gamma0(ds: xr.Dataset) -> float | None:
    try:
        return float(json.loads(ds.attrs["setup_json"])["gamma0"])
    except (KeyError, ValueError, TypeError):
        return None


def figure_damping_phase(ds: xr.Dataset) -> MplFigure | None:
    """Phase curves x2 over x1 at one force for several D, one panel per model (Fig. 4.22/4.24/4.27,
    sheet 4.53/4.55/4.58); ``None`` when the dataset has no ``phase_trajectory``."""
    if "phase_trajectory" not in ds:
        return None
    models = [str(m) for m in ds["model"].values]
    pd = ds["phase_damping"].values
    nf = float(ds["phase_normal_force_n"].values)
    g0 = _gamma0(ds)
    cmap = matplotlib.colormaps.get_cmap("viridis")
    cols = [cmap(0.9 * k / max(1, pd.size - 1)) for k in range(pd.size)]
    fig, axes = new_subplots(1, len(models), figsize=(4.4 * len(models), 3.8), squeeze=False, sharex=True,
                             sharey=True, layout="constrained")
    for j, m in enumerate(models):
        ax = axes[0, j]
        tr = ds["phase_trajectory"].sel(model=m).values  # [D, run, sample, component]
        for k, dval in enumerate(pd):
            for r in range(tr.shape[1]):
                x1, x2 = tr[k, r, :, 1], tr[k, r, :, 2]
                if np.isfinite(x1).any():
                    ax.plot(x1, x2, lw=0.9 if r == 0 else 0.5, alpha=1.0 if r == 0 else 0.6, color=cols[k],
                            label=f"D = {dval:g}" if r == 0 else None)
        if g0 is not None:
            ax.axhline(g0, color="0.5", lw=0.7, ls=":")
        nrun = int(np.isfinite(tr[0, :, 0, 1]).sum()) if tr.size else 0
        ax.set_title(f"{m}, N = {nf:g} N" + (f" ({nrun} runs per D)" if m != Model.DETERMINISTIC else ""), fontsize=9)
        ax.set_xlabel(X1_LABEL)
        if j == 0:
            ax.set_ylabel(X2_LABEL)
            _legend(ax, 7)
        tidy_x_ticks(ax)
    return fig


def damping_phase_figure(ds: xr.Dataset, directory: str | Path, prefix: str = "damping") -> list[Figure]:
    """:func:`figure_damping_phase` written to ``<prefix>_phase.png``; empty when the dataset has no
    ``phase_trajectory``."""
    fig = figure_damping_phase(ds)
    if fig is None:
        return []
    pd = ds["phase_damping"].values
    nf = float(ds["phase_normal_force_n"].values)
    return [(_save(fig, Path(directory) / f"{prefix}_phase.png"),
             f"Phase curves x2 over x1 at N = {nf:g} N for damping ratios D = "
             + ", ".join(f"{v:g}" for v in pd)
             + " (thesis Fig. 4.22 deterministic, 4.24 white noise, 4.27 contact analysis; sheet Fig. 4.53, 4.55, "
             "4.58): with growing D the stick-slip cycle shrinks until the stick line x2 = γ0 (dotted) is no longer "
             "reached and the motion decays onto steady sliding; stochastic models: several runs per D.")]


def figure_damping_maps(ds: xr.Dataset) -> MplFigure:
    """E[X_gh] and E[M] over (D, N), one column per model (Fig. 4.23/4.25/4.28); one force: curves over D."""
    models = [str(m) for m in ds["model"].values]
    dd = ds["damping_ratio"].values
    nn = ds["normal_force_n"].values
    fig, axes = new_subplots(2, len(models), figsize=(4.2 * len(models), 6.4), squeeze=False, layout="constrained")
    quantities = (("x_gh_mean", "E[X_gh]", "E[X_gh] (dimensionless, x = y/L)"),
                  ("stick_count_mean", "E[M]", "E[M] (count per run)"))
    for j, m in enumerate(models):
        for i, (var, short, lab) in enumerate(quantities):
            ax = axes[i, j]
            z = ds[var].sel(model=m).values
            if nn.size > 1:
                pc = ax.pcolormesh(dd, nn, z, shading="nearest", cmap="viridis")
                cb = fig.colorbar(pc, ax=ax, label=lab)
                cb.ax.yaxis.set_major_locator(MaxNLocator(nbins=5))
                ax.plot(ds["d_hopf"].values, nn, "w--", lw=1, label="D_H")
                _mesh_limits(ax, dd, nn)
                ax.set_ylabel("N [N]")
            else:
                ax.plot(dd, z[0], "o-", ms=3, color=_COLORS.get(m, "k"))
                ax.axvline(float(ds["d_hopf"].values[0]), ls="--", color="0.5", label="D_H")
                ax.set_ylabel(lab)
            ax.set_xlabel(DAMPING_LABEL)
            ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
            ax.set_title(f"{m}: {short}" + (" (0: no stick)" if var == "x_gh_mean" else ""), fontsize=9)
    return fig


def figure_damping_mdiff(ds: xr.Dataset) -> MplFigure | None:
    """M_diff = M_d − E[M_s] over (D, N) per stochastic model (4.26/4.29); ``None`` without ``m_diff``."""
    if "m_diff" not in ds:
        return None
    dd = ds["damping_ratio"].values
    nn = ds["normal_force_n"].values
    sm = [str(m) for m in ds["stochastic_model"].values]
    fig, axes = new_subplots(1, len(sm), figsize=(4.4 * len(sm), 3.6), squeeze=False, layout="constrained")
    for j, m in enumerate(sm):
        ax = axes[0, j]
        z = ds["m_diff"].sel(stochastic_model=m).values
        if nn.size > 1:
            lim = max(1.0, float(np.nanmax(np.abs(z))))
            pc = ax.pcolormesh(dd, nn, z, shading="nearest", cmap=MDIFF_CMAP, vmin=-lim, vmax=lim)
            fig.colorbar(pc, ax=ax, label="M_diff (count per run)")
            _mesh_limits(ax, dd, nn)
            ax.set_ylabel("N [N]")
        else:
            ax.plot(dd, z[0], "o-", ms=3)
            ax.axhline(0, color="0.5", lw=0.8)
            ax.set_ylabel("M_diff (count per run)")
        ax.set_xlabel(DAMPING_LABEL)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
        ax.set_title(f"M_diff = M_d − E[M_s], {m} (4.41)\n< 0: more stick-slip than deterministic", fontsize=8)
    return fig


def damping_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "damping") -> list[Figure]:
    """X_gh and M maps over (D, N) (Fig. 4.23/4.25/4.28), M_diff (4.26/4.29), P(D) and D_max(N), and the
    phase curves over D at one force (4.22/4.24/4.27)."""
    d = Path(directory)
    out: list[Figure] = damping_phase_figure(ds, d, prefix)
    nn = ds["normal_force_n"].values
    out.append((_save(figure_damping_maps(ds), d / f"{prefix}_maps.png"),
                "X_gh (thesis convention: 0 where no stick in the window) and the stick count M over D and N "
                "for each model (thesis Fig. 4.23, 4.25, 4.28; sheet 4.54–4.59); dashed: Hopf boundary D_H."))
    mdiff = figure_damping_mdiff(ds)
    if mdiff is not None:
        neg, pos = mdiff_colours()
        out.append((_save(mdiff, d / f"{prefix}_mdiff.png"),
                    f"M_diff = M_d − E[M_s] (eq. 4.41, thesis Fig. 4.26a/4.29a): {neg} (negative) where the "
                    "stochastic runs stick more often than the deterministic one — there the deterministic answer "
                    f"underestimates stick-slip; {pos} (positive) where the deterministic run sticks more often."))
    if nn.size > 1:
        out.append(_probability_map(ds, d, prefix))
    if "d_max_risk" in ds:  # a result without risk levels has the sample extreme only
        out.append(_risk_figure(ds, d, prefix))
        out.append(_dmax_figure(ds, d, prefix))
    return out


def _pct(a: float) -> str:
    return f"{100 * a:g} %"


def _risk(ds: xr.Dataset, name: str, m: str, j: int = 0) -> Any:
    """``name`` (``d_max_risk``, ``_low``, ``_high``, ``_high_open``) of model ``m``, ``j``-th risk level, over N."""
    return ds[name].sel(model=m).values[:, j]


def figure_damping_probability(ds: xr.Dataset) -> MplFigure:
    """P(stick-slip cycle) as a heat map over D × N, one panel per model, with D_max^d, D_max(α) of the panel's
    model at the first risk level α (bars: its interval) and D_H (small multiples instead of one panel of
    3 × len(N) overlapping curves and bands)."""
    models = [str(m) for m in ds["model"].values]
    dd = ds["damping_ratio"].values
    nn = ds["normal_force_n"].values
    fig, axes = new_subplots(1, len(models), figsize=(4.2 * len(models), 3.6), squeeze=False, sharey=True,
                             layout="constrained")
    dd_det = ds["d_max_sample_extreme"].sel(model=Model.DETERMINISTIC).values if Model.DETERMINISTIC in models else None
    risk = "d_max_risk" in ds
    a0 = float(ds["risk_level"].values[0]) if risk else float("nan")
    pc = None
    for j, m in enumerate(models):
        ax = axes[0, j]
        p = ds["stick_probability"].sel(model=m).values
        pc = ax.pcolormesh(dd, nn, p, shading="nearest", cmap="Greys", vmin=0, vmax=1)
        if dd_det is not None:
            ax.plot(dd_det, nn, "o-", color="tab:orange", ms=3, lw=1.2, label=r"$D_\mathrm{max}^d$")
        if m != Model.DETERMINISTIC and risk:
            v, lo, hi = (_risk(ds, k, m) for k in ("d_max_risk", "d_max_risk_low", "d_max_risk_high"))
            col = _COLORS.get(m, "k")
            ax.plot(v, nn, "s--", color=col, ms=3, lw=1.2, label=r"$D_\mathrm{max}$" + f"({_pct(a0)})")
            ok = np.isfinite(v)
            ax.hlines(nn[ok], np.where(np.isfinite(lo), lo, float(np.min(dd)))[ok],
                      np.where(np.isfinite(hi), hi, float(np.min(dd)))[ok], color=col, lw=2.5, alpha=0.35)
        ax.plot(ds["d_hopf"].values, nn, ":", color="tab:green", lw=1.2, label=r"$D_H$")
        _mesh_limits(ax, dd, nn)
        if j == 0:
            ax.set_ylabel("N [N]")
        ax.set_xlabel(DAMPING_LABEL)
        ax.set_title(f"{m}: P(stick-slip cycle)", fontsize=9)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
        _legend(ax, 7)
    if pc is not None:
        fig.colorbar(pc, ax=list(axes[0]), label="P(stick-slip cycle) (probability)", fraction=0.03)
    return fig


def _probability_map(ds: xr.Dataset, d: Path, prefix: str) -> Figure:
    """:func:`figure_damping_probability` written, with its caption."""
    path = _save(figure_damping_probability(ds), d / f"{prefix}_probability.png")
    risk = "d_max_risk" in ds
    a0 = float(ds["risk_level"].values[0]) if risk else float("nan")
    what = (f"D_max({_pct(a0)}) of the panel's model (largest D with P ≥ {_pct(a0)}; pale bar: its interval)" if risk
            else "no D_max(α) (a result saved before it existed)")
    return (path, "Probability of a stick-slip cycle after the transient (fraction of runs; grey scale, white = "
                  "0, black = 1) over damping D and normal force N, one panel per model; lines: D_max^d "
                  f"(deterministic, orange), {what} and the Hopf boundary D_H (dotted).")


def _risk_force_index(ds: xr.Dataset) -> int:
    """The force of the risk figure: the phase force, else the middle force."""
    nn = ds["normal_force_n"].values
    nf = float(ds["phase_normal_force_n"].values) if "phase_normal_force_n" in ds else float(nn[(nn.size - 1) // 2])
    return int(np.argmin(np.abs(nn - nf)))


def figure_damping_risk(ds: xr.Dataset) -> MplFigure | None:
    """P(stick-slip | D) with its Clopper–Pearson band at the phase force (else the middle force), one panel per
    stochastic model; each risk level α dashed, D_max(α) marked at height α with its interval (an open upper end
    drawn to the grid end with ▷), D_H and D_max^d as vertical lines.  ``None`` without risk levels."""
    if "d_max_risk" not in ds:
        return None
    models = [str(m) for m in ds["model"].values]
    dd = ds["damping_ratio"].values
    nn = ds["normal_force_n"].values
    stoch = [m for m in models if m != Model.DETERMINISTIC] or models
    i = _risk_force_index(ds)
    alphas = [float(a) for a in ds["risk_level"].values]
    conf = json.loads(ds.attrs.get("config_json", "{}")).get("confidence", 0.95)
    fig, axes = new_subplots(1, len(stoch), figsize=(4.6 * len(stoch), 3.6), squeeze=False, sharey=True,
                             layout="constrained")
    det = float(ds["d_max_sample_extreme"].sel(model=Model.DETERMINISTIC).values[i]) if Model.DETERMINISTIC in models \
        else np.nan
    grey = ("0.25", "0.55", "0.75")
    for j, m in enumerate(stoch):
        ax = axes[0, j]
        col = _COLORS.get(m, "k")
        p = ds["stick_probability"].sel(model=m).values[i]
        lo = ds["stick_probability_low"].sel(model=m).values[i]
        hi = ds["stick_probability_high"].sel(model=m).values[i]
        nrun = int(ds["n_runs"].sel(model=m).values[i, 0])
        ax.fill_between(dd, lo, hi, color=col, alpha=0.18, step="mid", label=f"{100 * conf:g} % band")
        ax.plot(dd, p, "o-", ms=2.5, lw=1, color=col, label=f"P ({nrun} runs)")
        ax.axvline(float(ds["d_hopf"].values[i]), ls=":", color="tab:green", lw=1.2, label=r"$D_H$")
        if np.isfinite(det):
            ax.axvline(det, ls="-", color="tab:orange", lw=1.2, label=r"$D_\mathrm{max}^d$")
        for k, a in enumerate(alphas):
            g = grey[min(k, len(grey) - 1)]
            ax.axhline(a, ls="--", lw=0.8, color=g)
            v = float(_risk(ds, "d_max_risk", m, k)[i])
            rlo = float(_risk(ds, "d_max_risk_low", m, k)[i])
            rhi = float(_risk(ds, "d_max_risk_high", m, k)[i])
            open_hi = bool(_risk(ds, "d_max_risk_high_open", m, k)[i])
            x0 = rlo if np.isfinite(rlo) else float(np.min(dd))
            if np.isfinite(rhi):
                ax.plot([x0, rhi], [a, a], "-", color=g, lw=4, alpha=0.6, solid_capstyle="butt")
                if open_hi:
                    ax.plot([rhi], [a], ">", color=g, ms=7)
            if np.isfinite(v):
                ax.plot([v], [a], "D", color=col, mec="k", ms=5,
                        label=r"$D_\mathrm{max}$(α) [interval]" if k == 0 else None)
        ax.set_yscale("symlog", linthresh=min(alphas), linscale=0.6)
        ax.set_ylim(0, 1.05)
        ax.set_xlabel(DAMPING_LABEL)
        if j == 0:
            ax.set_ylabel("P(stick-slip | D) (probability)")
        ax.set_title(f"{m}, N = {nn[i]:g} N; dashed: α = " + ", ".join(_pct(a) for a in alphas), fontsize=8)
        ax.xaxis.set_major_locator(MaxNLocator(nbins=5))
        if j == 0:
            _legend(ax, 7)
    return fig


def _risk_figure(ds: xr.Dataset, d: Path, prefix: str) -> Figure:
    """:func:`figure_damping_risk` written, with its caption."""
    fig = figure_damping_risk(ds)
    assert fig is not None
    nn = ds["normal_force_n"].values
    i = _risk_force_index(ds)
    conf = json.loads(ds.attrs.get("config_json", "{}")).get("confidence", 0.95)
    return (_save(fig, d / f"{prefix}_risk.png"),
            f"P(stick-slip | D) at N = {nn[i]:g} N with its per-D Clopper–Pearson {100 * conf:g} % band (shaded), "
            "one panel per stochastic model; dashed: the risk levels α; ◆ D_max(α) = the largest D with estimated "
            "P ≥ α, grey bar: its interval [largest D whose lower bound is ≥ α, largest D whose upper bound is ≥ α] "
            "(▷: open, the upper end is the grid end — the runs cannot exclude P ≥ α there); orange: D_max^d "
            "(deterministic), dotted green: the Hopf boundary D_H. Vertical axis linear below the smallest α, "
            "logarithmic above.")


def figure_damping_dmax(ds: xr.Dataset) -> MplFigure | None:
    """D_max^d and D_max(α) at the first risk level over N with the interval bars; limits at the grid's end drawn
    as ▲ "> grid", missing ones (no cycle even at the first grid D) as ▼ "< grid start"; the sample extreme
    (thesis D_max^s) as small ×.  ``None`` without risk levels."""
    if "d_max_risk" not in ds:
        return None
    models = [str(m) for m in ds["model"].values]
    dd = ds["damping_ratio"].values
    nn = ds["normal_force_n"].values
    fig, ax = new_subplots(figsize=(6.4, 3.8), layout="constrained")
    span = float(nn.max() - nn.min()) if nn.size > 1 else 1.0
    labelled: set[tuple[int, str]] = set()
    a0 = float(ds["risk_level"].values[0])
    for k, m in enumerate(models):
        det = m == Model.DETERMINISTIC
        y = ds["d_max_sample_extreme"].sel(model=m).values if det else _risk(ds, "d_max_risk", m)
        lo = y if det else _risk(ds, "d_max_risk_low", m)
        hi = y if det else _risk(ds, "d_max_risk_high", m)
        off = (k - 1) * 0.012 * (span if nn.size > 1 else 1.0)
        x = nn + off
        col = _COLORS.get(m, "k")
        at_end, below = grid_edges(dd, y)
        inside = ~at_end & ~below
        name = r"$D_\mathrm{max}^d$" if det else r"$D_\mathrm{max}$" + f"({_pct(a0)}), {m}"
        ax.plot(x, np.where(below, np.nan, y), "-", color=col, lw=1, alpha=0.6)
        ax.plot(x[inside], y[inside], "o", color=col, label=name)
        y0 = float(np.min(dd))
        if at_end.any():
            ax.plot(x[at_end], y[at_end], "^", color=col, ms=8, mfc="none", mew=1.5)
        if below.any():
            ax.plot(x[below], np.full(int(below.sum()), y0), "v", color=col, ms=8, mfc="none", mew=1.5)
        for i in (int(j) for j in np.nonzero(at_end | below)[0]):  # one label per force, shared by the models
            kind_txt = "> grid" if at_end[i] else "< grid start"
            if (i, kind_txt) not in labelled:
                labelled.add((i, kind_txt))
                ax.annotate(kind_txt, (nn[i], y[i] if at_end[i] else y0), textcoords="offset points",
                            xytext=(0, 8) if at_end[i] else (12, -4), ha="center" if at_end[i] else "left",
                            fontsize=7, color="0.25")
        if not det:
            ok = np.isfinite(hi)
            bottom = np.where(np.isfinite(lo), lo, y0)
            ax.vlines(x[ok], bottom[ok], hi[ok], color=col, alpha=0.5, lw=2)
            opn = ok & _risk(ds, "d_max_risk_high_open", m).astype(bool)
            if opn.any():
                ax.plot(x[opn], hi[opn], "^", color=col, ms=6, alpha=0.7)
            ext = ds["d_max_sample_extreme"].sel(model=m).values
            ax.plot(x + 0.5 * off if nn.size > 1 else x, ext, "x", color=col, ms=5, alpha=0.7,
                    label=f"sample extreme, {m}" if k == len(models) - 1 else None)
    ax.plot(nn, ds["d_hopf"].values, "s--", color="0.4", label=r"$D_H$ (linear)")
    ax.axhspan(float(np.min(dd)), float(np.max(dd)), color="0.93", zorder=-1, label="D grid")
    ax.set_xlabel("N [N]")
    ax.set_ylabel("D_max, D_H: damping ratio (dimensionless)")
    ax.set_title(r"$D_\mathrm{max}^d$ and $D_\mathrm{max}$" + f"({_pct(a0)}) with interval (bars); "
                 "×: sample extreme", fontsize=9)
    lo_d, hi_d = float(np.min(dd)), float(np.max(dd))
    ax.set_ylim(lo_d - 0.15 * (hi_d - lo_d + 1e-3), hi_d + 0.15 * (hi_d - lo_d + 1e-3))
    ax.xaxis.set_major_locator(MaxNLocator(nbins=6))
    _legend(ax, 7)
    return fig


def _dmax_figure(ds: xr.Dataset, d: Path, prefix: str) -> Figure:
    """:func:`figure_damping_dmax` written, with its caption."""
    fig = figure_damping_dmax(ds)
    assert fig is not None
    a0 = float(ds["risk_level"].values[0])
    return (_save(fig, d / f"{prefix}_dmax.png"),
            f"D_max^d (deterministic) and D_max({_pct(a0)}) (white, contact: the largest D with P(stick-slip) ≥ "
            f"{_pct(a0)}; bars: its interval from the per-D Clopper–Pearson bands, ▲ on a bar: open upper end) and "
            "the Hopf boundary D_H over N; ×: the sample extreme (thesis D_max^s, the largest D at which any run "
            "stuck — it grows with the number of runs). ▲ \"> grid\": at the last grid D, so the limit lies beyond "
            "the grid; ▼ \"< grid start\": below the first grid D.")


def figure_forcing_bifurcation(ds: xr.Dataset) -> MplFigure:
    """Bifurcation diagrams: X_gh over η, deterministic (black) and every stochastic run (grey), one panel per
    forcing amplitude and stochastic model (Fig. 4.30/4.34/4.61)."""
    models = [str(m) for m in ds["model"].values]
    eta = ds["eta"].values
    qs = ds["forcing_q"].values
    stoch = [m for m in models if m != Model.DETERMINISTIC]
    fig, axes = new_subplots(len(qs), max(1, len(stoch)), figsize=(5 * max(1, len(stoch)), 3.4 * len(qs)),
                             squeeze=False, layout="constrained")
    for i, q in enumerate(qs):
        for j, m in enumerate(stoch or models):
            ax = axes[i, j]
            x = ds["x_gh"].sel(model=m, forcing_q=q).where(ds["in_window"].sel(model=m, forcing_q=q) > 0).values
            for k, e in enumerate(eta):
                v = x[k].ravel()
                v = v[np.isfinite(v)]
                ax.plot(np.full(v.size, e), v, ".", color="0.6", ms=2)
            if Model.DETERMINISTIC in models:
                xd = ds["x_gh"].sel(model=Model.DETERMINISTIC, forcing_q=q).where(
                    ds["in_window"].sel(model=Model.DETERMINISTIC, forcing_q=q) > 0).values
                for k, e in enumerate(eta):
                    v = xd[k, 0]
                    v = v[np.isfinite(v)]
                    ax.plot(np.full(v.size, e), v, ".", color="k", ms=3)
            ax.set_title(f"q = {q:g}: deterministic (black), {m} (grey)", fontsize=9)
            ax.set_xlabel(ETA_LABEL)
            ax.set_ylabel(X_GH_LABEL)
            tidy_x_ticks(ax, 6)
            _tidy_y(ax)
    return fig


def figure_forcing_mean_std(ds: xr.Dataset) -> MplFigure:
    """E[X_gh] ± σ(X_gh) over η for each model, one panel per forcing amplitude (Fig. 4.31/4.35/4.64/4.68)."""
    models = [str(m) for m in ds["model"].values]
    eta = ds["eta"].values
    qs = ds["forcing_q"].values
    fig, axes = new_subplots(1, len(qs), figsize=(5 * len(qs), 3.6), squeeze=False, layout="constrained")
    for i, q in enumerate(qs):
        ax = axes[0, i]
        for k, m in enumerate(models):
            mu = ds["x_gh_mean"].sel(model=m, forcing_q=q).values
            sd = ds["x_gh_std"].sel(model=m, forcing_q=q).values
            off = (k - 1) * 0.01
            ax.errorbar(eta + off, mu, yerr=sd, fmt="o", ms=2.5, capsize=1.5, color=_COLORS.get(m, "k"), label=m)
        ax.set_title(f"E[X_gh] ± σ, q = {q:g}", fontsize=9)
        ax.set_xlabel(ETA_LABEL)
        ax.set_ylabel("E[X_gh] ± σ (dimensionless, x = y/L)")
        tidy_x_ticks(ax, 6)
        _tidy_y(ax)
        _legend(ax, 7)
    return fig


def figure_forcing_sigma_ratio(ds: xr.Dataset) -> MplFigure | None:
    """σ(X_gh) contact / white over η per forcing amplitude; ``None`` without ``sigma_ratio``."""
    if "sigma_ratio" not in ds:
        return None
    eta = ds["eta"].values
    fig, ax = new_subplots(figsize=(6, 3.4), layout="constrained")
    for q in ds["forcing_q"].values:
        ax.plot(eta, ds["sigma_ratio"].sel(forcing_q=q).values, "o-", ms=3, label=f"q = {q:g}")
    ax.axhline(1.0, color="0.5", lw=0.8)
    ax.set_xlabel(ETA_LABEL)
    ax.set_ylabel("σ_contact / σ_white (dimensionless)")
    tidy_x_ticks(ax, 6)
    _legend(ax, 8)
    return fig


def forcing_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "forcing") -> list[Figure]:
    """Bifurcation diagrams (Fig. 4.30/4.34/4.61), E[X_gh] ± σ over η (4.31/4.35/4.64/4.68)."""
    d = Path(directory)
    out: list[Figure] = [
        (_save(figure_forcing_bifurcation(ds), d / f"{prefix}_bifurcation.png"),
         "Bifurcation diagrams: X_gh after the transient over the forcing frequency η, deterministic (black) "
         "and all stochastic runs (grey) (thesis Fig. 4.30, 4.34, 4.61)."),
        (_save(figure_forcing_mean_std(ds), d / f"{prefix}_mean_std.png"),
         "E[X_gh] ± σ(X_gh) over η for each model (thesis Fig. 4.31, 4.35, 4.64, 4.68)."),
    ]
    ratio = figure_forcing_sigma_ratio(ds)
    if ratio is not None:
        out.append((_save(ratio, d / f"{prefix}_sigma_ratio.png"),
                    "Ratio of the X_gh standard deviations, contact-analysis process over white noise "
                    "(thesis: ≈ 1.2 brake small q, ≈ 1.05 brake large q, ≈ 2.5 sheet)."))
    return out


def _tidy_y(ax: Any, nbins: int = 6) -> None:
    """At most ``nbins`` y ticks, small numbers with a common ×10^k offset (X_gh ~ 1e-4)."""
    ax.yaxis.set_major_locator(MaxNLocator(nbins=nbins))
    ax.ticklabel_format(axis="y", style="sci", scilimits=(-3, 4), useOffset=True)


def figure_lyapunov(ds: xr.Dataset) -> MplFigure:
    """λ / E[Λ] over η for each N (Fig. 4.41–4.43, 4.69–4.71); merged pairs marked ×, diverging cells
    (λ a lower bound) ▲; a panel without any defined value says why instead of drawing empty axes."""
    models = [str(m) for m in ds["model"].values]
    qs = ds["forcing_q"].values
    nn = ds["normal_force_n"].values
    eta = ds["eta"].values
    fig, axes = new_subplots(len(qs), len(models), figsize=(4.3 * len(models), 3.2 * len(qs)), squeeze=False,
                             layout="constrained")
    for i, q in enumerate(qs):
        for j, m in enumerate(models):
            ax = axes[i, j]
            ax.set_title(f"{m}, q = {q:g}", fontsize=9)
            st_all = np.asarray(ds["status"].sel(model=m, forcing_q=q).values).ravel()
            lam_all = np.asarray(ds["lyapunov"].sel(model=m, forcing_q=q).values, dtype=float)
            if not np.isfinite(lam_all).any():
                counts = {str(k): int(np.sum(st_all == k)) for k in np.unique(st_all)}
                why = ", ".join(f"{v} {k}" for k, v in sorted(counts.items()))
                ax.text(0.5, 0.5, f"no defined exponent\nin {st_all.size} cells:\n{why}\n(nonlinear = twin check "
                        "failed,\nvalue would depend on δ)", ha="center", va="center", fontsize=8,
                        transform=ax.transAxes)
                ax.set_xticks([])
                ax.set_yticks([])
                continue
            for nf in nn:
                lam = ds["lyapunov"].sel(model=m, forcing_q=q, normal_force_n=nf).values
                st = ds["status"].sel(model=m, forcing_q=q, normal_force_n=nf).values
                line = ax.plot(eta, lam, "o-", ms=3, lw=0.8, label=f"N = {nf:g} N")
                mg = st == "merged"
                if mg.any():
                    ax.plot(eta[mg], np.zeros(int(mg.sum())), "x", color=line[0].get_color(), ms=6)
                dv = st == "diverging"
                if dv.any():
                    ax.plot(eta[dv], lam[dv], "^", color=line[0].get_color(), ms=6, mfc="none")
            ax.axhline(0, color="0.5", lw=0.8)
            ax.set_xlim(float(np.min(eta)) - 0.05, float(np.max(eta)) + 0.05)
            ax.set_xlabel(ETA_LABEL)
            ax.set_ylabel(("λ" if m == Model.DETERMINISTIC else "E[Λ]") + " (dimensionless, per unit τ)")
            tidy_x_ticks(ax, 6)
            _tidy_y(ax)
            if i == 0 and j == 0:
                _legend(ax, 7)
    return fig


def lyapunov_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "lyapunov") -> list[Figure]:
    """:func:`figure_lyapunov` written to ``<prefix>.png`` with its caption."""
    integ = str(ds.attrs.get("integrator", "euler"))
    return [(_save(figure_lyapunov(ds), Path(directory) / f"{prefix}.png"),
             "Largest Lyapunov exponent on the stick line per slip→stick transition, λ deterministic and E[Λ] "
             f"stochastic, over η for each N (thesis Fig. 4.41–4.43, 4.69–4.71; integrator {integ}); × on the axis: "
             "the two runs merged exactly (w = 0, no value); ▲: diverging, the separation grew by orders of "
             "magnitude before leaving the linear regime, the value is a lower bound; gaps: undefined (nonlinear).")]


def figure_normal_force_phase(ds: xr.Dataset, damping_index: int = 0) -> MplFigure | None:
    """Phase diagrams x2 over x1 at the ``damping_index``-th D, one panel per model, one colour per normal force
    (Fig. 4.12–4.14, 4.18–4.20); ``None`` when the dataset has no ``trajectory``."""
    if "trajectory" not in ds:
        return None
    models = [str(m) for m in ds["model"].values]
    nn = ds["normal_force_n"].values
    dval = float(ds["damping_ratio"].values[damping_index])
    fig, axes = new_subplots(1, len(models), figsize=(4.3 * len(models), 3.6), squeeze=False, layout="constrained")
    for j, m in enumerate(models):
        ax = axes[0, j]
        for k, nf in enumerate(nn):
            tr = ds["trajectory"].sel(model=m, normal_force_n=nf).isel(damping_ratio=damping_index).values
            for r in range(tr.shape[0]):
                if np.isfinite(tr[r, :, 1]).any():
                    ax.plot(tr[r, :, 1], tr[r, :, 2], lw=0.4, color=f"C{k}",
                            label=f"N = {nf:g} N" if r == 0 else None)
        ax.set_title(f"{m}, D = {dval:g}", fontsize=9)
        ax.set_xlabel(X1_LABEL)
        ax.set_ylabel(X2_LABEL)
        tidy_x_ticks(ax)
        _tidy_y(ax)
        _legend(ax, 7)
    return fig


def figure_normal_force_pdf(ds: xr.Dataset, damping_index: int = 0) -> MplFigure:
    """PDFs of X_gh after the transient at the ``damping_index``-th D, one panel per normal force (Fig.
    4.16/4.17/4.21): histograms of the stochastic models, the deterministic values as black lines; a force
    where nothing sticks in any model says so in its panel."""
    models = [str(m) for m in ds["model"].values]
    nn = ds["normal_force_n"].values
    dval = float(ds["damping_ratio"].values[damping_index])
    fig, axes = new_subplots(1, len(nn), figsize=(4.2 * len(nn), 3.3), squeeze=False, layout="constrained")
    for k, nf in enumerate(nn):
        ax = axes[0, k]
        drawn = False
        for m in models:
            at = {"model": m, "normal_force_n": nf}
            x = ds["x_gh"].sel(at).where(ds["in_window"].sel(at) > 0)
            v = x.isel(damping_ratio=damping_index).values.ravel()
            v = v[np.isfinite(v)]
            if m == Model.DETERMINISTIC:
                for xv in np.unique(np.round(v, 12))[:5]:
                    ax.axvline(xv, color="k", lw=1)
                    drawn = True
            elif v.size > 1:
                ax.hist(v, bins=25, density=True, histtype="step", color=_COLORS.get(m, "k"), label=m)
                drawn = True
        ax.set_title(f"N = {nf:g} N, D = {dval:g}", fontsize=9)
        if not drawn:  # not a blank 0–1 frame that reads like a result
            no_data(ax, "no stick after the transient\n(no X_gh in any model)")
            continue
        ax.set_xlabel(X_GH_LABEL)
        ax.set_ylabel("PDF of X_gh (dimensionless)")
        tidy_x_ticks(ax)
        _tidy_y(ax, 5)
        _legend(ax, 7)
    return fig


def normal_force_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "normal_force") -> list[Figure]:
    """Phase diagrams (Fig. 4.12–4.14, 4.18–4.20) and PDFs of X_gh (Fig. 4.16/4.17/4.21)."""
    d = Path(directory)
    out: list[Figure] = []
    for di, dval in enumerate(ds["damping_ratio"].values):
        phase = figure_normal_force_phase(ds, di)
        if phase is not None:
            out.append((_save(phase, d / f"{prefix}_phase_D{di}.png"),
                        f"Phase diagrams at D = {dval:g} for each model and normal force (thesis Fig. 4.12–4.14, "
                        "4.18–4.20; sheet 4.44–4.46, 4.49–4.51)."))
        out.append((_save(figure_normal_force_pdf(ds, di), d / f"{prefix}_pdf_D{di}.png"),
                    f"PDFs of X_gh after the transient at D = {dval:g} (thesis Fig. 4.16, 4.17, 4.21; sheet 4.47, "
                    "4.48, 4.52); black lines: deterministic values; \"no stick\": no slip→stick transition after the "
                    "transient in any model."))
    return out


#: The figures of each study kind by name (:func:`study_figure`); the first is the kind's main figure.
STUDY_FIGURES: dict[str, dict[str, Any]] = {
    "damping": {"probability": figure_damping_probability, "maps": figure_damping_maps,
                "mdiff": figure_damping_mdiff, "risk": figure_damping_risk, "dmax": figure_damping_dmax,
                "phase": figure_damping_phase},
    "forcing": {"bifurcation": figure_forcing_bifurcation, "mean_std": figure_forcing_mean_std,
                "sigma_ratio": figure_forcing_sigma_ratio},
    "lyapunov": {"lyapunov": figure_lyapunov},
    "normal-force": {"pdf": figure_normal_force_pdf, "phase": figure_normal_force_phase},
}


def study_figure(kind: str, ds: xr.Dataset, which: str | None = None, **kwargs: Any) -> MplFigure:
    """The figure ``which`` (a name of :data:`STUDY_FIGURES` ``[kind]``; default: the kind's main figure — the
    P(stick-slip) map of a damping study (its E[X_gh]/E[M] curves with one force), the bifurcation diagram,
    the Lyapunov exponents, the X_gh PDFs) of a study dataset; ``kwargs`` go to the builder
    (``damping_index=`` for the normal-force figures).  ``ValueError`` for an unknown name or a figure the
    dataset has no data for."""
    figures = STUDY_FIGURES.get(kind)
    if figures is None:
        raise ValueError(f"no figures for study kind {kind!r} (known: {', '.join(STUDY_FIGURES)})")
    if which is None:
        which = next(iter(figures))
        if kind == "damping" and ds["normal_force_n"].size < 2:
            which = "maps"
    if which not in figures:
        raise ValueError(f"no figure {which!r} for a {kind} study (known: {', '.join(figures)})")
    fig = figures[which](ds, **kwargs)
    if fig is None:
        raise ValueError(f"this {kind} result holds no data for the {which!r} figure")
    return fig

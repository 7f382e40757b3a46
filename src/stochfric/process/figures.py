"""Figures of the statistical contact analysis, after thesis Fig. 3.16–3.23.

Matplotlib's object API with the Agg canvas (no pyplot, no global state).  Every ``figure_*``
function builds one :class:`~matplotlib.figure.Figure` and returns it; the ``plot_*`` function of the
same name writes it as a PNG and returns its path; :func:`analysis_figure` picks a figure of an analysis
by name (``StatisticalContactAnalysis.plot``).  Pressures in MPa, lengths in µm, path frequencies in
1/mm and spectra in mm (conversion only here).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from stochfric.plotting import MU_LABEL, log_ticks, new_figure, save_figure
from stochfric.units import MEGAPASCAL, MICROMETRE

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from stochfric.process.checks import ProcessCheck

#: The figures read these results by their attributes only; they are not imported here, so that the result
#: classes can offer ``plot()`` without an import cycle (``tests/unit/test_layers.py``).
StatisticalContactAnalysis = Any  # stochfric.process.analysis_result.StatisticalContactAnalysis
ContactModelSpread = Any  # stochfric.process.contact_models.ContactModelSpread

__all__ = [
    "ANALYSIS_FIGURES",
    "analysis_figure",
    "figure_contact_fraction",
    "figure_contact_model_spread",
    "figure_ergodicity",
    "figure_fits",
    "figure_mu_path",
    "figure_mu_pdfs",
    "figure_process_check",
    "figure_spectra",
    "figure_surrogate_check",
    "figure_surrogates",
    "plot_contact_fraction",
    "plot_contact_model_spread",
    "plot_ergodicity",
    "plot_fits",
    "plot_mu_path",
    "plot_mu_pdfs",
    "plot_process_check",
    "plot_spectra",
    "plot_surrogate_check",
    "plot_surrogates",
    "write_process_figures",
]


def _selected(n: int) -> list[int]:
    """Three approaches as in the thesis (2, 6, 12 of 1…12 µm): indices 1, n/2−1, n−1."""
    return sorted({min(1, n - 1), max(0, n // 2 - 1), n - 1})


#: Path frequency [1/m] → 1/mm, and a one-sided spectrum [m] → mm (the plotted units).
_PER_MM = 1e-3
_MM = 1e3


def figure_mu_pdfs(a: StatisticalContactAnalysis) -> Figure:
    """PDFs of μ over the ensemble at three approaches (Fig. 3.16)."""
    fig = new_figure(9.0, 3.3)
    idx = _selected(a.ensemble.approach_m.size)
    axes = np.atleast_1d(fig.subplots(1, len(idx)))
    for ax, k in zip(axes, idx, strict=True):
        e = a.pdf_edges[k]
        ax.stairs(a.pdf_density[k], e, fill=True, alpha=0.6)
        ax.set_title(
            f"u = {a.ensemble.approach_m[k] / MICROMETRE:.3g} µm, p = {a.ensemble_pressure_pa[k] / MEGAPASCAL:.3g} MPa",
            fontsize=9,
        )
        ax.set_xlabel(MU_LABEL)
        ax.set_ylabel("PDF of μ (dimensionless)")
        ax.xaxis.set_major_locator(_nbins(4))
    fig.suptitle(f"μ over {a.config.realizations} realisations ({a.config.surrogate} surrogates)")
    return fig


def plot_mu_pdfs(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_mu_pdfs` written to ``path``."""
    return save_figure(figure_mu_pdfs(a), path)


def _nbins(n: int) -> Any:
    from matplotlib.ticker import MaxNLocator

    return MaxNLocator(nbins=n)


def figure_contact_fraction(a: StatisticalContactAnalysis) -> Figure:
    """Mean A_c/A_nom over the mean pressure E[N]/A_nom with the linear fit (Fig. 3.17)."""
    fig = new_figure(5.0, 4.0)
    ax = fig.subplots()
    p = a.ensemble_pressure_pa
    ax.plot(p / MEGAPASCAL, a.ensemble_area_fraction, "o", label="ensemble mean")
    fit = a.contact_fraction_fit
    ax.plot(p / MEGAPASCAL, fit["slope"] * p + fit["intercept"], "-", label=f"linear fit, R² = {fit['r_squared']:.4f}")
    ax.set_xlabel("E[N]/A_nom [MPa]")
    ax.set_ylabel("E[A_c]/A_nom (dimensionless)")
    ax.legend()
    return fig


def plot_contact_fraction(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_contact_fraction` written to ``path``."""
    return save_figure(figure_contact_fraction(a), path)


def figure_ergodicity(a: StatisticalContactAnalysis) -> Figure:
    """Ergodicity (Fig. 3.18b): σ of μ along one long surface vs across independent surfaces.

    Left: μ of the non-overlapping windows of every long surface (one colour per surface) with
    the ensemble mean; right: σ along a path (mean over surfaces) and σ across surfaces at a fixed
    position (mean over positions), the two populations of :func:`ergodicity_check`.
    """
    fig = new_figure(9.0, 3.6)
    axes = fig.subplots(1, 2)
    u = a.ensemble.approach_m / MICROMETRE
    blocks = a.path.blocks.mu  # (K, J, U)
    for k in range(blocks.shape[0]):
        axes[0].plot(u, blocks[k].T, color=f"C{k % 10}", lw=0.5, alpha=0.6)
    axes[0].plot(u, blocks.mean(axis=(0, 1)), "k-", lw=2, label="mean of all windows")
    axes[0].set_xlabel("u [µm]")
    axes[0].set_ylabel(MU_LABEL)
    axes[0].set_title(f"{blocks.shape[0]} long surfaces × {blocks.shape[1]} windows", fontsize=9)
    axes[0].legend()
    erg = a.ergodicity
    axes[1].plot(u, erg.path_std, "o-", label="σ along one surface")
    axes[1].plot(u, erg.ensemble_std, "s--", label="σ across surfaces")
    axes[1].set_xlabel("u [µm]")
    axes[1].set_ylabel("σ_μ (dimensionless)")
    axes[1].legend()
    fig.suptitle(
        f"ergodicity: max |z| = {erg.max_abs_z:.2f} vs threshold {erg.threshold:.2f} → "
        + ("consistent" if erg.consistent else "NOT consistent")
    )
    return fig


def plot_ergodicity(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_ergodicity` written to ``path``."""
    return save_figure(figure_ergodicity(a), path)


def figure_mu_path(a: StatisticalContactAnalysis) -> Figure:
    """μ(y) along the first long surface for three approaches."""
    fig = new_figure(7.0, 3.6)
    ax = fig.subplots()
    y = a.path.positions_m / MICROMETRE
    for k in _selected(a.ensemble.approach_m.size):
        ax.plot(y, a.path.samples.mu[0, :, k], label=f"p = {a.pressure_pa[k] / MEGAPASCAL:.3g} MPa")
    ax.set_xlabel(f"y [µm] (windows shifted by a_y = {a.path.window_shift_m / MICROMETRE:.3g} µm)")
    ax.set_ylabel("μ(y) (dimensionless)")
    ax.legend()
    return fig


def plot_mu_path(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_mu_path` written to ``path``."""
    return save_figure(figure_mu_path(a), path)


def figure_spectra(a: StatisticalContactAnalysis) -> Figure:
    """Averaged autocorrelation and one-sided PSD (method §0) for three approaches (Fig. 3.19–3.21)."""
    fig = new_figure(10.0, 3.8)
    ax1, ax2 = fig.subplots(1, 2)
    for k in _selected(a.ensemble.approach_m.size):
        lab = f"p = {a.pressure_pa[k] / MEGAPASCAL:.3g} MPa"
        ax1.plot(a.lags_m / MICROMETRE, a.acf[k], label=lab)
        ax2.plot(np.asarray(a.frequencies) * _PER_MM, np.asarray(a.psd[k]) * _MM, label=lab)
    ax1.axhline(0.0, color="k", lw=0.5)
    ax1.set_xlabel("lag [µm]")
    ax1.set_ylabel("R(lag) (3.18) (dimensionless)")
    ax1.set_title(f"mean ℓ_corr = {np.nanmean(a.correlation_length_m) / MICROMETRE:.3g} µm", fontsize=10)
    ax2.set_yscale("log")
    ax2.set_xlabel("path frequency f [1/mm]")
    ax2.set_ylabel("S [mm] (one-sided)")
    ax2.set_title(f"PSD averaged over {a.config.long_surfaces} surfaces", fontsize=10)
    log_ticks(ax2, "y")
    ax1.legend()
    return fig


def plot_spectra(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_spectra` written to ``path``."""
    return save_figure(figure_spectra(a), path)


def figure_fits(a: StatisticalContactAnalysis) -> Figure:
    """E[μ], σ_μ and E[S] over the mean pressure with the model functions a p^b + c (Fig. 3.22)."""
    fig = new_figure(11.0, 3.6)
    axes = fig.subplots(1, 3)
    p = a.pressure_pa
    data = (
        ("mu_mean", a.mu_mean, a.mu_mean_se, "E[μ] (dimensionless)", 1.0, ""),
        ("mu_std", a.mu_std, a.mu_std_se, "σ_μ (dimensionless)", 1.0, ""),
        ("psd_level", a.psd_level, a.psd_level_se, "E[S] [µm]", 1.0 / MICROMETRE, " [m]"),
    )
    pp = np.geomspace(p.min(), p.max(), 200)
    for ax, (key, y, se, label, scale, fit_unit) in zip(axes, data, strict=True):
        fit = a.fits[key]
        used = np.asarray(fit.used)
        ax.errorbar(p[used] / MEGAPASCAL, y[used] * scale, yerr=se[used] * scale, fmt="o", label="used")
        ax.errorbar(p[~used] / MEGAPASCAL, y[~used] * scale, yerr=se[~used] * scale, fmt="x", color="0.5",
                    label="excluded")
        ax.plot(pp / MEGAPASCAL, fit(pp) * scale, "-", label=f"{fit.a:.3g} p^{fit.b:.3g} + {fit.c:.3g}{fit_unit}")
        ax.set_xscale("log")
        log_ticks(ax, "x")
        ax.set_xlabel("p [MPa]")
        ax.set_ylabel(label)
        ax.legend(fontsize=7)
    return fig


def plot_fits(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_fits` written to ``path``."""
    return save_figure(figure_fits(a), path)


def figure_process_check(check: ProcessCheck) -> Figure:
    """Generated process vs target: standard deviation and spectrum (Fig. 3.23)."""
    fig = new_figure(10.0, 3.8)
    ax1, ax2 = fig.subplots(1, 2)
    p = np.asarray(check.pressure_pa) / MEGAPASCAL
    ax1.plot(p, check.target_std, "k-o", label="target σ")
    ax1.errorbar(p, check.std_pointwise, yerr=check.std_pointwise_se, fmt="s", label="generated (pointwise)")
    ax1.plot(p, check.std_grid_mean, "x", label="generated (grid, mean)")
    ax1.set_xscale("log")
    log_ticks(ax1, "x")
    ax1.set_xlabel("p [MPa]")
    ax1.set_ylabel("σ of μ̂_SD (dimensionless)")
    ax1.legend(fontsize=7)
    f = np.asarray(check.frequencies) * _PER_MM
    for j, pj in enumerate(p):
        line = ax2.plot(f, np.asarray(check.target_psd[j]) * _MM, "-", label=f"target, {pj:.3g} MPa")[0]
        ax2.plot(f, np.asarray(check.generated_psd[j]) * _MM, ".", color=line.get_color(),
                 label=f"generated ({check.realizations})")
    ax2.set_yscale("log")
    log_ticks(ax2, "y")
    ax2.set_xlabel("path frequency f [1/mm]")
    ax2.set_ylabel("S [mm] (one-sided)")
    ax2.legend(fontsize=6)
    return fig


def plot_process_check(check: ProcessCheck, path: str | Path) -> Path:
    """:func:`figure_process_check` written to ``path``."""
    return save_figure(figure_process_check(check), path)


def figure_surrogates(original: np.ndarray, surrogates: dict[str, np.ndarray], *, unit: float = MICROMETRE) -> Figure:
    """Original and surrogate height maps (one colour scale) with their height PDFs (phase, IAAFT, quilt)."""
    n = 1 + len(surrogates)
    fig = new_figure(3.2 * n + 3.4, 3.3)
    axes = fig.subplots(1, n + 1)
    maps = {"original": original, **surrogates}
    lo, hi = float(original.min()) / unit, float(original.max()) / unit
    im = None
    for ax, (label, z) in zip(axes[:n], maps.items(), strict=True):
        im = ax.imshow(z.T / unit, origin="lower", cmap="viridis", vmin=lo, vmax=hi)
        ax.set_title(label)
        ax.set_axis_off()
        axes[n].hist(z.ravel() / unit, bins=80, density=True, histtype="step", label=label)
    if im is not None:
        fig.colorbar(im, ax=list(axes[:n]), label="height z [µm]", orientation="horizontal", shrink=0.5,
                     aspect=30)
    axes[n].set_yscale("log")
    axes[n].set_xlabel("z [µm]")
    axes[n].set_ylabel("probability density [1/µm]")
    axes[n].legend(fontsize=7)
    return fig


def plot_surrogates(
    original: np.ndarray, surrogates: dict[str, np.ndarray], path: str | Path, *, unit: float = MICROMETRE
) -> Path:
    """:func:`figure_surrogates` written to ``path``."""
    return save_figure(figure_surrogates(original, surrogates, unit=unit), path)


def figure_surrogate_check(a: StatisticalContactAnalysis) -> Figure:
    """The measured map against its surrogate ensemble (method §3): μ(u) band and summit statistics.

    Left: every realisation's μ(u) (grey), the ensemble mean ± 3 sd, and the measured map's own
    μ(u) (red).  Right: the summit count, mean radius β̄ and σ_S of the realisations as
    histograms in units of their ensemble standard deviation, with the measured map's z marked.
    """
    fig = new_figure(9.0, 3.8)
    axes = fig.subplots(1, 2)
    c = a.surrogate_check
    u = a.ensemble.approach_m / MICROMETRE
    mu = a.ensemble.mu
    axes[0].plot(u, mu.T, color="0.85", lw=0.5)
    m, s = mu.mean(axis=0), mu.std(axis=0, ddof=1)
    axes[0].fill_between(u, m - 3 * s, m + 3 * s, color="C0", alpha=0.2, label="ensemble mean ± 3 sd")
    axes[0].plot(u, m, "C0-")
    axes[0].plot(u, c.mu_measured, "C3o-", ms=3, label="measured map")
    axes[0].set_xlabel("u [µm]")
    axes[0].set_ylabel(MU_LABEL)
    axes[0].legend()
    stats = a.ensemble.summit_stats
    labels = ("summit count", "mean radius β̄", "σ_S")
    if stats is not None:
        z_ens = (stats - stats.mean(axis=0)) / np.where(stats.std(axis=0, ddof=1) > 0, stats.std(axis=0, ddof=1), 1.0)
        for k, name in enumerate(("summit_count", "summit_radius_mean_m", "summit_height_std_m")):
            axes[1].hist(z_ens[:, k] + 8 * k, bins=15, color=f"C{k}", alpha=0.5, label=labels[k])
            axes[1].axvline(c.z[name] + 8 * k, color=f"C{k}", lw=2)
        axes[1].set_xticks([0, 8, 16], labels)
        axes[1].set_xlabel("z per statistic (dimensionless)")
        axes[1].set_ylabel("realisations (count)")
    else:
        axes[1].set_xticks([])
        axes[1].set_yticks([])
        axes[1].text(0.5, 0.5, "no summit statistics\nin this ensemble", ha="center", va="center",
                     transform=axes[1].transAxes)
    axes[1].set_title("z of the measured map (lines) vs the ensemble (bars)", fontsize=9)
    failures = c.failures()
    fig.suptitle(
        f"surrogates ({c.surrogate}, amplitude {c.amplitude}) vs measured map → "
        + ("credible" if c.credible else "NOT credible: " + ", ".join(failures[:4])
           + (f" (+{len(failures) - 4} more)" if len(failures) > 4 else "")),
        fontsize=10,
    )
    return fig


def plot_surrogate_check(a: StatisticalContactAnalysis, path: str | Path) -> Path:
    """:func:`figure_surrogate_check` written to ``path``."""
    return save_figure(figure_surrogate_check(a), path)


def write_process_figures(a: StatisticalContactAnalysis, directory: str | Path) -> list[Path]:
    """All figures of the analysis into ``directory`` (Fig. 3.16–3.23 analogues)."""
    d = Path(directory)
    return [
        plot_surrogate_check(a, d / "surrogate_check.png"),
        plot_mu_pdfs(a, d / "mu_pdfs.png"),
        plot_contact_fraction(a, d / "contact_fraction.png"),
        plot_ergodicity(a, d / "ergodicity.png"),
        plot_mu_path(a, d / "mu_path.png"),
        plot_spectra(a, d / "acf_psd.png"),
        plot_fits(a, d / "model_functions.png"),
        plot_process_check(a.process_check, d / "process_check.png"),
    ]


#: The figures of an analysis by name (:func:`analysis_figure`); the first is the main figure.
ANALYSIS_FIGURES: dict[str, Callable[[StatisticalContactAnalysis], Figure]] = {
    "model_functions": figure_fits,
    "surrogate_check": figure_surrogate_check,
    "mu_pdfs": figure_mu_pdfs,
    "contact_fraction": figure_contact_fraction,
    "ergodicity": figure_ergodicity,
    "mu_path": figure_mu_path,
    "acf_psd": figure_spectra,
    "process_check": lambda a: figure_process_check(a.process_check),
}


def analysis_figure(a: StatisticalContactAnalysis, which: str | None = None) -> Figure:
    """The figure ``which`` of the analysis (a name of :data:`ANALYSIS_FIGURES`, the file name
    :func:`write_process_figures` gives it without ``.png``; default: ``model_functions``, E[μ], σ_μ and
    E[S] over p with the fitted model functions).  ``ValueError`` for an unknown name."""
    name = which or next(iter(ANALYSIS_FIGURES))
    if name not in ANALYSIS_FIGURES:
        raise ValueError(f"no figure {name!r} of a statistical contact analysis (known: {', '.join(ANALYSIS_FIGURES)})")
    return ANALYSIS_FIGURES[name](a)


def figure_contact_model_spread(spread: ContactModelSpread) -> Figure:
    """The contact models side by side (issue 31): E[μ](p) over the surrogates (±1.96 SE) and over the
    measured windows (95 % interval) per model, the envelope shaded; σ_μ(p) per model; the path spectra per
    model where the spread holds them (normalised by their variance, so the shapes compare)."""
    with_path = bool(spread.paths)
    fig = new_figure(11.5 if with_path else 8.0, 3.8)
    axes = fig.subplots(1, 3 if with_path else 2)
    p = spread.pressure_pa / MEGAPASCAL
    env = spread.envelope()
    axes[0].fill_between(p, env["mu_min"], env["mu_max"], color="0.88", label="model envelope")
    for k, m in enumerate(spread.models):
        colour = f"C{k}"
        sur = spread.surrogate_statistics(m)
        axes[0].errorbar(p, sur["mu_mean"], yerr=1.96 * sur["mu_mean_se"], fmt="o-", color=colour, ms=3,
                         label=f"{m} (surrogates)")
        win = spread.window_statistics(m)
        if win is not None:
            ci = win["mu_mean_ci95"]
            axes[0].fill_between(p, ci[:, 0], ci[:, 1], color=colour, alpha=0.12)
        axes[1].errorbar(p, sur["mu_std"], yerr=1.96 * sur["mu_std_se"], fmt="o-", color=colour, ms=3, label=m)
    from matplotlib.ticker import NullFormatter

    for ax, label in ((axes[0], "E[μ] (dimensionless)"), (axes[1], "σ_μ (dimensionless)")):
        ax.set_xscale("log")
        ax.xaxis.set_minor_formatter(NullFormatter())  # labelled minor ticks of a short log range overlap
        if p.size <= 8:  # a short log range has one decade label at most: label the pressures themselves
            ax.set_xticks(p, [f"{v:.3g}" for v in p])
        else:
            log_ticks(ax, "x")
        ax.set_xlabel("nominal pressure p [MPa]")
        ax.set_ylabel(label)
    axes[0].legend(fontsize=7, title="shaded: measured windows, 95 %", title_fontsize=7)
    axes[1].legend(fontsize=7)
    if with_path:
        ax = axes[2]
        for k, m in enumerate(spread.models):
            if m not in spread.paths:
                continue
            path_m = spread.paths[m]
            f, s, _se = path_m.spectrum()
            var = float(np.sum(s) * (f[1] - f[0])) if f.size > 1 else 1.0
            cl = path_m.correlation_length()[0]
            ax.loglog(f * 1e-3, s / var * 1e3, color=f"C{k}",
                      label=f"{m}: ℓ_int = {cl / MICROMETRE:.3g} µm" if np.isfinite(cl) else m)
        log_ticks(ax, "x")
        log_ticks(ax, "y")
        ax.set_xlabel("path frequency f [1/mm]")
        ax.set_ylabel("S(f)/σ² [mm]")
        ax.set_title(f"path at p = {next(iter(spread.paths.values())).pressure_pa / MEGAPASCAL:.3g} MPa", fontsize=8)
        ax.legend(fontsize=7)
    return fig


def plot_contact_model_spread(spread: ContactModelSpread, path: str | Path) -> Path:
    """:func:`figure_contact_model_spread` written to ``path``."""
    return save_figure(figure_contact_model_spread(spread), path)

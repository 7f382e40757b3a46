"""Figures of the studies (matplotlib Agg; PNG files only).

Each ``*_figures(ds, directory)`` returns ``[(path, caption), …]``; captions name the thesis
figure the plot corresponds to.
"""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np
import xarray as xr

from ..io_utils import write_atomic

Figure = tuple[Path, str]
_COLORS = {"deterministic": "k", "white": "tab:blue", "contact": "tab:red"}


def _legend(ax: Any, size: int) -> None:
    if ax.get_legend_handles_labels()[0]:
        ax.legend(fontsize=size)


def _save(fig: Any, path: Path) -> Path:
    fig.tight_layout()
    write_atomic(path, lambda tmp: fig.savefig(tmp, dpi=110, format="png"))
    plt.close(fig)
    return path


def _gamma0(ds: xr.Dataset) -> float | None:
    try:
        return float(json.loads(ds.attrs["setup_json"])["gamma0"])
    except (KeyError, ValueError, TypeError):
        return None


def damping_phase_figure(ds: xr.Dataset, directory: str | Path, prefix: str = "damping") -> list[Figure]:
    """Phase curves x2 over x1 at one force for several D, one panel per model (Fig. 4.22/4.24/4.27,
    sheet 4.53/4.55/4.58); empty when the dataset has no ``phase_trajectory``."""
    if "phase_trajectory" not in ds:
        return []
    d = Path(directory)
    models = [str(m) for m in ds["model"].values]
    pd = ds["phase_damping"].values
    nf = float(ds["phase_normal_force"].values)
    g0 = _gamma0(ds)
    cmap = plt.get_cmap("viridis")
    cols = [cmap(0.9 * k / max(1, pd.size - 1)) for k in range(pd.size)]
    fig, axes = plt.subplots(1, len(models), figsize=(4.4 * len(models), 3.8), squeeze=False, sharex=True,
                             sharey=True)
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
        ax.set_title(f"{m}, N = {nf:g} N" + (f" ({nrun} runs per D)" if m != "deterministic" else ""), fontsize=9)
        ax.set_xlabel("x1")
        ax.set_ylabel("x2")
        if j == 0:
            _legend(ax, 7)
    return [(_save(fig, d / f"{prefix}_phase.png"),
             f"Phase curves x2 over x1 at N = {nf:g} N for damping ratios D = "
             + ", ".join(f"{v:g}" for v in pd)
             + " (thesis Fig. 4.22 deterministic, 4.24 white noise, 4.27 contact analysis; sheet Fig. 4.53, 4.55, "
             "4.58): with growing D the stick-slip cycle shrinks until the stick line x2 = γ0 (dotted) is no longer "
             "reached and the motion decays onto steady sliding; stochastic models: several runs per D.")]


def damping_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "damping") -> list[Figure]:
    """X_gh and M maps over (D, N) (Fig. 4.23/4.25/4.28), M_diff (4.26/4.29), P(D) and D_max(N), and the
    phase curves over D at one force (4.22/4.24/4.27)."""
    d = Path(directory)
    out: list[Figure] = damping_phase_figure(ds, d, prefix)
    models = [str(m) for m in ds["model"].values]
    dd = ds["damping_ratio"].values
    nn = ds["normal_force"].values
    fig, axes = plt.subplots(2, len(models), figsize=(4.2 * len(models), 6.4), squeeze=False)
    for j, m in enumerate(models):
        for i, (var, lab) in enumerate((("x_gh_mean", "E[X_gh] (0: no stick)"), ("m_mean", "E[M]"))):
            ax = axes[i, j]
            z = ds[var].sel(model=m).values
            if nn.size > 1:
                pc = ax.pcolormesh(dd, nn, z, shading="nearest", cmap="viridis")
                fig.colorbar(pc, ax=ax, label=lab)
                ax.plot(ds["d_hopf"].values, nn, "w--", lw=1, label="D_H")
                ax.set_ylabel("N [N]")
            else:
                ax.plot(dd, z[0], "o-", ms=3, color=_COLORS.get(m, "k"))
                ax.axvline(float(ds["d_hopf"].values[0]), ls="--", color="0.5", label="D_H")
                ax.set_ylabel(lab)
            ax.set_xlabel("D")
            ax.set_title(f"{m}: {lab}", fontsize=9)
    out.append((_save(fig, d / f"{prefix}_maps.png"),
                "X_gh (thesis convention: 0 where no stick in the window) and the stick count M over D and N "
                "for each model (thesis Fig. 4.23, 4.25, 4.28; sheet 4.54–4.59); dashed: Hopf boundary D_H."))
    if "m_diff" in ds:
        sm = [str(m) for m in ds["stochastic_model"].values]
        fig, axes = plt.subplots(1, len(sm), figsize=(4.4 * len(sm), 3.4), squeeze=False)
        for j, m in enumerate(sm):
            ax = axes[0, j]
            z = ds["m_diff"].sel(stochastic_model=m).values
            if nn.size > 1:
                lim = max(1.0, float(np.nanmax(np.abs(z))))
                pc = ax.pcolormesh(dd, nn, z, shading="nearest", cmap="RdBu", vmin=-lim, vmax=lim)
                fig.colorbar(pc, ax=ax, label="M_diff")
                ax.set_ylabel("N [N]")
            else:
                ax.plot(dd, z[0], "o-", ms=3)
                ax.axhline(0, color="0.5", lw=0.8)
                ax.set_ylabel("M_diff")
            ax.set_xlabel("D")
            ax.set_title(f"M_diff = M_d − E[M_s], {m} (4.41); < 0: deterministic unsafe", fontsize=8)
        out.append((_save(fig, d / f"{prefix}_mdiff.png"),
                    "M_diff = M_d − E[M_s] (eq. 4.41, thesis Fig. 4.26a/4.29a): blue (negative) where the "
                    "deterministic model predicts no stick-slip but stochastic runs still stick."))
    fig, axes = plt.subplots(1, 2, figsize=(10, 3.8))
    ax = axes[0]
    for m in models:
        for i, nf in enumerate(nn):
            p = ds["stick_probability"].sel(model=m).values[i]
            lo = ds["stick_probability_low"].sel(model=m).values[i]
            hi = ds["stick_probability_high"].sel(model=m).values[i]
            ls = ["-", "--", ":", "-."][i % 4]
            ax.plot(dd, p, ls, color=_COLORS.get(m, "k"), label=f"{m}, N={nf:g}" if len(nn) <= 4 else None)
            if m != "deterministic":
                ax.fill_between(dd, lo, hi, color=_COLORS.get(m, "k"), alpha=0.08)
    ax.set_xlabel("D")
    ax.set_ylabel("P(stick-slip cycle)")
    ax.set_title("fraction of runs with a cycle, Clopper–Pearson 95 %", fontsize=9)
    if len(nn) <= 4:
        _legend(ax, 7)
    ax = axes[1]
    for k, m in enumerate(models):
        y = ds["d_max"].sel(model=m).values
        hi = ds["d_max_high"].sel(model=m).values
        off = (k - 1) * 0.004 * (nn.max() - nn.min() + 1)
        ax.plot(nn + off, y, "o-", color=_COLORS.get(m, "k"), label=f"D_max, {m}")
        if m != "deterministic":
            top = np.where(np.isfinite(hi), hi, np.nanmax(dd))
            ax.vlines(nn + off, y, top, color=_COLORS.get(m, "k"), alpha=0.5)
    ax.plot(nn, ds["d_hopf"].values, "s--", color="0.4", label="D_H (linear)")
    ax.set_xlabel("N [N]")
    ax.set_ylabel("D")
    ax.set_title("largest damping with stick-slip; bars: [D_max^s, D_hi]", fontsize=9)
    _legend(ax, 7)
    out.append((_save(fig, d / f"{prefix}_dmax.png"),
                "Left: estimated probability of a stick-slip cycle over D with Clopper–Pearson bands. Right: "
                "D_max^d (deterministic), D_max^s (white, contact; bars up to D_hi, where the pooled upper bound "
                "on P falls below p_detect) and the Hopf boundary D_H over N."))
    return out


def forcing_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "forcing") -> list[Figure]:
    """Bifurcation diagrams (Fig. 4.30/4.34/4.61), E[X_gh] ± σ over η (4.31/4.35/4.64/4.68)."""
    d = Path(directory)
    out: list[Figure] = []
    models = [str(m) for m in ds["model"].values]
    eta = ds["eta"].values
    qs = ds["forcing_q"].values
    stoch = [m for m in models if m != "deterministic"]
    fig, axes = plt.subplots(len(qs), max(1, len(stoch)), figsize=(5 * max(1, len(stoch)), 3.4 * len(qs)),
                             squeeze=False)
    for i, q in enumerate(qs):
        for j, m in enumerate(stoch or models):
            ax = axes[i, j]
            x = ds["x_gh"].sel(model=m, forcing_q=q).where(ds["in_window"].sel(model=m, forcing_q=q) > 0).values
            for k, e in enumerate(eta):
                v = x[k].ravel()
                v = v[np.isfinite(v)]
                ax.plot(np.full(v.size, e), v, ".", color="0.6", ms=2)
            if "deterministic" in models:
                xd = ds["x_gh"].sel(model="deterministic", forcing_q=q).where(
                    ds["in_window"].sel(model="deterministic", forcing_q=q) > 0).values
                for k, e in enumerate(eta):
                    v = xd[k, 0]
                    v = v[np.isfinite(v)]
                    ax.plot(np.full(v.size, e), v, ".", color="k", ms=3)
            ax.set_title(f"q = {q:g}: deterministic (black), {m} (grey)", fontsize=9)
            ax.set_xlabel("η")
            ax.set_ylabel("X_gh")
    out.append((_save(fig, d / f"{prefix}_bifurcation.png"),
                "Bifurcation diagrams: X_gh after the transient over the forcing frequency η, deterministic (black) "
                "and all stochastic runs (grey) (thesis Fig. 4.30, 4.34, 4.61)."))
    fig, axes = plt.subplots(1, len(qs), figsize=(5 * len(qs), 3.6), squeeze=False)
    for i, q in enumerate(qs):
        ax = axes[0, i]
        for k, m in enumerate(models):
            mu = ds["x_gh_mean"].sel(model=m, forcing_q=q).values
            sd = ds["x_gh_std"].sel(model=m, forcing_q=q).values
            off = (k - 1) * 0.01
            ax.errorbar(eta + off, mu, yerr=sd, fmt="o", ms=2.5, capsize=1.5, color=_COLORS.get(m, "k"), label=m)
        ax.set_title(f"E[X_gh] ± σ, q = {q:g}", fontsize=9)
        ax.set_xlabel("η")
        _legend(ax, 7)
    out.append((_save(fig, d / f"{prefix}_mean_std.png"),
                "E[X_gh] ± σ(X_gh) over η for each model (thesis Fig. 4.31, 4.35, 4.64, 4.68)."))
    if "sigma_ratio" in ds:
        fig, ax = plt.subplots(figsize=(6, 3.4))
        for q in qs:
            ax.plot(eta, ds["sigma_ratio"].sel(forcing_q=q).values, "o-", ms=3, label=f"q = {q:g}")
        ax.axhline(1.0, color="0.5", lw=0.8)
        ax.set_xlabel("η")
        ax.set_ylabel("σ_contact / σ_white")
        _legend(ax, 8)
        out.append((_save(fig, d / f"{prefix}_sigma_ratio.png"),
                    "Ratio of the X_gh standard deviations, contact-analysis process over white noise "
                    "(thesis: ≈ 1.2 brake small q, ≈ 1.05 brake large q, ≈ 2.5 sheet)."))
    return out


def lyapunov_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "lyapunov") -> list[Figure]:
    """λ / E[Λ] over η for each N (Fig. 4.41–4.43, 4.69–4.71); merged pairs marked ×."""
    d = Path(directory)
    models = [str(m) for m in ds["model"].values]
    qs = ds["forcing_q"].values
    nn = ds["normal_force"].values
    eta = ds["eta"].values
    fig, axes = plt.subplots(len(qs), len(models), figsize=(4.3 * len(models), 3.2 * len(qs)), squeeze=False)
    for i, q in enumerate(qs):
        for j, m in enumerate(models):
            ax = axes[i, j]
            for nf in nn:
                lam = ds["lyapunov"].sel(model=m, forcing_q=q, normal_force=nf).values
                st = ds["status"].sel(model=m, forcing_q=q, normal_force=nf).values
                line = ax.plot(eta, lam, "o-", ms=3, lw=0.8, label=f"N = {nf:g} N")
                mg = st == "merged"
                if mg.any():
                    ax.plot(eta[mg], np.zeros(int(mg.sum())), "x", color=line[0].get_color(), ms=6)
            ax.axhline(0, color="0.5", lw=0.8)
            ax.set_title(f"{m}, q = {q:g}", fontsize=9)
            ax.set_xlabel("η")
            ax.set_ylabel("λ" if m == "deterministic" else "E[Λ]")
            if i == 0 and j == 0:
                _legend(ax, 7)
    return [(_save(fig, d / f"{prefix}.png"),
             "Largest Lyapunov exponent on the stick line, λ (4.43) deterministic and E[Λ] (4.44) stochastic, "
             "over η for each N (thesis Fig. 4.41–4.43, 4.69–4.71); × on the axis: the two runs merged "
             "exactly (w = 0, no value).")]


def normal_force_figures(ds: xr.Dataset, directory: str | Path, prefix: str = "normal_force") -> list[Figure]:
    """Phase diagrams (Fig. 4.12–4.14, 4.18–4.20) and PDFs of X_gh (Fig. 4.16/4.17/4.21)."""
    d = Path(directory)
    out: list[Figure] = []
    models = [str(m) for m in ds["model"].values]
    nn = ds["normal_force"].values
    for di, dval in enumerate(ds["damping_ratio"].values):
        if "trajectory" in ds:
            fig, axes = plt.subplots(1, len(models), figsize=(4.3 * len(models), 3.5), squeeze=False)
            for j, m in enumerate(models):
                ax = axes[0, j]
                for k, nf in enumerate(nn):
                    tr = ds["trajectory"].sel(model=m, normal_force=nf).values[di]
                    for r in range(tr.shape[0]):
                        if np.isfinite(tr[r, :, 1]).any():
                            ax.plot(tr[r, :, 1], tr[r, :, 2], lw=0.4, color=f"C{k}",
                                    label=f"N = {nf:g} N" if r == 0 else None)
                ax.set_title(f"{m}, D = {dval:g}", fontsize=9)
                ax.set_xlabel("x1")
                ax.set_ylabel("x2")
                _legend(ax, 7)
            out.append((_save(fig, d / f"{prefix}_phase_D{di}.png"),
                        f"Phase diagrams at D = {dval:g} for each model and normal force (thesis Fig. 4.12–4.14, "
                        "4.18–4.20; sheet 4.44–4.46, 4.49–4.51)."))
        fig, axes = plt.subplots(1, len(nn), figsize=(4.2 * len(nn), 3.2), squeeze=False)
        for k, nf in enumerate(nn):
            ax = axes[0, k]
            for m in models:
                x = ds["x_gh"].sel(model=m, normal_force=nf).where(ds["in_window"].sel(model=m, normal_force=nf) > 0)
                v = x.values[di].ravel()
                v = v[np.isfinite(v)]
                if m == "deterministic":
                    for xv in np.unique(np.round(v, 12))[:5]:
                        ax.axvline(xv, color="k", lw=1)
                elif v.size > 1:
                    ax.hist(v, bins=25, density=True, histtype="step", color=_COLORS.get(m, "k"), label=m)
            ax.set_title(f"N = {nf:g} N, D = {dval:g}", fontsize=9)
            ax.set_xlabel("X_gh")
            ax.set_ylabel("PDF")
            _legend(ax, 7)
        out.append((_save(fig, d / f"{prefix}_pdf_D{di}.png"),
                    f"PDFs of X_gh after the transient at D = {dval:g} (thesis Fig. 4.16, 4.17, 4.21; sheet 4.47, "
                    "4.48, 4.52); black lines: deterministic values; empty: no stick-slip."))
    return out


FIGURES = {
    "damping": damping_figures,
    "forcing": forcing_figures,
    "lyapunov": lyapunov_figures,
    "normal-force": normal_force_figures,
}

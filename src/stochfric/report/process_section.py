"""Report section for method §3–§4: statistics of μ and the friction-process model of the
shipped measured surface, rendered from a computed :class:`~stochfric.studies.chapter3.Chapter3`."""

from __future__ import annotations

import html
import math
from pathlib import Path
from typing import Any

from ..process.figures import write_process_figures
from ..studies.chapter3 import Chapter3


def friction_process_section(directory: Path, ch3: Chapter3) -> str:
    """HTML of the statistical contact analysis of the shipped surface (method §3–§4), rendered from
    ``ch3`` (:func:`stochfric.studies.chapter3.chapter3_analysis`); writes its figures only."""
    a = ch3.analysis
    cfg = a.config
    seed = ch3.seed
    model_path, nc_path = ch3.model_path, ch3.statistics_path
    figs = write_process_figures(a, directory / "friction_process" / "figures")

    def f(v: Any, spec: str = ".4g") -> str:
        return "—" if v is None or not math.isfinite(float(v)) else format(float(v), spec)

    rows = _model_rows(a, f)
    fits = "".join(
        f"<tr><td>{label}</td><td>{f(a.fits[key].a)} ± {f(a.fits[key].a_se, '.2g')}</td>"
        f"<td>{f(a.fits[key].b)} ± {f(a.fits[key].b_se, '.2g')}</td>"
        f"<td>{f(a.fits[key].c)} ± {f(a.fits[key].c_se, '.2g')}</td></tr>"
        for key, label in (("mu_mean", "E[μ]"), ("mu_std", "σ_μ"), ("psd_level", "E[S] [m]"))
    )
    erg = a.ergodicity
    sc = a.surrogate_check
    names = (("summit_count", "summit count", 1.0, ".0f"), ("summit_radius_mean_m", "mean summit radius β̄ [µm]",
             1e6, ".3g"), ("summit_height_std_m", "σ<sub>S</sub> [nm]", 1e9, ".3g"))
    sc_rows = "".join(
        f"<tr><td>{label}</td><td>{f(sc.measured[key] * scale, spec)}</td>"
        f"<td>{f(sc.ensemble_mean[key] * scale, spec)} ± {f(sc.ensemble_std[key] * scale, '.2g')}</td>"
        f"<td>{f(sc.z[key], '+.2f')}</td></tr>"
        for key, label, scale, spec in names
    )
    mu_z = [v for v in sc.mu_z if math.isfinite(v)]
    sc_rows += (
        f"<tr><td>μ(u), {len(mu_z)} approaches</td><td colspan='2'>measured map's own μ(u) vs the "
        f"ensemble</td><td>max |z| = {f(max((abs(v) for v in mu_z), default=math.nan), '.2f')}</td></tr>"
    )
    verdict = "credible" if sc.credible else "NOT credible (" + ", ".join(sc.failures()) + ")"
    wc = a.window_check
    if wc is None:
        window_html = "<p><b>Measured windows:</b> not checked (too few summits for 2 × 2 windows).</p>"
    else:
        k = max(range(len(wc.z)), key=lambda i: abs(wc.z[i]))
        window_html = (
            f"<p><b>Do the surrogates scatter like the measurement?</b> σ of μ over {wc.measured_windows} "
            f"disjoint windows of {f(wc.window_size_m[0] * 1e6, '.3g')} × {f(wc.window_size_m[1] * 1e6, '.3g')}"
            f" µm cut from the measured map vs over {wc.surrogate_windows} such windows of the surrogates; at the "
            f"worst approach u<sub>{k}</sub>: {f(wc.measured_std[k], '.3g')} "
            f"[{f(wc.measured_std_ci95[k][0], '.3g')}, {f(wc.measured_std_ci95[k][1], '.3g')}] vs "
            f"{f(wc.surrogate_std[k], '.3g')}; max |z| = {f(wc.max_abs_z, '.2f')} (threshold "
            f"{f(wc.threshold, '.2f')}) → <b>{html.escape(wc.verdict)}</b>.</p>"
        )
    cc = a.copy_check
    if cc is not None:
        window_html += (
            f"<p><b>Are the surrogates new surfaces?</b> Largest normalised cross-correlation over all shifts of "
            f"{cc.surrogates} surrogates with the map: {f(cc.max_ncc_with_map, '.2f')}, between surrogates: "
            f"{f(cc.max_ncc_between_surrogates, '.2f')} (limit {f(cc.ncc_limit, 'g')}); largest verbatim piece "
            f"of the map: {f(100 * (cc.largest_piece_fraction or 0.0), '.2g')} % (limit "
            f"{f(100 * cc.piece_limit, 'g')} %) → {'a COPY' if cc.is_copy else 'new surfaces'}.</p>"
        )
    ho, mw = a.holdout, a.measured_windows
    if ho is not None:
        window_html += (
            f"<p><b>Does the model hold on data it never saw?</b> {html.escape(ho.method)} surrogates made from one "
            f"half of the map, tested on the other (2 folds, {ho.held_out_windows} windows each, {ho.realizations} "
            f"surrogates per fold): <b>{html.escape(ho.verdict)}</b> — {html.escape(ho.reason)}."
            + (f" The test detects a scatter ratio of μ ≥ {f(ho.detectable_scatter_ratio, '.2g')} with 80 % "
               "probability." if ho.tests else "") + "</p>"
        )
    if mw is not None:
        window_html += (
            f"<p><b>What rests on the measurement alone:</b> μ over {mw.windows} disjoint windows of "
            f"{f(mw.window_size_m[0] * 1e6, '.3g')} × {f(mw.window_size_m[1] * 1e6, '.3g')} µm of the map: E[μ] "
            f"{f(mw.mu_mean[0], '.3g')} [{f(mw.mu_mean_ci95[0][0], '.3g')}, {f(mw.mu_mean_ci95[0][1], '.3g')}] at the "
            f"first approach, σ_μ {f(mw.mu_std[0], '.3g')} [{f(mw.mu_std_ci95[0][0], '.2g')}, "
            f"{f(mw.mu_std_ci95[0][1], '.2g')}] (95 % jackknife intervals; windows smaller than the model's). "
            "Every other number of this section comes from the surrogate model.</p>"
        )
    if cc is not None and cc.verbatim is not None:
        window_html += f"<p><b>Verbatim content:</b> {html.escape(cc.verbatim.summary())}.</p>"
    cr = a.credibility
    gate = ("credible: the model would be written" if cr.credible else
            f"{cr.status.upper()} (" + ", ".join(cr.codes()) + "): `friction-process` would exit 3 "
            "and write no model file without --accept-not-credible")
    parts = [
        f"<p><b>Do the surrogates resemble the measured map?</b> Amplitude estimate "
        f"<code>{html.escape(str(sc.amplitude))}</code> (edge jump of the non-periodic map removed), "
        f"z = (measured − median)/(1.4826 MAD) over the map and its realisations; one Monte Carlo rank test of "
        f"the largest |z| (5 % family-wise): credible if every |z| &lt; {f(sc.limit, '.2f')}, the critical value "
        f"from the realisations' own largest |z|"
        + (f" ({sc.global_exceed} of them reach the map's)" if sc.global_exceed is not None else "") + ": "
        f"<b>{html.escape(verdict)}</b>.</p>"
        "<table><tr><th></th><th>measured map</th><th>surrogates (mean ± sd)</th><th>z</th></tr>"
        + sc_rows + "</table>",
        window_html,
        f"<p><b>Verdict of the gate:</b> {html.escape(gate)}.</p>",
        f"<p>Statistical contact analysis (method §3–§4) of the shipped surface, brake-pad material, "
        f"{cfg.realizations} random-phase realisations, {cfg.long_surfaces} long surfaces × "
        f"{cfg.length_factor} lengths, seed {seed}. Ergodicity (non-overlapping windows along each long "
        f"surface vs across the independent surfaces): max |z| = {f(erg.max_abs_z, '.2f')} "
        f"(threshold {f(erg.threshold, '.2f')}) → {html.escape(erg.verdict)}. "
        f"Model file <code>{html.escape(model_path.relative_to(directory).as_posix())}</code>, statistics "
        f"<code>{html.escape(Path(nc_path).relative_to(directory).as_posix())}</code> "
        "(use with <code>stochfric simulate --model contact --process FILE</code>).</p>",
        "<p>E[μ] and σ_μ of the model with 95 % intervals: "
        + ("Monte Carlo and the sampling uncertainty of the measurement (its effective independent windows; "
           "more surrogates cannot shrink that part)" if getattr(a.model_intervals, "includes_sampling", False)
           else "Monte Carlo only (the map holds too few summits for measured windows)") + ".</p>"
        "<table><tr><th>p [MPa]</th><th>E[μ]</th><th>σ_μ</th><th>ℓ_corr [µm] (integral scale)</th>"
        "<th>E[S] [m]</th></tr>"
        + rows + "</table>",
        "<p>Model functions f(p) = a p<sup>b</sup> + c (3.21), p in Pa, ± standard errors:</p>"
        "<table><tr><th></th><th>a</th><th>b</th><th>c</th></tr>" + fits + "</table>",
    ]
    for p in figs:
        rel = p.relative_to(directory).as_posix()
        parts.append(
            f"<figure><img src='{html.escape(rel)}' alt='{html.escape(p.stem)}'>"
            f"<figcaption>Statistics of μ: {html.escape(p.stem.replace('_', ' '))} "
            "(thesis Fig. 3.16–3.23 analogues)</figcaption></figure>"
        )
    return "".join(parts)


def _model_rows(a: Any, f: Any) -> str:
    """The rows p, E[μ] [interval], σ_μ [interval], ℓ_corr, E[S] of the model table."""
    mi = a.model_intervals

    def ci(key: str, k: int) -> str:
        if mi is None:
            return ""
        lo, hi = getattr(mi, key)[k]
        return f" [{f(lo, '.3g')}, {f(hi, '.3g')}]"

    return "".join(
        f"<tr><td>{f(a.pressure_pa[k] / 1e6)}</td><td>{f(a.mu_mean[k], '.4f')}{ci('mu_mean_ci95', k)}</td>"
        f"<td>{f(a.mu_std[k], '.4f')}{ci('mu_std_ci95', k)}</td>"
        f"<td>{f(a.correlation_length_m[k] * 1e6)}</td>"
        f"<td>{f(a.psd_level[k], '.3g')}</td></tr>"
        for k in range(len(a.pressure_pa))
    )

"""Report section for method §3–§4: statistics of μ and the friction-process model of the
shipped measured surface (statistical contact analysis, issue 4)."""

from __future__ import annotations

import html
import math
from pathlib import Path
from typing import Any

#: Default seed of the section (recorded on the page).
SECTION_SEED = 2013


def friction_process_section(directory: Path, *, quick: bool = False, seed: int = SECTION_SEED) -> str:
    """Run the statistical contact analysis of the shipped surface and return its HTML section.

    Brake-pad material (Tables 3.1/3.2), plane detrend, no filter, the default approach range
    (in units of σ_S) and a_y; ``quick``: 30 realisations and 4 long surfaces instead of
    100 and 10.  Writes the model file, the NetCDF of all statistics and the figures under
    ``directory/friction_process``.
    """
    from ..contact.asperity import default_approach_m
    from ..contact.materials import load_material
    from ..process.ensemble import default_window_shift_points
    from ..process.figures import write_process_figures
    from ..process.statistics import AnalysisConfig, analyse
    from ..surface.io import default_surface_path, read_surface
    from ..surface.preprocess import Preparation, prepare
    from ..surface.summits import summits_of

    out = directory / "friction_process"
    out.mkdir(parents=True, exist_ok=True)
    surface = read_surface(default_surface_path())
    _fine, coarse = prepare(surface, Preparation())
    u = default_approach_m(summits_of(coarse))
    cfg = AnalysisConfig(
        realizations=30 if quick else 100, long_surfaces=4 if quick else 10,
        window_shift_points=default_window_shift_points(coarse.nb_grid_pts[1]), seed=seed,
    )
    a = analyse(coarse, load_material("brake-pad"), u, cfg, name="shipped surface (al3d-1)")
    model_path = a.model.save(out / "friction_process.json")
    nc_path = a.to_netcdf(out / "statistics.nc")
    figs = write_process_figures(a, out / "figures")
    d: dict[str, Any] = a.to_json_dict()

    def f(v: Any, spec: str = ".4g") -> str:
        return "—" if v is None or not math.isfinite(float(v)) else format(float(v), spec)

    rows = "".join(
        f"<tr><td>{f(d['pressure_pa'][k] / 1e6)}</td><td>{f(d['mu_mean'][k], '.4f')}</td>"
        f"<td>{f(d['mu_std'][k], '.4f')}</td>"
        f"<td>{f((d['correlation_length_m'][k] or math.nan) * 1e6)}</td>"
        f"<td>{f(d['psd_level_m'][k], '.3g')}</td></tr>"
        for k in range(len(d["pressure_pa"]))
    )
    fits = "".join(
        f"<tr><td>{label}</td><td>{f(d['fit'][key]['a'])} ± {f(d['fit'][key]['a_se'], '.2g')}</td>"
        f"<td>{f(d['fit'][key]['b'])} ± {f(d['fit'][key]['b_se'], '.2g')}</td>"
        f"<td>{f(d['fit'][key]['c'])} ± {f(d['fit'][key]['c_se'], '.2g')}</td></tr>"
        for key, label in (("mu_mean", "E[μ]"), ("mu_std", "σ_μ"), ("psd_level", "E[S] [m]"))
    )
    erg = d["ergodicity"]
    sc = d["surrogate_check"]
    names = (("summit_count", "summit count", 1.0, ".0f"), ("summit_radius_mean_m", "mean summit radius β̄ [µm]",
             1e6, ".3g"), ("summit_height_std_m", "σ<sub>S</sub> [nm]", 1e9, ".3g"))
    sc_rows = "".join(
        f"<tr><td>{label}</td><td>{f(sc['measured'][key] * scale, spec)}</td>"
        f"<td>{f(sc['ensemble_mean'][key] * scale, spec)} ± {f(sc['ensemble_std'][key] * scale, '.2g')}</td>"
        f"<td>{f(sc['z'][key], '+.2f')}</td></tr>"
        for key, label, scale, spec in names
    )
    mu_z = [v for v in sc["mu_z"] if v is not None]
    sc_rows += (
        f"<tr><td>μ(u), {len(mu_z)} approaches</td><td colspan='2'>measured map's own μ(u) vs the "
        f"ensemble</td><td>max |z| = {f(max((abs(v) for v in mu_z), default=math.nan), '.2f')}</td></tr>"
    )
    verdict = "credible" if sc["credible"] else "NOT credible (" + ", ".join(sc["failures"]) + ")"
    parts = [
        f"<p><b>Do the surrogates resemble the measured map?</b> Amplitude estimate "
        f"<code>{html.escape(str(sc['amplitude']))}</code> (edge jump of the non-periodic map removed), "
        f"z = (measured − ensemble mean)/ensemble sd, credible if every |z| &lt; {f(sc['limit'], '.0f')}: "
        f"<b>{html.escape(verdict)}</b>.</p>"
        "<table><tr><th></th><th>measured map</th><th>surrogates (mean ± sd)</th><th>z</th></tr>"
        + sc_rows + "</table>",
        f"<p>Statistical contact analysis (method §3–§4) of the shipped surface, brake-pad material, "
        f"{cfg.realizations} random-phase realisations, {cfg.long_surfaces} long surfaces × "
        f"{cfg.length_factor} lengths, seed {seed}. Ergodicity (non-overlapping windows along each long "
        f"surface vs across the independent surfaces): max |z| = {f(erg['max_abs_z'], '.2f')} "
        f"(threshold {f(erg['threshold'], '.2f')}) → {html.escape(str(erg['verdict']))}. "
        f"Model file <code>{html.escape(model_path.relative_to(directory).as_posix())}</code>, statistics "
        f"<code>{html.escape(Path(nc_path).relative_to(directory).as_posix())}</code> "
        "(use with <code>stochfric simulate --model contact --process FILE</code>).</p>",
        "<table><tr><th>p [MPa]</th><th>E[μ]</th><th>σ_μ</th><th>ℓ_corr [µm]</th><th>E[S] [m]</th></tr>"
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

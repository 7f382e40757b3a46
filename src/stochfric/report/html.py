"""One-page HTML report of the studies: ``DIR/index.html`` with PNG figures next to it.

:func:`write_report` draws every figure of every study result, writes tables of the key
numbers, a short computed reading of the results, and the parameters, seeds and package
versions of each study.  Given a :class:`~stochfric.studies.chapter3.Chapter3` result, chapter-3
sections show the shipped real surface's statistics and GW contact (method §1–2) and the
statistics of μ and the friction-process model from that surface (method §3–§4; module
``process_section``).  The report renders; it computes nothing.
"""

from __future__ import annotations

import html
import json
import math
import multiprocessing
import os
import re
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np

from ..contact.figures import write_contact_figures
from ..io_utils import package_versions, write_text_atomic
from ..oscillator.options import Model
from ..studies.base import StudyResult
from ..studies.chapter3 import Chapter3
from ..studies.damping import DampingSummary, DMaxRisk
from ..studies.figures import damping_figures, forcing_figures, lyapunov_figures, normal_force_figures
from ..studies.forcing import ForcingSummary
from ..studies.kinds import study_kind
from ..studies.lyapunov import LyapunovSummary
from ..studies.normal_force import NormalForceSummary
from ..surface.figures import write_surface_figures
from .process_section import friction_process_section

_CSS = """
body{font-family:system-ui,sans-serif;max-width:1150px;margin:2em auto;padding:0 1em;color:#222}
h1{font-size:1.6em}h2{border-bottom:1px solid #ccc;padding-bottom:.2em;margin-top:2em}
figure{margin:1em 0}figure img{max-width:100%;border:1px solid #eee}figcaption{font-size:.9em;color:#444}
table{border-collapse:collapse;font-size:.85em;margin:.8em 0}td,th{border:1px solid #ccc;padding:.2em .5em;
text-align:right}th{background:#f4f4f4}pre{background:#f7f7f7;padding:.6em;overflow-x:auto;font-size:.8em}
.reading{background:#f3f8ff;border-left:4px solid #4a90d9;padding:.5em 1em}
ul.answers li{margin:.3em 0}.warnhelp dt{font-weight:bold;margin-top:.5em}
"""

_SUBSCRIPT = re.compile(r"(?<![\w&;])([^\W\d_])_([^\W_]+)(?:\^([^\W_]+))?(?![\w])")


def rich_text(text: str) -> str:
    """HTML-escape ``text`` and typeset thesis symbols: ``D_max^d`` → D<sub>max</sub><sup>d</sup>,
    ``X_gh`` → X<sub>gh</sub>, ``σ_ζ`` → σ<sub>ζ</sub> (identifiers such as ``stick_window`` stay)."""
    def sub(m: re.Match[str]) -> str:
        sup = f"<sup>{m.group(3)}</sup>" if m.group(3) else ""
        return f"{m.group(1)}<sub>{m.group(2)}</sub>{sup}"

    return _SUBSCRIPT.sub(sub, html.escape(text))


def dmax_text(value: float | None, grid: Sequence[float]) -> str:
    """A D_max for tables: the number, "≥ D_end (> grid)" at the grid's end (the limit lies beyond
    the grid) or "< grid start" when not even the first grid D has a cycle."""
    if value is None or not math.isfinite(float(value)):
        return f"< grid start ({min(grid):g})"
    if value >= max(grid) - 1e-12:
        return f"≥ {value:.4g} (> grid)"
    return f"{value:.4g}"


def _fmt(v: Any, spec: str = ".4g") -> str:
    if v is None:
        return "—"
    if isinstance(v, float | np.floating):
        return "—" if not math.isfinite(float(v)) else format(float(v), spec)
    return html.escape(str(v))


def _table(header: Sequence[str], rows: Sequence[Sequence[Any]]) -> str:
    h = "".join(f"<th>{rich_text(str(c))}</th>" for c in header)
    body = "".join("<tr>" + "".join(f"<td>{_fmt(c)}</td>" for c in row) + "</tr>" for row in rows)
    return f"<table><tr>{h}</tr>{body}</table>"


def _figure(path: Path, caption: str, directory: Path) -> str:
    rel = path.relative_to(directory).as_posix()
    return (f'<figure><img src="{html.escape(rel)}" alt="{html.escape(caption[:80])}">'
            f"<figcaption>{rich_text(caption)}</figcaption></figure>")


def _provenance(result: StudyResult[Any]) -> str:
    a = result.dataset.attrs
    parts = []
    for key in ("config_json", "setup_json", "executor_json", "versions_json"):
        if key in a:
            try:
                txt = json.dumps(json.loads(a[key]), indent=1)
            except ValueError:
                txt = str(a[key])
            if key == "setup_json":
                d = json.loads(a[key])
                d.pop("process", None)
                txt = json.dumps(d, indent=1)
            parts.append(f"<details><summary>{key.replace('_json', '')}</summary><pre>{html.escape(txt)}</pre>"
                         "</details>")
    parts.append(f"<p>seed entropy: {html.escape(str(a.get('seed_entropy')))}; "
                 f"{html.escape(str(a.get('seed_rule', '')))}</p>")
    return "".join(parts)


_PATH_TEXT = {"mass": "mass (thesis: global path of the mass)", "relative": "relative path",
              "position": "position (REPRODUCTION MODE: at the mass position x1, eq. 4.36/4.38 as printed)"}
_WHITE_TEXT = {"sigma_mu": "sigma_mu (thesis: σ_ζ = σ_μ(p))",
               "spectral_level": "spectral_level (σ_ζ = S0/2, the process's low-frequency spectral level)",
               "thesis": "thesis (REPRODUCTION MODE: printed eq. 4.31, σ_ζ,eff = σ_μ(p)·Lω0·Δτ, "
                         "intensity depends on Δτ)"}


class _ModelChoices(Protocol):
    """What :func:`model_choices_text` reads of a study summary."""

    @property
    def path_coordinate(self) -> str: ...
    @property
    def white_intensity(self) -> str: ...
    @property
    def white_increment(self) -> str: ...
    @property
    def process_level(self) -> str: ...
    @property
    def white_model(self) -> str | None: ...
    @property
    def normal_force_n(self) -> list[float] | float: ...
    @property
    def sigma_zeta(self) -> list[float] | float: ...
    @property
    def sigma_zeta_effective(self) -> list[float] | float: ...


def model_choices_text(summary: _ModelChoices) -> str:
    """One line with the path coordinate, the white-noise intensity rule and σ_ζ of a study summary."""
    pc, wi = summary.path_coordinate, summary.white_intensity
    sz, forces = summary.sigma_zeta, summary.normal_force_n
    if isinstance(sz, list) and isinstance(forces, list) and len(sz) == len(forces):
        sz_txt = ", ".join(f"{_fmt(v, '.4g')} (N = {nf:g} N)" for v, nf in zip(sz, forces, strict=True))
    else:
        sz_txt = _fmt(sz, ".4g")
    eff = summary.sigma_zeta_effective
    eff_txt = ""
    if summary.white_increment == "thesis":
        vals = eff if isinstance(eff, list) else [eff]
        eff_txt = "; effective σ_ζ,eff = " + ", ".join(_fmt(v, ".4g") for v in vals)
    lvl_txt = ("; contact-process variance: psd_level (REPRODUCTION MODE: from the thesis's E[S](p) fit, "
               "normalised by its check σ = 0.08 at 0.5 MPa)" if summary.process_level == "psd_level" else "")
    standing = f" The white model is a {summary.white_model}." if summary.white_model else ""
    return (f"Contact process read along: {_PATH_TEXT.get(str(pc), str(pc))}; white-noise intensity rule: "
            f"{_WHITE_TEXT.get(str(wi), str(wi))}; σ_ζ of the white model = {sz_txt}{eff_txt}{lvl_txt}.{standing}")


def _pct(a: float) -> str:
    return f"{100 * a:g} %"


def risk_text(e: DMaxRisk, grid: Sequence[float], runs: int | None = None, compact: bool = False) -> str:
    """A D_max(α) of the summary as "0.205 [0.19, 0.21]"; an open upper end as "≥ 0.25 (grid end)",
    or, when the runs cannot resolve α, "≥ 0.25 (10 runs cannot resolve 10 %)" (``compact``: "≥ 0.25*");
    "< grid start" below the grid."""
    start = f"< grid start ({min(grid):g})"
    v, (lo, hi) = e.value, e.interval
    lo_t = start if lo is None else f"{lo:.4g}"
    if hi is None:
        hi_t = start
    elif e.high_open and e.resolved:
        hi_t = f"≥ {hi:.4g} (grid end)"
    elif e.high_open:
        who = runs if runs is not None else "these"
        hi_t = f"≥ {hi:.4g}" + ("*" if compact else f" ({who} runs cannot resolve {_pct(e.risk_level)})")
    else:
        hi_t = f"{hi:.4g}"
    return f"{start if v is None else f'{v:.4g}'} [{lo_t}, {hi_t}]"


def _unresolved_note(summary: DampingSummary) -> str:
    """"*: open upper end, 10 runs cannot resolve 10 % (≥ 36 runs needed), …" or ""."""
    alphas = summary.risk_levels
    need = summary.risk_levels_runs_to_resolve
    bad = [j for j in range(len(alphas))
           if any(not e[j].resolved for per_force in summary.d_max_risk.values() for e in per_force)]
    if not bad:
        return ""
    return ("*: open upper end — " + str(summary.runs) + " runs cannot resolve " + ", ".join(
        _pct(alphas[j]) + (f" (≥ {need[j]} runs needed)" if need[j] else "") for j in bad)
        + ": 0 sticking runs do not exclude P ≥ α.")


def _damping_rows(summary: DampingSummary, alphas: Sequence[float]) -> tuple[list[list[Any]], list[str]]:
    """Per force: the damping table's row and the reading's line."""
    grid, runs, risk, ext = summary.damping_ratio, summary.runs, summary.d_max_risk, summary.d_max_sample_extreme
    stoch = list(risk) or list(ext)
    det = summary.d_max_deterministic
    rows, lines = [], []
    for i, nf in enumerate(summary.normal_force_n):
        dd = det[i] if det is not None else None
        row: list[Any] = [nf, summary.d_hopf[i], dmax_text(dd, grid) if det is not None else None]
        row += [risk_text(risk[m][i][j], grid, runs, compact=True) for m in stoch for j in range(len(alphas))]
        row += [dmax_text(ext[m][i].value, grid) if m in ext else None for m in stoch]
        rows.append(row)
        txt = f"N = {nf:g} N: D_H = {summary.d_hopf[i]:.3g}, D_max^d = {dmax_text(dd, grid)}"
        for j, a in enumerate(alphas):
            txt += f"; D_max({_pct(a)}): " + ", ".join(f"{m} {risk_text(risk[m][i][j], grid, runs, compact=True)}"
                                                       for m in stoch)
        lines.append(txt)
    return rows, lines


def damping_reading(summary: DampingSummary) -> tuple[str, str]:
    """(table HTML, reading: short bullet lines "• …") for a damping study summary."""
    grid, runs, risk, ext = summary.damping_ratio, summary.runs, summary.d_max_risk, summary.d_max_sample_extreme
    stoch = list(risk) or list(ext)
    alphas = summary.risk_levels if risk else []
    header = (["N [N]", "D_H", "D_max^d"] + [f"D_max({_pct(a)}) {m} [low, high]" for m in stoch for a in alphas]
              + [f"sample extreme {m} (thesis D_max^s)" for m in stoch])
    rows, lines = _damping_rows(summary, alphas)
    if alphas:
        conf = summary.confidence
        lines.append(f"D_max(α) = largest D with P(stick-slip) ≥ α; [low, high] from the per-D Clopper–Pearson "
                     f"{100 * conf:g} % bands of P (each end a one-sided {50 * (1 + conf):g} % bound).")
        note = _unresolved_note(summary)
        if note:
            lines.append(note)
    if ext:
        lines.append(f"Sample extreme (thesis D_max^s: largest D at which any of the {runs} runs stuck; grows with "
                     "the runs, not a limit): " + "; ".join(
                         f"{m} " + ", ".join(dmax_text(e.value, grid) for e in ext[m]) for m in ext) + ".")
    if summary.d_max_deterministic:
        ok = all(d is None or d >= h - 1e-12 for d, h in zip(summary.d_max_deterministic, summary.d_hopf,
                                                              strict=True))
        lines.append("D_max^d ≥ D_H at every force: subcritical Hopf bifurcation (stick-slip from a large start "
                     "above the linear boundary)." if ok else
                     "D_max^d < D_H at some force (check the grid and the stick window).")
    ph = summary.phase
    if ph:
        parts = "; ".join(f"{m} " + ", ".join(_fmt(v, ".2g") for v in vals)
                          for m, vals in ph.has_cycle_fraction.items())
        lines.append(f"Phase curves at N = {ph.normal_force_n:g} N, D = "
                     + ", ".join(f"{v:g}" for v in ph.damping_ratio)
                     + f" ({ph.damping_rule}); fraction still sticking after the transient: {parts}.")
    return _table(header, rows), "\n".join(f"• {x}" for x in lines)


def reading_html(reading: str) -> str:
    """A reading as HTML: bullet lines ("• …", one per line) as a list, other text as a paragraph."""
    items = [x[2:] for x in reading.split("\n") if x.startswith("• ")]
    if items and len(items) == len(reading.split("\n")):
        return "<ul class='reading'>" + "".join(f"<li>{rich_text(x)}</li>" for x in items) + "</ul>"
    return f"<p class='reading'>{rich_text(reading)}</p>"


def forcing_reading(summary: ForcingSummary) -> tuple[str, str]:
    """(table, reading) for a forcing study summary."""
    med = summary.sigma_ratio_median or {}
    ci = summary.sigma_ratio_median_ci or {}

    def _ci(q: float) -> str:
        c = ci.get(f"{q:g}")
        return f"{_fmt(c.low, '.3g')} … {_fmt(c.high, '.3g')}" if c else "—"

    rows = [[q, med.get(f"{q:g}"), _ci(q)] for q in summary.forcing_q]
    txt = "; ".join(f"q = {q:g}: median σ_contact/σ_white over η = {_fmt(med.get(f'{q:g}'), '.3g')} "
                    f"(95 % bootstrap interval {_ci(q)})"
                    for q in summary.forcing_q) if med else "no white/contact pair"
    txt += " (thesis brake: ≈ 1.2 small q, ≈ 1.05 large q; sheet ≈ 2.5)."
    return _table(["q", "median σ_contact/σ_white", "95 % interval"], rows), txt


def lyapunov_signs(summary: LyapunovSummary, model: str) -> list[str]:
    """Per forcing amplitude, the η-sign string of ``model``: ``+``/``-`` beyond 2 SE (a diverging cell's
    lower bound counts), ``0`` within, ``.`` undefined; a cell is the sign shared by every N, else ``~``."""
    lam = summary.lyapunov[model]  # [q][N][η]
    se = summary.lyapunov_se[model]
    out = []
    for qi in range(len(summary.forcing_q)):
        chars = []
        for ei in range(len(summary.eta)):
            signs = set()
            for ni in range(len(summary.normal_force_n)):
                v, e = lam[qi][ni][ei], se[qi][ni][ei]
                if not math.isfinite(v):
                    signs.add(".")
                    continue
                e = e if math.isfinite(e) else 0.0
                signs.add("+" if v - 2 * e > 0 else "-" if v + 2 * e < 0 else "0")
            chars.append(signs.pop() if len(signs) == 1 else "~")
        out.append("".join(chars))
    return out


def _defined_cells(summary: LyapunovSummary, model: str) -> str:
    """``"k of n"``: the cells of ``model`` with a defined exponent (``ok`` or ``diverging``)."""
    counts = summary.status_counts[model]
    return f"{counts.get('ok', 0) + counts.get('diverging', 0)} of {sum(counts.values())}"


def lyapunov_reading(summary: LyapunovSummary) -> tuple[str, str]:
    """(table, reading) for a Lyapunov study summary."""
    rows = []
    for m in summary.models:
        c, sig = summary.status_counts[m], summary.significance[m]
        rows.append([m, c.get("ok"), c.get("diverging"), c.get("merged"), c.get("too-few-transitions"),
                     c.get("nonlinear"), sig.positive, sig.negative])
    # no η-sign string for the white model: its defined cells vanish as Δτ → 0 (docs/studies.md)
    signs = "; ".join(f"{m} q = {q:g}: {line}" for m in summary.models if m != Model.WHITE
                      for q, line in zip(summary.forcing_q, lyapunov_signs(summary, m), strict=True))
    white = f", white noise {summary.sde_integrator} at Δτ = {summary.dt:g}" if Model.WHITE in summary.models else ""
    txt = ("Exponent per slip→stick transition from the linear regime (twin check; NaN = undefined, with the "
           "reason counted; diverging = the separation grew ≥ 100-fold before the check failed, the value a lower "
           "bound). Cells positive / negative by more than 2 standard errors: " + ", ".join(
               f"{m} {summary.significance[m].positive} / {summary.significance[m].negative}"
               for m in summary.models)
           + f"; perturbation δ = {summary.perturbation:g}, τ_end = {summary.tau_end:g}, integrator "
           f"{summary.integrator} ({summary.integrator_mode}{white})"
           + ((". Sign over η (η = " + ", ".join(f"{e:g}" for e in summary.eta) + "; + / − beyond 2 SE, "
               "0 within, . undefined, ~ the forces differ): " + signs) if signs else "")
           + (f". White noise: no sign is read ({_defined_cells(summary, Model.WHITE)} cells have a defined exponent "
              "here; such cells vanish as Δτ → 0, docs/studies.md)" if Model.WHITE in summary.models else "")
           + ". For the contact model the path offset of "
           "the two runs is a neutral direction, so a positive value is no evidence of chaos by itself.")
    return _table(["model", "ok", "diverging (lower bound)", "merged (w = 0)", "too few transitions",
                   "nonlinear (undefined)", "λ > 2 SE", "λ < −2 SE"], rows), txt


#: A table cell whose value would be meaningless (:func:`se_percent`).
UNDEFINED = "undefined"


def se_percent(se: float | None) -> float | str | None:
    """A standard error as a percentage for a table cell: ``100·se``, or :data:`UNDEFINED` above 100 % (an SE
    of 2.6·10⁴ % says nothing but that the estimate is not resolved); ``None``/NaN stay empty cells."""
    if se is None or not math.isfinite(float(se)):
        return se
    return UNDEFINED if 100 * float(se) > 100 else 100 * float(se)


def normal_force_reading(summary: NormalForceSummary) -> tuple[str, str]:
    """(table, reading) for a normal-force study summary."""
    s = summary
    rows = []
    # tables [normal_force_n][damping_ratio] (docs/glossary.md); rows per D, then per N
    for m in s.models:
        for di, d in enumerate(s.damping_ratio):
            for ni, nf in enumerate(s.normal_force_n):
                rows.append([m, d, nf, s.x_gh_mean[m][ni][di], s.x_gh_mean_se[m][ni][di], s.x_gh_std[m][ni][di],
                             s.x_gh_std_se[m][ni][di], 100 * s.vark[m][ni][di], se_percent(s.vark_se[m][ni][di]),
                             s.n_events[m][ni][di]])
    txt = ""
    if Model.WHITE in s.models and Model.CONTACT in s.models:
        parts = []
        for di, d in enumerate(s.damping_ratio):
            for ni, nf in enumerate(s.normal_force_n):
                sw, sc = s.x_gh_std[Model.WHITE][ni][di], s.x_gh_std[Model.CONTACT][ni][di]
                if math.isfinite(sw) and math.isfinite(sc) and sw > 0:
                    rc = s.sigma_ratio_contact_white[ni][di] if s.sigma_ratio_contact_white else None
                    iv = (f" [{_fmt(rc.low, '.2g')}, {_fmt(rc.high, '.2g')}]"
                          if rc is not None and math.isfinite(rc.low) else "")
                    parts.append(f"N = {nf:g} N, D = {d:g}: {sc / sw:.2g}{iv}")
        txt = ("σ(X_gh) contact/white [95 % bootstrap interval]: " + "; ".join(parts)
               + ". Empty cells: no stick-slip after the transient.")
    if any(row[8] == UNDEFINED for row in rows):
        txt += ((" " if txt else "") + "SE % “undefined”: the standard error of VarK exceeds 100 percentage points "
                "(E[X_gh] near 0, so VarK = σ/|E| is not resolved by these runs).")
    return _table(["model", "D", "N [N]", "E[X_gh]", "SE", "σ", "SE", "VarK %", "SE %", "events"], rows), txt


_WITH: dict[str, str] = {Model.DETERMINISTIC: "deterministically", Model.WHITE: "with white noise",
                         Model.CONTACT: "with the contact-analysis process"}


def _limit_words(v: float | None, grid: Sequence[float], interval: Sequence[Any] | None = None,
                 first: bool = True) -> str:
    """"stick-slip up to D = 0.14" (``first``) or "up to 0.16 [0.16, 0.175]"; the grid's ends in words."""
    if v is None:
        return f"{'no stick-slip' if first else 'none'} even at D = {min(grid):g} (the grid start)"
    iv = ""
    if interval is not None:
        hi = interval[1]
        iv = f" [{_fmt(interval[0], '.3g')}, {_fmt(hi, '.3g') if hi is not None else '> grid'}]"
    head = "stick-slip up to D = " if first else "up to "
    if v >= max(grid) - 1e-12:
        return f"{head}{v:.3g} or beyond (the grid end){iv}"
    return f"{head}{v:.3g}{iv}"


def _risk_above(e: DMaxRisk, det: float | None) -> bool:
    """The whole interval of D_max(α) lies above the deterministic limit ``det``."""
    lo = e.interval[0]
    return det is not None and lo is not None and lo > det + 1e-12


def _risk_reaches_above(e: DMaxRisk, det: float | None) -> bool:
    """The interval of D_max(α) reaches above the deterministic limit ``det`` (or there is none)."""
    hi = e.interval[1]
    return hi is not None and (det is None or hi > det + 1e-12)


def _deterministic_verdict(summary: DampingSummary, det: list[float | None], i: int, a: float) -> str:
    """The headline's verdict on D_max^d at force ``i`` and the first risk level ``a``, and the forces
    where P(stick-slip) ≥ α above it."""
    risk, forces = summary.d_max_risk, summary.normal_force_n
    stoch = list(risk)
    over = [m for m in stoch if _risk_above(risk[m][i][0], det[i])]
    d = det[i]
    if d is not None and d >= max(summary.damping_ratio) - 1e-12:
        line = " — the limits reach the grid end: extend the D grid to compare them"
    elif over:
        line = (f" — the deterministic limit is exceeded at {_pct(a)} risk ({' and '.join(over)}: "
                f"P(stick-slip) ≥ {_pct(a)} above D_max^d)")
    elif any(_risk_reaches_above(risk[m][i][0], det[i]) for m in stoch):
        line = (f" — the deterministic limit is neither confirmed nor exceeded at {_pct(a)} risk (intervals reach "
                "above it: more runs)")
    else:
        line = f" — the deterministic limit holds at {_pct(a)} risk (P(stick-slip) < {_pct(a)} above it)"
    if len(forces) > 1:
        per = []
        for m in stoch:
            bad = [forces[k] for k in range(len(forces)) if _risk_above(risk[m][k][0], det[k])]
            per.append(f"{m}: " + (", ".join(f"{f:g}" for f in bad) + " N" if bad else "none"))
        line += (f". Forces where P(stick-slip) ≥ {_pct(a)} above D_max^d ({len(forces)} forces): "
                 + "; ".join(per))
    return line


def damping_headline(summary: DampingSummary) -> str:
    """One-line answer of a damping study at the phase force (the thesis's case): D_max^d, and D_max(α) of
    each stochastic model at the first risk level α with its interval; the verdict whether P(stick-slip) ≥ α
    above D_max^d (interval wholly above it), is excluded there, or is not resolved; over all forces where
    it is.  Without a stochastic model: the deterministic limit alone."""
    forces, grid, det, risk = summary.normal_force_n, summary.damping_ratio, summary.d_max_deterministic, \
        summary.d_max_risk
    stoch = list(risk)
    nf = summary.phase.normal_force_n if summary.phase else forces[(len(forces) - 1) // 2]
    i = min(range(len(forces)), key=lambda k: abs(forces[k] - nf))
    parts = [f"{_limit_words(det[i], grid)} {_WITH[Model.DETERMINISTIC]}"] if det is not None else []
    head = f"{summary.preset}, N = {forces[i]:g} N: "
    if not stoch:
        return head + ", ".join(parts) + "."
    a = risk[stoch[0]][i][0].risk_level
    rparts = [f"{risk_text(risk[m][i][0], grid, summary.runs, compact=True)} {_WITH.get(m, m)}" for m in stoch]
    line = head + "".join(f"{x}, " for x in parts) + f"P(stick-slip) ≥ {_pct(a)} up to D = " + ", ".join(rparts)
    if det is not None:
        line += _deterministic_verdict(summary, det, i, a)
    if any(not risk[m][i][0].resolved for m in stoch):
        line += f" (*{summary.runs} runs cannot resolve {_pct(a)})"
    return line + "."


def _det_verdict(risk: dict[str, list[list[DMaxRisk]]], det: float | None, k: int, j: int,
                 grid: Sequence[float]) -> str:
    """Whether the deterministic limit D_max^d at force ``k`` holds at risk level ``j`` for every stochastic model."""
    if det is not None and det >= max(grid) - 1e-12:
        return "at the grid end: extend the D grid"
    over, open_ = [], []
    for m, per_force in risk.items():
        lo, hi = per_force[k][j].interval
        if lo is not None and (det is None or lo > det + 1e-12):
            over.append(m)
        elif hi is not None and (det is None or hi > det + 1e-12):
            open_.append(m)
    if over:
        return "<b>not safe</b>: " + ", ".join(over) + " stick-slips above it"
    if open_:
        return "not resolved (" + ", ".join(open_) + ": more runs)"
    return "holds"


def verdict_section(results: Sequence[StudyResult[Any]]) -> str:
    """The one-look answer at the top of the report: per preset (damping study), per normal force, the
    deterministic limit D_max^d, the stick-slip limit D_max(α) of each stochastic model with its interval at
    the first risk level, and whether the deterministic limit holds at that risk."""
    out = []
    for res in results:
        s = res.summary
        if not isinstance(s, DampingSummary) or not s.d_max_risk:
            continue
        risk, grid, runs = s.d_max_risk, s.damping_ratio, s.runs
        det = s.d_max_deterministic or [None] * len(s.normal_force_n)
        a = next(iter(risk.values()))[0][0].risk_level
        header = ["N [N]", "D_H (linear)", "D_max^d (deterministic)",
                  *[f"D_max({_pct(a)}) {m} [interval]" for m in risk], f"deterministic limit at {_pct(a)} risk"]
        rows = []
        for k, nf in enumerate(s.normal_force_n):
            rows.append([f"{nf:g}", _fmt(s.d_hopf[k], ".3g"), dmax_text(det[k], grid),
                         *[risk_text(risk[m][k][0], grid, runs, compact=True) for m in risk],
                         _det_verdict(risk, det[k], k, 0, grid)])
        table = _table(header, rows).replace("&lt;b&gt;", "<b>").replace("&lt;/b&gt;", "</b>")
        note = _unresolved_note(s)
        out.append(f"<h3>{html.escape(s.preset)}</h3>" + table
                   + (f"<p class='note'>{html.escape(note)}</p>" if note else ""))
    if not out:
        return ""
    sources = sorted({r.summary.process_source for r in results if isinstance(r.summary, DampingSummary)})
    about = "; ".join(
        f"{src.split(':', 1)[1]}: the thesis's friction-process model of that preset (Tables 3.3/3.6), not the "
        "shipped surface's own analysis" if src.startswith("preset:") else
        f"the friction-process model {src.split(':', 1)[-1]}" for src in sources)
    return ("<h2>Verdict</h2>"
            f"<p class='about'><b>Whose friction model:</b> {html.escape(about)}.</p>"
            "<p>Will it stick-slip? D_max(α) is the largest damping ratio D at which stick-slip "
            "(a slip→stick transition after the transient) has probability ≥ α, with its 95 % interval "
            "(docs/studies.md, damping); the deterministic limit is <i>not safe</i> where a stochastic model's "
            "whole interval lies above it. Above D_max(α) the risk is below α.</p>" + "".join(out))


def normal_force_headline(summary: NormalForceSummary) -> str:
    """One line: at which forces each model has stick-slip, per damping ratio."""
    forces = summary.normal_force_n
    parts = []
    for di, d in enumerate(summary.damping_ratio):
        has = {m: [forces[k] for k in range(len(forces)) if summary.n_events[m][k][di] > 0]
               for m in summary.models}
        if all(len(v) == len(forces) for v in has.values()):
            parts.append(f"at D = {d:g} stick-slip at every force in every model")
        else:
            parts.append(f"at D = {d:g} stick-slip " + "; ".join(
                f"{m} " + (", ".join(f"{f:g}" for f in v) + " N" if v else "nowhere") for m, v in has.items()))
    return (f"{summary.preset}, N = " + ", ".join(f"{f:g}" for f in forces) + " N: " + "; ".join(parts)
            + ".")


def forcing_headline(summary: ForcingSummary) -> str:
    """One line: σ(X_gh) contact/white over η, against the thesis's ratios."""
    med = summary.sigma_ratio_median
    head = f"{summary.preset}, forced, N = {summary.normal_force_n:g} N"
    if not med:
        return head + ": no white/contact pair to compare."
    return (head + ": σ(X_gh) contact/white, median over η: " + ", ".join(
        f"{_fmt(med.get(f'{q:g}'), '.3g')} at q = {q:g}" for q in summary.forcing_q)
        + " (thesis: ≈ 1.2 / ≈ 1.05 brake, small / large q; ≈ 2.5 sheet).")


def lyapunov_headline(summary: LyapunovSummary) -> str:
    """One line: how many cells have a positive largest Lyapunov exponent beyond 2 SE, per model."""
    return (f"{summary.preset}, Lyapunov exponent on the stick line: cells with λ > 0 by more than 2 SE: "
            + ", ".join(f"{m} {summary.significance[m].positive}" for m in summary.models if m != Model.WHITE)
            + (" (white noise: not defined as Δτ → 0)" if Model.WHITE in summary.models else "") + ".")


#: what each simulation warning class means for the results, and what to do about it
WARNING_HELP = {
    "coarse-time-step": (
        "The time step Δτ is coarse for this motion: the thesis (Fig. 4.7, 4.8) shows Δτ > 0.01 changing "
        "stick-slip cycles and forced solutions, so X_gh may carry discretisation error.",
        "rerun with a smaller time step (--dt 0.001, or dt in the study file) or check a few cells with "
        "--integrator accurate; results that do not move are converged."),
    "slip-shorter-than-grid": (
        "Some slip phases were shorter than one grid spacing of the friction process, so friction there was "
        "interpolated between two grid points (thesis 4.1.3) and barely varies.",
        "use a process with a finer grid (smaller dx) when oscillations are this small."),
    "process-grid-not-periodic": (
        "The process grid does not span a whole number of periods, so its periodic continuation has a seam.",
        "choose dx = length / n (simulate --process-length does this)."),
    "event-buffer-full": (
        "More slip→stick transitions than stored: the stick count M is exact, but only the first X_gh were kept.",
        "raise max_events (simulate) or shorten τ_end."),
}


def warnings_section(results: Sequence[StudyResult[Any]]) -> str:
    """Every warning class the run produced: how often, in which studies, what it means, what to do."""
    seen: dict[str, list[str]] = {}
    for res in results:
        for w in res.summary.warnings:
            seen.setdefault(w.code, []).append(f"{res.kind} ({res.summary.preset}) ×{w.count}")
    if not seen:
        return "<p>No simulation warnings in this run.</p>"
    items = []
    for code in sorted(seen):
        what, todo = WARNING_HELP.get(code, ("See the warning messages of the simulations.", "—"))
        items.append(f"<dt>{html.escape(code)}: {html.escape(', '.join(seen[code]))}</dt>"
                     f"<dd>{rich_text(what)} <i>What to do:</i> {rich_text(todo)}</dd>")
    return "<p>Warnings this run produced:</p><dl class='warnhelp'>" + "".join(items) + "</dl>"


@dataclass(frozen=True)
class ReportSection:
    """How the report shows one study kind (:data:`~stochfric.studies.kinds.STUDY_KINDS`): its figures
    ``figures(dataset, directory, prefix=…)`` → [(path, caption)], its table and reading
    ``reading(summary)`` → (table HTML, reading) and its one-line answer ``headline(summary)``."""

    figures: Callable[..., list[Any]]
    reading: Callable[[Any], tuple[str, str]]
    headline: Callable[[Any], str]


#: One entry per study kind, keyed by the kinds' names.
SECTIONS: dict[str, ReportSection] = {
    "damping": ReportSection(damping_figures, damping_reading, damping_headline),
    "forcing": ReportSection(forcing_figures, forcing_reading, forcing_headline),
    "lyapunov": ReportSection(lyapunov_figures, lyapunov_reading, lyapunov_headline),
    "normal-force": ReportSection(normal_force_figures, normal_force_reading, normal_force_headline),
}


def contact_section(directory: Path, ch3: Chapter3) -> str:
    """Chapter-3 analysis of the shipped real surface: statistics, summits, GW contact (method §1–2),
    rendered from ``ch3``; writes its figures only."""
    path, stats, mat, res = ch3.surface_path, ch3.surface_stats, ch3.material, ch3.contact
    sub = directory / "contact"
    figs = [Path(p) for p in write_surface_figures(sub, fine=ch3.fine, coarse=ch3.coarse,
                                                   fine_summits=ch3.fine_summits,
                                                   coarse_summits=ch3.coarse_summits, step=ch3.preparation.step)]
    figs += [Path(p) for p in write_contact_figures(sub, [res])]
    um = 1e-6
    rows = [[res.approach_m[k] / um, res.contact_area_m2[k], res.area_fraction[k], res.pressure_pa[k] / 1e6,
             int(res.n_contacts[k]), res.mu[k]] for k in range(res.approach_m.size)]
    out = [f"<p>Surface {html.escape(Path(path).name)} (shipped, see data/NOTICE.md): grid "
           f"{stats.grid[0]}×{stats.grid[1]}, Sq = {stats.sq_m / um:.4g} µm, {stats.n_summits} summits, "
           f"σ_S = {_fmt(stats.summit_height_std_m / um)} µm, β̄ = "
           f"{_fmt(stats.summit_radius_mean_m / um)} µm; material {html.escape(mat.name)} "
           f"(E* = {mat.e_star_pa / 1e9:.3g} GPa, τ_max = {mat.shear_strength_pa / 1e6:.3g} MPa).</p>",
           _table(["u [µm]", "A_c [m²]", "A_c/A_nom", "p [MPa]", "contacts", "μ (3.16)"], rows)]
    out += [_figure(p, f"Surface / contact analysis: {p.stem.replace('_', ' ')} (method §1–2, thesis Fig. 3.9–3.11)",
                    directory) for p in figs if p.suffix == ".png"]
    return "".join(out)


def process_statistics_section(directory: Path, ch3: Chapter3) -> str:
    """Statistics of μ and the friction-process model of the shipped surface (method §3–§4)."""
    return friction_process_section(directory, ch3)


#: A figure job: function, positional and keyword arguments; its result is used as it is.
FigureJob = tuple[Callable[..., Any], tuple[Any, ...], dict[str, Any]]


def render_jobs(
    jobs: Sequence[FigureJob], workers: int | None = None, more: Callable[[], Sequence[FigureJob]] | None = None,
) -> list[Any]:
    """Run the report's figure jobs, in order of ``jobs`` then ``more()``, on up to ``workers`` processes.

    Rendering PNGs is pure matplotlib and takes most of the report's time (≈ 13 s for the full
    reproduction on one core); the jobs are independent (each writes its own files atomically),
    so they run in forked worker processes where the platform has ``fork`` (Linux), serially
    otherwise or with ``workers = 1``.  ``None``: ``min(2, cpu count)``.  ``more`` (optional) is called in
    this process once ``jobs`` are handed to the workers, and its jobs run after them: work that the later
    jobs need (the chapter-3 analysis) shares the cores with the drawing instead of preceding it.  The HTML
    is assembled from the results in the same order either way, so the report is the same file.
    """
    n = min(2, os.cpu_count() or 1) if workers is None else int(workers)
    if n <= 1 or (len(jobs) < 2 and more is None) or "fork" not in multiprocessing.get_all_start_methods():
        jobs = [*jobs, *(more() if more is not None else ())]
        return [fn(*args, **kw) for fn, args, kw in jobs]
    with ProcessPoolExecutor(max_workers=n, mp_context=multiprocessing.get_context("fork")) as ex:
        futures = [ex.submit(fn, *args, **kw) for fn, args, kw in jobs]
        if more is not None:
            futures += [ex.submit(fn, *args, **kw) for fn, args, kw in more()]
        return [f.result() for f in futures]


_INTRO = ("<p>Friction oscillator driven by deterministic, white-noise and contact-analysis friction, side by "
          "side (N. Gaus, KIT 2013, chapter 4). Dimensionless x = y/L (L = 1 m), τ = ω0 t; forces in N. "
          "\"method §…\" refers to the sections of docs/method.md in the stochfric repository. "
          "White-noise friction is a phenomenological time-domain noise: its intensity σ_ζ is fixed by no surface "
          "measurement, and it is not the limit of the measured contact process — at a fixed spectral level the "
          "contact model's σ(X_gh) grows as ℓ^β (β ≈ −0.2 … −0.3) as the correlation length ℓ shrinks "
          "(docs/method.md §5.1a, <code>stochfric study white-limit</code>).</p>")


def study_section(k: int, res: StudyResult[Any], figures: Sequence[tuple[Path, str]], directory: Path
                  ) -> tuple[str, str]:
    """The section of the ``k``-th study result (title, reading, choices, table, figures, warnings,
    provenance) and its line of the Reading list."""
    section = SECTIONS[res.kind]
    s = res.summary
    body = [f"<h2 id='s{k}'>{rich_text(study_kind(res.kind).title)} — {html.escape(s.preset)}</h2>"]
    table, reading = section.reading(s)
    answer = f"<li><a href='#s{k}'>{html.escape(res.kind)}</a>: {rich_text(section.headline(s))}</li>"
    body.append(reading_html(reading))
    body.append(f"<p class='choices'>{rich_text(model_choices_text(s))}</p>")
    body.append(table)
    body += [_figure(path, cap, directory) for path, cap in figures]
    if s.warnings:
        body.append("<p>Simulation warnings: " + html.escape(", ".join(f"{x.code} ×{x.count}" for x in s.warnings))
                    + " (explained under Reading).</p>")
    body.append(_provenance(res))
    return "".join(body), answer


def write_report(
    results: Sequence[StudyResult[Any]],
    directory: str | Path,
    *,
    title: str = "stochfric studies",
    chapter3: Chapter3 | Callable[[], Chapter3] | None = None,
    extra_html: str = "",
    workers: int | None = None,
) -> Path:
    """Write ``directory/index.html`` (and the PNG figures) for the study ``results``.

    ``chapter3`` (:func:`stochfric.studies.chapter3.chapter3_analysis`) adds the chapter-3
    sections; the report renders it and computes nothing.  Given as a function, it is called while
    the study figures are drawn (:func:`render_jobs`' ``more``), so the analysis and the drawing share
    the cores.  The figures are drawn on ``workers`` processes.
    """
    d = Path(directory)
    d.mkdir(parents=True, exist_ok=True)
    body = [f"<h1>{html.escape(title)}</h1>", _INTRO]
    jobs: list[FigureJob] = [
        (SECTIONS[res.kind].figures, (res.dataset, d),
         {"prefix": f"{k:02d}_{res.kind.replace('-', '_')}_{res.summary.preset}"})
        for k, res in enumerate(results)]
    def chapter3_jobs() -> list[FigureJob]:
        if chapter3 is None:
            return []
        ch3 = chapter3() if callable(chapter3) else chapter3
        return [(contact_section, (d, ch3), {}), (process_statistics_section, (d, ch3), {})]

    rendered = render_jobs(jobs, workers, more=chapter3_jobs if chapter3 is not None else None)
    readings = []
    for k, res in enumerate(results):
        section, answer = study_section(k, res, rendered[k], d)
        body.append(section)
        readings.append(answer)
    if readings:
        body.insert(2, verdict_section(results) + "<h2>Reading</h2><p>One answer per study; details, tables and "
                    "figures in its section.</p><ul class='answers'>" + "".join(readings) + "</ul>"
                    + warnings_section(results))
    if chapter3 is not None:
        body.append("<h2>Chapter 3: contact analysis of the shipped real surface</h2>")
        body.append(rendered[len(results)])
        body.append("<h2>Chapter 3: statistics of μ and the friction-process model</h2>")
        body.append(rendered[len(results) + 1])
    body.append(extra_html)
    body.append("<h2>Versions</h2><pre>" + html.escape(json.dumps(package_versions(), indent=1)) + "</pre>")
    page = (f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
            f"<style>{_CSS}</style></head><body>{''.join(body)}</body></html>")
    return write_text_atomic(d / "index.html", page)

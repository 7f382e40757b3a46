"""The HTML report: every figure present, decodable and rendered by a headless browser.

Needs the Debian package ``chromium`` for the browser check (skipped with a reason if it is
missing); the file checks always run.
"""

from __future__ import annotations

import dataclasses
import itertools
import json
import os
import re
import shutil
import stat
import subprocess
from html.parser import HTMLParser
from pathlib import Path
from typing import Any

import matplotlib.image as mpimg
import pytest

import stochfric.studies.figures as study_figures
from stochfric.oscillator.options import IntegrationOptions
from stochfric.report.html import WARNING_HELP, damping_reading, process_statistics_section, write_report
from stochfric.studies.chapter3 import chapter3_analysis
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import SampleExtreme, damping_study
from stochfric.studies.forcing import forcing_study
from stochfric.studies.lyapunov import lyapunov_study
from stochfric.studies.normal_force import normal_force_study

PNG = b"\x89PNG\r\n\x1a\n"
CHECK_SCRIPT = """<script>
window.addEventListener('load', () => {
  const imgs = [...document.images];
  const bad = imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'));
  const d = document.createElement('pre'); d.id = 'imgcheck';
  const subs = document.querySelectorAll('ul.answers sub').length;
  d.textContent = 'IMGCHECK' + JSON.stringify({n: imgs.length, bad: bad, subs: subs}) + 'END';
  document.body.appendChild(d);
});
</script>"""


class _Imgs(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.src: list[str] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        if tag == "img":
            self.src.append(dict(attrs)["src"] or "")


FIGURES: dict[str, dict[str, Any]] = {}  # figure file name → what the figure showed before it was closed
RESULTS: list[Any] = []  # the study results the report fixture rendered


def _inspect(fig: Any) -> dict[str, Any]:
    """Overlapping x tick labels and empty panels of a drawn figure."""
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    overlaps, empty, texts, meshes = [], [], [], 0
    for ax in fig.axes:
        if ax.get_label() == "<colorbar>":
            continue
        labels = [t for t in ax.get_xticklabels() if t.get_visible() and t.get_text()]
        boxes = sorted((t.get_window_extent(renderer) for t in labels), key=lambda b: b.x0)
        overlaps += [ax.get_title() for a, b in itertools.pairwise(boxes) if a.x1 > b.x0]
        has_data = bool(ax.lines or ax.patches or ax.collections)
        notes = [t.get_text() for t in ax.texts]
        texts += notes
        meshes += sum(type(c).__name__ == "QuadMesh" for c in ax.collections)
        if not has_data and not any("no stick" in n for n in notes):
            empty.append(ax.get_title())
    return {"overlaps": overlaps, "empty": empty, "texts": texts, "meshes": meshes,
            "legends": sum(ax.get_legend() is not None for ax in fig.axes)}


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    d = tmp_path_factory.mktemp("report")
    results = [
        normal_force_study(NormalForceConfig(runs=3, phase_runs=2, seed=1)),
        damping_study(DampingConfig(normal_forces=(4000.0, 6000.0), damping_ratios="0.08:0.2:5", runs=3, seed=1)),
        forcing_study(ForcingConfig(eta="0.5:2:3", runs=3, seed=1)),
        lyapunov_study(LyapunovConfig(normal_forces=(4000.0,), eta=(1.2, 2.0), runs=2, tau_end=60.0, seed=1)),
    ]
    RESULTS[:] = results
    save = study_figures._save

    def inspecting_save(fig: Any, path: Path) -> Path:
        FIGURES[Path(path).name] = _inspect(fig)
        return save(fig, path)

    old = os.umask(0o022)
    try:
        with pytest.MonkeyPatch.context() as mp:
            mp.setattr(study_figures, "_save", inspecting_save)
            # one process: the figures are inspected in this process (the forked path is compared below)
            return write_report(results, d, title="test report", chapter3=chapter3_analysis(d, quick=True),
                                workers=1)
    finally:
        os.umask(old)


def test_every_image_file_exists_and_decodes(report: Path) -> None:
    text = report.read_text(encoding="utf-8")
    p = _Imgs()
    p.feed(text)
    assert len(p.src) >= 10
    for src in p.src:
        f = report.parent / src
        assert f.exists(), src
        assert f.read_bytes()[:8] == PNG, src
        assert mpimg.imread(f).shape[0] > 50
    for needle in ("D<sub>max</sub><sup>d</sup>", "D<sub>H</sub>", "σ<sub>contact</sub>/σ<sub>white</sub>", "seed",
                   "versions", "contact analysis of the shipped", "statistics of μ", "Reading"):
        assert needle in text, needle


def test_friction_process_section(tmp_path: Path) -> None:
    """method §3–§4 on the shipped surface: tables, figures, and a model file simulate can use."""
    from stochfric.friction_process.model import load_process_model
    from stochfric.oscillator.integrate import simulate
    from stochfric.oscillator.parameters import PhysicalParameters

    text = process_statistics_section(tmp_path, chapter3_analysis(tmp_path, quick=True))
    for needle in ("Ergodicity", "E[μ]", "σ_μ", "ℓ_corr", "a p<sup>b</sup> + c"):
        assert needle in text, needle
    p = _Imgs()
    p.feed(text)
    assert len(p.src) >= 5
    for src in p.src:
        assert (tmp_path / src).read_bytes()[:8] == PNG
    model = load_process_model(tmp_path / "friction_process" / "friction_process.json")
    params = PhysicalParameters(mass=2.0, stiffness=1e6, belt_speed=1.0, normal_force=5600.0,
                                contact_area=0.016).to_dimensionless()
    # the measured surface is 1.2 mm long: a brake-like cycle slides further and reads further,
    # independent segments of the process (it never repeats)
    res = simulate(params, model="contact", process=model, runs=2, seed=1,
                   integration=IntegrationOptions(tau_end=5.0))
    assert not any(w.code == "process-exhausted" for w in res.warnings)
    assert res.diagnostics["process_segments"].min() > 1
    assert res.process is not None and res.stick_count.shape == (1, 2)


def test_report_renders_in_headless_chromium(report: Path, tmp_path: Path) -> None:
    exe = shutil.which("chromium") or shutil.which("chromium-browser")
    if exe is None:
        pytest.skip("chromium not installed (Debian: apt-get install -y chromium)")
    page = report.parent / "check.html"
    page.write_text(report.read_text(encoding="utf-8").replace("</body>", CHECK_SCRIPT + "</body>"), encoding="utf-8")
    args = [exe, "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
            "--disable-background-networking", "--disable-component-update", "--disable-sync",
            f"--user-data-dir={tmp_path / 'profile'}", "--virtual-time-budget=5000"]
    out = subprocess.run([*args, "--dump-dom", page.as_uri()], capture_output=True, text=True, timeout=60)
    m = re.search(r'<pre id="imgcheck">IMGCHECK(.*?)END</pre>', out.stdout)
    assert m, out.stderr[-2000:]
    res = json.loads(m.group(1))
    assert res["n"] >= 10 and res["bad"] == [], res
    assert res["subs"] >= 2, res  # real subscripts in the Reading answers
    shot = tmp_path / "shot.png"
    subprocess.run([*args, f"--screenshot={shot}", "--window-size=1200,3000", report.as_uri()],
                   capture_output=True, timeout=60)
    assert shot.exists() and shot.read_bytes()[:8] == PNG


def test_report_files_are_readable_by_others(report: Path) -> None:
    """Written under umask 022: every file 0644 (mkstemp alone gave 0600 and broken images on a share)."""
    files = [p for p in report.parent.rglob("*") if p.is_file()]
    assert len(files) >= 10
    assert {p.name: oct(stat.S_IMODE(p.stat().st_mode)) for p in files if stat.S_IMODE(p.stat().st_mode) != 0o644} \
        == {}


def test_mdiff_caption_names_the_colours_of_the_colour_map(report: Path) -> None:
    neg, pos = study_figures.mdiff_colours()
    assert (neg, pos) == ("red", "blue")  # RdBu: low end red
    text = report.read_text(encoding="utf-8")
    assert f"{neg} (negative)" in text and f"{pos} (positive)" in text and "blue (negative)" not in text


def test_probability_panel_is_a_heat_map_per_model_with_the_limits(report: Path) -> None:
    fig = FIGURES["01_damping_brake_probability.png"]
    assert fig["meshes"] == 3 and fig["legends"] == 3  # one D × N map per model, each with its D_max lines
    assert (report.parent / "01_damping_brake_probability.png").exists()


def test_no_overlapping_ticks_and_no_blank_panels(report: Path) -> None:
    assert FIGURES, "no figure was inspected"
    bad = {k: (v["overlaps"], v["empty"]) for k, v in FIGURES.items() if v["overlaps"] or v["empty"]}
    assert bad == {}
    # D = 0.15 at 720 N: nothing sticks in any model, and the panel says so
    assert any("no stick" in t for t in FIGURES["00_normal_force_brake_pdf_D1.png"]["texts"])


def test_grid_edges_are_named(report: Path) -> None:
    # the contact model still sticks at the last grid D (0.2) at 6000 N in this run
    assert "> grid" in FIGURES["01_damping_brake_dmax.png"]["texts"]
    damping = next(r for r in RESULTS if r.kind == "damping").summary
    summary = dataclasses.replace(
        damping, normal_force_n=[1000.0, 2000.0], damping_ratio=[0.05, 0.1, 0.15], d_hopf=[0.01, 0.02],
        d_max_deterministic=[None, 0.15], models=["deterministic", "white"], d_max_risk={}, phase=None,
        d_max_sample_extreme={"white": [SampleExtreme(0.1, (0.1, None)), SampleExtreme(0.15, (0.15, None))]})
    table, reading = damping_reading(summary)
    assert "<td>0.01</td><td>&lt; grid start (0.05)</td>" in table  # D_max^d below the grid, not "—"
    assert "<td>≥ 0.15 (&gt; grid)</td>" in table  # D_max^d at the grid's end
    assert "< grid start" in reading


def test_reading_answers_first_and_explains_warnings(report: Path) -> None:
    text = report.read_text(encoding="utf-8")
    reading = text[text.index("<h2>Reading</h2>"):text.index("<h2 id='s0'>")]
    answers = re.findall(r"<li>(.*?)</li>", reading)
    assert len(answers) == 4
    damping = next(a for a in answers if "damping" in a)
    assert re.search(r"brake, N = \d+ N: stick-slip up to D = [\d.]+.* deterministically, .* with white noise", damping)
    assert "— the deterministic limit is" in damping
    assert "D_max" not in reading and "<sub>" in reading  # real subscripts, no raw thesis names
    codes = {m.group(1) for m in re.finditer(r"<dt>([a-z-]+):", reading)}
    warned = {w.code for res in RESULTS for w in res.summary.warnings}
    assert codes == warned, "every warning of the run is explained, and only those"
    for code in codes:
        assert code in WARNING_HELP
        assert WARNING_HELP[code][1].split()[0] in reading and "What to do" in reading


def test_figures_drawn_on_two_processes_give_the_same_report(report: Path, tmp_path: Path) -> None:
    """render_jobs on 2 forked workers: the same HTML and byte-identical PNGs as one process."""
    one, two = tmp_path / "one", tmp_path / "two"
    write_report(RESULTS, one, title="t", workers=1)
    write_report(RESULTS, two, title="t", workers=2)
    assert (one / "index.html").read_text(encoding="utf-8") == (two / "index.html").read_text(encoding="utf-8")
    pngs = sorted(p.name for p in one.glob("*.png"))
    assert len(pngs) >= 8 and pngs == sorted(p.name for p in two.glob("*.png"))
    assert all((one / n).read_bytes() == (two / n).read_bytes() for n in pngs)

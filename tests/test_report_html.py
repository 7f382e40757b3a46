"""The HTML report: every figure present, decodable and rendered by a headless browser.

Needs the Debian package ``chromium`` for the browser check (skipped with a reason if it is
missing); the file checks always run.
"""

from __future__ import annotations

import json
import re
import shutil
import subprocess
from html.parser import HTMLParser
from pathlib import Path

import matplotlib.image as mpimg
import pytest

from stochfric.report.html import process_statistics_section, write_report
from stochfric.studies.config import DampingConfig, ForcingConfig, LyapunovConfig, NormalForceConfig
from stochfric.studies.damping import damping_study
from stochfric.studies.forcing import forcing_study
from stochfric.studies.lyapunov import lyapunov_study
from stochfric.studies.normal_force import normal_force_study

PNG = b"\x89PNG\r\n\x1a\n"
CHECK_SCRIPT = """<script>
window.addEventListener('load', () => {
  const imgs = [...document.images];
  const bad = imgs.filter(i => !(i.complete && i.naturalWidth > 0)).map(i => i.getAttribute('src'));
  const d = document.createElement('pre'); d.id = 'imgcheck';
  d.textContent = 'IMGCHECK' + JSON.stringify({n: imgs.length, bad: bad}) + 'END';
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


@pytest.fixture(scope="module")
def report(tmp_path_factory: pytest.TempPathFactory) -> Path:
    d = tmp_path_factory.mktemp("report")
    results = [
        normal_force_study(NormalForceConfig(runs=3, phase_runs=2, seed=1)),
        damping_study(DampingConfig(normal_forces=(4000.0, 6000.0), damping="0.08:0.2:5", runs=3, seed=1)),
        forcing_study(ForcingConfig(eta="0.5:2:3", runs=3, seed=1)),
        lyapunov_study(LyapunovConfig(normal_forces=(4000.0,), eta=(1.2, 2.0), runs=2, tau_end=60.0, seed=1)),
    ]
    return write_report(results, d, title="test report", contact=True)


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
    for needle in ("D_max^d", "D_H", "σ_contact/σ_white", "seed", "versions", "contact analysis of the shipped",
                   "statistics of μ", "Reading"):
        assert needle in text, needle


def test_friction_process_section(tmp_path: Path) -> None:
    """METHOD §3–§4 on the shipped surface: tables, figures, and a model file simulate can use."""
    from stochfric.oscillator.integrate import simulate
    from stochfric.oscillator.parameters import PhysicalParameters
    from stochfric.process.model import load_process_model

    text = process_statistics_section(tmp_path, quick=True)
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
    from stochfric.oscillator.integrate import SimulationWarningCategory

    # the measured surface is 1.2 mm long: a brake-like cycle exhausts it, and says so
    with pytest.warns(SimulationWarningCategory, match="process exhausted"):
        res = simulate(params, model="contact", process=model, runs=2, seed=1, tau_end=5.0)
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
    shot = tmp_path / "shot.png"
    subprocess.run([*args, f"--screenshot={shot}", "--window-size=1200,3000", report.as_uri()],
                   capture_output=True, timeout=60)
    assert shot.exists() and shot.read_bytes()[:8] == PNG

"""The README and the method page stand alone (issue 11): no files outside the repository, every
link and anchor resolves, §0–§7 as referenced by "method §4c" in the code, time figures name the
machine they were measured on."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
README = ROOT / "README.md"
METHOD = ROOT / "docs" / "method.md"


def _slug(heading: str) -> str:
    """GitHub's anchor of a heading."""
    s = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return s.replace(" ", "-")


def _anchors(path: Path) -> set[str]:
    return {_slug(m.group(1)) for m in re.finditer(r"^#+ (.+)$", path.read_text(encoding="utf-8"), re.MULTILINE)}


@pytest.mark.parametrize("path", [README, METHOD], ids=lambda p: p.name)
def test_no_reference_outside_the_repository(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    assert "METHOD.md" not in text and "shared/spec" not in text and "../seed" not in text
    for target in re.findall(r"\]\(([^)#\s]+)", text):
        if re.match(r"[a-z]+://", target) or not re.search(r"[./]", target):  # a URL, or "E[μ](p)"
            continue
        resolved = (path.parent / target).resolve()
        assert resolved.is_relative_to(ROOT), target
        assert resolved.exists(), target


@pytest.mark.parametrize("path", [README, METHOD], ids=lambda p: p.name)
def test_every_anchor_resolves(path: Path) -> None:
    text = path.read_text(encoding="utf-8")
    for target, anchor in re.findall(r"\]\(([^)#\s]*)#([^)\s]+)\)", text):
        doc = (path.parent / target) if target else path
        assert anchor in _anchors(doc), f"{target}#{anchor}"


def test_method_page_keeps_the_section_numbers() -> None:
    text = METHOD.read_text(encoding="utf-8")
    numbers = [int(n) for n in re.findall(r"^## (\d+)\. ", text, re.MULTILINE)]
    assert numbers == list(range(8))
    assert "### 5.1" in text and "### 5.2" in text
    for sub in "abcde":  # §4a … §4e
        assert re.search(rf"^{sub}\) \*\*", text, re.MULTILINE), sub
    errata = re.findall(r"^(\d+)\. \*\*", text.split("## 7.")[1], re.MULTILINE)
    assert [int(e) for e in errata] == list(range(1, 11))
    for eq in ("(3.1)", "(3.7)", "(3.16)", "(3.21)", "(4.23)", "(4.31)", "(4.41)", "(4.44)"):
        assert eq in text, eq


def test_time_figures_name_the_machine() -> None:
    """Every "… s" figure in the README sits in a section that names the machine (cores) and the date
    of the measurement."""
    sections = re.split(r"^## ", README.read_text(encoding="utf-8"), flags=re.MULTILINE)
    timed = [sec for sec in sections if re.search(r"\b\d+(\.\d+)? ?(s|min)\b", sec)]
    assert timed, "the README gives no measured time at all"
    for sec in timed:
        assert re.search(r"\d+ cores", sec) and re.search(r"\d{4}-\d{2}-\d{2}", sec), sec[:200]


def test_no_file_of_the_product_cites_the_outside_spec() -> None:
    """Code, help, docs, examples and benchmarks point at docs/method.md ("method §…"), never at a
    METHOD.md or a ../shared path that a user of the package does not have."""
    bad = []
    for folder in ("src", "docs", "examples", "benchmarks"):
        for p in (ROOT / folder).rglob("*"):
            if p.is_file() and p.suffix in {".py", ".md", ".toml", ".txt", ".html"}:
                text = p.read_text(encoding="utf-8", errors="replace")
                bad += [f"{p.relative_to(ROOT)}: {w}" for w in ("METHOD.md", "METHOD §", "METHOD erratum",
                                                                "shared/spec", "../seed") if w in text]
    assert bad == []

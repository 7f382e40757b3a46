"""Data flows one way (issue 12): surface → contact → process → oscillator → studies → report → cli.

Every ``import`` in the package (module level and inside functions, absolute and relative) is
read from the source with :mod:`ast`; a module may import its own layer or a lower one, never a
higher one.  The foundation modules (units, random, validation, io_utils, plotting) sit below
every layer and import none of them.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "stochfric"

#: Layer of each top-level module or sub-package of stochfric, lowest first.
LAYERS: dict[str, int] = {
    "units": 0, "random": 0, "validation": 0, "io_utils": 0, "plotting": 0, "progress": 0, "__init__": 0, "data": 0,
    "vector_width": 0,
    "surface": 1,
    "contact": 2,
    "process": 3,
    "oscillator": 4,
    "studies": 5,
    "report": 6,
    "cli": 7, "__main__": 7,
}  # fmt: skip


def _layer_of(module: str) -> int:
    """Layer of a dotted module name inside stochfric (``stochfric.process.model`` → 3)."""
    parts = module.split(".")
    assert parts[0] == "stochfric", module
    if len(parts) == 1:
        return 0
    name = parts[1]
    if name not in LAYERS:
        raise AssertionError(f"module stochfric.{name} has no layer in tests/unit/test_layers.py")
    return LAYERS[name]


def _imports(path: Path, root: Path = PACKAGE) -> list[tuple[str, int]]:
    """(imported stochfric module, line) for every import statement of the file under ``root``."""
    package = list(path.relative_to(root.parent).with_suffix("").parts[:-1])
    out: list[tuple[str, int]] = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            out += [(a.name, node.lineno) for a in node.names if a.name.split(".")[0] == "stochfric"]
        elif isinstance(node, ast.ImportFrom):
            if node.level:
                base = package[: len(package) - node.level + 1]
                mod = ".".join([*base, node.module] if node.module else base)
            else:
                mod = node.module or ""
            if mod.split(".")[0] == "stochfric":
                out.append((mod, node.lineno))
    return out


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_module_imports_a_higher_layer(path: Path) -> None:
    own = _layer_of(".".join(path.relative_to(PACKAGE.parent).with_suffix("").parts))
    upward = [
        f"line {line}: {mod}" for mod, line in _imports(path) if _layer_of(mod) > own
    ]
    assert not upward, f"{path.relative_to(PACKAGE)} (layer {own}) imports a higher layer: {upward}"


def test_the_checker_sees_relative_and_local_imports(tmp_path: Path) -> None:
    src = tmp_path / "stochfric" / "surface"
    src.mkdir(parents=True)
    f = src / "x.py"
    f.write_text("def g():\n    from ..report import html\n    import stochfric.studies.base\n", encoding="utf-8")
    mods = sorted(m for m, _ in _imports(f, tmp_path / "stochfric"))
    assert mods == ["stochfric.report", "stochfric.studies.base"]
    assert _layer_of("stochfric.report") > _layer_of("stochfric.surface.x")

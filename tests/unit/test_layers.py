"""Data flows one way: friction_process → surface → contact → process → oscillator → studies → report → cli.

Every import of the package is read from the source with :mod:`ast` and a module may import its own
layer or a lower one, never a higher one; and no module imports itself through others (the graph of the
imports has no cycle).  Read as imports: ``import`` and ``from … import`` statements
(module level and inside functions, absolute and relative; ``from X import name`` is an import of
``X.name`` where that is a module or package, and ``from stochfric import name`` / ``stochfric.name``
of the home module of the API name), and ``importlib.import_module`` / ``__import__`` calls, whose
names must be string literals.  The foundation modules (units, arrays, random, validation, io_utils,
plotting, progress, vector_width, errors) sit below every layer and import none of them.
The friction-process models (``friction_process``: model files, spectral representation, the thesis's
process presets) sit on floor 1, below the surface: the oscillator needs them, not the surface analysis,
so that ``import stochfric.oscillator`` loads no module of ``surface``, ``contact`` or ``process``.
"""

from __future__ import annotations

import ast
import subprocess
import sys
from pathlib import Path

import pytest

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "stochfric"

#: Layer of each top-level module or sub-package of stochfric, lowest first.
LAYERS: dict[str, int] = {
    "units": 0, "random": 0, "validation": 0, "io_utils": 0, "plotting": 0, "progress": 0, "__init__": 0, "data": 0,
    "vector_width": 0, "arrays": 0, "errors": 0, "interrupts": 0,
    "friction_process": 1,
    "surface": 2,
    "contact": 3,
    "process": 4,
    "oscillator": 5,
    "studies": 6,
    "report": 7,
    "cli": 8, "__main__": 8,
}  # fmt: skip

#: The one dynamic import whose name is a variable: ``stochfric.__getattr__`` imports the home module
#: of an API name on first use.  Those names are resolved where they are used instead.
FACADE = "__init__.py"

#: The calls read as imports.
_IMPORT_CALLS = ("import_module", "__import__")


class UncheckableImport(AssertionError):
    """A dynamic import whose module name is no string literal (the checker cannot see its layer)."""


def _layer_of(module: str) -> int:
    """Layer of a dotted module name inside stochfric (``stochfric.contact.asperity`` → 3)."""
    parts = module.split(".")
    assert parts[0] == "stochfric", module
    if len(parts) == 1:
        return 0
    name = parts[1]
    if name not in LAYERS:
        raise AssertionError(f"module stochfric.{name} has no layer in tests/unit/test_layers.py")
    return LAYERS[name]


def _api(root: Path) -> dict[str, str]:
    """The package's API: name → home module (the literal dict ``API`` of ``root/__init__.py``)."""
    init = root / "__init__.py"
    if not init.is_file():
        return {}
    target: ast.expr
    for node in ast.parse(init.read_text(encoding="utf-8")).body:
        if isinstance(node, ast.AnnAssign) and node.value is not None:
            target, value = node.target, node.value
        elif isinstance(node, ast.Assign) and len(node.targets) == 1:
            target, value = node.targets[0], node.value
        else:
            continue
        if isinstance(target, ast.Name) and target.id == "API":
            return dict(ast.literal_eval(value))
    return {}


class _Reader:
    """The stochfric imports of one file of the package under ``root``."""

    def __init__(self, path: Path, root: Path) -> None:
        self.path = path
        self.root = root
        self.package = list(path.relative_to(root.parent).with_suffix("").parts[:-1])
        self.api = _api(root)
        self.found: list[tuple[str, int]] = []

    def _is_module(self, dotted: str) -> bool:
        path = self.root.parent.joinpath(*dotted.split("."))
        return (path / "__init__.py").is_file() or path.with_suffix(".py").is_file()

    def _member(self, module: str, name: str) -> str:
        """What ``from module import name`` imports: the sub-module, the API name's home, or ``module``."""
        if self._is_module(f"{module}.{name}"):
            return f"{module}.{name}"
        if module == self.root.name and name in self.api:
            return self.api[name]
        return module

    def _absolute(self, name: str, level: int, package: list[str], line: int) -> str:
        if level == 0:
            return name
        if level > len(package):
            raise UncheckableImport(f"{self._where(line)}: relative import beyond the top-level package")
        return ".".join([*package[: len(package) - level + 1], *([name] if name else [])])

    def _where(self, line: int) -> str:
        return f"{self.path.relative_to(self.root.parent)}:{line}"

    def _add(self, module: str, line: int) -> None:
        if module.split(".")[0] == self.root.name:
            self.found.append((module, line))

    def read(self) -> list[tuple[str, int]]:
        tree = ast.parse(self.path.read_text(encoding="utf-8"))
        aliases = {"import_module", "__import__"}
        packages: set[str] = set()  # names bound to the package itself (``import stochfric as sf``)
        for node in ast.walk(tree):
            if isinstance(node, ast.Import):
                for a in node.names:
                    self._add(a.name, node.lineno)
                    if a.name.split(".")[0] == self.root.name and (a.asname is None or a.name == self.root.name):
                        packages.add(a.asname or self.root.name)
            elif isinstance(node, ast.ImportFrom):
                module = self._absolute(node.module or "", node.level, self.package, node.lineno)
                if module == "importlib":
                    aliases |= {a.asname for a in node.names if a.name == "import_module" and a.asname}
                for a in node.names:
                    self._add(self._member(module, a.name), node.lineno)
        for node in ast.walk(tree):
            if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id in packages:
                self._add(self._member(self.root.name, node.attr), node.lineno)
            elif isinstance(node, ast.Call):
                func = node.func
                called = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
                if called in _IMPORT_CALLS or (isinstance(func, ast.Name) and called in aliases):
                    self._dynamic(node, called)
        return self.found

    def _dynamic(self, call: ast.Call, called: str) -> None:
        """``import_module(name, package)`` or ``__import__(name, globals, locals, fromlist, level)``."""
        args: dict[int | str, ast.expr] = dict(enumerate(call.args))
        args.update({k.arg: k.value for k in call.keywords if k.arg})
        name = args.get(0, args.get("name"))
        if not (isinstance(name, ast.Constant) and isinstance(name.value, str)):
            if self.path == self.root / FACADE:
                return
            raise UncheckableImport(
                f"{self._where(call.lineno)}: {called}() with a name that is no literal; the layering "
                "test cannot see what it imports: import it by a literal name (or a plain import statement)"
            )
        if called == "__import__":
            level_node = args.get(4, args.get("level"))
            level = level_node.value if isinstance(level_node, ast.Constant) else 0 if level_node is None else -1
            if not isinstance(level, int) or level < 0:
                raise UncheckableImport(f"{self._where(call.lineno)}: __import__ with a level that is no literal")
            module = self._absolute(name.value, level, self.package, call.lineno)
            self._add(module, call.lineno)
            fromlist = args.get(3, args.get("fromlist"))
            if fromlist is not None:
                for member in ast.literal_eval(fromlist):
                    self._add(self._member(module, member), call.lineno)
            return
        relative = name.value[: len(name.value) - len(name.value.lstrip("."))]
        self._add(self._absolute(name.value[len(relative):], len(relative), self._package_of(args, call), call.lineno),
                  call.lineno)

    def _package_of(self, args: dict[int | str, ast.expr], call: ast.Call) -> list[str]:
        """The anchor of a relative ``import_module``: a literal or ``__package__`` (this file's package)."""
        package = args.get(1, args.get("package"))
        if package is None or (isinstance(package, ast.Name) and package.id == "__package__"):
            return self.package
        if isinstance(package, ast.Constant) and isinstance(package.value, str):
            return package.value.split(".")
        raise UncheckableImport(f"{self._where(call.lineno)}: import_module with a package that is no literal")


def _imports(path: Path, root: Path = PACKAGE) -> list[tuple[str, int]]:
    """(imported stochfric module, line) for every import of the file under ``root``."""
    return _Reader(path, root).read()


def _upward(path: Path, root: Path = PACKAGE) -> list[str]:
    """The imports of ``path`` from a higher layer than its own, as ``line N: module``."""
    own = _layer_of(".".join(path.relative_to(root.parent).with_suffix("").parts))
    return [f"line {line}: {mod}" for mod, line in _imports(path, root) if _layer_of(mod) > own]


MODULES = sorted(p for p in PACKAGE.rglob("*.py"))


@pytest.mark.parametrize("path", MODULES, ids=lambda p: str(p.relative_to(PACKAGE)))
def test_no_module_imports_a_higher_layer(path: Path) -> None:
    upward = _upward(path)
    assert not upward, f"{path.relative_to(PACKAGE)} imports a higher layer: {upward}"


def _tree(tmp_path: Path) -> Path:
    """A package ``stochfric`` with the layers' sub-packages and an API facade, under ``tmp_path``."""
    root = tmp_path / "stochfric"
    for sub in ("surface", "contact", "process", "oscillator", "studies", "report", "cli"):
        (root / sub).mkdir(parents=True)
        (root / sub / "__init__.py").write_text("", encoding="utf-8")
    (root / "units.py").write_text("", encoding="utf-8")
    (root / "__init__.py").write_text(
        'import importlib\n__version__ = "0"\nAPI = {"analyse": "stochfric.process.statistics"}\n\n'
        "def __getattr__(name):\n    return getattr(importlib.import_module(API[name]), name)\n",
        encoding="utf-8",
    )
    return root


def _write(root: Path, where: str, source: str) -> Path:
    path = root / where
    path.write_text(source, encoding="utf-8")
    return path


def test_the_checker_sees_relative_and_local_imports(tmp_path: Path) -> None:
    root = _tree(tmp_path)
    f = _write(root, "surface/x.py", "def g():\n    from ..report import html\n    import stochfric.studies.base\n")
    assert sorted(m for m, _ in _imports(f, root)) == ["stochfric.report", "stochfric.studies.base"]
    assert _layer_of("stochfric.report") > _layer_of("stochfric.surface.x")


@pytest.mark.parametrize(
    ("where", "source", "module"),
    [
        ("surface/x.py", "from .. import report\n", "stochfric.report"),
        ("process/x.py", "from stochfric import cli\n", "stochfric.cli"),
        ("studies/x.py", 'import importlib\nimportlib.import_module("stochfric.report")\n', "stochfric.report"),
        ("studies/x.py", 'from importlib import import_module as im\nim("..report", __package__)\n',
         "stochfric.report"),
        ("studies/x.py", 'import importlib\nimportlib.import_module(".cli", "stochfric")\n', "stochfric.cli"),
        ("contact/x.py", '__import__("stochfric", fromlist=["studies"])\n', "stochfric.studies"),
        ("contact/x.py", '__import__("report", globals(), None, [], 2)\n', "stochfric.report"),
        ("surface/x.py", "from stochfric import analyse\n", "stochfric.process.statistics"),
        ("surface/x.py", "import stochfric as sf\n\ndef f():\n    return sf.analyse\n", "stochfric.process.statistics"),
    ],
)
def test_the_checker_fails_on_an_upward_import(tmp_path: Path, where: str, source: str, module: str) -> None:
    root = _tree(tmp_path)
    path = _write(root, where, source)
    assert module in [m for m, _ in _imports(path, root)]
    assert _upward(path, root), f"{where}: {source!r} passed the checker"


@pytest.mark.parametrize(
    "source",
    [
        "import importlib\n\ndef f(name):\n    return importlib.import_module(name)\n",
        'import importlib\n\ndef f(p):\n    return importlib.import_module(".x", p)\n',
        "def f(name):\n    return __import__(name)\n",
    ],
)
def test_the_checker_refuses_a_dynamic_import_it_cannot_read(tmp_path: Path, source: str) -> None:
    path = _write(_tree(tmp_path), "surface/x.py", source)
    with pytest.raises(UncheckableImport, match="no literal"):
        _imports(path, tmp_path / "stochfric")


def test_the_checker_passes_imports_of_the_same_or_a_lower_layer(tmp_path: Path) -> None:
    root = _tree(tmp_path)
    path = _write(root, "process/x.py", "from .. import units, surface\nfrom stochfric import __version__\n"
                  'import importlib\nimportlib.import_module("..contact", __package__)\n')
    assert sorted(m for m, _ in _imports(path, root)) == [
        "stochfric", "stochfric.contact", "stochfric.surface", "stochfric.units"
    ]
    assert not _upward(path, root)
    assert not _upward(root / "__init__.py", root)  # the facade's variable name is resolved where it is used


# --- no circles: the graph of the package's imports --------------------------------------------------


def _file_of(module: str, root: Path) -> Path | None:
    """The file of a dotted stochfric module: ``a/b.py``, or ``a/b/__init__.py`` for a package."""
    path = root.parent.joinpath(*module.split("."))
    if path.with_suffix(".py").is_file():
        return path.with_suffix(".py")
    if (path / "__init__.py").is_file():
        return path / "__init__.py"
    return None


def _graph(root: Path = PACKAGE) -> dict[Path, set[Path]]:
    """Each file of the package → the files of the package it imports (:func:`_imports`: module level and
    inside functions, relative and dynamic; an imported package is its ``__init__.py``; the parent
    packages Python imports on the way are not edges).  Self-imports are left out."""
    graph: dict[Path, set[Path]] = {}
    for path in sorted(root.rglob("*.py")):
        targets = {_file_of(module, root) for module, _ in _imports(path, root)}
        graph[path] = {t for t in targets if t is not None and t != path}
    return graph


def _cycles(graph: dict[Path, set[Path]]) -> list[list[Path]]:
    """One cycle (``[a, b, …, a]``) per strongly connected component of more than one file (Tarjan)."""
    index: dict[Path, int] = {}
    low: dict[Path, int] = {}
    stack: list[Path] = []
    on_stack: set[Path] = set()
    components: list[set[Path]] = []

    def connect(v: Path) -> None:  # recursion depth ≤ number of files (≈ 100)
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, ())):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = set()
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.add(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(component)

    for v in sorted(graph):
        if v not in index:
            connect(v)
    return [_cycle_in(graph, component) for component in components]


def _cycle_in(graph: dict[Path, set[Path]], component: set[Path]) -> list[Path]:
    """A shortest cycle through the component's first file (breadth-first inside the component)."""
    start = min(component)
    previous: dict[Path, Path] = {}
    frontier = [start]
    while frontier:
        following = []
        for v in frontier:
            for w in sorted(graph[v] & component):
                if w == start:
                    path = [v]
                    while path[-1] != start:
                        path.append(previous[path[-1]])
                    return [start, *reversed(path[:-1]), start]
                if w not in previous:
                    previous[w] = v
                    following.append(w)
        frontier = following
    raise AssertionError(f"no cycle through {start} in its strongly connected component")


def _closure(graph: dict[Path, set[Path]], starts: list[Path]) -> set[Path]:
    """Every file reachable from ``starts`` through the import graph (``starts`` included)."""
    seen = set(starts)
    todo = list(starts)
    while todo:
        for w in graph[todo.pop()] - seen:
            seen.add(w)
            todo.append(w)
    return seen


def _shown(path: Path, root: Path = PACKAGE) -> str:
    return str(path.relative_to(root.parent))


def test_the_imports_have_no_cycle() -> None:
    """No file imports itself through others: each floor is a tree of modules, a cycle is broken by moving
    what both need (a local import inside a function is still an import here)."""
    cycles = _cycles(_graph())
    assert not cycles, "import cycles: " + "; ".join(" -> ".join(_shown(p) for p in c) for c in cycles)


#: The floors below the oscillator that it must not need: a simulation reads no surface.
NOT_BELOW_THE_OSCILLATOR = ("stochfric.surface", "stochfric.contact", "stochfric.process")


def test_the_oscillator_imports_no_surface_contact_or_analysis_module_statically() -> None:
    oscillator = sorted((PACKAGE / "oscillator").rglob("*.py"))
    reached = {".".join(p.relative_to(PACKAGE.parent).with_suffix("").parts) for p in _closure(_graph(), oscillator)}
    bad = sorted(m for m in reached for pkg in NOT_BELOW_THE_OSCILLATOR if m == pkg or m.startswith(pkg + "."))
    assert not bad, f"stochfric/oscillator/ imports (transitively) {bad}"


def test_importing_the_oscillator_loads_no_surface_contact_or_analysis_module() -> None:
    code = ("import sys, stochfric.oscillator\n"
            f"print('\\n'.join(m for m in sorted(sys.modules) for p in {NOT_BELOW_THE_OSCILLATOR!r} "
            "if m == p or m.startswith(p + '.')))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300, check=False)
    assert done.returncode == 0, done.stderr
    loaded = done.stdout.split()
    assert not loaded, f"import stochfric.oscillator loads {loaded}"


def test_the_cycle_finder_sees_a_cycle_through_local_and_package_imports(tmp_path: Path) -> None:
    root = _tree(tmp_path)
    a = _write(root, "studies/a.py", "from . import b\n")
    b = _write(root, "studies/b.py", "def f():\n    from .c import g\n")
    c = _write(root, "studies/c.py", "import stochfric.studies\n")
    init = _write(root, "studies/__init__.py", "from .a import x\n")
    _write(root, "studies/d.py", "from .a import x\nfrom . import d\n")  # imports a, and itself: no cycle
    graph = _graph(root)
    assert graph[c] == {init} and graph[root / "studies" / "d.py"] == {a}
    assert _cycles(graph) == [[init, a, b, c, init]]  # from the first file of the component
    c.write_text("from stochfric import units\n", encoding="utf-8")
    assert _cycles(_graph(root)) == []
    assert _closure(_graph(root), [a]) == {a, b, c, root / "units.py"}


#: The longest function the package may hold (lines, decorators excluded): a longer one is split.
MAX_FUNCTION_LINES = 120


def test_no_function_is_longer_than_the_limit() -> None:
    long = []
    for path in MODULES:
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef):
                lines = (node.end_lineno or node.lineno) - node.lineno + 1
                if lines > MAX_FUNCTION_LINES:
                    long.append(f"{path.relative_to(PACKAGE)}:{node.lineno} {node.name} ({lines} lines)")
    assert not long, f"functions over {MAX_FUNCTION_LINES} lines: {long}"

"""One base for the package's errors (issue 28): every exception class stochfric defines derives from
:class:`stochfric.errors.StochfricError`, so that a caller catches the package's errors once; the input
errors stay ``ValueError``s, so that code that caught ``ValueError`` keeps working."""

from __future__ import annotations

import ast
import importlib
import inspect
import json
from pathlib import Path

import pytest

from stochfric.errors import InputError, ProcessModelError, StochfricError

PACKAGE = Path(__file__).resolve().parents[2] / "src" / "stochfric"

#: The error classes the package had before the common base, each a ValueError (issue 28 names them).
INPUT_ERRORS = {
    "stochfric.surface.io": "SurfaceError",
    "stochfric.contact.asperity": "ContactError",
    "stochfric.contact.materials": "MaterialError",
    "stochfric.oscillator.parameters": "ParameterError",
    "stochfric.oscillator.case": "CaseError",
    "stochfric.studies.errors": "StudyError",
    "stochfric.io_utils": "OutputPathError",
}


def _modules() -> list[str]:
    """Every module of the package but the ``__main__`` scripts (importing those runs the command line)."""
    out = []
    for path in sorted(PACKAGE.rglob("*.py")):
        parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
        if parts[-1] == "__main__":
            continue
        out.append(".".join(parts[:-1] if parts[-1] == "__init__" else parts))
    return out


def _exception_classes() -> dict[str, type[BaseException]]:
    """``module.Class`` → class, for every exception class defined at the top of a module of the package
    (found by importing the module, and cross-checked against the ``class`` statements :mod:`ast` reads)."""
    found: dict[str, type[BaseException]] = {}
    for name in _modules():
        module = importlib.import_module(name)
        for cls_name, cls in inspect.getmembers(module, inspect.isclass):
            if cls.__module__ == name and issubclass(cls, BaseException):
                found[f"{name}.{cls_name}"] = cls
        path = Path(module.__file__ or "")
        for node in ast.parse(path.read_text(encoding="utf-8")).body:
            if isinstance(node, ast.ClassDef) and isinstance(getattr(module, node.name, None), type):
                cls = getattr(module, node.name)
                if issubclass(cls, BaseException):
                    assert f"{name}.{node.name}" in found
    return found


CLASSES = _exception_classes()


def test_the_walk_finds_the_package_errors() -> None:
    for module, name in INPUT_ERRORS.items():
        assert f"{module}.{name}" in CLASSES, f"{module}.{name} not found"
    assert "stochfric.io_utils.MemoryRequestError" in CLASSES
    assert "stochfric.errors.StochfricError" in CLASSES


@pytest.mark.parametrize("name", sorted(n for n, c in CLASSES.items() if issubclass(c, Exception)
                                        and not issubclass(c, Warning)))
def test_every_error_of_the_package_derives_from_the_base(name: str) -> None:
    assert issubclass(CLASSES[name], StochfricError), (
        f"{name} does not derive from stochfric.errors.StochfricError: give it that base (an input error: "
        "InputError, also a ValueError)")


def test_the_only_exceptions_outside_the_base_are_no_errors() -> None:
    """A Ctrl-C of a study sweep is a KeyboardInterrupt (it must not be caught as an error)."""
    others = sorted(n for n, c in CLASSES.items() if not issubclass(c, Exception) or issubclass(c, Warning))
    assert others == ["stochfric.studies.executors.SweepInterrupted"]
    assert not issubclass(CLASSES[others[0]], Exception)


@pytest.mark.parametrize(("module", "name"), sorted(INPUT_ERRORS.items()))
def test_the_input_errors_stay_value_errors(module: str, name: str) -> None:
    cls = getattr(importlib.import_module(module), name)
    assert issubclass(cls, InputError) and issubclass(cls, ValueError)


def test_a_bad_process_model_file_is_a_process_model_error(tmp_path: Path) -> None:
    from stochfric.friction_process.model import load_process_model, process_model_from_dict

    bad = tmp_path / "m.json"
    bad.write_text(json.dumps({"kind": "band_limited", "name": "x"}), encoding="utf-8")
    with pytest.raises(ProcessModelError, match="is missing"):
        load_process_model(bad)
    with pytest.raises(ProcessModelError, match="unknown process model kind 'pink'"):
        process_model_from_dict({"kind": "pink"})
    bad.write_text("[1, 2]", encoding="utf-8")
    with pytest.raises(ValueError, match="is not a friction-process model file"):  # still a ValueError
        load_process_model(bad)


def test_a_bad_model_is_a_process_model_error() -> None:
    from stochfric.friction_process.presets import brake_process

    model = brake_process()
    data = model.to_dict()
    with pytest.raises(ProcessModelError, match="dx must be > 0 m"):
        type(model).from_dict({**data, "dx": -1.0})
    with pytest.raises(ProcessModelError, match="falling_ratio must lie in"):
        type(model).from_dict({**data, "falling_ratio": 2.0})


def test_a_bad_study_config_from_python_is_a_package_error_on_one_line() -> None:
    from stochfric.studies.config import DampingConfig
    from stochfric.studies.errors import StudyConfigError

    with pytest.raises(StudyConfigError) as info:
        DampingConfig(runs=0, seed=-1)
    assert isinstance(info.value, StochfricError) and isinstance(info.value, ValueError)
    assert "\n" not in str(info.value) and "runs" in str(info.value) and "seed" in str(info.value)


def test_wrong_types_and_values_of_the_foundation_are_package_errors() -> None:
    from stochfric.random import as_seed_sequence
    from stochfric.units import length_to_m

    with pytest.raises(StochfricError, match="seed must be a non-negative int"):
        as_seed_sequence("1")  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        as_seed_sequence(1.5)  # type: ignore[arg-type]
    with pytest.raises(StochfricError, match="unknown length unit"):
        length_to_m(1.0, "furlong")

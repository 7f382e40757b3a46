"""docs/api.md is executed: its ``python`` blocks run in order, in one namespace, in a temporary
directory (issue 20 §4: a docs page whose code runs in the tests)."""

from __future__ import annotations

import re
from pathlib import Path

import pytest

DOC = Path(__file__).resolve().parents[1] / "docs" / "api.md"


def _blocks() -> list[str]:
    return re.findall(r"```python\n(.*?)```", DOC.read_text(encoding="utf-8"), flags=re.S)


def test_api_page_has_code() -> None:
    assert len(_blocks()) >= 4


def test_api_page_runs(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.chdir(tmp_path)
    namespace: dict[str, object] = {"__name__": "docs_api"}
    for k, block in enumerate(_blocks()):
        try:
            exec(compile(block, f"docs/api.md block {k + 1}", "exec"), namespace)
        except Exception as exc:  # pragma: no cover - the failure message is the point
            pytest.fail(f"docs/api.md block {k + 1} failed: {type(exc).__name__}: {exc}")
    assert (tmp_path / "report" / "index.html").is_file()


def test_the_api_names_resolve_to_their_home_objects() -> None:
    import importlib

    import stochfric as sf

    for name, home in sf.API.items():
        assert getattr(sf, name) is getattr(importlib.import_module(home), name), name
    with pytest.raises(AttributeError, match="the API is"):
        sf.no_such_function  # noqa: B018

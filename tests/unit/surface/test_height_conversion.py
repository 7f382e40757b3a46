"""A height conversion factor on the command line and in the library: ``--height-unit FACTOR*UNIT``
(issue 32 §7).  Expected heights are the written numbers × factor × unit, computed by hand."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.surface.io import SurfaceError, parse_height_unit, read_surface

ROWS = (np.arange(6 * 8, dtype=float).reshape(6, 8) % 7) * 0.25 + np.arange(6 * 8).reshape(6, 8) * 0.01


@pytest.mark.parametrize(("text", "expected"), [("nm", (1.0, "nm")), ("0.5*nm", (0.5, "nm")),
                                                ("2e-3 um", (2e-3, "um")), (" 4 * m ", (4.0, "m"))])
def test_parse(text: str, expected: tuple[float, str]) -> None:
    assert parse_height_unit(text) == expected


@pytest.mark.parametrize(("text", "words"), [("-1*um", "positive finite"), ("0*um", "positive finite"),
                                             ("x*um", "write FACTOR"), ("2*furlong", "unknown length unit")])
def test_bad_factor_or_unit(text: str, words: str) -> None:
    with pytest.raises(SurfaceError, match=words):
        parse_height_unit(text)


def test_plain_matrix_with_a_factor(tmp_path: Path) -> None:
    p = tmp_path / "m.txt"
    np.savetxt(p, ROWS)
    s = read_surface(p, physical_size_m=(8e-6, 6e-6), height_unit="0.5*um")
    np.testing.assert_allclose(s.heights_m, ROWS * 0.5e-6, rtol=1e-12)
    assert s.info["height_conversion_factor"] == 0.5 and s.info["height_unit"] == "um"


def test_headered_text_without_unit_takes_the_factor(tmp_path: Path) -> None:
    """SurfaceTopography reads the header (the size, in µm); the heights get unit and factor from the option."""
    p = tmp_path / "phase.txt"
    with open(p, "w", encoding="utf-8") as fh:
        fh.write("# Width: 40 um\n# Height: 30 um\n")
        np.savetxt(fh, ROWS, fmt="%.6f")
    s = read_surface(p, height_unit="2e-3*um")
    assert s.info["reader"] != "numpy"
    # SurfaceTopography's text layout: line j is y_j, so heights_m[i, j] = ROWS[j, i]
    np.testing.assert_allclose(s.heights_m, ROWS.T * 2e-9, rtol=1e-6)


def test_command_line_factor_and_error(tmp_path: Path) -> None:
    p = tmp_path / "m.txt"
    rng = np.random.default_rng(1)
    np.savetxt(p, rng.normal(size=(48, 48)))
    res = CliRunner().invoke(app, ["surface", str(p), "--size-um", "96:96", "--height-unit", "0*um"])
    assert res.exit_code == 2 and "conversion factor must be a positive finite number" in res.stderr
    assert "Traceback" not in res.output


@pytest.mark.parametrize(("make", "words"), [
    (lambda d: d, "is a directory; give a height-map file"),
    (lambda d: Path("/dev/zero"), "is not a regular file"),
    (lambda d: (d / "e.x3p").touch() or d / "e.x3p", "is empty (0 bytes)"),
    (lambda d: d / "missing.x3p", "no such file"),
])
def test_a_map_file_is_checked_before_any_reader_opens_it(tmp_path: Path, make: object, words: str) -> None:
    """Issue 32: every file read checks first that it is a regular file of a plausible size (a device would
    block a reader, a directory or an empty file gave a reader's error)."""
    with pytest.raises(SurfaceError, match=re.escape(words)):
        read_surface(make(tmp_path), physical_size_m=(1e-4, 1e-4), height_unit="um")  # type: ignore[operator]

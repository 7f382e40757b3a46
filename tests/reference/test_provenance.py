"""The figures of ../shared/data/topographies/PROVENANCE.md, reproduced for every file.

grid, physical size, undefined points, Sq raw and Sq after removing the best-fit plane
(stochfric's own ``detrend(..., "plane")``), byte count and sha256 prefix.
"""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from stochfric.surface.io import SurfaceError, file_sha256, read_surface
from stochfric.surface.preprocess import detrend
from stochfric.surface.statistics import height_moments

DATA = Path(__file__).resolve().parents[3] / "shared" / "data" / "topographies"
PROVENANCE = DATA / "PROVENANCE.md"

pytestmark = pytest.mark.skipif(
    not PROVENANCE.is_file(),
    reason=f"shared topographies not found at {DATA} (CI clones them as ../shared)",
)

ROW = re.compile(
    r"^\| `(?P<file>[^`]+)` \| (?P<nx>\d+)x(?P<ny>\d+) \| (?P<lx>[\d.]+) x (?P<ly>[\d.]+) "
    r"(?P<unit>mm) \| (?P<undef>yes|no) \| (?P<sq>[\d.]+) \| (?P<sqd>[\d.]+) \| "
    r"(?P<bytes>\d+) \| (?P<sha>[0-9a-f]+) \|$"
)


def _rows() -> list[dict[str, str]]:
    if not PROVENANCE.is_file():
        return []
    rows = [m.groupdict() for line in PROVENANCE.read_text(encoding="utf-8").splitlines()
            if (m := ROW.match(line.strip()))]  # fmt: skip
    return rows


def _sig(value: float, digits: int) -> float:
    return float(f"{value:.{digits}g}")


def test_table_is_complete() -> None:
    rows = _rows()
    assert len(rows) == 7
    assert {r["file"] for r in rows} == {p.name for p in DATA.iterdir() if p.is_file() and p.suffix != ".md"}


@pytest.mark.parametrize("row", _rows(), ids=lambda r: r["file"])
def test_file_matches_provenance(row: dict[str, str]) -> None:
    path = DATA / row["file"]
    assert path.stat().st_size == int(row["bytes"])
    assert file_sha256(path).startswith(row["sha"])
    has_undefined = row["undef"] == "yes"
    if has_undefined:
        with pytest.raises(SurfaceError, match="undefined point"):
            read_surface(path)
    s = read_surface(path, fill_undefined=has_undefined)
    assert (s.n_undefined_filled > 0) == has_undefined
    assert s.nb_grid_pts == (int(row["nx"]), int(row["ny"]))
    # sizes and Sq are printed with 4 significant digits
    lx_mm, ly_mm = (v * 1e3 for v in s.physical_size_m)
    assert _sig(lx_mm, 4) == pytest.approx(float(row["lx"]), rel=1e-9)
    assert _sig(ly_mm, 4) == pytest.approx(float(row["ly"]), rel=1e-9)
    sq_raw_um = height_moments(s.heights_m)[0] * 1e6
    sq_det_um = height_moments(detrend(s.heights_m, "plane"))[0] * 1e6
    assert _sig(sq_raw_um, 4) == pytest.approx(float(row["sq"]), rel=1e-9)
    assert _sig(sq_det_um, 4) == pytest.approx(float(row["sqd"]), rel=1e-9)
    assert np.isfinite(s.heights_m).all()

"""Text height maps: a ``.txt`` with a header SurfaceTopography's text reader understands is read by it,
a plain matrix by numpy (issue 29 item 7).

SurfaceTopography's text layout: each line of the file is one ``y`` position and the values along a line
run along ``x``, so ``heights_m[i, j]`` is value ``i`` of line ``j`` (the transpose of the plain-matrix
layout, where line ``i`` is ``x = iΔx``).  Expected values are computed by hand from the numbers written.
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.surface.io import SurfaceError, read_surface

#: 6 lines of 8 values: a non-planar pattern with every value distinct.
ROWS = (np.arange(6 * 8, dtype=float).reshape(6, 8) % 7) * 0.25 + np.arange(6 * 8).reshape(6, 8) * 0.01


def _write(path: Path, header: list[str], rows: np.ndarray = ROWS, delimiter: str = " ") -> Path:
    with open(path, "w", encoding="utf-8") as fh:
        for line in header:
            fh.write(f"# {line}\n")
        np.savetxt(fh, rows, fmt="%.6f", delimiter=delimiter)
    return path


def test_headered_text_file_is_read_by_surfacetopography(tmp_path: Path) -> None:
    p = _write(tmp_path / "gwy.txt", ["Channel: Height", "Width: 40 µm", "Height: 30 um", "Value units: um"])
    s = read_surface(p)
    assert s.nb_grid_pts == (8, 6)  # 8 values per line along x, 6 lines along y
    np.testing.assert_allclose(s.physical_size_m, (40e-6, 30e-6), rtol=1e-12)
    np.testing.assert_allclose(s.heights_m, ROWS.T * 1e-6, rtol=1e-12, atol=1e-18)
    assert s.grid_spacing_m == pytest.approx((5e-6, 5e-6))
    assert s.info["reader"] == "AscReader"
    assert s.info["file_unit"] == "um" and s.info["height_unit"] == "um"
    assert s.info["file_physical_size"] == pytest.approx([40.0, 30.0])
    assert s.info["file_size_units"] == ["um", "um"]
    assert s.info["file_height_scale_factor"] is None
    json.dumps(s.info)  # provenance stays JSON-serialisable


def test_header_with_different_lateral_and_height_units(tmp_path: Path) -> None:
    p = _write(tmp_path / "mixed.txt", ["Width: 0.04 mm", "Height: 30 um", "Value units: nm"])
    s = read_surface(p)
    np.testing.assert_allclose(s.physical_size_m, (40e-6, 30e-6), rtol=1e-12)  # 0.04 mm, 30 µm
    np.testing.assert_allclose(s.heights_m, ROWS.T * 1e-9, rtol=1e-12, atol=1e-21)
    assert s.info["file_unit"] == "nm"
    assert s.info["file_physical_size"] == pytest.approx([40_000.0, 30_000.0])  # in the file unit, nm


def test_height_conversion_factor_of_the_header_is_applied(tmp_path: Path) -> None:
    # e.g. a phase map in rad with the factor to µm: z = 0.05 µm per stored unit
    p = _write(tmp_path / "phase.txt", ["Width: 40 um", "Height: 30 um", "height conversion factor (-> um) = 0.05"])
    s = read_surface(p)
    np.testing.assert_allclose(s.heights_m, ROWS.T * 0.05e-6, rtol=1e-12, atol=1e-18)
    np.testing.assert_allclose(s.physical_size_m, (40e-6, 30e-6), rtol=1e-12)
    assert s.info["file_height_scale_factor"] == pytest.approx(0.05)
    assert s.info["file_unit"] == "um"


def test_plain_text_matrix_keeps_the_numpy_reader(tmp_path: Path) -> None:
    p = _write(tmp_path / "plain.txt", ["exported by a script, no metadata"])
    with pytest.raises(SurfaceError, match="plain matrix without physical size and height unit"):
        read_surface(p)
    s = read_surface(p, physical_size_m=(60e-6, 80e-6), height_unit="um")
    assert s.nb_grid_pts == (6, 8)  # numpy layout: line i is x = iΔx
    np.testing.assert_allclose(s.heights_m, ROWS * 1e-6, rtol=1e-12, atol=1e-18)
    assert s.physical_size_m == (60e-6, 80e-6)
    assert s.info["reader"] == "numpy"


@pytest.mark.parametrize("suffix", [".csv", ".npy"])
def test_csv_and_npy_stay_numpy_only(tmp_path: Path, suffix: str) -> None:
    p = tmp_path / f"h{suffix}"
    if suffix == ".npy":
        np.save(p, ROWS)
    else:
        _write(p, ["Width: 40 um", "Height: 30 um", "Value units: um"], delimiter=",")
    with pytest.raises(SurfaceError, match="plain matrix"):
        read_surface(p)
    s = read_surface(p, physical_size_m=(60e-6, 80e-6), height_unit="um")
    assert s.info["reader"] == "numpy"
    np.testing.assert_allclose(s.heights_m, ROWS * 1e-6, rtol=1e-12, atol=1e-18)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"physical_size_m": (1e-5, 1e-5)}, r"^hdr\.txt stores its physical size; a size can only be given"),
        ({"height_unit": "nm"}, r"^hdr\.txt stores its length unit \(um\); a height unit can only be given"),
    ],
)
def test_user_metadata_for_a_headered_file_is_refused(tmp_path: Path, kwargs: dict[str, object], match: str) -> None:
    p = _write(tmp_path / "hdr.txt", ["Width: 40 um", "Height: 30 um", "Value units: um"])
    with pytest.raises(SurfaceError, match=match) as err:
        read_surface(p, **kwargs)  # type: ignore[arg-type]
    assert "\n" not in str(err.value)


def test_size_without_unit_combines_with_the_user_height_unit(tmp_path: Path) -> None:
    p = _write(tmp_path / "size_only.txt", ["Width: 40 um", "Height: 30 um"])
    with pytest.raises(SurfaceError, match=r"does not store a length unit.*--height-unit"):
        read_surface(p)
    with pytest.raises(SurfaceError, match="stores its physical size"):
        read_surface(p, physical_size_m=(1e-5, 1e-5), height_unit="nm")
    s = read_surface(p, height_unit="nm")
    # the size keeps the file's lateral unit (µm); only the heights take the given unit (nm)
    np.testing.assert_allclose(s.physical_size_m, (40e-6, 30e-6), rtol=1e-12)
    np.testing.assert_allclose(s.heights_m, ROWS.T * 1e-9, rtol=1e-12, atol=1e-21)
    assert s.info["reader"] == "AscReader"
    assert s.info["file_unit"] is None and s.info["height_unit"] == "nm"
    assert s.info["file_size_units"] == ["um", "um"]


def test_unit_without_size_combines_with_the_user_size(tmp_path: Path) -> None:
    p = _write(tmp_path / "unit_only.txt", ["Value units: nm"])
    with pytest.raises(SurfaceError, match=r"does not store its physical size; give it \(command line: --size-um"):
        read_surface(p)
    with pytest.raises(SurfaceError, match="stores its length unit"):
        read_surface(p, physical_size_m=(40e-6, 30e-6), height_unit="um")
    s = read_surface(p, physical_size_m=(40e-6, 30e-6))
    assert s.physical_size_m == pytest.approx((40e-6, 30e-6), rel=1e-12)
    np.testing.assert_allclose(s.heights_m, ROWS.T * 1e-9, rtol=1e-12, atol=1e-21)
    assert s.info["file_unit"] == "nm" and s.info["file_physical_size"] is None


def test_size_in_one_direction_only_is_refused(tmp_path: Path) -> None:
    p = _write(tmp_path / "width_only.txt", ["Width: 40 um", "Value units: um"])
    with pytest.raises(SurfaceError, match="physical size in one direction only"):
        read_surface(p)


def test_cli_reads_a_headered_text_file_without_size(tmp_path: Path) -> None:
    from scipy import ndimage

    rng = np.random.default_rng(1)
    z = ndimage.gaussian_filter(rng.standard_normal((48, 64)), 2.0, mode="wrap")
    z *= 0.3 / z.std()  # Sq 0.3 µm
    p = _write(tmp_path / "rough.txt", ["Channel: Height", "Width: 64 um", "Height: 48 um", "Value units: um"], z)
    res = CliRunner().invoke(app, ["surface", str(p), "--json"])
    assert res.exit_code == 0, res.output
    d = json.loads(res.stdout)
    assert d["grid"] == [64, 48]
    assert d["physical_size_m"] == pytest.approx([64e-6, 48e-6], rel=1e-12)
    assert d["preparation"]["reader"] == "AscReader"
    res = CliRunner().invoke(app, ["surface", str(p), "--size-um", "64:48"])
    assert res.exit_code == 2 and "Traceback" not in res.output
    assert res.stderr.strip().splitlines()[-1].startswith("error: rough.txt stores its physical size")

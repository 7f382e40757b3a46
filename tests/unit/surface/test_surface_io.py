"""Reading height maps: instrument files through SurfaceTopography, plain matrices, errors."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from stochfric.surface.io import (
    DEFAULT_SURFACE_NAME,
    Surface,
    SurfaceError,
    default_surface_path,
    file_sha256,
    read_surface,
    surface_from_array,
)

SHARED = Path(__file__).resolve().parents[4] / "shared" / "data" / "topographies"


def test_default_surface_is_the_shipped_al3d_file() -> None:
    path = default_surface_path()
    assert path.name == DEFAULT_SURFACE_NAME
    assert file_sha256(path).startswith("13a832361afb3489")  # PROVENANCE.md
    notice = path.parent / "NOTICE.md"
    assert notice.is_file()
    text = notice.read_text(encoding="utf-8")
    assert "MIT" in text and DEFAULT_SURFACE_NAME in text


def test_read_default_surface_in_metres() -> None:
    s = read_surface(default_surface_path())
    assert s.nb_grid_pts == (200, 296)
    np.testing.assert_allclose(s.physical_size_m, (8.76054e-05, 1.29655992e-04), rtol=1e-6)
    np.testing.assert_allclose(s.grid_spacing_m, (4.38027e-07, 4.38027e-07), rtol=1e-6)
    assert s.n_undefined_filled == 0
    assert s.info["reader"] == "AL3DReader"
    z = s.heights_m
    assert np.isfinite(z).all()
    # PROVENANCE.md: Sq raw 7.688 µm
    assert np.sqrt(np.mean((z - z.mean()) ** 2)) == pytest.approx(7.688e-6, rel=1e-3)
    assert not z.flags.writeable


def test_plain_matrix_needs_size_and_unit(tmp_path: Path) -> None:
    p = tmp_path / "h.npy"
    np.save(p, np.zeros((8, 9)))
    with pytest.raises(SurfaceError, match="physical size and height unit"):
        read_surface(p)
    with pytest.raises(SurfaceError, match="height unit"):
        read_surface(p, physical_size_m=(1e-3, 1e-3))
    with pytest.raises(SurfaceError, match="physical size"):
        read_surface(p, height_unit="um")


@pytest.mark.parametrize("suffix", [".npy", ".txt", ".csv"])
def test_plain_matrix_layout_and_units(tmp_path: Path, suffix: str) -> None:
    h = np.arange(8 * 9, dtype=float).reshape(8, 9) / 7.0
    p = tmp_path / f"h{suffix}"
    if suffix == ".npy":
        np.save(p, h)
    else:
        np.savetxt(p, h, delimiter="," if suffix == ".csv" else " ")
    s = read_surface(p, physical_size_m=(80e-6, 90e-6), height_unit="um")
    assert s.nb_grid_pts == (8, 9)  # axis 0 is x
    np.testing.assert_allclose(s.heights_m, h * 1e-6, rtol=1e-12)
    assert s.grid_spacing_m == pytest.approx((10e-6, 10e-6))
    assert s.info["sha256"] == file_sha256(p)


def test_undefined_points_refused_or_filled_harmonically(tmp_path: Path) -> None:
    x = np.arange(10.0)
    h = np.add.outer(2.0 * x, 3.0 * np.arange(12.0))  # a plane: harmonic
    h[4, 5] = np.nan
    h[7, 2] = np.nan
    p = tmp_path / "holes.npy"
    np.save(p, h)
    with pytest.raises(SurfaceError, match=r"2 undefined point\(s\).*--fill-undefined"):
        read_surface(p, physical_size_m=(1e-3, 1e-3), height_unit="m")
    s = read_surface(p, physical_size_m=(1e-3, 1e-3), height_unit="m", fill_undefined=True)
    assert s.n_undefined_filled == 2
    # a linear function is harmonic: interpolation reproduces it exactly
    assert s.heights_m[4, 5] == pytest.approx(2 * 4 + 3 * 5, abs=1e-9)
    assert s.heights_m[7, 2] == pytest.approx(2 * 7 + 3 * 2, abs=1e-9)


def test_masked_array_input_is_undefined() -> None:
    h = np.ma.masked_array(np.ones((6, 6)), mask=np.zeros((6, 6), bool))
    h.mask[2, 3] = True
    with pytest.raises(SurfaceError, match="undefined"):
        surface_from_array(h, physical_size_m=(1.0, 1.0))
    s = surface_from_array(h, physical_size_m=(1.0, 1.0), fill_undefined=True)
    assert s.heights_m[2, 3] == pytest.approx(1.0)


def test_all_undefined_is_refused() -> None:
    with pytest.raises(SurfaceError, match="no defined point"):
        surface_from_array(np.full((6, 6), np.nan), physical_size_m=(1.0, 1.0), fill_undefined=True)


def test_unknown_and_corrupt_files(tmp_path: Path) -> None:
    garbage = tmp_path / "noise.xyz1"
    garbage.write_bytes(b"this is not a topography\x00\x01" * 20)
    with pytest.raises(SurfaceError, match="no SurfaceTopography reader"):
        read_surface(garbage)
    truncated = tmp_path / "cut.al3d"
    truncated.write_bytes(default_surface_path().read_bytes()[:3000])
    with pytest.raises(SurfaceError, match=r"cannot read cut\.al3d"):
        read_surface(truncated)
    with pytest.raises(SurfaceError, match="no such file"):
        read_surface(tmp_path / "missing.x3p")
    bad_txt = tmp_path / "words.txt"
    bad_txt.write_text("a b c\nd e f\n")
    with pytest.raises(SurfaceError):
        read_surface(bad_txt, physical_size_m=(1.0, 1.0), height_unit="m")


def test_non_uniform_line_scan_is_refused(tmp_path: Path) -> None:
    x = np.sort(np.random.default_rng(0).uniform(0.0, 1.0, 40))
    p = tmp_path / "profile.xyz"
    np.savetxt(p, np.c_[x, np.sin(x)])
    with pytest.raises(SurfaceError, match="non-uniform line scan"):
        read_surface(p)


def test_unit_override_of_a_file_with_unit_is_refused() -> None:
    with pytest.raises(SurfaceError, match="stores its length unit"):
        read_surface(default_surface_path(), height_unit="um")
    with pytest.raises(SurfaceError, match="stores its physical size"):
        read_surface(default_surface_path(), physical_size_m=(1e-3, 1e-3))


def test_unknown_height_unit(tmp_path: Path) -> None:
    p = tmp_path / "h.npy"
    np.save(p, np.zeros((6, 6)))
    with pytest.raises(SurfaceError, match="unknown length unit"):
        read_surface(p, physical_size_m=(1.0, 1.0), height_unit="furlong")


@pytest.mark.parametrize(
    ("heights", "size", "match"),
    [
        (np.zeros(5), (1.0, 1.0), "2-D"),
        (np.array([[0.0, np.nan], [0.0, 0.0]]), (1.0, 1.0), "NaN"),
        (np.zeros((5, 5)), (1.0, -1.0), "physical size in y"),
        (np.zeros((5, 5)), (1.0,), "two lengths"),
    ],
)
def test_surface_validation(heights: np.ndarray, size: tuple[float, ...], match: str) -> None:
    with pytest.raises(SurfaceError, match=match):
        Surface(heights_m=heights, physical_size_m=size)  # type: ignore[arg-type]


@pytest.mark.skipif(not (SHARED / "opd-1.opd").is_file(), reason="shared topographies absent")
def test_instrument_file_with_undefined_points() -> None:
    with pytest.raises(SurfaceError, match=r"116 undefined point\(s\)"):
        read_surface(SHARED / "opd-1.opd")
    s = read_surface(SHARED / "opd-1.opd", fill_undefined=True)
    assert s.n_undefined_filled == 116
    assert np.isfinite(s.heights_m).all()
    assert s.nb_grid_pts == (640, 480)

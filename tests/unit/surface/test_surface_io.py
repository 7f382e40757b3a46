"""Reading height maps: instrument files through SurfaceTopography, plain matrices, errors."""

from __future__ import annotations

import os
import zipfile
from pathlib import Path

import numpy as np
import pytest

from stochfric.surface.io import (
    DEFAULT_SURFACE_NAME,
    SPIKE_SQ,
    Surface,
    SurfaceError,
    default_surface_path,
    file_sha256,
    plausibility_warnings,
    read_surface,
    surface_from_array,
    verify_checksums,
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


# ---------------------------------------------------------------- integrity (issue 11)

ALL_SHARED = ["al3d-1.al3d", "frt-1.frt", "mnt-1.mnt", "opd-1.opd", "plu-1.plu", "sur-2.sur", "x3p-2.x3p"]


def _shared(name: str) -> Path:
    path = SHARED / name
    if not path.is_file():
        if os.environ.get("CI"):
            pytest.fail(f"{path} is missing (CI is set: the shared instrument files must be present)")
        pytest.skip(f"{path} not available")
    return path


def _detrended_sq(z: np.ndarray) -> float:
    nx, ny = z.shape
    ii, jj = np.meshgrid(np.arange(nx), np.arange(ny), indexing="ij")
    a = np.stack([np.ones(z.size), ii.ravel(), jj.ravel()], axis=1)
    coef, *_ = np.linalg.lstsq(a, z.ravel(), rcond=None)
    return float(np.std(z.ravel() - a @ coef))


def _flip(src: Path, dst: Path) -> Path:
    """Invert 4 consecutive bytes at three places in the second half of the file."""
    data = bytearray(src.read_bytes())
    n = len(data)
    for start in (n // 2, n // 2 + 40_001, (3 * n) // 4):
        for k in range(4):
            data[start + k] ^= 0xFF
    dst.write_bytes(bytes(data))
    return dst


@pytest.mark.parametrize("name", ALL_SHARED)
def test_no_real_shared_file_trips_the_plausibility_check(name: str) -> None:
    s = read_surface(_shared(name), fill_undefined=True)
    assert s.info["warnings"] == []
    # margin: the largest excess over the median map's range stays well below SPIKE_SQ
    assert plausibility_warnings(s.heights_m, spike_sq=0.9 * SPIKE_SQ) == []


@pytest.mark.parametrize(("name", "sq_nm"), [("plu-1.plu", 18.28), ("sur-2.sur", 17.29)])
def test_flipped_bytes_are_reported_and_name_the_file(name: str, sq_nm: float, tmp_path: Path) -> None:
    good = read_surface(_shared(name), fill_undefined=True)
    assert _detrended_sq(np.asarray(good.heights_m)) == pytest.approx(sq_nm * 1e-9, rel=1e-3)  # PROVENANCE.md
    bad_path = _flip(_shared(name), tmp_path / f"corrupt-{name}")
    bad = read_surface(bad_path, fill_undefined=True)
    assert _detrended_sq(np.asarray(bad.heights_m)) > 3 * sq_nm * 1e-9  # the corruption matters
    (w,) = bad.info["warnings"]
    assert w["code"] == "implausible-spike"
    assert f"corrupt-{name}" in w["message"] and w["worst_excess_sq"] > SPIKE_SQ


def test_spike_rule_on_a_synthetic_surface() -> None:
    rng = np.random.default_rng(3)
    z = rng.normal(size=(64, 64)) * 1e-7  # Sq = 0.1 µm
    assert plausibility_warnings(z) == []
    z[20, 30] = 40e-7  # 40 Sq: beyond the median map's range (about ±4 Sq) by > 20 Sq
    (w,) = plausibility_warnings(z, name="syn")
    assert w["count"] == 1 and w["worst_index"] == [20, 30] and w["message"].startswith("syn: ")
    z[20, 30] = 15e-7  # 15 Sq: within 20 Sq of the range
    assert plausibility_warnings(z) == []
    # a 3x3 block is a feature, not an isolated spike: the median map contains it
    z[10:13, 10:13] = 60e-7
    assert plausibility_warnings(z) == []


def test_x3p_checksums_are_verified(tmp_path: Path) -> None:
    src = _shared("x3p-2.x3p")
    assert verify_checksums(src) == "zip CRC-32, main.xml MD5, point-data MD5"
    assert verify_checksums(default_surface_path()) == "none"
    # 1) a flipped byte inside the compressed data: the zip CRC (or inflate) fails
    bad = _flip(src, tmp_path / "flipped.x3p")
    with pytest.raises(SurfaceError, match=r"flipped\.x3p is corrupt"):
        read_surface(bad)
    # 2) a consistent zip whose point data no longer match the MD5 recorded in main.xml
    repacked = tmp_path / "md5.x3p"
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(repacked, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "bindata/data.bin":
                data = data[:100] + bytes([data[100] ^ 0x40]) + data[101:]
            zout.writestr(item, data)
    with pytest.raises(SurfaceError, match=r"md5\.x3p is corrupt: the MD5 of its point data"):
        read_surface(repacked)
    # 3) main.xml edited: md5checksum.hex no longer matches
    edited = tmp_path / "xml.x3p"
    with zipfile.ZipFile(src) as zin, zipfile.ZipFile(edited, "w", zipfile.ZIP_DEFLATED) as zout:
        for item in zin.infolist():
            data = zin.read(item.filename)
            if item.filename == "main.xml":
                data = data.replace(b"</p:ISO5436_2>", b"<!-- edited --></p:ISO5436_2>")
            zout.writestr(item, data)
    with pytest.raises(SurfaceError, match=r"xml\.x3p is corrupt: the MD5 of main.xml"):
        read_surface(edited)

"""Lateral-scale plausibility and the embossed-relief rule (issue 29, item 7; docs/surface_contact.md,
"Preparation", "Lateral scale and embossed relief"): a stated size no instrument measures is refused with that
reason, a pixel size implausibly large for the heights is warned about, a coin is not a rough surface, while
rough maps - stationary, strongly non-Gaussian, with scratches or particles, and the six rough shared files -
pass with the statistic far from its limit."""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage

from stochfric.surface import plausibility as pl
from stochfric.surface import prepare_checks as pc
from stochfric.surface.io import Surface, SurfaceError, read_surface
from stochfric.surface.preprocess import Preparation, preparation_report, prepare_with_report


def _self_affine(n: int, hurst: float = 0.8, rolloff: float = 0.03, seed: int = 0) -> np.ndarray:
    """Isotropic self-affine Gaussian field (unit Sq), roll-off below ``rolloff`` × the sampling frequency."""
    rng = np.random.default_rng(seed)
    q = np.hypot(np.fft.fftfreq(n)[:, None], np.fft.fftfreq(n)[None, :])
    q[0, 0] = 1.0
    amp = np.maximum(q, rolloff) ** (-(1.0 + hurst))
    amp[0, 0] = 0.0
    z = np.fft.ifft2(amp * np.exp(2j * np.pi * rng.random((n, n)))).real
    return z / z.std()


def _gauss(n: int, corr: float, seed: int) -> np.ndarray:
    z = ndimage.gaussian_filter(np.random.default_rng(seed).normal(size=(n, n)), corr, mode="wrap")
    return z / z.std()


def _surface(h: np.ndarray, side_m: float, info: dict[str, object] | None = None) -> Surface:
    return Surface(heights_m=h, physical_size_m=(side_m, side_m), info=dict(info or {}))


def _afm(n: int = 512) -> np.ndarray:
    """An AFM-like rough map: Sq = 5 nm (shown at 10 µm: pixel 19.5 nm)."""
    return 5e-9 * _self_affine(n, 0.8, 0.02, seed=4)


def _coin(kind: str, n: int = 512, seed: int = 0) -> tuple[np.ndarray, float]:
    """A 20 mm field with a coin's relief, 30 µm high, on a flat field with 0.2 µm Gaussian roughness:
    ``"letters"``: rim, inner ring, letter-like bars and a bar-built numeral (flat tops, steep edges);
    ``"portrait"``: rim and a smooth head-like relief (sum of Gaussian bumps, 60 µm high)."""
    size = 20e-3
    x = (np.arange(n) - n / 2) * size / n
    xx, yy = np.meshgrid(x, x, indexing="ij")
    r = np.hypot(xx, yy)
    rr = 0.4 * size
    relief = ((r > 0.92 * rr) & (r < rr)).astype(float)
    if kind == "letters":
        relief[(r > 0.80 * rr) & (r < 0.83 * rr)] = 1.0
        w = max(n // 100, 2)
        for k in range(6):  # letters: vertical strokes and cross bars
            j0 = int(0.32 * n) + k * 7 * w
            relief[int(0.35 * n) : int(0.35 * n) + 7 * w, j0 : j0 + w] = 1.0
            relief[int(0.35 * n) : int(0.35 * n) + w, j0 : j0 + 4 * w] = 1.0
            relief[int(0.35 * n) + 3 * w : int(0.35 * n) + 4 * w, j0 : j0 + 3 * w] = 1.0
        relief[int(0.55 * n) : int(0.55 * n) + 9 * w, int(0.45 * n) : int(0.45 * n) + 2 * w] = 1.0  # a "1"
        relief = 30e-6 * ndimage.gaussian_filter(relief, 1.0)
    else:
        def bump(cx: float, cy: float, sx: float, sy: float, a: float) -> np.ndarray:
            return a * np.exp(-0.5 * (((xx - cx * rr) / (sx * rr)) ** 2 + ((yy - cy * rr) / (sy * rr)) ** 2))

        head = (bump(0, 0, 0.35, 0.28, 1.0) + bump(-0.05, 0.28, 0.08, 0.06, 0.5) + bump(-0.25, -0.1, 0.18, 0.25, 0.6)
                + bump(0.35, 0, 0.1, 0.18, 0.4))  # fmt: skip
        head = np.where(r < 0.8 * rr, head, 0.0)
        relief = np.maximum(30e-6 * ndimage.gaussian_filter(relief, 1.0), 60e-6 * head / head.max())
    return relief + 0.2e-6 * _gauss(n, 1.5, seed), size


# ----------------------------------------------------------------------------- lateral scale


def test_a_512_scan_stated_as_160_m_is_refused_for_its_lateral_size_not_blamed_on_the_material() -> None:
    with pytest.raises(SurfaceError) as err:
        prepare_with_report(_surface(_afm(), 160.0))
    msg = str(err.value)
    assert "the stated size 160 m × 160 m (pixel size 312.5 mm × 312.5 mm) is not that of a surface measurement" in msg
    assert "lateral unit or size metadata is probably wrong" in msg and "--size-um" in msg
    assert "not a rough surface" not in msg and "material" not in msg
    # the same heights at the size an AFM scans: a rough surface, no plausibility warning
    fine, _, rep = prepare_with_report(_surface(_afm(), 10e-6))
    lateral = rep.rough_surface["lateral_scale"]
    assert lateral["plausible"] and rep.rough_surface["rough"]
    assert lateral["pixel_size_m"] == pytest.approx([10e-6 / 512] * 2)
    assert 1e-3 < lateral["rms_gradient"] < 1  # the range of measured rough surfaces
    assert not [w for w in fine.info["warnings"] if w["code"].startswith("implausible")]
    assert rep.rough_surface["relief"]["tile_sq_ratio"] < pl.RELIEF_RATIO / 4


def test_bypassed_lateral_refusal_is_a_warning_that_names_pixel_size_slope_and_mu() -> None:
    fine, _, rep = prepare_with_report(_surface(_afm(), 160.0), Preparation(rough_check=False))
    codes = [w["code"] for w in fine.info["warnings"]]
    assert codes[:2] == ["implausible-lateral-size", "implausible-pixel-size"]
    sdq = rep.rough_surface["lateral_scale"]["rms_gradient"]
    at_10um = preparation_report(_surface(_afm(), 10e-6)).rough_surface["lateral_scale"]["rms_gradient"]
    assert sdq == pytest.approx(at_10um * 10e-6 / 160.0, rel=1e-9)  # Sdq scales with 1 / pixel size
    pixel = fine.info["warnings"][1]
    assert pixel["rms_gradient"] == sdq and pixel["pixel_size_m"] == pytest.approx([160.0 / 512] * 2)
    assert "pixel size 312.5 mm × 312.5 mm" in pixel["message"] and f"Sdq = {sdq:.3g}" in pixel["message"]
    assert "mu scale with the pixel size" in pixel["message"] and "blaming the material" in pixel["message"]
    assert json.loads(json.dumps(rep.to_dict(), allow_nan=False)) == rep.to_dict()


def test_a_lateral_unit_read_1000_times_too_large_is_warned_or_refused_by_the_instrument() -> None:
    h = _afm(256)
    fine, _, rep = prepare_with_report(_surface(h, 160e-3))  # µm read as mm: no instrument limit is passed
    (w,) = [w for w in fine.info["warnings"] if w["code"] == "implausible-pixel-size"]
    assert rep.rough_surface["lateral_scale"]["plausible"] and w["rms_gradient"] < pl.SLOPE_MIN
    # the same map from a scanning-probe file format: an AFM scanner cannot cover 160 mm
    with pytest.raises(SurfaceError, match=r"not that of a scanning-probe map: .*\(DIReader\).*150 µm"):
        prepare_with_report(_surface(h, 160e-3, {"reader": "DIReader"}))
    # ... but 100 µm is a plausible AFM field, and a profiler's 160 mm map with µm roughness is not warned about
    assert preparation_report(_surface(h, 100e-6, {"reader": "DIReader"})).rough_surface["lateral_scale"]["plausible"]
    fine, _, _ = prepare_with_report(_surface(1e-6 * _self_affine(256, seed=2), 160e-3))
    assert not [w for w in fine.info["warnings"] if w["code"].startswith("implausible")]


def test_a_matrix_given_a_size_in_the_wrong_unit_is_pointed_at_size_um(tmp_path: Path) -> None:
    path = tmp_path / "afm.npy"
    np.save(path, _afm(256))
    matrix = read_surface(path, physical_size_m=(160.0, 160.0), height_unit="m")  # 160e6 µm for 160 µm
    with pytest.raises(SurfaceError, match=r"size given for the matrix is probably wrong: --size-um takes LX:LY in"):
        prepare_with_report(matrix)


def test_a_field_below_the_atomic_scale_is_refused() -> None:
    with pytest.raises(SurfaceError, match=r"stated size 0.5 nm × 0.5 nm .* not that of a surface measurement"):
        prepare_with_report(_surface(1e-11 * _self_affine(64, seed=1), 0.5e-9))


# ----------------------------------------------------------------------------- embossed relief


@pytest.mark.parametrize("kind", ["letters", "portrait"])
def test_a_coin_is_refused_as_an_embossed_relief_with_its_statistic(kind: str) -> None:
    h, size = _coin(kind)
    with pytest.raises(SurfaceError, match=r"not a rough surface \(embossed relief or designed structure") as err:
        prepare_with_report(_surface(h, size))
    rep = preparation_report(_surface(h, size), Preparation(rough_check=False))
    relief = rep.rough_surface["relief"]
    assert relief["relief"] and relief["checked"] and rep.rough_surface["rough"] is False
    assert relief["tile_sq_ratio"] > 3 * pl.RELIEF_RATIO  # relief height / micro-roughness, far from the limit
    assert f"is {relief['tile_sq_ratio']:.3g} times" in str(err.value) and "256 tiles of 32x32 points" in str(err.value)
    assert relief["tile_sq_low_m"] == pytest.approx(0.2e-6, rel=0.5)  # the flat field's micro-roughness
    assert rep.rough_surface["lateral_scale"]["plausible"]  # a 20 mm field is a plausible measurement


def test_the_relief_reason_comes_first_and_smaller_grids_are_caught_too() -> None:
    h, size = _coin("portrait")
    rep = preparation_report(_surface(h, size), Preparation(rough_check=False))
    assert rep.rough_surface["reason"].startswith("embossed relief")
    for n in (128, 256):
        small, _ = _coin("letters", n=n)
        assert pl.relief_verdict(small)["tile_sq_ratio"] > 3 * pl.RELIEF_RATIO


def _rough_maps() -> dict[str, np.ndarray]:
    maps: dict[str, np.ndarray] = {}
    for n in (128, 256, 512):
        z, g = _self_affine(n, 0.8, 0.03, seed=n), _gauss(n, 3.0, seed=n)
        maps[f"gaussian corr 4 px, {n}"] = _gauss(n, 4.0, seed=n + 1)
        maps[f"self-affine H 1 no roll-off, {n}"] = _self_affine(n, 1.0, 0.0, seed=n + 2)
        maps[f"lognormal (skewness ~4), {n}"] = np.exp(0.77 * z)
        maps[f"plateau-honed, {n}"] = np.minimum(0.2 * _gauss(n, 1.5, n + 3), 2.0 * (_gauss(n, 6.0, n + 4) + 1.2))
        maps[f"truncated (worn), {n}"] = np.minimum(z, 0.0) + 0.05 * _gauss(n, 1.0, n + 5)
        scratched = z.copy()
        rows = np.arange(n)
        for k in range(3):  # three deep scratches across the map
            cols = (rows * (0.3 + 0.2 * k) + n * 0.2 * k).astype(int) % n
            scratched[rows, cols] -= 6.0
            scratched[rows, (cols + 1) % n] -= 6.0
        maps[f"three scratches, {n}"] = scratched
        xx, yy = np.ogrid[:n, :n]
        centres = np.random.default_rng(n).integers(0, n, size=(6, 2))
        maps[f"six particles, {n}"] = g + sum(10 * np.exp(-((xx - i) ** 2 + (yy - j) ** 2) / (2 * (n / 100) ** 2))
                                              for i, j in centres)  # fmt: skip
    return maps


def test_stationary_non_gaussian_scratched_and_particle_rough_maps_pass_the_relief_rule() -> None:
    ratios = {}
    for name, z in _rough_maps().items():
        relief = pl.relief_verdict(pc.polynomial_residual(z, pc.auto_degree(z)[0]))  # the form step's residual
        assert relief["checked"] and not relief["relief"] and relief["reason"] is None, name
        ratios[name] = relief["tile_sq_ratio"]
    # through the preparation: the same statistic, and the map is a rough surface
    z = _rough_maps()["lognormal (skewness ~4), 256"]
    rep = preparation_report(_surface(1e-6 * z, 256e-6))
    assert rep.rough_surface["rough"] and rep.rough_surface["relief"]["tile_sq_ratio"] == pytest.approx(
        ratios["lognormal (skewness ~4), 256"], rel=0.02)  # outliers replaced first
    assert max(ratios.values()) < 0.6 * pl.RELIEF_RATIO, ratios
    assert min(ratios.values()) > 1.0  # the statistic is measured, not a constant
    assert ratios["gaussian corr 4 px, 512"] < 2.0  # a fine stationary field: tiles alike


def test_tile_sq_and_the_quantisation_and_fill_guards() -> None:
    z = np.zeros((64, 64))
    z[:32] = 1.0  # two flat halves: every tile flat (plane removed), except none straddles the edge
    assert pl.tile_sq(z, 16) == pytest.approx(np.zeros((4, 4)))
    h = 1e-6 * _gauss(128, 2.0, 1)
    flat = h.copy()
    flat[:40] = 0.0  # a third of the map exactly flat (filled or saturated)
    exact = pl.relief_verdict(flat)
    assert exact["relief"] and exact["tile_sq_ratio"] is None and "is infinite times" in exact["reason"]
    assert not pl.relief_verdict(flat, undefined_fraction=0.35)["relief"]  # the filled part is discounted
    quantised = pl.relief_verdict(flat, quantum_m=1e-6)  # flat within one quantum: q/√12 is the floor
    assert quantised["tile_sq_low_m"] == pytest.approx(1e-6 / math.sqrt(12)) and not quantised["relief"]
    assert pl.relief_verdict(h[:48, :48])["checked"] is False  # fewer than 4 tiles along a side
    assert pl.rms_gradient(np.outer(np.arange(8.0), np.ones(8)), (0.5, 1.0)) == pytest.approx(2.0)


# ----------------------------------------------------------------------------- the shared files

#: name → the relief statistic (90 % / 10 % quantile of the tile Sq) and Sdq, docs/surface_contact.md
SHARED = {
    "al3d-1.al3d": (3.10, 0.0897), "x3p-2.x3p": (2.47, 0.0621), "opd-1.opd": (1.56, 0.0181),
    "plu-1.plu": (1.42, 0.00445), "sur-2.sur": (3.17, 0.00136), "mnt-1.mnt": (3.37, 0.00344),
}  # fmt: skip


@pytest.mark.parametrize("name", sorted(SHARED))
def test_the_rough_shared_files_pass_with_the_documented_margin(name: str, shared_file: Callable[[str], Path]) -> None:
    fine, _, rep = prepare_with_report(read_surface(shared_file(name), fill_undefined=True))
    ratio, sdq = SHARED[name]
    relief, lateral = rep.rough_surface["relief"], rep.rough_surface["lateral_scale"]
    assert rep.rough_surface["rough"] and relief["checked"] and lateral["plausible"]
    assert relief["tile_sq_ratio"] == pytest.approx(ratio, abs=0.01)
    assert relief["tile_sq_ratio"] < pl.RELIEF_RATIO / 2.5  # the margin stated in the docs
    assert lateral["rms_gradient"] == pytest.approx(sdq, rel=0.01)
    assert not [w for w in fine.info["warnings"] if w["code"].startswith("implausible")]
    assert not math.isnan(relief["tile_sq_low_m"])

"""Metrological preparation steps (ISO 25178-2 / 16610): form rule, L-filter, outliers, ties, undefined
points, rough-surface check; on synthetic maps with known answers."""

from __future__ import annotations

import dataclasses
import json
import math

import numpy as np
import pytest

from stochfric.surface import prepare_checks as pc
from stochfric.surface.io import Surface, SurfaceError, surface_from_array
from stochfric.surface.preprocess import (
    STEP_ORDER,
    Preparation,
    PreparationReport,
    detrend,
    preparation_report,
    prepare,
    prepare_with_report,
)


def _rough(nx: int = 128, ny: int = 96, seed: int = 0, corr: float = 2.0) -> np.ndarray:
    from scipy import ndimage

    z = ndimage.gaussian_filter(np.random.default_rng(seed).normal(size=(nx, ny)), corr, mode="wrap")
    return z / z.std() * 1e-6


def _surface(h: np.ndarray) -> Surface:
    return Surface(heights_m=h, physical_size_m=(h.shape[0] * 1e-6, h.shape[1] * 1e-6))


def test_poly3_removes_a_cubic_and_auto_picks_the_form() -> None:
    h = _rough()
    x = np.linspace(-1, 1, h.shape[0])[:, None]
    y = np.linspace(-1, 1, h.shape[1])[None, :]
    cubic = 5e-6 * (x**3 + 0.5 * x * y * y + 0.3 * y**3)
    np.testing.assert_allclose(detrend(h + cubic, "poly3"), detrend(h, "poly3"), atol=1e-15)
    assert detrend(h, "poly1").shape == h.shape  # alias of plane
    degree, sq = pc.auto_degree(h + cubic)
    assert degree == 3 and sq[0] > sq[1] > sq[2]
    assert pc.auto_degree(h)[0] == 1  # a rough field without form keeps the plane
    bowl = 4e-6 * (x * x + y * y)
    assert pc.auto_degree(h + bowl)[0] == 2
    report = preparation_report(_surface(h + bowl))
    assert report.form["applied"] == "quadratic" and len(report.form["sq_by_degree_m"]) == 3


def test_gaussian_lfilter_transmission_and_robustness() -> None:
    n, dx, lc = 512, 1e-6, 64e-6
    x = np.arange(n) * dx
    for wavelength, expected in ((lc, 0.5), (4 * lc, 1 - 0.5 ** (1 / 16)), (lc / 4, 1.0)):
        z = np.sin(2 * np.pi * x / wavelength)[:, None] * np.ones((1, 64))
        rough, _ = pc.gaussian_lfilter(z, (dx, dx), lc)
        amp = np.abs(rough[n // 4 : 3 * n // 4, 32]).max()  # roughness = 1 − Gaussian transmission
        assert amp == pytest.approx(1 - (1 - expected), abs=0.03) if expected < 1 else amp == pytest.approx(1, abs=0.03)
    z = np.zeros((128, 64))
    z[64, 32] = 100.0  # one huge spike: the robust mean line does not follow it
    _, rec = pc.gaussian_lfilter(z + _rough(128, 64) * 1e6, (dx, dx), 20e-6, robust=True)
    assert rec["robust_iterations"] >= 1
    fine, _ = prepare(_surface(_rough()), Preparation(detrend="robust-gaussian", cutoff_m=40e-6))
    assert fine.info["preparation"]["form"]["applied"] == "robust-gaussian"


def test_outliers_found_filled_and_reported_but_legit_roughness_kept() -> None:
    h = _rough(seed=3)
    assert pc.outlier_mask(h)[0].sum() == 0
    spiky = h.copy()
    spots = [(10, 10), (50, 60), (100, 20), (70, 71), (71, 71)]
    for k, (i, j) in enumerate(spots):
        spiky[i, j] += (30 if k % 2 else -40) * 1e-6
    fine, _, rep = prepare_with_report(_surface(spiky))
    out = rep.outliers
    assert out["count"] == len(spots) and sorted(map(tuple, out["positions"])) == sorted(spots)
    assert out["fraction"] == pytest.approx(len(spots) / h.size)
    assert np.abs(fine.heights_m).max() < 6e-6
    assert "outliers-replaced" in {w["code"] for w in fine.info["warnings"]}
    off = prepare_with_report(_surface(spiky), Preparation(outliers=False))[2]
    assert off.outliers["count"] == 0


def test_quantised_heights_warn_and_dither() -> None:
    q = 0.25e-6
    h = np.round(_rough(seed=5) / q) * q
    fine, _, rep = prepare_with_report(_surface(h))
    assert rep.quantisation["tie_fraction"] > pc.TIE_WARN
    assert rep.quantisation["quantum_m"] == pytest.approx(q)
    assert "quantised-heights" in {w["code"] for w in fine.info["warnings"]}
    fine2, _, rep2 = prepare_with_report(_surface(h), Preparation(quantised="dither"))
    assert rep2.quantisation["applied"] is True
    assert "quantised-heights" not in {w["code"] for w in fine2.info["warnings"]}
    d = fine2.heights_m
    assert np.count_nonzero(np.diff(d, axis=0) == 0) == 0
    assert np.abs(d - fine.heights_m).max() <= q / 2 + 1e-12
    assert not prepare_with_report(_surface(_rough()))[2].quantisation["quantised"]


def test_undefined_limit_and_part_outline() -> None:
    h = _rough(seed=7)
    holes = h.copy()
    holes[40:45, 40:47] = np.nan  # 35 interior points
    s = surface_from_array(holes, physical_size_m=(128e-6, 96e-6), fill_undefined=True)
    rep = preparation_report(s)
    assert rep.undefined["count"] == 35 and rep.undefined["border_fraction"] == 0.0
    with pytest.raises(SurfaceError, match="undefined points, more than the limit"):
        prepare(s, Preparation(max_undefined=0.001))
    frame = h.copy()
    frame[:15, :] = np.nan  # a surround along a border: 11.7 %
    s = surface_from_array(frame, physical_size_m=(128e-6, 96e-6), fill_undefined=True)
    with pytest.raises(SurfaceError, match=r"not a rough surface .part outline"):  # the basic reason first
        prepare(s)
    with pytest.raises(SurfaceError, match="undefined points, more than the limit"):
        prepare(s, Preparation(rough_check=False))
    with pytest.raises(SurfaceError, match="part outline"):
        prepare(s, Preparation(max_undefined=0.5))
    assert preparation_report(s, Preparation(max_undefined=0.5, rough_check=False)).rough_surface["rough"] is False


def test_step_is_refused_but_skewed_roughness_is_not() -> None:
    h = _rough(seed=9)
    step = h.copy()
    step[40:90] += 20e-6  # a raised band (a part on a substrate); an edge step is future work
    with pytest.raises(SurfaceError, match=r"not a rough surface .*step or two-level"):
        prepare(_surface(step), Preparation(detrend="plane"))
    skewed = np.exp(h / h.std())  # lognormal heights, skewness ≈ 6
    assert preparation_report(_surface(skewed * 1e-6)).rough_surface["rough"]
    rng = np.random.default_rng(1)
    for z in (rng.normal(size=200_000), rng.uniform(size=200_000), rng.exponential(size=200_000)):
        assert pc.otsu_split(z)["separation"] < pc.STEP_SEPARATION


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"detrend": "gaussian"}, "needs the nesting index"),
        ({"detrend": "plane", "cutoff_m": 1e-5}, "applies only to"),
        ({"detrend": "gaussian", "cutoff_m": 0.0}, "finite number > 0"),
        ({"detrend": "gaussian", "cutoff_m": math.nan}, "finite number > 0"),
        ({"detrend": "gaussian", "cutoff_m": math.inf}, "finite number > 0"),
        ({"outlier_k": 2.0}, ">= 3"),
        ({"outlier_k": -1.0}, "> 0"),
        ({"outlier_sq": math.inf}, "> 0"),
        ({"max_undefined": 0.0}, "> 0"),
        ({"max_undefined": 1.5}, "in 0"),
        ({"quantised": "smooth"}, "warn, dither"),
        ({"outliers": "yes"}, "True or False"),
    ],
)
def test_new_fields_are_validated(kwargs: dict[str, object], match: str) -> None:
    with pytest.raises(SurfaceError, match=match):
        Preparation(**kwargs)  # type: ignore[arg-type]


def test_cutoff_range_is_checked_against_the_grid() -> None:
    with pytest.raises(SurfaceError, match="out of range"):
        prepare(_surface(_rough()), Preparation(detrend="gaussian", cutoff_m=1e-6))
    with pytest.raises(SurfaceError, match="out of range"):
        prepare(_surface(_rough()), Preparation(detrend="gaussian", cutoff_m=1.0))


def test_to_dict_round_trips() -> None:
    p = Preparation(detrend="poly3", outliers=False, max_undefined=0.2)
    assert Preparation(**p.to_dict()) == p
    assert set(Preparation().to_dict()) == {"detrend", "median_radius", "step"}
    assert set(p.settings()) >= {"cutoff_m", "outliers", "outlier_k", "quantised", "max_undefined", "rough_check"}


def test_the_report_is_a_frozen_record_whose_dict_is_the_json() -> None:
    fine, coarse, rep = prepare_with_report(_surface(_rough(seed=11)), Preparation(median_radius=1, step=2))
    d = rep.to_dict()
    assert list(d) == ["order", "settings", "undefined", "quantisation", "outliers", "form", "rough_surface",
                       "median_radius", "step"]
    assert d["order"] == list(STEP_ORDER) and (d["median_radius"], d["step"]) == (1, 2)
    assert d["settings"] == Preparation(median_radius=1, step=2).settings()
    assert fine.info["preparation"] == d and coarse.info["preparation"] == d
    assert json.loads(json.dumps(d)) == d
    assert PreparationReport.from_dict(d).to_dict() == d
    d["form"]["applied"] = "changed"  # the dict is a copy
    assert rep.form["applied"] == "plane"
    with pytest.raises(dataclasses.FrozenInstanceError):
        rep.step = 3  # type: ignore[misc]
    assert "\n" not in repr(rep) and "step 2" in repr(rep)

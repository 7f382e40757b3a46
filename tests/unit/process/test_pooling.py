"""Pooling several scans as one ensemble (issue 29, item 5): the between-scan test, how many scans,
the pixel-size tolerance and the summits a scan must keep.

Two crops of one stationary map pass the random-effects test, two unrelated maps are refused, the
false-alarm rate on independent maps of one generator stays within what α allows, and on the real
files two halves of one map pass while x3p-2 against opd-1 is refused.  Fixed seeds throughout.
"""

from __future__ import annotations

import functools
import json
import math
from pathlib import Path

import numpy as np
import pytest
from scipy import ndimage
from scipy import stats as sps

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.errors import AnalysisError
from stochfric.process.pooling import (
    BETWEEN_SCAN_ALPHA,
    MIN_SUMMITS_PER_SCAN,
    POOL_PIXEL_RTOL,
    BetweenScanTest,
    between_scan_test,
    check_resampling_keeps_summits,
    detectable_between_scan_sd,
    measured_window_mu,
    on_common_pixel_size,
    pixel_sizes_agree,
    require_summits_for_pooling,
    scans_needed,
    sigma_mu_relative_se,
)
from stochfric.surface.grid import crop_surface, resample_surface
from stochfric.surface.io import Surface, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of

MAT = get_material("brake-pad")
SHARED = Path(__file__).resolve().parents[4] / "shared" / "data" / "topographies"


def _field(shape: tuple[int, int], corr: float, seed: int = 0, rms: float = 1e-6) -> Surface:
    z = ndimage.gaussian_filter(np.random.default_rng(seed).standard_normal(shape), corr, mode="wrap")
    return Surface(heights_m=rms * z / z.std(), physical_size_m=(shape[0] * 1e-6, shape[1] * 1e-6))


def _part(surface: Surface, rows: slice, cols: slice) -> Surface:
    """The sub-grid ``[rows, cols]`` of ``surface`` at its own pixel size."""
    h = np.array(surface.heights_m[rows, cols])
    dx, dy = surface.grid_spacing_m
    return Surface(heights_m=h, physical_size_m=(h.shape[0] * dx, h.shape[1] * dy), source=surface.source)


def _halves(surface: Surface, axis: int = 0) -> list[Surface]:
    nx, ny = surface.nb_grid_pts
    if axis == 0:
        return [_part(surface, slice(0, nx // 2), slice(None)), _part(surface, slice(nx // 2, nx), slice(None))]
    return [_part(surface, slice(None), slice(0, ny // 2)), _part(surface, slice(None), slice(ny // 2, ny))]


def _test(scans: list[Surface]) -> BetweenScanTest:
    """The between-scan test as the analysis would run it: 6 approaches by the default rule on the scan
    with the fewest summits, windows by the window check's rule."""
    fewest = min((summits_of(s) for s in scans), key=lambda s: s.count)
    u = default_approach_m(fewest, num=6)
    return between_scan_test(measured_window_mu(scans, MAT, u), approach_m=u)


# --------------------------------------------------------------------------------------------------
# The statistics against their definitions
# --------------------------------------------------------------------------------------------------


def test_anova_matches_scipy_with_unequal_groups_and_undefined_windows() -> None:
    rng = np.random.default_rng(3)
    a = rng.normal(0.5, 0.1, size=(12, 3))
    b = rng.normal(0.55, 0.1, size=(9, 3))
    c = rng.normal(0.5, 0.2, size=(15, 3))
    b[2, 1] = np.nan  # a window with undefined μ at approach 1 is dropped there
    t = between_scan_test([a, b, c])
    for j in range(3):
        groups = [g[np.isfinite(g[:, j]), j] for g in (a, b, c)]
        f, p = sps.f_oneway(*groups)
        assert t.f_statistic[j] == pytest.approx(f, rel=1e-10)
        assert t.p_value[j] == pytest.approx(p, rel=1e-8)
        bf = sps.levene(*groups, center="median")
        assert t.scatter_p_value[j] == pytest.approx(bf.pvalue, rel=1e-8)
        n = np.array([g.size for g in groups], dtype=float)
        n0 = (n.sum() - (n**2).sum() / n.sum()) / 2
        msw = sum(((g - g.mean()) ** 2).sum() for g in groups) / (n.sum() - 3)
        msb = f * msw
        assert t.sigma_w2[j] == pytest.approx(msw, rel=1e-10)
        assert t.sigma_b2[j] == pytest.approx(max((msb - msw) / n0, 0.0), rel=1e-10, abs=1e-15)
        assert 0.0 <= t.icc[j] <= 1.0
    assert t.df_within[1] == t.df_within[0] - 1
    assert t.windows == (12, 9, 15)
    json.dumps(t.to_dict(), allow_nan=False)
    assert "Holm" in t.rule and "Brown-Forsythe" in t.rule


def test_variance_component_is_recovered_and_holm_names_the_failing_approaches() -> None:
    rng = np.random.default_rng(11)
    scans = 40
    # approach 0: scan means scatter with σ_b = 0.1 around σ_w = 0.1; approach 1: no between-scan component
    offsets = rng.normal(0.0, 0.1, size=scans)
    data = [np.stack([o + rng.normal(0.5, 0.1, 16), rng.normal(0.5, 0.1, 16)], axis=1) for o in offsets]
    t = between_scan_test(data)
    assert t.sigma_b2[0] == pytest.approx(0.01, rel=0.5)
    assert t.sigma_b2[1] < 0.002
    assert t.icc[0] == pytest.approx(0.5, abs=0.2)
    assert not t.one_surface and t.failing_means == (0,) and t.failing_approaches == (0,)
    assert "window means differ at approach(es) 0" in t.verdict
    assert t.variance_ratio[0] == pytest.approx(t.sigma_b2[0] / t.sigma_w2[0])
    # H0 σ_b²/σ_w² ≤ 2 (more than the data hold) is not rejected
    lenient = between_scan_test(data, null_variance_ratio=2.0)
    assert lenient.one_surface and lenient.p_value[0] > t.p_value[0]


def test_detectable_between_scan_sd_has_the_stated_power() -> None:
    """The random-effects and the fixed-effects numbers give 80 % power (Monte Carlo, normal windows)."""
    level, n, k, reps = 0.01, 16, 2, 4000
    rand_b, fixed_sd = detectable_between_scan_sd([n] * k, level=level)
    f_crit = sps.f.isf(level, k - 1, k * n - k)
    rng = np.random.default_rng(5)

    def power(means: np.ndarray) -> float:
        x = means[:, :, None] + rng.standard_normal((reps, k, n))
        m = x.mean(axis=2)
        msb = n * ((m - m.mean(axis=1, keepdims=True)) ** 2).sum(axis=1) / (k - 1)
        msw = ((x - m[:, :, None]) ** 2).sum(axis=(1, 2)) / (k * n - k)
        return float(np.mean(msb / msw > f_crit))

    assert power(rng.normal(0.0, rand_b, size=(reps, k))) == pytest.approx(0.8, abs=0.03)
    delta = math.sqrt(2.0) * fixed_sd  # two scans whose true means have sd fixed_sd (ddof 1)
    assert power(np.tile([0.0, delta], (reps, 1))) == pytest.approx(0.8, abs=0.03)
    # more windows per scan detect smaller differences
    fewer, more = detectable_between_scan_sd([9, 9], level=level), detectable_between_scan_sd([25, 25], level=level)
    assert fewer[1] > fixed_sd > more[1] and fewer[0] > rand_b > more[0]


def test_bad_input_is_refused() -> None:
    with pytest.raises(AnalysisError, match="at least two scans"):
        between_scan_test([np.ones((4, 2))])
    with pytest.raises(AnalysisError, match="same U"):
        between_scan_test([np.ones((4, 2)), np.ones((4, 3))])
    with pytest.raises(AnalysisError, match="no approach"):
        between_scan_test([np.full((4, 2), np.nan), np.ones((4, 2))])
    with pytest.raises(AnalysisError, match="alpha"):
        between_scan_test([np.ones((4, 2)), np.ones((4, 2))], alpha=1.5)


# --------------------------------------------------------------------------------------------------
# (a)–(c): synthetic maps
# --------------------------------------------------------------------------------------------------


def test_two_crops_of_one_map_are_one_surface() -> None:
    big = _field((512, 256), 2.0, seed=1)
    t = _test(_halves(big, axis=0))
    assert t.scans == 2 and t.windows == (16, 16)
    assert t.one_surface, t.to_dict()
    assert t.failing_approaches == () and t.verdict == "one surface"
    assert np.all(t.p_value > BETWEEN_SCAN_ALPHA / 12)
    # the power it had (80 % at α/(2U)): scan means about 1.4 within-scan sd apart, σ_b about 3 sd
    ratio = t.detectable_mean_sd / np.sqrt(t.sigma_w2)
    expected = detectable_between_scan_sd([16, 16], level=BETWEEN_SCAN_ALPHA / 12)
    assert ratio == pytest.approx(np.full(6, expected[1]), rel=1e-9) and 0.5 < expected[1] < 2.0
    assert t.detectable_sigma_b / np.sqrt(t.sigma_w2) == pytest.approx(np.full(6, expected[0]), rel=1e-9)


@pytest.mark.parametrize(("corr_b", "rms_b"), [(3.0, 1e-6), (2.0, 1.5e-6)])
def test_two_unrelated_maps_are_refused(corr_b: float, rms_b: float) -> None:
    t = _test([_field((256, 256), 2.0, seed=2), _field((256, 256), corr_b, seed=3, rms=rms_b)])
    assert not t.one_surface
    assert t.failing_means and np.nanmin(t.p_value) < 1e-5
    assert "NOT one surface" in t.verdict


def test_false_alarm_rate_on_independent_maps_of_one_generator() -> None:
    """20 pairs of crops of independent stationary maps of one generator: the number refused stays
    within the binomial bound of the stated α (P(more) < 0.001 if the rate were α)."""
    refused = 0
    for k in range(20):
        a = crop_surface(_field((288, 288), 2.0, seed=100 + 2 * k), (256, 256))
        b = crop_surface(_field((288, 288), 2.0, seed=101 + 2 * k), (256, 256))
        refused += not _test([a, b]).one_surface
    bound = int(sps.binom.ppf(0.999, 20, BETWEEN_SCAN_ALPHA))
    assert refused <= bound, (refused, bound)


# --------------------------------------------------------------------------------------------------
# (d) how many scans
# --------------------------------------------------------------------------------------------------


def test_sigma_mu_relative_se() -> None:
    for n in (2, 5, 30, 200):
        assert sigma_mu_relative_se(n, 3.0) == pytest.approx(1.0 / math.sqrt(2.0 * (n - 1)), rel=1e-12)
    assert sigma_mu_relative_se(10_000, 7.0) == pytest.approx(math.sqrt(6.0 / 40_000), rel=1e-3)
    assert sigma_mu_relative_se(50, 6.0) > sigma_mu_relative_se(50, 3.0)
    with pytest.raises(AnalysisError):
        sigma_mu_relative_se(1)


def test_scans_needed_is_sensible_and_monotone() -> None:
    one = scans_needed(0.05, 0.1, windows_per_scan=1)
    assert one.scans == 51 and one.relative_se <= 0.1  # 1/√(2·50) = 0.1
    assert one.sigma_mu_se == pytest.approx(0.05 * one.relative_se)
    tiles = scans_needed(0.05, 0.1, windows_per_scan=16)
    assert tiles.scans == 4 and tiles.windows == 64
    assert "independent" in tiles.assumption
    precisions = [0.3, 0.2, 0.1, 0.05, 0.02]
    counts = [scans_needed(None, r, windows_per_scan=16).scans for r in precisions]
    assert counts == sorted(counts) and counts[0] < counts[-1]
    assert scans_needed(None, 0.1, windows_per_scan=16, kurtosis=8.0).scans > tiles.scans
    assert scans_needed(None, 0.5, windows_per_scan=16).scans == 1
    json.dumps(tiles.to_dict(), allow_nan=False)
    with pytest.raises(AnalysisError):
        scans_needed(None, 0.0, windows_per_scan=16)


# --------------------------------------------------------------------------------------------------
# (e) pixel sizes and summits
# --------------------------------------------------------------------------------------------------


def test_pixel_size_tolerance() -> None:
    assert POOL_PIXEL_RTOL == 5e-3
    assert pixel_sizes_agree([(1e-7, 2e-7), (1.001e-7, 2.002e-7)])  # 0.1 %: one measurement, two files
    assert not pixel_sizes_agree([(1e-7, 2e-7), (1.02e-7, 2e-7)])  # 2 %
    assert not pixel_sizes_agree([(1e-7, 2e-7), (1e-7, 2.02e-7)])
    assert pixel_sizes_agree([(1e-7, 1e-7)] * 3)
    a = _field((64, 64), 2.0, seed=0)
    b = Surface(heights_m=a.heights_m, physical_size_m=(64 * 1.001e-6, 64 * 1.001e-6))
    same = on_common_pixel_size([a, b])
    assert same[0].grid_spacing_m == pytest.approx(same[1].grid_spacing_m, rel=1e-12)
    assert np.array_equal(same[1].heights_m, a.heights_m)  # no interpolation
    assert "pixel_size_relabelled_from" in same[1].info
    c = Surface(heights_m=a.heights_m, physical_size_m=(64 * 1.02e-6, 64e-6))
    with pytest.raises(AnalysisError, match="pixel sizes differ"):
        on_common_pixel_size([a, c])


def test_scans_are_not_reduced_to_a_handful_of_summits() -> None:
    scan = _field((256, 256), 4.0, seed=7)  # 1 µm pixels, 239 summits; 1.5 µm: 220; 5 µm (51 × 51): 132
    counts = check_resampling_keeps_summits([scan], (1.5e-6, 1.5e-6), names=["a"])
    assert counts[0] >= MIN_SUMMITS_PER_SCAN
    with pytest.raises(AnalysisError, match=r"at least 180 summits per scan.*a: \d+ after resampling to 5 x 5 um"):
        check_resampling_keeps_summits([scan], (5e-6, 5e-6), names=["a"])  # 51 × 51 points
    require_summits_for_pooling([MIN_SUMMITS_PER_SCAN, 1000])
    with pytest.raises(AnalysisError, match="analyse each scan on its own"):
        require_summits_for_pooling([41, 21], names=["afm-1", "afm-2"])


# --------------------------------------------------------------------------------------------------
# (f) the real files
# --------------------------------------------------------------------------------------------------


def _real(name: str) -> Surface:
    path = SHARED / name
    if not path.is_file():
        pytest.skip(f"{path} not available")
    return _prepared(path)


@functools.cache
def _prepared(path: Path) -> Surface:
    """The prepared map (default preparation, undefined points filled), read once per session."""
    return prepare(read_surface(path, fill_undefined=True))[0]


def test_two_halves_of_one_real_map_pass() -> None:
    opd = _real("opd-1.opd")
    for axis in (0, 1):
        t = _test(_halves(opd, axis))
        assert t.windows == (16, 16)
        assert t.one_surface, (axis, t.to_dict())


def test_x3p_against_opd_resampled_to_one_pixel_size_is_refused() -> None:
    x3p, opd = _real("x3p-2.x3p"), _real("opd-1.opd")
    assert not pixel_sizes_agree([x3p.grid_spacing_m, opd.grid_spacing_m])
    target = (max(x3p.grid_spacing_m[0], opd.grid_spacing_m[0]), max(x3p.grid_spacing_m[1], opd.grid_spacing_m[1]))
    scans = [crop_surface(resample_surface(s, target), (256, 256)) for s in (x3p, opd)]
    assert min(summits_of(s).count for s in scans) >= MIN_SUMMITS_PER_SCAN
    t = _test(scans)
    assert not t.one_surface
    assert np.nanmin(t.p_value) < 1e-3

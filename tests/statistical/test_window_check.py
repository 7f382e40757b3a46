"""The measured-window check (issue 18 §2): scatter of μ across disjoint windows of the measurement
against the same windows of its surrogates (:func:`stochfric.process.checks.window_scatter_check`).

Fixed seeds.  Three tiers: the test statistic is calibrated (its false-alarm rate at the nominal
5 % is 5 %, for Gaussian and for skewed, heavy-tailed values, with the small window counts the
check meets); the check passes Gaussian surrogates of a map that *is* a stationary Gaussian field;
and it fails, as it must, random-phase surrogates of a strongly non-stationary map (one half
smooth, one half rough), whose windows scatter far more than any Gaussian field's.
"""

from __future__ import annotations

import numpy as np
import pytest
from scipy import ndimage
from scipy import stats as sps

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.checks import surrogate_check, window_scatter_check, window_tiles
from stochfric.process.ensemble import ensemble_contact, tile_contact, tile_grid
from stochfric.surface.io import Surface
from stochfric.surface.summits import summits_of

MAT = get_material("brake-pad")


@pytest.mark.parametrize("kind", ["normal", "lognormal"])
def test_false_alarm_rate_is_nominal(kind: str) -> None:
    """|z| > 1.96 in 5 % of 600 trials of one population against itself (J = 9 vs 400 values)."""
    rng = np.random.default_rng(11)
    hits = 0
    trials = 600
    for _ in range(trials):
        draw = rng.standard_normal if kind == "normal" else (lambda size: rng.lognormal(0.0, 0.5, size))
        a, b = draw((9, 1)), draw((400, 1))
        z = window_scatter_check(a, b, tiles=3, window_size_m=(1.0, 1.0)).z[0]
        hits += abs(z) > float(sps.norm.isf(0.025))
    # binomial(600, 0.05): mean 30, sd 5.3; allow 3 sd either way (a skewed kurtosis estimate from 400)
    assert 14 <= hits <= 46, hits


def test_a_scatter_ratio_of_three_is_detected() -> None:
    rng = np.random.default_rng(2)
    check = window_scatter_check(3.0 * rng.standard_normal((16, 2)), rng.standard_normal((800, 2)), tiles=4,
                                 window_size_m=(1.0, 1.0))
    assert not check.consistent and min(check.z) > check.threshold


def _field(rng: np.random.Generator, shape: tuple[int, int], corr_px: float) -> np.ndarray:
    z = ndimage.gaussian_filter(rng.standard_normal(shape), corr_px, mode="wrap")
    return z / z.std()


def _window_check(surface: Surface, seed: int, realizations: int = 30):  # type: ignore[no-untyped-def]
    sm = summits_of(surface)
    u = default_approach_m(sm, num=6)
    tiles = window_tiles(sm.count)
    assert tiles is not None
    ens = ensemble_contact(surface, MAT, u, realizations=realizations, seed=seed, tiles=tiles)
    area, force, _ = tile_contact(surface.heights_m, surface.grid_spacing_m, MAT, u, tiles=tiles, rule="thesis")
    measured = area * MAT.shear_strength_pa / force
    i0, i1, j0, j1 = tile_grid(surface.nb_grid_pts, tiles)[0]
    return window_scatter_check(measured, ens.tile_samples.mu, tiles=tiles, window_size_m=(i1 - i0, j1 - j0))


def test_gaussian_surrogates_of_a_gaussian_field_pass() -> None:
    """8 independent stationary Gaussian maps: at most one false alarm (family-wise α = 0.05 each)."""
    fails = []
    for k in range(8):
        rng = np.random.default_rng(100 + k)
        s = Surface(heights_m=1e-6 * _field(rng, (96, 96), 1.5), physical_size_m=(9.6e-4, 9.6e-4))
        check = _window_check(s, seed=k)
        fails.append(not check.consistent)
    assert sum(fails) <= 1, fails


def test_gaussian_surrogates_of_a_half_smooth_half_rough_map_fail() -> None:
    rng = np.random.default_rng(5)
    z = _field(rng, (96, 96), 1.5)
    z[:, 48:] *= 6.0  # the right half six times rougher: windows differ far more than a stationary field allows
    s = Surface(heights_m=1e-6 * z, physical_size_m=(9.6e-4, 9.6e-4))
    check = _window_check(s, seed=1)
    assert not check.consistent
    assert check.max_abs_z > check.threshold


def test_summit_check_fails_gaussian_surrogates_of_a_spiky_map() -> None:
    """The summit check fails, as it must, random-phase surrogates of a strongly non-Gaussian map: a
    smooth Gaussian field carrying 150 sharp bumps of 6 sd (its summit population is two populations
    that no Gaussian field of the same spectrum has).  100 realisations: the rank test cannot reject with
    fewer than 19, and decides a failure (none of R reaching the map) from about 80."""
    rng = np.random.default_rng(5)
    n = 256
    base = _field(rng, (n, n), 3.0)
    bumps = np.zeros((n, n))
    idx = rng.integers(0, n, size=(150, 2))
    bumps[idx[:, 0], idx[:, 1]] = 1.0
    bumps = ndimage.gaussian_filter(bumps, 1.0, mode="wrap")
    s = Surface(heights_m=1e-6 * (base + 6.0 * bumps / bumps.max()), physical_size_m=(n * 1e-6, n * 1e-6))
    u = default_approach_m(summits_of(s), num=6)
    check = surrogate_check(s, MAT, ensemble_contact(s, MAT, u, realizations=100, seed=1, method="phase"))
    assert not check.credible and check.global_exceed == 0 and check.decided(100, looks=3)[0]
    assert abs(check.z["summit_count"]) > 10 and abs(check.z["summit_height_std_m"]) > 10

"""The surrogate rule ``auto``, the copy check and the worker count (issue 18 §2).

``auto`` picks quilting only where patches of 16 summit spacings fit three times along the shorter
side, random phases otherwise, and says why; a "surrogate" that is the map itself is caught as a
copy and makes the analysis not credible; realisations on 1 or 2 worker processes are bit-identical.
"""

from __future__ import annotations

from collections.abc import Iterator

import numpy as np
import pytest

from stochfric.contact.asperity import default_approach_m
from stochfric.contact.materials import get_material
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.checks import copy_check
from stochfric.process.credibility import assess_credibility
from stochfric.process.ensemble import SurrogateOptions, ensemble_contact, path_contact
from stochfric.random import spawn_seed_sequences
from stochfric.surface.io import Surface, default_surface_path, read_surface
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import summits_of
from stochfric.surface.surrogates import SurrogateMethod, SurrogateSettings, register_surrogate, unregister_surrogate
from synthetic_maps import as_surface, gaussian_heights, spiky_heights  # tests/synthetic_maps.py

MAT = get_material("brake-pad")


def _field(shape: tuple[int, int], corr: float, seed: int = 0) -> Surface:
    return as_surface(gaussian_heights(shape, corr, seed))


def _spiky(shape: tuple[int, int], seed: int = 0) -> Surface:
    return as_surface(spiky_heights(shape, seed))


def test_auto_picks_phase_for_gaussian_curvature_and_quilt_otherwise() -> None:
    cfg = AnalysisConfig(surrogate="auto")
    gaussian = _field((320, 320), 1.0)
    opts, why = cfg.surrogate_for([gaussian.heights_m])
    assert opts.method == "phase" and "Gaussian curvature" in why and "exact" in why
    spiky = _spiky((320, 320))
    opts, why = cfg.surrogate_for([spiky.heights_m])
    assert opts.method == "quilt" and why.startswith("quilt (auto: non-Gaussian curvature")
    shipped = prepare(read_surface(default_surface_path()))[1]  # non-Gaussian, 226 summits on 200 × 296 points
    opts, why = cfg.surrogate_for([shipped.heights_m])
    assert opts.method == "phase" and "cannot quilt" in why and "does not fit 3 times" in why
    opts, why = AnalysisConfig(surrogate="phase").surrogate_for([spiky.heights_m])
    assert opts.method == "phase" and why == "phase (chosen by the user)"


def test_curvature_gaussianity_is_calibrated_on_gaussian_fields() -> None:
    """|z| well inside the limit on Gaussian fields of several sizes and correlation lengths; far outside on
    the spiky field."""
    from stochfric.surface.statistics import GAUSSIAN_CURVATURE_Z, curvature_gaussianity

    for k, (n, corr) in enumerate([(200, 0.7), (300, 1.5), (400, 3.0)]):
        s = _field((n, n + 17), corr, seed=k)
        t = curvature_gaussianity(s.heights_m, summits_of(s).count)
        assert t.gaussian and abs(t.z) < GAUSSIAN_CURVATURE_Z / 3, t
    spiky = _spiky((320, 320))
    t = curvature_gaussianity(spiky.heights_m, summits_of(spiky).count)
    assert not t.gaussian and t.z > 10 * GAUSSIAN_CURVATURE_Z


class _Copier(SurrogateMethod):
    """A surrogate method that returns the map itself (what no surrogate may do)."""

    name = "copy"
    summary = "the map itself"

    def heights(self, heights: np.ndarray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> np.ndarray:
        return np.tile(heights, (1, factor))


@pytest.fixture
def copier() -> Iterator[str]:
    register_surrogate(_Copier())
    yield _Copier.name
    unregister_surrogate(_Copier.name)


def test_a_surrogate_that_is_the_map_is_a_copy_and_not_credible(copier: str) -> None:
    s = _field((96, 96), 2.0)
    seeds = spawn_seed_sequences(1, 4)
    copies = copy_check([s], SurrogateOptions(method=copier), seeds)
    assert copies.is_copy and copies.max_ncc_with_map == pytest.approx(1.0)
    fresh = copy_check([s], SurrogateOptions(method="phase"), seeds)
    assert not fresh.is_copy and fresh.max_ncc_with_map < 0.9
    quilt = copy_check([_spiky((320, 320))], SurrogateOptions(method="quilt"), seeds)
    assert not quilt.is_copy and 0.0 < quilt.largest_piece_fraction < 0.1
    u = np.linspace(1e-7, 1e-6, 4)
    verdict = assess_credibility(
        name="m", approach_m=u, surrogate_ok=True, surrogate_failures=[], window_ok=True, window_max_z=0.0,
        copies=copies, mu_means=[np.full(4, 0.5)], area_fractions=[np.full(4, 0.01)], fit_mask=np.ones(4, bool),
        valid_fit_points=4,
    )  # fmt: skip
    assert verdict.codes() == ["surrogate-copies-map"]


@pytest.mark.parametrize("method", ["phase", "quilt"])
def test_two_workers_give_the_serial_numbers(method: str) -> None:
    s = _field((160, 200), 1.0, seed=3)
    u = default_approach_m(summits_of(s), num=4)
    one = ensemble_contact(s, MAT, u, realizations=5, seed=9, tiles=3, workers=1, method=method)
    two = ensemble_contact(s, MAT, u, realizations=5, seed=9, tiles=3, workers=2, method=method)
    assert np.array_equal(one.mu, two.mu) and np.array_equal(one.summit_stats, two.summit_stats)
    assert one.tile_samples is not None and two.tile_samples is not None
    assert np.array_equal(one.tile_samples.mu, two.tile_samples.mu)
    p1 = path_contact(s, MAT, u, long_surfaces=3, length_factor=2, shift_points=7, seed=2, workers=1, method=method)
    p2 = path_contact(s, MAT, u, long_surfaces=3, length_factor=2, shift_points=7, seed=2, workers=2, method=method)
    assert np.array_equal(p1.samples.mu, p2.samples.mu) and np.array_equal(p1.blocks.mu, p2.blocks.mu)

"""Ensembles and sliding windows (method §4a–c): fast windows equal the naive analysis."""

from __future__ import annotations

import json
from typing import Any

import numpy as np
import pytest

from stochfric.contact.asperity import asperity_sums, default_approach_m
from stochfric.contact.materials import get_material
from stochfric.errors import AnalysisError
from stochfric.friction_process.model_base import SigmaZetaRule
from stochfric.friction_process.tabulated import PressureRule, VarianceRule
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.ensemble import (
    SurrogateOptions,
    ensemble_contact,
    naive_window_contact,
    path_contact,
    window_contact,
    window_starts,
)
from stochfric.surface.io import Surface, default_surface_path, read_surface, surface_from_array
from stochfric.surface.preprocess import prepare
from stochfric.surface.summits import find_summits, summits_of
from stochfric.surface.synthesis import longer_surface

MAT = get_material("brake-pad")


@pytest.fixture(scope="module")
def fine() -> Surface:
    f, _ = prepare(read_surface(default_surface_path()))
    return f


@pytest.mark.parametrize("rule", ["thesis", "8-neighbour"])
def test_fast_windows_equal_naive_windows(fine: Surface, rule: str) -> None:
    long = longer_surface(fine, 3, 4)
    u = default_approach_m(summits_of(fine))
    kw: dict[str, Any] = dict(window_points=296, shift_points=37, rule=rule)
    fast = window_contact(long.heights_m, long.grid_spacing_m, MAT, u, **kw)
    naive = naive_window_contact(long.heights_m, long.grid_spacing_m, MAT, u, **kw)
    assert fast[0].shape == (window_starts(888, 296, 37).size, u.size)
    np.testing.assert_allclose(fast[0], naive[0], rtol=1e-12)
    np.testing.assert_allclose(fast[1], naive[1], rtol=1e-12)
    np.testing.assert_array_equal(fast[2], naive[2])


def test_each_window_referenced_to_its_own_highest_summit(fine: Surface) -> None:
    long = longer_surface(fine, 4, 9)
    u = np.array([1e-12, 1e-7])
    _a, n, c = window_contact(long.heights_m, long.grid_spacing_m, MAT, u, window_points=296, shift_points=50)
    # at a vanishing approach exactly one summit (the window's highest) touches in every window
    np.testing.assert_array_equal(c[:, 0], 1)
    # and the window at column 100 equals an analysis of the cropped window on its own
    s = find_summits(long.heights_m[:, 100:396], long.grid_spacing_m)
    ref = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=MAT.e_star_pa)
    np.testing.assert_allclose(n[2], ref[1], rtol=1e-9)


def test_window_starts() -> None:
    np.testing.assert_array_equal(window_starts(10, 4, 3), [0, 3, 6])
    with pytest.raises(AnalysisError):
        window_starts(3, 4, 1)


def test_ensemble_streams_do_not_depend_on_the_number_of_realisations(fine: Surface) -> None:
    u = default_approach_m(summits_of(fine))
    small = ensemble_contact(fine, MAT, u, realizations=3, seed=5)
    big = ensemble_contact(fine, MAT, u, realizations=5, seed=5)
    np.testing.assert_array_equal(small.normal_force_n, big.normal_force_n[:3])
    assert small.mu.shape == (3, u.size)
    assert not np.allclose(big.mu[0], big.mu[1])
    with pytest.raises(AnalysisError, match="surrogate"):
        ensemble_contact(fine, MAT, u, realizations=2, method="x")


def test_path_and_block_shapes(fine: Surface) -> None:
    u = default_approach_m(summits_of(fine), num=4)
    pc = path_contact(fine, MAT, u, long_surfaces=2, length_factor=3, shift_points=74, seed=1)
    assert pc.samples.mu.shape == (2, 9, 4)
    assert pc.window_shift_m == pytest.approx(74 * fine.grid_spacing_m[1])
    np.testing.assert_allclose(pc.positions_m[1], pc.window_shift_m)
    # the non-overlapping windows of the same long surfaces are every 4th shifted window
    assert pc.blocks.mu.shape == (2, 3, 4)
    np.testing.assert_allclose(pc.blocks.mu, pc.samples.mu[:, ::4], rtol=1e-12)


def test_surrogate_options_and_keywords_are_the_same(fine: Surface) -> None:
    """The surrogate options have one home: keywords, a SurrogateOptions and the analysis settings agree."""
    u = default_approach_m(summits_of(fine), num=3)
    opts = SurrogateOptions(amplitude="raw", rule="8-neighbour")
    by_kw = ensemble_contact(fine, MAT, u, realizations=2, seed=3, amplitude="raw", rule="8-neighbour")
    by_opts = ensemble_contact(fine, MAT, u, realizations=2, seed=3, options=opts)
    np.testing.assert_array_equal(by_kw.normal_force_n, by_opts.normal_force_n)
    assert by_kw.info == by_opts.info
    # keywords override the options' fields
    assert SurrogateOptions.of(opts, rule="thesis") == SurrogateOptions(amplitude="raw")
    cfg = AnalysisConfig(surrogate="phase", amplitude="raw", summit_rule="8-neighbour")
    assert cfg.surrogate_options == opts
    path_kw = path_contact(fine, MAT, u, long_surfaces=2, length_factor=2, shift_points=148, seed=1, amplitude="raw")
    path_opts = path_contact(fine, MAT, u, long_surfaces=2, length_factor=2, shift_points=148, seed=1,
                             options=SurrogateOptions(amplitude="raw"))
    np.testing.assert_array_equal(path_kw.samples.normal_force_n, path_opts.samples.normal_force_n)
    with pytest.raises(AnalysisError, match="amplitude"):
        path_contact(fine, MAT, u, long_surfaces=2, length_factor=2, shift_points=148, amplitude="x")
    with pytest.raises(AnalysisError, match="surrogate"):
        AnalysisConfig(surrogate="x")


def test_counts_share_one_validator() -> None:
    """Counts of the analysis settings and of the window functions: int (NumPy ints too), never bool."""
    cfg = AnalysisConfig(realizations=np.int64(4))
    assert cfg.realizations == 4 and type(cfg.realizations) is int
    with pytest.raises(AnalysisError, match="realizations must be an integer >= 1, got True"):
        AnalysisConfig(realizations=True)
    with pytest.raises(AnalysisError, match="length_factor must be an integer >= 2, got 1"):
        AnalysisConfig(length_factor=1)
    with pytest.raises(AnalysisError, match="shift_points must be an integer >= 1, got 0"):
        window_starts(10, 4, 0)


def test_sigma_zeta_rule_is_the_enum_and_round_trips_through_json() -> None:
    """``sigma_zeta_rule`` is a :class:`SigmaZetaRule` (a name given as text is turned into it), stored
    as its text, and read back to an equal config; another name is refused."""
    cfg = AnalysisConfig(sigma_zeta_rule="spectral_level")  # type: ignore[arg-type]
    assert cfg.sigma_zeta_rule is SigmaZetaRule.SPECTRAL_LEVEL
    text = json.dumps(cfg.to_dict())
    assert json.loads(text)["sigma_zeta_rule"] == "spectral_level"
    assert AnalysisConfig(**json.loads(text)) == cfg
    with pytest.raises(AnalysisError, match="sigma_zeta_rule must be one of"):
        AnalysisConfig(sigma_zeta_rule="psd")  # type: ignore[arg-type]


def test_pressure_and_variance_rules_are_the_process_layers_enums() -> None:
    """The spectrum rules of the tabulated model are one choice each (:class:`PressureRule`,
    :class:`VarianceRule`), for the config and the model alike; text is turned into them, other names refused."""
    cfg = AnalysisConfig(pressure_rule="interpolate", variance_rule="tabulated")  # type: ignore[arg-type]
    assert cfg.pressure_rule is PressureRule.INTERPOLATE and cfg.variance_rule is VarianceRule.TABULATED
    assert AnalysisConfig(**json.loads(json.dumps(cfg.to_dict()))) == cfg
    for field in ("pressure_rule", "variance_rule"):
        with pytest.raises(AnalysisError, match=f"{field} must be one of"):
            AnalysisConfig(**{field: "linear"})


def test_large_surface_many_windows_equal_naive() -> None:
    """Windows with thousands of summits each (the old blocked path crashed on any real file)."""
    rng = np.random.default_rng(0)
    z = rng.standard_normal((300, 1200)) * 1e-7
    u = np.array([1e-8, 5e-8, 2e-7, 4e-7])
    kw: dict[str, Any] = dict(window_points=400, shift_points=23)
    fast = window_contact(z, (1e-6, 1e-6), MAT, u, **kw)
    naive = naive_window_contact(z, (1e-6, 1e-6), MAT, u, **kw)
    assert find_summits(z[:, :400], (1e-6, 1e-6)).count > 5000
    np.testing.assert_allclose(fast[0], naive[0], rtol=1e-10)
    np.testing.assert_allclose(fast[1], naive[1], rtol=1e-10)
    np.testing.assert_array_equal(fast[2], naive[2])


def test_ensemble_records_summit_statistics(fine: Surface) -> None:
    u = default_approach_m(summits_of(fine), num=3)
    ens = ensemble_contact(fine, MAT, u, realizations=3, seed=1)
    assert ens.summit_stats is not None and ens.summit_stats.shape == (3, 3)
    s = find_summits(
        __import__("stochfric.surface.surrogates", fromlist=["x"]).similar_surface(
            fine, np.random.default_rng(np.random.SeedSequence(1).spawn(3)[0])
        ).heights_m,
        fine.grid_spacing_m,
    )
    np.testing.assert_allclose(ens.summit_stats[0], [s.count, s.radius_m.mean(), s.heights_m.std()])


def test_window_without_summit_is_refused() -> None:
    flat = surface_from_array(np.zeros((10, 40)), physical_size_m=(1e-5, 4e-5))
    with pytest.raises(AnalysisError, match="no summit"):
        window_contact(flat.heights_m, flat.grid_spacing_m, MAT, [1e-7], window_points=10, shift_points=5)

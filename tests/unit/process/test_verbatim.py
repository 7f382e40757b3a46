"""The verbatim measure of a surrogate, independent of how it was made (issue 29, item 3).

Acceptance: a generator that returns the map's own windows reshuffled, and one that returns the map,
are both reported as >= 90 % verbatim and labelled resampling / copy by the measure itself; quilted
surrogates are mostly verbatim (resampling), random-phase surrogates and independent Gaussian fields
are new.  Fixed seeds; the tolerances are statistical (64 sampled points: a binomial sd <= 6 %).
"""

from __future__ import annotations

import json
import math

import numpy as np
import numpy.typing as npt
import pytest
from scipy import ndimage

from stochfric.errors import AnalysisError, StochfricError
from stochfric.process import verbatim as verbatim_module
from stochfric.process.verbatim import (
    COPY_PIECE_SHARE,
    MIN_BLOCK,
    RESAMPLING_FRACTION,
    VERBATIM_NCC,
    BlockMatcher,
    clopper_pearson_interval,
    default_block,
    independent_pieces,
    laplacian,
    pool_verbatim,
    summit_spacing_points,
    verbatim_fraction,
    verbatim_label,
)
from stochfric.surface.io import read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.quilting import quilt_heights
from stochfric.surface.summits import find_summits
from stochfric.surface.synthesis import random_phase_heights
from synthetic_maps import spiky_heights  # tests/synthetic_maps.py

Array = npt.NDArray[np.float64]


_spiky = spiky_heights


def _gaussian(shape: tuple[int, int], corr: float, seed: int) -> Array:
    z = ndimage.gaussian_filter(np.random.default_rng(seed).standard_normal(shape), corr, mode="wrap")
    return np.asarray(1e-6 * z / z.std())


def the_map(heights: Array, rng: np.random.Generator) -> Array:
    """A "generator" that returns the map."""
    return np.array(heights)


def windows_reshuffled(heights: Array, rng: np.random.Generator, tiles: int = 4) -> Array:
    """A "generator" that cuts the map into tiles × tiles windows and puts them back in random order,
    each as it is or rotated by 180° at random."""
    nx, ny = heights.shape
    wx, wy = nx // tiles, ny // tiles
    windows = [heights[i * wx : (i + 1) * wx, j * wy : (j + 1) * wy] for i in range(tiles) for j in range(tiles)]
    order = rng.permutation(len(windows))
    turn = rng.integers(0, 2, size=len(windows))
    out = np.empty((wx * tiles, wy * tiles))
    for k, (o, r) in enumerate(zip(order, turn, strict=True)):
        i, j = divmod(k, tiles)
        out[i * wx : (i + 1) * wx, j * wy : (j + 1) * wy] = windows[o][::-1, ::-1] if r else windows[o]
    return out


@pytest.fixture(scope="module")
def spiky() -> Array:
    return _spiky((320, 320))


@pytest.fixture(scope="module")
def spiky_matcher(spiky: Array) -> BlockMatcher:
    return BlockMatcher(spiky, default_block(spiky))


# --- the pieces ----------------------------------------------------------------------------------


def test_laplacian_is_the_five_point_stencil() -> None:
    x, y = np.meshgrid(np.arange(7.0), np.arange(9.0), indexing="ij")
    lap = laplacian(3.0 * x**2 - y**2 + 2.0 * x * y)
    assert lap.shape == (5, 7) and np.allclose(lap, 6.0 - 2.0)
    z = np.random.default_rng(1).standard_normal((6, 5))
    manual = z[2:, 1:-1] + z[:-2, 1:-1] + z[1:-1, 2:] + z[1:-1, :-2] - 4 * z[1:-1, 1:-1]
    assert np.array_equal(laplacian(z), manual)


def test_block_side_is_one_summit_spacing_at_least_min_block(spiky: Array) -> None:
    n = find_summits(spiky, (1.0, 1.0)).count
    assert summit_spacing_points(spiky) == pytest.approx(math.sqrt(spiky.size / n))
    assert default_block(spiky) == max(MIN_BLOCK, round(math.sqrt(spiky.size / n)))
    smooth = _gaussian((200, 240), 4.0, seed=3)  # sparse summits: a spacing well above the minimum
    assert default_block(smooth) == round(summit_spacing_points(smooth)) > MIN_BLOCK
    assert summit_spacing_points(np.zeros((20, 20))) == math.inf


def test_independent_pieces_and_interval() -> None:
    assert independent_pieces(768 * 576, 5) == 768 * 576 // 25
    assert independent_pieces(10, 5) == 1
    lo, hi = clopper_pearson_interval(0, 64)
    assert lo == 0.0 and hi == pytest.approx(1 - 0.025 ** (1 / 64))
    lo, hi = clopper_pearson_interval(64, 64)
    assert hi == 1.0 and lo == pytest.approx(0.025 ** (1 / 64))
    lo, hi = clopper_pearson_interval(32, 64)
    assert lo < 0.5 < hi and hi - 0.5 == pytest.approx(0.5 - lo)
    assert verbatim_label(1.0, 1.0) == "copy"
    assert verbatim_label(1.0, COPY_PIECE_SHARE / 2) == "resampling"
    assert verbatim_label(RESAMPLING_FRACTION, 0.0) == "resampling"
    assert verbatim_label(RESAMPLING_FRACTION - 0.01, 0.0) == "new"


# --- the acceptance: copies and resamplings ------------------------------------------------------


def test_a_generator_that_returns_the_map_is_a_copy(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    m = verbatim_fraction(the_map(spiky, np.random.default_rng(0)), spiky, matcher=spiky_matcher)
    assert m.fraction >= 0.99 and m.block_fraction >= 0.99 and m.label == "copy" and m.is_copy
    assert m.largest_piece_share == 1.0 and m.median_block_ncc == pytest.approx(1.0, abs=1e-6)
    assert m.ci95[0] > 0.9 and m.blocks == 64 and m.block == default_block(spiky)
    assert "copy of the measurement" in m.summary() and "independent pieces" in m.summary()


def test_a_rotated_or_shifted_map_is_a_copy(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    turned = verbatim_fraction(spiky[::-1, ::-1], spiky, matcher=spiky_matcher)
    assert turned.fraction >= 0.99 and turned.label == "copy" and turned.largest_piece_share == 1.0
    shifted = np.roll(spiky, (40, 70), axis=(0, 1))[:150, 30:]  # one piece of the map (rolled: two)
    m = verbatim_fraction(shifted, spiky, matcher=spiky_matcher)
    assert m.fraction >= 0.95 and m.label == "copy"


def test_reshuffled_windows_are_a_verbatim_resampling(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    for seed in (1, 2):
        surrogate = windows_reshuffled(spiky, np.random.default_rng(seed))
        m = verbatim_fraction(surrogate, spiky, matcher=spiky_matcher, rng=100 + seed)
        # expected ≈ (1 − 6/318)² = 0.963: only the two Laplacian rows (columns) at each of the three
        # seams per axis are no piece of the map (20 seeds: 0.92 … 1.00, mean 0.970)
        assert m.fraction >= 0.9, m.summary()
        assert m.label == "resampling" and m.is_resampling  # 16 pieces: no single one covers half of it
        assert m.largest_piece_share < COPY_PIECE_SHARE
        assert "resampling of the measurement" in m.summary()
        # random blocks across the seams are not verbatim: the block fraction is lower, ≈ (1 − 18/314)²
        # = 0.89 for blocks of 5 (20 seeds: mean 0.892)
        assert m.block_fraction <= m.fraction


def test_quilted_surrogates_are_mostly_verbatim(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    measures = []
    for seed in (11, 12):
        q = quilt_heights(spiky, seed).heights
        m = verbatim_fraction(q, spiky, matcher=spiky_matcher, rng=seed)
        assert m.fraction > 0.7 and m.label == "resampling", m.summary()
        assert m.median_block_ncc > 0.999  # a verbatim piece keeps NCC 1 under the seam repair and low band
        measures.append(m)
    pooled = pool_verbatim(measures)
    assert pooled.blocks == 128 and pooled.surrogates == 2 and pooled.label == "resampling"
    assert pooled.verbatim_blocks == sum(m.verbatim_blocks for m in measures)
    assert pooled.measured_pieces == independent_pieces(spiky.size, spiky_matcher.block)


def test_a_long_quilt_is_measured_over_its_whole_length(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    q = quilt_heights(spiky[:, :160], 5, factor=3).heights  # 320 × 480, longer than the map in y
    m = verbatim_fraction(q, spiky[:, :160], rng=5)
    assert q.shape == (320, 480) and m.label == "resampling" and m.fraction > 0.7


# --- new surfaces ----------------------------------------------------------------------------------


def test_random_phase_surrogates_are_new(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    measures = [
        verbatim_fraction(random_phase_heights(spiky, 100 + s), spiky, matcher=spiky_matcher, rng=s) for s in range(3)
    ]
    for m in measures:
        assert m.fraction <= 0.05 and m.label == "new", m.summary()
        assert m.median_block_ncc < 0.95
    pooled = pool_verbatim(measures)
    assert pooled.label == "new" and pooled.ci95[1] < RESAMPLING_FRACTION


def test_independent_gaussian_fields_of_one_spectrum_are_new() -> None:
    a = _gaussian((256, 256), 1.0, seed=21)
    matcher = BlockMatcher(a, default_block(a))
    other = _gaussian((256, 256), 1.0, seed=22)  # same spectrum, independent phases
    for surrogate in (other, random_phase_heights(a, 23)):
        m = verbatim_fraction(surrogate, a, matcher=matcher, rng=4)
        assert m.fraction <= 0.05 and m.label == "new", m.summary()
        assert max(m.block_ncc) < VERBATIM_NCC


def test_real_map_quilts_resample_and_phases_are_new(shared_file) -> None:  # type: ignore[no-untyped-def]
    """plu-1 (768 × 576, block 5): quilts mostly verbatim, random phases not at all."""
    z = prepare(read_surface(shared_file("plu-1.plu")), Preparation())[1].heights_m
    matcher = BlockMatcher(z, default_block(z))
    quilt = verbatim_fraction(quilt_heights(z, 1).heights, z, matcher=matcher, rng=1)
    assert quilt.label == "resampling" and quilt.fraction > 0.7
    phase = verbatim_fraction(random_phase_heights(z, 1), z, matcher=matcher, rng=1)
    assert phase.label == "new" and phase.fraction <= 0.05
    resampled = verbatim_fraction(windows_reshuffled(z, np.random.default_rng(3)), z, matcher=matcher, rng=3)
    assert resampled.fraction >= 0.9 and resampled.label == "resampling"


# --- the machinery ------------------------------------------------------------------------------------


def test_same_seed_same_numbers(spiky: Array) -> None:
    q = quilt_heights(spiky, 7).heights
    one = verbatim_fraction(q, spiky, rng=3)
    two = verbatim_fraction(q, spiky, rng=3)
    assert one == two and one.to_dict() == two.to_dict()
    other = verbatim_fraction(q, spiky, rng=4)
    assert other.block_ncc != one.block_ncc


def test_fft_and_direct_matching_agree(spiky: Array) -> None:
    b = default_block(spiky)
    fft = BlockMatcher(spiky, b, method="fft")
    direct = BlockMatcher(spiky, b, method="direct")
    q = quilt_heights(spiky, 9).heights
    for surrogate in (q, random_phase_heights(spiky, 9)):
        a = verbatim_fraction(surrogate, spiky, matcher=fft, rng=2)
        d = verbatim_fraction(surrogate, spiky, matcher=direct, rng=2)
        assert a.verbatim_blocks == d.verbatim_blocks and a.label == d.label
        assert np.allclose(a.block_ncc, d.block_ncc, atol=1e-5)
    lap = laplacian(q)
    pieces = np.stack([lap[i : i + b, j : j + b] for i, j in ((3, 4), (100, 200), (250, 17))])
    mf, md = fft.match(pieces), direct.match(pieces)
    assert np.allclose(mf.ncc, md.ncc, atol=1e-5)
    assert np.array_equal(mf.i, md.i) and np.array_equal(mf.j, md.j) and np.array_equal(mf.rotated, md.rotated)


@pytest.mark.parametrize(("threshold", "cap"), [(0.95, 0.02), (0.98, 0.02), (0.98, 0.0)])
def test_indexed_search_finds_exactly_the_verbatim_blocks(
    spiky: Array, spiky_matcher: BlockMatcher, threshold: float, cap: float, monkeypatch: pytest.MonkeyPatch
) -> None:
    """The k-d tree candidates (projection bound) lose no block whose best NCC reaches the threshold;
    with a candidate cap of 0 every block with a candidate is matched against every window instead, with
    the same result."""
    monkeypatch.setattr(verbatim_module, "_TREE_MAX_CANDIDATES", cap)
    if cap == 0.0:
        monkeypatch.setattr(verbatim_module, "_TREE_MIN_CAP", 0)
    b = spiky_matcher.block
    rng = np.random.default_rng(6)
    pieces = []
    for surrogate in (quilt_heights(spiky, 6).heights, random_phase_heights(spiky, 6), spiky[::-1, ::-1]):
        lap = laplacian(surrogate)
        for i, j in zip(rng.integers(0, lap.shape[0] - b, 40), rng.integers(0, lap.shape[1] - b, 40), strict=True):
            pieces.append(lap[i : i + b, j : j + b])
    blocks = np.stack(pieces)
    full = spiky_matcher.match(blocks)
    indexed = spiky_matcher.verbatim(blocks, threshold)
    hit = full.ncc >= threshold
    assert 40 <= hit.sum() < len(blocks)
    assert np.array_equal(hit, indexed.ncc >= threshold)
    assert np.all(np.isneginf(indexed.ncc[~hit]))
    assert np.allclose(indexed.ncc[hit], full.ncc[hit], atol=1e-5)


def test_flat_blocks_are_skipped_and_reported() -> None:
    z = _spiky((200, 200), seed=4)
    surrogate = np.array(z)
    surrogate[:, 100:] = 0.0  # half of the surrogate is a plane: its blocks have no curvature
    m = verbatim_fraction(surrogate, z, rng=1)
    assert m.blocks == 64 and m.skipped_flat > 0 and m.fraction >= 0.9


def test_to_dict_is_json_and_complete(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    m = verbatim_fraction(random_phase_heights(spiky, 3), spiky, matcher=spiky_matcher)
    d = json.loads(json.dumps(m.to_dict()))
    assert d["label"] == "new" and d["block_points"] == spiky_matcher.block and d["blocks"] == 64
    assert d["threshold"] == VERBATIM_NCC and len(d["ci95"]) == 2 and len(d["block_ncc_quartiles"]) == 3
    assert d["measured_pieces"] == independent_pieces(spiky.size, spiky_matcher.block)


def test_bad_input_is_refused(spiky: Array, spiky_matcher: BlockMatcher) -> None:
    with pytest.raises(AnalysisError, match="block side"):
        BlockMatcher(spiky, 400)
    with pytest.raises(AnalysisError, match="matching method"):
        BlockMatcher(spiky, 5, method="guess")
    with pytest.raises(AnalysisError, match="blocks"):
        verbatim_fraction(spiky, spiky, blocks=0, matcher=spiky_matcher)
    with pytest.raises(AnalysisError, match="threshold"):
        verbatim_fraction(spiky, spiky, threshold=1.5, matcher=spiky_matcher)
    with pytest.raises(AnalysisError, match="another shape"):
        verbatim_fraction(spiky[:100, :100], spiky[:100, :100], matcher=spiky_matcher)
    with pytest.raises(AnalysisError, match="exceeds the surrogate"):
        verbatim_fraction(spiky[:6, :6], spiky, matcher=BlockMatcher(spiky, 6))
    with pytest.raises(AnalysisError, match="plane"):
        BlockMatcher(np.zeros((30, 30)), 5)
    plane = np.add.outer(np.arange(60.0), np.arange(60.0))  # heights of a plane: zero Laplacian
    with pytest.raises(AnalysisError, match="no curvature"):
        verbatim_fraction(plane, spiky, matcher=spiky_matcher)
    with pytest.raises(AnalysisError, match="nothing to pool"):
        pool_verbatim([])
    with pytest.raises(StochfricError):
        verbatim_fraction(np.full((20, 20), np.nan), spiky)

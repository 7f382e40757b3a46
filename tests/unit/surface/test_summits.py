"""Summit rules, radii β = −1/κ and the flat/plateau policy."""

from __future__ import annotations

import numpy as np
import pytest

from stochfric.surface.io import Surface, SurfaceError
from stochfric.surface.summits import find_summits, summits_of


def _brute_force(z: np.ndarray, rule: str) -> set[tuple[int, int]]:
    if rule == "thesis":
        offs = [(-2, 0), (-1, 0), (1, 0), (2, 0), (0, -2), (0, -1), (0, 1), (0, 2)]
    else:
        offs = [(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1) if (a, b) != (0, 0)]
    m = max(max(abs(a), abs(b)) for a, b in offs)
    out = set()
    for i in range(m, z.shape[0] - m):
        for j in range(m, z.shape[1] - m):
            if all(z[i, j] > z[i + a, j + b] for a, b in offs):
                out.add((i, j))
    return out


@pytest.mark.parametrize("rule", ["thesis", "8-neighbour"])
def test_rules_match_brute_force(rule: str) -> None:
    z = np.random.default_rng(3).normal(size=(30, 27))
    s = find_summits(z, (1.0, 1.0), rule=rule)
    assert set(zip(s.i.tolist(), s.j.tolist(), strict=True)) == _brute_force(z, rule)
    assert s.count > 10


def test_rules_differ_as_defined() -> None:
    z = np.zeros((9, 9))
    # (4, 4) beats its 4 nearest neighbours but not the point 2 away in x
    z[4, 4] = 1.0
    z[6, 4] = 2.0
    s_thesis = find_summits(z, (1.0, 1.0), rule="thesis")
    s_eight = find_summits(z, (1.0, 1.0), rule="8-neighbour")
    assert (4, 4) not in set(zip(s_thesis.i.tolist(), s_thesis.j.tolist(), strict=True))
    assert (4, 4) in set(zip(s_eight.i.tolist(), s_eight.j.tolist(), strict=True))
    # a diagonal neighbour higher: summit by the thesis rule, not by the 8-neighbour rule
    z = np.zeros((9, 9))
    z[4, 4] = 1.0
    z[5, 5] = 1.5
    s_thesis = find_summits(z, (1.0, 1.0), rule="thesis")
    s_eight = find_summits(z, (1.0, 1.0), rule="8-neighbour")
    assert (4, 4) in set(zip(s_thesis.i.tolist(), s_thesis.j.tolist(), strict=True))
    assert (4, 4) not in set(zip(s_eight.i.tolist(), s_eight.j.tolist(), strict=True))


@pytest.mark.parametrize(("dx", "dy"), [(1e-6, 1e-6), (0.5e-6, 2e-6)])
def test_radius_of_a_paraboloid_is_exact(dx: float, dy: float) -> None:
    # z = −x²/(2Rx) − y²/(2Ry): κ = ½(−1/Rx − 1/Ry), β = −1/κ = 2/(1/Rx + 1/Ry)
    rx, ry = 40e-6, 10e-6
    x = (np.arange(21) - 10) * dx
    y = (np.arange(17) - 8) * dy
    xx, yy = np.meshgrid(x, y, indexing="ij")
    z = -(xx**2) / (2 * rx) - yy**2 / (2 * ry)
    s = find_summits(z, (dx, dy))
    assert s.count == 1
    assert (s.i[0], s.j[0]) == (10, 8)
    assert s.radius_m[0] == pytest.approx(2.0 / (1 / rx + 1 / ry), rel=1e-9)
    assert s.heights_m[0] == 0.0


def test_border_points_are_not_candidates() -> None:
    z = np.zeros((10, 10))
    z[1, 5] = 1.0  # only one neighbour on the low-x side
    z[5, 5] = 0.5
    s = find_summits(z, (1.0, 1.0), rule="thesis")
    assert list(zip(s.i.tolist(), s.j.tolist(), strict=True)) == [(5, 5)]
    s8 = find_summits(z, (1.0, 1.0), rule="8-neighbour")
    assert (1, 5) in set(zip(s8.i.tolist(), s8.j.tolist(), strict=True))


def test_plateau_is_excluded_and_counted() -> None:
    z = np.zeros((10, 10))
    z[4, 4] = z[4, 5] = 1.0  # two equal tops
    s = find_summits(z, (1.0, 1.0))
    assert s.count == 0
    assert s.n_plateau == 2


def test_kappa_is_negative_at_every_summit() -> None:
    z = np.random.default_rng(7).normal(size=(60, 60))
    s = find_summits(z, (1e-6, 1e-6))
    assert s.n_excluded_flat == 0
    assert np.all(s.radius_m > 0.0)
    i, j = s.i, s.j
    kappa = 0.5 * (z[i + 1, j] + z[i - 1, j] + z[i, j + 1] + z[i, j - 1] - 4 * z[i, j]) / 1e-12
    np.testing.assert_allclose(s.radius_m, -1.0 / kappa)


def test_density_and_surface_wrapper() -> None:
    z = np.random.default_rng(1).normal(size=(20, 25))
    surf = Surface(heights_m=z, physical_size_m=(2e-3, 5e-3))
    s = summits_of(surf)
    assert s.area_m2 == pytest.approx(1e-5)
    assert s.density_per_m2 == pytest.approx(s.count / 1e-5)


def test_small_grid_and_bad_input() -> None:
    assert find_summits(np.zeros((4, 40)), (1.0, 1.0)).count == 0
    with pytest.raises(SurfaceError, match="unknown summit rule"):
        find_summits(np.zeros((9, 9)), (1.0, 1.0), rule="4-neighbour")
    with pytest.raises(SurfaceError, match="grid spacing"):
        find_summits(np.zeros((9, 9)), (0.0, 1.0))

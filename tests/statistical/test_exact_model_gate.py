"""The gate passes a model that is exact (issue 29: "validate on synthetic maps of known statistics").

Crops of a periodic Gaussian self-affine map (H = 0.8, the map of ``benchmarks/holdout_gaussian_maps.py``) are
scans whose random-phase model is exact.  A gate that can never say "credible" to the truth is no gate: since the
summit check and the held-out test became Monte Carlo rank tests (docs/statistical_contact.md §0a, §0e) two
pooled 512² crops are credible, and one crop is refused by nothing (undecided only because one 512² map cannot
detect a factor 2 in σ_μ).  Slow tier (about 30 s per analysis on 2 cores); the same cases over six maps are
``python benchmarks/gate_gaussian_scans.py``."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.pipeline import analyse_scans

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "benchmarks"))
from holdout_gaussian_maps import SPACING_M, gaussian_map

pytestmark = pytest.mark.slow
N = 512


def _scans(tmp_path: Path, seed: int, corners: list[tuple[int, int]]) -> list[Path]:
    whole = gaussian_map(1700, seed)
    paths = []
    for k, (i, j) in enumerate(corners):
        path = tmp_path / f"crop{k}.npy"
        np.save(path, whole[i:i + N, j:j + N])
        paths.append(path)
    return paths


def _analyse(paths: list[Path]):  # type: ignore[no-untyped-def]
    return analyse_scans(paths, "brake-pad", config=AnalysisConfig(seed=1, surrogate="phase"),
                         physical_size_m=(N * SPACING_M, N * SPACING_M), height_unit="m", workers=2).analysis


def test_two_crops_of_a_gaussian_map_are_credible_under_their_exact_model(tmp_path: Path) -> None:
    a = _analyse(_scans(tmp_path, 1, [(0, 0), (600, 600)]))
    assert a.credibility.status == "credible", [r.message for r in a.credibility.reasons]
    assert a.holdout is not None and a.holdout.detectable_scatter_ratio <= 2.0


def test_one_crop_is_refused_by_nothing_but_its_power(tmp_path: Path) -> None:
    a = _analyse(_scans(tmp_path, 1, [(0, 0)]))
    assert [r.code for r in a.credibility.reasons] == ["holdout-undecided"], a.credibility.reasons
    assert a.holdout is not None and "scans of this size" in a.holdout.reason
    assert a.surrogate_check.decided(int(a.ensemble.contact_area_m2.shape[0]), looks=a.config.summit_looks) == ([], [])

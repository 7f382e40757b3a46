"""The verdict on a shared file does not move with the seed (issue 29, acceptance: "the verdict on each shared
file is identical for 10 seeds (or undecided for all)"): over seeds 1–10 every status is the same.

The shipped al3d-1 runs at the defaults (R = 100, the summit check growing to 3200 by its work budget, K = 10):
there its summit check decides for every seed that the random-phase surrogates fail (docs/statistical_contact.md
§0a).  At R = 40 it does not — the map's own largest |z| depends on 40 draws through their median and MAD, and
one seed passed it at 40 (§0e) — so the small ensemble is kept for the larger maps only, where the analyses cost
minutes each.  Slow tier; run with ``pytest -m slow -s tests/statistical/test_verdict_stability.py``."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import pytest

from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.pipeline import analyse_scans

pytestmark = pytest.mark.slow

#: The rough shared files the preparation accepts, with the pairing whose μ is physical on them (§5), and the
#: ensemble (R, K long surfaces): the defaults on the shipped map, R = 40 and K = 4 on the larger ones.
FILES = {"al3d-1.al3d": ("brake-pad", 100, 10), "x3p-2.x3p": ("dc04", 40, 4), "opd-1.opd": ("dc04", 40, 4),
         "plu-1.plu": ("dc04", 40, 4), "sur-2.sur": ("dc04", 40, 4), "mnt-1.mnt": ("dc04", 40, 4)}
SEEDS = range(1, 11)


@pytest.mark.parametrize("name", list(FILES))
def test_the_status_is_the_same_for_ten_seeds(name: str, shared_file: Callable[[str], Path]) -> None:
    path = shared_file(name)
    material, realizations, long_surfaces = FILES[name]
    statuses = []
    for seed in SEEDS:
        run = analyse_scans([path], material, fill_undefined=True, workers=2,
                            config=AnalysisConfig(realizations=realizations, long_surfaces=long_surfaces, seed=seed))
        statuses.append(run.analysis.credibility.status)
        codes = sorted(r.code for r in run.analysis.credibility.reasons)
        grown = int(run.analysis.ensemble.contact_area_m2.shape[0])
        print(f"verdict {name} seed {seed}: {statuses[-1]} {codes} realisations {grown}")  # the docs' table (-s)
    assert len(set(statuses)) == 1, f"{name}: {statuses}"

"""Figures are written as PNG files (thesis Fig. 3.7–3.11)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stochfric.contact.asperity import asperity_contact
from stochfric.contact.figures import write_contact_figures
from stochfric.contact.materials import get_material
from stochfric.surface.figures import write_surface_figures
from stochfric.surface.io import Surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of

PNG = b"\x89PNG\r\n\x1a\n"


def test_surface_and_contact_figures(tmp_path: Path) -> None:
    z = np.random.default_rng(2).normal(size=(60, 50)) * 1e-6
    s = Surface(heights_m=z, physical_size_m=(6e-4, 5e-4))
    fine, coarse = prepare(s, Preparation(median_radius=1, step=2))
    fs, cs = summits_of(fine), summits_of(coarse)
    paths = write_surface_figures(
        tmp_path / "fig", fine=fine, coarse=coarse, fine_summits=fs, coarse_summits=cs, step=2
    )
    res = asperity_contact(coarse, cs, get_material("brake-pad"))
    paths += write_contact_figures(tmp_path / "fig", [res])
    names = sorted(p.name for p in paths)
    assert names == ["contact.png", "fine_vs_coarse.png", "pdfs.png", "surface.png"]
    for p in paths:
        data = p.read_bytes()
        assert data[:8] == PNG
        assert len(data) > 10_000

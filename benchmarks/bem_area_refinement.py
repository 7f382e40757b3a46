"""Grid convergence of the boundary-element contact area: the pixel count against the perimeter-corrected
area (Yastrebov et al. 2017; docs/bem_validation.md §4) on refined grids.

* synthetic: periodic Gaussian self-affine maps (H = 0.8, λ_s = 4 px, 256²), refined ×2 and ×3 by
  zero-padding their spectrum (exact for a band-limited map: the refined map is the same surface), at
  A/A_nom ≈ 1 % and 4 %;
* measured: the shipped surface al3d-1 (200 × 296, its border frame lowered), refined ×2 and ×3 by cubic
  splines (the data do not define the surface between the pixels: the refined map is one interpolation of
  it), at 1.32, 3.0 and 6.65 MPa with the brake pad (GW's A/A_nom ≈ 1.5, 3.5, 8.4 %, docs/surface_contact.md).

Run: ``python benchmarks/bem_area_refinement.py`` (about 3 min on one core).
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
from stochfric.contact.bem import BemSettings, BemSolution, bem_contact
from stochfric.contact.halfspace import framed_and_refined
from validate_bem_kappa import rms_gradient, self_affine_map

SHARED = Path(__file__).resolve().parents[2] / "shared" / "data" / "topographies"


def spectral_refine(h: np.ndarray, k: int) -> np.ndarray:
    """The periodic band-limited map ``h`` on a k × finer grid (its DFT zero-padded; the Nyquist row and column
    are left out, which a map with λ_s = 4 px does not hold)."""
    n0, n1 = h.shape
    spec = np.fft.fft2(h)
    out = np.zeros((n0 * k, n1 * k), dtype=complex)
    a, b = n0 // 2, n1 // 2
    out[:a, :b], out[:a, -b:], out[-a:, :b], out[-a:, -b:] = spec[:a, :b], spec[:a, -b:], spec[-a:, :b], spec[-a:, -b:]
    return np.asarray(np.fft.ifft2(out).real * k * k)


def line(label: str, k: int, sol: BemSolution) -> str:
    pix = " ".join(f"{v:.5f}" for v in sol.area_fraction)
    cor = " ".join(f"{v:.5f}" for v in sol.corrected_area_fraction)
    return f"| {label} | ×{k} | {pix} | {cor} |"


def main() -> None:
    t0 = time.perf_counter()
    print("| map | grid | A/A_nom pixel count | A/A_nom corrected |\n|---|---|---|---|")
    size = 1e-4
    for seed in (0, 1):
        h0 = self_affine_map(256, hurst=0.8, size_m=size, short_wavelength_m=4 * size / 256, seed=seed)
        p = np.array([0.01, 0.04]) * 1e9 * rms_gradient(h0, (size, size)) / 2
        for k in (1, 2, 3):
            sol = bem_contact(spectral_refine(h0, k), (size, size), 1e9, p, settings=BemSettings(time_limit_s=3000))
            print(line(f"synthetic seed {seed}", k, sol), flush=True)
    from stochfric.contact.materials import get_material
    from stochfric.surface.scans import load_scan

    scan = load_scan(SHARED / "al3d-1.al3d", fill_undefined=True)
    mat = get_material("brake-pad")
    p = np.array([1.32e6, 3.0e6, 6.65e6])
    framed = framed_and_refined(np.asarray(scan.fine.heights_m), 2, 1)
    for k in (1, 2, 3):
        sol = bem_contact(framed_and_refined(framed, 0, k), scan.fine.physical_size_m, mat.e_star_pa, p,
                          settings=BemSettings(time_limit_s=3000))
        print(line("al3d-1", k, sol), flush=True)
    print(f"\ntotal {time.perf_counter() - t0:.0f} s")


if __name__ == "__main__":
    main()

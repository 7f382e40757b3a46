"""Small-load area slope κ of the BEM (stochfric.contact.bem) on synthetic self-affine maps.

At small nominal pressure p the real contact area of a randomly rough surface grows linearly,
A_c / A_nom = κ p / (E* ḡ), with ḡ the rms gradient of the heights.  Boundary-element results
for Gaussian self-affine surfaces give κ ≈ 2 (Prodanov, Dapp & Müser, Tribol. Lett. 53 (2014)
433; Müser et al., Tribol. Lett. 65 (2017) 118), approached as the discretisation is refined;
Persson's theory gives √(8/π) ≈ 1.60.

The maps: periodic, square, random phases with deterministic amplitudes, isotropic power
spectrum C(q) ∝ q^{−2(1+H)} between the roll-off q_r and the short cutoff q_s, flat (roll-off
plateau) from the longest wavelength L down to q_r, zero above q_s.  ḡ² = ⟨|∇h|²⟩ is computed
spectrally (Parseval: ḡ² = Σ_q q²|ĥ_q|² / (nx·ny)² with ĥ the unnormalised DFT, see
:func:`rms_gradient`).  Pressures are chosen from the expected κ = 2 so that A_c/A_nom is about
1 %, 2 % and 4 % (override with ``--fractions``).

Two sequences, for H = 0.3, 0.5, 0.8:

* ``fixed-pixels``: the short cutoff λ_s at a fixed number of pixels (``--ppw``, default 4) and
  L/λ_r = 2 (roll-off at half the box, ``--rolloff``), grids 64, 128, 256, 512: the bandwidth
  λ_r/λ_s grows with the grid at constant discretisation;
* ``fixed-physics``: λ_s = L/16 fixed in physical units, grids 64 … 512 (4 … 32 points per
  λ_s): the same spectrum refined, which shows the discretisation trend.

Three seeds per map (``--seeds``); the per-map lines come first, then mean ± sd over the seeds.
Run ``python benchmarks/validate_bem_kappa.py`` (about 5 min on 2 cores) or ``--quick``
(< 1 min: H = 0.8, grids 64 and 128, one seed); ``--json FILE`` writes every number.  The
tables in docs/bem_validation.md come from the full run.
"""

from __future__ import annotations

import argparse
import json
import time
from dataclasses import asdict, dataclass
from pathlib import Path

import numpy as np
import numpy.typing as npt

from stochfric.contact.bem import BemSettings, bem_contact

FloatArray = npt.NDArray[np.float64]

#: Expected small-load slope (BEM, Prodanov et al. 2014; Müser et al. 2017).
KAPPA_EXPECTED = 2.0


def self_affine_map(
    n: int,
    *,
    hurst: float,
    size_m: float = 1e-4,
    rolloff_wavelength_m: float | None = None,
    short_wavelength_m: float,
    rms_height_m: float = 1e-6,
    seed: int = 0,
) -> FloatArray:
    """A periodic n × n Gaussian self-affine height map [m] of side ``size_m`` [m].

    Random phases (drawn from the DFT of real white noise, so Hermitian by construction),
    deterministic amplitudes √C(q): C ∝ q^{−2(1+H)} for q_r ≤ |q| ≤ q_s, C = C(q_r) for
    2π/L ≤ |q| < q_r, 0 for |q| > q_s and at q = 0.  ``rolloff_wavelength_m`` defaults to L/2.
    Scaled to ``rms_height_m``.
    """
    lam_r = size_m / 2 if rolloff_wavelength_m is None else rolloff_wavelength_m
    q_r, q_s = 2 * np.pi / lam_r, 2 * np.pi / short_wavelength_m
    q1 = 2 * np.pi * np.fft.fftfreq(n, d=size_m / n)
    q = np.hypot(q1[:, None], q1[None, :])
    amp = np.zeros_like(q)
    band = (q > 0) & (q <= q_s * (1 + 1e-12))
    amp[band] = np.maximum(q[band], q_r) ** (-(1 + hurst))
    phase = np.angle(np.fft.fft2(np.random.default_rng(seed).standard_normal((n, n))))
    h = np.fft.ifft2(amp * np.exp(1j * phase)).real
    return np.asarray(h * rms_height_m / h.std())


def rms_gradient(h: FloatArray, size_m: tuple[float, float]) -> float:
    """ḡ = √⟨|∇h|²⟩ [1] of a periodic map, spectrally: ⟨|∇h|²⟩ = Σ_q q² |ĥ_q|² / (nx·ny)² with
    ĥ = fft2(h) (Parseval for the trigonometric interpolant; the Nyquist modes count with their
    |q|)."""
    nx, ny = h.shape
    qx = 2 * np.pi * np.fft.fftfreq(nx, d=size_m[0] / nx)
    qy = 2 * np.pi * np.fft.fftfreq(ny, d=size_m[1] / ny)
    q2 = qx[:, None] ** 2 + qy[None, :] ** 2
    hq = np.fft.fft2(h)
    return float(np.sqrt(np.sum(q2 * np.abs(hq) ** 2) / (nx * ny) ** 2))


@dataclass(frozen=True)
class KappaRow:
    """κ of one map at a few pressures."""

    sequence: str
    hurst: float
    grid: int
    points_per_short_wavelength: float
    size_over_short_wavelength: float
    seed: int
    area_fraction: list[float]
    kappa: list[float]
    iterations: list[int]
    corrected_kappa: list[float]
    seconds: float


def kappa_of_map(
    h: FloatArray,
    size_m: float,
    *,
    e_star_pa: float = 1e9,
    fractions: tuple[float, ...] = (0.01, 0.02, 0.04),
    solver: str = "tamaas",
    tolerance: float = 1e-8,
) -> tuple[FloatArray, FloatArray, list[int], float, FloatArray]:
    """κ = (A_c/A_nom) E* ḡ / p at pressures aimed at the area ``fractions`` (κ = 2 assumed);
    returns (area fractions, κ, iterations, seconds, κ of the perimeter-corrected area)."""
    g = rms_gradient(h, (size_m, size_m))
    p = np.asarray(fractions) * e_star_pa * g / KAPPA_EXPECTED
    t0 = time.perf_counter()
    sol = bem_contact(
        h, (size_m, size_m), e_star_pa, p, settings=BemSettings(solver=solver, tolerance=tolerance, time_limit_s=600)
    )
    dt = time.perf_counter() - t0
    kappa = sol.area_fraction * e_star_pa * g / p
    corrected = sol.corrected_area_fraction * e_star_pa * g / p
    return sol.area_fraction, kappa, [int(v) for v in sol.iterations], dt, corrected


def run(
    hursts: tuple[float, ...],
    grids: tuple[int, ...],
    *,
    ppw: float = 4.0,
    physical_short: int = 16,
    rolloff: float = 2.0,
    sequences: tuple[str, ...] = ("fixed-pixels", "fixed-physics"),
    seeds: tuple[int, ...] = (0,),
    fractions: tuple[float, ...] = (0.01, 0.02, 0.04),
    solver: str = "tamaas",
) -> list[KappaRow]:
    """Both sequences (see the module docstring) for every H, grid and seed."""
    size = 1e-4
    rows: list[KappaRow] = []
    for hurst in hursts:
        for sequence in sequences:
            for n in grids:
                lam_s = ppw * size / n if sequence == "fixed-pixels" else size / physical_short
                for seed in seeds:
                    h = self_affine_map(
                        n, hurst=hurst, size_m=size, rolloff_wavelength_m=size / rolloff, short_wavelength_m=lam_s,
                        seed=seed,
                    )  # fmt: skip
                    af, kappa, its, dt, kc = kappa_of_map(h, size, fractions=fractions, solver=solver)
                    rows.append(
                        KappaRow(
                            sequence=sequence, hurst=hurst, grid=n, points_per_short_wavelength=lam_s * n / size,
                            size_over_short_wavelength=size / lam_s, seed=seed, area_fraction=[float(v) for v in af],
                            kappa=[float(v) for v in kappa], iterations=its, seconds=dt,
                            corrected_kappa=[float(v) for v in kc],
                        )
                    )  # fmt: skip
                    print(_line(rows[-1]), flush=True)
    return rows


def _line(r: KappaRow) -> str:
    ks = "  ".join(
        f"{a * 100:5.2f}%:{k:5.3f}/{c:5.3f}"
        for a, k, c in zip(r.area_fraction, r.kappa, r.corrected_kappa, strict=True)
    )
    return (
        f"| {r.sequence:13s} | {r.hurst:3.1f} | {r.grid:4d} | {r.points_per_short_wavelength:5.1f} | "
        f"{r.size_over_short_wavelength:6.1f} | {r.seed} | {ks} | {r.seconds:6.2f} |"
    )


HEADER = (
    "| sequence      | H   | grid | px/λs | L/λs   | seed | A/A_nom : κ pixels / κ corrected           | s      |\n"
    "|---------------|-----|------|-------|--------|------|--------------------------------------------|--------|"
)


def summary(rows: list[KappaRow], *, corrected: bool = False) -> str:
    """Mean ± standard deviation of κ over the seeds, per sequence, H and grid, at each pressure
    (``corrected``: κ of the perimeter-corrected area, Yastrebov et al. 2017)."""
    what = "corrected κ" if corrected else "κ (pixels)"
    out = [
        f"| sequence      | H   | grid | px/λs | L/λs  | seeds | {what} at A/A_nom ≈ targets (mean ± sd) | s (mean) |",
        "|---------------|-----|------|-------|-------|-------|-------------------------------------------|----------|",
    ]
    keys = sorted({(r.sequence, r.hurst, r.grid) for r in rows}, key=lambda k: (k[0], k[1], k[2]))
    for seq, hurst, grid in keys:
        group = [r for r in rows if (r.sequence, r.hurst, r.grid) == (seq, hurst, grid)]
        k = np.array([r.corrected_kappa if corrected else r.kappa for r in group])
        a = np.array([r.area_fraction for r in group])
        cells = "  ".join(
            f"{am * 100:4.1f}%: {km:4.2f}±{ks:4.2f}" for am, km, ks in zip(a.mean(0), k.mean(0), k.std(0), strict=True)
        )
        r0, sec = group[0], float(np.mean([r.seconds for r in group]))
        out.append(
            f"| {seq:13s} | {hurst:3.1f} | {grid:4d} | {r0.points_per_short_wavelength:5.1f} | "
            f"{r0.size_over_short_wavelength:5.0f} | {len(group):5d} | {cells} | {sec:8.2f} |"
        )
    return "\n".join(out)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="H = 0.8, grids 64 and 128 (< 1 min)")
    ap.add_argument("--hurst", type=float, nargs="+", default=[0.3, 0.5, 0.8])
    ap.add_argument("--grids", type=int, nargs="+", default=[64, 128, 256, 512])
    ap.add_argument("--rolloff", type=float, default=2.0, help="L / λ_r (roll-off wavelength)")
    ap.add_argument("--ppw", type=float, default=4.0, help="points per short wavelength (fixed-pixels sequence)")
    ap.add_argument("--seeds", type=int, nargs="+", default=[0, 1, 2])
    ap.add_argument("--fractions", type=float, nargs="+", default=[0.01, 0.02, 0.04])
    ap.add_argument("--solver", default="tamaas")
    ap.add_argument(
        "--sequences", nargs="+", default=["fixed-pixels", "fixed-physics"], choices=["fixed-pixels", "fixed-physics"]
    )
    ap.add_argument("--json", type=Path, default=None)
    args = ap.parse_args()
    hursts, grids, seeds = tuple(args.hurst), tuple(args.grids), tuple(args.seeds)
    if args.quick:
        hursts, grids, seeds = (0.8,), (64, 128), (0,)
    t0 = time.perf_counter()
    print(HEADER)
    rows = run(
        hursts, grids, ppw=args.ppw, rolloff=args.rolloff, seeds=seeds, fractions=tuple(args.fractions),
        solver=args.solver, sequences=tuple(args.sequences),
    )  # fmt: skip
    print("\n" + summary(rows))
    print("\n" + summary(rows, corrected=True))
    print(f"\ntotal {time.perf_counter() - t0:.1f} s; expected κ ≈ {KAPPA_EXPECTED} (BEM), √(8/π) = 1.596 (Persson)")
    if args.json:
        args.json.write_text(json.dumps([asdict(r) for r in rows], indent=1))


if __name__ == "__main__":
    main()

"""Is the map a plausible rough-surface measurement?  Lateral scale and embossed relief (issue 29, item 7).

Two checks of the rough-surface step of the preparation (:func:`stochfric.surface.preprocess.prepare_with_report`,
step 5), each returning a plain record for the preparation report; the preparation decides what to refuse
(docs/surface_contact.md, "Preparation", "Lateral scale and embossed relief").

**Lateral scale** (:func:`lateral_scale_verdict`).  Every number of the contact analysis that has a length in it
(summit density, radii, the plasticity index, the real contact area and so μ) scales with the pixel size; a
file whose lateral unit or size metadata is wrong gives results wrong by that factor, and nothing in the
heights says so.  Three rules, from what instruments can measure:

(a) *Field of view.*  Areal topography instruments (AFM / SPM, optical profilers — interferometric, confocal,
    focus variation —, stylus area scans) measure fields from about 100 nm (an AFM zoom) to at most a few
    hundred mm (stitched optical maps, stylus area scans of 200 mm, large Fizeau apertures).  A map whose
    larger side exceeds :data:`FIELD_MAX_M` = 1 m, or whose smaller side is below :data:`FIELD_MIN_M` = 1 nm
    (a few atomic spacings: even an atom-resolved STM image spans more), is not a surface measurement: its
    lateral unit or size metadata is wrong.  Refused.
(b) *Instrument.*  Where the file format belongs to scanning-probe microscopes only (:data:`SPM_READERS`, the
    reader SurfaceTopography chose, ``surface.info["reader"]``), the field cannot exceed the scanner's range:
    piezo scanners of commercial AFMs reach 90 … 150 µm (about 200 µm at most).  A side above
    :data:`SPM_FIELD_MAX_M` = 1 mm (5 × that) is a metadata error.  Refused.  The vendor names
    SurfaceTopography reads (``info["instrument"]``: e.g. "Alicona Imaging", "Digital Surf") do not say the
    measuring principle and :func:`~stochfric.surface.io.read_surface` does not keep them; they are not used.
    Formats that can hold any instrument's data (Gwyddion, Igor IBW, WSxM, BCR/SDF, NumPy, text) and the
    nano-measuring machine (NMM, an AFM on a 25 mm stage) are left out.
(c) *Heights against the pixel size.*  The RMS gradient Sdq (ISO 25178-2) at the pixel scale, from finite
    differences of the form-removed map, lies between about 10⁻³ and 1 for measured rough engineering
    surfaces (hundreds of topographies: Jacobs, Junge & Pastewka, Surf. Topogr. Metrol. Prop. 5, 013001
    (2017); the contact-mechanics challenge, Müser et al., Tribol. Lett. 65, 118 (2017): Sdq ≈ 1 at the
    smallest scale; the shared files: 1.4·10⁻³ … 0.09).  At a pixel above :data:`SLOPE_PIXEL_MIN_M` = 100 µm
    even optical flats and polished wafers reach ~10⁻⁵ (their noise and figure); an Sdq below
    :data:`SLOPE_MIN` = 10⁻⁵ there means a pixel size implausibly large for the heights (a lateral unit read
    10³ … 10⁶ too large).  Warned (code ``implausible-pixel-size``), not refused: a very smooth surface
    measured with a coarse pixel cannot be excluded from the numbers alone.

**Embossed relief** (:func:`relief_verdict`).  A coin, an engraved or embossed part, a lithographic pattern is
a designed relief on a smooth field, not a statistically homogeneous rough surface: the summit statistics of
the contact analysis (one Gaussian population of asperities over the whole map) do not describe it.  The
discriminator is the *stationarity of the local roughness*: the map is cut into square tiles
(:func:`tile_sq`), each tile's plane is removed and its Sq taken.  For a stationary random field the tile
Sq's scatter only by sampling — Sq² of a tile with k independent degrees of freedom is σ² χ²ₖ / k, so the ratio
of the 90 % to the 10 % quantile of the tile Sq is √(χ²ₖ,₀.₉ / χ²ₖ,₀.₁) = 4.7 for k = 2 and 13 only for k = 1,
a tile no larger than one correlation area; the per-tile plane leaves in a tile only wavelengths shorter than
the tile, so k is larger.  A relief has tiles on its smooth field (Sq = the micro-roughness) next to tiles
with its steep edges or smooth bumps (Sq = a fraction of the relief height): the ratio is about
0.4 × relief height / micro-roughness (34 … 85 for a 30 µm relief on 0.2 µm
roughness).  Refused when the ratio exceeds :data:`RELIEF_RATIO` = 10.  Measured (docs/surface_contact.md):
the six rough shared files 1.42 … 3.37 (a factor 3 below the limit), synthetic stationary Gaussian and
self-affine maps 1.1 … 3.5 (7.4 once, a noise-free Gaussian-smoothed field two correlation lengths across),
strongly non-Gaussian rough maps (lognormal up to skewness ±9, plateau-honed, truncated, pores, scratches,
particles) up to 6.8 at 128² and 3.6 at 512², synthetic coins 34 … 85.  Taking the 10 % and 90 % quantiles,
features on fewer than a tenth of the tiles (a few scratches, particles, pores) leave the ratio as it is.  Not
recognised: a close-up of a smooth relief that fills the whole field (no tile on the flat field: its tiles are
alike), and reliefs lower than about 25 times the micro-roughness.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from stochfric.arrays import FloatArray

__all__ = [
    "FIELD_MAX_M",
    "FIELD_MIN_M",
    "RELIEF_MIN_TILES",
    "RELIEF_QUANTILES",
    "RELIEF_RATIO",
    "RELIEF_TILES_PER_SIDE",
    "RELIEF_TILE_MIN_POINTS",
    "SLOPE_MIN",
    "SLOPE_PIXEL_MIN_M",
    "SPM_FIELD_MAX_M",
    "SPM_READERS",
    "lateral_scale_verdict",
    "relief_verdict",
    "rms_gradient",
    "tile_sq",
]

#: Largest side [m] of an areal topography measurement (rule a).
FIELD_MAX_M = 1.0
#: Smallest side [m] of an areal topography measurement (rule a).
FIELD_MIN_M = 1e-9
#: SurfaceTopography readers of formats written by scanning-probe microscopes only (rule b): Bruker / Veeco /
#: Digital Instruments Nanoscope, NT-MDT, Molecular Imaging, Park Systems, Nanosurf easyScan, JPK.
SPM_READERS: tuple[str, ...] = ("DIReader", "MDTReader", "MIReader", "PSReader", "EZDReader", "JPKReader")
#: Largest side [m] of a scanning-probe map: 5 × the largest piezo scanner range (rule b).
SPM_FIELD_MAX_M = 1e-3
#: Pixel size [m] above which a pixel-scale RMS gradient below :data:`SLOPE_MIN` is warned about (rule c).
SLOPE_PIXEL_MIN_M = 100e-6
#: Pixel-scale RMS gradient (Sdq) below which the pixel size is implausibly large for the heights (rule c).
SLOPE_MIN = 1e-5
#: Tiles of the relief rule: about this many along the shorter side ...
RELIEF_TILES_PER_SIDE = 16
#: ... but at least this many points wide (a tile Sq needs several correlation lengths of the finest
#: roughness), and at least 4 tiles along each side, else the rule is not applied.
RELIEF_TILE_MIN_POINTS = 16
RELIEF_MIN_TILES = 4
#: Quantiles of the tile Sq compared by the relief rule.
RELIEF_QUANTILES = (0.10, 0.90)
#: Ratio of the two quantiles above which the map is an embossed relief.
RELIEF_RATIO = 10.0


def rms_gradient(heights: npt.ArrayLike, spacing_m: tuple[float, float]) -> float:
    """Sdq (ISO 25178-2), the RMS gradient √(⟨(∂z/∂x)²⟩ + ⟨(∂z/∂y)²⟩) [-] from forward differences at the
    pixel scale; heights and spacing in the same unit."""
    z = np.asarray(heights, dtype=np.float64)
    gx = np.diff(z, axis=0) / spacing_m[0]
    gy = np.diff(z, axis=1) / spacing_m[1]
    return float(math.sqrt(float(np.mean(gx * gx)) + float(np.mean(gy * gy))))


def _fmt_len(v: float) -> str:
    """A length [m] in the unit that reads best (nm, µm, mm, m, km)."""
    for unit, f in (("km", 1e3), ("m", 1.0), ("mm", 1e-3), ("µm", 1e-6)):
        if abs(v) >= f:
            return f"{v / f:.4g} {unit}"
    return f"{v / 1e-9:.4g} nm"


def lateral_scale_verdict(
    form_removed: npt.ArrayLike, physical_size_m: tuple[float, float], *, reader: str | None = None,
    name: str = "the height map",
) -> dict[str, Any]:
    """Is the stated lateral size consistent with an instrument and with the heights (module doc, rules a–c)?

    ``form_removed``: the heights [m] after form removal; ``reader``: SurfaceTopography's reader class name
    (``surface.info["reader"]``) or None.  Returns ``{"plausible": bool, "reason": str | None, "warning":
    dict | None, …}``: ``plausible`` False (rules a, b) means refuse; ``warning`` is the coded warning of
    rule c (``implausible-pixel-size``).  The message says what is wrong and what to do.
    """
    z = np.asarray(form_removed, dtype=np.float64)
    nx, ny = z.shape
    lx, ly = float(physical_size_m[0]), float(physical_size_m[1])
    dx, dy = lx / nx, ly / ny
    sdq = rms_gradient(z, (dx, dy))
    pixel = max(dx, dy)
    stated = f"the stated size {_fmt_len(lx)} × {_fmt_len(ly)} (pixel size {_fmt_len(dx)} × {_fmt_len(dy)})"
    spm = reader in SPM_READERS
    reason = None
    if max(lx, ly) > FIELD_MAX_M or min(lx, ly) < FIELD_MIN_M:
        reason = (f"{stated} is not that of a surface measurement: areal topography instruments (AFM, optical "
                  f"profilers, confocal, stylus area scans) measure fields from ~100 nm to a few hundred mm "
                  f"(limits {_fmt_len(FIELD_MIN_M)} … {_fmt_len(FIELD_MAX_M)})")
    elif spm and max(lx, ly) > SPM_FIELD_MAX_M:
        reason = (f"{stated} is not that of a scanning-probe map: the file is a scanning-probe format ({reader}), "
                  f"whose piezo scanners cover at most ~150 µm (limit {_fmt_len(SPM_FIELD_MAX_M)})")
    if reader == "numpy":  # a plain matrix: the size is the one given with it
        fix = "the size given for the matrix is probably wrong: --size-um takes LX:LY in micrometres"
    else:
        fix = ("the file's lateral unit or size metadata is probably wrong: correct it in the instrument software, "
               "or export the heights as a matrix (.npy/.txt/.csv) and give the size explicitly (--size-um LX:LY "
               "--height-unit UNIT)")
    if reason is not None:
        reason = f"{reason}; {fix}"
    warning = None
    if pixel > SLOPE_PIXEL_MIN_M and sdq < SLOPE_MIN:
        warning = {
            "code": "implausible-pixel-size", "pixel_size_m": [dx, dy], "rms_gradient": sdq,
            "message": (f"{name}: pixel size {_fmt_len(dx)} × {_fmt_len(dy)} with an RMS gradient Sdq = {sdq:.3g} at "
                        f"the pixel scale, far below the 1e-3 … 1 of measured rough surfaces (limit {SLOPE_MIN:g} "
                        f"for pixels above {_fmt_len(SLOPE_PIXEL_MIN_M)}): the pixel size is implausibly large "
                        "for the heights. Summit density, radii, contact area and mu scale with the pixel "
                        "size and would be wrong by the same factor - check the lateral unit of the file "
                        "before blaming the material"),
        }  # fmt: skip
    return {
        "plausible": reason is None,
        "reason": reason,
        "warning": warning,
        "physical_size_m": [lx, ly],
        "pixel_size_m": [dx, dy],
        "rms_gradient": sdq,
        "reader": reader,
        "scanning_probe_format": spm,
        "limits": {"field_max_m": FIELD_MAX_M, "field_min_m": FIELD_MIN_M, "spm_field_max_m": SPM_FIELD_MAX_M,
                   "slope_min": SLOPE_MIN, "slope_pixel_min_m": SLOPE_PIXEL_MIN_M},
    }  # fmt: skip


def _tile_side(shape: tuple[int, int]) -> int:
    return max(RELIEF_TILE_MIN_POINTS, min(shape) // RELIEF_TILES_PER_SIDE)


def tile_sq(heights: npt.ArrayLike, side: int | None = None) -> FloatArray:
    """Sq of each square tile of ``side`` points (default: the relief rule's) after removing the tile's
    least-squares plane; the tiles cover the centre of the map (the remainder is split between the edges).
    Shape ``(tiles along x, tiles along y)``."""
    z = np.asarray(heights, dtype=np.float64)
    s = _tile_side(z.shape) if side is None else int(side)
    tx, ty = z.shape[0] // s, z.shape[1] // s
    if tx < 1 or ty < 1:
        return np.zeros((tx, ty))
    ox, oy = (z.shape[0] - tx * s) // 2, (z.shape[1] - ty * s) // 2
    t = z[ox : ox + tx * s, oy : oy + ty * s].reshape(tx, s, ty, s).transpose(0, 2, 1, 3).reshape(tx * ty, s * s)
    u = (np.arange(s, dtype=np.float64) - (s - 1) / 2) / s
    uu, vv = np.meshgrid(u, u, indexing="ij")
    design = np.stack([np.ones(s * s), uu.ravel(), vv.ravel()], axis=1)
    coef, *_ = np.linalg.lstsq(design, t.T, rcond=None)
    r = t - (design @ coef).T
    return np.asarray(np.sqrt(np.mean(r * r, axis=1)).reshape(tx, ty), dtype=np.float64)


def relief_verdict(
    form_removed: npt.ArrayLike, *, quantum_m: float | None = None, undefined_fraction: float = 0.0
) -> dict[str, Any]:
    """Is the form-removed map an embossed relief rather than a rough surface (module doc)?

    ``{"relief": bool, "reason": str | None, "tile_sq_ratio": float | None, …}``; ``tile_sq_ratio`` is the 90 %
    over the 10 % quantile of the tile Sq (:func:`tile_sq`), refused above :data:`RELIEF_RATIO`.  Each tile Sq
    is taken in quadrature with the quantisation noise q/√12 of ``quantum_m`` (a tile flat within one quantum is
    not resolved as flat).  Filled undefined points are smooth by construction (harmonic), so the lower quantile
    is moved up by ``undefined_fraction``; at more than 50 % filled, or with fewer than 4 tiles along a side,
    the rule is not applied (``checked`` False).
    """
    z = np.asarray(form_removed, dtype=np.float64)
    side = _tile_side(z.shape)
    tiles = tile_sq(z, side)
    lo_q, hi_q = RELIEF_QUANTILES
    low_quantile = lo_q + max(0.0, float(undefined_fraction))
    record: dict[str, Any] = {
        "relief": False, "reason": None, "checked": False, "tile_sq_ratio": None, "tile_side_points": side,
        "tiles": [int(tiles.shape[0]), int(tiles.shape[1])], "quantiles": [low_quantile, hi_q],
        "tile_sq_low_m": None, "tile_sq_high_m": None, "limit": RELIEF_RATIO,
    }  # fmt: skip
    if min(tiles.shape) < RELIEF_MIN_TILES or low_quantile >= 0.5:
        return record
    floor = (quantum_m or 0.0) / math.sqrt(12.0)
    sq = np.sqrt(tiles.ravel() ** 2 + floor * floor)
    low, high = (float(v) for v in np.quantile(sq, [low_quantile, hi_q]))
    ratio = high / low if low > 0 else math.inf
    record.update(checked=True, tile_sq_ratio=ratio if math.isfinite(ratio) else None, tile_sq_low_m=low,
                  tile_sq_high_m=high)  # fmt: skip
    if ratio > RELIEF_RATIO:
        record["relief"] = True
        shown = f"{ratio:.3g}" if math.isfinite(ratio) else "infinite"
        record["reason"] = (
            f"embossed relief or designed structure (a coin, an engraving, a pattern), not a statistically "
            f"homogeneous rough surface: the local roughness is not stationary - over {tiles.size} tiles of "
            f"{side}x{side} points the {100 * hi_q:g} % quantile of the tile Sq ({high:.3g} m) is {shown} times "
            f"the {100 * low_quantile:.3g} % quantile ({low:.3g} m), limit {RELIEF_RATIO:g} (rough surfaces give "
            "1.1 ... 7.4): a smooth field next to steep edges or bumps"
        )
    return record

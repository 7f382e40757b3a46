"""Scans as the analysis reads them: read, prepare, find summits, pool several onto one grid (method §1, §3).

The first steps of every pipeline of the package (``surface``, ``contact``, ``friction-process``):
:func:`load_scan` reads one instrument file (default: the shipped surface), prepares it as stated by a
:class:`~stochfric.surface.preprocess.Preparation` and finds the summits of the fine and the coarse
map; :func:`pool_scans` puts several prepared scans of one surface onto one grid (the same pixel size
within :data:`PIXEL_RTOL`, or resampled to the coarsest with ``resample``; cropped to the common size),
recording what it did.  SI units throughout.
"""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from stochfric.surface.grid import crop_surface, resample_surface
from stochfric.surface.io import Surface, SurfaceError, default_surface_path, read_surface
from stochfric.surface.preprocess import Preparation, PreparationReport, prepare_with_report
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, Summits, summits_of

__all__ = ["PIXEL_RTOL", "PooledScans", "PreparedScan", "load_scan", "pixel_size_spread", "pixel_sizes_agree",
           "pool_scans", "relabel_to_mean_pixel_size"]

#: Relative tolerance within which two scans' pixel sizes count as one when pooled: an instrument's lateral
#: calibration is uncertain by about 0.5–1 %, so two files of one measurement (or two scans of one
#: instrument) 0.1 % apart are one pixel size; they then get their mean pixel size without interpolation.
PIXEL_RTOL = 5e-3


def pixel_size_spread(spacings: Sequence[tuple[float, float]]) -> tuple[float, float]:
    """The relative spread (max − min)/min of the scans' pixel sizes along x and along y."""
    sp = np.asarray([[float(a), float(b)] for a, b in spacings], dtype=np.float64)
    if sp.size == 0:
        raise SurfaceError("no pixel size given")
    if not np.all(np.isfinite(sp)) or np.any(sp <= 0):
        raise SurfaceError(f"pixel sizes must be finite and > 0, got {sp.tolist()}")
    lo, hi = sp.min(axis=0), sp.max(axis=0)
    spread = (hi - lo) / lo
    return float(spread[0]), float(spread[1])


def pixel_sizes_agree(spacings: Sequence[tuple[float, float]], rtol: float = PIXEL_RTOL) -> bool:
    """True when the pixel sizes ``(Δx, Δy)`` [m] agree within ``rtol`` along each axis (relative spread
    (max − min)/min): one pixel size within the instrument's lateral calibration (:data:`PIXEL_RTOL`)."""
    if not (math.isfinite(float(rtol)) and float(rtol) >= 0):
        raise SurfaceError(f"the pixel-size tolerance must be a finite number >= 0, got {rtol!r}")
    return max(pixel_size_spread(spacings)) <= float(rtol)


def relabel_to_mean_pixel_size(surfaces: Sequence[Surface]) -> list[Surface]:
    """Every scan with its heights and the mean pixel size (its physical size relabelled, the old pixel size
    in ``info["pixel_size_relabelled_from"]``); a scan already at the mean is returned as it is."""
    spacings = [s.grid_spacing_m for s in surfaces]
    dx = float(np.mean([sp[0] for sp in spacings]))
    dy = float(np.mean([sp[1] for sp in spacings]))
    out = []
    for s in surfaces:
        if s.grid_spacing_m == (dx, dy):
            out.append(s)
            continue
        nx, ny = s.nb_grid_pts
        out.append(Surface(heights_m=s.heights_m, physical_size_m=(nx * dx, ny * dy), source=s.source,
                           n_undefined_filled=s.n_undefined_filled,
                           info={**s.info, "pixel_size_relabelled_from": list(s.grid_spacing_m)}))  # fmt: skip
    return out


@dataclass(frozen=True, kw_only=True, eq=False)
class PreparedScan:
    """One scan read and prepared: the raw, fine (prepared) and coarse (coarsened) maps, their
    summits, the preparation and its report (:func:`~stochfric.surface.preprocess.prepare_with_report`)."""

    path: Path
    default_surface: bool
    raw: Surface
    fine: Surface
    coarse: Surface
    fine_summits: Summits
    coarse_summits: Summits
    preparation: Preparation
    report: PreparationReport
    summit_rule: str
    fill_undefined: bool

    def record(self) -> dict[str, Any]:
        """The preparation record of the JSON outputs (file, checksum, reader, every setting, the report)."""
        return {
            "file": str(self.path),
            "default_surface": self.default_surface,
            "sha256": self.raw.info.get("sha256"),
            "reader": self.raw.info.get("reader"),
            **self.preparation.settings(),
            "detrend": self.report.form["applied"],
            "detrend_requested": self.preparation.detrend,
            "fill_undefined": self.fill_undefined,
            "n_undefined_filled": self.raw.n_undefined_filled,
            "summit_rule": self.summit_rule,
            "preparation_report": self.report.to_dict(),
        }

    def warnings(self) -> list[dict[str, Any]]:
        """The reading's and the preparation's warnings (``{"code", "message"}``), each message once."""
        seen: set[str] = set()
        out: list[dict[str, Any]] = []
        for w in [dict(x) for x in self.raw.info.get("warnings", [])] + [
            dict(x) for x in self.coarse.info.get("warnings", [])
        ]:
            if w["message"] not in seen:
                seen.add(w["message"])
                out.append(w)
        return out


def load_scan(
    path: str | os.PathLike[str] | None = None,
    *,
    preparation: Preparation | None = None,
    summit_rule: str = DEFAULT_SUMMIT_RULE,
    physical_size_m: tuple[float, float] | None = None,
    height_unit: str | None = None,
    fill_undefined: bool = False,
) -> PreparedScan:
    """Read ``path`` (default: the shipped surface), prepare it by ``preparation`` (default: the stated
    defaults) and find the summits of the fine and the coarse map by ``summit_rule``.

    ``physical_size_m`` and ``height_unit`` are needed for plain matrices (``.npy``, ``.txt``, ``.csv``);
    :class:`~stochfric.surface.io.SurfaceError` for a file that cannot be read or prepared.
    """
    prep = preparation if preparation is not None else Preparation()
    file = default_surface_path() if path is None else Path(path)
    raw = read_surface(file, physical_size_m=physical_size_m, height_unit=height_unit, fill_undefined=fill_undefined)
    fine, coarse, report = prepare_with_report(raw, prep)
    fine_summits = summits_of(fine, rule=summit_rule)
    coarse_summits = fine_summits if coarse is fine else summits_of(coarse, rule=summit_rule)
    return PreparedScan(
        path=file, default_surface=path is None, raw=raw, fine=fine, coarse=coarse, fine_summits=fine_summits,
        coarse_summits=coarse_summits, preparation=prep, report=report, summit_rule=summit_rule,
        fill_undefined=fill_undefined,
    )  # fmt: skip


@dataclass(frozen=True, kw_only=True, eq=False)
class PooledScans:
    """Prepared scans of one surface on one grid: the coarse maps the analysis reads (``surfaces``), the
    scans they came from, and what pooling did (``resampled_to_m``: the common pixel size where the scans
    were resampled; ``cropped_to``: the common grid where they were cropped)."""

    scans: tuple[PreparedScan, ...]
    surfaces: tuple[Surface, ...]
    resampled_to_m: tuple[float, float] | None = None
    cropped_to: tuple[int, int] | None = None
    warnings: list[dict[str, Any]] = field(default_factory=list)

    @property
    def name(self) -> str:
        """The scans' file stems joined by ``+``."""
        return "+".join(s.path.stem for s in self.scans)

    def records(self) -> list[dict[str, Any]]:
        """One preparation record per scan, with what pooling did to it."""
        out = []
        for s in self.scans:
            r = s.record()
            if self.resampled_to_m is not None:
                r["resampled_to_m"] = list(self.resampled_to_m)
            if self.cropped_to is not None:
                r["cropped_to"] = list(self.cropped_to)
            out.append(r)
        return out

    def record(self) -> dict[str, Any]:
        """The ``preparation`` entry of the JSON: the one scan's record, or ``{"scans": [...]}``."""
        records = self.records()
        return records[0] if len(records) == 1 else {"scans": records}


def pool_scans(scans: list[PreparedScan] | tuple[PreparedScan, ...], *, resample: bool = False) -> PooledScans:
    """Several prepared scans of one surface onto one grid (their coarse maps).

    The pixel sizes must agree within :data:`PIXEL_RTOL` unless ``resample`` (linear interpolation to the
    coarsest pixel size, :func:`~stochfric.surface.grid.resample_surface`); maps of different size are
    cropped to the common size (:func:`~stochfric.surface.grid.crop_surface`).  Both are recorded.
    """
    if not scans:
        raise SurfaceError("no scan given")
    warnings = [w for s in scans for w in s.warnings()]  # each scan's warnings, each message once per scan
    surfaces = [s.coarse for s in scans]
    if len(surfaces) == 1:
        return PooledScans(scans=tuple(scans), surfaces=tuple(surfaces), warnings=warnings)
    spacings = [s.grid_spacing_m for s in surfaces]
    target: tuple[float, float] | None = None
    if pixel_sizes_agree(spacings):  # one pixel size within the calibration: relabel, no interpolation
        surfaces = relabel_to_mean_pixel_size(surfaces)
    else:
        if not resample:
            listing = ", ".join(f"{s.path.name}: {sp[0] * 1e6:.4g}×{sp[1] * 1e6:.4g} µm"
                                for s, sp in zip(scans, spacings, strict=True))
            raise SurfaceError(f"pooled scans need one pixel size ({listing}); give --resample to resample them "
                               "to the coarsest, or prepare them with --step so that they match")
        target = (max(sp[0] for sp in spacings), max(sp[1] for sp in spacings))
        surfaces = [resample_surface(s, target) for s in surfaces]
    shape = (min(s.nb_grid_pts[0] for s in surfaces), min(s.nb_grid_pts[1] for s in surfaces))
    cropped: tuple[int, int] | None = None
    if any(s.nb_grid_pts != shape for s in surfaces):
        surfaces = [crop_surface(s, shape) for s in surfaces]
        cropped = shape
    return PooledScans(scans=tuple(scans), surfaces=tuple(surfaces), resampled_to_m=target, cropped_to=cropped,
                       warnings=warnings)

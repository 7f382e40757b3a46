"""A statistical contact analysis read back from its statistics file (``friction_process_statistics.nc``).

:meth:`~stochfric.process.analysis_result.StatisticalContactAnalysis.to_netcdf` (and ``stochfric
friction-process --out``, :meth:`~stochfric.process.pipeline.ScanAnalysis.write`) saves the analysis's
statistics: every array with its units and the checks' records as JSON attributes.  It does not save the
surrogate maps, the process model (that is ``friction_process.json``:
:func:`~stochfric.friction_process.model.load_process_model`) or the generated-process check, so the full
:class:`~stochfric.process.analysis_result.StatisticalContactAnalysis` cannot be rebuilt from it.
:class:`SavedAnalysis` is what the file holds, typed: the dataset, the settings
(:class:`~stochfric.process.analysis_config.AnalysisConfig`), the gate's verdict
(:class:`~stochfric.process.credibility.Credibility`), the records of the fits and checks (their ``to_dict``
forms), and the main statistics per approach as arrays under the analysis's names.
"""

from __future__ import annotations

import json
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Self

import numpy as np
import xarray as xr

from stochfric.arrays import FloatArray
from stochfric.io_utils import ResultFileError, read_netcdf, write_netcdf_atomic
from stochfric.process.analysis_config import AnalysisConfig
from stochfric.process.credibility import Credibility

__all__ = ["ANALYSIS_TITLE", "SavedAnalysis"]

#: How the ``title`` attribute of a saved analysis begins (:meth:`StatisticalContactAnalysis.to_dataset`).
ANALYSIS_TITLE = "stochfric statistical contact analysis"

#: The JSON attributes read into dictionaries (``None`` where the analysis did not have the check).
_RECORDS = ("fits", "ergodicity", "surrogate_check", "window_check", "scan_scatter", "copy_check", "holdout",
            "measured_windows", "model_intervals", "sources", "contact_fraction_fit")


class _Column:
    """A read-only attribute: the dataset variable of the attribute's name as a float array."""

    def __init__(self, doc: str) -> None:
        self.__doc__ = doc

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    def __get__(self, obj: SavedAnalysis | None, owner: type) -> FloatArray:
        if obj is None:
            raise AttributeError(self.name)
        return np.asarray(obj.dataset[self.name].values, dtype=np.float64)


@dataclass(frozen=True, kw_only=True, eq=False)
class SavedAnalysis:
    """The saved statistics of a statistical contact analysis (module docstring); SI units, arrays over the
    approach u.  ``dataset`` holds every array of the file; the records are the checks' ``to_dict`` forms
    (``window_check``, ``holdout``, ``measured_windows``, ``model_intervals`` ``None`` where not made)."""

    dataset: xr.Dataset
    config: AnalysisConfig
    seed_entropy: int
    material: dict[str, Any]
    surface_info: dict[str, Any]
    surrogate_choice: str
    credibility: Credibility
    fits: dict[str, Any]
    ergodicity: dict[str, Any]
    surrogate_check: dict[str, Any]
    window_check: dict[str, Any] | None
    scan_scatter: dict[str, Any]
    copy_check: dict[str, Any]
    holdout: dict[str, Any] | None
    measured_windows: dict[str, Any] | None
    model_intervals: dict[str, Any] | None
    sources: dict[str, str]
    contact_fraction_fit: dict[str, Any]
    window_shift_m: float
    window_length_m: float
    long_surface_length_m: float
    versions: dict[str, str]

    @classmethod
    def load(cls, path: str | Path) -> Self:
        """The statistics saved in ``path`` (``friction_process_statistics.nc``).  A missing file is a
        :class:`FileNotFoundError`, a file of another kind an :class:`~stochfric.errors.InputError`."""
        what = "statistical contact analysis (friction_process_statistics.nc of stochfric friction-process --out)"
        ds = read_netcdf(path, what)
        if not str(ds.attrs.get("title", "")).startswith(ANALYSIS_TITLE):
            raise ResultFileError(f"{path} is not a {what}; stochfric.load reads any saved result")
        return cls.from_dataset(ds, source=path)

    @classmethod
    def from_dataset(cls, ds: xr.Dataset, *, source: str | Path = "the dataset") -> Self:
        """The record of a dataset :meth:`StatisticalContactAnalysis.to_dataset` made (also after a NetCDF
        round trip)."""
        a = ds.attrs
        try:
            records = {k: json.loads(a[k]) for k in _RECORDS}
            cred = json.loads(a["credibility"])
            return cls(
                dataset=ds, config=AnalysisConfig(**json.loads(a["config"])), seed_entropy=int(a["seed_entropy"]),
                material=json.loads(a["material"]), surface_info=json.loads(a["surface"]),
                surrogate_choice=str(a["surrogate_choice"]),
                credibility=Credibility.from_dict(cred),
                window_shift_m=float(a["window_shift_m"]), window_length_m=float(a["window_length_m"]),
                long_surface_length_m=float(a["long_surface_length_m"]), versions=json.loads(a["versions"]),
                **records,
            )  # fmt: skip
        except (KeyError, TypeError, ValueError) as exc:
            raise ResultFileError(f"{source} is not a statistical contact analysis this stochfric reads ({exc!r}): "
                                  "run stochfric friction-process again") from None

    approach_m = _Column("The approaches u [m].")
    pressure_pa = _Column("Mean pressure p(u) of the path windows [Pa].")
    area_fraction = _Column("Mean A_c/A_nom of the path windows.")
    mu_mean = _Column("E[μ] along the path.")
    mu_std = _Column("σ_μ along the path.")
    mu_mean_se = _Column("Standard error of E[μ] over the long surfaces.")
    mu_std_se = _Column("Standard error of σ_μ over the long surfaces.")
    correlation_length_m = _Column("Integral correlation length S(0)/(4σ_μ²) [m], mean over the long surfaces.")
    correlation_length_se_m = _Column("Its standard error [m].")
    psd_level = _Column("Low-frequency level E[S] = S(f→0) of the one-sided PSD of μ̂ [m].")

    def __repr__(self) -> str:
        p = self.pressure_pa / 1e6
        mu = self.mu_mean
        verdict = "credible" if self.credibility.credible else f"NOT credible ({', '.join(self.credibility.codes())})"
        return (f"SavedAnalysis({self.config.surrogate} → {self.surrogate_choice or '?'} surrogates, "
                f"{self.config.realizations} realisations, seed {self.seed_entropy}: {p.size} approaches, "
                f"p {np.nanmin(p):.3g}…{np.nanmax(p):.3g} MPa, E[μ] {np.nanmin(mu):.3g}…{np.nanmax(mu):.3g}; "
                f"{verdict})")

    @property
    def credible(self) -> bool:
        """The gate's verdict (:mod:`stochfric.process.credibility`)."""
        return self.credibility.credible

    def to_dataset(self) -> xr.Dataset:
        """The dataset as read (units in the variables' attributes, provenance in the dataset's)."""
        return self.dataset

    def to_netcdf(self, path: str | Path) -> Path:
        """Write the dataset again, atomically."""
        return write_netcdf_atomic(path, self.dataset)

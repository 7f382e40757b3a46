"""Saved results back as typed objects: :func:`load` reads any file stochfric writes and tells its kind
from the metadata the writer stamped into it (not from the file's name).  File (writer) → type:

* ``simulation.nc`` (``stochfric simulate --out``, ``SimulationResult.to_netcdf``; ``simulation.json`` reads
  the ``.nc`` beside it) → :class:`~stochfric.oscillator.result.SimulationResult` (``metadata_json`` of schema
  ``stochfric.simulation/1``).
* ``<kind>.nc`` or ``<kind>.json`` (``stochfric study … --out``, ``StudyResult.save``) →
  :class:`~stochfric.studies.base.StudyResult` with the kind's typed summary (schema ``stochfric.study/2``).
* ``white_limit_<preset>.json`` or ``.nc`` (``stochfric white-limit --out``) →
  :class:`~stochfric.studies.white_limit.WhiteLimitResult` (``study = "white-limit"``; the per-run X_gh
  are not saved).
* the NetCDF of ``stochfric contact --output`` → :class:`~stochfric.contact.asperity.ContactResult`.
* ``friction_process_statistics.nc`` (``stochfric friction-process --out``) →
  :class:`~stochfric.process.saved.SavedAnalysis` (the saved statistics; the full analysis is not saved).
* ``friction_process.json`` (a process model's ``save``) → the friction-process model (``kind``
  ``tabulated`` or ``band_limited``, :func:`~stochfric.friction_process.model.load_process_model`).
* ``contact_models.json`` or ``contact_models_samples.nc`` (``stochfric contact-models --out``) →
  :class:`~stochfric.process.contact_models.ContactModelSpread` (``kind = "contact_model_spread"``; both
  files are read).
* ``assess.json`` (``stochfric assess --out``) → :class:`SavedAssessment` (schema ``stochfric.assess/1``).

Each type's own ``load(path)`` reads its kind only.  A missing path is a :class:`FileNotFoundError`; a
directory, a file stochfric did not write or one of a kind it does not know a
:class:`~stochfric.io_utils.ResultFileError` (a ``ValueError``) that names the path and the kinds it reads.
"""

from __future__ import annotations

import json
import os
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self, TypeAlias

import numpy as np

from ..arrays import FloatArray
from ..io_utils import HDF5_SIGNATURE, ResultFileError, read_json_file, result_file
from ..oscillator.machine import Machine

if TYPE_CHECKING:
    from ..contact.asperity import ContactResult
    from ..friction_process.model_base import FrictionProcessModel
    from ..oscillator.result import SimulationResult
    from ..process.contact_models import ContactModelSpread
    from ..process.saved import SavedAnalysis
    from .assess import ForceVerdict
    from .base import StudyResult
    from .white_limit import WhiteLimitResult


__all__ = ["KNOWN_RESULTS", "LoadedResult", "SavedAssessment", "load"]

#: The result files :func:`load` reads, one line each (the error for any other file lists them).
KNOWN_RESULTS = (
    "simulation (simulation.nc of stochfric simulate --out, SimulationResult.to_netcdf)",
    "study (<kind>.nc or <kind>.json of stochfric study … --out, StudyResult.save)",
    "white-limit study (white_limit_<preset>.json or .nc)",
    "contact result (the netCDF of stochfric contact --output)",
    "statistical contact analysis (friction_process_statistics.nc)",
    "friction-process model (friction_process.json)",
    "contact-model spread (contact_models.json or contact_models_samples.nc)",
    "assessment (assess.json)",
)


@dataclass(frozen=True, kw_only=True, eq=False)
class SavedAssessment:
    """An assessment read back from ``assess.json`` (:func:`~stochfric.studies.assess.assess`): the status,
    the reasons, the machine, the verdict per force and the first screen as written; the surface analysis as
    its JSON summary (``analysis``; the full analysis and the studies are the files in ``files``, each
    readable with :func:`load`)."""

    status: str
    reasons: list[str]
    forced: bool
    machine: Machine
    material: dict[str, Any]
    scans: list[str]
    approach_m: FloatArray | None
    risk_level: float
    forces: list[ForceVerdict]
    first_screen: list[str]
    analysis: dict[str, Any] | None
    studies: dict[str, Any]
    files: dict[str, str]
    versions: dict[str, str]

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Self:
        """The assessment saved in ``path`` (``assess.json``).  A missing file is a :class:`FileNotFoundError`,
        a file of another kind an :class:`~stochfric.errors.InputError`."""
        from .assess import ASSESS_SCHEMA, ForceVerdict

        what = "assessment (assess.json of stochfric assess --out)"
        d = read_json_file(path, what)
        if not isinstance(d, dict) or d.get("schema") != ASSESS_SCHEMA:
            found = d.get("schema") if isinstance(d, dict) else None
            raise ResultFileError(f"{path} is not an {what} of {ASSESS_SCHEMA}"
                                  + (f" but {found}" if found else "") + "; stochfric.load reads any saved result")
        try:
            forces = [ForceVerdict(**_tuples(f)) for f in d["forces"]]
            return cls(
                status=d["status"], reasons=list(d["reasons"]), forced=bool(d.get("forced", False)),
                machine=Machine.model_validate(d["machine"]), material=d["material"], scans=list(d["scans"]),
                approach_m=None if d["approach_m"] is None else np.asarray(d["approach_m"], dtype=np.float64),
                risk_level=float(d["risk_level"]), forces=forces, first_screen=list(d["first_screen"]),
                analysis=d["analysis"], studies=d["studies"], files=d["files"], versions=d.get("versions", {}),
            )  # fmt: skip
        except (KeyError, TypeError, ValueError) as exc:
            raise ResultFileError(f"{path} is not an {what} this stochfric reads ({exc!r})") from None

    @property
    def exit_code(self) -> int:
        """0 with a verdict, 3 otherwise (as the command's)."""
        return 0 if self.status == "verdict" else 3

    def __repr__(self) -> str:
        return (f"SavedAssessment({self.machine.name}: {self.status}, {len(self.forces)} force(s), "
                f"{len(self.reasons)} reason(s); scans {', '.join(self.scans)})")



def _tuples(record: dict[str, Any]) -> dict[str, Any]:
    """A JSON record with its lists as tuples (the intervals of a :class:`ForceVerdict`)."""
    return {k: tuple(v) if isinstance(v, list) else v for k, v in record.items()}

#: What :func:`load` returns: one of the types of the module docstring.
LoadedResult: TypeAlias = ("SimulationResult | StudyResult[Any] | WhiteLimitResult | ContactResult | SavedAnalysis"
                           " | FrictionProcessModel | ContactModelSpread | SavedAssessment")


def load(path: str | os.PathLike[str]) -> LoadedResult:
    """The typed result saved in ``path`` (module docstring: which file gives which type).  The kind is read
    from the file's stamped metadata, not from its name.  A missing path is a :class:`FileNotFoundError`;
    a directory or a file of another kind a :class:`~stochfric.io_utils.ResultFileError` naming the path
    and the kinds it reads."""
    p = result_file(path, "stochfric result")
    with p.open("rb") as fh:
        head = fh.read(len(HDF5_SIGNATURE))
    if head == HDF5_SIGNATURE:
        return _load_netcdf(p, path)
    data = read_json_file(p, "stochfric result (a NetCDF-4 or JSON file stochfric wrote)")
    if isinstance(data, dict):
        found = _load_json(p, data)
        if found is not None:
            return found
    raise ResultFileError(f"{path}: not a result stochfric knows: a JSON file without the stamp of one of its "
                          f"results; it reads {'; '.join(KNOWN_RESULTS)}")


def _attrs(p: Path, path: str | os.PathLike[str]) -> dict[str, str]:
    """The global attributes of a NetCDF-4 file as text, without reading its arrays."""
    import h5netcdf

    try:
        with h5netcdf.File(p, "r") as f:
            raw = dict(f.attrs)
    except (OSError, ValueError, KeyError) as exc:
        raise ResultFileError(f"{path}: cannot read it as a NetCDF-4 file ({exc})") from None
    return {str(k): v.decode() if isinstance(v, bytes) else str(v) for k, v in raw.items()}


def _load_netcdf(p: Path, path: str | os.PathLike[str]) -> LoadedResult:
    from ..contact.asperity import CONTACT_TITLE, ContactResult
    from ..oscillator.result import SCHEMA as SIMULATION_SCHEMA
    from ..oscillator.result import SimulationResult
    from ..process.contact_models import SPREAD_KIND, ContactModelSpread
    from ..process.saved import ANALYSIS_TITLE, SavedAnalysis
    from .base import StudyResult
    from .white_limit import WHITE_LIMIT, WhiteLimitResult

    a = _attrs(p, path)
    if "metadata_json" in a:
        try:
            schema = json.loads(a["metadata_json"]).get("schema")
        except (ValueError, AttributeError):
            schema = None
        if schema == SIMULATION_SCHEMA:
            return SimulationResult.load(p)
    study = a.get("study")
    if study == WHITE_LIMIT:
        return WhiteLimitResult.load(p)
    if study:
        return StudyResult.load(p, study)
    if a.get("kind") == SPREAD_KIND:
        return ContactModelSpread.load(p)
    title = a.get("title", "")
    if title == CONTACT_TITLE:
        return ContactResult.load(p)
    if title.startswith(ANALYSIS_TITLE):
        return SavedAnalysis.load(p)
    raise ResultFileError(f"{path}: not a result stochfric knows: a NetCDF file without the stamp of one of its "
                          f"results (title {title!r}); it reads {'; '.join(KNOWN_RESULTS)}")


def _load_json(p: Path, data: dict[str, Any]) -> LoadedResult | None:
    from ..friction_process.model import load_process_model
    from ..process.contact_models import SPREAD_KIND, ContactModelSpread
    from .assess import ASSESS_SCHEMA
    from .base import STUDY_SCHEMA, StudyResult
    from .white_limit import WHITE_LIMIT, WhiteLimitResult

    schema, kind = data.get("schema"), data.get("kind")
    if data.get("study") == WHITE_LIMIT:
        return WhiteLimitResult.load(p)
    if schema == STUDY_SCHEMA or (isinstance(schema, str) and schema.startswith("stochfric.study/")):
        return StudyResult.load(p, data.get("study") if isinstance(data.get("study"), str) else None)
    if schema == ASSESS_SCHEMA:
        return SavedAssessment.load(p)
    if kind == SPREAD_KIND:
        return ContactModelSpread.load(p)
    if kind in ("tabulated", "band_limited") and "schema_version" in data:
        return load_process_model(p)
    if {"x_gh", "t_gh", "integrator", "seed_entropy"} <= data.keys():  # simulation.json: the .nc holds the record
        from ..oscillator.result import SimulationResult

        nc = p.with_suffix(".nc")
        if not nc.is_file():
            raise FileNotFoundError(f"{p} is the JSON summary of a simulation; the result is {nc.name} beside it "
                                    f"(stochfric simulate --out writes both), and {nc} does not exist")
        return SimulationResult.load(nc)
    return None


"""Results of oscillator simulations: per-trajectory slip→stick data with provenance.

A :class:`SimulationResult` holds, for every parameter set ``i`` and run ``r``, the
slip→stick positions ``X_gh`` (dimensionless, ``x = y/L``) with their times, the stick
count ``M`` (number of slip→stick transitions in ``0 < τ ≤ τ_end``), optionally the
decimated trajectory, and diagnostics; plus the parameters, seed, integrator, friction
law, process model, warnings and package versions.  It converts to an
:class:`xarray.Dataset` (dimensions ``param_set``, ``run``, ``event``, ``time``) and
saves to NetCDF atomically; :meth:`SimulationResult.load` reads such a file back as the typed result
(:func:`load_result`: as the plain Dataset).
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, Self

import numpy as np
import numpy.typing as npt
import xarray as xr

from ..io_utils import ResultFileError, package_versions, read_netcdf, write_netcdf_atomic
from .parameters import OscillatorParameters

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

SCHEMA = "stochfric.simulation/1"


@dataclass(frozen=True)
class SimulationWarning:
    """A condition the user should know about, with an actionable message."""

    code: str
    message: str

    def to_dict(self) -> dict[str, str]:
        return {"code": self.code, "message": self.message}


@dataclass
class SimulationResult:
    """Ensemble result; arrays are indexed ``[param_set, run, ...]``.

    ``x_gh``/``t_gh`` are NaN-padded to ``max_events``; ``stick_count`` may exceed the
    stored events (a warning says so).  ``trajectory`` is ``[param_set, run, k, (τ, x1, x2)]``
    or ``None``.
    """

    params: list[OscillatorParameters]
    x_gh: npt.NDArray[np.float64]
    t_gh: npt.NDArray[np.float64]
    stick_count: npt.NDArray[np.int64]
    diagnostics: dict[str, npt.NDArray[np.float64]]
    trajectory: npt.NDArray[np.float64] | None
    model: str
    integrator: str
    dt: float
    tau_end: float
    runs: int
    seed_entropy: int
    path_coordinate: str
    x0: list[tuple[float, float]]
    laws: list[dict[str, Any]]
    sigma_zeta: list[float]
    process: dict[str, Any] | None
    warnings: list[SimulationWarning] = field(default_factory=list)
    settings: dict[str, Any] = field(default_factory=dict)
    versions: dict[str, str] = field(default_factory=package_versions)
    #: Further dataset attributes of the saved file (the command line adds the case's modes:
    #: ``white_intensity``, ``process_level``, …): kept by :meth:`load`, written again by :meth:`to_dataset`.
    attrs: dict[str, Any] = field(default_factory=dict)

    @property
    def n_param_sets(self) -> int:
        return len(self.params)

    def x_gh_list(self, param_set: int = 0) -> list[list[float]]:
        """The stored ``X_gh`` of every run of one parameter set, as plain lists."""
        out = []
        for r in range(self.runs):
            row = self.x_gh[param_set, r]
            out.append([float(v) for v in row[np.isfinite(row)]])
        return out

    def plot(self, param_set: int = 0) -> Figure:
        """The phase portrait of parameter set ``param_set`` (x2 over x1, 3-D with x3 = ητ for forced
        motion; :func:`~stochfric.oscillator.figures.figure_phase_portrait`) as a matplotlib figure; needs
        the trajectory (``save_trajectory=True``).  Save it with ``fig.savefig(path)``."""
        from .figures import figure_phase_portrait

        return figure_phase_portrait(self, param_set)

    def __repr__(self) -> str:
        x = self.x_gh[np.isfinite(self.x_gh)]
        stats = (f"E[X_gh] = {float(np.mean(x)):.4g}, σ(X_gh) = {float(np.std(x, ddof=1)):.3g}" if x.size > 1
                 else "no slip→stick transition")
        return (f"SimulationResult({self.model}, {self.integrator}, {len(self.params)} parameter set(s) × "
                f"{self.runs} run(s), τ_end = {self.tau_end:g}, Δτ = {self.dt:g}, seed {self.seed_entropy}: "
                f"M = {float(np.mean(self.stick_count)):.3g} transitions per run, {stats} (x = y/L); "
                f"{len(self.warnings)} warning(s))")

    def _run_record(self) -> dict[str, Any]:
        """How the runs were made: model, integrator, time grid, runs, seed, path coordinate."""
        return {"model": self.model, "integrator": self.integrator, "dt": self.dt, "tau_end": self.tau_end,
                "runs": self.runs, "seed_entropy": str(self.seed_entropy), "path_coordinate": self.path_coordinate}

    def metadata(self) -> dict[str, Any]:
        """Everything needed to reproduce the result (JSON-serialisable)."""
        return {
            "schema": SCHEMA,
            **self._run_record(),
            "x0": [list(x) for x in self.x0],
            "parameters": [p.to_dict() for p in self.params],
            "friction_law": self.laws,
            "sigma_zeta": self.sigma_zeta,
            "process": self.process,
            "settings": self.settings,
            "warnings": [w.to_dict() for w in self.warnings],
            "versions": self.versions,
        }

    def to_dataset(self) -> xr.Dataset:
        """Labelled arrays with units and provenance (ARCHITECTURE habit 6)."""
        npar, nrun, nev = self.x_gh.shape
        coords: dict[str, Any] = {
            "param_set": np.arange(npar),
            "run": np.arange(nrun),
            "event": np.arange(nev),
        }
        per_set = {
            "gamma0": [p.gamma0 for p in self.params],
            "n": [p.n for p in self.params],
            "damping_ratio": [p.damping_ratio for p in self.params],
            "q": [p.q for p in self.params],
            "eta": [p.eta for p in self.params],
            "omega0_rad_s": [p.omega0 for p in self.params],
            "normal_force_n": [
                np.nan if p.normal_force is None else p.normal_force for p in self.params
            ],
            "pressure_pa": [np.nan if p.pressure_pa is None else p.pressure_pa for p in self.params],
            "sigma_zeta": self.sigma_zeta,
        }
        for name, values in per_set.items():
            coords[name] = ("param_set", np.asarray(values, dtype=float))
        data: dict[str, Any] = {
            "x_gh": (("param_set", "run", "event"), self.x_gh,
                     {"long_name": "slip->stick position X_gh = y/L", "units": "1"}),
            "t_gh": (("param_set", "run", "event"), self.t_gh,
                     {"long_name": "dimensionless time of slip->stick tau = omega0 t",
                      "units": "1"}),
            "stick_count": (("param_set", "run"), self.stick_count,
                            {"long_name": "number M of slip->stick transitions", "units": "1"}),
        }
        for name, arr in self.diagnostics.items():
            data[name] = (("param_set", "run"), arr, {"units": "1"})
        if self.trajectory is not None:
            t = self.trajectory[0, 0, :, 0]
            coords["time"] = ("time", t, {"long_name": "tau = omega0 t", "units": "1"})
            data["x1"] = (("param_set", "run", "time"), self.trajectory[..., 1],
                          {"long_name": "x1 = y/L", "units": "1"})
            data["x2"] = (("param_set", "run", "time"), self.trajectory[..., 2],
                          {"long_name": "x2 = dx1/dtau", "units": "1"})
        ds = xr.Dataset(data_vars=data, coords=coords)
        ds.attrs["title"] = "stochfric friction-oscillator simulation"
        ds.attrs["metadata_json"] = json.dumps(self.metadata(), default=_json_default)
        ds.attrs["model"] = self.model
        ds.attrs["integrator"] = self.integrator
        ds.attrs["seed_entropy"] = str(self.seed_entropy)
        ds.attrs["path_coordinate"] = self.path_coordinate
        for key in ("white_increment", "white_stream"):  # every mode as a plain attribute
            ds.attrs[key] = str(self.settings.get(key, ""))
        for key, value in self.attrs.items():
            ds.attrs.setdefault(key, value)
        return ds

    def to_netcdf(self, path: str | Path) -> Path:
        """Write :meth:`to_dataset` to ``path`` (NetCDF-4 via h5netcdf), atomically."""
        ds = self.to_dataset()
        return write_netcdf_atomic(path, ds)

    @classmethod
    def load(cls, path: str | Path) -> Self:
        """The result saved in ``path`` (:meth:`to_netcdf`, or ``simulation.nc`` of ``stochfric simulate
        --out``): arrays, parameter sets, seed, laws, process, settings, warnings and versions as written;
        the attributes the command line adds go to :attr:`attrs`.  A missing file is a
        :class:`FileNotFoundError`; a file of another kind an :class:`~stochfric.errors.InputError`."""
        return cls.from_dataset(read_netcdf(path, f"simulation result ({SCHEMA}, simulation.nc)"), source=path)

    @classmethod
    def from_dataset(cls, ds: xr.Dataset, *, source: str | Path = "the dataset") -> Self:
        """The result :meth:`to_dataset` made ``ds`` from (inverse of it, also after a NetCDF round trip)."""
        meta = _metadata(ds, source)
        fields = set(OscillatorParameters.__dataclass_fields__)
        params = [OscillatorParameters(**{k: v for k, v in p.items() if k in fields}) for p in meta["parameters"]]
        trajectory = None
        if "x1" in ds:
            x1 = np.asarray(ds["x1"].values, dtype=np.float64)
            trajectory = np.empty((*x1.shape, 3))
            trajectory[..., 0] = np.asarray(ds["time"].values, dtype=np.float64)
            trajectory[..., 1] = x1
            trajectory[..., 2] = np.asarray(ds["x2"].values, dtype=np.float64)
        own = {"title", "metadata_json", "model", "integrator", "seed_entropy", "path_coordinate",
               "white_increment", "white_stream"}
        return cls(
            params=params,
            x_gh=np.asarray(ds["x_gh"].values, dtype=np.float64),
            t_gh=np.asarray(ds["t_gh"].values, dtype=np.float64),
            stick_count=np.asarray(ds["stick_count"].values, dtype=np.int64),
            diagnostics={str(name): np.asarray(v.values) for name, v in ds.data_vars.items()
                         if v.dims == ("param_set", "run") and name != "stick_count"},
            trajectory=trajectory, model=meta["model"], integrator=meta["integrator"], dt=meta["dt"],
            tau_end=meta["tau_end"], runs=meta["runs"], seed_entropy=int(meta["seed_entropy"]),
            path_coordinate=meta["path_coordinate"], x0=[(float(a), float(b)) for a, b in meta["x0"]],
            laws=meta["friction_law"], sigma_zeta=meta["sigma_zeta"], process=meta["process"],
            warnings=[SimulationWarning(**w) for w in meta["warnings"]], settings=meta["settings"],
            versions=meta["versions"], attrs={k: v for k, v in ds.attrs.items() if k not in own},
        )  # fmt: skip

    def to_json_dict(self, param_set: int = 0) -> dict[str, Any]:
        """The CLI's ``--json`` object for one parameter set."""
        p = self.params[param_set]
        return {
            "x_gh": self.x_gh_list(param_set),
            "t_gh": [
                [float(v) for v in row[np.isfinite(row)]] for row in self.t_gh[param_set]
            ],
            "stick_count": [int(v) for v in self.stick_count[param_set]],
            "parameters": p.to_dict(),
            **self._run_record(),
            "x0": list(self.x0[param_set]),
            "friction_law": self.laws[param_set],
            "sigma_zeta": self.sigma_zeta[param_set],
            "white_increment": self.settings.get("white_increment", "ito"),
            "white_stream": self.settings.get("white_stream"),
            "sigma_zeta_effective": list(self.settings.get("sigma_zeta_effective", self.sigma_zeta))[param_set],
            "process": self.process,
            "diagnostics": {
                k: [float(x) for x in v[param_set]] for k, v in self.diagnostics.items()
            },
            "warnings": [w.to_dict() for w in self.warnings],
            "versions": self.versions,
        }


def _json_default(obj: object) -> object:
    if isinstance(obj, np.generic):
        return obj.item()
    if isinstance(obj, np.ndarray):
        return obj.tolist()
    raise TypeError(f"not JSON serialisable: {type(obj).__name__}")


def _metadata(ds: xr.Dataset, source: str | Path) -> dict[str, Any]:
    """The ``metadata_json`` record of a simulation dataset; :class:`ResultFileError` for another file."""
    try:
        meta = json.loads(ds.attrs["metadata_json"])
    except (KeyError, TypeError, ValueError):
        meta = None
    if not isinstance(meta, dict) or meta.get("schema") != SCHEMA:
        found = meta.get("schema") if isinstance(meta, dict) else None
        raise ResultFileError(f"{source} is not a stochfric simulation result ({SCHEMA})"
                              + (f" but {found}" if found else "") + ": give simulation.nc of "
                              "stochfric simulate --out, or a file of SimulationResult.to_netcdf; "
                              "stochfric.load reads any saved result")
    return meta


def load_result(path: str | Path) -> xr.Dataset:
    """The plain :class:`xarray.Dataset` of a result written by :meth:`SimulationResult.to_netcdf`
    (fully into memory).  For the typed :class:`SimulationResult` use :meth:`SimulationResult.load`."""
    out: xr.Dataset = read_netcdf(path, f"simulation result ({SCHEMA}, simulation.nc)")
    _metadata(out, path)
    return out

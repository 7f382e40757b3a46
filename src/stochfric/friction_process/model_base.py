"""What every friction-process model is and shares (method §4d/e).

:class:`FrictionProcessModel` is what the oscillator needs from a model; :class:`ProcessModelBase`
is the implementation the model kinds share (statistics over pressure from the fitted model
functions, the band f_k = k/ℓ < 1/(2Δx) and its grid, realisations by the spectral representation
2.48/4.32, JSON files).  The kinds: :class:`~stochfric.friction_process.band_limited.BandLimitedProcessModel`
and :class:`~stochfric.friction_process.tabulated.TabulatedProcessModel`; any of them is loaded through
:func:`stochfric.friction_process.model.load_process_model`.
"""

from __future__ import annotations

import json
import math
import os
from enum import StrEnum
from pathlib import Path
from typing import Any, Protocol, Self

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.errors import InputError, InputTypeError, ProcessModelError
from stochfric.friction_process.model_function import ModelFunction, checked_pressure
from stochfric.friction_process.spectral import (
    band_limited_frequencies,
    generate_process,
    nyquist_frequency,
)
from stochfric.io_utils import read_text_checked, write_json_atomic
from stochfric.random import SeedLike
from stochfric.validation import positive

__all__ = [
    "LOW_FREQUENCY_FRACTION",
    "PRESSURE_RANGE_RTOL",
    "SCHEMA_VERSION",
    "ExtrapolationError",
    "FrictionProcessModel",
    "ProcessModelBase",
    "SigmaZetaRule",
    "check_pressure_range",
    "fitted_pressure_range",
    "low_frequency_level",
]


class SigmaZetaRule(StrEnum):
    """How a process model gives the white-noise intensity σ_ζ(p) (method §5.1, eq. 4.17)."""

    #: σ_ζ = σ_μ(p), the thesis's rule (§4.1.2)
    SIGMA_MU = "sigma_mu"
    #: σ_ζ = S0/2, the process's low-frequency one-sided PSD level
    SPECTRAL_LEVEL = "spectral_level"


#: Version of the model files' schema (``"schema_version"``); :meth:`ProcessModelBase.from_dict` refuses others.
SCHEMA_VERSION = 2

#: Fraction of the band (lowest frequencies, at least one bin) over which the low-frequency
#: level S0 of the ``"spectral_level"`` σ_ζ rule is averaged.
LOW_FREQUENCY_FRACTION = 0.25


def low_frequency_level(psd_over_band: ArrayLike) -> float:
    """S0 [m]: mean one-sided PSD over the lowest quarter of the band (at least one bin).

    ``psd_over_band`` is S(f_i) at the band's frequencies in increasing order.  For a flat
    spectrum S0 is its level.  Used by the σ_ζ rule ``"spectral_level"``: σ_ζ = S0/2.
    """
    s = np.asarray(psd_over_band, dtype=np.float64)
    if s.ndim != 1 or s.size == 0:
        raise InputError("the band spectrum must be a non-empty 1-D array")
    k = max(1, math.floor(LOW_FREQUENCY_FRACTION * s.size))
    return float(np.mean(s[:k]))


#: Units of the serialised models (SI; PSD in the convention of method §0).
_UNITS = {"dx": "m", "length": "m", "pressure": "Pa", "frequency": "1/m", "psd": "m (one-sided, method §0)"}


class FrictionProcessModel(Protocol):
    """What the oscillator needs from a friction-process model (method §4e, §5.1, §5.2).

    Units: pressure p [Pa], path frequency f [1/m], one-sided PSD S [m] (method §0),
    grid spacing ``dx`` and ``length`` [m]; μ, σ_μ, σ_ζ dimensionless.
    """

    @property
    def name(self) -> str:
        """Label of the model."""
        ...

    @property
    def dx(self) -> float:
        """Grid spacing Δx [m] of a realisation."""
        ...

    @property
    def length(self) -> float:
        """Process length ℓ [m] (period of the realisation)."""
        ...

    def mean(self, p_pa: float) -> float:
        """E[μ](p)."""
        ...

    def std(self, p_pa: float) -> float:
        """σ_μ(p)."""
        ...

    def frequencies(self) -> NDArray[np.float64]:
        """The band's path frequencies [1/m]."""
        ...

    def spectrum(self, f: ArrayLike, p_pa: float) -> NDArray[np.float64]:
        """One-sided PSD S(f; p) [m]."""
        ...

    def sigma_zeta(self, p_pa: float) -> float:
        """White-noise intensity σ_ζ(p) (eq. 4.17)."""
        ...

    def generate(self, p_pa: float, rng: np.random.Generator | SeedLike) -> NDArray[np.float64]:
        """One realisation of μ̂_SD on the grid x_j = j dx."""
        ...

    def to_dict(self) -> dict[str, Any]:
        """JSON-compatible dict with a ``"kind"`` tag."""
        ...


class ProcessModelBase:
    """What every friction-process model shares: pressure statistics from the fitted model
    functions, the band f_k = k/ℓ < 1/(2Δx) and its grid, realisations by the spectral
    representation (2.48/4.32), JSON files.  Subclasses are frozen dataclasses that define the
    fields below and :meth:`spectrum`, :meth:`sigma_zeta`, :meth:`to_dict`, :meth:`from_dict`.
    """

    name: str
    mu_mean: ModelFunction
    mu_std: ModelFunction
    dx: float
    length: float
    sigma_zeta_rule: SigmaZetaRule

    def _check_common(self) -> None:
        """Validate and normalise name, model functions, Δx, ℓ and the σ_ζ rule."""
        if not isinstance(self.name, str) or not self.name:
            raise ProcessModelError(f"name must be a non-empty string, got {self.name!r}")
        for attr in ("mu_mean", "mu_std"):
            if not isinstance(getattr(self, attr), ModelFunction):
                raise InputTypeError(f"{attr} must be a ModelFunction, got {getattr(self, attr)!r}")
        dx = positive("dx", self.dx, "m", error=ProcessModelError)
        length = positive("length", self.length, "m", error=ProcessModelError)
        object.__setattr__(self, "dx", dx)
        object.__setattr__(self, "length", length)
        if length <= 2.0 * dx:
            raise ProcessModelError(
                f"length {length!r} m must exceed 2·dx = {2 * dx!r} m so that the band "
                "k/length < 1/(2·dx) holds at least one frequency"
            )
        if self.sigma_zeta_rule not in tuple(SigmaZetaRule):
            raise ProcessModelError(
                f"sigma_zeta_rule must be one of {[str(r) for r in SigmaZetaRule]}, got {self.sigma_zeta_rule!r}"
            )
        object.__setattr__(self, "sigma_zeta_rule", SigmaZetaRule(self.sigma_zeta_rule))

    @staticmethod
    def _check_kind(data: dict[str, Any], kind: str) -> None:
        """Refuse a dict of another kind or schema version (:meth:`from_dict`)."""
        found = data.get("kind", kind)
        if found != kind:
            raise ProcessModelError(f"not a {kind.replace('_', '-')} process model: kind = {found!r}")
        version = data.get("schema_version", SCHEMA_VERSION)
        if version != SCHEMA_VERSION:
            raise ProcessModelError(
                f"unsupported schema_version {version!r} (this version reads {SCHEMA_VERSION}); "
                "rerun `stochfric friction-process` to write the model anew"
            )

    # --- statistics over pressure ------------------------------------------------------

    def mean(self, p_pa: float) -> float:
        """E[μ](p) = a p^b + c (eq. 3.21, Tables 3.3/3.6), p [Pa] > 0."""
        return self.mu_mean(checked_pressure(p_pa))

    def std(self, p_pa: float) -> float:
        """σ_μ(p) = a p^b + c (eq. 3.21), p [Pa] > 0.

        Raises ValueError where the fit turns negative (outside its range of validity).
        """
        s = self.mu_std(checked_pressure(p_pa))
        if s < 0.0:
            raise InputError(
                f"the σ_μ model function of {self.name!r} is negative ({s:.4g}) at "
                f"p = {p_pa:.6g} Pa: the fit is used outside its range of validity"
            )
        return s

    # --- the band ----------------------------------------------------------------------

    @property
    def frequency_step(self) -> float:
        """Δf = 1/ℓ [1/m]."""
        return 1.0 / self.length

    @property
    def n_points(self) -> int:
        """Number of grid points n = round(ℓ/Δx) of a realisation."""
        return round(self.length / self.dx)

    @property
    def grid_is_periodic(self) -> bool:
        """Whether ℓ/Δx is an integer (to 1e-9 relative), i.e. the grid spans one period ℓ.

        Only then is a realisation's grid variance exactly the model variance and its periodic
        continuation with period n Δx seamless.
        """
        ratio = self.length / self.dx
        return abs(ratio - round(ratio)) <= 1e-9 * ratio

    def grid(self) -> NDArray[np.float64]:
        """Grid positions x_j = j Δx [m], j = 0..n−1, of :meth:`generate`."""
        return np.arange(self.n_points, dtype=np.float64) * self.dx

    def frequencies(self) -> NDArray[np.float64]:
        """Band f_k = k/ℓ [1/m], k = 1..K, f_K < 1/(2Δx) (:func:`band_limited_frequencies`)."""
        return band_limited_frequencies(self.dx, self.length)

    def spectrum(self, f: ArrayLike, p_pa: float) -> NDArray[np.float64]:  # pragma: no cover - abstract
        """One-sided PSD S(f; p) [m] at path frequencies f [1/m] (method §0), 0 outside the band."""
        raise NotImplementedError

    def variance(self, p_pa: float) -> float:
        """Σ_i S(f_i; p) Δf over the band."""
        return float(np.sum(self.spectrum(self.frequencies(), p_pa)) * self.frequency_step)

    # --- realisations ------------------------------------------------------------------

    def generate(self, p_pa: float, rng: np.random.Generator | SeedLike) -> NDArray[np.float64]:
        """One realisation of μ̂_SD(x_j; p) on :meth:`grid` (eq. 2.48/4.32, method §4e).

        Zero-mean part only; the friction coefficient is μ = E[μ](p) + μ̂_SD (eq. 3.22).
        Draws K = len(frequencies()) phases from ``rng`` (see
        :func:`stochfric.friction_process.spectral.generate_process`).
        """
        f = self.frequencies()
        return generate_process(f, self.spectrum(f, p_pa), self.dx, self.length, rng)

    # --- files -------------------------------------------------------------------------

    def _dict_head(self, kind: str) -> dict[str, Any]:
        """The leading entries of :meth:`to_dict` every model kind shares (kind, schema, μ fits, grid)."""
        return {"kind": kind, "schema_version": SCHEMA_VERSION, "name": self.name, "mu_mean": self.mu_mean.to_dict(),
                "mu_std": self.mu_std.to_dict(), "dx": self.dx, "length": self.length}

    @staticmethod
    def _head_fields(data: dict[str, Any]) -> dict[str, Any]:
        """Constructor arguments from the entries of :meth:`_dict_head` (inverse of it)."""
        return {"name": data["name"], "mu_mean": ModelFunction.from_dict(data["mu_mean"]),
                "mu_std": ModelFunction.from_dict(data["mu_std"]), "dx": data["dx"], "length": data["length"]}

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Self:  # pragma: no cover - abstract
        raise NotImplementedError

    @classmethod
    def load(cls, path: str | os.PathLike[str]) -> Self:
        """Read a model written by :meth:`save`."""
        return cls.from_dict(json.loads(read_text_checked(path)))

    def _dict_tail(self) -> dict[str, Any]:
        """The derived entries at the end of :meth:`to_dict` (ignored by ``from_dict``)."""
        return {"units": dict(_UNITS), "nyquist_frequency": nyquist_frequency(self.dx)}

    def to_dict(self) -> dict[str, Any]:  # pragma: no cover - abstract
        """JSON-compatible dict with ``kind`` and SI units."""
        raise NotImplementedError

    def save(self, path: str | os.PathLike[str]) -> Path:
        """Write :meth:`to_dict` as JSON to ``path`` atomically (temporary file + rename); returns the path."""
        return write_json_atomic(path, self.to_dict())


class ExtrapolationError(ProcessModelError):
    """A friction-process model is asked for pressures outside the range it was fitted on (issue 30)."""


#: Relative tolerance at the ends of a fitted pressure range (pressures are recorded to float precision).
PRESSURE_RANGE_RTOL = 1e-9


def fitted_pressure_range(model: Any) -> tuple[float, float] | None:
    """(p_min, p_max) [Pa] a process model was fitted on, or None where it records none (the thesis's preset
    models: Tables 3.3/3.6 give no range).  A wrapper (``base``) reports its base model's range."""
    method = getattr(model, "pressure_range_pa", None)
    if callable(method):
        lo, hi = method()
        return float(lo), float(hi)
    base = getattr(model, "base", None)
    return fitted_pressure_range(base) if base is not None else None


def check_pressure_range(model: Any, pressures_pa: ArrayLike, *, allow: bool = False, context: str = "") -> str | None:
    """No silent extrapolation (issue 30, item 3): None when every pressure [Pa] lies in the model's fitted
    range (or the model records none); otherwise the stamp every output must carry when ``allow``, else
    :class:`ExtrapolationError` with the range and what to do.  ``context`` says who asks (e.g. ``"N = 500 N
    over A = 0.016 m²"``)."""
    rng = fitted_pressure_range(model)
    p = np.atleast_1d(np.asarray(pressures_pa, dtype=np.float64))
    if rng is None or p.size == 0:
        return None
    lo, hi = rng
    outside = (p < lo * (1.0 - PRESSURE_RANGE_RTOL)) | (p > hi * (1.0 + PRESSURE_RANGE_RTOL))
    if not outside.any():
        return None
    bad = p[outside]
    span = (f"{bad.min() / 1e6:.4g} MPa" if bad.min() == bad.max()
            else f"{bad.min() / 1e6:.4g}–{bad.max() / 1e6:.4g} MPa")
    name = getattr(model, "name", "the friction-process model")
    where = f" ({context})" if context else ""
    stamp = (f"EXTRAPOLATED: the friction-process model {name!r} was fitted on p = {lo / 1e6:.4g}–{hi / 1e6:.4g} MPa "
             f"and is used at p = {span}{where}, outside that range")
    if allow:
        return stamp
    raise ExtrapolationError(
        f"the friction-process model {name!r} was fitted on p = {lo / 1e6:.4g}–{hi / 1e6:.4g} MPa; this run needs "
        f"p = {span}{where}, outside it, where its E[mu](p) and sigma_mu(p) are an extrapolation of the fit. "
        "Analyse the surface at these pressures (stochfric assess with the machine, or friction-process with an "
        "approach range that covers them), or pass --allow-extrapolation to use the model anyway (every output "
        "is then stamped)")

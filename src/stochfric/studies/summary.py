"""Typed study summaries: :class:`StudySummary`, the fields every study's summary starts with, and the
JSON codec of summary dataclasses (:func:`to_json`, :func:`from_json`).

A summary is a frozen dataclass.  Its JSON object has one key per field (the field's name, or the
``json_key`` of its metadata), tuples as lists and NaN/inf as ``null``; a field with the metadata
:data:`OPTIONAL` is left out while it is ``None`` (the study does not have it).
:func:`from_json` reads the object back by the field types: ``null`` in a ``float`` field is NaN, in
a ``float | None`` field ``None``.  Units are those of the study's dataset: SI (forces in N), the
oscillator's dimensionless x = y/L (L = 1 m) and τ = ω0 t, damping ratio D [-].
"""

from __future__ import annotations

import dataclasses
import enum
import math
import types
import typing
from dataclasses import dataclass, field
from typing import Any, Self, TypeVar

import numpy as np

from .errors import StudyError

T = TypeVar("T")

#: Metadata of a summary field the study has only in some configurations: ``None`` and left out of the
#: JSON while it is ``None`` (``field(default=None, metadata=OPTIONAL)``).
OPTIONAL = {"omit_none": True}

#: A table of one model: ``[outer grid axis][inner grid axis]`` (the study's docstring names the axes).
Table = list[list[float]]


def to_json(value: Any, *, nan_as_null: bool = True) -> Any:
    """Plain JSON values: dataclasses as objects (see the module docstring), tuples as lists, numpy
    as Python, NaN/inf as ``None`` (``nan_as_null=False``: kept, for ``json.dumps(allow_nan=True)``)."""
    def conv(v: Any) -> Any:
        return to_json(v, nan_as_null=nan_as_null)

    if dataclasses.is_dataclass(value) and not isinstance(value, type):
        out: dict[str, Any] = {}
        for f in dataclasses.fields(value):
            v = getattr(value, f.name)
            if v is None and f.metadata.get("omit_none"):
                continue
            out[f.metadata.get("json_key", f.name)] = conv(v)
        return out
    if isinstance(value, dict):
        return {str(k): conv(v) for k, v in value.items()}
    if isinstance(value, list | tuple):
        return [conv(v) for v in value]
    if isinstance(value, np.ndarray):
        return conv(value.tolist())
    if isinstance(value, np.generic):
        return conv(value.item())
    if isinstance(value, float) and nan_as_null:
        return value if math.isfinite(value) else None
    return value


def from_json(cls: type[T], data: Any) -> T:
    """The dataclass ``cls`` from the JSON object :func:`to_json` wrote (``TypeError``/``KeyError``/
    ``ValueError`` where the object does not fit the fields)."""
    out: T = _decode(cls, data)
    return out


def _decode(tp: Any, v: Any) -> Any:
    """``v`` (plain JSON) as a value of the type ``tp``."""
    origin = typing.get_origin(tp)
    if tp is Any:
        return v
    if origin in (typing.Union, types.UnionType):
        return _decode_union(typing.get_args(tp), v)
    if isinstance(tp, type) and issubclass(tp, enum.Enum):
        return tp(v)
    if isinstance(tp, type) and dataclasses.is_dataclass(tp):
        if not isinstance(v, dict):
            raise TypeError(f"{tp.__name__}: expected an object, got {type(v).__name__}")
        hints = typing.get_type_hints(tp)
        kw = {f.name: _decode(hints[f.name], v[f.metadata.get("json_key", f.name)])
              for f in dataclasses.fields(tp) if f.metadata.get("json_key", f.name) in v}
        return tp(**kw)
    if origin is list:
        (arg,) = typing.get_args(tp)
        return [_decode(arg, x) for x in v]
    if origin is tuple:
        args = typing.get_args(tp)
        if len(args) == 2 and args[1] is Ellipsis:
            return tuple(_decode(args[0], x) for x in v)
        return tuple(_decode(a, x) for a, x in zip(args, v, strict=True))
    if origin is dict:
        return {str(k): _decode(typing.get_args(tp)[1], x) for k, x in v.items()}
    if tp is float:
        return math.nan if v is None else float(v)
    if tp in (int, str, bool):
        if not isinstance(v, tp):
            raise TypeError(f"expected {tp.__name__}, got {v!r}")
        return v
    raise TypeError(f"no JSON reading for the type {tp!r}")


def _decode_union(args: tuple[Any, ...], v: Any) -> Any:
    """``X | None`` (``null`` is ``None``) and ``list[…] | float`` (by the JSON value's shape)."""
    if v is None and type(None) in args:
        return None
    rest = [a for a in args if a is not type(None)]
    sequences = [a for a in rest if typing.get_origin(a) in (list, tuple)]
    scalars = [a for a in rest if a not in sequences]
    pick = sequences if isinstance(v, list) and sequences else scalars or sequences
    return _decode(pick[0], v)


#: The summary class of each study kind, filled as the study modules define them
#: (:meth:`StudySummary.__init_subclass__`); read by :func:`summary_class`.
_SUMMARY_CLASSES: dict[str, type[StudySummary]] = {}


def summary_class(kind: str) -> type[StudySummary]:
    """The summary class of the study kind ``kind`` (what :meth:`~stochfric.studies.base.StudyResult.load`
    reads a saved summary into); :class:`StudyError` naming the kinds for another.  The study modules
    define these classes and :mod:`stochfric.studies` imports every study module, so the kinds are known
    wherever a study module can be imported; this module sits below them and imports none (no cycle)."""
    try:
        return _SUMMARY_CLASSES[kind]
    except KeyError:
        raise StudyError(f"unknown study kind {kind!r}; one of {', '.join(sorted(_SUMMARY_CLASSES))}") from None


def summary_kinds() -> list[str]:
    """The study kinds that have a summary class (sorted): the kinds a saved study can be of."""
    return sorted(_SUMMARY_CLASSES)


@dataclass(frozen=True)
class WarningCount:
    """How often one simulation warning class (``code``, e.g. ``coarse-time-step``) occurred in a study."""

    code: str
    count: int


@dataclass(frozen=True, kw_only=True)
class StudySummary:
    """The fields every study's summary starts with (a study's own class adds its grid and results).

    ``schema`` (:data:`~stochfric.studies.base.STUDY_SCHEMA`), ``study`` (its kind), ``preset`` and
    ``process_source`` (the case), ``runs`` (Monte Carlo runs per cell; the deterministic model runs
    once), ``seed`` (root seed), ``tau_end`` and ``dt`` (dimensionless simulated time and time step,
    τ = ω0 t), ``models``; the modelling choices (method §5): ``path_coordinate`` (where the contact
    process is read), ``white_intensity`` (the σ_ζ rule), ``white_increment`` and ``process_level``,
    ``white_model`` (the white model's standing, where it ran); ``warnings`` (simulation warnings,
    counted by class), ``extrapolation`` (the process model used outside its fitted pressures, allowed
    explicitly: one stamp per such force) and ``versions`` (packages that shaped the numbers).
    """

    schema: str
    study: str
    preset: str
    process_source: str
    runs: int
    seed: int
    tau_end: float
    dt: float
    models: list[str]
    path_coordinate: str
    white_intensity: str
    white_increment: str
    process_level: str
    white_model: str | None = field(default=None, metadata=OPTIONAL)
    warnings: list[WarningCount] = field(default_factory=list)
    #: Stamps of forces at which the process model was used outside its fitted pressures (allowed explicitly).
    extrapolation: list[str] | None = field(default=None, metadata=OPTIONAL)
    versions: dict[str, str] = field(default_factory=dict)

    def __init_subclass__(cls, *, kind: str | None = None, **kwargs: Any) -> None:
        """A study kind's summary class names its kind (``class DampingSummary(StudySummary,
        kind="damping")``): :func:`summary_class` finds it by that name."""
        super().__init_subclass__(**kwargs)
        if kind is not None:
            _SUMMARY_CLASSES[kind] = cls

    def to_json(self) -> dict[str, Any]:
        """The summary as one JSON object (module docstring)."""
        out: dict[str, Any] = to_json(self)
        return out

    @classmethod
    def from_json(cls, data: dict[str, Any]) -> Self:
        """The summary :meth:`to_json` wrote."""
        return from_json(cls, data)


@dataclass(frozen=True, kw_only=True)
class ForcedSummary(StudySummary):
    """The fields the summaries of the forced studies (forcing, Lyapunov) add, as their configs do:
    the grids ``forcing_q`` (q = Q/(cL), [-]) and ``eta`` (η = Ω/ω0, [-]), ``damping_ratio`` [-] and
    the integrators (:func:`~stochfric.studies.config.integrator_record`)."""

    forcing_q: list[float]
    eta: list[float]
    damping_ratio: float
    integrator: str
    sde_integrator: str
    integrator_mode: str

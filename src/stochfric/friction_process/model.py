"""The pressure-dependent friction-process model consumed by the oscillator (method §4d/e, thesis eq. 3.22).

μ(x; p) = E[μ](p) + μ̂_SD(x; p) along the path x [m] at contact pressure p [Pa]: E[μ] and σ_μ are
model functions a p^b + c (eq. 3.21/3.25), μ̂_SD the spectral representation (eq. 2.48/4.32) of a
band-limited one-sided PSD S(f; p) [m] whose variance is σ_μ(p)² (docs/friction_process.md).  The
one import point of the model kinds (:mod:`.model_function`, :mod:`.model_base`,
:mod:`.band_limited`, :mod:`.tabulated`); reads any model back from its ``"kind"``-tagged dict or
file (:func:`process_model_from_dict`, :func:`load_process_model`).
"""

from __future__ import annotations

import json
import os
from typing import Any

from stochfric.errors import ProcessModelError
from stochfric.friction_process.band_limited import BandLimitedProcessModel, SpectrumShape
from stochfric.friction_process.model_base import (
    LOW_FREQUENCY_FRACTION,
    FrictionProcessModel,
    SigmaZetaRule,
    low_frequency_level,
)
from stochfric.friction_process.model_function import ModelFunction
from stochfric.friction_process.tabulated import PressureRule, TabulatedProcessModel, VarianceRule
from stochfric.io_utils import read_text_checked

__all__ = [
    "LOW_FREQUENCY_FRACTION",
    "BandLimitedProcessModel",
    "FrictionProcessModel",
    "ModelFunction",
    "PressureRule",
    "SigmaZetaRule",
    "SpectrumShape",
    "TabulatedProcessModel",
    "VarianceRule",
    "load_process_model",
    "low_frequency_level",
    "process_model_from_dict",
]


def process_model_from_dict(data: dict[str, Any]) -> FrictionProcessModel:
    """Rebuild any process model from its ``to_dict`` output, dispatching on ``"kind"``."""
    kind = data.get("kind")
    if kind == "band_limited":
        return BandLimitedProcessModel.from_dict(data)
    if kind == "tabulated":
        return TabulatedProcessModel.from_dict(data)
    raise ProcessModelError(f"unknown process model kind {kind!r}; known: ['band_limited', 'tabulated']")


def load_process_model(path: str | os.PathLike[str]) -> FrictionProcessModel:
    """Load any friction-process model file written by a model's ``save`` (JSON).

    Raises :class:`~stochfric.errors.ProcessModelError` (a ``ValueError``) with the file name for a file
    that is not a process model.
    """
    try:
        data = json.loads(read_text_checked(path))
    except (OSError, json.JSONDecodeError) as exc:
        why = getattr(exc, "strerror", None) or exc
        raise ProcessModelError(f"cannot read friction-process model {path}: {why}") from None
    except UnicodeDecodeError as exc:
        raise ProcessModelError(f"{path} is not a friction-process model file (not UTF-8 text: byte {exc.start}, "
                         f"{exc.reason})") from None
    if not isinstance(data, dict):
        raise ProcessModelError(f"{path} is not a friction-process model file")
    try:
        return process_model_from_dict(data)
    except KeyError as exc:
        raise ProcessModelError(f"{path} is not a valid friction-process model: the field {exc} is missing") from None
    except (TypeError, AttributeError) as exc:
        raise ProcessModelError(
            f"{path} is not a valid friction-process model: a field has the wrong type ({exc})") from None
    except ValueError as exc:
        raise ProcessModelError(f"{path}: {exc}") from None

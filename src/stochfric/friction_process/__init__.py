"""The friction process μ(x; p) that the oscillator reads (method §4d/e, thesis eq. 3.22, 2.48/4.32).

This floor sits below the oscillator and above the foundation only: it knows nothing of surfaces or
contact.  It holds the friction-process models — the :class:`~.model_base.FrictionProcessModel`
protocol and its base (:mod:`.model_base`), the model functions a p^b + c (:mod:`.model_function`),
the band-limited (:mod:`.band_limited`), tabulated (:mod:`.tabulated`) and rescaled
(:mod:`.rescaled`) models, reading any model back (:mod:`.model`) —, the PSD convention and the
spectral representation (:mod:`.spectral`), the path estimators ACF/PSD/ℓ_corr (:mod:`.spectra`)
and the thesis's two process models (:mod:`.presets`, Tables 3.3/3.6).  The statistical contact
analysis that *produces* a model from a measured surface lives one floor up, in
:mod:`stochfric.process`.

Importing this package imports numpy and nothing of the other floors.
"""

from __future__ import annotations

from stochfric.friction_process.model import (
    BandLimitedProcessModel,
    FrictionProcessModel,
    ModelFunction,
    SigmaZetaRule,
    TabulatedProcessModel,
    load_process_model,
    process_model_from_dict,
)
from stochfric.friction_process.presets import ProcessLevel, brake_process, sheet_process

__all__ = [
    "BandLimitedProcessModel",
    "FrictionProcessModel",
    "ModelFunction",
    "ProcessLevel",
    "SigmaZetaRule",
    "TabulatedProcessModel",
    "brake_process",
    "load_process_model",
    "process_model_from_dict",
    "sheet_process",
]

"""The case of a study (method §6): its names for :mod:`stochfric.oscillator.case` (errors,
setup), the setup from a study config, the record of its modelling choices, the model list.

The three friction models of method §6 are run side by side: ``deterministic`` (the
pressure law 4.13 alone), ``white`` (plus white noise of intensity σ_ζ, §5.1: by default the
thesis's σ_ζ = σ_μ(p), or the process's low-frequency spectral level, or the printed-(4.31)
reproduction mode ``thesis`` with σ_ζ,eff = σ_μ(p)·Lω0·Δτ, ``white_intensity``)
and ``contact`` (plus a band-limited process from the friction-process model, §5.2).

Grids and the stick window live in :mod:`.grids`, tasks in :mod:`.tasks`; their names are
importable from here as before.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from ..oscillator.case import PATH_COORDINATES as PATH_COORDINATES
from ..oscillator.case import WHITE_INTENSITY_RULES as WHITE_INTENSITY_RULES
from ..oscillator.case import WHITE_MODEL_STANDING, CaseError, CaseSetup, case_setup
from ..oscillator.case import law_for as law_for
from ..oscillator.case import process_rule_of as process_rule_of
from ..oscillator.case import white_increment_of as white_increment_of
from ..oscillator.case import with_white_intensity as with_white_intensity

# Moved to their own modules (one concept each); importable from here as before.
from .grids import STICK_WINDOW as STICK_WINDOW
from .grids import pad_events as pad_events
from .grids import parse_grid as parse_grid
from .grids import window_mask as window_mask
from .tasks import TaskSpec as TaskSpec
from .tasks import execute_task as execute_task
from .tasks import integrator_for as integrator_for
from .tasks import runs_for as runs_for
from .tasks import task_for as task_for
from .tasks import warnings_of as warnings_of

#: The studies' names for the case of :mod:`stochfric.oscillator.case`: a study's configuration
#: errors are case errors, its setup is the case setup.
StudyError = CaseError
StudySetup = CaseSetup
make_setup = case_setup


def setup_for(config: Any, tau_end: float | None = None) -> StudySetup:
    """:func:`make_setup` from a study config (``tau_end`` overrides a missing ``config.tau_end``)."""
    te = config.tau_end if config.tau_end is not None else tau_end
    return make_setup(config.preset, config.process_file, te, config.dt, config.white_intensity,
                      getattr(config, "process_level", "sigma_mu"))


def model_choices(config: Any, setup: StudySetup, forces: Sequence[float]) -> dict[str, Any]:
    """JSON record of the modelling choices: path coordinate, σ_ζ rule, σ_ζ per force and the
    effective σ_ζ of the white-noise SDE (differs only in ``thesis`` mode)."""
    return {
        "path_coordinate": config.path_coordinate,
        "white_intensity": config.white_intensity,
        "white_increment": setup.white_increment,
        "process_level": setup.process_level,
        "sigma_zeta": [setup.sigma_zeta(nf) for nf in forces],
        "sigma_zeta_effective": [setup.sigma_zeta_effective(nf) for nf in forces],
        **({"white_model": WHITE_MODEL_STANDING} if "white" in config.models else {}),
    }


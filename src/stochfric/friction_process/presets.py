"""The friction-process models of the thesis's two application cases: brake pad (§3.2) and DC04
steel sheet (§3.3), and the ``psd_level`` reproduction mode of their process level.

Values from method §4d (model-function fits, thesis Tables 3.3 and 3.6, p in Pa).  Each model is a
:class:`~stochfric.friction_process.model.BandLimitedProcessModel` whose spectrum has variance σ_μ(p)²
exactly (method §4d).  Recorded but **not used** by the default process: the thesis's fits of the
mean PSD level E[S](p) (third rows of Tables 3.3/3.6), whose normalisation the thesis does not
state (method §7.8); only the ``psd_level`` reproduction mode reads them.  The oscillator cases
built on these models (mass, stiffness, belt speed, contact area, study forces) are the presets of
:mod:`stochfric.oscillator.presets`.

Known discrepancies of the thesis, recorded here and in ``docs/friction_process.md``,
deliberately not "fixed" (the fits are used exactly as printed):

* Brake, §3.2.5: the text quotes σ_μ(0.5 MPa) = 0.087 from the model function, but
  Table 3.3 gives σ_μ(5·10⁵ Pa) = 1.6063·(5·10⁵)^−0.4163 + 0.0663 ≈ 0.0731.
* Sheet, Table 4.4: σ_ζ = σ_μ̂SD at p = 0.1 / 0.5 / 1 MPa is printed as
  0.1001 / 0.0805 / 0.0594; the Table 3.6 fit gives 0.0995 / 0.0767 / 0.0667
  (fit relative to table: −0.6 %, −4.7 %, +12.4 %).  Table 4.4's first row also reads
  N = 1 / 5 / 10 instead of 100 / 500 / 1000 N (method §7.5).
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass
from enum import StrEnum
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.errors import InputError
from stochfric.friction_process.model import BandLimitedProcessModel, ModelFunction, SigmaZetaRule
from stochfric.random import SeedLike

__all__ = [
    "BRAKE_PSD_LEVEL_FIT",
    "SHEET_PSD_LEVEL_FIT",
    "ProcessLevel",
    "PsdLevelProcessModel",
    "brake_process",
    "process_with_level",
    "psd_level_process",
    "sheet_process",
]


def brake_process() -> BandLimitedProcessModel:
    """Friction process of the brake pad on a disc (thesis §3.2; method §4d table "brake").

    Table 3.3 fits (p in Pa): E[μ] = 5.8574 p^−0.4478 + 0.2603, σ_μ = 1.6063 p^−0.4163 + 0.0663;
    Δx = 0.05/79 m ≈ 6.33·10⁻⁴ m (thesis: 6.3·10⁻⁴ m, adjusted so that the 79 grid points span
    exactly one period ℓ), length 0.05 m, flat spectrum (the thesis found the brake spectrum
    constant, Fig. 3.20/3.21).
    """
    return BandLimitedProcessModel(
        name="brake",
        mu_mean=ModelFunction(a=5.8574, b=-0.4478, c=0.2603),
        mu_std=ModelFunction(a=1.6063, b=-0.4163, c=0.0663),
        dx=0.05 / 79,  # thesis 6.3e-4 m, adjusted so that 79 points span exactly one period
        length=0.05,
        spectrum_shape="flat",
    )


def sheet_process() -> BandLimitedProcessModel:
    """Friction process of DC04 steel sheet on DC04 (thesis §3.3; method §4d table "sheet").

    Table 3.6 fits (p in Pa): E[μ] = 28.3661 p^−0.4786 + 0.2194, σ_μ = −1.0185 p^0.0120 + 1.2689;
    Δx = 0.02/67 m ≈ 2.99·10⁻⁴ m (thesis: 3·10⁻⁴ m, adjusted to span exactly one period with 67
    points), length 0.02 m, spectrum falling linearly to half its level over the band — our
    stand-in for the thesis's "falls slightly with frequency" (§3.3.3) until measured spectra
    exist.
    """
    return BandLimitedProcessModel(
        name="sheet",
        mu_mean=ModelFunction(a=28.3661, b=-0.4786, c=0.2194),
        mu_std=ModelFunction(a=-1.0185, b=0.0120, c=1.2689),
        dx=0.02 / 67,  # thesis 3e-4 m, adjusted so that 67 points span exactly one period
        length=0.02,
        spectrum_shape="falling",
        falling_ratio=0.5,
    )


#: The thesis's E[S](p) fits (third rows of Tables 3.3/3.6, p in Pa), **metadata only** for the
#: default process: their PSD normalisation is unstated (method §7.8) and incompatible with
#: method §0; the ``psd_level`` reproduction mode reads them (:class:`PsdLevelProcessModel`).
BRAKE_PSD_LEVEL_FIT = ModelFunction(a=0.0068, b=-0.3174, c=2.4785e-5)
SHEET_PSD_LEVEL_FIT = ModelFunction(a=0.0223, b=-0.3174, c=-5.9154e-5)


# --- reproduction mode: the process level from the thesis's E[S](p) fits --------------------

#: The thesis's own check of a generated brake process (§3.2.5, Fig. 3.23): standard deviation
#: σ_μ̂SD = 0.08 at p = 0.5 MPa.  It fixes the unstated normalisation of the E[S] fits.
THESIS_CHECK_STD = 0.08
THESIS_CHECK_PRESSURE_PA = 5e5


class ProcessLevel(StrEnum):
    """Variance of the contact process."""

    #: σ_μ(p)², method §4d (default)
    SIGMA_MU = "sigma_mu"
    #: reproduction mode: from the thesis's E[S](p) fit (:class:`PsdLevelProcessModel`)
    PSD_LEVEL = "psd_level"


@dataclass(frozen=True, kw_only=True)
class PsdLevelProcessModel:
    """Reproduction mode ``psd_level``: the process level from the thesis's E[S](p) model function.

    The thesis generates μ̂_SD from "the constant spectrum level of the model function" (brake,
    §4.2.1) or "the spectrum of this pressure" (sheet, §3.3.4) — in its own, unstated PSD
    normalisation (method §7.8) — not from σ_μ(p).  This model keeps the base model's band and
    spectrum shape and sets the variance to

        σ_SD(p)² = C · E[S](p) · K Δf,    C = 0.08² / (E[S]_brake(0.5 MPa) · K_brake Δf_brake),

    i.e. E[S](p) (Table 3.3/3.6, p in Pa) read as a one-sided PSD level over the band K Δf
    [1/m], with the one constant C that makes the brake's process at 0.5 MPa have the standard
    deviation the thesis reports for its check (σ_μ̂SD = 0.08, §3.2.5).  The same C is used for
    the sheet (the same PSD estimator on both surfaces).  Result: brake σ_SD = 1.31 / 1.20 / 1.09
    σ_μ(p) at 720 / 2720 / 8000 N, sheet 2.26 / 2.26 / 2.29 σ_μ(p) at 400 / 880 / 1750 N.

    The white-noise intensity is *not* changed (σ_ζ = σ_μ(p) of the base model, thesis Table 4.4).
    A reproduction mode, not a model: ``docs/friction_process.md`` §5.
    """

    base: BandLimitedProcessModel
    psd_level: ModelFunction
    calibration: float
    sigma_zeta_rule: SigmaZetaRule = SigmaZetaRule.SIGMA_MU

    @property
    def name(self) -> str:
        return f"{self.base.name} (psd_level)"

    @property
    def dx(self) -> float:
        return self.base.dx

    @property
    def length(self) -> float:
        return self.base.length

    @property
    def grid_is_periodic(self) -> bool:
        return self.base.grid_is_periodic

    def mean(self, p_pa: float) -> float:
        """E[μ](p) of the base model (eq. 3.21)."""
        return self.base.mean(p_pa)

    def std(self, p_pa: float) -> float:
        """σ_SD(p) = √(C · E[S](p) · K Δf) [-]; ValueError where the E[S] fit is not positive."""
        level = self.psd_level(float(p_pa))
        if not level > 0.0:
            raise InputError(f"the E[S] model function of {self.base.name!r} is not positive ({level:.4g}) at "
                             f"p = {p_pa:.6g} Pa")
        band = len(self.base.frequencies()) * self.base.frequency_step
        return math.sqrt(self.calibration * level * band)

    def _gain(self, p_pa: float) -> float:
        return self.std(p_pa) / self.base.std(p_pa)

    def frequencies(self) -> NDArray[np.float64]:
        return self.base.frequencies()

    def spectrum(self, f: ArrayLike, p_pa: float) -> NDArray[np.float64]:
        """One-sided PSD [m] (method §0): the base shape with variance σ_SD(p)²."""
        out: NDArray[np.float64] = self.base.spectrum(f, p_pa) * self._gain(p_pa) ** 2
        return out

    def variance(self, p_pa: float) -> float:
        return self.base.variance(p_pa) * self._gain(p_pa) ** 2

    def sigma_zeta(self, p_pa: float) -> float:
        """White-noise intensity of the base model under this rule (unchanged by the level)."""
        return dataclasses.replace(self.base, sigma_zeta_rule=self.sigma_zeta_rule).sigma_zeta(p_pa)

    def generate(self, p_pa: float, rng: np.random.Generator | SeedLike) -> NDArray[np.float64]:
        """The base realisation (same phases) scaled to σ_SD(p)."""
        out: NDArray[np.float64] = self.base.generate(p_pa, rng) * self._gain(p_pa)
        return out

    def to_dict(self) -> dict[str, Any]:
        """Provenance record (``kind = "psd_level"``; not readable by ``load_process_model``)."""
        return {"kind": "psd_level", "base": self.base.to_dict(), "psd_level": self.psd_level.to_dict(),
                "calibration": self.calibration, "sigma_zeta_rule": self.sigma_zeta_rule,
                "rule": "sigma_SD(p)^2 = calibration * psd_level(p) * K * df; calibration from the thesis's "
                        "check sigma = 0.08 at 0.5 MPa (brake, section 3.2.5)"}


def _psd_calibration() -> float:
    base = brake_process()
    band = len(base.frequencies()) * base.frequency_step
    return THESIS_CHECK_STD**2 / (BRAKE_PSD_LEVEL_FIT(THESIS_CHECK_PRESSURE_PA) * band)


def psd_level_process(base: BandLimitedProcessModel, psd_level_fit: ModelFunction) -> PsdLevelProcessModel:
    """``base`` in the ``psd_level`` reproduction mode with the E[S](p) fit ``psd_level_fit``
    (:class:`PsdLevelProcessModel`)."""
    return PsdLevelProcessModel(base=base, psd_level=psd_level_fit, calibration=_psd_calibration())


def process_with_level(base: BandLimitedProcessModel, psd_level_fit: ModelFunction | None,
                       level: ProcessLevel | str) -> Any:
    """``base`` under the process-level rule ``level``: itself (``sigma_mu``) or in the ``psd_level``
    reproduction mode with the E[S](p) fit ``psd_level_fit``; ValueError for another level or a
    missing fit."""
    if level == ProcessLevel.SIGMA_MU:
        return base
    if level == ProcessLevel.PSD_LEVEL:
        if psd_level_fit is None:
            raise InputError(f"the process {base.name!r} has no E[S](p) fit for the psd_level mode")
        return psd_level_process(base, psd_level_fit)
    raise InputError(f"unknown process level {level!r}; choose one of {[str(v) for v in ProcessLevel]}")

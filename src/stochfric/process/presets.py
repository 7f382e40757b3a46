"""The thesis's two application cases: brake pad (§4.2) and DC04 steel sheet (§4.3).

Values from method §6 (oscillator and study parameters) and §4d (model-function fits,
thesis Tables 3.3 and 3.6, p in Pa).  Each :class:`Preset` carries a
:class:`~stochfric.process.model.BandLimitedProcessModel` whose spectrum has variance
σ_μ(p)² exactly (method §4d).  Recorded but **not used**: the thesis's fits of the mean
PSD level E[S](p) (third rows of Tables 3.3/3.6), whose normalisation the thesis does not
state (method §7.8); they cannot be mixed with the PSD convention of method §0.

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
import warnings
from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from stochfric.process.model import BandLimitedProcessModel, ModelFunction
from stochfric.random import SeedLike

__all__ = [
    "PRESETS",
    "PROCESS_LEVELS",
    "Preset",
    "PsdLevelProcessModel",
    "brake",
    "get_preset",
    "process_with_level",
    "psd_level_process",
    "sheet",
]

#: Length scale L [m] of the dimensionless displacement x = y/L (thesis: L = 1 m).
_LENGTH_SCALE_M = 1.0

#: ``study_parameters`` keys before docs/glossary.md → their names now (still read, with a DeprecationWarning).
RENAMED_STUDY_PARAMETERS: Mapping[str, str] = MappingProxyType({
    "damping_study_force": "damping_study_force_n",
    "forcing_study_force": "forcing_study_force_n",
    "normal_force_study_forces": "normal_force_study_forces_n",
})


def _renamed_key(key: str) -> str:
    new = RENAMED_STUDY_PARAMETERS.get(key)
    if new is None:
        return key
    warnings.warn(f"preset study_parameters key {key!r} is deprecated: use {new!r} (docs/glossary.md)",
                  DeprecationWarning, stacklevel=3)
    return new


class _StudyParameters(Mapping[str, Any]):
    """Read-only mapping of a preset's study settings under the glossary's keys; the keys before
    the glossary (:data:`RENAMED_STUDY_PARAMETERS`) are accepted and read with a DeprecationWarning."""

    __slots__ = ("_data",)

    def __init__(self, data: Mapping[str, Any]) -> None:
        out: dict[str, Any] = {}
        for key, value in data.items():
            new = _renamed_key(key)
            if new in out or (new != key and new in data):
                raise ValueError(f"study_parameters: give {new} only ({key} is its deprecated name)")
            out[new] = value
        self._data = out

    def __getitem__(self, key: str) -> Any:
        return self._data[_renamed_key(key)]

    def __iter__(self) -> Iterator[str]:
        return iter(self._data)

    def __len__(self) -> int:
        return len(self._data)

    def __repr__(self) -> str:
        return f"{type(self).__name__}({self._data!r})"


@dataclass(frozen=True, kw_only=True)
class Preset:
    """One application case of the thesis (method §6), SI units.

    Attributes
    ----------
    name:
        ``"brake"`` or ``"sheet"``.
    mass:
        Oscillating mass m [kg].
    stiffness:
        Spring stiffness c [N/m].
    belt_speed:
        Belt speed v0 [m/s].
    contact_area_m2:
        Nominal contact area A [m²] for the pressure p = N/A (eq. 4.13).
    normal_force_range_n:
        (N_min, N_max) [N] of the stick-slip range studied in the thesis.
    default_normal_force_n:
        A representative normal force N [N] inside that range.
    process:
        The friction-process model (E[μ](p), σ_μ(p), band-limited spectrum, σ_ζ rule).
    tau_end, dt:
        Default dimensionless simulation end time τ_end and step Δτ (method §6).
    description:
        One-line provenance.
    study_parameters:
        The thesis's study settings (read-only mapping), forces in N:
        ``damping_undamped`` (D = 5e-6), ``damping_damped`` (D of the damped runs),
        ``damping_study_force_n``, ``forcing_study_force_n``, ``normal_force_study_forces_n``
        (their names before docs/glossary.md, without ``_n``, are still accepted and read,
        with a DeprecationWarning).
    recorded_psd_level_fit:
        The thesis's E[S](p) fit (third row of Table 3.3/3.6), **metadata only, not
        used**: its PSD normalisation is unstated (method §7.8) and incompatible with
        method §0; the process spectrum is instead scaled to σ_μ(p)².

    The names before docs/glossary.md (``contact_area``, ``normal_force_range``,
    ``default_normal_force``, ``pressure_range``) are still read, as read-only aliases.
    """

    name: str
    mass: float
    stiffness: float
    belt_speed: float
    contact_area_m2: float
    normal_force_range_n: tuple[float, float]
    default_normal_force_n: float
    process: BandLimitedProcessModel
    tau_end: float = 50.0
    dt: float = 0.005
    description: str = ""
    study_parameters: Mapping[str, Any] = field(default_factory=dict)
    recorded_psd_level_fit: ModelFunction | None = None

    def __post_init__(self) -> None:
        for attr, unit in (
            ("mass", "kg"),
            ("stiffness", "N/m"),
            ("belt_speed", "m/s"),
            ("contact_area_m2", "m²"),
            ("default_normal_force_n", "N"),
            ("tau_end", "(dimensionless)"),
            ("dt", "(dimensionless)"),
        ):
            value = float(getattr(self, attr))
            if not math.isfinite(value) or value <= 0.0:
                raise ValueError(f"{attr} must be a positive finite number {unit}, got {value!r}")
            object.__setattr__(self, attr, value)
        lo, hi = (float(v) for v in self.normal_force_range_n)
        if not (0.0 < lo < hi and math.isfinite(hi)):
            raise ValueError(
                f"normal_force_range_n must be (N_min, N_max) with 0 < N_min < N_max, "
                f"got {self.normal_force_range_n!r}"
            )
        object.__setattr__(self, "normal_force_range_n", (lo, hi))
        if not lo <= self.default_normal_force_n <= hi:
            raise ValueError(
                f"default_normal_force_n {self.default_normal_force_n!r} N lies outside "
                f"normal_force_range_n {self.normal_force_range_n!r}"
            )
        if not isinstance(self.process, BandLimitedProcessModel):
            raise TypeError(f"process must be a BandLimitedProcessModel, got {self.process!r}")
        object.__setattr__(self, "study_parameters", _StudyParameters(self.study_parameters))

    @property
    def omega0(self) -> float:
        """Natural circular frequency ω0 = √(c/m) [rad/s] (below eq. 4.7)."""
        return math.sqrt(self.stiffness / self.mass)

    @property
    def gamma0(self) -> float:
        """Dimensionless belt speed γ0 = v0/(L ω0), L = 1 m (below eq. 4.7)."""
        return self.belt_speed / (_LENGTH_SCALE_M * self.omega0)

    def pressure(self, normal_force: float) -> float:
        """Nominal contact pressure p = N/A [Pa] for a normal force N [N] (eq. 4.13)."""
        n = float(normal_force)
        if not math.isfinite(n) or n <= 0.0:
            raise ValueError(f"normal_force must be a positive finite number [N], got {n!r}")
        return n / self.contact_area_m2

    @property
    def pressure_range_pa(self) -> tuple[float, float]:
        """(p_min, p_max) [Pa] of :attr:`normal_force_range_n`."""
        lo, hi = self.normal_force_range_n
        return lo / self.contact_area_m2, hi / self.contact_area_m2

    # names before docs/glossary.md, still read (no warning: read wherever a case is built)
    @property
    def contact_area(self) -> float:
        """Old name of :attr:`contact_area_m2`."""
        return self.contact_area_m2

    @property
    def normal_force_range(self) -> tuple[float, float]:
        """Old name of :attr:`normal_force_range_n`."""
        return self.normal_force_range_n

    @property
    def default_normal_force(self) -> float:
        """Old name of :attr:`default_normal_force_n`."""
        return self.default_normal_force_n

    @property
    def pressure_range(self) -> tuple[float, float]:
        """Old name of :attr:`pressure_range_pa`."""
        return self.pressure_range_pa


def brake() -> Preset:
    """Brake pad on a disc (thesis §3.2, §4.2; method §4d table "brake", §6).

    m = 2 kg, c = 10⁶ N/m, v0 = 1 m/s → ω0 ≈ 707 rad/s, γ0 ≈ 1.414·10⁻³;
    A_pad = 0.016 m², stick-slip range N = 500 … 20000 N (p ≈ 0.031 … 1.25 MPa);
    Table 3.3 fits (p in Pa): E[μ] = 5.8574 p^−0.4478 + 0.2603,
    σ_μ = 1.6063 p^−0.4163 + 0.0663; process Δx = 0.05/79 m ≈ 6.33·10⁻⁴ m (thesis: 6.3·10⁻⁴ m,
    adjusted so that the 79 grid points span exactly one period ℓ), length 0.05 m, flat
    spectrum (the thesis found the brake spectrum constant, Fig. 3.20/3.21).
    """
    process = BandLimitedProcessModel(
        name="brake",
        mu_mean=ModelFunction(a=5.8574, b=-0.4478, c=0.2603),
        mu_std=ModelFunction(a=1.6063, b=-0.4163, c=0.0663),
        dx=0.05 / 79,  # thesis 6.3e-4 m, adjusted so that 79 points span exactly one period
        length=0.05,
        spectrum_shape="flat",
    )
    return Preset(
        name="brake",
        mass=2.0,
        stiffness=1e6,
        belt_speed=1.0,
        contact_area_m2=0.016,
        normal_force_range_n=(500.0, 20000.0),
        default_normal_force_n=5600.0,
        process=process,
        tau_end=50.0,
        dt=0.005,
        description="Brake pad on a rigid disc, Gaus (2013) §3.2 and §4.2, Table 3.3 fits",
        study_parameters={
            "damping_undamped": 5e-6,
            "damping_damped": 0.15,
            "damping_study_force_n": 5600.0,
            "forcing_study_force_n": 4000.0,
            "normal_force_study_forces_n": (720.0, 2720.0, 8000.0),
        },
        recorded_psd_level_fit=ModelFunction(a=0.0068, b=-0.3174, c=2.4785e-5),
    )


def sheet() -> Preset:
    """DC04 steel sheet on DC04 (thesis §3.3, §4.3; method §4d table "sheet", §6).

    m = 1 kg, c = 10⁵ N/m, v0 = 1 m/s → ω0 ≈ 316 rad/s, γ0 ≈ 3.16·10⁻³;
    A = 10⁻³ m², stick-slip range N = 100 … 2000 N (p = 0.1 … 2 MPa);
    Table 3.6 fits (p in Pa): E[μ] = 28.3661 p^−0.4786 + 0.2194,
    σ_μ = −1.0185 p^0.0120 + 1.2689; process Δx = 0.02/67 m ≈ 2.99·10⁻⁴ m (thesis: 3·10⁻⁴ m,
    adjusted to span exactly one period with 67 points), length 0.02 m, spectrum
    falling linearly to half its level over the band — our stand-in for the thesis's
    "falls slightly with frequency" (§3.3.3) until measured spectra exist (issue 4).
    """
    process = BandLimitedProcessModel(
        name="sheet",
        mu_mean=ModelFunction(a=28.3661, b=-0.4786, c=0.2194),
        mu_std=ModelFunction(a=-1.0185, b=0.0120, c=1.2689),
        dx=0.02 / 67,  # thesis 3e-4 m, adjusted so that 67 points span exactly one period
        length=0.02,
        spectrum_shape="falling",
        falling_ratio=0.5,
    )
    return Preset(
        name="sheet",
        mass=1.0,
        stiffness=1e5,
        belt_speed=1.0,
        contact_area_m2=1e-3,
        normal_force_range_n=(100.0, 2000.0),
        default_normal_force_n=1400.0,
        process=process,
        tau_end=50.0,
        dt=0.005,
        description="DC04 steel sheet on DC04, Gaus (2013) §3.3 and §4.3, Table 3.6 fits",
        study_parameters={
            "damping_undamped": 5e-6,
            "damping_damped": 0.17,
            "damping_study_force_n": 1400.0,
            "forcing_study_force_n": 1100.0,
            "normal_force_study_forces_n": (400.0, 880.0, 1750.0),
        },
        recorded_psd_level_fit=ModelFunction(a=0.0223, b=-0.3174, c=-5.9154e-5),
    )


#: Factories of the thesis's presets by name; call one to get a fresh :class:`Preset`.
PRESETS: Mapping[str, Callable[[], Preset]] = MappingProxyType({"brake": brake, "sheet": sheet})


def get_preset(name: str) -> Preset:
    """The preset called ``name`` (``"brake"`` or ``"sheet"``); ValueError for others."""
    try:
        factory = PRESETS[name]
    except (KeyError, TypeError):
        raise ValueError(f"unknown preset {name!r}; available presets: {sorted(PRESETS)}") from None
    return factory()


# --- reproduction mode: the process level from the thesis's E[S](p) fits (issue 10) -----------

#: The thesis's own check of a generated brake process (§3.2.5, Fig. 3.23): standard deviation
#: σ_μ̂SD = 0.08 at p = 0.5 MPa.  It fixes the unstated normalisation of the E[S] fits.
THESIS_CHECK_STD = 0.08
THESIS_CHECK_PRESSURE_PA = 5e5

#: Process-level rules: ``sigma_mu`` (default: variance σ_μ(p)², method §4d) and ``psd_level``
#: (reproduction mode, :class:`PsdLevelProcessModel`).
PROCESS_LEVELS: tuple[str, ...] = ("sigma_mu", "psd_level")


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
    sigma_zeta_rule: str = "sigma_mu"

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
            raise ValueError(f"the E[S] model function of {self.base.name!r} is not positive ({level:.4g}) at "
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
        return dataclasses.replace(self.base, sigma_zeta_rule=self.sigma_zeta_rule).sigma_zeta(p_pa)  # type: ignore[arg-type]

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
    b = brake()
    fit = b.recorded_psd_level_fit
    assert fit is not None
    band = len(b.process.frequencies()) * b.process.frequency_step
    return THESIS_CHECK_STD**2 / (fit(THESIS_CHECK_PRESSURE_PA) * band)


def psd_level_process(preset: Preset) -> PsdLevelProcessModel:
    """The preset's process in the ``psd_level`` reproduction mode (:class:`PsdLevelProcessModel`)."""
    fit = preset.recorded_psd_level_fit
    if fit is None:
        raise ValueError(f"preset {preset.name!r} records no E[S](p) fit")
    return PsdLevelProcessModel(base=preset.process, psd_level=fit, calibration=_psd_calibration())


def process_with_level(preset: Preset, level: str) -> Any:
    """The preset's process model under the process-level rule ``level`` (:data:`PROCESS_LEVELS`)."""
    if level == "sigma_mu":
        return preset.process
    if level == "psd_level":
        return psd_level_process(preset)
    raise ValueError(f"unknown process level {level!r}; choose one of {list(PROCESS_LEVELS)}")


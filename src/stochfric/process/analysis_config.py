"""Settings of the statistical contact analysis (:func:`stochfric.process.statistics.analyse`).

Flat fields (they are written as they are to the JSON summary and the NetCDF attributes); the
surrogate settings among them are one :class:`~stochfric.process.ensemble.SurrogateOptions`
(:attr:`AnalysisConfig.surrogate_options`).
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from stochfric.arrays import FloatArray
from stochfric.errors import AnalysisError
from stochfric.friction_process.model_base import SigmaZetaRule
from stochfric.friction_process.tabulated import PressureRule, VarianceRule
from stochfric.process.checks import WINDOW_TILES
from stochfric.process.decisions import looks_within
from stochfric.process.ensemble import SurrogateOptions
from stochfric.process.fit import DEFAULT_MAX_AREA_FRACTION
from stochfric.process.holdout import HOLDOUT_MAX_REALIZATIONS, HOLDOUT_REALIZATIONS
from stochfric.surface.quilting import QUILT_METHOD
from stochfric.surface.statistics import curvature_gaussianity
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, SUMMIT_RULES, find_summits
from stochfric.surface.surrogates import AUTO_SURROGATE, SURROGATES, surrogate_method
from stochfric.surface.synthesis import AMPLITUDE_METHODS, DEFAULT_AMPLITUDE, PHASE_METHOD, AmplitudeEstimate
from stochfric.validation import count

__all__ = ["AUTO_SURROGATE", "HOLDOUT_GROWTH", "SUMMIT_GROWTH", "SUMMIT_MAX_GROWTH", "SUMMIT_WORK_POINTS",
           "AnalysisConfig", "summit_budget"]  # AUTO_SURROGATE: .surface.surrogates

#: The default budgets of the two sequential checks (docs/statistical_contact.md §0a, §0e).  The held-out test
#: starts with 24 per fold and may grow to 192 (HOLDOUT_GROWTH; its Student-t threshold falls from 3.63 at 24 to
#: 3.24 at 192 for 36 tests).  The summit check's rank test starts with the ensemble's R = 100 and doubles while
#: undecided, by default while the grown ensemble holds at most SUMMIT_WORK_POINTS surface points (a bounded amount
#: of work whatever the map's size), at least to SUMMIT_GROWTH·R and at most to SUMMIT_MAX_GROWTH·R
#: (:func:`summit_budget`).  At 32 R = 3200 the binomial bound decides a p-value outside about 5 % ± 0.9 %; at 4 R
#: = 400, outside 5 % ± 2.3 % — where the shipped map's p-value lies (3–4 %), which left its verdict to the seed.
SUMMIT_GROWTH = 4
SUMMIT_MAX_GROWTH = 32
SUMMIT_WORK_POINTS = 2**30
HOLDOUT_GROWTH = 8


def summit_budget(realizations: int, points: int) -> int:
    """The summit check's default budget for an ensemble of ``realizations`` surrogates of ``points`` surface points
    each (all pooled scans together): R·2^j, the largest with R·2^j·points ≤ :data:`SUMMIT_WORK_POINTS`, within
    [:data:`SUMMIT_GROWTH`·R, :data:`SUMMIT_MAX_GROWTH`·R].  The shipped al3d-1 (59,200 points) gets 32 R, a 512²
    map 32 R, x3p-2 and mnt-1 16 R, a 1700² map 4 R (docs/statistical_contact.md §0e)."""
    r, n = int(realizations), max(int(points), 1)
    budget = SUMMIT_GROWTH * r
    while 2 * budget <= SUMMIT_MAX_GROWTH * r and 2 * budget * n <= SUMMIT_WORK_POINTS:
        budget *= 2
    return budget


@dataclass(frozen=True, kw_only=True)
class AnalysisConfig:
    """Settings of :func:`analyse` (defaults: the thesis's proportions, §3.2.4–3.2.5).

    ``window_shift_points`` is a_y in grid points of y; ``length_factor`` the long surfaces'
    length in units of the original (thesis: 53 mm / 5.3 mm = 10), which is also the number of
    non-overlapping windows per long surface in the ergodicity check; ``amplitude`` the
    amplitude estimate of the measured map (``"tukey"``, default, and ``"hann"``: edge jump removed;
    ``"raw"``: the thesis's DFT of the map as it is, :func:`stochfric.surface.synthesis.amplitude_spectrum`);
    ``surrogate`` the surrogate method, ``"auto"`` by default as in ``stochfric friction-process``
    (:meth:`surrogate_for`; ``"phase"`` is the thesis's random phases);
    ``sigma_zeta_rule`` the model's rule for the white-noise intensity σ_ζ(p) (:class:`SigmaZetaRule`);
    ``window_tiles`` the most tiles per side of the measured-window check
    (:func:`~stochfric.process.checks.window_tiles`).
    """

    realizations: int = 100
    long_surfaces: int = 10
    length_factor: int = 10
    window_shift_points: int = 16
    surrogate: str = AUTO_SURROGATE
    amplitude: str = DEFAULT_AMPLITUDE
    summit_rule: str = DEFAULT_SUMMIT_RULE
    iaaft_tol: float = 1e-3
    max_area_fraction: float = DEFAULT_MAX_AREA_FRACTION
    pressure_rule: PressureRule = PressureRule.NEAREST
    variance_rule: VarianceRule = VarianceRule.SIGMA_MU
    sigma_zeta_rule: SigmaZetaRule = SigmaZetaRule.SIGMA_MU
    pdf_bins: int = 30
    check_realizations: int = 200
    window_tiles: int = WINDOW_TILES
    holdout_realizations: int | None = None
    holdout_max_realizations: int | None = None
    summit_max_realizations: int | None = None
    seed: int | None = None

    def __post_init__(self) -> None:
        for name, low, why in (
            ("realizations", 2, "a standard deviation needs two"),
            ("long_surfaces", 3, "the ergodicity check and the standard errors of the path statistics use the "
                                 "scatter between independent long surfaces"),
        ):
            v = getattr(self, name)
            if not isinstance(v, bool) and isinstance(v, int | np.integer) and v < low:
                raise AnalysisError(f"{name} must be >= {low} ({why}), got {v}")
        start = self.holdout_realizations
        if start is None:  # as many as the ensemble, within 4 … HOLDOUT_REALIZATIONS
            start = min(HOLDOUT_REALIZATIONS, max(4, int(self.realizations)))
            object.__setattr__(self, "holdout_realizations", start)
        if self.holdout_max_realizations is None:  # the sequential decision may double them 3 times, up to the cap
            object.__setattr__(self, "holdout_max_realizations",
                               min(HOLDOUT_MAX_REALIZATIONS, HOLDOUT_GROWTH * int(start)))
        for name in ("realizations", "long_surfaces", "window_shift_points", "pdf_bins", "check_realizations",
                     "window_tiles", "holdout_realizations", "holdout_max_realizations", "summit_max_realizations"):
            if getattr(self, name) is not None:  # summit_max_realizations None: by the map (with_summit_budget)
                object.__setattr__(self, name, count(name, getattr(self, name), error=AnalysisError))
        object.__setattr__(self, "length_factor", count("length_factor", self.length_factor, 2, error=AnalysisError))
        if self.holdout_start < 4 or self.holdout_budget < self.holdout_start:
            raise AnalysisError(f"the held-out validation needs 4 <= holdout_realizations <= holdout_max_realizations, "
                                f"got {self.holdout_realizations} and {self.holdout_max_realizations}")
        if self.summit_max_realizations is not None and int(self.summit_max_realizations) < int(self.realizations):
            raise AnalysisError(f"summit_max_realizations ({self.summit_max_realizations}) must be at least "
                                f"realizations ({self.realizations}): it is the most the summit check may grow to")
        if self.window_tiles < 2:
            raise AnalysisError(f"window_tiles must be >= 2 (at least 2 x 2 windows), got {self.window_tiles}")
        if not 0.0 < self.max_area_fraction <= 1.0:
            raise AnalysisError(f"max_area_fraction must lie in (0, 1], got {self.max_area_fraction!r}")
        if self.sigma_zeta_rule not in tuple(SigmaZetaRule):
            raise AnalysisError(f"sigma_zeta_rule must be one of {[str(r) for r in SigmaZetaRule]}, "
                               f"got {self.sigma_zeta_rule!r}")
        object.__setattr__(self, "sigma_zeta_rule", SigmaZetaRule(self.sigma_zeta_rule))
        for name, rule in (("pressure_rule", PressureRule), ("variance_rule", VarianceRule)):
            if getattr(self, name) not in tuple(rule):
                raise AnalysisError(f"{name} must be one of {[str(r) for r in rule]}, got {getattr(self, name)!r}")
            object.__setattr__(self, name, rule(getattr(self, name)))
        if self.surrogate != AUTO_SURROGATE and self.surrogate not in SURROGATES:
            raise AnalysisError(f"unknown surrogate method {self.surrogate!r}; use {AUTO_SURROGATE!r} or one of "
                               f"{', '.join(SURROGATES)}")
        if self.amplitude not in AMPLITUDE_METHODS:
            raise AnalysisError(f"amplitude must be one of {AMPLITUDE_METHODS}, got {self.amplitude!r}")
        object.__setattr__(self, "amplitude", AmplitudeEstimate(self.amplitude))
        if self.summit_rule not in SUMMIT_RULES:
            raise AnalysisError(f"unknown summit rule {self.summit_rule!r}; use one of {', '.join(SUMMIT_RULES)}")

    @property
    def holdout_start(self) -> int:
        """Surrogates per fold the held-out validation starts with (resolved in ``__post_init__``)."""
        return int(self.holdout_realizations or HOLDOUT_REALIZATIONS)

    @property
    def summit_looks(self) -> int:
        """The looks the summit check may take: the ensemble doubles from ``realizations`` within
        ``summit_max_realizations`` (the L of :func:`~stochfric.process.decisions.decision_margin`; before the
        budget is resolved for a map, the most the default rule allows, which decides no more readily)."""
        budget = self.summit_max_realizations
        return looks_within(self.realizations, int(budget) if budget is not None else
                            SUMMIT_MAX_GROWTH * int(self.realizations))

    def with_summit_budget(self, points: int) -> AnalysisConfig:
        """This configuration with the summit check's budget resolved for an ensemble of surrogates of ``points``
        surface points (:func:`summit_budget`); unchanged when the budget was given."""
        if self.summit_max_realizations is not None:
            return self
        return replace(self, summit_max_realizations=summit_budget(self.realizations, points))

    @property
    def holdout_budget(self) -> int:
        """The most surrogates per fold the held-out validation may make."""
        return int(self.holdout_max_realizations or HOLDOUT_MAX_REALIZATIONS)

    @property
    def surrogate_options(self) -> SurrogateOptions:
        """The surrogate settings (``surrogate``, ``amplitude``, ``iaaft_tol``, ``summit_rule``) as one
        object; ``"auto"`` stands here as ``"quilt"`` until :meth:`surrogate_for` resolves it for a map."""
        method = QUILT_METHOD if self.surrogate == AUTO_SURROGATE else self.surrogate
        return SurrogateOptions(method=method, amplitude=self.amplitude, iaaft_tol=self.iaaft_tol,
                                rule=self.summit_rule)

    def surrogate_for(self, heights: list[FloatArray]) -> tuple[SurrogateOptions, str]:
        """The surrogate options for these maps and why.  ``"auto"``: random phases where they are exact,
        i.e. where every map's curvature is that of a Gaussian field
        (:func:`~stochfric.surface.statistics.curvature_gaussianity`); otherwise ``"quilt"`` when every
        map can be quilted (:func:`~stochfric.surface.quilting.quilt_applicable`), ``"phase"`` when not."""
        opts = self.surrogate_options
        if self.surrogate != AUTO_SURROGATE:
            return opts, f"{self.surrogate} (chosen by the user)"
        counts = [find_summits(h, (1.0, 1.0), rule=self.summit_rule).count for h in heights]
        tests = [curvature_gaussianity(h, n) for h, n in zip(heights, counts, strict=True)]
        kurt = ", ".join(f"{t.laplacian_kurtosis:.3g}" for t in tests)
        if all(t.gaussian for t in tests):
            return replace(opts, method=PHASE_METHOD), (
                f"{PHASE_METHOD} (auto: Gaussian curvature, Laplacian kurtosis {kurt} within "
                f"{tests[0].limit:g}·√(24/n_s) of 3: random phases are exact)")
        quilt = surrogate_method(QUILT_METHOD)
        verdicts = [quilt.applicable(h, rule=self.summit_rule) for h in heights]
        if all(ok for ok, _ in verdicts):
            return opts, (f"{QUILT_METHOD} (auto: non-Gaussian curvature, Laplacian kurtosis {kurt}; "
                          + "; ".join(r for _, r in verdicts) + ")")
        why = next(r for ok, r in verdicts if not ok)
        return replace(opts, method=PHASE_METHOD), (
            f"{PHASE_METHOD} (auto: non-Gaussian curvature, Laplacian kurtosis {kurt}, but cannot quilt: {why})")

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary (JSON / netCDF attributes)."""
        return dict(self.__dict__)

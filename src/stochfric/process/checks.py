"""Checks of the statistical contact analysis against itself (method §3, §4b, §4e).

* :func:`surrogate_check` — does the measured map look like a member of its own surrogate
  ensemble (summit count, β̄, σ_S, μ(u))?  (:class:`SurrogateCheck`)
* :func:`ergodicity_check` — path statistics of one long surface against the ensemble of
  independent long surfaces from the same generator (Fig. 3.18b).  (:class:`ErgodicityCheck`)
* :func:`check_generated_process` — realisations of the friction-process model against their
  target standard deviation and spectrum (Fig. 3.23).  (:class:`ProcessCheck`)
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Sequence
from dataclasses import dataclass, field, fields
from typing import Any, ClassVar

import numpy as np
import numpy.typing as npt
from scipy import stats as sps

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import asperity_sums, bowden_tabor_mu
from stochfric.contact.materials import Material
from stochfric.errors import AnalysisError, InputError
from stochfric.friction_process.model_base import FrictionProcessModel
from stochfric.friction_process.spectral import one_sided_psd
from stochfric.process.decisions import (
    SUMMIT_ALPHA,
    critical_value,
    decision_margin,
    monte_carlo_draws_to_decide,
    monte_carlo_rank_decision,
)
from stochfric.process.ensemble import ContactSamples, SurrogateOptions, summit_statistics
from stochfric.process.verbatim import (
    BlockMatcher,
    VerbatimMeasure,
    default_block,
    pool_verbatim,
    verbatim_fraction,
)
from stochfric.random import SeedLike, as_seed_sequence, spawn_generators
from stochfric.surface.io import Surface
from stochfric.surface.quilting import COPY_NCC_LIMIT, COPY_PIECE_LIMIT, copy_metrics
from stochfric.surface.summits import DEFAULT_SUMMIT_RULE, find_summits

__all__ = [
    "COPY_CHECK_SURROGATES",
    "ERGODICITY_ALPHA",
    "SURROGATE_Z_LIMIT",
    "WINDOW_CHECK_ALPHA",
    "WINDOW_MIN_SUMMITS",
    "WINDOW_TILES",
    "CopyCheck",
    "ErgodicityCheck",
    "ProcessCheck",
    "ScanScatter",
    "SurrogateCheck",
    "WindowScatterCheck",
    "check_generated_process",
    "copy_check",
    "ergodicity_check",
    "surrogate_check",
    "window_scatter_check",
    "window_tiles",
]


#: Family-wise false-alarm probability of the ergodicity verdict (two-sided, Bonferroni).
ERGODICITY_ALPHA = 0.05


def _json_fields(check: Any) -> dict[str, Any]:
    """The fields of the dataclass ``check`` by name, JSON-ready (tuples as lists, dicts copied)."""
    def plain(value: Any) -> Any:
        if isinstance(value, tuple | list):
            return [plain(v) for v in value]
        if isinstance(value, dict):
            return {k: plain(v) for k, v in value.items()}
        return value

    return {f.name: plain(getattr(check, f.name)) for f in fields(check)}


@dataclass(frozen=True, kw_only=True)
class _ZVerdict:
    """A family of z tests read together: consistent if every |z| ≤ ``threshold`` (two-sided,
    Bonferroni over the tests); ``max_abs_z`` is the largest |z|.  A subclass names what is
    consistent (``SUBJECT``) and states its rule (``RULE``) for the JSON."""

    SUBJECT: ClassVar[str]
    RULE: ClassVar[str]

    threshold: float
    consistent: bool
    max_abs_z: float

    @property
    def verdict(self) -> str:
        """``"consistent …"`` or ``"NOT consistent …"``."""
        verdict = "consistent" + self.SUBJECT
        return verdict if self.consistent else "NOT " + verdict

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: the fields, the verdict and the rule."""
        return {**_json_fields(self), "verdict": self.verdict, "rule": self.RULE}


@dataclass(frozen=True, kw_only=True)
class ErgodicityCheck(_ZVerdict):
    """Path statistics of one long surface against the ensemble of independent ones (method §4b).

    Like with like: both populations are the **non-overlapping windows of long surfaces from the
    same generator** (K surfaces × J windows, :attr:`PathContact.blocks`).  Per approach:

    * **mean** — one-way analysis of variance: F = J·Σ(m_k − m̄)²/(K−1) over
      ΣΣ(μ_kj − m_k)²/(K(J−1)), m_k the path mean of surface k.  A non-ergodic process gives every
      realisation its own mean, and the path means scatter more than the windows along a path
      explain (F large).  ``z_mean`` is the two-sided-equivalent z of the one-sided p-value.
    * **standard deviation** — D = mean_k sd_j(μ_kj) − mean_j sd_k(μ_kj): the scatter *along*
      one surface against the scatter *across* independent surfaces at a fixed position;
      ``z_std`` = D / SE, SE by the jackknife over surfaces (the surfaces are the independent
      units, so correlation between windows of one surface is accounted for).

    Verdict: consistent if every |z| ≤ ``threshold`` = Φ⁻¹(1 − α/(4U)) (two-sided, Bonferroni
    over the 2U tests, α = 0.05).  The false-alarm rate measured on a surface that is ergodic by
    construction is in docs/statistical_contact.md and tests/statistical/test_ergodicity.py.
    """

    SUBJECT = " with ergodicity"
    RULE = ("non-overlapping windows of K independent long surfaces of one generator: ANOVA of the path means "
            "and jackknife z of sd along a path minus sd across surfaces; |z| <= Bonferroni threshold "
            "(alpha = 0.05, 2U tests)")

    z_mean: tuple[float, ...]
    z_std: tuple[float, ...]
    p_mean: tuple[float, ...]
    path_std: tuple[float, ...]
    ensemble_std: tuple[float, ...]
    surfaces: int
    windows_per_surface: int


def _sd_difference(mu: FloatArray) -> float:
    """mean over surfaces of sd along the path − mean over positions of sd across surfaces."""
    return float(np.mean(mu.std(axis=1, ddof=1)) - np.mean(mu.std(axis=0, ddof=1)))


def ergodicity_check(blocks_mu: npt.ArrayLike, *, alpha: float = ERGODICITY_ALPHA) -> ErgodicityCheck:
    """Ergodicity of μ along the path from non-overlapping windows, shape (K surfaces, J, U)."""
    mu = np.asarray(blocks_mu, dtype=np.float64)
    if mu.ndim != 3 or mu.shape[0] < 3 or mu.shape[1] < 2:
        raise InputError("need μ of shape (surfaces >= 3, windows per surface >= 2, approaches)")
    if not np.all(np.isfinite(mu)):
        raise AnalysisError("a window carries no load at some approach (μ undefined); use larger approaches")
    k_count, j_count, n_u = mu.shape
    z_mean, z_std, p_mean, path_sd, ens_sd = [], [], [], [], []
    for u in range(n_u):
        x = mu[:, :, u]
        m_k = x.mean(axis=1)
        msb = j_count * float(np.sum((m_k - m_k.mean()) ** 2)) / (k_count - 1)
        msw = float(np.sum((x - m_k[:, None]) ** 2)) / (k_count * (j_count - 1))
        if msw > 0.0:
            p = float(sps.f.sf(msb / msw, k_count - 1, k_count * (j_count - 1)))
        else:
            p = 1.0 if msb == 0.0 else 0.0
        p_mean.append(p)
        z_mean.append(float(sps.norm.isf(max(p, 1e-300) / 2.0)))
        d = _sd_difference(x)
        loo = np.array([_sd_difference(np.delete(x, k, axis=0)) for k in range(k_count)])
        se = math.sqrt((k_count - 1) / k_count * float(np.sum((loo - loo.mean()) ** 2)))
        z_std.append(d / se if se > 0.0 else (0.0 if d == 0.0 else math.copysign(math.inf, d)))
        path_sd.append(float(np.mean(x.std(axis=1, ddof=1))))
        ens_sd.append(float(np.mean(x.std(axis=0, ddof=1))))
    threshold = float(sps.norm.isf(alpha / (4.0 * n_u)))
    max_abs = float(np.max(np.abs(np.concatenate((z_mean, z_std)))))
    return ErgodicityCheck(
        z_mean=tuple(z_mean),
        z_std=tuple(z_std),
        p_mean=tuple(p_mean),
        path_std=tuple(path_sd),
        ensemble_std=tuple(ens_sd),
        threshold=threshold,
        consistent=bool(max_abs <= threshold),
        max_abs_z=max_abs,
        surfaces=k_count,
        windows_per_surface=j_count,
    )


#: |z| of the measured map against the surrogate ensemble above which the surrogates are not
#: credible for that surface (the measured value lies outside ±3 ensemble standard deviations).
SURROGATE_Z_LIMIT = 3.0

_SUMMIT_STAT_NAMES = ("summit_count", "summit_radius_mean_m", "summit_height_std_m")


@dataclass(frozen=True, kw_only=True)
class SurrogateCheck:
    """Does the measured map look like a member of its own surrogate ensemble? (method §3)

    Checked: summit count, mean summit radius β̄, summit-height standard deviation σ_S, and μ(u) at every
    approach (the measured map referenced to its own highest summit, like every realisation).  Per quantity
    z = (value − median) / (1.4826 × MAD), median and MAD over the map *and* its R realisations together: a
    robust measure of the ensemble's spread (not the standard error of its centre: the question is whether
    the map could be one of the realisations).

    **One test for all quantities** (since 2026-11-28; a Monte Carlo rank test of the largest |z|, Barnard
    1963, Besag & Diggle 1977, the "global envelope" of Myllymäki et al. 2017): T = max |z| over the quantities
    for the map and for every realisation; under "the map is a member of the ensemble" the R + 1 values of T
    are exchangeable, so the map fails when (1 + K)/(R + 1) ≤ α, K the realisations with T ≥ the map's —
    an exact family-wise false-alarm rate α = :data:`~stochfric.process.decisions.SUMMIT_ALPHA` for any R and
    any correlation or shape of the quantities (with S pooled scans, each scan against the ensemble at α/S).
    ``limit`` is the critical value of T that follows (the realisations' T at that rank): "every |z| <
    limit" is the test.  The verdict is decided against the Monte Carlo error of K
    (:func:`~stochfric.process.decisions.monte_carlo_rank_decision`).  Before, each |z| was held against a
    fixed limit 3 with a bootstrap SE and a Bonferroni margin over 16 quantities; that margin (about ±0.9 in
    z at R = 100) left an exactly Gaussian map whose model is exact ``undecided`` (docs §0e).  The extreme-rank-length
    form of the rank test (no scale) was tried for this check and measured worse: on al3d-1 at the defaults its K
    swung between 0 and 12 of 100 over 10 seeds (the map's own rank vector moves with the draws), where the
    largest |z| gave K/R 0.015–0.065 (docs §0e).  The decision bounds the binomial error of K only, not the
    dependence of the map's own T on the draws through the median and MAD (at R = 40 al3d-1 passed for 2 of 10
    seeds that larger ensembles fail).
    """

    measured: dict[str, float]
    ensemble_mean: dict[str, float]
    ensemble_std: dict[str, float]
    z: dict[str, float]
    mu_measured: tuple[float, ...]
    mu_z: tuple[float, ...]
    limit: float
    credible: bool
    surrogate: str
    amplitude: str
    per_scan_z: tuple[dict[str, float], ...] = ()
    #: The robust centre (median) and scale (1.4826 × MAD) of the ensemble the z use, for the summit
    #: statistics and for μ(u).
    ensemble_center: dict[str, float] = field(default_factory=dict)
    ensemble_scale: dict[str, float] = field(default_factory=dict)
    mu_center: tuple[float, ...] = ()
    mu_scale: tuple[float, ...] = ()
    #: Bootstrap standard errors of ``z`` and ``mu_z`` over the realisations (empty: the Gaussian formula).
    z_se: dict[str, float] = field(default_factory=dict)
    mu_z_se: tuple[float, ...] = ()
    #: The Monte Carlo rank test (class docstring): the map's largest |z| (the worst scan's), how many of the
    #: R realisations reach it (K), and the level per scan (α/S).  None: a record from before the test, decided
    #: by the per-quantity rule of :meth:`decided`.
    global_t: float | None = None
    global_exceed: int | None = None
    global_alpha: float | None = None

    @property
    def max_abs_mu_z(self) -> float | None:
        """The largest |z| of the measured map's μ(u) against the ensemble (None without approaches)."""
        return float(np.nanmax(np.abs(self.mu_z))) if self.mu_z else None

    def decided(self, realizations: int, margin: float | None = None, looks: int = 1) -> tuple[list[str], list[str]]:
        """The failures a seed cannot undo and the quantities a seed could flip.

        The Monte Carlo rank test (class docstring) decided against the binomial error of K
        (:func:`~stochfric.process.decisions.monte_carlo_rank_decision`, ``looks`` the looks the ensemble may
        take): failed — the quantities at or beyond ``limit`` (the worst at least); undecided — the worst
        quantity.  A record without the test (saved before 2026-11-28) is decided per quantity: |z| against
        the limit 3 with its bootstrap SE and the margin ``margin`` (default
        :func:`~stochfric.process.decisions.decision_margin` over the quantities and ``looks``)."""
        if self.global_exceed is not None and self.global_alpha is not None:
            verdict = monte_carlo_rank_decision(self.global_exceed, realizations, self.global_alpha, looks)
            if verdict == "pass":
                return [], []
            items = self._estimates(realizations)
            worst = [n for n, v, _ in items if not abs(v) < self.limit] or [
                max(items, key=lambda it: abs(it[1]) if math.isfinite(it[1]) or math.isinf(it[1]) else -1.0)[0]]
            return (worst, []) if verdict == "fail" else ([], worst)
        items = self._estimates(realizations)
        k = self._margin(items, looks) if margin is None else margin
        failed, near = [], []
        for name, v, se in items:
            if not math.isfinite(v):
                if math.isinf(v):
                    failed.append(name)
                continue
            if abs(v) - k * se >= self.limit:
                failed.append(name)
            elif abs(v) + k * se >= self.limit:
                near.append(name)
        return failed, near

    def _estimates(self, realizations: int) -> list[tuple[str, float, float]]:
        """(name, z, SE_z) of every quantity (μ as ``mu(u_k)``): the bootstrap SE where recorded, else the
        Gaussian formula √((π/2)/R + 1.36 z²/R)."""
        r = max(int(realizations), 3)
        items = [*self.z.items(), *((f"mu(u_{k})", v) for k, v in enumerate(self.mu_z))]
        boot = [*(self.z_se.get(n, math.nan) for n in self.z),
                *(self.mu_z_se[k] if k < len(self.mu_z_se) else math.nan for k in range(len(self.mu_z)))]
        return [(name, v, se if math.isfinite(se) else math.sqrt(0.5 * math.pi / r + MAD_SCALE_VARIANCE * v * v / r))
                for (name, v), se in zip(items, boot, strict=True)]

    @staticmethod
    def _margin(items: list[tuple[str, float, float]], looks: int) -> float:
        """:func:`~stochfric.process.decisions.decision_margin` over the defined quantities and ``looks``."""
        return decision_margin(max(1, sum(1 for _, v, _ in items if not math.isnan(v))), looks)

    def realizations_to_decide(self, realizations: int, looks: int = 1) -> int | None:
        """About how many realisations would decide an undecided check (None when decided, or when the map
        sits on the limit itself).  The rank test: :func:`~stochfric.process.decisions.monte_carlo_draws_to_decide`.
        A record without it: SE_z falls as 1/√R, so a quantity at distance δ = ||z| − limit| is decided once
        k·SE_z·√(R/R') < δ, R' = R (k SE_z/δ)², rounded up to R·2^j."""
        if self.global_exceed is not None and self.global_alpha is not None:
            return monte_carlo_draws_to_decide(self.global_exceed, realizations, self.global_alpha, looks)
        _, near = self.decided(realizations, looks=looks)
        if not near:
            return None
        items = self._estimates(realizations)
        k = self._margin(items, looks)
        r = max(int(realizations), 1)
        need = r
        for name, v, se in items:
            if name not in near:
                continue
            gap = abs(abs(v) - self.limit)
            if not se > 0.0 or gap < 1e-3:
                return None  # on the limit itself: no number of realisations decides it
            need = max(need, math.ceil(r * (k * se / gap) ** 2))
        return int(r * 2 ** math.ceil(math.log2(need / r))) if need > r else 2 * r

    def failures(self) -> list[str]:
        """Names of the quantities with |z| ≥ limit (μ as ``mu(u_k)``)."""
        out = [n for n, v in self.z.items() if not abs(v) < self.limit]
        out += [f"mu(u_{k})" for k, v in enumerate(self.mu_z) if not abs(v) < self.limit]
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary: the fields, the largest |z| of μ, the failures and the rule."""
        return {**_json_fields(self), "max_abs_mu_z": self.max_abs_mu_z,
                "failures": self.failures(),
                "rule": ("z = (measured - median) / (1.4826 x MAD) over the map and its realisations; Monte Carlo "
                         "rank test of max |z| at the family-wise level global_alpha: credible if every |z| < limit"
                         if self.global_exceed is not None else
                         "z = (measured - ensemble median) / (1.4826 x ensemble MAD); credible if every |z| < limit")}


def _worst(z: FloatArray) -> FloatArray:
    """Per column, the entry of largest magnitude over the rows (scans)."""
    idx = np.argmax(np.abs(np.where(np.isnan(z), 0.0, z)), axis=0)
    return np.take_along_axis(z, idx[None, :], axis=0)[0]


def surrogate_check(
    surface: Surface | Sequence[Surface], material: Material, ensemble: ContactSamples, *,
    rule: str = DEFAULT_SUMMIT_RULE, alpha: float = SUMMIT_ALPHA,
) -> SurrogateCheck:
    """Compare the measured ``surface`` with its surrogate ``ensemble`` (:func:`ensemble_contact`) by the Monte
    Carlo rank test of :class:`SurrogateCheck` at the family-wise level ``alpha``.

    With several scans of one surface, every scan is compared with the whole ensemble (all its
    realisations stand for the same surface) at ``alpha``/S; ``measured`` holds the mean over the scans,
    ``z`` and ``mu_z`` the largest-magnitude z over the scans, ``per_scan_z`` each scan's, the test the scan
    with the fewest realisations at least as extreme.
    """
    if ensemble.summit_stats is None:
        raise InputError("the ensemble carries no summit statistics (use ensemble_contact)")
    if not 0.0 < alpha < 1.0:
        raise InputError(f"the summit check's level must lie in (0, 1), got {alpha!r}")
    scans = [surface] if isinstance(surface, Surface) else list(surface)
    stats = ensemble.summit_stats
    e_mean = stats.mean(axis=0)
    e_sd = stats.std(axis=0, ddof=1)
    e_center, e_scale = robust_center_scale(stats)
    u = ensemble.approach_m
    mu_e = ensemble.mu
    mu_center, mu_scale = robust_center_scale(mu_e)
    ens_rows = np.column_stack([stats, mu_e])
    n_stats = stats.shape[1]
    alpha_scan = float(alpha) / len(scans)
    metas, mus, zs, mu_zs, tests = [], [], [], [], []
    for scan in scans:
        s = find_summits(scan.heights_m, scan.grid_spacing_m, rule=rule)
        meas = summit_statistics(s.heights_m, s.radius_m)
        if s.count:
            area, force, _count = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=material.e_star_pa)
            mu_meas = bowden_tabor_mu(area, force, material.shear_strength_pa)
        else:
            mu_meas = np.full(u.size, np.nan)
        z_rows = _pooled_z(np.vstack([np.concatenate([meas, mu_meas])[None, :], ens_rows]))
        t = _max_abs(z_rows)
        exceed = int(np.sum(t[1:] >= t[0]))
        tests.append((exceed, float(t[0]), critical_value(t[1:], alpha_scan)))
        metas.append(meas)
        mus.append(mu_meas)
        zs.append(z_rows[0, :n_stats])
        mu_zs.append(z_rows[0, n_stats:])
    z = _worst(np.stack(zs))
    mu_z = _worst(np.stack(mu_zs))
    exceed, t_map, limit = min(tests, key=lambda it: (it[0], -it[1]))
    meas = np.mean(np.stack(metas), axis=0)
    mu_meas = np.mean(np.stack(mus), axis=0)
    names = _SUMMIT_STAT_NAMES
    r = ens_rows.shape[0]
    credible = bool((1.0 + exceed) / (r + 1.0) > alpha_scan)
    return SurrogateCheck(
        measured={n: float(v) for n, v in zip(names, meas, strict=True)},
        ensemble_mean={n: float(v) for n, v in zip(names, e_mean, strict=True)},
        ensemble_std={n: float(v) for n, v in zip(names, e_sd, strict=True)},
        z={n: float(v) for n, v in zip(names, z, strict=True)},
        mu_measured=tuple(float(v) for v in mu_meas),
        mu_z=tuple(float(v) for v in mu_z),
        limit=limit,
        credible=credible,
        surrogate=str(ensemble.info.get("surrogate", "")),
        amplitude=str(ensemble.info.get("amplitude", "")),
        per_scan_z=tuple({n: float(v) for n, v in zip(names, zz, strict=True)} for zz in zs),
        ensemble_center={n: float(v) for n, v in zip(names, e_center, strict=True)},
        ensemble_scale={n: float(v) for n, v in zip(names, e_scale, strict=True)},
        mu_center=tuple(float(v) for v in mu_center), mu_scale=tuple(float(v) for v in mu_scale),
        global_t=t_map, global_exceed=exceed, global_alpha=alpha_scan,
    )


def _pooled_z(rows: FloatArray) -> FloatArray:
    """z of every row (the map first, then the realisations) per column against the median and 1.4826 × MAD of
    all rows together (exchangeable under the null).  A column all rows share has z = 0; one the rows differ
    in with no spread (MAD and sd 0 cannot differ) is impossible; a row's NaN stays NaN."""
    center, scale = robust_center_scale(rows)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = (rows - center) / scale
    z = np.where(np.isfinite(scale) & (scale > 0.0), z, np.where(rows == center, 0.0, np.inf))
    return np.where(np.isnan(rows), np.nan, z)


def _max_abs(z: FloatArray) -> FloatArray:
    """Per row the largest |z| over the columns with a value (−∞ for a row without any)."""
    a = np.abs(z)
    return np.asarray(np.max(np.where(np.isnan(a), -np.inf, a), axis=1), dtype=np.float64)


#: 1.4826 × MAD estimates a Gaussian sd; its asymptotic variance is about 1.36 σ²/R (efficiency 37 %).
MAD_TO_SD = 1.482602218505602
MAD_SCALE_VARIANCE = 1.36


def robust_center_scale(samples: FloatArray) -> tuple[FloatArray, FloatArray]:
    """Per column over the finite rows: the median and 1.4826 × the median absolute deviation (the sd where
    the MAD is 0, e.g. a summit count most realisations share); NaN without finite rows."""
    x = np.asarray(samples, dtype=np.float64)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        center = np.nanmedian(x, axis=0)
        scale = MAD_TO_SD * np.nanmedian(np.abs(x - center), axis=0)
        sd = np.nanstd(x, axis=0, ddof=1)
    return center, np.where(scale > 0.0, scale, sd)


#: Surrogates whose overlap with the map (and with each other) is measured by :func:`copy_check`.
COPY_CHECK_SURROGATES = 4


@dataclass(frozen=True, kw_only=True)
class CopyCheck:
    """Are the surrogates new surfaces?  (:func:`copy_check`): the largest normalised cross-correlation
    of the first surrogates with the map and between pairs of them, the largest verbatim piece of the
    map (methods that resample it), their limits and the verdict."""

    surrogates: int
    max_ncc_with_map: float | None
    largest_piece_fraction: float | None
    max_ncc_between_surrogates: float | None
    ncc_limit: float = COPY_NCC_LIMIT
    piece_limit: float = COPY_PIECE_LIMIT
    is_copy: bool
    #: The verbatim content measured independently of how the surrogates were made
    #: (:func:`~stochfric.process.verbatim.verbatim_fraction`, pooled over the surrogates).
    verbatim: VerbatimMeasure | None = None
    rule: str = ("first realisations made again from their seeds; largest NCC over all shifts (>= 1/4 overlap) "
                 "with the map and between pairs of surrogates, largest verbatim piece of the map (quilt); a copy "
                 "above the limits; verbatim fraction by curvature-block matching at the summit scale")

    @property
    def label(self) -> str:
        """``copy``, ``resampling`` (mostly verbatim pieces of the measurement: a block bootstrap) or ``new``."""
        if self.is_copy:
            return "copy"
        return self.verbatim.label if self.verbatim is not None else "new"

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (the fields by name, the verbatim measure as its dict, the label)."""
        out = {f.name: getattr(self, f.name) for f in fields(self) if f.name != "verbatim"}
        out["verbatim"] = None if self.verbatim is None else self.verbatim.to_dict()
        out["label"] = self.label
        return out


@dataclass(frozen=True, kw_only=True)
class ScanScatter:
    """Scatter of μ(u) between pooled scans beside the scatter within a scan and the ensemble's
    (:func:`~stochfric.process.statistics.analyse`); lists over the approaches, None where undefined."""

    scans: int
    #: μ of each whole scan (scans × U).
    scan_mu: list[list[float | None]]
    between_scan_std: list[float | None]
    within_scan_window_std: list[float | None]
    ensemble_std: list[float | None]
    rule: str = ("between: sd over scans of mu of each whole scan; within: sd over the disjoint windows of one "
                 "scan, mean over scans; ensemble: sd of mu over the surrogates of original size")

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (the fields by name)."""
        return _json_fields(self)


def copy_check(
    scans: Sequence[Surface], options: SurrogateOptions, seeds: Sequence[np.random.SeedSequence], *,
    count: int = COPY_CHECK_SURROGATES,
) -> CopyCheck:
    """Are the surrogates new surfaces?  The first ``count`` realisations are made again from their
    own seed streams (``seeds[r]``, scan ``r mod S``, the same numbers as in the ensemble) and
    compared with their scan and with each other (:func:`stochfric.surface.quilting.copy_metrics`:
    the largest normalised cross-correlation over all shifts and, for a method that resamples the
    map (:attr:`~stochfric.surface.surrogates.SurrogateMethod.resamples`), the largest verbatim
    piece of the map).  ``is_copy`` when any exceeds its limit."""
    n = min(int(count), len(seeds))
    method, settings = options.surrogate, options.settings
    maps, rows, verbatim = [], [], []
    matchers = [BlockMatcher(s.heights_m, default_block(s.heights_m, options.rule)) for s in scans[:n]]
    for r in range(n):
        scan = scans[r % len(scans)]
        gen = np.random.Generator(np.random.PCG64(seeds[r]))
        h, source = method.copy_sample(scan.heights_m, gen, settings)
        rows.append(copy_metrics(h, scan.heights_m, source=source))
        verbatim.append(verbatim_fraction(h, scan.heights_m, matcher=matchers[r % len(scans)], rng=r,
                                          rule=options.rule))
        maps.append(h)
    pairs = [copy_metrics(maps[a], maps[a + 1]) for a in range(0, n - 1, 2)]
    return CopyCheck(
        surrogates=n,
        max_ncc_with_map=max((m.max_ncc for m in rows), default=None),
        largest_piece_fraction=max((m.largest_piece_fraction for m in rows), default=None),
        max_ncc_between_surrogates=max((m.max_ncc for m in pairs), default=None),
        is_copy=any(m.is_copy for m in rows) or any(m.is_copy for m in pairs),
        verbatim=pool_verbatim(verbatim) if verbatim else None,
    )


#: Family-wise false-alarm probability of the measured-window check (two-sided, Bonferroni over U).
WINDOW_CHECK_ALPHA = 0.05
#: Default number of tiles per side of the measured-window check (16 disjoint windows of a quarter
#: of the map's side), reduced when the tiles would hold fewer than ``WINDOW_MIN_SUMMITS`` summits.
WINDOW_TILES = 4
WINDOW_MIN_SUMMITS = 20


def window_tiles(summit_count: int, tiles: int = WINDOW_TILES, min_summits: int = WINDOW_MIN_SUMMITS) -> int | None:
    """Tiles per side for the measured-window check: the largest n ≤ ``tiles`` with at least 2
    whose n² tiles hold ``min_summits`` summits each on average; None if even 2 × 2 do not."""
    for n in range(int(tiles), 1, -1):
        if summit_count / (n * n) >= min_summits:
            return n
    return None


def _variance_df(n: int, kurtosis: float) -> float:
    """Effective degrees of freedom of a sample variance of n values with kurtosis κ:
    Var(s²) = σ⁴(κ − (n−3)/(n−1))/n = 2σ⁴/df (n − 1 for a Gaussian sample)."""
    return 2.0 * n / max(kurtosis - (n - 3) / (n - 1), 1e-12)


@dataclass(frozen=True, kw_only=True)
class WindowScatterCheck(_ZVerdict):
    """Scatter of μ(u) across windows of size w: the measurement against its surrogates (method §3).

    The prepared measurement is cut into disjoint ``tiles × tiles`` windows of size w (J windows
    over all scans); every surrogate of original size is cut the same way (R·J' windows).  Each
    window is analysed on its own (referenced to its own highest summit).  Per approach:
    s_m = sd of μ over the measured windows, s_s = sd over the surrogate windows, and the
    variance ratio F = s_m²/s_s² is referred to an F distribution with the effective degrees of
    freedom df = 2n/(κ − (n−3)/(n−1)) of each side (Var(s²) = 2σ⁴/df; n − 1 for Gaussian μ), κ
    the kurtosis of μ over the surrogate windows (no Gaussian assumption; under the null both
    populations share it; an F rather than a normal approximation because J is small).  ``z`` is
    the signed two-sided-equivalent normal deviate of that test; the CIs are the χ²(df)
    intervals of each sd.  Consistent if every |z| ≤ Φ⁻¹(1 − α/(2U)) (two-sided, Bonferroni
    over the U approaches, α = 0.05).  This check
    uses the measurement itself as the reference: a surrogate method cannot pass it by
    construction, only by making windows that scatter like the measured ones.
    """

    SUBJECT = ""
    RULE = ("sd of mu over disjoint windows of the measurement vs over the same windows of the surrogates; F test "
            "of the variance ratio with kurtosis-adjusted degrees of freedom (kurtosis from the surrogate windows), "
            "as a two-sided z; |z| <= Bonferroni threshold (alpha = 0.05, U approaches)")

    tiles: int
    window_size_m: tuple[float, float]
    measured_windows: int
    surrogate_windows: int
    measured_std: tuple[float, ...]
    measured_std_ci95: tuple[tuple[float, float], ...]
    surrogate_std: tuple[float, ...]
    surrogate_std_ci95: tuple[tuple[float, float], ...]
    measured_mean: tuple[float, ...]
    surrogate_mean: tuple[float, ...]
    kurtosis: tuple[float, ...]
    z: tuple[float, ...]


def window_scatter_check(
    measured_mu: npt.ArrayLike, surrogate_mu: npt.ArrayLike, *, tiles: int, window_size_m: tuple[float, float],
    alpha: float = WINDOW_CHECK_ALPHA,
) -> WindowScatterCheck:
    """The measured-window check (:class:`WindowScatterCheck`) from μ of the measured windows,
    shape (J, U), and of the surrogate windows, shape (R, J', U) or (R·J', U)."""
    m = np.asarray(measured_mu, dtype=np.float64)
    s = np.asarray(surrogate_mu, dtype=np.float64)
    s = s.reshape(-1, s.shape[-1])
    if m.ndim != 2 or m.shape[0] < 3 or s.shape[0] < 4 or m.shape[1] != s.shape[1]:
        raise InputError("need mu of >= 3 measured and >= 4 surrogate windows over the same approaches")
    n_u = m.shape[1]
    out: dict[str, list[Any]] = {k: [] for k in ("sm", "smci", "ss", "ssci", "mm", "ms", "kap", "z")}
    for k in range(n_u):
        a = m[:, k][np.isfinite(m[:, k])]
        b = s[:, k][np.isfinite(s[:, k])]
        if a.size < 3 or b.size < 4:
            raise AnalysisError(
                "a window of the measured-window check carries no load at some approach; use larger approaches"
            )
        sa, sb = float(a.std(ddof=1)), float(b.std(ddof=1))
        cb = b - b.mean()
        kap = float(np.mean(cb**4) / np.mean(cb**2) ** 2) if sb > 0.0 else 3.0
        df_a, df_b = _variance_df(a.size, kap), _variance_df(b.size, kap)
        if sa > 0.0 and sb > 0.0:
            ratio = (sa / sb) ** 2
            p_lo = float(sps.f.cdf(ratio, df_a, df_b))
            p_two = min(1.0, 2.0 * min(p_lo, 1.0 - p_lo))
            z = math.copysign(float(sps.norm.isf(max(p_two, 1e-300) / 2.0)), ratio - 1.0)
        else:
            z = 0.0 if sa == sb else math.inf
        ci_a = (sa * math.sqrt(df_a / sps.chi2.isf(0.025, df_a)), sa * math.sqrt(df_a / sps.chi2.isf(0.975, df_a)))
        ci_b = (sb * math.sqrt(df_b / sps.chi2.isf(0.025, df_b)), sb * math.sqrt(df_b / sps.chi2.isf(0.975, df_b)))
        out["sm"].append(sa)
        out["smci"].append(ci_a)
        out["ss"].append(sb)
        out["ssci"].append(ci_b)
        out["mm"].append(float(a.mean()))
        out["ms"].append(float(b.mean()))
        out["kap"].append(kap)
        out["z"].append(float(z))
    threshold = float(sps.norm.isf(alpha / (2.0 * n_u)))
    max_abs = float(np.max(np.abs(out["z"])))
    return WindowScatterCheck(
        tiles=int(tiles), window_size_m=(float(window_size_m[0]), float(window_size_m[1])),
        measured_windows=int(m.shape[0]), surrogate_windows=int(s.shape[0]),
        measured_std=tuple(out["sm"]), measured_std_ci95=tuple(out["smci"]), surrogate_std=tuple(out["ss"]),
        surrogate_std_ci95=tuple(out["ssci"]), measured_mean=tuple(out["mm"]), surrogate_mean=tuple(out["ms"]),
        kurtosis=tuple(out["kap"]), z=tuple(out["z"]), threshold=threshold, consistent=bool(max_abs <= threshold),
        max_abs_z=max_abs,
    )  # fmt: skip


@dataclass(frozen=True, kw_only=True)
class ProcessCheck:
    """Generated process vs its target at some pressures (Fig. 3.23 analogue).

    Per pressure: target σ = √variance(p) and the generated standard deviation of μ̂ at one grid
    point over the realisations (``std_pointwise``, with its standard error from the fourth
    moment) and the mean grid standard deviation of the realisations; the target spectrum and
    the realisations' mean periodogram (method §0) with its standard error.
    """

    pressure_pa: tuple[float, ...]
    target_std: tuple[float, ...]
    std_pointwise: tuple[float, ...]
    std_pointwise_se: tuple[float, ...]
    std_grid_mean: tuple[float, ...]
    frequencies: tuple[float, ...]
    target_psd: tuple[tuple[float, ...], ...]
    generated_psd: tuple[tuple[float, ...], ...]
    generated_psd_se: tuple[tuple[float, ...], ...]
    realizations: int

    def max_std_z(self) -> float:
        """Largest |std_pointwise − target| / SE over the pressures."""
        z = [abs(g - t) / s for g, t, s in zip(self.std_pointwise, self.target_std, self.std_pointwise_se, strict=True)]
        return float(max(z))

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready summary (no spectra)."""
        return {
            "pressure_pa": list(self.pressure_pa),
            "target_std": list(self.target_std),
            "generated_std_pointwise": list(self.std_pointwise),
            "generated_std_pointwise_se": list(self.std_pointwise_se),
            "generated_std_grid_mean": list(self.std_grid_mean),
            "max_std_z": self.max_std_z(),
            "realizations": self.realizations,
        }


def check_generated_process(
    model: FrictionProcessModel,
    pressures_pa: npt.ArrayLike,
    *,
    realizations: int = 200,
    seed: SeedLike = None,
) -> ProcessCheck:
    """Generate ``realizations`` processes per pressure and compare with the target (Fig. 3.23).

    Realisation r uses the r-th child stream of ``seed`` (the same streams at every pressure).
    """
    ps = np.atleast_1d(np.asarray(pressures_pa, dtype=np.float64))
    gens_seed = as_seed_sequence(seed)
    t_std: list[float] = []
    g_std: list[float] = []
    g_se: list[float] = []
    g_grid: list[float] = []
    t_psd: list[tuple[float, ...]] = []
    g_psd: list[tuple[float, ...]] = []
    g_psd_se: list[tuple[float, ...]] = []
    freqs: FloatArray = np.empty(0)
    for p in ps:
        vals = np.stack([model.generate(float(p), g) for g in spawn_generators(gens_seed, realizations)])
        target_var = float(np.sum(model.spectrum(model.frequencies(), float(p))) / model.length)
        t_std.append(math.sqrt(target_var))
        # pointwise (x = 0) variance over the realisations: E[μ̂] = 0 is known
        x0 = vals[:, 0]
        s2 = float(np.mean(x0**2))
        se_s2 = math.sqrt(max(float(np.mean(x0**4)) - s2**2, 0.0) / realizations)
        g_std.append(math.sqrt(s2))
        g_se.append(se_s2 / (2.0 * math.sqrt(s2)) if s2 > 0 else 0.0)
        g_grid.append(float(np.mean(vals.std(axis=1))))
        freqs, per = one_sided_psd(vals, model.dx)
        t_psd.append(tuple(float(v) for v in model.spectrum(freqs, float(p))))
        g_psd.append(tuple(float(v) for v in per.mean(axis=0)))
        g_psd_se.append(tuple(float(v) for v in per.std(axis=0, ddof=1) / math.sqrt(realizations)))
    return ProcessCheck(
        pressure_pa=tuple(float(v) for v in ps),
        target_std=tuple(t_std),
        std_pointwise=tuple(g_std),
        std_pointwise_se=tuple(g_se),
        std_grid_mean=tuple(g_grid),
        frequencies=tuple(float(v) for v in freqs),
        target_psd=tuple(t_psd),
        generated_psd=tuple(g_psd),
        generated_psd_se=tuple(g_psd_se),
        realizations=realizations,
    )

"""Out-of-sample validation of a surrogate model, and the measured windows as evidence (method §3, §4b).

A surrogate method is a *model* of the measured surface.  Tested on the map it was built from, a method
that only reshuffles the map passes by construction; so the model is tested on data it never saw.

**Folds.**  Every scan is cut into two halves along its longer side.  Fold 1 builds the surrogates from
the first halves and tests them against the second; fold 2 the other way round (2-fold cross-validation).
With several scans the halves of all scans are pooled per fold.

**What is compared.**  The held-out half is cut into ``t × t`` disjoint windows (``t`` the largest number
≤ 4 whose windows hold ≥ :data:`HOLDOUT_MIN_SUMMITS` summits on average); each surrogate — of the size
of a half, made by the method from the training half — is cut the same way.  Per window: μ at every
approach (GW + Bowden–Tabor, each window referenced to its own highest summit, as in the measured-window
check), the summit count, the mean summit radius β̄ and the summit-height sd σ_S.  For each quantity two
statistics of the J windows of a map: their **mean** and the **logarithm of their standard deviation** (an sd
is skewed; its log is nearly normal, so z is nearly Student-t).

**The test.**  The model predicts the distribution of each statistic: its value on each of the R surrogates.
z = (held-out − mean)/(sd √(1 + 1/R)), the prediction of one new value from R draws, so z is Student-t with R − 1
degrees of freedom for Gaussian statistics; all tests of both folds form one family, threshold
c = t_{R−1}⁻¹(1 − α/(2m)) (Bonferroni, family-wise α = :data:`HOLDOUT_ALPHA`; :func:`student_threshold`).  Until
2026-11-28 c was the normal quantile Φ⁻¹(1 − α/(2m)) = 3.34 for m = 60, whose tail is 3.4 times too thin for
R = 24 (about 17 % family-wise instead of 5 %); the exact model of a Gaussian map was then refused or left
undecided.  Two Monte Carlo rank tests were tried the same day (the largest |z|, and the global extreme rank
length of Myllymäki et al. 2017): both exact under exchangeability, but the held-out half's own statistic moves
with the draws (the scale of a heavy-tailed statistic; the coarse ranks of 24 draws), and the decision rule,
which bounds the binomial error of K only, let one seed call opd-1's quilt model credible and another not
credible (docs/statistical_contact.md §0a).  The z rule carries the Monte Carlo error of z itself.

**Its false-alarm rate, measured.**  On exact Gaussian maps (the random-phase model true) at a fixed R = 24,
``benchmarks/holdout_calibration.py`` counts the maps whose largest |z| exceeds c.  With the sd of the windows
tested as it is and the predictive draws of before 2026-11-28 that was 21 % of 241 256² maps and 17 % of 90
512² maps, not 5 %: the window mean of β̄ scattered 1.6–1.8 times wider than predicted (the tapered spectrum
was rescaled by a map-dependent factor), and the skewed window sd had 1.2–1.5 times the predicted spread.
The log sd and Welch's normalisation of the predictive spectrum are the two corrections; docs §0a has the
rates they give.

**A verdict that does not move with the seed.**  z carries a Monte Carlo error SE_z ≈ √(1/R + z²/(2(R − 1))).
``credible`` needs every |z| + 2 SE_z < c, ``not credible`` some |z| − 2 SE_z > c; otherwise R doubles (the first
R unchanged: surrogate k of a fold is fixed by the seed, the fold and k, and of pooled scan i by child i of that)
until it is decided or :data:`HOLDOUT_MAX_REALIZATIONS` are spent; then it is ``undecided``.

**The model's predictive distribution.**  The surrogates that stand for the model are drawn by
:meth:`~stochfric.surface.surrogates.SurrogateMethod.predictive_heights`: a prediction of an *independent*
sample.  For random phases that is a new Gaussian field with random amplitudes whose spectrum is the training
half's tapered periodogram (:func:`~stochfric.surface.synthesis.gaussian_field_heights`), not the half's own
amplitudes with random phases:
surrogates that all keep the training half's realised low-wavenumber power make the model's distribution too
narrow for a new sample, and a Gaussian map was refused by its own exact model (docs §0a).

**Power.**  The output states the smallest ratio of held-out to model scatter of μ, and the smallest
shift of the held-out window mean of μ (in units of the window sd), that the test detects with 80 %
probability at these numbers of windows and surrogates (median over the approaches), at the threshold the
test tends to with many surrogates, the normal Bonferroni quantile Φ⁻¹(1 − α/(2m)): a power read from the
threshold of the surrogates made so far would move with how many the sequential decision happened to need.

**The measured windows** (:func:`measured_windows`): μ(u) over the disjoint windows of the whole prepared
measurement — numbers that rest on the measurement alone, with their sampling uncertainty: the jackknife
SE over windows and 95 % intervals, and the effective number of independent windows from the correlation
of neighbouring windows (n_eff = J (1 − ρ₁)/(1 + ρ₁), ρ₁ ≥ 0 the lag-1 correlation of μ between
neighbouring windows).  The jackknife treats the J windows as independent; the SE is scaled by
√(J/n_eff) and the t quantile taken at n_eff − 1 degrees of freedom, so correlated windows widen the
intervals as their lost information demands.
"""

from __future__ import annotations

import math
import warnings
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import stats as sps

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import bowden_tabor_mu
from stochfric.contact.materials import Material
from stochfric.errors import AnalysisError
from stochfric.io_utils import json_ready
from stochfric.process.ensemble import SurrogateOptions, summit_statistics, tile_contact, tile_grid
from stochfric.random import SeedLike, child_seed, spawn_seed_sequences
from stochfric.surface.io import Surface
from stochfric.surface.summits import find_summits, summit_rule

__all__ = [
    "HOLDOUT_ALPHA",
    "HOLDOUT_MAX_REALIZATIONS",
    "HOLDOUT_MIN_SUMMITS",
    "HOLDOUT_REALIZATIONS",
    "HeldOutTest",
    "HoldoutValidation",
    "MeasuredWindows",
    "holdout_validation",
    "measured_windows",
    "split_halves",
    "student_threshold",
    "window_summary",
]

#: Family-wise false-alarm probability of the out-of-sample test (all quantities, both folds).
HOLDOUT_ALPHA = 0.05
#: Summits a window must hold on average (β̄ and σ_S of a window need a few tens).
HOLDOUT_MIN_SUMMITS = 20
#: Surrogates per fold to start with, and the most the sequential decision may make.
HOLDOUT_REALIZATIONS = 24
HOLDOUT_MAX_REALIZATIONS = 192
#: Monte Carlo standard errors a decision keeps from the threshold: a reversal needs one seed to decide each
#: way, a 4-SE swing (docs/statistical_contact.md §0a).
DECISION_MARGIN = 2.0
#: Most windows per side.
HOLDOUT_TILES = 4
#: The scatter ratio of μ the test must detect with 80 % probability to vouch for a model: σ_μ is what the
#: oscillator studies read, and a factor 2 in it moves the damping limit D_max(α) by more than its intervals.
#: A test that cannot see a factor 2 leaves the model ``undecided`` and says how many scans would decide it.
REQUIRED_SCATTER_RATIO = 2.0

_SUMMIT_NAMES = ("summit_count", "summit_radius_mean_m", "summit_height_std_m")


@dataclass(frozen=True, kw_only=True)
class HeldOutTest:
    """One test: a statistic (``mean`` or ``log sd`` over the windows of a map) of one quantity, held-out
    value against the model's distribution, pooled over nothing: one fold."""

    fold: int
    quantity: str
    statistic: str
    held_out: float
    model_mean: float
    model_sd: float
    z: float
    mc_se: float


@dataclass(frozen=True, kw_only=True)
class HoldoutValidation:
    """The out-of-sample validation of one surrogate method (module docstring)."""

    method: str
    verdict: str
    reason: str
    alpha: float
    threshold: float
    realizations: int
    tiles: int
    window_size_m: tuple[float, float]
    held_out_windows: int
    max_abs_z: float
    worst: str
    detectable_scatter_ratio: float
    detectable_mean_shift_sd: float
    tests: tuple[HeldOutTest, ...] = field(repr=False)
    rule: str = ("2-fold cross-validation over halves of every scan; per window mu(u), summit count, mean summit "
                 "radius, summit-height sd; mean and log sd over the windows of a map against their distribution over "
                 "the surrogates of the other half; |z| <= Student-t Bonferroni threshold (R - 1 degrees of "
                 "freedom, family-wise alpha); decided only 2 Monte Carlo SE away from it, else more surrogates")

    @property
    def credible(self) -> bool:
        """True when the model was decided consistent with the held-out data."""
        return self.verdict == "credible"

    @classmethod
    def unavailable(cls, method: str, reason: str) -> HoldoutValidation:
        """No out-of-sample test was possible (a map too small to hold out half of it, a method that does
        not apply to a half): the model stays unvalidated, the verdict ``undecided``."""
        nan = math.nan
        return cls(method=method, verdict="undecided", reason=reason, alpha=HOLDOUT_ALPHA, threshold=nan,
                   realizations=0, tiles=0, window_size_m=(nan, nan), held_out_windows=0, max_abs_z=nan, worst="",
                   detectable_scatter_ratio=nan, detectable_mean_shift_sd=nan, tests=())

    def to_dict(self) -> dict[str, Any]:
        """The JSON form (the tests as a list of dicts)."""
        out = {k: getattr(self, k) for k in (
            "method", "verdict", "reason", "alpha", "threshold", "realizations", "tiles", "held_out_windows",
            "max_abs_z", "worst", "detectable_scatter_ratio", "detectable_mean_shift_sd", "rule")}
        out["window_size_m"] = list(self.window_size_m)
        out["tests"] = [t.__dict__.copy() for t in self.tests]
        return json_ready(out)


@dataclass(frozen=True, kw_only=True)
class MeasuredWindows:
    """μ(u) over disjoint windows of the prepared measurement(s): numbers that rest on the measurement
    alone (module docstring).  Arrays over the approaches."""

    tiles: int
    window_size_m: tuple[float, float]
    windows: int
    mu: FloatArray = field(repr=False)
    mu_mean: FloatArray
    mu_mean_ci95: FloatArray
    mu_std: FloatArray
    mu_std_ci95: FloatArray
    neighbour_correlation: FloatArray
    effective_windows: FloatArray
    source: str = "measurement"
    rule: str = ("disjoint t x t windows of every prepared scan, each referenced to its own highest summit; mean "
                 "and sd over the windows with jackknife 95 % intervals, the SE scaled by sqrt(J / n_eff) and the t "
                 "quantile at n_eff - 1; effective windows n_eff = J (1 - rho1)/(1 + rho1), rho1 >= 0 the lag-1 "
                 "correlation of neighbouring windows")

    def to_dict(self) -> dict[str, Any]:
        """The JSON form."""
        return json_ready({
            "tiles": self.tiles, "window_size_m": list(self.window_size_m), "windows": self.windows,
            "mu": np.asarray(self.mu).tolist(), "mu_mean": list(self.mu_mean),
            "mu_mean_ci95": np.asarray(self.mu_mean_ci95).tolist(), "mu_std": list(self.mu_std),
            "mu_std_ci95": np.asarray(self.mu_std_ci95).tolist(),
            "neighbour_correlation": list(self.neighbour_correlation),
            "effective_windows": list(self.effective_windows), "source": self.source, "rule": self.rule,
        })


def split_halves(surface: Surface) -> tuple[Surface, Surface]:
    """The two halves of ``surface`` along its longer side (equal size; an odd last row or column dropped)."""
    z = np.asarray(surface.heights_m)
    axis = 0 if z.shape[0] >= z.shape[1] else 1
    n = z.shape[axis] // 2
    parts = (z[:n], z[n:2 * n]) if axis == 0 else (z[:, :n], z[:, n:2 * n])
    dx, dy = surface.grid_spacing_m
    halves = []
    for k, h in enumerate(parts):
        size = (h.shape[0] * dx, h.shape[1] * dy)
        halves.append(Surface(heights_m=np.ascontiguousarray(h), physical_size_m=size,
                              source=f"half {k + 1} of {surface.source}", n_undefined_filled=0))
    return halves[0], halves[1]


def choose_tiles(summit_count: int, tiles: int = HOLDOUT_TILES, min_summits: int = HOLDOUT_MIN_SUMMITS) -> int | None:
    """Windows per side: the largest t ≤ ``tiles`` (≥ 2) whose t² windows hold ``min_summits`` each on average."""
    for t in range(int(tiles), 1, -1):
        if summit_count / (t * t) >= min_summits:
            return t
    return None


def _window_quantities(heights: FloatArray, spacing: tuple[float, float], material: Material, u: FloatArray,
                       tiles: int, rule: str) -> FloatArray:
    """Per window of the ``tiles × tiles`` grid: μ(u) (U columns) then summit count, β̄, σ_S; (T, U + 3)."""
    area, force, _count = tile_contact(heights, spacing, material, u, tiles=tiles, rule=rule)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu = bowden_tabor_mu(area, force, material.shear_strength_pa)
    s = find_summits(heights, spacing, rule=rule)
    m = summit_rule(rule).margin
    rows = []
    for i0, i1, j0, j1 in tile_grid(heights.shape, tiles):
        inside = (s.i >= i0 + m) & (s.i < i1 - m) & (s.j >= j0 + m) & (s.j < j1 - m)
        rows.append(summit_statistics(s.heights_m[inside], s.radius_m[inside]))
    return np.concatenate([np.asarray(mu, dtype=np.float64), np.stack(rows)], axis=1)


def _statistics(q: FloatArray) -> FloatArray:
    """Mean and log sd over the windows (rows) of each quantity (column), NaN-aware (a window without load
    at the first approach has no μ there): (2, Q).  The scatter is tested as log s: an sd over J windows is
    skewed (χ-like), and its z against a t threshold had 1.2–1.5 times the predicted spread on exact Gaussian
    maps; log s is nearly normal with sd ≈ 1/√(2(J − 1)) (the variance-stabilising transform; docs §0a)."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        return np.stack([np.nanmean(q, axis=0), np.log(np.nanstd(q, axis=0, ddof=1))])


def _detectable(c: float, r: int, log_sd_spread: float) -> tuple[float, float]:
    """Smallest scatter ratio and mean shift (in window sd) detected with 80 % power at threshold c.

    ``log_sd_spread``: sd over surrogates of the log of a map's window sd (≈ the relative spread of the
    scatter statistic).  A held-out scatter ρ times the model's shifts log s by log ρ and leaves its spread, so
    z ≈ N(log ρ / (spread · √(1 + 1/R)), 1) and P(z > c) = 0.8 at log ρ = (c + z_0.8) spread √(1 + 1/R).
    Mean shift: the window mean's spread is sd/√J_eff, which the surrogates measure; reported as a multiple
    of the mean-statistic's own sd (c + z_0.8)."""
    z80 = float(sps.norm.ppf(0.8))
    inflate = math.sqrt(1.0 + 1.0 / r)
    return math.exp((c + z80) * log_sd_spread * inflate), (c + z80) * inflate


def _power(tests: list[HeldOutTest], c: float, r: int) -> tuple[float, float, float]:
    """The detectable scatter ratio and mean shift (:func:`_detectable`) at the median spread of the log
    window sd of μ over the surrogates, and that spread."""
    sd_stats = [t for t in tests if t.statistic == "log sd" and t.quantity.startswith("mu(")]
    rel = float(np.median([t.model_sd for t in sd_stats])) if sd_stats else math.nan
    if not (math.isfinite(rel) and rel > 0):
        return math.nan, math.nan, rel
    ratio, shift = _detectable(c, r, rel)
    return ratio, shift, rel


def _scans_needed(c: float, r: int, rel: float, scans: int) -> int:
    """Scans of the present size that would let the test detect :data:`REQUIRED_SCATTER_RATIO`: the spread of
    the log window sd falls as 1/√(windows), so the scans needed grow with (rel / rel_needed)², rel_needed the
    spread at which :func:`_detectable` gives the required ratio (its closed form solved for the spread)."""
    needed = math.log(REQUIRED_SCATTER_RATIO) / ((c + float(sps.norm.ppf(0.8))) * math.sqrt(1.0 + 1.0 / r))
    return max(scans + 1, math.ceil(scans * (rel / needed) ** 2))


def _fold_tests(fold: int, held: FloatArray, model: FloatArray, names: list[str]) -> list[HeldOutTest]:
    """Tests of one fold: ``held`` (2, Q) statistics of the held-out windows, ``model`` (R, 2, Q) of the
    surrogates.  z = (held-out − mean)/(sd √(1 + 1/R)) over the R surrogates (the prediction of one new value),
    with its Monte Carlo error SE_z ≈ √(1/R + z²/(2(R − 1)))."""
    out = []
    for s, stat in enumerate(("mean", "log sd")):
        for q, name in enumerate(names):
            values = model[:, s, q]
            values = values[np.isfinite(values)]
            x = float(held[s, q])
            if values.size < 3 or not math.isfinite(x):
                continue
            m, sd = float(values.mean()), float(values.std(ddof=1))
            if sd <= 0.0:
                z = 0.0 if x == m else math.copysign(math.inf, x - m)
            else:
                z = (x - m) / (sd * math.sqrt(1.0 + 1.0 / values.size))
            se = math.sqrt(1.0 / values.size + z * z / (2.0 * (values.size - 1))) if math.isfinite(z) else 0.0
            out.append(HeldOutTest(fold=fold, quantity=name, statistic=stat, held_out=x, model_mean=m, model_sd=sd,
                                   z=float(z), mc_se=float(se)))
    return out


def student_threshold(alpha: float, tests: int, realizations: int) -> float:
    """The two-sided Bonferroni threshold of |z| for ``tests`` tests at family-wise ``alpha`` when each z is a
    prediction from ``realizations`` = R draws: z is Student-t with R − 1 degrees of freedom for Gaussian
    statistics, so c = t_{R−1}⁻¹(1 − α/(2m)) (3.84 for m = 60 and R = 24; the normal quantile, 3.34, had 3.4
    times the nominal tail there)."""
    m, r = max(int(tests), 1), max(int(realizations), 3)
    return float(sps.t.isf(alpha / (2.0 * m), df=r - 1))


def holdout_validation(
    scans: Sequence[Surface], material: Material, approach_m: FloatArray, options: SurrogateOptions, *,
    seed: SeedLike = None, realizations: int = HOLDOUT_REALIZATIONS,
    max_realizations: int = HOLDOUT_MAX_REALIZATIONS, alpha: float = HOLDOUT_ALPHA,
    progress: Callable[[int, int], None] | None = None,
) -> HoldoutValidation:
    """Validate the surrogate method of ``options`` on held-out halves of ``scans`` (module docstring).

    Raises :class:`~stochfric.errors.AnalysisError` when no half holds 2 × 2 windows of
    :data:`HOLDOUT_MIN_SUMMITS` summits (the map is too small to validate anything out of sample)."""
    u = np.asarray(approach_m, dtype=np.float64)
    method = options.surrogate
    halves = [split_halves(s) for s in scans]
    rule = options.rule
    counts = [find_summits(h.heights_m, h.grid_spacing_m, rule=rule).count for pair in halves for h in pair]
    tiles = choose_tiles(min(counts))
    if tiles is None:
        raise AnalysisError(
            f"a half of the map holds {min(counts)} summits, too few for 2 x 2 windows of {HOLDOUT_MIN_SUMMITS} "
            "summits: the surrogate model cannot be validated on held-out data; measure a larger area or pool "
            "several scans")
    for pair in halves:
        ok, why = method.applicable(pair[0].heights_m, rule=rule)
        if not ok:
            raise AnalysisError(f"the {method.name} method does not apply to half of the map ({why}): it cannot be "
                                "validated out of sample; choose another --surrogate")
    names = [f"mu(u_{k})" for k in range(u.size)] + list(_SUMMIT_NAMES)
    held = [np.mean([_statistics(_window_quantities(pair[1 - f].heights_m, pair[1 - f].grid_spacing_m, material,
                                                    u, tiles, rule)) for pair in halves], axis=0)
            for f in range(2)]  # fold f trains on half f, tests on half 1 − f (pooled over scans)
    # one stream per fold, surrogate k its child k: the first surrogates never depend on the budget
    seeds = [spawn_seed_sequences(fold_seed, int(max_realizations)) for fold_seed in spawn_seed_sequences(seed, 2)]
    settings = options.settings
    model: list[list[FloatArray]] = [[], []]
    r = 0
    target = min(int(realizations), int(max_realizations))
    c = c_power = 0.0
    tests: list[HeldOutTest] = []
    while True:
        for f in range(2):
            for k in range(r, target):
                stats_k = []
                for i, pair in enumerate(halves):
                    train = pair[f]
                    # scan i's own stream: one generator for every scan made the pooled scans' surrogates share
                    # their white noise, so their statistics did not average and the test lost its power with
                    # more scans (nine 512² crops detected a scatter ratio of 2.2, four 2.3; found 2026-11-28)
                    # (scan 0 keeps the fold's stream, so a single scan's draws are those of before)
                    gen = np.random.Generator(np.random.PCG64(seeds[f][k] if i == 0 else child_seed(seeds[f][k], i)))
                    h = method.predictive_heights(train.heights_m, gen, settings=settings)
                    stats_k.append(_statistics(_window_quantities(h, train.grid_spacing_m, material, u, tiles, rule)))
                model[f].append(np.mean(stats_k, axis=0))
                if progress is not None:
                    progress(len(model[0]) + len(model[1]), 2 * target)
        r = target
        tests = _fold_tests(1, held[0], np.stack(model[0]), names) + _fold_tests(2, held[1], np.stack(model[1]), names)
        c = student_threshold(alpha, len(tests), r)
        fail = any(abs(t.z) - DECISION_MARGIN * t.mc_se > c for t in tests)
        passed = all(abs(t.z) + DECISION_MARGIN * t.mc_se < c for t in tests)
        # the power at the threshold for many surrogates (module docstring), not at c of the R made so far
        c_power = float(sps.norm.isf(alpha / (2.0 * max(len(tests), 1))))
        ratio, shift, rel = _power(tests, c_power, r)
        if fail or passed or r >= max_realizations:
            break
        target = min(2 * r, int(max_realizations))
    worst = max(tests, key=lambda t: abs(t.z)) if tests else None
    if fail and worst is not None:
        verdict = "not credible"
        reason = (f"held-out {worst.statistic} of {worst.quantity} (fold {worst.fold}) lies at z = {worst.z:+.2f} "
                  f"± {worst.mc_se:.2f} of the model's distribution, beyond {c:.2f}")
    elif passed and ratio <= REQUIRED_SCATTER_RATIO:
        verdict = "credible"
        reason = f"every held-out statistic within {c:.2f} standard deviations of the model's (2 MC SE margin)"
    elif passed:
        verdict = "undecided"
        reason = (f"no held-out statistic contradicts the model, but the test detects only a scatter ratio of μ "
                  f"≥ {ratio:.2g} (needed: {REQUIRED_SCATTER_RATIO:g}); about "
                  f"{_scans_needed(c_power, r, rel, len(scans))} scans of this size would decide it")
    else:
        verdict = "undecided"
        near = [t for t in tests if abs(abs(t.z) - c) <= DECISION_MARGIN * t.mc_se]
        reason = (f"{len(near)} statistic(s) within 2 Monte Carlo SE of the threshold {c:.2f} after {r} "
                  f"surrogates per fold; about {4 * r} would decide it (raise --validation-budget)")
        if not ratio <= REQUIRED_SCATTER_RATIO:
            reason += (f"; even then the test detects only a scatter ratio of μ ≥ {ratio:.2g}: about "
                       f"{_scans_needed(c_power, r, rel, len(scans))} scans of this size are needed")
    i0, i1, j0, j1 = tile_grid(halves[0][0].nb_grid_pts, tiles)[0]
    dx, dy = scans[0].grid_spacing_m
    return HoldoutValidation(
        method=method.name, verdict=verdict, reason=reason, alpha=alpha, threshold=c, realizations=r, tiles=tiles,
        window_size_m=((i1 - i0) * dx, (j1 - j0) * dy), held_out_windows=tiles * tiles * len(scans),
        max_abs_z=float(max((abs(t.z) for t in tests), default=0.0)),
        worst=f"{worst.statistic} of {worst.quantity}, fold {worst.fold}" if worst else "",
        detectable_scatter_ratio=ratio, detectable_mean_shift_sd=shift, tests=tuple(tests),
    )  # fmt: skip


def measured_windows(scans: Sequence[Surface], material: Material, approach_m: FloatArray, *, rule: str,
                     tiles: int | None = None) -> MeasuredWindows | None:
    """μ(u) over the disjoint windows of the prepared scans (module docstring); None when a scan holds
    too few summits for 2 × 2 windows."""
    u = np.asarray(approach_m, dtype=np.float64)
    count = min(find_summits(s.heights_m, s.grid_spacing_m, rule=rule).count for s in scans)
    t = tiles if tiles is not None else choose_tiles(count)
    if t is None:
        return None
    blocks = []
    for s in scans:
        area, force, _n = tile_contact(s.heights_m, s.grid_spacing_m, material, u, tiles=t, rule=rule)
        with np.errstate(invalid="ignore", divide="ignore"):
            blocks.append(np.asarray(bowden_tabor_mu(area, force, material.shear_strength_pa), dtype=np.float64))
    mu_all, mean, mean_ci, std, std_ci, rho1, n_eff = window_summary(blocks, t)
    i0, i1, j0, j1 = tile_grid(scans[0].nb_grid_pts, t)[0]
    dx, dy = scans[0].grid_spacing_m
    return MeasuredWindows(
        tiles=t, window_size_m=((i1 - i0) * dx, (j1 - j0) * dy), windows=mu_all.shape[0], mu=mu_all, mu_mean=mean,
        mu_mean_ci95=mean_ci, mu_std=std, mu_std_ci95=std_ci, neighbour_correlation=rho1, effective_windows=n_eff,
    )  # fmt: skip


def window_summary(
    blocks: Sequence[FloatArray], tiles: int
) -> tuple[FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray, FloatArray]:
    """Mean and sd of μ over the disjoint windows of every scan (``blocks``: one (tiles², P) array per scan,
    row-major tiles) with their 95 % intervals (module docstring: jackknife SE × √(J/n_eff), t at n_eff − 1):
    ``(mu_all, mean, mean_ci95, sd, sd_ci95, rho1, n_eff)``; the intervals have shape (P, 2)."""
    mu_all = np.concatenate(blocks)
    j, n_p = mu_all.shape
    rho = [np.array([_lag1(b.reshape(tiles, tiles, n_p)[:, :, k]) for k in range(n_p)]) for b in blocks]
    mean, std = np.nanmean(mu_all, axis=0), np.nanstd(mu_all, axis=0, ddof=1)
    # jackknife over windows: SE of the mean and of the sd
    loo_mean = np.stack([np.nanmean(np.delete(mu_all, i, axis=0), axis=0) for i in range(j)])
    loo_std = np.stack([np.nanstd(np.delete(mu_all, i, axis=0), axis=0, ddof=1) for i in range(j)])
    se_mean = np.sqrt((j - 1) / j * np.sum((loo_mean - loo_mean.mean(axis=0)) ** 2, axis=0))
    se_std = np.sqrt((j - 1) / j * np.sum((loo_std - loo_std.mean(axis=0)) ** 2, axis=0))
    rho1 = np.clip(np.nanmean(np.stack(rho), axis=0), 0.0, 0.99)
    n_eff = j * (1.0 - rho1) / (1.0 + rho1)
    # the jackknife treats the windows as independent: neighbours correlated by rho1 carry only n_eff windows'
    # information, so the SE grows by sqrt(J / n_eff) and the t quantile has n_eff - 1 degrees of freedom
    inflate = np.sqrt(j / n_eff)
    se_mean, se_std = se_mean * inflate, se_std * inflate
    tq = sps.t.ppf(0.975, np.maximum(n_eff - 1.0, 1.0))
    mean_ci = np.stack([mean - tq * se_mean, mean + tq * se_mean], axis=1)
    std_ci = np.stack([np.maximum(std - tq * se_std, 0.0), std + tq * se_std], axis=1)
    return mu_all, mean, mean_ci, std, std_ci, rho1, n_eff


def _lag1(grid: FloatArray) -> float:
    """Correlation of μ between horizontally and vertically neighbouring windows of one scan (NaN-free pairs)."""
    a = np.concatenate([grid[:-1, :].ravel(), grid[:, :-1].ravel()])
    b = np.concatenate([grid[1:, :].ravel(), grid[:, 1:].ravel()])
    ok = np.isfinite(a) & np.isfinite(b)
    if ok.sum() < 3 or np.std(a[ok]) == 0.0 or np.std(b[ok]) == 0.0:
        return 0.0
    return float(np.corrcoef(a[ok], b[ok])[0, 1])

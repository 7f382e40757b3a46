"""Largest Lyapunov exponent on the stick line (method §6.4; thesis eq. 4.43/4.44, Fig. 4.41–4.43).

Poincaré section: the stick line x2 = γ0, crossed at the slip→stick transitions.  For each
(model, q, N, η) a reference run starts at ``x0`` (default: sticking at the origin,
(0, γ0)), a comparison run at ``x0 + (δ, 0)`` and a *twin* at ``x0 + (2δ, 0)``, δ =
``perturbation`` (default 10⁻⁶, dimensionless, i.e. 1 µm for L = 1 m; the thesis gives no
value — method §7.9).  All three use the same noise realisation (``common_random_numbers``).

    w(i) = |X_gh,ref(i) − X_gh,pert(i)|,  λ = (1/K) Σ_{i=1}^{K} ln(w(i)/w(1))        (4.43)
    E[Λ] = (1/K) Σ_{i=1}^{K} ln(E[W(i)]/E[W(1)])   (mean over R run pairs)           (4.44)

K = the number of transitions both runs have (stochastic: the smallest over the runs).

**What is measured, and when it is undefined.**  A finite-difference exponent is a
property of the dynamics only while the separation stays in the *linear regime*: there w(i)
is proportional to δ.  Once w reaches the scale of the attractor (or, for the contact model,
of the process grid: the two runs then read unrelated parts of the surface) it saturates, and
(4.43) becomes a function of δ.

* **Twin check.**  In the linear regime the signed differences obey d₂(i) = 2 d(i); a pair is
  *linear* when |d₂(i) − 2 d(i)| ≤ ``linearity_tolerance`` · 2 max_{j≤i} |d(j)| (default 0.1)
  for every i ≤ K.  This catches saturation and the non-smooth parts of the switching logic (a
  breakaway moved across a grid step; probably the white noise's slip remainder ΔW_k √(h/Δτ),
  not Lipschitz in h at h = 0; the contact model's breakaway check) alike, without a length scale.
* **Diverging pairs.**  A pair whose separation grew by at least
  :data:`DIVERGING_GROWTH` (10²) over w(1) within the transitions that pass the twin check, and only
  then failed it, has left the linear regime by saturating, not by a jump: status ``diverging``,
  λ = the slope of ln w over that linear prefix, a *lower bound* of the exponent
  (``lyapunov_is_lower_bound``); never ``nonlinear``.  A cell of R pairs is ``diverging`` when every
  pair is ``ok`` or ``diverging`` and one at least is diverging (the mean is then a lower bound).
* **Integrator.**  The study runs ``accurate`` (adaptive DOP853 with events) for the deterministic and
  contact models by default: at the thesis's Euler Δτ = 0.005 the switching logic locks spurious
  cycles (brake 4000 N, q = 5·10⁻⁴, η = 1.2: λ = −0.86 against +0.28) and breaks the twin check of
  most contact pairs.  ``integrator = "euler"`` is the reproduction mode; both are recorded
  (``integrator``, ``sde_integrator``, ``integrator_mode`` in the JSON and the dataset attributes).
  White noise stays an SDE (Euler–Maruyama at the config's Δτ).
* ``lyapunov`` (with ``lyapunov_se``, ``status``) is the exponent *per slip→stick transition*:
  the least-squares slope of ln w(i) over all i = 1 … K (deterministic: SE from the regression;
  stochastic: mean over the R run pairs, SE = s/√R).  It is reported only when every pair is
  linear, else NaN with status ``nonlinear``; ``merged`` (the runs coincide, or contract 10⁶-fold,
  within fewer than 5 transitions; thesis: no value) and ``too-few-transitions`` (K < 5) are the
  other reasons.  A contracting pair is fitted up to the transition before its separation falls
  10⁶-fold below its largest so far (:data:`RESOLVED_CONTRACTION`): below that, at the
  integrator's tolerance and the rounding of X_gh, ln w scatters at the floor or is −∞ (w = 0), and
  those points would pull the slope toward 0 by an amount set by the integrator's accuracy and
  τ_end.  The window does not depend on δ, so a reported value is the δ → 0 limit up to the
  linearisation error (test: δ = 1e-8 … 1e-4 agree within their standard errors).  A window
  "until w saturates" would not do: for the contact model ln w(i) is no straight line, so a δ-dependent window gives
  δ-dependent slopes.
* ``separation_index_443`` is (4.43)/(4.44) evaluated exactly as printed, at this δ, with its
  own ``separation_index_status`` (``nonlinear`` where the twin check fails: then the number
  depends on δ).  Note that for w(i) = w(1) e^{a(i−1)} it equals a(K − 1)/2, not a; it weights
  near-zero w(i) through the logarithm, so even in the linear regime it is ill-conditioned.
  It is kept to compare with the thesis's figures, not under the name of an exponent.

For the contact model the exponent is that of the extended state (x1, x2, x3, path coordinate)
in the frozen process realisation: the tangent dynamics contain the slope of the interpolated
process, dμ̂/dx ~ σ_μ/Δx, so it measures the sensitivity to the surface's fine structure as much
as the oscillator's.  The path offset of the runs is never reset (each reads the process where
it is), so it is a neutral direction: the contact model's largest exponent is ≥ 0 in the long
run, and a positive finite-time value alone is no evidence of chaos (docs/studies.md).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from ..oscillator.case import MU0
from ..oscillator.options import Model
from .base import Study, StudyResult
from .config import LyapunovConfig, integrator_record
from .errors import StudyError
from .executors import Executor, SweepStats
from .summary import ForcedSummary
from .tasks import TaskSpec

STATUS = ("ok", "diverging", "merged", "too-few-transitions", "nonlinear")
#: Fewest transitions in the linear regime for a growth rate.
MIN_LINEAR = 5
#: Growth of the separation, relative to its first value, within the linear regime from which a pair
#: whose twin check fails later is ``diverging`` (its slope up to there a lower bound), not ``nonlinear``.
DIVERGING_GROWTH = 100.0
#: Fewest transitions of the linear prefix for the slope of a diverging pair.
MIN_DIVERGING = 3
#: Contraction, relative to the largest separation so far, below which a separation is no longer
#: resolved: the fit of :func:`lyapunov_rate` ends before the first w(i) < RESOLVED_CONTRACTION ·
#: max_{j≤i} w(j) (or w(i) = 0).  With δ = 10⁻⁶ that is w ≈ 10⁻¹², the integrator's tolerance and four
#: decades above the rounding of X_gh (≈ 10⁻¹⁶), where a contracting pair's ln w stops falling and
#: scatters (and, once it is exactly 0, has no logarithm).  Relative to w, so the window does not
#: depend on δ in the linear regime.
RESOLVED_CONTRACTION = 1e-6


def resolved_prefix(w: npt.ArrayLike) -> int:
    """Number of leading separations above the resolution floor (:data:`RESOLVED_CONTRACTION`): all of
    them unless the pair contracts ≥ 10⁶-fold below its largest separation so far (or reaches w = 0)."""
    arr = np.asarray(w, dtype=float)
    low = arr < RESOLVED_CONTRACTION * np.maximum.accumulate(arr) if arr.size else arr.astype(bool)
    low |= arr == 0.0
    return int(np.argmax(low)) if low.any() else arr.size


def lyapunov_exponent(w: npt.ArrayLike) -> tuple[float, str, int]:
    """λ of eq. (4.43) from the distances w(1..K) (NaN entries end the sequence).

    Returns ``(λ, status, K)``; status ``merged`` (some w = 0) or ``too-few-transitions``
    (K < 2) gives λ = NaN.
    """
    arr = np.asarray(w, dtype=float)
    fin = np.isfinite(arr)
    k = int(np.argmin(fin)) if not fin.all() else arr.size
    arr = arr[:k]
    if k < 2:
        return math.nan, "too-few-transitions", k
    if np.any(arr == 0.0):
        return math.nan, "merged", k
    return float(np.mean(np.log(arr / arr[0]))), "ok", k


def lyapunov_rate(w: npt.ArrayLike, linear: bool = True) -> tuple[float, float, str, int]:
    """Exponent per slip→stick transition: least-squares slope of ln w(i) over i = 1 … K.

    ``w`` are the separations w(1..K) (NaN entries end the sequence).  The window is all K
    transitions, or those before the separation leaves the resolved range (:func:`resolved_prefix`:
    a contracting pair reaches the rounding floor, where ln w stops falling), so in the linear regime
    (w ∝ δ) the slope depends neither on δ nor on how far below the floor the integrator's accuracy
    lets the runs go; ``linear`` is the twin check (:func:`is_linear`); without it the value would
    depend on δ: status ``nonlinear``, NaN.  Other statuses: ``merged`` (the runs coincide or contract
    to the floor within fewer than :data:`MIN_LINEAR` transitions: the map contracts to a point;
    thesis: no value), ``too-few-transitions`` (K < :data:`MIN_LINEAR`).
    Returns ``(rate, se, status, K)``; ``se`` is the regression standard error of the slope, K the
    transitions fitted.
    """
    arr = np.asarray(w, dtype=float)
    fin = np.isfinite(arr)
    k = int(np.argmin(fin)) if not fin.all() else arr.size
    arr = arr[:k]
    if k < MIN_LINEAR:
        return math.nan, math.nan, "too-few-transitions", k
    k = resolved_prefix(arr)
    arr = arr[:k]
    if k < MIN_LINEAR:
        return math.nan, math.nan, "merged", k
    if not linear:
        return math.nan, math.nan, "nonlinear", k
    i = np.arange(k, dtype=float)
    y = np.log(arr)
    slope, icpt = np.polyfit(i, y, 1)
    res = y - (slope * i + icpt)
    sxx = float(np.sum((i - i.mean()) ** 2))
    se = math.sqrt(float(np.sum(res**2)) / (k - 2) / sxx)
    return float(slope), se, "ok", k


def linear_prefix(d: npt.ArrayLike, d_twin: npt.ArrayLike, tolerance: float) -> int:
    """Number of leading transitions that pass the twin check of :func:`is_linear` (all K when it holds)."""
    a = np.asarray(d, dtype=float)
    fin = np.isfinite(a)
    k = int(np.argmin(fin)) if not fin.all() else a.size
    a = a[:k]
    b = np.asarray(d_twin, dtype=float)[:k]
    if b.size < k:
        b = np.concatenate([b, np.full(k - b.size, np.nan)])
    scale = 2.0 * np.maximum.accumulate(np.abs(a)) if k else a
    with np.errstate(invalid="ignore"):
        good = np.isfinite(b) & (np.abs(b - 2.0 * a) <= tolerance * scale)
    return int(np.argmin(good)) if not good.all() else k


def diverging_rate(w: npt.ArrayLike, n_linear: int) -> tuple[float, float, bool]:
    """Slope (and its SE) of ln w over the first ``n_linear`` transitions, and whether the pair is
    *diverging*: w grew by at least :data:`DIVERGING_GROWTH` over w(1) within them (at least
    :data:`MIN_DIVERGING` transitions, no w = 0).  Past the linear regime the separation saturates, so
    the slope is a lower bound of the exponent."""
    arr = np.asarray(w, dtype=float)[:n_linear]
    if arr.size < MIN_DIVERGING or not np.all(np.isfinite(arr)) or np.any(arr <= 0.0):
        return math.nan, math.nan, False
    if float(np.max(arr / arr[0])) < DIVERGING_GROWTH:
        return math.nan, math.nan, False
    i = np.arange(arr.size, dtype=float)
    y = np.log(arr)
    slope, icpt = np.polyfit(i, y, 1)
    if arr.size > 2:
        res = y - (slope * i + icpt)
        se = math.sqrt(float(np.sum(res**2)) / (arr.size - 2) / float(np.sum((i - i.mean()) ** 2)))
    else:
        se = math.nan
    return float(slope), se, True


def is_linear(d: npt.ArrayLike, d_twin: npt.ArrayLike, tolerance: float) -> bool:
    """True when the twin run's signed X_gh differences (perturbation 2δ) are twice the pair's.

    ``d(i) = X_gh,pert(i) − X_gh,ref(i)``, ``d_twin(i)`` the same for the twin; linear when
    |d_twin(i) − 2 d(i)| ≤ ``tolerance`` · 2 max_{j ≤ i} |d(j)| for every finite d(i) (the running
    maximum keeps zero crossings of d from counting as nonlinear).  w = |d|.
    """
    a = np.asarray(d, dtype=float)
    fin = np.isfinite(a)
    k = int(np.argmin(fin)) if not fin.all() else a.size
    a = a[:k]
    b = np.asarray(d_twin, dtype=float)[:k]
    if b.size < k or np.any(~np.isfinite(b)):
        return False
    scale = 2.0 * np.maximum.accumulate(np.abs(a)) if k else a
    return bool(np.all(np.abs(b - 2.0 * a) <= tolerance * scale))


def pair_rate(w: npt.ArrayLike, d: npt.ArrayLike, d_twin: npt.ArrayLike, tolerance: float,
              linear: bool) -> tuple[float, float, str, int]:
    """``(rate, se, status, K)`` of one run pair: :func:`lyapunov_rate` (``linear``: the twin check,
    :func:`is_linear`); a pair that fails the check after growing by :data:`DIVERGING_GROWTH` within its
    linear prefix is ``diverging``, its slope up to there a lower bound (:func:`diverging_rate`)."""
    rate, se, status, k = lyapunov_rate(w, linear)
    if status == "nonlinear":
        n_pre = linear_prefix(d, d_twin, tolerance)
        lb, lb_se, div = diverging_rate(w, n_pre)
        if div:
            return lb, lb_se, "diverging", n_pre
    return rate, se, status, k


def ensemble_rate(rates: npt.NDArray[np.float64], statuses: npt.NDArray[Any]) -> tuple[float, float, str, int]:
    """``(mean, se, status, pairs ok or diverging)`` of a cell's R > 1 run pairs: the mean exponent with
    SE = s/√R when every pair is ``ok`` or ``diverging`` (then a lower bound, status ``diverging``, if one
    is); else NaN with the first undefined pair's reason (one undefined pair makes the mean undefined: no
    selection bias)."""
    runs = len(rates)
    if np.all((statuses == "ok") | (statuses == "diverging")):
        return (float(np.mean(rates)), float(np.std(rates, ddof=1) / math.sqrt(runs)),
                "ok" if np.all(statuses == "ok") else "diverging", runs)
    bad = [s_ for s_ in ("merged", "nonlinear", "too-few-transitions") if np.any(statuses == s_)]
    return math.nan, math.nan, bad[0], int(np.sum(statuses == "ok"))


@dataclass(frozen=True)
class Significance:
    """Cells of one model whose exponent is defined, positive by more than 2 SE, negative by more than 2 SE."""

    defined: int
    positive: int
    negative: int


def significance(rate: npt.NDArray[np.float64], se: npt.NDArray[np.float64]) -> Significance:
    """:class:`Significance` of the exponents ``rate`` with standard errors ``se`` (NaN SE counts as 0)."""
    ok = np.isfinite(rate)
    se0 = np.where(np.isfinite(se), se, 0.0)
    return Significance(defined=int(ok.sum()), positive=int(np.sum(ok & (rate - 2 * se0 > 0))),
                        negative=int(np.sum(ok & (rate + 2 * se0 < 0))))


#: Per model, a value per cell ``[forcing_q][normal_force_n][eta]``.
Cells = list[list[list[float]]]


@dataclass(frozen=True, kw_only=True)
class LyapunovSummary(ForcedSummary, kind="lyapunov"):
    """The Lyapunov study's summary (module docstring).

    Grid: ``normal_force_n`` [N] beside ``forcing_q`` and ``eta`` (:class:`ForcedSummary`); σ_ζ,
    σ_ζ,eff [-] per force; ``perturbation`` δ (dimensionless x = y/L), ``linearity_tolerance`` of the
    twin check.  Per model and cell
    ``[forcing_q][normal_force_n][eta]``: ``lyapunov`` (exponent per slip→stick transition, [-]) with its
    SE and ``status``, whether it is a lower bound (``diverging``, growth ≥ ``diverging_growth``), K of
    (4.43)/(4.44), and (4.43)/(4.44) as printed (``separation_index_443``) with its status.  Per model:
    cells per status, :class:`Significance` and the fraction of defined cells positive beyond 2 SE.
    """

    normal_force_n: list[float]
    sigma_zeta: list[float]
    sigma_zeta_effective: list[float]
    perturbation: float
    linearity_tolerance: float
    lyapunov: dict[str, Cells]
    lyapunov_se: dict[str, Cells]
    status: dict[str, list[list[list[str]]]]
    lyapunov_is_lower_bound: dict[str, list[list[list[bool]]]]
    diverging_growth: float
    n_transitions: dict[str, list[list[list[int]]]]
    status_counts: dict[str, dict[str, int]]
    significance: dict[str, Significance]
    positive_fraction: dict[str, float | None]
    separation_index_443: dict[str, Cells]
    separation_index_status: dict[str, list[list[list[str]]]]


@dataclass(frozen=True)
class _Exponents:
    """The analysis of every cell ``[model, q, N, η]`` (and run pair): the exponent per transition
    (``rate``…), and (4.43)/(4.44) as printed (``separation``…)."""

    separation: npt.NDArray[np.float64]
    separation_status: npt.NDArray[Any]
    n_transitions: npt.NDArray[np.int64]
    separation_runs: npt.NDArray[np.float64]
    rate: npt.NDArray[np.float64]
    rate_se: npt.NDArray[np.float64]
    rate_status: npt.NDArray[Any]
    n_ok: npt.NDArray[np.int64]
    rate_runs: npt.NDArray[np.float64]
    rate_status_runs: npt.NDArray[Any]

    @classmethod
    def empty(cls, shape: tuple[int, ...], runs: int) -> _Exponents:
        """NaN values, empty statuses, zero counts."""
        return cls(separation=np.full(shape, np.nan), separation_status=np.full(shape, "", dtype=object),
                   n_transitions=np.zeros(shape, dtype=np.int64), separation_runs=np.full((*shape, runs), np.nan),
                   rate=np.full(shape, np.nan), rate_se=np.full(shape, np.nan),
                   rate_status=np.full(shape, "", dtype=object), n_ok=np.zeros(shape, dtype=np.int64),
                   rate_runs=np.full((*shape, runs), np.nan),
                   rate_status_runs=np.full((*shape, runs), "", dtype=object))


class LyapunovStudy(Study[LyapunovConfig]):
    """One task per (model, q, N): parameter sets (η0, η0, η0, η1, …) = (ref, pert δ, twin 2δ)."""

    kind = "lyapunov"
    default_tau_end = 200.0

    def __init__(self, config: LyapunovConfig) -> None:
        super().__init__(config)
        sp = self.setup.preset.study_parameters
        self.forces = config.normal_forces or sp.normal_force_study_forces
        self.damping_ratio = config.damping_ratio if config.damping_ratio is not None else sp.damping_undamped
        self._check_perturbation()

    def _check_perturbation(self) -> None:
        """Refuse a δ that is not small against the attractor: the stick-slip cycle's x1 scale is the static
        deflection n μ0 (spring force = static friction; n = N/(cL), μ0 = 0.4), and (4.43) needs δ in the
        linear regime, far below it.  δ ≥ 0.1 n μ0 at the smallest force is refused, saying what to give."""
        n_min = min(self.setup.parameters(nf, self.damping_ratio).n for nf in self.forces)
        scale = n_min * MU0
        if self.config.perturbation >= 0.1 * scale:
            raise StudyError(
                f"perturbation {self.config.perturbation:g} is not small against the attractor: the stick-slip "
                f"cycle at N = {min(self.forces):g} N spans about n μ0 = {scale:.2g} (dimensionless x = y/L); the "
                f"exponent needs the runs in the linear regime: give a perturbation below {0.1 * scale:.1g}, "
                "e.g. 1e-6 (the default)")

    def axes(self) -> dict[str, Sequence[Any]]:
        return {"model": self.config.models, "forcing_q": self.config.forcing_q, "normal_force_n": self.forces}

    def task(self, index: int, point: dict[str, Any]) -> TaskSpec:
        config, st = self.config, self.setup
        params = []
        x0s = []
        for eta in config.eta:
            p = st.parameters(point["normal_force_n"], self.damping_ratio, point["forcing_q"] * st.preset.stiffness,
                              eta)
            base = config.x0 if config.x0 is not None else (0.0, p.gamma0)
            params += [p, p, p]
            x0s += [(float(base[0]) + k * config.perturbation, float(base[1])) for k in (0, 1, 2)]
        return self.task_for(index, point, params, x0=tuple(x0s), common_random_numbers=True)

    def assemble(self, tasks: list[TaskSpec], results: dict[int, dict[str, Any]], stats: SweepStats,
                 chash: str | None, executor: Executor | None) -> StudyResult[LyapunovSummary]:
        config = self.config
        x = self.stack(tasks, results, "x_gh")  # [model, q, N, 3 eta, run, event]
        ref, pert, twin = x[:, :, :, 0::3], x[:, :, :, 1::3], x[:, :, :, 2::3]
        w = np.abs(ref - pert)
        dd = pert - ref  # signed differences of the pair and of the twin
        dd2 = twin - ref
        ex = _Exponents.empty(w.shape[:4], config.runs)
        for idx in np.ndindex(*w.shape[:4]):
            runs = 1 if config.models[idx[0]] == Model.DETERMINISTIC else config.runs
            self.analyse_cell(ex, idx, w[idx][:runs], dd[idx], dd2[idx])
        coords: dict[str, Any] = {
            "model": list(config.models),
            "forcing_q": ("forcing_q", np.asarray(config.forcing_q), {"units": "1"}),
            "normal_force_n": ("normal_force_n", np.asarray(self.forces, float), {"units": "N"}),
            "eta": ("eta", np.asarray(config.eta), {"units": "1"}),
            "run": np.arange(config.runs),
            "event": np.arange(x.shape[-1]),
        }
        ds = self.dataset(_variables(w, dd, dd2, ex), coords, executor, chash, perturbation=config.perturbation,
                          linearity_tolerance=config.linearity_tolerance, **integrator_record(config))
        return StudyResult(self.kind, ds, self.summarise(ex, self.warnings(tasks, results)), stats)

    def analyse_cell(self, ex: _Exponents, idx: tuple[int, ...], w: npt.NDArray[np.float64],
                     d: npt.NDArray[np.float64], d_twin: npt.NDArray[np.float64]) -> None:
        """Fill ``ex`` at the cell ``idx`` from its run pairs' separations ``w`` (the runs done) and signed
        differences ``d`` (δ), ``d_twin`` (2δ): per pair :func:`pair_rate`, per cell :func:`ensemble_rate`
        (one pair: its own) and (4.43)/(4.44) of E[W(i)] up to the smallest K of the runs."""
        tol, runs = self.config.linearity_tolerance, len(w)
        linear = np.array([is_linear(d[r], d_twin[r], tol) for r in range(runs)])
        for r in range(runs):
            ex.separation_runs[(*idx, r)], _, _ = lyapunov_exponent(w[r])
            rate, se, status, k_fit = pair_rate(w[r], d[r], d_twin[r], tol, bool(linear[r]))
            ex.rate_runs[(*idx, r)], ex.rate_status_runs[(*idx, r)] = rate, status
            if runs == 1:
                ex.rate_se[idx], ex.n_ok[idx] = se, k_fit
        counts = np.sum(np.isfinite(w), axis=-1)
        kmin = int(counts.min()) if counts.size else 0
        ew = w[:, :kmin].mean(axis=0) if kmin else np.zeros(0)
        ex.separation[idx], ex.separation_status[idx], ex.n_transitions[idx] = lyapunov_exponent(ew)
        if ex.separation_status[idx] == "ok" and not linear.all():
            ex.separation_status[idx] = "nonlinear"  # w not ∝ δ: the printed value is a function of δ here
        rs = ex.rate_status_runs[idx][:runs]
        if runs == 1:
            ex.rate[idx], ex.rate_status[idx] = ex.rate_runs[(*idx, 0)], rs[0]
        else:
            ex.rate[idx], ex.rate_se[idx], ex.rate_status[idx], ex.n_ok[idx] = ensemble_rate(
                ex.rate_runs[idx][:runs], rs)

    def summarise(self, ex: _Exponents, warns: list[dict[str, str]]) -> LyapunovSummary:
        """The :class:`LyapunovSummary` of the analysed cells."""
        config, models, rec = self.config, list(self.config.models), integrator_record(self.config)
        sig: dict[str, Significance] = {m: significance(ex.rate[i], ex.rate_se[i]) for i, m in enumerate(models)}

        def per_model(a: npt.NDArray[Any]) -> dict[str, Any]:
            return {m: a[i].tolist() for i, m in enumerate(models)}

        return LyapunovSummary(
            **self.summary_head(self.forces, warns),
            normal_force_n=list(self.forces), forcing_q=list(config.forcing_q), eta=list(config.eta),
            damping_ratio=self.damping_ratio, perturbation=config.perturbation,
            linearity_tolerance=config.linearity_tolerance, integrator=rec["integrator"],
            sde_integrator=rec["sde_integrator"], integrator_mode=rec["integrator_mode"],
            lyapunov=per_model(ex.rate), lyapunov_se=per_model(ex.rate_se), status=per_model(ex.rate_status),
            lyapunov_is_lower_bound=per_model(ex.rate_status == "diverging"),
            diverging_growth=DIVERGING_GROWTH, n_transitions=per_model(ex.n_transitions),
            status_counts={m: {s_: int(np.sum(ex.rate_status[i] == s_)) for s_ in STATUS}
                           for i, m in enumerate(models)},
            # cells whose exponent is positive (negative) by more than 2 standard errors, of the defined ones
            significance=sig,
            positive_fraction={m: (sig[m].positive / sig[m].defined) if sig[m].defined else None for m in models},
            separation_index_443=per_model(ex.separation), separation_index_status=per_model(ex.separation_status),
        )


#: Run the lyapunov study (module docstring); ``executor``, ``checkpoint``, ``progress`` as :meth:`Study.run`.
lyapunov_study = LyapunovStudy.study

_D4 = ("model", "forcing_q", "normal_force_n", "eta")


def _variables(w: npt.NDArray[np.float64], dd: npt.NDArray[np.float64], dd2: npt.NDArray[np.float64],
               ex: _Exponents) -> dict[str, Any]:
    """The dataset variables of the separations and of the analysed cells."""
    d4, d6 = _D4, (*_D4, "run", "event")
    return {
        "w": (d6, w, {"units": "1", "long_name": "w(i) = |X_gh,ref(i) - X_gh,pert(i)|"}),
        "d_pair": (d6, dd, {"units": "1", "long_name": "X_gh,pert - X_gh,ref (delta)"}),
        "d_twin": (d6, dd2, {"units": "1", "long_name": "X_gh,twin - X_gh,ref (2 delta)"}),
        "lyapunov": (d4, ex.rate, {"units": "1", "long_name": "largest Lyapunov exponent per slip->stick transition: "
                                   "slope of ln w(i), i = 1..K (mean over run pairs); a lower bound where "
                                   "status is diverging; NaN unless status ok or diverging"}),
        "lyapunov_is_lower_bound": (d4, (ex.rate_status == "diverging").astype(np.int8),
                                    {"units": "1", "long_name": "1 where lyapunov is a lower bound (diverging)"}),
        "lyapunov_se": (d4, ex.rate_se, {"units": "1", "long_name": "standard error of lyapunov"}),
        "status": (d4, ex.rate_status.astype(str), {"long_name": "ok | diverging | merged | too-few-transitions | "
                                                    "nonlinear"}),
        "n_transitions": (d4, ex.n_transitions, {"units": "1", "long_name": "K used in (4.43)/(4.44)"}),
        "n_ok_pairs": (d4, ex.n_ok, {"units": "1", "long_name": "deterministic: K of the fit; stochastic: pairs ok "
                                     "or diverging"}),
        "lyapunov_runs": ((*d4, "run"), ex.rate_runs, {"units": "1", "long_name": "exponent of each run pair"}),
        "status_runs": ((*d4, "run"), ex.rate_status_runs.astype(str), {}),
        "separation_index_443": (d4, ex.separation, {"units": "1", "long_name": "(4.43)/(4.44) evaluated as printed "
                                                     "at this delta, also where the pair is nonlinear (then "
                                                     "delta-dependent; not a Lyapunov exponent)"}),
        "separation_index_status": (d4, ex.separation_status.astype(str), {
            "long_name": "ok | merged | too-few-transitions | nonlinear (twin check failed)"}),
        "separation_index_443_runs": ((*d4, "run"), ex.separation_runs, {"units": "1"}),
    }

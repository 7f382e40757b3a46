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
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy import stats as sps

from stochfric.contact.asperity import ContactError, asperity_sums
from stochfric.contact.materials import Material
from stochfric.process.ensemble import ContactSamples, summit_statistics
from stochfric.process.model_base import FrictionProcessModel
from stochfric.process.spectral import one_sided_psd
from stochfric.random import SeedLike, as_seed_sequence, spawn_generators
from stochfric.surface.io import Surface
from stochfric.surface.summits import find_summits

__all__ = [
    "ERGODICITY_ALPHA",
    "SURROGATE_Z_LIMIT",
    "ErgodicityCheck",
    "ProcessCheck",
    "SurrogateCheck",
    "check_generated_process",
    "ergodicity_check",
    "surrogate_check",
]

FloatArray = npt.NDArray[np.float64]

#: Family-wise false-alarm probability of the ergodicity verdict (two-sided, Bonferroni).
ERGODICITY_ALPHA = 0.05


@dataclass(frozen=True, kw_only=True)
class ErgodicityCheck:
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

    z_mean: tuple[float, ...]
    z_std: tuple[float, ...]
    p_mean: tuple[float, ...]
    path_std: tuple[float, ...]
    ensemble_std: tuple[float, ...]
    threshold: float
    consistent: bool
    max_abs_z: float
    surfaces: int
    windows_per_surface: int

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {
            "z_mean": list(self.z_mean),
            "z_std": list(self.z_std),
            "p_mean": list(self.p_mean),
            "path_std": list(self.path_std),
            "ensemble_std": list(self.ensemble_std),
            "threshold": self.threshold,
            "max_abs_z": self.max_abs_z,
            "consistent": self.consistent,
            "verdict": "consistent with ergodicity" if self.consistent else "NOT consistent with ergodicity",
            "rule": "non-overlapping windows of K independent long surfaces of one generator: ANOVA of the path "
            "means and jackknife z of sd along a path minus sd across surfaces; |z| <= Bonferroni threshold "
            "(alpha = 0.05, 2U tests)",
            "surfaces": self.surfaces,
            "windows_per_surface": self.windows_per_surface,
        }


def _sd_difference(mu: FloatArray) -> float:
    """mean over surfaces of sd along the path − mean over positions of sd across surfaces."""
    return float(np.mean(mu.std(axis=1, ddof=1)) - np.mean(mu.std(axis=0, ddof=1)))


def ergodicity_check(blocks_mu: npt.ArrayLike, *, alpha: float = ERGODICITY_ALPHA) -> ErgodicityCheck:
    """Ergodicity of μ along the path from non-overlapping windows, shape (K surfaces, J, U)."""
    mu = np.asarray(blocks_mu, dtype=np.float64)
    if mu.ndim != 3 or mu.shape[0] < 3 or mu.shape[1] < 2:
        raise ValueError("need μ of shape (surfaces >= 3, windows per surface >= 2, approaches)")
    if not np.all(np.isfinite(mu)):
        raise ContactError("a window carries no load at some approach (μ undefined); use larger approaches")
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

    z = (measured − ensemble mean) / ensemble standard deviation (the ensemble's *spread*, not
    the standard error of its mean: the question is whether the measured map could be one of the
    realisations).  Checked: summit count, mean summit radius β̄, summit-height standard deviation
    σ_S, and μ(u) at every approach (the measured map referenced to its own highest summit, like
    every realisation).  Credible if every |z| < :data:`SURROGATE_Z_LIMIT`.
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

    def failures(self) -> list[str]:
        """Names of the quantities with |z| ≥ limit (μ as ``mu(u_k)``)."""
        out = [n for n, v in self.z.items() if not abs(v) < self.limit]
        out += [f"mu(u_{k})" for k, v in enumerate(self.mu_z) if not abs(v) < self.limit]
        return out

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary."""
        return {
            "measured": dict(self.measured),
            "ensemble_mean": dict(self.ensemble_mean),
            "ensemble_std": dict(self.ensemble_std),
            "z": dict(self.z),
            "mu_measured": list(self.mu_measured),
            "mu_z": list(self.mu_z),
            "max_abs_mu_z": float(np.nanmax(np.abs(self.mu_z))) if self.mu_z else None,
            "limit": self.limit,
            "credible": self.credible,
            "failures": self.failures(),
            "surrogate": self.surrogate,
            "amplitude": self.amplitude,
            "rule": "z = (measured - ensemble mean) / ensemble sd; credible if every |z| < limit",
        }


def surrogate_check(
    surface: Surface, material: Material, ensemble: ContactSamples, *, rule: str = "thesis"
) -> SurrogateCheck:
    """Compare the measured ``surface`` with its surrogate ``ensemble`` (:func:`ensemble_contact`)."""
    if ensemble.summit_stats is None:
        raise ValueError("the ensemble carries no summit statistics (use ensemble_contact)")
    s = find_summits(surface.heights_m, surface.grid_spacing_m, rule=rule)
    meas = summit_statistics(s.heights_m, s.radius_m)
    stats = ensemble.summit_stats
    e_mean = stats.mean(axis=0)
    e_sd = stats.std(axis=0, ddof=1)
    u = ensemble.approach_m
    if s.count:
        area, force, _count = asperity_sums(s.heights_m, s.radius_m, u, e_star_pa=material.e_star_pa)
        with np.errstate(divide="ignore", invalid="ignore"):
            mu_meas = np.where(force > 0.0, area * material.shear_strength_pa / force, np.nan)
    else:
        mu_meas = np.full(u.size, np.nan)
    mu_e = ensemble.mu
    with np.errstate(divide="ignore", invalid="ignore"):
        mu_z = (mu_meas - np.nanmean(mu_e, axis=0)) / np.nanstd(mu_e, axis=0, ddof=1)
        z = (meas - e_mean) / e_sd
    z = np.where(np.isfinite(z), z, np.where(meas == e_mean, 0.0, np.inf))
    mu_z = np.where(np.isfinite(mu_z), mu_z, np.inf)
    names = _SUMMIT_STAT_NAMES
    credible = bool(np.all(np.abs(z) < SURROGATE_Z_LIMIT) and np.all(np.abs(mu_z) < SURROGATE_Z_LIMIT))
    return SurrogateCheck(
        measured={n: float(v) for n, v in zip(names, meas, strict=True)},
        ensemble_mean={n: float(v) for n, v in zip(names, e_mean, strict=True)},
        ensemble_std={n: float(v) for n, v in zip(names, e_sd, strict=True)},
        z={n: float(v) for n, v in zip(names, z, strict=True)},
        mu_measured=tuple(float(v) for v in mu_meas),
        mu_z=tuple(float(v) for v in mu_z),
        limit=SURROGATE_Z_LIMIT,
        credible=credible,
        surrogate=str(ensemble.info.get("surrogate", "")),
        amplitude=str(ensemble.info.get("amplitude", "")),
    )


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

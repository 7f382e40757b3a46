"""Persson's contact mechanics as a closed-form model: A/A_nom(p) from the rms gradient (docs/persson.md).

A rigid, randomly rough surface pressed on an elastic half-space of contact modulus E* (already
combined, 3.10) at the nominal pressure p.  Persson's theory (Persson 2001; 2006, eq. for the
elastic contact) gives the real contact area fraction

    P(p) = A/A_nom = erf(1 / (2√G)),   G = (π/4) (E*/p)² ∫_{q0}^{q1} q³ C(q) dq,

with C(q) the isotropic 2-D power spectral density normalised as ⟨h²⟩ = ∫ d²q C(q).  Since the
mean square gradient is ḡ² = ⟨|∇h|²⟩ = ∫ d²q q² C(q) = 2π ∫ q³ C(q) dq,

    G = (E* ḡ / p)² / 8,   P = erf(√2 p / (E* ḡ)),   P ≈ κ p / (E* ḡ) for p ≪ E* ḡ,  κ = √(8/π) ≈ 1.596.

Only ḡ of the map enters: no summit detection, no radii.  Exact (boundary-element / Green's
function molecular dynamics) solutions give a small-load slope κ close to 2 (Prodanov, Dapp & Müser
2014; Müser et al. 2017), weakly dependent on the Hurst exponent and on how well the short
wavelengths are resolved; corrections to the theory have been proposed (Yang & Persson 2008; Wang &
Müser 2017).  The ``corrected`` variant here is only a one-parameter rescaling to the exact
small-load slope, P = erf(κ_c (√π/2) p/(E* ḡ)) with κ_c = 2, so that dP/d(p/(E*ḡ)) = κ_c at p → 0 and
P → 1 at large p; it is *not* the Yang–Persson theory.

Plasticity is left out: Persson's elastoplastic theory (Persson 2001; 2006, "constant hardness")
solves the stress diffusion with a second boundary at the penetration hardness and has no closed
form of the kind used here, so nothing plastic is implemented (see :func:`recommend_contact_models`
for when an elastic model is questionable).

References
----------
B. N. J. Persson, J. Chem. Phys. 115 (2001) 3840.  B. N. J. Persson, Surf. Sci. Rep. 61 (2006) 201.
M. Prodanov, W. B. Dapp, M. H. Müser, Tribol. Lett. 53 (2014) 433.
M. H. Müser et al., Tribol. Lett. 65 (2017) 118 (contact-mechanics challenge).
C. Yang, B. N. J. Persson, J. Phys.: Condens. Matter 20 (2008) 215214.
A. Wang, M. H. Müser, Tribol. Lett. 65 (2017) 103.
J. A. Greenwood, J. B. P. Williamson, Proc. R. Soc. Lond. A 295 (1966) 300.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt
from scipy.special import erf

from stochfric.arrays import FloatArray
from stochfric.contact.asperity import ContactError
from stochfric.surface.statistics import ELASTIC_LIMIT, PLASTIC_LIMIT

__all__ = [
    "CONTACT_MODELS",
    "CORRECTED_KAPPA",
    "GRADIENT_METHODS",
    "PERSSON_KAPPA",
    "PerssonContact",
    "persson_area_fraction",
    "persson_contact",
    "recommend_contact_models",
    "rms_gradient",
    "small_load_kappa",
]

#: Small-load slope of Persson's original theory, A/A_nom ≈ κ p/(E* ḡ): κ = √(8/π) ≈ 1.596.
PERSSON_KAPPA = math.sqrt(8 / math.pi)
#: Small-load slope of the ``corrected`` variant: κ_c = 2, close to the exact (BEM/GFMD) value
#: (Prodanov, Dapp & Müser 2014; Müser et al. 2017).
CORRECTED_KAPPA = 2.0
#: Estimators of the rms gradient ḡ (:func:`rms_gradient`).
GRADIENT_METHODS = ("finite-difference", "spectral")
#: Model names of :func:`recommend_contact_models`.
CONTACT_MODELS = ("gw", "bem", "bem-plastic", "persson")


def _map_and_spacing(heights_m: npt.ArrayLike, physical_size_m: Any) -> tuple[FloatArray, float, float]:
    h = np.asarray(heights_m, dtype=np.float64)
    if h.ndim != 2 or min(h.shape) < 2:
        raise ContactError(f"rms gradient: heights_m must be a 2-D map of at least 2 x 2 points, got shape {h.shape}")
    if not np.all(np.isfinite(h)):
        raise ContactError("rms gradient: heights_m has non-finite values (fill undefined points first)")
    try:
        lx, ly = (float(v) for v in physical_size_m)
    except (TypeError, ValueError) as exc:
        raise ContactError(
            f"rms gradient: physical_size_m must be two lengths (Lx, Ly) [m], got {physical_size_m!r}"
        ) from exc
    if not (math.isfinite(lx) and math.isfinite(ly) and lx > 0.0 and ly > 0.0):
        raise ContactError(f"rms gradient: physical_size_m must be finite and > 0 m, got {(lx, ly)!r}")
    nx, ny = h.shape
    return h, lx / nx, ly / ny


def _nyquist_weight(n: int) -> FloatArray:
    """Weight 1/2 on the Nyquist index of an even-length axis (the symmetric real interpolant splits
    that coefficient equally between +q_N and −q_N), 1 elsewhere."""
    w = np.ones(n)
    if n % 2 == 0:
        w[n // 2] = 0.5
    return w


def rms_gradient(heights_m: npt.ArrayLike, physical_size_m: Any, *, method: str = "finite-difference") -> float:
    """Root-mean-square gradient ḡ = ⟨|∇h|²⟩^½ [-] of a height map.

    ``heights_m`` has shape (nx, ny), axis 0 along x; ``physical_size_m = (Lx, Ly)`` [m], pixel
    Δx = Lx/nx, Δy = Ly/ny (the convention of :class:`~stochfric.surface.io.Surface`).

    ``method="finite-difference"`` (default): first-order forward differences between neighbouring
    samples, ∂h/∂x ≈ (h[i+1, j] − h[i, j])/Δx and ∂h/∂y ≈ (h[i, j+1] − h[i, j])/Δy, both on the
    (nx−1) × (ny−1) points whose stencils lie inside the map, ḡ² = mean(∂h/∂x² + ∂h/∂y²).  This is
    the estimator of SurfaceTopography's ``rms_gradient`` for a non-periodic map (its default
    "upwind" stencil, trimmed at the edges) and equals it to rounding.  It never differences across
    the map's edge, so a measured (non-periodic) window is fine, and it is the slope of the
    piecewise-linear surface through the samples, i.e. of the discrete surface a boundary-element
    solution on the same grid sees.  Its transfer function 2 sin(qΔ/2)/Δ lies below q: a mode at
    wavelength λ has its gradient underestimated by sin(πΔ/λ)/(πΔ/λ) (1 % at λ = 13 Δ, 36 % at the
    Nyquist wavelength 2Δ).

    ``method="spectral"``: the map taken as one period of a periodic surface; with the DFT
    coefficients c_q = Σ h e^{−iq·x} / (nx ny) (the map's Fourier series, ``np.fft.fft2(h) / (nx ny)``),
    ḡ² = Σ_q w_q |q|² |c_q|², q = 2π (k_x/Lx, k_y/Ly), which is exactly the mean of |∇h|² of the
    real trigonometric interpolant of the samples (Parseval); w_q = 1 except that an even axis'
    Nyquist coefficient is split equally between ±q_N (w = ½ per such axis).  The PSD form is
    ḡ² = ∫ d²q q² C(q) with C(q) = (L/2π)² |c_q|².  A measured window is not periodic: the jump
    between opposite edges adds a spurious spectrum ∝ 1/q² along the axes, so the spectral ḡ of
    an unwindowed measured map exceeds the surface's (docs/persson.md gives a measured example).

    Raises :class:`~stochfric.contact.asperity.ContactError` for a map that is not 2-D of at least
    2 × 2 finite points, a bad size or an unknown method.
    """
    h, dx, dy = _map_and_spacing(heights_m, physical_size_m)
    if method == "finite-difference":
        gx = np.diff(h, axis=0)[:, :-1] / dx
        gy = np.diff(h, axis=1)[:-1, :] / dy
        return float(math.sqrt(float(np.mean(gx * gx + gy * gy))))
    if method == "spectral":
        nx, ny = h.shape
        c = np.fft.fft2(h) / (nx * ny)
        qx = 2.0 * np.pi * np.fft.fftfreq(nx, d=dx)
        qy = 2.0 * np.pi * np.fft.fftfreq(ny, d=dy)
        q2 = qx[:, None] ** 2 + qy[None, :] ** 2
        w = _nyquist_weight(nx)[:, None] * _nyquist_weight(ny)[None, :]
        return float(math.sqrt(float(np.sum(w * q2 * np.abs(c) ** 2))))
    raise ContactError(f"rms gradient: unknown method {method!r}; choose one of {', '.join(GRADIENT_METHODS)}")


def _positive_scalar(name: str, value: Any) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError) as exc:
        raise ContactError(f"Persson contact: {name} must be a number, got {value!r}") from exc
    if not (math.isfinite(v) and v > 0.0):
        raise ContactError(f"Persson contact: {name} must be finite and > 0, got {v!r}")
    return v


def _pressures(pressure_pa: npt.ArrayLike) -> FloatArray:
    p = np.asarray(pressure_pa, dtype=np.float64)
    if p.size == 0:
        raise ContactError("Persson contact: pressure_pa is empty; give one or more nominal pressures [Pa]")
    if not np.all(np.isfinite(p)) or np.any(p <= 0.0):
        raise ContactError("Persson contact: nominal pressures must be finite and > 0 Pa")
    return p


def persson_area_fraction(
    pressure_pa: npt.ArrayLike, e_star_pa: float, rms_gradient: float, *, corrected: bool = False
) -> FloatArray:
    """Real contact area fraction A/A_nom [-] of Persson's elastic theory at the nominal pressures p [Pa].

    Original (``corrected=False``): P = erf(√2 p/(E* ḡ)), i.e. erf(1/(2√G)) with
    G = (π/4)(E*/p)² ∫ q³ C dq = (E* ḡ/p)²/8; small-load slope κ = √(8/π) ≈ 1.596.

    ``corrected=True``: P = erf(κ_c (√π/2) p/(E* ḡ)) with κ_c = 2 (:data:`CORRECTED_KAPPA`) — a
    one-parameter rescaling of the argument so that the small-load slope is the exact (BEM/GFMD)
    κ ≈ 2 and P → 1 at large p.  It is not the Yang–Persson (2008) or Wang–Müser (2017) correction.

    ``e_star_pa``: contact modulus E* [Pa] (3.10); ``rms_gradient``: ḡ [-] of the rough surface (for
    two rough surfaces, ḡ² = ḡ1² + ḡ2²).  Vectorised: the result has the shape of ``pressure_pa``.
    Raises :class:`~stochfric.contact.asperity.ContactError` for p ≤ 0, E* ≤ 0, ḡ ≤ 0 or non-finite
    values.
    """
    p = _pressures(pressure_pa)
    e_star = _positive_scalar("e_star_pa", e_star_pa)
    g = _positive_scalar("rms_gradient", rms_gradient)
    kappa = CORRECTED_KAPPA if corrected else PERSSON_KAPPA
    # erf(x) ≈ 2x/√π at small x, so the argument κ (√π/2) p/(E* ḡ) gives the slope κ; for κ = √(8/π)
    # it is √2 p/(E* ḡ), Persson's 1/(2√G).
    out: FloatArray = np.asarray(erf(kappa * (math.sqrt(math.pi) / 2.0) * p / (e_star * g)), dtype=np.float64)
    return out


def small_load_kappa(
    area_fraction: npt.ArrayLike, pressure_pa: npt.ArrayLike, e_star_pa: float, rms_gradient: float
) -> FloatArray:
    """Slope κ = (A/A_nom) E* ḡ / p [-] of the small-load law A/A_nom ≈ κ p/(E* ḡ).

    Meaningful where p ≪ E* ḡ (the law is linear there); broadcasts ``area_fraction`` against
    ``pressure_pa``.  Raises :class:`~stochfric.contact.asperity.ContactError` for p ≤ 0, E* ≤ 0,
    ḡ ≤ 0, non-finite values or an area fraction outside [0, 1].
    """
    a = np.asarray(area_fraction, dtype=np.float64)
    if a.size == 0 or not np.all(np.isfinite(a)) or np.any(a < 0.0) or np.any(a > 1.0):
        raise ContactError("small-load kappa: area_fraction must be non-empty, finite and in [0, 1]")
    p = _pressures(pressure_pa)
    e_star = _positive_scalar("e_star_pa", e_star_pa)
    g = _positive_scalar("rms_gradient", rms_gradient)
    try:
        out: FloatArray = np.asarray(a * e_star * g / p, dtype=np.float64)
    except ValueError as exc:
        raise ContactError(
            f"small-load kappa: area_fraction {a.shape} and pressure_pa {p.shape} do not broadcast"
        ) from exc
    return out


@dataclass(frozen=True, kw_only=True)
class PerssonContact:
    """Persson's contact on one map over the nominal pressures (:func:`persson_contact`).

    ``pressure_pa`` p [Pa], ``area_fraction`` A/A_nom [-], ``contact_area_m2`` A = P·A_nom [m²],
    ``normal_force_n`` N = p·A_nom [N] (1-D, one entry per pressure); ``rms_gradient`` ḡ [-] of the
    map by ``estimator`` (``"finite-difference"`` or ``"spectral"``, :func:`rms_gradient`);
    ``kappa`` the small-load slope (√(8/π) original, 2 corrected); ``nominal_area_m2`` Lx·Ly [m²].
    """

    pressure_pa: FloatArray
    area_fraction: FloatArray
    contact_area_m2: FloatArray
    normal_force_n: FloatArray
    rms_gradient: float
    kappa: float
    corrected: bool
    nominal_area_m2: float
    estimator: str

    def to_dict(self) -> dict[str, Any]:
        """JSON-ready dictionary (arrays as lists, ``model = "persson"``, ``variant`` original/corrected)."""
        return {
            "model": "persson",
            "variant": "corrected" if self.corrected else "original",
            "pressure_pa": self.pressure_pa.tolist(),
            "area_fraction": self.area_fraction.tolist(),
            "contact_area_m2": self.contact_area_m2.tolist(),
            "normal_force_n": self.normal_force_n.tolist(),
            "rms_gradient": self.rms_gradient,
            "kappa": self.kappa,
            "corrected": self.corrected,
            "nominal_area_m2": self.nominal_area_m2,
            "estimator": self.estimator,
        }


def persson_contact(
    heights_m: npt.ArrayLike,
    physical_size_m: Any,
    e_star_pa: float,
    pressures_pa: npt.ArrayLike,
    *,
    corrected: bool = False,
    gradient_method: str = "finite-difference",
) -> PerssonContact:
    """Persson's elastic contact of a height map at the nominal pressures ``pressures_pa`` [Pa].

    ḡ from :func:`rms_gradient` with ``gradient_method`` (default finite differences: a measured
    window is not periodic, and the spectral estimator would count the jump between its opposite
    edges), A/A_nom from :func:`persson_area_fraction`, A = (A/A_nom)·Lx·Ly and N = p·Lx·Ly.  The map
    is used as given (level it first, e.g. with the package's preparation); a flat map (ḡ = 0) is an
    error.  Raises :class:`~stochfric.contact.asperity.ContactError` with one line on bad input.
    """
    g = rms_gradient(heights_m, physical_size_m, method=gradient_method)
    p = np.atleast_1d(_pressures(pressures_pa)).ravel()
    if g <= 0.0:
        raise ContactError("Persson contact: the map is flat (rms gradient 0); nothing to press")
    frac = persson_area_fraction(p, e_star_pa, g, corrected=corrected)
    lx, ly = (float(v) for v in physical_size_m)
    a_nom = lx * ly
    return PerssonContact(
        pressure_pa=p,
        area_fraction=frac,
        contact_area_m2=frac * a_nom,
        normal_force_n=p * a_nom,
        rms_gradient=g,
        kappa=CORRECTED_KAPPA if corrected else PERSSON_KAPPA,
        corrected=bool(corrected),
        nominal_area_m2=a_nom,
        estimator=gradient_method,
    )


def recommend_contact_models(plasticity_index: float | None) -> tuple[tuple[str, ...], str]:
    """Contact models for a plasticity index γ (3.7; ψ in Greenwood & Williamson 1966), best first.

    Names: ``"gw"`` (Greenwood–Williamson, the thesis's model), ``"bem"`` (elastic boundary-element
    half-space), ``"bem-plastic"`` (boundary elements with a hardness cap), ``"persson"`` (this
    module).  Rule (Greenwood & Williamson 1966; limits :data:`~stochfric.surface.statistics.ELASTIC_LIMIT`
    and :data:`~stochfric.surface.statistics.PLASTIC_LIMIT`): γ < 0.6 elastic → ("bem", "gw",
    "persson"); 0.6 ≤ γ ≤ 1 elastic-plastic → ("bem-plastic", "bem", "gw", "persson"); γ > 1 plastic →
    ("bem-plastic",); ``None`` (unknown) → all four.  With yield the real area at a given load is
    larger than the elastic one (at full plasticity A ≈ N/H), so elastic models underestimate A_c
    and hence μ = τ A_c / N.  Returns (names, one-sentence reason).  A negative or non-finite γ is a
    :class:`~stochfric.contact.asperity.ContactError`.
    """
    if plasticity_index is None:
        return (
            ("bem", "bem-plastic", "gw", "persson"),
            "plasticity index unknown: all contact models apply as candidates; compute the plasticity "
            "index (E*, hardness, summit statistics) to choose between elastic and plastic models",
        )
    try:
        g = float(plasticity_index)
    except (TypeError, ValueError) as exc:
        raise ContactError(f"plasticity index must be a number or None, got {plasticity_index!r}") from exc
    if not (math.isfinite(g) and g >= 0.0):
        raise ContactError(f"plasticity index must be finite and >= 0 (or None if unknown), got {g!r}")
    if g < ELASTIC_LIMIT:
        return (
            ("bem", "gw", "persson"),
            f"plasticity index γ = {g:.3g} < {ELASTIC_LIMIT:g}: the summits deform elastically; the elastic "
            "boundary-element solution is the reference, GW the thesis's model, Persson's theory a "
            "closed-form check from the rms gradient",
        )
    if g <= PLASTIC_LIMIT:
        return (
            ("bem-plastic", "bem", "gw", "persson"),
            f"plasticity index γ = {g:.3g} in [{ELASTIC_LIMIT:g}, {PLASTIC_LIMIT:g}]: part of the contacts "
            "yield; the boundary-element solution with a hardness cap is the reference, the elastic "
            "models (BEM, GW, Persson) underestimate the real contact area and hence mu",
        )
    return (
        ("bem-plastic",),
        f"plasticity index γ = {g:.3g} > {PLASTIC_LIMIT:g}: the contact is mostly plastic; use the "
        "boundary-element solution with a hardness cap — GW and the other elastic models underestimate "
        "the real contact area (which approaches N/H) and hence mu = tau A_c / N",
    )

"""Preparing a measured surface for the contact analysis (method §1.1–1.2, thesis 3.2.1).

In the vocabulary of ISO 25178-2 / ISO 16610 and in this order, each step chosen by the user or by
a stated rule and recorded (:func:`prepare_with_report`): 1 undefined points, 2 quantisation check,
3 outlier removal, 4 form removal, 5 rough-surface check (lateral scale, step, part outline, embossed
relief: :mod:`stochfric.surface.plausibility`), 6 quantisation treatment, 7 median filter
(thesis r = 5 / 6, edges mirrored), 8 coarse discretisation (thesis k = 10).  Steps 1–7 give the
*fine* surface, step 8 the *coarse* one (rules and numbers: :mod:`stochfric.surface.prepare_checks`
and docs/surface_contact.md, "Preparation").
"""

from __future__ import annotations

import copy
import math
from dataclasses import asdict, dataclass, fields
from pathlib import Path
from typing import Any, Literal

import numpy as np
import numpy.typing as npt
from scipy import ndimage

from stochfric.arrays import FloatArray
from stochfric.surface import plausibility as pl
from stochfric.surface import prepare_checks as pc
from stochfric.surface.io import MIN_GRID_POINTS, Surface, SurfaceError, _fill_harmonic

__all__ = [
    "DETREND_MODES",
    "FORM_FILTERS",
    "QUANTISED_TREATMENTS",
    "STEP_ORDER",
    "DetrendMode",
    "Preparation",
    "PreparationReport",
    "coarsen",
    "detrend",
    "median_filter",
    "preparation_report",
    "prepare",
    "prepare_with_report",
]

DetrendMode = Literal["none", "mean", "plane", "quadratic", "poly3", "auto", "gaussian", "robust-gaussian"]
#: Polynomial modes and their degree (``mean`` is degree 0).
_DEGREES = {"mean": 0, "plane": 1, "quadratic": 2, "poly3": 3}
FORM_FILTERS: tuple[str, ...] = ("gaussian", "robust-gaussian")
DETREND_MODES: tuple[str, ...] = ("none", "mean", "plane", "quadratic", "poly3", "auto", *FORM_FILTERS)
QUANTISED_TREATMENTS: tuple[str, ...] = ("warn", "dither")
#: SurfaceTopography's names for the same modes, and degree-named synonyms.
_MODE_SYNONYMS = {"center": "mean", "height": "plane", "curvature": "quadratic", "poly1": "plane", "poly2": "quadratic"}
_BY_DEGREE = {1: "plane", 2: "quadratic", 3: "poly3"}
#: Seed of the dither noise (fixed: the same map is prepared the same way every time).
DITHER_SEED = 0
#: The preparation steps in the order they are applied (:attr:`PreparationReport.order`).
STEP_ORDER: tuple[str, ...] = ("undefined", "quantisation check", "outliers", "form", "rough-surface check",
                               "quantisation treatment", "median filter", "coarsening")


def _normalise_mode(mode: str) -> str:
    m = _MODE_SYNONYMS.get(mode, mode)
    if m not in DETREND_MODES:
        raise SurfaceError(
            f"unknown detrend mode {mode!r}; use one of {', '.join(DETREND_MODES)} "
            f"(or SurfaceTopography's {', '.join(list(_MODE_SYNONYMS)[:3])})"
        )
    return m


def _positive_float(
    name: str, value: Any, *, low: float = 0.0, high: float = math.inf, inclusive: bool = False
) -> float:
    if isinstance(value, bool) or not isinstance(value, int | float | np.integer | np.floating):
        raise SurfaceError(f"{name} must be a number, got {value!r}")
    v = float(value)
    if not math.isfinite(v) or v <= 0.0:
        raise SurfaceError(f"{name} must be a finite number > 0, got {value!r}")
    if v < low or v > high or (not inclusive and v == low and low > 0):
        rng = f"in {low:g} … {high:g}" if math.isfinite(high) else f">= {low:g}"
        raise SurfaceError(f"{name} must be {rng}, got {value!r}")
    return v


@dataclass(frozen=True, kw_only=True)
class Preparation:
    """How a surface is prepared; recorded with every result (module doc for the order).

    Attributes
    ----------
    detrend:
        Form removal: ``"auto"`` (default, the stated rule), ``"none"``, ``"mean"``, ``"plane"``,
        ``"quadratic"``, ``"poly3"``, ``"gaussian"``, ``"robust-gaussian"`` (aliases ``"center"``,
        ``"height"``, ``"curvature"``, ``"poly1"``, ``"poly2"`` are accepted and normalised).
    cutoff_m:
        Nesting index λc [m] of the Gaussian L-filter; required for the two filter modes and
        refused otherwise.  Must lie between 5 grid spacings and the larger map side.
    median_radius:
        Median filter radius r >= 0 [grid points]; window (2r+1)×(2r+1); 0 = off.
    step:
        Coarsening step k >= 1: keep every k-th point; 1 = off.
    outliers:
        Remove isolated spikes/pits (default True).
    outlier_k:
        Multiple k of the robust residual scale σ_r (default 6, at least 3).
    outlier_sq:
        Multiple m of the robust height scale S (default 5, at least 2).
    quantised:
        Treatment of quantised heights: ``"warn"`` (default) or ``"dither"``.
    max_undefined:
        Largest fraction of undefined (filled) points accepted, in (0, 1] (default 0.05).
    rough_check:
        Refuse maps that are not a rough surface (step, part outline, embossed relief) or whose stated lateral
        size no instrument measures (:mod:`stochfric.surface.plausibility`); default True.
    """

    detrend: str = "auto"
    median_radius: int = 0
    step: int = 1
    cutoff_m: float | None = None
    outliers: bool = True
    outlier_k: float = pc.OUTLIER_K
    outlier_sq: float = pc.OUTLIER_SQ
    quantised: str = "warn"
    max_undefined: float = pc.MAX_UNDEFINED_DEFAULT
    rough_check: bool = True

    def __post_init__(self) -> None:
        object.__setattr__(self, "detrend", _normalise_mode(str(self.detrend)))
        for name, value, low in (("median_radius", self.median_radius, 0), ("step", self.step, 1)):
            if isinstance(value, bool) or not isinstance(value, int | np.integer):
                raise SurfaceError(f"{name} must be an integer, got {value!r}")
            if value < low:
                raise SurfaceError(f"{name} must be >= {low}, got {value}")
            object.__setattr__(self, name, int(value))
        if self.detrend in FORM_FILTERS:
            if self.cutoff_m is None:
                raise SurfaceError(f"detrend {self.detrend!r} needs the nesting index λc (cutoff, --cutoff-um)")
            object.__setattr__(
                self, "cutoff_m", _positive_float("the cutoff λc [m] (--cutoff-um × 1e-6)", self.cutoff_m)
            )
        elif self.cutoff_m is not None:
            raise SurfaceError(f"a cutoff λc applies only to detrend gaussian or robust-gaussian, not {self.detrend!r}")
        object.__setattr__(
            self, "outlier_k", _positive_float("outlier_k (--outlier-k)", self.outlier_k, low=3.0, inclusive=True)
        )
        object.__setattr__(
            self, "outlier_sq", _positive_float("outlier_sq (--outlier-sq)", self.outlier_sq, low=2.0, inclusive=True)
        )
        object.__setattr__(
            self,
            "max_undefined",
            _positive_float("max_undefined (--max-undefined)", self.max_undefined, high=1.0, inclusive=True),
        )
        if str(self.quantised) not in QUANTISED_TREATMENTS:
            raise SurfaceError(
                f"quantised (--quantised) must be one of {', '.join(QUANTISED_TREATMENTS)}, got {self.quantised!r}"
            )
        object.__setattr__(self, "quantised", str(self.quantised))
        for name in ("outliers", "rough_check"):
            if not isinstance(getattr(self, name), bool | np.bool_):
                raise SurfaceError(f"{name} must be True or False, got {getattr(self, name)!r}")
            object.__setattr__(self, name, bool(getattr(self, name)))

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary (JSON / netCDF attributes): ``detrend``, ``median_radius``, ``step``
        and every other field that differs from its default, so that ``Preparation(**d)`` gives
        the same preparation back (:meth:`settings` has all fields)."""
        full = asdict(self)
        keep = {"detrend", "median_radius", "step"}
        return {f.name: full[f.name] for f in fields(self) if f.name in keep or full[f.name] != f.default}

    def settings(self) -> dict[str, Any]:
        """Every field (the complete record)."""
        return asdict(self)


def detrend(heights: npt.ArrayLike, mode: str = "plane") -> FloatArray:
    """Subtract the least-squares polynomial of ``mode`` from ``heights`` (same units).

    Polynomial modes and ``"auto"`` (the degree chosen by
    :func:`~stochfric.surface.prepare_checks.auto_degree`); the Gaussian filters need the grid
    spacing and go through :func:`prepare`.  The fit uses the grid indices as coordinates; for a
    uniform grid this gives the same residual as a fit over physical positions (the polynomial
    spaces are the same).
    """
    h = np.asarray(heights, dtype=np.float64)
    m = _normalise_mode(mode)
    if m == "none":
        return h.copy()
    if m == "auto":
        degree, _ = pc.auto_degree(h)
        return pc.polynomial_residual(h, degree)
    if m in FORM_FILTERS:
        raise SurfaceError(f"detrend {m!r} needs the grid spacing and a cutoff; use prepare()")
    return pc.polynomial_residual(h, _DEGREES[m])


def median_filter(heights: npt.ArrayLike, radius: int) -> FloatArray:
    """2-D median filter over a (2r+1)×(2r+1) window, edges mirrored (method §1.1)."""
    h = np.asarray(heights, dtype=np.float64)
    if radius < 0:
        raise SurfaceError(f"median radius must be >= 0, got {radius}")
    if radius == 0:
        return h.copy()
    return np.asarray(ndimage.median_filter(h, size=2 * radius + 1, mode="reflect"))


def coarsen(surface: Surface, step: int) -> Surface:
    """Keep every ``step``-th point in x and y (method §1.2); spacing becomes ``step·Δ``.

    Raises :class:`SurfaceError` if fewer than ``MIN_GRID_POINTS`` points would remain in a
    direction (the summit rule needs two neighbours on each side).
    """
    if step < 1:
        raise SurfaceError(f"step must be >= 1, got {step}")
    if step == 1:
        return surface
    h = surface.heights_m[::step, ::step]
    nx, ny = h.shape
    if min(nx, ny) < MIN_GRID_POINTS:
        raise SurfaceError(
            f"step {step} leaves {nx}×{ny} points of the {surface.nb_grid_pts[0]}×"
            f"{surface.nb_grid_pts[1]} grid; at least {MIN_GRID_POINTS} per direction are "
            f"needed, use a step <= {min(surface.nb_grid_pts) // MIN_GRID_POINTS}"
        )
    dx, dy = surface.grid_spacing_m
    return Surface(
        heights_m=np.array(h),
        physical_size_m=(nx * step * dx, ny * step * dy),
        source=surface.source,
        n_undefined_filled=surface.n_undefined_filled,
        info={**surface.info, "coarsened_from": list(surface.nb_grid_pts)},
    )


def _rms(h: FloatArray) -> float:
    return float(np.sqrt(np.mean((h - h.mean()) ** 2)))


def _name(surface: Surface) -> str:
    return Path(surface.source).name if surface.source != "array" else "the height map"


@dataclass(frozen=True, kw_only=True)
class PreparationReport:
    """What every preparation step did to one surface (:func:`prepare_with_report`; module doc for the steps).

    Each step's entry is a plain dictionary of its numbers (the JSON record, SI units in the keys):
    ``undefined`` (step 1: count, fraction, border fraction, limit), ``quantisation`` (steps 2 and 6: tie
    fractions, height quantum, whether dithered), ``outliers`` (step 3: count, fraction, positions, the
    rule's scales), ``form`` (step 4: requested and applied form, Sq before and after, Sq by degree, the
    ``auto`` rule), ``rough_surface`` (step 5: the verdict, with the ``lateral_scale`` and
    ``relief`` records of :mod:`~stochfric.surface.plausibility`); ``median_radius`` and ``step`` are steps 7
    and 8, ``settings`` the complete :class:`Preparation`.  :meth:`to_dict` gives the JSON record
    (``preparation.preparation_report`` of the command outputs, ``fine.info["preparation"]``).
    """

    order: tuple[str, ...]
    settings: dict[str, Any]
    undefined: dict[str, Any]
    quantisation: dict[str, Any]
    outliers: dict[str, Any]
    form: dict[str, Any]
    rough_surface: dict[str, Any]
    median_radius: int
    step: int

    def to_dict(self) -> dict[str, Any]:
        """The JSON record (a deep copy: changing it leaves the report as it is)."""
        return {
            "order": list(self.order),
            "settings": copy.deepcopy(self.settings),
            "undefined": copy.deepcopy(self.undefined),
            "quantisation": copy.deepcopy(self.quantisation),
            "outliers": copy.deepcopy(self.outliers),
            "form": copy.deepcopy(self.form),
            "rough_surface": copy.deepcopy(self.rough_surface),
            "median_radius": self.median_radius,
            "step": self.step,
        }

    @classmethod
    def from_dict(cls, record: dict[str, Any]) -> PreparationReport:
        """The report back from :meth:`to_dict` (e.g. ``fine.info["preparation"]``)."""
        return cls(order=tuple(record["order"]), **{f.name: copy.deepcopy(record[f.name])
                                                    for f in fields(cls) if f.name != "order"})

    def __repr__(self) -> str:
        return (f"PreparationReport(form {self.form['requested']} -> {self.form['applied']}, "
                f"{self.outliers['count']} outliers replaced, {self.undefined['count']} undefined points filled, "
                f"median radius {self.median_radius}, step {self.step})")


def prepare_with_report(
    surface: Surface, preparation: Preparation | None = None
) -> tuple[Surface, Surface, PreparationReport]:
    """Apply ``preparation`` to ``surface``; return ``(fine, coarse, report)``.

    ``report`` (:class:`PreparationReport`) says what every step did (its :meth:`~PreparationReport.to_dict`
    is also stored as ``fine.info["preparation"]``); the coded warnings of the preparation are appended to
    ``fine.info["warnings"]`` after the reading's.

    Raises
    ------
    SurfaceError
        Too small a grid, too many undefined points, a cutoff out of range, a map that is not a
        rough surface, a step that leaves too few points.
    """
    prep = preparation if preparation is not None else Preparation()
    name = _name(surface)
    _check_grid(surface, prep)
    undefined = _undefined_points(surface, prep, name)
    read = np.array(surface.heights_m, dtype=np.float64)
    quantisation = _quantisation_check(read, prep)
    cleaned, outliers, warnings = _remove_outliers(read, surface, prep, name)
    h, form = _remove_form(cleaned, read, surface, prep, name)
    rough, plausibility = _rough_surface_check(h, cleaned, surface, undefined, quantisation, prep, name)
    h, quantised = _treat_quantisation(h, quantisation, prep, name)
    h = median_filter(h, prep.median_radius)
    report = PreparationReport(order=STEP_ORDER, settings=prep.settings(), undefined=undefined,
                               quantisation=quantisation, outliers=outliers, form=form, rough_surface=rough,
                               median_radius=prep.median_radius, step=prep.step)  # fmt: skip
    info = dict(surface.info)
    info["warnings"] = [dict(w) for w in surface.info.get("warnings", [])] + warnings + plausibility + quantised
    info["preparation"] = report.to_dict()
    fine = Surface(
        heights_m=h,
        physical_size_m=surface.physical_size_m,
        source=surface.source,
        n_undefined_filled=surface.n_undefined_filled,
        info=info,
    )
    return fine, coarsen(fine, prep.step), report


def _check_grid(surface: Surface, prep: Preparation) -> None:
    """Refuse, before any work, a grid too small for the summit rule or for the median window."""
    nx, ny = surface.nb_grid_pts
    if min(nx, ny) < MIN_GRID_POINTS:
        raise SurfaceError(
            f"the surface has only {nx}×{ny} points; at least {MIN_GRID_POINTS} per direction are needed"
        )
    if 2 * prep.median_radius + 1 > min(nx, ny):
        raise SurfaceError(
            f"--median-radius {prep.median_radius} gives a {2 * prep.median_radius + 1}-point window, larger than "
            f"the {nx}×{ny} map; use a radius of at most {(min(nx, ny) - 1) // 2} (the thesis uses 5 and 6)"
        )


def _undefined_points(surface: Surface, prep: Preparation, name: str) -> dict[str, Any]:
    """Step 1: the undefined points filled on reading; a part outline or more than ``max_undefined`` is refused."""
    und_fraction = float(surface.info.get("undefined_fraction", surface.n_undefined_filled / surface.heights_m.size))
    border_fraction = float(surface.info.get("undefined_border_fraction", 0.0))
    if prep.rough_check and border_fraction > pc.OUTLINE_BORDER_FRACTION:
        # a part outline is the more basic reason than the undefined fraction it causes
        raise SurfaceError(
            f"{name} is not a rough surface (part outline: {100 * border_fraction:.3g} % of the map is an undefined "
            f"surround connected to its border, limit {100 * pc.OUTLINE_BORDER_FRACTION:g} %: the measuring field "
            "extends past the part); crop the map to the part, or pass --no-rough-check to analyse it anyway"
        )
    if und_fraction > prep.max_undefined:
        raise SurfaceError(
            f"{name} has {100 * und_fraction:.3g} % undefined points, more than the limit "
            f"{100 * prep.max_undefined:.3g} % (--max-undefined): the harmonic fill has no summit, so it "
            "would bias the summit density by that fraction; crop the measurement or raise the limit"
        )
    return {
        "count": int(surface.n_undefined_filled),
        "fraction": und_fraction,
        "border_fraction": border_fraction,
        "limit": prep.max_undefined,
    }


def _quantisation_check(read: FloatArray, prep: Preparation) -> dict[str, Any]:
    """Step 2: tie fraction and height quantum of the heights as read (before any step breaks the ties)."""
    ties = pc.tie_statistics(read)
    return {
        "tie_fraction": ties["tie_fraction"],
        "tie_fraction_x": ties["tie_fraction_x"],
        "tie_fraction_y": ties["tie_fraction_y"],
        "quantum_m": ties["quantum"],
        "warn_above": pc.TIE_WARN,
        "quantised": ties["tie_fraction"] > pc.TIE_WARN,
        "treatment": prep.quantised,
        "applied": False,
    }


def _remove_outliers(
    h: FloatArray, surface: Surface, prep: Preparation, name: str
) -> tuple[FloatArray, dict[str, Any], list[dict[str, Any]]]:
    """Step 3: isolated spikes / pits (|z − median₅ₓ₅ z| > max(k σ_r, m S)) replaced by harmonic
    interpolation; the heights, the step's record and its warning."""
    n = h.size
    out: dict[str, Any] = {"enabled": prep.outliers, "count": 0, "fraction": 0.0, "positions": [],
                           "window": pc.OUTLIER_WINDOW, "k": prep.outlier_k, "m_sq": prep.outlier_sq}  # fmt: skip
    if not prep.outliers:
        return h, out, []
    mask, scales = pc.outlier_mask(h, k=prep.outlier_k, m_sq=prep.outlier_sq)
    count = int(np.count_nonzero(mask))
    ii, jj = np.nonzero(mask)
    cap = pc.OUTLIER_POSITIONS_CAP
    out.update(
        count=count, fraction=count / n, positions=[[int(a), int(b)] for a, b in zip(ii[:cap], jj[:cap], strict=True)],
        positions_cap=cap, threshold_m=scales["threshold"], sigma_r_m=scales["sigma_r"],
        s_robust_m=scales["s_robust"],
    )  # fmt: skip
    if not 0 < count < n:
        return h, out, []
    warning = {
        "code": "outliers-replaced", "count": count, "fraction": count / n,
        "message": (f"{name}: {count} isolated spike/pit point(s) ({100 * count / n:.3g} % of the map) "
                    f"more than {out['threshold_m']:.3g} m from their 5x5 median replaced by harmonic "
                    "interpolation (--no-outliers keeps them)"),
    }  # fmt: skip
    return _fill_harmonic(np.ma.MaskedArray(h, mask=mask), surface.physical_size_m), out, [warning]


def _remove_form(
    h: FloatArray, read: FloatArray, surface: Surface, prep: Preparation, name: str
) -> tuple[FloatArray, dict[str, Any]]:
    """Step 4: the form removed by ``prep.detrend`` (polynomial, the ``auto`` rule or an ISO 16610
    L-filter); the heights and the step's record.  A map left flat is refused."""
    degree_auto, sq_deg = pc.auto_degree(h)
    form: dict[str, Any] = {
        "requested": prep.detrend,
        "sq_read_m": _rms(np.asarray(surface.heights_m)),
        "sq_read_plane_m": _rms(pc.polynomial_residual(read, 1)),
        "sq_by_degree_m": sq_deg,
        "auto_degree": degree_auto,
        "auto_rule": (f"degree 1, raised while the next degree removes more than "
                      f"{100 * pc.AUTO_VARIANCE_GAIN:g} % of the remaining variance, up to 3"),
    }  # fmt: skip
    if prep.detrend in FORM_FILTERS:
        assert prep.cutoff_m is not None
        spacing = surface.grid_spacing_m
        low, high = 5.0 * max(spacing), max(surface.physical_size_m)
        if not low <= prep.cutoff_m <= high:
            raise SurfaceError(
                f"the cutoff λc = {prep.cutoff_m * 1e6:.4g} µm is out of range for {name}: it must lie between "
                f"5 grid spacings ({low * 1e6:.4g} µm) and the larger map side ({high * 1e6:.4g} µm)"
            )
        levelled = pc.polynomial_residual(h, 1)
        h, frec = pc.gaussian_lfilter(levelled, spacing, prep.cutoff_m, robust=prep.detrend == "robust-gaussian")
        form.update(applied=prep.detrend, degree=None, cutoff_m=prep.cutoff_m, **frec)
    elif prep.detrend == "none":
        form.update(applied="none", degree=None)
    else:
        degree = degree_auto if prep.detrend == "auto" else _DEGREES[prep.detrend]
        form.update(applied="mean" if degree == 0 else _BY_DEGREE[degree], degree=degree)
        h = pc.polynomial_residual(h, degree)
    form["sq_after_m"] = _rms(h)
    if not float(np.ptp(h)) > 0.0:
        raise SurfaceError(f"{name} is flat after the form removal (all heights equal): there is no roughness, "
                           "hence no summit, to analyse")
    return h, form


def _rough_surface_check(
    h: FloatArray, before_form: FloatArray, surface: Surface, undefined: dict[str, Any], quant: dict[str, Any],
    prep: Preparation, name: str,
) -> tuple[dict[str, Any], list[dict[str, Any]]]:
    """Step 5: is the form-removed map a plausible measurement of a rough surface?  The verdict and the coded
    warnings.

    First the lateral scale (:func:`~stochfric.surface.plausibility.lateral_scale_verdict`: a stated size no
    instrument measures is refused, a pixel size implausibly large for the heights warned about), then the
    rough-surface verdict: a step / two-level map (Otsu), a part outline, an embossed relief (non-stationary
    local roughness, :func:`~stochfric.surface.plausibility.relief_verdict`) are refused.  The step is judged on
    the form-removed heights, or on the plane residual where that one finds a step.  ``rough_check`` off: nothing
    is refused; the verdict is recorded and an implausible lateral size becomes a warning.
    """
    lateral = pl.lateral_scale_verdict(h, surface.physical_size_m, reader=surface.info.get("reader"), name=name)
    warnings = [lateral.pop("warning")] if lateral["warning"] is not None else []
    if not lateral["plausible"]:
        if prep.rough_check:
            raise SurfaceError(f"{name}: {lateral['reason']}; pass --no-rough-check only if the stated size is right")
        warnings.insert(0, {"code": "implausible-lateral-size", "physical_size_m": lateral["physical_size_m"],
                            "message": f"{name}: {lateral['reason']} (analysed anyway: --no-rough-check)"})
    border_fraction = undefined["border_fraction"]
    verdict = pc.rough_surface_verdict(h, undefined_border_fraction=border_fraction)
    if verdict["rough"]:
        # a higher-order form (or an L-filter) can absorb part of a step: judge the plane residual too
        plane_verdict = pc.rough_surface_verdict(pc.polynomial_residual(before_form, 1))
        if not plane_verdict["rough"]:
            verdict = {**plane_verdict, "reason": f"{plane_verdict['reason']}, after a plane fit",
                       "undefined_border_fraction": border_fraction}
    relief = pl.relief_verdict(h, quantum_m=quant["quantum_m"], undefined_fraction=undefined["fraction"])
    if relief["relief"]:
        reasons = [relief["reason"]] + ([verdict["reason"]] if verdict["reason"] else [])
        verdict.update(rough=False, reason="; ".join(reasons))
    verdict.update(relief=relief, lateral_scale=lateral, checked=prep.rough_check)
    if prep.rough_check and not verdict["rough"]:
        raise SurfaceError(
            f"{name} is not a rough surface ({verdict['reason']}); crop the map to one level, to the part or to "
            "a rough region, or pass --no-rough-check to analyse it anyway"
        )
    return verdict, warnings


def _treat_quantisation(
    h: FloatArray, quant: dict[str, Any], prep: Preparation, name: str
) -> tuple[FloatArray, list[dict[str, Any]]]:
    """Step 6: quantised heights dithered by one quantum (``prep.quantised = "dither"``, recorded in
    ``quant``) or warned about; the heights and the warning."""
    q = quant["quantum_m"]
    if not quant["quantised"] or q is None:
        return h, []
    if prep.quantised == "dither":
        quant.update(applied=True, seed=DITHER_SEED)
        return pc.dither(h, q, seed=DITHER_SEED), []
    return h, [{
        "code": "quantised-heights", "tie_fraction": quant["tie_fraction"], "quantum_m": q,
        "message": (f"{name}: {100 * quant['tie_fraction']:.3g} % of the neighbouring height pairs are "
                    f"identical (height quantum {q:.3g} m, limit {100 * pc.TIE_WARN:g} %); flat tops fail "
                    "the strict summit rule, so summits are missed - --quantised dither adds uniform "
                    "noise of one quantum"),
    }]  # fmt: skip


def prepare(surface: Surface, preparation: Preparation | None = None) -> tuple[Surface, Surface]:
    """Apply ``preparation`` to ``surface``; return ``(fine, coarse)``.

    ``fine`` is the surface after steps 1–7 (module doc), ``coarse`` additionally coarsened (the
    two are the same object for ``step = 1``). The contact analysis uses ``coarse``.  The
    report of every step is ``fine.info["preparation"]`` (:meth:`PreparationReport.to_dict`).
    """
    fine, coarse, _ = prepare_with_report(surface, preparation)
    return fine, coarse


def preparation_report(surface: Surface, preparation: Preparation | None = None) -> PreparationReport:
    """What :func:`prepare` does to ``surface`` (the report alone; raises like :func:`prepare`)."""
    return prepare_with_report(surface, preparation)[2]

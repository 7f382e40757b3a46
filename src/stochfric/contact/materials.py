"""Material pairings for the contact analysis (method §1 table, thesis Tables 3.1/3.2/3.4/3.5).

``E*`` from (3.10): ``1/E* = (1−ν1²)/E1 + (1−ν2²)/E2``, ``E2 = ∞`` for a rigid counter-body;
hardness ``H = 5.6 R_p`` (thesis 3.1.3) unless tabulated; ``τ_max`` the shear strength of
Bowden–Tabor (3.15/3.16).  Body 1 is the rough body (the measured surface), body 2 the
counter-body.  The presets ``brake-pad`` and ``dc04`` (SI units) reproduce the thesis; the
library adds pairings from standards (grey cast iron EN 1561, steel EN 10025-2 / EN 1993-1-1,
aluminium EN 1999-1-1).  The thesis's misprint of E* for DC04 (method erratum 2), the sources
of every value and the plausible ranges that :class:`Material` enforces are tabulated in
docs/surface_contact.md, "Materials".

Names are looked up case-insensitively, and ``_``, blanks and ``-`` are the same
(``"DC04"``, ``"Brake_Pad"``); the canonical name is what results record.
"""

from __future__ import annotations

import difflib
import json
import math
import numbers
import re
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from stochfric.errors import InputError
from stochfric.io_utils import read_text_checked
from stochfric.units import GIGAPASCAL, MEGAPASCAL

__all__ = [
    "E_RANGE_PA",
    "HARDNESS_FACTOR",
    "HARDNESS_RANGE_PA",
    "MATERIALS",
    "POISSON_RANGE",
    "SHEAR_STRENGTH_RANGE_PA",
    "YIELD_STRENGTH_RANGE_PA",
    "Material",
    "MaterialError",
    "canonical_material_name",
    "get_material",
    "load_material",
    "material_names",
    "material_table",
]

#: H = 5.6 R_p (thesis 3.1.3).
HARDNESS_FACTOR = 5.6

#: Young's modulus [Pa]: soft engineering elastomers (~1 MPa) to diamond (~1.2 TPa).
E_RANGE_PA = (1.0e6, 1.2e12)
#: Poisson ratio: (0, 0.5]; 0.5 is incompressible, above is thermodynamically impossible for an
#: isotropic solid, ν ≤ 0 (auxetic foams) is no engineering friction material.
POISSON_RANGE = (0.0, 0.5)
#: Yield strength R_p [Pa]: soft polymers and lead (~1 MPa) to the ideal strength of diamond (~100 GPa).
YIELD_STRENGTH_RANGE_PA = (1.0e6, 1.0e11)
#: Hardness H [Pa]: ~1 MPa to diamond (Vickers 70–150 GPa).
HARDNESS_RANGE_PA = (1.0e6, 1.5e11)
#: Bowden–Tabor shear strength τ_max [Pa]: from boundary films (~0.1 MPa) up; above, R_p bounds it.
SHEAR_STRENGTH_RANGE_PA = (1.0e5, 1.0e11)

_UNIT_GUESSES = {"GPa": GIGAPASCAL, "MPa": MEGAPASCAL}


class MaterialError(InputError):
    """A material parameter is invalid or a material name is unknown."""


@dataclass(frozen=True)
class _Range:
    """Plausible range of one field and what a value outside it usually means."""

    what: str  # what the field is
    lo: float
    hi: float
    span: str  # what the ends of the range are
    unit: str = "Pa"
    lo_open: bool = False  # lo itself is refused
    guesses: tuple[str, ...] = ()  # units the value may have been given in
    typical: float = 1.0  # a typical value [Pa]: of two possible units, the one landing nearer wins


_E_SPAN = "soft elastomers ~1 MPa to diamond ~1.2 TPa"
_NU_SPAN = "metals 0.27-0.35, polymers 0.35-0.45, elastomers ~0.5"
_RANGES: dict[str, _Range] = {
    "e1_pa": _Range(
        "Young's modulus of the rough body (1)", *E_RANGE_PA, _E_SPAN, guesses=("GPa", "MPa"), typical=1e10
    ),
    "e2_pa": _Range(
        "Young's modulus of the counter-body (2)", *E_RANGE_PA, _E_SPAN + "; inf (JSON null) for a rigid body",
        guesses=("GPa", "MPa"), typical=1e10,
    ),
    "nu1": _Range("Poisson ratio of the rough body (1)", *POISSON_RANGE, _NU_SPAN, unit="", lo_open=True),
    "nu2": _Range("Poisson ratio of the counter-body (2)", *POISSON_RANGE, _NU_SPAN, unit="", lo_open=True),
    "yield_strength_pa": _Range(
        "yield strength R_p", *YIELD_STRENGTH_RANGE_PA, "soft polymers and lead ~1 MPa to diamond ~100 GPa",
        guesses=("MPa", "GPa"), typical=3e8,
    ),
    "shear_strength_pa": _Range(
        "Bowden-Tabor shear strength tau_max", *SHEAR_STRENGTH_RANGE_PA,
        "boundary films ~0.1 MPa up to the yield strength", guesses=("MPa", "GPa"), typical=1e8,
    ),
    "hardness_pa": _Range(
        "hardness H", *HARDNESS_RANGE_PA, "soft polymers ~1 MPa to diamond ~150 GPa", guesses=("MPa", "GPa"),
        typical=2e9,
    ),
}  # fmt: skip


def _num(x: float) -> str:
    """``x`` readably: ``235``, ``0.3``, ``2.1e11``, ``1e-05``."""
    if not math.isfinite(x) or x == 0.0 or 1e-3 <= abs(x) < 1e4:
        return f"{x:.4g}"
    mantissa, exponent = f"{x:.3e}".split("e")
    return f"{mantissa.rstrip('0').rstrip('.')}e{int(exponent)}"


def _unit_guess(r: _Range, value: float) -> str | None:
    """The unit a too-small ``value`` was likely given in (it lands in range, nearest the typical value)."""
    best: tuple[float, str] | None = None
    for unit in r.guesses:
        factor = _UNIT_GUESSES[unit]
        limit = 1.3e6 if unit == "MPa" and r.typical >= 1e10 else 1e4  # moduli are often in MPa (N/mm²)
        if value < limit and r.lo <= value * factor <= r.hi:
            distance = abs(math.log10(value * factor / r.typical))
            if best is None or distance < best[0]:
                best = (distance, unit)
    return None if best is None else best[1]


def _range_error(name: str, key: str, value: float) -> MaterialError:
    """The one-line error for ``key = value`` outside its plausible range."""
    r = _RANGES[key]
    unit = f" {r.unit}" if r.unit else ""
    span = f"{_num(r.lo)} < {key} <= {_num(r.hi)}" if r.lo_open else f"{_num(r.lo)} … {_num(r.hi)}{unit}"
    head = f"material {name!r}: {key} = {_num(value)}{unit} is not a plausible {r.what} (plausible {span}: {r.span})"
    if key in ("nu1", "nu2"):
        if value == 0.0:
            hint = "0 is most likely a missing value; give the measured ratio"
        elif value < 0.0:
            hint = "a negative ratio (an auxetic foam) is no engineering friction material; check the sign"
        elif 1.0 < value <= 50.0:
            hint = f"a percentage? {value:g} % is {value / 100:g}"
        elif math.isnan(value):
            hint = "NaN is no value"
        else:
            hint = "a Poisson ratio above 0.5 is impossible for an isotropic solid"
        return MaterialError(f"{head}; {hint}")
    example = " (210 GPa is 2.1e11)" if key in ("e1_pa", "e2_pa") else " (235 MPa is 2.35e8)"
    guess = _unit_guess(r, value) if math.isfinite(value) and 0.0 < value < r.lo else None
    if guess is not None:
        hint = f"values are in Pa; if {value:g} {guess} is meant, write {_num(value * _UNIT_GUESSES[guess])}"
    elif value <= 0.0:
        hint = f"it must be positive; values are in Pa{example}"
    elif math.isnan(value):
        hint = "NaN is no value"
    elif math.isinf(value):
        hint = ("only the counter-body may be rigid (e2_pa = inf, JSON null)" if key == "e1_pa"
                else "a finite value is needed")  # fmt: skip
    else:
        hint = f"values are in Pa{example}"
    return MaterialError(f"{head}; {hint}")


def _number(name: str, key: str, value: Any) -> float:
    """``value`` as a float, or a :class:`MaterialError` naming ``key``."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        unit = _RANGES[key].unit
        raise MaterialError(
            f"material {name!r}: {key} must be a number{' in ' + unit if unit else ''}, "
            f"got {value!r} ({type(value).__name__})"
        )
    return float(value)


def _check(name: str, key: str, value: float) -> None:
    r = _RANGES[key]
    ok = (r.lo < value if r.lo_open else r.lo <= value) and value <= r.hi
    if not ok:  # NaN fails both comparisons
        raise _range_error(name, key, value)


@dataclass(frozen=True, kw_only=True)
class Material:
    """Elastic pairing of the rough body (1) and the counter-body (2); SI units.

    Every field is checked against a plausible physical range and the pairing against two rules
    of physics (:meth:`__post_init__`; docs/surface_contact.md, "Materials"), so a material
    read from a file is checked too.

    Attributes
    ----------
    name:
        Identifier (``"brake-pad"``, ``"dc04"`` or user-chosen).
    e1_pa, nu1:
        Young's modulus [Pa] and Poisson ratio of the rough body.
    e2_pa, nu2:
        Young's modulus [Pa] (``math.inf`` = rigid) and Poisson ratio of the counter-body.
    yield_strength_pa:
        ``R_p`` [Pa] of the softer material (for the hardness).
    shear_strength_pa:
        ``τ_max`` [Pa] (Bowden–Tabor, 3.15).
    hardness_pa:
        ``H`` [Pa]; ``None`` means ``5.6 R_p``.
    description:
        Free text (source of the values).
    """

    name: str
    e1_pa: float
    nu1: float
    e2_pa: float = math.inf
    nu2: float = 0.3
    yield_strength_pa: float
    shear_strength_pa: float
    hardness_pa: float | None = None
    description: str = ""

    def __post_init__(self) -> None:
        """Check types, plausible ranges and the rules ``H ≥ R_p`` and ``τ_max ≤ R_p``.

        Numbers are stored as ``float``.  Ranges (SI): E 1e6 … 1.2e12 Pa (``e2_pa`` may be
        ``inf``), ν in (0, 0.5], R_p 1e6 … 1e11 Pa, H 1e6 … 1.5e11 Pa, τ_max 1e5 … 1e11 Pa.
        Rules: an indentation hardness is never below the uniaxial yield strength (the
        constraint factor H/R_p is ≥ 1, about 3 for metals); the junction shear strength never
        exceeds the shear yield strength of the softer body (R_p/√3 by von Mises, R_p/2 by
        Tresca), so ``τ_max ≤ R_p`` with room for rounding (the thesis's DC04: 500 MPa vs
        860/√3 = 497 MPa); ``τ_max ≤ H`` follows.
        """
        if not isinstance(self.name, str) or not self.name.strip():
            raise MaterialError(f"a material needs a name (a non-empty string), got {self.name!r}")
        name = self.name
        if not isinstance(self.description, str):
            raise MaterialError(f"material {name!r}: description must be a string, got {self.description!r}")
        keys = ["e1_pa", "nu1", "e2_pa", "nu2", "yield_strength_pa", "shear_strength_pa"]
        if self.hardness_pa is not None:
            keys.append("hardness_pa")
        for key in keys:
            value = _number(name, key, getattr(self, key))
            object.__setattr__(self, key, value)
            if not (key == "e2_pa" and value == math.inf):
                _check(name, key, value)
        rp, tau, h = self.yield_strength_pa, self.shear_strength_pa, self.hardness
        if h < rp:
            raise MaterialError(
                f"material {name!r}: hardness_pa = {h / MEGAPASCAL:.4g} MPa is below yield_strength_pa = "
                f"{rp / MEGAPASCAL:.4g} MPa; an indentation hardness is at least the yield strength "
                "(about 3 R_p for metals; 5.6 R_p by the thesis's rule when hardness_pa is null): "
                "is one of them in the wrong unit, or the two swapped?"
            )
        if tau > rp:
            raise MaterialError(
                f"material {name!r}: shear_strength_pa = {tau / MEGAPASCAL:.4g} MPa exceeds yield_strength_pa = "
                f"{rp / MEGAPASCAL:.4g} MPa; a junction cannot be stronger in shear than the softer body "
                f"(shear yield R_p/sqrt(3) = {rp / math.sqrt(3) / MEGAPASCAL:.4g} MPa): give tau_max "
                "<= R_p, or R_p of the softer body"
            )

    @property
    def e_star_pa(self) -> float:
        """Contact modulus E* [Pa] (3.10): ``1/E* = (1−ν1²)/E1 + (1−ν2²)/E2``."""
        inv = (1.0 - self.nu1**2) / self.e1_pa
        if math.isfinite(self.e2_pa):
            inv += (1.0 - self.nu2**2) / self.e2_pa
        return 1.0 / inv

    @property
    def hardness(self) -> float:
        """Hardness H [Pa]: the tabulated value or ``5.6 R_p`` (thesis 3.1.3)."""
        if self.hardness_pa is not None:
            return float(self.hardness_pa)
        return HARDNESS_FACTOR * self.yield_strength_pa

    def to_dict(self) -> dict[str, Any]:
        """Plain dictionary incl. the derived E* and H (``inf`` written as ``None``)."""
        d = asdict(self)
        if not math.isfinite(d["e2_pa"]):
            d["e2_pa"] = None
        d["e_star_pa"] = self.e_star_pa
        d["hardness_used_pa"] = self.hardness
        return d

    @classmethod
    def from_mapping(cls, data: dict[str, Any]) -> Material:
        """Build from a mapping with the field names (SI); ``e2_pa`` null/absent = rigid."""
        allowed = {
            "name", "e1_pa", "nu1", "e2_pa", "nu2", "yield_strength_pa",
            "shear_strength_pa", "hardness_pa", "description",
        }  # fmt: skip
        derived = {"e_star_pa", "hardness_used_pa"}
        unknown = set(data) - allowed - derived
        if unknown:
            raise MaterialError(f"unknown material field(s) {sorted(unknown)}; allowed: {sorted(allowed)}")
        kwargs = {k: v for k, v in data.items() if k in allowed}
        for key, value in kwargs.items():
            if key in ("name", "description"):
                if not isinstance(value, str):
                    raise MaterialError(f"material field {key} must be a string, got {value!r}")
            elif value is None and key in ("e2_pa", "hardness_pa"):
                continue  # rigid counter-body; hardness from the yield strength
            elif isinstance(value, bool) or not isinstance(value, int | float):
                raise MaterialError(f"material field {key} must be a number in SI units, got {value!r}")
        if kwargs.get("e2_pa") is None:
            kwargs["e2_pa"] = math.inf
        missing = {"name", "e1_pa", "nu1", "yield_strength_pa", "shear_strength_pa"} - set(kwargs)
        if missing:
            raise MaterialError(f"material is missing {sorted(missing)}")
        try:
            return cls(**kwargs)
        except TypeError as exc:
            raise MaterialError(f"invalid material: {exc}") from None


@dataclass(frozen=True)
class _Pairing:
    """What a library entry is made of and where its values come from (for the table)."""

    rough_body: str
    counter_body: str
    sources: str


_S235_RP = 235 * MEGAPASCAL
_AW6082_RP = 250 * MEGAPASCAL

MATERIALS: dict[str, Material] = {
    "brake-pad": Material(
        name="brake-pad",
        e1_pa=1.0 * GIGAPASCAL,
        nu1=0.3,
        e2_pa=math.inf,
        nu2=0.3,
        yield_strength_pa=305 * MEGAPASCAL,
        shear_strength_pa=35 * MEGAPASCAL,
        hardness_pa=1708 * MEGAPASCAL,
        description="worn brake pad on a rigid disc (thesis Tables 3.1/3.2): R_p of iron oxide, tau_max of graphite",
    ),
    "dc04": Material(
        name="dc04",
        e1_pa=210 * GIGAPASCAL,
        nu1=0.3,
        e2_pa=210 * GIGAPASCAL,
        nu2=0.3,
        yield_strength_pa=860 * MEGAPASCAL,
        shear_strength_pa=500 * MEGAPASCAL,
        hardness_pa=4850 * MEGAPASCAL,
        description="DC04 steel sheet on DC04 (thesis Tables 3.4/3.5, E* = 115 GPa; the thesis prints 1.15)",
    ),
    "pad-grey-iron": Material(
        name="pad-grey-iron",
        e1_pa=1.0 * GIGAPASCAL,
        nu1=0.3,
        e2_pa=110 * GIGAPASCAL,
        nu2=0.26,
        yield_strength_pa=305 * MEGAPASCAL,
        shear_strength_pa=35 * MEGAPASCAL,
        hardness_pa=1708 * MEGAPASCAL,
        description=(
            "organic brake pad (1, thesis Tables 3.1/3.2: E, nu, R_p of iron oxide, H, tau_max of graphite) "
            "on an elastic grey cast iron disc EN-GJL-250 (2, EN 1561: E 103-118 GPa -> 110 GPa, nu 0.26)"
        ),
    ),
    "steel-s235": Material(
        name="steel-s235",
        e1_pa=210 * GIGAPASCAL,
        nu1=0.3,
        e2_pa=210 * GIGAPASCAL,
        nu2=0.3,
        yield_strength_pa=_S235_RP,
        shear_strength_pa=_S235_RP / math.sqrt(3.0),
        hardness_pa=None,
        description=(
            "structural steel S235 (1) on S235 (2): E 210 GPa, nu 0.3 (EN 1993-1-1 3.2.6), "
            "R_p = R_eH 235 MPa (EN 10025-2, t <= 16 mm), H = 5.6 R_p, tau_max = R_p/sqrt(3) (von Mises)"
        ),
    ),
    "aluminium-steel": Material(
        name="aluminium-steel",
        e1_pa=70 * GIGAPASCAL,
        nu1=0.3,
        e2_pa=210 * GIGAPASCAL,
        nu2=0.3,
        yield_strength_pa=_AW6082_RP,
        shear_strength_pa=_AW6082_RP / math.sqrt(3.0),
        hardness_pa=None,
        description=(
            "aluminium EN AW-6082-T6 (1: E 70 GPa, nu 0.3, EN 1999-1-1 3.2.5; R_p0.2 250 MPa, extrusion "
            "t <= 5 mm, EN 1999-1-1 Table 3.2b) on steel S235 (2: EN 1993-1-1); H = 5.6 R_p, "
            "tau_max = R_p/sqrt(3) of the softer aluminium"
        ),
    ),
}

_PAIRINGS: dict[str, _Pairing] = {
    "brake-pad": _Pairing("worn brake pad (friction layer)", "rigid disc", "thesis Tables 3.1/3.2"),
    "dc04": _Pairing("DC04 steel sheet", "DC04 steel sheet", "thesis Tables 3.4/3.5 (E* misprint corrected)"),
    "pad-grey-iron": _Pairing(
        "organic brake pad (thesis values)", "grey cast iron disc EN-GJL-250",
        "thesis Tables 3.1/3.2 (pad); EN 1561 informative annex (disc E, nu)",
    ),
    "steel-s235": _Pairing("structural steel S235", "structural steel S235", "EN 1993-1-1 3.2.6; EN 10025-2"),
    "aluminium-steel": _Pairing(
        "aluminium EN AW-6082-T6", "structural steel S235", "EN 1999-1-1 3.2.5 and Table 3.2b; EN 1993-1-1 3.2.6",
    ),
}  # fmt: skip


def canonical_material_name(name: str) -> str:
    """``name`` in the library's spelling: lower case, blanks and ``_`` as ``-`` (``"Brake_Pad"`` → ``"brake-pad"``)."""
    return re.sub(r"[\s_\-]+", "-", name.strip().lower())


def material_names() -> list[str]:
    """Canonical names of the library's materials."""
    return sorted(MATERIALS)


def material_table() -> list[dict[str, Any]]:
    """One row per library material (for listing): name, bodies, E*, H, τ_max, sources, description."""
    rows = []
    for name in material_names():
        m, p = MATERIALS[name], _PAIRINGS[name]
        rows.append({
            "name": name, "rough_body": p.rough_body, "counter_body": p.counter_body,
            "e1_pa": m.e1_pa, "nu1": m.nu1, "e2_pa": None if math.isinf(m.e2_pa) else m.e2_pa, "nu2": m.nu2,
            "e_star_pa": m.e_star_pa, "yield_strength_pa": m.yield_strength_pa, "hardness_pa": m.hardness,
            "hardness_tabulated": m.hardness_pa is not None, "shear_strength_pa": m.shear_strength_pa,
            "sources": p.sources, "description": m.description,
        })  # fmt: skip
    return rows


def get_material(name: str) -> Material:
    """The library material ``name``; case, blanks, ``_`` and ``-`` do not matter (``"DC04"``)."""
    if not isinstance(name, str):
        raise MaterialError(f"a material name must be a string, got {name!r}")
    key = canonical_material_name(name)
    try:
        return MATERIALS[key]
    except KeyError:
        close = difflib.get_close_matches(key, material_names(), n=1)
        hint = f" (did you mean {close[0]!r}?)" if close else ""
        raise MaterialError(
            f"unknown material {name!r}{hint}; use one of {', '.join(material_names())} (case and '-'/'_' "
            "do not matter) or the path of a JSON file with the fields of stochfric.contact.Material in SI "
            'units (docs/surface_contact.md, "Materials")'
        ) from None


def load_material(spec: str | Path) -> Material:
    """A library name (:func:`get_material`), or the path of a JSON file holding
    :meth:`Material.from_mapping` fields; a library name wins over a file of that name."""
    text = str(spec)
    if canonical_material_name(text) in MATERIALS:
        return MATERIALS[canonical_material_name(text)]
    p = Path(text)
    if p.suffix.lower() == ".json" or p.is_file():
        try:
            data = json.loads(read_text_checked(p))
        except FileNotFoundError:
            raise MaterialError(f"material file {p} not found") from None
        except (OSError, ValueError) as exc:
            raise MaterialError(f"cannot read material file {p}: {exc}") from None
        if not isinstance(data, dict):
            raise MaterialError(f"material file {p} must hold a JSON object")
        try:
            return Material.from_mapping(data)
        except (MaterialError, ValueError) as exc:
            raise MaterialError(f"material file {p}: {exc}") from None
    return get_material(text)

"""Material pairings for the contact analysis (method §1 table, thesis Tables 3.1/3.2/3.4/3.5).

``E*`` from (3.10): ``1/E* = (1−ν1²)/E1 + (1−ν2²)/E2``, ``E2 = ∞`` for a rigid counter-body;
hardness ``H = 5.6 R_p`` (thesis 3.1.3) unless tabulated; ``τ_max`` the shear strength of
Bowden–Tabor (3.15/3.16).  The presets ``brake-pad`` and ``dc04`` (SI units) and the thesis's
misprint of E* for DC04 (method erratum 2) are tabulated in docs/surface_contact.md, "Materials".
"""

from __future__ import annotations

import json
import math
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from stochfric.errors import InputError
from stochfric.units import GIGAPASCAL, MEGAPASCAL

__all__ = [
    "HARDNESS_FACTOR",
    "MATERIALS",
    "Material",
    "MaterialError",
    "get_material",
    "load_material",
    "material_names",
]

#: H = 5.6 R_p (thesis 3.1.3).
HARDNESS_FACTOR = 5.6


class MaterialError(InputError):
    """A material parameter is invalid or a material name is unknown."""


@dataclass(frozen=True, kw_only=True)
class Material:
    """Elastic pairing of the rough body (1) and the counter-body (2); SI units.

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
        if not self.name:
            raise MaterialError("a material needs a name")
        for key in ("e1_pa", "yield_strength_pa", "shear_strength_pa"):
            v = float(getattr(self, key))
            if not (math.isfinite(v) and v > 0.0):
                raise MaterialError(f"{key} must be finite and > 0 Pa, got {v!r}")
        e2 = float(self.e2_pa)
        if math.isnan(e2) or e2 <= 0.0:
            raise MaterialError(f"e2_pa must be > 0 Pa (inf for a rigid body), got {e2!r}")
        for key in ("nu1", "nu2"):
            v = float(getattr(self, key))
            if not (-1.0 < v <= 0.5):
                raise MaterialError(f"{key} must lie in (-1, 0.5], got {v!r}")
        if self.hardness_pa is not None:
            h = float(self.hardness_pa)
            if not (math.isfinite(h) and h > 0.0):
                raise MaterialError(f"hardness_pa must be finite and > 0 Pa, got {h!r}")

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
}


def material_names() -> list[str]:
    """Names of the preset materials."""
    return sorted(MATERIALS)


def get_material(name: str) -> Material:
    """The preset ``name`` (``brake-pad``, ``dc04``)."""
    try:
        return MATERIALS[name]
    except KeyError:
        raise MaterialError(
            f"unknown material {name!r}; use one of {', '.join(material_names())} "
            "or a JSON file with the fields of stochfric.contact.Material"
        ) from None


def load_material(spec: str | Path) -> Material:
    """A preset name, or the path of a JSON file holding :meth:`Material.from_mapping` fields."""
    text = str(spec)
    if text in MATERIALS:
        return MATERIALS[text]
    p = Path(text)
    if p.suffix.lower() == ".json" or p.is_file():
        try:
            data = json.loads(p.read_text(encoding="utf-8"))
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

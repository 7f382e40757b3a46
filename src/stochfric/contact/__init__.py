"""Contact analysis of one surface (METHOD.md §2, thesis 3.1.3, 3.2.2, 3.3.2).

GW/Hertz sums with Bowden–Tabor friction (:mod:`.asperity`), materials (:mod:`.materials`),
closed-form references (:mod:`.reference`) and the elastic half-space boundary-element check
(:mod:`.halfspace`, needs the optional ContactMechanics).
"""

from __future__ import annotations

from stochfric.contact.asperity import (
    ContactError,
    ContactResult,
    asperity_contact,
    asperity_sums,
    default_approach_m,
    read_contact_result,
)
from stochfric.contact.halfspace import halfspace_available, halfspace_contact
from stochfric.contact.materials import (
    MATERIALS,
    Material,
    MaterialError,
    get_material,
    load_material,
    material_names,
)
from stochfric.contact.reference import gw_contact, gw_integral, gw_integral_closed, hertz_contact

__all__ = [
    "MATERIALS",
    "ContactError",
    "ContactResult",
    "Material",
    "MaterialError",
    "asperity_contact",
    "asperity_sums",
    "default_approach_m",
    "get_material",
    "gw_contact",
    "gw_integral",
    "gw_integral_closed",
    "halfspace_available",
    "halfspace_contact",
    "hertz_contact",
    "load_material",
    "material_names",
    "read_contact_result",
]

"""Contact analysis of one surface (method §2, thesis 3.1.3, 3.2.2, 3.3.2).

GW/Hertz sums with Bowden–Tabor friction (:mod:`.asperity`), materials (:mod:`.materials`),
closed-form references (:mod:`.reference`), the elastic half-space boundary-element check at
equal load (:mod:`.halfspace`, needs the optional ContactMechanics) and the validity checks of
a result (:mod:`.validity`).
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
from stochfric.contact.halfspace import (
    EqualLoadComparison,
    compare_equal_load,
    halfspace_available,
    halfspace_contact,
)
from stochfric.contact.materials import (
    MATERIALS,
    Material,
    MaterialError,
    get_material,
    load_material,
    material_names,
)
from stochfric.contact.reference import gw_contact, gw_integral, gw_integral_closed, hertz_contact
from stochfric.contact.validity import ValidityWarning, contact_validity, plasticity_validity, result_validity

__all__ = [
    "MATERIALS",
    "ContactError",
    "ContactResult",
    "EqualLoadComparison",
    "Material",
    "MaterialError",
    "ValidityWarning",
    "asperity_contact",
    "asperity_sums",
    "compare_equal_load",
    "contact_validity",
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
    "plasticity_validity",
    "read_contact_result",
    "result_validity",
]

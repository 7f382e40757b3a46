"""The contact models by name (method §2): one small strategy object per model, one registry.

A :class:`ContactModel` computes the contact of one prepared surface, a :class:`ContactProblem`
(the surface, its summits, the pairing, the approaches), and returns a
:class:`~stochfric.contact.asperity.ContactResult`; this is the operation of ``stochfric contact``.
Its ``control`` says how the model is driven:

* ``"approach"``: solved at the approaches u of the problem (GW/Hertz: ``gw``);
* ``"load"``: solved at the normal forces N that the GW model gives at those approaches, so that the
  two are compared at equal load (μ = A_c τ_max / N compares models only at the same N; the elastic
  half-space: ``bem``).

:data:`CONTACT_MODELS` maps each name to its model; the command line offers these names
(``--method``, :data:`ALIASES` the spellings it accepted before).  A new model is one subclass of
:class:`ContactModel` (its options are its dataclass fields, see :meth:`ContactModel.configured`) and
one :func:`register_contact_model` call.
"""

from __future__ import annotations

from abc import ABC, abstractmethod
from collections.abc import Mapping
from dataclasses import dataclass, field, fields, replace
from functools import cached_property
from typing import Any, Literal, Self, get_args

import numpy.typing as npt

from stochfric.contact.asperity import ContactError, ContactResult, asperity_contact
from stochfric.contact.halfspace import halfspace_contact
from stochfric.contact.materials import Material
from stochfric.errors import InputTypeError
from stochfric.surface.io import Surface
from stochfric.surface.summits import Summits

__all__ = [
    "ALIASES",
    "CONTACT_MODELS",
    "ContactModel",
    "ContactProblem",
    "Control",
    "ElasticHalfSpace",
    "GreenwoodWilliamson",
    "contact_model",
    "contact_model_names",
    "register_contact_model",
]

#: How a model is driven: at the given approaches, or at the GW normal forces of those approaches.
Control = Literal["approach", "load"]


@dataclass(frozen=True, kw_only=True, eq=False)
class ContactProblem:
    """One prepared surface as a contact model reads it.

    ``surface`` is the prepared (coarse) surface, ``summits`` its summits, ``material`` the pairing,
    ``approach_m`` the approaches u [m] (``None``: :func:`~stochfric.contact.asperity.default_approach_m`
    of the summits) and ``preparation`` the record stored with the result.
    """

    surface: Surface
    summits: Summits
    material: Material
    approach_m: npt.ArrayLike | None = None
    preparation: Mapping[str, Any] = field(default_factory=dict)

    @cached_property
    def asperity(self) -> ContactResult:
        """The GW/Hertz + Bowden–Tabor result over the approaches (computed once): the ``gw`` model's
        result, the normal forces of the ``"load"`` models, the validity checks of the command."""
        return asperity_contact(self.surface, self.summits, self.material, self.approach_m,
                                preparation=dict(self.preparation))


@dataclass(frozen=True, kw_only=True, eq=False)
class ContactModel(ABC):
    """A contact model: its ``name`` (the ``--method`` value), a one-line ``summary``, the literature
    ``reference`` and its ``control`` (:data:`Control`); :meth:`contact` computes it.

    Options of a model are further dataclass fields with defaults in its subclass.
    """

    name: str
    summary: str
    reference: str
    control: Control

    def __post_init__(self) -> None:
        if not self.name or self.name != self.name.strip().lower() or " " in self.name:
            raise ContactError(f"a contact model's name is one lower-case word, got {self.name!r}")
        if self.control not in get_args(Control):
            raise ContactError(f"control must be one of {', '.join(get_args(Control))}, got {self.control!r}")

    @abstractmethod
    def contact(self, problem: ContactProblem) -> ContactResult:
        """The contact of ``problem``'s surface: over its approaches (``control = "approach"``) or at the
        GW normal forces of its approaches (``control = "load"``, ``problem.asperity.normal_force_n``)."""

    def configured(self, **options: Any) -> Self:
        """This model with those of ``options`` that are its own option fields set; the others are
        ignored (the command line hands its model options to whichever model is chosen)."""
        own = {f.name for f in fields(self)} - {f.name for f in fields(ContactModel)}
        return replace(self, **{k: v for k, v in options.items() if k in own})


@dataclass(frozen=True, kw_only=True, eq=False)
class GreenwoodWilliamson(ContactModel):
    """GW/Hertz summits + Bowden–Tabor friction over the approach
    (:func:`~stochfric.contact.asperity.asperity_contact`; ``method = "asperity"`` in the result)."""

    def contact(self, problem: ContactProblem) -> ContactResult:
        return problem.asperity


@dataclass(frozen=True, kw_only=True, eq=False)
class ElasticHalfSpace(ContactModel):
    """The elastic half-space by boundary elements (:func:`~stochfric.contact.halfspace.halfspace_contact`,
    optional ContactMechanics) at the GW normal forces; ``method = "halfspace"`` in the result.

    ``frame_points``: border frame lowered out of reach (``None``: the summit rule's margin);
    ``refine``: solve on a ``refine``-times finer grid (cubic splines).
    """

    frame_points: int | None = None
    refine: int = 1

    def contact(self, problem: ContactProblem) -> ContactResult:
        gw = problem.asperity
        return halfspace_contact(
            problem.surface, problem.material, normal_force_n=gw.normal_force_n, summits=problem.summits,
            frame_points=self.frame_points, refine=self.refine, preparation=dict(gw.preparation),
        )  # fmt: skip


#: Every contact model by name, in the order they were registered.
CONTACT_MODELS: dict[str, ContactModel] = {}

#: Earlier names of the models (``stochfric contact --method asperity|halfspace``), still accepted.
ALIASES: dict[str, str] = {"asperity": "gw", "halfspace": "bem"}


def register_contact_model(model: ContactModel) -> ContactModel:
    """Add ``model`` to :data:`CONTACT_MODELS` under its name and return it; :class:`ContactError` for a
    name (or alias) already taken."""
    if not isinstance(model, ContactModel):
        raise InputTypeError(f"a contact model must be a ContactModel, got {type(model).__name__}")
    if model.name in CONTACT_MODELS or model.name in ALIASES:
        raise ContactError(f"a contact model named {model.name!r} is already registered")
    CONTACT_MODELS[model.name] = model
    return model


def contact_model_names() -> tuple[str, ...]:
    """The names of the registered models, in registration order."""
    return tuple(CONTACT_MODELS)


def contact_model(name: str) -> ContactModel:
    """The model registered as ``name`` (or under an alias of :data:`ALIASES`); :class:`ContactError`
    with the known names otherwise."""
    key = ALIASES.get(name, name)
    try:
        return CONTACT_MODELS[key]
    except KeyError:
        aliases = ", ".join(f"{old} = {new}" for old, new in ALIASES.items())
        raise ContactError(f"unknown contact model {name!r}; use one of {', '.join(CONTACT_MODELS)} "
                           f"(aliases: {aliases})") from None


register_contact_model(GreenwoodWilliamson(
    name="gw",
    summary="Greenwood-Williamson: Hertzian summits, Bowden-Tabor friction, over the approach",
    reference="Greenwood & Williamson, Proc. R. Soc. A 295 (1966) 300; Bowden & Tabor (1950); thesis 3.1.3",
    control="approach",
))
register_contact_model(ElasticHalfSpace(
    name="bem",
    summary="elastic half-space by boundary elements at the GW loads: the equal-load reference",
    reference="Polonsky & Keer, Wear 231 (1999) 206; Johnson, Contact Mechanics (1985); thesis Fig. 3.12-3.14",
    control="load",
))

"""The contact models by name (stochfric.contact.models): the registry, its look-up, and the command
line taking ``--method`` from it, a model registered after the import included."""

from __future__ import annotations

import json
from collections.abc import Iterator
from dataclasses import dataclass, replace

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli.application import app
from stochfric.contact.asperity import ContactError, ContactResult, asperity_contact
from stochfric.contact.materials import get_material
from stochfric.contact.models import (
    ALIASES,
    CONTACT_MODELS,
    ContactModel,
    ContactProblem,
    ElasticHalfSpace,
    GreenwoodWilliamson,
    contact_model,
    contact_model_names,
    register_contact_model,
)
from stochfric.surface.io import default_surface_path, read_surface
from stochfric.surface.preprocess import Preparation, prepare
from stochfric.surface.summits import summits_of

#: The dummy model's factor on the GW contact area (so μ = A_c τ_max / N scales by it too).
SCALE = 2.5


@dataclass(frozen=True, kw_only=True, eq=False)
class ScaledGW(ContactModel):
    """A test model: the GW result with its contact area scaled by ``scale``."""

    scale: float = SCALE

    def contact(self, problem: ContactProblem) -> ContactResult:
        gw = problem.asperity
        return replace(gw, method=self.name, contact_area_m2=self.scale * gw.contact_area_m2)


@pytest.fixture
def dummy() -> Iterator[ContactModel]:
    model = register_contact_model(ScaledGW(name="dummy", summary="GW with a scaled area (test)",
                                            reference="none", control="approach"))
    try:
        yield model
    finally:
        CONTACT_MODELS.pop("dummy", None)


@pytest.fixture(scope="module")
def problem() -> ContactProblem:
    _, coarse = prepare(read_surface(default_surface_path()), Preparation(step=4))
    return ContactProblem(surface=coarse, summits=summits_of(coarse), material=get_material("brake-pad"),
                          approach_m=np.array([0.2e-6, 0.4e-6, 0.6e-6]))


def test_the_registry_holds_gw_and_bem() -> None:
    assert contact_model_names()[:2] == ("gw", "bem")
    gw, bem = contact_model("gw"), contact_model("bem")
    assert isinstance(gw, GreenwoodWilliamson) and gw.control == "approach"
    assert isinstance(bem, ElasticHalfSpace) and bem.control == "load"
    for m in (gw, bem):
        assert m.summary and "\n" not in m.summary and m.reference
    assert ALIASES == {"asperity": "gw", "halfspace": "bem"}
    assert contact_model("asperity") is gw and contact_model("halfspace") is bem


def test_an_unknown_name_is_refused_with_the_names() -> None:
    with pytest.raises(ContactError, match=r"unknown contact model 'persson'; use one of gw, bem"):
        contact_model("persson")


def test_a_name_is_registered_once(dummy: ContactModel) -> None:
    with pytest.raises(ContactError, match="already registered"):
        register_contact_model(ScaledGW(name="dummy", summary="again", reference="none", control="approach"))
    with pytest.raises(ContactError, match="already registered"):  # an alias is taken too
        register_contact_model(ScaledGW(name="asperity", summary="x", reference="none", control="approach"))
    with pytest.raises(ContactError, match="control"):
        ScaledGW(name="other", summary="x", reference="none", control="force")  # type: ignore[arg-type]
    with pytest.raises(ContactError, match="lower-case word"):
        ScaledGW(name="Two Words", summary="x", reference="none", control="approach")


def test_gw_is_asperity_contact(problem: ContactProblem) -> None:
    res = contact_model("gw").contact(problem)
    ref = asperity_contact(problem.surface, problem.summits, problem.material, problem.approach_m)
    assert res is problem.asperity and res.method == "asperity"
    np.testing.assert_array_equal(res.mu, ref.mu)
    np.testing.assert_array_equal(res.contact_area_m2, ref.contact_area_m2)


def test_configured_sets_only_the_models_own_options() -> None:
    bem = contact_model("bem").configured(refine=2, frame_points=3, unknown=1)
    assert isinstance(bem, ElasticHalfSpace) and (bem.refine, bem.frame_points, bem.name) == (2, 3, "bem")
    assert contact_model("bem").refine == 1  # the registered model is unchanged
    assert isinstance(contact_model("gw").configured(refine=2), GreenwoodWilliamson)


def test_bem_solves_at_the_gw_loads(problem: ContactProblem) -> None:
    pytest.importorskip("ContactMechanics")
    res = contact_model("bem").contact(problem)
    assert res.method == "halfspace" and res.preparation["halfspace"]["control"] == "load"
    np.testing.assert_allclose(res.normal_force_n, problem.asperity.normal_force_n, rtol=1e-6)


def _contact(*args: str) -> tuple[int, str, str]:
    result = CliRunner().invoke(app, ["contact", "--material", "brake-pad", "--step", "4",
                                      "--approach-um", "0.2:0.6:3", *args])
    return result.exit_code, result.stdout, result.stderr


def test_the_command_runs_a_model_registered_after_the_import(dummy: ContactModel) -> None:
    code, out, err = _contact("--method", "gw", "--json")
    assert code == 0, err
    gw = json.loads(out)
    code, out, err = _contact("--method", "dummy", "--json")
    assert code == 0, err
    d = json.loads(out)
    assert d["method"] == "dummy" and "asperity" not in d  # approach-controlled: no equal-load record
    np.testing.assert_allclose(d["approach_m"], gw["approach_m"])
    np.testing.assert_allclose(d["contact_area_m2"], np.multiply(gw["contact_area_m2"], SCALE))
    np.testing.assert_allclose(d["mu"], np.multiply(gw["mu"], SCALE))
    code, out, _ = _contact("--method", "dummy")
    assert code == 0 and "method dummy" in out


@pytest.mark.parametrize(("new", "old"), [("gw", "asperity"), ("bem", "halfspace")])
def test_the_old_names_give_the_same_output(new: str, old: str) -> None:
    if new == "bem":
        pytest.importorskip("ContactMechanics")
    code, out, err = _contact("--method", new, "--json")
    assert code == 0, err
    assert out == _contact("--method", old, "--json")[1]
    assert json.loads(out)["method"] == old  # the JSON keeps the result's method
    if new == "gw":
        assert out == _contact("--json")[1]  # the default


def test_an_unknown_method_lists_the_models() -> None:
    code, _, err = _contact("--method", "persson")
    assert code == 2
    assert "'persson' is not one of gw, bem" in err and "halfspace = bem" in err
    help_text = " ".join(CliRunner().invoke(app, ["contact", "--help"]).stdout.replace("│", " ").split())
    assert "gw (" in help_text and "asperity (= gw)" in help_text and "halfspace (= bem)" in help_text

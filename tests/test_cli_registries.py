"""A new surrogate method is one class and one registry entry: the command line offers it and the
analysis runs it end to end (issue 28: one typed vocabulary per option)."""

from __future__ import annotations

import json
from collections.abc import Iterator

import numpy as np
import pytest
from typer.testing import CliRunner

from stochfric.cli import app
from stochfric.surface.surrogates import (
    SURROGATES,
    SurrogateMethod,
    SurrogateSettings,
    register_surrogate,
    surrogate_method,
    unregister_surrogate,
)
from stochfric.surface.synthesis import phase_longer_heights

SMALL = ["--realizations", "12", "--long-surfaces", "3", "--length-factor", "3", "--seed", "3"]


class _Mirrored(SurrogateMethod):
    """Random phases of the map mirrored in x: a dummy method that only this test knows."""

    name = "mirrored-phase"
    summary = "random phases of the mirrored map (test only)"
    calls = 0

    def heights(self, heights: np.ndarray, rng: np.random.Generator, *, factor: int,
                settings: SurrogateSettings) -> np.ndarray:
        type(self).calls += 1
        return phase_longer_heights(heights[::-1, :], factor, rng, amplitude=settings.amplitude)


@pytest.fixture
def mirrored() -> Iterator[str]:
    register_surrogate(_Mirrored())
    yield _Mirrored.name
    unregister_surrogate(_Mirrored.name)


def test_the_registry_holds_the_three_methods_in_order() -> None:
    assert tuple(SURROGATES)[:3] == ("phase", "iaaft", "quilt")
    assert surrogate_method("quilt").resamples and not surrogate_method("phase").resamples
    with pytest.raises(ValueError, match="new name"):
        register_surrogate(SURROGATES["phase"])
    with pytest.raises(ValueError, match="package's own"):
        unregister_surrogate("phase")


def test_a_registered_method_runs_through_the_command_line(mirrored: str) -> None:
    _Mirrored.calls = 0
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", *SMALL, "--surrogate", mirrored,
                                   "--accept-not-credible", "--json", "--workers", "1"])
    assert res.exit_code == 0, res.output
    data = json.loads(res.stdout)
    assert data["config"]["surrogate"] == mirrored and data["surrogate_check"]["surrogate"] == mirrored
    assert data["surrogate_choice"] == f"{mirrored} (chosen by the user)"
    # realisations, long surfaces and the copy check all came from the new method (one process: counted here)
    assert _Mirrored.calls >= 12 + 3
    assert data["copy_check"]["surrogates"] > 0


def test_an_unknown_method_is_refused_with_the_registered_names() -> None:
    res = CliRunner().invoke(app, ["friction-process", "--material", "brake-pad", "--surrogate", "gauss"])
    assert res.exit_code == 2
    assert "gauss" in res.output and "quilt" in res.output and "Traceback" not in res.output

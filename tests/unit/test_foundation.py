"""Unit tests of the foundation modules: random streams, unit conversions, validators, figures I/O."""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import pytest

from stochfric.io_utils import available_memory_bytes, format_bytes
from stochfric.plotting import new_figure, new_subplots, save_figure
from stochfric.random import (
    BOOTSTRAP_KEY,
    as_generator,
    as_seed_sequence,
    child_generator,
    child_seed,
    seed_entropy,
    spawn_generators,
    spawn_seed_sequences,
)
from stochfric.units import MEGAPASCAL, MICROMETRE, length_to_m, pressure_to_pa
from stochfric.validation import finite, non_negative, positive

# --- random ----------------------------------------------------------------------------------------


def test_child_seed_is_numpy_spawn_without_mutation() -> None:
    root = np.random.SeedSequence(2013)
    expected = np.random.SeedSequence(2013).spawn(3)[2]  # numpy's own spawn of child 2
    got = child_seed(root, 2)
    np.testing.assert_array_equal(got.generate_state(8), expected.generate_state(8))
    assert root.n_children_spawned == 0  # not mutated
    # nested keys: task k, then trajectory (i, r) of that task
    np.testing.assert_array_equal(
        child_seed(child_seed(7, 3), 1, 4).generate_state(4),
        np.random.SeedSequence(7, spawn_key=(3, 1, 4)).generate_state(4),
    )


def test_streams_are_reproducible_and_independent_of_how_many_are_drawn() -> None:
    a = [g.random(5) for g in spawn_generators(11, 3)]
    b = [g.random(5) for g in spawn_generators(11, 6)][:3]
    for x, y in zip(a, b, strict=True):
        np.testing.assert_array_equal(x, y)
    assert not np.allclose(a[0], a[1])
    assert [s.spawn_key for s in spawn_seed_sequences(11, 2)] == [(0,), (1,)]
    np.testing.assert_array_equal(child_generator(5, BOOTSTRAP_KEY).random(3),
                                  child_generator(5, BOOTSTRAP_KEY).random(3))


def test_seed_normalisation_and_errors() -> None:
    assert seed_entropy(42) == 42
    assert isinstance(as_seed_sequence(None), np.random.SeedSequence)
    g = np.random.default_rng(1)
    assert as_generator(g) is g
    with pytest.raises(ValueError, match="non-negative"):
        as_seed_sequence(-1)
    with pytest.raises(TypeError):
        as_seed_sequence(1.5)  # type: ignore[arg-type]
    with pytest.raises(TypeError):
        as_seed_sequence(True)


# --- units and validators ------------------------------------------------------------------------


def test_unit_conversions_at_the_edges() -> None:
    assert length_to_m(3.0, "µm") == pytest.approx(3.0 * MICROMETRE)
    assert length_to_m(3.0, "um") == length_to_m(3.0, "µm")
    assert pressure_to_pa(0.35, "MPa") == pytest.approx(0.35 * MEGAPASCAL)
    with pytest.raises(ValueError, match="unknown length unit 'inch'"):
        length_to_m(1.0, "inch")
    with pytest.raises(ValueError, match="unknown pressure unit"):
        pressure_to_pa(1.0, "bar")


class _MyError(ValueError):
    pass


def test_validators_say_what_is_wrong() -> None:
    assert positive("mass m", 2, "kg") == 2.0
    assert non_negative("D", 0.0) == 0.0
    with pytest.raises(_MyError, match=r"mass m must be > 0 kg, got -2"):
        positive("mass m", -2, "kg", error=_MyError)
    with pytest.raises(ValueError, match="must be finite"):
        finite("x", float("nan"))
    with pytest.raises(ValueError, match="must be a number"):
        finite("x", "abc")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match=">= 0"):
        non_negative("D", -0.1)


# --- memory and figures --------------------------------------------------------------------------


def test_memory_figures() -> None:
    avail = available_memory_bytes()
    assert avail is None or avail > 0
    assert format_bytes(1.94e12) == "1.94 TB"
    assert format_bytes(999) == "999 B"


def test_figures_are_written_atomically_with_the_umask(tmp_path: Path) -> None:
    fig = new_figure(3.0, 2.0)
    fig.add_subplot(1, 1, 1).plot([0, 1], [1, 0])
    old = os.umask(0o022)
    try:
        out = save_figure(fig, tmp_path / "sub" / "f.png")
        svg = save_figure(fig, tmp_path / "f.svg")
    finally:
        os.umask(old)
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert svg.read_text(encoding="utf-8").lstrip().startswith("<?xml")
    assert (out.stat().st_mode & 0o777) == 0o644
    assert not list(tmp_path.glob("**/.*.tmp"))  # no temporary file left behind
    fig2, axes = new_subplots(2, 3, figsize=(6.0, 4.0), squeeze=False, layout="constrained")
    assert axes.shape == (2, 3) and fig2.get_layout_engine() is not None

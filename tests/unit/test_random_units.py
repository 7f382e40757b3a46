"""stochfric.random and stochfric.units beyond tests/unit/test_foundation.py.

Random: the streams are numpy's own (``default_rng(seed)`` and ``SeedSequence.spawn``), so their
numbers are checked against numpy, not against the package; and the package's two ways of deriving a
trajectory's stream (``random.child_seed`` and ``oscillator.integrate.trajectory_seed``) must agree,
since results are documented as "trajectory (i, r) uses spawn key (i, r)".
Units: every conversion factor, and unit names that must not be confused (mPa is not MPa).
"""

from __future__ import annotations

import re

import numpy as np
import pytest

from stochfric.oscillator.integrate import trajectory_seed
from stochfric.random import (
    BOOTSTRAP_KEY,
    INTERVAL_KEY,
    as_generator,
    as_seed_sequence,
    child_generator,
    child_seed,
    seed_entropy,
    spawn_generators,
    spawn_seed_sequences,
)
from stochfric.units import length_to_m, pressure_to_pa


def test_an_int_seed_gives_numpys_default_generator_stream() -> None:
    np.testing.assert_array_equal(as_generator(5).random(4), np.random.default_rng(5).random(4))
    np.testing.assert_array_equal(as_generator(np.int64(5)).random(4), np.random.default_rng(5).random(4))
    ss = np.random.SeedSequence(9)
    assert as_seed_sequence(ss) is ss


def test_fresh_entropy_is_recorded_and_differs_between_calls() -> None:
    a, b = seed_entropy(None), seed_entropy(None)
    assert a != b and a > 2**64  # 128 bits of OS entropy: results must store it as text (see test_result)
    ss = np.random.SeedSequence(a)
    np.testing.assert_array_equal(as_generator(ss).random(2), as_generator(a).random(2))


def test_children_of_a_child_extend_its_spawn_key_like_numpy() -> None:
    parent = np.random.SeedSequence(1, spawn_key=(4,), pool_size=8)
    kids = spawn_seed_sequences(parent, 2)
    ref = np.random.SeedSequence(1, spawn_key=(4,), pool_size=8).spawn(2)
    assert [k.spawn_key for k in kids] == [(4, 0), (4, 1)]
    for k, r in zip(kids, ref, strict=True):
        assert k.pool_size == 8
        np.testing.assert_array_equal(k.generate_state(4), r.generate_state(4))
    assert spawn_seed_sequences(parent, 0) == [] and spawn_generators(3, 0) == []
    with pytest.raises(ValueError, match="non-negative, got -1"):
        spawn_seed_sequences(3, -1)


@pytest.mark.parametrize("root", [2013, np.random.SeedSequence(7, spawn_key=(3,))])
def test_the_oscillator_trajectory_stream_is_the_random_modules_child(root: object) -> None:
    ss = as_seed_sequence(root)  # type: ignore[arg-type]
    for i, r in ((0, 0), (2, 5), (11, 0)):
        np.testing.assert_array_equal(trajectory_seed(ss, (i,), r).generate_state(4),
                                      child_seed(ss, i, r).generate_state(4))
    np.testing.assert_array_equal(child_generator(ss, 2, 5).standard_normal(3),
                                  np.random.Generator(np.random.PCG64(trajectory_seed(ss, (2,), 5))).standard_normal(3))


def test_reserved_keys_cannot_collide_with_task_indices() -> None:
    assert BOOTSTRAP_KEY != INTERVAL_KEY and min(BOOTSTRAP_KEY, INTERVAL_KEY) > 10**9
    a = child_generator(1, BOOTSTRAP_KEY).random(2)
    b = child_generator(1, INTERVAL_KEY).random(2)
    c = child_generator(1, 0).random(2)
    assert not np.array_equal(a, b) and not np.array_equal(a, c)


@pytest.mark.parametrize(("value", "unit", "metres"), [
    (2.0, "m", 2.0), (2.0, "mm", 2e-3), (2.0, "um", 2e-6), (2.0, "µm", 2e-6), (2.0, "nm", 2e-9), (3, "mm", 3e-3),
])
def test_length_units(value: float, unit: str, metres: float) -> None:
    out = length_to_m(value, unit)
    assert type(out) is float and out == pytest.approx(metres, rel=1e-15)


@pytest.mark.parametrize(("value", "unit", "pascal"), [
    (0.35, "Pa", 0.35), (0.35, "kPa", 350.0), (0.35, "MPa", 350_000.0), (115, "GPa", 1.15e11),
])
def test_pressure_units(value: float, unit: str, pascal: float) -> None:
    assert pressure_to_pa(value, unit) == pytest.approx(pascal, rel=1e-15)


@pytest.mark.parametrize("unit", ["mPa", "mpa", "MPA", "bar", ""])
def test_pressure_unit_names_are_exact(unit: str) -> None:
    """A milli-pascal read as a mega-pascal would be off by 10⁹: only the listed spellings are accepted."""
    with pytest.raises(ValueError, match=re.escape("use one of ['GPa', 'MPa', 'Pa', 'kPa']")):
        pressure_to_pa(1.0, unit)


@pytest.mark.parametrize("unit", ["M", "MM", "micron", "inch"])
def test_length_unit_names_are_exact(unit: str) -> None:
    with pytest.raises(ValueError, match=re.escape("use one of ['m', 'mm', 'nm', 'um', 'µm']")):
        length_to_m(1.0, unit)

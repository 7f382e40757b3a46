"""Random-number handling: one normalisation point and per-trajectory child streams.

Every stochastic function of the package takes ``seed`` (an ``int``, a
:class:`numpy.random.SeedSequence` or ``None``) or an ``rng``
(:class:`numpy.random.Generator`).  Ensembles never share a stream between
realisations: :func:`spawn_generators` gives realisation *k* the *k*-th child of
the root :class:`~numpy.random.SeedSequence` (NumPy NEP 19, SciPy SPEC 7), so
the numbers of realisation *k* do not depend on how many workers ran, on the
chunking, or on the machine.

The compiled generators are submodules, imported only where used (they compile with numba):
:mod:`.philox` (the counter-based Philox4x32-10 stream, Box–Muller normals, and numpy's
SeedSequence and PCG64 in compiled code) and :mod:`.ziggurat` (the ziggurat normals of the
default white-noise stream, with its tables in ``stochfric/data``).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np

from stochfric.errors import InputError, InputTypeError

SeedLike = int | np.random.SeedSequence | None


def as_seed_sequence(seed: SeedLike) -> np.random.SeedSequence:
    """Normalise ``seed`` to a :class:`numpy.random.SeedSequence`.

    ``None`` draws fresh entropy (recorded in the result through
    :func:`seed_entropy`), an ``int`` must be non-negative.
    """
    if isinstance(seed, np.random.SeedSequence):
        return seed
    if seed is None:
        return np.random.SeedSequence()
    if isinstance(seed, bool) or not isinstance(seed, int | np.integer):
        raise InputTypeError(f"seed must be a non-negative int, a SeedSequence or None, got {seed!r}")
    if seed < 0:
        raise InputError(f"seed must be non-negative, got {seed}")
    return np.random.SeedSequence(int(seed))


def seed_entropy(seed: SeedLike) -> int:
    """The root entropy of ``seed`` as an int, for recording in results."""
    ss = as_seed_sequence(seed)
    ent = ss.entropy
    if isinstance(ent, Sequence):  # pragma: no cover - only for hand-made sequences
        return int(ent[0])
    return int(ent)  # type: ignore[arg-type]


def as_generator(rng: np.random.Generator | SeedLike) -> np.random.Generator:
    """Normalise ``rng``/``seed`` to a :class:`numpy.random.Generator` (PCG64)."""
    if isinstance(rng, np.random.Generator):
        return rng
    return np.random.Generator(np.random.PCG64(as_seed_sequence(rng)))


#: Reserved first spawn-key entries for streams that are not tasks or trajectories (their keys
#: start with small indices): the bootstrap of a study's statistics and its ratio intervals.
BOOTSTRAP_KEY = 2**31 - 1
INTERVAL_KEY = 2**31 - 2


def child_seed(seed: SeedLike, *key: int) -> np.random.SeedSequence:
    """The child of ``seed`` with spawn key ``(*seed.spawn_key, *key)``, derived without mutating ``seed``.

    The single place where the package derives streams: task k of a study is ``child_seed(seed, k)``,
    trajectory (i, r) of that task ``child_seed(task, i, r)``, realisation k of an ensemble
    ``child_seed(seed, k)``; the same key always gives the same numbers, whoever computes it.
    """
    root = as_seed_sequence(seed)
    return np.random.SeedSequence(
        entropy=root.entropy, spawn_key=(*root.spawn_key, *(int(k) for k in key)), pool_size=root.pool_size
    )


def child_generator(seed: SeedLike, *key: int) -> np.random.Generator:
    """A PCG64 generator on :func:`child_seed` ``(seed, *key)``."""
    return np.random.Generator(np.random.PCG64(child_seed(seed, *key)))


def spawn_seed_sequences(seed: SeedLike, n: int) -> list[np.random.SeedSequence]:
    """``n`` independent child seed sequences of ``seed`` (child *k* is fixed by ``seed`` and *k*).

    Unlike :meth:`numpy.random.SeedSequence.spawn`, this does not mutate ``seed``
    when a :class:`~numpy.random.SeedSequence` is passed: children are derived from
    ``(entropy, spawn_key + (k,))`` directly, so calling it twice gives the same children.
    """
    if n < 0:
        raise InputError(f"number of streams must be non-negative, got {n}")
    root = as_seed_sequence(seed)
    return [child_seed(root, k) for k in range(n)]


def spawn_generators(seed: SeedLike, n: int) -> list[np.random.Generator]:
    """``n`` independent PCG64 generators, child *k* of ``seed`` for stream *k*."""
    return [np.random.Generator(np.random.PCG64(s)) for s in spawn_seed_sequences(seed, n)]

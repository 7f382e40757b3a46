"""Realisations on several cores: the same numbers as serially, in the same order.

Every realisation (or long surface) of the statistical contact analysis is a pure function of its
index and its own child seed stream, so they can be computed in any order and on any number of
processes; :func:`map_indexed` returns them in index order.  Worker processes are forked (Linux),
so the large inputs (the measured maps) are inherited, not pickled per task; only the small
results travel back.  Without ``fork`` (or with one worker) the work runs serially.
"""

from __future__ import annotations

import multiprocessing
import os
import signal
from collections.abc import Callable
from concurrent.futures import ProcessPoolExecutor
from typing import Any, TypeVar

from stochfric.errors import InputError

__all__ = ["default_workers", "map_indexed"]

T = TypeVar("T")

#: The function of the running map, inherited by the forked workers.
_JOB: Callable[[int], Any] | None = None


def default_workers() -> int:
    """Cores this process may use (the affinity mask where the platform has one)."""
    try:
        return max(1, len(os.sched_getaffinity(0)))
    except AttributeError:  # pragma: no cover - not Linux
        return max(1, os.cpu_count() or 1)


def _quiet_worker() -> None:
    """Worker initializer: Ctrl-C goes to the whole process group, but only the parent answers it
    (it stops the workers); a worker printing its own KeyboardInterrupt traceback would only be noise."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _call(index: int) -> Any:
    assert _JOB is not None
    return index, _JOB(index)


def map_indexed(
    job: Callable[[int], T], count: int, *, workers: int | None = None, done: Callable[[int], None] | None = None,
) -> list[T]:
    """``[job(0), …, job(count − 1)]`` on ``workers`` processes (default: all cores).

    ``done(k)`` is called in the parent after each result with the number finished so far.
    """
    global _JOB
    n = default_workers() if workers is None else int(workers)
    if n < 1:
        raise InputError(f"workers must be >= 1, got {workers!r}")
    if n == 1 or count < 2 or "fork" not in multiprocessing.get_all_start_methods():
        out = []
        for k in range(count):
            out.append(job(k))
            if done is not None:
                done(k + 1)
        return out
    results: list[Any] = [None] * count
    _JOB = job
    pool = ProcessPoolExecutor(max_workers=min(n, count), mp_context=multiprocessing.get_context("fork"),
                               initializer=_quiet_worker)
    try:
        finished = 0
        for index, value in pool.map(_call, range(count)):
            results[index] = value
            finished += 1
            if done is not None:
                done(finished)
    except Exception:  # a failed job: drop the queued jobs, let the running ones finish, report the failure
        # (terminating workers here leaves the pool's manager thread setting results on cancelled futures,
        # which prints InvalidStateError tracebacks after the one-line error)
        pool.shutdown(wait=True, cancel_futures=True)
        raise
    except BaseException:  # Ctrl-C: stop the workers now, do not wait for their jobs
        for proc in list(getattr(pool, "_processes", {}).values()):
            proc.terminate()
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    finally:
        _JOB = None
    pool.shutdown(wait=True)
    return results

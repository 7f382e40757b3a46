"""Executors for study sweeps: serial, local processes, Dask (method §0 randomness rule).

A sweep is a list of independent :class:`~stochfric.studies.tasks.TaskSpec`; an executor
runs :func:`~stochfric.studies.tasks.execute_task` on each and yields ``(task, arrays)``
as tasks finish, in any order.  Every task draws its random numbers from the stream fixed
by the root seed and its cells' own parameter values (:func:`~stochfric.studies.tasks.cell_stream_key`), so the
same seed gives identical arrays on every executor and with any number of workers.

:func:`run_tasks` adds checkpointing (:class:`~stochfric.studies.store.CheckpointStore`):
finished tasks are saved as they arrive and skipped on a rerun; a Ctrl-C or a crash loses at
most the tasks that were running.  A Ctrl-C raises :class:`SweepInterrupted`, which says how
many tasks are saved.  Worker processes watch their parent and exit when it dies (even by
``kill -9``), so no orphaned workers keep memory or CPU.
"""

from __future__ import annotations

import contextlib
import os
import signal
import threading
import time
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from dataclasses import dataclass
from enum import StrEnum
from multiprocessing import get_context
from pathlib import Path
from typing import Any

import numpy.typing as npt

from ..interrupts import ctrl_c_latch
from .errors import StudyError
from .store import CheckpointStore
from .tasks import TaskSpec, execute_task

TaskResult = dict[str, npt.NDArray[Any]]
TaskFunction = Callable[[TaskSpec, int | None], TaskResult]


class ExecutorKind(StrEnum):
    """Where a study's tasks run (:func:`make_executor`): one after the other in this process, in local
    worker processes, or on a Dask cluster.  Never changes the numbers."""

    SERIAL = "serial"
    PROCESSES = "processes"
    DASK = "dask"


class Executor(ABC):
    """Runs tasks and yields ``(task, result)`` as they finish."""

    name: str = "executor"

    @abstractmethod
    def run(self, fn: TaskFunction, tasks: Sequence[TaskSpec]) -> Iterator[tuple[TaskSpec, TaskResult]]:
        """Yield ``(task, fn(task, threads))`` for every task, in completion order."""

    def describe(self) -> dict[str, Any]:
        """Record of the executor (not part of the config hash: it never changes the numbers)."""
        return {"executor": self.name}


class SerialExecutor(Executor):
    """One task after the other in this process; each task uses ``threads`` threads."""

    name = ExecutorKind.SERIAL

    def __init__(self, threads: int | None = None) -> None:
        self.threads = threads

    def run(self, fn: TaskFunction, tasks: Sequence[TaskSpec]) -> Iterator[tuple[TaskSpec, TaskResult]]:
        for t in tasks:
            yield t, fn(t, self.threads)

    def describe(self) -> dict[str, Any]:
        return {"executor": self.name, "threads": self.threads}


PARENT_POLL_S = 0.5
"""How often [s] a worker checks that its parent is still alive."""


def _exit_with_parent(parent_pid: int, poll_s: float = PARENT_POLL_S) -> None:
    """Worker initializer: a daemon thread ends this process as soon as ``parent_pid`` is gone.

    After ``kill -9`` of the parent the workers are re-parented (``os.getppid()`` changes); the
    thread then calls ``os._exit`` so that the worker, and with it the multiprocessing resource
    tracker whose pipe it holds, does not outlive the run.
    """

    def watch() -> None:
        while os.getppid() == parent_pid:
            time.sleep(poll_s)
        os._exit(1)

    threading.Thread(target=watch, name="stochfric-parent-watch", daemon=True).start()
    # Ctrl-C reaches the whole process group; the parent answers it (terminates the workers, says
    # how many tasks are saved), so a worker prints no traceback of its own
    signal.signal(signal.SIGINT, signal.SIG_IGN)


@contextlib.contextmanager
def _workers_ignore_ctrl_c() -> Iterator[None]:
    """Block SIGINT while worker processes are started, so that they start with it blocked (the signal mask
    is inherited across ``fork`` and ``exec``; the workers' initializer then ignores it): a Ctrl-C while a
    worker is still importing would otherwise print that worker's partial traceback.  In the parent a
    blocked SIGINT stays pending and is delivered when the mask is restored (or at once, where another
    thread of the process takes it: the mask is per thread), so a Ctrl-C during the start is answered, not
    lost (ignoring it here instead lost it: a study run under load then finished and
    exited 0).  Where the platform has no signal masks, SIGINT is ignored during the start as before."""
    if threading.current_thread() is not threading.main_thread():
        yield
        return
    if hasattr(signal, "pthread_sigmask"):
        old = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})
        try:
            yield
        finally:
            signal.pthread_sigmask(signal.SIG_SETMASK, old)
        return
    previous = signal.signal(signal.SIGINT, signal.SIG_IGN)  # pragma: no cover - no signal masks
    try:
        yield
    finally:
        signal.signal(signal.SIGINT, previous)


class ProcessExecutor(Executor):
    """Local worker processes (``concurrent.futures.ProcessPoolExecutor``, spawn start method).

    ``workers`` defaults to all cores; each task runs single-threaded in its worker.  Workers exit
    when this process dies (:func:`_exit_with_parent`); on Ctrl-C they are terminated at once.
    """

    name = ExecutorKind.PROCESSES

    def __init__(self, workers: int | None = None) -> None:
        n = workers if workers is not None else (os.cpu_count() or 1)
        if n < 1:
            raise StudyError(f"workers must be >= 1, got {workers}")
        self.workers = int(n)

    def run(self, fn: TaskFunction, tasks: Sequence[TaskSpec]) -> Iterator[tuple[TaskSpec, TaskResult]]:
        if not tasks:
            return
        pool = ProcessPoolExecutor(max_workers=min(self.workers, len(tasks)), mp_context=get_context("spawn"),
                                   initializer=_exit_with_parent, initargs=(os.getpid(),))
        futures: dict[Future[TaskResult], TaskSpec] = {}
        try:
            with _workers_ignore_ctrl_c():  # the workers start here and inherit the ignored SIGINT
                for t in tasks:
                    futures[pool.submit(fn, t, 1)] = t
            pending = set(futures)
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for f in done:
                    yield futures[f], f.result()
        except BaseException:  # Ctrl-C, a failed task, the consumer gone: do not wait for running tasks
            for proc in list(getattr(pool, "_processes", {}).values()):
                proc.terminate()
            pool.shutdown(wait=False, cancel_futures=True)
            raise
        pool.shutdown(wait=True)

    def describe(self) -> dict[str, Any]:
        return {"executor": self.name, "workers": self.workers}


class DaskExecutor(Executor):
    """Tasks on a Dask cluster: an existing scheduler ``address`` or a given ``client``.

    Needs ``dask[distributed]`` (``pip install 'stochfric[dask]'``).
    """

    name = ExecutorKind.DASK

    def __init__(self, address: str | None = None, client: Any = None) -> None:
        if address is None and client is None:
            raise StudyError("the Dask executor needs a scheduler address (--scheduler tcp://HOST:PORT)")
        self.address = address
        self._client = client

    def run(self, fn: TaskFunction, tasks: Sequence[TaskSpec]) -> Iterator[tuple[TaskSpec, TaskResult]]:
        try:
            from distributed import Client, as_completed
        except ImportError:  # pragma: no cover - depends on the environment
            raise StudyError(
                "the Dask executor needs dask.distributed: pip install 'dask[distributed]'"
            ) from None
        client = self._client
        own = client is None
        if own:
            # never the global default client: a failed or closed default client would capture every later dask
            # computation in this process (xarray's netCDF writer asks dask for its scheduler)
            try:
                client = Client(self.address, set_as_default=False)
            except (ValueError, OSError, TimeoutError) as exc:
                raise StudyError(f"cannot use the Dask scheduler {self.address!r} ({exc}): give the address of a "
                                 "running scheduler, --scheduler tcp://HOST:PORT") from None
        try:
            futs = {}
            for t in tasks:
                f = client.submit(fn, t, 1, pure=False)
                futs[f.key] = (f, t)
            ac = as_completed([f for f, _ in futs.values()])
            try:
                for f in ac:
                    yield futs[f.key][1], f.result()
            finally:
                for f, _ in futs.values():
                    if not f.done():
                        f.cancel()
        finally:
            if own:
                client.close()

    def describe(self) -> dict[str, Any]:
        return {"executor": self.name, "address": self.address}


def make_executor(kind: ExecutorKind | str = ExecutorKind.SERIAL, *, workers: int | None = None,
                  scheduler: str | None = None) -> Executor:
    """The executor of an :class:`ExecutorKind` (or its name; ``scheduler`` given implies ``dask``)."""
    if scheduler is not None:
        return DaskExecutor(address=scheduler)
    try:
        chosen = ExecutorKind(kind)
    except ValueError:
        *rest, last = ExecutorKind
        raise StudyError(f"unknown executor {kind!r}; choose {', '.join(rest)} or {last}") from None
    if chosen is ExecutorKind.SERIAL:
        return SerialExecutor(threads=workers)
    if chosen is ExecutorKind.PROCESSES:
        return ProcessExecutor(workers=workers)
    raise StudyError("the dask executor needs --scheduler ADDRESS")


@dataclass
class SweepStats:
    """What :func:`run_tasks` did: tasks computed now and tasks loaded from checkpoints."""

    computed: int = 0
    loaded: int = 0


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`run_tasks`: how far the sweep got and where its finished tasks are.

    ``saved`` counts the tasks on disk in ``checkpoint`` (``None``: no checkpoint, nothing kept).
    """

    def __init__(self, stats: SweepStats, total: int, checkpoint: Path | None) -> None:
        super().__init__(f"interrupted after {stats.loaded + stats.computed} of {total} tasks")
        self.stats = stats
        self.total = total
        self.checkpoint = checkpoint

    @property
    def saved(self) -> int:
        """Finished tasks that a rerun with the same checkpoint loads instead of recomputing."""
        return self.stats.loaded + self.stats.computed if self.checkpoint is not None else 0


def run_tasks(
    tasks: Sequence[TaskSpec],
    *,
    executor: Executor | None = None,
    store: CheckpointStore | None = None,
    progress: Callable[[int, int], None] | None = None,
    fn: TaskFunction = execute_task,
) -> tuple[dict[int, TaskResult], SweepStats]:
    """Run ``tasks`` (skipping those finished in ``store``), saving each as it finishes.

    Returns the results by task index and the counts.  ``progress(done, total)`` is called
    after every finished (or loaded) task.  A Ctrl-C raises :class:`SweepInterrupted`.
    """
    indices = [t.index for t in tasks]
    if len(set(indices)) != len(indices):
        raise StudyError("task indices must be unique")
    ex = executor if executor is not None else SerialExecutor()
    results: dict[int, TaskResult] = {}
    stats = SweepStats()
    todo: list[TaskSpec] = []
    for t in tasks:
        if store is not None and store.has(t.index):
            results[t.index] = store.load(t.index)
            stats.loaded += 1
        else:
            todo.append(t)
    total = len(tasks)
    if progress is not None:
        progress(len(results), total)
    try:
        with ctrl_c_latch() as interrupted:
            if interrupted.is_set():  # a Ctrl-C swallowed before the sweep (stochfric.interrupts)
                raise KeyboardInterrupt
            for t, arrays in ex.run(fn, todo):
                if store is not None:
                    store.save(t.index, arrays)
                results[t.index] = arrays
                stats.computed += 1
                if progress is not None:
                    progress(len(results), total)
                if interrupted.is_set():  # a Ctrl-C whose KeyboardInterrupt was swallowed (stochfric.interrupts)
                    raise KeyboardInterrupt
    except SweepInterrupted:
        raise
    except KeyboardInterrupt:
        raise SweepInterrupted(stats, total, store.directory if store is not None else None) from None
    return results, stats

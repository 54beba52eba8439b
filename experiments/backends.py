"""Where runs execute: in this process, in a local process pool, or on a Ray cluster.

Every backend maps a picklable function over independent tasks and yields the results as they
finish (in any order); the runner stores each one as it arrives. Results never depend on the
backend: each task carries its own seeds.
"""

from __future__ import annotations

import contextlib
import logging
import multiprocessing
import os
from collections.abc import Callable, Iterator, Sequence
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from typing import Any, Protocol, TypeVar

T = TypeVar("T")
R = TypeVar("R")

BACKENDS = ("process", "ray", "serial")
log = logging.getLogger(__name__)


class Backend(Protocol):
    """Runs ``fn`` over tasks and yields the results as they complete."""

    workers: int

    def map_unordered(self, fn: Callable[[T], R], tasks: Sequence[T]) -> Iterator[R]:
        """Yield ``fn(task)`` for every task, in completion order."""
        ...


def default_workers() -> int:
    """All the cores this process may use."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


class SerialBackend:
    """In this process, one task after the other (debugging, profiling)."""

    workers = 1

    def map_unordered(self, fn: Callable[[T], R], tasks: Sequence[T]) -> Iterator[R]:
        """Yield ``fn(task)`` in task order."""
        for task in tasks:
            yield fn(task)


ONE_THREAD = {
    name: "1"
    for name in (
        "OMP_NUM_THREADS",
        "OPENBLAS_NUM_THREADS",
        "MKL_NUM_THREADS",
        "NUMEXPR_NUM_THREADS",
    )
}
"""Each worker is one run on one core: no BLAS or OpenMP thread pools (as Ray's workers)."""


@contextlib.contextmanager
def _environment(values: dict[str, str]) -> Iterator[None]:
    """Set environment variables that are not set already (inherited by spawned workers)."""
    added = {k: v for k, v in values.items() if k not in os.environ}
    os.environ.update(added)
    try:
        yield
    finally:
        for key in added:
            os.environ.pop(key, None)


class ProcessBackend:
    """A local ``ProcessPoolExecutor``; one task per worker at a time.

    Workers are started with ``spawn`` so that none inherits a pybullet client, a thread or a
    lock from the parent; each imports what it needs once and runs many tasks. Each worker
    gets one BLAS/OpenMP thread (:data:`ONE_THREAD`, unless the caller set those variables):
    the parallelism is across runs, and idle thread pools would compete for the cores.
    """

    def __init__(self, workers: int | None = None, start_method: str = "spawn") -> None:
        self.workers = workers or default_workers()
        if self.workers < 1:
            raise ValueError(f"workers must be >= 1, got {self.workers}")
        self.start_method = start_method

    def map_unordered(self, fn: Callable[[T], R], tasks: Sequence[T]) -> Iterator[R]:
        """Yield results as workers finish; cancels what is pending if the consumer stops."""
        if not tasks:
            return
        context = multiprocessing.get_context(self.start_method)
        workers = min(self.workers, len(tasks))
        executor = ProcessPoolExecutor(max_workers=workers, mp_context=context)
        try:
            with _environment(ONE_THREAD):  # workers start on the first submits
                pending: set[Future[R]] = {executor.submit(fn, task) for task in tasks}
            while pending:
                done, pending = wait(pending, return_when=FIRST_COMPLETED)
                for future in done:
                    yield future.result()
        finally:
            executor.shutdown(wait=True, cancel_futures=True)


class RayBackend:
    """Ray tasks, one CPU each: a local Ray instance, or an existing cluster via ``address``.

    With ``address=None`` a local instance with ``workers`` CPUs is started (and stopped at the
    end); with an address (``"auto"``, ``"ray://host:10001"``) the experiment joins that cluster,
    whose workers must be able to import this project (``pip install -e .`` on each node, or a
    Ray runtime environment). Results come back to this process, which writes all the files.
    """

    def __init__(self, workers: int | None = None, address: str | None = None) -> None:
        try:
            import ray
        except ImportError as error:
            raise RuntimeError("the Ray backend needs ray: pip install -e '.[ray]'") from error
        self._ray = ray
        self.address = address
        self.workers = workers or default_workers()

    def _init(self) -> bool:
        """Connect or start Ray; returns whether this backend started it (and must stop it)."""
        ray = self._ray
        if ray.is_initialized():
            return False
        if self.address is None:
            # "local" starts a new instance even when a cluster started by `ray start` runs
            # here (a bare ray.init() would join it).
            ray.init(
                address="local",
                num_cpus=self.workers,
                include_dashboard=False,
                log_to_driver=False,
                configure_logging=False,
            )
        else:
            ray.init(address=self.address, log_to_driver=False, configure_logging=False)
        return True

    def map_unordered(self, fn: Callable[[T], R], tasks: Sequence[T]) -> Iterator[R]:
        """Submit every task and yield results as ``ray.wait`` reports them."""
        if not tasks:
            return
        ray = self._ray
        started = self._init()
        pending: list[Any] = []
        try:
            remote = ray.remote(num_cpus=1, max_retries=0)(_call)
            pending = [remote.remote(fn, task) for task in tasks]
            while pending:
                done, pending = ray.wait(pending, num_returns=1)
                for ref in done:
                    yield ray.get(ref)
        finally:
            for ref in pending:
                ray.cancel(ref, force=True)
            if started:
                ray.shutdown()


def _call(fn: Callable[[T], R], task: T) -> R:
    return fn(task)


def make_backend(name: str, workers: int | None = None, address: str | None = None) -> Backend:
    """The backend called ``name`` (``process``, ``ray`` or ``serial``)."""
    if name == "process":
        return ProcessBackend(workers)
    if name == "ray":
        return RayBackend(workers, address)
    if name == "serial":
        return SerialBackend()
    raise ValueError(f"backend: expected one of {', '.join(BACKENDS)}, got {name!r}")

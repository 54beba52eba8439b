"""Where runs execute: in this process, in a local process pool, or on a Ray cluster.

Every backend maps a picklable function over independent tasks and yields the results as they
finish (in any order); the runner stores each one as it arrives. Results never depend on the
backend: each task carries its own seeds.

Faults: a worker process that dies (a crash, the OOM killer, a kill) loses only the task it
was running, which is tried again on a fresh worker up to ``max_retries`` times; the other
tasks go on. A task that still fails is reported at the end by :class:`TasksLost`, after every
other result has been yielded. An exception raised *by* a task is not a fault of the worker:
it propagates at once. When the driver dies, its workers notice within half a second and exit
(no orphan keeps running or holds memory).
"""

from __future__ import annotations

import contextlib
import functools
import logging
import multiprocessing
import os
import signal
import threading
import time
import traceback
from collections import deque
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass
from multiprocessing.connection import Connection, wait
from typing import Any, Protocol, TypeVar

from experiments.env_modules import call_with_modules

T = TypeVar("T")
R = TypeVar("R")

BACKENDS = ("process", "ray", "serial")
DEFAULT_RETRIES = 2
"""Retries of a task whose worker died (so three attempts in all)."""
log = logging.getLogger(__name__)


def with_env_modules(fn: Callable[[T], R], env_modules: tuple[str, ...]) -> Callable[[T], R]:
    """``fn``, made to import ``env_modules`` first in the worker that runs it
    (:mod:`experiments.env_modules`); ``fn`` itself when there are none."""
    if not env_modules:
        return fn
    return functools.partial(call_with_modules, env_modules, fn)


@dataclass(frozen=True)
class LostTask:
    """A task given up after its workers died ``attempts`` times."""

    task: Any
    attempts: int
    reason: str


class TasksLost(RuntimeError):
    """Some tasks were given up (their workers kept dying); every other result was yielded."""

    def __init__(self, lost: Sequence[LostTask]) -> None:
        self.lost = tuple(lost)
        described = "; ".join(f"{_label(item.task)}: {item.reason}" for item in self.lost)
        super().__init__(
            f"{len(self.lost)} task(s) lost after their workers died repeatedly: {described}"
        )


class RunFailed(RuntimeError):
    """A task could not finish: its env or agent raised (a user's env that hands the agent a
    NaN, an env id a worker cannot make). The message names the run or cell and the cause;
    what finished before it is kept, and the same command resumes once the cause is fixed."""

    @classmethod
    def of(cls, what: str, error: Exception) -> RunFailed:
        """The failure of ``what`` ("run NAME", "cell NAME") by ``error``."""
        return cls(f"{what} failed: {type(error).__name__}: {error}")


def _label(task: Any) -> str:
    return str(getattr(task, "name", task))


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


WATCH_PERIOD_S = 0.5
"""How often a worker checks that the process that started it is still alive."""


def _watch_parent(parent: int) -> None:
    while True:
        time.sleep(WATCH_PERIOD_S)
        if os.getppid() != parent:  # the driver died: this process was re-parented
            os._exit(1)


def _worker_main(connection: Connection, parent: int) -> None:
    """A worker: run tasks received on ``connection`` until told to stop or the driver dies."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the driver's to handle
    threading.Thread(target=_watch_parent, args=(parent,), daemon=True).start()
    while True:
        try:
            message = connection.recv()
        except (EOFError, OSError):
            return
        if message is None:
            return
        index, fn, task = message
        reply: tuple[Any, ...]
        try:
            reply = ("ok", index, fn(task))
        except BaseException as error:  # report it; the driver decides
            reply = ("error", index, error, traceback.format_exc())
        try:
            connection.send(reply)
        except Exception as error:  # an unpicklable result or exception
            connection.send(("error", index, RuntimeError(repr(error)), traceback.format_exc()))


class _Worker:
    def __init__(self, context: Any) -> None:
        self.connection, child = context.Pipe()
        self.process = context.Process(target=_worker_main, args=(child, os.getpid()), daemon=True)
        self.process.start()
        child.close()
        self.task: int | None = None

    def stop(self, timeout: float = 5.0) -> None:
        with contextlib.suppress(OSError, ValueError):
            self.connection.send(None)
        self.process.join(timeout)
        if self.process.is_alive():
            self.process.kill()
            self.process.join()
        self.connection.close()


class ProcessBackend:
    """A pool of local worker processes; one task per worker at a time.

    Workers are started with ``spawn`` so that none inherits a pybullet client, a thread or a
    lock from the parent; each imports what it needs once and runs many tasks. Each worker
    gets one BLAS/OpenMP thread (:data:`ONE_THREAD`, unless the caller set those variables):
    the parallelism is across runs, and idle thread pools would compete for the cores.
    A worker that dies costs only its task, retried up to ``max_retries`` times on a new worker.
    """

    def __init__(
        self,
        workers: int | None = None,
        start_method: str = "spawn",
        max_retries: int = DEFAULT_RETRIES,
        env_modules: tuple[str, ...] = (),
    ) -> None:
        self.env_modules = env_modules
        """Modules each worker imports before a task (``run.py --env-module``)."""
        self.workers = workers or default_workers()
        if self.workers < 1:
            raise ValueError(f"workers must be >= 1, got {self.workers}")
        if max_retries < 0:
            raise ValueError(f"max_retries must be >= 0, got {max_retries}")
        self.start_method = start_method
        self.max_retries = max_retries

    def map_unordered(self, fn: Callable[[T], R], tasks: Sequence[T]) -> Iterator[R]:
        """Yield results as workers finish; stops every worker if the consumer stops."""
        if not tasks:
            return
        fn = with_env_modules(fn, self.env_modules)
        context = multiprocessing.get_context(self.start_method)
        queue = deque(range(len(tasks)))
        deaths = [0] * len(tasks)
        lost: list[LostTask] = []
        pool: list[_Worker] = []
        try:
            with _environment(ONE_THREAD):
                pool = [_Worker(context) for _ in range(min(self.workers, len(tasks)))]
            while queue or any(w.task is not None for w in pool):
                for slot, worker in enumerate(pool):
                    if worker.task is not None or not queue:
                        continue
                    if not worker.process.is_alive():  # died idle, or after its last reply
                        worker.stop(timeout=0.0)
                        with _environment(ONE_THREAD):
                            worker = pool[slot] = _Worker(context)
                    worker.task = queue.popleft()
                    try:
                        worker.connection.send((worker.task, fn, tasks[worker.task]))
                    except OSError:  # it died before taking the task: a death like any other
                        self._bury(worker, tasks, deaths, queue, lost)
                busy = [w for w in pool if w.task is not None]
                if not busy:
                    continue
                ready = set(wait([w.connection for w in busy] + [w.process.sentinel for w in busy]))
                for worker in busy:
                    died = worker.process.sentinel in ready
                    if worker.connection in ready:
                        try:
                            reply = worker.connection.recv()
                        except (EOFError, OSError):
                            died = True
                        else:
                            worker.task = None
                            if reply[0] != "ok":  # the driver shows the error it raises
                                log.debug(
                                    "task %s failed in a worker:\n%s",
                                    _label(tasks[reply[1]]),
                                    reply[3],
                                )
                                raise reply[2]
                            yield reply[2]
                            continue
                    if died:
                        self._bury(worker, tasks, deaths, queue, lost)
            if lost:
                raise TasksLost(lost)
        finally:
            for worker in pool:
                worker.stop(timeout=0.0 if worker.task is not None else 5.0)

    def _bury(
        self,
        worker: _Worker,
        tasks: Sequence[Any],
        deaths: list[int],
        queue: deque[int],
        lost: list[LostTask],
    ) -> None:
        """A worker died: retry its task if it may be, else give it up."""
        worker.process.join(5.0)
        if worker.process.is_alive():  # its pipe broke but it lingers: end it
            worker.process.kill()
            worker.process.join()
        code = worker.process.exitcode
        reason = f"killed by signal {-code}" if code is not None and code < 0 else f"exit {code}"
        index, worker.task = worker.task, None
        if index is None:
            return
        deaths[index] += 1
        log.warning("worker running %s died (%s)", _label(tasks[index]), reason)
        if deaths[index] <= self.max_retries:
            queue.appendleft(index)
        else:
            lost.append(LostTask(tasks[index], deaths[index], f"worker {reason}"))


class RayBackend:
    """Ray tasks, one CPU each: a local Ray instance, or an existing cluster via ``address``.

    With ``address=None`` a local instance with ``workers`` CPUs is started (and stopped at the
    end); with an address (``"auto"``, ``"ray://host:10001"``) the experiment joins that cluster,
    whose workers must be able to import this project (``pip install -e .`` on each node, or a
    Ray runtime environment). Results come back to this process, which writes all the files.
    """

    def __init__(
        self,
        workers: int | None = None,
        address: str | None = None,
        max_retries: int = DEFAULT_RETRIES,
        env_modules: tuple[str, ...] = (),
    ) -> None:
        self.env_modules = env_modules
        """Modules each worker imports before a task (``run.py --env-module``)."""
        try:
            import ray
        except ImportError as error:
            raise RuntimeError("the Ray backend needs ray: pip install -e '.[ray]'") from error
        self._ray = ray
        self.address = address
        self.workers = workers or default_workers()
        self.max_retries = max_retries

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
        """Submit every task and yield results as ``ray.wait`` reports them. Ray retries a task
        whose worker died ``max_retries`` times (exceptions raised by the task are not
        retried); a task lost after that is reported by :class:`TasksLost` at the end."""
        if not tasks:
            return
        ray = self._ray
        started = self._init()
        pending: list[Any] = []
        lost: list[LostTask] = []
        try:
            remote = ray.remote(num_cpus=1, max_retries=self.max_retries)(_call)
            fn = with_env_modules(fn, self.env_modules)
            refs = [remote.remote(fn, task) for task in tasks]
            task_of = {ref: task for ref, task in zip(refs, tasks, strict=True)}
            pending = list(refs)
            while pending:
                done, pending = ray.wait(pending, num_returns=1)
                for ref in done:
                    try:
                        result = ray.get(ref)
                    except ray.exceptions.RayTaskError as error:
                        raise error.as_instanceof_cause() from None
                    except ray.exceptions.RayError as error:  # the worker or its node died
                        lost.append(LostTask(task_of[ref], self.max_retries + 1, str(error)))
                        continue
                    yield result
            if lost:
                raise TasksLost(lost)
        finally:
            for ref in pending:
                ray.cancel(ref, force=True)
            if started:
                ray.shutdown()


def _call(fn: Callable[[T], R], task: T) -> R:
    return fn(task)


def make_backend(
    name: str,
    workers: int | None = None,
    address: str | None = None,
    max_retries: int = DEFAULT_RETRIES,
    env_modules: tuple[str, ...] = (),
) -> Backend:
    """The backend called ``name`` (``process``, ``ray`` or ``serial``); its workers import
    ``env_modules`` before each task (``serial`` runs in this process, which imported them)."""
    if name == "process":
        return ProcessBackend(workers, max_retries=max_retries, env_modules=env_modules)
    if name == "ray":
        return RayBackend(workers, address, max_retries=max_retries, env_modules=env_modules)
    if name == "serial":
        return SerialBackend()
    raise ValueError(f"backend: expected one of {', '.join(BACKENDS)}, got {name!r}")

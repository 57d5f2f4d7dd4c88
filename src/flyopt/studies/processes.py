"""Running a sweep's chunks in worker processes on this machine.

Worker processes ignore Ctrl-C (the parent stops them) and, on Linux, die
with their parent even when it is killed.
"""

from __future__ import annotations

import contextlib
import os
import signal
import sys
import threading
from collections.abc import Callable, Sequence
from typing import TYPE_CHECKING

import pandas as pd

from flyopt.studies.chunks import IN_FLIGHT_PER_WORKER
from flyopt.studies.interrupt import POLL_SECONDS

if TYPE_CHECKING:
    from concurrent.futures import Future, ProcessPoolExecutor
    from multiprocessing.context import BaseContext

    from flyopt.studies.interrupt import Stop

__all__ = ["cpu_count", "run_processes"]


def cpu_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


#: The task of this worker process, set by the pool's initializer.
_TASK: Callable[[pd.DataFrame], pd.DataFrame] | None = None


#: The signals a worker is forked with held (:func:`_held`) until its initializer has its own handlers for them.
HELD = frozenset({signal.SIGINT, signal.SIGTERM})


def _init_worker(task: Callable[[pd.DataFrame], pd.DataFrame]) -> None:
    global _TASK
    _TASK = task
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    signal.signal(signal.SIGTERM, signal.SIG_DFL)  # the parent ends a worker so (a fork inherits its handler)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, HELD)  # held since the fork (:func:`_held`): a pending one acts now
    _die_with_parent()


class _held:
    """Hold SIGINT and SIGTERM in this thread while workers are forked (a pool forks them in its first
    ``submit``): a fork inherits the parent's handlers, which take both for a Ctrl-C, so a ``kill`` in the moments
    before a worker's initializer ran was noted by the worker and forgotten (it went on with its chunk until the
    command killed it 5 s later). Held, they wait in the worker for its own handlers (:func:`_init_worker`), and
    in this process for the end of the block."""

    def __enter__(self) -> None:
        self.before = signal.pthread_sigmask(signal.SIG_BLOCK, HELD)

    def __exit__(self, *exc: object) -> None:
        signal.pthread_sigmask(signal.SIG_SETMASK, self.before)


def _die_with_parent() -> None:
    """Ask Linux to kill this process when its parent dies (``prctl(PR_SET_PDEATHSIG)``)."""
    if not sys.platform.startswith("linux"):  # pragma: no cover - elsewhere, at the parent's exit
        return
    import ctypes

    parent = os.getppid()
    pr_set_pdeathsig = 1
    ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGKILL, 0, 0, 0)
    if parent == 1 or os.getppid() != parent:  # the parent died before the request
        os._exit(1)


def _run_in_worker(index: int, points: pd.DataFrame) -> tuple[int, pd.DataFrame]:
    if _TASK is None:  # set by the pool's initializer before any chunk arrives
        raise RuntimeError("a sweep worker got a chunk before its task")
    return index, _TASK(points)


def _mp_context(preload: str) -> BaseContext:
    import multiprocessing as mp

    methods = mp.get_all_start_methods()
    # fork is fast and safe while this process runs a single thread; otherwise
    # (e.g. a Dask client's threads) a fresh forkserver
    if "fork" in methods and threading.active_count() == 1:
        return mp.get_context("fork")
    if "forkserver" in methods:
        context = mp.get_context("forkserver")
        # the server imports the task's module (numpy, pandas, CasADi) once; workers fork from it
        context.set_forkserver_preload([preload])
        return context
    return mp.get_context("spawn")  # pragma: no cover - Windows


def run_processes(
    task: Callable[[pd.DataFrame], pd.DataFrame],
    pending: Sequence[tuple[int, pd.DataFrame]],
    n_workers: int,
    finished: Callable[[int, pd.DataFrame], None],
    stop: Stop,
) -> None:
    """Run ``task`` on the ``pending`` chunks in ``n_workers`` processes, calling ``finished(index, frame)``
    for each as it finishes; Ctrl-C (``stop``) or an error ends the workers at once."""
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    module = getattr(task, "func", task).__module__
    context = _mp_context(module)
    # only a fork inherits this process's handlers; a forkserver started in a held block would hold them for good
    hold = _held if context.get_start_method() == "fork" else contextlib.nullcontext
    pool = ProcessPoolExecutor(max_workers=n_workers, mp_context=context, initializer=_init_worker, initargs=(task,))
    try:
        # a few chunks in flight per worker, not all: the results of chunks that finish
        # while this process saves others wait in memory, and a 10^6-point sweep's would pile up
        queue = iter(pending)
        running: set[Future[tuple[int, pd.DataFrame]]] = set()
        while True:
            for i, chunk in queue:
                with hold():
                    running.add(pool.submit(_run_in_worker, i, chunk))
                if len(running) >= IN_FLIGHT_PER_WORKER * n_workers:
                    break
            if not running:
                break
            stop.check()
            done, running = wait(running, timeout=POLL_SECONDS, return_when=FIRST_COMPLETED)
            for future in done:
                finished(*future.result())
        stop.check()
    except BaseException:
        _terminate(pool)
        raise
    pool.shutdown()


def _terminate(pool: ProcessPoolExecutor) -> None:
    """Stop a process pool now: pending chunks cancelled, running workers ended."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        process.terminate()
    for process in processes:
        process.join(timeout=5.0)
        if process.is_alive():  # pragma: no cover - SIGTERM is not ignored by the workers
            process.kill()
            process.join(timeout=5.0)

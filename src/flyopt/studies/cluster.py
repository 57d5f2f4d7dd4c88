"""Running a sweep's chunks on a Dask cluster.

A Dask scheduler (``tcp://host:8786``, a ``Client`` or a cluster) runs the
chunks on a cluster; it is connected to (:func:`connect`) before anything
is written, so a wrong address leaves nothing behind.
"""

from __future__ import annotations

import re
import time
from collections.abc import Callable, Iterator, Sequence
from contextlib import contextmanager
from typing import TYPE_CHECKING, Any

import pandas as pd

from flyopt.errors import SceneError, shorten
from flyopt.studies.chunks import IN_FLIGHT_PER_WORKER
from flyopt.studies.interrupt import POLL_SECONDS

if TYPE_CHECKING:
    from flyopt.studies.interrupt import Stop

__all__ = [
    "CONNECT_SECONDS",
    "NO_WORKERS_SECONDS",
    "WorkersLost",
    "connect",
    "run_dask",
    "scheduler_address",
    "threads",
]

#: Longest wait for a Dask scheduler to answer [s].
CONNECT_SECONDS = 5.0
#: A Dask cluster without a single worker for this long has lost them [s].
NO_WORKERS_SECONDS = 10.0


#: The address of a Dask scheduler: an optional protocol, a host name, IPv4 or [IPv6] address, a port.
_ADDRESS = re.compile(
    r"(?:(?P<protocol>tcp|tls|ws|wss|ucx)://)?(?P<host>[A-Za-z0-9](?:[A-Za-z0-9.-]{0,252})|\[[0-9A-Fa-f:.]{2,45}\]):(?P<port>[0-9]{1,5})"
)


def scheduler_address(text: str) -> str:
    """``text`` when it is the address of a Dask scheduler, ``[protocol://]host:port``; else a SceneError.

    Checked before anything connects: Dask would otherwise wait for its
    timeout on a malformed address and leave a traceback from its client's
    clean-up. The scheduler must be one you trust: Dask sends it and its
    workers pickles, which can run code.
    """
    found = _ADDRESS.fullmatch(text) if isinstance(text, str) else None
    if found is None or not 0 < int(found["port"]) < 65536:
        raise SceneError(
            "--scheduler",
            f"{shorten(text)} is not a scheduler address: give [tcp|tls|ws|wss|ucx://]host:port, "
            "e.g. tcp://10.0.0.5:8786, with a port from 1 to 65535",
        )
    return text


@contextmanager
def connect(scheduler: Any) -> Iterator[Any]:
    """A Dask client for ``scheduler`` (None: no client), closed at the end if opened here.

    Connects (within :data:`CONNECT_SECONDS`) before the sweep writes
    anything, so a wrong address leaves no parts folder behind.

    Raises
    ------
    SceneError
        ``--scheduler``: dask.distributed is missing, or the scheduler does
        not answer.
    """
    if scheduler is None:
        yield None
        return
    try:
        from dask.distributed import Client
    except ImportError as err:  # pragma: no cover - dask is in the test extras
        raise SceneError(
            "--scheduler", "running on a Dask cluster needs dask[distributed] (pip install 'flyopt[cluster]')"
        ) from err
    if isinstance(scheduler, Client):
        yield scheduler
        return
    from distributed.deploy import Cluster

    if not isinstance(scheduler, Cluster):  # a cluster object knows its own address
        scheduler_address(scheduler)
    try:
        client = Client(scheduler, timeout=CONNECT_SECONDS, set_as_default=False)
    except (OSError, TimeoutError, ValueError, TypeError) as err:
        reason = (str(err).strip().splitlines() or [type(err).__name__])[0]
        raise SceneError(
            "--scheduler", f"cannot connect to the Dask scheduler {scheduler!r} within {CONNECT_SECONDS:g} s: {reason}"
        ) from None
    try:
        yield client
    finally:
        client.close()


class WorkersLost(Exception):
    """A Dask cluster has no worker left to run the chunks."""


def _run_task(
    task: Callable[[pd.DataFrame], pd.DataFrame], index: int, points: pd.DataFrame
) -> tuple[int, pd.DataFrame]:
    return index, task(points)


def run_dask(
    client: Any,
    task: Callable[[pd.DataFrame], pd.DataFrame],
    pending: Sequence[tuple[int, pd.DataFrame]],
    finished: Callable[[int, pd.DataFrame], None],
    stop: Stop,
) -> None:
    """Run ``task`` on the ``pending`` chunks on the Dask cluster of ``client``, calling
    ``finished(index, frame)`` for each as it arrives.

    Raises
    ------
    WorkersLost
        A chunk killed every worker that ran it, the scheduler is gone, or the
        cluster has had no worker for :data:`NO_WORKERS_SECONDS`.
    """
    from dask.distributed import KilledWorker, as_completed

    # results are fetched as they come: a result asked for later may have been lost
    # with its worker, and waiting for it would wait for a worker that may never come.
    # A few chunks per worker thread are in flight, not all: results that arrive while
    # this process saves others wait in its memory.
    queue = as_completed(loop=client.loop, with_results=True)
    futures, waiting = [], iter(pending)
    flight = {"chunks": 0, "threads": threads(client)}

    def top_up() -> None:
        room = IN_FLIGHT_PER_WORKER * max(flight["threads"], 1) - flight["chunks"]
        for _, (i, chunk) in zip(range(max(room, 0)), waiting):
            future = client.submit(_run_task, task, i, chunk, pure=False)
            futures.append(future)
            queue.add(future)
            flight["chunks"] += 1

    alone_since = None
    try:
        top_up()
        while not queue.is_empty():
            stop.check()
            try:
                batch = queue.next_batch(block=False)
            except KilledWorker as err:
                raise WorkersLost(f"a chunk killed every Dask worker that ran it ({type(err).__name__})") from None
            for _, result in batch:
                finished(*result)
            flight["chunks"] -= len(batch)
            top_up()
            if batch:
                alone_since = None
                continue
            try:
                workers = client.scheduler_info()["workers"]
            except (OSError, TimeoutError) as err:
                raise WorkersLost(f"the connection to the Dask scheduler was lost ({type(err).__name__})") from None
            flight["threads"] = sum(int(w.get("nthreads", 1)) for w in workers.values())
            top_up()
            if workers:
                alone_since = None
            elif alone_since is None:
                alone_since = time.monotonic()
            elif time.monotonic() - alone_since > NO_WORKERS_SECONDS:
                raise WorkersLost(f"all Dask workers were lost (none for {NO_WORKERS_SECONDS:g} s)")
            time.sleep(POLL_SECONDS)
    except BaseException:
        try:
            client.cancel(futures)
        except (OSError, TimeoutError):  # the scheduler is gone: nothing left to cancel
            pass
        raise


def threads(client: Any) -> int:
    """Worker threads of a Dask cluster now (0 when it cannot say)."""
    try:
        workers = client.scheduler_info()["workers"]
    except (OSError, TimeoutError, KeyError):
        return 0
    return sum(int(w.get("nthreads", 1)) for w in workers.values())

"""Running a sweep's chunks: serially, in worker processes or on a Dask cluster, with resume.

The runner knows nothing of flywheels: it runs a *task* (a picklable callable
taking a table of points and returning a table of results, one row per
point) over chunks of points, and hands each finished chunk on.

Chunks are sized by what they cost (:func:`chunk_bounds`): each takes at
most :data:`CHUNK_SECONDS` by the sweep's estimate and at most
1/(:data:`GUIDED` × workers) of what is left, down to
:data:`MIN_CHUNK_SECONDS`, so a 60-point sweep of a scene whose every point
needs a periodic solution is spread over the workers, the last chunks are
small enough that the workers finish together (also when the points near
the end cost more than the estimate says), and a 10⁶-point closed-form sweep
is not cut into a million pieces. Points that share a physics stay in one
chunk where they can (their analysis is then made once).

By default chunks run in parallel in worker processes on this machine, one
per CPU (serially when the sweep is estimated to take under
:data:`SERIAL_SECONDS` in one process, so that starting processes would cost
more than it saves), with a progress line and an ETA on stderr. A Dask
scheduler (``tcp://host:8786``, a ``Client`` or a cluster) runs them on a
cluster instead; it is connected to before anything is written, so a wrong
address leaves nothing behind.

With an output file every finished chunk is written to
``OUTPUT.parts/chunk-NNNNN.parquet`` at once, so a crash loses at most the
chunks in flight; ``resume`` reuses the chunks on disk after checking that
each is the chunk it claims to be (a damaged one is computed again). Every
temporary file lives in ``OUTPUT.parts/`` too, so nothing is left that a
rerun does not see. Worker processes ignore Ctrl-C (the parent stops them)
and, on Linux, die with their parent even when it is killed. The parent
notes Ctrl-C and acts on it where that is safe (between saves, while it
waits for workers; a chunk it computes itself at once), never half-way
through saving a chunk or inside the process pool's bookkeeping.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import re
import shutil
import signal
import sys
import threading
import time
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from flyopt.errors import Interrupted, SceneError, shorten
from flyopt.outputs.files import check_folder
from flyopt.outputs.results import read_results, write_results

__all__ = [
    "CHUNK_SECONDS",
    "GUIDED",
    "MAX_CHUNK_POINTS",
    "MIN_CHUNK_SECONDS",
    "SERIAL_SECONDS",
    "Parts",
    "chunk_bounds",
    "connect",
    "fingerprint",
    "run_chunks",
]

#: Longest estimated time of one chunk [s] in one process: long enough that the cost of a
#: chunk (sending it, saving its part, ~5-10 ms) is small, short enough that a crash or
#: Ctrl-C loses little.
CHUNK_SECONDS = 1.0
#: Guided cutting: a chunk takes at most 1 / (GUIDED * workers) of the estimated time left,
#: so chunks shrink towards the end and the workers finish together.
GUIDED = 2
#: Shortest estimated time of a chunk [s] (one point at least): its cost in a worker process
#: (~2 ms to send it and its results) stays a few percent.
MIN_CHUNK_SECONDS = 0.05
#: Most points in one chunk: bounds the memory of a chunk's arrays (~10 MB for 10,000
#: points of 9 combinations).
MAX_CHUNK_POINTS = 10_000
#: Under workers="auto" a sweep estimated to take less than this in one process
#: runs serially: starting worker processes (0.05 s forked, ~2 s from a fresh
#: forkserver) and shipping the chunks would cost more than it saves.
SERIAL_SECONDS = 1.0
#: Estimated cost of one combination [s]: closed form (measured ~1 µs) and IPOPT
#: (measured ~2 ms per NLP, benchmarks/results/design.md).
SECONDS_CLOSED_FORM = 2e-6
SECONDS_IPOPT = 2.5e-3
#: Chunks sent to each worker process at a time (one running, one waiting).
IN_FLIGHT_PER_WORKER = 2
#: Longest wait for a Dask scheduler to answer [s].
CONNECT_SECONDS = 5.0
#: A Dask cluster without a single worker for this long has lost them [s].
NO_WORKERS_SECONDS = 10.0
#: How often the process and Dask loops look at finished chunks, at Ctrl-C and
#: at the Dask workers [s].
POLL_SECONDS = 0.1


def cpu_count() -> int:
    """CPUs this process may run on."""
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def chunk_bounds(
    costs: ArrayLike,
    *,
    workers: int = 1,
    starts: ArrayLike | None = None,
    breaks: Iterable[int] | None = None,
    chunk_size: int | None = None,
) -> np.ndarray:
    """Where to cut a sweep's points (in the order they run) into chunks.

    Parameters
    ----------
    costs : array_like of float
        Estimated time of each point in one process [s], in run order (a
        point that needs a new analysis carries its cost).
    workers : int
        Workers the chunks are for.
    starts : array_like of bool, optional
        Where a cut may fall without splitting points that share work (the
        first point of each physics); default: anywhere.
    breaks : array_like of int, optional
        Positions where a chunk must end (e.g. the ends of blocks whose rows
        are put back in point order together).
    chunk_size : int, optional
        Points per chunk, as given by the user: cuts every ``chunk_size``
        points (and at ``breaks``), whatever the costs.

    Returns
    -------
    ndarray of int
        ``[0, b1, ..., n]``: chunk ``k`` holds the points ``bounds[k]:bounds[k+1]``.

    Notes
    -----
    Guided self-scheduling: a chunk aims at ``R / (GUIDED * workers)`` of the
    estimated time ``R`` still to cut, within [:data:`MIN_CHUNK_SECONDS`,
    :data:`CHUNK_SECONDS`], and holds at most :data:`MAX_CHUNK_POINTS`
    points. A cut that would split a group of ``starts`` moves to the group's
    end when the chunk then stays within twice its aim, else to the group's
    start; a chunk of one group is split only where the group's points after
    its first (its designs, without its analysis) exceed twice the aim.
    """
    costs = np.asarray(costs, dtype=float)
    n = len(costs)
    ends = sorted({int(b) for b in (breaks if breaks is not None else ()) if 0 < b < n} | {n})
    if n == 0:
        return np.array([0], dtype=np.int64)
    if chunk_size is not None:
        bounds, start = [0], 0
        for end in ends:
            bounds.extend(range(start + chunk_size, end, chunk_size))
            bounds.append(end)
            start = end
        return np.array(bounds, dtype=np.int64)
    cum = np.concatenate([[0.0], np.cumsum(costs)])
    share = GUIDED * max(workers, 1)
    group = None if starts is None else np.flatnonzero(np.asarray(starts, dtype=bool))
    bounds, start, block = [0], 0, 0
    while start < n:
        while ends[block] <= start:
            block += 1
        limit = min(ends[block], start + MAX_CHUNK_POINTS)
        aim = min(CHUNK_SECONDS, max(MIN_CHUNK_SECONDS, (cum[-1] - cum[start]) / share))
        # the first end whose chunk reaches the aim (a relative 1e-9 spares round-off a point)
        end = int(np.searchsorted(cum, cum[start] + aim * (1 - 1e-9), side="left"))
        end = min(max(end, start + 1), limit)
        if group is not None and end < limit:
            k = int(np.searchsorted(group, end, side="right"))  # groups starting after `end`
            begin = int(group[k - 1]) if k else 0  # the group `end` falls in
            if begin != end:
                after = int(group[k]) if k < len(group) else n
                if after <= limit and cum[after] - cum[start] <= 2 * aim:
                    end = after
                elif begin > start:
                    end = begin
                elif after <= limit and cum[after] - cum[start + 1] <= 2 * aim:
                    end = after  # one group: split only where its designs outweigh its analysis
        bounds.append(end)
        start = end
    return np.array(bounds, dtype=np.int64)


def fingerprint(identity: object, points: pd.DataFrame, layout: object) -> str:
    """A digest of what a sweep computes: parts of another sweep are never reused.

    Parameters
    ----------
    identity : str
        Everything the results depend on besides the points (the scene, the
        method, solver options), as a text stable across processes.
    points : pandas.DataFrame
    layout : object
        How the points are cut into chunks (its ``repr`` is hashed).
    """
    digest = hashlib.sha256(repr(identity).encode())
    digest.update(repr(layout).encode())
    digest.update(pd.util.hash_pandas_object(points, index=False).to_numpy().tobytes())
    return digest.hexdigest()


# --------------------------------------------------------------------------
# The parts folder
# --------------------------------------------------------------------------


class Parts:
    """The folder ``OUTPUT.parts``: one file per finished chunk, a manifest, temporary files.

    Parameters
    ----------
    output : str or Path
        The sweep's output file; the folder is beside it.
    """

    MANIFEST = "sweep.json"

    def __init__(self, output: str | os.PathLike[str]) -> None:
        output = Path(output)
        self.folder = output.with_name(output.name + ".parts")

    def path(self, index: int) -> Path:
        """The file of chunk ``index``."""
        return self.folder / f"chunk-{index:05d}.parquet"

    def manifest(self) -> dict[str, Any]:
        """What the folder's manifest records (``{}`` when there is none or it is unreadable)."""
        try:
            return json.loads((self.folder / self.MANIFEST).read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return {}

    def open(self, record: Mapping[str, Any], chunks: Sequence[tuple[int, pd.DataFrame]], resume: bool) -> list[int]:
        """Create the folder, or (``resume``) find the chunks already in it.

        Parameters
        ----------
        record : dict
            The manifest: ``fingerprint`` and what else identifies the sweep.
        chunks : list of (int, pandas.DataFrame)
            Every chunk of the sweep, to check the parts against.
        resume : bool

        Returns
        -------
        list of int
            The chunks whose part is sound (each read and checked, then let
            go: the results are read again when they are needed). A part
            that cannot be read or does not hold its chunk's points is said
            on stderr (one line), removed and left to be computed again.

        Raises
        ------
        SceneError
            The folder exists without ``resume``, or holds another sweep.
        """
        if not self.folder.exists():
            check_folder(self.folder)
            self.folder.mkdir()
            (self.folder / self.MANIFEST).write_text(json.dumps(record), encoding="utf-8")
            return []
        if not resume:
            raise SceneError(
                "--output",
                f"{str(self.folder)!r} holds the chunks of an earlier, "
                f"unfinished sweep: resume it (--resume) or delete the folder",
            )
        if self.manifest().get("fingerprint") != record["fingerprint"]:
            raise SceneError(
                "--resume",
                f"the parts in {str(self.folder)!r} come from a "
                f"different sweep (scene, fields, values or chunk size differ); "
                f"delete the folder to start over",
            )
        for stale in self.folder.glob("*.tmp-*"):  # left by a killed run
            stale.unlink(missing_ok=True)
        done = []
        for i, chunk in chunks:
            path = self.path(i)
            if not path.exists():
                continue
            problem = _damage(path, chunk)
            if problem:
                print(f"flyopt sweep: {path}: {problem}; computing chunk {i} again", file=sys.stderr)
                path.unlink()
            else:
                done.append(i)
        return done

    def read(self, index: int, columns: Sequence[str] | None = None) -> pd.DataFrame:
        """The results of chunk ``index`` (``columns`` only, when given)."""
        return read_results(self.path(index), columns=columns)

    def save(self, index: int, frame: pd.DataFrame) -> None:
        """Write the results of chunk ``index`` (atomically)."""
        write_results(frame, self.path(index), temporary_folder=self.folder)

    def remove(self) -> None:
        """Remove the folder and everything in it."""
        shutil.rmtree(self.folder, ignore_errors=True)


def _damage(path, chunk):
    """What is wrong with the part file of ``chunk`` ("" when it is sound)."""
    try:
        frame = read_results(path)
    except Exception as err:  # noqa: BLE001 - whatever the reader says, the part is unusable
        text = str(err).strip().splitlines()
        return f"cannot be read ({type(err).__name__}: {text[0] if text else ''})"
    if len(frame) != len(chunk):
        return f"holds {len(frame)} rows, not the chunk's {len(chunk)}"
    missing = [c for c in chunk.columns if c not in frame.columns]
    if missing:
        return f"lacks the column {missing[0]!r}"
    if not (frame["point"].to_numpy() == chunk["point"].to_numpy()).all():
        return "holds other points than its chunk"
    return ""


# --------------------------------------------------------------------------
# Progress
# --------------------------------------------------------------------------


class _Progress:
    """A progress line with rate and ETA on stderr (a bar on a terminal)."""

    def __init__(self, total_points, total_chunks, enabled, stream=None, done_points=0):
        self.total, self.chunks = total_points, total_chunks
        self.enabled = enabled
        self.stream = stream or sys.stderr
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self.start = time.perf_counter()
        self.points, self.skipped, self.designs, self.done_chunks = 0, done_points, 0, 0
        self.last = 0.0

    def update(self, points, designs):
        self.points += points
        self.designs += designs
        self.done_chunks += 1
        now = time.perf_counter()
        final = self.skipped + self.points >= self.total
        if self.enabled and (final or now - self.last > (0.2 if self.tty else 5.0)):
            self.last = now
            self._write(final)

    def close(self):
        """End the line on a terminal when the run stopped before the last chunk."""
        if self.enabled and self.tty and self.skipped + self.points < self.total:
            self._write(False)
            self.stream.write("\n")
            self.stream.flush()

    def _write(self, final):
        elapsed = max(time.perf_counter() - self.start, 1e-9)
        done = self.skipped + self.points
        rate = self.points / elapsed
        left = self.total - done
        eta = left / rate if rate > 0 else math.inf
        fraction = done / self.total if self.total else 1.0
        bar = "#" * int(24 * fraction) + "-" * (24 - int(24 * fraction))
        text = (
            f"sweep [{bar}] {done}/{self.total} points ({100 * fraction:.0f}%), "
            f"{self.designs / elapsed:,.0f} designs/s, "
            f"{'done in ' + _clock(elapsed) if final else 'ETA ' + _clock(eta)}"
        )
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + text + end)
        self.stream.flush()


def _clock(seconds):
    if not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


# --------------------------------------------------------------------------
# Running
# --------------------------------------------------------------------------


#: The address of a Dask scheduler: an optional protocol, a host name, IPv4 or [IPv6] address, a port.
_ADDRESS = re.compile(
    r"(?:(?P<protocol>tcp|tls|ws|wss|ucx)://)?(?P<host>[A-Za-z0-9](?:[A-Za-z0-9.-]{0,252})|\[[0-9A-Fa-f:.]{2,45}\]):(?P<port>[0-9]{1,5})"
)

#: The address of a scheduler in this process (a LocalCluster(processes=False)): inproc://host/pid/n.
_IN_PROCESS = re.compile(r"inproc://[A-Za-z0-9.:\[\]-]+/[0-9]+/[0-9]+")


def scheduler_address(text: str) -> str:
    """``text`` when it is the address of a Dask scheduler, ``[protocol://]host:port`` (or a scheduler of this
    process, ``inproc://host/pid/n``); else a SceneError.

    Checked before anything connects: Dask would otherwise wait for its
    timeout on a malformed address and leave a traceback from its client's
    clean-up. The scheduler must be one you trust: Dask sends it and its
    workers pickles, which can run code.
    """
    if isinstance(text, str) and _IN_PROCESS.fullmatch(text):
        return text
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
    if isinstance(scheduler, str):  # else a cluster object (LocalCluster) that Client takes as it is
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


def run_chunks(
    task: Callable[[pd.DataFrame], pd.DataFrame],
    chunks: Sequence[tuple[int, pd.DataFrame]],
    pending: Sequence[tuple[int, pd.DataFrame]],
    *,
    parts: Parts | None = None,
    done: Iterable[int] | None = None,
    sink: Callable[[int, pd.DataFrame], None] | None = None,
    workers: int = 1,
    client: Any = None,
    progress: bool = False,
) -> tuple[dict[int, pd.DataFrame], list[int]]:
    """Run ``task`` on the ``pending`` chunks; save each as it finishes.

    Parameters
    ----------
    task : callable
        ``task(points) -> pandas.DataFrame``; picklable to run in processes.
    chunks : list of (int, pandas.DataFrame)
        Every chunk of the sweep (for the counts).
    pending : list of (int, pandas.DataFrame)
        The chunks to run now.
    parts : Parts, optional
        Where finished chunks are saved.
    done : collection of int, optional
        Chunks finished before (e.g. found in ``parts``), for the counts.
    sink : callable, optional
        ``sink(index, frame)``, called with each finished chunk once it is
        saved (in the order they finish). Without it the results are kept
        and returned.
    workers : int
        Worker processes (1: serially, in this process).
    client : dask.distributed.Client, optional
        Run on this Dask cluster instead.
    progress : bool
        A progress line with rate and ETA on stderr.

    Returns
    -------
    results : dict
        Chunk index to its table, for the chunks run here (empty with a ``sink``).
    ran : list of int
        The chunks run in this call, in the order they finished.

    Raises
    ------
    Interrupted
        Ctrl-C, or a Dask cluster that lost its workers: the finished chunks
        are kept in ``parts`` and the message says how many and that
        ``--resume`` continues.
    """
    done = set(done or ())
    results = {}
    ran = []
    sizes = {i: len(chunk) for i, chunk in chunks}
    meter = _Progress(sum(sizes.values()), len(chunks), progress, done_points=sum(sizes[i] for i in done))

    def finished(i, frame):
        if parts is not None:
            parts.save(i, frame)
        if sink is None:
            results[i] = frame
        else:
            sink(i, frame)
        ran.append(i)
        meter.update(len(frame), int(frame["n_combinations"].sum()) if "n_combinations" in frame else len(frame))

    try:
        with _ctrl_c() as stop:
            if not pending:
                pass
            elif client is not None:
                _run_dask(client, task, pending, finished, stop)
            elif workers > 1:
                _run_processes(task, pending, workers, finished, stop)
            else:
                for i, chunk in pending:
                    with stop.at_once():
                        frame = task(chunk)
                    finished(i, frame)
                    stop.check()
    except KeyboardInterrupt:
        raise Interrupted(stopped("interrupted", parts, len(done) + len(ran), len(chunks))) from None
    except _WorkersLost as err:
        raise Interrupted(stopped(str(err), parts, len(done) + len(ran), len(chunks))) from None
    finally:
        meter.close()
    return results, ran


def stopped(why: str, parts: Parts | None, saved: int, total: int) -> str:
    """One line: why a sweep stopped, what it kept and how to continue."""
    if parts is None:
        return f"{why}; nothing was saved (no output file: give one to keep finished chunks)"
    return f"{why}; {saved} of {total} chunks saved in {parts.folder}; --resume continues"


class _WorkersLost(Exception):
    """A Dask cluster has no worker left to run the chunks."""


class _Stop:
    """Ctrl-C while chunks run: noted by the signal handler, acted on where it is safe.

    A :class:`KeyboardInterrupt` raised wherever the main thread happens to be
    can land inside a process pool's bookkeeping (holding a lock the shutdown
    then waits for: a hang), inside ``logging`` or half-way through saving a
    chunk. So the handler only notes the request, and the loops look at it
    between chunks and while they wait. Only a chunk computed in this process
    (serial mode) is stopped at once: that is plain computation, and waiting
    for it to finish could take minutes.
    """

    def __init__(self):
        self.requested = False
        self._at_once = False

    def handler(self, signum, frame):
        self.requested = True
        if self._at_once:
            self._at_once = False
            raise KeyboardInterrupt

    def check(self):
        """Raise :class:`KeyboardInterrupt` here if Ctrl-C was pressed."""
        if self.requested:
            raise KeyboardInterrupt

    @contextmanager
    def at_once(self):
        """A block that Ctrl-C stops at once (the computation of a serial chunk)."""
        self.check()
        self._at_once = True
        try:
            yield
        finally:
            self._at_once = False


@contextmanager
def _ctrl_c():
    """Hand Ctrl-C to a :class:`_Stop` for the duration (main thread only)."""
    stop = _Stop()
    if threading.current_thread() is not threading.main_thread():
        yield stop  # signals reach the main thread only; nothing to catch here
        return
    previous = signal.signal(signal.SIGINT, stop.handler)
    try:
        yield stop
    finally:
        signal.signal(signal.SIGINT, previous)


# -- worker processes ------------------------------------------------------

_TASK: Callable[[Any], Any] | None = None


def _init_worker(task):
    global _TASK
    _TASK = task
    signal.signal(signal.SIGINT, signal.SIG_IGN)  # Ctrl-C is the parent's to handle
    _die_with_parent()


def _die_with_parent():
    """Ask Linux to kill this process when its parent dies (``prctl(PR_SET_PDEATHSIG)``)."""
    if not sys.platform.startswith("linux"):  # pragma: no cover - elsewhere, at the parent's exit
        return
    import ctypes

    parent = os.getppid()
    pr_set_pdeathsig = 1
    ctypes.CDLL(None, use_errno=True).prctl(pr_set_pdeathsig, signal.SIGKILL, 0, 0, 0)
    if parent == 1 or os.getppid() != parent:  # the parent died before the request
        os._exit(1)


def _run_in_worker(index, points):
    if _TASK is None:  # set by the pool's initializer before any chunk arrives
        raise RuntimeError("a sweep worker got a chunk before its task")
    return index, _TASK(points)


def _mp_context(preload):
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


def _run_processes(task, pending, n_workers, finished, stop):
    from concurrent.futures import FIRST_COMPLETED, ProcessPoolExecutor, wait

    module = getattr(task, "func", task).__module__
    pool = ProcessPoolExecutor(
        max_workers=n_workers, mp_context=_mp_context(module), initializer=_init_worker, initargs=(task,)
    )
    try:
        # a few chunks in flight per worker, not all: the results of chunks that finish
        # while this process saves others wait in memory, and a 10^6-point sweep's would pile up
        queue = iter(pending)
        running = set()
        while True:
            for i, chunk in queue:
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


def _terminate(pool):
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


# -- Dask ------------------------------------------------------------------


def _run_task(task, index, points):
    return index, task(points)


def _run_dask(client, task, pending, finished, stop):
    from dask.distributed import KilledWorker, as_completed

    # results are fetched as they come: a result asked for later may have been lost
    # with its worker, and waiting for it would wait for a worker that may never come.
    # A few chunks per worker thread are in flight, not all: results that arrive while
    # this process saves others wait in its memory.
    queue = as_completed(loop=client.loop, with_results=True)
    futures, waiting = [], iter(pending)
    flight = {"chunks": 0, "threads": _threads(client)}

    def top_up():
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
                raise _WorkersLost(f"a chunk killed every Dask worker that ran it ({type(err).__name__})") from None
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
                raise _WorkersLost(f"the connection to the Dask scheduler was lost ({type(err).__name__})") from None
            flight["threads"] = sum(int(w.get("nthreads", 1)) for w in workers.values())
            top_up()
            if workers:
                alone_since = None
            elif alone_since is None:
                alone_since = time.monotonic()
            elif time.monotonic() - alone_since > NO_WORKERS_SECONDS:
                raise _WorkersLost(f"all Dask workers were lost (none for {NO_WORKERS_SECONDS:g} s)")
            time.sleep(POLL_SECONDS)
    except BaseException:
        try:
            client.cancel(futures)
        except (OSError, TimeoutError):  # the scheduler is gone: nothing left to cancel
            pass
        raise


def _threads(client):
    """Worker threads of a Dask cluster now (0 when it cannot say)."""
    try:
        workers = client.scheduler_info()["workers"]
    except (OSError, TimeoutError, KeyError):
        return 0
    return sum(int(w.get("nthreads", 1)) for w in workers.values())

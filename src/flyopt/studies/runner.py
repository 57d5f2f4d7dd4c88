"""Running a sweep's chunks: serially, in worker processes or on a Dask cluster, with resume.


Running
-------
Points are cut into chunks. By default chunks run in parallel in worker
processes on this machine, one per CPU (serially when the sweep is estimated
to take under a second in one process, so that starting processes would cost
more than it saves: a 10,000-point closed-form sweep takes ~0.15 s), with a
progress line and an ETA on stderr. ``scheduler="tcp://host:8786"`` (or a
``dask.distributed`` Client or cluster) runs them on a Dask cluster instead.
With an ``output`` file every finished chunk is written to
``OUTPUT.parts/chunk-NNNNN.parquet`` at once, so a crash loses at most the
chunks in flight; ``resume=True`` skips the chunks already on disk. The
final file (Parquet or CSV, by its suffix) is assembled at the end and the
parts removed.
"""

from __future__ import annotations

import hashlib
import math
import os
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd

from flyopt.design import closed_form as batch
from flyopt.errors import SceneError
from flyopt.studies.evaluate import _evaluate



#: Points per chunk when every point is closed form, and when some need IPOPT.
CHUNK_CLOSED_FORM = 2500
CHUNK_IPOPT = 50
#: Under workers="auto" a sweep estimated to take less than this in one process
#: runs serially: starting worker processes (0.05 s forked, ~2 s from a fresh
#: forkserver) and shipping the chunks would cost more than it saves.
SERIAL_SECONDS = 1.0
#: Estimated cost of one combination [s]: closed form (measured ~1 µs) and IPOPT
#: (measured ~2 ms per NLP, benchmarks/results/design.md).
SECONDS_CLOSED_FORM = 2e-6
SECONDS_IPOPT = 2.5e-3


def _estimated_seconds(inputs, method):
    per_point = len(inputs.material_names) * len(inputs.shaft_names)
    if inputs.material is not None:
        per_point //= max(len(inputs.material_names), 1)
    if inputs.shaft is not None:
        per_point //= max(len(inputs.shaft_names), 1)
    covered = np.array([batch.covers(g, o) for g, o in zip(inputs.geometry, inputs.objective)],
                       dtype=bool) if method != "ipopt" else np.zeros(inputs.n, dtype=bool)
    closed = int(covered.sum())
    return per_point * (closed * SECONDS_CLOSED_FORM + (inputs.n - closed) * SECONDS_IPOPT)


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
        text = (f"sweep [{bar}] {done}/{self.total} points ({100 * fraction:.0f}%), "
                f"{self.designs / elapsed:,.0f} designs/s, "
                f"{'done in ' + _clock(elapsed) if final else 'ETA ' + _clock(eta)}")
        end = "\n" if final or not self.tty else ""
        self.stream.write(("\r" if self.tty else "") + text + end)
        self.stream.flush()


def _clock(seconds):
    if not math.isfinite(seconds):
        return "?"
    seconds = int(round(seconds))
    return f"{seconds // 3600}:{seconds // 60 % 60:02d}:{seconds % 60:02d}"


def _run_chunk(ctx, index, points):
    return index, _evaluate(ctx, points)


_WORKER_CONTEXT = None


def _init_worker(ctx):
    global _WORKER_CONTEXT
    _WORKER_CONTEXT = ctx


def _run_chunk_in_worker(index, points):
    return index, _evaluate(_WORKER_CONTEXT, points)


def _cpu_count():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:  # pragma: no cover - not Linux
        return os.cpu_count() or 1


def _mp_context():
    import multiprocessing as mp

    methods = mp.get_all_start_methods()
    # fork is fast and safe while this process runs a single thread; otherwise
    # (e.g. a Dask client's threads) a fresh forkserver
    if "fork" in methods and threading.active_count() == 1:
        return mp.get_context("fork")
    if "forkserver" in methods:
        context = mp.get_context("forkserver")
        # the server imports flyopt (numpy, pandas, CasADi) once; workers fork from it
        context.set_forkserver_preload(["flyopt.studies.runner"])
        return context
    return mp.get_context("spawn")  # pragma: no cover - Windows


def _fingerprint(ctx, points, chunk_size):
    scene = ctx.scene.replace(source=None)
    text = repr((repr(scene), ctx.a_max, ctx.driving_torque, ctx.reusable, ctx.method,
                 sorted((ctx.solver_options or {}).items()), ctx.axes, chunk_size))
    digest = hashlib.sha256(text.encode())
    digest.update(pd.util.hash_pandas_object(points, index=False).to_numpy().tobytes())
    return digest.hexdigest()


def _parts_dir(output):
    output = Path(output)
    return output.with_name(output.name + ".parts")


def _part_path(parts, index):
    return parts / f"chunk-{index:05d}.parquet"


def _run_processes(ctx, pending, n_workers, finished):
    from concurrent.futures import ProcessPoolExecutor, as_completed

    with ProcessPoolExecutor(max_workers=n_workers, mp_context=_mp_context(),
                             initializer=_init_worker, initargs=(ctx,)) as pool:
        futures = [pool.submit(_run_chunk_in_worker, i, chunk) for i, chunk in pending]
        try:
            for future in as_completed(futures):
                finished(*future.result())
        except BaseException:
            for future in futures:
                future.cancel()
            raise


def _run_dask(scheduler, ctx, pending, finished):
    try:
        from dask.distributed import Client, as_completed
    except ImportError as err:  # pragma: no cover - dask is in the test extras
        raise SceneError("scheduler", "running on a Dask cluster needs dask[distributed] "
                         "(pip install 'flyopt[cluster]')") from err
    own = not isinstance(scheduler, Client)
    if own:
        address = scheduler if isinstance(scheduler, str) else scheduler
        try:
            client = Client(address)
        except (OSError, TimeoutError, ValueError) as err:
            raise SceneError("scheduler", f"cannot connect to the Dask scheduler "
                             f"{scheduler!r}: {err}") from err
    else:
        client = scheduler
    try:
        context = client.scatter(ctx, broadcast=True)
        futures = [client.submit(_run_chunk, context, i, chunk, pure=False)
                   for i, chunk in pending]
        for future in as_completed(futures):
            finished(*future.result())
    finally:
        if own:
            client.close()



"""Running a sweep's chunks: serially, in worker processes or on a Dask cluster, with resume.

The runner knows nothing of flywheels: it runs a *task* (a picklable callable
taking a table of points and returning a table of results, one row per
point) over chunks of points (:mod:`flyopt.studies.chunks`), and hands each
finished chunk on, saved first in the sweep's parts folder
(:mod:`flyopt.studies.parts`) when it has one.

By default chunks run in parallel in worker processes on this machine
(:mod:`flyopt.studies.processes`), one per CPU (serially when the sweep is
estimated to take under :data:`~flyopt.studies.chunks.SERIAL_SECONDS` in
one process, so that starting processes would cost more than it saves),
with a progress line and an ETA on stderr (:mod:`flyopt.studies.progress`).
A Dask scheduler runs them on a cluster instead
(:mod:`flyopt.studies.cluster`). Ctrl-C is acted on where it is safe
(:mod:`flyopt.studies.interrupt`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Sequence
from typing import Any

import pandas as pd

from flyopt.errors import Interrupted
from flyopt.studies.cluster import WorkersLost, run_dask
from flyopt.studies.interrupt import ctrl_c
from flyopt.studies.parts import Parts
from flyopt.studies.processes import run_processes
from flyopt.studies.progress import Progress

__all__ = ["run_chunks", "stopped"]


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
    results: dict[int, pd.DataFrame] = {}
    ran: list[int] = []
    sizes = {i: len(chunk) for i, chunk in chunks}
    meter = Progress(sum(sizes.values()), len(chunks), progress, done_points=sum(sizes[i] for i in done))

    def finished(i: int, frame: pd.DataFrame) -> None:
        if parts is not None:
            parts.save(i, frame)
        if sink is None:
            results[i] = frame
        else:
            sink(i, frame)
        ran.append(i)
        meter.update(len(frame), int(frame["n_combinations"].sum()) if "n_combinations" in frame else len(frame))

    try:
        with ctrl_c() as stop:
            if not pending:
                pass
            elif client is not None:
                run_dask(client, task, pending, finished, stop)
            elif workers > 1:
                run_processes(task, pending, workers, finished, stop)
            else:
                for i, chunk in pending:
                    with stop.at_once():
                        frame = task(chunk)
                    finished(i, frame)
                    stop.check()
    except KeyboardInterrupt:
        raise Interrupted(stopped("interrupted", parts, len(done) + len(ran), len(chunks))) from None
    except WorkersLost as err:
        raise Interrupted(stopped(str(err), parts, len(done) + len(ran), len(chunks))) from None
    finally:
        meter.close()
    return results, ran


def stopped(why: str, parts: Parts | None, saved: int, total: int) -> str:
    """One line: why a sweep stopped, what it kept and how to continue."""
    if parts is None:
        return f"{why}; nothing was saved (no output file: give one to keep finished chunks)"
    return f"{why}; {saved} of {total} chunks saved in {parts.folder}; --resume continues"

"""Tests of flyopt.studies.interrupt: Ctrl-C while chunks run is acted on where it is safe.

A save in progress completes and no other chunk starts, also when Ctrl-C
comes twice; a chunk computed in this process is stopped at once; the
previous SIGINT handler is put back.
"""

import os
import re
import signal
import time
from pathlib import Path

import pandas as pd
import pytest

from flyopt.errors import Interrupted
from flyopt.studies import runner
from flyopt.studies.interrupt import Stop


class _SavingParts:
    """Stands in for parts.Parts: records saves; Ctrl-C (twice) arrives inside the first."""

    folder = Path("parts")

    def __init__(self):
        self.saved = []

    def save(self, index, frame):
        if not self.saved:
            os.kill(os.getpid(), signal.SIGINT)
            os.kill(os.getpid(), signal.SIGINT)
            time.sleep(0.05)  # the handler runs here, in the middle of the save
        self.saved.append((index, len(frame)))


def _points(n):
    return [(i, pd.DataFrame({"x": [float(i)]})) for i in range(n)]


def _square(points):
    time.sleep(0.3)  # long enough that no worker finishes a second chunk first
    return pd.DataFrame({"y": points["x"] ** 2})


@pytest.mark.parametrize("workers", [1, 2])
def test_ctrl_c_during_a_save_finishes_the_save_then_stops(workers):
    """Regression (issue 11): Ctrl-C raised KeyboardInterrupt wherever the main thread
    was: in the middle of saving a chunk (a chunk lost), inside the process pool's
    bookkeeping (a hang on a lock at shutdown) or in ``logging`` (a traceback, and the
    sweep went on). Ctrl-C now only asks to stop; the save in progress completes and
    the run stops without starting another chunk, also when Ctrl-C comes twice.
    (Worker processes may have finished a chunk in the same instant; that one is saved
    too, so the count is checked against the saves.)"""
    chunks, parts = _points(6), _SavingParts()
    previous = signal.getsignal(signal.SIGINT)
    with pytest.raises(Interrupted) as stop:
        runner.run_chunks(_square, chunks, chunks, parts=parts, workers=workers)
    assert re.fullmatch(r"interrupted; (\d) of 6 chunks saved in parts; --resume continues", str(stop.value)), str(
        stop.value
    )
    saved = int(str(stop.value).split("; ")[1].split()[0])
    assert saved == len(parts.saved) and all(rows == 1 for _, rows in parts.saved)
    assert saved == 1 if workers == 1 else 1 <= saved <= workers
    assert signal.getsignal(signal.SIGINT) is previous  # the handler is put back


def _interrupted_serial_chunk(points):
    os.kill(os.getpid(), signal.SIGINT)
    time.sleep(5)  # a long computation: Ctrl-C must not wait for it
    return _square(points)


def test_ctrl_c_stops_a_serial_chunk_at_once():
    """A chunk computed in this process is stopped at once: it is only computation,
    and waiting for it could take minutes."""
    chunks = _points(3)
    start = time.monotonic()
    with pytest.raises(Interrupted, match=r"^interrupted; 0 of 3 chunks saved"):
        runner.run_chunks(_interrupted_serial_chunk, chunks, chunks, parts=_SavingParts())
    assert time.monotonic() - start < 4


def _masks(_points):
    """In a worker: the signals it holds and its SIGTERM handler, after its initializer."""
    return pd.DataFrame(
        {
            "held": [sorted(int(s) for s in signal.pthread_sigmask(signal.SIG_BLOCK, []))],
            "sigterm": [signal.getsignal(signal.SIGTERM) == signal.SIG_DFL],
        }
    )


def test_a_worker_is_forked_with_ctrl_c_and_sigterm_held_until_its_own_handlers(monkeypatch, tmp_path):
    """A fork inherits the parent's handlers (SIGTERM and Ctrl-C as a KeyboardInterrupt): a signal in the moments
    before a worker's initializer ran printed that worker's traceback. Forked with both held, the worker takes them
    once its initializer has set its own handlers."""
    from flyopt.studies import processes

    seen = tmp_path / "at-start"
    real = processes._init_worker

    def init(task):  # what the worker holds as it starts, before the initializer
        seen.write_text(" ".join(str(int(s)) for s in signal.pthread_sigmask(signal.SIG_BLOCK, [])))
        real(task)

    monkeypatch.setattr(processes, "_init_worker", init)
    monkeypatch.setattr(processes.threading, "active_count", lambda: 1)  # forked, as a sweep of one thread is
    out = []
    processes.run_processes(_masks, _points(2), 2, lambda i, frame: out.append(frame), Stop())
    assert {int(s) for s in seen.read_text().split()} >= {signal.SIGINT, signal.SIGTERM}
    for frame in out:  # the task runs with both taken again, SIGTERM ending the worker
        assert signal.SIGINT not in frame["held"][0] and signal.SIGTERM not in frame["held"][0]
        assert bool(frame["sigterm"][0])
    assert signal.pthread_sigmask(signal.SIG_BLOCK, []) == set()  # and this process holds nothing after


def test_a_forkserver_started_for_a_sweep_holds_no_signal(monkeypatch):
    """Where this process runs threads the workers come from a forkserver, which a held block around the pool's
    start left holding Ctrl-C and SIGTERM for the rest of its life (a kill did not end it)."""
    import multiprocessing.forkserver as forkserver
    import threading

    from flyopt.studies import processes

    forkserver._forkserver._stop()  # one of this test's own
    stop = threading.Event()
    waiting = threading.Thread(target=stop.wait, daemon=True)
    waiting.start()  # a second thread: a forkserver, as under a Dask client's threads
    try:
        out = []
        processes.run_processes(_masks, _points(2), 2, lambda i, frame: out.append(frame), Stop())
        pid = forkserver._forkserver._forkserver_pid
        assert pid is not None and len(out) == 2
        status = Path(f"/proc/{pid}/status").read_text()
        blocked = int(next(line for line in status.splitlines() if line.startswith("SigBlk:")).split()[1], 16)
        assert not blocked & (1 << (signal.SIGINT - 1)) and not blocked & (1 << (signal.SIGTERM - 1)), hex(blocked)
    finally:
        stop.set()
        forkserver._forkserver._stop()

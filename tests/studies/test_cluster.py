"""Tests of flyopt.studies.cluster: a scheduler address checked first, a scheduler that does not answer, a
cluster that loses its workers.

A malformed address is refused in one line before any client is made; the others end the sweep within a bounded time with one line, leaves nothing
stale behind, and keeps the finished chunks for ``--resume``.
"""

import subprocess
import sys
import threading
import time

import pytest
from test_runner import LONG, PUNCH, VARY, wait_for

from flyopt.errors import Interrupted, SceneError
from flyopt.studies import cluster as cluster_module
from flyopt.studies.sweep import sweep


def test_unreachable_scheduler_is_one_line_and_leaves_nothing(tmp_path, monkeypatch):
    """Regression (issue 11): a failed scheduler connection left a stale .parts folder
    that blocked the next run. The scheduler is connected to (within CONNECT_SECONDS, here
    cut to 1 s: the wait is Dask's, the test is of what is left behind) before anything is written."""
    from flyopt.studies import cluster

    monkeypatch.setattr(cluster, "CONNECT_SECONDS", 1.0)
    out = tmp_path / "study.parquet"
    start = time.monotonic()
    with pytest.raises(SceneError, match="cannot connect to the Dask scheduler 'tcp://127.0.0.1:1' within 1 s") as info:
        sweep(PUNCH, VARY, output=out, scheduler="tcp://127.0.0.1:1")
    assert time.monotonic() - start < 30
    assert info.value.field == "--scheduler" and "\n" not in str(info.value)
    assert list(tmp_path.iterdir()) == []
    sweep(PUNCH, VARY, output=out)  # nothing stale blocks the next run
    assert out.exists()


@pytest.mark.parametrize("address", ["not a url", "tcp://x:99999", "tcp://host", "http://host:8786", "tcp://:8786", ""])
def test_a_malformed_scheduler_address_is_refused_before_connecting(tmp_path, address, monkeypatch):
    """Issue 25, item 7: 'not a url' waited 11 s for Dask's timeout and ended in a traceback from
    the client's clean-up. The address is checked first: refused in words, no client made, nothing written."""
    import dask.distributed

    class NoClient:
        def __init__(self, *args, **kwargs):
            raise AssertionError("a client was made for a malformed address")

    monkeypatch.setattr(dask.distributed, "Client", NoClient)
    out = tmp_path / "study.parquet"
    with pytest.raises(SceneError, match="is not a scheduler address") as info:
        sweep(PUNCH, VARY, output=out, scheduler=address)
    assert info.value.field == "--scheduler"
    assert list(tmp_path.iterdir()) == []


@pytest.mark.parametrize("address", ["tcp://10.0.0.5:8786", "10.0.0.5:8786", "tls://sched.example.com:8786", "[::1]:1"])
def test_a_scheduler_address_of_every_form_is_taken(address):
    assert cluster_module.scheduler_address(address) == address


def test_a_malformed_scheduler_on_the_command_line_is_one_line_at_once(tmp_path):
    run = subprocess.run(
        [sys.executable, "-m", "flyopt", "sweep", str(PUNCH), "--vary", "delta=0.01:0.1:3", "--scheduler", "not a url"],
        capture_output=True,
        text=True,
        timeout=60,
        cwd=tmp_path,
    )
    assert run.returncode == 2 and len(run.stderr.splitlines()) == 1 and "Traceback" not in run.stderr
    assert "'not a url' is not a scheduler address" in run.stderr
    assert list(tmp_path.iterdir()) == []


@pytest.mark.slow  # 4-10 s of a local cluster; the unreachable scheduler's refusal stays in the default run
def test_losing_every_dask_worker_stops_the_sweep(tmp_path, monkeypatch):
    """Regression (issue 11): a sweep whose Dask workers all went away waited forever.
    Without a worker for NO_WORKERS_SECONDS it stops with Interrupted, the finished
    chunks kept, and --resume (here without Dask) completes it."""
    from dask.distributed import LocalCluster

    monkeypatch.setattr(cluster_module, "NO_WORKERS_SECONDS", 1.0)
    out = tmp_path / "study.parquet"
    parts = tmp_path / "study.parquet.parts"
    outcome = {}
    with LocalCluster(processes=False, n_workers=2, threads_per_worker=1, dashboard_address=":0") as cluster:

        def run():
            try:
                outcome["frame"] = sweep(
                    PUNCH,
                    LONG["vary"],
                    method=LONG["method"],
                    chunk_size=LONG["chunk_size"],
                    scheduler=cluster,
                    output=out,
                )
            except BaseException as err:  # noqa: BLE001 - handed to the test thread
                outcome["error"] = err

        thread = threading.Thread(target=run, daemon=True)
        thread.start()
        wait_for(lambda: any(parts.glob("chunk-*.parquet")) or not thread.is_alive(), 120, "the first chunk")
        cluster.scale(0)
        thread.join(timeout=60)
        assert not thread.is_alive(), "the sweep did not stop after losing its workers"
    err = outcome.get("error")
    assert isinstance(err, Interrupted), outcome
    assert str(err).startswith("all Dask workers were lost (none for 1 s); ")
    assert "chunks saved in" in str(err) and str(err).endswith("--resume continues")
    assert "\n" not in str(err)
    saved = int(str(err).split("; ")[1].split(" of ")[0])
    assert len(list(parts.glob("chunk-*.parquet"))) == saved >= 1
    done = sweep(
        PUNCH, LONG["vary"], method=LONG["method"], chunk_size=LONG["chunk_size"], output=out, resume=True, workers=1
    )
    assert done.attrs["sweep"]["complete"] and len(done.attrs["sweep"]["chunks_reused"]) == saved

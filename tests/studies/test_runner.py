"""Tests of flyopt.studies.runner: how a sweep stops, and what it leaves behind.

A sweep is stopped by Ctrl-C, killed, loses its Dask workers, or is pointed
at a scheduler that does not answer; its part files are damaged. In each
case the run must end within a bounded time with one line, leave no process
and no temporary file behind, keep the finished chunks, and ``--resume``
must then give the file an uninterrupted run gives.

Processes are watched through /proc (Linux): a sweep's worker processes are
the descendants of the process that runs it.
"""

import os
import re
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.errors import Interrupted, SceneError
from flyopt.outputs.results import ResultWriter, read_results
from flyopt.studies import runner
from flyopt.studies.sweep import sweep

PUNCH = flyopt.load(PROBLEMS / "punch-press.toml")
VARY = {"delta": "0.02:0.2:log5", "speed": "30,60rpm", "objective": "mass,outer_diameter"}

#: A sweep long enough to be stopped in the middle: 40 points of 9 IPOPT designs each
#: (~60 ms a point), one point per chunk, in 2 worker processes (~1.2 s in all).
LONG = dict(vary={"delta": "0.02:0.2:log40"}, method="ipopt", chunk_size=1)

DRIVER = textwrap.dedent("""
    import sys

    import flyopt
    from flyopt.errors import Interrupted

    scene = flyopt.load(sys.argv[1])
    try:
        flyopt.sweep(scene, {vary!r}, method={method!r}, chunk_size={chunk_size!r},
                     workers=2, output=sys.argv[2], resume=sys.argv[3] == "resume")
    except Interrupted as err:
        print(type(err).__name__, err, flush=True)
        sys.exit(130)
    print("done", flush=True)
""").format(**LONG)


def children(pid):
    """The pids of every living descendant of ``pid`` (from /proc; zombies count as dead)."""
    parent_of = {}
    for entry in Path("/proc").iterdir():
        if not entry.name.isdigit():
            continue
        try:
            stat = (entry / "stat").read_text()
        except OSError:
            continue
        fields = stat[stat.rindex(")") + 2 :].split()  # after "pid (comm) "
        if fields[0] != "Z":
            parent_of[int(entry.name)] = int(fields[1])
    found, frontier = set(), {pid}
    while frontier:
        frontier = {p for p, parent in parent_of.items() if parent in frontier} - found
        found |= frontier
    return found


def alive(pids):
    """The pids of ``pids`` still running (not gone, not zombies)."""
    living = set()
    for pid in pids:
        try:
            state = Path(f"/proc/{pid}/stat").read_text()
        except OSError:
            continue
        if state[state.rindex(")") + 2] != "Z":
            living.add(pid)
    return living


def wait_for(condition, seconds, what):
    """Poll ``condition()`` until true; fail after ``seconds``."""
    deadline = time.monotonic() + seconds
    while not condition():
        if time.monotonic() > deadline:
            pytest.fail(f"waited {seconds} s for {what}")
        time.sleep(0.01)


def start_driver(tmp_path, out, resume=False):
    script = tmp_path / "driver.py"
    script.write_text(DRIVER)
    return subprocess.Popen(
        [sys.executable, str(script), str(PROBLEMS / "punch-press.toml"), str(out), "resume" if resume else "new"],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
        start_new_session=True,
        cwd=tmp_path,
    )


def stop_after_first_chunk(tmp_path, out, sig, group):
    """Start the driver, send ``sig`` once a chunk is on disk; the workers it had."""
    parts = out.with_name(out.name + ".parts")
    driver = start_driver(tmp_path, out)
    workers = set()
    try:
        wait_for(lambda: any(parts.glob("chunk-*.parquet")) or driver.poll() is not None, 120, "the first chunk")
        assert driver.poll() is None, driver.communicate()
        workers = children(driver.pid)
        assert len(workers) >= 2  # the two worker processes (and their helpers)
        (os.killpg if group else os.kill)(driver.pid, sig)
        # the workers hold the driver's stdout: output ends when they are gone too
        stdout, stderr = driver.communicate(timeout=60)
    finally:  # whatever happened, leave no process of this test behind
        for pid in alive(workers | ({driver.pid} if driver.poll() is None else set())):
            os.kill(pid, signal.SIGKILL)
        driver.wait(10)
    return driver.returncode, stdout, stderr, workers


@pytest.fixture(scope="module")
def uninterrupted():
    """The table of LONG run in one go, in this process."""
    return sweep(PUNCH, LONG["vary"], method=LONG["method"], chunk_size=LONG["chunk_size"], workers=1)


def resume_and_compare(tmp_path, out, expected):
    driver = start_driver(tmp_path, out, resume=True)
    stdout, stderr = driver.communicate(timeout=120)
    assert (driver.returncode, stdout) == (0, "done\n"), stderr
    pd.testing.assert_frame_equal(read_results(out), expected)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", out.name]


# --------------------------------------------------------------------------
# Ctrl-C and kill
# --------------------------------------------------------------------------


def test_ctrl_c_stops_workers_keeps_chunks_and_resume_completes(tmp_path, uninterrupted):
    """Regression (issue 11): Ctrl-C (SIGINT to the process group, as a terminal sends
    it) ends the workers, keeps the finished chunks, removes temporary files and raises
    Interrupted saying how many chunks are saved and that --resume continues."""
    out = tmp_path / "study.parquet"
    status, stdout, stderr, workers = stop_after_first_chunk(tmp_path, out, signal.SIGINT, group=True)
    assert status == 130 and stdout.startswith("Interrupted interrupted; "), (stdout, stderr)
    assert stdout.count("\n") == 1 and "chunks saved in" in stdout and "--resume" in stdout
    assert "Traceback" not in stderr
    wait_for(lambda: not alive(workers), 10, "the workers to end")
    parts = tmp_path / "study.parquet.parts"
    chunks = sorted(p.name for p in parts.glob("chunk-*"))
    assert sorted(p.name for p in parts.iterdir()) == chunks + ["sweep.json"]  # no temporary
    assert all(re.fullmatch(r"chunk-\d{5}\.parquet", name) for name in chunks)
    assert len(chunks) == int(stdout.split("; ")[1].split(" of ")[0]) >= 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", "study.parquet.parts"]
    resume_and_compare(tmp_path, out, uninterrupted)


def test_killed_sweep_leaves_no_worker_and_resume_cleans_up(tmp_path, uninterrupted):
    """Regression (issue 11): a killed sweep (SIGKILL to it alone) left its worker
    processes running. They die with their parent; what is left is the parts folder,
    which --resume continues and removes."""
    out = tmp_path / "study.parquet"
    status, _, _, workers = stop_after_first_chunk(tmp_path, out, signal.SIGKILL, group=False)
    assert status == -signal.SIGKILL
    wait_for(lambda: not alive(workers), 10, "the workers of a killed sweep to end")
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", "study.parquet.parts"]
    resume_and_compare(tmp_path, out, uninterrupted)


class _SavingParts:
    """Stands in for runner.Parts: records saves; Ctrl-C (twice) arrives inside the first."""

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


def test_interrupt_while_writing_the_output_leaves_no_hidden_file(tmp_path, monkeypatch):
    """Regression (issue 11): the output was written to a hidden temporary file beside it
    (``.study.parquet.tmp-PID``, 40 MB for a large sweep), left behind by an interrupt or
    a kill. The output is streamed to a temporary file in the parts folder, removed on an
    interrupt (here while the file is being finished, its rows written), and the finished
    chunks are kept for --resume."""
    out = tmp_path / "study.parquet"
    whole = sweep(PUNCH, VARY, chunk_size=4)
    original = ResultWriter.close
    seen = []

    def interrupted_close(writer):
        writer._flush()  # every row is in the temporary file
        seen.append(writer.temporary.stat().st_size)
        raise KeyboardInterrupt

    monkeypatch.setattr(ResultWriter, "close", interrupted_close)
    with pytest.raises(Interrupted, match=r"5 of 5 chunks saved in .*--resume continues"):
        sweep(PUNCH, VARY, chunk_size=4, output=out)
    assert seen and seen[0] > 0
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.parquet.parts"]
    assert sorted(p.name for p in (tmp_path / "study.parquet.parts").iterdir()) == [
        *(f"chunk-{i:05d}.parquet" for i in range(5)),
        "sweep.json",
    ]
    monkeypatch.setattr(ResultWriter, "close", original)
    done = sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert done.attrs["sweep"]["chunks_reused"] == [0, 1, 2, 3, 4]
    pd.testing.assert_frame_equal(read_results(out), whole)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.parquet"]


def test_resume_removes_temporary_files_a_kill_left_in_the_parts(tmp_path):
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=2)
    parts = tmp_path / "study.parquet.parts"
    (parts / "study.parquet.tmp-99999").write_bytes(b"PAR1 half a file")
    (parts / "chunk-00002.parquet.tmp-99999").write_bytes(b"PAR1")
    sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.parquet"]


# --------------------------------------------------------------------------
# Damaged parts
# --------------------------------------------------------------------------


def truncate(path):
    data = path.read_bytes()
    path.write_bytes(data[: len(data) // 2])


def other_chunk(path):
    path.write_bytes(path.with_name("chunk-00000.parquet").read_bytes())


def empty(path):
    path.write_bytes(b"")


@pytest.mark.parametrize(
    "damage, words",
    [
        (truncate, "cannot be read"),
        (empty, "cannot be read"),
        (other_chunk, "holds other points than its chunk"),
    ],
)
def test_resume_recomputes_a_damaged_part(tmp_path, capsys, damage, words):
    """Regression (issue 11): a truncated part file crashed --resume (pyarrow's error).
    Each part is read back and checked against its chunk; a damaged one is said in one
    line on stderr and computed again, never used."""
    out = tmp_path / "study.parquet"
    whole = sweep(PUNCH, VARY, chunk_size=4)
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=3)
    damage(tmp_path / "study.parquet.parts" / "chunk-00001.parquet")
    capsys.readouterr()
    done = sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "chunk-00001.parquet: " in err and words in err
    assert "computing chunk 1 again" in err
    assert done.attrs["sweep"]["chunks_reused"] == [0, 2]
    assert done.attrs["sweep"]["chunks_run"] == [1, 3, 4]
    pd.testing.assert_frame_equal(read_results(out), whole)


def test_part_with_missing_rows_is_recomputed(tmp_path, capsys):
    out = tmp_path / "study.parquet"
    sweep(PUNCH, VARY, chunk_size=4, output=out, max_chunks=2)
    part = tmp_path / "study.parquet.parts" / "chunk-00001.parquet"
    read_results(part).iloc[:3].to_parquet(part, index=False)
    sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert "holds 3 rows, not the chunk's 4" in capsys.readouterr().err
    pd.testing.assert_frame_equal(read_results(out), sweep(PUNCH, VARY, chunk_size=4))


# --------------------------------------------------------------------------
# Dask
# --------------------------------------------------------------------------


def test_unreachable_scheduler_is_one_line_and_leaves_nothing(tmp_path):
    """Regression (issue 11): a failed scheduler connection left a stale .parts folder
    that blocked the next run. The scheduler is connected to (within a few seconds)
    before anything is written."""
    out = tmp_path / "study.parquet"
    start = time.monotonic()
    with pytest.raises(SceneError, match="cannot connect to the Dask scheduler 'tcp://127.0.0.1:1' within 5 s") as info:
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


@pytest.mark.parametrize(
    "address",
    ["tcp://10.0.0.5:8786", "10.0.0.5:8786", "tls://sched.example.com:8786", "[::1]:1", "inproc://192.0.2.2/18458/1"],
)
def test_a_scheduler_address_of_every_form_is_taken(address):
    assert runner.scheduler_address(address) == address


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


def test_losing_every_dask_worker_stops_the_sweep(tmp_path, monkeypatch):
    """Regression (issue 11): a sweep whose Dask workers all went away waited forever.
    Without a worker for NO_WORKERS_SECONDS it stops with Interrupted, the finished
    chunks kept, and --resume (here without Dask) completes it."""
    from dask.distributed import LocalCluster

    monkeypatch.setattr(runner, "NO_WORKERS_SECONDS", 1.0)
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


def test_chunk_bounds_by_cost():
    # 60 points of 0.1 s, 2 workers: a chunk takes a quarter of what is left, at most 1 s
    # (10 points), so the chunks shrink towards the end, down to a point
    assert runner.chunk_bounds(np.full(60, 0.1), workers=2).tolist() == [
        0,
        10,
        20,
        30,
        38,
        44,
        48,
        51,
        54,
        56,
        57,
        58,
        59,
        60,
    ]
    # 10^6 closed-form points: 1 s would be 55,556 points, held to MAX_CHUNK_POINTS
    bounds = runner.chunk_bounds(np.full(1_000_000, 1.8e-5), workers=2)
    sizes = np.diff(bounds)
    assert sizes.max() == runner.MAX_CHUNK_POINTS and (sizes[:90] == sizes.max()).all()
    assert 100 < len(sizes) < 110 and sizes[-1] < sizes[-5] < sizes.max()
    # a small sweep: chunks of at least MIN_CHUNK_SECONDS (0.05 s), not of 0.01 s
    assert runner.chunk_bounds(np.full(24, 0.01), workers=2).tolist() == [0, 6, 11, 16, 21, 24]
    # the user's chunk size, cut again at the breaks
    assert runner.chunk_bounds(np.ones(10), chunk_size=4, breaks=[6]).tolist() == [0, 4, 6, 10]


def test_chunk_bounds_keep_groups_together():
    # 6 physics of 10 points; the first point of each carries its analysis (0.5 s)
    costs = np.full(60, 1e-3)
    costs[::10] += 0.5
    starts = np.zeros(60, dtype=bool)
    starts[::10] = True
    bounds = runner.chunk_bounds(costs, workers=2, starts=starts)
    assert bounds.tolist() == [0, 20, 30, 40, 50, 60]  # never a physics in two chunks
    assert runner.chunk_bounds(costs, workers=2).tolist() == [0, 11, 24, 31, 41, 51, 60]
    # a group whose designs alone outweigh a chunk is split (aim 0.125 s: 12,500 points,
    # held to MAX_CHUNK_POINTS)
    big = runner.chunk_bounds(np.full(25_000, 1e-5), starts=np.r_[True, np.zeros(24_999, bool)])
    assert big.tolist() == [0, 10_000, 17_500, 25_000]

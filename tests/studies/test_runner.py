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
import time
from pathlib import Path

import pandas as pd
import pytest
from conftest import PROBLEMS

import flyopt
from flyopt.errors import Interrupted
from flyopt.outputs.results import ResultWriter, read_results
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


@pytest.mark.slow  # 3-6 s; the default run is over its five minutes
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
    assert sorted(p.name for p in parts.iterdir()) == chunks + ["lock", "sweep.json"]  # no temporary
    assert all(re.fullmatch(r"chunk-\d{5}\.parquet", name) for name in chunks)
    assert len(chunks) == int(stdout.split("; ")[1].split(" of ")[0]) >= 1
    assert sorted(p.name for p in tmp_path.iterdir()) == ["driver.py", "study.parquet.parts"]
    resume_and_compare(tmp_path, out, uninterrupted)


@pytest.mark.slow  # 5 s; by default: Ctrl-C and resume (below), a killed slider-crank sweep resumed (test_evaluate.py)
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
        "lock",
        "sweep.json",
    ]
    monkeypatch.setattr(ResultWriter, "close", original)
    done = sweep(PUNCH, VARY, chunk_size=4, output=out, resume=True)
    assert done.attrs["sweep"]["chunks_reused"] == [0, 1, 2, 3, 4]
    pd.testing.assert_frame_equal(read_results(out), whole)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["study.parquet"]

"""SIGTERM (``kill``, a scheduler's stop) ends a command as Ctrl-C does: its temporary output removed, one line,
status 130. It killed the process at once, leaving ``NAME.tmp-PID-…`` beside the output."""

import os
import signal
import subprocess
import sys
import time

import pytest
from conftest import PROBLEMS, ROOT

# flyopt's console entry, its temporary output's close held back until SIGTERM arrives: the window in which
# a signal used to leave the temporary file behind
DRIVER = """
import sys, time
import flyopt.outputs.files as files

real_close, ready = files.Temporary.close, sys.argv[1]

def held(self):
    files.Temporary.close = real_close  # once: the clean-up closes the file again
    open(ready, "w").close()  # the temporary file is written: say so, then work on (a sleep would not see
    end = time.monotonic() + 60  # the signal at once where another thread of the process took it)
    while time.monotonic() < end:
        pass
    real_close(self)

files.Temporary.close = held
sys.argv = ["flyopt", *sys.argv[2:]]
from flyopt.cli.main import entry
sys.exit(entry())
"""


def _run_until_written(tmp_path, *args):
    ready = tmp_path / "ready"
    env = {**os.environ, "PYTHONPATH": str(ROOT / "src")}
    process = subprocess.Popen(
        [sys.executable, "-c", DRIVER, str(ready), *map(str, args)],
        cwd=tmp_path,
        env=env,
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    _wait_for(ready, process)
    return process


def _wait_for(ready, process):
    """Until the driver says its temporary output is written (then the flag is removed)."""
    deadline = time.monotonic() + 60
    while not ready.exists():
        assert process.poll() is None, process.communicate()
        assert time.monotonic() < deadline
        time.sleep(0.05)
    ready.unlink()


@pytest.mark.parametrize("command", ["solve", "report"])
def test_sigterm_while_an_output_is_written_leaves_nothing_but_one_line(tmp_path, command):
    out = tmp_path / ("r.txt" if command == "solve" else "r.html")
    process = _run_until_written(tmp_path, command, PROBLEMS / "shear-press.toml", "-o", out, "-q")
    assert [p.name for p in tmp_path.iterdir() if ".tmp-" in p.name]  # the temporary output, held open
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert err == f"flyopt: error: {PROBLEMS / 'shear-press.toml'}: interrupted\n"
    assert sorted(p.name for p in tmp_path.iterdir()) == []  # no output, no temporary


def test_sigterm_where_ctrl_c_is_ignored_cleans_up_as_well(tmp_path):
    """A job a script starts in the background (``flyopt solve ... &``) ignores Ctrl-C: SIGTERM still
    interrupts it, and its temporary output is removed."""
    out = tmp_path / "r.txt"
    ignoring = (
        "import os, signal, sys; signal.signal(signal.SIGINT, signal.SIG_IGN); "
        "os.execv(sys.executable, [sys.executable, '-c', *sys.argv[1:]])"
    )
    ready = tmp_path / "ready"
    process = subprocess.Popen(
        [sys.executable, "-c", ignoring, DRIVER, str(ready), "solve", PROBLEMS / "shear-press.toml", "-o", out, "-q"],
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    _wait_for(ready, process)
    process.send_signal(signal.SIGTERM)
    _, err = process.communicate(timeout=60)
    assert process.returncode == 130, err
    assert sorted(p.name for p in tmp_path.iterdir()) == []


def test_a_signal_after_the_status_leaves_it(tmp_path):
    """Once the command has its status, Ctrl-C and SIGTERM that arrive while the interpreter shuts down are
    ignored: SIGTERM there raised a KeyboardInterrupt's traceback and turned status 0 into 130."""
    script = (
        "import os, signal, sys\n"
        "import flyopt.cli.main as m\n"
        "m.main = lambda argv=None: 0\n"
        "status = m.entry()\n"
        "os.kill(os.getpid(), signal.SIGINT)\n"
        "os.kill(os.getpid(), signal.SIGTERM)\n"
        "print('still here', flush=True)\n"
        "sys.exit(status)\n"
    )
    done = subprocess.run(
        [sys.executable, "-c", script],
        cwd=tmp_path,
        env={**os.environ, "PYTHONPATH": str(ROOT / "src")},
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert (done.returncode, done.stdout, done.stderr) == (0, "still here\n", "")

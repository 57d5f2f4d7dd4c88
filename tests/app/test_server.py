"""`flyopt app` as a process: what it leaves behind when it is stopped."""

from __future__ import annotations

import os
import signal
import socket
import subprocess
import sys
import time
import urllib.request
from pathlib import Path

import pytest

SRC = Path(__file__).resolve().parents[2] / "src"


def _free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@pytest.mark.slow  # SIGTERM is checked by default where the browser tests' server stops (tests/app/test_browser.py)
@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_stopped_server_leaves_no_sessions_folder(how, tmp_path):
    """Each session of the app keeps the editor's text (and its sweeps' and drawings' files) in a private
    temporary folder, removed when the session ends. A server stopped with sessions open (Ctrl-C, or SIGTERM
    from a service manager) left every such folder, the user's scene in it, in the temporary directory; now it
    removes them as it stops (the temporary directory is this test's own, by TMPDIR)."""
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    port = _free_port()
    env = {
        **os.environ,
        "TMPDIR": str(tmp_path),
        "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
    }
    process = subprocess.Popen(
        [sys.executable, "-m", "flyopt", "app", "--port", str(port), "--no-browser"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    try:
        for _ in range(600):  # the page's first request makes a session, and its folder
            try:
                urllib.request.urlopen(f"http://127.0.0.1:{port}/", timeout=60).close()
                break
            except OSError:
                if process.poll() is not None:
                    raise RuntimeError(process.stderr.read().decode()) from None
                time.sleep(0.1)
        assert len(list(tmp_path.glob("flyopt-app-*"))) == 1
        process.send_signal(how)
        process.wait(30)
    finally:
        if process.poll() is None:
            process.kill()
            process.wait(10)
        process.stderr.close()
    assert list(tmp_path.glob("flyopt-app-*")) == []

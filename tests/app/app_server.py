"""`flyopt app` started as a user starts it, for the tests that need a real server."""

from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import time
import urllib.request
from collections.abc import Iterator
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


@contextlib.contextmanager
def served(temporary: Path) -> Iterator[tuple[str, subprocess.Popen[bytes]]]:
    """(url, process) of ``flyopt app`` on a free port, its temporary directory ``temporary`` (TMPDIR), once it
    answers (its first request makes a session); stopped by SIGTERM on leaving, or killed if it is still up."""
    port = free_port()
    env = {
        **os.environ,
        "TMPDIR": str(temporary),
        "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
    }
    process = subprocess.Popen(
        [sys.executable, "-m", "flyopt", "app", "--port", str(port), "--no-browser"],
        env=env,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.PIPE,
    )
    url = f"http://127.0.0.1:{port}/"
    try:
        for _ in range(600):
            try:
                # a loaded host answers the page's first request in seconds; each request that timed out would
                # leave one more session to build on the server
                urllib.request.urlopen(url, timeout=60).close()
                break
            except OSError:
                if process.poll() is not None:
                    assert process.stderr is not None
                    raise RuntimeError(process.stderr.read().decode()) from None
                time.sleep(0.1)
        yield url, process
    finally:
        if process.poll() is None:
            process.terminate()
        try:
            process.wait(30)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(10)
        assert process.stderr is not None
        process.stderr.close()

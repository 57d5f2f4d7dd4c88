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


def stderr_log(temporary: Path) -> Path:
    """The file a server :func:`served` with the temporary directory ``temporary`` writes its stderr to."""
    return temporary.parent / f"{temporary.name}-stderr.log"


@contextlib.contextmanager
def served(temporary: Path, stderr: list[str] | None = None) -> Iterator[tuple[str, subprocess.Popen[bytes]]]:
    """(url, process) of ``flyopt app`` on a free port, its temporary directory ``temporary`` (TMPDIR), once it
    answers (its first request makes a session); stopped by SIGTERM on leaving, or killed if it is still up.

    What the server wrote on its stderr goes to a file beside ``temporary`` (a pipe nobody reads would stop the
    server once full) and, once it has stopped, is appended to ``stderr`` where given."""
    port = free_port()
    log_path = stderr_log(temporary)
    env = {
        **os.environ,
        "TMPDIR": str(temporary),
        "PYTHONPATH": f"{SRC}{os.pathsep}{os.environ.get('PYTHONPATH', '')}",
    }
    with open(log_path, "wb") as log:  # the server writes to its own copy of the handle; this one closes here
        process = subprocess.Popen(
            [sys.executable, "-m", "flyopt", "app", "--port", str(port), "--no-browser"],
            env=env,
            stdout=subprocess.DEVNULL,
            stderr=log,
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
                    raise RuntimeError(log_path.read_text(encoding="utf-8", errors="replace")) from None
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
        if stderr is not None:
            stderr.append(log_path.read_text(encoding="utf-8", errors="replace"))

"""`flyopt app` as a process: what it leaves behind when it is stopped."""

from __future__ import annotations

import signal

import pytest

from tests.app.app_server import served


@pytest.mark.slow  # SIGTERM is checked by default where the browser tests' server stops (tests/app/test_browser.py)
@pytest.mark.parametrize("how", [signal.SIGTERM, signal.SIGINT], ids=["SIGTERM", "SIGINT"])
def test_a_stopped_server_leaves_no_sessions_folder(how, tmp_path):
    """Each session of the app keeps the editor's text (and its sweeps' and drawings' files) in a private
    temporary folder, removed when the session ends. A server stopped with sessions open (Ctrl-C, or SIGTERM
    from a service manager) left every such folder, the user's scene in it, in the temporary directory; now it
    removes them as it stops (the temporary directory is this test's own, by TMPDIR)."""
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    with served(tmp_path) as (_, process):
        assert len(list(tmp_path.glob("flyopt-app-*"))) == 1
        process.send_signal(how)
        process.wait(30)
    assert list(tmp_path.glob("flyopt-app-*")) == []

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


def test_a_write_to_a_closed_connection_is_not_printed_and_anything_else_is():
    """A browser tab closed while the server still sends it an edit's diagrams leaves Tornado's
    WebSocketClosedError (or StreamClosedError) in a task nobody awaits; asyncio printed it with a traceback.
    The server's handler drops those and hands every other exception to asyncio's own handler."""
    pytest.importorskip("tornado", reason="the app extra (panel, tornado) is not installed")
    from tornado.iostream import StreamClosedError
    from tornado.websocket import WebSocketClosedError

    from flyopt.app.page import closed_connection_handler

    seen: list[dict] = []

    class Loop:
        def default_exception_handler(self, context):
            seen.append(context)

    for error in (WebSocketClosedError(), StreamClosedError()):
        closed_connection_handler(Loop(), {"message": "Task exception was never retrieved", "exception": error})
    assert seen == []
    other = {"message": "Task exception was never retrieved", "exception": ValueError("a bug of the app")}
    plain = {"message": "an error without an exception"}
    closed_connection_handler(Loop(), other)
    closed_connection_handler(Loop(), plain)
    assert seen == [other, plain]


def test_the_server_runs_on_a_loop_with_that_handler(monkeypatch):
    """`flyopt app` serves on an asyncio loop whose exception handler is the one above (Panel's serve, stubbed
    here, runs Tornado's IOLoop on this thread's asyncio loop)."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio

    from flyopt.app import model, page

    seen = []

    def serve(*args, **kwargs):
        loop = asyncio.get_event_loop()
        seen.append((loop, loop.get_exception_handler()))

    monkeypatch.setattr(pn, "serve", serve)
    monkeypatch.setattr(pn, "extension", lambda *args, **kwargs: None)  # Panel's global config left as it is
    monkeypatch.setattr(model, "serving", lambda host: None)
    monkeypatch.setattr(model, "close_workspaces", lambda: None)  # this process's other workspaces left open
    previous = signal.getsignal(signal.SIGTERM)
    try:
        page.serve(0, "127.0.0.1", browser=False)
    finally:
        signal.signal(signal.SIGTERM, previous)
    ((loop, handler),) = seen
    assert handler is page.closed_connection_handler
    asyncio.set_event_loop(None)
    loop.close()


@pytest.mark.slow  # a server of its own; the rules are checked without one in test_address.py by default
def test_a_rebound_name_builds_no_session_by_the_page_nor_by_a_forged_websocket_token(tmp_path):
    """DNS rebinding: another site's name pointed at 127.0.0.1. The page asked for by that name builds no
    session; nor does the app's websocket opened by that page's script with a session token it wrote naming
    Host 127.0.0.1 (an outside review: the tokens were not signed, and Bokeh reads the session's headers from
    them; the websocket of a page's own origin is let in whatever the origins list holds)."""
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio
    import json
    import urllib.request

    from bokeh.util.token import generate_jwt_token, generate_session_id
    from tornado.httpclient import HTTPRequest
    from tornado.iostream import StreamClosedError
    from tornado.websocket import WebSocketClosedError, websocket_connect

    with served(tmp_path) as (url, _):
        port = int(url.rstrip("/").rpartition(":")[2])
        sessions = lambda: len(list(tmp_path.glob("flyopt-app-*")))  # noqa: E731
        assert sessions() == 1  # the helper's own first request
        request = urllib.request.Request(url, headers={"Host": f"attacker.example:{port}"})
        urllib.request.urlopen(request, timeout=60).close()
        assert sessions() == 1

        async def forged() -> str:
            token = generate_jwt_token(
                generate_session_id(), signed=False, extra_payload={"headers": {"Host": f"127.0.0.1:{port}"}}
            )
            rebound = {"Host": f"attacker.example:{port}", "Origin": f"http://attacker.example:{port}"}
            try:
                ws = await websocket_connect(
                    HTTPRequest(f"ws://127.0.0.1:{port}/ws", headers=rebound), subprotocols=["bokeh", token]
                )
            except Exception as err:  # noqa: BLE001 -- refused at the handshake: what is wanted
                return f"refused: {err}"
            pulled = ""
            try:
                for part in (json.dumps({"msgid": "1", "msgtype": "PULL-DOC-REQ"}), "{}", "{}"):
                    await ws.write_message(part)
                while (message := await asyncio.wait_for(ws.read_message(), 20)) is not None:
                    pulled += message if isinstance(message, str) else ""
            except (asyncio.TimeoutError, WebSocketClosedError, StreamClosedError):
                pass  # the server closed it (an invalid token's signature), or sent all it had
            ws.close()
            return pulled

        pulled = asyncio.run(forged())
        assert "Template (problems/)" not in pulled, "the forged token's session was built"
        assert sessions() == 1

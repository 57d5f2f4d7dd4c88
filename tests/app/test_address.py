"""``flyopt app --host``: which addresses are taken, which are this machine's alone, and the origins the
server's websocket takes, each a value Bokeh's own list accepts (``::1`` and ``''`` used to stop the server
with Bokeh's "Invalid host value" and "Empty host value", exit 1, after it said where it was serving)."""

from __future__ import annotations

import socket

import pytest

from flyopt.app import address


@pytest.mark.parametrize("host", ["127.0.0.1", "0.0.0.0", "localhost", "127.0.0.2"])
def test_an_ipv4_address_or_a_name_that_resolves_is_taken_as_written(host):
    assert address.checked_host(host) == host


@pytest.mark.parametrize(
    ("text", "said"),
    [
        ("::1", "is an IPv6 address"),
        ("[::1]", "is an IPv6 address"),
        ("::", "is an IPv6 address"),
        ("", "is not an address"),
        ("no such host!", "is not an address"),
        ("a..b", "is not an address"),
        ("-x", "is not an address"),
        ("x" * 64, "is not an address"),
        ("http://localhost", "is not an address"),
        ("nowhere.invalid", "names no address"),  # RFC 6761: .invalid never resolves
        ("127.1", "write an IPv4 address in full"),  # the C library's short form, taken as a name
        ("0", "write an IPv4 address in full"),
    ],
)
def test_anything_else_is_refused_saying_what_is_allowed(text, said):
    with pytest.raises(ValueError, match="^--host: ") as caught:
        address.checked_host(text)
    message = str(caught.value)
    assert said in message and repr(text) in message and "127.0.0.1" in message and "\n" not in message


def test_a_name_is_taken_in_lower_case():
    assert address.checked_host("LOCALHOST") == "localhost"
    assert address.local(address.checked_host("LocalHost"))


@pytest.mark.parametrize(
    ("host", "local"),
    [("127.0.0.1", True), ("127.0.0.2", True), ("localhost", True), ("0.0.0.0", False), ("192.0.2.7", False)],
)
def test_only_the_loopback_serves_this_machine_alone(host, local):
    assert address.local(host) is local


def test_the_origins_are_the_served_address_and_the_loopback_names():
    assert address.origins("127.0.0.1", 5006) == ["127.0.0.1:5006", "localhost:5006"]
    assert address.origins("192.0.2.7", 80) == ["192.0.2.7:80", "localhost:80", "127.0.0.1:80"]


@pytest.mark.parametrize("host", ["127.0.0.1", "localhost", "0.0.0.0", "192.0.2.7"])
def test_bokeh_takes_every_origin_given(host):
    util = pytest.importorskip("bokeh.server.util", reason="the app extra (panel, bokeh) is not installed")
    origins = address.origins(host, 5006)
    assert util.create_hosts_allowlist(origins, 5006) == origins
    assert util.check_allowlist(f"{host}:5006", origins)


@pytest.mark.parametrize("host", ["::1", "", "no such host!"])
def test_flyopt_app_refuses_a_bad_host_in_one_line_before_serving(host, monkeypatch, capsys):
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app import page
    from flyopt.cli.main import main

    monkeypatch.setattr(page, "serve", lambda *args: pytest.fail("served"))
    assert main(["app", "--host", host, "--no-browser"]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("flyopt: error: --host: ") and "Traceback" not in err


def test_flyopt_app_serves_the_checked_host(monkeypatch, capsys):
    pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app import page
    from flyopt.cli.main import main

    served = []
    monkeypatch.setattr(page, "serve", lambda *args: served.append(args))
    assert main(["app", "--host", "0.0.0.0", "--port", "5123", "--no-browser"]) == 0
    assert served == [(5123, "0.0.0.0", False)]
    err = capsys.readouterr().err
    assert "anyone who can reach this address" in err and "http://0.0.0.0:5123/" in err


SERVED = address.served_names("127.0.0.1")
TYPED = {"Host": "127.0.0.1:5006", "Sec-Fetch-Site": "none", "Sec-Fetch-Mode": "navigate", "Sec-Fetch-Dest": "document"}


def test_the_served_names_are_the_host_and_this_machine_s_own():
    assert address.served_names("Workstation.LAN") >= {"workstation.lan", socket.gethostname().lower()}


@pytest.mark.parametrize(
    "headers",
    [
        TYPED,  # the address typed, or opened by flyopt app
        {**TYPED, "Sec-Fetch-Site": "same-origin"},  # reloaded
        {**TYPED, "Host": "localhost:5006"},
        {**TYPED, "Host": "LOCALHOST:5006"},
        {**TYPED, "Host": "localhost:8080"},  # a port forward (ssh -L, docker -p): any port
        {**TYPED, "Host": "192.0.2.7:5006"},  # served on 0.0.0.0, opened by the machine's LAN address
        {**TYPED, "Host": f"{socket.gethostname()}:5006"},  # ... or by its name
        {**TYPED, "Host": "[::1]:5006"},
        {**TYPED, "Host": "127.0.0.1"},  # port 80
        {**TYPED, "Sec-Fetch-Site": "cross-site", "Sec-Fetch-User": "?1"},  # a link on another page, clicked
        {"host": "127.0.0.1:5006"},  # a script or curl: no Sec-Fetch-* headers
        {},
    ],
)
def test_a_page_the_user_opens_builds_a_session(headers):
    assert address.refused_request(headers, SERVED) is None


@pytest.mark.parametrize(
    ("headers", "said"),
    [
        ({**TYPED, "Host": "attacker.example:5006"}, "not served as attacker.example:5006"),  # DNS rebinding
        ({**TYPED, "Host": "attacker.example"}, "not served as attacker.example"),
        ({**TYPED, "Host": "127.0.0.1.attacker.example:5006"}, "not served as"),
        ({"Host": "127.0.0.1:5006", "Sec-Fetch-Site": "cross-site", "Sec-Fetch-Dest": "image"}, "another site"),
        ({**TYPED, "Sec-Fetch-Site": "cross-site"}, "another site"),  # navigated by a script, no click
        ({**TYPED, "Sec-Fetch-Site": "same-site", "Sec-Fetch-Dest": "iframe", "Sec-Fetch-User": "?1"}, "another"),
    ],
)
def test_a_request_another_site_made_builds_none(headers, said):
    refused = address.refused_request(headers, SERVED)
    assert refused is not None and said in refused


def test_the_server_refuses_another_site_s_request_without_building_a_session(monkeypatch):
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    from flyopt.app import page

    built = []
    monkeypatch.setattr(page, "SERVED_NAMES", set(SERVED))
    monkeypatch.setattr(page, "Session", lambda pn: built.append(pn))
    monkeypatch.setattr(type(pn.state), "headers", property(lambda _self: {"Host": "attacker.example:5006"}))
    shown = page.session()
    assert built == [] and "not served as attacker.example:5006" in shown.object


def test_the_sessions_are_signed_so_that_a_script_cannot_forge_the_headers_they_carry(monkeypatch):
    """Bokeh puts the page request's headers into the session's token, and the session reads them from there:
    an unsigned token a rebound name's script wrote, naming Host 127.0.0.1, built a whole session."""
    pn = pytest.importorskip("panel", reason="the app extra (panel) is not installed")
    import asyncio
    import signal

    from flyopt.app import model, page

    given = {}
    monkeypatch.setattr(pn, "serve", lambda *args, **kwargs: given.update(kwargs))
    monkeypatch.setattr(pn, "extension", lambda *args, **kwargs: None)
    monkeypatch.setattr(model, "serving", lambda host: None)
    monkeypatch.setattr(model, "close_workspaces", lambda: None)
    previous = signal.getsignal(signal.SIGTERM)
    try:
        page.serve(0, "127.0.0.1", browser=False)
    finally:
        signal.signal(signal.SIGTERM, previous)
        loop = asyncio.get_event_loop()
        asyncio.set_event_loop(None)
        loop.close()
    assert given["sign_sessions"] is True and len(given["secret_key"]) >= 32
    from bokeh.util.token import check_token_signature, generate_jwt_token, generate_session_id

    forged = generate_jwt_token(generate_session_id(), signed=False, extra_payload={"headers": {"Host": "x"}})
    assert not check_token_signature(forged, secret_key=given["secret_key"].encode(), signed=True)

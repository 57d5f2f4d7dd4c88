"""The address the app is served on: which ``--host`` is taken, whether it is this machine's alone, the
origins whose pages may open the app's websocket, and which requests for the page build a session.

Standard library only: ``flyopt app`` checks its options with it before Panel is imported. Every command's
parser reads :data:`DEFAULT`, so ``ipaddress`` and ``socket`` are imported where they are used.
"""

from __future__ import annotations

import re
from collections.abc import Collection, Mapping
from typing import Any

#: The address served unless ``--host`` says otherwise.
DEFAULT = "127.0.0.1"

#: The names, besides the loopback addresses (127.0.0.0/8), that reach this machine alone.
LOOPBACK_NAMES = frozenset({"localhost"})

#: A host name: dot-separated labels of letters, digits and inner hyphens, 63 characters at most each
#: (RFC 1123), 253 in all.
_LABEL = re.compile(r"(?!-)[A-Za-z0-9-]{1,63}(?<!-)")
_LONGEST_NAME = 253


def checked_host(text: str) -> str:
    """``--host`` as served: an IPv4 address or a host name that resolves; ValueError saying what is allowed
    for anything else. An IPv6 address is refused: the server's list of the origins its websocket takes
    (Bokeh's) cannot hold one, and refused ``::1`` when the page was served."""
    import ipaddress
    import socket

    allowed = "an IPv4 address such as 127.0.0.1, or a host name of this machine such as localhost"
    try:
        address = ipaddress.ip_address(text.removeprefix("[").removesuffix("]"))
    except ValueError:
        pass
    else:
        if address.version == 6:
            raise ValueError(f"--host: {text!r} is an IPv6 address, which the app's server cannot take: {allowed}")
        return str(address)
    labels = text.rstrip(".").split(".")
    if not text or len(text) > _LONGEST_NAME or not all(_LABEL.fullmatch(label) for label in labels):
        raise ValueError(f"--host: {text!r} is not an address: {allowed}")
    if labels[-1].isdigit():  # 127.1, 0: the C library's short forms of an address, not names (RFC 1123)
        raise ValueError(f"--host: {text!r} is not an address (write an IPv4 address in full): {allowed}")
    try:
        socket.getaddrinfo(text, None)
    except (OSError, UnicodeError):
        raise ValueError(f"--host: {text!r} names no address this machine can find: {allowed}") from None
    return text.lower()  # a name's case means nothing (LOCALHOST is localhost)


def local(host: str) -> bool:
    """Whether ``host`` (as :func:`checked_host` gives it) serves this machine alone."""
    import ipaddress

    if host in LOOPBACK_NAMES:
        return True
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return False


def origins(host: str, port: int) -> list[str]:
    """The ``host:port`` of the pages that may open the app's websocket from another origin (Bokeh's list):
    the served address and this machine's loopback names. The page's own websocket is of its own origin, which
    Tornado lets in whatever the list holds (a port forward's, a LAN address's); a page of another origin needs
    to be on this list, and none is."""
    names = [host, "localhost", "127.0.0.1"]
    return list(dict.fromkeys(f"{name}:{port}" for name in names))


def _host_name(host: str) -> str:
    """The name or address of a ``Host`` header, without its port (an IPv6 address without its brackets)."""
    host = host.strip().lower()
    if host.startswith("["):
        return host[1:].partition("]")[0]
    return host.rpartition(":")[0] if host.count(":") == 1 else host


def _named_by_address(name: str) -> bool:
    """Whether ``name`` is an IP address or ``localhost``: what no other site can point at this machine."""
    import ipaddress

    try:
        ipaddress.ip_address(name)
    except ValueError:
        return name in LOOPBACK_NAMES
    return True


def served_names(host: str) -> frozenset[str]:
    """The names a request for the page may give in its ``Host`` besides an address and ``localhost``: the name
    it is served as (``--host``) and this machine's own (what colleagues type when it is served on 0.0.0.0)."""
    import socket

    return frozenset(name.lower() for name in (host, socket.gethostname(), socket.getfqdn()) if name)


def refused_request(headers: Mapping[str, Any], names: Collection[str]) -> str | None:
    """Why the page's request with ``headers`` builds no session, or None for one that may; ``names`` are
    :func:`served_names`.

    Every request for the page builds a whole session (its widgets, its private folder). A name of another
    site's pointed at this machine (DNS rebinding) could load the app, so the ``Host`` must name it by an
    address (127.0.0.1, a LAN address, through a port forward on any port), ``localhost``, the name it is
    served as (``--host``) or this machine's own name; a proxy must pass one of those. A page of another site could make the user's
    browser ask for it many times (``<img src="http://127.0.0.1:5006/">``), so a request the browser says
    another site made (``Sec-Fetch-Site``) is refused, unless it opens a page the user clicked to
    (a navigation to a document with ``Sec-Fetch-User``). Browsers send ``Sec-Fetch-*`` to localhost and to
    HTTPS only: a page served over HTTP on a LAN address is not guarded so (docs/app.md, Security). A client
    that sends none (a script, curl) is not a browser led by another site, and is let in as before.
    """
    named = {str(key).lower(): str(value) for key, value in headers.items()}
    host = named.get("host")
    if host is not None:
        name = _host_name(host)
        if not (_named_by_address(name) or name in names):
            return f"this app is not served as {host}: open it by this machine's address or name, or localhost"
    site = named.get("sec-fetch-site", "none")
    if site in ("none", "same-origin"):
        return None
    opened = (
        named.get("sec-fetch-mode") == "navigate"
        and named.get("sec-fetch-dest") == "document"
        and named.get("sec-fetch-user") == "?1"
    )
    return None if opened else "a page of another site asked for this app: open it yourself"

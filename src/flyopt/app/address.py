"""The address the app is served on: which ``--host`` is taken, whether it is this machine's alone, the
origins whose pages may open the app's websocket, and which requests for the page build a session.

Standard library only: ``flyopt app`` checks its options with it before Panel is imported. Every command's
parser reads :data:`DEFAULT`, so ``ipaddress`` and ``socket`` are imported where they are used.
"""

from __future__ import annotations

import re
from collections.abc import Mapping, Sequence
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
    try:
        socket.getaddrinfo(text, None)
    except (OSError, UnicodeError):
        raise ValueError(f"--host: {text!r} names no address this machine can find: {allowed}") from None
    return text


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
    """The ``host:port`` a page must come from to open the app's websocket: the served address and this
    machine's loopback names; for the address of every interface (0.0.0.0), this machine's own names and IPv4
    addresses too, which is what the others who may use it type."""
    import socket

    names = [host, "localhost", "127.0.0.1"]
    if host == "0.0.0.0":
        for name in sorted({socket.gethostname(), socket.getfqdn()}):
            names.append(name)
            try:
                names += sorted({str(info[4][0]) for info in socket.getaddrinfo(name, None, socket.AF_INET)})
            except OSError:
                continue
    return list(dict.fromkeys(f"{name}:{port}" for name in names if name and ":" not in name))


def refused_request(headers: Mapping[str, Any], allowed: Sequence[str]) -> str | None:
    """Why the page's request with ``headers`` builds no session, or None for one that may.

    Every request for the page builds a whole session (its widgets, its private folder). A page of another
    site could make the user's browser ask for it many times (``<img src="http://127.0.0.1:5006/">``), and a
    name of another site's pointed at this machine (DNS rebinding) could load it. So a request is refused when
    its ``Host`` is not one of ``allowed`` (:func:`origins`), and when the browser says it comes from another
    site (``Sec-Fetch-Site``) other than as a page the user opened by a click (a navigation to a document with
    ``Sec-Fetch-User``). A client that sends no ``Sec-Fetch-*`` headers (a script, curl) is not a browser led by
    another site, and is let in as before.
    """
    named = {str(key).lower(): str(value) for key, value in headers.items()}
    host = named.get("host")
    if host is not None and (host if ":" in host else f"{host}:80").lower() not in {a.lower() for a in allowed}:
        return f"this app is served as {allowed[0]}, not {host}"
    site = named.get("sec-fetch-site", "none")
    if site in ("none", "same-origin"):
        return None
    opened = (
        named.get("sec-fetch-mode") == "navigate"
        and named.get("sec-fetch-dest") == "document"
        and named.get("sec-fetch-user") == "?1"
    )
    return None if opened else "a page of another site asked for this app: open it yourself"

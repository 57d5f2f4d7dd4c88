"""``flyopt app``: serve the local web app (the ``app`` extra: Panel).

::

    flyopt app [--port N] [--host H] [--no-browser]

Serves on 127.0.0.1 unless ``--host`` names another address (IPv4 or a host name that resolves:
:mod:`flyopt.app.address`), which is the
user's explicit choice and is said on stderr (anyone who can reach it can
use the app). Without the extra it refuses in one line naming
``pip install "flyopt[app]"`` (exit 2).
"""

from __future__ import annotations

import argparse

from flyopt.app.address import DEFAULT


def add_app_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt app``; the handler is :func:`run_app`."""
    parser.add_argument("--port", type=int, default=5006, metavar="N", help="the port to serve on (default 5006)")
    parser.add_argument(
        "--host",
        default=DEFAULT,
        metavar="H",
        help=f"the address to serve on (default {DEFAULT}: this machine only); another address lets others in",
    )
    parser.add_argument("--no-browser", action="store_true", help="do not open the app in the browser")
    parser.set_defaults(run=run_app)


def run_app(args: argparse.Namespace) -> int:
    """``flyopt app``: serve until interrupted; 2 without the ``app`` extra, or with a bad port or host."""
    import importlib.util
    import sys

    from flyopt.app import address
    from flyopt.cli.exits import EXIT_INPUT, EXIT_OK, fail

    if importlib.util.find_spec("panel") is None:
        return fail('flyopt app needs the app extra: pip install "flyopt[app]"', EXIT_INPUT)
    if not 0 < args.port < 65536:
        return fail(f"--port: {args.port} is not a port (1 to 65535)", EXIT_INPUT)
    try:
        host = address.checked_host(args.host)
    except ValueError as err:
        return fail(str(err), EXIT_INPUT)
    if not address.local(host):
        print(
            f"flyopt: note: serving on {host}, not {DEFAULT}: anyone who can reach this address can use the app",
            file=sys.stderr,
        )
    from flyopt.app.page import serve

    print(f"flyopt app on http://{host}:{args.port}/ (Ctrl-C stops it)", file=sys.stderr)
    serve(args.port, host, not args.no_browser)
    return EXIT_OK

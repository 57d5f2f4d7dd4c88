"""``flyopt new KIND [-o FILE]``: a commented template scene to start from.

The templates are package data (``flyopt/data/templates/KIND.toml``); each
loads, solves and validates against the scene schema (tests/cli/test_new.py).
"""

from __future__ import annotations

import argparse
from importlib import resources

from flyopt.cli.exits import EXIT_OK

__all__ = ["TEMPLATES", "template", "add_new_arguments", "run_new"]

TEMPLATES = {
    "press": "a press from its process data (strokes, energy per stroke, slowdown)",
    "engine": "a reciprocating engine from its indicator diagram ([engine])",
    "motor": "a machine driven by an induction motor (the periodic model)",
    "wheel": "a whole wheel to build: rim, web and hub sized by stress",
}
"""The kinds of template, each a file ``flyopt/data/templates/KIND.toml``, with what it describes."""


def template(kind: str) -> str:
    """The text of the template scene ``kind`` (one of :data:`TEMPLATES`)."""
    if kind not in TEMPLATES:
        raise ValueError(f"no template {kind!r} (known: {', '.join(TEMPLATES)})")
    return resources.files("flyopt").joinpath("data", "templates", f"{kind}.toml").read_text(encoding="utf-8")


def add_new_arguments(parser: argparse.ArgumentParser) -> None:
    """The options of ``flyopt new``; the handler is :func:`run_new`."""
    parser.add_argument(
        "kind",
        choices=tuple(TEMPLATES),
        help="; ".join(f"{kind}: {text}" for kind, text in TEMPLATES.items()),
    )
    parser.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="write the template to FILE (atomically; its folder must exist) instead of stdout",
    )
    parser.add_argument("--force", action="store_true", help="replace FILE if it exists")
    parser.add_argument(
        "-q",
        "--quiet",
        action="store_true",
        help="print nothing but errors (no 'wrote FILE'); the template still goes to FILE or stdout",
    )
    parser.set_defaults(run=run_new)


def run_new(args: argparse.Namespace) -> int:
    """``flyopt new``: the template on stdout, or written to ``-o FILE`` (refused when FILE exists, unless --force)."""
    from flyopt.errors import SceneError

    if args.output is None and args.force:  # it would be dropped: nothing is replaced on standard output
        raise SceneError("--force", "replaces the file -o/--output names, which is not given (the template is printed)")
    text = template(args.kind)
    if args.output is None:
        print(text, end="")
        return EXIT_OK
    import os

    from flyopt.outputs.files import check_folder, write_text

    check_folder(args.output, "-o/--output")
    if not args.output.lower().endswith(".toml"):
        raise SceneError("-o/--output", f"{args.output!r}: a scene is written as TOML, to a .toml file")
    if os.path.lexists(args.output) and not args.force:
        raise SceneError("-o/--output", f"{args.output!r} exists: pass --force to replace it, or name another file")
    write_text(args.output, text)
    if not args.quiet:
        print(f"wrote {args.output}")
    return EXIT_OK

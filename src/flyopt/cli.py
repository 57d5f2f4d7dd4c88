"""Command line: ``flyopt solve SCENE.toml [--json]`` and ``flyopt check SCENE.toml``.

Bad input ends with one line on stderr naming the file, the field and what is
allowed, and exit status 2; nothing is printed on stdout before the whole
result is ready.
"""

import argparse
import json
import sys

from . import __version__
from .analysis import analyse
from .errors import NonPeriodicCycle, SceneError, SolverFailed
from .scene import load

EXIT_OK, EXIT_FAILED, EXIT_INPUT = 0, 1, 2


def main(argv=None):
    """Entry point of the ``flyopt`` command; returns the exit status."""
    parser = _parser()
    args = parser.parse_args(argv)
    try:
        return args.run(args)
    except SceneError as err:
        return _fail(str(err), EXIT_INPUT)
    except NonPeriodicCycle as err:
        return _fail(str(err), EXIT_INPUT)
    except SolverFailed as err:
        return _fail(f"{args.scene}: {err}", EXIT_FAILED)
    except ArithmeticError as err:
        return _fail(f"{args.scene}: {err}", EXIT_FAILED)


def _parser():
    parser = argparse.ArgumentParser(prog="flyopt", description="Flywheel design for speed regulation.")
    parser.add_argument("--version", action="version", version=f"flyopt {__version__}")
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    solve = commands.add_parser("solve", help="analyse a scene's cycle and size its flywheel")
    solve.add_argument("scene", help="scene file (TOML)")
    solve.add_argument("--json", action="store_true", help="print one JSON object, all numbers in SI")
    solve.set_defaults(run=_solve)

    check = commands.add_parser("check", help="check a scene file and say what is wrong")
    check.add_argument("scene", help="scene file (TOML)")
    check.set_defaults(run=_check)
    return parser


def _solve(args):
    scene = load(args.scene)
    result = analyse(scene)
    if args.json:
        text = json.dumps({"scene": args.scene, **result.to_dict()}, indent=2, allow_nan=False)
    else:
        from .report import analysis_report

        text = analysis_report(result, args.scene)
    print(text)
    return EXIT_OK


def _check(args):
    scene = load(args.scene)
    analyse(scene)  # a cycle that does not close is an input error too
    print(f"{args.scene}: ok ({scene.title})")
    return EXIT_OK


def _fail(message, status):
    print(f"flyopt: error: {message}", file=sys.stderr)
    return status


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())

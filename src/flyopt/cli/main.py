"""The ``flyopt`` command: one argparse tree, one error handler.

::

    flyopt solve SCENE.toml [--json] [--verify] [-o FILE] ...   analyse and design
    flyopt check SCENE.toml                                     check a scene file
    flyopt plot SCENE.toml|RESULTS --what DIAGRAM -o FILE
    flyopt report SCENE.toml -o FILE [--units SYSTEM]           the engineering report (.html, .pdf)
    flyopt export SCENE.toml -o FILE                            the wheel's drawing (.dxf, .svg, .pdf)
    flyopt sweep | pareto | tradeoff SCENE.toml [-o FILE] ...   design studies
    flyopt new KIND [-o FILE] [--force]                         a commented template scene
    flyopt materials [--units SYSTEM] [--json]                  the built-in material library
    flyopt bench ...                                            speed against error
    flyopt app [--port N] [--host H] [--no-browser]             the local web app (app extra)
    flyopt --version

Each subcommand's handler (``args.run``) returns an exit status from the
table in :mod:`flyopt.cli.exits`; :func:`flyopt.cli.exits.run` runs it and
says what it raises in one line.
Nothing is printed on stdout before the whole result is ready.

Two conventions hold for every command (bench has its own options):

``-o FILE``
    The result goes to FILE, written atomically (a temporary file beside it,
    moved into place when complete: an error or Ctrl-C leaves no half-written
    file); its folder must exist. ``solve`` writes there what it would print,
    the text report or (``--json``) the JSON document.
``-q``, ``--quiet``
    Nothing but errors on stderr, and the result: in the ``-o`` file, or on
    stdout when there is no file (``solve`` and ``sweep`` without ``-o``
    print their result as usual). Progress lines, summaries, "wrote FILE"
    and ``check``'s "ok" are left out; the exit status still says how it went.

``--version`` reads the version from the installed package's metadata
(:data:`flyopt.__version__`) only when asked, so the argparse tree costs
nothing for it.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import signal
import sys
from collections.abc import Callable, Sequence
from typing import Any

from flyopt.cli.exits import EXIT_INPUT, OneLineParser, run, sigterm_as_ctrl_c


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of the ``flyopt`` command; returns the exit status.

    Parameters
    ----------
    argv : list of str, optional
        The arguments after ``flyopt`` (default: ``sys.argv[1:]``).

    Returns
    -------
    int
        An exit status of :mod:`flyopt.cli.exits`. Bad options exit through
        argparse (status 2, one error line).
    """
    return run(_parser(), argv)


def entry() -> int:
    """The ``flyopt`` console script and ``python -m flyopt``: :func:`main`, then exit quietly.

    The console's streams write what their encoding lacks in ASCII (:func:`flyopt.cli.console.fit_streams`).
    SIGTERM (``kill``, a scheduler's stop) is a Ctrl-C (:func:`~flyopt.cli.exits.sigterm_as_ctrl_c`): the
    command ends as interrupted (status 130), its temporary files removed. Once the command has its status
    the work is over: a Ctrl-C or SIGTERM that arrives while the interpreter shuts down would only replace
    that status by death by signal (or a KeyboardInterrupt's traceback), so both are ignored from then on.
    """
    from flyopt.cli.console import fit_streams

    fit_streams()  # a console that cannot show ω or kg·m² gets them in ASCII, not an encoding error
    signal.signal(signal.SIGTERM, sigterm_as_ctrl_c)
    status = main()
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    return status


def _parser() -> argparse.ArgumentParser:
    from flyopt.cli import app, export, materials, new, plot, report, scene, studies

    parser = OneLineParser(
        prog="flyopt",
        description="Flywheel design for speed regulation.",
        epilog="exit status: 0 ok, 1 solver failed or design failed its check, 2 bad input, "
        "3 infeasible, 4 verification flagged, 5 an output could not be written, 130 interrupted (Ctrl-C, SIGTERM), "
        "141 stdout closed early "
        "(see flyopt.cli.exits)",
    )
    parser.add_argument("--version", action=_Version)
    commands = parser.add_subparsers(dest="command", required=True, metavar="COMMAND")

    solve = commands.add_parser("solve", help="analyse a scene's cycle and size its flywheel")
    scene.add_solve_arguments(solve)
    solve.add_argument(
        "-o",
        "--output",
        metavar="FILE",
        help="write the report (or with --json the JSON) to FILE instead of stdout, atomically; its folder must exist",
    )
    studies.add_quiet_argument(solve)
    solve.set_defaults(run=_printed_to_file(solve.get_default("run")))
    for name, add, text in (
        ("check", scene.add_check_arguments, "check a scene file and say what is wrong"),
        ("plot", plot.add_plot_arguments, "draw a diagram of a scene, or of sweep/Pareto results (png, svg, pdf)"),
        (
            "report",
            report.add_report_arguments,
            "the engineering report of a scene: one self-contained HTML or PDF file",
        ),
        (
            "export",
            export.add_export_arguments,
            "the manufacturing drawing of a scene's wheel: DXF (the cad extra), SVG or PDF",
        ),
    ):
        command = commands.add_parser(name, help=text)
        add(command)
        studies.add_quiet_argument(command)
        command.set_defaults(run=_silenced(command.get_default("run")))
    for name, add, texts in (
        ("sweep", studies.add_sweep_arguments, studies.SWEEP_HELP),
        ("pareto", studies.add_pareto_arguments, studies.PARETO_HELP),
        ("tradeoff", studies.add_tradeoff_arguments, studies.TRADEOFF_HELP),
    ):
        add(commands.add_parser(name, **texts))
    new.add_new_arguments(commands.add_parser("new", help="write a commented template scene to start from"))
    materials.add_materials_arguments(
        commands.add_parser("materials", help="list the built-in materials: density, strengths, rim speed, source")
    )
    app.add_app_arguments(
        commands.add_parser("app", help="the local web app: edit a scene, see its answer (app extra)")
    )
    bench = commands.add_parser(
        "bench",
        add_help=False,  # --help is bench's own
        help="speed against error of each way to an answer (see flyopt bench --help)",
    )
    bench.set_defaults(run=_bench, takes_rest=True)  # its own options, parsed by flyopt.bench
    return parser


class _Version(argparse.Action):
    """``--version``: print ``flyopt VERSION`` on stdout and exit 0; the version is read only then."""

    def __init__(
        self,
        option_strings: Sequence[str],
        dest: str = argparse.SUPPRESS,
        default: Any = argparse.SUPPRESS,
        help: str = "print flyopt's version and exit",
    ) -> None:
        super().__init__(option_strings, dest=dest, default=default, nargs=0, help=help)

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: Any,
        option_string: str | None = None,
    ) -> None:
        import flyopt

        print(f"flyopt {flyopt.__version__}")
        parser.exit()


def _printed_to_file(handler: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """A handler whose printed result goes to ``-o FILE`` instead of stdout, atomically.

    The file's folder is checked before anything is computed (and by the
    handler, once it has read the scene, that it is no input); the file is
    written only when the handler returns (an error or Ctrl-C writes
    nothing), then "wrote FILE" is said unless ``--quiet``.
    """

    def run_to_file(args: argparse.Namespace) -> int:
        if args.output is None:
            return handler(args)
        from flyopt.outputs.files import check_folder, write_text

        check_folder(args.output, "-o/--output")  # the handler, once it has read the scene, checks that
        # the file is none the scene reads (flyopt.outputs.files.check_not_scene)
        printed = io.StringIO()
        with contextlib.redirect_stdout(printed):
            status = handler(args)
        if status == EXIT_INPUT:  # a refusal the handler said and returned: no result, and the file is left as it was
            return status
        write_text(args.output, printed.getvalue())
        if not args.quiet:
            print(f"wrote {args.output}")
        return status

    return run_to_file


def _silenced(handler: Callable[[argparse.Namespace], int]) -> Callable[[argparse.Namespace], int]:
    """A handler whose stdout ``--quiet`` silences: its result is a file or its exit status."""

    def run_quietly(args: argparse.Namespace) -> int:
        if not args.quiet:
            return handler(args)
        with contextlib.redirect_stdout(io.StringIO()):
            return handler(args)

    return run_quietly


def _bench(args: argparse.Namespace) -> int:
    from flyopt.bench import main as bench_main

    return bench_main(args.rest, parser_class=OneLineParser)


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())

"""The exit codes of the ``flyopt`` command, and :func:`run`, the one place that maps errors to them.

==========  ===========================================================
status      meaning
==========  ===========================================================
0           done: a design, or no flywheel needed, or a diagram written
1           a solver did not converge, a design failed its check against
            the constraints, or the arithmetic failed (no design reported)
2           bad input: a scene, an option or a file that cannot be read
            or written (one line on stderr naming the file, the field and
            what is allowed; nothing written)
3           infeasible: no material and shaft can give the inertia
4           verification flagged: the simulation finds the design misses
            the allowed δ
5           an output could not be written (disk full, no permission, a
            read-only file system): one line naming the file; nothing is
            left under its name
130         interrupted (Ctrl-C, SIGTERM, or a sweep that lost its
            workers); what was finished is kept, no temporary file is
            left, and ``--resume`` continues
141         stdout was closed early (``flyopt solve ... | head``): the
            reader stopped reading; nothing more is written, nothing on
            stderr (128 + SIGPIPE, what the shell reports for a C tool)
==========  ===========================================================

Every error is one line on stderr: ``flyopt: error: FILE: FIELD: what is
wrong``, ``FILE:LINE: FIELD`` where the field is written in the command's
scene file (as ``flyopt check`` places it).
"""

from __future__ import annotations

import argparse
import os
import signal
import sys
from collections.abc import Sequence
from typing import TYPE_CHECKING, NoReturn

from flyopt.errors import ExpressionError, FlyoptError, Interrupted, NonPeriodicCycle, OutputError, SceneError

if TYPE_CHECKING:
    from types import FrameType

    from flyopt.pipeline import Solution

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_INPUT = 2
EXIT_INFEASIBLE = 3
EXIT_FLAGGED = 4
EXIT_OUTPUT = 5
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141


def calculation_exit(result: object) -> int:
    """The exit status of a scene that is one calculation (``flyopt solve``, ``flyopt report``): 4 when an
    operation's speed falls beyond machine.delta (its ``holds`` is False), else 0."""
    return EXIT_FLAGGED if getattr(result, "holds", None) is False else EXIT_OK


def solution_exit(solution: Solution) -> int:
    """The exit status of a solved scene (``flyopt solve``, ``flyopt report``): 3 infeasible,
    4 a verification (of the flywheel or of the drive) flagged or a [flywheel] that exists short
    of machine.delta, else 0."""
    if solution.status == "infeasible":
        return EXIT_INFEASIBLE
    if solution.status == "insufficient":
        return EXIT_FLAGGED
    for check in (solution.verification, getattr(solution, "drive_check", None)):
        if check is not None and check.flagged:
            return EXIT_FLAGGED
    return EXIT_OK


def fail(message: object, status: int) -> int:
    """Say ``message`` in one line on stderr and return ``status``."""
    print(f"flyopt: error: {one_line(message)}", file=sys.stderr)
    return status


def one_line(message: object, limit: int = 1000) -> str:
    """The message on one line, cut to ``limit`` characters (an echoed input may be huge), every character that
    acts rather than shows written as its escape (:func:`flyopt.report.characters.visible`): a key the user wrote
    with an ESC in it would otherwise start a terminal sequence on the user's screen."""
    from flyopt.report.characters import visible

    text = visible(" ".join(str(message).split()))
    return text if len(text) <= limit else text[: limit - 1] + "…"


def status_of(err: BaseException, where: str | None) -> int:
    """Say a failure in one line on stderr and return its exit status.

    Parameters
    ----------
    err : BaseException
        A :class:`flyopt.errors.FlyoptError`, an :class:`OSError`, an
        :class:`ArithmeticError`, a :class:`ValueError` (other than the
        input errors, which are FlyoptErrors: a computation that failed) or
        a :class:`KeyboardInterrupt`.
    where : str or None
        The file the command works on, named when the error does not name one.

    Returns
    -------
    int
        The status of the table above.

    Raises
    ------
    BaseException
        ``err`` itself when it is none of those (a bug: its traceback is wanted).
    """
    prefix = f"{where}: " if where else ""
    if isinstance(err, SceneError):
        # it names its file itself (an option, --vary or --output, has none); a field of the command's scene
        # file is placed on its line, as flyopt check places it
        return fail(_placed(err, where), EXIT_INPUT)
    if isinstance(err, NonPeriodicCycle):
        return fail(str(err), EXIT_INPUT)
    if isinstance(err, ExpressionError):
        return fail(f"{prefix}{err}", EXIT_INPUT)
    if isinstance(err, Interrupted):
        return fail(f"{prefix}{err}", EXIT_INTERRUPTED)
    if isinstance(err, KeyboardInterrupt):
        return fail(f"{prefix}interrupted", EXIT_INTERRUPTED)
    if isinstance(err, OutputError):
        return fail(f"{err.filename}: {err.strerror}", EXIT_OUTPUT)
    if isinstance(err, OSError):
        name = f"{err.filename}: " if getattr(err, "filename", None) else prefix
        return fail(f"{name}{err.strerror or err}", EXIT_INPUT)
    if isinstance(err, (FlyoptError, ArithmeticError, ValueError)):
        # a solver that did not converge, or arithmetic that failed on the way ("math domain
        # error" is a ValueError): no result, said in one line
        return fail(f"{prefix}{err}", EXIT_FAILED)
    raise err


#: The largest scene file whose refusal :func:`status_of` places on its line [bytes]: the placing scans the
#: whole text in Python (about 1 s a MB), which a refusal of a large inline table should not wait for;
#: ``flyopt check`` places every error whatever the size.
PLACED_BYTES = 1_000_000


def _placed(err: SceneError, scene: str | None) -> str:
    """``err`` as ``FILE:LINE: field: message`` where its field is written in ``scene`` (the command's scene
    file, which it names), as ``flyopt check`` says it (:func:`flyopt.cli.toml_lines.line_of`); else as it is."""
    from pathlib import Path

    if not (err.field and err.source and scene and Path(err.source) == Path(scene)):
        return str(err)
    from flyopt.cli.toml_lines import key_lines, line_of

    try:
        if os.path.getsize(scene) > PLACED_BYTES:
            return str(err)
        line = line_of(key_lines(Path(scene).read_text(encoding="utf-8", errors="replace")), err.field)
    except (OSError, ValueError):  # the file gone or changed meanwhile: the error as it is
        return str(err)
    return str(err) if line is None else str(err.with_source(f"{err.source}:{line}"))


def run(parser: argparse.ArgumentParser, argv: Sequence[str] | None = None) -> int:
    """Parse a command line, run its handler, and turn what it raises into its exit status.

    The one error handler of every ``flyopt`` command.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        Sets ``run``, the handler (``run(args) -> status``); a handler that
        parses the rest of the line itself (``flyopt bench``) also sets
        ``takes_rest`` and finds the rest in ``args.rest``.
    argv : list of str, optional
        Default: ``sys.argv[1:]``.

    Returns
    -------
    int
        The handler's status, or the status of the table above for what it raised.
    """
    args, rest = parser.parse_known_args(sys.argv[1:] if argv is None else list(argv))
    if getattr(args, "takes_rest", False):
        args.rest = rest
    elif rest:
        parser.error(f"unrecognized arguments: {' '.join(rest)}")
    try:
        status = args.run(args)
        if sys.stdout is not None:  # None: started with stdout closed (>&-), where print writes nothing
            sys.stdout.flush()  # a closed pipe shows here, not at exit
        return status
    except BrokenPipeError:
        return _stdout_closed()
    except (FlyoptError, OSError, ArithmeticError, ValueError, KeyboardInterrupt) as err:
        return status_of(err, getattr(args, "scene", None))


def _stdout_closed() -> int:
    """The reader of stdout went away (``flyopt solve ... | head``): stop quietly.

    Python would print "Exception ignored ... BrokenPipeError" when it flushes
    stdout at exit; pointing stdout at the null device first keeps that quiet.
    """
    try:
        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
    except (OSError, ValueError):  # stdout without a file descriptor (captured in a test)
        pass
    return EXIT_BROKEN_PIPE


def sigterm_as_ctrl_c(signum: int, frame: FrameType | None) -> None:
    """SIGTERM's handler (``kill``, a scheduler's stop): what Ctrl-C does at this point, so that the command
    cleans up as after Ctrl-C and ends as interrupted. It died at once, leaving an output's
    ``NAME.tmp-PID-…`` beside it. Ctrl-C is raised as the signal itself, not by calling its handler, so that
    every kind of handler hears it: Python's KeyboardInterrupt, a sweep's
    :class:`~flyopt.studies.interrupt.Stop`, the app's server (an asyncio loop's, which only the signal
    wakes). Where Ctrl-C is ignored (a job a script starts in the background), SIGTERM still interrupts."""
    if callable(signal.getsignal(signal.SIGINT)):
        signal.raise_signal(signal.SIGINT)
        return
    raise KeyboardInterrupt


class OneLineParser(argparse.ArgumentParser):
    """argparse, with a bad option said in one line (exit status 2) instead of the usage block.

    ``flyopt solve: error: argument --units: invalid choice: 'furlongs' (choose from ...); see flyopt
    solve --help``: the usage of a command with a dozen options is five to seven lines that bury the
    one that matters. The subcommands' parsers are of this class too (argparse makes them so), and
    ``flyopt bench``'s own (:mod:`flyopt.bench.cli`).
    """

    def error(self, message: str) -> NoReturn:
        if message.endswith("expected one argument"):  # e.g. --range -1:0.5: argparse takes -1:0.5 for an option
            message += " (write a value that starts with '-' as --option=VALUE)"
        self.exit(EXIT_INPUT, f"{self.prog}: error: {one_line(message)}; see {self.prog} --help\n")

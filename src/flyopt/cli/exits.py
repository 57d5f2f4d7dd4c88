"""The exit codes of the ``flyopt`` command and the one place that maps errors to them.

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
130         interrupted (Ctrl-C, or a sweep that lost its workers); what
            was finished is kept and ``--resume`` continues
141         stdout was closed early (``flyopt solve ... | head``): the
            reader stopped reading; nothing more is written, nothing on
            stderr (128 + SIGPIPE, what the shell reports for a C tool)
==========  ===========================================================

Every error is one line on stderr: ``flyopt: error: FILE: FIELD: what is
wrong``.
"""

import sys

from flyopt.errors import ExpressionError, FlyoptError, Interrupted, NonPeriodicCycle, SceneError

EXIT_OK = 0
EXIT_FAILED = 1
EXIT_INPUT = 2
EXIT_INFEASIBLE = 3
EXIT_FLAGGED = 4
EXIT_INTERRUPTED = 130
EXIT_BROKEN_PIPE = 141


def fail(message, status):
    """Say ``message`` in one line on stderr and return ``status``."""
    print(f"flyopt: error: {_one_line(message)}", file=sys.stderr)
    return status


def _one_line(message, limit=1000):
    """The message on one line, cut to ``limit`` characters (an echoed input may be huge)."""
    text = " ".join(str(message).split())
    return text if len(text) <= limit else text[:limit - 1] + "…"


def status_of(err, where):
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
    if isinstance(err, (SceneError, NonPeriodicCycle)):
        # they name their file themselves; an option (--vary, --output) has no file
        return fail(str(err), EXIT_INPUT)
    if isinstance(err, ExpressionError):
        return fail(f"{prefix}{err}", EXIT_INPUT)
    if isinstance(err, Interrupted):
        return fail(f"{prefix}{err}", EXIT_INTERRUPTED)
    if isinstance(err, KeyboardInterrupt):
        return fail(f"{prefix}interrupted", EXIT_INTERRUPTED)
    if isinstance(err, OSError):
        name = f"{err.filename}: " if getattr(err, "filename", None) else prefix
        return fail(f"{name}{err.strerror or err}", EXIT_INPUT)
    if isinstance(err, (FlyoptError, ArithmeticError, ValueError)):
        # a solver that did not converge, or arithmetic that failed on the way ("math domain
        # error" is a ValueError): no result, said in one line
        return fail(f"{prefix}{err}", EXIT_FAILED)
    raise err

"""Domain errors of flyopt.

Each subclasses a built-in so callers may catch either the specific error or
the built-in (the python-control pattern).

Messages quote what the user wrote through :func:`shorten`, so that a
megabyte of input gives a message of one short line.
"""

import math

QUOTE_LENGTH = 60
"""Longest quotation of user text in a message [characters]; longer text is cut."""


def shorten(value: object, limit: int = QUOTE_LENGTH) -> str:
    """The ``repr`` of a value the user gave, cut to about ``limit`` characters.

    Parameters
    ----------
    value : object
        What the user wrote (a string, number, list, ...).
    limit : int
        Longest quotation [characters].

    Returns
    -------
    str
        ``repr(value)`` when it is short; otherwise its first characters, an
        ellipsis and the length, e.g. ``'1111111111…' (1000004 characters)``.

    Examples
    --------
    >>> shorten("1500 rpm")
    "'1500 rpm'"
    >>> shorten("x" * 1000, limit=10)
    "'xxxxxxxx…' (1000 characters)"
    """
    if isinstance(value, str):
        if len(value) + 2 <= limit:
            return repr(value)
        head = repr(value[: max(limit - 2, 1)])
        return f"{head[:-1]}…{head[-1]} ({len(value)} characters)"
    if isinstance(value, (list, tuple, dict)) and len(value) > limit:  # never build the whole repr
        return f"a {type(value).__name__} of {len(value)} items"
    if isinstance(value, int) and value.bit_length() > 4 * limit:  # repr refuses over 4300 digits
        return f"an integer of about {int((value.bit_length() - 1) * math.log10(2)) + 1} digits"
    return clip(repr(value), limit)


def clip(text: str, limit: int = 2 * QUOTE_LENGTH) -> str:
    """Text cut to ``limit`` characters with an ellipsis and its length (unquoted, e.g. a field path)."""
    return text if len(text) <= limit else f"{text[: limit - 1]}… ({len(text)} characters)"


class FlyoptError(Exception):
    """Base class of every error flyopt raises on purpose."""


class SceneError(FlyoptError, ValueError):
    """A scene file (or scene dictionary) is invalid.

    Parameters
    ----------
    field : str
        Dotted path of the offending field, e.g. ``machine.delta``.
    message : str
        What is wrong and what is allowed.
    source : str, optional
        The file the scene came from.
    """

    def __init__(self, field: str, message: str, source: str | None = None) -> None:
        self.field = field
        self.message = message
        self.source = source
        super().__init__(self._text())

    def _text(self) -> str:
        where = f"{self.source}: " if self.source else ""
        field = f"{clip(self.field)}: " if self.field else ""  # a field path may hold a key the user wrote
        return f"{where}{field}{self.message}"

    def with_source(self, source: str | None) -> "SceneError":
        """Return the same error, now naming the file it came from."""
        return SceneError(self.field, self.message, source)


class ExpressionError(FlyoptError, ValueError):
    """An expression string uses syntax, names or functions that are not allowed."""


class NonPeriodicCycle(FlyoptError, ValueError):
    """The work of the driving and resisting torques does not balance over a cycle.

    A flywheel cannot regulate such a machine: its mean speed drifts.
    """

    def __init__(self, imbalance: float, cycle_work: float, source: str | None = None) -> None:
        self.imbalance = imbalance
        self.cycle_work = cycle_work
        self.source = source
        where = f"{source}: torque: " if source else ""
        super().__init__(
            f"{where}non-periodic fluctuation: the work over one cycle does not balance "
            f"(net {imbalance:+.6g} J against {cycle_work:.6g} J of cycle work); "
            f"no flywheel can regulate it, only a governor"
        )

    def with_source(self, source: str | None) -> "NonPeriodicCycle":
        """Return the same error, now naming the file it came from."""
        return NonPeriodicCycle(self.imbalance, self.cycle_work, source)


class SolverFailed(FlyoptError, RuntimeError):
    """A numerical solver did not converge; its result is not a design."""

    #: The solver's return status (IPOPT's ``return_status``), set where it is known.
    status: str
    #: The design combination whose solve failed, set where there is one.
    combination: str


class BrokenInvariant(FlyoptError, RuntimeError):
    """A fact flyopt's own code relies on does not hold: a defect of flyopt, never of the input.

    Raised where an ``assert`` would stand (``python -O`` strips those); the message says which fact.
    """


class Interrupted(FlyoptError, RuntimeError):
    """A long run (a sweep) was stopped by the user (Ctrl-C) or lost its workers.

    What was finished is kept; the message says how to continue (``--resume``).
    The command line exits with status 130 for a user's interrupt.
    """


class OutputError(FlyoptError, OSError):
    """An output file could not be written (disk full, no permission, a read-only file system).

    Not bad input: the scene and the options were fine. The message names the
    file that could not be written; nothing is left under its name. The
    command line exits with status 5.
    """

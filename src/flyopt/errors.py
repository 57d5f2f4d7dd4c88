"""Domain errors of flyopt.

Each subclasses a built-in so callers may catch either the specific error or
the built-in (the python-control pattern).
"""


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

    def __init__(self, field, message, source=None):
        self.field = field
        self.message = message
        self.source = source
        super().__init__(self._text())

    def _text(self):
        where = f"{self.source}: " if self.source else ""
        field = f"{self.field}: " if self.field else ""
        return f"{where}{field}{self.message}"

    def with_source(self, source):
        """Return the same error, now naming the file it came from."""
        return SceneError(self.field, self.message, source)


class ExpressionError(FlyoptError, ValueError):
    """An expression string uses syntax, names or functions that are not allowed."""


class NonPeriodicCycle(FlyoptError, ValueError):
    """The work of the driving and resisting torques does not balance over a cycle.

    A flywheel cannot regulate such a machine: its mean speed drifts.
    """

    def __init__(self, imbalance, cycle_work, source=None):
        self.imbalance = imbalance
        self.cycle_work = cycle_work
        self.source = source
        where = f"{source}: torque: " if source else ""
        super().__init__(
            f"{where}non-periodic fluctuation: the work over one cycle does not balance "
            f"(net {imbalance:+.6g} J against {cycle_work:.6g} J of cycle work); "
            f"no flywheel can regulate it, only a governor")

    def with_source(self, source):
        """Return the same error, now naming the file it came from."""
        return NonPeriodicCycle(self.imbalance, self.cycle_work, source)


class SolverFailed(FlyoptError, RuntimeError):
    """A numerical solver did not converge; its result is not a design."""


class Interrupted(FlyoptError, RuntimeError):
    """A long run (a sweep) was stopped by the user (Ctrl-C) or lost its workers.

    What was finished is kept; the message says how to continue (``--resume``).
    The command line exits with status 130 for a user's interrupt.
    """

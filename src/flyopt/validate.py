"""The small checks of numbers and names that every stage makes, with one message style.

A refused value gives one line that names the field, says what is allowed
and quotes what was given (through :func:`flyopt.errors.shorten`)::

    shaft 'main': diameter [m] must be a finite number > 0, got -0.05
    geometry 'rimm' is not known; did you mean 'rim'? (allowed: thin_rim, rim, disc, rim_web, rim_arms)

Each raises ValueError; the scene loader turns it into a SceneError naming
the file. This module imports nothing from flyopt but :mod:`flyopt.errors`
and :mod:`flyopt.names`, so every stage may use it.
"""

from __future__ import annotations

import math
from typing import Any

from flyopt.errors import shorten
from flyopt.names import choice

__all__ = ["number", "finite", "positive", "finite_array", "choice"]


def number(
    value: Any,
    field: str,
    *,
    minimum: float | None = None,
    strict: bool = True,
    below: float | None = None,
    allowed: str | None = None,
) -> float:
    """``value`` as a finite float in its range, else a ValueError of one line.

    Parameters
    ----------
    value : object
        What was given; a bool is refused (``True`` is no number of anything).
    field : str
        The field as the user knows it, with its unit, e.g. ``"diameter [m]"``.
    minimum : float or None
        Lower bound: exclusive when ``strict`` (``> minimum``), else inclusive.
    strict : bool
    below : float or None
        Exclusive upper bound.
    allowed : str or None
        Words for what is allowed, instead of the ones made from the bounds.

    Returns
    -------
    float
    """
    if allowed is None:
        allowed = "a finite number"
        if minimum is not None:
            allowed += f" {'>' if strict else '>='} {minimum:g}"
        if below is not None:
            allowed += f"{' and' if minimum is not None else ''} < {below:g}"
    try:
        is_bool = (
            isinstance(value, bool) or getattr(getattr(value, "dtype", None), "kind", "") == "b"
        )  # numpy bools too
        result = math.nan if is_bool else float(value)
    except (TypeError, ValueError, OverflowError):
        result = math.nan
    if (
        not math.isfinite(result)
        or (minimum is not None and (result <= minimum if strict else result < minimum))
        or (below is not None and result >= below)
    ):
        raise ValueError(f"{field} must be {allowed}, got {shorten(value)}")
    return result


def finite(value: Any, field: str) -> float:
    """``value`` as a finite float (see :func:`number`)."""
    return number(value, field)


def positive(value: Any, field: str) -> float:
    """``value`` as a finite float > 0 (see :func:`number`)."""
    return number(value, field, minimum=0.0)


def finite_array(value: Any, field: str) -> Any:  # a float ndarray
    """``value`` as a non-empty array of finite floats, else a ValueError of one line.

    ``field`` names the argument with its unit, as for :func:`number`.
    """
    import numpy as np

    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{field} must be a number or an array of numbers, got {shorten(value)}") from err
    if array.size == 0:
        raise ValueError(f"{field} must not be empty")
    if not np.all(np.isfinite(array)):
        raise ValueError(
            f"{field} must be finite; it holds {int(np.count_nonzero(~np.isfinite(array)))} non-finite value(s)"
        )
    return array

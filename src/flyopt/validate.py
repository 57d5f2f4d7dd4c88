"""Checks of numeric arguments shared by every stage: one wording for each kind of refusal.

Each check returns the value as the type the caller computes with, or raises
ValueError naming the argument, its unit and what is allowed.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import numpy.typing as npt

from flyopt.errors import shorten


def positive(value: Any, name: str, unit: str) -> float:  # anything: what is not a number is refused
    """``value`` as a float, or ValueError naming ``name`` unless finite and > 0."""
    if isinstance(value, (bool, np.bool_)):
        raise ValueError(f"{name} must be a positive number [{unit}], got {value!r}")
    try:
        number = float(value)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{name} must be a positive number [{unit}], got {shorten(value)}") from err
    if not math.isfinite(number) or number <= 0.0:
        raise ValueError(f"{name} must be a positive finite number [{unit}], got {shorten(value)}")
    return number


def finite_array(value: npt.ArrayLike, name: str, unit: str) -> npt.NDArray[np.float64]:
    """``value`` as a non-empty float array, or ValueError naming ``name``."""
    try:
        array = np.asarray(value, dtype=float)
    except (TypeError, ValueError) as err:
        raise ValueError(f"{name} must be a number or an array of numbers [{unit}], got {shorten(value)}") from err
    if array.size == 0:
        raise ValueError(f"{name} must not be empty [{unit}]")
    if not np.all(np.isfinite(array)):
        raise ValueError(
            f"{name} must be finite [{unit}]; it holds {int(np.count_nonzero(~np.isfinite(array)))} non-finite value(s)"
        )
    return array

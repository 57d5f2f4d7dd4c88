"""Preferred numbers (ISO 3, DIN 323-1): the series a shop's diameters are rounded to.

The basic series R5, R10, R20 and R40 in their rounded values live in the
package data file ``flyopt/data/preferred_numbers.toml`` with their source;
:func:`series_values` gives the values of a series nearest a length, in the
form :func:`flyopt.design.rounding.grid_values` gives a step's multiples, so
that rounding takes a wheel's outer and hub diameters from a series where the
scene asks for one (``[design] diameter_series``).
"""

from __future__ import annotations

import bisect
import functools
import math
from importlib import resources

from flyopt._toml import tomllib

__all__ = ["SERIES", "series_values", "mantissas"]

_DATA_FILE = "preferred_numbers.toml"

#: The series a scene may name, coarsest first.
SERIES = ("R5", "R10", "R20", "R40")

#: Relative slack of a value already in the series (the solve's round-off): it is not moved.
ON_SERIES = 1e-9


@functools.lru_cache(maxsize=1)
def _load() -> dict[str, tuple[float, ...]]:
    text = resources.files("flyopt").joinpath("data", _DATA_FILE).read_text(encoding="utf-8")
    data = tomllib.loads(text)
    if not str(data.get("source", "")).strip():
        raise ValueError(f"flyopt/data/{_DATA_FILE} cites no source")
    out = {}
    for name in SERIES:
        values = tuple(float(v) for v in data["series"][name])
        if values[0] != 1.0 or list(values) != sorted(set(values)) or values[-1] >= 10.0:
            raise ValueError(f"flyopt/data/{_DATA_FILE}: series.{name} must rise from 1 to below 10")
        out[name] = values
    return out


def mantissas(series: str) -> tuple[float, ...]:
    """The rounded values of one decade of a series, 1 to below 10 (ValueError for an unknown name)."""
    table = _load()
    if series not in table:
        raise ValueError(f"preferred-number series {series!r} is not one of {', '.join(SERIES)}")
    return table[series]


def series_values(value: float, series: str, reach: int = 1) -> tuple[float, ...]:
    """The values of ``series`` within ``reach`` places below and above ``value`` (> 0), ascending: the
    value itself (reach 1) where it is in the series, else the one below and the one above it.

    The same unit in and out (metres in flyopt): a series value is a mantissa times a power of ten.
    """
    if not (value > 0 and math.isfinite(value)):
        raise ValueError(f"a length to round must be positive and finite, got {value!r}")
    decade = math.floor(math.log10(value))
    # m / 10^-k rather than m * 10^k: 6.0 / 10 is the double nearest 0.6, 6.0 * 0.1 is not
    numbers = [
        m * 10.0**k if k >= 0 else m / 10.0**-k for k in range(decade - 2, decade + 3) for m in mantissas(series)
    ]
    at = bisect.bisect_left(numbers, value)
    near = min((at - 1, at), key=lambda k: abs(numbers[k] / value - 1.0) if 0 <= k < len(numbers) else math.inf)
    if abs(numbers[near] / value - 1.0) <= ON_SERIES:
        low, high = near - (reach - 1), near + (reach - 1)
    else:
        below = at - 1  # numbers[below] < value < numbers[at]
        low, high = below - (reach - 1), below + reach
    return tuple(numbers[k] for k in range(low, high + 1))

"""Checked fields of a scene file: tables with known keys, numbers with units.

:class:`Table` refuses an unknown key (naming the closest allowed one) and
reads each value as a quantity of a dimension; :func:`unit_factor` and
:func:`scaled` read a section's ``unit`` and the numbers written in it.
"""

from __future__ import annotations

import math
import unicodedata
from collections.abc import Iterable, Sized
from typing import Any, Literal, overload

import numpy as np
import numpy.typing as npt

from flyopt.errors import SceneError, shorten
from flyopt.names import hint
from flyopt.units import DIMENSIONS, MAGNITUDES, is_plain, quantity, unit_value


def unit_factor(raw: object, dimension: str, where: str) -> float:
    """The SI value of one ``raw`` unit (a section's ``unit = "mm"``)."""
    if not isinstance(raw, str):
        raise SceneError(where, f"must be a unit string, got {shorten(raw)}")
    return unit_value(raw, dimension, where)


def scaled(raw: object, dimension: str, where: str, factor: float) -> float:
    """A number times the section's unit (a string of one too: "20" in a table of ``position_unit = "mm"`` is
    20 mm), or a string with its own unit."""
    if isinstance(raw, str) and not is_plain(raw):
        return quantity(raw, dimension, where)
    return quantity(raw, "dimensionless", where) * factor


def first_too_large(values: npt.NDArray[np.float64], dimension: str) -> int | None:
    """Index of the first of a table's ``values`` (SI) above the largest size :data:`flyopt.units.MAGNITUDES`
    allows its dimension, or None (:func:`check_scale` then says why). Only the largest: a table's value near 0
    is a zero's round-off (a force of 1.6e-28 N where a sine crosses), which divides nothing; one beyond it
    overflows the cycle's work (a torque of 1e308 N·m made it inf, and the answer "no flywheel needed")."""
    if dimension not in MAGNITUDES:
        return None
    over = np.abs(values) > MAGNITUDES[dimension][1]
    return int(np.argmax(over)) if over.any() else None


def check_table_size(values: npt.NDArray[np.float64], dimension: str, where: str, label: str) -> None:
    """Refuse a table whose values are not zero and all below the least size :data:`flyopt.units.MAGNITUDES`
    allows its dimension: a single value near 0 is a zero's round-off (:func:`first_too_large` leaves it), but
    a whole table of them is no machine: torques of 1e-300 N·m made a wheel's mass underflow to 0 (exit 1, naming
    no field), and of 1e-12 N·m "designed" a wheel of 8e-15 kg."""
    if dimension not in MAGNITUDES or not values.size:
        return
    largest = float(np.max(np.abs(values)))
    low = MAGNITUDES[dimension][0]
    if 0.0 < largest < low:
        unit = DIMENSIONS[dimension][1].replace("**", "^")
        raise SceneError(
            where,
            f"the largest {label} is {largest:.3g} {unit} (allowed: a table whose largest reaches {low:g} {unit}, or all "
            "zeros; below, every value is a zero's round-off)",
        )


class Table:
    """A dictionary from TOML with checked keys and typed accessors."""

    def __init__(self, data: object, where: str, allowed: Iterable[str]) -> None:
        if not isinstance(data, dict):
            raise SceneError(where or "(top level)", f"must be a table, got {type(data).__name__}")
        allowed = set(allowed)
        unknown = sorted(set(data) - allowed)
        if unknown:
            key = unknown[0]
            path = f"{where}.{key}" if where else key
            raise SceneError(
                path, f"unknown key{hint(key, sorted(allowed))} (allowed here: {', '.join(sorted(allowed))})"
            )
        self.data: dict[str, Any] = data
        self.where = where

    def _path(self, key: str) -> str:
        return f"{self.where}.{key}" if self.where else key

    def has(self, key: str) -> bool:
        """Whether the table gives ``key``."""
        return key in self.data

    def raw(self, key: str) -> Any:
        """The value of ``key`` as written (None when not given), for messages."""
        return self.data.get(key)

    def get(self, key: str, default: Any = None) -> Any:
        """The value of ``key`` as written, or ``default``."""
        return self.data.get(key, default)

    def require(self, key: str) -> Any:
        """The value of ``key`` as written; an error naming the field when it is missing."""
        if key not in self.data:
            raise SceneError(self._path(key), "is missing")
        return self.data[key]

    def unique_name(self, kind: str, seen: set[str]) -> str:
        """The table's ``name``: a non-empty string, not among ``seen`` (the names of the tables of its ``kind``
        before it: "material", "shaft", "member"), which then takes it."""
        name = self.require("name")
        if not isinstance(name, str) or not name.strip():
            raise SceneError(self._path("name"), f"must be a non-empty string, got {shorten(name)}")
        check_line(name, self._path("name"))
        if name in seen:
            raise SceneError(self._path("name"), f"{kind} {shorten(name)} is given twice")
        seen.add(name)
        return name

    @overload
    def quantity(
        self,
        key: str,
        dimension: str,
        required: Literal[True],
        default: float | None = None,
        *,
        own_range: bool = False,
    ) -> float: ...
    @overload
    def quantity(
        self, key: str, dimension: str, required: bool = False, *, default: float, own_range: bool = False
    ) -> float: ...
    @overload
    def quantity(
        self, key: str, dimension: str, required: bool = False, default: None = None, *, own_range: bool = False
    ) -> float | None: ...

    def quantity(
        self, key: str, dimension: str, required: bool = False, default: float | None = None, *, own_range: bool = False
    ) -> float | None:
        """The SI float of ``key`` in ``dimension``; ``default`` when not given (an error when ``required``, which
        says what to give: "engine.bore: is missing: give a length (e.g. '0.8 m')").

        A value given is held to its dimension's :data:`flyopt.units.MAGNITUDES` (:func:`check_scale`), unless
        ``own_range``: the caller holds the field to a narrower range of its own at once, in its own words.
        """
        if key not in self.data:
            if required:
                raise SceneError(self._path(key), f"is missing: give {DIMENSIONS[dimension][2]}")
            return default
        value = quantity(self.data[key], dimension, self._path(key))
        if not own_range:
            check_scale(value, dimension, self._path(key), self.data[key])
        return value

    def positive(self, key: str, dimension: str) -> float:
        """The SI float of ``key``, which the table must give, finite and above 0: an error naming the field and
        quoting it as written ("must be positive, got '-5.5 kW'") otherwise."""
        value = self.quantity(key, dimension, required=True)
        if not (value > 0 and value != float("inf")):
            raise SceneError(self._path(key), f"must be positive, got {shorten(self.raw(key))}")
        return value


SPEED_RANGE = (1e-6, 1e6)
"""Allowed machine.speed (and a press's crank speed) [rad/s]: 1e6 rad/s is about 9.5 million rpm; beyond
either end ω² and the energies overflow."""
SPEED_WHY = "about 1e-5 to 9.5 million rpm, beyond any machine a flywheel regulates"


DELTA_RANGE = (1e-6, 2.0)
"""Allowed coefficient of fluctuation of speed δ = (ω_max − ω_min)/ω_mean, 2 itself excluded (ω_min would be 0):
the inertia grows as 1/δ, and below 1e-6 it cannot be computed (1/300 is a tight generator)."""


MAX_LINE_LENGTH = 200
"""The longest a name or the title may be [characters]: each is printed whole in the text's tables, the report's
headings and the plots' legends, whose layout of a name of 100,000 characters took minutes and gigabytes."""


def check_line(text: str, where: str, note: str = "") -> None:
    """Refuse a name (or a title) that is not one line of text: a control character (a line break, a tab, ESC,
    NUL) in it would split the text report's lines and, written raw into a DXF's properties, end its section
    (a material named "iron\\n  0\\nEOF" made the exported drawing unreadable); or longer than
    :data:`MAX_LINE_LENGTH` (``note`` says where a longer text belongs)."""
    if any(unicodedata.category(c) in ("Cc", "Zl", "Zp") for c in text):
        raise SceneError(where, f"{shorten(text)} holds a control character: a name is one line of text")
    if len(text) > MAX_LINE_LENGTH:
        raise SceneError(
            where, f"is {len(text)} characters long (allowed: at most {MAX_LINE_LENGTH}{f'; {note}' if note else ''})"
        )


def check_count(items: Sized, where: str, limit: int, what: str, note: str = "") -> None:
    """Refuse a list of more than ``limit`` items, ``what`` naming them ("[[shaft]] tables", "steps"): each list a
    scene gives is held to what a machine has, before an item is read (5,000 steps of a shaft ran the beam's
    check for over 5 minutes and 5.6 GB; 300,000 materials would take half an hour)."""
    if len(items) > limit:
        raise SceneError(where, f"has {len(items)} {what} (allowed: at most {limit}{f' {note}' if note else ''})")


SAFETY_RANGE = (1.0, 100.0)
"""Allowed factor of safety, the design's and a material's [-]: 1 is none; beyond 100 no wheel is designed
(the courses take 5 to 10 on cast iron) and the allowable stress falls towards zero."""
SAFETY_WHY = "the strength over the allowable stress: 1 (none) to 100"


def check_delta(delta: float, where: str, raw: object, note: str, derived: str = "") -> None:
    """Refuse a δ outside :data:`DELTA_RANGE`: the machine's, a press's, or one ``derived`` from what ``where``
    gives (a press's slowdown: ``derived`` names the relation). One rule and one message for every δ, naming
    ``where`` and the range; ``note`` follows it (typical values)."""
    low, high = DELTA_RANGE
    if low <= delta < high:
        return
    allowed = f"between {low:g} and {high:g} ({high:g} excluded)"
    if derived:
        raise SceneError(where, f"{shorten(raw)} gives δ = {derived} = {delta:.4g}; δ must lie {allowed}; {note}")
    raise SceneError(where, f"must lie {allowed}, got {shorten(raw)}; {note}")


def check_magnitude(value: float, where: str, raw: object, low: float, high: float, unit: str, why: str) -> None:
    """Refuse a positive ``value`` outside ``[low, high]`` (SI, in ``unit``): beyond them the computation overflows.

    ``why`` says what the bounds are (documented in README's Limits).
    """
    if not low <= value <= high:
        unit = f" {unit}" if unit else ""
        raise SceneError(where, f"{shorten(raw)} is out of range (allowed: {low:g} to {high:g}{unit}; {why})")


def check_scale(value: float, dimension: str, where: str, raw: object) -> None:
    """Refuse a scalar quantity whose size lies outside :data:`flyopt.units.MAGNITUDES` of its dimension (0 is
    allowed): one rule for every field a section reads, in the words of :func:`check_magnitude`."""
    if value == 0 or dimension not in MAGNITUDES:
        return
    low, high, why = MAGNITUDES[dimension]
    if not low <= abs(value) <= high:
        unit = DIMENSIONS[dimension][1].replace("**", "^")
        unit = f" {unit}" if unit else ""
        raise SceneError(where, f"{shorten(raw)} is out of range (allowed: a size of {low:g} to {high:g}{unit}; {why})")


def mean_speed(machine: Table, required: bool) -> float:
    """machine.speed [rad/s]: positive and within :data:`SPEED_RANGE` (NaN where not given and not
    ``required``); the one reading of it, by the loader and by the energy terms' W = P Φ / ω_m."""
    omega = machine.quantity("speed", "angular_speed", required=required, own_range=True)
    if omega is None:
        return math.nan
    if omega <= 0:
        raise SceneError("machine.speed", f"must be positive, got {shorten(machine.raw('speed'))}")
    check_magnitude(omega, "machine.speed", machine.raw("speed"), *SPEED_RANGE, "rad/s", SPEED_WHY)
    return omega


def cycle_of(machine: Table) -> float:
    """machine.cycle [rad], positive (one turn where not given)."""
    cycle = machine.quantity("cycle", "angle", default=2 * math.pi)
    if cycle <= 0:
        raise SceneError("machine.cycle", f"must be positive, got {shorten(machine.raw('cycle'))}")
    return cycle

"""Tables over the cycle angle, inline or from a CSV file, checked and read as a PiecewiseLinear.

The angles must not decrease, a vertical step is two rows at one angle, and
the table must cover the cycle from 0 to Φ (within :data:`ANGLE_TOLERANCE`).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from flyopt.cycle.torque import PiecewiseLinear
from flyopt.errors import SceneError, shorten
from flyopt.io.csv_table import csv_table
from flyopt.io.fields import check_scale, check_table_size, first_too_large, scaled
from flyopt.io.input_files import check_rows
from flyopt.io.toml_file import InlineRows

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

ANGLE_TOLERANCE = 1e-9
"""Relative tolerance on a table's first and last angle against 0 and Φ."""


def angle_curve(
    raw: object,
    where: str,
    cycle: float,
    unit: float,
    angle_unit: float,
    dimension: str = "torque",
    label: str | None = None,
    minimum: tuple[float, str] | None = None,
) -> PiecewiseLinear:
    """A table [[angle, value], ...] over the cycle as a PiecewiseLinear (values in SI).

    ``label`` names the values in messages (default: the dimension);
    ``minimum``, a pair (least value [SI], why), refuses a value below it.
    """
    label = label or dimension
    if not isinstance(raw, (list, InlineRows)) or len(raw) < 2:
        raise SceneError(where, f"must be a list of at least two [angle, {label}] pairs")
    check_rows(len(raw), where)
    if isinstance(raw, InlineRows):  # plain finite numbers: what scaled gives each, float(x) * unit
        angles = raw.array[:, 0] * angle_unit
        values = raw.array[:, 1] * unit
    else:
        angles = np.empty(len(raw))
        values = np.empty(len(raw))
        for k, pair in enumerate(raw):
            if not isinstance(pair, list) or len(pair) != 2:
                raise SceneError(f"{where}[{k}]", f"must be an [angle, {label}] pair, got {shorten(pair)}")
            angles[k] = scaled(pair[0], "angle", f"{where}[{k}] angle", angle_unit)
            values[k] = scaled(pair[1], dimension, f"{where}[{k}] {label}", unit)
    if minimum is not None and (k := _first_below(values, minimum[0])) is not None:
        written = raw.array[k, 1] if isinstance(raw, InlineRows) else raw[k][1]
        raise SceneError(
            f"{where}[{k}]",
            f"the {label} {shorten(written)} at {np.degrees(angles[k]):.6g} deg is below {minimum[0]:g}: {minimum[1]}",
        )
    problem, k = _table_problem(angles, cycle)
    if problem == "decreasing":
        raise SceneError(
            where,
            f"angles must not decrease: point {k} ({np.degrees(angles[k]):.6g} deg) "
            f"comes after {np.degrees(angles[k - 1]):.6g} deg",
        )
    if problem == "three":
        raise SceneError(
            where,
            f"three points at one angle ({np.degrees(angles[k]):.6g} deg); "
            "a vertical step is exactly two points at one angle",
        )
    if problem == "open":
        raise SceneError(
            where,
            f"the table covers {np.degrees(angles[0]):.6g} to {np.degrees(angles[-1]):.6g} deg "
            f"but the cycle is 0 to {np.degrees(cycle):.6g} deg: the cycle does not close "
            "(the first point must be at 0 and the last at the cycle angle)",
        )
    if (row := first_too_large(values, dimension)) is not None:
        written = float(raw.array[row, 1]) if isinstance(raw, InlineRows) else raw[row][1]
        check_scale(values[row], dimension, f"{where}[{row}] {label}", written)
    check_table_size(values, dimension, where, label)
    angles[0], angles[-1] = 0.0, cycle
    return PiecewiseLinear(angles, values)


def _first_below(values, least):
    """Index of the first value below ``least`` (a row the table refuses), or None."""
    below = values < least
    return int(np.argmax(below)) if below.any() else None


def _table_problem(angles, cycle):
    """The first thing wrong with a table's angles [rad], and the row where it shows.

    Returns
    -------
    problem : {"decreasing", "three", "open"} or None
        An angle below the one before it; three rows at one angle (a
        vertical step is two); a first or last angle off 0 or the cycle
        angle by more than ``ANGLE_TOLERANCE`` of the cycle.
    row : int or None
        Index of the row (the later of two decreasing ones, the middle one of three).
    """
    steps = np.diff(angles)
    if np.any(steps < 0):
        return "decreasing", int(np.argmax(steps < 0)) + 1
    flat = (steps[1:] == 0) & (steps[:-1] == 0)
    if np.any(flat):
        return "three", int(np.argmax(flat)) + 1
    tol = ANGLE_TOLERANCE * cycle
    if abs(angles[0]) > tol or abs(angles[-1] - cycle) > tol:
        return "open", None
    return None, None


def angle_curve_file(
    raw: object,
    where: str,
    files: Path,
    cycle: float,
    unit: float,
    angle_unit: float,
    column: str,
    units: Sequence[str],
    minimum: tuple[float, str] | None = None,
    dimension: str = "torque",
) -> PiecewiseLinear:
    """A table [angle, value] read from a CSV file, with the checks of inline points (its values of
    ``dimension``).

    Parameters
    ----------
    raw : object
        The ``points_file`` value: a path, relative to the scene file's folder.
    where : str
        The field, e.g. ``torque.resisting.points_file``.
    files : Path
        The folder of the scene file.
    cycle : float
        Cycle angle Φ [rad].
    unit, angle_unit : float
        SI value of one unit of the second and first column.
    column : str
        What the second column holds ("torque", "force", ...), for messages.
    units : tuple of str
        The two columns' units as written (for messages).
    minimum : (float, str), optional
        The least value of the second column [SI] and why: a row below it is refused.

    Returns
    -------
    PiecewiseLinear

    Raises
    ------
    SceneError
        The file cannot be read, or a line or the table is wrong: the message
        names the CSV file, the line and what is allowed.
    """
    numbers, lines, name = csv_table(raw, where, files, ("angle", column), units)
    angles = numbers[:, 0] * angle_unit
    values = numbers[:, 1] * unit
    if minimum is not None and (k := _first_below(values, minimum[0])) is not None:
        raise SceneError(
            where,
            f"{name} line {lines[k]}: the {column} {numbers[k, 1]:.6g} {units[1]} is below "
            f"{minimum[0]:g}: {minimum[1]}",
        )
    problem, k = _table_problem(angles, cycle)
    if problem == "decreasing":
        raise SceneError(
            where,
            f"{name} line {lines[k]}: angles must not decrease: {np.degrees(angles[k]):.6g} deg "
            f"comes after {np.degrees(angles[k - 1]):.6g} deg on line {lines[k - 1]}",
        )
    if problem == "three":
        raise SceneError(
            where,
            f"{name} line {lines[k]}: three rows at one angle ({np.degrees(angles[k]):.6g} deg, "
            f"lines {lines[k - 1]} to {lines[k + 1]}); a vertical step is exactly two rows at one angle",
        )
    if problem == "open":
        raise SceneError(
            where,
            f"{name} lines {lines[0]} to {lines[-1]}: the table covers "
            f"{np.degrees(angles[0]):.6g} to {np.degrees(angles[-1]):.6g} deg but the cycle is 0 to "
            f"{np.degrees(cycle):.6g} deg: the cycle does not close (the first row must be at 0 and "
            "the last at the cycle angle)",
        )
    if (k := first_too_large(values, dimension)) is not None:
        try:
            check_scale(values[k], dimension, where, float(numbers[k, 1]))
        except SceneError as err:
            raise SceneError(where, f"{name} line {lines[k]}: the {column} {err.message}") from None
    try:
        check_table_size(values, dimension, where, column)
    except SceneError as err:
        raise SceneError(where, f"{name}: {err.message}") from None
    angles[0], angles[-1] = 0.0, cycle
    return PiecewiseLinear(angles, values)

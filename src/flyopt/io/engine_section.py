"""The [engine] section: cylinders, crank train and indicator data of a piston engine."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np
import numpy.typing as npt

from flyopt.errors import SceneError, shorten
from flyopt.io.angle_tables import angle_curve, angle_curve_file
from flyopt.io.fields import Table, scaled, unit_factor
from flyopt.names import hint

if TYPE_CHECKING:
    from flyopt.machine.engine import Engine


def read_engine(raw: object, files: Path = Path()) -> Engine:
    """The [engine] section: an :class:`~flyopt.machine.engine.Engine` (cylinders, crank train, indicator data)."""
    from flyopt.machine.engine import CYCLE_ANGLES, MAX_CYLINDERS, STANDARD_ATMOSPHERE, Engine  # CasADi

    table = Table(
        raw,
        "engine",
        {
            "cycle",
            "cylinders",
            "firing_angles",
            "bore",
            "stroke",
            "rod",
            "reciprocating_mass",
            "rod_mass",
            "rod_centre",
            "rod_inertia",
            "angle_unit",
            "pressure_unit",
            "pressure",
            "pressure_file",
            "crankcase_pressure",
            "description",
        },
    )
    kind = table.require("cycle")
    if not isinstance(kind, str) or kind not in CYCLE_ANGLES:  # a list or table is unhashable
        raise SceneError(
            "engine.cycle",
            f"{shorten(kind)} is not known{hint(kind, CYCLE_ANGLES)} (allowed: '4-stroke', a cycle of 720 deg, or '2-stroke', 360 deg)",
        )
    cycle = CYCLE_ANGLES[kind]
    count = table.require("cylinders")
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= MAX_CYLINDERS:
        raise SceneError(
            "engine.cylinders", f"must be a whole number of cylinders from 1 to {MAX_CYLINDERS}, got {shorten(count)}"
        )
    angle_unit = unit_factor(table.get("angle_unit"), "angle", "engine.angle_unit") if table.has("angle_unit") else 1.0
    firing = [k * cycle / count for k in range(count)]  # default: evenly spaced over the cycle
    if table.has("firing_angles"):
        raw_angles = table.get("firing_angles")
        if not isinstance(raw_angles, list) or len(raw_angles) != count:
            raise SceneError(
                "engine.firing_angles",
                f"must be a list of {count} angles, one per cylinder (the "
                f"crank angle at which its cycle starts), got {shorten(raw_angles)}",
            )
        for k, value in enumerate(raw_angles):
            firing[k] = scaled(value, "angle", f"engine.firing_angles[{k}]", angle_unit)
            if not 0.0 <= firing[k] < cycle:
                raise SceneError(
                    f"engine.firing_angles[{k}]",
                    f"{shorten(value)} lies outside the cycle: a firing "
                    f"angle is the crank angle at which the cylinder's cycle starts, from 0 up to "
                    f"(not including) {math.degrees(cycle):g} deg for a {kind} engine",
                )
    sizes = {}
    for key in ("bore", "stroke", "rod"):
        sizes[key] = table.quantity(key, "length", required=True)
        if not (math.isfinite(sizes[key]) and sizes[key] > 0):
            raise SceneError(f"engine.{key}", f"must be a positive length, got {shorten(table.raw(key))}")
    if not sizes["rod"] > sizes["stroke"] / 2:
        raise SceneError(
            "engine.rod",
            f"{shorten(table.raw('rod'))} is not longer than the crank radius, "
            f"stroke/2 = {sizes['stroke'] / 2 * 1e3:.6g} mm: the crank could not turn "
            "(the connecting rod is measured centre to centre)",
        )
    masses = {
        "reciprocating_mass": table.quantity("reciprocating_mass", "mass", required=True),
        "rod_mass": table.quantity("rod_mass", "mass", default=0.0),
    }
    for key, value in masses.items():
        if not (math.isfinite(value) and value >= 0):
            raise SceneError(f"engine.{key}", f"must be a finite mass >= 0, got {shorten(table.raw(key))}")
    rod = {"rod_centre": 0.0, "rod_inertia": 0.0}
    if table.has("rod_mass"):
        for key in rod:
            if not table.has(key):
                raise SceneError(
                    f"engine.{key}",
                    "is missing: rod_mass, rod_centre (from the crank pin) and "
                    "rod_inertia (about the rod's centre of mass) come together",
                )
        rod["rod_centre"] = table.quantity("rod_centre", "length", required=True, own_range=True)
        if not 0.0 <= rod["rod_centre"] <= sizes["rod"]:
            raise SceneError(
                "engine.rod_centre",
                f"{shorten(table.raw('rod_centre'))} is not between the pins: the "
                f"centre of mass lies 0 to {shorten(table.raw('rod'))} from the "
                "crank pin",
            )
        rod["rod_inertia"] = table.quantity("rod_inertia", "inertia", required=True)
        if not (math.isfinite(rod["rod_inertia"]) and rod["rod_inertia"] >= 0):
            raise SceneError(
                "engine.rod_inertia", f"must be a finite number >= 0, got {shorten(table.raw('rod_inertia'))}"
            )
    else:
        for key in rod:
            if table.has(key):
                raise SceneError(f"engine.{key}", "describes the rest of the connecting rod: give rod_mass with it")
    unit = (
        unit_factor(table.get("pressure_unit"), "stress", "engine.pressure_unit") if table.has("pressure_unit") else 1.0
    )
    forms = [k for k in ("pressure", "pressure_file") if table.has(k)]
    if len(forms) != 1:
        raise SceneError(
            "engine.pressure",
            "give exactly one of pressure = [[angle, pressure], ...] or "
            'pressure_file = "indicator.csv": the absolute cylinder pressure of one cylinder over '
            "its cycle" + (" (given both)" if forms else ""),
        )
    absolute = (0.0, "the table holds absolute pressures, which cannot be negative")
    if forms[0] == "pressure_file":
        units = (table.get("angle_unit", "rad"), table.get("pressure_unit", "Pa"))
        pressure = angle_curve_file(
            table.get("pressure_file"),
            "engine.pressure_file",
            files,
            cycle,
            unit,
            angle_unit,
            "pressure",
            units,
            minimum=absolute,
            dimension="stress",
        )
    else:
        pressure = angle_curve(
            table.get("pressure"),
            "engine.pressure",
            cycle,
            unit,
            angle_unit,
            "stress",
            label="pressure",
            minimum=absolute,
        )
    crankcase = table.quantity("crankcase_pressure", "stress", default=STANDARD_ATMOSPHERE)
    if not (math.isfinite(crankcase) and crankcase >= 0):
        raise SceneError(
            "engine.crankcase_pressure",
            f"must be an absolute pressure >= 0, got {shorten(table.raw('crankcase_pressure'))}",
        )
    if not table.has("pressure_unit"):
        plain = _plain_rows(table.get(forms[0]), forms[0], len(pressure.values))
        if plain.all():
            _check_plain_pressures(float(pressure.values.max()), crankcase, f"engine.{forms[0]}")
        elif plain.any():
            _check_plain_cells(pressure.values, plain, table.get(forms[0]))
    try:
        return Engine(
            kind,
            tuple(firing),
            sizes["bore"],
            sizes["stroke"],
            sizes["rod"],
            masses["reciprocating_mass"],
            pressure,
            crankcase,
            masses["rod_mass"],
            rod["rod_centre"],
            rod["rod_inertia"],
        )
    except ValueError as err:
        raise SceneError("engine", str(err)) from None


def _plain_rows(raw: object, form: str, rows: int) -> npt.NDArray[np.bool_]:
    """Which of the indicator table's ``rows`` pressures are plain numbers: every one of a CSV file's, an inline
    table's cells that carry no unit of their own (as "0.35 N/mm^2" does)."""
    from flyopt.units import is_plain

    if form == "pressure_file" or not isinstance(raw, list):
        return np.ones(rows, dtype=bool)
    return np.array([is_plain(pair[1]) for pair in raw], dtype=bool)  # pairs: the table has been read


#: The factor between neighbouring pressures of an indicator table, one a plain number (pascals) and the other
#: with its unit, from which the plain one's unit was left out. No engine's cylinder pressure rises 300-fold from
#: one point to the next (1 bar to 300 bar, beyond any engine's peak; the shipped tables' largest step is 3.3-fold,
#: the exhaust valve's opening), and every pressure unit but the pascal is 1000 pascals (kPa) or more.
PLAIN_JUMP = 300.0


def _check_plain_cells(values: npt.NDArray[np.float64], plain: npt.NDArray[np.bool_], raw: list[list[object]]) -> None:
    """Refuse an inline indicator table without ``pressure_unit`` whose plain cells (pascals), beside cells with
    their own unit, cannot be pascals: all of them below the plain-stress slip band's top, or one next to a cell
    with its unit :data:`PLAIN_JUMP` times it or more. "60 bar" or "6000 kPa" written on the peak alone, the rest
    in bar or kPa without a unit, read the rest as pascals: a cylinder near vacuum but for one point. A plain zero
    is the same in every unit and is left out."""
    from flyopt.units import PLAIN_SLIPS

    floor = PLAIN_SLIPS["stress"][1]
    counted = plain & (values != 0.0)
    if not counted.any():
        return
    k = int(np.flatnonzero(counted)[np.argmax(values[counted])])
    if values[k] < floor:
        why = (
            f"it is the largest of the table's plain numbers, and below {floor:.6g} Pa, which no engine's cylinder "
            "pressure is"
        )
    else:
        low, high = np.minimum(values[:-1], values[1:]), np.maximum(values[:-1], values[1:])
        across = (counted[:-1] & ~plain[1:]) | (counted[1:] & ~plain[:-1])  # a plain cell and one with its unit
        jumps = np.flatnonzero(across & (low > 0.0) & (high >= PLAIN_JUMP * low))
        if not len(jumps):
            return
        j = int(jumps[0])
        k, other = (j, j + 1) if plain[j] else (j + 1, j)
        why = (
            f"the point beside it, {shorten(raw[other][1])}, differs from it {high[j] / low[j]:.3g}-fold, and no "
            f"cylinder pressure changes {PLAIN_JUMP:g}-fold from one point to the next"
        )
    raise SceneError(
        f"engine.pressure[{k}]",
        f"the pressure {shorten(raw[k][1])} is a plain number beside cells that carry their unit, and no "
        f"pressure_unit is given, so it is {values[k]:.6g} Pa; {why}: give each cell its unit, or give "
        'pressure_unit (e.g. "bar")',
    )


def _check_plain_pressures(largest: float, crankcase: float, field: str) -> None:
    """Refuse an indicator table of plain numbers (read as pascals: no pressure_unit) that never rises above the
    crankcase's pressure, or above the plain-stress slip band's top (:data:`flyopt.units.PLAIN_SLIPS`): its
    unit was left out. A table in bar or MPa written without ``pressure_unit`` was read as pascals, an engine
    whose cylinder never pushed, and a flywheel was designed for its pistons' inertia alone."""
    from flyopt.units import PLAIN_SLIPS

    floor = PLAIN_SLIPS["stress"][1]
    if largest > crankcase and largest >= floor:
        return
    if largest <= crankcase:  # a cylinder that never pushes: pascals are not what was meant
        reason = f"does not rise above the crankcase's {crankcase:.6g} Pa, as an engine's cylinder pressure does"
        way = 'give pressure_unit, e.g. "bar" or "MPa"'
    else:
        reason = f"is below {floor:.6g} Pa, which no engine's cylinder pressure is"
        way = 'give pressure_unit, e.g. "bar" or "MPa" (or "Pa" if pascals are meant)'
    raise SceneError(
        field,
        "the pressures are plain numbers and no pressure_unit is given, so they are pascals: the largest, "
        f"{largest:.6g} Pa, {reason}: {way}",
    )

"""The [torque] section: the driving and resisting torque curves, or the net areas between them."""

from __future__ import annotations

import math
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING

from flyopt.cycle.expression import Expression
from flyopt.cycle.torque import Constant, ExpressionTorque
from flyopt.errors import ExpressionError, SceneError, shorten
from flyopt.io.angle_tables import angle_curve, angle_curve_file
from flyopt.io.fields import Table, check_scale, scaled, unit_factor
from flyopt.io.motor_section import read_motor
from flyopt.units import DIMENSIONS, quantity

if TYPE_CHECKING:
    from collections.abc import Sequence

    from flyopt.cycle.torque import MotorTorque, TorqueCurve
    from flyopt.machine.transmission import Shaft


@dataclass(frozen=True)
class NetAreas:
    """The signed areas between the torque curves, in order, as energies [J], and the work per
    cycle [J] where it is known (``work_per_cycle``: the mean torque and the power follow)."""

    energies: tuple[float, ...]
    work: float | None = None


def read_torques(
    section: object,
    cycle: float,
    shafts: Sequence[Shaft] = (),
    efficiency: float = 1.0,
    member_loads: bool = False,
    files: Path = Path(),
) -> tuple[TorqueCurve | MotorTorque | None, TorqueCurve | MotorTorque | None, NetAreas | None]:
    """(driving, resisting, net) of the [torque] table.

    With forces or torques on [[member]]s (``member_loads``), a curve left
    out is zero: the members' loads may carry the whole load (or drive),
    and an unknown constant or the cycle's own balance settles the rest.
    """
    torque = Table(section, "torque", {"driving", "resisting", "net"})
    if torque.has("net"):
        if torque.has("driving") or torque.has("resisting"):
            raise SceneError(
                "torque.net",
                "give either the net areas or the driving and resisting torques, not both (the torque is given twice)",
            )
        return None, None, read_net_areas(torque.get("net"))
    curves = []
    for name in ("driving", "resisting"):
        if torque.has(name):
            curves.append(read_curve(torque.get(name), f"torque.{name}", cycle, shafts, efficiency, files))
        elif member_loads:
            curves.append(Constant(0.0))
        else:
            raise SceneError(
                f"torque.{name}",
                "is missing: give [torque.driving] and [torque.resisting], "
                "or [torque.net] with the net areas (a curve may be left out, meaning zero, "
                "when [[member]] forces or torques carry the load)",
            )
    driving, resisting = curves
    if isinstance(driving, Constant) and isinstance(resisting, Constant) and driving.unknown and resisting.unknown:
        raise SceneError("torque.resisting.constant", "both torques are unknown; at most one may be")
    return driving, resisting, None


def read_curve(
    section: object,
    where: str,
    cycle: float,
    shafts: Sequence[Shaft] = (),
    efficiency: float = 1.0,
    files: Path = Path(),
) -> TorqueCurve | MotorTorque:
    """One torque curve of [torque]: a constant, an expression, a motor, or a table (inline or CSV)."""
    table = Table(
        section,
        where,
        {"points", "points_file", "constant", "expression", "motor", "unit", "angle_unit", "description"},
    )
    forms = [k for k in ("points", "points_file", "constant", "expression", "motor") if table.has(k)]
    if len(forms) != 1:
        raise SceneError(
            where,
            "give exactly one of points, points_file, constant, expression or motor"
            + (f" (the torque is given twice: {', '.join(forms)})" if forms else ""),
        )
    form = forms[0]
    unit = 1.0
    if table.has("unit"):
        unit = unit_factor(table.get("unit"), "torque", f"{where}.unit")
    if form == "constant":
        raw = table.get("constant")
        if isinstance(raw, str) and raw.strip().lower() == "unknown":
            return Constant(None)
        value = scaled(raw, "torque", f"{where}.constant", unit)
        check_scale(value, "torque", f"{where}.constant", raw)
        return Constant(value)
    if form == "motor":
        return read_motor(table.get("motor"), f"{where}.motor", shafts, efficiency, files)
    if form == "expression":
        try:
            expr = Expression(table.get("expression"), variables=("phi", "omega"))
        except ExpressionError as err:
            raise SceneError(f"{where}.expression", str(err)) from None
        return ExpressionTorque(expr, unit, where=f"{where}.expression")
    angle_unit = (
        unit_factor(table.get("angle_unit"), "angle", f"{where}.angle_unit") if table.has("angle_unit") else 1.0
    )
    if form == "points_file":
        units = (table.get("angle_unit", "rad"), table.get("unit", DIMENSIONS["torque"][1]))
        return angle_curve_file(
            table.get("points_file"), f"{where}.points_file", files, cycle, unit, angle_unit, "torque", units
        )
    return angle_curve(table.get("points"), f"{where}.points", cycle, unit, angle_unit)


#: Largest energy one net area may make [J] (a machine's cycle is far below: beyond it the sums overflow).
MAX_AREA_ENERGY = 1e15

#: Smallest energy a net area that is not zero may make [J] (a nanojoule, below any machine's cycle: beneath
#: it the required inertia and the rim's mass underflow to zero).
MIN_AREA_ENERGY = 1e-9


def read_net_areas(section: object) -> NetAreas:
    """[torque.net]: the signed areas between the curves, as energies [J] (or a drawing's areas and scales)."""
    table = Table(
        section, "torque.net", {"areas", "area_unit", "torque_scale", "angle_scale", "work_per_cycle", "description"}
    )
    areas = table.require("areas")
    if not isinstance(areas, list) or len(areas) < 2:
        raise SceneError("torque.net.areas", "must be a list of at least two signed areas")
    drawing = [table.has(k) for k in ("area_unit", "torque_scale", "angle_scale")]
    if any(drawing) and not all(drawing):
        raise SceneError(
            "torque.net",
            "areas measured on a drawing need all of area_unit, torque_scale "
            "and angle_scale (energy = area x torque scale x angle scale)",
        )
    if all(drawing):
        factor = (
            table.quantity("area_unit", "area", required=True)
            * table.quantity("torque_scale", "torque_scale", required=True)
            * table.quantity("angle_scale", "angle_scale", required=True)
        )
        if factor <= 0:
            raise SceneError("torque.net", "the drawing scales must be positive")
        energies = []
        for k, a in enumerate(areas):
            if isinstance(a, str):
                raise SceneError(
                    f"torque.net.areas[{k}]",
                    f"with drawing scales the areas are plain numbers (in area_unit), got {shorten(a)}",
                )
            energies.append(factor * quantity(a, "dimensionless", f"torque.net.areas[{k}]"))
    else:
        energies = [quantity(a, "energy", f"torque.net.areas[{k}]") for k, a in enumerate(areas)]
    for k, energy in enumerate(energies):
        if not abs(energy) <= MAX_AREA_ENERGY:  # NaN too
            raise SceneError(
                f"torque.net.areas[{k}]",
                f"{shorten(areas[k])} makes {energy:.3g} J (allowed: at most {MAX_AREA_ENERGY:g} J in size, "
                "beyond any machine's cycle; check the drawing scales)",
            )
        if energy != 0.0 and abs(energy) < MIN_AREA_ENERGY:
            raise SceneError(
                f"torque.net.areas[{k}]",
                f"{shorten(areas[k])} makes {energy:.3g} J (allowed: 0, or at least {MIN_AREA_ENERGY:g} J in size, "
                "below which no machine's cycle lies; check the drawing scales)",
            )
    work = table.quantity("work_per_cycle", "energy")
    if work is not None and not (math.isfinite(work) and work > 0):
        raise SceneError("torque.net.work_per_cycle", f"must be positive, got {shorten(table.raw('work_per_cycle'))}")
    return NetAreas(tuple(energies), work)

"""[energy] and [strokes]: a machine in the energy terms the courses give, written as a scene.

[energy] gives a machine by its power (or its work per cycle) and its coefficient of
fluctuation of energy C_E, the largest fluctuation over the work per cycle::

    [energy]
    power = "300 kW"            # or work_per_cycle = "200 kJ"
    fluctuation = 0.1           # C_E = ΔE_max / W

The cycle is machine.cycle (one turn unless given: "720 deg" for a four-stroke engine).
The work per cycle is W = P Φ / ω_m, and ΔE_max = C_E W; the scene becomes the net areas
(+ΔE_max, −ΔE_max) with that work, so the energy method sizes the flywheel from them and the
analysis still shows the mean torque and the power (docs/flywheel-design.md, sections 4, 5).

[strokes] gives an engine by the work of its strokes, each half a crank turn, drawn as
triangles (the default) or rectangles of that area over the line of zero torque::

    [strokes]
    work = ["-1050 J", "-4200 J", "10650 J", "-1500 J"]   # suction, compression, expansion, exhaust
    shape = "triangle"          # or "rectangle"
    # or work as multiples of the cycle's work, [0, -0.5, 1.5, 0], with power or work_per_cycle

The cycle is as many half turns as strokes (four: 720°); the driving torque is the table of
the strokes' shapes and the resisting torque the unknown constant the cycle balances, so the
crossings and A_max are exact (sections 4 and 12).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_magnitude, cycle_of, mean_speed
from flyopt.io.operation_section import ENERGY_RANGE, POWER_RANGE
from flyopt.units import quantity

if TYPE_CHECKING:
    from collections.abc import Mapping

ENERGY_KEYS = ("power", "work_per_cycle", "fluctuation", "description")
STROKE_KEYS = ("work", "shape", "power", "work_per_cycle", "description")
SHAPES = ("triangle", "rectangle")
MAX_STROKES = 64
"""Most strokes of a [strokes] cycle (a cycle of 32 crank turns)."""
#: The multiples of the cycle's work must add to one within this.
MULTIPLE_SUM_TOLERANCE = 1e-9


def scene_data(data: Mapping[str, Any]) -> dict[str, Any]:
    """The scene dictionary an [energy] or [strokes] table stands for (the others kept as they are).

    Raises
    ------
    SceneError
        A field is missing or wrong, or the scene also gives the torques (or a [press]) that the
        table stands for.
    """
    given = [k for k in ("energy", "strokes") if k in data]
    if len(given) > 1:
        raise SceneError("strokes", "give either [energy] or [strokes], not both (the cycle's energy is given twice)")
    key = given[0]
    for other in ("torque", "press", "engine", "member", "operation"):
        if other in data:
            raise SceneError(
                key, f"gives the machine's energy over the cycle, and [{other}] gives it again: give one of them"
            )
    machine_table = Table(
        data.get("machine", {}), "machine", {"speed", "delta", "inertia", "gd2", "cycle", "efficiency", "description"}
    )
    machine = machine_table.data
    if "speed" not in machine:
        raise SceneError("machine.speed", "is needed: the work per cycle follows from the power at the mean speed")
    omega = mean_speed(machine_table, required=True)
    out = {k: v for k, v in data.items() if k != key}
    if key == "energy":
        cycle = cycle_of(machine_table)
        table = Table(data["energy"], "energy", ENERGY_KEYS)
        work = _work_per_cycle(table, "energy", omega, cycle, required=True)
        fluctuation = table.quantity("fluctuation", "dimensionless", required=True, own_range=True)
        if not (math.isfinite(fluctuation) and 0 < fluctuation <= 1e3):
            raise SceneError(
                "energy.fluctuation",
                f"must be positive (C_E, the largest fluctuation of energy over the work per cycle; "
                f"0.1 to 2 in practice), got {shorten(table.raw('fluctuation'))}",
            )
        swing = fluctuation * work
        out["torque"] = {"net": {"areas": [swing, -swing], "work_per_cycle": work}}
        return out
    table = Table(data["strokes"], "strokes", STROKE_KEYS)
    works = _stroke_works(table, omega)
    cycle = len(works) * math.pi
    if "cycle" in machine:
        given_cycle = cycle_of(machine_table)
        if abs(given_cycle - cycle) > 1e-9 * cycle:
            raise SceneError(
                "machine.cycle",
                f"is {math.degrees(given_cycle):.6g} deg, but {len(works)} strokes of half a turn make "
                f"{math.degrees(cycle):.6g} deg (leave machine.cycle out: [strokes] sets it)",
            )
    shape = table.get("shape", "triangle")
    if shape not in SHAPES:
        raise SceneError("strokes.shape", f"{shorten(shape)} is not known (allowed: {', '.join(SHAPES)})")
    out["machine"] = {**machine, "cycle": cycle}
    out["torque"] = {
        "driving": {"points": _stroke_points(works, shape), "description": f"{len(works)} strokes drawn as {shape}s"},
        "resisting": {"constant": "unknown"},
    }
    return out


def _work_per_cycle(table: Table, where: str, omega: float, cycle: float, required: bool) -> float:
    """W from ``power`` (P Φ / ω_m) or ``work_per_cycle`` [J]; NaN when neither is given and it is not required."""
    forms = [k for k in ("power", "work_per_cycle") if table.has(k)]
    if len(forms) > 1:
        raise SceneError(f"{where}.work_per_cycle", "give either power or work_per_cycle, not both")
    if not forms:
        if required:
            raise SceneError(f"{where}.power", "is needed: give the mean power (e.g. '300 kW') or work_per_cycle")
        return math.nan
    form = forms[0]
    value = table.quantity(form, "power" if form == "power" else "energy", required=True, own_range=True)
    if not (math.isfinite(value) and value > 0):
        raise SceneError(f"{where}.{form}", f"must be positive, got {shorten(table.raw(form))}")
    bounds, unit = (POWER_RANGE, "W") if form == "power" else (ENERGY_RANGE, "J")
    check_magnitude(value, f"{where}.{form}", table.raw(form), *bounds, unit, "beyond it the flywheel overflows")
    return value * cycle / omega if form == "power" else value


def _stroke_works(table: Table, omega: float) -> list[float]:
    """The work of each stroke [J], + done by the engine."""
    raw = table.get("work")
    if not isinstance(raw, list) or not 2 <= len(raw) <= MAX_STROKES:
        raise SceneError(
            "strokes.work",
            f"must be a list of 2 to {MAX_STROKES} strokes' work (e.g. ['-1050 J', '-4200 J', '10650 J', '-1500 J'])",
        )
    multiples = [not isinstance(w, str) for w in raw]
    if any(multiples) and not all(multiples):
        raise SceneError(
            "strokes.work",
            "give every stroke's work as an energy (e.g. '10 kJ') or every one as a multiple of the cycle's work",
        )
    if all(multiples):
        work = _work_per_cycle(table, "strokes", omega, len(raw) * math.pi, required=True)
        factors = [quantity(w, "dimensionless", f"strokes.work[{k}]") for k, w in enumerate(raw)]
        total = math.fsum(factors)
        if abs(total - 1.0) > MULTIPLE_SUM_TOLERANCE:
            raise SceneError(
                "strokes.work",
                f"as multiples of the cycle's work the strokes must add to 1, they add to {total:.9g}",
            )
        return [f * work for f in factors]
    for key in ("power", "work_per_cycle"):
        if table.has(key):
            raise SceneError(
                f"strokes.{key}",
                "is only for strokes' work given as multiples of the cycle's work (the energies give it already)",
            )
    works = [quantity(w, "energy", f"strokes.work[{k}]") for k, w in enumerate(raw)]
    for k, w in enumerate(works):
        if w and not ENERGY_RANGE[0] <= abs(w) <= ENERGY_RANGE[1]:
            raise SceneError(
                f"strokes.work[{k}]",
                f"{shorten(raw[k])} is out of range (allowed: 0 or ±{ENERGY_RANGE[0]:g} to ±{ENERGY_RANGE[1]:g} J)",
            )
    total = math.fsum(works)
    if not total > 0:
        raise SceneError(
            "strokes.work", f"the strokes' work adds to {total:.6g} J: an engine's cycle does positive work"
        )
    return works


def _stroke_points(works: list[float], shape: str) -> list[list[float]]:
    """[angle [rad], torque [N*m]] of the strokes drawn as triangles (peak 2W/π mid-stroke) or rectangles (W/π)."""
    points: list[list[float]] = []
    for k, w in enumerate(works):
        start, end = k * math.pi, (k + 1) * math.pi
        if shape == "triangle":
            if not points:
                points.append([start, 0.0])
            points += [[start + math.pi / 2, 2.0 * w / math.pi], [end, 0.0]]
        else:
            points += [[start, w / math.pi], [end, w / math.pi]]
    return points

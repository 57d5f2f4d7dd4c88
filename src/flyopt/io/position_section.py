"""The [position] section: a slider-crank engine at one crank position, for the forces there; or, beside
[[member]]s, a mechanism at one position, for its equivalents there (docs/flywheel-design.md, section 17)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.design_section import LENGTH_RANGE, LENGTH_WHY
from flyopt.io.fields import Table, check_magnitude
from flyopt.machine.crank_forces import ORIENTATIONS, CrankPosition

if TYPE_CHECKING:
    from flyopt.machine.equivalents import MechanismPosition
    from flyopt.machine.mechanism import Member

KEYS = {"angle", "crank", "rod", "bore", "pressure", "gas_force", "reciprocating_mass", "orientation", "description"}
MASS_RANGE = (0.0, 1e9)
#: Largest |crank angle| [rad] (a thousand turns), |pressure| [Pa] and |gas force| [N] a [position] takes.
MAX_ANGLE = 2e3 * math.pi
MAX_PRESSURE = 1e12
MAX_FORCE = 1e15


def read_position(raw: object) -> CrankPosition:
    """[position]: the crank angle from the inner dead centre, r, l, the gas load (bore and net pressure, or the
    gas force) and the reciprocating mass; ``orientation`` "vertical" adds the reciprocating parts' weight."""
    table = Table(raw, "position", KEYS)
    angle = table.quantity("angle", "angle", required=True, own_range=True)
    if not (math.isfinite(angle) and abs(angle) <= MAX_ANGLE):
        raise SceneError(
            "position.angle", f"must be a finite angle within ±1000 turns, got {shorten(table.raw('angle'))}"
        )
    lengths = {}
    for key in ("crank", "rod"):
        value = table.quantity(key, "length", required=True, own_range=True)
        if not (math.isfinite(value) and value > 0):
            raise SceneError(f"position.{key}", f"must be positive, got {shorten(table.raw(key))}")
        check_magnitude(value, f"position.{key}", table.raw(key), *LENGTH_RANGE, "m", LENGTH_WHY)
        lengths[key] = value
    if lengths["rod"] <= lengths["crank"]:
        raise SceneError(
            "position.rod",
            f"must be longer than the crank ({lengths['rod']:.6g} m against {lengths['crank']:.6g} m): "
            "the crank could not turn",
        )
    mass = table.quantity("reciprocating_mass", "mass", required=True, own_range=True)
    if not (math.isfinite(mass) and mass >= 0):
        raise SceneError("position.reciprocating_mass", f"must be >= 0, got {shorten(table.raw('reciprocating_mass'))}")
    check_magnitude(
        mass,
        "position.reciprocating_mass",
        table.raw("reciprocating_mass"),
        *MASS_RANGE,
        "kg",
        "piston, pin and rod end",
    )
    if table.has("gas_force") and (table.has("pressure") or table.has("bore")):
        raise SceneError("position.gas_force", "give either the gas_force or the bore with the pressure, not both")
    bore = gas = None
    pressure = 0.0
    if table.has("gas_force"):
        gas = table.quantity("gas_force", "force", required=True, own_range=True)
        if not (math.isfinite(gas) and abs(gas) <= MAX_FORCE):
            raise SceneError(
                "position.gas_force", f"must be finite, at most ±{MAX_FORCE:g} N, got {shorten(table.raw('gas_force'))}"
            )
    elif table.has("pressure") or table.has("bore"):
        for key in ("pressure", "bore"):
            if not table.has(key):
                raise SceneError(f"position.{key}", "is needed with the other of bore and pressure (F = p π d²/4)")
        bore = table.quantity("bore", "length", required=True, own_range=True)
        if not (math.isfinite(bore) and bore > 0):
            raise SceneError("position.bore", f"must be positive, got {shorten(table.raw('bore'))}")
        check_magnitude(bore, "position.bore", table.raw("bore"), *LENGTH_RANGE, "m", LENGTH_WHY)
        pressure = table.quantity("pressure", "stress", required=True, own_range=True)
        if not (math.isfinite(pressure) and abs(pressure) <= MAX_PRESSURE):
            raise SceneError(
                "position.pressure",
                f"must be finite, at most ±{MAX_PRESSURE:g} Pa, got {shorten(table.raw('pressure'))}",
            )
    orientation = table.get("orientation", "horizontal")
    if orientation not in ORIENTATIONS:
        raise SceneError(
            "position.orientation", f"{shorten(orientation)} is not known (allowed: {', '.join(ORIENTATIONS)})"
        )
    return CrankPosition(angle, lengths["crank"], lengths["rod"], mass, pressure, bore, gas, orientation)


#: The keys of a [position] beside [[member]]s: the equivalents of a mechanism at one position.
EQUIVALENT_KEYS = {"angle", "input_angle", "reduce_to", "force_at", "description"}
#: The keys that only the forces of a slider-crank engine take (a [position] alone).
FORCE_KEYS = KEYS - EQUIVALENT_KEYS


def read_mechanism_position(
    raw: object, cycle: float, mechanism: object, members: Sequence[Member]
) -> MechanismPosition:
    """[position] beside [[member]]s: the reference shaft's ``angle`` (or the mechanism's ``input_angle``), and
    optionally ``reduce_to`` a member and ``force_at`` a radius from its axis (docs/flywheel-design.md, section 17)."""
    from flyopt.machine.equivalents import MechanismPosition, reference_angle, varies_with_angle

    if isinstance(raw, dict):
        for key in sorted(FORCE_KEYS & set(raw)):
            raise SceneError(
                f"position.{key}",
                "belongs to the forces of a slider-crank engine (a [position] alone); beside [[member]]s a "
                f"[position] gives their equivalents (allowed here: {', '.join(sorted(EQUIVALENT_KEYS))})",
            )
    table = Table(raw, "position", EQUIVALENT_KEYS)
    if table.has("angle") and table.has("input_angle"):
        raise SceneError("position.input_angle", "give either angle (of the reference shaft) or input_angle, not both")
    given = None
    if table.has("input_angle"):
        given = table.quantity("input_angle", "angle", required=True, own_range=True)
        if not (math.isfinite(given) and abs(given) <= 2 * math.pi):
            raise SceneError(
                "position.input_angle",
                f"must lie within one turn, -360 to 360 deg, got {shorten(table.raw('input_angle'))}",
            )
        try:
            angle: float | None = reference_angle(mechanism, given)
        except ValueError as err:
            raise SceneError("position.input_angle", f"{err}: give angle, of the reference shaft") from None
    elif table.has("angle"):
        angle = table.quantity("angle", "angle", required=True)
    elif varies_with_angle(members):
        raise SceneError(
            "position.angle",
            "is missing: the members' ratios or loads vary with the angle (give angle, of the reference shaft, "
            "or input_angle, of the mechanism's input)",
        )
    else:
        angle = None
    if angle is not None and not (math.isfinite(angle) and 0.0 <= angle <= cycle * (1 + 1e-12)):
        key = "input_angle" if given is not None else "angle"
        what = (
            f"puts the reference shaft at {math.degrees(angle):.6g} deg, outside"
            if given is not None
            else "must lie within"
        )
        raise SceneError(
            f"position.{key}",
            f"{what} the cycle, 0 to {math.degrees(cycle):.6g} deg (machine.cycle), got {shorten(table.raw(key))}",
        )
    reduce_to = table.get("reduce_to")
    if reduce_to is not None and (not isinstance(reduce_to, str) or not reduce_to.strip()):
        raise SceneError("position.reduce_to", f"must be the name of a [[member]], got {shorten(reduce_to)}")
    force_at = None
    if table.has("force_at"):
        if reduce_to is None:
            raise SceneError("position.force_at", "needs reduce_to: the member from whose axis the radius is measured")
        force_at = table.quantity("force_at", "length", required=True, own_range=True)
        if not (math.isfinite(force_at) and force_at > 0):
            raise SceneError("position.force_at", f"must be positive, got {shorten(table.raw('force_at'))}")
        check_magnitude(force_at, "position.force_at", table.raw("force_at"), *LENGTH_RANGE, "m", LENGTH_WHY)
    return MechanismPosition(angle, given, reduce_to, force_at)

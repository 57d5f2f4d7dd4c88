"""The [position] section: a slider-crank engine at one crank position, for the forces there."""

from __future__ import annotations

import math

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_magnitude
from flyopt.machine.crank_forces import ORIENTATIONS, CrankPosition

KEYS = {"angle", "crank", "rod", "bore", "pressure", "gas_force", "reciprocating_mass", "orientation", "description"}
LENGTH_RANGE = (1e-6, 1e3)
MASS_RANGE = (0.0, 1e9)
#: Largest |crank angle| [rad] (a thousand turns), |pressure| [Pa] and |gas force| [N] a [position] takes.
MAX_ANGLE = 2e3 * math.pi
MAX_PRESSURE = 1e12
MAX_FORCE = 1e15


def read_position(raw: object) -> CrankPosition:
    """[position]: the crank angle from the inner dead centre, r, l, the gas load (bore and net pressure, or the
    gas force) and the reciprocating mass; ``orientation`` "vertical" adds the reciprocating parts' weight."""
    table = Table(raw, "position", KEYS)
    angle = table.quantity("angle", "angle", required=True)
    if not (math.isfinite(angle) and abs(angle) <= MAX_ANGLE):
        raise SceneError(
            "position.angle", f"must be a finite angle within ±1000 turns, got {shorten(table.raw('angle'))}"
        )
    lengths = {}
    for key in ("crank", "rod"):
        value = table.quantity(key, "length", required=True)
        if not (math.isfinite(value) and value > 0):
            raise SceneError(f"position.{key}", f"must be positive, got {shorten(table.raw(key))}")
        check_magnitude(value, f"position.{key}", table.raw(key), *LENGTH_RANGE, "m", "a micron to a kilometre")
        lengths[key] = value
    if lengths["rod"] <= lengths["crank"]:
        raise SceneError(
            "position.rod",
            f"must be longer than the crank ({lengths['rod']:.6g} m against {lengths['crank']:.6g} m): "
            "the crank could not turn",
        )
    mass = table.quantity("reciprocating_mass", "mass", required=True)
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
        gas = table.quantity("gas_force", "force", required=True)
        if not (math.isfinite(gas) and abs(gas) <= MAX_FORCE):
            raise SceneError(
                "position.gas_force", f"must be finite, at most ±{MAX_FORCE:g} N, got {shorten(table.raw('gas_force'))}"
            )
    elif table.has("pressure") or table.has("bore"):
        for key in ("pressure", "bore"):
            if not table.has(key):
                raise SceneError(f"position.{key}", "is needed with the other of bore and pressure (F = p π d²/4)")
        bore = table.quantity("bore", "length", required=True)
        if not (math.isfinite(bore) and bore > 0):
            raise SceneError("position.bore", f"must be positive, got {shorten(table.raw('bore'))}")
        check_magnitude(bore, "position.bore", table.raw("bore"), *LENGTH_RANGE, "m", "a micron to a kilometre")
        pressure = table.quantity("pressure", "stress", required=True)
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

"""The [flywheel] section: a flywheel that exists, to analyse rather than design."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_magnitude
from flyopt.machine.flywheel import ExistingFlywheel
from flyopt.units import quantity

if TYPE_CHECKING:
    from flyopt.machine.transmission import Shaft

#: Allowed flywheel inertia on its shaft [kg*m^2]: a gram at a millimetre to a power-station rotor, with room.
INERTIA_RANGE = (1e-12, 1e9)
#: Allowed mass [kg] and radius of gyration [m] of a flywheel given by them.
MASS_RANGE = (1e-6, 1e9)
RADIUS_RANGE = (1e-6, 1e3)


def read_flywheel(raw: object, shafts: tuple[Shaft, ...]) -> ExistingFlywheel:
    """The [flywheel] table: ``inertia``, or ``mass`` with ``radius_of_gyration``; ``shaft`` (default the reference)."""
    table = Table(raw, "flywheel", {"inertia", "mass", "radius_of_gyration", "shaft", "angles", "description"})
    by_mass = table.has("mass") or table.has("radius_of_gyration")
    if table.has("inertia") and by_mass:
        given = "mass" if table.has("mass") else "radius_of_gyration"
        raise SceneError(
            f"flywheel.{given}",
            "give either flywheel.inertia or flywheel.mass with flywheel.radius_of_gyration, not both",
        )
    mass = radius = None
    if by_mass:
        for key in ("mass", "radius_of_gyration"):
            if not table.has(key):
                raise SceneError(
                    f"flywheel.{key}", "is needed with the other of mass and radius_of_gyration (J = m k²)"
                )
        mass = _positive(table, "mass", "mass", MASS_RANGE, "kg", "a milligram to a million tonnes")
        radius = _positive(table, "radius_of_gyration", "length", RADIUS_RANGE, "m", "a micron to a kilometre")
        inertia = mass * radius * radius
        check_magnitude(
            inertia,
            "flywheel.mass",
            table.raw("mass"),
            *INERTIA_RANGE,
            "kg*m^2",
            "m k² must be a representable inertia",
        )
    elif table.has("inertia"):
        inertia = _positive(table, "inertia", "inertia", INERTIA_RANGE, "kg*m^2", "beyond it J ω² overflows")
    else:
        raise SceneError("flywheel.inertia", "is needed: give inertia, or mass with radius_of_gyration (J = m k²)")
    names = {s.name: s for s in shafts}
    reference = next((s for s in shafts if s.speed_ratio == 1.0), None)
    name = table.get("shaft")
    if name is None:
        if reference is None:
            raise SceneError(
                "flywheel.shaft",
                f"is needed: no [[shaft]] turns at the reference speed (the shafts are {', '.join(names)})",
            )
        shaft = reference
    elif not isinstance(name, str) or name not in names:
        raise SceneError(
            "flywheel.shaft", f"{shorten(name)} is not a [[shaft]] of the scene (they are {', '.join(names)})"
        )
    else:
        shaft = names[name]
    return ExistingFlywheel(inertia, shaft.name, shaft.speed_ratio, mass, radius, _angles(table))


#: Most angles a [flywheel] may ask the acceleration at.
MAX_ANGLES = 100


def _angles(table: Table) -> tuple[float, ...]:
    """flywheel.angles: where the check reports the angular acceleration [rad] (the cycle's bounds: at read)."""
    if not table.has("angles"):
        return ()
    raw = table.get("angles")
    items = raw if isinstance(raw, list) else [raw]
    if not 1 <= len(items) <= MAX_ANGLES:
        raise SceneError("flywheel.angles", f'must list 1 to {MAX_ANGLES} angles, e.g. ["45 deg"]')
    out = []
    for k, item in enumerate(items):
        where = f"flywheel.angles[{k}]" if isinstance(raw, list) else "flywheel.angles"
        value = quantity(item, "angle", where)
        if not math.isfinite(value):
            raise SceneError(where, f"must be a finite angle, got {shorten(item)}")
        out.append(value)
    return tuple(out)


def _positive(table: Table, key: str, dimension: str, bounds: tuple[float, float], unit: str, why: str) -> float:
    value = table.quantity(key, dimension, required=True, own_range=True)
    if not (math.isfinite(value) and value > 0):
        raise SceneError(f"flywheel.{key}", f"must be positive, got {shorten(table.raw(key))}")
    check_magnitude(value, f"flywheel.{key}", table.raw(key), *bounds, unit, why)
    return value

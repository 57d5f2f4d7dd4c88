"""The [operation] section: one operation, not a cycle (a rivet, a single stroke)."""

from __future__ import annotations

import math

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_magnitude
from flyopt.sizing.operation import Operation

#: Allowed energy of one operation [J], its duration [s] and the motor's power [W].
ENERGY_RANGE = (1e-9, 1e12)
DURATION_RANGE = (1e-9, 1e6)
POWER_RANGE = (1e-9, 1e10)


def read_operation(raw: object) -> Operation:
    """The [operation] table: ``energy`` of one operation, its ``duration``, the ``motor_power``."""
    table = Table(raw, "operation", {"energy", "duration", "motor_power", "description"})
    values = []
    for key, dimension, bounds, unit, why in (
        ("energy", "energy", ENERGY_RANGE, "J", "the work of one operation"),
        ("duration", "time", DURATION_RANGE, "s", "the time one operation takes"),
        ("motor_power", "power", POWER_RANGE, "W", "the motor's power"),
    ):
        value = table.quantity(key, dimension, required=True, own_range=True)
        if not (math.isfinite(value) and value > 0):
            raise SceneError(f"operation.{key}", f"must be positive ({why}), got {shorten(table.raw(key))}")
        check_magnitude(value, f"operation.{key}", table.raw(key), *bounds, unit, why)
        values.append(value)
    return Operation(*values)

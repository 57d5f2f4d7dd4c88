"""A motor's characteristic as a driving torque: an induction or DC motor, or a torque-speed table."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from flyopt.errors import SceneError, shorten
from flyopt.io.csv_table import csv_table
from flyopt.io.fields import Table, scaled, unit_factor
from flyopt.io.input_files import check_rows
from flyopt.io.toml_file import InlineRows

if TYPE_CHECKING:
    from collections.abc import Sequence

    from flyopt.cycle.torque import MotorTorque
    from flyopt.machine.transmission import Shaft


def read_motor(
    raw: object, where: str, shafts: Sequence[Shaft], efficiency: float, files: Path = Path()
) -> MotorTorque:
    """A motor characteristic as the driving torque at the reference shaft."""
    from flyopt.cycle.torque import MotorTorque
    from flyopt.machine.motor import DCMotor, InductionMotor

    kinds = {
        "induction": {"kind", "rated_power", "rated_speed", "synchronous_speed", "breakdown_ratio", "model", "shaft"},
        "dc": {"kind", "no_load_speed", "stall_torque", "rated_power", "rated_speed", "shaft"},
        "table": {"kind", "points", "points_file", "speed_unit", "unit", "shaft", "description"},
    }
    if not isinstance(raw, dict):
        raise SceneError(where, 'must be a table, e.g. { kind = "induction", rated_power = "7.5 kW", ... }')
    kind = raw.get("kind")
    if not isinstance(kind, str) or kind not in kinds:  # a list or table is unhashable: refuse it as unknown
        raise SceneError(f"{where}.kind", f"{shorten(kind)} is not known (allowed: induction, dc, table)")
    table = Table(raw, where, kinds[kind])
    speed_ratio, name = 1.0, None
    if table.has("shaft"):
        name = table.get("shaft")
        match = [s for s in shafts if s.name == name]
        if not match:
            raise SceneError(
                f"{where}.shaft", f"no [[shaft]] is named {shorten(name)} (known: {', '.join(s.name for s in shafts)})"
            )
        speed_ratio = match[0].speed_ratio
    if kind == "table":
        return MotorTorque(_motor_table(table, where, files), speed_ratio, efficiency, None, where=where, shaft=name)
    motor: InductionMotor | DCMotor
    try:
        if kind == "induction":
            model = table.get("model", "linear")
            if model not in ("linear", "kloss"):
                raise SceneError(f"{where}.model", f"{shorten(model)} is not known (allowed: linear, kloss)")
            motor = InductionMotor(
                table.positive("rated_power", "power"),
                table.positive("rated_speed", "angular_speed"),
                table.positive("synchronous_speed", "angular_speed"),
                table.quantity("breakdown_ratio", "dimensionless"),
            )
        else:
            model = None
            if table.has("stall_torque"):
                motor = DCMotor(
                    table.positive("no_load_speed", "angular_speed"), table.positive("stall_torque", "torque")
                )
            else:
                motor = DCMotor.from_rated(
                    table.positive("rated_power", "power"),
                    table.positive("rated_speed", "angular_speed"),
                    table.positive("no_load_speed", "angular_speed"),
                )
    except ValueError as err:
        if isinstance(err, SceneError):
            raise
        raise SceneError(where, str(err)) from None
    return MotorTorque(motor, speed_ratio, efficiency, model, where=where, shaft=name)


def _motor_table(table, where, files):
    """A :class:`~flyopt.machine.motor.TableMotor` from ``points`` or ``points_file`` rows [speed, torque]."""
    from flyopt.machine.motor import TableMotor

    forms = [k for k in ("points", "points_file") if table.has(k)]
    if len(forms) != 1:
        raise SceneError(
            where,
            "a motor table needs exactly one of points = [[speed, torque], ...] or "
            'points_file = "motor.csv"' + (" (given both)" if forms else ""),
        )
    unit = unit_factor(table.get("unit"), "torque", f"{where}.unit") if table.has("unit") else 1.0
    speed_unit = (
        unit_factor(table.get("speed_unit"), "angular_speed", f"{where}.speed_unit") if table.has("speed_unit") else 1.0
    )
    field_name = f"{where}.{forms[0]}"
    if forms[0] == "points_file":
        units = (table.get("speed_unit", "rad/s"), table.get("unit", "N*m"))
        numbers, lines, name = csv_table(table.get("points_file"), field_name, files, ("speed", "torque"), units)
        speeds, torques = numbers[:, 0] * speed_unit, numbers[:, 1] * unit

        def row(k):
            return f"{name} line {lines[k]}"
    else:
        raw = table.get("points")
        if not isinstance(raw, (list, InlineRows)) or len(raw) < 2:
            raise SceneError(
                field_name, "must be a list of at least two [speed, torque] pairs, from rest to the no-load speed"
            )
        check_rows(len(raw), field_name)
        if isinstance(raw, InlineRows):
            speeds, torques = raw.array[:, 0] * speed_unit, raw.array[:, 1] * unit
        else:
            speeds, torques = np.empty(len(raw)), np.empty(len(raw))
            for k, pair in enumerate(raw):
                if not isinstance(pair, list) or len(pair) != 2:
                    raise SceneError(f"{field_name}[{k}]", f"must be a [speed, torque] pair, got {shorten(pair)}")
                speeds[k] = scaled(pair[0], "angular_speed", f"{field_name}[{k}] speed", speed_unit)
                torques[k] = scaled(pair[1], "torque", f"{field_name}[{k}] torque", unit)

        def row(k):
            return f"point {k}"

    steps = np.diff(speeds)
    if np.any(steps <= 0):
        k = int(np.argmax(steps <= 0)) + 1
        raise SceneError(
            field_name,
            f"speeds must increase: {row(k)} ({speeds[k]:.6g} rad/s) comes after "
            f"{speeds[k - 1]:.6g} rad/s (a torque-speed curve has one torque at each speed)",
        )
    if speeds[0] != 0.0:
        raise SceneError(
            field_name,
            f"the table starts at {speeds[0]:.6g} rad/s ({row(0)}); it must start at rest, "
            "speed 0, where its torque is the starting torque",
        )
    if torques[-1] > 0.0:
        raise SceneError(
            field_name,
            f"the torque at the last row ({row(len(speeds) - 1)}, {speeds[-1]:.6g} rad/s) "
            f"is {torques[-1]:.6g} N*m: the table must reach the motor's no-load speed (a torque of "
            "0 or below)",
        )
    if torques[-1] > torques[-2]:
        raise SceneError(
            field_name,
            f"the torque rises over the last segment ({row(len(speeds) - 2)} to "
            f"{row(len(speeds) - 1)}); it is extended beyond the last row, so it must not rise there",
        )
    return TableMotor(speeds.tolist(), torques.tolist())

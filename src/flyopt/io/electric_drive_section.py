"""The [electric_drive] section: a motor, its reduction stages and its load, in the electric-drive texts' terms."""

from __future__ import annotations

import math

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SPEED_RANGE, SPEED_WHY, Table, check_magnitude
from flyopt.io.shaft_section import RATIO_RANGE, check_series, read_efficiency
from flyopt.machine.electric_drive import ElectricDrive, Stage
from flyopt.units import inertia_from_gd2

KEYS = {
    "motor_gd2",
    "motor_inertia",
    "stages",
    "load_torque",
    "load_force",
    "load_radius",
    "acceleration",
    "description",
}
STAGE_KEYS = {"ratio", "speed", "efficiency", "gd2", "inertia", "description"}
MAX_STAGES = 64


def read_electric_drive(raw: object, motor_speed: float) -> ElectricDrive:
    """[electric_drive], the motor turning at ``motor_speed`` (machine.speed) [rad/s]."""
    table = Table(raw, "electric_drive", KEYS)
    motor = _gd2(table, "electric_drive", "motor_gd2", "motor_inertia")
    stages_raw = table.require("stages")
    if not isinstance(stages_raw, list) or not 1 <= len(stages_raw) <= MAX_STAGES:
        raise SceneError(
            "electric_drive.stages",
            f"must be a list of 1 to {MAX_STAGES} stages from the motor, each {{ ratio or speed, efficiency, gd2 }}",
        )
    stages, speed = [], motor_speed
    for k, item in enumerate(stages_raw):
        where = f"electric_drive.stages[{k}]"
        stage = Table(item, where, STAGE_KEYS)
        if stage.has("ratio") == stage.has("speed"):
            raise SceneError(
                f"{where}.ratio", "give exactly one of ratio (speed in / speed out) and speed (of the shaft after it)"
            )
        if stage.has("ratio"):
            ratio = stage.quantity("ratio", "dimensionless", required=True, own_range=True)
            if not (math.isfinite(ratio) and ratio > 0):
                raise SceneError(f"{where}.ratio", f"must be positive, got {shorten(stage.raw('ratio'))}")
            check_magnitude(ratio, f"{where}.ratio", stage.raw("ratio"), *RATIO_RANGE, "", "a gear train's ratio")
        else:
            after = stage.quantity("speed", "angular_speed", required=True, own_range=True)
            if not (math.isfinite(after) and after > 0):
                raise SceneError(f"{where}.speed", f"must be positive, got {shorten(stage.raw('speed'))}")
            ratio = speed / after
            check_magnitude(ratio, f"{where}.speed", stage.raw("speed"), *RATIO_RANGE, "", "a gear train's ratio")
        eta = read_efficiency(stage.get("efficiency"), f"{where}.efficiency") if stage.has("efficiency") else 1.0
        stages.append(Stage(ratio, eta, _gd2(stage, where, "gd2", "inertia")))
        speed /= ratio
        if not SPEED_RANGE[0] <= speed <= SPEED_RANGE[1]:  # the ratios in series (60 of 1e-6 overflowed)
            raise SceneError(
                f"{where}.{'ratio' if stage.has('ratio') else 'speed'}",
                f"the shaft after it would turn at {speed:.3g} rad/s (allowed: {SPEED_RANGE[0]:g} to "
                f"{SPEED_RANGE[1]:g} rad/s, {SPEED_WHY})",
            )
    check_series([s.efficiency for s in stages], "electric_drive.stages")
    if table.has("load_torque") and (table.has("load_force") or table.has("load_radius")):
        raise SceneError(
            "electric_drive.load_force", "give either load_torque or load_force with load_radius, not both"
        )
    if table.has("load_force") or table.has("load_radius"):
        for key in ("load_force", "load_radius"):
            if not table.has(key):
                raise SceneError(
                    f"electric_drive.{key}", "is needed with the other of load_force and load_radius (T = F r)"
                )
        force = table.quantity("load_force", "force", required=True)
        radius = table.quantity("load_radius", "length", required=True)
        if not (math.isfinite(radius) and radius > 0):
            raise SceneError("electric_drive.load_radius", f"must be positive, got {shorten(table.raw('load_radius'))}")
        torque = force * radius
    else:
        torque = table.quantity("load_torque", "torque", default=0.0)
    if not math.isfinite(torque):
        raise SceneError("electric_drive.load_torque", "must be finite")
    acceleration = table.quantity("acceleration", "angular_acceleration")
    if acceleration is not None and not math.isfinite(acceleration):
        raise SceneError("electric_drive.acceleration", f"must be finite, got {shorten(table.raw('acceleration'))}")
    return ElectricDrive(motor_speed, motor, tuple(stages), torque, acceleration)


def _gd2(table: Table, where: str, gd2_key: str, inertia_key: str) -> float:
    """A flywheel moment GD² [N*m²], given as GD² or as an inertia J (GD² = 4 g J); 0 when neither."""
    if table.has(gd2_key) and table.has(inertia_key):
        raise SceneError(f"{where}.{inertia_key}", f"give either {gd2_key} or {inertia_key}, not both (GD² = 4 g J)")
    if table.has(inertia_key):  # each held to its dimension's sizes (flyopt.units.MAGNITUDES) as it is read
        j = table.quantity(inertia_key, "inertia", required=True)
        value = j / inertia_from_gd2(1.0)
        key = inertia_key
    else:
        value = table.quantity(gd2_key, "flywheel_moment", default=0.0)
        key = gd2_key
    if not (math.isfinite(value) and value >= 0):
        raise SceneError(f"{where}.{key}", f"must be >= 0, got {shorten(table.raw(key))}")
    return value

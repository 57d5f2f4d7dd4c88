"""The [mechanism] and the [[member]]s whose inertia and loads are reduced to the reference shaft."""

from __future__ import annotations

from pathlib import Path
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.angle_tables import angle_curve, angle_curve_file
from flyopt.io.fields import Table, scaled, unit_factor
from flyopt.io.toml_file import InlineRows
from flyopt.units import DIMENSIONS, quantity

if TYPE_CHECKING:
    from collections.abc import Sequence

    from flyopt.machine.engine import Engine
    from flyopt.machine.kinematics import GearTrain, SliderCrank
    from flyopt.machine.mechanism import Member


def read_mechanism(raw: object) -> SliderCrank | GearTrain | None:
    """The [mechanism] section: a slider-crank or a gear train (None when the scene gives none)."""
    if raw is None:
        return None
    from flyopt.machine.kinematics import GearTrain, SliderCrank  # CasADi: only for a scene with a mechanism

    kind = raw.get("kind") if isinstance(raw, dict) else None
    try:
        if kind == "slider_crank":
            table = Table(raw, "mechanism", {"kind", "crank", "rod", "offset", "description"})
            return SliderCrank(
                table.quantity("crank", "length", required=True),
                table.quantity("rod", "length", required=True),
                table.quantity("offset", "length", default=0.0),
            )
        if kind == "gear_train":
            table = Table(raw, "mechanism", {"kind", "ratios", "description"})
            ratios = table.require("ratios")
            if not isinstance(ratios, list) or not ratios:
                raise SceneError("mechanism.ratios", "must be a list of stage speed ratios ω_out/ω_in")
            return GearTrain([quantity(r, "dimensionless", f"mechanism.ratios[{k}]") for k, r in enumerate(ratios)])
    except ValueError as err:
        if isinstance(err, SceneError):
            raise
        raise SceneError("mechanism", str(err)) from None
    raise SceneError("mechanism.kind", f"{shorten(kind)} is not known (allowed: slider_crank, gear_train)")


def read_members(
    raw: object, mechanism: SliderCrank | GearTrain | None, cycle: float, files: Path = Path()
) -> tuple[Member, ...]:
    """The [[member]] tables: members whose inertia and loads are reduced to the reference shaft."""
    if raw is None:
        return ()
    from flyopt.machine.kinematics import GearTrain  # CasADi: only with members
    from flyopt.machine.mechanism import FORCE_SENSES, Member

    if not isinstance(raw, list):
        raise SceneError("member", "must be an array of tables: [[member]] with name, mass, ...")
    members, seen = [], set()
    for k, item in enumerate(raw):
        where = f"member[{k}]"
        table = Table(
            item,
            where,
            {
                "name",
                "mass",
                "inertia",
                "part",
                "centre",
                "velocity_ratio",
                "angular_ratio",
                "force",
                "force_sense",
                "torque",
                "unit",
                "angle_unit",
                "description",
                *(f"{key}_file" for key in _MEMBER_TABLES),
            },
        )
        name = table.require("name")
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{where}.name", f"must be a non-empty string, got {shorten(name)}")
        if name in seen:
            raise SceneError(f"{where}.name", f"member {shorten(name)} is given twice")
        seen.add(name)
        angle_unit = (
            unit_factor(table.get("angle_unit"), "angle", f"{where}.angle_unit") if table.has("angle_unit") else 1.0
        )
        mass = table.quantity("mass", "mass", default=0.0)
        inertia = table.quantity("inertia", "inertia", default=0.0)
        for key, value in (("mass", mass), ("inertia", inertia)):
            if value < 0:
                raise SceneError(f"{where}.{key}", "must not be negative")
        if table.has("part"):
            if any(
                table.has(k) for k in ("velocity_ratio", "angular_ratio", "velocity_ratio_file", "angular_ratio_file")
            ):
                raise SceneError(
                    f"{where}.part",
                    "give either part (ratios from [mechanism]) or velocity_ratio/angular_ratio, not both",
                )
            if mechanism is None:
                raise SceneError(f"{where}.part", "needs a [mechanism] to take the ratios from")
            part = table.get("part")
            try:
                if isinstance(mechanism, GearTrain):
                    if isinstance(part, bool) or not isinstance(part, int):
                        raise SceneError(
                            f"{where}.part",
                            f"a gear train's part is a shaft number 0...{len(mechanism.ratios)}, got {shorten(part)}",
                        )
                    kin = mechanism.kinematics(part)
                else:
                    centre = table.quantity("centre", "length") if table.has("centre") else None
                    kin = mechanism.kinematics(part, centre)
            except ValueError as err:
                if isinstance(err, SceneError):
                    raise
                raise SceneError(f"{where}.part", str(err)) from None
            velocity, angular = kin.velocity_ratio, kin.angular_ratio
        else:
            velocity = _member_curve(table, "velocity_ratio", "length", where, angle_unit, cycle, 0.0, files)
            angular = _member_curve(table, "angular_ratio", "dimensionless", where, angle_unit, cycle, 0.0, files)
        force = _member_curve(table, "force", "force", where, angle_unit, cycle, None, files)
        torque = _member_curve(table, "torque", "torque", where, angle_unit, cycle, None, files)
        sense = table.get("force_sense", "resisting")
        if sense not in FORCE_SENSES:
            raise SceneError(
                f"{where}.force_sense", f"{shorten(sense)} is not known (allowed: {', '.join(FORCE_SENSES)})"
            )
        try:
            members.append(Member(name, mass, inertia, velocity, angular, force, sense, torque))
        except ValueError as err:
            raise SceneError(where, str(err)) from None
    return tuple(members)


def with_engine(
    engine: Engine, mechanism: SliderCrank | GearTrain | None, members: Sequence[Member]
) -> tuple[Member, ...]:
    """The engine's pistons and rods followed by the scene's own [[member]]s (names checked apart)."""
    if mechanism is not None:
        raise SceneError(
            "mechanism",
            "an [engine] brings its own slider-cranks, one per cylinder; a [mechanism] "
            "cannot be added to it (give other members their velocity_ratio and angular_ratio)",
        )
    own = {m.name for m in engine.members}
    for k, member in enumerate(members):
        if member.name in own:
            raise SceneError(
                f"member[{k}].name", f"{shorten(member.name)} is the name of a member of the [engine]; choose another"
            )
    return engine.members + tuple(members)


_MEMBER_TABLES = ("force", "torque", "velocity_ratio", "angular_ratio")
"""Member fields that may be a table over the angle, inline or from a CSV file (``force_file``, ...)."""


def _member_curve(table, key, dimension, where, angle_unit, cycle, default, files=Path()):
    """A member's number or [[angle, value], ...] table (values with units or plain SI), or ``KEY_file``'s CSV."""
    file_key = f"{key}_file"
    if table.has(key) and table.has(file_key):
        raise SceneError(f"{where}.{file_key}", f"give either {key} or {file_key}, not both")
    if not table.has(key) and not table.has(file_key):
        return default
    unit = 1.0
    if table.has("unit") and key in ("force", "torque"):
        unit = unit_factor(table.get("unit"), dimension, f"{where}.unit")
    if table.has(file_key):
        units = (
            table.get("angle_unit", "rad"),
            table.get("unit")
            if table.has("unit") and key in ("force", "torque")
            else DIMENSIONS[dimension][1] or "plain numbers",
        )
        curve = angle_curve_file(
            table.get(file_key), f"{where}.{file_key}", files, cycle, unit, angle_unit, key.replace("_", " "), units
        )
        return (curve.angles, curve.values)
    raw = table.get(key)
    field_name = f"{where}.{key}"
    if not isinstance(raw, (list, InlineRows)):
        return scaled(raw, dimension, field_name, unit)
    curve = angle_curve(raw, field_name, cycle, unit, angle_unit, dimension)
    return (curve.angles, curve.values)

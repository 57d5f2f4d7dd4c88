"""The [mechanism] and the [[member]]s whose inertia and loads are reduced to the reference shaft."""

from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.angle_tables import angle_curve, angle_curve_file
from flyopt.io.fields import Table, check_count, scaled, unit_factor
from flyopt.io.shaft_section import RATIO_RANGE
from flyopt.io.toml_file import InlineRows
from flyopt.units import DIMENSIONS, quantity

if TYPE_CHECKING:
    from collections.abc import Sequence

    from flyopt.machine.engine import Engine
    from flyopt.machine.kinematics import GearTrain, SliderCrank
    from flyopt.machine.linkages import Linkage
    from flyopt.machine.mechanism import Member

MECHANISM_KINDS = ("slider_crank", "gear_train", "guide_bar", "four_bar", "cam")
"""The kinds of [mechanism] a scene may name."""

_LINKAGE_KEYS = {"kind", "speed_ratio", "phase", "description"}
"""Keys every guide_bar, four_bar and cam takes: its input's speed against the reference shaft and its phase."""


MAX_MEMBERS = 64
"""Most [[member]] tables, and most segments of a cam's motion, a scene may give (each is summed at every angle)."""
#: Farthest a member's centre of mass may sit from its part's pivot [m]: beyond it J_e overflows.
MAX_CENTRE = 1e3


def read_mechanism(raw: object) -> SliderCrank | GearTrain | Linkage | None:
    """The [mechanism] section: a slider-crank, a gear train, a guide-bar, a four-bar or a cam (None when none)."""
    if raw is None:
        return None
    from flyopt.machine.kinematics import GearTrain, SliderCrank  # CasADi: only for a scene with a mechanism

    kind = raw.get("kind") if isinstance(raw, dict) else None
    try:
        if kind in ("guide_bar", "four_bar", "cam"):
            return _read_linkage(raw, kind)
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
    raise SceneError("mechanism.kind", f"{shorten(kind)} is not known (allowed: {', '.join(MECHANISM_KINDS)})")


def _read_linkage(raw: object, kind: str) -> Linkage:
    """A guide_bar, four_bar or cam, in the book's terms (link lengths, angles, the follower's laws)."""
    from flyopt.machine.linkages import CAM_LAWS, CAM_MOTIONS, Cam, FourBar, GuideBar

    if kind == "guide_bar":
        table = Table(raw, "mechanism", _LINKAGE_KEYS | {"crank", "frame", "lever"})
    elif kind == "four_bar":
        table = Table(raw, "mechanism", _LINKAGE_KEYS | {"crank", "coupler", "rocker", "frame", "branch"})
    else:
        table = Table(raw, "mechanism", _LINKAGE_KEYS | {"lift", "segments"})
    speed_ratio = table.quantity("speed_ratio", "dimensionless", default=1.0, own_range=True)
    if not RATIO_RANGE[0] <= abs(speed_ratio) <= RATIO_RANGE[1]:
        raise SceneError(
            "mechanism.speed_ratio",
            f"{shorten(table.raw('speed_ratio'))} is out of range (allowed: {RATIO_RANGE[0]:g} to {RATIO_RANGE[1]:g} "
            "in size; the inertias scale as its square)",
        )
    phase = table.quantity("phase", "angle", default=0.0)
    if kind == "guide_bar":
        return GuideBar(
            table.quantity("crank", "length", required=True),
            table.quantity("frame", "length", required=True),
            table.quantity("lever", "length"),
            speed_ratio,
            phase,
        )
    if kind == "four_bar":
        branch = table.get("branch", "open")
        if branch not in ("open", "crossed"):
            raise SceneError("mechanism.branch", f"{shorten(branch)} is not known (allowed: open, crossed)")
        a, b, c, d = (table.quantity(key, "length", required=True) for key in ("crank", "coupler", "rocker", "frame"))
        return FourBar(a, b, c, d, branch, speed_ratio, phase)
    lift = table.quantity("lift", "length")
    segments = table.require("segments")
    if not isinstance(segments, list) or not segments:
        raise SceneError("mechanism.segments", "must be a list of tables {motion, law, angle, lift}")
    check_count(segments, "mechanism.segments", MAX_MEMBERS, "segments")
    rows = []
    for k, item in enumerate(segments):
        where = f"mechanism.segments[{k}]"
        row = Table(item, where, {"motion", "law", "angle", "lift"})
        motion = row.require("motion")
        if motion not in CAM_MOTIONS:
            raise SceneError(f"{where}.motion", f"{shorten(motion)} is not known (allowed: {', '.join(CAM_MOTIONS)})")
        angle = row.quantity("angle", "angle", required=True)
        if motion == "dwell":
            for key in ("law", "lift"):
                if row.has(key):
                    raise SceneError(f"{where}.{key}", "a dwell has no law and no lift")
            rows.append((motion, None, angle, 0.0))
            continue
        law = row.require("law")
        if law not in CAM_LAWS:
            raise SceneError(f"{where}.law", f"{shorten(law)} is not known (allowed: {', '.join(CAM_LAWS)})")
        h = row.quantity("lift", "length", default=lift) if row.has("lift") or lift is not None else None
        if h is None:
            raise SceneError(f"{where}.lift", "is missing (give it here or the cam's lift in [mechanism])")
        rows.append((motion, law, angle, h))
    return Cam(rows, speed_ratio, phase)


def read_members(
    raw: object, mechanism: SliderCrank | GearTrain | Linkage | None, cycle: float, files: Path = Path()
) -> tuple[Member, ...]:
    """The [[member]] tables: members whose inertia and loads are reduced to the reference shaft."""
    if raw is None:
        return ()
    from flyopt.machine.kinematics import GearTrain  # CasADi: only with members
    from flyopt.machine.linkages import Linkage
    from flyopt.machine.mechanism import FORCE_SENSES, Member

    if not isinstance(raw, list):
        raise SceneError("member", "must be an array of tables: [[member]] with name, mass, ...")
    check_count(raw, "member", MAX_MEMBERS, "[[member]] tables")
    members, seen = [], set[str]()
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
        name = table.unique_name("member", seen)
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
            if isinstance(mechanism, Linkage):
                turns = cycle / mechanism.period
                if abs(turns - round(turns)) > 1e-9 * max(turns, 1.0) or round(turns) < 1:
                    raise SceneError(
                        "mechanism.speed_ratio",
                        f"the mechanism repeats every {math.degrees(mechanism.period):.10g} deg of the reference "
                        f"shaft, which does not divide machine.cycle ({math.degrees(cycle):.10g} deg)",
                    )
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
                    if centre is not None and not abs(centre) <= MAX_CENTRE:
                        raise SceneError(
                            f"{where}.centre",
                            f"{shorten(table.raw('centre'))} is out of range (allowed: within {MAX_CENTRE:g} m of "
                            "the part's pivot)",
                        )
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
    engine: Engine, mechanism: SliderCrank | GearTrain | Linkage | None, members: Sequence[Member]
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
            table.get(file_key),
            f"{where}.{file_key}",
            files,
            cycle,
            unit,
            angle_unit,
            key.replace("_", " "),
            units,
            dimension=dimension,
        )
        return (curve.angles, curve.values)
    raw = table.get(key)
    field_name = f"{where}.{key}"
    if not isinstance(raw, (list, InlineRows)):
        return scaled(raw, dimension, field_name, unit)
    curve = angle_curve(raw, field_name, cycle, unit, angle_unit, dimension)
    return (curve.angles, curve.values)

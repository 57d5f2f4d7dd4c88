"""A described [[shaft]]'s ``train``: the drive train's torsional elements from the motor to the crank.

Each element is an inline table of one kind (docs/flywheel-design.md, section 26):

- an inertia: ``{ name = "motor pulley", shaft = "motor", inertia = "0.008 kg*m^2" }`` (or ``gd2``), or
  ``{ name = "motor rotor", shaft = "motor" }``, which takes the rest of that [[shaft]]'s ``inertia``
  (the one the energy method already counts; all of it when the train puts nothing else on that shaft):
  the inertias a train puts on a shaft add up to its [[shaft]]'s ``inertia``, so the sizing and the
  torsional model never disagree;
- the wheel being designed: ``{ flywheel = true }``, once, on this shaft;
- an elastic element between two inertias: ``{ stiffness = "250 kN*m/rad" }`` (a coupling),
  ``{ length = "120 mm", diameter = "48 mm" }`` (a shaft piece, in this shaft's ``material`` unless
  it names its own), ``{ belt = "2.4 MN/m", radius = "90 mm" }`` (two spans of that stretch stiffness
  on a pulley of that radius on the inertia before it), or ``{ span = ["wheel_at", "torque_at"] }``
  (this shaft's own steps between two positions, each a length or ``wheel_at`` / ``torque_at``).

Inertias with nothing elastic between them turn together (a gear mesh: the two wheels on shafts of
different speed ratios). The cycle's net torque enters at the last inertia.
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import Table, check_count, check_line
from flyopt.machine.drive_train import TrainInertia, TrainSpring
from flyopt.units import MAGNITUDES, inertia_from_gd2, quantity

if TYPE_CHECKING:
    from flyopt.machine.shaft_layout import ShaftLayout
    from flyopt.machine.transmission import Shaft

__all__ = ["read_train"]

#: The key that says which kind an element is (an inertia gives ``inertia``, ``gd2`` or only ``shaft``).
KIND_KEYS = {"flywheel": "flywheel", "stiffness": "stiffness", "length": "piece", "belt": "belt", "span": "span"}
ALLOWED = {"name", "shaft", "inertia", "gd2", "flywheel", "stiffness", "length", "diameter", "material", "belt"}
ALLOWED |= {"radius", "span"}
#: An inertia that takes the rest of its [[shaft]]'s (replaced before the train is returned).
REST = -1.0
MIN_GAP = MAGNITUDES["length"][0]
"""The least distance between two places on a shaft that must differ (a step's ends, the bearings,
the wheel and where the torque enters, a span's ends) [m]: the least length a scene gives, a micron. Torque
entering 1e-13 m from the wheel made the torsional model's stiffness so large that its forced response
failed ("a natural frequency of the undamped system")."""


def apart(a: float, b: float) -> bool:
    """Whether two places on a shaft are :data:`MIN_GAP` apart, to the round-off of their millimetres
    (300.001 mm is a micron from 300 mm; 16004.001 mm from 16004 mm by 1e-15 m less: the tolerance, a
    picometre, is ten times the spacing of the doubles at a shaft's greatest length, 1 km)."""
    return abs(b - a) >= MIN_GAP * (1.0 - 1e-6)


MAX_ELEMENTS = 128
"""Most elements of a drive train: its torsional model grows with their square (4,012 elements took 9.7 s and
410 MB, 40,000 would take gigabytes); a sixteen-cylinder engine's crankshaft is some 35."""

#: Relative agreement asked of a shaft's train inertias with its [[shaft]] inertia.
INERTIA_RTOL = 1e-9


def read_train(
    raw: object, where: str, own: Shaft, layout: ShaftLayout, shafts: tuple[Shaft, ...]
) -> tuple[TrainInertia | TrainSpring, ...]:
    """The train of the described shaft ``own`` (its ``layout``), its shafts' names resolved to speed ratios.

    Raises
    ------
    SceneError
        Naming ``{where}[j]`` and the field: an element of no or two kinds, an unknown shaft, a
        non-positive value, two elastic elements in a row or one at an end, no or two flywheels,
        an elastic element other than a belt between shafts of different speed ratios, or inertias
        that do not add up to their [[shaft]]'s.
    """
    if not isinstance(raw, list) or len(raw) < 3:
        raise SceneError(
            where,
            "must be a list of the drive train's elements from the motor to the crank, at least an inertia, an "
            'elastic element and an inertia, e.g. [{ flywheel = true }, { span = ["wheel_at", "torque_at"] }, '
            '{ name = "crank", shaft = "crankshaft" }]',
        )
    check_count(raw, where, MAX_ELEMENTS, "elements")
    by_name = {s.name: s for s in shafts}
    out: list[TrainInertia | TrainSpring] = []
    for j, item in enumerate(raw):
        at = f"{where}[{j}]"
        table = Table(item, at, ALLOWED)
        kinds = [key for key in KIND_KEYS if table.has(key)]
        if len(kinds) > 1:
            raise SceneError(f"{at}.{kinds[1]}", f"an element is one thing: {kinds[0]} and {kinds[1]} given together")
        name = table.get("name", "")
        if not isinstance(name, str):
            raise SceneError(f"{at}.name", f"must be a text, got {shorten(name)}")
        check_line(name, f"{at}.name")
        if not kinds:
            out.append(_inertia(table, at, name, own, by_name))
            continue
        kind = KIND_KEYS[kinds[0]]
        if kind == "flywheel":
            if table.get("flywheel") is not True:
                raise SceneError(f"{at}.flywheel", f"must be true (the designed wheel's place), got {shorten(item)}")
            _only(table, at, {"flywheel", "name", "shaft"})
            if table.has("shaft") and table.get("shaft") != own.name:
                raise SceneError(
                    f"{at}.shaft",
                    f"the flywheel sits on this shaft, {own.name!r}, at its wheel_at, got {shorten(table.raw('shaft'))}",
                )
            out.append(TrainInertia(name or "flywheel", own.name, own.speed_ratio, None))
            continue
        if not out:
            raise SceneError(at, "an elastic element must come between two inertias (an inertia or the flywheel first)")
        before = out[-1]
        if not isinstance(before, TrainInertia):
            raise SceneError(at, "two elastic elements in a row: put an inertia between them")
        out.append(_spring(table, at, kind, name, before, own, layout))
    _check_train(out, where, own, by_name)
    return tuple(out)


def _only(table: Table, at: str, keys: set[str]) -> None:
    extra = sorted(set(table.data) - keys)
    if extra:
        raise SceneError(
            f"{at}.{extra[0]}", f"does not belong to this kind of element (allowed: {', '.join(sorted(keys))})"
        )


def _inertia(table: Table, at: str, name: str, own: Shaft, by_name: dict[str, Shaft]) -> TrainInertia:
    _only(table, at, {"name", "shaft", "inertia", "gd2"})
    shaft_name = table.get("shaft", own.name)
    if not isinstance(shaft_name, str) or shaft_name not in by_name:
        raise SceneError(f"{at}.shaft", f"no [[shaft]] is named {shorten(shaft_name)} (known: {', '.join(by_name)})")
    shaft = by_name[shaft_name]
    if table.has("inertia") and table.has("gd2"):
        raise SceneError(f"{at}.gd2", "give either inertia or gd2, not both (the same inertia, GD² = 4 g J)")
    if table.has("inertia") or table.has("gd2"):
        key = "gd2" if table.has("gd2") else "inertia"
        value = table.quantity(key, "flywheel_moment" if key == "gd2" else "inertia", required=True)
        if not (math.isfinite(value) and value > 0.0):
            raise SceneError(f"{at}.{key}", f"must be positive, got {shorten(table.raw(key))}")
        inertia = inertia_from_gd2(value) if key == "gd2" else value
    else:
        inertia = REST  # the rest of that [[shaft]]'s inertia, found once the whole train is read
    return TrainInertia(name or shaft.name, shaft.name, shaft.speed_ratio, inertia)


def _spring(
    table: Table, at: str, kind: str, name: str, before: TrainInertia, own: Shaft, layout: ShaftLayout
) -> TrainSpring:
    shaft, ratio = before.shaft, before.ratio
    if kind == "stiffness":
        _only(table, at, {"name", "stiffness"})
        k = _positive(table, "stiffness", at, "torsional_stiffness")
        return TrainSpring(name or "coupling", kind, shaft, ratio, stiffness=k)
    if kind == "piece":
        _only(table, at, {"name", "length", "diameter", "material"})
        length = _positive(table, "length", at, "length")
        diameter = _positive(table, "diameter", at, "length")
        material = table.get("material", layout.material)
        if not isinstance(material, str) or not material.strip():
            raise SceneError(f"{at}.material", f"must be a material's name, got {shorten(material)}")
        return TrainSpring(
            name or "shaft piece", kind, shaft, ratio, length=length, diameter=diameter, material=material.strip()
        )
    if kind == "belt":
        _only(table, at, {"name", "belt", "radius"})
        k_b = _positive(table, "belt", at, "stiffness")
        radius = _positive(table, "radius", at, "length")
        return TrainSpring(name or "belt", kind, shaft, ratio, stiffness=k_b, radius=radius)
    _only(table, at, {"name", "span"})
    ends = table.get("span")
    if not isinstance(ends, list) or len(ends) != 2:
        raise SceneError(
            f"{at}.span", f'must be two positions on this shaft, e.g. ["wheel_at", "torque_at"], got {shorten(ends)}'
        )
    named = {"wheel_at": layout.wheel_at, "torque_at": layout.torque_at}
    xs = []
    for e, end in enumerate(ends):
        x = named[end] if isinstance(end, str) and end in named else quantity(end, "length", f"{at}.span[{e}]")
        if not (math.isfinite(x) and 0.0 <= x <= layout.length):
            raise SceneError(
                f"{at}.span[{e}]",
                f"must lie on the shaft, 0 to {layout.length * 1e3:g} mm, or be wheel_at or torque_at, got {shorten(end)}",
            )
        xs.append(x)
    if not apart(xs[0], xs[1]):
        raise SceneError(
            f"{at}.span", f"must be two positions at least {MIN_GAP * 1e3:g} mm apart, got {shorten(ends)}"
        )
    if before.shaft != own.name:
        raise SceneError(
            at, f"a span of {own.name!r}'s own steps must follow an inertia on that shaft, not on {before.shaft!r}"
        )
    return TrainSpring(name or "shaft", kind, shaft, ratio, start=min(xs), end=max(xs))


def _positive(table: Table, key: str, at: str, dimension: str) -> float:
    value = table.quantity(key, dimension, required=True)
    if not (math.isfinite(value) and value > 0.0):
        raise SceneError(f"{at}.{key}", f"must be positive, got {shorten(table.raw(key))}")
    return value


def _check_train(out: list[TrainInertia | TrainSpring], where: str, own: Shaft, by_name: dict[str, Shaft]) -> None:
    """The train's shape: inertias at both ends, one flywheel, the ratios across each element, the inertias' sums."""
    last = len(out) - 1
    if not isinstance(out[-1], TrainInertia):
        raise SceneError(
            f"{where}[{last}]", "the train must end with an inertia (the crank end), not an elastic element"
        )
    wheels = [j for j, e in enumerate(out) if isinstance(e, TrainInertia) and e.is_wheel]
    if len(wheels) != 1:
        raise SceneError(
            where if not wheels else f"{where}[{wheels[1]}].flywheel",
            "must place the designed wheel once: { flywheel = true }"
            + (f" (given {len(wheels)} times)" if wheels else ""),
        )
    if not any(isinstance(e, TrainSpring) for e in out):
        raise SceneError(where, "needs an elastic element between two inertias: a train of rigid inertias has no mode")
    for j, element in enumerate(out):
        if isinstance(element, TrainSpring):
            after = out[j + 1]  # an inertia: two elastic elements in a row are refused as they are read
            if element.kind != "belt" and not math.isclose(after.ratio, element.ratio, rel_tol=1e-12):
                raise SceneError(
                    f"{where}[{j}]",
                    f"joins shaft {element.shaft!r} (speed ratio {element.ratio:g}) to {after.shaft!r} "
                    f"({after.ratio:g}): only a belt joins shafts of different speeds elastically",
                )
    _resolve_rest(out, where, by_name)


def _resolve_rest(out: list[TrainInertia | TrainSpring], where: str, by_name: dict[str, Shaft]) -> None:
    """Each shaft's train inertias against its [[shaft]] ``inertia``: one element that gives none takes the rest
    (which must be positive); without one, they must add up to it."""
    given: dict[str, float] = {}
    rest: dict[str, int] = {}
    last: dict[str, int] = {}
    for j, element in enumerate(out):
        if not isinstance(element, TrainInertia) or element.inertia is None:
            continue
        last[element.shaft] = j
        if element.inertia == REST:
            if element.shaft in rest:
                raise SceneError(
                    f"{where}[{j}].inertia",
                    f"is missing, and {where}[{rest[element.shaft]}] already takes the rest of shaft "
                    f"{element.shaft!r}'s inertia: give this one's",
                )
            rest[element.shaft] = j
        else:
            given[element.shaft] = given.get(element.shaft, 0.0) + element.inertia
    for shaft_name, j in last.items():
        total, whole = given.get(shaft_name, 0.0), by_name[shaft_name].inertia
        if shaft_name in rest:
            k = rest[shaft_name]
            remainder = whole - total
            if not remainder > INERTIA_RTOL * whole:
                raise SceneError(
                    f"{where}[{k}].inertia",
                    f"is missing, and nothing is left of [[shaft]] {shaft_name!r}'s inertia ({whole:.6g} kg*m^2) "
                    f"after the train's others ({total:.6g} kg*m^2): give the inertia on that [[shaft]] "
                    "(the energy method counts it) or here",
                )
            element = out[k]
            if isinstance(element, TrainInertia):  # it is: rest[] holds inertias only
                out[k] = TrainInertia(element.name, element.shaft, element.ratio, remainder)
        elif not math.isclose(total, whole, rel_tol=INERTIA_RTOL):
            raise SceneError(
                f"{where}[{j}].inertia",
                f"the train's inertias on shaft {shaft_name!r} add up to {total:.6g} kg*m^2, but that [[shaft]]'s "
                f"inertia is {whole:.6g} kg*m^2 (the one the energy method counts): make them agree, or leave "
                "one out to take the rest",
            )

"""The [[shaft]]s a flywheel may sit on, and the efficiencies from the motor to the reference shaft."""

from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SAFETY_RANGE, SAFETY_WHY, Table, check_count, check_magnitude, check_scale
from flyopt.io.train_section import MIN_GAP, apart, read_train
from flyopt.machine.drive_train import TrainSpring
from flyopt.machine.shaft_layout import ShaftLayout, SideLoad
from flyopt.machine.transmission import Shaft, series_efficiency
from flyopt.units import inertia_from_gd2, quantity

if TYPE_CHECKING:
    from collections.abc import Iterable, Sequence

MAX_SHAFTS = 64
"""Most [[shaft]] tables a scene may give: each is a place the wheel may sit, designed and ranked in turn."""
MAX_STEPS = 64
"""Most steps (``segments``) of a described shaft, and most side ``loads`` on it: the beam's finite elements
grow with them (5,000 steps ran for over 5 minutes and 5.6 GB)."""

RATIO_RANGE = (1e-6, 1e6)
RATIO_WHY = "ω_shaft/ω_reference of a gear train"
"""Allowed speed ratio ω_shaft/ω_reference of a [[shaft]]: inertias scale as its square, beyond it they overflow."""


def read_shafts(raw: object) -> tuple[Shaft, ...]:
    """The [[shaft]] tables (the reference shaft alone when the scene gives none)."""
    if raw is None:
        return (Shaft("reference", 1.0),)
    if not isinstance(raw, list) or not raw:
        raise SceneError("shaft", "must be an array of tables: [[shaft]] with name and speed_ratio")
    check_count(raw, "shaft", MAX_SHAFTS, "[[shaft]] tables")
    seen: set[str] = set()
    shafts, trains = [], []
    for k, item in enumerate(raw):
        shaft, train = read_shaft(item, k, seen)
        shafts.append(shaft)
        if train is not NO_TRAIN:
            trains.append((k, train))
    for k, train in trains:  # after every shaft is read: a train names the other shafts
        shaft, layout = shafts[k], shafts[k].layout
        if layout is None:  # only a described shaft's train is kept (read_layout gave it)
            continue
        elements = read_train(train, f"shaft[{k}].train", shaft, layout, tuple(shafts))
        shafts[k] = dataclasses.replace(shaft, layout=dataclasses.replace(layout, train=elements))
    return tuple(shafts)


#: :func:`read_shaft`'s train of a shaft that gives none (or is no part): a train given as None is refused.
NO_TRAIN = object()


def read_shaft(item: object, k: int, seen: set[str]) -> tuple[Shaft, Any]:
    """The k-th [[shaft]] table (from 0) read alone, and its ``train`` as written (:data:`NO_TRAIN` where it gives
    none or is no part: its pieces name the other shafts, so :func:`read_shafts` reads it once all are read); ``seen``
    holds the names before it and takes this one's. ``flyopt check`` reads each table so, to name every wrong one."""
    where = f"shaft[{k}]"
    table = Table(
        item,
        where,
        {"name", "speed_ratio", "efficiency", "diameter", "inertia", "gd2", "description"} | LAYOUT_KEYS,
    )
    name = table.unique_name("shaft", seen)
    ratio = table.quantity("speed_ratio", "dimensionless", required=True, own_range=True)
    if ratio <= 0:
        raise SceneError(f"{where}.speed_ratio", f"must be positive (ω_shaft/ω_reference), got {shorten(ratio)}")
    check_magnitude(
        ratio,
        f"{where}.speed_ratio",
        table.raw("speed_ratio"),
        *RATIO_RANGE,
        "",
        RATIO_WHY,
    )
    eff = read_efficiency(table.get("efficiency"), f"{where}.efficiency") if table.has("efficiency") else 1.0
    if table.raw("diameter") == DESIGNED:
        raise SceneError(
            f"{where}.diameter",
            'cannot be "design" here: the design chooses a seat only on a shaft described as a part, as a '
            'step of its segments (segments = [..., { to = "520 mm", diameter = "design" }, ...])',
        )
    diameter = table.quantity("diameter", "length")
    if diameter is not None and diameter <= 0:
        raise SceneError(
            f"{where}.diameter", f"must be positive (the shaft seat), got {shorten(table.raw('diameter'))}"
        )
    layout = read_layout(table, where)
    if layout is not None and layout.designs_seat:
        if diameter is not None:
            raise SceneError(
                f"{where}.diameter",
                f"the seat {shorten(table.raw('diameter'))} is given, and the step under the wheel says "
                '"design": give one of them',
            )
    elif layout is not None:
        seat = layout.diameter_at(layout.wheel_at)
        if diameter is not None and not math.isclose(diameter, seat, rel_tol=1e-9):
            raise SceneError(
                f"{where}.diameter",
                f"the seat {shorten(table.raw('diameter'))} differs from the step under the wheel "
                f"({seat * 1e3:g} mm): give one of them",
            )
        diameter = seat
    shaft = Shaft(name, ratio, eff, diameter, _shaft_inertia(table, where), layout)
    return shaft, table.raw("train") if layout is not None and table.has("train") else NO_TRAIN


#: The keys of a [[shaft]] described as a part (docs/scene-schema.md); ``segments`` says it is described.
LAYOUT_KEYS = frozenset(
    {
        "segments",
        "bearings",
        "wheel_at",
        "torque_at",
        "material",
        "finish",
        "fillet",
        "loads",
        "balance_grade",
        "safety_factor",
        "max_slope",
        "max_deflection",
        "critical_margin",
        "train",
        "damping_ratio",
        "diameter_series",
    }
)


def read_layout(table: Table, where: str) -> ShaftLayout | None:
    """The shaft as a part, from a [[shaft]] that gives ``segments``; None when it gives none of its keys."""
    given = sorted(k for k in LAYOUT_KEYS if table.has(k))
    if not given:
        return None
    if not table.has("segments"):
        raise SceneError(
            f"{where}.segments",
            f"is missing: {given[0]} describes the shaft as a part, which needs its steps "
            '(segments = [{ to = "200 mm", diameter = "60 mm" }, ...])',
        )
    steps, diameters = _segments(table.raw("segments"), f"{where}.segments")
    designed = tuple(j for j, d in enumerate(diameters) if math.isnan(d))
    length = steps[-1]
    bearings = _positions(table, "bearings", where, length, count=2)
    if not apart(bearings[0], bearings[1]):
        raise SceneError(
            f"{where}.bearings",
            f"must be two positions at least {MIN_GAP * 1e3:g} mm apart, got {shorten(table.raw('bearings'))}",
        )
    wheel_at = _position(table.require("wheel_at"), f"{where}.wheel_at", length)
    torque_at = _position(table.require("torque_at"), f"{where}.torque_at", length)
    if not apart(torque_at, wheel_at):
        raise SceneError(
            f"{where}.torque_at",
            f"must be at least {MIN_GAP * 1e3:g} mm from wheel_at: the torque enters the shaft away from the wheel "
            "seat (crank, pinion, coupling) and the shaft between them twists",
        )
    material = table.require("material")
    if not isinstance(material, str) or not material.strip():
        raise SceneError(f"{where}.material", f"must be a material's name, got {shorten(material)}")
    finish = table.get("finish", "machined")
    from flyopt.design.shaft.strength import FINISHES

    if finish not in FINISHES:
        raise SceneError(
            f"{where}.finish", f"{shorten(finish)} is not a surface finish (allowed: {', '.join(FINISHES)})"
        )
    fillet = _positive(table, "fillet", where, "length", "the shoulders' fillet radius")
    grade = _positive(table, "balance_grade", where, "speed", "ISO 21940-11's G, e.g. '6.3 mm/s'")
    safety = _positive(table, "safety_factor", where, "dimensionless", "the factor of safety required", True)
    if safety is not None and safety < 1.0:
        raise SceneError(f"{where}.safety_factor", f"must be >= 1, got {shorten(table.raw('safety_factor'))}")
    if safety is not None:
        check_magnitude(safety, f"{where}.safety_factor", table.raw("safety_factor"), *SAFETY_RANGE, "", SAFETY_WHY)
    slope = _positive(table, "max_slope", where, "angle", "the slope allowed at a bearing")
    deflection = _positive(table, "max_deflection", where, "length", "the deflection allowed at the wheel")
    margin = table.quantity("critical_margin", "dimensionless", own_range=True)
    if margin is not None and not (math.isfinite(margin) and 0.0 <= margin < 1.0):
        raise SceneError(
            f"{where}.critical_margin",
            f"must be a share in [0, 1) of the running range's end, got {shorten(table.raw('critical_margin'))}",
        )
    damping = table.quantity("damping_ratio", "dimensionless", own_range=True)
    if damping is not None and not (math.isfinite(damping) and 0.0 < damping < 1.0):
        raise SceneError(
            f"{where}.damping_ratio",
            f"must be a ratio in (0, 1) (each torsional mode's modal damping), got {shorten(table.raw('damping_ratio'))}",
        )
    seat_step = next(j for j, end in enumerate(steps) if wheel_at <= end)
    if designed and seat_step not in designed:
        raise SceneError(
            f"{where}.segments[{seat_step}].diameter",
            f"must be \"design\" too: the designed diameter is the wheel seat's (the wheel's bore and key follow "
            f"it), and segments[{designed[0]}] asks for it",
        )
    series = table.get("diameter_series", "R40")
    from flyopt.design.preferred import SERIES

    if series not in SERIES:
        raise SceneError(
            f"{where}.diameter_series",
            f"{shorten(series)} is not a preferred-number series (allowed: {', '.join(SERIES)}, ISO 3)",
        )
    if table.has("diameter_series") and not designed:
        raise SceneError(
            f"{where}.diameter_series",
            'chooses the designed seat diameter: give a step diameter = "design", or leave it out',
        )
    options: dict[str, Any] = {
        "balance_grade": grade,
        "safety_factor": safety,
        "max_slope": slope,
        "critical_margin": margin,
        "damping_ratio": damping,
    }
    return ShaftLayout(
        steps,
        diameters,
        (bearings[0], bearings[1]),
        wheel_at,
        torque_at,
        material.strip(),
        finish=finish,
        fillet=fillet,
        loads=_side_loads(table.get("loads", []), f"{where}.loads", length),
        max_deflection=deflection,
        designed=designed,
        diameter_series=series,
        **{k: v for k, v in options.items() if v is not None},
    )


def _positive(table: Table, key: str, where: str, dimension: str, what: str, own_range: bool = False) -> float | None:
    value = table.quantity(key, dimension, own_range=own_range)
    if value is not None and not (math.isfinite(value) and value > 0.0):
        raise SceneError(f"{where}.{key}", f"must be positive ({what}), got {shorten(table.raw(key))}")
    return value


def _position(raw: object, where: str, length: float) -> float:
    x = quantity(raw, "length", where)
    check_scale(x, "length", where, raw)  # a micron from the end at least: 1e-300 m made the beam's FE matrix inf
    if not (math.isfinite(x) and 0.0 <= x <= length):
        raise SceneError(
            where, f"must lie on the shaft, 0 to {length * 1e3:g} mm (the last segment's end), got {shorten(raw)}"
        )
    return x


def _positions(table: Table, key: str, where: str, length: float, count: int) -> list[float]:
    raw = table.require(key)
    if not isinstance(raw, list) or len(raw) != count:
        raise SceneError(f"{where}.{key}", f"must be a list of {count} positions along the shaft, got {shorten(raw)}")
    return sorted(_position(r, f"{where}.{key}[{k}]", length) for k, r in enumerate(raw))


def _segments(raw: object, where: str) -> tuple[tuple[float, ...], tuple[float, ...]]:
    """The steps' ends and diameters [m] from ``[{ to = ..., diameter = ... }, ...]``, in order along the shaft."""
    if not isinstance(raw, list) or not raw:
        raise SceneError(where, 'must be a non-empty list of steps, e.g. [{ to = "200 mm", diameter = "60 mm" }, ...]')
    check_count(raw, where, MAX_STEPS, "steps")
    steps: list[float] = []
    diameters: list[float] = []
    for k, item in enumerate(raw):
        seg = Table(item, f"{where}[{k}]", {"to", "diameter"})
        end = seg.quantity("to", "length", required=True)
        design = seg.raw("diameter") == DESIGNED
        d = math.nan if design else seg.quantity("diameter", "length", required=True)
        previous = steps[-1] if steps else 0.0
        if not (math.isfinite(end) and end > previous and apart(previous, end)):
            raise SceneError(
                f"{where}[{k}].to",
                f"must be at least {MIN_GAP * 1e3:g} mm beyond the previous step's end ({previous * 1e3:g} mm), "
                f"got {shorten(seg.raw('to'))}",
            )
        if not design and not (math.isfinite(d) and d > 0.0):
            raise SceneError(
                f"{where}[{k}].diameter",
                f'must be positive, or "design" (the seat\'s, chosen by the design), got {shorten(seg.raw("diameter"))}',
            )
        steps.append(end)
        diameters.append(d)
    return tuple(steps), tuple(diameters)


#: A step's ``diameter`` the design chooses (docs/flywheel-design.md, section 26).
DESIGNED = "design"


def _side_loads(raw: object, where: str, length: float) -> tuple[SideLoad, ...]:
    if not isinstance(raw, list):
        raise SceneError(where, 'must be a list of loads, e.g. [{ at = "700 mm", force = "3 kN", angle = "90 deg" }]')
    check_count(raw, where, MAX_STEPS, "loads")
    loads = []
    for k, item in enumerate(raw):
        load = Table(item, f"{where}[{k}]", {"at", "force", "angle", "description"})
        at = _position(load.require("at"), f"{where}[{k}].at", length)
        force = load.quantity("force", "force", required=True)
        if not (math.isfinite(force) and force >= 0.0):
            raise SceneError(f"{where}[{k}].force", f"must be a finite force >= 0, got {shorten(load.raw('force'))}")
        if not isinstance(load.get("description", ""), str):
            raise SceneError(f"{where}[{k}].description", f"must be a text, got {shorten(load.raw('description'))}")
        angle = load.quantity("angle", "angle", default=0.0)
        if not math.isfinite(angle):
            raise SceneError(f"{where}[{k}].angle", f"must be a finite angle, got {shorten(load.raw('angle'))}")
        loads.append(SideLoad(at, force, angle))
    return tuple(loads)


def check_shaft_materials(shafts: Iterable[Shaft], library: dict) -> None:
    """Each described shaft's material is known and gives what the shaft's checks need (E, S_ut, S_y).

    Raises
    ------
    SceneError
        Naming ``shaft[k].material``: an unknown name (with the closest), or a material without them.
    """
    from flyopt.design.materials import get_material

    for k, shaft in enumerate(shafts):
        if shaft.layout is None:
            continue
        where = f"shaft[{k}].material"
        try:
            material = get_material(shaft.layout.material, library)
        except ValueError as err:
            raise SceneError(where, str(err)) from None
        if material.elastic_modulus is None:
            raise SceneError(where, f"{material.name!r} gives no elastic_modulus, which the shaft's deflection needs")
        given = [d for d in shaft.layout.diameters if not math.isnan(d)]
        try:
            sut, sy = material.strength(min(given, default=_smallest_seat(shaft.layout)))
        except ValueError as err:
            raise SceneError(where, str(err)) from None
        if sut is None or sy is None:
            raise SceneError(
                where, f"{material.name!r} gives no tensile and yield strength, which the shaft's fatigue check needs"
            )
        _check_fatigue_ranges(shaft.layout, material, f"shaft[{k}]")
        for j, element in enumerate(shaft.layout.train):
            if not isinstance(element, TrainSpring) or element.kind != "piece":
                continue
            at = f"shaft[{k}].train[{j}].material"
            try:
                piece = get_material(element.material, library)
            except ValueError as err:
                raise SceneError(at, str(err)) from None
            if piece.elastic_modulus is None:
                raise SceneError(
                    at, f"{piece.name!r} gives no elastic_modulus, which the piece's G = E/(2(1 + nu)) needs"
                )


def _check_fatigue_ranges(layout: ShaftLayout, material: Any, where: str) -> None:
    """Each step's diameter and strength within the ranges of Shigley's fits (k_b: 2.79-254 mm; Neuber's
    constant: S_ut 50-250 kpsi), refused here rather than when the design checks its first wheel."""
    from flyopt.design.shaft import strength

    for j, d in enumerate(layout.diameters):
        if math.isnan(d):  # designed: the search keeps to the fits' ranges (flyopt.design.shaft.diameter)
            continue
        try:
            sut = material.strength(d)[0]
            strength.endurance_limit(sut, d, layout.finish)
        except ValueError as err:
            raise SceneError(f"{where}.segments[{j}].diameter", str(err)) from None
        try:
            strength.notch_sensitivity(0.02 * d, sut)
        except ValueError as err:
            raise SceneError(f"{where}.material", f"{material.name!r}: {err}") from None


def _smallest_seat(layout: ShaftLayout) -> float:
    """The smallest diameter the design may give a designed seat [m]."""
    from flyopt.design.shaft.diameter import seat_series

    return seat_series(layout.diameter_series)[0]


def check_designed_seats(shafts: Iterable[Shaft], bore: float | None) -> None:
    """Refuse ``[design] bore`` beside a designed seat: the wheel's bore is the seat the design chooses.

    Raises
    ------
    SceneError
        Naming ``design.bore``.
    """
    designed = next((s.name for s in shafts if s.layout is not None and s.layout.designs_seat), None)
    if designed is not None and bore is not None:
        raise SceneError(
            "design.bore",
            f'is given, and [[shaft]] {designed!r} designs its seat (a step diameter = "design"), which is the '
            "wheel's bore: leave design.bore out",
        )


#: The largest inertia a [[shaft]] may carry [kg*m^2]: a thousand times a large turbine-generator train's
#: (about 1e5 to 1e6). Beyond it the flywheel, the machine's inertia minus round-off, is lost in the sum
#: J_F + J_e of the periodic model (1e300 made it exactly 0).
MAX_SHAFT_INERTIA = 1e9


def _shaft_inertia(table, where):
    """The inertia already on a [[shaft]], about its axis [kg*m^2]: ``inertia``, or ``gd2`` (GD² = 4 g J), or 0."""
    if table.has("inertia") and table.has("gd2"):
        raise SceneError(f"{where}.gd2", "give either inertia or gd2, not both (the same inertia, GD² = 4 g J)")
    key = "gd2" if table.has("gd2") else "inertia"
    if not table.has(key):
        return 0.0
    value = table.quantity(key, "flywheel_moment" if key == "gd2" else "inertia", own_range=True)
    if not (math.isfinite(value) and value >= 0):
        raise SceneError(
            f"{where}.{key}",
            f"must be a finite number >= 0 (the inertia already turning with the shaft), got {shorten(table.raw(key))}",
        )
    inertia = inertia_from_gd2(value) if key == "gd2" else value
    if inertia > MAX_SHAFT_INERTIA:
        raise SceneError(
            f"{where}.{key}",
            f"{shorten(table.raw(key))} is beyond any machine's shaft (allowed: at most {MAX_SHAFT_INERTIA:g} kg*m^2; "
            "a turbine-generator's whole train is about 1e5 to 1e6 kg*m^2)",
        )
    return inertia


def reference_efficiency(shafts: Iterable[Shaft]) -> float:
    """Efficiency from the motor to the reference shaft: that of the shaft turning at ratio 1."""
    at_reference = {s.efficiency for s in shafts if s.speed_ratio == 1.0}
    if len(at_reference) > 1:
        raise SceneError(
            "machine.efficiency",
            "several shafts turn at the reference speed with different "
            "efficiencies; say which applies with machine.efficiency",
        )
    return at_reference.pop() if at_reference else 1.0


def read_efficiency(raw: object, where: str) -> float:
    """An efficiency in (0, 1], or a list of stage efficiencies in series (their product)."""
    return series_efficiency(read_stages(raw, where))


SERIES_LEAST = 1e-9
"""Least efficiency of stages in series, their product: each stage's may be any in (0, 1], but a chain that passes
on less than a billionth of its power is no transmission, and 60 stages of 1e-6 underflowed to 0 (a "float
division by zero", exit 1, naming no field)."""


def check_series(etas: Sequence[float], where: str) -> float:
    """The product of efficiencies in series, refused below :data:`SERIES_LEAST` naming ``where``."""
    product = math.prod(etas)
    if product < SERIES_LEAST:
        raise SceneError(
            where,
            f"the efficiencies in series multiply to {product:.3g} (allowed: at least {SERIES_LEAST:g}; less passes on "
            "no power to speak of)",
        )
    return product


def read_stages(raw: object, where: str) -> tuple[float, ...]:
    """Stage efficiencies in series: one number in (0, 1], or a non-empty list of them, each named in an error;
    their product at least :data:`SERIES_LEAST`."""
    stages = raw if isinstance(raw, list) else [raw]
    if not stages:
        raise SceneError(where, "must be a number in (0, 1] or a non-empty list of stage efficiencies")
    etas = []
    for k, s in enumerate(stages):
        label = f"{where}[{k}]" if isinstance(raw, list) else where
        eta = quantity(s, "dimensionless", label)
        if not 0 < eta <= 1:
            raise SceneError(label, f"must lie in (0, 1], got {shorten(s)}")
        etas.append(eta)
    check_series(etas, where)
    return tuple(etas)

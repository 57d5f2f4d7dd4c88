"""[press]: a press or shear from its process data, read and checked, and written as a scene.

A scene with a [press] table gives the process instead of the torques::

    [press]
    strokes_per_minute = 12         # or strokes_per_hour = 720, or stroke_period = "5 s"
    energy_per_stroke = "15 kJ"     # or force = [[position, force], ...] over the working stroke,
                                    # or punching = { thickness, shear_strength or energy_per_area,
                                    #                 hole_diameter or cut_length }
    working_time = "2 s"            # or working_angle = "144 deg" of the crank
    slowdown = 0.111                # (ω_top − ω_bottom)/ω_top over the working stroke; or delta,
                                    # or flywheel_speed_min (with flywheel_speed)
    flywheel_speed = "225 rpm"      # top speed of the flywheel shaft (optional)

:func:`scene_data` checks it completely (every error a
:class:`~flyopt.errors.SceneError` naming ``press.<field>`` and what is
allowed) and returns the scene dictionary it stands for: [machine] (speed,
delta, cycle), [torque] (the process load as the resisting torque over the
crank angle; the driving torque an unknown constant unless the scene gives
one, e.g. a motor) and, with ``flywheel_speed``, the flywheel's [[shaft]]. The
scene reader (:func:`flyopt.io.scene.from_dict`) then reads that dictionary
like any other, so analysis, design and sweeps run on their one path. The
physics (the conversions) is :mod:`flyopt.machine.press`; the model is the
textbook's (docs/flywheel-design.md, sections 2, 8 and 11).
"""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from flyopt.errors import SceneError, shorten
from flyopt.io.fields import SPEED_RANGE, Table, check_delta, check_magnitude, scaled
from flyopt.io.input_files import check_rows
from flyopt.io.operation_section import ENERGY_RANGE
from flyopt.machine import press as physics
from flyopt.units import MAGNITUDES, quantity, unit_value

if TYPE_CHECKING:
    from collections.abc import Mapping

PRESS_KEYS = (
    "strokes_per_minute",
    "strokes_per_hour",
    "stroke_period",
    "energy_per_stroke",
    "force",
    "force_unit",
    "position_unit",
    "punching",
    "working_time",
    "working_angle",
    "stroke",
    "slowdown",
    "delta",
    "flywheel_speed",
    "flywheel_speed_min",
    "description",
)
"""Keys of the [press] table."""

PUNCHING_KEYS = ("thickness", "shear_strength", "energy_per_area", "hole_diameter", "cut_length", "description")
"""Keys of ``press.punching``."""

FLYWHEEL_SHAFT = "flywheel"
"""Name of the [[shaft]] that ``press.flywheel_speed`` adds (the flywheel's own shaft)."""

CRANKSHAFT = "crankshaft"
"""Name of the reference shaft added beside it when the scene gives no [[shaft]]."""

_RATE = ("strokes_per_minute", "strokes_per_hour", "stroke_period")
_ENERGY = ("energy_per_stroke", "force", "punching")
_WORKING = ("working_time", "working_angle", "stroke")
_FLUCTUATION = ("slowdown", "delta", "flywheel_speed_min")


def scene_data(data: Mapping[str, Any]) -> dict[str, Any]:
    """The scene dictionary a [press] table stands for.

    Parameters
    ----------
    data : dict
        A scene file's contents (as ``tomllib`` reads them) with a ``press``
        table. It is not changed.

    Returns
    -------
    dict
        The same contents without ``press``, with [machine] ``speed`` (the
        crank's mean speed, one stroke per turn), ``delta`` and ``cycle`` (one
        turn); [torque] ``resisting`` (the process load over the crank angle,
        from φ = 0 at the start of the working stroke) and ``driving`` (an
        unknown constant, unless the scene gives one); and, with
        ``flywheel_speed``, a [[shaft]] ``flywheel`` at its speed ratio (and a
        ``crankshaft`` at ratio 1 when the scene gives no [[shaft]]), on which
        the design puts the flywheel unless [design] names its shafts. The
        user's other tables and keys are kept as they are.

    Raises
    ------
    SceneError
        A [press] field is missing, unknown or wrong, or the scene gives a
        [machine] speed, delta or cycle, or a resisting torque, that the
        press sets (the message names both).

    Notes
    -----
    docs/flywheel-design.md, sections 2 (δ and the slowdown), 8 (the speed
    ratio of the flywheel shaft) and 11 (presses); the conversions are
    :mod:`flyopt.machine.press`.
    """
    press = Table(data["press"], "press", PRESS_KEYS).data
    rate, omega_crank, period = _crank(press)
    angle = _working_angle(press, period)
    source, rows, note = _load(press, angle)
    fluctuation, delta = _delta(press)
    ratio = _flywheel_ratio(press, delta, omega_crank)

    out = {key: value for key, value in data.items() if key != "press"}
    out["machine"] = _machine(data.get("machine"), rate, fluctuation, omega_crank, delta)
    out["torque"] = _torque(data.get("torque"), source, rows, note)
    if ratio is not None:
        out["shaft"] = _shafts(data.get("shaft"), ratio, press["flywheel_speed"])
        design = data.get("design", {})
        if isinstance(design, dict) and "shafts" not in design:
            out["design"] = {**design, "shafts": [FLYWHEEL_SHAFT]}
    return out


# -- the crank and the working stroke ---------------------------------------------


MIN_WORKING_ANGLE = 1e-6
"""Shortest working stroke [rad of the crank]: a shorter one is a step the cycle cannot resolve."""


def _crank(press):
    """(the key given, the crank's mean speed [rad/s], the stroke period [s])."""
    key = _one_of(
        press,
        _RATE,
        "press.strokes_per_minute",
        "give the stroke rate as strokes_per_minute (e.g. 12), strokes_per_hour (e.g. 720: holes an hour) "
        "or stroke_period (e.g. '5 s')",
    )
    if key in ("strokes_per_minute", "strokes_per_hour"):
        strokes = _number(press, key, "dimensionless")
        per = "a minute" if key == "strokes_per_minute" else "an hour"
        if strokes <= 0:
            raise SceneError(
                f"press.{key}",
                f"must be positive (strokes {per}, one crank turn each), got {shorten(press[key])}",
            )
        omega = physics.crank_speed(strokes if key == "strokes_per_minute" else strokes / 60.0)
        _check_crank_speed(omega, "press.strokes_per_minute", press[key])
        return key, omega, physics.stroke_period(omega)
    period = _time(press[key], "press.stroke_period")
    if period <= 0:
        raise SceneError(
            "press.stroke_period",
            f"must be positive (the time of one stroke, one crank turn), got {shorten(press[key])}",
        )
    omega = physics.crank_speed_of_period(period)
    _check_crank_speed(omega, "press.stroke_period", press[key])
    return key, omega, period


def _check_crank_speed(omega, where, raw):
    """Refuse a stroke rate whose crank speed is outside the machine speeds flyopt computes (machine.speed's range)."""
    low, high = SPEED_RANGE
    if not low <= omega <= high:
        raise SceneError(
            where,
            f"{shorten(raw)} makes the crank turn at {omega:.3g} rad/s (allowed: {low:g} to {high:g} rad/s, "
            "the range of machine.speed)",
        )


def _working_angle(press, period):
    """The crank angle of the working stroke [rad], 0 < θ_w < 2π."""
    key = _one_of(
        press,
        _WORKING,
        "press.working_time",
        "give how long the working stroke lasts as working_time (e.g. '2 s'), "
        "working_angle (e.g. '60 deg' of the crank), or the punch's stroke (e.g. '100 mm', with punching.thickness)",
    )
    if key == "stroke":
        return _stroke_angle(press)
    if key == "working_time":
        time = _time(press[key], "press.working_time")
        if not 0 < time < period:
            raise SceneError(
                "press.working_time",
                f"must be positive and shorter than the stroke period ({period:.6g} s), got {shorten(press[key])}",
            )
        angle = physics.working_angle(time, period)
        if angle < MIN_WORKING_ANGLE:
            raise SceneError(
                "press.working_time",
                f"{shorten(press[key])} is {angle:.3g} rad of the crank (allowed: at least "
                f"{MIN_WORKING_ANGLE:g} rad, {MIN_WORKING_ANGLE / physics.TURN:g} of the stroke period)",
            )
        return angle
    angle = _number(press, key, "angle")
    if not MIN_WORKING_ANGLE <= angle < physics.TURN:
        raise SceneError(
            "press.working_angle",
            f"must lie between {MIN_WORKING_ANGLE:g} rad and 360 deg (exclusive: one crank turn is "
            f"the whole stroke), got {shorten(press[key])}",
        )
    return angle


def _stroke_angle(press):
    """The working angle from the punch's stroke s and the plate's thickness t: the courses' punching time,
    t / (2 s) of a turn (the punch taken to move uniformly, 2 s a turn), i.e. θ_w = π t / s."""
    stroke = _number(press, "stroke", "length")
    if not (math.isfinite(stroke) and stroke > 0):
        raise SceneError("press.stroke", f"must be positive (the punch's stroke), got {shorten(press['stroke'])}")
    punching = press.get("punching")
    if not isinstance(punching, dict) or "thickness" not in punching:
        raise SceneError(
            "press.stroke",
            "sets the punching time from the plate's thickness: give punching = { thickness, ... } with it",
        )
    thickness = _positive(
        Table(punching, "press.punching", PUNCHING_KEYS).data, "thickness", "length", "press.punching"
    )
    if not thickness < 2 * stroke:
        raise SceneError(
            "press.stroke",
            f"{shorten(press['stroke'])} is not longer than half the plate's thickness: the punch must clear the plate",
        )
    return physics.punching_angle(thickness, stroke)


# -- the load -----------------------------------------------------------------


def _load(press, angle):
    """(the key given, the resisting torque table over one turn, a description of it)."""
    key = _one_of(
        press,
        _ENERGY,
        "press.energy_per_stroke",
        "give the work of one stroke as energy_per_stroke (e.g. '15 kJ'), force = [[position, force], "
        "...] over the working stroke, or punching = { thickness, shear_strength or energy_per_area, "
        "hole_diameter or cut_length }",
    )
    for unit in ("force_unit", "position_unit"):
        if unit in press and key != "force":
            raise SceneError(f"press.{unit}", "belongs to press.force (the units of its table), which is not given")
    degrees = math.degrees(angle)
    if key == "energy_per_stroke":
        energy = _number(press, key, "energy")
        if energy <= 0:
            raise SceneError("press.energy_per_stroke", f"must be positive, got {shorten(press[key])}")
        note = f"press: {energy:.6g} J a stroke, taken evenly over the working angle of {degrees:.6g} deg"
    elif key == "punching":
        energy, force = _punching(press[key])
        how = f"F_max = {force:.6g} N, E = F_max t/2" if force is not None else "E = w L t, the sheared area's energy"
        note = f"press: punching, {how} = {energy:.6g} J a stroke, taken evenly over the working angle of {degrees:.6g} deg"
    else:
        positions, forces = _force_table(press)
        energy = physics.force_energy(positions, forces)
        if not energy > 0:
            raise SceneError(
                "press.force",
                f"the table does no work (∫F dx = {energy:.6g} J): give the force the "
                "ram works against over the working stroke",
            )
        angles, torques = physics.force_torque(positions, forces, angle)
        note = (
            f"press: the force table, {energy:.6g} J a stroke, its positions uniform over the working angle "
            f"of {degrees:.6g} deg"
        )
        return key, physics.resisting_table(angles, torques, angle), note
    check_magnitude(energy, f"press.{key}", press[key], *ENERGY_RANGE, "J", "the energy of one stroke")
    torque = physics.working_torque(energy, angle)
    return key, physics.resisting_table([0.0, angle], [torque, torque], angle), note


def _punching(raw):
    """(E [J], F_max [N] or None) of ``press.punching``: E = ½ F_max t with F_max = τ L t from the
    shear strength, or E = w L t from the energy per sheared area (the book's "N·m per mm² sheared")."""
    table = Table(raw, "press.punching", PUNCHING_KEYS).data
    if "thickness" not in table:
        raise SceneError(
            "press.punching.thickness",
            "is missing: punching needs the plate's thickness, its ultimate shear_strength (or the "
            "energy_per_area sheared), and hole_diameter or cut_length",
        )
    thickness = _positive(table, "thickness", "length", "press.punching")
    strength = _one_of(
        table,
        ("shear_strength", "energy_per_area"),
        "press.punching.shear_strength",
        "give the plate's ultimate shear_strength (e.g. '350 MPa') or the energy_per_area sheared (e.g. '6 J/mm^2')",
    )
    value = _positive(
        table, strength, "stress" if strength == "shear_strength" else "energy_per_area", "press.punching"
    )
    cut = _one_of(
        table,
        ("hole_diameter", "cut_length"),
        "press.punching.hole_diameter",
        "give the cut as hole_diameter (a round hole, cut length π d) or cut_length (the sheared edge's length)",
    )
    length = _positive(table, cut, "length", "press.punching")
    if cut == "hole_diameter":
        length *= math.pi
    if strength == "energy_per_area":
        return physics.sheared_area_energy(value, length, thickness), None
    force = physics.punching_force(value, length, thickness)
    return physics.punching_energy(force, thickness), force


def _force_table(press):
    """(positions [m], forces [N]) of ``press.force``, checked."""
    where = "press.force"
    raw = press["force"]
    position_unit = _unit(press, "position_unit", "length")
    force_unit = _unit(press, "force_unit", "force")
    if hasattr(raw, "array"):  # a large table read without tomllib (flyopt.io.toml_file.InlineRows)
        check_rows(len(raw), where)
        raw = raw.array.tolist()
    if not isinstance(raw, list) or len(raw) < 2:
        raise SceneError(
            where,
            "must be a list of at least two [position, force] pairs over the working stroke, "
            'e.g. [["0 mm", "0 kN"], ["20 mm", "660 kN"]]',
        )
    check_rows(len(raw), where)
    positions, forces = [], []
    for k, pair in enumerate(raw):
        if not isinstance(pair, list) or len(pair) != 2:
            raise SceneError(f"{where}[{k}]", f"must be a [position, force] pair, got {shorten(pair)}")
        positions.append(scaled(pair[0], "length", f"{where}[{k}] position", position_unit))
        forces.append(scaled(pair[1], "force", f"{where}[{k}] force", force_unit))
        if forces[-1] < 0:
            raise SceneError(
                f"{where}[{k}]",
                f"the force must not be negative (the force the ram works against), got {shorten(pair[1])}",
            )
        if k and positions[k] < positions[k - 1]:
            raise SceneError(
                f"{where}[{k}]",
                f"positions must not decrease over the working stroke: "
                f"{positions[k]:.6g} m comes after {positions[k - 1]:.6g} m",
            )
        if k >= 2 and positions[k] == positions[k - 2]:
            raise SceneError(
                f"{where}[{k}]",
                f"three points at one position ({positions[k]:.6g} m); a step is exactly two points at one position",
            )
    if positions[-1] == positions[0]:
        raise SceneError(where, "the working stroke has no length: the last position must lie beyond the first")
    return positions, forces


# -- the speed fluctuation and the flywheel shaft ------------------------------------------


_PRESS_DELTAS = "presses 1/10 to 1/7"


def _delta(press):
    """(the key given, flyopt's δ)."""
    key = _one_of(
        press,
        _FLUCTUATION,
        "press.slowdown",
        "give the allowed speed drop over the working stroke as slowdown ((ω_top − ω_bottom)/ω_top, "
        "e.g. 0.1), delta (δ = (ω_max − ω_min)/ω_mean), or flywheel_speed_min with flywheel_speed",
    )
    if key == "slowdown":
        slowdown = _number(press, key, "dimensionless")
        if not 0 < slowdown < 1:
            raise SceneError(
                "press.slowdown",
                f"must lie between 0 and 1 (exclusive): the fraction of its top speed "
                f"the flywheel loses over the working stroke (1 would stop it), got "
                f"{shorten(press[key])}; presses about 0.1 (δ 1/10 to 1/7)",
            )
        delta = physics.delta_from_slowdown(slowdown)
        check_delta(delta, "press.slowdown", press[key], _PRESS_DELTAS, derived="2s/(2 − s)")
        return key, delta
    if key == "delta":
        delta = _number(press, key, "dimensionless")
        check_delta(delta, "press.delta", press[key], f"{_PRESS_DELTAS} (the slowdown 2δ/(2 + δ) between 0 and 1)")
        return key, delta
    if "flywheel_speed" not in press:
        raise SceneError(
            "press.flywheel_speed_min", "needs press.flywheel_speed, the top speed it is the lowest speed of"
        )
    top = _flywheel_top(press)
    bottom = _number(press, key, "angular_speed")
    if not 0 < bottom < top:
        raise SceneError(
            "press.flywheel_speed_min",
            f"must be positive and below flywheel_speed "
            f"({shorten(press['flywheel_speed'])}), got {shorten(press[key])}",
        )
    delta = physics.delta_from_slowdown(1.0 - bottom / top)
    check_delta(
        delta, "press.flywheel_speed_min", press[key], _PRESS_DELTAS, derived="2(1 − ω_min/ω_top)/(1 + ω_min/ω_top)"
    )
    return key, delta


def _flywheel_top(press):
    top = _number(press, "flywheel_speed", "angular_speed")
    if top <= 0:
        raise SceneError(
            "press.flywheel_speed",
            f"must be positive (the flywheel shaft's top speed), got {shorten(press['flywheel_speed'])}",
        )
    return top


def _flywheel_ratio(press, delta, omega_crank):
    """The flywheel shaft's speed ratio to the crank, or None without ``flywheel_speed``."""
    if "flywheel_speed" not in press:
        return None
    return physics.flywheel_speed_ratio(_flywheel_top(press), delta, omega_crank)


# -- the scene's tables ----------------------------------------------------------------


def _machine(raw, rate, fluctuation, omega_crank, delta):
    """[machine] with the press's speed, delta and cycle (the user's other keys kept)."""
    if raw is None:
        raw = {}
    if not isinstance(raw, dict):
        return raw  # the scene reader says what is wrong
    for key, press_key, what in (
        ("speed", rate, "the crank's mean speed is the stroke rate"),
        ("delta", fluctuation, "the speed fluctuation follows from the press's"),
        ("cycle", rate, "a press's cycle is one crank turn a stroke"),
    ):
        if key in raw:
            raise SceneError(
                f"press.{press_key}",
                f"machine.{key} is given too: {what}; give it once, in [press] (leave machine.{key} out)",
            )
    return {**raw, "speed": f"{omega_crank!r} rad/s", "delta": delta, "cycle": f"{physics.TURN!r} rad"}


def _torque(raw, source, rows, note):
    """[torque] with the process load as the resisting torque; driving an unknown constant unless given."""
    if raw is None:
        raw = {}
    if not isinstance(raw, dict):
        return raw
    for key in ("resisting", "net"):
        if key in raw:
            raise SceneError(
                f"press.{source}",
                f"torque.{key} is given too: the process load of a [press] is its "
                f"resisting torque; give the load once (leave [torque.{key}] out)",
            )
    out = {**raw, "resisting": {"points": rows, "unit": "N*m", "angle_unit": "rad", "description": note}}
    out.setdefault("driving", {"constant": "unknown"})
    return out


def _shafts(raw, ratio, top):
    """[[shaft]] with the flywheel's shaft added (and the crankshaft, when the scene gives none)."""
    shaft = {
        "name": FLYWHEEL_SHAFT,
        "speed_ratio": ratio,
        "description": f"the flywheel shaft, top speed {top} (press.flywheel_speed)",
    }
    if raw is None:
        return [{"name": CRANKSHAFT, "speed_ratio": 1.0}, shaft]
    if not isinstance(raw, list):
        return raw
    for k, item in enumerate(raw):
        if isinstance(item, dict) and item.get("name") == FLYWHEEL_SHAFT:
            raise SceneError(
                "press.flywheel_speed",
                f"shaft[{k}] is named {FLYWHEEL_SHAFT!r} too: flywheel_speed "
                f"adds the flywheel's shaft under that name; rename yours",
            )
    return [*raw, shaft]


# -- reading --------------------------------------------------------------------


def _one_of(table, keys, where, allowed):
    """The one key of ``keys`` the table gives; an error naming them when none or several are given."""
    given = [k for k in keys if k in table]
    if len(given) != 1:
        prefix = where.rsplit(".", 1)[0]
        field = f"{prefix}.{given[1]}" if given else where
        found = f" (given: {', '.join(given)})" if given else ""
        raise SceneError(field, f"{allowed}: exactly one of {', '.join(keys)}{found}")
    return given[0]


def _number(table, key, dimension, where="press"):
    """The SI float of ``table[key]``; a wrong value names the field."""
    return quantity(table[key], dimension, f"{where}.{key}")


#: Magnitudes a press's positive inputs may take, by dimension (SI): beyond them the stroke's energy or the
#: flywheel under- or overflows. Lengths and energies per area as any scene's (:data:`flyopt.units.MAGNITUDES`);
#: a plate's shear strength from a pascal, not the millipascal any stress may be.
PRESS_MAGNITUDES = {
    "length": (*MAGNITUDES["length"][:2], "m", MAGNITUDES["length"][2]),
    "stress": (1.0, MAGNITUDES["stress"][1], "Pa", "a pascal to a terapascal"),
    "energy_per_area": (*MAGNITUDES["energy_per_area"][:2], "J/m^2", MAGNITUDES["energy_per_area"][2]),
}


def _positive(table, key, dimension, where):
    value = _number(table, key, dimension, where)
    if value <= 0:
        raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table[key])}")
    if dimension in PRESS_MAGNITUDES:
        low, high, unit, why = PRESS_MAGNITUDES[dimension]
        check_magnitude(value, f"{where}.{key}", table[key], low, high, unit, why)
    return value


def _unit(press, key, dimension):
    """The SI value of one ``press.<key>`` unit (1 when not given)."""
    if key not in press:
        return 1.0
    raw = press[key]
    if not isinstance(raw, str):
        raise SceneError(f"press.{key}", f"must be a unit string (e.g. 'mm', 'kN'), got {shorten(raw)}")
    return unit_value(raw, dimension, f"press.{key}")


def _time(raw, where):
    """A time [s]: a plain number of seconds, or a string with a unit of time ("2 s", "500 ms", "0.1 min")."""
    if isinstance(raw, bool):
        raise SceneError(
            where,
            f"expected a time, got {shorten(raw)}: give seconds, or a time with its unit "
            "(e.g. '2 s', '500 ms', '0.1 min')",
        )
    return quantity(raw, "time", where)

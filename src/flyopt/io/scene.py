"""Scene files: one machine to regulate, read from TOML and checked field by field.

A scene says how fast the reference shaft turns, the allowed coefficient of
speed fluctuation δ, the torques over one cycle (two curves, or the signed net
areas between them), and the shafts a flywheel may sit on. Every value may
carry a unit ("1500 rpm", "100 N*m/mm"); plain numbers are SI. Everything that
is wrong is reported as a :class:`~flyopt.errors.SceneError` naming the field.

See README.md for the format with an example, and problems/ for scenes.
"""

import math
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass, field, replace
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from flyopt._toml import tomllib
from flyopt.cycle.expression import Expression
from flyopt.cycle.torque import Constant, ExpressionTorque, PiecewiseLinear
from flyopt.errors import ExpressionError, SceneError, clip, shorten
from flyopt.machine.transmission import Shaft, inertia_at_reference
from flyopt.names import hint, unknown
from flyopt.units import DIMENSIONS, inertia_from_gd2, quantity

if TYPE_CHECKING:
    from flyopt.design.materials import Material

ANGLE_TOLERANCE = 1e-9
"""Relative tolerance on a table's first and last angle against 0 and Φ."""


@dataclass(frozen=True)
class NetAreas:
    """The signed areas between the torque curves, in order, as energies [J]."""

    energies: tuple


@dataclass(frozen=True)
class Scene:
    """A machine to regulate, in SI units.

    Attributes
    ----------
    title : str
    omega_mean : float
        Mean speed ω_m of the reference shaft [rad/s].
    delta : float
        Allowed coefficient of speed fluctuation δ [-].
    j_constant : float
        Constant part J_c of the equivalent inertia at the reference shaft
        [kg*m^2]: machine.inertia (or gd2) plus the inertia on every
        [[shaft]] by the ratio-squared transfer (:func:`constant_inertia`).
    cycle_angle : float
        Angle Φ of one cycle of the reference shaft [rad].
    efficiency : float
        Efficiency from the motor to the reference shaft [-].
    driving, resisting : torque curve or None
        Equivalent torques at the reference shaft (None when ``net`` is
        given; ``Constant(0.0)`` for a curve left out when [[member]] loads
        are given).
    net : NetAreas or None
    shafts : tuple of Shaft
    design : DesignSpec
        Geometry, H/B range, envelope and objective of the flywheel design.
    design_materials, design_shafts : tuple of str or None
        Materials and shafts the design may choose from (None: all).
    materials : tuple of Material
        The scene's own materials.
    members : tuple of flyopt.machine.mechanism.Member
        Members whose kinetic energy and loads are reduced to the reference
        shaft (J_e(φ) = J_c + Σ ..., their forces join the resisting torque).
    mechanism : SliderCrank, GearTrain or None
    engine : flyopt.machine.engine.Engine or None
        The [engine]: its pistons and rods are the first of ``members``.
    source : str or None
        File the scene came from.
    """

    title: str
    omega_mean: float
    delta: float
    j_constant: float = 0.0
    cycle_angle: float = 2 * math.pi
    efficiency: float = 1.0
    driving: object = None
    resisting: object = None
    net: NetAreas | None = None
    shafts: tuple = (Shaft("reference", 1.0),)
    design: object = None  # DesignSpec (defaults when the scene has no [design])
    design_materials: tuple | None = None  # names the design may use; None: every known material
    design_shafts: tuple | None = None  # names of [[shaft]] the design may use; None: all
    materials: tuple = ()  # user materials ([[material]]), extending the built-in ones
    members: tuple = ()  # flyopt.machine.mechanism.Member of [[member]]: J_e(φ) and member loads
    mechanism: object = None  # SliderCrank or GearTrain of [mechanism]
    drive: object = None  # flyopt.io.drive.DriveSpec of [drive]: the motor and ratio designed with the wheel
    engine: object = None  # flyopt.machine.engine.Engine of [engine]; its members lead ``members``
    source: str | None = field(default=None, compare=False)

    def material_library(self) -> "dict[str, Material]":
        """Built-in materials extended or overridden by the scene's own."""
        from flyopt.design.materials import material_library

        return material_library(self.materials)

    def replace(self, **changes: Any) -> "Scene":
        """A copy with some fields changed (for studies and tests)."""
        return replace(self, **changes)


def load(path: str | os.PathLike[str], data: Mapping[str, Any] | None = None) -> Scene:
    """Read and check a scene file.

    Parameters
    ----------
    path : str or Path
        A TOML scene file.
    data : dict, optional
        The file's contents as :func:`read_toml` gave them (read once by a
        caller that also needs them); default: read the file.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        The file cannot be read, is not valid TOML, or a field is wrong; the
        message names the file and the field.
    """
    path = Path(path)
    if data is None:
        data = read_toml(path)
    try:
        return from_dict(data, source=str(path))
    except SceneError as err:
        raise err.with_source(str(path)) from None


def read_toml(path):
    """The contents of a TOML scene file, as ``tomllib`` reads them.

    Large tables of plain numbers (``points = [[0, 150], [5, 152.5], ...]``,
    a member's ``force = [[...]]``, ...) are read by string handling and
    ``float`` instead of ``tomllib``, which takes 60 ms for 10,000 rows; such a
    table comes back as an :class:`InlineRows` that :func:`from_dict` reads as
    the list it stands for (see :func:`_parse_toml`).

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    dict

    Raises
    ------
    SceneError
        The file cannot be read or is not TOML (the message names the file).
    """
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        raise SceneError(
            "", f"cannot read the file: {err.strerror if hasattr(err, 'strerror') and err.strerror else err}", str(path)
        ) from None
    try:
        return _parse_toml(text)
    except tomllib.TOMLDecodeError as err:
        raise SceneError("", f"not valid TOML: {err}", str(path)) from None
    except ValueError as err:  # an integer of over 4300 digits
        raise SceneError("", f"not a scene: {clip(str(err))}", str(path)) from None
    except (RecursionError, MemoryError):
        raise SceneError(
            "",
            f"not a scene: arrays or tables nested too deeply (or too large) to read ({len(text)} characters)",
            str(path),
        ) from None


# -- large inline tables ---------------------------------------------------------

FAST_TABLE_CHARACTERS = 2000
"""Inline tables at least this long [characters] are read without ``tomllib`` (shorter ones: no gain)."""

#: A TOML number of the forms tables use: an integer without leading zeros, a fraction, an
#: exponent (no "_", "inf", "nan", hex: those go to tomllib). Possessive: no backtracking.
_TOML_NUMBER = r"[+-]?+(?:0|[1-9][0-9]*+)(?:\.[0-9]++)?+(?:[eE][+-]?+[0-9]++)?+"
_TOML_BLANK = r"[ \t\r\n]*+"
_TOML_PAIR = (
    rf"\[{_TOML_BLANK}{_TOML_NUMBER}{_TOML_BLANK},{_TOML_BLANK}{_TOML_NUMBER}{_TOML_BLANK}(?:,{_TOML_BLANK})?+\]"
)
_TOML_PAIRS = re.compile(
    rf"\[{_TOML_BLANK}{_TOML_PAIR}(?:{_TOML_BLANK},{_TOML_BLANK}{_TOML_PAIR})*+{_TOML_BLANK}"
    rf"(?:,{_TOML_BLANK})?+\]"
)
_TABLE_KEY = re.compile(r"^[ \t]*(?:points|force|torque|velocity_ratio|angular_ratio)[ \t]*=[ \t]*(?=\[)", re.MULTILINE)
_BRACKETS = str.maketrans("[],", "   ")


class InlineRows:
    """A large inline table ``[[a, b], ...]`` of plain numbers, read without ``tomllib``.

    Stands for the list of pairs ``tomllib`` would have given: :func:`_points`
    and :func:`_member_curve` read it as that list (the same floats: TOML
    and Python's ``float`` round a decimal the same way).

    Attributes
    ----------
    array : ndarray, shape (n, 2)
        The numbers, as ``float`` of each TOML number (an integer ``-0`` is 0.0, as ``float(0)``).
    """

    __slots__ = ("array",)

    def __init__(self, array):
        self.array = array

    def __len__(self):
        return len(self.array)

    def __repr__(self):
        return f"a table of {len(self.array)} rows"


def _parse_toml(text):
    """``tomllib.loads(text)``, with every large table of plain-number pairs read by :func:`_fast_rows`.

    Each such table (``KEY = [[number, number], ...]`` at the start of a
    line, KEY one of points, force, torque, velocity_ratio, angular_ratio,
    blanks and newlines only between its items, at least
    ``FAST_TABLE_CHARACTERS`` long) is cut out of the text and replaced by a
    unique string; ``tomllib`` reads the rest, and each string, found exactly
    once as a value, becomes the :class:`InlineRows` of its table. Anything
    else (a comment inside the table, a unit string, a text in which a
    replacement is not found as one value, e.g. inside a multi-line string)
    is left to ``tomllib`` whole, so what is read, and every error, is
    ``tomllib``'s.
    """
    tables: dict[str, Any] = {}
    pieces: list[str] = []
    end = 0
    nonce = None
    key = _TABLE_KEY.search(text)
    while key is not None:
        match = _TOML_PAIRS.match(text, key.end())
        rows = None
        if match is not None and match.end() - match.start() >= FAST_TABLE_CHARACTERS:
            rows = _fast_rows(match.group())
        if match is not None and rows is not None:
            if nonce is None:
                nonce = _nonce(text)
            marker = f"flyopt-table-{nonce}-{len(tables)}"
            tables[marker] = rows
            pieces += [text[end : match.start()], f'"{marker}"']
            end = match.end()
        key = _TABLE_KEY.search(text, match.end() if match is not None and rows is not None else key.end())
    if not tables:
        return tomllib.loads(text)
    try:
        data = tomllib.loads("".join(pieces) + text[end:])
    except (tomllib.TOMLDecodeError, ValueError, RecursionError):
        return tomllib.loads(text)
    expected = len(tables)
    if _put_rows(data, tables) != expected:
        return tomllib.loads(text)
    return data


def _fast_rows(table):
    """The :class:`InlineRows` of a matched ``[[a, b], ...]`` text, or None to leave it to tomllib.

    None for a carriage return not followed by a newline (not TOML), and for
    a number beyond the floats (tomllib and the field's checks say what is wrong).
    """
    if "\r" in table and table.count("\r") != table.count("\r\n"):
        return None
    tokens = table.translate(_BRACKETS).split()
    numbers = np.array(tokens, dtype=float)
    if not np.isfinite(numbers).all():
        return None
    for k in np.flatnonzero((numbers == 0) & np.signbit(numbers)):
        if tokens[k].lstrip("+-").isdigit():  # the integer -0 is 0 in TOML, and float(0) is 0.0
            numbers[k] = 0.0
    return InlineRows(numbers.reshape(-1, 2))


def _nonce(text):
    """A string that does not occur in ``text`` (for the markers of :func:`_parse_toml`)."""
    k = 0
    while f"flyopt-table-{k}x" in text:
        k += 1
    return f"{k}x"


def _put_rows(data, tables):
    """Replace each marker string of ``tables`` in the parsed ``data`` by its rows; the count replaced."""
    found = 0
    items = data.items() if isinstance(data, dict) else enumerate(data)
    for key, value in items:
        if isinstance(value, str):
            if value in tables:
                data[key] = tables.pop(value)
                found += 1
        elif isinstance(value, (dict, list)):
            found += _put_rows(value, tables)
    return found


def from_dict(data: Mapping[str, Any], source: str | None = None) -> Scene:
    """Build a scene from a dictionary shaped like a scene file.

    Parameters
    ----------
    data : dict
        As ``tomllib`` (or :func:`read_toml`) reads a scene file.
    source : str, optional
        The file the scene came from: a ``points_file`` (or a member's
        ``force_file``, ...) is relative to its folder; without one, to the
        working directory.

    Returns
    -------
    Scene

    Raises
    ------
    SceneError
        A field is missing, unknown or wrong.
    """
    files = Path(source).parent if source else Path()  # a points_file is relative to the scene file
    if (
        isinstance(data, dict) and "press" in data
    ):  # a press from its process data (docs/flywheel-design.md, section 11)
        from flyopt.io.press import scene_data

        data = scene_data(data)
    top = _Table(
        data,
        "",
        {
            "title",
            "description",
            "machine",
            "torque",
            "shaft",
            "design",
            "material",
            "mechanism",
            "member",
            "sweep",
            "drive",
            "motor_option",
            "engine",
        },
    )  # [sweep] is read by flyopt.studies.sweep.load_sweep
    machine = _Table(
        top.require("machine"), "machine", {"speed", "delta", "inertia", "gd2", "cycle", "efficiency", "description"}
    )
    omega = machine.quantity("speed", "angular_speed", required=True)
    if omega <= 0:
        raise SceneError("machine.speed", f"must be positive, got {shorten(machine.raw('speed'))}")
    delta = machine.quantity("delta", "dimensionless", required=True)
    if not 0 < delta < 2:
        raise SceneError(
            "machine.delta",
            f"must lie between 0 and 2 (exclusive), got {shorten(machine.raw('delta'))}; "
            "typical values are 1/5 (crushers) to 1/300 (AC generators)",
        )
    if machine.has("inertia") and machine.has("gd2"):
        raise SceneError("machine.gd2", "give either machine.inertia or machine.gd2, not both")
    j_c = machine.quantity("inertia", "inertia", default=0.0)
    if machine.has("gd2"):
        j_c = inertia_from_gd2(machine.quantity("gd2", "flywheel_moment"))
    if j_c < 0:
        raise SceneError("machine.inertia" if machine.has("inertia") else "machine.gd2", "must not be negative")
    cycle = machine.quantity("cycle", "angle", default=2 * math.pi)
    if cycle <= 0:
        raise SceneError("machine.cycle", f"must be positive, got {shorten(machine.raw('cycle'))}")
    engine = _engine(top.get("engine"), files) if top.has("engine") else None
    if engine is not None:
        if machine.has("cycle") and abs(cycle - engine.cycle_angle) > ANGLE_TOLERANCE * engine.cycle_angle:
            raise SceneError(
                "machine.cycle",
                f"is {math.degrees(cycle):.6g} deg, but the cycle of a {engine.cycle} "
                f"engine is {math.degrees(engine.cycle_angle):.6g} deg (leave machine.cycle out: "
                "[engine] cycle sets it)",
            )
        cycle = engine.cycle_angle

    shafts = _shafts(top.get("shaft"))
    j_c = constant_inertia(j_c, shafts)
    efficiency = (
        _efficiency(machine.get("efficiency"), "machine.efficiency")
        if machine.has("efficiency")
        else _reference_efficiency(shafts)
    )

    mechanism = _mechanism(top.get("mechanism"))
    members = _members(top.get("member"), mechanism, cycle, files)
    if engine is not None:
        members = _with_engine(engine, mechanism, members)
    member_loads = any(m.force is not None or m.torque is not None for m in members)
    driving, resisting, net = _torques(
        top.get("torque", {}) if member_loads else top.require("torque"), cycle, shafts, efficiency, member_loads, files
    )
    if engine is not None and net is not None:
        raise SceneError(
            "torque.net",
            "an [engine] needs torque curves, not net areas: its gas torque is a curve "
            'over the crank angle (give [torque.resisting], e.g. constant = "unknown")',
        )
    if members and net is not None:
        raise SceneError(
            "member",
            "members need the torque curves ([torque.driving] and [torque.resisting]), "
            "not net areas: their inertia varies with the angle",
        )
    materials = _materials(top.get("material"))
    design, design_materials, design_shafts = _design(top.get("design", {}), shafts, materials)
    drive = None
    if top.has("drive") or top.has("motor_option"):
        from flyopt.design.materials import design_material_names, material_library
        from flyopt.io.drive import drive_spec

        library = material_library(materials)
        drive = drive_spec(
            top.get("drive"),
            top.get("motor_option"),
            shafts,
            materials={n: library[n] for n in design_material_names(library, design_materials)},
        )
    title = top.get("title", "")
    if not isinstance(title, str):
        raise SceneError("title", f"must be a string, got {shorten(title)}")
    return Scene(
        title=title or (Path(source).stem if source else "scene"),
        omega_mean=omega,
        delta=delta,
        j_constant=j_c,
        cycle_angle=cycle,
        efficiency=efficiency,
        driving=driving,
        resisting=resisting,
        net=net,
        shafts=shafts,
        design=design,
        design_materials=design_materials,
        design_shafts=design_shafts,
        materials=materials,
        members=members,
        mechanism=mechanism,
        drive=drive,
        engine=engine,
        source=source,
    )


def constant_inertia(j_machine, shafts):
    """J_c at the reference shaft: the machine's own plus the inertia on each shaft [kg*m^2].

    J_c = J_machine + Σ_k J_k i_k², i_k = ω_k/ω the shaft's speed ratio: the
    same kinetic energy at every speed (docs/flywheel-design.md, sections 3
    and 8; the reduction of GD² to one shaft of the electric-drive texts, in
    flyopt's speed-ratio convention), no efficiency applied.

    Parameters
    ----------
    j_machine : float
        machine.inertia (or gd2) [kg*m^2], already at the reference shaft.
    shafts : iterable of Shaft

    Returns
    -------
    float
    """
    return j_machine + math.fsum(inertia_at_reference(s.inertia, s.speed_ratio) for s in shafts)


# -- sections ------------------------------------------------------------------


def _torques(section, cycle, shafts=(), efficiency=1.0, member_loads=False, files=Path()):
    """(driving, resisting, net) of the [torque] table.

    With forces or torques on [[member]]s (``member_loads``), a curve left
    out is zero: the members' loads may carry the whole load (or drive),
    and an unknown constant or the cycle's own balance settles the rest.
    """
    torque = _Table(section, "torque", {"driving", "resisting", "net"})
    if torque.has("net"):
        if torque.has("driving") or torque.has("resisting"):
            raise SceneError(
                "torque.net",
                "give either the net areas or the driving and resisting torques, not both (the torque is given twice)",
            )
        return None, None, _net_areas(torque.get("net"))
    curves = []
    for name in ("driving", "resisting"):
        if torque.has(name):
            curves.append(_curve(torque.get(name), f"torque.{name}", cycle, shafts, efficiency, files))
        elif member_loads:
            curves.append(Constant(0.0))
        else:
            raise SceneError(
                f"torque.{name}",
                "is missing: give [torque.driving] and [torque.resisting], "
                "or [torque.net] with the net areas (a curve may be left out, meaning zero, "
                "when [[member]] forces or torques carry the load)",
            )
    driving, resisting = curves
    if isinstance(driving, Constant) and isinstance(resisting, Constant) and driving.unknown and resisting.unknown:
        raise SceneError("torque.resisting.constant", "both torques are unknown; at most one may be")
    return driving, resisting, None


def _curve(section, where, cycle, shafts=(), efficiency=1.0, files=Path()):
    table = _Table(
        section,
        where,
        {"points", "points_file", "constant", "expression", "motor", "unit", "angle_unit", "description"},
    )
    forms = [k for k in ("points", "points_file", "constant", "expression", "motor") if table.has(k)]
    if len(forms) != 1:
        raise SceneError(
            where,
            "give exactly one of points, points_file, constant, expression or motor"
            + (f" (the torque is given twice: {', '.join(forms)})" if forms else ""),
        )
    form = forms[0]
    unit = 1.0
    if table.has("unit"):
        unit = _unit_factor(table.get("unit"), "torque", f"{where}.unit")
    if form == "constant":
        raw = table.get("constant")
        if isinstance(raw, str) and raw.strip().lower() == "unknown":
            return Constant(None)
        value = _scaled(raw, "torque", f"{where}.constant", unit)
        return Constant(value)
    if form == "motor":
        return _motor(table.get("motor"), f"{where}.motor", shafts, efficiency, files)
    if form == "expression":
        try:
            expr = Expression(table.get("expression"), variables=("phi", "omega"))
        except ExpressionError as err:
            raise SceneError(f"{where}.expression", str(err)) from None
        return ExpressionTorque(expr, unit, where=f"{where}.expression")
    angle_unit = (
        _unit_factor(table.get("angle_unit"), "angle", f"{where}.angle_unit") if table.has("angle_unit") else 1.0
    )
    if form == "points_file":
        units = (table.get("angle_unit", "rad"), table.get("unit", DIMENSIONS["torque"][1]))
        return _points_file(
            table.get("points_file"), f"{where}.points_file", files, cycle, unit, angle_unit, "torque", units
        )
    return _points(table.get("points"), f"{where}.points", cycle, unit, angle_unit)


def _points(raw, where, cycle, unit, angle_unit, dimension="torque", label=None, minimum=None):
    """A table [[angle, value], ...] over the cycle as a PiecewiseLinear (values in SI).

    ``label`` names the values in messages (default: the dimension);
    ``minimum``, a pair (least value [SI], why), refuses a value below it.
    """
    label = label or dimension
    if not isinstance(raw, (list, InlineRows)) or len(raw) < 2:
        raise SceneError(where, f"must be a list of at least two [angle, {label}] pairs")
    if isinstance(raw, InlineRows):  # plain finite numbers: what _scaled gives each, float(x) * unit
        angles = raw.array[:, 0] * angle_unit
        values = raw.array[:, 1] * unit
    else:
        angles = np.empty(len(raw))
        values = np.empty(len(raw))
        for k, pair in enumerate(raw):
            if not isinstance(pair, list) or len(pair) != 2:
                raise SceneError(f"{where}[{k}]", f"must be an [angle, {label}] pair, got {shorten(pair)}")
            angles[k] = _scaled(pair[0], "angle", f"{where}[{k}] angle", angle_unit)
            values[k] = _scaled(pair[1], dimension, f"{where}[{k}] {label}", unit)
    if minimum is not None and np.any(values < minimum[0]):
        k = int(np.argmax(values < minimum[0]))
        written = raw.array[k, 1] if isinstance(raw, InlineRows) else raw[k][1]
        raise SceneError(
            f"{where}[{k}]",
            f"the {label} {shorten(written)} at {np.degrees(angles[k]):.6g} deg is below {minimum[0]:g}: {minimum[1]}",
        )
    problem, k = _table_problem(angles, cycle)
    if problem == "decreasing":
        raise SceneError(
            where,
            f"angles must not decrease: point {k} ({np.degrees(angles[k]):.6g} deg) "
            f"comes after {np.degrees(angles[k - 1]):.6g} deg",
        )
    if problem == "three":
        raise SceneError(
            where,
            f"three points at one angle ({np.degrees(angles[k]):.6g} deg); "
            "a vertical step is exactly two points at one angle",
        )
    if problem == "open":
        raise SceneError(
            where,
            f"the table covers {np.degrees(angles[0]):.6g} to {np.degrees(angles[-1]):.6g} deg "
            f"but the cycle is 0 to {np.degrees(cycle):.6g} deg: the cycle does not close "
            "(the first point must be at 0 and the last at the cycle angle)",
        )
    angles[0], angles[-1] = 0.0, cycle
    return PiecewiseLinear(angles, values)


def _table_problem(angles, cycle):
    """The first thing wrong with a table's angles [rad], and the row where it shows.

    Returns
    -------
    problem : {"decreasing", "three", "open"} or None
        An angle below the one before it; three rows at one angle (a
        vertical step is two); a first or last angle off 0 or the cycle
        angle by more than ``ANGLE_TOLERANCE`` of the cycle.
    row : int or None
        Index of the row (the later of two decreasing ones, the middle one of three).
    """
    steps = np.diff(angles)
    if np.any(steps < 0):
        return "decreasing", int(np.argmax(steps < 0)) + 1
    flat = (steps[1:] == 0) & (steps[:-1] == 0)
    if np.any(flat):
        return "three", int(np.argmax(flat)) + 1
    tol = ANGLE_TOLERANCE * cycle
    if abs(angles[0]) > tol or abs(angles[-1] - cycle) > tol:
        return "open", None
    return None, None


def _points_file(raw, where, files, cycle, unit, angle_unit, column, units, minimum=None):
    """A table [angle, value] read from a CSV file, with the checks of inline points.

    Parameters
    ----------
    raw : object
        The ``points_file`` value: a path, relative to the scene file's folder.
    where : str
        The field, e.g. ``torque.resisting.points_file``.
    files : Path
        The folder of the scene file.
    cycle : float
        Cycle angle Φ [rad].
    unit, angle_unit : float
        SI value of one unit of the second and first column.
    column : str
        What the second column holds ("torque", "force", ...), for messages.
    units : tuple of str
        The two columns' units as written (for messages).
    minimum : (float, str), optional
        The least value of the second column [SI] and why: a row below it is refused.

    Returns
    -------
    PiecewiseLinear

    Raises
    ------
    SceneError
        The file cannot be read, or a line or the table is wrong: the message
        names the CSV file, the line and what is allowed.
    """
    numbers, lines, name = _csv_table(raw, where, files, ("angle", column), units)
    angles = numbers[:, 0] * angle_unit
    values = numbers[:, 1] * unit
    if minimum is not None and np.any(values < minimum[0]):
        k = int(np.argmax(values < minimum[0]))
        raise SceneError(
            where,
            f"{name} line {lines[k]}: the {column} {numbers[k, 1]:.6g} {units[1]} is below "
            f"{minimum[0]:g}: {minimum[1]}",
        )
    problem, k = _table_problem(angles, cycle)
    if problem == "decreasing":
        raise SceneError(
            where,
            f"{name} line {lines[k]}: angles must not decrease: {np.degrees(angles[k]):.6g} deg "
            f"comes after {np.degrees(angles[k - 1]):.6g} deg on line {lines[k - 1]}",
        )
    if problem == "three":
        raise SceneError(
            where,
            f"{name} line {lines[k]}: three rows at one angle ({np.degrees(angles[k]):.6g} deg, "
            f"lines {lines[k - 1]} to {lines[k + 1]}); a vertical step is exactly two rows at one angle",
        )
    if problem == "open":
        raise SceneError(
            where,
            f"{name} lines {lines[0]} to {lines[-1]}: the table covers "
            f"{np.degrees(angles[0]):.6g} to {np.degrees(angles[-1]):.6g} deg but the cycle is 0 to "
            f"{np.degrees(cycle):.6g} deg: the cycle does not close (the first row must be at 0 and "
            "the last at the cycle angle)",
        )
    angles[0], angles[-1] = 0.0, cycle
    return PiecewiseLinear(angles, values)


def _csv_table(raw, where, files, columns, units):
    """The rows of a two-column CSV file named by a scene field (see :func:`_read_csv`).

    Parameters
    ----------
    raw : object
        The field's value: a path, relative to the scene file's folder ``files``.
    where : str
        The field, for messages.
    files : Path
    columns, units : tuple of str
        What the two columns hold and their units as written (for messages).

    Returns
    -------
    numbers : ndarray, shape (n, 2)
    lines : sequence of int
        Line number of each row.
    name : str
        The file as messages name it.
    """
    if not isinstance(raw, str) or not raw.strip():
        raise SceneError(where, f"must be the name of a CSV file (a string), got {shorten(raw)}")
    path = files / raw
    name = clip(str(path))
    try:
        text = path.read_text(encoding="utf-8-sig")
    except (OSError, UnicodeDecodeError) as err:
        reason = (
            err.strerror
            if isinstance(err, OSError) and err.strerror
            else "not UTF-8 text"
            if isinstance(err, UnicodeDecodeError)
            else str(err)
        )
        raise SceneError(where, f"cannot read {name}: {reason}") from None
    numbers, lines = _read_csv(text, where, name, columns, units)
    return numbers, lines, name


def _read_csv(text, where, name, columns, units):
    """The numbers of a two-column CSV table, and the line of each row.

    A header line (the first line with text, when it has a letter and none
    of its fields is a number), blank lines and lines starting with ``#``
    are skipped; lines end at
    ``\\n`` (a ``\\r`` before it is a blank). A clean file (a header at most,
    then one row ``angle,value`` per line) is read in one pass over its
    fields; anything else line by line, which names the first wrong line.
    Both give the same rows (Python's ``float`` reads every number).

    Returns
    -------
    numbers : ndarray, shape (n, 2)
        Rows of the two columns (angle and value, speed and torque) in the file's units, n >= 2.
    lines : sequence of int
        Line number (from 1) of each row.
    """
    first = text.find("\n")
    header = _is_header(text if first < 0 else text[:first])
    body = (text[first + 1 :] if first >= 0 else "") if header else text
    body = body.rstrip()
    codes = np.frombuffer(body.encode("utf-8"), dtype=np.uint8)
    ends, commas = np.flatnonzero(codes == 10), np.flatnonzero(codes == 44)
    if len(commas) == len(ends) + 1 >= 2 and np.all(commas[:-1] < ends) and np.all(commas[1:] > ends):
        try:  # one comma on each line: rows of two fields
            numbers = np.array(body.replace("\n", ",").split(","), dtype=float)
        except ValueError:
            numbers = None
        if numbers is not None and np.isfinite(numbers).all():
            offset = 2 if header else 1
            return numbers.reshape(-1, 2), range(offset, offset + len(commas))
    return _read_csv_lines(text.split("\n"), where, name, columns, units)


def _read_csv_lines(rows, where, name, columns, units):
    """:func:`_read_csv` line by line: the first wrong line, named, or the same numbers."""
    numbers, lines = [], []
    allowed = {k: f"a plain number, the {columns[k]} in {units[k]}" for k in (0, 1)}
    header = True  # the first line with text may name the columns
    for number, line in enumerate(rows, 1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        if header:
            header = False
            if _is_header(line):
                continue
        fields = line.split(",")
        if len(fields) != 2:
            raise SceneError(
                where,
                f"{name} line {number}: expected 2 columns, {columns[0]} and {columns[1]} separated by "
                f"a comma, got {len(fields)}: {shorten(stripped)}",
            )
        row = []
        for k, text in enumerate(fields):
            try:
                value = float(text)
            except ValueError:
                raise SceneError(
                    where,
                    f"{name} line {number}, column {k + 1}: {shorten(text.strip())} is not a "
                    f"number (allowed: {allowed[k]})",
                ) from None
            if not math.isfinite(value):
                raise SceneError(
                    where,
                    f"{name} line {number}, column {k + 1}: {shorten(text.strip())} is not "
                    f"finite (allowed: {allowed[k]})",
                )
            row.append(value)
        numbers.append(row)
        lines.append(number)
    if len(numbers) < 2:
        found = f"only line {lines[0]} holds one" if numbers else "there is none"
        first = "at angle 0, the last at the cycle angle" if columns[0] == "angle" else "at rest"
        raise SceneError(
            where, f"{name}: a table needs at least two rows of {columns[0]},{columns[1]} (the first {first}); {found}"
        )
    return np.array(numbers), lines


def _is_header(line):
    """A first line naming the columns: it has a letter, and none of its comma-separated fields is a number."""
    if line.lstrip().startswith("#") or not any(c.isalpha() for c in line):
        return False
    for text in line.split(","):
        try:
            float(text)
            return False
        except ValueError:
            pass
    return True


def _motor(raw, where, shafts, efficiency, files=Path()):
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
    if kind not in kinds:
        raise SceneError(f"{where}.kind", f"{shorten(kind)} is not known (allowed: induction, dc, table)")
    table = _Table(raw, where, kinds[kind])
    speed_ratio = 1.0
    if table.has("shaft"):
        name = table.get("shaft")
        match = [s for s in shafts if s.name == name]
        if not match:
            raise SceneError(
                f"{where}.shaft", f"no [[shaft]] is named {shorten(name)} (known: {', '.join(s.name for s in shafts)})"
            )
        speed_ratio = match[0].speed_ratio
    if kind == "table":
        return MotorTorque(_motor_table(table, where, files), speed_ratio, efficiency, None, where=where)
    motor: InductionMotor | DCMotor
    try:
        if kind == "induction":
            model = table.get("model", "linear")
            if model not in ("linear", "kloss"):
                raise SceneError(f"{where}.model", f"{shorten(model)} is not known (allowed: linear, kloss)")
            motor = InductionMotor(
                table.quantity("rated_power", "power", required=True),
                table.quantity("rated_speed", "angular_speed", required=True),
                table.quantity("synchronous_speed", "angular_speed", required=True),
                table.quantity("breakdown_ratio", "dimensionless"),
            )
        else:
            model = None
            if table.has("stall_torque"):
                motor = DCMotor(
                    table.quantity("no_load_speed", "angular_speed", required=True),
                    table.quantity("stall_torque", "torque"),
                )
            else:
                motor = DCMotor.from_rated(
                    table.quantity("rated_power", "power", required=True),
                    table.quantity("rated_speed", "angular_speed", required=True),
                    table.quantity("no_load_speed", "angular_speed", required=True),
                )
    except ValueError as err:
        if isinstance(err, SceneError):
            raise
        raise SceneError(where, str(err)) from None
    return MotorTorque(motor, speed_ratio, efficiency, model, where=where)


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
    unit = _unit_factor(table.get("unit"), "torque", f"{where}.unit") if table.has("unit") else 1.0
    speed_unit = (
        _unit_factor(table.get("speed_unit"), "angular_speed", f"{where}.speed_unit")
        if table.has("speed_unit")
        else 1.0
    )
    field_name = f"{where}.{forms[0]}"
    if forms[0] == "points_file":
        units = (table.get("speed_unit", "rad/s"), table.get("unit", "N*m"))
        numbers, lines, name = _csv_table(table.get("points_file"), field_name, files, ("speed", "torque"), units)
        speeds, torques = numbers[:, 0] * speed_unit, numbers[:, 1] * unit

        def row(k):
            return f"{name} line {lines[k]}"
    else:
        raw = table.get("points")
        if not isinstance(raw, (list, InlineRows)) or len(raw) < 2:
            raise SceneError(
                field_name, "must be a list of at least two [speed, torque] pairs, from rest to the no-load speed"
            )
        if isinstance(raw, InlineRows):
            speeds, torques = raw.array[:, 0] * speed_unit, raw.array[:, 1] * unit
        else:
            speeds, torques = np.empty(len(raw)), np.empty(len(raw))
            for k, pair in enumerate(raw):
                if not isinstance(pair, list) or len(pair) != 2:
                    raise SceneError(f"{field_name}[{k}]", f"must be a [speed, torque] pair, got {shorten(pair)}")
                speeds[k] = _scaled(pair[0], "angular_speed", f"{field_name}[{k}] speed", speed_unit)
                torques[k] = _scaled(pair[1], "torque", f"{field_name}[{k}] torque", unit)

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


def _mechanism(raw):
    if raw is None:
        return None
    from flyopt.machine.kinematics import GearTrain, SliderCrank  # CasADi: only for a scene with a mechanism

    kind = raw.get("kind") if isinstance(raw, dict) else None
    try:
        if kind == "slider_crank":
            table = _Table(raw, "mechanism", {"kind", "crank", "rod", "offset", "description"})
            return SliderCrank(
                table.quantity("crank", "length", required=True),
                table.quantity("rod", "length", required=True),
                table.quantity("offset", "length", default=0.0),
            )
        if kind == "gear_train":
            table = _Table(raw, "mechanism", {"kind", "ratios", "description"})
            ratios = table.require("ratios")
            if not isinstance(ratios, list) or not ratios:
                raise SceneError("mechanism.ratios", "must be a list of stage speed ratios ω_out/ω_in")
            return GearTrain([quantity(r, "dimensionless", f"mechanism.ratios[{k}]") for k, r in enumerate(ratios)])
    except ValueError as err:
        if isinstance(err, SceneError):
            raise
        raise SceneError("mechanism", str(err)) from None
    raise SceneError("mechanism.kind", f"{shorten(kind)} is not known (allowed: slider_crank, gear_train)")


def _members(raw, mechanism, cycle, files=Path()):
    if raw is None:
        return ()
    from flyopt.machine.kinematics import GearTrain  # CasADi: only with members
    from flyopt.machine.mechanism import FORCE_SENSES, Member

    if not isinstance(raw, list):
        raise SceneError("member", "must be an array of tables: [[member]] with name, mass, ...")
    members, seen = [], set()
    for k, item in enumerate(raw):
        where = f"member[{k}]"
        table = _Table(
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
            _unit_factor(table.get("angle_unit"), "angle", f"{where}.angle_unit") if table.has("angle_unit") else 1.0
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


def _engine(raw, files=Path()):
    """The [engine] section: an :class:`~flyopt.machine.engine.Engine` (cylinders, crank train, indicator data)."""
    from flyopt.machine.engine import CYCLE_ANGLES, MAX_CYLINDERS, STANDARD_ATMOSPHERE, Engine  # CasADi

    table = _Table(
        raw,
        "engine",
        {
            "cycle",
            "cylinders",
            "firing_angles",
            "bore",
            "stroke",
            "rod",
            "reciprocating_mass",
            "rod_mass",
            "rod_centre",
            "rod_inertia",
            "angle_unit",
            "pressure_unit",
            "pressure",
            "pressure_file",
            "crankcase_pressure",
            "description",
        },
    )
    kind = table.require("cycle")
    if kind not in CYCLE_ANGLES:
        raise SceneError(
            "engine.cycle",
            f"{shorten(kind)} is not known{hint(kind, CYCLE_ANGLES)} (allowed: '4-stroke', a cycle of 720 deg, or '2-stroke', 360 deg)",
        )
    cycle = CYCLE_ANGLES[kind]
    count = table.require("cylinders")
    if isinstance(count, bool) or not isinstance(count, int) or not 1 <= count <= MAX_CYLINDERS:
        raise SceneError(
            "engine.cylinders", f"must be a whole number of cylinders from 1 to {MAX_CYLINDERS}, got {shorten(count)}"
        )
    angle_unit = _unit_factor(table.get("angle_unit"), "angle", "engine.angle_unit") if table.has("angle_unit") else 1.0
    firing = [k * cycle / count for k in range(count)]  # default: evenly spaced over the cycle
    if table.has("firing_angles"):
        raw_angles = table.get("firing_angles")
        if not isinstance(raw_angles, list) or len(raw_angles) != count:
            raise SceneError(
                "engine.firing_angles",
                f"must be a list of {count} angles, one per cylinder (the "
                f"crank angle at which its cycle starts), got {shorten(raw_angles)}",
            )
        for k, value in enumerate(raw_angles):
            firing[k] = _scaled(value, "angle", f"engine.firing_angles[{k}]", angle_unit)
            if not 0.0 <= firing[k] < cycle:
                raise SceneError(
                    f"engine.firing_angles[{k}]",
                    f"{shorten(value)} lies outside the cycle: a firing "
                    f"angle is the crank angle at which the cylinder's cycle starts, from 0 up to "
                    f"(not including) {math.degrees(cycle):g} deg for a {kind} engine",
                )
    sizes = {}
    for key in ("bore", "stroke", "rod"):
        sizes[key] = table.quantity(key, "length", required=True)
        if not (math.isfinite(sizes[key]) and sizes[key] > 0):
            raise SceneError(f"engine.{key}", f"must be a positive length, got {shorten(table.raw(key))}")
    if not sizes["rod"] > sizes["stroke"] / 2:
        raise SceneError(
            "engine.rod",
            f"{shorten(table.raw('rod'))} is not longer than the crank radius, "
            f"stroke/2 = {sizes['stroke'] / 2 * 1e3:.6g} mm: the crank could not turn "
            "(the connecting rod is measured centre to centre)",
        )
    masses = {
        "reciprocating_mass": table.quantity("reciprocating_mass", "mass", required=True),
        "rod_mass": table.quantity("rod_mass", "mass", default=0.0),
    }
    for key, value in masses.items():
        if not (math.isfinite(value) and value >= 0):
            raise SceneError(f"engine.{key}", f"must be a finite mass >= 0, got {shorten(table.raw(key))}")
    rod = {"rod_centre": 0.0, "rod_inertia": 0.0}
    if table.has("rod_mass"):
        for key in rod:
            if not table.has(key):
                raise SceneError(
                    f"engine.{key}",
                    "is missing: rod_mass, rod_centre (from the crank pin) and "
                    "rod_inertia (about the rod's centre of mass) come together",
                )
        rod["rod_centre"] = table.quantity("rod_centre", "length")
        if not 0.0 <= rod["rod_centre"] <= sizes["rod"]:
            raise SceneError(
                "engine.rod_centre",
                f"{shorten(table.raw('rod_centre'))} is not between the pins: the "
                f"centre of mass lies 0 to {shorten(table.raw('rod'))} from the "
                "crank pin",
            )
        rod["rod_inertia"] = table.quantity("rod_inertia", "inertia")
        if not (math.isfinite(rod["rod_inertia"]) and rod["rod_inertia"] >= 0):
            raise SceneError(
                "engine.rod_inertia", f"must be a finite number >= 0, got {shorten(table.raw('rod_inertia'))}"
            )
    else:
        for key in rod:
            if table.has(key):
                raise SceneError(f"engine.{key}", "describes the rest of the connecting rod: give rod_mass with it")
    unit = (
        _unit_factor(table.get("pressure_unit"), "stress", "engine.pressure_unit")
        if table.has("pressure_unit")
        else 1.0
    )
    forms = [k for k in ("pressure", "pressure_file") if table.has(k)]
    if len(forms) != 1:
        raise SceneError(
            "engine.pressure",
            "give exactly one of pressure = [[angle, pressure], ...] or "
            'pressure_file = "indicator.csv": the absolute cylinder pressure of one cylinder over '
            "its cycle" + (" (given both)" if forms else ""),
        )
    absolute = (0.0, "the table holds absolute pressures, which cannot be negative")
    if forms[0] == "pressure_file":
        units = (table.get("angle_unit", "rad"), table.get("pressure_unit", "Pa"))
        pressure = _points_file(
            table.get("pressure_file"),
            "engine.pressure_file",
            files,
            cycle,
            unit,
            angle_unit,
            "pressure",
            units,
            minimum=absolute,
        )
    else:
        pressure = _points(
            table.get("pressure"),
            "engine.pressure",
            cycle,
            unit,
            angle_unit,
            "stress",
            label="pressure",
            minimum=absolute,
        )
    crankcase = table.quantity("crankcase_pressure", "stress", default=STANDARD_ATMOSPHERE)
    if not (math.isfinite(crankcase) and crankcase >= 0):
        raise SceneError(
            "engine.crankcase_pressure",
            f"must be an absolute pressure >= 0, got {shorten(table.raw('crankcase_pressure'))}",
        )
    try:
        return Engine(
            kind,
            tuple(firing),
            sizes["bore"],
            sizes["stroke"],
            sizes["rod"],
            masses["reciprocating_mass"],
            pressure,
            crankcase,
            masses["rod_mass"],
            rod["rod_centre"],
            rod["rod_inertia"],
        )
    except ValueError as err:
        raise SceneError("engine", str(err)) from None


def _with_engine(engine, mechanism, members):
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
        unit = _unit_factor(table.get("unit"), dimension, f"{where}.unit")
    if table.has(file_key):
        units = (
            table.get("angle_unit", "rad"),
            table.get("unit")
            if table.has("unit") and key in ("force", "torque")
            else DIMENSIONS[dimension][1] or "plain numbers",
        )
        curve = _points_file(
            table.get(file_key), f"{where}.{file_key}", files, cycle, unit, angle_unit, key.replace("_", " "), units
        )
        return (curve.angles, curve.values)
    raw = table.get(key)
    field_name = f"{where}.{key}"
    if not isinstance(raw, (list, InlineRows)):
        return _scaled(raw, dimension, field_name, unit)
    curve = _points(raw, field_name, cycle, unit, angle_unit, dimension)
    return (curve.angles, curve.values)


def _net_areas(section):
    table = _Table(section, "torque.net", {"areas", "area_unit", "torque_scale", "angle_scale", "description"})
    areas = table.require("areas")
    if not isinstance(areas, list) or len(areas) < 2:
        raise SceneError("torque.net.areas", "must be a list of at least two signed areas")
    drawing = [table.has(k) for k in ("area_unit", "torque_scale", "angle_scale")]
    if any(drawing) and not all(drawing):
        raise SceneError(
            "torque.net",
            "areas measured on a drawing need all of area_unit, torque_scale "
            "and angle_scale (energy = area x torque scale x angle scale)",
        )
    if all(drawing):
        factor = (
            table.quantity("area_unit", "area")
            * table.quantity("torque_scale", "torque_scale")
            * table.quantity("angle_scale", "angle_scale")
        )
        if factor <= 0:
            raise SceneError("torque.net", "the drawing scales must be positive")
        energies = []
        for k, a in enumerate(areas):
            if isinstance(a, str):
                raise SceneError(
                    f"torque.net.areas[{k}]",
                    f"with drawing scales the areas are plain numbers (in area_unit), got {shorten(a)}",
                )
            energies.append(factor * quantity(a, "dimensionless", f"torque.net.areas[{k}]"))
    else:
        energies = [quantity(a, "energy", f"torque.net.areas[{k}]") for k, a in enumerate(areas)]
    return NetAreas(tuple(energies))


def _shafts(raw):
    if raw is None:
        return (Shaft("reference", 1.0),)
    if not isinstance(raw, list) or not raw:
        raise SceneError("shaft", "must be an array of tables: [[shaft]] with name and speed_ratio")
    shafts, seen = [], set()
    for k, item in enumerate(raw):
        where = f"shaft[{k}]"
        table = _Table(item, where, {"name", "speed_ratio", "efficiency", "diameter", "inertia", "gd2", "description"})
        name = table.require("name")
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{where}.name", f"must be a non-empty string, got {shorten(name)}")
        if name in seen:
            raise SceneError(f"{where}.name", f"shaft {shorten(name)} is given twice")
        seen.add(name)
        ratio = table.quantity("speed_ratio", "dimensionless", required=True)
        if ratio <= 0:
            raise SceneError(f"{where}.speed_ratio", f"must be positive (ω_shaft/ω_reference), got {shorten(ratio)}")
        eff = _efficiency(table.get("efficiency"), f"{where}.efficiency") if table.has("efficiency") else 1.0
        diameter = table.quantity("diameter", "length")
        if diameter is not None and diameter <= 0:
            raise SceneError(
                f"{where}.diameter", f"must be positive (the shaft seat), got {shorten(table.raw('diameter'))}"
            )
        shafts.append(Shaft(name, ratio, eff, diameter, _shaft_inertia(table, where)))
    return tuple(shafts)


def _shaft_inertia(table, where):
    """The inertia already on a [[shaft]], about its axis [kg*m^2]: ``inertia``, or ``gd2`` (GD² = 4 g J), or 0."""
    if table.has("inertia") and table.has("gd2"):
        raise SceneError(f"{where}.gd2", "give either inertia or gd2, not both (the same inertia, GD² = 4 g J)")
    key = "gd2" if table.has("gd2") else "inertia"
    if not table.has(key):
        return 0.0
    value = table.quantity(key, "flywheel_moment" if key == "gd2" else "inertia")
    if not (math.isfinite(value) and value >= 0):
        raise SceneError(
            f"{where}.{key}",
            f"must be a finite number >= 0 (the inertia already turning with the shaft), got {shorten(table.raw(key))}",
        )
    return inertia_from_gd2(value) if key == "gd2" else value


#: The strength fields of a [[material]] (beyond density, rim speed, allowable stress and cost).
_MATERIAL_STRENGTH = {
    "elastic_modulus": "stress",
    "poisson_ratio": "dimensionless",
    "tensile_strength": "stress",
    "yield_strength": "stress",
    "ductile": "bool",
    "safety_factor": "dimensionless",
    "min_wall": "length",
    "bearing_pressure": "stress",
}


def _materials(raw):
    from flyopt.design.materials import make_material

    if raw is None:
        return ()
    if not isinstance(raw, list):
        raise SceneError("material", "must be an array of tables: [[material]] with name and density")
    materials, seen = [], set()
    for k, item in enumerate(raw):
        where = f"material[{k}]"
        table = _Table(
            item,
            where,
            {
                "name",
                "density",
                "max_rim_speed",
                "allowable_stress",
                "cost",
                "source",
                "description",
                "hub_rule",
                *_MATERIAL_STRENGTH,
            },
        )
        name = table.require("name")
        if not isinstance(name, str) or not name.strip():
            raise SceneError(f"{where}.name", f"must be a non-empty string, got {shorten(name)}")
        if name in seen:
            raise SceneError(f"{where}.name", f"material {shorten(name)} is given twice")
        seen.add(name)
        strength = "tensile_strength" if table.get("ductile") is not True else "yield_strength"
        if not (table.has("max_rim_speed") or table.has("allowable_stress") or table.has(strength)):
            raise SceneError(
                where,
                f"give max_rim_speed, allowable_stress (v_max then follows from σ = ρ v²) "
                f"or {strength} (the allowable stress is it over the safety factor)",
            )
        values = {
            "density": table.quantity("density", "density", required=True),
            "max_rim_speed": table.quantity("max_rim_speed", "speed"),
            "allowable_stress": table.quantity("allowable_stress", "stress"),
            "cost": table.quantity("cost", "cost_per_mass"),
        }
        for key, value in values.items():
            if value is not None and (value < 0 or (value == 0 and key != "cost")):
                raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table.raw(key))}")
        for key, dimension in _MATERIAL_STRENGTH.items():
            if not table.has(key):
                continue
            if dimension == "bool":
                if not isinstance(table.get(key), bool):
                    raise SceneError(f"{where}.{key}", f"must be true or false, got {shorten(table.raw(key))}")
                values[key] = table.get(key)
                continue
            value = table.quantity(key, dimension)
            if key == "poisson_ratio":
                if not 0.0 <= value < 0.5:
                    raise SceneError(f"{where}.{key}", f"must be in [0, 0.5), got {shorten(table.raw(key))}")
            elif key == "safety_factor":
                if value < 1.0:
                    raise SceneError(f"{where}.{key}", f"must be >= 1, got {shorten(table.raw(key))}")
            elif value <= 0:
                raise SceneError(f"{where}.{key}", f"must be positive, got {shorten(table.raw(key))}")
            values[key] = value
        if table.has("hub_rule"):
            from flyopt.design.hub import hub_rules

            rule = table.get("hub_rule")
            if rule not in hub_rules():
                raise SceneError(
                    f"{where}.hub_rule", f"{shorten(rule)} is not a hub rule (allowed: {', '.join(hub_rules())})"
                )
            values["hub_rule"] = rule
        source = table.get("source", "scene file")
        try:
            materials.append(make_material(name, source=str(source), **values))
        except ValueError as err:
            raise SceneError(where, str(err)) from None
    return tuple(materials)


def _design(raw, shafts, materials):
    from flyopt.design.geometry import GEOMETRIES
    from flyopt.design.materials import material_library
    from flyopt.design.spec import CRITERIA, OBJECTIVES, DesignSpec

    table = _Table(
        raw,
        "design",
        {
            "geometry",
            "materials",
            "shafts",
            "hb_ratio",
            "max_outer_diameter",
            "max_width",
            "d_mean",
            "objective",
            "description",
            "criterion",
            "safety_factor",
            "bore",
            "arms",
            "min_wall",
            "prune",
        },
    )
    library = material_library(materials)
    names = _name_list(table, "materials", library, "material")
    shaft_names = _name_list(table, "shafts", {s.name: s for s in shafts}, "shaft")
    options = {}
    for key in ("geometry", "objective", "criterion"):
        if table.has(key):
            value = table.get(key)
            vocabulary: Any = {"geometry": GEOMETRIES, "objective": OBJECTIVES, "criterion": CRITERIA}[key]
            allowed = tuple(vocabulary)
            if value not in allowed:
                raise SceneError(f"design.{key}", unknown(value, allowed))
            options[key] = value
    if table.has("hb_ratio"):
        hb = table.get("hb_ratio")
        pair = hb if isinstance(hb, list) else [hb, hb]
        if len(pair) != 2:
            raise SceneError("design.hb_ratio", f"must be one number or a range [min, max], got {shorten(hb)}")
        low, high = (quantity(v, "dimensionless", "design.hb_ratio") for v in pair)
        if not 0 < low <= high:
            raise SceneError("design.hb_ratio", f"must be a range 0 < min <= max, got {shorten(hb)}")
        options["hb_ratio"] = (low, high)
    for key in ("max_outer_diameter", "max_width", "d_mean", "min_wall"):
        if table.has(key):
            value = table.quantity(key, "length")
            if value <= 0:
                raise SceneError(f"design.{key}", f"must be positive, got {shorten(table.raw(key))}")
            options[key] = value
    if table.has("bore"):
        value = table.quantity("bore", "length")
        if value < 0:
            raise SceneError("design.bore", f"must be >= 0 (0: no bore), got {shorten(table.raw('bore'))}")
        envelope = options.get("max_outer_diameter", math.inf)
        if value >= envelope:
            raise SceneError(
                "design.bore",
                f"{shorten(table.raw('bore'))} does not fit inside "
                f"max_outer_diameter {shorten(table.raw('max_outer_diameter'))}",
            )
        options["bore"] = value
    if table.has("safety_factor"):
        value = table.quantity("safety_factor", "dimensionless")
        if value < 1:
            raise SceneError(
                "design.safety_factor",
                f"must be >= 1 (the allowable stress is the strength "
                f"over it), got {shorten(table.raw('safety_factor'))}",
            )
        options["safety_factor"] = value
    if table.has("arms"):
        arms = table.get("arms")
        arms = arms if isinstance(arms, list) else [arms]
        if (
            not arms
            or any(isinstance(n, bool) or not isinstance(n, int) or n < 3 for n in arms)
            or len(set(arms)) != len(arms)
        ):
            raise SceneError(
                "design.arms",
                f"must be whole arm counts >= 3, each once (e.g. [4, 6, 8]), got {shorten(table.raw('arms'))}",
            )
        options["arms"] = tuple(arms)
    if table.has("prune"):
        value = table.get("prune")
        if not isinstance(value, bool):
            raise SceneError("design.prune", f"must be true or false, got {shorten(table.raw('prune'))}")
        options["prune"] = value
    if options.get("objective") == "cost":
        from flyopt.design.materials import design_material_names

        chosen = design_material_names(library, names)
        missing = [n for n in chosen if library[n].cost is None]
        if missing:
            raise SceneError(
                "design.objective",
                f"'cost' needs a cost per kg for every material; none is given for {', '.join(missing)}",
            )
    try:
        spec = DesignSpec(**options)
    except ValueError as err:
        raise SceneError("design", str(err)) from None
    return spec, names, shaft_names


def _name_list(table, key, known, what):
    if not table.has(key):
        return None
    raw = table.get(key)
    if not isinstance(raw, list) or not raw or not all(isinstance(n, str) for n in raw):
        raise SceneError(f"design.{key}", f"must be a non-empty list of {what} names")
    for k, name in enumerate(raw):
        if name not in known:
            raise SceneError(
                f"design.{key}[{k}]", f"unknown {what} {shorten(name)}{hint(name, known)} (known: {', '.join(known)})"
            )
    if len(set(raw)) != len(raw):
        raise SceneError(f"design.{key}", f"a {what} is named twice")
    return tuple(raw)


def _reference_efficiency(shafts):
    """Efficiency from the motor to the reference shaft: that of the shaft turning at ratio 1."""
    at_reference = {s.efficiency for s in shafts if s.speed_ratio == 1.0}
    if len(at_reference) > 1:
        raise SceneError(
            "machine.efficiency",
            "several shafts turn at the reference speed with different "
            "efficiencies; say which applies with machine.efficiency",
        )
    return at_reference.pop() if at_reference else 1.0


def _efficiency(raw, where):
    """An efficiency in (0, 1], or a list of stage efficiencies in series (their product)."""
    stages = raw if isinstance(raw, list) else [raw]
    if not stages:
        raise SceneError(where, "must be a number in (0, 1] or a non-empty list of stage efficiencies")
    product = 1.0
    for k, s in enumerate(stages):
        label = f"{where}[{k}]" if isinstance(raw, list) else where
        eta = quantity(s, "dimensionless", label)
        if not 0 < eta <= 1:
            raise SceneError(label, f"must lie in (0, 1], got {shorten(s)}")
        product *= eta
    return product


def _unit_factor(raw, dimension, where):
    if not isinstance(raw, str):
        raise SceneError(where, f"must be a unit string, got {shorten(raw)}")
    return quantity(f"1 {raw}", dimension, where)


def _scaled(raw, dimension, where, factor):
    """A number times the section's unit, or a string with its own unit."""
    if isinstance(raw, str):
        return quantity(raw, dimension, where)
    return quantity(raw, "dimensionless", where) * factor


class _Table:
    """A dictionary from TOML with checked keys and typed accessors."""

    def __init__(self, data, where, allowed):
        if not isinstance(data, dict):
            raise SceneError(where or "(top level)", f"must be a table, got {type(data).__name__}")
        unknown = sorted(set(data) - set(allowed))
        if unknown:
            key = unknown[0]
            path = f"{where}.{key}" if where else key
            raise SceneError(
                path, f"unknown key{hint(key, sorted(allowed))} (allowed here: {', '.join(sorted(allowed))})"
            )
        self.data, self.where = data, where

    def _path(self, key):
        return f"{self.where}.{key}" if self.where else key

    def has(self, key):
        return key in self.data

    def raw(self, key):
        return self.data.get(key)

    def get(self, key, default=None):
        return self.data.get(key, default)

    def require(self, key):
        if key not in self.data:
            raise SceneError(self._path(key), "is missing")
        return self.data[key]

    def quantity(self, key, dimension, required=False, default=None):
        if key not in self.data:
            if required:
                raise SceneError(self._path(key), "is missing")
            return default
        return quantity(self.data[key], dimension, self._path(key))

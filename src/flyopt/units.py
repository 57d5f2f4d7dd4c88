"""Units at the boundary: parse quantities with pint, hand SI floats inward.

Scene files and the command line speak units ("1500 rpm", "0.8 m",
"100 N*m/mm"); everything past this module sees plain SI floats.
Plain numbers are taken as SI (angles in radians, speeds in rad/s). A
fraction may be written with its unit ("1 %", "5 permille"): it is converted
to a plain number (0.01, 0.005) like any other unit, and is no speed or angle.

The common forms ("1500 rpm", "3.5 kN*m", "7800 kg/m^3": a number, a space and
a unit of :data:`FAST_UNITS`) are read from a small table without pint, which
takes about half a second to import and build; every other string, and every
error, goes through pint. The table holds pint's own conversion factors and
gives the same float as pint, bit for bit (tests/test_units_fast.py checks
each entry against pint).
"""

from __future__ import annotations

import functools
import math
import re
from typing import TYPE_CHECKING, Any, TypeVar

from flyopt.errors import SceneError, clip, shorten

if TYPE_CHECKING:
    import numpy as np
    import numpy.typing as npt

#: A speed or an array of speeds (numpy is not imported here: a conversion is the same arithmetic on either).
_Speeds = TypeVar("_Speeds", float, "npt.NDArray[np.float64]")

G_STANDARD = 9.81
"""Acceleration of gravity used for GD² [m/s^2] (the electric-drive convention, GD² = 4 g J)."""

MAX_QUANTITY_LENGTH = 100
"""Longest string accepted as a number with a unit [characters] ("1500 rpm" has 8)."""

MAX_EXPONENT_DIGITS = 3
"""Most digits of an exponent in a quantity string ("m^2", "10**-3 m"): a power, not a tower."""

_POWER = re.compile(r"\*\*|\^")
_EXPONENT = re.compile(r"\s*\(?\s*[+-]?\s*\d{1," + str(MAX_EXPONENT_DIGITS) + r"}(?![\d_])(?:\.\d*)?\s*\)?")

# Dimension name -> (pint dimensionality string, SI unit to convert to, words for errors)
DIMENSIONS = {
    "angle": ("", "rad", "an angle (e.g. '90 deg' or radians)"),
    "angular_speed": ("1/[time]", "rad/s", "a rotational speed (e.g. '1500 rpm' or rad/s)"),
    "torque": ("[mass]*[length]**2/[time]**2", "N*m", "a torque (e.g. '200 N*m')"),
    "energy": ("[mass]*[length]**2/[time]**2", "J", "an energy (e.g. '1500 J')"),
    "inertia": ("[mass]*[length]**2", "kg*m**2", "a moment of inertia (e.g. '3.5 kg*m^2')"),
    "flywheel_moment": ("[mass]*[length]**3/[time]**2", "N*m**2", "a flywheel moment GD² (e.g. '3.5 N*m^2')"),
    "length": ("[length]", "m", "a length (e.g. '0.8 m')"),
    "mass": ("[mass]", "kg", "a mass (e.g. '475 kg')"),
    "density": ("[mass]/[length]**3", "kg/m**3", "a density (e.g. '7800 kg/m^3')"),
    "speed": ("[length]/[time]", "m/s", "a speed (e.g. '36 m/s')"),
    "stress": ("[mass]/[length]/[time]**2", "Pa", "a stress (e.g. '100 MPa')"),
    "power": ("[mass]*[length]**2/[time]**3", "W", "a power (e.g. '7.5 kW')"),
    "force": ("[mass]*[length]/[time]**2", "N", "a force (e.g. '100 N')"),
    "area": ("[length]**2", "m**2", "an area (e.g. '580 mm^2')"),
    "energy_per_area": ("[mass]/[time]**2", "J/m**2", "an energy per sheared area (e.g. '6 J/mm^2')"),
    "torque_scale": ("[mass]*[length]/[time]**2", "N*m/m", "a torque scale (e.g. '100 N*m/mm')"),
    "angle_scale": ("1/[length]", "rad/m", "an angle scale (e.g. '0.01 rad/mm')"),
    "dimensionless": ("", "", "a plain number"),
    "cost_per_mass": ("1/[mass]", "1/kg", "a cost per kilogram (e.g. '2.1 1/kg')"),
    "time": ("[time]", "s", "a time (e.g. '2 s')"),
    "angular_acceleration": ("1/[time]**2", "rad/s**2", "an angular acceleration (e.g. '800 rpm/s' or rad/s^2)"),
    "torsional_stiffness": (
        "[mass]*[length]**2/[time]**2",
        "N*m/rad",
        "a torsional stiffness (e.g. '250 kN*m/rad')",
    ),
    "stiffness": ("[mass]/[time]**2", "N/m", "a stiffness (e.g. '2.4 MN/m' or '2400 N/mm')"),
}

#: The magnitudes a scalar quantity of a scene may take, by dimension: (smallest, largest, in words), SI, of its
#: absolute value; 0 is always allowed (a section says where it is not). Beyond them a value is a slip of unit or
#: of exponent, and the computation under- or overflows: a crank of 1e-320 m divides by zero, a member of
#: 1e300 kg overflows the energies. Each is wider than any machine a flywheel regulates; the sections hold some
#: fields to narrower ranges of their own (machine.speed, delta, a material's strengths).
MAGNITUDES: dict[str, tuple[float, float, str]] = {
    "length": (1e-6, 1e3, "a micron to a kilometre"),
    "mass": (1e-6, 1e9, "a milligram to a million tonnes"),
    "inertia": (1e-9, 1e12, "1e-9 to 1e12 kg*m^2"),
    "flywheel_moment": (4e-8, 4e13, "GD^2 = 4 g J of 1e-9 to 1e12 kg*m^2"),
    "force": (1e-9, 1e15, "a nanonewton to 1e15 N"),
    "torque": (1e-9, 1e15, "1e-9 to 1e15 N*m"),
    "energy": (1e-9, 1e15, "a nanojoule to a petajoule"),
    "power": (1e-9, 1e12, "a nanowatt to a terawatt"),
    "stress": (1e-3, 1e12, "a millipascal to a terapascal"),
    "energy_per_area": (1e-3, 1e12, "a millijoule to a terajoule a square metre"),
    "area": (1e-12, 1e6, "a square micron to a square kilometre"),
    "density": (1.0, 1e5, "from a foam to beyond osmium's 22,600"),  # a [[material]]'s too
    "speed": (1e-9, 1e5, "a nanometre a second to 100 km/s"),
    "angular_speed": (1e-9, 1e7, "1e-9 to 1e7 rad/s"),
    "angular_acceleration": (1e-9, 1e12, "1e-9 to 1e12 rad/s^2"),
    "angle": (0.0, 1e6, "up to some 160,000 turns"),  # no divisor: however small, an angle is computed with
    "time": (1e-9, 1e9, "a nanosecond to some 30 years"),
    "dimensionless": (1e-9, 1e9, "a billionth to a billion"),
    "cost_per_mass": (1e-9, 1e9, "1e-9 to 1e9 a kilogram"),
    "torque_scale": (1e-9, 1e15, "1e-9 to 1e15 N*m a metre of the drawing"),
    "angle_scale": (1e-9, 1e9, "1e-9 to 1e9 rad a metre of the drawing"),
    "torsional_stiffness": (1e-6, 1e15, "1e-6 to 1e15 N*m/rad"),
    "stiffness": (1e-6, 1e15, "1e-6 to 1e15 N/m"),
}

#: Units read without pint, per dimension: the unit as written -> pint's factor to the SI unit of
#: ``DIMENSIONS`` (``Quantity(1, unit).to(si).magnitude``, written out; the test checks each against pint).
FAST_UNITS = {
    "angle": {
        "rad": 1.0,
        "radian": 1.0,
        "deg": 0.017453292519943295,
        "degree": 0.017453292519943295,
        "turn": 6.283185307179586,
        "rev": 6.283185307179586,
        "revolution": 6.283185307179586,
    },
    "angular_speed": {
        "rpm": 0.10471975511965977,
        "rev/min": 0.10471975511965977,
        "rad/s": 1.0,
        "deg/s": 0.017453292519943295,
        "rev/s": 6.283185307179586,
        "rps": 6.283185307179586,
        "Hz": 1.0,
        "1/s": 1.0,
        "/s": 1.0,
        "s^-1": 1.0,
        "1/min": 0.016666666666666666,
        "/min": 0.016666666666666666,
        "min^-1": 0.016666666666666666,
    },
    "torque": {"N*m": 1.0, "N m": 1.0, "kN*m": 1000.0, "kN m": 1000.0, "MN*m": 1000000.0, "N*mm": 0.001, "kN*mm": 1.0},
    "energy": {
        "J": 1.0,
        "kJ": 1000.0,
        "MJ": 1000000.0,
        "N*m": 1.0,
        "N m": 1.0,
        "kN*m": 1000.0,
        "kN m": 1000.0,
        "W*s": 1.0,
        "kWh": 3600000.0,
    },
    "inertia": {
        "kg*m^2": 1.0,
        "kg m^2": 1.0,
        "kg*m**2": 1.0,
        "kg m**2": 1.0,
        "t*m^2": 1000.0,
        "kg*cm^2": 0.0001,
        "kg*mm^2": 1e-06,
    },
    "flywheel_moment": {"N*m^2": 1.0, "N m^2": 1.0, "N*m**2": 1.0, "kN*m^2": 1000.0},
    "length": {"m": 1.0, "mm": 0.001, "cm": 0.01, "dm": 0.1, "km": 1000.0},
    "mass": {"kg": 1.0, "g": 0.001, "t": 1000.0, "tonne": 1000.0},
    "density": {
        "kg/m^3": 1.0,
        "kg/m**3": 1.0,
        "t/m^3": 1000.0,
        "g/cm^3": 999.9999999999999,
        "kg/dm^3": 999.9999999999999,
    },
    "speed": {"m/s": 1.0, "mm/s": 0.001, "m/min": 0.016666666666666666, "km/h": 0.2777777777777778},
    "stress": {
        "Pa": 1.0,
        "kPa": 1000.0,
        "MPa": 1000000.0,
        "GPa": 1000000000.0,
        "N/m^2": 1.0,
        "N/mm^2": 1000000.0,
        "bar": 100000.0,
        "mbar": 100.0,
        "psi": 6894.7572931683635,
    },
    "power": {"W": 1.0, "kW": 1000.0, "MW": 1000000.0, "hp": 745.6998715822701},
    "force": {"N": 1.0, "kN": 1000.0, "MN": 1000000.0},
    "area": {"m^2": 1.0, "m**2": 1.0, "cm^2": 0.0001, "cm**2": 0.0001, "mm^2": 1e-06, "mm**2": 1e-06},
    "angular_acceleration": {
        "rad/s^2": 1.0,
        "rad/s**2": 1.0,
        "rpm/s": 0.10471975511965977,
    },
    "energy_per_area": {
        "J/m^2": 1.0,
        "J/m**2": 1.0,
        "J/mm^2": 1000000.0,
        "J/mm**2": 1000000.0,
        "N*m/mm^2": 1000000.0,
        "N*m/mm**2": 1000000.0,
        "kJ/m^2": 1000.0,
        "kJ/m**2": 1000.0,
    },
    "torque_scale": {
        "N*m/m": 1.0,
        "N*m/cm": 100.0,
        "N*m/mm": 1000.0,
        "N m/mm": 1000.0,
        "kN*m/m": 1000.0,
        "kN*m/mm": 1000000.0,
    },
    "angle_scale": {
        "rad/m": 1.0,
        "rad/cm": 100.0,
        "rad/mm": 1000.0,
        "deg/m": 0.017453292519943295,
        "deg/cm": 1.7453292519943295,
        "deg/mm": 17.453292519943297,
    },
    "dimensionless": {"%": 0.01, "percent": 0.01, "permille": 0.001, "ppm": 1e-06},
    "cost_per_mass": {"1/kg": 1.0, "/kg": 1.0},
    "time": {"s": 1.0, "ms": 0.001, "min": 60.0},
    "torsional_stiffness": {"N*m/rad": 1.0, "kN*m/rad": 1000.0, "MN*m/rad": 1000000.0},
    "stiffness": {"N/m": 1.0, "kN/m": 1000.0, "MN/m": 1000000.0, "N/mm": 1000.0, "kN/mm": 1000000.0},
}

_PER_TURN = frozenset({"Hz", "1/s", "/s", "s^-1", "1/min", "/min", "min^-1"})
"""Rotational frequencies of :data:`FAST_UNITS`: a bare 1/time, revolutions per time (times 2π to rad/s)."""

#: A number as Python writes it (what pint reads), then a unit after blanks ("1500 rpm"), or a unit
#: beginning with % or / after optional blanks ("5%", "1500/min").
#: An integer with a leading zero ("0150") is no Python number: pint says so.
_COMMON_FORM = re.compile(
    r"([+-]?(?:(?:0|[1-9][0-9]*)(?![0-9.eE])|(?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?"
    r"|[0-9]+[eE][+-]?[0-9]+))(?:[ \t]*([%/][^ \t]*)|[ \t]+([^ \t].*))?\Z",
    re.ASCII,
)
_INTEGER = re.compile(r"[+-]?[0-9]+\Z")


@functools.lru_cache(maxsize=1)
def registry() -> Any:  # a pint.UnitRegistry (pint is imported here, on first use)
    """The one pint UnitRegistry of flyopt (built lazily: it takes a while)."""
    import pint

    ureg: Any = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("rev = revolution")
    return ureg


def quantity(value: object, dimension: str, field: str = "value") -> float:
    """Convert a scene value to an SI float of the given dimension.

    Parameters
    ----------
    value : int, float or str
        A plain number (taken as SI) or a string with a unit, e.g. "1500 rpm".
    dimension : str
        One of the keys of ``DIMENSIONS``.
    field : str
        Dotted name of the field, for the error message.

    Returns
    -------
    float
        The value in SI units (see ``DIMENSIONS``).

    Raises
    ------
    SceneError
        Not a number, unknown unit, wrong dimension, NaN or infinite; a
        string longer than ``MAX_QUANTITY_LENGTH`` or with a power of a
        power ("9**9**9 rpm") or an exponent of more than
        ``MAX_EXPONENT_DIGITS`` digits, refused before pint evaluates it.

    Notes
    -----
    Every number with a unit that flyopt reads (scene fields, the sweep's
    ``--vary`` and ``--range`` values) passes through this function, so the
    bounds above hold everywhere: pint evaluates a string's arithmetic with
    Python integers, and ``9**9**9`` would take hours.
    """
    words = DIMENSIONS[dimension][2]
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise SceneError(field, f"expected {words}, got {shorten(value)}")
    try:
        number = _si_number(value, dimension, field) if isinstance(value, str) else float(value)
    except OverflowError:  # an integer beyond the floats (TOML allows 4300 digits)
        number = math.inf
    if not math.isfinite(number):
        raise SceneError(field, f"must be finite, got {shorten(value)}")
    if dimension in PLAIN_SLIPS and is_plain(value):
        _check_plain(number, value, dimension, field)
    return number


#: Plain numbers (SI) that are, in all likelihood, values whose unit was left out: {dimension: (low, high,
#: the SI unit, what to write)}, a positive plain number from low up to (not including) high refused. A shaft
#: seat written ``diameter = 70`` (meaning mm) is a 70 m shaft, on which no key and no hub exists: the design
#: went on without that shaft, saying so only among its infeasible combinations. No length of a machine a
#: flywheel regulates reaches 10 m as a plain number (a larger one, a ship's line shafting, takes its unit:
#: "12 m"), and every part of one in millimetres is below 10,000; no strength, modulus or pressure flyopt reads
#: is below 1 kPa, and one in MPa or GPa is from 1 up. Each band refuses only a plain number: the same value
#: with its unit is read as written. Beyond a band (1e300), the field's own magnitude check says what is allowed.
PLAIN_SLIPS = {
    "length": (10.0, 1e4, "m", 'e.g. "{v} mm", or "{v} m" if metres are meant'),
    "stress": (1.0, 1e3, "Pa", 'e.g. "{v} MPa", "{v} bar" or "{v} GPa", or "{v} Pa" if pascals are meant'),
}


#: A number written in a string: digits, a decimal point, an exponent.
_NUMBER = re.compile(r"(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")
#: What may stand between the numbers of a string that names no unit: arithmetic and blanks ("7*10", "(35 + 35)",
#: "2**3", "2^3").
_ARITHMETIC = re.compile(r"[\s+\-*/^()]*")


def is_plain(value: object) -> bool:
    """Whether a scene value is a plain number: a number, or a string that names no unit: one number ("70"), or
    arithmetic on numbers ("7*10", which the reader evaluates to the plain 70: it carries no unit either)."""
    if not isinstance(value, str):
        return True
    try:
        float(value)
    except ValueError:
        return _NUMBER.search(value) is not None and _ARITHMETIC.fullmatch(_NUMBER.sub(" ", value)) is not None
    return True


def _check_plain(number: float, value: object, dimension: str, field: str) -> None:
    """Refuse a plain number within its dimension's band of :data:`PLAIN_SLIPS` (its unit left out), saying
    what to write."""
    low, high, unit, write = PLAIN_SLIPS[dimension]
    if not low <= number < high:
        return
    written = clip(str(value).strip())
    raise SceneError(
        field,
        f"the plain number {written} is {number:.15g} {unit} (plain numbers are SI): give its unit: "
        + write.format(v=written),
    )


def _si_number(text: str, dimension: str, field: str) -> float:
    """The SI float of a string with a unit (see :func:`quantity`)."""
    _check_size(text, field, DIMENSIONS[dimension][2])
    number = _table_number(text, dimension)
    return _pint_number(text, dimension, field) if number is None else number


def _table_number(text: str, dimension: str) -> float | None:
    """The SI float of a common form ("1500 rpm", "0.8 m", "0.05", "mm^2"), or None when pint must read it.

    Gives what :func:`_pint_number` gives, to the last bit: pint reads an
    integer literal as an int and a decimal as a float (``float(text)`` rounds
    the same way), and converts by one multiplication with its factor; a bare
    1/time is then multiplied by 2π, as there.

    Parameters
    ----------
    text : str
        The string as written (surrounding blanks allowed).
    dimension : str
        One of the keys of ``DIMENSIONS``.

    Returns
    -------
    float or None
        The value in SI units; None for anything else: another unit, another
        spelling, arithmetic, a unit of another dimension (pint then reads it,
        or says what is wrong).

    Raises
    ------
    OverflowError
        An integer beyond the floats, as pint's own conversion raises it.
    """
    text = text.strip()
    if text in FAST_UNITS[dimension] and text[0] != "/":  # a unit alone ("mm^2") is one of it, as pint reads it
        number: int | float = 1
        unit = text
    else:
        match = _COMMON_FORM.match(text)
        if match is None:
            return None
        digits, unit = match.group(1), match.group(2) or match.group(3)
        number = int(digits) if _INTEGER.match(digits) else float(digits)
        if unit is None:
            return float(number)
    factor = FAST_UNITS[dimension].get(unit)
    if factor is None:
        return None
    value = number * factor
    if dimension == "angular_speed" and unit in _PER_TURN:
        value *= 2.0 * math.pi
    return value


def unit_value(text: str, dimension: str, field: str) -> float:
    """The SI value of one unit written alone (a section's ``unit = "kN*m"``, ``angle_unit = "deg"``).

    The text must be a unit and nothing else: a number or a sign in it is refused (``"N*m*0"``, ``"-1"`` and
    ``"*2"`` were read as arithmetic on "1 " and the text, which made every torque 0 or twice its value), as is a
    unit without a dimension where ``dimension`` has one. Errors quote the text as written.

    Raises
    ------
    SceneError
        Naming ``field``.
    """
    words = DIMENSIONS[dimension][2]
    text = text.strip()
    if text in FAST_UNITS[dimension]:  # a common unit ("mm", "/min"): read without pint, as "1 mm" is
        return quantity(f"1 {text}", dimension, field)
    _check_size(text, field, words)
    _check_form(text, field, words)
    try:
        unit = registry().Unit(text)
    except Exception as err:  # pint: a scaling factor ("2 m", "-1"), a syntax error ("*2"), an unknown name
        undefined = type(err).__name__ == "UndefinedUnitError"
        reason = _pint_reason(err) if undefined else "a number, a sign or an operator on nothing is no part of a unit"
        raise SceneError(field, f"{shorten(text)} is not a unit of {words}: {reason}; write the unit alone") from None
    if unit.dimensionless and DIMENSIONS[dimension][0]:
        raise SceneError(field, f"{shorten(text)} is not a unit of {words}: it has no dimension; write the unit alone")
    return _si_of(registry().Quantity(1, unit), text, dimension, field)


def _pint_number(text: str, dimension: str, field: str) -> float:
    """The SI float of a string with a unit, read by pint (see :func:`quantity`)."""
    words = DIMENSIONS[dimension][2]
    _check_form(text, field, words)
    try:
        q = registry().Quantity(text.strip())
    except Exception as err:  # pint raises many types (UndefinedUnitError, DefinitionSyntaxError, ...)
        raise SceneError(field, f"cannot read {shorten(text)} as {words}: {_pint_reason(err)}") from None
    return _si_of(q, text, dimension, field)


def _si_of(q: Any, text: str, dimension: str, field: str) -> float:
    """The SI float of pint's reading ``q`` of ``text`` (a quantity, or a plain number), its dimension checked."""
    dim, si_unit, words = DIMENSIONS[dimension]
    if not hasattr(q, "units") or q.units == registry().dimensionless:
        return float(q.magnitude if hasattr(q, "magnitude") else q)  # no unit written (or "rad/rad"): SI
    # "%", "permille", "ppm", "m/mm" are units too: a fraction, converted like any other unit
    want = registry().get_dimensionality(dim) if dim else registry().Quantity(1).dimensionality
    # an angle has no dimension in SI, yet "3 deg" is no δ and "2 rad" no speed ratio: neither is taken for a
    # plain number, as "50 %" is no angle
    mistaken = dimension in ("angle", "dimensionless") and _is_angle(q) != (dimension == "angle")
    if q.dimensionality != want or mistaken:
        raise SceneError(field, f"{shorten(text)} has the wrong dimension: expected {words}")
    number = float(q.to(si_unit).magnitude) if si_unit else float(q.to("").magnitude)
    if dimension == "angular_speed" and not _is_angle(q):
        # a bare 1/time ("25 Hz", "1500 1/min") is a rotational frequency: revolutions per time
        number *= 2.0 * math.pi
    return number


#: What a quantity string may hold: letters (µ, Ω too), digits, blanks, the arithmetic of units and numbers
#: ("kg*m^2", "(35 + 35) mm", "10**-3 m", "1/min"), "%" and the degree sign. pint's tokenizer drops or reads
#: the rest its own way: "300 rpm!" was read as 300 rpm, "300rpm=400" as 120,000 rpm.
_QUANTITY_CHARACTERS = re.compile(r"[\w\s.*/^()+\-%°·²³]*")
#: A number of a quantity string, and what stands before it: a number right after another number, a unit or a
#: closing bracket, with blanks alone between, is multiplied by pint ("600 rpm 2" is 1200 rpm, "300 2 rpm" 600).
_JUXTAPOSED = re.compile(r"(?:[\w)]|(?<![\w.])\d+\.?\d*(?:[eE][-+]?\d+)?)\s+(?=[\d.])(?!1\s*/)")  # "1/min" a unit


def _check_form(text: str, field: str, words: str) -> None:
    """Refuse a quantity string that is not one number and its unit, read the way pint reads it: a character
    pint would drop or read as an operator ("!", "="), a number written after a number or a unit with only
    blanks between (pint multiplies them), or "%" beside another unit ("600 rpm%" is 6 rpm)."""
    bad = None
    if not _QUANTITY_CHARACTERS.fullmatch(text):
        bad = f"{_QUANTITY_CHARACTERS.sub('', text)[:1]!r} is no part of a number or a unit"
    elif _JUXTAPOSED.search(text.strip()):
        bad = "a number follows a number or a unit, and pint would multiply them"
    elif "%" in text and not re.fullmatch(r"\s*[-+]?(?:\d+\.?\d*|\.\d+)?(?:[eE][-+]?\d+)?\s*%\s*", text):
        bad = "a percentage stands alone after its number ('5 %')"
    if bad:
        raise SceneError(field, f"cannot read {shorten(text)} as {words}: {bad}; write one number and its unit")


def _check_size(text: str, field: str, words: str) -> None:
    """Refuse a string whose arithmetic could run for long: too long, or a power of a power."""
    if len(text) > MAX_QUANTITY_LENGTH:
        raise SceneError(
            field,
            f"{shorten(text)} is too long for {words}: a number with a unit "
            f"has at most {MAX_QUANTITY_LENGTH} characters",
        )
    for power in _POWER.finditer(text):
        exponent = _EXPONENT.match(text, power.end())
        if exponent is None or _POWER.match(text, exponent.end()):
            raise SceneError(
                field,
                f"cannot read {shorten(text)} as {words}: an exponent must be a number "
                f"of at most {MAX_EXPONENT_DIGITS} digits, not itself a power",
            )


def _is_angle(q: Any) -> bool:
    """True when the units hold an angle ("90 deg", "1 turn", "rpm"), not a ratio ("50 %") or a bare 1/time."""
    return "radian" in str(q.to_root_units().units)


def _pint_reason(err: Exception) -> str:
    """pint's reason, its first line; where pint's parser gives none of its own (an empty AssertionError for
    "-" or "*", Python's tokenizer's "EOF in multi-line statement" for "("), what the text is not, rather than
    the name of pint's exception or the tokenizer's tuple."""
    import tokenize

    if isinstance(err, (AssertionError, tokenize.TokenError, SyntaxError)) or not str(err).strip():
        return "it is not a number followed by a unit"
    return clip(str(err).strip().splitlines()[0])


def rpm_to_rad_s(n: _Speeds) -> _Speeds:
    """Rotational speed n [rev/min] to angular speed [rad/s]: ω = 2πn/60 (of each, for an array)."""
    return 2.0 * math.pi * n / 60.0


def rad_s_to_rpm(omega: float) -> float:
    """Angular speed ω [rad/s] to rotational speed [rev/min]: n = 60ω/(2π)."""
    return 60.0 * omega / (2.0 * math.pi)


def gd2_from_inertia(j: float, g: float = G_STANDARD) -> float:
    """Flywheel moment GD² [N*m^2] of a moment of inertia J [kg*m^2]: GD² = 4 g J."""
    return 4.0 * g * j


def inertia_from_gd2(gd2: float, g: float = G_STANDARD) -> float:
    """Moment of inertia J [kg*m^2] of a flywheel moment GD² [N*m^2]: J = GD²/(4 g)."""
    return gd2 / (4.0 * g)

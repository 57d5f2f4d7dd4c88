"""Units at the boundary: parse quantities with pint, hand SI floats inward.

Scene files and the command line speak units ("1500 rpm", "0.8 m",
"100 N*m/mm"); everything past this module sees plain SI floats.
Plain numbers are taken as SI (angles in radians, speeds in rad/s). A
fraction may be written with its unit ("1 %", "5 permille"): it is converted
to a plain number (0.01, 0.005) like any other unit, and is no speed or angle.
"""

import functools
import math
import re

from flyopt.errors import SceneError, clip, shorten

G_STANDARD = 9.81
"""Acceleration of gravity used for GD² [m/s^2] (the electric-drive convention, GD² = 4 g J)."""

MAX_QUANTITY_LENGTH = 100
"""Longest string accepted as a number with a unit [characters] ("1500 rpm" has 8)."""

MAX_EXPONENT_DIGITS = 3
"""Most digits of an exponent in a quantity string ("m^2", "10**-3 m"): a power, not a tower."""

_POWER = re.compile(r"\*\*|\^")
_EXPONENT = re.compile(r"\s*\(?\s*[+-]?\s*\d{1,%d}(?![\d_])(?:\.\d*)?\s*\)?" % MAX_EXPONENT_DIGITS)

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
    "torque_scale": ("[mass]*[length]/[time]**2", "N*m/m", "a torque scale (e.g. '100 N*m/mm')"),
    "angle_scale": ("1/[length]", "rad/m", "an angle scale (e.g. '0.01 rad/mm')"),
    "dimensionless": ("", "", "a plain number"),
    "cost_per_mass": ("1/[mass]", "1/kg", "a cost per kilogram (e.g. '2.1 1/kg')"),
}


@functools.lru_cache(maxsize=1)
def registry():
    """The one pint UnitRegistry of flyopt (built lazily: it takes a while)."""
    import pint

    ureg = pint.UnitRegistry(autoconvert_offset_to_baseunit=True)
    ureg.define("rev = revolution")
    return ureg


def quantity(value, dimension, field="value"):
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
    except OverflowError:       # an integer beyond the floats (TOML allows 4300 digits)
        number = math.inf
    if not math.isfinite(number):
        raise SceneError(field, f"must be finite, got {shorten(value)}")
    return number


def _si_number(text, dimension, field):
    """The SI float of a string with a unit (see :func:`quantity`)."""
    dim, si_unit, words = DIMENSIONS[dimension]
    _check_size(text, field, words)
    try:
        q = registry().Quantity(text.strip())
    except Exception as err:  # pint raises many types (UndefinedUnitError, DefinitionSyntaxError, ...)
        raise SceneError(field, f"cannot read {shorten(text)} as {words}: {_pint_reason(err)}") from None
    if not hasattr(q, "units") or q.units == registry().dimensionless:
        return float(q.magnitude if hasattr(q, "magnitude") else q)  # no unit written (or "rad/rad"): SI
    # "%", "permille", "ppm", "m/mm" are units too: a fraction, converted like any other unit
    want = registry().get_dimensionality(dim) if dim else registry().Quantity(1).dimensionality
    if q.dimensionality != want or (dimension == "angle" and not _is_angle(q)):
        raise SceneError(field, f"{shorten(text)} has the wrong dimension: expected {words}")
    number = float(q.to(si_unit).magnitude) if si_unit else float(q.to("").magnitude)
    if dimension == "angular_speed" and not _is_angle(q):
        # a bare 1/time ("25 Hz", "1500 1/min") is a rotational frequency: revolutions per time
        number *= 2.0 * math.pi
    return number


def _check_size(text, field, words):
    """Refuse a string whose arithmetic could run for long: too long, or a power of a power."""
    if len(text) > MAX_QUANTITY_LENGTH:
        raise SceneError(field, f"{shorten(text)} is too long for {words}: a number with a unit "
                         f"has at most {MAX_QUANTITY_LENGTH} characters")
    for power in _POWER.finditer(text):
        exponent = _EXPONENT.match(text, power.end())
        if exponent is None or _POWER.match(text, exponent.end()):
            raise SceneError(field, f"cannot read {shorten(text)} as {words}: an exponent must be a number "
                             f"of at most {MAX_EXPONENT_DIGITS} digits, not itself a power")


def _is_angle(q):
    """True when the units hold an angle ("90 deg", "1 turn", "rpm"), not a ratio ("50 %") or a bare 1/time."""
    return "radian" in str(q.to_root_units().units)


def _pint_reason(err):
    text = str(err).strip().splitlines()[0] if str(err).strip() else type(err).__name__
    return clip(text)


def rpm_to_rad_s(n):
    """Rotational speed n [rev/min] to angular speed [rad/s]: ω = 2πn/60."""
    return 2.0 * math.pi * n / 60.0


def rad_s_to_rpm(omega):
    """Angular speed ω [rad/s] to rotational speed [rev/min]: n = 60ω/(2π)."""
    return 60.0 * omega / (2.0 * math.pi)


def gd2_from_inertia(j, g=G_STANDARD):
    """Flywheel moment GD² [N*m^2] of a moment of inertia J [kg*m^2]: GD² = 4 g J."""
    return 4.0 * g * j


def inertia_from_gd2(gd2, g=G_STANDARD):
    """Moment of inertia J [kg*m^2] of a flywheel moment GD² [N*m^2]: J = GD²/(4 g)."""
    return gd2 / (4.0 * g)

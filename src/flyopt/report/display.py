"""Units of the user's choice for what people read: the text report, the plots, the engineering report.

flyopt computes and writes its files in SI (docs/nomenclature.md; the JSON
and the tables stay SI whatever is shown). What a person reads may be in one
of three systems (``--units``):

- ``si``: the SI base units (rad, rad/s, N·m, J, m, Pa, W, ...);
- ``engineering`` (the default of reports and plots): the machine designer's
  units, mm, rpm, kN·m, kJ, MPa, kW;
- ``imperial``: in, rpm, lbf·ft, psi, hp, lb.

Every factor is pint's own (``Quantity(1, unit).to(SI).magnitude``), written
out so that showing a number loads no unit library; tests/report/test_display.py
checks each against pint. One table, by dimension (the dimensions of
:data:`flyopt.units.DIMENSIONS` and :data:`flyopt.outputs.results.OUTPUT_DIMENSIONS`):
a quantity is shown as ``value_SI / factor`` followed by its label.
An output field is shown by its name (:func:`field_text`, :func:`heading`),
its dimension read from flyopt.outputs.results' table of every field flyopt
writes (:func:`dimension_of`), the table behind the JSON's ``units`` map.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, TypeVar

if TYPE_CHECKING:  # the command-line parser reads this module's tables: numpy stays unloaded for it
    import numpy as np
    import numpy.typing as npt

#: A value shown in a unit: a number, or an array of them.
Shown = TypeVar("Shown", float, "npt.NDArray[np.floating]")

#: The unit systems, the default first for reports.
SYSTEMS = ("engineering", "si", "imperial")

#: The default for what people read.
DEFAULT = "engineering"

#: dimension -> system -> (label, factor: SI value of one displayed unit).
UNITS = {
    "angle": {
        "si": ("rad", 1.0),
        "engineering": ("deg", 0.017453292519943295),
        "imperial": ("deg", 0.017453292519943295),
    },
    "angular_speed": {
        "si": ("rad/s", 1.0),
        "engineering": ("rpm", 0.10471975511965977),
        "imperial": ("rpm", 0.10471975511965977),
    },
    "angular_acceleration": {
        "si": ("rad/s²", 1.0),
        "engineering": ("rad/s²", 1.0),
        "imperial": ("rad/s²", 1.0),
    },
    "acceleration": {"si": ("m/s²", 1.0), "engineering": ("m/s²", 1.0), "imperial": ("ft/s²", 0.3048)},
    "torque": {"si": ("N·m", 1.0), "engineering": ("kN·m", 1000.0), "imperial": ("lbf·ft", 1.3558179483314004)},
    "energy": {"si": ("J", 1.0), "engineering": ("kJ", 1000.0), "imperial": ("ft·lbf", 1.3558179483314004)},
    "inertia": {"si": ("kg·m²", 1.0), "engineering": ("kg·m²", 1.0), "imperial": ("lb·ft²", 0.04214011009380480)},
    "flywheel_moment": {
        "si": ("N·m²", 1.0),
        "engineering": ("N·m²", 1.0),
        "imperial": ("lbf·ft²", 0.41325331065141085),
    },
    "length": {"si": ("m", 1.0), "engineering": ("mm", 0.001), "imperial": ("in", 0.0254)},
    "mass": {"si": ("kg", 1.0), "engineering": ("kg", 1.0), "imperial": ("lb", 0.45359237)},
    "density": {"si": ("kg/m³", 1.0), "engineering": ("kg/m³", 1.0), "imperial": ("lb/in³", 27679.904710203125)},
    "speed": {"si": ("m/s", 1.0), "engineering": ("m/s", 1.0), "imperial": ("ft/s", 0.3048)},
    "stress": {"si": ("Pa", 1.0), "engineering": ("MPa", 1e6), "imperial": ("psi", 6894.7572931683635)},
    "power": {"si": ("W", 1.0), "engineering": ("kW", 1000.0), "imperial": ("hp", 745.6998715822701)},
    "force": {"si": ("N", 1.0), "engineering": ("kN", 1000.0), "imperial": ("lbf", 4.4482216152605)},
    "area": {"si": ("m²", 1.0), "engineering": ("mm²", 1e-6), "imperial": ("in²", 0.00064516)},
    "time": {"si": ("s", 1.0), "engineering": ("s", 1.0), "imperial": ("s", 1.0)},
    "unbalance": {"si": ("kg·m", 1.0), "engineering": ("g·mm", 1e-6), "imperial": ("oz·in", 0.0007200778873750002)},
    # the specific unbalance e = U/m of ISO 21940-11 (a length; g·mm/kg is µm), for the report's e_per
    "eccentricity": {"si": ("m", 1.0), "engineering": ("µm", 1e-6), "imperial": ("in", 0.0254)},
    "dimensionless": {"si": ("-", 1.0), "engineering": ("-", 1.0), "imperial": ("-", 1.0)},
}


def check_system(system: str) -> str:
    """``system`` if it is known; ValueError naming the allowed ones otherwise."""
    if system not in SYSTEMS:
        raise ValueError(f"unit system {system!r} is not known (allowed: {', '.join(SYSTEMS)})")
    return system


def unit(dimension: str, system: str = DEFAULT) -> tuple[str, float]:
    """(label, factor) of a dimension in a system: shown value = SI value / factor."""
    check_system(system)
    try:
        return UNITS[dimension][system]
    except KeyError:
        raise ValueError(f"no display unit for dimension {dimension!r} (known: {', '.join(UNITS)})") from None


def label(dimension: str, system: str = DEFAULT) -> str:
    """The unit's label, e.g. "mm"."""
    return unit(dimension, system)[0]


def show(value: Shown | None, dimension: str, system: str = DEFAULT) -> Shown | None:
    """An SI value (number or numpy array) in the system's unit of its dimension (None stays None)."""
    if value is None:
        return None
    return value / unit(dimension, system)[1]


def quantity_text(value: float | None, dimension: str, system: str = DEFAULT, digits: int = 6) -> str:
    """ "<number> <label>" with ``digits`` significant digits ("-" for None, "inf"/"nan" as such)."""
    if value is None:
        return "-"
    shown = float(value) / unit(dimension, system)[1]
    text = number(shown, digits) if math.isfinite(shown) else str(shown)
    name = label(dimension, system)
    return text if name == "-" else f"{text} {name}"


def number(value: float | None, digits: int = 6) -> str:
    """A number with ``digits`` significant digits, no exponent for everyday sizes ("-" for None).

    The one way flyopt writes a number for people (the text report, plots'
    labels); thousands are grouped ("1,256.33"), trailing zeros dropped. A
    whole number longer than ``digits`` is rounded to them (23,053,542 Pa to
    6 digits is "23,053,500"), so that no digit is printed that was not asked for.
    """
    if value is None:
        return "-"
    if not math.isfinite(value):
        return str(value)  # inf, -inf, nan: say so rather than fail
    if value == 0:
        return "0"
    magnitude = math.floor(math.log10(abs(value)))
    if -4 <= magnitude < 9:
        decimals = digits - 1 - magnitude
        if decimals > 0:
            return f"{value:,.{decimals}f}".rstrip("0").rstrip(".")
        return f"{round(value, decimals):,.0f}"
    return f"{value:.{digits - 1}e}"


def dimension_of(name: str) -> str:
    """The dimension of an output field (``a_max``: "energy", ``d_outer``: "length", a part's ``inertia``).

    From flyopt.outputs.results' one table of the fields flyopt writes (QUANTITIES
    and the sweep inputs), so that the JSON's ``units`` map and what people
    read cannot disagree. ValueError for a name that is no quantity.
    """
    from flyopt.outputs import quantities

    dimension = quantities.dimension_of(name)
    if dimension is None:
        raise ValueError(f"{name!r} is not a quantity of flyopt.outputs.results (no dimension to show it in)")
    return dimension


def field_text(value: float | None, name: str, system: str = DEFAULT, digits: int = 6) -> str:
    """An output field's SI value as "<number> <label>" in ``system`` (:func:`quantity_text` by its name)."""
    return quantity_text(value, dimension_of(name), system, digits)


#: A value within this fraction of its column's largest magnitude is round-off, and is shown as 0.
NOISE_RTOL = 1e-12


def denoised(values: Sequence[float]) -> list[float]:
    """A column of numbers with its round-off shown as 0: every value within :data:`NOISE_RTOL` of the column's
    largest magnitude (an energy chain that closes at -3.7e-16 kJ of a 9 kJ cycle closes at 0)."""
    scale = max((abs(v) for v in values if math.isfinite(v)), default=0.0)
    return [0.0 if math.isfinite(v) and abs(v) <= NOISE_RTOL * scale else v for v in values]


def field_number(value: float | None, name: str, system: str = DEFAULT, digits: int = 6) -> str:
    """The number alone of :func:`field_text`: for a table whose heading carries the unit ("-" for None)."""
    return number(show(None if value is None else float(value), dimension_of(name), system), digits)


def heading(title: str, name: str, system: str = DEFAULT) -> str:
    """A table heading with the unit of the field ``name``: "mass [kg]" (the title alone if dimensionless)."""
    text = label(dimension_of(name), system)
    return title if text == "-" else f"{title} [{text}]"
